//! One block of Mazatrol EIA/ISO (`docs/dialects/mazatrol-eia.md` §3.2): its words, the checks,
//! then the block's functions in their order of execution.
//!
//! ```text
//!  assignments (IF … THEN, #i = …) ─▶ macros.rs, done
//!  words: vacant dropped, decimal point type, T-series diameters ─▶ Words
//!  codes: known for the series, simulated, one per modal group; tables 12.1/12.2 (ttpc_table.rs)
//!  G20/G21 … G98/G99 (modes) ─▶ F ─▶ S ─▶ T ─▶ M6, spindle start, coolant on ─▶ length offsets,
//!  compensation, frames, interpolation modes ─▶ one-shot actions ─▶ motion or cycle
//!  ─▶ spindle stop, coolant off, stops, calls, program end ─▶ G66's call
//! ```
//! *Invariant:* nothing of a block happens before all of its checks passed that can be made
//! without moving (a later motion error still undoes the whole block through the transaction).

use crate::codes::{g_def, g_name, Group};
use crate::ctx::Ctx;
use crate::mcodes::{m_code, MHandler, Phase};
use crate::modes::Turning;
use crate::rules::{dimension, scaled};
use crate::TtpcMode;
use stanok_canon::{Canon, Diagnostic, FeedMode, LengthUnits, Plane};
use stanok_interp_core::{DistanceMode, MotionMode, Outcome, Repeated, WordRules};
use stanok_syntax::{Address, ColSpan, Value};

/// A repeated letter is an error, except the second T of `T01 T02 M6` (the tool prepared next).
const WORD_RULES: WordRules = WordRules {
    repeated: Repeated::Refuse("mazatrol::repeated-word"),
    second_word: Some(b'T'),
};

/// The G codes of a block, sorted.
#[derive(Debug, Default)]
pub struct Codes {
    /// Group 01 (motion and cycles).
    pub motion: Option<(u32, ColSpan)>,
    /// Group 00, in written order.
    pub one_shot: Vec<(u32, ColSpan)>,
    /// The modal codes of the other groups, in written order.
    pub modal: Vec<(u32, Group, ColSpan)>,
}

impl Codes {
    /// True if the block has G `code`.
    pub fn has(&self, code: u32) -> bool {
        self.motion.is_some_and(|(c, _)| c == code)
            || self.one_shot.iter().any(|(c, _)| *c == code)
            || self.modal.iter().any(|(c, _, _)| *c == code)
    }

    /// The span of G `code`.
    pub fn span(&self, code: u32) -> Option<ColSpan> {
        self.motion
            .filter(|(c, _)| *c == code)
            .map(|(_, s)| s)
            .or_else(|| {
                self.one_shot
                    .iter()
                    .find(|(c, _)| *c == code)
                    .map(|(_, s)| *s)
            })
            .or_else(|| {
                self.modal
                    .iter()
                    .find(|(c, _, _)| *c == code)
                    .map(|(_, _, s)| *s)
            })
    }

    /// All codes.
    pub fn all(&self) -> impl Iterator<Item = (u32, ColSpan)> + '_ {
        self.motion
            .iter()
            .copied()
            .chain(self.one_shot.iter().copied())
            .chain(self.modal.iter().map(|(c, _, s)| (*c, *s)))
    }
}

/// One block.
pub(crate) fn execute(cx: &mut Ctx<'_>) -> Result<Outcome, Diagnostic> {
    if !cx.block.assignments.is_empty() {
        crate::macros::assignments(cx)?;
        return Ok(Outcome::Continue);
    }
    fill_words(cx)?;
    if cx.fe.prepared.every_block_call {
        return crate::macros::every_block_call(cx);
    }
    let codes = classify(cx)?;
    crate::ttpc_table::check(cx, &codes)?;
    remember_addresses(cx);
    let outcome = run(cx, &codes)?;
    Ok(outcome)
}

