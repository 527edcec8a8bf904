//! Mazatrol ordinary tool length offset G43/G44 H…, the tool change `T01 T02 M6`, and the
//! switching rules between G43/G44 and tool tip point control (spec mazatrol-tool-tip-control.md
//! §3, §10, §11).
//!
//! * **G43/G44** put the offset along the machine Z: the control point is the *virtual* tool
//!   tip at B = 0, `m − L·ẑ` (§11.2), whatever the head angle. As in the RS274 front end the
//!   offset goes into the work frame (`tlo = (0, 0, ±L)`) and `Canon::UseToolLengthOffset` is
//!   emitted. Selected from G49 without axis words, the axes move +L along Z so that the program
//!   position stays (the counterpart of G49 with motion, F114 bit 1 = 0).
//! * **L** (§10, one tool table in Stanok: TOOL OFFSET and TOOL DATA are the same): with H, the
//!   length of tool H; without H, the length in force (G43/G44/TTPC), else the length of the
//!   tool in the spindle (F93 bit 3 = 1: the ATC gave it), else 0.
//! * **`T01 T02 M6`** changes to tool 01 (02 is prepared) and, as with F93 bit 3 = 1 (the
//!   setting of the §3-3 examples), activates G43 with the new tool's length, moving no axis.
//! * **Direct switching** G43/G44 ↔ G43.4/G43.5 is the M-series rule (§11.1): with axis words the
//!   new control point goes to the programmed position, without them no axis moves. On the
//!   T-series (a mill-turn, its X a diameter) the source is silent (AMB-13): G43/G44 in TTPC is
//!   refused (`mazatrol::code-not-allowed-in-ttpc`) and G43.4/G43.5 in G43/G44
//!   (`mazatrol::ttpc-not-selectable`): go through G49.

use crate::ctx::Ctx;
use crate::{MazatrolState, TtpcMode};
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_kin::Kinematics;
use stanok_syntax::ColSpan;

/// The ordinary length offset in force (group 8 besides TTPC).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LengthOffset {
    /// G49 (or TTPC, which carries its own length).
    #[default]
    Off,
    /// G43: +L along Z.
    Plus,
    /// G44: −L along Z.
    Minus,
}

pub(crate) const G43: u32 = 430;
pub(crate) const G44: u32 = 440;

/// The length of tool `n` (first edge, L1 + wear); 0 for an unknown tool.
pub(crate) fn tool_length(cx: &Ctx<'_>, n: u32) -> f64 {
    cx.opts
        .control
        .tools
        .get(n)
        .and_then(|t| t.edges.first())
        .map_or(0.0, |e| e.length[0] + e.length_wear[0])
}

/// L without an H word (module doc).
pub(crate) fn length_without_h(cx: &Ctx<'_>) -> f64 {
    let m = cx.fe.modes;
    if m.mode != TtpcMode::Off || m.offset != LengthOffset::Off {
        m.length
    } else {
        tool_length(cx, cx.st.current_tool)
    }
}

/// True on a T-series control: the machine is a mill-turn (X a diameter on the C spindle).
pub(crate) fn t_series(cx: &Ctx<'_>) -> bool {
    cx.opts
        .five_axis
        .as_ref()
        .is_some_and(|k| k.x_is_diameter())
}

fn set_tlo(cx: &mut Ctx<'_>, z: f64) {
    let offset = Pose { z, ..Pose::ZERO };
    cx.st.frame.set_tlo(offset);
    cx.out.push(Canon::UseToolLengthOffset { offset });
}

/// `T… [T…] M6`: the tool change; the new tool's length is put in force as G43 (F93 bit 3 = 1).
pub(crate) fn tool_change(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.fe.modes.mode != TtpcMode::Off {
        return Err(cx.err(
            "mazatrol::code-not-allowed-in-ttpc",
            "M06 (tool change) is not allowed in tool tip point control: cancel it with G49 first",
            span,
        ));
    }
    let tool = match cx.words.take(b'T') {
        Some(t) => cx.non_negative_integer(t, "tool number T")?,
        None => cx.st.selected_tool.unwrap_or(cx.st.current_tool),
    };
    cx.out.push(Canon::StartToolChange);
    cx.out.push(Canon::ChangeTool { tool, slot: tool });
    cx.st.current_tool = tool;
    cx.st.selected_tool = None;
    if let Some(next) = cx.words.second.take() {
        let next = cx.non_negative_integer(next, "next tool number T")?;
        cx.out.push(Canon::SelectTool { tool: next });
        cx.st.selected_tool = Some(next);
    }
    let length = tool_length(cx, tool);
    cx.fe.modes.length = length;
    cx.fe.modes.offset = LengthOffset::Plus;
    set_tlo(cx, length);
    Ok(())
}

