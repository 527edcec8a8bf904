//! RS274/NGC motion: G0/G1 (with G53), G2/G3 in both formats, G80, and the feed checks of each
//! feed mode, with LinuxCNC's error texts.

use super::{arc_tolerance, g_name, radius_tolerance, unsupported};
use crate::arc::{helix_length, ArcError};
use crate::arc_rules;
use crate::codes::*;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::state::{DistanceMode, MotionMode};
use stanok_canon::{Canon, Diagnostic, FeedMode, Plane, Pose};
use stanok_syntax::ColSpan;

/// A motion block. Inlined into `execute`, so that an ordinary block makes one call
/// (`motion_block_inner`); the G7x profile's corner words take the cold path.
#[inline(always)]
pub(super) fn motion_block(
    cx: &mut Ctx<'_>,
    params: &mut crate::params::Parameters,
    code: u32,
    span: ColSpan,
    explicit: bool,
    g53: Option<ColSpan>,
    f_in_block: bool,
) -> Result<(), Diagnostic> {
    if cx.fe.modes.in_profile && matches!(code, G0 | G1 | G2 | G3) {
        return motion_in_profile(cx, params, code, span, explicit, g53, f_in_block);
    }
    // Tested first: the write journals the whole `Rs274State` (a copy of it), and only the
    // first motion of a run finds it set (measured, docs/performance.md).
    // G5 and G5.1 keep LinuxCNC's motion mode as it was (−1 after G5.3 included).
    if cx.fe.modes.motion_unset && !matches!(code, G5 | G5_1) {
        cx.fe.modes.motion_unset = false;
    }
    motion_block_inner(cx, params, code, span, explicit, g53, f_in_block)
}

/// In a G7x profile the block's words are recorded for the cycle (`lathe_cycles::profile_block`), and
/// A and C on a move are its end corner's fillet and chamfer, not axes.
#[cold]
#[inline(never)]
fn motion_in_profile(
    cx: &mut Ctx<'_>,
    params: &mut crate::params::Parameters,
    code: u32,
    span: ColSpan,
    explicit: bool,
    g53: Option<ColSpan>,
    f_in_block: bool,
) -> Result<(), Diagnostic> {
    let block = super::lathe_cycles::profile_block(cx, code)?;
    motion_block_inner(cx, params, code, span, explicit, g53, f_in_block)?;
    // Taken back by the front end's rollback if the block fails after its motion.
    cx.fe.profile_blocks.push(block);
    cx.fe.profile_block_pushed = true;
    Ok(())
}

