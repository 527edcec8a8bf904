//! Canned cycles as blocks (`docs/dialects/mazatrol-eia.md` §10, §11): the M-series drilling
//! cycles and the T-series face/side cycles (geometry in `drilling.rs`), the T-series turning
//! cycles G70–G79 (geometry in `turning.rs`, profiles in `profile.rs`), turned into moves here.

use crate::block::Codes;
use crate::ctx::Ctx;
use crate::drilling::{hole, Hole, HoleStep, Kind};
use crate::front::Request;
use crate::modes::{CycleModes, Turning};
use crate::turning::{self, Step, Zx};
use stanok_canon::{Canon, Diagnostic, LineMove, Plane, Pose};
use stanok_interp_core::arc::PlanarArc;
use stanok_interp_core::DistanceMode;
use stanok_syntax::{Address, ColSpan};

/// True if `code` is a drilling-type cycle of the series.
pub(crate) fn is_cycle(cx: &Ctx<'_>, code: u32) -> bool {
    if cx.fe.m.t() {
        Kind::t_series(code, 0.0).is_some()
    } else {
        Kind::m_series(code).is_some()
    }
}

/// (drilling axis, the two positioning axes) of the cycle in force.
fn axes(cx: &Ctx<'_>, code: u32) -> (usize, [usize; 2]) {
    if cx.fe.m.t() {
        if matches!(code, 870 | 880 | 890) {
            (0, [2, 5]) // side: along X, positioned in Z and C
        } else {
            (2, [0, 5]) // face: along Z, positioned in X and C
        }
    } else {
        match cx.st.plane {
            Plane::XY => (2, [0, 1]),
            Plane::ZX => (1, [2, 0]),
            Plane::YZ => (0, [1, 2]),
        }
    }
}

/// A cycle code starts or continues the cycle mode.
pub(crate) fn enter(cx: &mut Ctx<'_>, code: u32, _span: ColSpan) -> Result<(), Diagnostic> {
    if crate::compensate::active(cx) {
        return Err(cx.err(
            "mazatrol::compensation",
            "canned cycles are not allowed under cutter compensation: cancel it with G40 first",
            _span,
        ));
    }
    let (axis, _) = axes(cx, code);
    let here = cx.st.program_position().to_array()[axis];
    let c = match cx.fe.m.cycle {
        Some(mut c) => {
            c.code = code;
            c
        }
        None => CycleModes {
            code,
            initial: here,
            r: None,
            z: None,
            q: 0.0,
            dwell: 0.0,
            incremental: false,
            r_inc: 0.0,
            z_inc: 0.0,
        },
    };
    cx.fe.m.cycle = Some(c);
    Ok(())
}

/// True if the word with `letter` was written with a decimal point.
fn has_point(cx: &Ctx<'_>, letter: u8) -> bool {
    cx.block
        .words
        .iter()
        .find(|w| w.address == Address::Letter(letter))
        .is_some_and(|w| cx.block.slice(w.span).contains('.'))
}

/// A T-series µm word (G74/G75 P Q, G76 P Q, G83/G87 Q): µm without a decimal point, mm with one.
fn micro(cx: &mut Ctx<'_>, letter: u8) -> Option<f64> {
    let v = cx.words.take(letter)?;
    let inch = cx.st.units == stanok_canon::LengthUnits::Inches;
    Some(if has_point(cx, letter) {
        cx.mm(v.v)
    } else if inch {
        v.v * 1e-4 * 25.4
    } else {
        v.v * 1e-3
    })
}

/// Moves along one axis or in the plane during a cycle (program coordinates).
fn go(cx: &mut Ctx<'_>, rapid: bool, p: [f64; 9], at: ColSpan) -> Result<(), Diagnostic> {
    crate::motion::emit_straight(cx, rapid, Pose::from_array(p), at)
}

