//! Mazatrol EIA/ISO: the Fanuc-compatible Mazak language (`docs/dialects/mazatrol-eia.md`).
#![deny(missing_docs)]

pub mod codes;
pub mod comp;
pub mod drilling;
pub mod macro_b;
pub mod polar;
pub mod profile;
pub mod rules;
pub mod turning;
pub mod vars;
