//! # stanok-machine: the machine a program runs on
//!
//! * [`MachineData`]: what a machine is (axes, travel limits, rates, acceleration, jerk) and what its
//!   control stores ([`MachineData::control`]: tool table, zero-offset and workpiece tables, home
//!   positions, preset parameters), read from TOML with diagnostics that point at the offending
//!   line, plus the built-in machines ([`MachineData::builtin`]: `mill`). [`MachineData::to_toml`]
//!   writes it back.
//! * [`control`]: the TOML sections of the stored data and their validation; the sparse writer
//!   is `control_write.rs`.
//! * [`linuxcnc`]: LinuxCNC tool tables (`.tbl`) and parameter files (`.var`), read and written.
//! * [`files`]: the `--tools` / `--offsets` files, read by extension.
//! * [`SimMachine`]: executes a Canon stream on a simulated machine, refusing what the machine cannot
//!   do (travel limits, missing axes) with a [`Diagnostic`](stanok_canon::Diagnostic) at the block,
//!   runs it through the look-ahead planner and servo interpolator of `stanok-motion`
//!   (`sim_motion.rs`: setpoints checked against travel and dynamic limits), and builds the
//!   [`RunReport`] with the planned cycle time beside the nominal one.
//! * [`TravelCheck`]: the travel limits and missing axes of a Canon stream (joints under
//!   tool-centre-point control) — what `SimMachine` refuses, and what `stanok check` and the
//!   panel's preview list before a program starts.
//!
//! Planned here later: built-in lathe and 5-axis machines.
//!
//! Architecture invariant: this crate reads Canon, never G-code; machine data never panics on any
//! text, and the simulated machine never lets an accepted command exceed a travel limit.
#![deny(missing_docs)]

pub mod control;
mod control_write;
mod data;
pub mod files;
pub mod linuxcnc;
mod sim;
mod sim_motion;
pub mod time_bound;
mod tool_body;
mod travel;

pub use control_write::perm_to_toml;
pub use data::{
    offsets_from_toml_str, perm_from_toml_str, tools_from_toml_str, AxisData, AxisKind,
    ChannelData, MachineData, MazatrolData, MazatrolFeedMode, MazatrolSeries, PermParameters,
    StoredOffsets, BAD_DATA, BUILTIN_FIVE_AXIS, BUILTIN_MACHINES,
};
pub use sim::{BoundingBox, LoggedEvent, RunReport, SimMachine};
pub use sim_motion::{
    AxisMotion, BlockTime, ContourError, ContourErrors, FeedHoldReport, SetpointSink, SimOptions,
    SpindleRange, StockObserver,
};
pub use stanok_motion::overrides::{OverrideChange, OverrideKind, OverrideSwitch};
pub use stanok_motion::Setpoint;
pub use travel::TravelCheck;
