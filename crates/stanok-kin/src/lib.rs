//! # stanok-kin: kinematics
//!
//! One small trait, [`Kinematics`], maps a tool pose (what the Canon stream speaks: the tool tip in
//! the workpiece-fixed machine frame, mm, plus the rotary axis values, degrees) to joint positions
//! (what the drives move) and back. Each machine type lives in its own file:
//!
//! | file | machine |
//! |---|---|
//! | `cartesian.rs` | [`Cartesian`]: the identity (3-axis mills and lathes; 5-axis machines with TCP off) |
//! | `head_head.rs` | [`head_head`]: two rotary axes in the head (TT), pairs AB, AC, BC |
//! | `table_table.rs` | [`table_table`]: two rotary axes in the table (DD), pairs AB, AC, BC |
//! | `head_table.rs` | [`head_table`]: one in the table, one in the head (TD/DT), pairs AB, AC, BC |
//! | `millturn.rs` | [`millturn_bc`]: the Mazatrol mill-turn B head + C workpiece spindle, X on diameter |
//! | `chain.rs` | [`FiveAxis`]: the one rotary-chain model all of them are instances of |
//! | `orientation.rs` | Euler ZY'Z'', roll-pitch-yaw, vectors, signed angles, great-circle interpolation |
//! | `data.rs` | [`KinematicsData`]: the `[kinematics]` section of the machine-data TOML |
//! | `fat.rs` | [`from_fat`]: the Balt-System `FAT=` characterization line (TT, DD, DT) |
//!
//! Architecture invariant: kinematics never sees the planner's buffer, offsets, units or G-code.
//! Invariant (property-tested for every machine type in `tests/props.rs`): `forward(inverse(p)) = p`
//! within 1e-9 for every reachable pose.
#![deny(missing_docs)]

mod cartesian;
mod chain;
mod data;
mod fat;
mod head_head;
mod head_table;
mod millturn;
pub mod orientation;
mod table_table;

pub use cartesian::Cartesian;
pub use chain::{Carrier, FiveAxis, RotaryAxis};
pub use data::{KinematicsData, MachineType, TtpcFrame};
pub use fat::{from_fat, FatError};
pub use head_head::head_head;
pub use head_table::head_table;
pub use millturn::millturn_bc;
use stanok_canon::Pose;
pub use table_table::table_table;

/// Joint positions, in the order of the machine's axes X Y Z A B C U V W (mm or degrees).
pub type Joints = [f64; 9];

/// The two rotary axes of a 5-axis machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RotaryPair {
    /// A (about X) and B (about Y).
    AB,
    /// A (about X) and C (about Z).
    AC,
    /// B (about Y) and C (about Z).
    BC,
}

/// Why a pose has no joint solution (or the reverse).
#[derive(Debug, Clone, PartialEq)]
pub enum KinError {
    /// The pose cannot be reached by this machine (e.g. outside the working space).
    Unreachable(String),
    /// No rotary position of this machine gives the tool vector (within the axis limits).
    OrientationUnreachable,
    /// A zero orientation vector was given.
    ZeroVector,
    /// The machine data cannot describe a machine (parallel axes, wrong axis count…).
    Degenerate(String),
}

impl std::fmt::Display for KinError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            KinError::Unreachable(why) => write!(f, "pose unreachable: {why}"),
            KinError::OrientationUnreachable => {
                write!(f, "tool orientation unreachable by this machine")
            }
            KinError::ZeroVector => write!(f, "zero orientation vector"),
            KinError::Degenerate(why) => write!(f, "bad kinematics data: {why}"),
        }
    }
}

impl std::error::Error for KinError {}

/// Tool pose ⇄ joints for one machine type.
pub trait Kinematics {
    /// Joint positions that put the tool at `pose`.
    fn inverse(&self, pose: &Pose) -> Result<Joints, KinError>;
    /// Tool pose for the given joint positions.
    fn forward(&self, joints: &Joints) -> Result<Pose, KinError>;
    /// The unit tool vector (tip → holder, workpiece-fixed frame) at `pose`; (0, 0, 1) on a machine
    /// without rotary orientation axes.
    fn tool_vector(&self, _pose: &Pose) -> [f64; 3] {
        [0.0, 0.0, 1.0]
    }
    /// `current` with its rotary axes set so that the tool points along `t` (chosen among the
    /// solutions by continuity, limits and least motion); a machine without orientation axes only
    /// accepts its fixed direction.
    fn orient(&self, t: [f64; 3], current: &Pose) -> Result<Pose, KinError> {
        let fixed = self.tool_vector(current);
        let t = orientation::normalised(t).ok_or(KinError::ZeroVector)?;
        if (t - nalgebra::Vector3::from(fixed)).norm() < 1e-9 {
            Ok(*current)
        } else {
            Err(KinError::OrientationUnreachable)
        }
    }
}
