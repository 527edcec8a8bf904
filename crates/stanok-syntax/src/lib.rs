//! # stanok-syntax: program text to blocks
//!
//! Lexing and parsing only; no meaning. (Implementation in progress.)
#![deny(missing_docs)]

mod ast;
pub use ast::*;
