//! Motion (`docs/dialects/mazatrol-eia.md` §5, §6.2): end points, G00/G01, G02/G03 with I J K
//! or R and helices, G02.1/G03.1 spirals, G32/G33/G34 threads, G04, G27–G30.1, G31, G53, G60,
//! and the G22 stored stroke check every move passes.
//!
//! Arcs (Fanuc): I J K are the centre relative to the start in both G90 and G91; R > 0 takes the
//! arc of at most 180°, R < 0 the larger one; an end off the circle by more than the machine's arc
//! tolerance is an error, within it the arc is a spiral in Canon. Helices move the plane's third
//! axis linearly with the angle.

use crate::block::{motion_of, Codes};
use crate::ctx::Ctx;
use crate::TtpcMode;
use stanok_canon::{Canon, Diagnostic, LineMove, Plane, Pose, ProbeKind};
use stanok_geom::centre_from_radius;
use stanok_interp_core::arc::PlanarArc;
use stanok_interp_core::{is_linear, MotionMode};
use stanok_syntax::ColSpan;

pub(crate) use crate::endpoint::end_point;
use crate::endpoint::AXES;

/// The group-01 code of the block becomes the modal motion.
pub(crate) fn set_mode(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    if let Some(m) = motion_of(code) {
        cx.st.motion = m;
        cx.fe.m.motion = code;
        cx.fe.m.cycle = None;
        return Ok(());
    }
    match code {
        800 => cx.fe.m.cycle = None,
        21 | 31 | 320 | 330 | 340 | 770 | 780 | 790 => {
            cx.fe.m.motion = code;
            cx.fe.m.cycle = None;
            cx.st.motion = MotionMode::Linear;
        }
        _ => crate::cycles::enter(cx, code, span)?,
    }
    Ok(())
}

/// The block's motion in the modal group-01 mode. Returns true if the block moved.
pub(crate) fn block_motion(cx: &mut Ctx<'_>, codes: &Codes) -> Result<bool, Diagnostic> {
    if cx.fe.modes.mode != TtpcMode::Off {
        let moves = cx.has_axis_words() || cx.words.any(b"IJK");
        if moves {
            crate::ttpc::ttpc_motion(cx, cx.whole())?;
        }
        return Ok(moves);
    }
    if cx.fe.m.polar {
        return crate::polar_run::motion(cx);
    }
    if let Some(r) = cx.fe.m.cylinder {
        return crate::polar_run::cylinder_motion(cx, r);
    }
    if cx.fe.m.cycle.is_some() {
        let in_block = codes
            .motion
            .is_some_and(|(c, _)| crate::cycles::is_cycle(cx, c));
        if in_block || cx.has_axis_words() {
            crate::cycles::drill(cx, codes)?;
            return Ok(true);
        }
        return Ok(false);
    }
    if !cx.has_axis_words() && !cx.words.any(b"UVW") {
        return Ok(false);
    }
    let at = codes.motion.map_or(cx.whole(), |(_, s)| s);
    match cx.fe.m.motion {
        0 | 10 => {
            let (end, _) = end_point(cx)?;
            straight_to(cx, end, at)?;
        }
        20 | 30 => arc(cx, cx.fe.m.motion == 30, false, at)?,
        21 | 31 => arc(cx, cx.fe.m.motion == 31, true, at)?,
        320 | 330 | 340 => thread(cx, at)?,
        770 | 780 | 790 => crate::cycles::single(cx, cx.fe.m.motion, at)?,
        _ => {
            let (end, _) = end_point(cx)?;
            straight_to(cx, end, at)?;
        }
    }
    Ok(true)
}

/// The path feed of a feed move (mm/min; G93: length × F).
fn feed_for(cx: &Ctx<'_>, length: f64, at: ColSpan) -> Result<f64, Diagnostic> {
    if cx.st.feed <= 0.0 {
        return Err(cx.err(
            "mazatrol::feed-missing",
            "a feed move needs a feed: no F has been programmed",
            at,
        ));
    }
    Ok(cx.path_feed(length))
}

/// A straight move to `end` in the modal mode (G00 rapid, otherwise feed), through cutter
/// compensation when it is on.
pub(crate) fn straight_to(cx: &mut Ctx<'_>, end: Pose, at: ColSpan) -> Result<(), Diagnostic> {
    let rapid = cx.st.motion == MotionMode::Rapid;
    if crate::compensate::active(cx) {
        return crate::compensate::line(cx, rapid, end, at);
    }
    emit_straight(cx, rapid, end, at)
}

