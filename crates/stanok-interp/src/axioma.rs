//! AxiOMA Control block semantics (spec axioma-1 §2, §5, §6, §13, §15, §16 and axioma-2 §2, §3.3, §4).
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
//! and warns. Functions of later capabilities (frames, compensation, cycles, splines, 5-axis …) are
//! recognised and rejected with `interp::unsupported` naming the issue that adds them.

use crate::arc::{self, ArcError};
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::rs274::Outcome;
use crate::state::{DistanceMode, MotionMode, PathMode};
use crate::words::Val;
use stanok_canon::{AuxTiming, Canon, Diagnostic, FeedMode, LengthUnits, Plane, SpindleDirection};
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
    /// A cancel/default code of a group whose active form is a later capability: accepted, no effect.
    Default(&'static str),
    /// Known, not yet implemented: the issue that adds it.
    Later(&'static str),
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
        150 => Default("Plane2_polar"),
        400 => Default("EqCorrect"),
        490 => Default("ToolLengthCorrect"),
        530 => Default("ZeroShift"),
        720 => Default("Frame_Mirror"),
        1720 => Default("Frame_Scale"),
        2720 => Default("Frame_Rot"),
        800 => Default("CannedCycle"),
        970 => Default("Dimension2"),
        1530 => Default("WCSTable"),
        1930 => Default("ProgCoordShift"),
        160 | 100 | 540..=590 | 730 | 1730 | 2730 | 1540..=1590 | 1940 | 1950 | 430 | 440 | 450 => {
            Later("coordinate systems, frames, offsets and tool data")
        }
        410 | 420 | 1430 | 1440 | 1100 | 1110 | 810 | 830 | 2760 | 2810 | 2820 | 2880 | 2890
        | 3870 | 3880 | 3890 => Later("AxiOMA cutter compensation, cycles and PLC outputs"),
        750 | 280 | 290 | 960 => Later("AxiOMA splines, technology, probing and home positions"),
        _ => return None,
    })
}

/// Modal group of a G action (for "last one wins").
fn group_key(a: GAction, code: u32) -> u32 {
    match a {
        GAction::Motion(_) => 1,
        GAction::Dwell => 2,
        GAction::Plane(_) => 3,
        GAction::Units(_) => 4,
        GAction::Distance(_) => 5,
        GAction::ArcCentre(_) => 6,
        GAction::FeedMode(_) => 7,
        GAction::PathMode(_) => 8,
        GAction::Retract(_) => 9,
        GAction::Default(_) | GAction::Later(_) => 1000 + code,
    }
}

/// One M function: its table 2.2 group order, prefix/postfix timing and what it does.
#[derive(Debug, Clone, Copy, PartialEq)]
enum MAction {
    Stop {
        optional: bool,
    },
    End,
    EndToWaitingPosition,
    Spindle {
        spindle: u8,
        on: Option<SpindleDirection>,
        coolant: bool,
    },
    Coolant(u32),
    ToolChange,
    Aux,
}

struct MFunction {
    number: u32,
    /// Execution order within prefix/postfix (spec axioma-2 §4.1: spindle 1, coolant 2, tool 3).
    order: u32,
    timing: AuxTiming,
    action: MAction,
}

