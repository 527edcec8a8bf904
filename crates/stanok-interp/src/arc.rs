//! Arc construction: from the words of a G2/G3 block to a centre and a number of turns, with each
//! dialect's consistency rules and error numbers.
//!
//! Everything here works in the *programming plane* with coordinates (a, b) = the plane's ordered
//! pair — (X, Y) for G17, (Z, X) for G18, (Y, Z) for G19 — so that "counter-clockwise" is always a
//! positive rotation from +a towards +b (right-handed about the plane normal, as both manuals define
//! it). Lengths are mm (the caller converts program units first).
//!
//! RS274/NGC (spec rs274ngc §4.3):
//! * centre format: `C = S + (i, j)` (G91.1, a missing offset is 0) or `C = (i, j)` (G90.1, both
//!   required); with r1 = |S−C|, r2 = |E−C|, Δ = |r1−r2| the arc is rejected when
//!   `Δ > 100·T  or  (Δ > T and Δ/max(r1,r2) > 0.1 %)`, T = 0.0005 in / 0.005 mm by default. The
//!   centre is kept as computed, so the motion is a spiral ending exactly at E (LinuxCNC);
//! * radius format: |R| ≥ half chord (within T), centre on the side given by the sign of R and the
//!   direction; `E = S` is an error.
//!
//! AxiOMA (spec axioma-2 §2.3.6–§2.3.9, the spec's proposals where the manual is silent):
//! * centre: G190 absolute, G191 relative, and relative under G91 whatever G190/G191 say; a missing
//!   centre letter means offset 0 (under G190: the start coordinate, with a warning);
//! * r_s ≈ 0 or no centre and no radius → 621; |r_s − r_e| > tolerance → 622; otherwise the centre is
//!   moved onto the perpendicular bisector of S–E so that the arc is a true circle;
//! * `R` (unsigned, sweep ≤ 180°) and `CR=` (negative: sweep > 180°): radius ≤ 0 or chord longer than
//!   2r + tolerance → 623; `E = S` → 622;
//! * `P` = additional full turns (integer ≥ 0).

use stanok_geom::{centre_from_radius, RadiusError};

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

/// RS274/NGC centre format. `tolerance` is T in mm.
pub fn rs274_centre_format(
    start: [f64; 2],
    end: [f64; 2],
    centre: [f64; 2],
    turns: u32,
    tolerance: f64,
) -> Result<PlanarArc, ArcError> {
    let r1 = dist(start, centre);
    let r2 = dist(end, centre);
    // LinuxCNC: a radius below 0.00005 in (0.00127 mm) is a zero-radius arc.
    if r1 < 0.00127 || r2 < 0.00127 {
        return Err(ArcError::ZeroRadius);
    }
    let delta = (r1 - r2).abs();
    if delta > 100.0 * tolerance || (delta > tolerance && delta / r1.max(r2) > 0.001) {
        return Err(ArcError::RadiusMismatch { r1, r2 });
    }
    Ok(PlanarArc { centre, turns })
}

/// RS274/NGC radius format: `radius` signed as written (negative: more than 180°).
pub fn rs274_radius_format(
    start: [f64; 2],
    end: [f64; 2],
    radius: f64,
    ccw: bool,
    turns: u32,
    tolerance: f64,
) -> Result<PlanarArc, ArcError> {
    if dist(start, end) < 1e-9 {
        return Err(ArcError::EndEqualsStart);
    }
    let centre = centre_from_radius(start, end, radius.abs(), ccw, radius < 0.0, tolerance)
        .map_err(radius_error)?;
    Ok(PlanarArc { centre, turns })
}