/// The drilling cycle of the block (`docs` §10, §11.8).
pub(crate) fn drill(cx: &mut Ctx<'_>, _codes: &Codes) -> Result<(), Diagnostic> {
    let Some(mut c) = cx.fe.m.cycle else {
        return Ok(());
    };
    let at = cx.whole();
    let t = cx.fe.m.t();
    let (axis, pos_axes) = axes(cx, c.code);
    let letters = [b'X', b'Y', b'Z', b'A', b'B', b'C'];
    let inc = cx.st.distance == DistanceMode::Incremental;
    // The cycle's words (modal).
    if let Some(r) = cx.words.take(b'R') {
        let v = cx.mm(r.v);
        // The T-series R is always an increment from the initial point; the M-series' follows
        // G90/G91.
        if t || inc {
            c.r_inc = v;
            c.incremental = true;
            c.r = Some(c.initial + v);
        } else {
            c.incremental = false;
            c.r = Some(v);
        }
    }
    let depth_letter = letters[axis];
    let depth_inc = if t {
        [b'U', b'V', b'W'][axis.min(2)]
    } else {
        0
    };
    let mut bottom_word = cx.words.take(depth_letter).map(|v| (cx.mm(v.v), inc));
    if depth_inc != 0 {
        if let Some(w) = cx.words.take(depth_inc) {
            bottom_word = Some((cx.mm(w.v), true));
        }
    }
    if let Some(q) = if t {
        micro(cx, b'Q')
    } else {
        cx.words.take(b'Q').map(|v| cx.mm(v.v))
    } {
        c.q = q;
    }
    if let Some(p) = cx.words.take(b'P') {
        c.dwell = p.v / 1000.0;
    }
    let repeats = match cx.words.take(b'K') {
        Some(k) if k.v >= 0.0 && k.v.fract() == 0.0 && k.v <= 9999.0 => k.v as u32,
        Some(k) => {
            return Err(cx.err(
                "mazatrol::value-range",
                format!("K{}: the repeats are 0 … 9999", k.v),
                k.span,
            ))
        }
        None => 1,
    };
    // The plane positions of the hole (increments repeated K times under G91).
    let mut delta = [None::<f64>; 2];
    let mut absolute = [None::<f64>; 2];
    for (k, &ax) in pos_axes.iter().enumerate() {
        let l = letters[ax];
        if let Some(v) = cx.words.take(l) {
            let v = if ax < 3 { cx.mm(v.v) } else { v.v };
            if inc {
                delta[k] = Some(v);
            } else {
                absolute[k] = Some(v);
            }
        }
        if t && ax < 3 {
            if let Some(v) = cx.words.take([b'U', b'V', b'W'][ax]) {
                delta[k] = Some(cx.mm(v.v));
            }
        }
    }
    // The other axes may be positioned in the block too (absolute or incremental).
    for (ax, &letter) in letters.iter().enumerate() {
        if ax == axis || pos_axes.contains(&ax) {
            continue;
        }
        if let Some(v) = cx.words.peek(letter) {
            return Err(cx.err(
                "mazatrol::cycle",
                format!(
                    "{} is not a word of the {} cycle in this plane",
                    letter as char,
                    crate::codes::g_name(c.code)
                ),
                v.span,
            ));
        }
    }
    if let Some((v, inc_w)) = bottom_word {
        if inc_w {
            c.z_inc = v;
            let from = if t {
                c.initial
            } else {
                c.r.unwrap_or(c.initial)
            };
            c.z = Some(from + v);
        } else {
            c.z = Some(v);
        }
    } else if c.incremental && !t {
        c.z = c.r.map(|r| r + c.z_inc);
    }
    let name = crate::codes::g_name(c.code);
    let (Some(r), Some(z)) = (c.r.or(if t { Some(c.initial) } else { None }), c.z) else {
        cx.fe.m.cycle = Some(c);
        return Err(cx.err(
            "mazatrol::cycle",
            format!(
                "{name} needs {}",
                if c.z.is_none() {
                    format!("the bottom {}", depth_letter as char)
                } else {
                    "the R level".to_string()
                }
            ),
            at,
        ));
    };
    cx.fe.m.cycle = Some(c);
    let kind = if t {
        Kind::t_series(c.code, c.q).map(|k| k.0)
    } else {
        Kind::m_series(c.code)
    };
    let Some(kind) = kind else {
        return Ok(());
    };
    let (spindle, turning) = crate::spindle::cycle_spindle(cx);
    let h = Hole {
        initial: c.initial,
        r,
        z,
        q: c.q,
        dwell: c.dwell,
        clearance: cx.fe.params.peck_clearance,
        to_initial: cx.fe.m.return_initial,
        rigid: cx.fe.m.rigid,
    };
    let steps = hole(kind, &h, &name).map_err(|e| cx.err("mazatrol::cycle", e.0, at))?;
    if matches!(kind, Kind::Tap | Kind::TapLeft) && turning == Turning::Stopped {
        return Err(cx.err(
            "mazatrol::cycle",
            format!("{name}: tapping needs the spindle turning"),
            at,
        ));
    }
    for _ in 0..repeats {
        // Position the hole at the current level.
        let mut p = cx.st.program_position().to_array();
        for k in 0..2 {
            let ax = pos_axes[k];
            if let Some(d) = delta[k] {
                p[ax] += d;
            }
            if let Some(a) = absolute[k] {
                p[ax] = a;
            }
        }
        go(cx, true, p, at)?;
        run_hole(cx, &steps, axis, pos_axes, spindle, turning, at)?;
    }
    if h.rigid && matches!(kind, Kind::Tap | Kind::TapLeft) {
        cx.fe.m.rigid = false;
    }
    Ok(())
}

