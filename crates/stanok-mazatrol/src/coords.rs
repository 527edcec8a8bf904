//! Coordinate systems (`docs/dialects/mazatrol-eia.md` §4.1, §7): the work frame composed from
//! the selected work offset, the external offset, G92/G50 and G52 shifts, G51 scaling, G51.1
//! mirror, G68 / G68.5 / G92.5 rotations and the T-series facing-turret mirror; and the codes
//! that change them, G10 included.
//!
//! ```text
//!   machine = origin + F(p) + shift + tool offset
//!   origin  = work offset (G54…G59 / G54.1 Pn / G53.5) + external offset (G10 L2 P0)
//!   shift   = G92/G50 + G52
//!   F       = turret mirror ∘ G68.5 ∘ G92.5 ∘ G68 ∘ G51.1 ∘ G51     (the innermost first [F])
//! ```
//! *Invariant:* the frame is recomputed from the modes whenever one of them changes
//! ([`apply_frame`]), so it never disagrees with them; the current position stays in machine
//! coordinates and the program position follows the new frame.

use crate::ctx::Ctx;
use crate::modes::{Scaling, WorkSystem};
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_interp_core::frame::{mul, rotation, Affine, Mat3, IDENTITY};
use stanok_interp_core::DistanceMode;
use stanok_syntax::{Address, ColSpan};