/// STEP 2: the words, evaluated (vacant words dropped), with the decimal point type and the
/// T-series diameters applied.
fn fill_words(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    {
        let env = cx.fe.env(cx.st);
        cx.words.fill(cx.block, &env, &WORD_RULES, cx.warnings)?;
    }
    let dwell = cx.words.g.iter().any(|(c, _)| *c == 40);
    let cycle_in_block = cx
        .words
        .g
        .iter()
        .any(|(c, _)| matches!(*c, 730 | 830 | 760 | 870));
    let q_length = !cx.fe.m.t()
        && (cycle_in_block
            || cx
                .fe
                .m
                .cycle
                .is_some_and(|c| matches!(c.code, 730 | 830 | 760 | 870)));
    let decimal = cx.fe.params.decimal_point_type;
    let inch = cx.st.units == LengthUnits::Inches;
    if decimal == 1 {
        for w in &cx.block.words {
            let (Address::Letter(l), Value::Number(v)) = (w.address, w.value) else {
                continue;
            };
            let text = cx.block.slice(w.span);
            let d = dimension(l, dwell, q_length);
            let s = scaled(v, text.get(1..).unwrap_or(""), d, 1, inch);
            if s != v && v != 0.0 {
                cx.words.scale(l, s / v);
            }
        }
    }
    // T-series: X and U are diameters under G123.1 (not in TTPC, which is Cartesian: AMB-12).
    let selects_ttpc = cx.words.g.iter().any(|(c, _)| matches!(*c, 434 | 435));
    if cx.fe.m.t() && !cx.fe.m.x_radius && cx.fe.modes.mode == TtpcMode::Off && !selects_ttpc {
        cx.words.scale(b'X', 0.5);
        cx.words.scale(b'U', 0.5);
    }
    Ok(())
}

/// #4102 … #4120: the addresses of this block, for the next.
fn remember_addresses(cx: &mut Ctx<'_>) {
    let mut a = cx.fe.m.last_address;
    for (i, l) in b"BDFHMNOST".iter().enumerate() {
        let v = match l {
            b'M' => cx.words.m.first().map(|(m, _)| f64::from(*m)),
            b'N' => cx.block.number.map(f64::from),
            _ => cx.words.peek(*l).map(|v| v.v),
        };
        if v.is_some() {
            a[i] = v;
        }
    }
    if a != cx.fe.m.last_address {
        cx.fe.m.last_address = a;
    }
}

/// Sorts the G codes: known on the series, simulated, one per modal group.
pub(crate) fn classify(cx: &Ctx<'_>) -> Result<Codes, Diagnostic> {
    let series = cx.fe.m.series;
    let ttpc = cx.fe.modes.mode != TtpcMode::Off;
    let mut codes = Codes::default();
    for &(code, span) in &cx.words.g {
        if matches!(code, 434 | 435) {
            codes.modal.push((code, Group::Length, span));
            continue;
        }
        let Some(def) = g_def(series, code) else {
            return Err(cx.err(
                "mazatrol::unknown-code",
                format!(
                    "{} is not a G code of the {} (table {})",
                    g_name(code),
                    series.name(),
                    series.table()
                ),
                span,
            ));
        };
        if !def.simulated {
            // In TTPC the table's alarm comes first when it forbids the code.
            if ttpc {
                crate::ttpc_table::column_one(cx, code, false, span)?;
            }
            return Err(cx.err(
                "mazatrol::not-simulated",
                format!("{} ({}) is not simulated by Stanok", g_name(code), def.name),
                span,
            ));
        }
        match def.group {
            Group::OneShot => codes.one_shot.push((code, span)),
            Group::Motion => {
                if let Some((other, _)) = codes.motion {
                    return Err(conflict(cx, other, code, def.group, span));
                }
                codes.motion = Some((code, span));
            }
            g => {
                if let Some(&(other, _, _)) = codes.modal.iter().find(|(_, og, _)| *og == g) {
                    return Err(conflict(cx, other, code, g, span));
                }
                codes.modal.push((code, g, span));
            }
        }
    }
    Ok(codes)
}

fn conflict(cx: &Ctx<'_>, a: u32, b: u32, g: Group, span: ColSpan) -> Diagnostic {
    cx.err(
        "mazatrol::modal-conflict",
        format!(
            "{} and {} are both {} codes: one per block",
            g_name(a),
            g_name(b),
            g.describe()
        ),
        span,
    )
}

