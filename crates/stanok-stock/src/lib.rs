//! # stanok-stock: what the machine cuts
#![deny(missing_docs)]

pub mod dexel;
pub mod field;
pub mod lathe;
pub mod mesh;
mod mesh_merge;
pub mod mill;
pub mod render;
pub mod report;
pub mod sim;
pub mod spec;
pub mod sweep;
mod tilted;
pub mod tool;
mod vec3;
