//! # stanok-kin: kinematics
//!
//! One small trait, [`Kinematics`], maps a tool pose (machine Cartesian, what the Canon stream
//! speaks) to joint positions (what the drives move) and back. Each machine type lives in its own
//! file. Today there is the identity machine, [`Cartesian`] (a 3-axis mill: joints = X Y Z plus any
//! rotary axis taken as is); the 5-axis head-head, table-table and head-table machines (TRAORI,
//! CVU, tool-tip control) come with the 5-axis issue, each with the property test
//! `forward(inverse(p)) ≈ p`.
//!
//! Architecture invariant: kinematics never sees the planner's buffer, offsets, units or G-code.
#![deny(missing_docs)]

mod cartesian;

pub use cartesian::Cartesian;
use stanok_canon::Pose;

/// Joint positions, in the order of the machine's axes (mm or degrees).
pub type Joints = [f64; 9];

/// Why a pose has no joint solution (or the reverse).
#[derive(Debug, Clone, PartialEq)]
pub enum KinError {
    /// The pose cannot be reached by this machine (e.g. outside the working space).
    Unreachable(String),
}

/// Tool pose ⇄ joints for one machine type.
pub trait Kinematics {
    /// Joint positions that put the tool at `pose`.
    fn inverse(&self, pose: &Pose) -> Result<Joints, KinError>;
    /// Tool pose for the given joint positions.
    fn forward(&self, joints: &Joints) -> Result<Pose, KinError>;
}
