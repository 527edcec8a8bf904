//! # stanok-rs274: the RS274/NGC (LinuxCNC) front end
//!
//! A block's G codes are sorted into LinuxCNC's modal groups (spec rs274ngc §2.1) and executed in
//! LinuxCNC's order of execution within a line — the order is part of the contract, the corpus traces
//! depend on it:
//!
//! ```text
//!  1 comment / message (front.rs)             9 G17–G19            17 G90.1/G91.1
//!  2 G93/G94/G95                              10 G20/G21            18 G98/G99
//!  3 F                                        10a G7/G8             19 G10, G28, G30, G52, G92 …
//!  4 S                                        11 G40–G42            20 motion (G0–G3, G5.x, G33,
//!  5 T                                        12 G43/G43.1/G43.2/G49    G38.x, G7x, G8x), G53
//!  6 M6                                       13 G54–G59.3          21 M0/M1/M2/M30
//!  7 M3/M4/M5, M7/M8/M9, M100–M199           14 G61/G61.1/G64
//!  8 G4                                       15 G90/G91
//! ```
//!
//! Files: `front.rs` the front end (the driver's contract: lines, control flow, the block
//! transaction's RS274/NGC parts); `motion.rs` G0–G3/G80/G53 and the feed checks; `offsets.rs`
//! the G54…G59.3 table, G10 L2/L20, G92/G52 and program end; `tools.rs` T, M6, tool length
//! offsets and the tool table (G10 L0/L1/L10/L11); `home.rs` G28/G30 and their stored positions;
//! `cycles.rs` G73, G74, G81–G89; `sync.rs` G33, G33.1, G76; `lathe_cycles.rs` (+ `lathe.rs`, the
//! profile call) G70–G72; `probe.rs` G38.2–G38.5; `spline.rs` G5, G5.1, G5.2/G5.3;
//! `cutter_comp.rs` G40/G41/G42/G41.1/G42.1; `mcodes.rs` M19, M48–M53, M61, M62–M66;
//! `modal_context.rs` M70–M73; `params.rs` parameters and expressions; `predefined.rs`
//! LinuxCNC's named read-only parameters; `flow.rs` O-word control flow; `subfiles.rs` subroutine
//! files and the program log; `arc_rules.rs` LinuxCNC's arc tolerance rules.
//!
//! Codes no capability covers yet (the UVW planes, M60) are recognised and rejected with
//! `interp::unsupported`, never silently ignored. The `COMMENT("interpreter: …")` calls LinuxCNC
//! emits on mode changes are reproduced, so that `stanok canon` diffs cleanly against LinuxCNC's
//! own traces.

mod arc_rules;
mod cfmt;
mod checks;
mod codes;
pub(crate) mod cutter_comp;
mod cycles;
mod degrees;
mod flow;
mod front;
mod groups;
mod home;
mod lathe;
pub(crate) mod lathe_cycles;
mod mcodes;
pub(crate) mod modal_context;
mod motion;
mod offsets;
mod params;
mod predefined;
mod probe;
mod spline;
mod subfiles;
mod sync;
mod tools;

/// The core's pieces under the names the front end's files use.
mod ctx {
    pub use stanok_interp_core::ctx::*;
    /// A block's context with the RS274/NGC part.
    pub type Ctx<'a> = stanok_interp_core::Ctx<'a, crate::front::Rs274Part>;
}
use stanok_interp_core::{arc, frame, state};

pub(crate) use flow::FlowAction;
pub use front::{Rs274, Rs274Options, Rs274Part};
pub use params::{normalise_name, Parameters, MAX_PARAMETERS};
pub(crate) use stanok_interp_core::Outcome;

use crate::codes::*;
use crate::ctx::{is_linear, Ctx, AXIS_WORDS};
use crate::state::{DistanceMode, MotionMode, PathMode};
use stanok_canon::{
    Canon, Diagnostic, FeedMode, LengthUnits, Plane, SpindleDirection, SurfaceSpeedLaw,
};

use groups::{classify, g_name, group_of, GCodes, Group, NO_CODE};
use motion::motion_block;
pub use offsets::g5x_from_params;
use offsets::{g10_origin, g92_family, program_end, select_coordinate_system};
use stanok_syntax::ColSpan;