/// Emits a straight move (program coordinates), checked against the stroke limit.
pub(crate) fn emit_straight(
    cx: &mut Ctx<'_>,
    rapid: bool,
    end: Pose,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let feed = if rapid {
        0.0
    } else {
        let length = {
            let a = cx.st.program_position().to_array();
            let b = end.to_array();
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
        };
        feed_for(cx, length, at)?
    };
    let end_m = cx.st.frame.to_machine(&end);
    stroke_check(cx, &[cx.st.position.to_array(), end_m.to_array()], at)?;
    cx.straight(rapid, end, feed);
    Ok(())
}

/// G02/G03 (and G02.1/G03.1 spirals).
pub(crate) fn arc(
    cx: &mut Ctx<'_>,
    ccw: bool,
    spiral: bool,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    if cx.fe.m.t()
        && plane != Plane::YZ
        && cx
            .opts
            .five_axis
            .as_ref()
            .is_some_and(|k| k.x_is_diameter())
    {
        return Err(cx.err(
            "mazatrol::diameter-axis-arc",
            "this machine's X is a diameter axis: arcs in a plane with X need a machine with X on the radius (e.g. mazak-t)",
            at,
        ));
    }
    let (a, b, _) = plane.axes();
    let start = {
        let mut p = cx.st.program_position().to_array();
        if let Some(q) = crate::compensate::programmed_point(cx) {
            p[a] = q[0];
            p[b] = q[1];
        }
        p
    };
    let offsets = [b'I', b'J', b'K'];
    let r_word = cx.words.take(b'R');
    let ij = [cx.words.take(offsets[a]), cx.words.take(offsets[b])];
    // The other centre word is read and ignored (Fanuc: only the plane's two count).
    let n_off = offsets[3 - a - b];
    cx.words.take(n_off);
    let turns_word = if spiral { cx.words.take(b'L') } else { None };
    let (end, _) = end_point(cx)?;
    let e = end.to_array();
    let (s2, e2) = ([start[a], start[b]], [e[a], e[b]]);
    let tol = cx.opts.arc_tolerance_mm;
    let centre = if let Some(r) = r_word {
        let radius = cx.mm(r.v);
        if radius == 0.0 {
            return Err(cx.err("mazatrol::arc-radius", "R0 is not a radius", r.span));
        }
        match centre_from_radius(s2, e2, radius.abs(), ccw, radius < 0.0, tol) {
            Ok(c) => c,
            Err(stanok_geom::RadiusError::EndEqualsStart) => {
                return Err(cx.err(
                    "mazatrol::arc-radius",
                    "R cannot describe a full circle: use I J K",
                    r.span,
                ))
            }
            Err(stanok_geom::RadiusError::RadiusTooSmall { half_chord, .. }) => {
                return Err(cx.err(
                    "mazatrol::arc-radius",
                    format!(
                    "the end point is {:.4} mm from the start, more than the diameter {:.4} of R{}",
                    2.0 * half_chord,
                    2.0 * radius.abs(),
                    r.v
                ),
                    r.span,
                ))
            }
            Err(e) => return Err(cx.err("mazatrol::arc-radius", e.to_string(), r.span)),
        }
    } else {
        let i = ij[0].map_or(0.0, |v| cx.mm(v.v));
        let j = ij[1].map_or(0.0, |v| cx.mm(v.v));
        [s2[0] + i, s2[1] + j]
    };
    let r1 = (s2[0] - centre[0]).hypot(s2[1] - centre[1]);
    let r2 = (e2[0] - centre[0]).hypot(e2[1] - centre[1]);
    if r1 < 1e-9 || r2 < 1e-9 {
        return Err(cx.err(
            "mazatrol::arc-radius",
            "the arc has no radius: its centre is on its start or end point",
            at,
        ));
    }
    if !spiral && (r1 - r2).abs() > tol {
        return Err(cx.err(
            "mazatrol::arc-radius",
            format!(
                "start radius {r1:.4} and end radius {r2:.4} differ by more than the arc tolerance {tol:.4}"
            ),
            at,
        ));
    }
    let turns = match turns_word {
        Some(l) => cx.non_negative_integer(l, "L (extra turns)")? + 1,
        None => 1,
    };
    if crate::compensate::active(cx) {
        return crate::compensate::arc(cx, ccw, end, centre, at);
    }
    emit_arc(cx, ccw, end, centre, turns, at)
}

