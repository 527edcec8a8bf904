//! # stanok-axioma: the AxiOMA Control front end
//!
//! Block semantics (spec axioma-1 §2, §5, §6, §13, §15, §16 and axioma-2 §2, §3.3, §4), the
//! high-level language (`hll/`), the chain of frames (`chain.rs`), compensation, cycles,
//! splines, M tables, technology and 5-axis orientation. `front.rs` is the front end the driver
//! calls (`stanok_interp_core::FrontEnd`).
//!
//! Order of execution inside one block (the manual's prefix/postfix model, spec axioma-2 §4.1):
//!
//! ```text
//!  1. MSG("…")                         5. prefix M functions, by group order:
//!  2. modal G codes (plane, units,        spindle (1) with its S, coolant (2), tool (3) with its T,
//!     G90/G91, G190/G191, feed type,      then the other prefix groups in table order
//!     G60/G64, BRISK/SOFT …)           6. G04 dwell or the block's motion
//!  3. F                                7. postfix M functions by group order; program control
//!  4. S and T without an M function       (M00/M01/M02/M30/M99) always last
//! ```
//!
//! Conflicting words: the manual says only the last word of a group takes effect; Stanok does that
//! and warns. LEAD and TILT (named by the manual, described nowhere) are recognised and rejected
//! with `interp::unsupported`. 3D tool radius compensation (CUT3D*, `comp3d/`) hooks in at three
//! points: its mode words and the G40/G41/G42 it claims, `comp3d::before_motion` (normals, ISD,
//! orientation method) and `comp3d::after_block` (the block's motions to its look-ahead).

mod arc_rules;
mod chain;
pub mod comp3d;
pub mod cutter_comp;
pub mod cycles;
mod extension;
mod frames;
mod front;
mod hll;
mod home;
mod mfunc;
mod modes;
mod motion;
pub mod mtable;
mod orientation;
mod outputs;
mod polar;
pub mod probe;
pub mod splines;
mod technology;
mod tools;

/// The core's pieces under the names the front end's files use.
mod ctx {
    pub use stanok_interp_core::ctx::*;
    /// A block's context with the AxiOMA part.
    pub type Ctx<'a> = stanok_interp_core::Ctx<'a, crate::front::AxiomaPart>;
}
use stanok_interp_core::{arc, frame, state, words};

pub use chain::AxiomaChain;
pub use extension::{AxiomaMachineParams, Extension};
pub use front::{Axioma, AxiomaPart};
pub use hll::value::HVal;
pub use modes::{AxiomaModes, HomeReturn, LengthComp, Polar};
pub use mtable::{MEntry, MGroup, MTable};
pub use probe::ProbeLatch;
pub use technology::css_rpm;

use crate::ctx::Ctx;
use crate::state::{DistanceMode, MotionMode, PathMode};
use crate::words::Val;
use stanok_canon::{AuxTiming, Canon, Diagnostic, FeedMode, LengthUnits, Plane};
use stanok_interp_core::Outcome;
use stanok_syntax::{ColSpan, Keyword};

fn g_name(code: u32) -> String {
    format!("G{:02}", code / 10)
}

/// What a G code does, by the modal group of table 2.1.
#[derive(Debug, Clone, Copy, PartialEq)]
enum GAction {
    Motion(MotionMode),
    Dwell,
    Plane(Plane),
    Units(LengthUnits),
    Distance(DistanceMode),
    ArcCentre(DistanceMode),
    FeedMode(FeedMode),
    PathMode(bool),
    Retract(bool),
    /// G72 (false) / G73 (true).
    Mirror(bool),
    /// G172 / G173.
    Scale(bool),
    /// G272 / G273.
    Rotate(bool),
    /// G193 / G194 / G195 (the code ×10).
    Shift(u32),
    /// G53 (None) / G54…G59 (1…6).
    ZeroOffset(Option<u8>),
    /// G153 (None) / G154…G159 (1…6).
    Workpiece(Option<u8>),
    /// G10: radius/diameter programming per axis.
    Diameter,
    /// G15 (false) / G16 (true).
    Polar(bool),
    /// G43 / G44 / G45 / G49 (the code ×10).
    LengthComp(u32),
    /// G28 (true) / G29 (false).
    Home(bool),
    /// G40 / G41 / G42 / G143 / G144 (the code ×10).
    Radius(u32),
    /// G110 (true, set) / G111 (false, reset).
    Output(bool),
    /// G75 probe move (Interpolate group).
    Probe,
    /// G96 (true) / G97 (false): constant surface speed.
    Css(bool),
    /// G80.
    CycleCancel,
    /// G81 … G389.
    Cycle(cycles::CycleKind),
}

