//! # stanok-stock: what the machine cuts
#![deny(missing_docs)]

pub mod dexel;
pub mod mill;
pub mod sweep;
pub mod tool;
mod vec3;