/// AxiOMA centre format (centre already resolved to absolute plane coordinates).
pub fn axioma_centre_format(
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
pub fn axioma_radius_format(
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

fn radius_error(e: RadiusError) -> ArcError {
    match e {
        RadiusError::EndEqualsStart => ArcError::EndEqualsStart,
        RadiusError::RadiusTooSmall { half_chord, radius } => {
            ArcError::RadiusTooSmall { half_chord, radius }
        }
        RadiusError::NonPositiveRadius => ArcError::NonPositiveRadius,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-3;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < TOL && (a[1] - b[1]).abs() < TOL
    }

    #[test]
    fn rs274_radius_example_centre() {
        // spec rs274ngc §4.3.2: G2 X10 Y15 R20 from (0,0) → centre (19.8551, −2.4034).
        let a = rs274_radius_format([0.0, 0.0], [10.0, 15.0], 20.0, false, 1, 0.005).unwrap();
        assert!(close(a.centre, [19.8551, -2.4034]), "{:?}", a.centre);
        // R−20: the other side, (−9.8551, 17.4034).
        let a = rs274_radius_format([0.0, 0.0], [10.0, 15.0], -20.0, false, 1, 0.005).unwrap();
        assert!(close(a.centre, [-9.8551, 17.4034]), "{:?}", a.centre);
    }

    #[test]
    fn rs274_tolerance_rule_of_the_document() {
        let t = 0.0005 * 25.4; // inch program: T = 0.0005 in
        let inch = |v: f64| v * 25.4;
        // r1 = 0.1, r2 = 0.1008 in: 0.79 % > 0.1 % and Δ > T → rejected.
        let e = rs274_centre_format([0.0, 0.0], [inch(0.2008), 0.0], [inch(0.1), 0.0], 1, t);
        assert!(matches!(e, Err(ArcError::RadiusMismatch { .. })));
        // r = 1, Δ = 0.0008 in = 0.08 % → accepted.
        let ok = rs274_centre_format([0.0, 0.0], [inch(2.0008), 0.0], [inch(1.0), 0.0], 1, t);
        assert!(ok.is_ok());
        // r = 100, Δ = 0.06 in > 100·T = 0.05 in → rejected although only 0.06 %.
        let e = rs274_centre_format([0.0, 0.0], [inch(200.06), 0.0], [inch(100.0), 0.0], 1, t);
        assert!(matches!(e, Err(ArcError::RadiusMismatch { .. })));
    }

    #[test]
    fn axioma_centre_correction_lands_on_bisector() {
        // Example 5.6 in (Z, X): S (−25, 20), E (−75, 35), C (−54.25, 13.33): radii differ by 0.0017.
        let a =
            axioma_centre_format([-25.0, 20.0], [-75.0, 35.0], [-54.25, 13.33], 0, 0.01).unwrap();
        let rs = dist([-25.0, 20.0], a.centre);
        let re = dist([-75.0, 35.0], a.centre);
        assert!((rs - re).abs() < 1e-9);
        assert!((rs - 30.0).abs() < 0.01);
        // With a tolerance below the mismatch the same data is error 622.
        let e = axioma_centre_format([-25.0, 20.0], [-75.0, 35.0], [-54.25, 13.33], 0, 0.001);
        assert!(matches!(e, Err(ArcError::RadiusMismatch { .. })));
    }

    #[test]
    fn axioma_cr_sign_selects_side() {
        // Example 5.9: from (67.5, 80.511) to (17.203, 38.029), CR=±34.913, CCW.
        let s = [67.5, 80.511];
        let e = [17.203, 38.029];
        let minor = axioma_radius_format(s, e, 34.913, false, true, 0, 0.01).unwrap();
        assert!(
            close(minor.centre, [49.8568, 50.3840]),
            "{:?}",
            minor.centre
        );
        let major = axioma_radius_format(s, e, 34.913, true, true, 0, 0.01).unwrap();
        assert!(
            close(major.centre, [34.8462, 68.1560]),
            "{:?}",
            major.centre
        );
        assert_eq!(
            axioma_radius_format(s, e, 10.0, false, true, 0, 0.01),
            Err(ArcError::RadiusTooSmall {
                half_chord: dist(s, e) / 2.0,
                radius: 10.0
            })
        );
        assert_eq!(
            axioma_radius_format(s, s, 10.0, false, true, 0, 0.01),
            Err(ArcError::EndEqualsStart)
        );
    }
}