fn g_action(code: u32) -> Option<GAction> {
    use GAction::*;
    Some(match code {
        0 => Motion(MotionMode::Rapid),
        10 => Motion(MotionMode::Linear),
        20 => Motion(MotionMode::ArcCw),
        30 => Motion(MotionMode::ArcCcw),
        40 => Dwell,
        170 => Plane(stanok_canon::Plane::XY),
        180 => Plane(stanok_canon::Plane::ZX),
        190 => Plane(stanok_canon::Plane::YZ),
        200 | 700 => Units(LengthUnits::Inches),
        210 | 710 => Units(LengthUnits::Millimetres),
        900 => Distance(DistanceMode::Absolute),
        910 => Distance(DistanceMode::Incremental),
        1900 => ArcCentre(DistanceMode::Absolute),
        1910 => ArcCentre(DistanceMode::Incremental),
        930 => FeedMode(stanok_canon::FeedMode::InverseTime),
        940 => FeedMode(stanok_canon::FeedMode::UnitsPerMinute),
        950 => FeedMode(stanok_canon::FeedMode::UnitsPerRevolution),
        600 => PathMode(true),
        640 => PathMode(false),
        980 => Retract(true),
        990 => Retract(false),
        150 => Polar(false),
        160 => Polar(true),
        400 | 410 | 420 | 1430 | 1440 => Radius(code),
        1100 => Output(true),
        1110 => Output(false),
        430 | 440 | 450 | 490 => LengthComp(code),
        530 => ZeroOffset(None),
        540..=590 if code.is_multiple_of(10) => ZeroOffset(Some((code / 10 - 53) as u8)),
        720 => Mirror(false),
        730 => Mirror(true),
        1720 => Scale(false),
        1730 => Scale(true),
        2720 => Rotate(false),
        2730 => Rotate(true),
        800 => CycleCancel,
        960 => Css(true),
        970 => Css(false),
        1530 => Workpiece(None),
        1540..=1590 if code.is_multiple_of(10) => Workpiece(Some((code / 10 - 153) as u8)),
        1930 | 1940 | 1950 => Shift(code),
        100 => Diameter,
        810 | 830 | 2760 | 2810 | 2820 | 2880 | 2890 | 3870 | 3880 | 3890 => {
            Cycle(cycles::CycleKind::from_code(code)?)
        }
        280 => Home(true),
        290 => Home(false),
        750 => Probe,
        _ => return None,
    })
}

/// Modal group of a G action (for "last one wins").
fn group_key(a: GAction, _code: u32) -> u32 {
    match a {
        GAction::Motion(_) | GAction::Probe => 1,
        GAction::Dwell => 2,
        GAction::Plane(_) => 3,
        GAction::Units(_) => 4,
        GAction::Distance(_) => 5,
        GAction::ArcCentre(_) => 6,
        GAction::FeedMode(_) => 7,
        GAction::PathMode(_) => 8,
        GAction::Retract(_) => 9,
        GAction::Mirror(_) => 10,
        GAction::Scale(_) => 11,
        GAction::Rotate(_) => 12,
        GAction::Shift(_) => 13,
        GAction::ZeroOffset(_) => 14,
        GAction::Workpiece(_) => 15,
        GAction::Diameter => 16,
        GAction::Polar(_) => 17,
        GAction::LengthComp(_) => 18,
        GAction::Home(_) => 1,
        GAction::Radius(_) => 19,
        GAction::Output(_) => 20,
        GAction::CycleCancel | GAction::Cycle(_) => 21,
        GAction::Css(_) => 22,
    }
}

