//! AxiOMA motion blocks: G04 dwell, G00/G01 and the arcs G02/G03 in their centre, R and CR= forms.

use super::cutter_comp::Comp;
use crate::arc::ArcError;
use crate::arc_rules;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::state::{DistanceMode, MotionMode};
use crate::words::Val;
use stanok_canon::{Canon, Diagnostic, FeedMode};
use stanok_syntax::ColSpan;

/// G04 X<s> or G04 E<s> (spec axioma-2 §2.6): 0…65 s to the millisecond, 65…65000 s to the second.
pub(super) fn dwell_block(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let x = cx.words.take(b'X');
    let e = cx.words.take(b'E');
    let t = match (x, e) {
        (Some(_), Some(e)) => {
            return Err(cx.err(
                "axioma::dwell-x-and-e",
                "G04 with both X and E: write the dwell time once",
                e.span,
            ))
        }
        (Some(v), None) | (None, Some(v)) => v,
        (None, None) => {
            return Err(cx.err(
                "axioma::dwell-time-missing",
                "G04 needs the dwell time as X<seconds> or E<seconds>",
                span,
            ))
        }
    };
    if !(0.0..=65000.0).contains(&t.v) {
        return Err(cx
            .err(
                "axioma::dwell-range",
                format!("dwell time {} s out of range", t.v),
                t.span,
            )
            .with_note(
                "allowed: 0 … 65 s (resolution 0.001 s) and 65 … 65000 s (resolution 1 s)",
            ));
    }
    let seconds = if t.v > 65.0 {
        t.v.round()
    } else {
        (t.v * 1000.0).round() / 1000.0
    };
    if let Some(&l) = AXIS_WORDS
        .iter()
        .find(|&&l| cx.words.has(l) && !cx.words.is_used(l))
    {
        let v = cx.words.take(l).map(|v| v.span).unwrap_or(span);
        return Err(cx.err(
            "axioma::dwell-with-motion",
            format!(
                "G04 acts only in its own block: {} cannot move here",
                l as char
            ),
            v,
        ));
    }
    cx.out.push(Canon::Dwell { seconds });
    Ok(())
}

pub(super) fn motion(cx: &mut Ctx<'_>, span: ColSpan, cr: Option<Val>) -> Result<(), Diagnostic> {
    let mode = cx.st.motion;
    if cx.fe.modes.polar.on {
        return polar_motion(cx, span, cr);
    }
    let centre_letters = [b'I', b'J', b'K'];
    let is_arc = matches!(mode, MotionMode::ArcCw | MotionMode::ArcCcw);
    let has_centre = is_arc && cx.words.any(&centre_letters);
    let has_radius = is_arc && (cx.words.has(b'R') || cr.is_some());
    if !cx.has_axis_words() && !has_centre && !has_radius {
        if let Some(v) = cr {
            return Err(cx.err(
                "interp::unused-word",
                "CR= has no meaning in this block",
                v.span,
            ));
        }
        return Ok(());
    }
    match mode {
        MotionMode::Rapid | MotionMode::Linear | MotionMode::None => {
            if let Some(v) = cr {
                return Err(cx.err(
                    "interp::unused-word",
                    "CR= has no meaning in this block",
                    v.span,
                ));
            }
            let (end, _) = cx.end_point()?;
            if mode == MotionMode::Rapid {
                if cx.fe.ext.comp.is_active() {
                    return Comp::line(cx, true, end, 0.0, span);
                }
                cx.straight(true, end, 0.0);
            } else {
                let length = super::technology::feed_length(
                    &cx.st.program_position().to_array(),
                    &end.to_array(),
                );
                let feed = feed_check(cx, span, length)?;
                if cx.fe.ext.comp.is_active() {
                    return Comp::line(cx, false, end, feed, span);
                }
                cx.straight(false, end, feed);
            }
            Ok(())
        }
        MotionMode::ArcCw | MotionMode::ArcCcw => {
            arc_move(cx, mode == MotionMode::ArcCcw, span, cr)
        }
    }
}

