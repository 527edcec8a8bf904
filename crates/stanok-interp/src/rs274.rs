//! RS274/NGC (LinuxCNC) block semantics.
//!
//! A block's G codes are sorted into LinuxCNC's modal groups (spec rs274ngc §2.1) and executed in
//! LinuxCNC's order of execution within a line — the order is part of the contract, the corpus traces
//! depend on it:
//!
//! ```text
//!  1 comment / message (done by the driver)   9 G17–G19            17 G90.1/G91.1
//!  2 G93/G94/G95                              10 G20/G21            18 G98/G99
//!  3 F                                        11 G40–G42            19 G10 (L2, L20)
//!  4 S                                        12 G43/G49            20 motion (G0–G3, G80), G53
//!  5 T                                        13 G54–G59.3          21 M0/M1/M2/M30
//!  6 M6                                       14 G61/G61.1/G64
//!  7 M3/M4/M5, M7/M8/M9, M100–M199           15 G90/G91
//!  8 G4                                       16 (reserved)
//! ```
//!
//! Codes that belong to later capabilities (canned cycles, cutter compensation, G92, G28, probing,
//! splines …) are recognised and rejected with `interp::unsupported`, never silently ignored.
//! The `COMMENT("interpreter: …")` calls LinuxCNC emits on mode changes are reproduced, so that
//! `stanok canon` diffs cleanly against LinuxCNC's own traces.

use crate::arc::{self, ArcError};
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::params::Parameters;
use crate::state::{DistanceMode, MotionMode, PathMode};
use stanok_canon::{Canon, Diagnostic, FeedMode, LengthUnits, Plane, Pose, SpindleDirection};
use stanok_syntax::ColSpan;

/// What the driver does after the block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Go on with the next block.
    Continue,
    /// M2/M30: the program is over.
    End,
}

/// LinuxCNC's modal groups (the ones this module distinguishes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Group {
    NonModal,
    Motion,
    Plane,
    Distance,
    ArcDistance,
    FeedMode,
    Units,
    CutterComp,
    ToolLength,
    Retract,
    CoordSystem,
    PathControl,
    SpindleMode,
    LatheDiameter,
}

/// Group of a G code (×10), or None if LinuxCNC does not know it.
fn group_of(code: u32) -> Option<Group> {
    use Group::*;
    Some(match code {
        40 | 100 | 280 | 281 | 300 | 301 | 520 | 530 | 920 | 921 | 922 | 923 | 53 => NonModal,
        0
        | 10
        | 20
        | 30
        | 50
        | 51
        | 52
        | 330
        | 331
        | 382..=385
        | 700
        | 710
        | 711
        | 712
        | 720
        | 721
        | 722
        | 730
        | 740
        | 760
        | 800..=890 => Motion,
        170 | 180 | 190 | 171 | 181 | 191 => Plane,
        900 | 910 => Distance,
        901 | 911 => ArcDistance,
        930 | 940 | 950 => FeedMode,
        200 | 210 => Units,
        400 | 410 | 420 | 411 | 421 => CutterComp,
        430 | 431 | 432 | 490 => ToolLength,
        980 | 990 => Retract,
        540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => CoordSystem,
        610 | 611 | 640 => PathControl,
        960 | 970 => SpindleMode,
        70 | 80 => LatheDiameter,
        _ => return None,
    })
}

