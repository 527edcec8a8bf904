//! RS274/NGC tool data (spec rs274ngc §4.9, §4.10, §4.12, §4.23–§4.26): T (select), M6 (change),
//! G43/G43.1/G43.2/G49 (tool length offset), G10 L0/L1/L10/L11 (the tool table), and the loaded
//! tool's parameters #5400…#5413, with LinuxCNC's messages.
//!
//! The tool table is interpreter state (a copy of the options' table kept in [`Parameters`],
//! changed only when a block commits). A LinuxCNC tool is edge D1 of a Stanok tool: its per-axis
//! `offset` is what G43 applies, `radius` is half LinuxCNC's diameter D.
//!
//! LinuxCNC keeps #5400…#5413 as a copy of the loaded tool's table entry, refreshed at M6 and when
//! G10 L1 changes that tool — *not* the offset in force (G43 H10 or G43.1 leave #5403 alone).
//! Stanok writes them at the same events.

use super::axis_values;
use crate::codes::*;
use crate::ctx::Ctx;
use crate::params::Parameters;
use stanok_canon::setup::{Tool, ToolEdge};
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_interp_core::Val;
use stanok_syntax::ColSpan;

fn not_found(cx: &Ctx<'_>, number: impl std::fmt::Display, at: ColSpan) -> Diagnostic {
    cx.err(
        "rs274::tool-not-found",
        format!("Requested tool {number} not found in the tool table"),
        at,
    )
}

/// The edge LinuxCNC uses (D1), or an empty one.
fn edge(tool: Option<&Tool>) -> ToolEdge {
    tool.and_then(|t| t.edges.first())
        .copied()
        .unwrap_or_default()
}

/// A whole tool number from an H word: LinuxCNC's "Non integer value for integer" and "Requested
/// tool … not found" (H0 is the loaded tool, whichever it is).
fn h_tool(cx: &Ctx<'_>, params: &Parameters, h: Val) -> Result<u32, Diagnostic> {
    if (h.v - h.v.round()).abs() > 1e-4 {
        return Err(cx.err(
            "rs274::not-an-integer",
            "Non integer value for integer",
            h.span,
        ));
    }
    let n = h.v.round();
    if n == 0.0 {
        return Ok(cx.st.current_tool);
    }
    if n < 0.0 || params.tools().get(n as u32).is_none() {
        return Err(not_found(cx, n, h.span));
    }
    Ok(n as u32)
}

/// T: prepare a tool. It must be in the table (T0 = no tool). A machine without tool data (empty
/// table) accepts any T: there is nothing to check it against.
pub(super) fn select_tool(cx: &mut Ctx<'_>, params: &Parameters, t: Val) -> Result<(), Diagnostic> {
    // LinuxCNC reads T as an integer (within 10⁻⁴) and refuses a negative one with its words.
    if (t.v - t.v.round()).abs() > 1e-4 {
        return Err(cx.err(
            "rs274::not-an-integer",
            "Non integer value for integer",
            t.span,
        ));
    }
    if t.v.round() < 0.0 {
        return Err(cx.err(
            "rs274::negative-tool",
            "Negative tool id (tool not found)",
            t.span,
        ));
    }
    let tool = cx.non_negative_integer(
        Val {
            v: t.v.round(),
            ..t
        },
        "T word",
    )?;
    let table = &params.tools().tools;
    if tool != 0 && !table.is_empty() && !table.contains_key(&tool) {
        return Err(not_found(cx, tool, t.span));
    }
    cx.st.selected_tool = Some(tool);
    cx.out.push(Canon::SelectTool { tool });
    Ok(())
}

/// Writes #5400…#5413 from the loaded tool's table entry (zeros for T0 or a tool without data).
pub(super) fn load_tool_parameters(params: &mut Parameters, tool: u32) {
    let e = edge(params.tools().get(tool));
    params.set(5400, tool as f64);
    params.set_pose_mm(5401, &e.offset);
    params.set_mm(5410, 2.0 * e.radius);
    params.set(5411, e.front_angle);
    params.set(5412, e.back_angle);
    params.set(5413, e.orientation as f64);
}

