//! Arcs in the programming plane: the types every front end's arc rules produce, and the
//! geometry they share.
//!
//! Everything here works in the *programming plane* with coordinates (a, b) = the plane's ordered
//! pair — (X, Y) for G17, (Z, X) for G18, (Y, Z) for G19 — so that "counter-clockwise" is always a
//! positive rotation from +a towards +b (right-handed about the plane normal, as the manuals define
//! it). Lengths are mm (the caller converts program units first). Each dialect's consistency rules
//! (tolerances, centre correction, error numbers) live in its front end (`arc_rules.rs` there) and
//! return a [`PlanarArc`] or an [`ArcError`].

use stanok_canon::{Plane, Pose};
use stanok_geom::RadiusError;

/// The arc's geometry in the programming plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarArc {
    /// Centre (a, b), mm, program frame.
    pub centre: [f64; 2],
    /// Total turns as LinuxCNC counts them (1 = the programmed arc only).
    pub turns: u32,
}

/// Why an arc was rejected; the caller turns it into a diagnostic at the right word.
#[derive(Debug, Clone, PartialEq)]
pub enum ArcError {
    /// RS274/NGC: end radius differs from start radius beyond the tolerance.
    RadiusMismatch {
        /// |S − C|, mm.
        r1: f64,
        /// |E − C|, mm.
        r2: f64,
    },
    /// Start or end radius (near) zero.
    ZeroRadius,
    /// Radius format with end point = start point.
    EndEqualsStart,
    /// Radius shorter than half the chord.
    RadiusTooSmall {
        /// Half the chord, mm.
        half_chord: f64,
        /// |R|, mm.
        radius: f64,
    },
    /// Radius ≤ 0 where only a positive one is allowed.
    NonPositiveRadius,
}

/// Distance between two plane points.
pub fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

/// The arc error of a failed radius-format centre construction.
pub fn radius_error(e: RadiusError) -> ArcError {
    match e {
        RadiusError::EndEqualsStart => ArcError::EndEqualsStart,
        RadiusError::RadiusTooSmall { half_chord, radius } => {
            ArcError::RadiusTooSmall { half_chord, radius }
        }
        RadiusError::NonPositiveRadius => ArcError::NonPositiveRadius,
    }
}

/// Spatial length of an arc in program coordinates (for inverse-time feed).
pub fn helix_length(
    start: Pose,
    end: Pose,
    plane: Plane,
    centre: [f64; 2],
    ccw: bool,
    turns: u32,
) -> f64 {
    let (a, b, n) = plane.axes();
    let s = start.to_array();
    let e = end.to_array();
    let mut c3 = [0.0; 3];
    c3[a] = centre[0];
    c3[b] = centre[1];
    c3[n] = s[n];
    let mut axis = [0.0; 3];
    axis[n] = if ccw { 1.0 } else { -1.0 };
    stanok_geom::Helix {
        start: [s[0], s[1], s[2]],
        end: [e[0], e[1], e[2]],
        centre: c3,
        axis,
        turns,
    }
    .length()
}