fn g_name(code: u32) -> String {
    if code.is_multiple_of(10) {
        format!("G{}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// Number of groups in [`Group`].
const GROUPS: usize = 14;
/// "No code of this group in the block".
const NO_CODE: u32 = u32::MAX;

/// The G codes of one block, one per group (plain arrays: this runs for every block).
struct GCodes {
    code: [u32; GROUPS],
    span: [ColSpan; GROUPS],
    /// G53 travels with the motion group in LinuxCNC ("G53 may share a line with G0/G1").
    g53: Option<ColSpan>,
}

impl GCodes {
    fn new() -> Self {
        GCodes {
            code: [NO_CODE; GROUPS],
            span: [ColSpan::default(); GROUPS],
            g53: None,
        }
    }

    fn get(&self, g: Group) -> Option<(u32, ColSpan)> {
        let c = self.code[g as usize];
        (c != NO_CODE).then(|| (c, self.span[g as usize]))
    }
}

fn unsupported(cx: &Ctx<'_>, what: &str, issue: &str, at: ColSpan) -> Diagnostic {
    cx.err(
        "interp::unsupported",
        format!("{what} is not supported yet"),
        at,
    )
    .with_note(format!("planned in the issue on {issue}"))
}

fn classify(cx: &Ctx<'_>) -> Result<GCodes, Diagnostic> {
    let mut g = GCodes::new();
    for &(code, span) in &cx.words.g {
        let Some(group) = group_of(code) else {
            return Err(cx.err(
                "rs274::unknown-g-code",
                format!("Unknown g code used: {}", g_name(code)),
                span,
            ));
        };
        if code == 530 {
            g.g53 = Some(span);
            continue;
        }
        let prev = g.code[group as usize];
        if prev != NO_CODE {
            return Err(cx
                .err(
                    "rs274::two-g-codes-same-group",
                    "Two g codes used from same modal group",
                    span,
                )
                .with_note(format!("{} and {}", g_name(prev), g_name(code))));
        }
        g.code[group as usize] = code;
        g.span[group as usize] = span;
    }
    Ok(g)
}

/// M codes by LinuxCNC's modal groups: stopping (4), tool change (6), spindle (7), coolant (8),
/// user-defined (M100–M199). Plain fields with a sentinel: this runs for every block.
struct MCodes {
    stop: u32,
    stop_span: ColSpan,
    tool_change: bool,
    spindle: u32,
    /// Coolant codes in written order (at most four M words per line).
    coolant: [u32; 4],
    n_coolant: usize,
    user: [u32; 4],
    n_user: usize,
}

fn classify_m(cx: &Ctx<'_>) -> Result<MCodes, Diagnostic> {
    let mut m = MCodes {
        stop: NO_CODE,
        stop_span: ColSpan::default(),
        tool_change: false,
        spindle: NO_CODE,
        coolant: [0; 4],
        n_coolant: 0,
        user: [0; 4],
        n_user: 0,
    };
    if cx.words.m.len() > 4 {
        return Err(cx.err(
            "rs274::too-many-m-codes",
            "Too many m codes on line",
            cx.words.m[4].1,
        ));
    }
    for &(code, span) in &cx.words.m {
        let taken = match code {
            0 | 1 | 2 | 30 | 60 => {
                let t = m.stop != NO_CODE;
                m.stop = code;
                m.stop_span = span;
                t
            }
            6 => std::mem::replace(&mut m.tool_change, true),
            3..=5 => std::mem::replace(&mut m.spindle, code) != NO_CODE,
            7..=9 => {
                m.coolant[m.n_coolant] = code;
                m.n_coolant += 1;
                false
            }
            100..=199 => {
                m.user[m.n_user] = code;
                m.n_user += 1;
                false
            }
            19 | 48..=53 | 61..=68 | 70..=73 => {
                return Err(unsupported(
                    cx,
                    &format!("M{code}"),
                    "RS274/NGC completeness",
                    span,
                ))
            }
            _ => {
                return Err(cx.err(
                    "rs274::unknown-m-code",
                    format!("Unknown m code used: M{code}"),
                    span,
                ))
            }
        };
        if taken {
            return Err(cx.err(
                "rs274::two-m-codes-same-group",
                "Two m codes used from same modal group",
                span,
            ));
        }
    }
    Ok(m)
}

/// The document's arc tolerance T (spec rs274ngc §4.3.1): 0.0005 in or 0.005 mm, in mm.
fn arc_tolerance(cx: &Ctx<'_>) -> f64 {
    if let Some(t) = cx.opts.rs274_arc_tolerance_mm {
        return t;
    }
    match cx.st.units {
        LengthUnits::Inches => 0.0005 * 25.4,
        LengthUnits::Millimetres => 0.005,
    }
}

/// Executes one RS274/NGC block (comments already emitted by the driver).
pub fn execute(cx: &mut Ctx<'_>, params: &mut Parameters) -> Result<Outcome, Diagnostic> {
    let g = classify(cx)?;
    let m = classify_m(cx)?;

    // Codes recognised but belonging to later capabilities.
    for (code, span) in [
        g.get(Group::NonModal),
        g.get(Group::Motion),
        g.get(Group::CutterComp),
        g.get(Group::ToolLength),
        g.get(Group::SpindleMode),
        g.get(Group::LatheDiameter),
        g.get(Group::Plane),
    ]
    .into_iter()
    .flatten()
    {
        let issue = match code {
            280 | 281 | 300 | 301 | 520 | 920..=923 => Some("coordinate systems and offsets"),
            100 => None, // G10: L2/L20 here, the rest below
            430..=432 => Some("coordinate systems and offsets (tool length)"),
            410 | 420 | 411 | 421 => Some("RS274/NGC cutter compensation"),
            50 | 51 | 52 | 330 | 331 | 382..=385 | 700..=760 | 810..=890 => {
                Some("RS274/NGC cycles, splines and probing")
            }
            960 => Some("feed and spindle technology"),
            70 => Some("coordinate systems and offsets (lathe diameter mode)"),
            171 | 181 | 191 => Some("RS274/NGC completeness (UVW planes)"),
            _ => None,
        };
        if let Some(issue) = issue {
            return Err(unsupported(cx, &g_name(code), issue, span));
        }
    }

    // 2. Feed mode.
    if let Some((code, _)) = g.get(Group::FeedMode) {
        let (mode, text) = match code {
            930 => (FeedMode::InverseTime, "inverse time"),
            950 => (FeedMode::UnitsPerRevolution, "units per revolution"),
            _ => (FeedMode::UnitsPerMinute, "units per minute"),
        };
        cx.out.push(Canon::Comment {
            text: format!("interpreter: feed mode set to {text}"),
        });
        cx.st.feed_mode = mode;
        cx.out.push(Canon::SetFeedMode { mode });
        if mode != FeedMode::InverseTime {
            cx.st.feed = 0.0;
            cx.out.push(Canon::SetFeedRate { feed: 0.0 });
        }
    }
    // 3. F (per-move in inverse time: see `motion`).
    let f_word = cx.words.take(b'F');
    if let Some(f) = f_word {
        if f.v < 0.0 {
            return Err(cx.err("rs274::negative-f", "Negative F word found", f.span));
        }
        let feed = cx.mm(f.v);
        cx.st.feed = if cx.st.feed_mode == FeedMode::InverseTime {
            f.v
        } else {
            feed
        };
        if cx.st.feed_mode != FeedMode::InverseTime {
            cx.out.push(Canon::SetFeedRate { feed });
        }
    }
    // 4. S.
    if let Some(s) = cx.words.take(b'S') {
        if s.v < 0.0 {
            return Err(cx.err("rs274::negative-s", "Negative spindle speed used", s.span));
        }
        cx.st.spindle_speed[0] = s.v;
        cx.out.push(Canon::SetSpindleSpeed {
            spindle: 0,
            rpm: s.v,
        });
    }
    // 5. T.
    if let Some(t) = cx.words.take(b'T') {
        let tool = cx.non_negative_integer(t, "T word")?;
        cx.st.selected_tool = Some(tool);
        cx.out.push(Canon::SelectTool { tool });
    }
    // 6. M6.
    if m.tool_change {
        let tool = cx.st.selected_tool.unwrap_or(cx.st.current_tool);
        cx.out.push(Canon::StartToolChange);
        cx.out.push(Canon::StopSpindle { spindle: 0 });
        cx.st.spindle_on[0] = false;
        cx.out.push(Canon::ChangeTool { tool });
        cx.st.current_tool = tool;
    }
    // 7. Spindle, coolant, user M codes.
    if m.spindle != NO_CODE {
        let code = m.spindle;
        match code {
            3 | 4 => {
                let direction = if code == 3 {
                    SpindleDirection::Clockwise
                } else {
                    SpindleDirection::CounterClockwise
                };
                cx.st.spindle_on[0] = true;
                cx.out.push(Canon::StartSpindle {
                    spindle: 0,
                    direction,
                });
            }
            _ => {
                cx.st.spindle_on[0] = false;
                cx.out.push(Canon::StopSpindle { spindle: 0 });
            }
        }
    }
    for &code in &m.coolant[..m.n_coolant] {
        match code {
            7 => {
                cx.st.mist = true;
                cx.out.push(Canon::Mist { on: true });
            }
            8 => {
                cx.st.flood = true;
                cx.out.push(Canon::Flood { on: true });
            }
            _ => {
                cx.st.mist = false;
                cx.st.flood = false;
                cx.out.push(Canon::Mist { on: false });
                cx.out.push(Canon::Flood { on: false });
            }
        }
    }
    for &code in &m.user[..m.n_user] {
        cx.out.push(Canon::AuxiliaryFunction {
            number: code,
            timing: stanok_canon::AuxTiming::Prefix,
        });
    }
    // 8. Dwell.
    if let Some((40, span)) = g.get(Group::NonModal) {
        let Some(p) = cx.words.take(b'P') else {
            return Err(cx.err(
                "rs274::dwell-p-missing",
                "Dwell time P word missing with G4",
                span,
            ));
        };
        if p.v < 0.0 {
            return Err(cx.err(
                "rs274::negative-dwell",
                "Negative P word used with G4",
                p.span,
            ));
        }
        cx.out.push(Canon::Dwell { seconds: p.v });
    }
    // 9. Plane.
    if let Some((code, _)) = g.get(Group::Plane) {
        let plane = match code {
            180 => Plane::ZX,
            190 => Plane::YZ,
            _ => Plane::XY,
        };
        cx.st.plane = plane;
        cx.out.push(Canon::SelectPlane { plane });
    }
    // 10. Units.
    if let Some((code, _)) = g.get(Group::Units) {
        let units = if code == 200 {
            LengthUnits::Inches
        } else {
            LengthUnits::Millimetres
        };
        cx.st.units = units;
        cx.out.push(Canon::UseLengthUnits { units });
    }
    // 11. Cutter compensation: only G40 reaches here (G41/G42 rejected above).
    // 12. Tool length: only G49 reaches here.
    if let Some((490, _)) = g.get(Group::ToolLength) {
        cx.st.frame.tlo = Pose::ZERO;
        cx.out
            .push(Canon::UseToolLengthOffset { offset: Pose::ZERO });
    }
    // 13. Coordinate system.
    if let Some((code, _)) = g.get(Group::CoordSystem) {
        let index = match code {
            591 => 7,
            592 => 8,
            593 => 9,
            c => (c / 10 - 53) as u8,
        };
        if index == cx.st.g5x_index {
            cx.out.push(Canon::Comment {
                text: "interpreter: continuing to use same coordinate system".into(),
            });
        } else {
            select_coordinate_system(cx, params, index, true);
        }
    }
    // 14. Path control.
    if let Some((code, _)) = g.get(Group::PathControl) {
        cx.st.path_mode = match code {
            610 => PathMode::ExactPath,
            611 => PathMode::ExactStop,
            _ => {
                let p = cx.words.take(b'P').map(|v| cx.mm(v.v)).unwrap_or(0.0);
                let _naive_cam = cx.words.take(b'Q');
                PathMode::Continuous { blend_tolerance: p }
            }
        };
    }
    // 15. Distance mode.
    if let Some((code, _)) = g.get(Group::Distance) {
        let mode = if code == 900 {
            DistanceMode::Absolute
        } else {
            DistanceMode::Incremental
        };
        if mode != cx.st.distance {
            cx.out.push(Canon::Comment {
                text: format!(
                    "interpreter: distance mode changed to {}",
                    if code == 900 {
                        "absolute"
                    } else {
                        "incremental"
                    }
                ),
            });
            cx.st.distance = mode;
        }
    }
    // 17. Arc distance mode.
    if let Some((code, _)) = g.get(Group::ArcDistance) {
        let mode = if code == 901 {
            DistanceMode::Absolute
        } else {
            DistanceMode::Incremental
        };
        if mode != cx.st.arc_distance {
            cx.out.push(Canon::Comment {
                text: format!(
                    "interpreter: IJK distance mode changed to {}",
                    if code == 901 {
                        "absolute"
                    } else {
                        "incremental"
                    }
                ),
            });
            cx.st.arc_distance = mode;
        }
    }
    // 18. Retract mode.
    if let Some((code, _)) = g.get(Group::Retract) {
        cx.st.retract_to_initial = code == 980;
        cx.out.push(Canon::Comment {
            text: format!(
                "interpreter: retract mode set to {}",
                if code == 980 { "old_z" } else { "r_plane" }
            ),
        });
    }
    // 19. G10.
    let mut axis_words_used_by_modal_0 = false;
    if let Some((100, span)) = g.get(Group::NonModal) {
        if g.get(Group::Motion).is_some() {
            return Err(cx.err(
                "rs274::two-axis-g-codes",
                "Cannot use two g codes that both use axis values",
                span,
            ));
        }
        g10(cx, params, span)?;
        axis_words_used_by_modal_0 = true;
    }
    // 20. Motion.
    let motion = match g.get(Group::Motion) {
        Some((code, span)) => Some((code, span, true)),
        None if cx.has_axis_words() && !axis_words_used_by_modal_0 => {
            let code = match cx.st.motion {
                MotionMode::Rapid => 0,
                MotionMode::Linear => 10,
                MotionMode::ArcCw => 20,
                MotionMode::ArcCcw => 30,
                MotionMode::None => 800,
            };
            Some((code, cx.whole(), false))
        }
        None => None,
    };
    if let Some((code, span, explicit)) = motion {
        motion_block(cx, code, span, explicit, g.g53, f_word.is_some())?;
    } else if let Some(span) = g.g53 {
        return Err(cx.err(
            "rs274::g53-without-motion",
            "Must use g0 or g1 with g53",
            span,
        ));
    }
    // Words nothing consumed: LinuxCNC's "… word with no G code that uses it".
    cx.check_all_used()?;
    // 21. Stops.
    if m.stop != NO_CODE {
        let (code, span) = (m.stop, m.stop_span);
        match code {
            0 => cx.out.push(Canon::ProgramStop { optional: false }),
            1 => cx.out.push(Canon::ProgramStop { optional: true }),
            60 => return Err(unsupported(cx, "M60", "RS274/NGC completeness", span)),
            _ => {
                program_end(cx, params, code == 30);
                return Ok(Outcome::End);
            }
        }
    }
    Ok(Outcome::Continue)
}

fn g5x_from_params(params: &Parameters, index: u8) -> (Pose, f64) {
    let base = 5201 + 20 * index as usize;
    let mut v = [0.0; 9];
    for (k, x) in v.iter_mut().enumerate() {
        *x = params.get(base + k);
    }
    (Pose::from_array(v), params.get(base + 9))
}

/// Makes a G54…G59.3 system active. LinuxCNC re-announces the G92 offset on a G5x selection but
/// not on the reset of a program end.
fn select_coordinate_system(cx: &mut Ctx<'_>, params: &Parameters, index: u8, announce_g92: bool) {
    let (offset, rotation) = g5x_from_params(params, index);
    cx.st.g5x_index = index;
    cx.st.frame.g5x = offset;
    cx.st.frame.rotation_deg = rotation;
    cx.out.push(Canon::SetG5xOffset { index, offset });
    if announce_g92 {
        cx.out.push(Canon::SetG92Offset {
            offset: cx.st.frame.g92,
        });
    }
    cx.out.push(Canon::SetXyRotation { degrees: rotation });
}

/// G10 L2 (origin from values) and L20 (origin so that the current point reads the values).
fn g10(cx: &mut Ctx<'_>, params: &mut Parameters, span: ColSpan) -> Result<(), Diagnostic> {
    let Some(l) = cx.words.take(b'L') else {
        return Err(cx.err(
            "rs274::g10-l-missing",
            "Line with G10 does not have L2, L10, L11, L20 or L1",
            span,
        ));
    };
    let l_num = l.v.round() as i64;
    if l_num != 2 && l_num != 20 {
        return Err(unsupported(
            cx,
            &format!("G10 L{}", l.v),
            "coordinate systems and offsets",
            l.span,
        ));
    }
    let Some(p) = cx.words.take(b'P') else {
        return Err(cx.err("rs274::g10-p-missing", "P word missing with G10", span));
    };
    let p_num = p.v.round();
    if (p.v - p_num).abs() > 1e-6 || !(0.0..=9.0).contains(&p_num) {
        return Err(cx.err(
            "rs274::g10-p-range",
            "P value out of range with G10 L2",
            p.span,
        ));
    }
    let index = if p_num == 0.0 {
        cx.st.g5x_index.max(1)
    } else {
        p_num as u8
    };
    let (mut offset, mut rotation) = g5x_from_params(params, index);
    let mut o = offset.to_array();
    let r_word = cx.words.take(b'R');
    if l_num == 2 {
        for (k, &letter) in AXIS_WORDS.iter().enumerate() {
            if let Some(v) = cx.words.take(letter) {
                o[k] = if crate::ctx::is_linear(k) {
                    cx.mm(v.v)
                } else {
                    v.v
                };
            }
        }
        if let Some(r) = r_word {
            rotation = r.v;
        }
    } else {
        // L20: choose the origin so that the current machine point has the given program values.
        if let Some(r) = r_word {
            rotation = r.v;
        }
        let mut frame = cx.st.frame;
        frame.g5x = offset;
        frame.rotation_deg = rotation;
        let mut want = frame.to_program(&cx.st.position).to_array();
        let mut given = [false; 9];
        for (k, &letter) in AXIS_WORDS.iter().enumerate() {
            if let Some(v) = cx.words.take(letter) {
                want[k] = if crate::ctx::is_linear(k) {
                    cx.mm(v.v)
                } else {
                    v.v
                };
                given[k] = true;
            }
        }
        frame.g5x = Pose::ZERO;
        let zero_origin = frame.to_machine(&Pose::from_array(want)).to_array();
        let m = cx.st.position.to_array();
        for k in 0..9 {
            if given[k] {
                o[k] = m[k] - zero_origin[k];
            }
        }
    }
    offset = Pose::from_array(o);
    let base = 5201 + 20 * index as usize;
    for (k, v) in o.iter().enumerate() {
        params.set(base + k, *v);
    }
    params.set(base + 9, rotation);
    if index == cx.st.g5x_index {
        cx.st.frame.g5x = offset;
        cx.st.frame.rotation_deg = rotation;
        cx.out.push(Canon::SetG5xOffset { index, offset });
        cx.out.push(Canon::SetXyRotation { degrees: rotation });
    } else {
        cx.out.push(Canon::Comment {
            text: "interpreter: setting coordinate system origin".into(),
        });
    }
    Ok(())
}

fn motion_block(
    cx: &mut Ctx<'_>,
    code: u32,
    span: ColSpan,
    explicit: bool,
    g53: Option<ColSpan>,
    f_in_block: bool,
) -> Result<(), Diagnostic> {
    match code {
        800 => {
            if explicit {
                cx.st.motion = MotionMode::None;
                cx.out.push(Canon::Comment {
                    text: "interpreter: motion mode set to none".into(),
                });
            }
            if cx.has_axis_words() {
                return Err(cx.err(
                    "rs274::axis-words-with-g80",
                    "Cannot use axis values with g80",
                    span,
                ));
            }
            Ok(())
        }
        0 | 10 => {
            let rapid = code == 0;
            let end = if let Some(g53_span) = g53 {
                if cx.st.distance == DistanceMode::Incremental {
                    return Err(cx.err(
                        "rs274::g53-incremental",
                        "Cannot use g53 incremental",
                        g53_span,
                    ));
                }
                // G53: the words are machine coordinates (tool length offset still applies).
                let mut m = cx.st.position.to_array();
                let tlo = cx.st.frame.tlo.to_array();
                for (k, &letter) in AXIS_WORDS.iter().enumerate() {
                    if let Some(v) = cx.words.take(letter) {
                        let v = if crate::ctx::is_linear(k) {
                            cx.mm(v.v)
                        } else {
                            v.v
                        };
                        m[k] = v + tlo[k];
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
                let a = cx.st.program_position().to_array();
                let b = end.to_array();
                let length = (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt();
                feed_for(cx, f_in_block, span, false, || length)?
            };
            cx.straight(rapid, end, feed);
            Ok(())
        }
        20 | 30 => {
            if let Some(g53_span) = g53 {
                return Err(cx.err(
                    "rs274::g53-with-arc",
                    "Must use g0 or g1 with g53",
                    g53_span,
                ));
            }
            cx.st.motion = if code == 20 {
                MotionMode::ArcCw
            } else {
                MotionMode::ArcCcw
            };
            arc_block(cx, code == 30, span, f_in_block)
        }
        _ => Err(unsupported(
            cx,
            &g_name(code),
            "RS274/NGC cycles, splines and probing",
            span,
        )),
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
            Ok(cx.st.feed)
        }
        FeedMode::UnitsPerRevolution => {
            if cx.st.feed <= 0.0 {
                return Err(cx.err("rs274::zero-feed", "Cannot feed with zero feed rate", span));
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
            let feed = cx.path_feed(length());
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
    let start = cx.st.program_position();
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
        arc::rs274_radius_format(s, e, cx.mm(r.v), ccw, turns, tol)
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
        arc::rs274_centre_format(s, e, centre, turns, tol).map_err(|err| {
            if let ArcError::RadiusMismatch { r1, r2 } = err {
                let k = cx.st.units.mm_per_unit();
                let la = AXIS_WORDS[a] as char;
                let lb = AXIS_WORDS[b] as char;
                return cx
                    .err(
                        "rs274::arc-radius-mismatch",
                        format!(
                            "Radius to end of arc differs from radius to start: start=({la}{:.4},{lb}{:.4}) center=({la}{:.4},{lb}{:.4}) end=({la}{:.4},{lb}{:.4}) r1={:.4} r2={:.4} abs_err={:.4} rel_err={:.4}%",
                            s[0] / k, s[1] / k, centre[0] / k, centre[1] / k, e[0] / k, e[1] / k,
                            r1 / k, r2 / k, (r1 - r2).abs() / k,
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
        })?
    };
    let feed = feed_for(cx, f_in_block, span, true, || {
        helix_length(start, end, plane, planar.centre, ccw, planar.turns)
    })?;
    cx.arc(plane, ccw, end, planar, feed);
    Ok(())
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
        ArcError::NonPositiveRadius => cx.err("rs274::arc-zero-radius", "Zero-radius arc", span),
        ArcError::RadiusMismatch { r1, r2 } => cx.err(
            "rs274::arc-radius-mismatch",
            format!("Radius to end of arc differs from radius to start: r1={r1:.4} r2={r2:.4}"),
            span,
        ),
    }
}

/// Spatial length of an arc in program coordinates (for inverse-time feed).
pub fn helix_length(
    start: Pose,
    end: Pose,
    plane: Plane,
    centre: [f64; 2],
    ccw: bool,
    turns: u32,
) -> f64 {
    let (a, b, n) = plane.axes();
    let s = start.to_array();
    let e = end.to_array();
    let mut c3 = [0.0; 3];
    c3[a] = centre[0];
    c3[b] = centre[1];
    c3[n] = s[n];
    let mut axis = [0.0; 3];
    axis[n] = if ccw { 1.0 } else { -1.0 };
    stanok_geom::Helix {
        start: [s[0], s[1], s[2]],
        end: [e[0], e[1], e[2]],
        centre: c3,
        axis,
        turns,
    }
    .length()
}

/// M2/M30: LinuxCNC's end-of-program resets, in its order.
fn program_end(cx: &mut Ctx<'_>, params: &Parameters, pallet_shuttle: bool) {
    select_coordinate_system(cx, params, 1, false);
    if cx.st.plane != Plane::XY {
        cx.st.plane = Plane::XY;
        cx.out.push(Canon::SelectPlane { plane: Plane::XY });
    }
    cx.st.distance = DistanceMode::Absolute;
    cx.st.feed_mode = FeedMode::UnitsPerMinute;
    cx.out.push(Canon::SetFeedMode {
        mode: FeedMode::UnitsPerMinute,
    });
    cx.st.feed = 0.0;
    cx.out.push(Canon::SetFeedRate { feed: 0.0 });
    cx.st.spindle_on[0] = false;
    cx.out.push(Canon::StopSpindle { spindle: 0 });
    cx.out.push(Canon::SetSpindleMode {
        spindle: 0,
        css_speed: 0.0,
    });
    if cx.st.mist {
        cx.st.mist = false;
        cx.out.push(Canon::Mist { on: false });
    }
    if cx.st.flood {
        cx.st.flood = false;
        cx.out.push(Canon::Flood { on: false });
    }
    cx.st.motion = MotionMode::Linear;
    if pallet_shuttle {
        cx.out.push(Canon::PalletShuttle);
    }
    cx.out.push(Canon::ProgramEnd);
}
