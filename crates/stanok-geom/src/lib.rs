//! # stanok-geom: the geometry of tool paths
//!
//! Pure functions on plain `[f64; N]` points, in millimetres and radians. This crate knows nothing
//! about G-code, Canon, time or machines: the interpreter uses it to build arcs from programmed
//! words ([`centre_from_radius`], [`ccw_sweep`]); motion, the simulated machine and the plotter use it
//! to measure and draw them ([`Helix`]).
//!
//! Architecture invariants:
//! * no function panics and none loops without bound, whatever the input (NaN included): degenerate
//!   input gives a documented fallback or an error value;
//! * the arc model is exactly the one of `stanok-canon`'s `ArcMove` (see [`Helix`]), so that every
//!   consumer agrees on where an arc goes.
//!
//! Splines: every spline of both controls is handed over as a rational B-spline ([`Nurbs`]).
//!
//! Cutter compensation: planar lines and arcs with offsets and intersections ([`offset2d`]);
//! whole open chains offset with their corners resolved ([`chain2d`], the lathe cycles' allowance).
//! 3D compensation (AxiOMA CUT3D*): cutter offsets, corner types and projected crossings
//! ([`offset3d`]).
//! AxiOMA ASPLINE / CSPLINE: the Akima ([`akima`]) and C² cubic ([`cubic_spline`]) splines
//! through points, both as Hermite segments in cubic Bézier form.
#![deny(missing_docs)]

pub mod akima;
mod arc2d;
mod bezier_split;
pub mod chain2d;
pub mod cubic_spline;
mod helix;
mod nurbs;
pub mod offset2d;
pub mod offset3d;
mod vec3;

pub use akima::{bezier_point, hermite_bezier};
pub use arc2d::{ccw_sweep, centre_from_radius, RadiusError};
pub use bezier_split::{bezier_pieces, BezierPiece};
pub use helix::{Helix, HelixFrame};
pub use nurbs::{bezier_knots, distance_to_segment, Nurbs, NurbsError, MAX_DEGREE};
pub use vec3::{add, cross, dot, norm, normalize, scale, sub, Vec3};