/// A motion block under G16: the plane point from R and Q (spec axioma-1 §17.4, §17.5).
fn polar_motion(cx: &mut Ctx<'_>, span: ColSpan, cr: Option<Val>) -> Result<(), Diagnostic> {
    if let Some(v) = cr {
        return Err(cx.err(
            "axioma::polar-cr",
            "CR= has no meaning in polar mode: a polar arc runs about the pole or its I/J/K centre",
            v.span,
        ));
    }
    if cx.fe.ext.comp.is_active() {
        return Err(cx.err(
            "axioma::comp-polar",
            "polar motion (G16) cannot be radius-compensated",
            span,
        ));
    }
    let start = cx.st.program_position();
    let Some((end, full_turn)) = super::polar::end_point(cx)? else {
        return Ok(());
    };
    let length = super::technology::feed_length(&start.to_array(), &end.to_array());
    match cx.st.motion {
        MotionMode::Rapid => cx.straight(true, end, 0.0),
        MotionMode::Linear | MotionMode::None => {
            let feed = feed_check(cx, span, length)?;
            cx.straight(false, end, feed);
        }
        MotionMode::ArcCw | MotionMode::ArcCcw => {
            let ccw = cx.st.motion == MotionMode::ArcCcw;
            let plane = cx.st.plane;
            let (a, b, _) = plane.axes();
            let (s, e) = (start.to_array(), end.to_array());
            let (s2, e2) = ([s[a], s[b]], [e[a], e[b]]);
            if !full_turn && (s2[0] - e2[0]).hypot(s2[1] - e2[1]) < 1e-9 {
                // G90 to the angle it is at: nothing to do in the plane (spec A18).
                return Ok(());
            }
            let planar = super::polar::arc_geometry(cx, s2, e2, span)?;
            let len = crate::arc::helix_length(start, end, plane, planar.centre, ccw, planar.turns);
            let feed = feed_check(cx, span, len)?;
            emit_arc(cx, plane, ccw, start, end, planar, feed, span)?;
        }
    }
    Ok(())
}

pub(super) fn feed_check(cx: &Ctx<'_>, span: ColSpan, length: f64) -> Result<f64, Diagnostic> {
    if cx.st.feed_mode == FeedMode::UnitsPerRevolution && cx.st.spindle_speed[0] <= 0.0 {
        return Err(cx.manual(
            615,
            "G95 feed move while the main spindle speed S is 0",
            span,
        ));
    }
    // A23: G95 stays legal after M05, but a feed per revolution of a standing spindle never moves.
    if cx.st.feed_mode == FeedMode::UnitsPerRevolution && !cx.st.spindle_on[0] {
        return Err(cx
            .manual(615, "G95 feed move while the main spindle is stopped", span)
            .with_note("start the spindle (M03/M04) or cancel G95 with G94/G93 after M05"));
    }
    let feed = cx.path_feed(length);
    if feed <= 0.0 {
        return Err(cx
            .err("axioma::feed-missing", "feed move with feed F = 0", span)
            .with_note("program F before the first G01/G02/G03 (after a G93/G94/G95 change F must be programmed again)"));
    }
    Ok(feed)
}

fn arc_move(cx: &mut Ctx<'_>, ccw: bool, span: ColSpan, cr: Option<Val>) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    let (a, b, _) = plane.axes();
    let letters = [b'I', b'J', b'K'];
    let start = cx.st.program_position();
    let extra_turns = match cx.words.take(b'P') {
        Some(p) => cx.non_negative_integer(p, "P (additional full turns)")?,
        None => 0,
    };
    let (end, _) = cx.end_point()?;
    let s = [start.to_array()[a], start.to_array()[b]];
    let e = [end.to_array()[a], end.to_array()[b]];
    let r = cx.words.take(b'R');
    let ia = cx.words.take(letters[a]);
    let ib = cx.words.take(letters[b]);
    let tol = cx.opts.arc_tolerance_mm;
    let has_centre = ia.is_some() || ib.is_some();
    let radius_word = r.or(cr);
    if has_centre && radius_word.is_some() {
        return Err(cx.manual(
            621,
            "invalid coordinates of the circle centre: both a centre (I/J/K) and a radius (R/CR=) are programmed",
            radius_word.map(|v| v.span).unwrap_or(span),
        ));
    }
    if r.is_some() && cr.is_some() {
        return Err(cx.manual(
            623,
            "invalid value of the circle radius: both R and CR= are programmed",
            span,
        ));
    }
    let result = if has_centre {
        let relative = cx.st.distance == DistanceMode::Incremental
            || cx.st.arc_distance == DistanceMode::Incremental;
        let mut c = [0.0; 2];
        for (k, (word, coord)) in [(ia, s[0]), (ib, s[1])].into_iter().enumerate() {
            c[k] = match word {
                Some(v) if relative => coord + cx.mm(v.v),
                Some(v) => cx.mm(v.v),
                None => {
                    if !relative {
                        cx.warnings.push(Diagnostic::warning(
                            "axioma::centre-letter-missing",
                            format!(
                                "{} missing under G190: the centre takes the start point's coordinate",
                                letters[[a, b][k]] as char
                            ),
                            cx.block.span_of(span),
                        ));
                    }
                    coord
                }
            };
        }
        arc_rules::centre_format(s, e, c, extra_turns, tol)
    } else if let Some(rv) = r {
        if rv.v <= 0.0 {
            return Err(cx
                .manual(
                    623,
                    "invalid value of the circle radius: R must be positive",
                    rv.span,
                )
                .with_note(
                    "for an arc of more than 180° use CR= with a negative value, or I/J/K",
                ));
        }
        arc_rules::radius_format(s, e, cx.mm(rv.v), false, ccw, extra_turns, tol)
    } else if let Some(cv) = cr {
        arc_rules::radius_format(s, e, cx.mm(cv.v.abs()), cv.v < 0.0, ccw, extra_turns, tol)
    } else {
        return Err(cx.manual(
            621,
            "invalid coordinates of the circle centre: no centre (I/J/K) and no radius (R/CR=)",
            span,
        ));
    };
    let at = radius_word.map(|v| v.span).unwrap_or(span);
    let planar = result.map_err(|err| match err {
        ArcError::ZeroRadius => cx.manual(621, "invalid coordinates of the circle centre: the centre is the start point", span),
        ArcError::RadiusMismatch { r1, r2 } => cx
            .manual(622, "invalid coordinates of the circle end point: it is not on the circle", span)
            .with_note(format!(
                "start radius {r1:.4} mm, end radius {r2:.4} mm: difference {:.4} mm > tolerance {tol} mm",
                (r1 - r2).abs()
            )),
        ArcError::EndEqualsStart => cx.manual(
            622,
            "invalid coordinates of the circle end point: a radius cannot define an arc that ends where it starts",
            span,
        ),
        ArcError::RadiusTooSmall { half_chord, radius } => cx
            .manual(623, "invalid value of the circle radius: too small to reach the end point", at)
            .with_note(format!("radius {radius:.4} mm < half the chord {half_chord:.4} mm")),
        ArcError::NonPositiveRadius => cx.manual(623, "invalid value of the circle radius", at),
    })?;
    let length = crate::arc::helix_length(start, end, plane, planar.centre, ccw, planar.turns);
    let feed = feed_check(cx, span, length)?;
    if cx.fe.ext.comp.is_active() {
        return Comp::arc(cx, ccw, start, end, planar, feed, span);
    }
    emit_arc(cx, plane, ccw, start, end, planar, feed, span)?;
    Ok(())
}

