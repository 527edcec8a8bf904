//! Tool tip point control G43.4 (type 1, rotary angles) and G43.5 (type 2, I J K tool vector),
//! G49 cancel (spec mazatrol-tool-tip-control.md §2–§7, §13, §15), inside the whole language:
//! the compatibility tables 12.1/12.2 are checked by `ttpc_table.rs`.
//!
//! # The stream
//!
//! G43.4/G43.5 emits `Canon::SetToolCentrePoint { active: true, tool_offset: L·b }` (L = the
//! length of tool H, b the spindle base vector): from then on positions are the tool tip in the
//! table frame (machine frame at zero rotary positions, plus the G54 work offset; the spec's
//! table frame glued at the selection pose equals it when TTPC is selected at zero rotary
//! positions, as in every oracle — a selection at another pose is not built) and the rotary values.
//!
//! * **Start with motion** (§5.2): the tip goes to X Y Z (G90/G91 on the tip), the rotary axes to
//!   A B C (type 1) or to the solution of I J K (type 2, `FiveAxis::orient`: travel range, least
//!   time, continuity), in the current motion mode.
//! * **Independent start** `G43.4 H1` (§5.1): the tip goes to where the tool-holder face was (the
//!   axes move +L along the tool axis).
//! * **In the mode** (§7): rotary-only / vector-only blocks hold the tip; I J K omitted components
//!   are 0, all omitted keeps the vector; A B C words in type 2 are not executed.
//! * **Programming frame** (§4): the table frame (parameter 0, default) as above, or with
//!   `[kinematics] ttpc_frame = "workpiece"` (parameter 1) the workpiece frame W, which does not
//!   turn with the table: a block's X Y Z are the tip in W at the block's end table pose, turned
//!   into the table frame by p_T = G(r_end)⁻¹·(P + w) − w (and G91 adds to the tip's current W
//!   position). The tip still moves on a straight line relative to the table (§4.2: "linearly
//!   relative to the table"), so F is its speed relative to the workpiece in both frames (§9). The
//!   G43.4/G43.5 block with motion is read in the table frame (the frames coincide at the
//!   selection pose).
//! * **G49** (§6) with motion (P12 bit 6 / F114 bit 1 = 0, the default; `[mazatrol] g49_moves`):
//!   TTPC off, then the axes move −L along the tool axis so the holder face goes to where the tip
//!   was.
//!
//! Alarms: G49 not alone (R-08, `mazatrol::g49-not-alone`); G43.4/G43.5 with another G code
//! other than G90/G91 (R-09 under the AMB-1 compatibility policy, `mazatrol::ttpc-with-other-g-code`);
//! a type-2 vector reversed within a block and a C word while the tool is parallel to the
//! table's C axis: ILLEGAL NUMBER INPUT (`mazatrol::illegal-number-input`); no kinematics
//! (R-10, `mazatrol::option-not-installed`).

use crate::ctx::Ctx;
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_interp_core::{DistanceMode, MotionMode};
use stanok_kin::{FiveAxis, Kinematics};
use stanok_syntax::ColSpan;

/// TTPC mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TtpcMode {
    /// G49.
    #[default]
    Off,
    /// G43.4: rotary angles.
    Type1,
    /// G43.5: tool vector.
    Type2,
}

/// The Mazatrol modal state (Copy: journalled with the block, restored when it fails).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MazatrolState {
    /// TTPC mode.
    pub mode: TtpcMode,
    /// The tool length offset amount L in force, mm.
    pub length: f64,
    /// The last type-2 tool vector (table frame, unit).
    pub vector: Option<[f64; 3]>,
    /// G43/G44 in force (outside TTPC; tlo.rs).
    pub offset: crate::tlo::LengthOffset,
}

const G43_4: u32 = 434;
const G49: u32 = 490;
const G43: u32 = crate::tlo::G43;
const G44: u32 = crate::tlo::G44;

pub(crate) fn kinematics(cx: &Ctx<'_>, at: ColSpan) -> Result<FiveAxis, Diagnostic> {
    cx.opts.five_axis.clone().ok_or_else(|| {
        cx.err(
            "mazatrol::option-not-installed",
            "tool tip point control needs a machine with its 5-axis kinematics",
            at,
        )
        .with_note("choose e.g. --machine millturn-bc or --machine 5axis-ac-table")
    })
}

pub(crate) fn illegal(cx: &Ctx<'_>, why: &str, at: ColSpan) -> Diagnostic {
    cx.err(
        "mazatrol::illegal-number-input",
        format!("ILLEGAL NUMBER INPUT: {why}"),
        at,
    )
}

/// A straight move to `end` (program coordinates) in the current motion mode.
pub(crate) fn move_to(cx: &mut Ctx<'_>, end: Pose, at: ColSpan) -> Result<(), Diagnostic> {
    let rapid = cx.st.motion == MotionMode::Rapid;
    let feed = if rapid { 0.0 } else { cx.st.feed };
    if !rapid && feed <= 0.0 {
        return Err(cx.err("mazatrol::feed-missing", "feed move with F = 0", at));
    }
    cx.straight(rapid, end, feed);
    Ok(())
}

