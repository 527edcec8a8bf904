//! Turning cycles on the fixed axes X (radial, index 0) and Z (index 2) whatever the plane
//! (spec axioma-3 §8, manual 11.7): G276 threading, G281/G282 recess roughing, G288/G289 grooving.
//!
//! G281 and G282 (and G288 and G289) are one algorithm with the roles of the axes exchanged:
//! `depth` is the axis the recess depth Q5 is measured on (X for G281/G288, Z for G282/G289) and
//! `along` the axis of its length (Q9 resp. Q6).
//! ```text
//!  recess ([D] A27 trapezoid, entry wall over Q7, exit wall over Q8):
//!    RAPID along → start; RAPID depth → surface − sD·Q1;
//!    pass k (d_k = min(k·Q6, D)): F=Q3 to (surface + sD·d_k, in(d_k)); F=Q3 along → out(d_k);
//!      not last: F=Q4 depth → surface + sD·(d_k − Q10); F=Q4 along → in(d_k)
//!    F=Q4 depth → surface − sD·Q1; RAPID depth → H0 (G98) | surface − sD·Q2 (G99)
//!    in(d) = start + sL·Q7·d/D, out(d) = start + sL·(L − Q8·d/D)
//!  groove ([D] A28): plunges at start + sL·min(j·(Q7 − Q9), L − Q7), j = 0 … ⌈(L − Q7)/(Q7 − Q9)⌉:
//!    F=Q3 depth → surface + sD·D; dwell Q8; F=Q4 depth → surface − sD·Q1; F=Q4 along → next
//!  thread ([D] A26): RAPID X → Xc; RAPID Z → Z_run = Zc − sZ·Q1; pass k: F=Q4 X → Xc + sX·t_k;
//!    StartSpindleSync(pitch Q7); F = S·Q7/cos(a/2) Z → Z_end = Zc + sZ·(Q6 + Q5); StopSpindleSync;
//!    F=Q4 X back by Q12; F=Q4 Z → Z_run; F=Q4 X → Xc. End RAPID Z → H0z | Zc − sZ·Q2.
//!    t_1 = min(Q9, Dt), t_k = min(t_(k−1) + Q10, Dt), then Q13 idle passes at Dt.
//! ```

use super::Call;
use stanok_canon::{Canon, Diagnostic};

const X: usize = 0;
const Z: usize = 2;

/// G281 (depth X, along Z) and G282 (depth Z, along X).
pub(super) fn recess(c: &mut Call<'_, '_>, depth: usize, along: usize) -> Result<(), Diagnostic> {
    let (kd, kl) = (c.unscale(depth), c.unscale(along));
    let q1 = c.q(1, 5.0, |v| v >= 0.1, "safety distance 1 must be ≥ 0.1 mm")?;
    let q5 = c.q(5, 0.0, |v| v != 0.0, "the recess depth Q5 must not be 0")?;
    let q6 = c.q(6, 0.0, |v| v > 0.0, "the pass depth Q6 must be > 0")?;
    let q7 = c.q(7, 0.0, |v| v >= 0.0, "the entry length Q7 must be ≥ 0")?;
    let q8 = c.q(8, 0.0, |v| v >= 0.0, "the exit length Q8 must be ≥ 0")?;
    let q9 = c.q(
        9,
        0.0,
        |v| v != 0.0 && v.abs() >= q7 + q8,
        "the recess length Q9 must not be 0 and |Q9| ≥ Q7 + Q8",
    )?;
    let q10 = c.q(10, q1, |v| v >= 0.0, "the return distance Q10 must be ≥ 0")?;
    let (sd, dd) = (q5.signum(), q5.abs());
    let (sl, len) = (q9.signum(), q9.abs());
    let p = c.p.to_array();
    let (surface, start) = (p[depth], p[along]);
    let h0 = c.h0.to_array()[depth];
    let ret = c.return_level(h0, surface, sd, q1, kd)?;
    let n = c.passes(dd, q6, 6)?;
    let wall_in = |d: f64| start + sl * q7 * d / dd * kl;
    let wall_out = |d: f64| start + sl * (len - q8 * d / dd) * kl;
    c.rapid(&[(along, start)]);
    c.rapid(&[(depth, surface - sd * q1 * kd)]);
    for k in 1..=n {
        let d = (k as f64 * q6).min(dd);
        c.cut(&[(depth, surface + sd * d * kd), (along, wall_in(d))]);
        c.cut(&[(along, wall_out(d))]);
        if k < n {
            c.idle(&[(depth, surface + sd * (d - q10) * kd)]);
            c.idle(&[(along, wall_in(d))]);
        }
    }
    c.idle(&[(depth, surface - sd * q1 * kd)]);
    c.rapid(&[(depth, ret)]);
    Ok(())
}

