//! # stanok-motion: from Canon motion to timed axis setpoints
//!
//! ```text
//!  Canon ─▶ adapter ─▶ path (chords, G64 blends) ─▶ planner (look-ahead) ─▶ interpolator ─▶ setpoints
//! ```
//! * [`adapter`]: modal motion state (G60/G61/G64 P, BRISK/SOFT, feed mode, spindle sync,
//!   overrides) stamped on every [`segment::PathSegment`]; forced exact stops.
//! * [`css`]: G96 along the path (the spindle speed per setpoint; G95 feeds cut to follow it).
//! * [`path`]: segments → tangent-continuous [`piece::Piece`]s: chords of arcs and splines, blends
//!   within the G64 tolerance (circular in BRISK, [`clothoid`] pairs in SOFT), per-piece
//!   speed/acceleration/jerk limits from the axis limits.
//! * [`planner`]: grbl-style reverse/forward passes over a bounded window.
//! * [`profile_trapezoid`] (BRISK), [`profile_scurve`] (SOFT): one piece's time law.
//! * [`interpolator`]: the servo-period grid, with [`hold`] (feed hold and resume) and
//!   [`overrides`] (feed, rapid and spindle override at once, on everything planned);
//!   [`stage::MotionStage`] wires everything.
//! * [`nominal`]: length / feed, the lower bound the run report keeps beside the planned time.
//!
//! Guarantees (property-tested in `tests/` and over the corpus in the `stanok` crate): no setpoint
//! exceeds an axis' velocity or acceleration limit (and jerk in SOFT), analytically and by finite
//! differences on the trace; under G64 P
//! the path stays within P; under G60/G61 every block end is met exactly at rest; the trace ends
//! exactly at the last programmed position and lasts the reported cycle time.
//!
//! Architecture invariant: this crate never sees offsets, units, modal groups or G-code; it takes
//! machine-frame positions (mm, deg), rates and returns seconds and setpoints.
#![deny(missing_docs)]

pub mod adapter;
pub mod clothoid;
pub mod contour;
pub mod css;
pub mod curve;
pub mod hold;
pub mod interpolator;
pub mod limits;
pub mod monitor;
pub mod nominal;
pub mod overrides;
pub mod path;
pub mod piece;
pub mod planner;
pub mod profile_scurve;
pub mod profile_trapezoid;
pub mod segment;
pub mod stage;
pub mod tcp;
pub mod timing;

pub use interpolator::Setpoint;
pub use limits::{AxisLimit, MotionConfig};
pub use stage::{MotionStage, StageStats};