/// Emits an arc (program coordinates, plane centre), checked against the stroke limit.
pub(crate) fn emit_arc(
    cx: &mut Ctx<'_>,
    ccw: bool,
    end: Pose,
    centre: [f64; 2],
    turns: u32,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    let length = stanok_interp_core::arc::helix_length(
        cx.st.program_position(),
        end,
        plane,
        centre,
        ccw,
        turns,
    );
    let feed = feed_for(cx, length, at)?;
    if cx.fe.m.stroke_on {
        let pts = arc_points(cx, ccw, end, centre, turns);
        stroke_check(cx, &pts, at)?;
    }
    cx.arc(plane, ccw, end, PlanarArc { centre, turns }, feed);
    Ok(())
}

/// Points of an arc (machine coordinates) 1 µm apart in chord height, for the stroke check.
fn arc_points(cx: &Ctx<'_>, ccw: bool, end: Pose, centre: [f64; 2], turns: u32) -> Vec<[f64; 9]> {
    let (a, b, n) = cx.st.plane.axes();
    let s = cx.st.program_position().to_array();
    let e = end.to_array();
    let a0 = (s[b] - centre[1]).atan2(s[a] - centre[0]);
    let a1 = (e[b] - centre[1]).atan2(e[a] - centre[0]);
    let r = (s[a] - centre[0]).hypot(s[b] - centre[1]);
    let mut sweep = if ccw {
        (a1 - a0).rem_euclid(std::f64::consts::TAU)
    } else {
        -(a0 - a1).rem_euclid(std::f64::consts::TAU)
    };
    if sweep == 0.0 {
        sweep = if ccw {
            std::f64::consts::TAU
        } else {
            -std::f64::consts::TAU
        };
    }
    sweep += (turns.saturating_sub(1)) as f64 * std::f64::consts::TAU * sweep.signum();
    let step = 2.0 * (1.0 - 1e-3 / r.max(1e-3)).clamp(-1.0, 1.0).acos();
    let k = ((sweep.abs() / step.max(1e-6)).ceil() as usize).clamp(4, 4096);
    (0..=k)
        .map(|i| {
            let t = i as f64 / k as f64;
            let ang = a0 + sweep * t;
            let mut p = s;
            p[a] = centre[0] + r * ang.cos();
            p[b] = centre[1] + r * ang.sin();
            p[n] = s[n] + (e[n] - s[n]) * t;
            cx.st.frame.to_machine(&Pose::from_array(p)).to_array()
        })
        .collect()
}

/// G32 / G33 / G34: a move synchronised with the spindle (`docs` §5.12).
fn thread(cx: &mut Ctx<'_>, at: ColSpan) -> Result<(), Diagnostic> {
    let variable = cx.fe.m.motion == 340;
    if variable {
        if let Some(k) = cx.words.take(b'K') {
            cx.fe.m.lead_change = cx.mm(k.v);
        }
    }
    let lead = cx.fe.m.lead;
    if lead <= 0.0 {
        return Err(cx.err("mazatrol::thread", "thread cutting needs the lead F", at));
    }
    let rpm = cx.st.spindle_speed[0];
    if !cx.st.spindle_on[0] || rpm <= 0.0 {
        return Err(cx.err(
            "mazatrol::thread",
            "thread cutting needs a turning spindle: start it with S and M03/M04",
            at,
        ));
    }
    let start = cx.st.program_position();
    let (end, _) = end_point(cx)?;
    let s = start.to_array();
    let e = end.to_array();
    let d = [e[0] - s[0], e[1] - s[1], e[2] - s[2]];
    let length = d[0].abs().max(d[2].abs()).max(d[1].abs());
    let pieces = if variable {
        crate::rules::g34_pieces(length, lead, cx.fe.m.lead_change, 100_000).ok_or_else(|| {
            cx.err(
                "mazatrol::thread",
                "G34: the lead would reach zero before the end of the thread",
                at,
            )
        })?
    } else {
        vec![(length, lead)]
    };
    for (reached, pitch) in pieces {
        let t = if length > 0.0 { reached / length } else { 1.0 };
        let mut p = s;
        for i in 0..9 {
            p[i] = s[i] + (e[i] - s[i]) * t;
        }
        cx.out.push(Canon::StartSpindleSync {
            pitch,
            velocity_mode: false,
        });
        let end_m = cx.st.frame.to_machine(&Pose::from_array(p));
        stroke_check(cx, &[cx.st.position.to_array(), end_m.to_array()], at)?;
        cx.out.push(Canon::StraightFeed(LineMove {
            start: cx.st.position,
            end: end_m,
            feed: pitch * rpm,
            law: stanok_canon::FeedLaw::PerMinute,
        }));
        cx.st.position = end_m;
        cx.out.push(Canon::StopSpindleSync);
    }
    Ok(())
}