fn m_function(number: u32) -> Option<MFunction> {
    use AuxTiming::{Postfix, Prefix};
    let (order, timing, action) = match number {
        0 => (99, Postfix, MAction::Stop { optional: false }),
        1 => (99, Postfix, MAction::Stop { optional: true }),
        2 | 30 => (99, Postfix, MAction::End),
        99 => (99, Postfix, MAction::EndToWaitingPosition),
        999 => (99, Postfix, MAction::Aux),
        n if matches!(n % 100, 3 | 4 | 5 | 13 | 14 | 19 | 70) && n < 500 && n / 100 != 1 => {
            let spindle = (n / 100).saturating_sub(1) as u8;
            let order = 10 + spindle as u32;
            match n % 100 {
                3 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::Clockwise),
                        coolant: false,
                    },
                ),
                4 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::CounterClockwise),
                        coolant: false,
                    },
                ),
                5 => (
                    order,
                    Postfix,
                    MAction::Spindle {
                        spindle,
                        on: None,
                        coolant: false,
                    },
                ),
                13 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::Clockwise),
                        coolant: true,
                    },
                ),
                14 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::CounterClockwise),
                        coolant: true,
                    },
                ),
                _ => (order, Prefix, MAction::Aux),
            }
        }
        7 | 8 => (20, Prefix, MAction::Coolant(number)),
        9 => (20, Postfix, MAction::Coolant(9)),
        6 | 66 => (30, Prefix, MAction::ToolChange),
        902 | 903 => (40, Prefix, MAction::Aux),
        905 => (40, Postfix, MAction::Aux),
        16 | 22 | 51 | 55 | 109 | 110 | 112 | 911 => (50, Postfix, MAction::Aux),
        17 | 21 | 50 | 54 | 108 | 111 | 910 => (50, Prefix, MAction::Aux),
        _ => return None,
    };
    Some(MFunction {
        number,
        order,
        timing,
        action,
    })
}

fn unsupported(cx: &Ctx<'_>, what: &str, issue: &str, at: ColSpan) -> Diagnostic {
    cx.err(
        "interp::unsupported",
        format!("{what} is not supported yet"),
        at,
    )
    .with_note(format!("planned in the issue on {issue}"))
}

