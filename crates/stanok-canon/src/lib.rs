//! # stanok-canon: the boundary between interpretation and motion
//!
//! The interpreter's only output is a stream of [`Canon`] commands, each wrapped in a [`Spanned`] that
//! names the block it came from. Motion, the simulated machine, reports and plots read this stream and
//! nothing else, so none of them depends on G-code, and the interpreter can be tested without motion.
//!
//! This crate depends on nothing of Stanok. It holds:
//! * [`Canon`] and its payload types ([`Pose`], [`LineMove`], [`ArcMove`], …), with every field's frame and
//!   unit in its doc;
//! * [`Span`] and [`Diagnostic`], shared by every stage;
//! * [`linuxcnc`], a printer of the stream in the exact format of LinuxCNC's `rs274 -g`;
//! * [`setup`], the stored control data (tool table, offset tables, home positions) that flows the
//!   other way, from machine data into the interpreter.
//!
//! Architecture invariant: positions in a `Canon` are machine Cartesian millimetres/degrees; the state
//! items (`SetG5xOffset`, `UseLengthUnits`, …) never change the meaning of a position.
#![deny(missing_docs)]

mod canon;
mod diag;
pub mod linuxcnc;
pub mod linuxcnc_trace;
mod quantities;
pub mod setup;
mod span;

pub use canon::{
    AccelerationProfile, ArcMove, AuxTiming, Canon, FeedLaw, FeedMode, LengthUnits, LineMove,
    LogAction, Motion, OrientationInterpolation, PathMode, Plane, Pose, ProbeKind,
    SpindleDirection, SplineMove, SurfaceSpeedLaw, AXIS_LETTERS,
};
pub use diag::{DiagCode, Diagnostic, Severity};
pub use span::{Span, Spanned};
