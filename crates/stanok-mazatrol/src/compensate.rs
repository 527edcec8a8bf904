//! G40/G41/G42 (and G46 on the T-series) as a stream over the blocks
//! (`docs/dialects/mazatrol-eia.md` §8.5; geometry in `comp.rs`).
//!
//! A compensated element is emitted at once with a provisional end (the perpendicular point of
//! its offset, which is final when the next block cancels) and stays *pending*: the driver holds
//! it and everything after it (`FrontEnd::held`), and the next element's block moves its end to
//! the corner point in place, inserts the corner arc and emits itself as the next pending one.
//!
//! ```text
//!   G41/G42 line S → P1 (start-up)    pending: S → perpendicular point of S→P1
//!   next element E                    start-up end := start(offset E)  (type A)
//!   next element E' after E           E's end := corner point; corner arc; E' from its start
//!   a block without plane motion      the pending element ends where it is (look-ahead ends)
//!   G40 and a plane move to E         the cancel line from the pending end to E
//! ```
//! *Invariants:* the pending command's queue index follows the releases (`released`); its edit is
//! undone if the editing block fails (the backup is restored by `rollback`); the programmed point
//! (where the program thinks the tool is) is kept apart from the tool's position.

use crate::comp::{self, tip_vector};
use crate::ctx::Ctx;
use crate::modes::CompMode;
use stanok_canon::{ArcMove, Canon, Diagnostic, LineMove, Pose, Spanned};
use stanok_geom::offset2d::{Seg2, P2};
use stanok_syntax::ColSpan;

/// The pending (last) compensated element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pending {
    /// The programmed element (plane coordinates), for the next corner.
    pub seg: Seg2,
    /// Where its tool piece starts (offset plane point, before the tip shift).
    pub tool_start: P2,
    /// Its command's index in the driver's queue.
    pub index: usize,
    /// A start-up line (type A: its end waits for the next element's offset start).
    pub startup: bool,
    /// A rapid.
    pub rapid: bool,
}

/// The compensation state (journalled inside `Modes`' neighbour `CompState`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CompState {
    /// Signed offset: +r to the left (G41), −r to the right (G42); 0 off.
    pub d: f64,
    /// The T-series tip shift (z, x) = r·tip vector; 0 on the M-series.
    pub shift: P2,
    /// The programmed point in the plane while compensation is on.
    pub programmed: Option<P2>,
    /// The pending element.
    pub pending: Option<Pending>,
    /// G40 was given: the next plane move cancels.
    pub cancelling: bool,
    /// G46: the side is chosen at the first move.
    pub auto: bool,
    /// The tip (T-series, for G46).
    pub tip: u8,
}

/// True while compensation acts on moves.
pub(crate) fn active(cx: &Ctx<'_>) -> bool {
    cx.fe.comp.d != 0.0 || cx.fe.comp.auto
}

/// The programmed point of the plane (where incremental words start from).
pub(crate) fn programmed_point(cx: &Ctx<'_>) -> Option<P2> {
    cx.fe.comp.programmed
}

/// G40 / G41 / G42 / G46.
pub(crate) fn mode(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let d_word = cx.words.take(b'D');
    if code == 400 {
        cx.fe.m.comp = CompMode::Off;
        if active(cx) {
            cx.fe.comp.cancelling = true;
        }
        return Ok(());
    }
    if cx.fe.modes.mode != crate::TtpcMode::Off {
        return Ok(()); // the table check refuses it first
    }
    let (r, tip) = if cx.fe.m.t() {
        let (_, _, r, tip) = cx.fe.tables.turn_offset(cx.fe.m.t_offset);
        (r, tip)
    } else {
        let n = match d_word {
            Some(d) => cx.non_negative_integer(d, "D")?,
            None => cx.fe.m.comp_d,
        };
        cx.fe.m.comp_d = n;
        if n != 0 && cx.fe.tables.edge(n).is_none() {
            cx.warnings.push(Diagnostic::warning(
                "mazatrol::unknown-tool",
                format!("D{n}: tool {n} is not in the tool table, radius 0"),
                cx.block.span_of(span),
            ));
        }
        (cx.fe.tables.radius(n), 0)
    };
    cx.fe.m.comp = match code {
        410 => CompMode::Left,
        420 => CompMode::Right,
        _ => CompMode::Auto,
    };
    let was_on = active(cx);
    let c = &mut cx.fe.comp;
    c.cancelling = false;
    c.auto = code == 460;
    c.tip = tip;
    c.d = match code {
        410 => r,
        420 => -r,
        _ => 0.0,
    };
    let t = tip_vector(tip);
    c.shift = [r * t[0], r * t[1]];
    if !was_on {
        let (a, b, _) = cx.st.plane.axes();
        let p = cx.st.program_position().to_array();
        cx.fe.comp.programmed = Some([p[a], p[b]]);
    }
    if r == 0.0 && code != 460 {
        // Radius 0: the path is the program's; keep the mode for #4007.
        cx.fe.comp.d = 0.0;
        cx.fe.comp.programmed = None;
    }
    Ok(())
}

