//! Arcs in a programming plane: the centre from a radius (G2/G3 with R or CR=) and the sweep angle.
//!
//! Plane coordinates are `(a, b)`, right-handed: counter-clockwise turns from +a towards +b (for G17
//! a = X, b = Y; for G18 a = Z, b = X; for G19 a = Y, b = Z).
//!
//! ## Centre from radius
//!
//! ```text
//!                 C (left)  ccw minor / cw major
//!                 |
//!                 | h = sqrt(r² − (d/2)²)
//!     S ----------M----------> E        d = |E − S|, M = (S + E)/2
//!                 |
//!                 | h
//!                 C (right) cw minor / ccw major
//! ```
//! Both candidate centres lie on the perpendicular bisector of the chord S→E at distance h from its
//! midpoint M. Travelling counter-clockwise around a centre on the left of the chord covers less than
//! 180° (the centre sees the chord on its right); the same centre travelled clockwise gives the long
//! way round. Hence "left" for (ccw ∧ minor) ∨ (cw ∧ major), "right" otherwise.
//!
//! Invariants: an `Ok` centre is at distance `radius` from both points (to rounding), except in the
//! tolerated case d/2 > r where it is the midpoint (a semicircle of radius d/2, which the caller
//! accepted by giving the tolerance). No input panics; NaN input gives an error, never a NaN centre.
//!
//! ## Sweep
//!
//! [`ccw_sweep`] measures the counter-clockwise angle from the start ray to the end ray with
//! `atan2(cross, dot)`, which is accurate for every angle (unlike `acos` near 0 and π), and maps it to
//! (0, 2π]: an angle of zero (or a rounding hair below) means the whole circle. Points that coincide
//! within the caller's tolerance are a full circle whatever their angles.

use std::f64::consts::TAU;
use std::fmt;

/// Why a centre could not be found from a radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RadiusError {
    /// Start and end are the same point: a radius does not define a circle (AxiOMA 622).
    EndEqualsStart,
    /// The chord is longer than the diameter by more than the tolerance (AxiOMA 623).
    RadiusTooSmall {
        /// Half the distance from start to end, mm.
        half_chord: f64,
        /// The programmed radius, mm.
        radius: f64,
    },
    /// The radius is zero, negative or not a number.
    NonPositiveRadius,
}

impl fmt::Display for RadiusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RadiusError::EndEqualsStart => f.write_str("end point equals start point"),
            RadiusError::RadiusTooSmall { half_chord, radius } => write!(
                f,
                "radius {radius} mm is smaller than half the chord {half_chord} mm"
            ),
            RadiusError::NonPositiveRadius => f.write_str("radius must be positive"),
        }
    }
}

impl std::error::Error for RadiusError {}

/// Centre of a circle through `start` and `end` (plane coordinates (a, b), right-handed: CCW = from +a
/// towards +b) with the given radius.
///
/// `ccw`: direction of travel; `major`: the arc is longer than 180°. The centre lies left of the chord
/// for `(ccw && !major) || (!ccw && major)`, right otherwise. If the chord is longer than 2r by at most
/// `tolerance`, returns the chord midpoint (semicircle).
pub fn centre_from_radius(
    start: [f64; 2],
    end: [f64; 2],
    radius: f64,
    ccw: bool,
    major: bool,
    tolerance: f64,
) -> Result<[f64; 2], RadiusError> {
    if radius.is_nan() || radius <= 0.0 {
        return Err(RadiusError::NonPositiveRadius);
    }
    let d = [end[0] - start[0], end[1] - start[1]];
    let chord = d[0].hypot(d[1]);
    if chord == 0.0 {
        return Err(RadiusError::EndEqualsStart);
    }
    let half_chord = chord / 2.0;
    // NaN coordinates land here too.
    if half_chord.is_nan() || half_chord > radius {
        let tolerated = half_chord - radius <= tolerance.max(0.0) / 2.0;
        if tolerated && half_chord.is_finite() {
            return Ok([start[0] + d[0] / 2.0, start[1] + d[1] / 2.0]);
        }
        return Err(RadiusError::RadiusTooSmall { half_chord, radius });
    }
    // (r − c)(r + c) loses less precision than r² − c² when r ≈ c.
    let h = ((radius - half_chord) * (radius + half_chord))
        .max(0.0)
        .sqrt();
    let left = ccw != major;
    let side = if left { 1.0 } else { -1.0 };
    // The chord direction turned 90° counter-clockwise points left.
    let n = [-d[1] / chord, d[0] / chord];
    Ok([
        start[0] + d[0] / 2.0 + side * h * n[0],
        start[1] + d[1] / 2.0 + side * h * n[1],
    ])
}

/// Planar counter-clockwise sweep from the angle of `start` to that of `end` about `centre`, in
/// (0, 2π]: the full circle (2π) when the points coincide within `same_point_tol` (mm) or lie on the
/// same ray. Degenerate input (a point on the centre, NaN) gives 2π.
pub fn ccw_sweep(centre: [f64; 2], start: [f64; 2], end: [f64; 2], same_point_tol: f64) -> f64 {
    if (end[0] - start[0]).hypot(end[1] - start[1]) <= same_point_tol {
        return TAU;
    }
    let s = [start[0] - centre[0], start[1] - centre[1]];
    let e = [end[0] - centre[0], end[1] - centre[1]];
    let sin_part = s[0] * e[1] - s[1] * e[0];
    let cos_part = s[0] * e[0] + s[1] * e[1];
    positive_angle(sin_part.atan2(cos_part))
}