/// G04: X / U seconds, P milliseconds (`docs` §5.5).
pub(crate) fn dwell(cx: &mut Ctx<'_>, _span: ColSpan) -> Result<(), Diagnostic> {
    let x = cx.words.take(b'X');
    let u = if cx.fe.m.t() {
        cx.words.take(b'U')
    } else {
        None
    };
    let p = cx.words.take(b'P');
    let given: Vec<_> = [x, u, p].into_iter().flatten().collect();
    if given.len() > 1 {
        return Err(cx.err(
            "mazatrol::repeated-word",
            "G04 takes one time: X, U or P",
            given[1].span,
        ));
    }
    // X/U were halved as diameters on the T-series: a time is not a diameter.
    let t_scale = if cx.fe.m.t() && !cx.fe.m.x_radius && cx.fe.modes.mode == TtpcMode::Off {
        2.0
    } else {
        1.0
    };
    let seconds = match (x.or(u), p) {
        (Some(v), _) => v.v * t_scale,
        (None, Some(p)) => p.v / 1000.0,
        _ => 0.0,
    };
    if seconds < 0.0 {
        return Err(cx.err(
            "mazatrol::value-range",
            "a dwell time cannot be negative",
            given[0].span,
        ));
    }
    cx.out.push(Canon::Dwell { seconds });
    Ok(())
}

/// The reference point n (1 … 4, 5 = floating) in machine coordinates.
fn reference_point(cx: &Ctx<'_>, n: usize, at: ColSpan) -> Result<[f64; 9], Diagnostic> {
    match cx.fe.tables.data.offsets.home.get(n - 1).copied().flatten() {
        Some(p) => Ok(p.to_array()),
        None if n == 1 => Ok([0.0; 9]),
        None => Err(cx.err(
            "mazatrol::reference-point",
            if n == 5 {
                "the floating reference point ([[home]] number = 5) is not in the machine data"
                    .to_string()
            } else {
                format!("reference point {n} is not in the machine data ([[home]] number = {n})")
            },
            at,
        )),
    }
}

/// A rapid in machine coordinates (tool offsets and frames bypassed).
fn rapid_machine(cx: &mut Ctx<'_>, m: [f64; 9], at: ColSpan) -> Result<(), Diagnostic> {
    let end = Pose::from_array(m);
    stroke_check(cx, &[cx.st.position.to_array(), m], at)?;
    cx.out.push(Canon::StraightTraverse(LineMove {
        start: cx.st.position,
        end,
        feed: 0.0,
        law: stanok_canon::FeedLaw::PerMinute,
    }));
    cx.st.position = end;
    Ok(())
}