/// RS274/NGC state beyond the shared modal groups (LinuxCNC's `setup` fields of the same names).
#[derive(Debug, Clone, Copy, Default)]
pub struct Rs274State {
    /// A group-1 code beyond G0–G3/G80 in force (`codes.rs`: G5, G38_2, G81 …): axis words
    /// alone repeat it. None = `ModalState::motion` says what is in force.
    pub motion_code: Option<u32>,
    /// Canned cycles: the sticky R (mm, as written: a G91 R stays an increment).
    pub cycle_r: f64,
    /// Canned cycles: the sticky drilling-axis word (mm, as written).
    pub cycle_cc: f64,
    /// Canned cycles: the sticky dwell P, s.
    pub cycle_p: f64,
    /// Canned cycles: the sticky peck Q, mm.
    pub cycle_q: f64,
    /// The units F was last programmed in: LinuxCNC keeps the F number across G20/G21, and
    /// `#<_feed>` reads that number (None: no F yet, the current units).
    pub feed_units: Option<LengthUnits>,
    /// After G5.3 LinuxCNC has no motion mode (-1); cleared by the next motion block.
    pub motion_unset: bool,
    /// G87: the sticky I, J, K (mm, as written): a repeat block may leave them out.
    pub cycle_ijk: [f64; 3],
    /// Canned cycles: the drilling-axis level when the series began (program mm).
    pub cycle_il: f64,
    /// `cycle_il` is set (a series is running).
    pub cycle_il_set: bool,
    /// Sense of the main spindle as last commanded (M3/M4); None before any.
    pub spindle_direction: Option<SpindleDirection>,
    /// G64 Q, mm (LinuxCNC's naive-CAM tolerance; it defaults to P).
    pub naive_cam_tolerance: f64,
    /// M50 P0 / M49 (or a G76) disabled the feed override.
    pub feed_override_disabled: bool,
    /// M51 P0 / M49 disabled the spindle speed override (G84 leaves it off at its end; M2 does
    /// not switch it back on).
    pub speed_override_disabled: bool,
    /// G96 constant surface speed in force.
    pub css: bool,
    /// G96's cutting speed, mm/min (from S when G96 or S was programmed).
    pub css_mm_per_min: f64,
    /// G96's D limit, rev/min (0 = none).
    pub css_max_rpm: f64,
    /// The surface-speed law last sent as `Canon::SetSurfaceSpeedLaw` (see `publish_css_law`).
    pub css_law: Option<SurfaceSpeedLaw>,
    /// The P, Q of the last G5 (mm): a following G5 without I, J continues tangentially.
    pub g5_pq: [f64; 2],
    /// Cutter radius compensation.
    pub comp: cutter_comp::CutterComp,
    /// A G70–G72 profile subroutine is running (its moves are captured, A/C are corners).
    pub in_profile: bool,
    /// The machine stands elsewhere than the interpreter believes: after a G74/G84 in G18/G19
    /// (`cycles::tap_feed`) until the next move.
    pub tap_apart: Option<TapApart>,
}

/// Where a G74/G84 in G18/G19 left the machine (its last feed went to the plane-rotated point)
/// and where the interpreter believes it is (the hole's clear point), machine X Y Z, mm. LinuxCNC
/// moves on from the believed point; but `M6`, `M61` and a probe reread the position from the
/// machine (rs274's stub and milltask alike), and from then on the rotated point is the position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TapApart {
    /// The machine's X Y Z.
    pub machine: [f64; 3],
    /// The interpreter's X Y Z.
    pub believed: [f64; 3],
    /// An M6 or M61 asked for the position to be reread before the next block.
    pub reread: bool,
}

/// Rereads the position from the machine if it stands apart (`TapApart`) and has not moved
/// since: the interpreter takes the machine's X Y Z. A position that no longer is the believed
/// one means a move came between, which brought machine and interpreter together again.
pub(crate) fn reread_position(cx: &mut Ctx<'_>) {
    if let Some(apart) = cx.fe.modes.tap_apart.take() {
        let p = &mut cx.st.position;
        if [p.x, p.y, p.z] == apart.believed {
            [p.x, p.y, p.z] = apart.machine;
        }
    }
}

