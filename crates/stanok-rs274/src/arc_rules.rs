//! RS274/NGC's arc rules (spec rs274ngc §4.3), in the programming plane of
//! `stanok_interp_core::arc` (coordinates (a, b), lengths mm):
//! * centre format: `C = S + (i, j)` (G91.1, a missing offset is 0) or `C = (i, j)` (G90.1, both
//!   required); with r1 = |S−C|, r2 = |E−C|, Δ = |r1−r2| the arc is rejected when
//!   `Δ > 100·T  or  (Δ > T and Δ/max(r1,r2) > 0.1 %)`, T = 0.0005 in / 0.005 mm by default. The
//!   centre is kept as computed, so the motion is a spiral ending exactly at E (LinuxCNC);
//! * radius format: |R| ≥ half chord (within T), centre on the side given by the sign of R and the
//!   direction; `E = S` is an error.

use stanok_geom::centre_from_radius;
use stanok_interp_core::arc::{dist, radius_error, ArcError, PlanarArc};

/// RS274/NGC centre format. `tolerance` is T in mm.
pub fn centre_format(
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
pub fn radius_format(
    start: [f64; 2],
    end: [f64; 2],
    radius: f64,
    ccw: bool,
    turns: u32,
    tolerance: f64,
) -> Result<PlanarArc, ArcError> {
    // |E − S| < 1e-9 mm, squared: a test needs no `hypot` (a libm call of ≈ 30 instructions on
    // every radius-format arc); squares of coordinates this small or large under- or overflow
    // to the same answer.
    let d = [end[0] - start[0], end[1] - start[1]];
    if d[0] * d[0] + d[1] * d[1] < 1e-18 {
        return Err(ArcError::EndEqualsStart);
    }
    let centre = centre_from_radius(start, end, radius.abs(), ccw, radius < 0.0, tolerance)
        .map_err(radius_error)?;
    Ok(PlanarArc { centre, turns })
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
        let a = radius_format([0.0, 0.0], [10.0, 15.0], 20.0, false, 1, 0.005).unwrap();
        assert!(close(a.centre, [19.8551, -2.4034]), "{:?}", a.centre);
        // R−20: the other side, (−9.8551, 17.4034).
        let a = radius_format([0.0, 0.0], [10.0, 15.0], -20.0, false, 1, 0.005).unwrap();
        assert!(close(a.centre, [-9.8551, 17.4034]), "{:?}", a.centre);
    }

    #[test]
    fn rs274_tolerance_rule_of_the_document() {
        let t = 0.0005 * 25.4; // inch program: T = 0.0005 in
        let inch = |v: f64| v * 25.4;
        // r1 = 0.1, r2 = 0.1008 in: 0.79 % > 0.1 % and Δ > T → rejected.
        let e = centre_format([0.0, 0.0], [inch(0.2008), 0.0], [inch(0.1), 0.0], 1, t);
        assert!(matches!(e, Err(ArcError::RadiusMismatch { .. })));
        // r = 1, Δ = 0.0008 in = 0.08 % → accepted.
        let ok = centre_format([0.0, 0.0], [inch(2.0008), 0.0], [inch(1.0), 0.0], 1, t);
        assert!(ok.is_ok());
        // r = 100, Δ = 0.06 in > 100·T = 0.05 in → rejected although only 0.06 %.
        let e = centre_format([0.0, 0.0], [inch(200.06), 0.0], [inch(100.0), 0.0], 1, t);
        assert!(matches!(e, Err(ArcError::RadiusMismatch { .. })));
    }
}