/// G27 / G28 / G29 / G30 / G30.1 (`docs` §5.7, §5.8).
pub(crate) fn reference(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    if crate::compensate::active(cx) {
        return Err(cx.err(
            "mazatrol::compensation",
            "G27–G30.1 are not allowed under cutter compensation: cancel it with G40 first",
            span,
        ));
    }
    let n = match code {
        300 => match cx.words.take(b'P') {
            Some(p) if (2.0..=4.0).contains(&p.v) && p.v.fract() == 0.0 => p.v as usize,
            Some(p) => {
                return Err(cx.err(
                    "mazatrol::value-range",
                    format!("G30 P{}: P is 2, 3 or 4", p.v),
                    p.span,
                ))
            }
            None => 2,
        },
        301 => 5,
        _ => 1,
    };
    let (target, given) = end_point(cx)?;
    if code == 290 {
        let Some(mid) = cx.fe.m.intermediate else {
            return Err(cx.err(
                "mazatrol::reference-point",
                "G29 needs an intermediate point: no G28/G30 before it",
                span,
            ));
        };
        let mut via = cx.st.position.to_array();
        for i in 0..9 {
            if given[i] {
                via[i] = mid[i];
            }
        }
        rapid_machine(cx, via, span)?;
        let t = cx.st.frame.to_machine(&target).to_array();
        let mut end = cx.st.position.to_array();
        for i in 0..9 {
            if given[i] {
                end[i] = t[i];
            }
        }
        return rapid_machine(cx, end, span);
    }
    let mid = cx.st.frame.to_machine(&target).to_array();
    let mut via = cx.st.position.to_array();
    for i in 0..9 {
        if given[i] {
            via[i] = mid[i];
        }
    }
    if code == 270 {
        rapid_machine(cx, via, span)?;
        let r = reference_point(cx, 1, span)?;
        for i in 0..9 {
            if given[i] && (via[i] - r[i]).abs() > 1e-3 {
                return Err(cx.err(
                    "mazatrol::reference-check",
                    format!(
                        "G27: {} is {:.4} mm from the reference point",
                        "XYZABCUVW".as_bytes()[i] as char,
                        (via[i] - r[i]).abs()
                    ),
                    span,
                ));
            }
        }
        return Ok(());
    }
    let r = reference_point(cx, n, span)?;
    rapid_machine(cx, via, span)?;
    cx.fe.m.intermediate = Some(via);
    let mut end = via;
    for i in 0..9 {
        if given[i] {
            end[i] = r[i];
        }
    }
    rapid_machine(cx, end, span)
}

/// G53: a rapid to machine coordinates of the named axes.
pub(crate) fn machine_move(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if crate::compensate::active(cx) {
        return Err(cx.err(
            "mazatrol::compensation",
            "G53 is not allowed under cutter compensation",
            span,
        ));
    }
    let mut m = cx.st.position.to_array();
    for (i, &l) in AXES.iter().enumerate() {
        if let Some(v) = cx.words.take(l) {
            m[i] = if is_linear(i) { cx.mm(v.v) } else { v.v };
            // X as a diameter on a radius machine: the halving applied to programmed X.
        }
    }
    rapid_machine(cx, m, span)
}

/// G60: the final approach from the negative side (`docs` §5.11).
pub(crate) fn unidirectional(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let (end, given) = end_point(cx)?;
    let d = cx.fe.params.g60_overshoot;
    let mut before = end.to_array();
    for (i, g) in given.iter().enumerate().take(3) {
        if *g {
            before[i] -= d;
        }
    }
    emit_straight(cx, true, Pose::from_array(before), span)?;
    emit_straight(cx, true, end, span)
}

/// G31 (G31.1–G31.3): a feed move that stops at the simulated probe's contact (`docs` §5.9).
pub(crate) fn skip(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if crate::compensate::active(cx) {
        return Err(cx.err(
            "mazatrol::compensation",
            "G31 is not allowed under cutter compensation",
            span,
        ));
    }
    let (end, _) = end_point(cx)?;
    let start = cx.st.position;
    let end_m = cx.st.frame.to_machine(&end);
    let feed = feed_for(cx, 1.0, span)?;
    let contact = first_contact(cx, &start, &end_m);
    let motion = LineMove {
        start,
        end: end_m,
        feed,
        law: stanok_canon::FeedLaw::PerMinute,
    };
    cx.out.push(Canon::StraightProbe {
        motion,
        probe: ProbeKind::Toward,
        contact: contact.map(Box::new),
    });
    let stop = contact.unwrap_or(end_m);
    cx.st.position = stop;
    let w = cx.st.frame.to_program(&stop).to_array();
    let mut skip = [0.0; 6];
    for i in 0..6 {
        skip[i] = if is_linear(i) {
            w[i] / cx.st.units.mm_per_unit()
        } else {
            w[i]
        };
    }
    if cx.fe.m.t() && !cx.fe.m.x_radius {
        skip[0] *= 2.0;
    }
    cx.fe.m.skip = skip;
    Ok(())
}

