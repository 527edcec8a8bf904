//! Milling cycles in the working plane (spec axioma-3 §9, manual 11.8): G387 rectangular pocket,
//! G388 slot, G389 circular pocket.
//!
//! Common: r_e = Q12 or the selected tool's radius (no tool or D0 → 603; Q12 < tool radius →
//! 603); stepover e = 2·r_e − Q13; layers d_k = min(k·Q6, |Q5|); W = a3 of the call point.
//! ```text
//!  pocket layer: F=Q3 a3 → W + s·d_k (at the centre); clearing from the centre outwards (F=Q3);
//!                F=Q4 a3 → L(Q1); F=Q4 plane → centre.          end: RAPID a3 → return level
//!  G387 [D] A29: rings j = 0 … n of half-extents (A − (n−j)δ, B − (n−j)δ), corner radius
//!       max(ρ_f − (n−j)δ, 0), ring 0 a segment along the longer side, ring n the final contour
//!       (A = Q7/2 − r_e, B = Q8/2 − r_e, ρ_f = Q10 − r_e). δ = min(A, B)/n with n chosen so that
//!       √2·δ ≤ e: the gap between neighbouring rings, sharp ring corners included, is ≤ e.
//!  G389 [D]: circles of radius j·R_f/n, n = ⌈R_f/e⌉, R_f = Q7/2 − r_e, each a full turn.
//!  G388 [D] A31: centres P1 = call point, P2 = P1 + (Q7 − Q8)·(cos Q11, sin Q11); layers
//!       alternate P1 → P2, P2 → P1; then racetracks of half-width min(j·Q13, Q8/2 − r_e) at full
//!       depth; F=Q4 a3 → L(Q1); RAPID a3 → return level.
//! ```
//! All ring / racetrack traversals follow Q9 (1 = CCW, −1 = CW seen from +a3) in program
//! coordinates; mirror and rotation frames transform them as the manual's tables say.

use super::Call;
use crate::arc::PlanarArc;
use stanok_canon::{Diagnostic, Pose};

/// What every milling cycle checks and derives first.
struct Milling {
    a: usize,
    b: usize,
    n: usize,
    /// Effective tool radius (program units after un-scaling).
    re: f64,
    q1: f64,
    s: f64,
    depth: f64,
    q6: f64,
    w: f64,
    ret: f64,
    /// 1 / scale in the plane (Q12, Q13 are never scaled).
    kp: f64,
    ccw: bool,
    layers: usize,
    centre: [f64; 2],
}

fn common(c: &mut Call<'_, '_>) -> Result<Milling, Diagnostic> {
    let plane = c.cx.st.plane;
    let (a, b, n) = plane.axes();
    if c.cx.fe.chain.non_uniform_in(plane).is_some() {
        return Err(c.cx.err(
            "axioma::cycle-unequal-scale",
            "milling cycles under unequal in-plane scale factors are not supported",
            c.span,
        ));
    }
    let (tool, edge) = (c.cx.st.current_tool, c.cx.fe.modes.edge);
    if tool == 0 || edge == 0 {
        return Err(c
            .cx
            .manual(
                603,
                "milling cycle called without a selected tool (T0 or D0)",
                c.span,
            )
            .with_note("select the cutter with T… M06 before the cycle"));
    }
    let r_tool =
        c.cx.opts
            .control
            .tools
            .edge(tool, edge as u32)
            .map(|e| e.radius + e.radius_wear)
            .unwrap_or(0.0);
    let kp = c.unscale(a);
    let k3 = c.unscale(n);
    let re = c.q(
        12,
        r_tool,
        |v| v >= r_tool - 1e-9 && v >= 0.0,
        "the tool radius Q12 must not be smaller than the selected tool's radius",
    )?;
    let q1 = c.q(1, 5.0, |v| v >= 0.1, "safety distance 1 must be ≥ 0.1 mm")?;
    let q5 = c.q(5, 0.0, |v| v != 0.0, "the depth Q5 must not be 0")?;
    let q6 = c.q(
        6,
        0.0,
        |v| v > 0.0 && v <= q5.abs(),
        "the layer depth Q6 must be > 0 and ≤ |Q5|",
    )?;
    let q9 = c.q(
        9,
        1.0,
        |v| v == 1.0 || v == -1.0,
        "the direction Q9 must be 1 (CCW) or −1 (CW)",
    )?;
    let s = q5.signum();
    let p = c.p.to_array();
    let w = p[n];
    let h0 = c.h0.to_array()[n];
    let ret = c.return_level(h0, w, s, q1, k3)?;
    // Q6 is never scaled: the layers count in unscaled depth.
    let layers = c.passes(q5.abs(), q6 * k3, 6)?;
    Ok(Milling {
        a,
        b,
        n,
        re: re * kp,
        q1: q1 * k3,
        s,
        depth: q5.abs(),
        q6: q6 * k3,
        w,
        ret,
        kp,
        ccw: q9 > 0.0,
        layers,
        centre: [p[a], p[b]],
    })
}