/// The tool length amount of offset number H (the tool's first edge, L1 + wear).
fn length_of(cx: &Ctx<'_>, h: stanok_interp_core::Val) -> Result<f64, Diagnostic> {
    let n = cx.non_negative_integer(h, "tool length offset number H")?;
    Ok(crate::tlo::tool_length(cx, n))
}

/// The I J K of a type-2 block, normalised; None when all are omitted.
fn vector_words(cx: &mut Ctx<'_>) -> Result<Option<[f64; 3]>, Diagnostic> {
    let ijk = [b'I', b'J', b'K'].map(|l| cx.words.take(l));
    if ijk.iter().all(Option::is_none) {
        return Ok(None);
    }
    let at = ijk
        .iter()
        .flatten()
        .next()
        .map(|v| v.span)
        .unwrap_or_else(|| cx.whole());
    let v = ijk.map(|w| w.map_or(0.0, |w| w.v));
    stanok_kin::orientation::normalised(v)
        .map(|t| Some(t.into()))
        .ok_or_else(|| illegal(cx, "the tool vector I J K is zero", at))
}

/// G43.4 / G43.5 (§5).
fn start(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let base = kinematics(cx, span)?;
    cx.fe.modes.length = match cx.words.take(b'H') {
        Some(h) => length_of(cx, h)?,
        None => crate::tlo::length_without_h(cx),
    };
    let direct = crate::tlo::leave_for_ttpc(cx, code, span)?;
    let b = base.base();
    let c0 = b.map(|x| x * cx.fe.modes.length);
    let kin = base.clone().with_tool_offset(c0);
    let was_on = cx.fe.modes.mode != TtpcMode::Off;
    let joints = if was_on {
        kinematics(cx, span)?
            .with_tool_offset(cx.fe.modes.length_vector(&b))
            .inverse(&cx.st.position)
            .unwrap_or(cx.st.position.to_array())
    } else {
        cx.st.position.to_array()
    };
    let tip = kin
        .forward(&joints)
        .map_err(|e| illegal(cx, &e.to_string(), span))?;
    cx.out.push(Canon::SetToolCentrePoint {
        active: true,
        tool_offset: c0,
    });
    cx.st.position = tip;
    cx.fe.modes.mode = if code == G43_4 {
        TtpcMode::Type1
    } else {
        TtpcMode::Type2
    };
    cx.fe.modes.vector = Some(kin.tool_vector(&tip));
    let has_motion = cx.has_axis_words() || cx.words.any(b"IJK");
    if has_motion {
        ttpc_motion(cx, span)
    } else if direct {
        // §11.1: a direct switch on its own moves no axis (the control point changes).
        Ok(())
    } else {
        // Independent start (§5.1): the tip goes where the holder face was.
        let holder = base
            .forward(&joints)
            .map_err(|e| illegal(cx, &e.to_string(), span))?;
        let end = cx.st.frame.to_program(&holder);
        move_to(cx, end, span)
    }
}

impl MazatrolState {
    fn length_vector(&self, base: &[f64; 3]) -> [f64; 3] {
        base.map(|x| x * self.length)
    }
}