/// One hole's steps as moves.
fn run_hole(
    cx: &mut Ctx<'_>,
    steps: &[HoleStep],
    axis: usize,
    pos_axes: [usize; 2],
    spindle: u8,
    turning: Turning,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let reverse = match turning {
        Turning::Cw => Turning::Ccw,
        Turning::Ccw => Turning::Cw,
        Turning::Stopped => Turning::Stopped,
    };
    for s in steps {
        let mut p = cx.st.program_position().to_array();
        match *s {
            HoleStep::Rapid(l) => {
                p[axis] = l;
                go(cx, true, p, at)?;
            }
            HoleStep::Feed(l) => {
                p[axis] = l;
                go(cx, false, p, at)?;
            }
            HoleStep::Dwell(t) => cx.out.push(Canon::Dwell { seconds: t }),
            HoleStep::Reverse => crate::spindle::set(cx, spindle, reverse),
            HoleStep::Restore => crate::spindle::set(cx, spindle, turning),
            HoleStep::Stop => cx.out.push(Canon::StopSpindle { spindle }),
            HoleStep::Orient => cx.out.push(Canon::OrientSpindle {
                spindle,
                degrees: 0.0,
                direction: 0,
                timeout: None,
            }),
            HoleStep::Shift(d) => {
                p[pos_axes[0]] += d;
                go(cx, true, p, at)?;
            }
            HoleStep::ProgramStop => cx.out.push(Canon::ProgramStop { optional: false }),
            HoleStep::RigidTap(l) => {
                let rpm = cx.st.spindle_speed[spindle as usize];
                let pitch = match cx.st.feed_mode {
                    stanok_canon::FeedMode::UnitsPerRevolution => cx.st.feed,
                    _ if rpm > 0.0 => cx.st.feed / rpm,
                    _ => 0.0,
                };
                cx.out.push(Canon::StartSpindleSync {
                    pitch,
                    velocity_mode: false,
                });
                let start = cx.st.position;
                p[axis] = l;
                let end = cx.st.frame.to_machine(&Pose::from_array(p));
                cx.out.push(Canon::RigidTap {
                    start,
                    end,
                    scale: 1.0,
                    law: stanok_canon::FeedLaw::PerMinute,
                });
                cx.out.push(Canon::StopSpindleSync);
            }
        }
    }
    Ok(())
}

/// The T-series turning plane point (z, x radius) of the current position.
fn here_zx(cx: &Ctx<'_>) -> Zx {
    let p = cx.st.program_position();
    [p.z, p.x]
}

/// Emits turning-plane steps (positions in program coordinates).
fn emit_steps(cx: &mut Ctx<'_>, steps: &[Step], at: ColSpan) -> Result<(), Diagnostic> {
    let rpm = cx.st.spindle_speed[0];
    for s in steps {
        let mut p = cx.st.program_position().to_array();
        let put = |q: Zx, p: &mut [f64; 9]| {
            p[2] = q[0];
            p[0] = q[1];
        };
        match *s {
            Step::Rapid(q) => {
                put(q, &mut p);
                go(cx, true, p, at)?;
            }
            Step::Feed(q) => {
                put(q, &mut p);
                go(cx, false, p, at)?;
            }
            Step::Arc { to, centre, ccw } => {
                put(to, &mut p);
                let end = Pose::from_array(p);
                let plane = cx.st.plane;
                if plane != Plane::ZX {
                    cx.st.plane = Plane::ZX;
                }
                let length = stanok_interp_core::arc::helix_length(
                    cx.st.program_position(),
                    end,
                    Plane::ZX,
                    centre,
                    ccw,
                    1,
                );
                let feed = cx.path_feed(length);
                cx.arc(Plane::ZX, ccw, end, PlanarArc { centre, turns: 1 }, feed);
                cx.st.plane = plane;
            }
            Step::Thread { to, lead } => {
                if rpm <= 0.0 || !cx.st.spindle_on[0] {
                    return Err(cx.err(
                        "mazatrol::thread",
                        "thread cutting needs a turning spindle: start it with S and M03/M04",
                        at,
                    ));
                }
                put(to, &mut p);
                let end = cx.st.frame.to_machine(&Pose::from_array(p));
                cx.out.push(Canon::StartSpindleSync {
                    pitch: lead,
                    velocity_mode: false,
                });
                cx.out.push(Canon::StraightFeed(LineMove {
                    start: cx.st.position,
                    end,
                    feed: lead * rpm,
                    law: stanok_canon::FeedLaw::PerMinute,
                }));
                cx.st.position = end;
                cx.out.push(Canon::StopSpindleSync);
            }
            Step::Dwell(t) => cx.out.push(Canon::Dwell { seconds: t }),
        }
    }
    Ok(())
}