/// A plane point as the axis targets of a move (a3 unchanged).
fn at(m: &Milling, pt: [f64; 2]) -> Vec<(usize, f64)> {
    vec![(m.a, pt[0]), (m.b, pt[1])]
}

fn arc_to(c: &mut Call<'_, '_>, m: &Milling, centre: [f64; 2], end: [f64; 2], ccw: bool) {
    let mut e = c.cx.st.program_position().to_array();
    e[m.a] = end[0];
    e[m.b] = end[1];
    let plane = c.cx.st.plane;
    let f = c.q3;
    c.cx.arc(
        plane,
        ccw,
        Pose::from_array(e),
        PlanarArc { centre, turns: 1 },
        f,
    );
}

fn start_and_layer(c: &mut Call<'_, '_>, m: &Milling, k: usize) {
    if k == 1 {
        c.rapid(&at(m, m.centre));
        c.rapid(&[(m.n, m.w - m.s * m.q1)]);
    }
    let d = (k as f64 * m.q6).min(m.depth);
    c.cut(&[(m.n, m.w + m.s * d)]);
}

fn end_layer(c: &mut Call<'_, '_>, m: &Milling) {
    c.idle(&[(m.n, m.w - m.s * m.q1)]);
    c.idle(&at(m, m.centre));
}

/// A rounded rectangle about `o`: local u along `dir`, v to its left, half-extents `ha` × `hb`,
/// corner radius `rho`.
struct RoundedRect {
    o: [f64; 2],
    dir: [f64; 2],
    ha: f64,
    hb: f64,
    rho: f64,
}

/// Runs a rounded rectangle once in the given direction, started (and ended) at the middle of
/// its side v = −hb.
fn ring(c: &mut Call<'_, '_>, m: &Milling, rect: &RoundedRect, ccw: bool) {
    let RoundedRect {
        o,
        dir,
        ha,
        hb,
        rho,
    } = *rect;
    let to = |u: f64, v: f64| {
        [
            o[0] + u * dir[0] - v * dir[1],
            o[1] + u * dir[1] + v * dir[0],
        ]
    };
    let rho = rho.clamp(0.0, ha.min(hb));
    c.cut(&at(m, to(0.0, -hb)));
    // Corners CCW from the bottom right: (sign u, sign v).
    let corners = [(1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0)];
    // CCW: bottom → right → top → left; CW runs the same corners in reverse.
    let order: [usize; 4] = if ccw { [0, 1, 2, 3] } else { [3, 2, 1, 0] };
    for &i in &order {
        let (su, sv) = corners[i];
        // Entering point of the corner's arc and its exit, in the running direction.
        let (p_in, p_out) = if ccw {
            if i % 2 == 0 {
                (to(su * (ha - rho), sv * hb), to(su * ha, sv * (hb - rho)))
            } else {
                (to(su * ha, sv * (hb - rho)), to(su * (ha - rho), sv * hb))
            }
        } else if i % 2 == 0 {
            (to(su * ha, sv * (hb - rho)), to(su * (ha - rho), sv * hb))
        } else {
            (to(su * (ha - rho), sv * hb), to(su * ha, sv * (hb - rho)))
        };
        c.cut(&at(m, p_in));
        if rho > 1e-9 {
            let centre = to(su * (ha - rho), sv * (hb - rho));
            arc_to(c, m, centre, p_out, ccw);
        }
    }
    c.cut(&at(m, to(0.0, -hb)));
}

/// G387.
pub(super) fn rectangular(c: &mut Call<'_, '_>) -> Result<(), Diagnostic> {
    let m = common(c)?;
    let re = m.re;
    let q7 = c.q(
        7,
        0.0,
        |v| v > 0.0 && v >= 2.0 * re - 1e-9,
        "the size Q7 must be > 0 and ≥ the tool diameter",
    )?;
    let q8 = c.q(
        8,
        0.0,
        |v| v > 0.0 && v >= 2.0 * re - 1e-9,
        "the size Q8 must be > 0 and ≥ the tool diameter",
    )?;
    let q10 = c.q(
        10,
        0.0,
        |v| v >= re - 1e-9 && v > 0.0 && v <= q7.min(q8) / 2.0 + 1e-9,
        "the corner radius Q10 must be ≥ the tool radius and ≤ half the smaller side",
    )?;
    let q11 = c.q(11, 0.0, |_| true, "")?;
    let q13 = c.q(
        13,
        0.0,
        |v| v > 0.0 && v < 2.0 * re,
        "the overlap Q13 must be > 0 and < the tool diameter",
    )?;
    let (ha, hb, rho_f) = (q7 / 2.0 - re, q8 / 2.0 - re, q10 - re);
    let e = 2.0 * re - q13 * m.kp;
    let short = ha.min(hb);
    let n = c.passes(short * std::f64::consts::SQRT_2, e, 13)?.max(1);
    let delta = short / n as f64;
    let dir = [q11.to_radians().cos(), q11.to_radians().sin()];
    for k in 1..=m.layers {
        start_and_layer(c, &m, k);
        // Ring 0: the segment along the longer local axis (nothing if A = B).
        let seg = (ha - hb).abs();
        if seg > 1e-9 {
            let (du, dv) = if ha >= hb { (seg, 0.0) } else { (0.0, seg) };
            let o = m.centre;
            let p = |s: f64| {
                [
                    o[0] + s * (du * dir[0] - dv * dir[1]),
                    o[1] + s * (du * dir[1] + dv * dir[0]),
                ]
            };
            c.cut(&at(&m, p(1.0)));
            c.cut(&at(&m, p(-1.0)));
            c.cut(&at(&m, m.centre));
        }
        for j in 1..=n {
            let shrink = (n - j) as f64 * delta;
            let rect = RoundedRect {
                o: m.centre,
                dir,
                ha: ha - shrink,
                hb: hb - shrink,
                rho: (rho_f - shrink).max(0.0),
            };
            ring(c, &m, &rect, m.ccw);
        }
        end_layer(c, &m);
    }
    c.rapid(&[(m.n, m.ret)]);
    Ok(())
}