use cutter_comp::Comp;

use mfunc::{m_function, run_m, set_speed, MFunction, MWords};
use motion::{dwell_block, motion};
use mtable::MKind;
use splines::{SplineKind, SplineWords};
use technology::TechWords;

/// `_area`: the part of the language it belongs to (for readers of the code; users are told only
/// that it is not implemented).
fn unsupported(cx: &Ctx<'_>, what: &str, _area: &str, at: ColSpan) -> Diagnostic {
    cx.err(
        "interp::unsupported",
        format!("{what} is not supported yet"),
        at,
    )
    .with_note("not implemented in this version of Stanok")
}

/// Executes one AxiOMA block.
pub fn execute(cx: &mut Ctx<'_>) -> Result<Outcome, Diagnostic> {
    technology::power_on(cx);
    let block_start = cx.out.queue.len();
    let mut words3 = comp3d::Words3::default();
    // Keywords.
    let mut cr: Option<Val> = None;
    let mut tech = TechWords::default();
    let mut sw = SplineWords::default();
    for i in 0..cx.words.keywords.len() {
        let (kw, index, val, span) = cx.words.keywords[i];
        match kw {
            // §3.5: the profile applies from this block on (A25).
            Keyword::Brisk | Keyword::Soft => {
                let soft = kw == Keyword::Soft;
                cx.st.soft_acceleration = soft;
                cx.out.push(Canon::SetAccelerationProfile {
                    profile: if soft {
                        stanok_canon::AccelerationProfile::Soft
                    } else {
                        stanok_canon::AccelerationProfile::Brisk
                    },
                });
            }
            k if TechWords::handles(k) => tech.take(cx, k, index, val, span)?,
            Keyword::Aspline => sw.keyword = Some((SplineKind::Akima, span)),
            Keyword::Cspline => sw.keyword = Some((SplineKind::Cubic, span)),
            Keyword::Bspline => sw.keyword = Some((SplineKind::Nurbs, span)),
            Keyword::Splbreak => {
                comp3d::forbidden(cx, "SPLBREAK", span)?;
                sw.splbreak = true
            }
            Keyword::Pw | Keyword::Pl | Keyword::Sd => {
                let Some(v) = val else {
                    return Err(cx.err("interp::missing-value", "the word has no value", span));
                };
                match kw {
                    Keyword::Pw => sw.weight = Some(v),
                    Keyword::Pl => sw.increment = Some(v),
                    _ => sw.degree = Some(v),
                }
            }
            Keyword::Traori
            | Keyword::TrafOff
            | Keyword::OriEuler
            | Keyword::OriRpy
            | Keyword::OriAxes
            | Keyword::OriVect
            | Keyword::OriWks
            | Keyword::OriMks => {
                comp3d::forbidden(cx, cx.block.slice(span), span)?;
                orientation::keyword(cx, kw, span)?
            }
            Keyword::Cut2df
            | Keyword::Cut3dc
            | Keyword::Cut3dcc
            | Keyword::Cut3dccd
            | Keyword::Cut3df
            | Keyword::Cut3dfs
            | Keyword::Cut3dff => {
                comp3d::mode_word(cx, kw, span)?;
            }
            Keyword::Isd => {
                let Some(v) = val else {
                    return Err(cx.err("interp::missing-value", "ISD= has no value", span));
                };
                words3.isd = Some(v);
            }
            Keyword::Cr => {
                cr = val;
                if cr.is_none() {
                    return Err(cx.err("interp::missing-value", "CR= has no value", span));
                }
            }
            Keyword::Lead | Keyword::Tilt => {
                // The manual names LEAD and TILT but describes them nowhere (spec axioma-4 §1.2).
                return Err(unsupported(cx, cx.block.slice(span), "LEAD/TILT", span));
            }
            _ => {
                return Err(unsupported(
                    cx,
                    cx.block.slice(span),
                    "keywords of other controls",
                    span,
                ))
            }
        }
    }
    // Extended addresses: orientation A2=…C3=, normals A4=…C5=, S2=… (speed of spindle 2), tools
    // and edges of spindles 2…4, Q parameters, the M905 depth.
    let mut indexed_speeds: Vec<(u8, f64)> = Vec::new();
    let mut spindle_tools: Vec<(u8, Val)> = Vec::new();
    let mut spindle_edges: Vec<(u8, Val)> = Vec::new();
    // `Q<i>=`: G110/G111 outputs or cycle parameters; `N1=`/`H1=`: the M905 depth (A15).
    let mut q_words: Vec<(u8, Val)> = Vec::new();
    let mut m905_depth: Option<Val> = None;
    let mut ori_words = orientation::OriWords::default();
    for &(letter, index, val) in &cx.words.indexed {
        if ori_words.take(letter, index, val) || words3.take(letter, index, val) {
            continue;
        }
        match letter {
            b'Q' => q_words.push((index, val)),
            b'N' | b'H'
                if index == 1 && cx.words.m.iter().any(|m| matches!(m.0, 902 | 903 | 905)) =>
            {
                m905_depth = Some(val)
            }
            b'S' if (1..=4).contains(&index) => indexed_speeds.push((index - 1, val.v)),
            // `T2=10`, `D3=2`: tool and edge of spindle 2…4 (spec axioma-2 §3.9–§3.10).
            b'T' if (2..=4).contains(&index) => spindle_tools.push((index - 1, val)),
            b'D' if (2..=4).contains(&index) => spindle_edges.push((index - 1, val)),
            _ => {
                return Err(unsupported(
                    cx,
                    &format!("{}{}=", letter as char, index),
                    "extended addresses",
                    val.span,
                ))
            }
        }
    }

    // G codes: last of a group wins (with a warning), per the manual.
    let mut actions: Vec<(GAction, u32, ColSpan)> = Vec::with_capacity(cx.words.g.len());
    for &(code, span) in &cx.words.g {
        let Some(a) = g_action(code) else {
            return Err(cx.err(
                "axioma::unknown-g-code",
                format!("unknown G function G{}", code as f64 / 10.0),
                span,
            ));
        };
        if let (GAction::Output(_), Some((_, prev, _))) = (
            a,
            actions
                .iter()
                .find(|(b, _, _)| matches!(b, GAction::Output(_))),
        ) {
            return Err(cx.err(
                "axioma::outputs-twice",
                format!(
                    "only one of G110/G111 per block ({} is already programmed)",
                    g_name(*prev)
                ),
                span,
            ));
        }
        let key = group_key(a, code);
        if let Some(pos) = actions
            .iter()
            .position(|(b, c, _)| group_key(*b, *c) == key)
        {
            let prev = actions.remove(pos);
            cx.warnings.push(Diagnostic::warning(
                "axioma::conflicting-words",
                format!(
                    "{} and {} exclude each other: only the last one takes effect",
                    g_name(prev.1),
                    g_name(code)
                ),
                cx.block.span_of(span),
            ));
        }
        actions.push((a, code, span));
    }

    let has_cycle_g = actions
        .iter()
        .any(|(a, _, _)| matches!(a, GAction::Cycle(_)));
    if let (true, Some((_, code, span))) = (
        has_cycle_g,
        actions
            .iter()
            .find(|(a, _, _)| matches!(a, GAction::Motion(_))),
    ) {
        return Err(cx.err(
            "axioma::cycle-and-interpolation",
            format!(
                "{} and a canned cycle in one block: the cycle would be activated and cancelled at once",
                g_name(*code)
            ),
            *span,
        ));
    }
    let comp_active = cx.fe.ext.comp.is_active();

    // 1. Message.
    if let Some(text) = cx.block.message {
        let text = cx.block.slice(text).to_string();
        cx.out.push(Canon::Message { text });
    } else if let Some(text) = cx.fe.message.take() {
        cx.out.push(Canon::Message { text });
    }
    // 2. Modal G codes.
    let mut motion_code: Option<(MotionMode, ColSpan)> = None;
    let mut dwell: Option<ColSpan> = None;
    for &(a, _code, span) in &actions {
        match a {
            GAction::Motion(m) => {
                motion_code = Some((m, span));
                cx.fe.ext.probe.g75 = false;
            }
            GAction::Probe => {
                motion_code = Some((MotionMode::Linear, span));
                cx.fe.ext.probe.g75 = true;
            }
            GAction::Dwell => dwell = Some(span),
            GAction::Plane(_) | GAction::Workpiece(_) | GAction::LengthComp(_)
                if cx.fe.ext.comp3d.in_contour() =>
            {
                return Err(comp3d::forbidden(cx, &g_name(_code), span).unwrap_err());
            }
            GAction::Plane(p) if cx.st.plane != p => {
                if comp_active {
                    return Err(forbidden_under_comp(
                        cx,
                        "a plane change (G17/G18/G19)",
                        span,
                    ));
                }
                cx.out.push(Canon::SelectPlane { plane: p });
                cx.st.plane = p;
                polar::on_plane_change(cx);
            }
            GAction::Units(u) => {
                if cx.st.units != u {
                    cx.out.push(Canon::UseLengthUnits { units: u });
                }
                cx.st.units = u;
            }
            GAction::Distance(d) => cx.st.distance = d,
            GAction::ArcCentre(d) => cx.st.arc_distance = d,
            GAction::FeedMode(f) => {
                if cx.st.feed_mode != f {
                    // Spec axioma-2 §3.3 / A22: a real change of feed type resets F.
                    cx.st.feed = 0.0;
                    cx.st.feed_mode = f;
                    cx.out.push(Canon::SetFeedMode { mode: f });
                }
                if f == FeedMode::UnitsPerRevolution && cx.st.spindle_speed[0] <= 0.0 {
                    return Err(cx.manual(
                        615,
                        "G95 activated while the main spindle speed S is 0",
                        span,
                    ));
                }
            }
            GAction::PathMode(exact) => {
                // §3.4: G60 exact stop / G64 continuous path, carried by the planner.
                cx.st.path_mode = if exact {
                    PathMode::ExactStop
                } else {
                    PathMode::Continuous {
                        blend_tolerance: 0.0,
                    }
                };
                cx.out.push(Canon::SetPathMode {
                    mode: if exact {
                        stanok_canon::PathMode::ExactStop
                    } else {
                        stanok_canon::PathMode::Continuous { tolerance: 0.0 }
                    },
                    naive_cam_tolerance: None,
                });
            }
            GAction::Css(on) => technology::css_mode(cx, on),
            GAction::Retract(initial) => cx.st.retract_to_initial = initial,
            GAction::Radius(code) if cx.fe.ext.comp3d.claims(code) => {
                comp3d::select(cx, code, span)?
            }
            GAction::Radius(code) if cx.fe.ext.comp3d.phase != comp3d::Phase::Off => {
                return Err(comp3d::forbidden(cx, &g_name(code), span)
                    .err()
                    .unwrap_or_else(|| {
                        cx.err(
                            "axioma::cut3d-forbidden",
                            format!("{} while 3D compensation is on", g_name(code)),
                            span,
                        )
                    }));
            }
            GAction::Radius(code) => Comp::select(cx, code, span)?,
            GAction::CycleCancel => cx.fe.ext.cycle.active = None,
            GAction::Cycle(kind) => cycles::activate(cx, kind),
            GAction::ZeroOffset(_)
            | GAction::Workpiece(_)
            | GAction::Shift(1940 | 1950)
            | GAction::Mirror(_)
            | GAction::Scale(_)
            | GAction::Rotate(_)
                if comp_active =>
            {
                return Err(forbidden_under_comp(cx, &g_name(_code), span));
            }
            _ => {}
        }
    }
    // Splines: mode changes and break points (§2.4.1, A16) before anything of this block moves.
    {
        let other_motion = actions.iter().any(|(a, _, _)| {
            matches!(
                a,
                GAction::Motion(_) | GAction::Probe | GAction::Home(_) | GAction::Cycle(_)
            )
        });
        let breaks = !cx.words.m.is_empty()
            || dwell.is_some()
            || actions.iter().any(|(a, _, _)| {
                matches!(
                    a,
                    GAction::ZeroOffset(_)
                        | GAction::Workpiece(_)
                        | GAction::Shift(_)
                        | GAction::Mirror(_)
                        | GAction::Scale(_)
                        | GAction::Rotate(_)
                        | GAction::Polar(_)
                        | GAction::Plane(_)
                )
            })
            || (cx.fe.ext.spline.kind == Some(SplineKind::Nurbs) && cx.words.any(b"TD"));
        splines::before_motion(cx, &sw, other_motion, breaks)?;
    }
    // An interpolation code cancels the cycle (§6.3); Q words go to G110/G111 or the cycle.
    if motion_code.is_some() {
        cx.fe.ext.cycle.active = None;
    }
    let output = actions.iter().find_map(|&(a, _, span)| match a {
        GAction::Output(on) => Some((on, span)),
        _ => None,
    });
    if output.is_none() && !q_words.is_empty() {
        if cx.fe.ext.cycle.active.is_none() {
            let (i, v) = q_words[0];
            return Err(cx
                .err(
                    "axioma::q-without-cycle",
                    format!("Q{i}= has no meaning here: no canned cycle is active"),
                    v.span,
                )
                .with_note(
                    "cycle parameters follow a cycle G code (G81 … G389); outputs need G110/G111",
                ));
        }
        cycles::set_params(cx, &q_words)?;
    }

    // 2b. Frames and offsets, in the manual's fixed order whatever the order of the words. A block
    // that programs mirror, scale, rotation, a shift or G10 takes its X/Y/Z as parameters: no motion.
    let mut parameter_block = false;
    let mut frame_changed = false;
    let frame_functions = actions
        .iter()
        .filter(|(a, _, _)| {
            matches!(
                a,
                GAction::Mirror(true) | GAction::Scale(true) | GAction::Rotate(true)
            )
        })
        .count();
    if frame_functions > 1 {
        let (_, _, span) = actions[actions.len() - 1];
        return Err(cx.err(
            "axioma::frames-in-one-block",
            "G73, G173 and G273 must each be programmed in a block of its own",
            span,
        ));
    }
    for &(a, code, span) in &actions {
        match a {
            GAction::ZeroOffset(s) => frames::zero_offset(cx, s)?,
            GAction::Workpiece(s) => frames::workpiece(cx, s)?,
            GAction::Mirror(on) => frames::mirror(cx, on)?,
            GAction::Scale(on) => frames::scale(cx, on)?,
            GAction::Rotate(on) => frames::rotate(cx, on)?,
            GAction::Shift(code) => frames::shift(cx, code)?,
            GAction::Diameter => {
                frames::diameter_mode(cx, span)?;
                parameter_block = true;
                continue;
            }
            GAction::LengthComp(code) => {
                tools::length_comp(cx, code)?;
                continue;
            }
            GAction::Polar(on) => {
                if on {
                    polar::g16(cx)?;
                    parameter_block = true;
                } else {
                    cx.fe.modes.polar.on = false;
                }
                continue;
            }
            _ => continue,
        }
        frame_changed = true;
        parameter_block |= matches!(
            a,
            GAction::Mirror(true) | GAction::Scale(true) | GAction::Rotate(true)
        ) || matches!(a, GAction::Shift(c) if c != 1930);
        let _ = code;
    }
    if frame_changed {
        frames::apply(cx);
    }
    // 3. F (a constant, an expression or FTABLE(i), §3.1).
    if let Some(f) = cx.words.take(b'F').or(tech.feed) {
        if f.v < 0.0 {
            return Err(cx.err("axioma::negative-feed", "negative feed F", f.span));
        }
        cx.st.feed = match cx.st.feed_mode {
            FeedMode::InverseTime => f.v,
            _ => cx.mm(f.v),
        };
        cx.out.push(Canon::SetFeedRate { feed: cx.st.feed });
    }

    // 4./5. S, T and prefix M functions.
    let table = &cx.fe.params.m_table;
    let mut ms: Vec<(MFunction, ColSpan)> = Vec::with_capacity(cx.words.m.len());
    for &(number, span) in &cx.words.m {
        // §13.2.3: no M function inside a 3D-compensated contour; the program end ends it.
        if !m_function(table, number).is_some_and(|f| {
            matches!(
                f.kind,
                MKind::ProgramEnd | MKind::ProgramEndToWaitingPosition
            )
        }) {
            comp3d::forbidden(cx, &format!("M{number}"), span)?;
        }
        let Some(f) = m_function(table, number) else {
            return Err(cx.err(
                "axioma::unknown-m-function",
                format!(
                    "M{number} is not in the M-function table of this machine (profile `{}`)",
                    table.profile
                ),
                span,
            ));
        };
        ms.push((f, span));
    }
    // Stable sort: same group order keeps the table's group order, then the written order.
    ms.sort_by_key(|(f, _)| f.order);
    let mut mw = MWords::default();
    mw.speed[0] = cx.words.take(b'S').or(tech.speed[0]);
    for &(spindle, v) in &indexed_speeds {
        mw.speed[spindle as usize] = Some(Val {
            v,
            span: cx.whole(),
        });
    }
    for (s, v) in tech.speed.iter().enumerate().skip(1) {
        if v.is_some() {
            mw.speed[s] = *v;
        }
    }
    let t_word = cx.words.take(b'T');
    let tool = match t_word {
        Some(t) => Some(cx.non_negative_integer(t, "tool number T")?),
        None => None,
    };
    if let Some(t) = tool {
        if t > 32767 {
            return Err(cx.err(
                "axioma::tool-number",
                format!("T{t}: tool numbers are 0 … 32767"),
                t_word.map(|v| v.span).unwrap_or_else(|| cx.whole()),
            ));
        }
    }
    mw.tool = tool;
    if let (Some(t), true) = (tool, comp_active) {
        // A5: T0 (with M06) suspends compensation and is allowed; another tool is not.
        if t != 0 {
            let at = t_word.map(|v| v.span).unwrap_or_else(|| cx.whole());
            return Err(forbidden_under_comp(cx, "a T word (new tool radius)", at));
        }
    }
    if let Some(&(_, span)) = cx.words.m.iter().find(|m| m.0 == 905) {
        let depth = m905_depth.map(|v| v.v);
        Comp::set_depth(cx, depth, m905_depth.map(|v| v.span).unwrap_or(span))?;
    } else {
        mw.spindle_param = m905_depth;
    }
    let has_tool_m = ms.iter().any(|(f, _)| f.kind == MKind::ToolChange);
    let d_word = cx.words.take(b'D');
    if let (Some(d), false) = (d_word, has_tool_m) {
        return Err(tools::stray_d(cx, d));
    }
    mw.edge = d_word;
    if let (Some(&(_, v)), false) = (spindle_tools.first().or(spindle_edges.first()), has_tool_m) {
        return Err(cx.err(
            "axioma::spindle-tool-without-change",
            "T<spindle>= and D<spindle>= act only together with M06 or M66",
            v.span,
        ));
    }

    technology::limits(cx, &tech)?;
    // An S whose spindle has no spindle function in this block is stored now (§3.7).
    for spindle in 0..4u8 {
        let with_m = ms.iter().any(|(f, _)| f.spindle() == Some(spindle));
        if let (Some(v), false) = (mw.speed[spindle as usize], with_m) {
            set_speed(cx, spindle, v)?;
            mw.speed_done[spindle as usize] = true;
        }
    }
    if let Some((_, _, span)) = actions
        .iter()
        .find(|(a, _, _)| matches!(a, GAction::Css(true)))
    {
        technology::check_css_speed(cx, *span)?;
    }
    technology::refresh(cx);
    if let (Some(t), false) = (tool, has_tool_m) {
        cx.st.selected_tool = Some(t);
        cx.out.push(Canon::SelectTool { tool: t });
        mw.tool_done = true;
    }
    for (f, span) in ms.iter().filter(|(f, _)| f.timing == AuxTiming::Prefix) {
        run_m(cx, f, &mut mw, *span)?;
    }
    // Tools of spindles 2…4 after the main spindle's change (manual §6.10: "T2 in the first spindle
    // and T3 in the second").
    if has_tool_m {
        tools::other_spindles(cx, &spindle_tools, &spindle_edges)?;
    }

    // Tool length: a changed σ·V is applied by this block's motion, or the next one's.
    tools::update(cx);
    // 6. Dwell or motion.
    let home = actions.iter().find_map(|&(a, _, span)| match a {
        GAction::Home(to) => Some((to, span)),
        _ => None,
    });
    if let Some((on, span)) = output {
        outputs::switch(cx, on, &q_words, span)?;
    }
    if let Some(span) = dwell {
        dwell_block(cx, span)?;
    } else if let (Some((_, span)), true) = (home, comp_active) {
        return Err(forbidden_under_comp(cx, "G28/G29", span));
    } else if cx.fe.ext.cycle.active.is_some() && cx.has_axis_words() && !parameter_block {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
        if cx.st.feed_mode == FeedMode::InverseTime {
            return Err(cx.manual(
                617,
                "G93 (inverse time) is not allowed in canned cycles",
                cx.whole(),
            ));
        }
        cycles::call(cx, cx.whole())?;
    } else if let Some((to_home, span)) = home {
        if to_home {
            home::g28(cx, span)?;
        } else {
            home::g29(cx, span)?;
        }
    } else if parameter_block {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
    } else {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
        let at = motion_code.map(|m| m.1).unwrap_or_else(|| cx.whole());
        let monitored = cx.fe.ext.probe.g75
            || (cx.fe.ext.m.batch_probe
                && cx.st.motion == MotionMode::Linear
                && !cx.fe.modes.polar.on);
        let generalized = orientation::check(cx, &ori_words)?;
        comp3d::before_motion(cx, &words3, generalized)?;
        if generalized {
            orientation::motion(cx, at, &ori_words)?;
        } else if cx.fe.ext.spline.kind.is_some() {
            splines::point(cx, at, &sw)?;
        } else if monitored {
            probe::probe_move(cx, at)?;
        } else {
            motion(cx, at, cr)?;
        }
    }
    cx.check_all_used()?;
    technology::refresh(cx);
    comp3d::after_block(cx, block_start)?;

    // 7. Postfix M functions; program control last.
    let mut outcome = Outcome::Continue;
    for (f, span) in ms.iter().filter(|(f, _)| f.timing == AuxTiming::Postfix) {
        if matches!(
            f.kind,
            MKind::ProgramEnd | MKind::ProgramEndToWaitingPosition
        ) {
            outcome = Outcome::End;
        }
        debug_assert!(!f.is_program_control() || f.timing == AuxTiming::Postfix);
        run_m(cx, f, &mut mw, *span)?;
    }
    for spindle in 0..4u8 {
        if let (Some(v), false) = (mw.speed[spindle as usize], mw.speed_done[spindle as usize]) {
            set_speed(cx, spindle, v)?;
        }
    }
    Comp::end_of_block(cx)?;
    Ok(outcome)
}

/// A word the manual forbids while radius compensation is active (spec axioma-3 §4.4).
fn forbidden_under_comp(cx: &Ctx<'_>, what: &str, at: ColSpan) -> Diagnostic {
    cx.err(
        "axioma::forbidden-under-compensation",
        format!("{what} is not allowed while radius compensation (G41/G42/G143/G144) is active"),
        at,
    )
    .with_note("switch compensation off with G40 (and its exit block) first")
}