/// Maps an `atan2` result in [−π, π] to (0, 2π]; zero, a rounding hair above it, and NaN become 2π.
pub(crate) fn positive_angle(theta: f64) -> f64 {
    /// Angles this close to zero are "the same ray" (1e-12 rad is 1 nm at 1 km).
    const SAME_RAY_RAD: f64 = 1e-12;
    if theta.is_nan() {
        TAU
    } else if theta <= SAME_RAY_RAD {
        theta + TAU
    } else {
        theta
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] - b[0]).hypot(a[1] - b[1])
    }

    #[test]
    fn quarter_circle_centres() {
        // (10,0) → (0,10), r = 10: ccw minor about the origin; cw minor about (10,10).
        let c = centre_from_radius([10.0, 0.0], [0.0, 10.0], 10.0, true, false, 0.0).unwrap();
        assert!(dist(c, [0.0, 0.0]) < 1e-12, "{c:?}");
        let c = centre_from_radius([10.0, 0.0], [0.0, 10.0], 10.0, false, false, 0.0).unwrap();
        assert!(dist(c, [10.0, 10.0]) < 1e-12, "{c:?}");
        // Major arcs swap the centres.
        let c = centre_from_radius([10.0, 0.0], [0.0, 10.0], 10.0, true, true, 0.0).unwrap();
        assert!(dist(c, [10.0, 10.0]) < 1e-12, "{c:?}");
    }

    #[test]
    fn errors_and_tolerated_semicircle() {
        let f = |s, e, r, tol| centre_from_radius(s, e, r, true, false, tol);
        assert_eq!(
            f([1.0, 1.0], [1.0, 1.0], 5.0, 0.1),
            Err(RadiusError::EndEqualsStart)
        );
        assert_eq!(
            f([0.0, 0.0], [1.0, 0.0], 0.0, 0.1),
            Err(RadiusError::NonPositiveRadius)
        );
        assert_eq!(
            f([0.0, 0.0], [1.0, 0.0], f64::NAN, 0.1),
            Err(RadiusError::NonPositiveRadius)
        );
        assert_eq!(
            f([0.0, 0.0], [20.0, 0.0], 9.0, 0.01),
            Err(RadiusError::RadiusTooSmall {
                half_chord: 10.0,
                radius: 9.0
            })
        );
        // Chord 20.005 > 2r = 20 by 0.005 ≤ tolerance: the midpoint.
        assert_eq!(f([0.0, 0.0], [20.005, 0.0], 10.0, 0.01), Ok([10.0025, 0.0]));
        // NaN coordinates are an error, not a NaN centre.
        assert!(f([f64::NAN, 0.0], [1.0, 0.0], 5.0, 0.0).is_err());
    }

    #[test]
    fn sweep_cases() {
        let o = [0.0, 0.0];
        assert!((ccw_sweep(o, [1.0, 0.0], [0.0, 1.0], 1e-9) - FRAC_PI_2).abs() < 1e-15);
        assert!((ccw_sweep(o, [0.0, 1.0], [1.0, 0.0], 1e-9) - 3.0 * FRAC_PI_2).abs() < 1e-15);
        assert!((ccw_sweep(o, [1.0, 0.0], [-1.0, 0.0], 1e-9) - PI).abs() < 1e-15);
        assert_eq!(ccw_sweep(o, [1.0, 0.0], [1.0, 1e-12], 1e-9), TAU);
        // Same ray, different radius (a spiral's full turn).
        assert_eq!(ccw_sweep(o, [1.0, 0.0], [2.0, 0.0], 1e-9), TAU);
        assert_eq!(ccw_sweep(o, o, [1.0, 0.0], 1e-9), TAU);
        assert_eq!(ccw_sweep(o, [f64::NAN, 0.0], [1.0, 0.0], 1e-9), TAU);
    }

    proptest! {
        #[test]
        fn centre_is_at_radius_on_the_right_side(
            sa in -500.0..500.0f64, sb in -500.0..500.0f64,
            ea in -500.0..500.0f64, eb in -500.0..500.0f64,
            extra in 0.0..2.0f64, ccw: bool, major: bool,
        ) {
            let (s, e) = ([sa, sb], [ea, eb]);
            let chord = dist(s, e);
            prop_assume!(chord > 1e-3);
            let r = chord / 2.0 * (1.0 + extra);
            let c = centre_from_radius(s, e, r, ccw, major, 0.0).unwrap();
            let tol = 1e-9 * (1.0 + r);
            prop_assert!((dist(c, s) - r).abs() < tol, "start at {} not {}", dist(c, s), r);
            prop_assert!((dist(c, e) - r).abs() < tol, "end at {} not {}", dist(c, e), r);
            // Side: sign of (E − S) × (C − S) is positive for "left".
            let side = (e[0] - s[0]) * (c[1] - s[1]) - (e[1] - s[1]) * (c[0] - s[0]);
            let h = (r * r - chord * chord / 4.0).max(0.0).sqrt();
            if h > 1e-6 * r {
                prop_assert_eq!(side > 0.0, ccw != major);
            }
            // The sweep of the resulting arc: ≤ 180° for minor, ≥ 180° for major.
            let sweep = if ccw {
                ccw_sweep(c, s, e, 1e-9)
            } else {
                ccw_sweep(c, e, s, 1e-9) // clockwise s→e is counter-clockwise e→s
            };
            let slack = 1e-6;
            if major {
                prop_assert!(sweep >= PI - slack, "major sweep {}", sweep);
                if h > 1e-3 * r { prop_assert!(sweep > PI); }
            } else {
                prop_assert!(sweep <= PI + slack, "minor sweep {}", sweep);
            }
        }
    }
}