/// The work origin of the selected system (machine, mm/deg).
fn origin(cx: &Ctx<'_>) -> [f64; 9] {
    let m = &cx.fe.m;
    let mut o = if m.mazatrol_wpc {
        match cx.fe.params.mazatrol_wpc {
            Some(w) => [w[0], w[1], w[2], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            None => cx.fe.tables.work_offset(1, 1),
        }
    } else {
        match m.work {
            WorkSystem::Standard(s) => cx.fe.tables.work_offset(s, 1),
            WorkSystem::Extra(p) => cx.fe.tables.extra_offset(p),
        }
    };
    for (i, e) in cx.fe.tables.external.iter().enumerate() {
        o[i] += e;
    }
    o
}

/// Rotation matrix about the unit axis `u` by `deg` (right hand).
pub(crate) fn axis_angle(u: [f64; 3], deg: f64) -> Mat3 {
    let (s, c) = deg.to_radians().sin_cos();
    let t = 1.0 - c;
    let [x, y, z] = u;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

/// F of the modes (see the module comment).
fn frames(cx: &Ctx<'_>) -> Affine {
    let m = &cx.fe.m;
    let mut f = Affine::IDENTITY;
    if let Some(Scaling { centre, k }) = m.scaling {
        let d = [[k[0], 0.0, 0.0], [0.0, k[1], 0.0], [0.0, 0.0, k[2]]];
        f = Affine::about(centre, d).after(&f);
    }
    for (i, c) in m.mirror.iter().enumerate() {
        if let Some(c) = c {
            let mut d = IDENTITY;
            d[i][i] = -1.0;
            let mut pole = [0.0; 3];
            pole[i] = *c;
            f = Affine::about(pole, d).after(&f);
        }
    }
    if let Some((c, deg)) = m.rotation {
        let (a, b, n) = cx.st.plane.axes();
        let mut pole = [0.0; 3];
        pole[a] = c[0];
        pole[b] = c[1];
        f = Affine::about(pole, rotation(n, deg)).after(&f);
    }
    if let Some((c, deg)) = m.work_rotation {
        f = Affine::about([c[0], c[1], 0.0], rotation(2, deg)).after(&f);
    }
    if let Some((pole, r)) = m.rotation3d {
        f = Affine::about(pole, r).after(&f);
    }
    if m.turret_mirror {
        let mut d = IDENTITY;
        d[0][0] = -1.0;
        f = Affine::about([0.0; 3], d).after(&f);
    }
    f
}

/// Recomputes the work frame from the modes and tables; emits what printers show.
pub(crate) fn apply_frame(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    let o = origin(cx);
    let m = &cx.fe.m;
    let mut shift = [0.0; 9];
    for (i, s) in shift.iter_mut().take(6).enumerate() {
        *s = m.g92[i] + m.local[i];
    }
    let origin = Pose::from_array(o);
    let shift = Pose::from_array(shift);
    let f = frames(cx);
    let index = match (m.mazatrol_wpc, m.work) {
        (true, _) => 0,
        (false, WorkSystem::Standard(s)) => s,
        (false, WorkSystem::Extra(_)) => 0,
    };
    if *cx.st.frame.origin() != origin || cx.st.g5x_index != index {
        cx.st.frame.set_origin(origin);
        cx.st.g5x_index = index;
        cx.out.push(Canon::SetG5xOffset {
            index,
            offset: origin,
        });
    }
    if *cx.st.frame.shift() != shift {
        cx.st.frame.set_shift(shift);
        cx.out.push(Canon::SetG92Offset { offset: shift });
    }
    if !cx.st.frame.set_frames(f) {
        return Err(cx.err(
            "mazatrol::scaling",
            "the scaling makes the coordinate system degenerate (a factor of zero)",
            cx.whole(),
        ));
    }
    Ok(())
}

/// G54 … G59, G54.1 P n.
pub(crate) fn work_system(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let w = if code == 541 {
        let p = match cx.words.take(b'P') {
            Some(p) => p,
            None => {
                cx.fe.m.work = WorkSystem::Extra(1);
                return apply_frame(cx);
            }
        };
        if p.v.fract() != 0.0 || !(1.0..=48.0).contains(&p.v) {
            return Err(cx.err(
                "mazatrol::value-range",
                format!("G54.1 P{}: P is 1…48", p.v),
                p.span,
            ));
        }
        WorkSystem::Extra(p.v as u8)
    } else {
        WorkSystem::Standard(((code - 540) / 10 + 1) as u8)
    };
    let _ = span;
    cx.fe.m.work = w;
    cx.fe.m.mazatrol_wpc = false;
    apply_frame(cx)
}

/// G53.5 on / G52.5 off (T).
pub(crate) fn mazatrol_system(cx: &mut Ctx<'_>, on: bool) -> Result<(), Diagnostic> {
    cx.fe.m.mazatrol_wpc = on;
    apply_frame(cx)
}

/// The linear axis words of a block that set coordinates (X Y Z A B C), in mm/deg.
fn axis_values(cx: &mut Ctx<'_>) -> [Option<f64>; 6] {
    let mut out = [None; 6];
    for (i, l) in [b'X', b'Y', b'Z', b'A', b'B', b'C'].iter().enumerate() {
        if let Some(v) = cx.words.take(*l) {
            out[i] = Some(if i < 3 { cx.mm(v.v) } else { v.v });
        }
    }
    out
}

/// G52: the local shift of the named axes (absolute values).
pub(crate) fn local(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    for (i, v) in axis_values(cx).iter().enumerate() {
        if let Some(v) = v {
            cx.fe.m.local[i] = *v;
        }
    }
    apply_frame(cx)
}

/// G92 (and G50 X Z on the T-series): the current position gets the named coordinates.
pub(crate) fn setting(cx: &mut Ctx<'_>, _span: ColSpan) -> Result<(), Diagnostic> {
    let now = cx.st.program_position().to_array();
    for (i, v) in axis_values(cx).iter().enumerate() {
        if let Some(v) = v {
            cx.fe.m.g92[i] += now[i] - v;
        }
    }
    apply_frame(cx)
}

/// G50 on the T-series: coordinate setting with X/Z (S, the clamp, is spindle.rs's).
pub(crate) fn g50_t(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.words.any(b"XYZABC") {
        setting(cx, span)?;
    }
    Ok(())
}

/// G92.5 X Y R (M): the work system turned about (x, y).
pub(crate) fn work_rotation(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let x = cx.words.take(b'X').map_or(0.0, |v| cx.mm(v.v));
    let y = cx.words.take(b'Y').map_or(0.0, |v| cx.mm(v.v));
    let Some(r) = cx.words.take(b'R') else {
        return Err(cx.err("mazatrol::missing-word", "G92.5 needs the angle R", span));
    };
    cx.fe.m.work_rotation = if r.v == 0.0 {
        None
    } else {
        Some(([x, y], r.v))
    };
    apply_frame(cx)
}

/// True if the word with `letter` was written with a decimal point.
fn has_point(cx: &Ctx<'_>, letter: u8) -> bool {
    cx.block
        .words
        .iter()
        .find(|w| w.address == Address::Letter(letter))
        .is_some_and(|w| cx.block.slice(w.span).contains('.'))
}

/// A scale factor word: as written with a point or under decimal point type 2, else thousandths.
fn factor(cx: &mut Ctx<'_>, letter: u8) -> Option<f64> {
    let v = cx.words.take(letter)?;
    if letter == b'P' && cx.fe.params.decimal_point_type == 1 && !has_point(cx, letter) {
        return Some(v.v / 1000.0);
    }
    Some(v.v)
}

/// G50/G51, G50.1/G51.1, G68/G69, G68.5/G69.5.
pub(crate) fn frame_mode(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let here = cx.st.program_position().to_array();
    match code {
        510 => {
            let mut centre = [here[0], here[1], here[2]];
            for (i, l) in [b'X', b'Y', b'Z'].iter().enumerate() {
                if let Some(v) = cx.words.take(*l) {
                    centre[i] = cx.mm(v.v);
                }
            }
            let k = if let Some(p) = factor(cx, b'P') {
                [p; 3]
            } else {
                let i = factor(cx, b'I');
                let j = factor(cx, b'J');
                let kk = factor(cx, b'K');
                if i.is_none() && j.is_none() && kk.is_none() {
                    return Err(cx.err(
                        "mazatrol::missing-word",
                        "G51 needs the factor P (all axes) or I J K (per axis)",
                        span,
                    ));
                }
                [i.unwrap_or(1.0), j.unwrap_or(1.0), kk.unwrap_or(1.0)]
            };
            if k.iter().any(|f| *f == 0.0 || !f.is_finite()) {
                return Err(cx.err(
                    "mazatrol::scaling",
                    "a scale factor of 0 makes the coordinate system degenerate",
                    span,
                ));
            }
            cx.fe.m.scaling = Some(Scaling { centre, k });
        }
        500 => cx.fe.m.scaling = None,
        511 | 501 => {
            let mut any = false;
            for (i, l) in [b'X', b'Y', b'Z'].iter().enumerate() {
                if let Some(v) = cx.words.take(*l) {
                    any = true;
                    cx.fe.m.mirror[i] = if code == 511 { Some(cx.mm(v.v)) } else { None };
                }
            }
            if !any {
                if code == 511 {
                    return Err(cx.err(
                        "mazatrol::missing-word",
                        "G51.1 needs the axes to mirror and their centres (X Y Z)",
                        span,
                    ));
                }
                cx.fe.m.mirror = [None; 3];
            }
        }
        680 if cx.fe.m.t() => cx.fe.m.turret_mirror = true,
        690 if cx.fe.m.t() => cx.fe.m.turret_mirror = false,
        680 => {
            let (a, b, _) = cx.st.plane.axes();
            let letters = [b'X', b'Y', b'Z'];
            let ca = cx.words.take(letters[a]).map_or(here[a], |v| cx.mm(v.v));
            let cb = cx.words.take(letters[b]).map_or(here[b], |v| cx.mm(v.v));
            let Some(r) = cx.words.take(b'R') else {
                return Err(cx.err("mazatrol::missing-word", "G68 needs the angle R", span));
            };
            let angle = match (cx.st.distance, cx.fe.m.rotation) {
                (DistanceMode::Incremental, Some((_, prev))) => prev + r.v,
                _ => r.v,
            };
            cx.fe.m.rotation = Some(([ca, cb], angle));
        }
        690 => cx.fe.m.rotation = None,
        685 => {
            let mut pole = [0.0; 3];
            for (i, l) in [b'X', b'Y', b'Z'].iter().enumerate() {
                if let Some(v) = cx.words.take(*l) {
                    pole[i] = cx.mm(v.v);
                }
            }
            let v = [b'I', b'J', b'K'].map(|l| cx.words.take(l).map_or(0.0, |w| w.v));
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if len < 1e-12 {
                return Err(cx.err(
                    "mazatrol::value-range",
                    "G68.5 needs a rotation axis I J K that is not zero",
                    span,
                ));
            }
            let Some(r) = cx.words.take(b'R') else {
                return Err(cx.err("mazatrol::missing-word", "G68.5 needs the angle R", span));
            };
            let u = [v[0] / len, v[1] / len, v[2] / len];
            let m = axis_angle(u, r.v);
            let m = match cx.fe.m.rotation3d {
                // A second G68.5 turns in the rotated system.
                Some((_, prev)) => mul(&prev, &m),
                None => m,
            };
            cx.fe.m.rotation3d = Some((pole, m));
        }
        695 => cx.fe.m.rotation3d = None,
        _ => {}
    }
    apply_frame(cx)
}

/// G10 (`docs` §7.5).
pub(crate) fn data_setting(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let Some(l) = cx.words.take(b'L') else {
        return Err(cx.err("mazatrol::missing-word", "G10 needs L", span));
    };
    let Some(p) = cx.words.take(b'P') else {
        return Err(cx.err("mazatrol::missing-word", "G10 needs P", span));
    };
    let l = cx.non_negative_integer(l, "L")?;
    let pn = cx.non_negative_integer(p, "P")?;
    let add = cx.st.distance == DistanceMode::Incremental;
    cx.fe.tables.touch();
    match l {
        2 | 20 => {
            if (l == 2 && pn > 6) || (l == 20 && !(1..=48).contains(&pn)) {
                return Err(cx.err(
                    "mazatrol::value-range",
                    format!(
                        "G10 L{l} P{pn}: P is {}",
                        if l == 2 { "0…6" } else { "1…48" }
                    ),
                    p.span,
                ));
            }
            let values = axis_values(cx);
            for (i, v) in values.iter().enumerate() {
                let Some(v) = v else { continue };
                let old = if l == 2 {
                    if pn == 0 {
                        cx.fe.tables.external[i]
                    } else {
                        cx.fe.tables.work_offset(pn as u8, 1)[i]
                    }
                } else {
                    cx.fe.tables.extra_offset(pn as u8)[i]
                };
                let new = if add { old + v } else { *v };
                if l == 2 {
                    cx.fe.tables.set_work_offset(pn as u8, i, new);
                } else {
                    cx.fe.tables.set_extra_offset(pn as u8, i, new);
                }
            }
            apply_frame(cx)
        }
        10..=13 if !cx.fe.m.t() => {
            let Some(r) = cx.words.take(b'R') else {
                return Err(cx.err("mazatrol::missing-word", format!("G10 L{l} needs R"), span));
            };
            let v = cx.mm(r.v);
            let e = cx.fe.tables.edge_mut(pn);
            let slot = match l {
                10 => &mut e.length[0],
                11 => &mut e.length_wear[0],
                12 => &mut e.radius,
                _ => &mut e.radius_wear,
            };
            *slot = if add { *slot + v } else { v };
            Ok(())
        }
        10 | 11 if cx.fe.m.t() => {
            let wear = l == 11;
            let turning = cx.fe.tables.is_turning(pn) || cx.fe.tables.edge(pn).is_none();
            // X is a diameter here (halved with the other X words).
            let x = cx.words.take(b'X').map(|v| cx.mm(v.v));
            let z = cx.words.take(b'Z').map(|v| cx.mm(v.v));
            let r = cx.words.take(b'R').map(|v| cx.mm(v.v));
            let q = cx.words.take(b'Q').map(|v| v.v);
            if turning {
                if let Some(kind) = cx
                    .fe
                    .tables
                    .data
                    .tools
                    .tools
                    .get_mut(&pn)
                    .map(|t| &mut t.kind)
                {
                    *kind = stanok_canon::setup::ToolKind::Turning;
                }
            }
            let e = cx.fe.tables.edge_mut(pn);
            let set = |slot: &mut f64, v: Option<f64>| {
                if let Some(v) = v {
                    *slot = if add { *slot + v } else { v };
                }
            };
            let (lx, lz) = if turning { (0, 1) } else { (usize::MAX, 0) };
            if wear {
                if lx != usize::MAX {
                    set(&mut e.length_wear[lx], x);
                }
                set(&mut e.length_wear[lz], z);
                set(&mut e.radius_wear, r);
            } else {
                if lx != usize::MAX {
                    set(&mut e.length[lx], x);
                }
                set(&mut e.length[lz], z);
                set(&mut e.radius, r);
            }
            if let Some(q) = q {
                if !(0.0..=9.0).contains(&q) || q.fract() != 0.0 {
                    return Err(cx.err(
                        "mazatrol::value-range",
                        format!("G10 Q{q}: the imaginary tip is 0…9"),
                        span,
                    ));
                }
                cx.fe.tables.edge_mut(pn).orientation = q as u8;
            }
            if cx.fe.m.t_offset == pn {
                crate::tools::set_turn_offset(cx, pn);
            }
            Ok(())
        }
        50 => Err(cx.err(
            "mazatrol::not-simulated",
            "G10 L50 (programmable parameter input) is not simulated by Stanok",
            span,
        )),
        _ => Err(cx.err(
            "mazatrol::value-range",
            format!(
                "G10 L{l} is not a data setting of the {}",
                cx.fe.m.series.name()
            ),
            span,
        )),
    }
}