fn motion_block_inner(
    cx: &mut Ctx<'_>,
    params: &mut crate::params::Parameters,
    code: u32,
    span: ColSpan,
    explicit: bool,
    g53: Option<ColSpan>,
    f_in_block: bool,
) -> Result<(), Diagnostic> {
    let handler = g_code(code).map_or(Handler::Unsupported, |c| c.handler);
    if handler != Handler::CannedCycle {
        // Leaving the canned cycles ends a series (its initial level is forgotten). Written
        // only when it changes: `rs274` is journalled on its first write (`state::Journalled`).
        if cx.fe.modes.cycle_il_set {
            cx.fe.modes.cycle_il_set = false;
        }
    }
    if matches!(
        handler,
        Handler::Straight | Handler::Arc | Handler::CancelMotion
    ) && cx.fe.modes.motion_code.is_some()
    {
        cx.fe.modes.motion_code = None;
    }
    // Moves whose path compensation cannot offset (LinuxCNC refuses them the same way).
    if cx.fe.modes.comp.on() {
        let what = match handler {
            Handler::Probe => "probe",
            Handler::Spline | Handler::Nurbs => "use splines",
            Handler::Thread | Handler::RigidTap | Handler::ThreadCycle => "thread or tap",
            Handler::CannedCycle => "use canned cycles",
            _ => "",
        };
        if !what.is_empty() {
            return Err(cx.err(
                "rs274::comp-forbids",
                format!("Cannot {what} with cutter radius compensation on"),
                span,
            ));
        }
    }
    match handler {
        Handler::CannedCycle => super::cycles::canned_cycle(cx, code, span),
        Handler::LatheCycle => super::lathe_cycles::begin(cx, code, span),
        Handler::Thread => super::sync::g33(cx, span),
        Handler::Spline if code == G5 => super::spline::cubic(cx, span, f_in_block),
        Handler::Spline => super::spline::quadratic(cx, span, f_in_block),
        Handler::Nurbs => super::spline::nurbs_point(cx, params, explicit, span),
        Handler::Probe => super::probe::straight_probe(cx, params, code, span),
        Handler::RigidTap => super::sync::g33_1(cx, span),
        Handler::ThreadCycle => super::sync::g76(cx, span),
        Handler::CancelMotion => {
            if explicit {
                cx.st.motion = MotionMode::None;
                cx.out.push(Canon::Comment {
                    text: "interpreter: motion mode set to none".into(),
                });
            }
            if cx.has_axis_words() {
                // LinuxCNC words it differently when G80 is written on the line and when it is
                // only the modal state (its power-on motion mode).
                return Err(if explicit {
                    cx.err(
                        "rs274::axis-words-with-g80",
                        "Cannot use axis values with g80",
                        span,
                    )
                } else {
                    cx.err(
                        "rs274::axis-words-without-g-code",
                        "Cannot use axis values without a g code that uses them",
                        span,
                    )
                });
            }
            Ok(())
        }
        Handler::Straight => {
            let rapid = code == G0;
            let end = if let Some(g53_span) = g53 {
                if cx.st.distance == DistanceMode::Incremental {
                    return Err(cx.err(
                        "rs274::g53-incremental",
                        "Cannot use g53 incremental",
                        g53_span,
                    ));
                }
                // G53: the words are machine coordinates of the controlled point, the tool length
                // offset not added (LinuxCNC's find_ends takes the offset off the word and canon
                // adds it back: rs274 prints machine Z0 under G43 H4 as Z = -offset; issue 21,
                // reproduction 1). Words not given keep the current machine position.
                let mut m = cx.st.position.to_array();
                for (k, &letter) in AXIS_WORDS.iter().enumerate() {
                    if let Some(v) = cx.words.take(letter) {
                        let v = if crate::ctx::is_linear(k) {
                            cx.mm(v.v)
                        } else {
                            v.v
                        };
                        m[k] = v;
                    }
                }
                cx.st.frame.to_program(&Pose::from_array(m))
            } else {
                cx.end_point()?.0
            };
            cx.st.motion = if rapid {
                MotionMode::Rapid
            } else {
                MotionMode::Linear
            };
            let feed = if rapid {
                0.0
            } else {
                let length = inverse_time_length(cx, &end);
                feed_for(cx, f_in_block, span, false, || length)?
            };
            // LinuxCNC compensates only with a tool radius above 0 (`cutter_comp_radius > 0.0`):
            // with none the moves are plain, corners get no arcs.
            if cx.fe.modes.comp.on() && cx.fe.modes.comp.radius > 0.0 && g53.is_none() {
                super::cutter_comp::straight(cx, rapid, end, feed, span)
            } else {
                cx.straight(rapid, end, feed);
                // The exit move after G40 has used the programmed point. Written only when set:
                // the write journals (copies) the whole `Rs274State` (`state::Journalled`), which
                // every straight move did (measured, docs/performance.md).
                let comp = &cx.fe.modes.comp;
                if comp.program.is_some() || comp.arc_refused {
                    let comp = &mut cx.fe.modes.comp;
                    comp.program = None;
                    comp.arc_refused = false;
                }
                Ok(())
            }
        }
        Handler::Arc => {
            if let Some(g53_span) = g53 {
                return Err(cx.err(
                    "rs274::g53-with-arc",
                    "Must use g0 or g1 with g53",
                    g53_span,
                ));
            }
            if cx.fe.modes.comp.arc_refused {
                return Err(cx
                    .err(
                        "rs274::comp-exit-arc",
                        "The move just after exiting cutter compensation mode must be straight, not an arc",
                        span,
                    )
                    .with_note("leave cutter compensation with a G0 or G1 move after G40"));
            }
            cx.st.motion = if code == G2 {
                MotionMode::ArcCw
            } else {
                MotionMode::ArcCcw
            };
            arc_block(cx, code == G3, span, f_in_block)
        }
        _ => Err(unsupported(
            cx,
            &g_name(code),
            "RS274/NGC cycles, splines and probing",
            span,
        )),
    }
}

