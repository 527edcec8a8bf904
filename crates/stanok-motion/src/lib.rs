//! # stanok-motion: from Canon motion to time
//!
//! What will live here (later issues): the look-ahead **planner** (junction and curvature speed
//! limits, G60/G64 exact stop and path tolerance, BRISK trapezoidal and SOFT jerk-limited profiles,
//! reverse and forward passes in the grbl/Klipper style) producing `PlannedBlock`s, and the
//! servo-period **interpolator** that turns planned blocks into setpoints with overrides and feed
//! hold. The planner will respect every axis' velocity, acceleration and jerk limit, property-tested.
//!
//! What lives here now: [`nominal`], the "nominal" time of a move: path length over the programmed
//! (or rapid) rate, as if every move started and stopped at full speed with infinite acceleration.
//! It is the number a run report can give before the planner exists, and a lower bound for the
//! planned time of the same moves.
//!
//! Architecture invariant: this crate never sees offsets, units, modal groups or G-code; it takes
//! machine-frame lengths (mm, or degrees for rotary-only moves), rates in units per minute and returns
//! seconds.
#![deny(missing_docs)]

pub mod nominal;