/// The Canon of a path-control mode (G61/G61.1/G64), as LinuxCNC re-announces it.
pub(crate) fn path_mode_canon(mode: PathMode, naive_cam: f64) -> Canon {
    let mode = match mode {
        PathMode::ExactStop => stanok_canon::PathMode::ExactStop,
        PathMode::ExactPath => stanok_canon::PathMode::ExactPath,
        PathMode::Continuous { blend_tolerance } => stanok_canon::PathMode::Continuous {
            tolerance: blend_tolerance,
        },
    };
    // rs274 prints the naive-CAM tolerance after G64 only (and after a canned cycle, which
    // restores it in any mode: `cycles.rs`).
    let naive_cam_tolerance =
        matches!(mode, stanok_canon::PathMode::Continuous { .. }).then_some(naive_cam);
    Canon::SetPathMode {
        mode,
        naive_cam_tolerance,
    }
}

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

/// Switches the length units. LinuxCNC keeps G64's P and Q as the numbers written, not as
/// lengths: a later re-announcement (a canned cycle's end, M72) sends the same numbers, read in the
/// new units. Stanok holds them in mm, so a change of units rescales them by the units' ratio.
pub(crate) fn set_units(cx: &mut Ctx<'_>, units: LengthUnits) {
    let ratio = units.mm_per_unit() / cx.st.units.mm_per_unit();
    if ratio != 1.0 {
        if let PathMode::Continuous { blend_tolerance } = &mut cx.st.path_mode {
            *blend_tolerance *= ratio;
        }
        cx.fe.modes.naive_cam_tolerance *= ratio;
    }
    cx.st.units = units;
}

