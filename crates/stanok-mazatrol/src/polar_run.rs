//! G12.1/G13.1 polar coordinate interpolation and G07.1 cylindrical interpolation as blocks
//! (`docs/dialects/mazatrol-eia.md` §12; the chords come from `polar.rs`).
//!
//! Each chord is a joint-space move (X the radius, C the angle; or Z and C) timed so that it takes
//! its virtual length at the programmed feed: Canon's feed applies to the XYZ length of a move
//! (or to its rotary length when no linear axis moves), so a chord's feed is
//! `F · (its feed length) / (its virtual length)`.

use crate::ctx::Ctx;
use crate::polar::{cylindrical_chords, polar_chords, to_virtual, Chord};
use stanok_canon::{Canon, Diagnostic, LineMove, Pose};
use stanok_geom::centre_from_radius;
use stanok_geom::offset2d::{Seg2, P2};
use stanok_interp_core::{DistanceMode, MotionMode};
use stanok_syntax::ColSpan;

/// The chord tolerance, mm.
const TOLERANCE: f64 = 1e-3;

fn need_c(cx: &Ctx<'_>, span: ColSpan, what: &str) -> Result<(), Diagnostic> {
    if !cx.opts.axes[5] {
        return Err(cx.err(
            "mazatrol::polar",
            format!("{what} needs a C axis: this machine has none"),
            span,
        ));
    }
    if !cx.fe.m.t() {
        return Err(cx.err(
            "mazatrol::unknown-code",
            format!("{what} is a T-series function"),
            span,
        ));
    }
    Ok(())
}

/// G12.1 on / G13.1 off, alone in their block.
pub(crate) fn polar_mode(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    if code == 131 {
        cx.fe.m.polar = false;
        return Ok(());
    }
    need_c(cx, span, "G12.1")?;
    if cx.has_axis_words() {
        return Err(cx.err(
            "mazatrol::polar",
            "G12.1 must be alone in its block (no axis words)",
            span,
        ));
    }
    if crate::compensate::active(cx) {
        return Err(cx.err(
            "mazatrol::compensation",
            "G12.1 cannot start under nose radius compensation [D]",
            span,
        ));
    }
    cx.fe.m.polar = true;
    Ok(())
}

/// `G07.1 C r` on, `G07.1 C0` off.
pub(crate) fn cylinder_mode(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    need_c(cx, span, "G07.1")?;
    let Some(c) = cx.words.take(b'C') else {
        return Err(cx.err(
            "mazatrol::missing-word",
            "G07.1 needs the cylinder radius C (C0 switches it off)",
            span,
        ));
    };
    let r = cx.mm(c.v);
    if r < 0.0 {
        return Err(cx.err(
            "mazatrol::value-range",
            "the cylinder radius must not be negative",
            c.span,
        ));
    }
    cx.fe.m.cylinder = (r > 0.0).then_some(r);
    Ok(())
}

/// Emits chords (joint ends in program coordinates `ends`), each timed by its virtual length.
fn emit_chords(
    cx: &mut Ctx<'_>,
    ends: &[(Pose, f64)],
    rapid: bool,
    total_virtual: f64,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let f = if rapid {
        0.0
    } else {
        if cx.st.feed <= 0.0 {
            return Err(cx.err(
                "mazatrol::feed-missing",
                "a feed move needs a feed: no F has been programmed",
                at,
            ));
        }
        cx.path_feed(total_virtual)
    };
    for &(end, virtual_len) in ends {
        let start = cx.st.position;
        let end_m = cx.st.frame.to_machine(&end);
        crate::motion::stroke_check(cx, &[start.to_array(), end_m.to_array()], at)?;
        let s = start.to_array();
        let e = end_m.to_array();
        let len = |r: std::ops::Range<usize>| r.map(|i| (e[i] - s[i]).powi(2)).sum::<f64>().sqrt();
        let xyz = len(0..3);
        let feed_len = if xyz > 0.0 { xyz } else { len(3..6) };
        let feed = if rapid || virtual_len <= 0.0 {
            f
        } else {
            f * feed_len / virtual_len
        };
        let m = LineMove {
            start,
            end: end_m,
            feed: if rapid { 0.0 } else { feed.max(1e-9) },
            law: stanok_canon::FeedLaw::PerMinute,
        };
        cx.out.push(if rapid {
            Canon::StraightTraverse(m)
        } else {
            Canon::StraightFeed(m)
        });
        cx.st.position = end_m;
    }
    Ok(())
}

