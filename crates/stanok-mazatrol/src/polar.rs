//! G12.1 polar coordinate interpolation and G07.1 cylindrical interpolation as chords in joint
//! space (`docs/dialects/mazatrol-eia.md` §12).
//!
//! **Polar.** The program moves in a virtual Cartesian face plane `(x_v, y_v)`; the machine has the
//! radius `r = |v|` (joint X) and the angle `C = atan2(y_v, x_v)` (degrees, unwrapped to the
//! nearest of the previous value). A joint-linear move between two joint points is a spiral piece
//! in the virtual plane, so an element is cut into chords by adaptive bisection: an interval is
//! accepted when the joint-linear path deviates from the exact element by at most `tol` at a
//! quarter, half and three quarters of it (the deviation of these smooth pieces is largest near
//! the middle). *Invariants:* consecutive chords share their joint end points; the C values change
//! continuously (no 360° jumps); each chord carries the exact virtual length of its piece, so the
//! front end times it at the programmed F; at most [`MAX_CHORDS`] chords per element, and a path
//! passing within [`CENTRE_EPS`] of the spindle centre is refused (C is undefined there).
//!
//! **Cylindrical.** The developed plane `(z, s)` with `s = r_cyl·C·π/180`: a line is linear in the
//! joints (one chord), an arc is cut into chords whose sagitta is at most `tol`.

use stanok_geom::offset2d::{Seg2, P2};

/// Most chords of one element.
pub const MAX_CHORDS: usize = 4096;
/// Closest approach to the spindle centre allowed in polar interpolation, mm.
pub const CENTRE_EPS: f64 = 1e-3;

/// The end of one chord.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chord {
    /// The element parameter at the chord's end (0…1).
    pub t: f64,
    /// Joint values at the chord's end: polar `[r, C°]`; cylindrical `[z, C°]`.
    pub joints: [f64; 2],
    /// The exact virtual (developed) length of the piece, mm.
    pub length: f64,
}

/// Why the element cannot be interpolated.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarError(pub String);

/// `a` moved by whole turns to the one nearest `prev` (degrees).
pub fn unwrap_deg(a: f64, prev: f64) -> f64 {
    a + 360.0 * ((prev - a) / 360.0).round()
}

/// The joints of a virtual point with C unwrapped near `prev_c`.
pub fn to_joints(v: P2, prev_c: f64) -> [f64; 2] {
    let r = v[0].hypot(v[1]);
    let c = v[1].atan2(v[0]).to_degrees();
    [r, unwrap_deg(c, prev_c)]
}

/// The virtual point of joints `[r, C°]`.
pub fn to_virtual(j: [f64; 2]) -> P2 {
    let c = j[1].to_radians();
    [j[0] * c.cos(), j[0] * c.sin()]
}

/// Chords of a virtual element (line or arc, `stanok_geom` `Seg2` in the `(x_v, y_v)` plane)
/// starting at joint angle `c0` (degrees), within `tol` mm.
pub fn polar_chords(seg: &Seg2, c0: f64, tol: f64) -> Result<Vec<Chord>, PolarError> {
    if seg.distance_to([0.0, 0.0]) < CENTRE_EPS {
        return Err(PolarError(format!(
            "the path passes within {CENTRE_EPS} mm of the spindle centre, where C is undefined"
        )));
    }
    let start = to_joints(seg.start(), c0);
    let total = seg.length();
    // Intervals still to judge, last one on top (so chords come out in order).
    let mut stack: Vec<(f64, f64, [f64; 2], [f64; 2])> = Vec::new();
    let end = to_joints(seg.end(), start[1] + sweep_hint(seg, start[1]));
    stack.push((0.0, 1.0, start, end));
    let mut out: Vec<Chord> = Vec::new();
    while let Some((t0, t1, j0, j1)) = stack.pop() {
        let ok = [0.25, 0.5, 0.75].iter().all(|&s| {
            let joint = [j0[0] + s * (j1[0] - j0[0]), j0[1] + s * (j1[1] - j0[1])];
            let exact = seg.point(t0 + s * (t1 - t0));
            let got = to_virtual(joint);
            (got[0] - exact[0]).hypot(got[1] - exact[1]) <= tol
        });
        if ok {
            out.push(Chord {
                t: t1,
                joints: j1,
                length: total * (t1 - t0),
            });
            if out.len() > MAX_CHORDS {
                return Err(PolarError(format!(
                    "more than {MAX_CHORDS} chords for one block (the path comes too close to the centre)"
                )));
            }
            continue;
        }
        if out.len() + stack.len() > MAX_CHORDS {
            return Err(PolarError(format!(
                "more than {MAX_CHORDS} chords for one block (the path comes too close to the centre)"
            )));
        }
        let tm = 0.5 * (t0 + t1);
        let jm = to_joints(seg.point(tm), j0[1]);
        let j1 = [j1[0], unwrap_deg(j1[1], jm[1])];
        stack.push((tm, t1, jm, j1));
        stack.push((t0, tm, j0, jm));
    }
    Ok(out)
}

/// How far C turns over the element, degrees (signed), so that the end angle is unwrapped on
/// the side the path actually goes round the centre.
fn sweep_hint(seg: &Seg2, c0: f64) -> f64 {
    // Follow the angle through a few points: the path cannot turn by 180° between them without
    // passing near the centre (refused above) … unless the element is long; 64 samples.
    let mut c = c0;
    for i in 1..=64 {
        let p = seg.point(i as f64 / 64.0);
        c = unwrap_deg(p[1].atan2(p[0]).to_degrees(), c);
    }
    c - c0
}