/// Executes one AxiOMA block.
pub fn execute(cx: &mut Ctx<'_>) -> Result<Outcome, Diagnostic> {
    // Keywords.
    let mut cr: Option<Val> = None;
    for i in 0..cx.words.keywords.len() {
        let (kw, _index, val, span) = cx.words.keywords[i];
        match kw {
            Keyword::Brisk => cx.st.soft_acceleration = false,
            Keyword::Soft => cx.st.soft_acceleration = true,
            Keyword::TrafOff
            | Keyword::OriEuler
            | Keyword::OriRpy
            | Keyword::OriAxes
            | Keyword::OriVect
            | Keyword::OriWks
            | Keyword::OriMks
            | Keyword::Cut2df => {}
            Keyword::Cr => {
                cr = val;
                if cr.is_none() {
                    return Err(cx.err("interp::missing-value", "CR= has no value", span));
                }
            }
            Keyword::Traori
            | Keyword::Cut3dc
            | Keyword::Cut3dcc
            | Keyword::Cut3dccd
            | Keyword::Cut3df
            | Keyword::Cut3dfs
            | Keyword::Cut3dff
            | Keyword::Lead
            | Keyword::Tilt => {
                return Err(unsupported(
                    cx,
                    cx.block.slice(span),
                    "5-axis kinematics and 3D compensation",
                    span,
                ))
            }
            _ => {
                return Err(unsupported(
                    cx,
                    cx.block.slice(span),
                    "AxiOMA splines, technology, probing and home positions",
                    span,
                ))
            }
        }
    }
    // Extended addresses: S2=… (speed of spindle 2); the others come with later issues.
    let mut indexed_speeds: Vec<(u8, f64)> = Vec::new();
    for &(letter, index, val) in &cx.words.indexed {
        match letter {
            b'S' if (1..=4).contains(&index) => indexed_speeds.push((index - 1, val.v)),
            _ => {
                return Err(unsupported(
                    cx,
                    &format!("{}{}=", letter as char, index),
                    "coordinate systems, frames, offsets and tool data",
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
        if let GAction::Later(issue) = a {
            return Err(unsupported(cx, &g_name(code), issue, span));
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

    // 1. Message.
    if let Some(text) = cx.block.message {
        let text = cx.block.slice(text).to_string();
        cx.out.push(Canon::Message { text });
    }
    // 2. Modal G codes.
    let mut motion_code: Option<(MotionMode, ColSpan)> = None;
    let mut dwell: Option<ColSpan> = None;
    for &(a, _code, span) in &actions {
        match a {
            GAction::Motion(m) => motion_code = Some((m, span)),
            GAction::Dwell => dwell = Some(span),
            GAction::Plane(p) => {
                if cx.st.plane != p {
                    cx.out.push(Canon::SelectPlane { plane: p });
                }
                cx.st.plane = p;
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
                cx.st.path_mode = if exact {
                    PathMode::ExactStop
                } else {
                    PathMode::Continuous {
                        blend_tolerance: 0.0,
                    }
                }
            }
            GAction::Retract(initial) => cx.st.retract_to_initial = initial,
            GAction::Default(_) | GAction::Later(_) => {}
        }
    }
    // 3. F.
    if let Some(f) = cx.words.take(b'F') {
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
    let mut ms: Vec<(MFunction, ColSpan)> = Vec::with_capacity(cx.words.m.len());
    for &(number, span) in &cx.words.m {
        let Some(f) = m_function(number) else {
            return Err(cx.err(
                "axioma::unknown-m-function",
                format!("M{number} is not in the M-function table of this machine"),
                span,
            ));
        };
        ms.push((f, span));
    }
    // Stable sort: same order number keeps written order.
    ms.sort_by_key(|(f, _)| f.order);
    let s_word = cx.words.take(b'S');
    let t_word = cx.words.take(b'T');
    let tool = match t_word {
        Some(t) => Some(cx.non_negative_integer(t, "tool number T")?),
        None => None,
    };
    let has_spindle_m = ms
        .iter()
        .any(|(f, _)| matches!(f.action, MAction::Spindle { spindle: 0, .. }));
    let has_tool_m = ms.iter().any(|(f, _)| f.action == MAction::ToolChange);
    let mut s_done = false;
    let mut t_done = false;
    if let Some(s) = s_word {
        if !has_spindle_m {
            set_speed(cx, 0, s.v)?;
            s_done = true;
        }
    }
    for &(spindle, v) in &indexed_speeds {
        cx.st.spindle_speed[spindle as usize] = v;
        cx.out.push(Canon::SetSpindleSpeed { spindle, rpm: v });
    }
    if let (Some(t), false) = (tool, has_tool_m) {
        cx.st.selected_tool = Some(t);
        cx.out.push(Canon::SelectTool { tool: t });
        t_done = true;
    }
    for (f, _span) in ms.iter().filter(|(f, _)| f.timing == AuxTiming::Prefix) {
        run_m(cx, f, &mut s_done, s_word, &mut t_done, tool)?;
    }

    // 6. Dwell or motion.
    if let Some(span) = dwell {
        dwell_block(cx, span)?;
    } else {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
        motion(
            cx,
            motion_code.map(|m| m.1).unwrap_or_else(|| cx.whole()),
            cr,
        )?;
    }
    cx.check_all_used()?;

    // 7. Postfix M functions; program control last.
    let mut outcome = Outcome::Continue;
    for (f, span) in ms.iter().filter(|(f, _)| f.timing == AuxTiming::Postfix) {
        match f.action {
            MAction::End | MAction::EndToWaitingPosition => {
                if f.action == MAction::EndToWaitingPosition {
                    cx.warnings.push(Diagnostic::warning(
                        "axioma::m99-waiting-position",
                        "M99: the move to the waiting position needs home positions (not supported yet); the program ends where it is",
                        cx.block.span_of(*span),
                    ));
                }
                for spindle in 0..4u8 {
                    if cx.st.spindle_on[spindle as usize] {
                        cx.st.spindle_on[spindle as usize] = false;
                        cx.out.push(Canon::StopSpindle { spindle });
                    }
                }
                if cx.st.mist {
                    cx.st.mist = false;
                    cx.out.push(Canon::Mist { on: false });
                }
                if cx.st.flood {
                    cx.st.flood = false;
                    cx.out.push(Canon::Flood { on: false });
                }
                cx.out.push(Canon::ProgramEnd);
                outcome = Outcome::End;
            }
            MAction::Stop { optional } => cx.out.push(Canon::ProgramStop { optional }),
            _ => run_m(cx, f, &mut s_done, s_word, &mut t_done, tool)?,
        }
    }
    if let (Some(s), false) = (s_word, s_done) {
        set_speed(cx, 0, s.v)?;
    }
    Ok(outcome)
}

fn set_speed(cx: &mut Ctx<'_>, spindle: u8, rpm: f64) -> Result<(), Diagnostic> {
    if rpm < 0.0 {
        return Err(cx.err(
            "axioma::negative-speed",
            "negative spindle speed S",
            cx.whole(),
        ));
    }
    cx.st.spindle_speed[spindle as usize] = rpm;
    cx.out.push(Canon::SetSpindleSpeed { spindle, rpm });
    Ok(())
}

fn run_m(
    cx: &mut Ctx<'_>,
    f: &MFunction,
    s_done: &mut bool,
    s_word: Option<Val>,
    t_done: &mut bool,
    tool: Option<u32>,
) -> Result<(), Diagnostic> {
    match f.action {
        MAction::Spindle {
            spindle,
            on,
            coolant,
        } => {
            if spindle == 0 && !*s_done {
                if let Some(s) = s_word {
                    set_speed(cx, 0, s.v)?;
                }
                *s_done = true;
            }
            if coolant {
                cx.st.flood = true;
                cx.out.push(Canon::Flood { on: true });
            }
            match on {
                Some(direction) => {
                    cx.st.spindle_on[spindle as usize] = true;
                    cx.out.push(Canon::StartSpindle { spindle, direction });
                }
                None => {
                    cx.st.spindle_on[spindle as usize] = false;
                    cx.out.push(Canon::StopSpindle { spindle });
                }
            }
        }
        MAction::Coolant(n) => cx.coolant(n),
        MAction::ToolChange => {
            if !*t_done {
                if let Some(t) = tool {
                    cx.st.selected_tool = Some(t);
                    cx.out.push(Canon::SelectTool { tool: t });
                }
                *t_done = true;
            }
            let t = cx.st.selected_tool.unwrap_or(cx.st.current_tool);
            cx.out.push(Canon::ChangeTool { tool: t });
            cx.st.current_tool = t;
        }
        MAction::Aux => cx.out.push(Canon::AuxiliaryFunction {
            number: f.number,
            timing: f.timing,
        }),
        MAction::Stop { optional } => cx.out.push(Canon::ProgramStop { optional }),
        MAction::End | MAction::EndToWaitingPosition => cx.out.push(Canon::ProgramEnd),
    }
    Ok(())
}

/// G04 X<s> or G04 E<s> (spec axioma-2 §2.6): 0…65 s to the millisecond, 65…65000 s to the second.
fn dwell_block(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
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

fn motion(cx: &mut Ctx<'_>, span: ColSpan, cr: Option<Val>) -> Result<(), Diagnostic> {
    let mode = cx.st.motion;
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
                cx.straight(true, end, 0.0);
            } else {
                let length = {
                    let a = cx.st.program_position().to_array();
                    let b = end.to_array();
                    (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt()
                };
                let feed = feed_check(cx, span, length)?;
                cx.straight(false, end, feed);
            }
            Ok(())
        }
        MotionMode::ArcCw | MotionMode::ArcCcw => {
            arc_move(cx, mode == MotionMode::ArcCcw, span, cr)
        }
    }
}

fn feed_check(cx: &Ctx<'_>, span: ColSpan, length: f64) -> Result<f64, Diagnostic> {
    if cx.st.feed_mode == FeedMode::UnitsPerRevolution && cx.st.spindle_speed[0] <= 0.0 {
        return Err(cx.manual(
            615,
            "G95 feed move while the main spindle speed S is 0",
            span,
        ));
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
        arc::axioma_centre_format(s, e, c, extra_turns, tol)
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
        arc::axioma_radius_format(s, e, cx.mm(rv.v), false, ccw, extra_turns, tol)
    } else if let Some(cv) = cr {
        arc::axioma_radius_format(s, e, cx.mm(cv.v.abs()), cv.v < 0.0, ccw, extra_turns, tol)
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
    let length = crate::rs274::helix_length(start, end, plane, planar.centre, ccw, planar.turns);
    let feed = feed_check(cx, span, length)?;
    cx.arc(plane, ccw, end, planar, feed);
    Ok(())
}