/// A T word without M6: the tool is prepared.
pub(crate) fn select_tool(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    if let Some(t) = cx.words.take(b'T') {
        let tool = cx.non_negative_integer(t, "tool number T")?;
        cx.out.push(Canon::SelectTool { tool });
        cx.st.selected_tool = Some(tool);
    }
    Ok(())
}

/// G43/G44 [H] [X Y Z …] (module doc).
pub(crate) fn length_offset(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let from_ttpc = cx.fe.modes.mode != TtpcMode::Off;
    if from_ttpc && t_series(cx) {
        return Err(cx
            .err(
                "mazatrol::code-not-allowed-in-ttpc",
                format!(
                    "G{} is not allowed in tool tip point control on this mill-turn (T-series) control",
                    code / 10
                ),
                span,
            )
            .with_note("cancel tool tip point control with G49 first (at a safe position)"));
    }
    let length = match cx.words.take(b'H') {
        Some(h) => {
            let n = cx.non_negative_integer(h, "tool length offset number H")?;
            tool_length(cx, n)
        }
        None => length_without_h(cx),
    };
    let before = cx.st.program_position();
    if from_ttpc {
        // TTPC off without motion: the axes stay, the control point becomes the virtual tip.
        let base = crate::kinematics(cx, span)?;
        let kin = base
            .clone()
            .with_tool_offset(base.base().map(|x| x * cx.fe.modes.length));
        let joints = kin.inverse(&cx.st.position).map_err(|e| {
            cx.err(
                "mazatrol::illegal-number-input",
                format!("ILLEGAL NUMBER INPUT: {e}"),
                span,
            )
        })?;
        cx.out.push(Canon::SetToolCentrePoint {
            active: false,
            tool_offset: [0.0; 3],
        });
        cx.st.position = Pose::from_array(joints);
    }
    let was_on = cx.fe.modes.offset != LengthOffset::Off;
    *cx.fe.modes = MazatrolState {
        length,
        offset: if code == G44 {
            LengthOffset::Minus
        } else {
            LengthOffset::Plus
        },
        ..MazatrolState::default()
    };
    set_tlo(cx, if code == G44 { -length } else { length });
    if cx.has_axis_words() {
        let (end, _) = cx.end_point()?;
        crate::move_to(cx, end, span)
    } else if !from_ttpc && !was_on {
        // From G49: the axes take up the offset (the program position stays).
        crate::move_to(cx, before, span)
    } else {
        // A direct switch on its own moves no axis (§11.1); the displayed position changes.
        Ok(())
    }
}

/// G49 while G43/G44 is in force: the offset is cleared and the axes move to remove it
/// (F114 bit 1 = 0): the holder face goes to where the virtual tip was.
pub(crate) fn cancel_length_offset(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let before = cx.st.program_position();
    *cx.fe.modes = MazatrolState::default();
    set_tlo(cx, 0.0);
    crate::move_to(cx, before, span)
}

/// G43.4/G43.5 while G43/G44 is in force (§11.1): the M-series replaces the length offset by
/// TTPC; the T-series refuses (AMB-13). Clears the ordinary offset from the frame; returns true
/// (a direct switch: without axis words no axis moves).
pub(crate) fn leave_for_ttpc(
    cx: &mut Ctx<'_>,
    code: u32,
    span: ColSpan,
) -> Result<bool, Diagnostic> {
    if cx.fe.modes.offset == LengthOffset::Off {
        return Ok(false);
    }
    if t_series(cx) {
        return Err(cx
            .err(
                "mazatrol::ttpc-not-selectable",
                format!(
                    "G43.{} cannot be selected while tool length offset G43/G44 is in force on this mill-turn (T-series) control",
                    code % 10
                ),
                span,
            )
            .with_note("cancel the tool length offset with G49 first (at a safe position)"));
    }
    cx.fe.modes.offset = LengthOffset::Off;
    set_tlo(cx, 0.0);
    Ok(true)
}