/// The length an inverse-time straight feed to `end` divides by, in mm (LinuxCNC's
/// `find_straight_length`): the XYZ distance if X, Y or Z moves by more than 10⁻⁷ program units,
/// else the UVW distance if they move, else the ABC distance in degrees (taken as program units).
/// A move of none of them is given the length that makes its rate 0.1 units/min whatever F is
/// (LinuxCNC's `inverse_time_rate_straight`, its issue 2410).
fn inverse_time_length(cx: &Ctx<'_>, end: &Pose) -> f64 {
    let a = cx.st.program_position().to_array();
    let b = end.to_array();
    let tiny = cx.mm(1e-7);
    let moved = |k: &[usize]| k.iter().any(|&k| (b[k] - a[k]).abs() > tiny);
    let norm = |k: &[usize]| k.iter().map(|&k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt();
    let length = if moved(&[0, 1, 2]) {
        norm(&[0, 1, 2])
    } else if moved(&[6, 7, 8]) {
        norm(&[6, 7, 8])
    } else {
        cx.mm(norm(&[3, 4, 5]))
    };
    if length == 0.0 && cx.st.feed > 0.0 {
        cx.mm(0.1) / cx.st.feed
    } else {
        length
    }
}

/// Checks the feed for a feed move and returns it in mm/min.
fn feed_for(
    cx: &mut Ctx<'_>,
    f_in_block: bool,
    span: ColSpan,
    arc: bool,
    length: impl FnOnce() -> f64,
) -> Result<f64, Diagnostic> {
    match cx.st.feed_mode {
        FeedMode::UnitsPerMinute => {
            // A G7x profile is only read: its feed is checked when the cycle cuts (`lathe.rs`).
            if cx.st.feed <= 0.0 && !cx.fe.modes.in_profile {
                return Err(cx.err(
                    "rs274::zero-feed",
                    if arc {
                        "Cannot make arc with zero feed rate"
                    } else {
                        "Cannot do g1 with zero feed rate"
                    },
                    span,
                ));
            }
            Ok(cx.st.feed)
        }
        FeedMode::UnitsPerRevolution => {
            // LinuxCNC's messages are those of G94.
            if cx.st.feed <= 0.0 {
                return Err(cx.err(
                    "rs274::zero-feed",
                    if arc {
                        "Cannot make arc with zero feed rate"
                    } else {
                        "Cannot do g1 with zero feed rate"
                    },
                    span,
                ));
            }
            if cx.st.spindle_speed[0] <= 0.0 {
                return Err(cx.err(
                    "rs274::zero-spindle-feed-per-rev",
                    "Cannot feed with zero spindle speed in feed per rev mode",
                    span,
                ));
            }
            Ok(cx.path_feed(0.0))
        }
        FeedMode::InverseTime => {
            if !f_in_block {
                return Err(cx.err(
                    "rs274::inverse-time-f-missing",
                    if arc {
                        "F word missing with inverse time arc move"
                    } else {
                        "F word missing with inverse time g1 move"
                    },
                    span,
                ));
            }
            // LinuxCNC 2.9 never asks for less than 0.1 program units per minute: a short move
            // at a low inverse time gets 0.1 (seen in rs274's traces; its issue 2410).
            let feed = cx.path_feed(length()).max(cx.mm(0.1));
            cx.out.push(Canon::SetFeedRate { feed });
            Ok(feed)
        }
    }
}

fn arc_block(
    cx: &mut Ctx<'_>,
    ccw: bool,
    span: ColSpan,
    f_in_block: bool,
) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    let (a, b, n) = plane.axes();
    let offset_letters = [b'I', b'J', b'K'];
    let plane_name = match plane {
        Plane::XY => "XY",
        Plane::ZX => "XZ",
        Plane::YZ => "YZ",
    };
    let has_ijk = cx.words.any(&offset_letters);
    let r_word = cx.words.take(b'R');
    // A G7x profile's arcs are read by LinuxCNC's lathe-cycle reader, with its own words.
    if cx.fe.modes.in_profile && r_word.is_none() && !has_ijk {
        return Err(cx.err(
            "rs274::g7x-arc-centre",
            "G7X error: either I or K must be present for arc",
            span,
        ));
    }
    if cx.fe.modes.in_profile && r_word.is_some() && has_ijk {
        return Err(cx.err(
            "rs274::g7x-arc-centre",
            "G7X error: both R and I or K flag used for arc",
            span,
        ));
    }
    if r_word.is_none() && !has_ijk {
        return Err(cx.err(
            "rs274::arc-r-ijk-missing",
            "R i j k words all missing for arc",
            span,
        ));
    }
    if r_word.is_some() && has_ijk {
        return Err(cx.err(
            "rs274::arc-mixed-format",
            "Mixed radius-ijk format for arc",
            span,
        ));
    }
    if let Some(v) = cx.words.take(offset_letters[n]) {
        return Err(cx.err(
            "rs274::arc-offset-in-wrong-plane",
            format!(
                "{} word given for arc in {} plane",
                offset_letters[n] as char,
                plane_name.to_lowercase()
            ),
            v.span,
        ));
    }
    let turns = match cx.words.take(b'P') {
        Some(p) => {
            let t = p.v.round();
            if (p.v - t).abs() > 1e-6 {
                return Err(cx.err(
                    "rs274::arc-p-not-integer",
                    "P value not an integer with G2 or G3",
                    p.span,
                ));
            }
            if t < 1.0 {
                return Err(cx.err(
                    "rs274::arc-p-not-positive",
                    "P value must be a positive integer with G2 or G3",
                    p.span,
                ));
            }
            t as u32
        }
        None => 1,
    };
    let start = cx.programmed_position();
    let (end, given) = cx.end_point()?;
    let plane_words = given[a] || given[b];
    let s = [start.to_array()[a], start.to_array()[b]];
    let e = [end.to_array()[a], end.to_array()[b]];
    let tol = arc_tolerance(cx);
    let planar = if let Some(r) = r_word {
        if !plane_words {
            return Err(cx.err(
                "rs274::arc-plane-words-missing",
                format!(
                    "{} and {} words missing for arc in {} plane",
                    AXIS_WORDS[a.min(b)] as char,
                    (AXIS_WORDS[a.max(b)] as char).to_ascii_lowercase(),
                    plane_name.to_lowercase()
                ),
                span,
            ));
        }
        arc_rules::radius_format(s, e, cx.mm(r.v), ccw, turns, radius_tolerance(cx))
            .map_err(|err| arc_error(cx, err, span))?
    } else {
        let oa = cx.words.take(offset_letters[a]);
        let ob = cx.words.take(offset_letters[b]);
        let centre = match cx.st.arc_distance {
            DistanceMode::Incremental => [
                s[0] + oa.map(|v| cx.mm(v.v)).unwrap_or(0.0),
                s[1] + ob.map(|v| cx.mm(v.v)).unwrap_or(0.0),
            ],
            DistanceMode::Absolute => {
                for (o, l) in [(oa, offset_letters[a]), (ob, offset_letters[b])] {
                    if o.is_none() {
                        return Err(cx.err(
                            "rs274::arc-absolute-offset-missing",
                            format!("{} word missing in absolute center arc", l as char),
                            span,
                        ));
                    }
                }
                [
                    cx.mm(oa.map_or(0.0, |v| v.v)),
                    cx.mm(ob.map_or(0.0, |v| v.v)),
                ]
            }
        };
        let checked = arc_rules::centre_format(s, e, centre, turns, tol);
        // In a G7x profile LinuxCNC reads the arc as written and refuses it only if the cycle
        // cuts it off its radius (`lathe_cycles::emit`).
        let checked = match checked {
            Err(ArcError::RadiusMismatch { .. }) if cx.fe.modes.in_profile => {
                arc_rules::centre_format(s, e, centre, turns, f64::INFINITY)
            }
            other => other,
        };
        checked.map_err(|err| radius_mismatch(cx, err, s, e, centre, tol, span))?
    };
    let feed = feed_for(cx, f_in_block, span, true, || {
        helix_length(start, end, plane, planar.centre, ccw, planar.turns)
    })?;
    if cx.fe.modes.comp.on() && cx.fe.modes.comp.radius > 0.0 {
        return super::cutter_comp::arc(cx, ccw, end, planar, feed, span);
    }
    cx.arc(plane, ccw, end, planar, feed);
    if cx.fe.modes.comp.program.is_some() {
        cx.fe.modes.comp.program = None;
    }
    Ok(())
}