/// Where the straight probe move first touches a probe surface (machine coordinates).
fn first_contact(cx: &Ctx<'_>, start: &Pose, end: &Pose) -> Option<Pose> {
    let s = start.to_array();
    let e = end.to_array();
    let mut best: Option<f64> = None;
    for surf in &cx.opts.control.probe_surfaces {
        let i = surf.axis.min(8);
        let inside = |v: f64| {
            if surf.at_or_below {
                v <= surf.value
            } else {
                v >= surf.value
            }
        };
        if inside(s[i]) {
            best = Some(0.0);
            continue;
        }
        if !inside(e[i]) || e[i] == s[i] {
            continue;
        }
        let t = (surf.value - s[i]) / (e[i] - s[i]);
        if (0.0..=1.0).contains(&t) {
            best = Some(best.map_or(t, |b: f64| b.min(t)));
        }
    }
    best.map(|t| {
        let mut p = s;
        for i in 0..9 {
            p[i] = s[i] + (e[i] - s[i]) * t;
        }
        Pose::from_array(p)
    })
}

/// G22 / G23 (`docs` §6.2).
pub(crate) fn stroke_mode(cx: &mut Ctx<'_>, code: u32) -> Result<(), Diagnostic> {
    if code == 230 {
        cx.fe.m.stroke_on = false;
        return Ok(());
    }
    let lo = [b'X', b'Y', b'Z'].map(|l| cx.words.take(l).map(|v| cx.mm(v.v)));
    let hi = [b'I', b'J', b'K'].map(|l| cx.words.take(l).map(|v| cx.mm(v.v)));
    if lo.iter().chain(hi.iter()).any(Option::is_some) {
        let mut a = [0.0; 3];
        let mut b = [0.0; 3];
        for i in 0..3 {
            let (p, q) = (lo[i].unwrap_or(0.0), hi[i].unwrap_or(0.0));
            a[i] = p.min(q);
            b[i] = p.max(q);
        }
        cx.fe.m.stroke = Some((a, b));
    }
    if cx.fe.m.stroke.is_none() {
        return Err(cx.err(
            "mazatrol::missing-word",
            "G22 needs the area: X Y Z and I J K, its two corners",
            cx.whole(),
        ));
    }
    cx.fe.m.stroke_on = true;
    Ok(())
}

/// Refuses a path (a polyline of machine points) that enters the G22 area.
pub(crate) fn stroke_check(cx: &Ctx<'_>, pts: &[[f64; 9]], at: ColSpan) -> Result<(), Diagnostic> {
    let (true, Some((lo, hi))) = (cx.fe.m.stroke_on, cx.fe.m.stroke) else {
        return Ok(());
    };
    for w in pts.windows(2) {
        if segment_enters(w[0], w[1], lo, hi) {
            return Err(cx.err(
                "mazatrol::stroke-check",
                format!(
                    "the move enters the G22 forbidden area [{:.3}, {:.3}] × [{:.3}, {:.3}] × [{:.3}, {:.3}]",
                    lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
                ),
                at,
            ));
        }
    }
    Ok(())
}

/// True if the segment p → q passes through the open box (lo, hi) (slab method).
fn segment_enters(p: [f64; 9], q: [f64; 9], lo: [f64; 3], hi: [f64; 3]) -> bool {
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for i in 0..3 {
        let d = q[i] - p[i];
        if d.abs() < 1e-12 {
            if p[i] <= lo[i] || p[i] >= hi[i] {
                return false;
            }
            continue;
        }
        let (mut a, mut b) = ((lo[i] - p[i]) / d, (hi[i] - p[i]) / d);
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        t0 = t0.max(a);
        t1 = t1.min(b);
        if t0 >= t1 {
            return false;
        }
    }
    t1 - t0 > 1e-12
}

#[cfg(test)]
mod tests {
    use super::segment_enters;

    #[test]
    fn the_slab_test() {
        let lo = [0.0, 0.0, 0.0];
        let hi = [10.0, 10.0, 10.0];
        let p = |x: f64, y: f64, z: f64| [x, y, z, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        assert!(segment_enters(p(-5.0, 5.0, 5.0), p(15.0, 5.0, 5.0), lo, hi));
        assert!(!segment_enters(
            p(-5.0, 15.0, 5.0),
            p(15.0, 15.0, 5.0),
            lo,
            hi
        ));
        // Along a face: not inside.
        assert!(!segment_enters(
            p(-5.0, 0.0, 5.0),
            p(15.0, 0.0, 5.0),
            lo,
            hi
        ));
        assert!(segment_enters(p(5.0, 5.0, 5.0), p(5.0, 5.0, 6.0), lo, hi));
    }
}