/// A block in TTPC mode (§7): type 1 rotary words, type 2 vector, the tip to X Y Z.
pub(crate) fn ttpc_motion(cx: &mut Ctx<'_>, at: ColSpan) -> Result<(), Diagnostic> {
    let base = kinematics(cx, at)?;
    if let MotionMode::ArcCw | MotionMode::ArcCcw = cx.st.motion {
        let ccw = cx.st.motion == MotionMode::ArcCcw;
        return crate::ttpc_arc::arc(cx, &base, ccw, at);
    }
    let kin = base
        .clone()
        .with_tool_offset(cx.fe.modes.length_vector(&base.base()));
    let t_now = kin.tool_vector(&cx.st.position);
    // rotary words are not executed in type 2 (read and dropped).
    let type2 = cx.fe.modes.mode == TtpcMode::Type2;
    let new_vector = if type2 {
        for l in [b'A', b'B', b'C'] {
            if let Some(w) = cx.words.take(l) {
                // AMB-9: no alarm in the source; a warning says the word did nothing.
                cx.warnings.push(Diagnostic::warning(
                    "mazatrol::rotary-word-ignored",
                    format!(
                        "{} is not executed under G43.5 (the tool vector I J K sets the orientation)",
                        l as char
                    ),
                    cx.block.span_of(w.span),
                ));
            }
        }
        vector_words(cx)?
    } else {
        None
    };
    // a C word (a table axis) while the tool is parallel to that axis.
    if !type2 {
        for axis in base
            .rotary_axes()
            .filter(|a| a.carrier == stanok_kin::Carrier::Table)
        {
            let letter = axis.name.to_ascii_uppercase() as u8;
            let Some(w) = cx.words.peek(letter) else {
                continue;
            };
            let d = stanok_kin::orientation::normalised(axis.direction).unwrap_or_default();
            let cross = [
                t_now[1] * d[2] - t_now[2] * d[1],
                t_now[2] * d[0] - t_now[0] * d[2],
                t_now[0] * d[1] - t_now[1] * d[0],
            ];
            let parallel = cross.iter().map(|x| x * x).sum::<f64>().sqrt() < 1e-9;
            let slot = axis.slot();
            let moves = match cx.st.distance {
                DistanceMode::Absolute => w.v != cx.st.position.to_array()[slot],
                DistanceMode::Incremental => w.v != 0.0,
            };
            if parallel && moves {
                return Err(illegal(
                    cx,
                    &format!(
                        "{} commanded while the tool axis is parallel to it",
                        axis.name
                    ),
                    w.span,
                ));
            }
        }
    }
    // Workpiece frame (§4.2): the words are the tip in the non-turning frame W; G91 adds to the
    // tip's current W position, which is G(r_now)·(its table-frame position).
    let workpiece = cx.fe.ttpc_workpiece_frame;
    let (mut end, _) = if workpiece {
        let table = cx.st.position;
        let in_w = base.table_at(&table, table.xyz());
        cx.st.position = table.with_xyz(in_w);
        let r = cx.end_point();
        cx.st.position = table;
        r?
    } else {
        cx.end_point()?
    };
    if type2 {
        // the rotary axes stay where they are unless the vector moves them.
        let now = cx.st.program_position().to_array();
        let mut e = end.to_array();
        e[3..6].copy_from_slice(&now[3..6]);
        end = Pose::from_array(e);
    }
    if let Some(t) = new_vector {
        // the direction must not reverse within the block.
        let dot = t[0] * t_now[0] + t[1] * t_now[1] + t[2] * t_now[2];
        if dot < -1.0 + 1e-9 {
            return Err(illegal(cx, "the tool direction would reverse", at));
        }
        let oriented = kin.orient(t, &cx.st.position).map_err(|e| {
            cx.err(
                "mazatrol::unreachable-orientation",
                format!("the tool vector cannot be reached: {e}"),
                at,
            )
        })?;
        let mut e = end.to_array();
        e[3..6].copy_from_slice(&oriented.to_array()[3..6]);
        end = Pose::from_array(e);
        cx.fe.modes.vector = Some(t);
    }
    if workpiece {
        // §4.3 with r_ref = the selection pose (zero rotary positions, module doc):
        // p_T_end = G(r_end)⁻¹·(P + w) − w, the frame adding and removing w.
        let m = cx.st.frame.to_machine(&end);
        let home = m.with_xyz(base.table_home(&m, m.xyz()));
        end = cx.st.frame.to_program(&home);
    }
    move_to(cx, end, at)
}

/// G49 (§6): TTPC off, then the holder face goes where the tip was (cancel with motion).
fn cancel(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.fe.modes.mode == TtpcMode::Off {
        return Ok(());
    }
    let moves = cx.fe.params.g49_moves;
    let base = kinematics(cx, span)?;
    let kin = base
        .clone()
        .with_tool_offset(cx.fe.modes.length_vector(&base.base()));
    let tip = cx.st.position;
    let joints = kin
        .inverse(&tip)
        .map_err(|e| illegal(cx, &e.to_string(), span))?;
    let holder_at_tip = base
        .inverse(&tip)
        .map_err(|e| illegal(cx, &e.to_string(), span))?;
    cx.out.push(Canon::SetToolCentrePoint {
        active: false,
        tool_offset: [0.0; 3],
    });
    cx.st.position = Pose::from_array(joints);
    *cx.fe.modes = MazatrolState::default();
    if !moves {
        // P12 bit 6 / F114 bit 1 = 1: the cancel moves no axis.
        return Ok(());
    }
    let end = cx.st.frame.to_program(&Pose::from_array(holder_at_tip));
    move_to(cx, end, span)
}

/// M02/M30 (and a reset) cancel TTPC without motion (R-11, `docs` §3.4).
pub(crate) fn reset(cx: &mut Ctx<'_>) {
    if cx.fe.modes.mode == TtpcMode::Off {
        return;
    }
    let Some(base) = cx.opts.five_axis.clone() else {
        return;
    };
    let kin = base
        .clone()
        .with_tool_offset(cx.fe.modes.length_vector(&base.base()));
    if let Ok(joints) = kin.inverse(&cx.st.position) {
        cx.st.position = Pose::from_array(joints);
    }
    cx.out.push(Canon::SetToolCentrePoint {
        active: false,
        tool_offset: [0.0; 3],
    });
    *cx.fe.modes = MazatrolState::default();
}

/// Group 08 of a block: G43 / G44 / G49 / G43.4 / G43.5 (S §5, §6, §11).
pub(crate) fn length_group(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    match code {
        G49 => {
            if cx.fe.modes.offset != crate::tlo::LengthOffset::Off {
                crate::tlo::cancel_length_offset(cx, span)
            } else {
                cancel(cx, span)
            }
        }
        G43 | G44 => crate::tlo::length_offset(cx, code, span),
        _ => start(cx, code, span),
    }
}