/// M6: the selected tool (or, with no T yet, the loaded one again) goes into the spindle. The
/// offset in force does not change: that is G43's job.
pub(super) fn change_tool(cx: &mut Ctx<'_>, params: &mut Parameters) {
    let tool = cx.st.selected_tool.unwrap_or(cx.st.current_tool);
    cx.out.push(Canon::StartToolChange);
    cx.out.push(Canon::StopSpindle { spindle: 0 });
    cx.st.spindle_on[0] = false;
    // rs274 prints the tool's slot in its table (0: no tool).
    let slot = params.tool_slot(tool).unwrap_or(0);
    cx.out.push(Canon::ChangeTool { tool, slot });
    cx.st.current_tool = tool;
    load_tool_parameters(params, tool);
}

/// G43, G43.1, G43.2, G49 (no motion: the next move of a compensated axis ends compensated, the
/// machine position stays and the program position is re-derived). Returns true if the code took
/// the block's axis words (G43.1, G43.2 with axes).
pub(super) fn tool_length_offset(
    cx: &mut Ctx<'_>,
    params: &Parameters,
    code: u32,
    span: ColSpan,
) -> Result<bool, Diagnostic> {
    let current = cx.st.frame.tlo().to_array();
    let tool_offset = |number: u32| edge(params.tools().get(number)).offset.to_array();
    let mut axes_used = false;
    let offset = match code {
        G49 => [0.0; 9],
        G43 => match cx.words.take(b'H') {
            Some(h) => tool_offset(h_tool(cx, params, h)?),
            // Without H: the loaded tool (loaded by an M6 of this very block too).
            None => tool_offset(cx.st.current_tool),
        },
        G43_1 => {
            // Replaces the named axes' offsets; the others keep theirs.
            let mut o = current;
            for (k, v) in axis_values(cx)?.into_iter().enumerate() {
                if let Some(v) = v {
                    o[k] = v;
                    axes_used = true;
                }
            }
            o
        }
        _ => {
            // G43.2: adds tool H's offsets, or (document; LinuxCNC 2.9 rejects it) the axis values.
            let h = cx.words.take(b'H');
            let has_axes = cx.has_axis_words();
            let add = match (h, has_axes) {
                (Some(h), true) => {
                    return Err(cx.err(
                        "rs274::g43-2-h-and-axes",
                        "G43.2: Can not have both H and axis words",
                        h.span,
                    ))
                }
                (None, false) => {
                    return Err(cx.err(
                        "rs274::g43-2-nothing",
                        "G43.2: No axes specified and H word missing",
                        span,
                    ))
                }
                (Some(h), false) => tool_offset(h_tool(cx, params, h)?),
                (None, true) => {
                    axes_used = true;
                    axis_values(cx)?.map(|v| v.unwrap_or(0.0))
                }
            };
            std::array::from_fn(|k| current[k] + add[k])
        }
    };
    let offset = Pose::from_array(offset);
    cx.st.frame.set_tlo(offset);
    cx.out.push(Canon::UseToolLengthOffset { offset });
    Ok(axes_used)
}

/// G10 L0: reload the tool table. Stanok's table is already what the program's G10 L1 wrote (as
/// LinuxCNC's file is), so only the command and LinuxCNC's condition remain.
pub(super) fn reload_tool_table(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    if cx.st.current_tool != 0 {
        let at = cx.whole();
        return Err(cx
            .err(
                "rs274::g10-l0-tool-loaded",
                format!(
                    "G10 L0 not allowed with loaded tool <{}>",
                    cx.st.current_tool
                ),
                at,
            )
            .with_note("unload it first with T0 M6"));
    }
    cx.out.push(Canon::ReloadToolTable);
    Ok(())
}

/// Rotates (x, y) by `deg` about Z.
fn rotate(v: [f64; 2], deg: f64) -> [f64; 2] {
    let (s, c) = deg.to_radians().sin_cos();
    [v[0] * c - v[1] * s, v[0] * s + v[1] * c]
}