/// G389.
pub(super) fn circular(c: &mut Call<'_, '_>) -> Result<(), Diagnostic> {
    let m = common(c)?;
    let re = m.re;
    let q7 = c.q(
        7,
        0.0,
        |v| v > 0.0 && v >= 2.0 * re - 1e-9,
        "the diameter Q7 must be > 0 and ≥ the tool diameter",
    )?;
    let q13 = c.q(
        13,
        0.0,
        |v| v > 0.0 && v < 2.0 * re,
        "the overlap Q13 must be > 0 and < the tool diameter",
    )?;
    let rf = q7 / 2.0 - re;
    let e = 2.0 * re - q13 * m.kp;
    let n = c.passes(rf, e, 13)?;
    for k in 1..=m.layers {
        start_and_layer(c, &m, k);
        for j in 1..=n {
            let rho = j as f64 * rf / n as f64;
            let p = [m.centre[0] + rho, m.centre[1]];
            c.cut(&at(&m, p));
            arc_to(c, &m, m.centre, p, m.ccw);
        }
        end_layer(c, &m);
    }
    c.rapid(&[(m.n, m.ret)]);
    Ok(())
}

/// G388.
pub(super) fn slot(c: &mut Call<'_, '_>) -> Result<(), Diagnostic> {
    let m = common(c)?;
    let re = m.re;
    let q8 = c.q(
        8,
        0.0,
        |v| v > 0.0 && v >= 2.0 * re - 1e-9,
        "the slot width Q8 must be > 0 and ≥ the tool diameter",
    )?;
    let q7 = c.q(
        7,
        0.0,
        |v| v > 0.0 && v >= 2.0 * re - 1e-9 && v >= q8,
        "the slot length Q7 must be ≥ the tool diameter and ≥ Q8",
    )?;
    let q11 = c.q(11, 0.0, |_| true, "")?;
    let q13 = c.q(
        13,
        0.0,
        |v| v > 0.0 && v < 2.0 * re,
        "the peripheral step Q13 must be > 0 and < the tool diameter",
    )?;
    let lc = q7 - q8;
    let dir = [q11.to_radians().cos(), q11.to_radians().sin()];
    let p1 = m.centre;
    let p2 = [p1[0] + lc * dir[0], p1[1] + lc * dir[1]];
    let half = q8 / 2.0 - re;
    let q13 = q13 * m.kp;
    let loops = c.passes(half, q13, 13)?;
    let mut here = p1;
    for k in 1..=m.layers {
        start_and_layer(c, &m, k);
        here = if k % 2 == 1 { p2 } else { p1 };
        c.cut(&at(&m, here));
    }
    // Racetracks about the segment, started at the cap apex behind the end the tool is at.
    let (e, other) = if here == p2 { (p2, p1) } else { (p1, p2) };
    let u = if lc > 1e-12 {
        [(other[0] - e[0]) / lc, (other[1] - e[1]) / lc]
    } else {
        dir
    };
    for j in 1..=loops {
        let w = (j as f64 * q13).min(half);
        let to = |a: f64, v: f64| [e[0] + a * u[0] - v * u[1], e[1] + a * u[1] + v * u[0]];
        c.cut(&at(&m, to(-w, 0.0)));
        let far = [e[0] + lc * u[0], e[1] + lc * u[1]];
        let s = if m.ccw { 1.0 } else { -1.0 };
        // Quarter about E to the side, the long side, half turn about the far centre, back.
        arc_to(c, &m, e, to(0.0, -s * w), m.ccw);
        c.cut(&at(&m, to(lc, -s * w)));
        arc_to(c, &m, far, to(lc, s * w), m.ccw);
        c.cut(&at(&m, to(0.0, s * w)));
        arc_to(c, &m, e, to(-w, 0.0), m.ccw);
    }
    c.idle(&[(m.n, m.w - m.s * m.q1)]);
    c.rapid(&[(m.n, m.ret)]);
    Ok(())
}