/// G288 (plunges along X, stepping along Z) and G289 (plunges along Z, stepping along X).
pub(super) fn groove(c: &mut Call<'_, '_>, depth: usize, along: usize) -> Result<(), Diagnostic> {
    let (kd, kl) = (c.unscale(depth), c.unscale(along));
    let q1 = c.q(1, 5.0, |v| v >= 0.1, "safety distance 1 must be ≥ 0.1 mm")?;
    let q5 = c.q(5, 0.0, |v| v != 0.0, "the groove depth Q5 must not be 0")?;
    let q6 = c.q(6, 0.0, |v| v != 0.0, "the groove length Q6 must not be 0")?;
    let q7 = c.q(
        7,
        0.0,
        |v| v > 0.0 && v <= q6.abs(),
        "the tool width Q7 must be > 0 and ≤ |Q6|",
    )?;
    let q8 = c.q(8, 0.0, |v| v >= 0.0, "the dwell Q8 must be ≥ 0")?;
    let q9 = c.q(
        9,
        0.0,
        |v| v > 0.0 && v < q7,
        "the overlap Q9 must be > 0 and < Q7",
    )?;
    let (sd, dd) = (q5.signum(), q5.abs());
    let (sl, len) = (q6.signum(), q6.abs());
    let p = c.p.to_array();
    let (surface, start) = (p[depth], p[along]);
    let h0 = c.h0.to_array()[depth];
    let ret = c.return_level(h0, surface, sd, q1, kd)?;
    let step = q7 - q9;
    let m = c.passes(len - q7, step, 9)?;
    c.rapid(&[(along, start)]);
    c.rapid(&[(depth, surface - sd * q1 * kd)]);
    for j in 0..=m {
        if j > 0 {
            let at = start + sl * (j as f64 * step).min(len - q7) * kl;
            c.idle(&[(along, at)]);
        }
        c.cut(&[(depth, surface + sd * dd * kd)]);
        c.dwell(q8);
        c.idle(&[(depth, surface - sd * q1 * kd)]);
    }
    c.rapid(&[(depth, ret)]);
    Ok(())
}