/// G10 L1 (values), L10 (so that the current point reads the values in the active system once G43
/// reloads the offset), L11 (the same in G59.3 without G92: a fixed tool setter).
pub(super) fn set_tool_entry(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    l: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let p = cx.words.take(b'P');
    let number = match p {
        Some(p) if p.v.fract() == 0.0 && p.v >= 1.0 && p.v <= u32::MAX as f64 => p.v as u32,
        _ => {
            let at = p.map_or(span, |p| p.span);
            return Err(cx
                .err(
                    "rs274::g10-p-range",
                    format!("P value out of range with G10 L{l}"),
                    at,
                )
                .with_note("P is the tool number, a whole number ≥ 1"));
        }
    };
    let Some(mut tool) = params.tools().get(number).cloned() else {
        return Err(not_found(cx, number, p.map_or(span, |p| p.span)));
    };
    let given = axis_values(cx)?;
    let r = cx.words.take(b'R');
    let i = cx.words.take(b'I');
    let j = cx.words.take(b'J');
    let q = cx.words.take(b'Q');
    if given.iter().all(Option::is_none) && r.is_none() && i.is_none() && j.is_none() && q.is_none()
    {
        return Err(cx.err(
            "rs274::g10-l1-nothing",
            "G10 L1 without offsets has no effect",
            span,
        ));
    }
    let mut e = edge(Some(&tool));
    let mut o = e.offset.to_array();
    if l == 1 {
        for (k, v) in given.iter().enumerate() {
            if let Some(v) = v {
                o[k] = *v;
            }
        }
    } else {
        // The current point without tool length offset, in the destination system: the active
        // one with G92 (L10), or G59.3 without G92 (L11). Offset = that − value, so that after
        // G43 the point reads `value`.
        let (system, with_shift) = if l == 11 {
            (9, false)
        } else {
            (cx.st.g5x_index.max(1), true)
        };
        let (origin, rotation) = super::g5x_from_params(params, system);
        let mut frame = cx.st.frame;
        frame.set_origin(origin);
        frame.set_rotation(if rotation == 0.0 {
            crate::frame::IDENTITY
        } else {
            crate::frame::rotation(2, rotation)
        });
        frame.set_tlo(Pose::ZERO);
        if !with_shift {
            frame.set_shift(Pose::ZERO);
        }
        let t = frame.to_program(&cx.st.position).to_array();
        // X and Y: the difference is rotated into the machine frame, where tool offsets live.
        // Naming only one of them keeps the old offset's component along the other (rotated)
        // axis, as LinuxCNC does.
        match (given[0], given[1]) {
            (None, None) => {}
            (x, y) => {
                let old = rotate([o[0], o[1]], -rotation);
                let d = [
                    x.map_or(old[0], |x| t[0] - x),
                    y.map_or(old[1], |y| t[1] - y),
                ];
                let m = rotate(d, rotation);
                o[0] = m[0];
                o[1] = m[1];
            }
        }
        for k in 2..9 {
            if let Some(v) = given[k] {
                o[k] = t[k] - v;
            }
        }
    }
    e.offset = Pose::from_array(o);
    if let Some(r) = r {
        e.radius = cx.mm(r.v);
    }
    if let Some(i) = i {
        e.front_angle = i.v;
    }
    if let Some(j) = j {
        e.back_angle = j.v;
    }
    if let Some(q) = q {
        if q.v.fract() != 0.0 {
            return Err(cx.err(
                "rs274::g10-q-not-integer",
                "Q number in G10 is not an integer",
                q.span,
            ));
        }
        if !(0.0..=9.0).contains(&q.v) {
            return Err(cx.err("rs274::g10-q-range", "Invalid tool orientation", q.span));
        }
        e.orientation = q.v as u8;
    }
    match tool.edges.first_mut() {
        Some(first) => *first = e,
        None => tool.edges.push(e),
    }
    params.set_tool(tool);
    let entry = |slot| Canon::SetToolTableEntry {
        slot,
        tool: number,
        offset: e.offset,
        diameter: 2.0 * e.radius,
        front_angle: e.front_angle,
        back_angle: e.back_angle,
        orientation: e.orientation,
    };
    cx.out.push(entry(params.tool_slot(number).unwrap_or(0)));
    // The loaded tool's copy (LinuxCNC's slot 0) and #5400… follow its table entry.
    if number == cx.st.current_tool {
        load_tool_parameters(params, number);
        cx.out.push(entry(0));
    }
    Ok(())
}