/// Chords of an element of the cylinder's developed plane `(z, s)` (s = r_cyl·C in mm) for a
/// cylinder of radius `r_cyl`; joints are `[z, C°]`.
pub fn cylindrical_chords(seg: &Seg2, r_cyl: f64, tol: f64) -> Result<Vec<Chord>, PolarError> {
    if r_cyl.is_nan() || r_cyl <= 0.0 {
        return Err(PolarError("the cylinder radius must be positive".into()));
    }
    let joint = |p: P2| [p[0], (p[1] / r_cyl).to_degrees()];
    let n = match *seg {
        Seg2::Line { .. } => 1,
        Seg2::Arc { r, sweep, .. } => {
            let half = if tol >= r {
                std::f64::consts::FRAC_PI_2
            } else {
                (1.0 - tol / r).acos()
            };
            ((sweep.abs() / (2.0 * half)).ceil() as usize).max(1)
        }
    };
    if n > MAX_CHORDS {
        return Err(PolarError(format!(
            "more than {MAX_CHORDS} chords for one block"
        )));
    }
    let total = seg.length();
    Ok((1..=n)
        .map(|i| {
            let t = i as f64 / n as f64;
            Chord {
                t,
                joints: joint(seg.point(t)),
                length: total / n as f64,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(a: P2, b: P2) -> Seg2 {
        Seg2::Line { a, b }
    }

    #[test]
    fn the_example_square_side() {
        // N46 of examples/mazak-t-job.eia: virtual (10, 0) → (10, 10).
        let ch = polar_chords(&line([10.0, 0.0], [10.0, 10.0]), 0.0, 1e-3).unwrap();
        let last = ch.last().unwrap();
        assert!((last.joints[0] - 200f64.sqrt()).abs() < 1e-12);
        assert!((last.joints[1] - 45.0).abs() < 1e-12);
        let total: f64 = ch.iter().map(|c| c.length).sum();
        assert!((total - 10.0).abs() < 1e-12);
        // Every chord's joint-linear path is within 1 µm of the side x = 10 (sampled densely).
        let mut prev = [10.0, 0.0];
        for c in &ch {
            for k in 0..=20 {
                let s = k as f64 / 20.0;
                let j = [
                    prev[0] + s * (c.joints[0] - prev[0]),
                    prev[1] + s * (c.joints[1] - prev[1]),
                ];
                let v = to_virtual(j);
                assert!((v[0] - 10.0).abs() < 1.1e-3, "{v:?}");
            }
            prev = c.joints;
        }
    }

    #[test]
    fn c_unwraps_around_the_square() {
        // The whole square of the example: C ends at 360°, not 0°.
        let corners = [
            [10.0, 0.0],
            [10.0, 10.0],
            [-10.0, 10.0],
            [-10.0, -10.0],
            [10.0, -10.0],
            [10.0, 0.0],
        ];
        let mut c = 0.0;
        for w in corners.windows(2) {
            let ch = polar_chords(&line(w[0], w[1]), c, 1e-3).unwrap();
            c = ch.last().unwrap().joints[1];
        }
        assert!((c - 360.0).abs() < 1e-9, "{c}");
        // Halfway along the top side (0, 10): r 10, C 90.
        let ch = polar_chords(&line([10.0, 10.0], [-10.0, 10.0]), 45.0, 1e-3).unwrap();
        let mid = ch
            .iter()
            .find(|c| (c.t - 0.5).abs() < 1e-12)
            .expect("a chord end at t = 0.5");
        assert!((mid.joints[0] - 10.0).abs() < 1e-12 && (mid.joints[1] - 90.0).abs() < 1e-12);
    }

    #[test]
    fn the_centre_is_refused() {
        assert!(polar_chords(&line([-5.0, 0.0], [5.0, 0.0]), 180.0, 1e-3).is_err());
        // Near it but not through it: many chords, still bounded.
        let ch = polar_chords(&line([-5.0, 0.01], [5.0, 0.01]), 180.0, 1e-3).unwrap();
        assert!(ch.len() < MAX_CHORDS);
        assert!((ch.last().unwrap().joints[1] - 0.01f64.atan2(5.0).to_degrees()).abs() < 1e-9);
    }

    #[test]
    fn cylindrical_lines_are_one_chord_and_arcs_keep_the_sagitta() {
        // Z from 0 to -20 while the developed s goes 0 → 31.415927 on R20: C 0 → 90.
        let s = 20.0 * std::f64::consts::FRAC_PI_2;
        let ch = cylindrical_chords(&line([0.0, 0.0], [-20.0, s]), 20.0, 1e-3).unwrap();
        assert_eq!(ch.len(), 1);
        assert!((ch[0].joints[1] - 90.0).abs() < 1e-12);
        assert!((ch[0].length - 20.0f64.hypot(s)).abs() < 1e-12);
        let arc = Seg2::arc_through([0.0, 10.0], [0.0, 0.0], [0.0, 20.0], true, false);
        let ch = cylindrical_chords(&arc, 20.0, 1e-3).unwrap();
        // Half circle R10 in 1 µm sagitta: n = ceil(π / (2·acos(1 − 1e-4))) = 112.
        assert_eq!(ch.len(), 112);
    }
}