/// G276 multi-pass threading along Z.
pub(super) fn thread(c: &mut Call<'_, '_>) -> Result<(), Diagnostic> {
    if !c.cx.fe.params.spindle_encoder {
        return Err(c
            .cx
            .manual(
                2301,
                "threading needs a spindle position encoder: none is configured",
                c.span,
            )
            .with_note(
                "G276 synchronises every pass with the spindle angle (spec axioma-3 §8.1)",
            ));
    }
    // §8.1 [M] precondition, §9.4 [D] error (issue 22 item 6): under G96 the spindle speed follows
    // the tool's radius, so S·pitch would not be a constant thread feed.
    if c.cx.fe.tech.css {
        return Err(c
            .cx
            .err(
                "axioma::thread-under-css",
                "G276 is called with constant surface speed G96 active",
                c.span,
            )
            .with_note(
                "switch to a constant spindle speed with G97 S… before the threading cycle",
            ));
    }
    let speed = c.cx.st.spindle_speed[0];
    if !c.cx.st.spindle_on[0] || speed <= 0.0 {
        return Err(c
            .cx
            .err(
                "axioma::thread-spindle-stopped",
                "G276 is called with the main spindle stopped",
                c.span,
            )
            .with_note("start the spindle with M3/M4 and S before the threading cycle"));
    }
    let (kx, kz) = (c.unscale(X), c.unscale(Z));
    let q1 = c.q(
        1,
        5.0,
        |v| v >= 0.1,
        "the run-up length Q1 must be ≥ 0.1 mm",
    )?;
    let q5 = c.q(5, 0.0, |v| v >= 0.0, "the run-out length Q5 must be ≥ 0")?;
    let q6 = c.q(6, 0.0, |v| v > 0.0, "the thread length Q6 must be > 0")?;
    let q7 = c.q(
        7,
        0.0,
        |v| v > 0.0 && v < q6,
        "the pitch Q7 must be > 0 and < Q6",
    )?;
    let q8 = c.q(8, 0.0, |v| v != 0.0, "the thread depth Q8 must not be 0")?;
    let dt = q8.abs();
    let q9 = c.q(
        9,
        0.0,
        |v| v > 0.0 && v <= dt,
        "the first cut Q9 must be > 0 and ≤ |Q8|",
    )?;
    let q10 = c.q(
        10,
        q9,
        |v| v > 0.0 && v <= dt,
        "the cut Q10 must be > 0 and ≤ |Q8|",
    )?;
    let q11 = c.q(
        11,
        0.0,
        |v| v > 0.0 && v < q7,
        "the thread tolerance Q11 must be > 0 and < Q7",
    )?;
    // Manual (3): S = 60·E/(P·T) with a 1 ms drive cycle — faster spindles may delay the passes.
    let s_max = 60.0 * q11 / (q7 * 0.001);
    if speed > s_max {
        c.cx.warnings.push(
            Diagnostic::warning(
                "axioma::thread-speed",
                format!("S{speed} is above the recommended {s_max:.0} rpm for the thread tolerance Q11 = {q11} mm"),
                c.cx.block.span(),
            )
            .with_note("the start of the 2nd and later passes may be delayed (spec axioma-3 §8.1 (3), T = 1 ms)"),
        );
    }
    let q12 = c.q(12, 2.0, |v| v > 0.0, "the retraction Q12 must be > 0")?;
    let q13 = c.q(
        13,
        0.0,
        |v| v >= 0.0 && v.fract() == 0.0 && v <= super::MAX_PASSES,
        "the idle passes Q13 must be a whole number ≥ 0",
    )?;
    let q14 = c.q(14, 0.0, |_| true, "")?;
    let q15 = c.q(
        15,
        0.0,
        |v| v == 0.0 || v == 1.0,
        "Q15 must be 0 (both flanks) or 1 (one flank)",
    )?;
    let q16 = c.q(
        16,
        60.0,
        |v| v > 0.0 && v < 180.0,
        "the thread angle Q16 must be > 0° and < 180°",
    )?;
    let half_taper = (q14.abs() / 2.0 / q6).atan();
    let feed = speed * q7 / half_taper.cos();
    if let Some(max) = c.cx.fe.params.max_feed {
        if feed > max {
            return Err(c
                .cx
                .err(
                    "axioma::thread-feed",
                    format!("thread feed {feed:.1} mm/min exceeds the maximum feed {max} mm/min"),
                    c.span,
                )
                .with_note(
                    "lower S: the thread feed is S·pitch/cos(a/2) (spec axioma-3 §8.1 (4))",
                ));
        }
    }
    let p = c.p.to_array();
    let (xc, zc) = (p[X], p[Z]);
    let h0z = c.h0.to_array()[Z];
    let sx = q8.signum();
    let sz = if zc - h0z > 0.0 { 1.0 } else { -1.0 };
    let z_run = zc - sz * q1 * kz;
    let z_end = zc + sz * (q6 + q5) * kz;
    // Taper: the radius changes by Q14/2 over Q6, with the same slope over Q1 and Q5.
    let slope = q14 / 2.0 / q6;
    let at_run = -slope * q1 * kx;
    let at_end = slope * (q6 + q5) * kx;
    let ret = if c.cx.st.retract_to_initial {
        h0z
    } else {
        let q2 = c.q(2, q1, |v| v >= 0.0, "safety distance 2 must be ≥ 0")?;
        zc - sz * q2 * kz
    };
    let cuts = c.passes(dt - q9, q10, 10)? + 1 + q13 as usize;
    let flank = (q16.to_radians() / 2.0).tan();
    c.rapid(&[(X, xc)]);
    c.rapid(&[(Z, z_run)]);
    let mut t = 0.0f64;
    for k in 0..cuts {
        t = if k == 0 {
            q9.min(dt)
        } else {
            (t + q10).min(dt)
        };
        // [D] A26: one-flank cutting shifts each pass towards the run-up side by t·tan(Q16/2).
        let shift = if q15 == 1.0 {
            -sz * t * flank * kz
        } else {
            0.0
        };
        let x = xc + sx * t * kx;
        c.idle(&[(X, x + at_run), (Z, z_run + shift)]);
        c.cx.out.push(Canon::StartSpindleSync {
            pitch: q7,
            velocity_mode: false,
        });
        c.axes_to(&[(X, x + at_end), (Z, z_end + shift)], Some(feed));
        c.cx.out.push(Canon::StopSpindleSync);
        c.idle(&[(X, x + at_end - sx * q12 * kx)]);
        c.idle(&[(Z, z_run)]);
        c.idle(&[(X, xc)]);
    }
    c.rapid(&[(Z, ret)]);
    Ok(())
}