/// A block in G12.1: the virtual face plane (X the radius, C a length) and Z.
pub(crate) fn motion(cx: &mut Ctx<'_>) -> Result<bool, Diagnostic> {
    let at = cx.whole();
    let now = cx.st.program_position().to_array();
    let v0 = to_virtual([now[0], now[5]]);
    let inc = cx.st.distance == DistanceMode::Incremental;
    let x = cx.words.take(b'X').map(|v| cx.mm(v.v));
    let u = cx.words.take(b'U').map(|v| cx.mm(v.v));
    let c = cx.words.take(b'C').map(|v| cx.mm(v.v));
    let z = cx.words.take(b'Z').map(|v| cx.mm(v.v));
    let w = cx.words.take(b'W').map(|v| cx.mm(v.v));
    if [x, u, c, z, w].iter().all(Option::is_none) {
        return Ok(false);
    }
    let mut v1 = v0;
    if let Some(x) = x {
        v1[0] = if inc { v0[0] + x } else { x };
    }
    if let Some(u) = u {
        v1[0] = v0[0] + u;
    }
    if let Some(c) = c {
        v1[1] = if inc { v0[1] + c } else { c };
    }
    let mut z1 = now[2];
    if let Some(z) = z {
        z1 = if inc { now[2] + z } else { z };
    }
    if let Some(w) = w {
        z1 = now[2] + w;
    }
    let rapid = cx.st.motion == MotionMode::Rapid;
    let seg = match cx.st.motion {
        MotionMode::ArcCw | MotionMode::ArcCcw => {
            let ccw = cx.st.motion == MotionMode::ArcCcw;
            let centre = if let Some(r) = cx.words.take(b'R') {
                let r = cx.mm(r.v);
                centre_from_radius(v0, v1, r.abs(), ccw, r < 0.0, cx.opts.arc_tolerance_mm)
                    .map_err(|e| cx.err("mazatrol::arc-radius", e.to_string(), at))?
            } else {
                let i = cx.words.take(b'I').map_or(0.0, |v| cx.mm(v.v));
                let j = cx.words.take(b'J').map_or(0.0, |v| cx.mm(v.v));
                [v0[0] + i, v0[1] + j]
            };
            Seg2::arc_through(centre, v0, v1, ccw, false)
        }
        _ => Seg2::Line { a: v0, b: v1 },
    };
    if seg.length() < 1e-12 {
        // Z alone: one move.
        let mut p = now;
        p[2] = z1;
        crate::motion::emit_straight(cx, rapid, Pose::from_array(p), at)?;
        return Ok(true);
    }
    let chords =
        polar_chords(&seg, now[5], TOLERANCE).map_err(|e| cx.err("mazatrol::polar", e.0, at))?;
    let ends = poses(&chords, now, z1, |j, p| {
        p[0] = j[0];
        p[5] = j[1];
    });
    emit_chords(cx, &ends, rapid, seg.length(), at)?;
    Ok(true)
}

/// Chord ends as poses (Z interpolated by the element parameter).
fn poses(
    chords: &[Chord],
    now: [f64; 9],
    z1: f64,
    set: impl Fn([f64; 2], &mut [f64; 9]),
) -> Vec<(Pose, f64)> {
    chords
        .iter()
        .map(|ch| {
            let mut p = now;
            set(ch.joints, &mut p);
            p[2] = now[2] + (z1 - now[2]) * ch.t;
            (Pose::from_array(p), ch.length)
        })
        .collect()
}

/// A block in G07.1: Z and C (degrees) on the cylinder of radius `r`.
pub(crate) fn cylinder_motion(cx: &mut Ctx<'_>, r: f64) -> Result<bool, Diagnostic> {
    let at = cx.whole();
    let now = cx.st.program_position().to_array();
    let inc = cx.st.distance == DistanceMode::Incremental;
    let z = cx.words.take(b'Z').map(|v| cx.mm(v.v));
    let w = cx.words.take(b'W').map(|v| cx.mm(v.v));
    let c = cx.words.take(b'C');
    let h = cx.words.take(b'H');
    if z.is_none() && w.is_none() && c.is_none() && h.is_none() && !cx.has_axis_words() {
        return Ok(false);
    }
    let mut z1 = now[2];
    if let Some(z) = z {
        z1 = if inc { now[2] + z } else { z };
    }
    if let Some(w) = w {
        z1 = now[2] + w;
    }
    let mut c1 = now[5];
    if let Some(c) = c {
        c1 = if inc { now[5] + c.v } else { c.v };
    }
    if let Some(h) = h {
        c1 = now[5] + h.v;
    }
    // The developed plane (z, s), s = r·C in mm.
    let s0 = r * now[5].to_radians();
    let s1 = r * c1.to_radians();
    let a: P2 = [now[2], s0];
    let b: P2 = [z1, s1];
    let rapid = cx.st.motion == MotionMode::Rapid;
    let seg = match cx.st.motion {
        MotionMode::ArcCw | MotionMode::ArcCcw => {
            let ccw = cx.st.motion == MotionMode::ArcCcw;
            let Some(rw) = cx.words.take(b'R') else {
                return Err(cx.err(
                    "mazatrol::missing-word",
                    "arcs in cylindrical interpolation are given with R",
                    at,
                ));
            };
            let rr = cx.mm(rw.v);
            let centre =
                centre_from_radius(a, b, rr.abs(), ccw, rr < 0.0, cx.opts.arc_tolerance_mm)
                    .map_err(|e| cx.err("mazatrol::arc-radius", e.to_string(), at))?;
            Seg2::arc_through(centre, a, b, ccw, false)
        }
        _ => Seg2::Line { a, b },
    };
    // The other axes of the block move linearly (X, Y).
    let (end_other, _) = crate::motion::end_point(cx)?;
    let chords =
        cylindrical_chords(&seg, r, TOLERANCE).map_err(|e| cx.err("mazatrol::polar", e.0, at))?;
    let other = end_other.to_array();
    let ends: Vec<(Pose, f64)> = chords
        .iter()
        .map(|ch| {
            let mut p = now;
            for i in [0, 1] {
                p[i] = now[i] + (other[i] - now[i]) * ch.t;
            }
            p[2] = ch.joints[0];
            p[5] = ch.joints[1];
            (Pose::from_array(p), ch.length)
        })
        .collect();
    emit_chords(cx, &ends, rapid, seg.length(), at)?;
    Ok(true)
}