/// G93/G94/G95 as LinuxCNC does it: announce, set, and (except for inverse time) reset F to 0.
pub(crate) fn set_feed_mode(cx: &mut Ctx<'_>, mode: FeedMode) {
    let text = match mode {
        FeedMode::InverseTime => "inverse time",
        FeedMode::UnitsPerRevolution => "units per revolution",
        FeedMode::UnitsPerMinute => "units per minute",
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

fn plane_of_code(code: u32) -> Plane {
    match code {
        G18 => Plane::ZX,
        G19 => Plane::YZ,
        _ => Plane::XY,
    }
}

/// The held commands while cutter compensation is on: the last compensated element's motion and
/// everything after it (see `cutter_comp`), counted in motion commands from the back.
pub fn held_motions(st: &Rs274State) -> usize {
    // LinuxCNC queues compensated moves only for a tool radius above 0: with a zero radius
    // nothing can move their ends, and an error later leaves them issued.
    if st.comp.on() && st.comp.last.is_some() && st.comp.radius > 0.0 {
        cutter_comp::held_count(&st.comp)
    } else {
        0
    }
}

/// The arc tolerance T (spec rs274ngc §4.3.1), mm: the option if set, else the document's
/// 0.0005 in / 0.005 mm (the spec's choice, ambiguity 1), or on a machine that asks for it
/// (`rs274_arc_tolerance = "linuxcnc"`, the built-in `linuxcnc` machine) LinuxCNC 2.9's default
/// `CENTER_ARC_RADIUS_TOLERANCE`, 2·0.001·√2 in / 2·0.01·√2 mm. The rule is the same
/// (`arc_rules::centre_format`).
fn arc_tolerance(cx: &Ctx<'_>) -> f64 {
    if let Some(t) = cx.fe.opts.arc_tolerance_mm {
        return t;
    }
    let linuxcnc = cx.fe.opts.linuxcnc_arc_tolerance;
    match cx.st.units {
        LengthUnits::Inches if linuxcnc => 2.0 * 0.001 * std::f64::consts::SQRT_2 * 25.4,
        LengthUnits::Millimetres if linuxcnc => 2.0 * 0.01 * std::f64::consts::SQRT_2,
        LengthUnits::Inches => 0.0005 * 25.4,
        LengthUnits::Millimetres => 0.005,
    }
}

/// How far a radius-format arc's chord may exceed its diameter and the arc still be cut (as a
/// half circle), as `arc_rules::radius_format`'s tolerance (which allows half of it): T, or
/// with LinuxCNC's tolerances its `RADIUS_TOLERANCE`, 0.00005 in in both units.
fn radius_tolerance(cx: &Ctx<'_>) -> f64 {
    match cx.fe.opts.arc_tolerance_mm {
        None if cx.fe.opts.linuxcnc_arc_tolerance => 2.0 * 0.00005 * 25.4,
        _ => arc_tolerance(cx),
    }
}

fn distance_mode(absolute: bool) -> DistanceMode {
    if absolute {
        DistanceMode::Absolute
    } else {
        DistanceMode::Incremental
    }
}

/// LinuxCNC's `COMMENT("interpreter: … mode changed to …")` on a change of G90/G91 or G90.1/G91.1.
pub(crate) fn announce_distance(
    cx: &mut Ctx<'_>,
    what: &str,
    old: DistanceMode,
    new: DistanceMode,
) {
    if old != new {
        let to = match new {
            DistanceMode::Absolute => "absolute",
            DistanceMode::Incremental => "incremental",
        };
        cx.out.push(Canon::Comment {
            text: format!("interpreter: {what} mode changed to {to}"),
        });
    }
}

/// Executes one RS274/NGC block (comments already emitted by the driver).
pub fn execute(cx: &mut Ctx<'_>, params: &mut Parameters) -> Result<Outcome, Diagnostic> {
    if let Some(apart) = cx.fe.modes.tap_apart {
        let p = &cx.st.position;
        if apart.reread {
            reread_position(cx);
        } else if [p.x, p.y, p.z] != apart.believed {
            cx.fe.modes.tap_apart = None;
        }
    }
    let mut g = GCodes::new();
    classify(cx, &mut g)?;
    // Most blocks have no M word: they skip the classification and steps 5a–7 and 21 entirely.
    let m = if cx.words.m.is_empty() {
        None
    } else {
        Some(mcodes::classify_m(cx)?)
    };

    checks::motion_axes(cx, &g)?;
    checks::spindle_selection(cx)?;
    checks::l_word_check(cx, &g)?;

    // Codes recognised but not supported: the UVW planes.
    if let Some((code @ (G17_1 | G18_1 | G19_1), span)) = g.get(Group::Plane, cx) {
        return Err(unsupported(
            cx,
            &g_name(code),
            "RS274/NGC completeness (UVW planes)",
            span,
        ));
    }

    // 2. Feed mode.
    if let Some((code, _)) = g.get(Group::FeedMode, cx) {
        set_feed_mode(
            cx,
            match code {
                G93 => FeedMode::InverseTime,
                G95 => FeedMode::UnitsPerRevolution,
                _ => FeedMode::UnitsPerMinute,
            },
        );
    }
    // 3. F (per-move in inverse time: see `motion`).
    let f_word = cx.words.take(b'F');
    if let Some(f) = f_word {
        if f.v < 0.0 {
            return Err(cx.err("rs274::negative-f", "Negative f word used", f.span));
        }
        let feed = cx.mm(f.v);
        cx.fe.modes.feed_units = Some(cx.st.units);
        cx.st.feed = if cx.st.feed_mode == FeedMode::InverseTime {
            f.v
        } else {
            feed
        };
        if cx.st.feed_mode != FeedMode::InverseTime {
            cx.out.push(Canon::SetFeedRate { feed });
        }
    }
    // 4. Spindle mode (G96/G97), then S.
    if let Some((code, _)) = g.get(Group::SpindleMode, cx) {
        let css = code == G96;
        let max_rpm = if css {
            match cx.words.take(b'D') {
                Some(d) if d.v <= 0.0 => {
                    return Err(cx.err("rs274::g96-d", "D word must be positive with G96", d.span))
                }
                Some(d) => d.v,
                None => 1e30,
            }
        } else {
            0.0
        };
        cx.fe.modes.css = css;
        cx.fe.modes.css_max_rpm = if max_rpm < 1e29 { max_rpm } else { 0.0 };
        cx.fe.modes.css_mm_per_min = css_mm_per_min(cx, cx.st.spindle_speed[0]);
        cx.out.push(Canon::SetSpindleMode {
            spindle: 0,
            constant_surface_speed: css,
            max_rpm,
        });
    }
    if let Some(s) = cx.words.take(b'S') {
        if s.v < 0.0 {
            return Err(cx.err("rs274::negative-s", "Negative spindle speed used", s.span));
        }
        cx.st.spindle_speed[0] = s.v;
        cx.fe.modes.css_mm_per_min = css_mm_per_min(cx, s.v);
        // Under G96 S is a surface speed: Canon carries it in m/min.
        let rpm = if cx.fe.modes.css && cx.st.units == LengthUnits::Inches {
            s.v * 0.3048
        } else {
            s.v
        };
        cx.out.push(Canon::SetSpindleSpeed { spindle: 0, rpm });
    }
    // 5. T.
    if let Some(t) = cx.words.take(b'T') {
        tools::select_tool(cx, params, t)?;
    }
    // 5a–7. The M codes before the dwell (out of line: rare).
    if let Some(m) = &m {
        mcodes::before_dwell(cx, params, m)?;
    }
    // 8. Dwell.
    if let Some((G4, span)) = g.get(Group::NonModal, cx) {
        let Some(p) = cx.words.take(b'P') else {
            return Err(cx.err("rs274::dwell-p-missing", "Dwell time missing with g4", span));
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
    if let Some((code, span)) = g.get(Group::Plane, cx) {
        if cx.fe.modes.comp.on() && cx.st.plane != plane_of_code(code) {
            return Err(cx.err(
                "rs274::comp-plane-change",
                "Cannot change planes with cutter radius compensation on",
                span,
            ));
        }
        let plane = plane_of_code(code);
        cx.st.plane = plane;
        cx.out.push(Canon::SelectPlane { plane });
    }
    // 10. Units.
    if let Some((code, _)) = g.get(Group::Units, cx) {
        let units = if code == G20 {
            LengthUnits::Inches
        } else {
            LengthUnits::Millimetres
        };
        set_units(cx, units);
        cx.out.push(Canon::UseLengthUnits { units });
    }
    // 10a. Lathe diameter mode: from here on every X word of the block is a diameter (LinuxCNC
    // halves X words as it reads them — positions, G92, G10 and G43.1 values alike; arc centres
    // I/K and radii stay radii).
    if let Some((code, _)) = g.get(Group::LatheDiameter, cx) {
        let diameter = code == G7;
        if diameter != cx.st.diameter_mode {
            cx.out.push(Canon::Comment {
                text: format!(
                    "interpreter: Lathe diameter mode changed to {}",
                    if diameter { "diameter" } else { "radius" }
                ),
            });
            cx.st.diameter_mode = diameter;
        }
    }
    if cx.st.diameter_mode {
        cx.words.scale(b'X', 0.5);
    }
    // 11. Cutter compensation.
    if let Some((code, span)) = g.get(Group::CutterComp, cx) {
        if code == G40 {
            cutter_comp::comp_off(cx, span)?;
        } else {
            cutter_comp::comp_on(cx, params, code, span)?;
        }
    }
    // 12. Tool length.
    let mut axis_words_used_by_g43 = false;
    if let Some((code, span)) = g.get(Group::ToolLength, cx) {
        axis_words_used_by_g43 = tools::tool_length_offset(cx, params, code, span)?;
        if axis_words_used_by_g43 {
            if let Some((_, motion_span)) = g.get(Group::Motion, cx) {
                // The document: G43.1 (and G43.2 with axes) and a motion on one line are an error.
                // LinuxCNC 2.9 applies the words to both.
                return Err(cx
                    .err(
                        "rs274::two-axis-g-codes",
                        "Cannot use two g codes that both use axis values",
                        motion_span,
                    )
                    .with_note(format!(
                        "{} takes the axis words as tool offsets: put the motion on its own line",
                        g_name(code)
                    )));
            }
        }
    }
    // 13. Coordinate system.
    if let Some((code, _)) = g.get(Group::CoordSystem, cx) {
        let index = match code {
            G59_1 => 7,
            G59_2 => 8,
            G59_3 => 9,
            c => ((c - G53) / 10) as u8,
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
    if let Some((code, _)) = g.get(Group::PathControl, cx) {
        cx.st.path_mode = match code {
            G61 => PathMode::ExactPath,
            G61_1 => PathMode::ExactStop,
            _ => {
                // A negative P is 0 and a negative Q is P, as LinuxCNC reads them.
                let p = cx.words.take(b'P').map_or(0.0, |v| cx.mm(v.v).max(0.0));
                let q = cx
                    .words
                    .take(b'Q')
                    .map(|v| cx.mm(v.v))
                    .filter(|&q| q >= 0.0)
                    .unwrap_or(p);
                cx.fe.modes.naive_cam_tolerance = q;
                PathMode::Continuous { blend_tolerance: p }
            }
        };
        cx.out.push(path_mode_canon(
            cx.st.path_mode,
            cx.fe.modes.naive_cam_tolerance,
        ));
    }
    // 15. Distance mode; 17. arc (IJK) distance mode. LinuxCNC comments only a real change.
    if let Some((code, _)) = g.get(Group::Distance, cx) {
        let new = distance_mode(code == G90);
        let old = std::mem::replace(&mut cx.st.distance, new);
        announce_distance(cx, "distance", old, new);
    }
    if let Some((code, _)) = g.get(Group::ArcDistance, cx) {
        let new = distance_mode(code == G90_1);
        let old = std::mem::replace(&mut cx.st.arc_distance, new);
        announce_distance(cx, "IJK distance", old, new);
    }
    // 18. Retract mode.
    if let Some((code, _)) = g.get(Group::Retract, cx) {
        cx.st.retract_to_initial = code == G98;
        cx.out.push(Canon::Comment {
            text: format!(
                "interpreter: retract mode set to {}",
                if code == G98 { "old_z" } else { "r_plane" }
            ),
        });
    }
    // 19. Group 0 (G4 ran at 8). G10, G28, G30, G52 and G92 take the axis words for themselves:
    // with them an explicit motion code is an error and the modal motion is suspended.
    let mut axis_words_used_by_modal_0 = axis_words_used_by_g43;
    // Where this block's commands start: a move without compensation (a cycle, a home) makes the
    // programmed point a G40 left behind stale (below).
    let queued = cx.out.queue.len();
    if let Some((code, span)) = g.get(Group::NonModal, cx) {
        if matches!(code, G10 | G28 | G30 | G52 | G92) {
            if g.get(Group::Motion, cx).is_some() {
                return Err(cx.err(
                    "rs274::two-axis-g-codes",
                    "Cannot use two g codes that both use axis values",
                    span,
                ));
            }
            axis_words_used_by_modal_0 = true;
        }
        match g_code(code).map(|c| c.handler) {
            Some(Handler::SetData) => g10(cx, params, span)?,
            Some(Handler::Home) => home::go_home(cx, params, code == G28)?,
            Some(Handler::StoreHome) => home::store_home(cx, params, code == G28_1),
            Some(Handler::Offset) => g92_family(cx, params, code, span)?,
            Some(Handler::NurbsEnd) => spline::nurbs_end(cx, params, span)?,
            _ => {}
        }
    }
    // The G96 law with this block's speed and offsets, before its motion.
    publish_css_law(cx);
    // 20. Motion.
    let motion = match g.get(Group::Motion, cx) {
        Some((code, span)) => Some((code, span, true)),
        // LinuxCNC's enhance_block: a block with centre words and no axis words under modal G2/G3
        // is an arc too (a full circle), as is a block with axis words under any motion mode.
        None if !axis_words_used_by_modal_0
            && (cx.has_axis_words()
                || (matches!(cx.st.motion, MotionMode::ArcCw | MotionMode::ArcCcw)
                    && cx.fe.modes.motion_code.is_none()
                    && (cx.words.has(b'I') || cx.words.has(b'J') || cx.words.has(b'K')))) =>
        {
            let code = match cx.st.motion {
                _ if cx.fe.modes.motion_code.is_some() => cx.fe.modes.motion_code.unwrap_or(G80),
                MotionMode::Rapid => G0,
                MotionMode::Linear => G1,
                MotionMode::ArcCw => G2,
                MotionMode::ArcCcw => G3,
                MotionMode::None => G80,
            };
            Some((code, cx.whole(), false))
        }
        None => None,
    };
    if let Some((code, span, explicit)) = motion {
        motion_block(cx, params, code, span, explicit, g.g53, f_word.is_some())?;
    } else if let Some(span) = g.g53 {
        return Err(cx.err(
            "rs274::g53-without-motion",
            "Must use g0 or g1 with g53",
            span,
        ));
    }
    let comp = cx.fe.modes.comp;
    if !comp.on()
        && comp.program.is_some()
        && cx
            .out
            .queue
            .iter()
            .skip(queued)
            .any(|c| c.value.motion().is_some())
    {
        cx.fe.modes.comp.program = None;
    }
    // Words nothing consumed: LinuxCNC's "… word with no G code that uses it".
    if cx.words.has(b'H') && !cx.words.is_used(b'H') {
        let at = cx.words.take(b'H').map(|v| v.span).unwrap_or_default();
        return Err(cx.err(
            "interp::unused-word",
            "H word with no G43 or G76 to use it",
            at,
        ));
    }
    cx.check_all_used()?;
    // 21. Stops.
    if let Some(m) = m.as_ref().filter(|m| m.stop != NO_CODE) {
        let (code, span) = (m.stop, m.stop_span);
        cutter_comp::flush(cx, span)?;
        match code {
            0 => cx.out.push(Canon::ProgramStop { optional: false }),
            1 => cx.out.push(Canon::ProgramStop { optional: true }),
            // M60: exchange the pallets, then stop as M0 (LinuxCNC's convert_stop).
            60 => {
                cx.out.push(Canon::PalletShuttle);
                cx.out.push(Canon::ProgramStop { optional: false });
            }
            _ => {
                program_end(cx, params, code == 30);
                publish_css_law(cx);
                return Ok(Outcome::End);
            }
        }
    }
    publish_css_law(cx);
    Ok(Outcome::Continue)
}

/// S as a cutting speed, mm/min: S is m/min under G21 and ft/min under G20.
fn css_mm_per_min(cx: &Ctx<'_>, s: f64) -> f64 {
    match cx.st.units {
        LengthUnits::Inches => s * 304.8,
        LengthUnits::Millimetres => s * 1000.0,
    }
}

/// Sends the G96 law the machine evaluates continuously (`Canon::SetSurfaceSpeedLaw`) whenever it
/// changes: at G96/G97, a new S or D, and when the offsets move the work zero of X, which LinuxCNC
/// takes as the spindle centre line (radius = work X). Checked at the end of every block, but only
/// while G96 is (or was just) in force, so that ordinary blocks pay one comparison.
#[inline(always)]
fn publish_css_law(cx: &mut Ctx<'_>) {
    let st = &cx.fe.modes;
    if st.css || st.css_law.is_some() {
        publish_css_law_in_force(cx);
    }
}

#[cold]
fn publish_css_law_in_force(cx: &mut Ctx<'_>) {
    let st = &cx.fe.modes;
    let law = if st.css {
        let mut zero = cx.st.program_position();
        zero.x = 0.0;
        Some(SurfaceSpeedLaw {
            mm_per_min: st.css_mm_per_min,
            axis: 0,
            centre: cx.st.frame.to_machine(&zero).x,
            min_rpm: 0.0,
            max_rpm: st.css_max_rpm,
        })
    } else {
        None
    };
    if law != cx.fe.modes.css_law {
        cx.fe.modes.css_law = law;
        cx.out.push(Canon::SetSurfaceSpeedLaw { spindle: 0, law });
    }
}

/// The block's axis words as values (mm for linear axes, degrees for A B C), marked used; absolute,
/// whatever G90/G91 (the codes that call this take them as values, not as motion).
fn axis_values(cx: &mut Ctx<'_>) -> Result<[Option<f64>; 9], Diagnostic> {
    let mut v = [None; 9];
    for (k, &letter) in AXIS_WORDS.iter().enumerate() {
        if let Some(w) = cx.words.take(letter) {
            if !cx.opts.axes[k] {
                return Err(cx.err(
                    "interp::axis-not-configured",
                    stanok_interp_core::Hooks::axis_not_configured_message(&*cx.fe, letter),
                    w.span,
                ));
            }
            v[k] = Some(if is_linear(k) { cx.mm(w.v) } else { w.v });
        }
    }
    Ok(v)
}

/// G10: dispatch on L (L0/L1/L10/L11 the tool table, L2/L20 the coordinate systems).
fn g10(cx: &mut Ctx<'_>, params: &mut Parameters, span: ColSpan) -> Result<(), Diagnostic> {
    let l = cx.words.take(b'L');
    let l_num = l
        .map(|l| l.v)
        .filter(|v| v.fract() == 0.0)
        .map(|v| v as i64);
    match l_num {
        Some(0) => tools::reload_tool_table(cx),
        Some(l @ (1 | 10 | 11)) => tools::set_tool_entry(cx, params, l as u32, span),
        Some(l @ (2 | 20)) => g10_origin(cx, params, l as u32, span),
        _ => Err(cx.err(
            "rs274::g10-l-invalid",
            "Line with G10 does not have L0, L1, L10, L11, L2, or L20",
            l.map_or(span, |l| l.span),
        )),
    }
}