/// Emits an arc; under unequal in-plane scale factors applies spec axioma-1 §11.3's rule: the end
/// point is scaled per axis like any point, the radius becomes `k_max·r`, and the centre is the
/// point at that distance from the actual start and the scaled end, on the side of the per-axis
/// scaled programmed centre (623 if no such point exists).
#[allow(clippy::too_many_arguments)]
fn emit_arc(
    cx: &mut Ctx<'_>,
    plane: stanok_canon::Plane,
    ccw: bool,
    start: stanok_canon::Pose,
    end: stanok_canon::Pose,
    planar: crate::arc::PlanarArc,
    feed: f64,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let Some(k_max) = cx.fe.chain.non_uniform_in(plane) else {
        cx.arc(plane, ccw, end, planar, feed);
        return Ok(());
    };
    let (a, b, _) = plane.axes();
    cx.apply_pending_tlo();
    let s_prog = start.to_array();
    let r = (s_prog[a] - planar.centre[0]).hypot(s_prog[b] - planar.centre[1]);
    let mut c_prog = s_prog;
    c_prog[a] = planar.centre[0];
    c_prog[b] = planar.centre[1];
    let c0 = cx
        .st
        .frame
        .to_machine(&stanok_canon::Pose::from_array(c_prog))
        .xyz();
    let s_m = cx.st.position.xyz();
    let e_m = cx.st.frame.to_machine(&end).xyz();
    let r2 = k_max * r;
    let (s2, e2, c2) = ([s_m[a], s_m[b]], [e_m[a], e_m[b]], [c0[a], c0[b]]);
    let chord = [e2[0] - s2[0], e2[1] - s2[1]];
    let d = chord[0].hypot(chord[1]);
    let centre2 = if d < 1e-9 {
        // Full circle: keep the direction of the scaled centre, at the new radius.
        let v = [c2[0] - s2[0], c2[1] - s2[1]];
        let len = v[0].hypot(v[1]).max(1e-12);
        [s2[0] + v[0] / len * r2, s2[1] + v[1] / len * r2]
    } else {
        if d / 2.0 > r2 + cx.opts.arc_tolerance_mm {
            return Err(cx
                .manual(
                    623,
                    "invalid value of the circle radius under unequal scale factors",
                    span,
                )
                .with_note(format!(
                    "radius k_max·r = {r2:.4} mm, half chord {:.4} mm",
                    d / 2.0
                )));
        }
        let h = (r2 * r2 - d * d / 4.0).max(0.0).sqrt();
        let mid = [(s2[0] + e2[0]) / 2.0, (s2[1] + e2[1]) / 2.0];
        let n = [-chord[1] / d, chord[0] / d];
        let side = ((c2[0] - mid[0]) * n[0] + (c2[1] - mid[1]) * n[1]).signum();
        let side = if side == 0.0 { 1.0 } else { side };
        [mid[0] + side * h * n[0], mid[1] + side * h * n[1]]
    };
    let mut centre_m = s_m;
    centre_m[a] = centre2[0];
    centre_m[b] = centre2[1];
    cx.arc_with_centre(plane, ccw, end, centre_m, planar.turns, feed);
    Ok(())
}
