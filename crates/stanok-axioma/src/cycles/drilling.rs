//! G81 drilling and G83 peck drilling (spec axioma-3 §7, manual 11.6).
//!
//! Tool axis a3 = Z (G17), Y (G18), X (G19). W = a3 of the call point (surface level),
//! s = sign(Q5), D = |Q5|, L(q) = W − s·q ("q above the surface"):
//! ```text
//!  G81: RAPID plane → call point (a3 = H0); RAPID a3 → L(Q1); F=Q3 a3 → W + s·D; dwell Q6;
//!       F=Q4 a3 → L(Q1); RAPID a3 → H0 (G98) | L(Q2) (G99)
//!  G83: … F=Q3 a3 → W + s·d1 (d1 = min(Q7, D)); dwell Q6; then until D:
//!       F=Q4 retract (Q9 > 0: by Q9 above the last level; else to L(Q1)); dwell Q10;
//!       F=Q11 approach to Q1 above the last level (skipped unless it lies between — A19);
//!       F=Q3 a3 → W + s·d_k (d_k = min(d_(k−1) + Q8, D)); dwell Q6
//!       finally F=Q4 a3 → L(Q1); RAPID → return level
//! ```
//! Parameters are never transformed by G173 (§6.6): lengths along a3 are divided by its scale.

use super::{Call, CycleKind};
use stanok_canon::Diagnostic;

pub(super) fn run(c: &mut Call<'_, '_>) -> Result<(), Diagnostic> {
    let (a, b, n) = c.cx.st.plane.axes();
    let k = c.unscale(n);
    let q1 = c.q(1, 5.0, |v| v >= 0.1, "safety distance 1 must be ≥ 0.1 mm")?;
    let q5 = c.q(5, 0.0, |v| v != 0.0, "the drilling depth Q5 must not be 0")?;
    let q6 = c.q(6, 0.0, |v| v >= 0.0, "the dwell Q6 must be ≥ 0")?;
    let s = q5.signum();
    let depth = q5.abs();
    let w = c.p.to_array()[n];
    let h0 = c.h0.to_array()[n];
    let level = |q: f64| w - s * q * k;
    let ret = c.return_level(h0, w, s, q1, k)?;
    let p = c.p.to_array();
    // 1. Parallel to the plane at the initial height, then 2. down to safety distance 1.
    c.rapid(&[(a, p[a]), (b, p[b])]);
    c.rapid(&[(n, level(q1))]);
    if c.kind == CycleKind::Drill {
        c.cut(&[(n, w + s * depth * k)]);
        c.dwell(q6);
    } else {
        let q7 = c.q(
            7,
            0.0,
            |v| v > 0.0 && v <= depth,
            "the first pass Q7 must be > 0 and ≤ |Q5|",
        )?;
        let q8 = c.q(
            8,
            q7,
            |v| v > 0.0 && v <= depth,
            "the pass depth Q8 must be > 0 and ≤ |Q5|",
        )?;
        let q9 = c.q(9, 0.0, |v| v >= 0.0, "the retraction Q9 must be ≥ 0")?;
        let q10 = c.q(10, 0.0, |v| v >= 0.0, "the dwell Q10 must be ≥ 0")?;
        let q11 = match c.q_opt(11, |v| v > 0.0, "the approach feed Q11 must be > 0")? {
            Some(f) => Some(f),
            None => c.q4,
        };
        let mut d = q7.min(depth);
        c.passes(depth - d, q8, 8)?;
        c.cut(&[(n, w + s * d * k)]);
        c.dwell(q6);
        while d < depth - 1e-12 {
            let next = (d + q8).min(depth);
            let retract = if q9 > 0.0 {
                w + s * (d - q9) * k
            } else {
                level(q1)
            };
            c.idle(&[(n, retract)]);
            c.dwell(q10);
            let approach = w + s * (d - q1) * k;
            let last = w + s * d * k;
            // A19: only when the approach level lies between the tool and the last level.
            if (approach - retract) * (last - approach) > 0.0 {
                c.axes_to(&[(n, approach)], q11);
            }
            c.cut(&[(n, w + s * next * k)]);
            c.dwell(q6);
            d = next;
        }
    }
    c.idle(&[(n, level(q1))]);
    c.rapid(&[(n, ret)]);
    Ok(())
}