fn cycle_err(cx: &Ctx<'_>, e: turning::CycleError, at: ColSpan) -> Diagnostic {
    cx.err("mazatrol::cycle", e.0, at)
}

/// After G71–G73 the program goes on after the profile's last block [F].
fn skip_profile(cx: &mut Ctx<'_>) {
    if let Some(after) = cx.fe.prepared.profile_after {
        cx.fe.request = Some(Request::Jump(after));
    }
}

/// G70–G76 (T-series multiple repetitive cycles).
pub(crate) fn turning(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    if crate::compensate::active(cx) && code != 700 {
        return Err(cx.err(
            "mazatrol::compensation",
            "G71–G76 are not allowed under nose radius compensation: cancel it with G40 first",
            span,
        ));
    }
    let a = here_zx(cx);
    let second = cx.words.has(b'P') && matches!(code, 710 | 720 | 730);
    match code {
        700 => {
            let Some(first) = cx.fe.prepared.profile_first else {
                return Err(cx.err("mazatrol::cycle", "G70 needs P and Q", span));
            };
            let last = cx.words.take(b'Q').map_or(0, |q| q.v as u32);
            cx.words.take(b'P');
            let back_to = cx.st.program_position().to_array();
            cx.fe.request = Some(Request::Profile {
                first,
                last,
                back_to,
            });
            Ok(())
        }
        710 | 720 if !second => {
            let depth_letter = if code == 710 { b'U' } else { b'W' };
            let d = cx.words.take(depth_letter).map(|v| cx.mm(v.v));
            let e = cx.words.take(b'R').map(|v| cx.mm(v.v));
            // U was halved as a diameter: G71's U is a radius depth.
            let d = d.map(|d| {
                if code == 710 && !cx.fe.m.x_radius {
                    2.0 * d
                } else {
                    d
                }
            });
            let slot = if code == 710 {
                &mut cx.fe.m.turn.g71
            } else {
                &mut cx.fe.m.turn.g72
            };
            if let Some(d) = d {
                slot.0 = d;
            }
            if let Some(e) = e {
                slot.1 = e;
            }
            Ok(())
        }
        710 | 720 => {
            cx.words.take(b'P');
            cx.words.take(b'Q');
            let u = cx.words.take(b'U').map_or(0.0, |v| cx.mm(v.v));
            let w = cx.words.take(b'W').map_or(0.0, |v| cx.mm(v.v));
            let (depth, retract) = if code == 710 {
                cx.fe.m.turn.g71
            } else {
                cx.fe.m.turn.g72
            };
            let Some(profile) = cx.fe.prepared.profile.clone() else {
                return Err(cx.err("mazatrol::cycle", "the profile was not read", span));
            };
            let words = turning::StockRemoval {
                depth,
                retract,
                allowance_x: u,
                allowance_z: w,
            };
            let steps = if code == 710 {
                turning::g71(a, &profile, words)
            } else {
                turning::g72(a, &profile, words)
            }
            .map_err(|e| cycle_err(cx, e, span))?;
            emit_steps(cx, &steps, span)?;
            skip_profile(cx);
            Ok(())
        }
        730 if !second => {
            // G73's U is a radius relief: undo the diameter halving of U.
            let k = if cx.fe.m.x_radius { 1.0 } else { 2.0 };
            let u = cx.words.take(b'U').map(|v| k * cx.mm(v.v));
            let w = cx.words.take(b'W').map(|v| cx.mm(v.v));
            let r = cx.words.take(b'R');
            if let Some(u) = u {
                cx.fe.m.turn.g73.0 = u;
            }
            if let Some(w) = w {
                cx.fe.m.turn.g73.1 = w;
            }
            if let Some(r) = r {
                cx.fe.m.turn.g73.2 = cx.non_negative_integer(r, "R (divisions)")?;
            }
            Ok(())
        }
        730 => {
            cx.words.take(b'P');
            cx.words.take(b'Q');
            let u = cx.words.take(b'U').map_or(0.0, |v| cx.mm(v.v));
            let w = cx.words.take(b'W').map_or(0.0, |v| cx.mm(v.v));
            let (di, dk, d) = cx.fe.m.turn.g73;
            let Some(profile) = cx.fe.prepared.profile.clone() else {
                return Err(cx.err("mazatrol::cycle", "the profile was not read", span));
            };
            let steps = turning::g73(a, &profile, [dk, di], d, [w, u])
                .map_err(|e| cycle_err(cx, e, span))?;
            emit_steps(cx, &steps, span)?;
            skip_profile(cx);
            Ok(())
        }
        740 | 750 => {
            let has_end = cx.words.any(b"XZUW");
            if !has_end {
                if let Some(r) = cx.words.take(b'R') {
                    let e = cx.mm(r.v);
                    if code == 740 {
                        cx.fe.m.turn.g74 = e;
                    } else {
                        cx.fe.m.turn.g75 = e;
                    }
                }
                return Ok(());
            }
            let (end, _) = crate::motion::end_point(cx)?;
            let p = micro(cx, b'P').unwrap_or(0.0);
            let q = micro(cx, b'Q').unwrap_or(0.0);
            let relief = cx.words.take(b'R').map_or(0.0, |v| cx.mm(v.v));
            let e = if code == 740 {
                cx.fe.m.turn.g74
            } else {
                cx.fe.m.turn.g75
            };
            let end = [end.z, end.x];
            // G74: P steps X (Δi), Q pecks Z (Δk); G75: P pecks X, Q steps Z.
            let (step, peck) = if code == 740 { (p, q) } else { (q, p) };
            let w = turning::Grooving {
                end,
                step,
                peck,
                retract: e,
                relief,
            };
            let steps = if code == 740 {
                turning::g74(a, w)
            } else {
                turning::g75(a, w)
            }
            .map_err(|e| cycle_err(cx, e, span))?;
            emit_steps(cx, &steps, span)
        }
        760 => {
            let has_end = cx.words.any(b"XZUW");
            if !has_end {
                if let Some(p) = cx.words.take(b'P') {
                    let (m, r, ang) = crate::rules::g76_p(cx.non_negative_integer(p, "P")?);
                    cx.fe.m.turn.g76.0 = m;
                    cx.fe.m.turn.g76.1 = r;
                    cx.fe.m.turn.g76.2 = f64::from(ang);
                }
                if let Some(q) = micro(cx, b'Q') {
                    cx.fe.m.turn.g76.3 = q;
                }
                if let Some(r) = cx.words.take(b'R') {
                    cx.fe.m.turn.g76.4 = cx.mm(r.v);
                }
                return Ok(());
            }
            let (end, _) = crate::motion::end_point(cx)?;
            let taper = cx.words.take(b'R').map_or(0.0, |v| cx.mm(v.v));
            let k = micro(cx, b'P').unwrap_or(0.0);
            let dd = micro(cx, b'Q').unwrap_or(0.0);
            let (m, r, ang, dmin, allowance) = cx.fe.m.turn.g76;
            let w = turning::Threading {
                end: [end.z, end.x],
                taper,
                height: k,
                first_depth: dd,
                min_depth: dmin,
                allowance,
                finishing_passes: m,
                chamfer_tenths: r,
                angle: ang,
                lead: cx.fe.m.lead,
                chamfer_angle: cx.fe.params.thread_chamfer_angle,
            };
            let steps = turning::g76(a, &w).map_err(|e| cycle_err(cx, e, span))?;
            emit_steps(cx, &steps, span)
        }
        _ => Ok(()),
    }
}

/// G77 / G78 / G79 (T single cycles), modal: each block with an end point runs the cycle.
pub(crate) fn single(cx: &mut Ctx<'_>, code: u32, at: ColSpan) -> Result<(), Diagnostic> {
    let a = here_zx(cx);
    let (end, _) = crate::motion::end_point(cx)?;
    let taper = cx.words.take(b'R').map_or(0.0, |v| cx.mm(v.v));
    let end = [end.z, end.x];
    let steps = match code {
        770 => turning::g77(a, end, taper),
        790 => turning::g79(a, end, taper),
        _ => {
            let lead = cx.fe.m.lead;
            if lead <= 0.0 {
                return Err(cx.err("mazatrol::thread", "G78 needs the lead F", at));
            }
            turning::g78(a, end, taper, lead, 0.0, cx.fe.params.thread_chamfer_angle)
        }
    };
    emit_steps(cx, &steps, at)
}