/// The block's functions in order (`docs` §3.2).
fn run(cx: &mut Ctx<'_>, codes: &Codes) -> Result<Outcome, Diagnostic> {
    // G65 / G66 / G66.1: every other word is an argument.
    if let Some(span) = codes.span(650) {
        crate::macros::simple_call(cx, span)?;
        return finish(cx, codes, false);
    }
    for code in [660, 661] {
        if let Some(span) = codes.span(code) {
            crate::macros::modal_call(cx, code, span)?;
            return finish(cx, codes, false);
        }
    }
    // G112: the block's M, S, T are for the other system.
    if let Some(span) = codes.span(1120) {
        crate::spindle::opposite_system(cx, span)?;
        return finish(cx, codes, false);
    }
    // 4. Modes that change how the rest reads.
    for &(code, g, span) in &codes.modal {
        match g {
            Group::Units => units(cx, code, codes, span)?,
            Group::Plane => plane(cx, code),
            Group::Distance => {
                cx.st.distance = if code == 900 {
                    DistanceMode::Absolute
                } else {
                    DistanceMode::Incremental
                }
            }
            Group::Feed => feed_mode(cx, code),
            Group::StrokeCheck => crate::motion::stroke_mode(cx, code)?,
            Group::PathMode => path_mode(cx, code),
            Group::CycleReturn => cx.fe.m.return_initial = code == 980,
            Group::PolarInput => cx.fe.m.polar_input = code == 1220,
            Group::RadiusInput => cx.fe.m.x_radius = code == 1221,
            _ => {}
        }
    }
    // 5. F, S, T.
    if let Some(f) = cx.words.take(b'F') {
        if f.v < 0.0 {
            return Err(cx.err("mazatrol::value-range", "F must not be negative", f.span));
        }
        let threading = codes
            .motion
            .is_some_and(|(c, _)| matches!(c, 320 | 330 | 340 | 780));
        let modal_thread =
            codes.motion.is_none() && matches!(cx.fe.m.motion, 320 | 330 | 340 | 780);
        if !threading && !modal_thread && !is_cycle_t(cx, codes) {
            cx.st.feed = cx.mm(f.v);
            cx.out.push(Canon::SetFeedRate { feed: cx.st.feed });
        } else {
            // The lead of a thread, mm per revolution: kept for the motion.
            cx.fe.m.lead = cx.mm(f.v);
        }
    }
    crate::spindle::speed(cx, codes)?;
    let m6 = cx
        .words
        .m
        .iter()
        .find(|(m, _)| m_code(*m).is_some_and(|c| c.handler.phase() == Phase::Tool))
        .map(|(_, s)| *s);
    if let Some(span) = m6 {
        crate::tools::tool_change(cx, span)?;
    } else {
        crate::tools::select(cx)?;
    }
    // 6. Spindle start, coolant on, orientation, rigid tapping (before the motion).
    let ms: Vec<(u32, ColSpan)> = cx.words.m.clone();
    check_m_codes(cx, &ms)?;
    for &(m, span) in &ms {
        let Some(row) = m_code(m) else { continue };
        match row.handler {
            MHandler::StartSpindle => crate::spindle::start(cx, m, span)?,
            MHandler::CoolantOn => cx.coolant(m),
            MHandler::Orient => crate::spindle::orient(cx, span)?,
            MHandler::RigidTapping => cx.fe.m.rigid = true,
            h => debug_assert_ne!(h.phase(), Phase::BeforeMotion),
        }
    }
    // 7. Offsets, compensation, frames, interpolation modes.
    for &(code, g, span) in &codes.modal {
        match g {
            Group::Compensation => crate::compensate::mode(cx, code, span)?,
            Group::Scaling | Group::Mirror | Group::Rotation | Group::Rotation3d => {
                crate::coords::frame_mode(cx, code, span)?
            }
            Group::WorkSystem => crate::coords::work_system(cx, code, span)?,
            Group::PolarInterpolation => crate::polar_run::polar_mode(cx, code, span)?,
            Group::Cylindrical => crate::polar_run::cylinder_mode(cx, span)?,
            Group::MacroModalCall => crate::macros::modal_call(cx, code, span)?,
            Group::CrossMachining => {
                cx.fe.m.cross = code == 1100;
                crate::spindle::single_system(cx, span);
            }
            Group::Hobbing => {}
            Group::SurfaceSpeed => {}
            _ => {}
        }
    }
    // Group 08: length offsets and tool tip point control (their own block rules, ttpc.rs).
    let length = codes
        .modal
        .iter()
        .find(|(_, g, _)| *g == Group::Length)
        .map(|(c, _, s)| (*c, *s));
    // 8. One-shot actions; 9. the motion. Blocks that set data take their axis words as data.
    let mut moved = false;
    let data_block = codes
        .one_shot
        .iter()
        .any(|(c, _)| matches!(*c, 100 | 520 | 920 | 925) || (*c == 500 && cx.fe.m.t()))
        || codes
            .modal
            .iter()
            .any(|(c, _, _)| matches!(*c, 220 | 510 | 511 | 501 | 680 | 685 | 71));
    let mut handled_motion = data_block;
    for &(code, span) in &codes.one_shot {
        match code {
            40 => crate::motion::dwell(cx, span)?,
            90 => {}
            100 => crate::coords::data_setting(cx, span)?,
            110 => {}
            520 => crate::coords::local(cx)?,
            920 => crate::coords::setting(cx, span)?,
            500 => crate::coords::g50_t(cx, span)?,
            925 => crate::coords::work_rotation(cx, span)?,
            525 | 535 => crate::coords::mazatrol_system(cx, code == 535)?,
            270 | 280 | 290 | 300 | 301 => {
                crate::motion::reference(cx, code, span)?;
                handled_motion = true;
                moved = true;
            }
            530 => {
                crate::motion::machine_move(cx, span)?;
                handled_motion = true;
                moved = true;
            }
            600 => {
                crate::motion::unidirectional(cx, span)?;
                handled_motion = true;
                moved = true;
            }
            310..=313 => {
                crate::motion::skip(cx, span)?;
                handled_motion = true;
                moved = true;
            }
            700..=760 if cx.fe.m.t() => {
                crate::cycles::turning(cx, code, span)?;
                handled_motion = true;
                moved = true;
            }
            1090 => crate::spindle::sequence(cx, span)?,
            450..=480 if !cx.fe.m.t() => {
                crate::tools::position_offset(cx, code, span)?;
                handled_motion = true;
                moved = true;
            }
            _ => {}
        }
    }
    if let Some((code, g)) = codes.motion {
        crate::motion::set_mode(cx, code, g)?;
    }
    if let Some((code, span)) = length {
        crate::ttpc::length_group(cx, code, span)?;
        moved = true;
    } else if !handled_motion {
        moved = crate::motion::block_motion(cx, codes)?;
    }
    let _ = moved;
    finish(cx, codes, moved)
}

