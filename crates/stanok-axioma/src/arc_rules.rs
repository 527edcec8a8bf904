//! AxiOMA's arc rules (spec axioma-2 §2.3.6–§2.3.9, the spec's proposals where the manual is
//! silent), in the programming plane of `stanok_interp_core::arc` (coordinates (a, b), mm):
//! * centre: G190 absolute, G191 relative, and relative under G91 whatever G190/G191 say; a missing
//!   centre letter means offset 0 (under G190: the start coordinate, with a warning);
//! * r_s ≈ 0 or no centre and no radius → 621; |r_s − r_e| > tolerance → 622; otherwise the centre is
//!   moved onto the perpendicular bisector of S–E so that the arc is a true circle;
//! * `R` (unsigned, sweep ≤ 180°) and `CR=` (negative: sweep > 180°): radius ≤ 0 or chord longer than
//!   2r + tolerance → 623; `E = S` → 622;
//! * `P` = additional full turns (integer ≥ 0).

use stanok_geom::centre_from_radius;
use stanok_interp_core::arc::{dist, radius_error, ArcError, PlanarArc};

/// AxiOMA centre format (centre already resolved to absolute plane coordinates).
pub fn centre_format(
    start: [f64; 2],
    end: [f64; 2],
    centre: [f64; 2],
    extra_turns: u32,
    tolerance: f64,
) -> Result<PlanarArc, ArcError> {
    let rs = dist(start, centre);
    let re = dist(end, centre);
    if rs < 1e-6 {
        return Err(ArcError::ZeroRadius);
    }
    if (rs - re).abs() > tolerance {
        return Err(ArcError::RadiusMismatch { r1: rs, r2: re });
    }
    // Centre correction: project C onto the perpendicular bisector of S–E, so that the corrected
    // centre is equidistant from both points (for a full circle S = E and C stays).
    let chord = [end[0] - start[0], end[1] - start[1]];
    let d = chord[0].hypot(chord[1]);
    let centre = if d > 1e-9 {
        let mid = [(start[0] + end[0]) / 2.0, (start[1] + end[1]) / 2.0];
        let u = [chord[0] / d, chord[1] / d];
        let along = (centre[0] - mid[0]) * u[0] + (centre[1] - mid[1]) * u[1];
        [centre[0] - along * u[0], centre[1] - along * u[1]]
    } else {
        centre
    };
    Ok(PlanarArc {
        centre,
        turns: 1 + extra_turns,
    })
}

/// AxiOMA `R` (major = false) or `CR=` (major = CR < 0) format; `radius` is the absolute value.
pub fn radius_format(
    start: [f64; 2],
    end: [f64; 2],
    radius: f64,
    major: bool,
    ccw: bool,
    extra_turns: u32,
    tolerance: f64,
) -> Result<PlanarArc, ArcError> {
    if radius <= 0.0 {
        return Err(ArcError::NonPositiveRadius);
    }
    if dist(start, end) < 1e-9 {
        return Err(ArcError::EndEqualsStart);
    }
    let centre =
        centre_from_radius(start, end, radius, ccw, major, tolerance).map_err(radius_error)?;
    Ok(PlanarArc {
        centre,
        turns: 1 + extra_turns,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-3;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < TOL && (a[1] - b[1]).abs() < TOL
    }

    #[test]
    fn axioma_centre_correction_lands_on_bisector() {
        // Example 5.6 in (Z, X): S (−25, 20), E (−75, 35), C (−54.25, 13.33): radii differ by 0.0017.
        let a = centre_format([-25.0, 20.0], [-75.0, 35.0], [-54.25, 13.33], 0, 0.01).unwrap();
        let rs = dist([-25.0, 20.0], a.centre);
        let re = dist([-75.0, 35.0], a.centre);
        assert!((rs - re).abs() < 1e-9);
        assert!((rs - 30.0).abs() < 0.01);
        // With a tolerance below the mismatch the same data is error 622.
        let e = centre_format([-25.0, 20.0], [-75.0, 35.0], [-54.25, 13.33], 0, 0.001);
        assert!(matches!(e, Err(ArcError::RadiusMismatch { .. })));
    }

    #[test]
    fn axioma_cr_sign_selects_side() {
        // Example 5.9: from (67.5, 80.511) to (17.203, 38.029), CR=±34.913, CCW.
        let s = [67.5, 80.511];
        let e = [17.203, 38.029];
        let minor = radius_format(s, e, 34.913, false, true, 0, 0.01).unwrap();
        assert!(
            close(minor.centre, [49.8568, 50.3840]),
            "{:?}",
            minor.centre
        );
        let major = radius_format(s, e, 34.913, true, true, 0, 0.01).unwrap();
        assert!(
            close(major.centre, [34.8462, 68.1560]),
            "{:?}",
            major.centre
        );
        assert_eq!(
            radius_format(s, e, 10.0, false, true, 0, 0.01),
            Err(ArcError::RadiusTooSmall {
                half_chord: dist(s, e) / 2.0,
                radius: 10.0
            })
        );
        assert_eq!(
            radius_format(s, s, 10.0, false, true, 0, 0.01),
            Err(ArcError::EndEqualsStart)
        );
    }
}