/// A pose with the plane point `q` (tool piece point + tip shift) and the other axes of `like`.
fn pose(cx: &Ctx<'_>, q: P2, like: &Pose) -> Pose {
    let (a, b, _) = cx.st.plane.axes();
    let mut v = like.to_array();
    v[a] = q[0] + cx.fe.comp.shift[0];
    v[b] = q[1] + cx.fe.comp.shift[1];
    Pose::from_array(v)
}

fn plane_point(cx: &Ctx<'_>, p: &Pose) -> P2 {
    let (a, b, _) = cx.st.plane.axes();
    let v = p.to_array();
    [v[a], v[b]]
}

fn gouge(cx: &Ctx<'_>, e: comp::CompError, at: ColSpan) -> Diagnostic {
    cx.err("mazatrol::compensation", e.0, at)
}

/// Emits a straight tool move to `end` (program coordinates) and returns its queue index.
fn emit_line(cx: &mut Ctx<'_>, rapid: bool, end: Pose, at: ColSpan) -> Result<usize, Diagnostic> {
    crate::motion::emit_straight(cx, rapid, end, at)?;
    Ok(cx.out.queue.len() - 1)
}

/// Emits a tool arc (program coordinates, plane centre) and returns its queue index.
fn emit_arc(
    cx: &mut Ctx<'_>,
    ccw: bool,
    end: Pose,
    centre: P2,
    at: ColSpan,
) -> Result<usize, Diagnostic> {
    let c = [
        centre[0] + cx.fe.comp.shift[0],
        centre[1] + cx.fe.comp.shift[1],
    ];
    crate::motion::emit_arc(cx, ccw, end, c, 1, at)?;
    Ok(cx.out.queue.len() - 1)
}

/// Moves the end of the pending command to the plane point `q` (program coordinates), keeping a
/// backup for the rollback.
fn edit_pending_end(cx: &mut Ctx<'_>, p: Pending, q: P2) {
    let Some(cmd) = cx.out.queue.get(p.index).cloned() else {
        return;
    };
    if cx.fe.comp_backup.is_none() {
        cx.fe.comp_backup = Some((p.index, cmd.clone()));
    }
    let end_prog = {
        let m = match &cmd.value {
            Canon::StraightTraverse(l) | Canon::StraightFeed(l) => l.end,
            Canon::ArcFeed(a) => a.end,
            _ => return,
        };
        let prog = cx.st.frame.to_program(&m);
        pose(cx, q, &prog)
    };
    let end_m = cx.st.frame.to_machine(&end_prog);
    let Some(slot) = cx.out.queue.get_mut(p.index) else {
        return;
    };
    match &mut slot.value {
        Canon::StraightTraverse(LineMove { end, .. })
        | Canon::StraightFeed(LineMove { end, .. })
        | Canon::ArcFeed(ArcMove { end, .. }) => *end = end_m,
        _ => {}
    }
    // Everything after it (held) starts from the new end; the tool is there now.
    cx.st.position = end_m;
}