/// 10. Spindle stop, coolant off, stops, calls and returns, program end; G66's call.
fn finish(cx: &mut Ctx<'_>, codes: &Codes, moved: bool) -> Result<Outcome, Diagnostic> {
    let mut outcome = Outcome::Continue;
    let ms: Vec<(u32, ColSpan)> = cx.words.m.clone();
    for &(m, span) in &ms {
        let Some(row) = m_code(m) else {
            crate::spindle::machine_m(cx, m, span);
            continue;
        };
        match row.handler {
            MHandler::StopSpindle => crate::spindle::stop(cx, m),
            MHandler::CoolantOff => cx.coolant(m),
            MHandler::Stop { optional: false } => {
                cx.out.push(Canon::ProgramStop { optional: false })
            }
            MHandler::Stop { optional: true } => {
                if cx.opts.optional_stop {
                    cx.out.push(Canon::ProgramStop { optional: true })
                }
            }
            MHandler::End => {
                crate::spindle::program_end(cx);
                cx.out.push(Canon::ProgramEnd);
                outcome = Outcome::End;
            }
            MHandler::Call => crate::macros::subprogram_call(cx, span)?,
            MHandler::Return => crate::macros::subprogram_return(cx, span)?,
            h => debug_assert_ne!(h.phase(), Phase::AfterMotion),
        }
    }
    if moved && cx.fe.m.css.is_some() {
        crate::spindle::refresh_css(cx);
    }
    if moved && cx.fe.m.modal_call.is_some() && !codes.has(660) && !codes.has(661) {
        crate::macros::after_move_call(cx)?;
    }
    cx.check_all_used()?;
    Ok(outcome)
}

/// At most three M codes per block [M].
fn check_m_codes(cx: &Ctx<'_>, ms: &[(u32, ColSpan)]) -> Result<(), Diagnostic> {
    if ms.len() > 3 {
        return Err(cx.err(
            "mazatrol::too-many-m-codes",
            "more than three M codes in one block",
            ms[3].1,
        ));
    }
    Ok(())
}

