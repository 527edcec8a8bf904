//! AxiOMA tool selection (T, D with M06/M66; spec axioma-2 §3.9–§3.10) and tool length
//! compensation G43/G44/G45/G49 (spec axioma-3 §2–§3).
//!
//! The offset is `σ·V`: the effective lengths `C_i = L_i + wear_i` of the active edge placed on the
//! machine axes given by the tool kind and the plane (tables 9.1/9.2 below; G45 fixes the plane),
//! σ = +1 (G43, G45 L > 0), −1 (G44, G45 L < 0), 0 (G49, no tool, T0, D0).
//!
//! When it takes effect (spec axioma-3 §3.4, A1): a change of σ·V is applied by the next block that
//! moves, on all Cartesian axes, including those the block does not program. The program position
//! therefore does not jump when G43 is read; `ModalState::pending_tlo` carries the new offset until
//! `Ctx::straight`/`Ctx::arc` put it into the work frame at the start of the next motion.

use crate::ctx::Ctx;
use crate::modes::LengthComp;
use crate::words::Val;
use stanok_canon::setup::ToolKind;
use stanok_canon::{Diagnostic, Plane, Pose};

/// Machine axis (0 = X, 1 = Y, 2 = Z) of C1, C2, C3 by tool kind and plane (manual tables 9.1, 9.2).
fn axes_of(kind: ToolKind, plane: Plane) -> [usize; 3] {
    let turning = matches!(kind, ToolKind::Turning | ToolKind::Grinding);
    match (turning, plane) {
        (false, Plane::XY) => [2, 1, 0],
        (false, Plane::ZX) => [1, 0, 2],
        (false, Plane::YZ) => [0, 2, 1],
        (true, Plane::XY) => [1, 0, 2],
        (true, Plane::ZX) => [0, 2, 1],
        (true, Plane::YZ) => [2, 1, 0],
    }
}

/// G43 / G44 / G45 L… / G49.
pub(super) fn length_comp(cx: &mut Ctx<'_>, code: u32) -> Result<(), Diagnostic> {
    cx.fe.modes.length_comp = match code {
        430 => LengthComp::Plus,
        440 => LengthComp::Minus,
        450 => {
            // `G45 L<n>`, n ∈ {±17, ±18, ±19}; anything else (or no L) is reset to 17 (spec §3.5).
            let l = cx.words.take(b'L').map(|v| v.v).unwrap_or(17.0);
            let (plane, sign) = match l {
                18.0 => (Plane::ZX, 1.0),
                19.0 => (Plane::YZ, 1.0),
                -17.0 => (Plane::XY, -1.0),
                -18.0 => (Plane::ZX, -1.0),
                -19.0 => (Plane::YZ, -1.0),
                _ => (Plane::XY, 1.0),
            };
            LengthComp::Fixed { plane, sign }
        }
        _ => LengthComp::Off,
    };
    Ok(())
}

/// M06/M66 with T and/or D: the tool in the spindle and the active edge (spec axioma-2 §3.10).
pub(super) fn tool_change(
    cx: &mut Ctx<'_>,
    tool: Option<u32>,
    d: Option<Val>,
) -> Result<(), Diagnostic> {
    if let Some(t) = tool {
        cx.st.current_tool = t;
        // T without D is D1 (rule 1); T0 has no edge.
        cx.fe.modes.edge = if t == 0 { 0 } else { 1 };
    }
    if let Some(d) = d {
        let edge = d.v;
        if edge.fract() != 0.0 || !(0.0..=4.0).contains(&edge) {
            return Err(cx.err(
                "axioma::edge-range",
                format!("D{edge}: cutting edges are D0 to D4"),
                d.span,
            ));
        }
        cx.fe.modes.edge = edge as u8;
    }
    let (t, e) = (cx.st.current_tool, cx.fe.modes.edge);
    if t != 0 && e != 0 {
        match cx.opts.control.tools.get(t) {
            None => cx.warnings.push(Diagnostic::warning(
                "axioma::tool-not-in-table",
                format!("T{t} is not in the tool table: its lengths and radius count as 0"),
                cx.block.span(),
            )),
            Some(tool) if tool.edges.len() < e as usize => {
                return Err(cx.err(
                    "axioma::edge-missing",
                    format!(
                        "T{t} has {} cutting edge(s): D{e} does not exist",
                        tool.edges.len()
                    ),
                    d.map(|d| d.span).unwrap_or_else(|| cx.whole()),
                ))
            }
            Some(_) => {}
        }
    }
    Ok(())
}

/// `D` outside an M06/M66 block is forbidden (spec axioma-2 §3.10).
pub(super) fn stray_d(cx: &Ctx<'_>, d: Val) -> Diagnostic {
    cx.err(
        "axioma::d-without-tool-change",
        "D selects a cutting edge only together with M06 or M66",
        d.span,
    )
}

/// σ·V for the current state.
pub(super) fn length_offset(cx: &Ctx<'_>) -> Pose {
    let (t, e) = (cx.st.current_tool, cx.fe.modes.edge);
    let (plane, sign) = match cx.fe.modes.length_comp {
        LengthComp::Off => return Pose::ZERO,
        LengthComp::Plus => (cx.st.plane, 1.0),
        LengthComp::Minus => (cx.st.plane, -1.0),
        LengthComp::Fixed { plane, sign } => (plane, sign),
    };
    if t == 0 || e == 0 {
        return Pose::ZERO;
    }
    let Some(tool) = cx.opts.control.tools.get(t) else {
        return Pose::ZERO;
    };
    let Some(edge) = tool.edges.get(e as usize - 1) else {
        return Pose::ZERO;
    };
    let axes = axes_of(tool.kind, plane);
    let mut v = [0.0; 9];
    for i in 0..3 {
        v[axes[i]] += sign * (edge.length[i] + edge.length_wear[i]);
    }
    Pose::from_array(v)
}

/// After a block: a changed σ·V waits for the next motion.
pub(super) fn update(cx: &mut Ctx<'_>) {
    if super::orientation::update_tool(cx) {
        return;
    }
    let want = length_offset(cx);
    let pending = (want != *cx.st.frame.tlo()).then_some(want);
    // Written only when it changes: the AxiOMA modes are journalled on their first `&mut`
    // access (`state::Journalled`), and almost every block leaves this as it was.
    if cx.fe.modes.pending_tlo != pending {
        cx.fe.modes.pending_tlo = pending;
    }
}

/// `T2=…`, `D2=…` (spindles 2…4) in an M06/M66 block: the tool and edge of those spindles.
pub(super) fn other_spindles(
    cx: &mut Ctx<'_>,
    tools: &[(u8, Val)],
    edges: &[(u8, Val)],
) -> Result<(), Diagnostic> {
    for &(spindle, t) in tools {
        let tool = cx.non_negative_integer(t, "tool number T")?;
        let i = spindle as usize;
        if cx.fe.modes.spindle_tools[i] != tool {
            cx.out
                .push(stanok_canon::Canon::ChangeSpindleTool { spindle, tool });
        }
        cx.fe.modes.spindle_tools[i] = tool;
        cx.fe.modes.spindle_edges[i] = if tool == 0 { 0 } else { 1 };
    }
    for &(spindle, d) in edges {
        if d.v.fract() != 0.0 || !(0.0..=4.0).contains(&d.v) {
            return Err(cx.err(
                "axioma::edge-range",
                format!("D{}: cutting edges are D0 to D4", d.v),
                d.span,
            ));
        }
        cx.fe.modes.spindle_edges[spindle as usize] = d.v as u8;
    }
    Ok(())
}