/// The element of a move from the programmed point to `end`.
fn element_line(cx: &Ctx<'_>, end: &Pose) -> Option<Seg2> {
    let a = cx.fe.comp.programmed?;
    let b = plane_point(cx, end);
    if (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9 {
        return None;
    }
    Some(Seg2::Line { a, b })
}

/// A straight move under compensation.
pub(crate) fn line(
    cx: &mut Ctx<'_>,
    rapid: bool,
    end: Pose,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let Some(seg) = element_line(cx, &end) else {
        // No plane motion: the look-ahead ends here; the pending element keeps its end.
        if cx.fe.comp.pending.is_some() {
            cx.warnings.push(Diagnostic::warning(
                "mazatrol::compensation-gap",
                "a move without motion in the compensation plane: the offset path before it ends \
                 at its perpendicular point and starts again from there (the control's look-ahead \
                 across such a block is not modelled)",
                cx.block.span_of(at),
            ));
        }
        settle(cx);
        let now = cx.st.program_position();
        let (a, b, _) = cx.st.plane.axes();
        let mut v = end.to_array();
        let n = now.to_array();
        v[a] = n[a];
        v[b] = n[b];
        crate::motion::emit_straight(cx, rapid, Pose::from_array(v), at)?;
        return Ok(());
    };
    element(cx, seg, rapid, end, at)
}

/// An arc under compensation (`centre` in the plane, program coordinates).
pub(crate) fn arc(
    cx: &mut Ctx<'_>,
    ccw: bool,
    end: Pose,
    centre: P2,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let Some(a) = cx.fe.comp.programmed else {
        return crate::motion::emit_arc(cx, ccw, end, centre, 1, at);
    };
    let b = plane_point(cx, &end);
    let full = (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9;
    let seg = Seg2::arc_through(centre, a, b, ccw, full);
    if cx.fe.comp.pending.is_none() && !cx.fe.comp.cancelling {
        return Err(cx.err(
            "mazatrol::compensation",
            "compensation starts with a straight move (G00/G01), not an arc",
            at,
        ));
    }
    if cx.fe.comp.cancelling {
        return Err(cx.err(
            "mazatrol::compensation",
            "compensation is cancelled with a straight move (G00/G01), not an arc",
            at,
        ));
    }
    element(cx, seg, false, end, at)
}

/// One element of the contour: start-up, corner, cancel.
fn element(
    cx: &mut Ctx<'_>,
    seg: Seg2,
    rapid: bool,
    end: Pose,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let b = plane_point(cx, &end);
    if cx.fe.comp.auto && cx.fe.comp.pending.is_some() {
        // G46: the side from the tip and the first contour element's direction (the start-up
        // line waits for it anyway, type A).
        let t = seg.tangent(0.0);
        let left = comp::g46_left(cx.fe.comp.tip, t);
        let (_, _, r, _) = cx.fe.tables.turn_offset(cx.fe.m.t_offset);
        cx.fe.comp.d = if left { r } else { -r };
        cx.fe.comp.auto = false;
        cx.fe.m.comp = if left {
            CompMode::Left
        } else {
            CompMode::Right
        };
    }
    let d = cx.fe.comp.d;
    if cx.fe.comp.cancelling {
        // Cancel (type A): from the pending end to the programmed end.
        settle(cx);
        *cx.fe.comp = crate::compensate::CompState::default();
        crate::motion::emit_straight(cx, rapid, end, at)?;
        return Ok(());
    }
    let pending = cx.fe.comp.pending;
    let (start, arc) = match pending {
        None => {
            // The start-up line: provisional end at its own perpendicular point (G46: at the
            // programmed point, the side is not known yet).
            let q = if cx.fe.comp.auto {
                b
            } else {
                comp::end_point(&seg, d).map_err(|e| gouge(cx, e, at))?
            };
            let target = pose(cx, q, &end);
            let index = emit_line(cx, rapid, target, at)?;
            cx.fe.comp.pending = Some(Pending {
                seg,
                tool_start: plane_point(cx, &cx.st.program_position()),
                index,
                startup: true,
                rapid,
            });
            cx.fe.comp.programmed = Some(b);
            return Ok(());
        }
        Some(p) if p.startup => {
            let s = comp::start_point(&seg, d).map_err(|e| gouge(cx, e, at))?;
            edit_pending_end(cx, p, s);
            (s, None)
        }
        Some(p) => {
            let c = comp::corner(&p.seg, &seg, d).map_err(|e| gouge(cx, e, at))?;
            edit_pending_end(cx, p, c.prev_end);
            (c.next_start, c.arc)
        }
    };
    if let Some(Seg2::Arc { c, sweep, .. }) = arc {
        let to = pose(cx, start, &cx.st.program_position());
        emit_arc(cx, sweep > 0.0, to, c, at)?;
    }
    let q_end = comp::end_point(&seg, d).map_err(|e| gouge(cx, e, at))?;
    let target = pose(cx, q_end, &end);
    let index = match seg {
        Seg2::Line { .. } => emit_line(cx, rapid, target, at)?,
        Seg2::Arc { c, sweep, .. } => emit_arc(cx, sweep > 0.0, target, c, at)?,
    };
    cx.fe.comp.pending = Some(Pending {
        seg,
        tool_start: start,
        index,
        startup: false,
        rapid,
    });
    cx.fe.comp.programmed = Some(b);
    Ok(())
}

/// The look-ahead ends: the pending element keeps its provisional end (final now).
pub(crate) fn settle(cx: &mut Ctx<'_>) {
    cx.fe.comp.pending = None;
}

/// How many commands at the back of the queue the compensation still may change.
pub(crate) fn held(state: &CompState, queue_len: usize) -> usize {
    match state.pending {
        Some(p) if p.index < queue_len => queue_len - p.index,
        _ => 0,
    }
}

/// The front command left the queue: the pending index moves down.
pub(crate) fn released(state: &mut CompState) {
    if let Some(p) = &mut state.pending {
        p.index = p.index.saturating_sub(1);
    }
}

/// Restores an edited pending command (the editing block failed).
pub(crate) fn restore(
    backup: Option<(usize, Spanned<Canon>)>,
    queue: &mut std::collections::VecDeque<Spanned<Canon>>,
) {
    if let Some((i, c)) = backup {
        if let Some(slot) = queue.get_mut(i) {
            *slot = c;
        }
    }
}