fn is_cycle_t(cx: &Ctx<'_>, codes: &Codes) -> bool {
    cx.fe.m.t() && codes.one_shot.iter().any(|(c, _)| matches!(c, 760))
}

/// G20 / G21: alone with modal codes only (`docs` §4.2).
fn units(cx: &mut Ctx<'_>, code: u32, codes: &Codes, span: ColSpan) -> Result<(), Diagnostic> {
    let moving = codes.motion.is_some_and(|(c, _)| c != 800);
    if cx.has_axis_words() || moving || !codes.one_shot.is_empty() {
        return Err(cx.err(
            "mazatrol::units-not-alone",
            format!(
                "{} must be in a block without axis words, motion or one-shot codes",
                g_name(code)
            ),
            span,
        ));
    }
    let units = if code == 200 {
        LengthUnits::Inches
    } else {
        LengthUnits::Millimetres
    };
    if cx.st.units != units {
        cx.st.units = units;
        cx.out.push(Canon::UseLengthUnits { units });
    }
    Ok(())
}

fn plane(cx: &mut Ctx<'_>, code: u32) {
    let (plane, zc) = match code {
        170 => (Plane::XY, false),
        180 => (Plane::ZX, false),
        190 => (Plane::YZ, false),
        _ => (Plane::YZ, true),
    };
    cx.fe.m.plane_zc = zc;
    if cx.st.plane != plane {
        cx.st.plane = plane;
        cx.out.push(Canon::SelectPlane { plane });
    }
}

fn feed_mode(cx: &mut Ctx<'_>, code: u32) {
    let mode = match code {
        930 => FeedMode::InverseTime,
        950 => FeedMode::UnitsPerRevolution,
        _ => FeedMode::UnitsPerMinute,
    };
    if cx.st.feed_mode != mode {
        cx.st.feed_mode = mode;
        cx.out.push(Canon::SetFeedMode { mode });
    }
}

fn path_mode(cx: &mut Ctx<'_>, code: u32) {
    use stanok_interp_core::PathMode;
    let was_tapping = cx.fe.m.path == 630;
    cx.fe.m.path = code;
    let mode = match code {
        610 => PathMode::ExactStop,
        611 => PathMode::ExactPath,
        _ => PathMode::Continuous {
            blend_tolerance: 0.0,
        },
    };
    if code == 620 && !cx.fe.once.g62 {
        cx.fe.once.g62 = true;
        cx.warnings.push(Diagnostic::warning(
            "mazatrol::not-modelled",
            "G62 automatic corner override is accepted as a mode; the feed reduction is not modelled",
            cx.block.span(),
        ));
    }
    if code == 630 {
        cx.out
            .push(Canon::SetFeedOverrideEnabled { enabled: false });
        cx.out.push(Canon::SetFeedHoldEnabled { enabled: false });
    } else if was_tapping {
        cx.out.push(Canon::SetFeedOverrideEnabled { enabled: true });
        cx.out.push(Canon::SetFeedHoldEnabled { enabled: true });
    }
    cx.st.path_mode = mode;
    cx.out.push(Canon::SetPathMode {
        mode: to_canon_path(mode),
        naive_cam_tolerance: None,
    });
}

fn to_canon_path(m: stanok_interp_core::PathMode) -> stanok_canon::PathMode {
    match m {
        stanok_interp_core::PathMode::ExactStop => stanok_canon::PathMode::ExactStop,
        stanok_interp_core::PathMode::ExactPath => stanok_canon::PathMode::ExactPath,
        stanok_interp_core::PathMode::Continuous { blend_tolerance } => {
            stanok_canon::PathMode::Continuous {
                tolerance: blend_tolerance,
            }
        }
    }
}

/// The spindle's direction for the cycles' restore.
pub(crate) fn turning_of(m: u32) -> Turning {
    match m {
        3 | 203 => Turning::Cw,
        4 | 204 => Turning::Ccw,
        _ => Turning::Stopped,
    }
}

/// The motion mode of a group-01 code.
pub(crate) fn motion_of(code: u32) -> Option<MotionMode> {
    Some(match code {
        0 => MotionMode::Rapid,
        10 => MotionMode::Linear,
        20 => MotionMode::ArcCw,
        30 => MotionMode::ArcCcw,
        _ => return None,
    })
}
