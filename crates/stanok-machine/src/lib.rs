//! # stanok-machine: the machine a program runs on
//!
//! * [`MachineData`]: what a machine is (axes, travel limits, rates, acceleration, jerk), read from
//!   TOML with diagnostics that point at the offending line, plus the built-in machines
//!   ([`MachineData::builtin`]: `mill`).
//! * [`SimMachine`]: executes a Canon stream on a simulated machine, refusing what the machine cannot
//!   do (travel limits, missing axes) with a [`Diagnostic`](stanok_canon::Diagnostic) at the block,
//!   and builds the [`RunReport`] with nominal timing (`stanok_motion::nominal`: no acceleration yet).
//!
//! Planned here later: tool and offset tables (incl. LinuxCNC `.tbl`/`.var` import), built-in lathe
//! and 5-axis machines, running the planner's setpoints instead of nominal times.
//!
//! Architecture invariant: this crate reads Canon, never G-code; machine data never panics on any
//! text, and the simulated machine never lets an accepted command exceed a travel limit.
#![deny(missing_docs)]

mod data;
mod sim;

pub use data::{AxisData, AxisKind, MachineData, BAD_DATA};
pub use sim::{BoundingBox, LoggedEvent, RunReport, SimMachine};
