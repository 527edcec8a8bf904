//! Tools (`docs/dialects/mazatrol-eia.md` §8.1–§8.4): the M-series magazine (`T… M6`, tlo.rs),
//! the T-series turret `T tt oo` with its X/Z offsets, and G45–G48 tool position offsets.

use crate::ctx::Ctx;
use crate::rules::t_word;
use crate::TtpcMode;
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_syntax::ColSpan;

/// `T… M6` (M-series) or `T tt oo M6` (T-series: M6 is not needed, the turret indexes on T).
pub(crate) fn tool_change(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.fe.m.t() {
        return turret(cx);
    }
    crate::tlo::tool_change(cx, span)
}

/// A T word without M6.
pub(crate) fn select(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    if cx.fe.m.t() {
        return turret(cx);
    }
    if cx.fe.modes.mode != TtpcMode::Off && cx.words.has(b'T') {
        // Preparing the next tool is harmless in TTPC.
    }
    crate::tlo::select_tool(cx)
}

/// The T-series offset `n` as the frame's tool offset (X on the radius, Z).
pub(crate) fn turn_offset_pose(cx: &Ctx<'_>, n: u32) -> Pose {
    if n == 0 {
        return Pose::ZERO;
    }
    let (x, z, _, _) = cx.fe.tables.turn_offset(n);
    Pose { x, z, ..Pose::ZERO }
}

/// `T tt oo`: index the turret to tool tt, put offset oo in force (`docs` §8.2).
fn turret(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    let Some(t) = cx.words.take(b'T') else {
        return Ok(());
    };
    if let Some(second) = cx.words.second.take() {
        return Err(cx.err(
            "mazatrol::repeated-word",
            "T appears twice in this block (the T-series T word is `T tt oo`)",
            second.span,
        ));
    }
    let value = cx.non_negative_integer(t, "T")?;
    let (tool, offset) = t_word(value);
    if cx.fe.modes.mode != TtpcMode::Off {
        return Err(cx.err(
            "mazatrol::code-not-allowed-in-ttpc",
            "T (turret indexing and tool offset) is not allowed during tool tip point control: cancel it with G49 first",
            t.span,
        ));
    }
    if tool != 0 && tool != cx.st.current_tool {
        cx.out.push(Canon::SelectTool { tool });
        cx.out.push(Canon::StartToolChange);
        cx.out.push(Canon::ChangeTool { tool, slot: tool });
        cx.st.current_tool = tool;
        cx.st.selected_tool = None;
    }
    if offset != 0 && cx.fe.tables.edge(offset).is_none() {
        cx.warnings.push(Diagnostic::warning(
            "mazatrol::unknown-tool",
            format!("tool offset {offset:02} is not in the tool table: offsets 0"),
            cx.block.span_of(t.span),
        ));
    }
    set_turn_offset(cx, offset);
    Ok(())
}

/// Puts T-series offset `n` (0 = none) into the frame.
pub(crate) fn set_turn_offset(cx: &mut Ctx<'_>, n: u32) {
    let pose = turn_offset_pose(cx, n);
    cx.fe.m.t_offset = n;
    if *cx.st.frame.tlo() != pose {
        cx.st.frame.set_tlo(pose);
        cx.out.push(Canon::UseToolLengthOffset { offset: pose });
    }
}

/// G45 / G46 / G47 / G48 (M): one move lengthened or shortened by d or 2d per axis word.
pub(crate) fn position_offset(
    cx: &mut Ctx<'_>,
    code: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let d_word = cx.words.take(b'D');
    let n = match d_word {
        Some(d) => cx.non_negative_integer(d, "D")?,
        None => cx.fe.m.comp_d,
    };
    let d = cx.fe.tables.radius(n);
    if matches!(
        cx.st.motion,
        stanok_interp_core::MotionMode::ArcCw | stanok_interp_core::MotionMode::ArcCcw
    ) {
        return Err(cx.err(
            "mazatrol::compensation",
            "G45–G48 work on straight moves only",
            span,
        ));
    }
    let factor = match code {
        450 => 1.0,
        460 => -1.0,
        470 => 2.0,
        _ => -2.0,
    };
    let start = cx.st.program_position().to_array();
    let written: Vec<(usize, f64)> = [b'X', b'Y', b'Z']
        .iter()
        .enumerate()
        .filter_map(|(i, l)| cx.words.peek(*l).map(|v| (i, v.v)))
        .collect();
    let (end, _) = crate::motion::end_point(cx)?;
    let mut e = end.to_array();
    for (i, word) in written {
        let delta = e[i] - start[i];
        let sign = if delta != 0.0 {
            delta.signum()
        } else if word < 0.0 || (word == 0.0 && word.is_sign_negative()) {
            -1.0
        } else {
            1.0
        };
        e[i] = start[i] + delta + factor * sign * d;
    }
    crate::motion::straight_to(cx, Pose::from_array(e), span)
}