/// The error of a centre-format arc (`s`, `e`, `centre` in the plane's axes, mm), with
/// LinuxCNC's numbers for a radius mismatch.
#[allow(clippy::too_many_arguments)]
pub(crate) fn radius_mismatch(
    cx: &Ctx<'_>,
    err: ArcError,
    s: [f64; 2],
    e: [f64; 2],
    centre: [f64; 2],
    tol: f64,
    span: ColSpan,
) -> Diagnostic {
    let (a, b, _) = cx.st.plane.axes();
    if let ArcError::RadiusMismatch { r1, r2 } = err {
        let k = cx.st.units.mm_per_unit();
        let la = AXIS_WORDS[a] as char;
        let lb = AXIS_WORDS[b] as char;
        return cx
            .err(
                "rs274::arc-radius-mismatch",
                format!(
                    "Radius to end of arc differs from radius to start: start=({la}{:.4},{lb}{:.4}) center=({la}{:.4},{lb}{:.4}) end=({la}{:.4},{lb}{:.4}) r1={:.4} r2={:.4} abs_err={} rel_err={:.4}%",
                    s[0] / k, s[1] / k, centre[0] / k, centre[1] / k, e[0] / k, e[1] / k,
                    r1 / k, r2 / k, crate::cfmt::g((r1 - r2).abs() / k, 4),
                    (r1 - r2).abs() / r1.max(r2) * 100.0
                ),
                span,
            )
            .with_note(format!(
                "allowed: |r1 − r2| ≤ {:.4} (hard limit {:.4}), or a relative error ≤ 0.1 %",
                tol / k,
                100.0 * tol / k
            ));
    }
    arc_error(cx, err, span)
}

fn arc_error(cx: &Ctx<'_>, err: ArcError, span: ColSpan) -> Diagnostic {
    match err {
        ArcError::EndEqualsStart => cx.err(
            "rs274::arc-end-equals-start",
            "Current point same as end point of arc",
            span,
        ),
        ArcError::ZeroRadius => cx.err("rs274::arc-zero-radius", "Zero-radius arc", span),
        ArcError::RadiusTooSmall { half_chord, radius } => cx
            .err(
                "rs274::arc-radius-too-small",
                "Arc radius too small to reach end point",
                span,
            )
            .with_note(format!(
                "half chord {half_chord:.4} mm > radius {radius:.4} mm"
            )),
        // `R0`: LinuxCNC finds the chord longer than the radius.
        ArcError::NonPositiveRadius => cx.err(
            "rs274::arc-radius-too-small",
            "Arc radius too small to reach end point",
            span,
        ),
        ArcError::RadiusMismatch { r1, r2 } => cx.err(
            "rs274::arc-radius-mismatch",
            format!("Radius to end of arc differs from radius to start: r1={r1:.4} r2={r2:.4}"),
            span,
        ),
    }
}
