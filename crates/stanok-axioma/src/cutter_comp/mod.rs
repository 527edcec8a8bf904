//! AxiOMA tool radius compensation G40/G41/G42/G143/G144 (spec axioma-3 §4, manual 9.2): the
//! state machine between the blocks and the geometry in `contour.rs`.
//!
//! ```text
//!          G41/G42 (entry: next in-plane line)         G40 (exit: next in-plane line)
//!   Off ───────────────────────────────▶ Left/Right ───────────────────────────────▶ Off
//!    │ ▲  G143/G144                        │  ▲ G41/G42 (no entry move: the element
//!    ▼ │  G40: offsets removed per axis    ▼  │  starts at its own offset start)
//!   Outside/Inside (per-axis offset o) ◀───┘ G143/G144: the last element ends at its
//!                                            perpendicular point, o = d·n
//! ```
//! Positions: `ModalState::position` stays the *programmed* point (G91 increments are relative to
//! it, §4.9); `Comp::tool` is the real tool-centre position whenever it differs. Under G41/G42
//! every in-plane motion becomes an element of the look-ahead window and is emitted when it is
//! finalised (at its slot among the held commands, see `extension.rs`); non-plane motions become
//! events of the element before them, run at the tool position reached then (§4.5.8).
//!
//! Decisions: r = r1 + wear(r1) of the active edge (A10), 0 with T0/D0 (§2.3); r < 0 → error; the
//! path is computed in program coordinates with r divided by the in-plane scale (the radius is
//! never scaled; unequal in-plane scale → error); a mirror swaps the sides by itself. Turning
//! tools: the whole path is shifted by r·v of the edge position (A9). Arcs under G143/G144, or
//! with offsets G40 has not removed yet → error (A11). Errors have no manual number (§4.10).

pub mod contour;
mod emit;
mod touch;

use crate::arc::PlanarArc;
use crate::ctx::Ctx;
use contour::{ContourError, Elem, Event, Head, Kind, Tag};
use emit::{arc_canon, line_canon, with_non_plane};
use stanok_canon::setup::ToolKind;
use stanok_canon::{Canon, Diagnostic, Pose, Span, Spanned};
use stanok_geom::offset2d::{dist2, Seg2, LEN_EPS, P2};
use stanok_syntax::ColSpan;
use std::collections::VecDeque;

/// Group EqCorrect.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CompMode {
    /// G40.
    #[default]
    Off,
    /// G41.
    Left,
    /// G42.
    Right,
    /// G143: stop one radius before the end point.
    Outside,
    /// G144: go one radius beyond the end point.
    Inside,
}

/// Compensation state (part of `Extension`, restored on a failing block).
#[derive(Debug, Clone, Default)]
pub struct Comp {
    /// The active function.
    pub mode: CompMode,
    /// M905 N1= look-ahead depth (None = the machine parameter).
    pub depth: Option<usize>,
    /// Per-axis plane offset of G143/G144 that G40 has not removed yet (tool − programmed).
    pub(super) offset: [f64; 2],
    /// The tool-centre position when it differs from the programmed point (program coordinates).
    pub(super) tool: Option<Pose>,
    entry_pending: bool,
    /// Blocks left in which a G00/G01 must come after G40/G41/G42/G143/G144 was selected
    /// (spec axioma-3 §4.3 rule 1: the selection block or the next one); 0 = none due.
    linear_due: u8,
    free_start: bool,
    exit_pending: bool,
    window: VecDeque<Elem>,
    head: Head,
    last: Option<Box<Elem>>,
    /// Edge vector r·v of a turning tool (plane components).
    tip: P2,
    ready: Vec<(u64, Spanned<Canon>)>,
}

/// Most non-plane blocks held between two compensated elements.
const MAX_EVENTS: usize = 10_000;

fn diag(code: &'static str, msg: impl Into<String>, span: Span) -> Diagnostic {
    Diagnostic::error(code, msg, span)
}

impl Comp {
    /// Anything of compensation acts on the next motion.
    pub fn is_active(&self) -> bool {
        self.mode != CompMode::Off
            || self.offset != [0.0, 0.0]
            || self.exit_pending
            || !self.window.is_empty()
    }

    fn contour(&self) -> bool {
        matches!(self.mode, CompMode::Left | CompMode::Right)
            || self.exit_pending
            || !self.window.is_empty()
    }

    /// The contour is being compensated (M905 and the forbidden words check this).
    pub fn in_contour(&self) -> bool {
        self.contour()
    }

    /// Slot of the first motion still waiting for the look-ahead.
    pub fn first_unresolved_slot(&self) -> Option<u64> {
        self.window.front().map(|e| e.tag.slot)
    }

    /// Takes the finalised motions.
    pub fn take_ready(&mut self) -> Vec<(u64, Spanned<Canon>)> {
        std::mem::take(&mut self.ready)
    }

    fn tool_pose(&self, cx: &Ctx<'_>) -> Pose {
        self.tool.unwrap_or_else(|| cx.st.program_position())
    }

    /// G40 (400), G41 (410), G42 (420), G143 (1430), G144 (1440) in a block.
    pub fn select(cx: &mut Ctx<'_>, code: u32, at: ColSpan) -> Result<(), Diagnostic> {
        let mode = cx.fe.ext.comp.mode;
        let new = match code {
            400 => CompMode::Off,
            410 => CompMode::Left,
            420 => CompMode::Right,
            1430 => CompMode::Outside,
            _ => CompMode::Inside,
        };
        if new == mode {
            return Ok(());
        }
        let c = &mut cx.fe.ext.comp;
        match new {
            CompMode::Off => {
                if matches!(mode, CompMode::Left | CompMode::Right) {
                    if c.entry_pending {
                        c.entry_pending = false;
                    } else {
                        c.exit_pending = true;
                    }
                }
                c.free_start = false;
            }
            CompMode::Left | CompMode::Right => {
                if matches!(mode, CompMode::Left | CompMode::Right) || c.exit_pending {
                    return Err(cx
                        .err(
                            "axioma::comp-side-change",
                            "G41 and G42 cannot be switched directly",
                            at,
                        )
                        .with_note(
                            "cancel with G40 (and its exit block) first (spec axioma-3 §4.4)",
                        ));
                }
                if c.offset == [0.0, 0.0] && mode == CompMode::Off {
                    c.entry_pending = true;
                } else {
                    c.free_start = true;
                }
            }
            CompMode::Outside | CompMode::Inside => {
                if c.exit_pending {
                    return Err(cx.err(
                        "axioma::comp-exit-pending",
                        "G143/G144 after G40 before the exit block of G41/G42",
                        at,
                    ));
                }
                if matches!(mode, CompMode::Left | CompMode::Right) {
                    // The last element ends at its perpendicular point; its offset is kept per axis.
                    let span = cx.block.span();
                    c.flush(span)?;
                    if let Some(last) = c.last.take() {
                        c.offset = contour::end_offset(&last);
                    }
                    c.head = Head::Own;
                    c.entry_pending = false;
                    c.free_start = false;
                }
            }
        }
        // Switching on from off (or G40 ending G41/G42) must be realised by a linear block; a
        // switch between G143/G144 and G41/G42 is already realised (the unlabelled example after
        // 9.13 selects G42 in a block without motion after G143 and goes on with G02).
        let realise = match new {
            CompMode::Off => matches!(mode, CompMode::Left | CompMode::Right),
            _ => mode == CompMode::Off,
        };
        cx.fe.ext.comp.mode = new;
        if realise {
            cx.fe.ext.comp.linear_due = 2;
        }
        Ok(())
    }

    /// End of a block: after a selection, G00/G01 must have come in the selection block or the
    /// next one (spec axioma-3 §4.3 rule 1, error [D]; "programmed" means modally active, as
    /// example 9.4's `N3 G41 X0 Y0` after `G01` shows).
    pub fn end_of_block(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
        let c = &mut cx.fe.ext.comp;
        if c.linear_due == 0 {
            return Ok(());
        }
        c.linear_due -= 1;
        if c.linear_due == 0 {
            return Err(cx
                .err(
                    "axioma::comp-linear-due",
                    "G00 or G01 must follow G40/G41/G42/G143/G144 in the same or the next block",
                    cx.whole(),
                )
                .with_note(
                    "the compensation is realised by that linear block (spec axioma-3 §4.3)",
                ));
        }
        Ok(())
    }

    /// Cutter radius for the current tool and edge, in program units of the plane.
    fn radius(cx: &Ctx<'_>, at: ColSpan) -> Result<(f64, P2), Diagnostic> {
        let (t, e) = (cx.st.current_tool, cx.fe.modes.edge);
        if t == 0 || e == 0 {
            return Ok((0.0, [0.0, 0.0]));
        }
        let Some(edge) = cx.opts.control.tools.edge(t, e as u32) else {
            return Ok((0.0, [0.0, 0.0]));
        };
        let r = edge.radius + edge.radius_wear;
        if r < 0.0 || !r.is_finite() {
            return Err(cx.err(
                "axioma::comp-negative-radius",
                format!(
                    "T{t} D{e}: the radius {r} mm is negative: radius compensation needs r ≥ 0"
                ),
                at,
            ));
        }
        let (a, b, _) = cx.st.plane.axes();
        let m = cx.st.frame.linear();
        let k = |i: usize| (0..3).map(|row| m[row][i] * m[row][i]).sum::<f64>().sqrt();
        let (ka, kb) = (k(a), k(b));
        if (ka - kb).abs() > 1e-9 || ka < 1e-12 {
            return Err(cx.err(
                "axioma::comp-unequal-scale",
                "radius compensation under unequal in-plane scale factors is not supported",
                at,
            ));
        }
        let r = r / ka;
        let turning = cx
            .opts
            .control
            .tools
            .get(t)
            .is_some_and(|tool| matches!(tool.kind, ToolKind::Turning | ToolKind::Grinding));
        let v = if turning {
            cx.fe.params.edge_positions[(edge.orientation as usize).min(9)]
        } else {
            [0.0, 0.0]
        };
        Ok((r, [r * v[0], r * v[1]]))
    }

    fn tag(cx: &Ctx<'_>) -> Tag {
        Tag {
            span: cx.out.span,
            number: cx.out.number,
            slot: cx.fe.ext.held_base + cx.out.queue.len() as u64,
            frame: *cx.st.frame,
            plane: cx.st.plane,
        }
    }

    /// A G00/G01 block while compensation is active (`end` in program coordinates).
    pub fn line(
        cx: &mut Ctx<'_>,
        rapid: bool,
        end: Pose,
        feed: f64,
        at: ColSpan,
    ) -> Result<(), Diagnostic> {
        cx.fe.ext.comp.linear_due = 0;
        cx.apply_pending_tlo();
        let (a, b, _) = cx.st.plane.axes();
        let p0 = cx.st.program_position().to_array();
        let p1 = end.to_array();
        let (s, e) = ([p0[a], p0[b]], [p1[a], p1[b]]);
        let in_plane = dist2(s, e) > 1e-12;
        let tag = Self::tag(cx);
        let fallback_feed = if rapid { cx.st.feed } else { feed };
        if cx.fe.ext.comp.contour() {
            let (r, tip) = Self::radius(cx, at)?;
            let mut c = std::mem::take(&mut cx.fe.ext.comp);
            let result = c.contour_line(
                cx,
                rapid,
                end,
                fallback_feed,
                [s, e],
                in_plane,
                (r, tip),
                tag,
                at,
            );
            cx.fe.ext.comp = c;
            result?;
        } else {
            let (r, _) = Self::radius(cx, at)?;
            touch::line(cx, r, rapid, end, feed, tag);
        }
        cx.st.position = cx.st.frame.to_machine(&end);
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    fn contour_line(
        &mut self,
        cx: &mut Ctx<'_>,
        rapid: bool,
        end: Pose,
        feed: f64,
        [s, e]: [P2; 2],
        in_plane: bool,
        (r, tip): (f64, P2),
        tag: Tag,
        at: ColSpan,
    ) -> Result<(), Diagnostic> {
        let d = if self.mode == CompMode::Right || (self.exit_pending && self.last_side() < 0.0) {
            -r
        } else {
            r
        };
        if !in_plane {
            let ev = Event {
                end,
                rapid,
                feed,
                tag,
            };
            if self.window.is_empty() {
                let from = self.tool_pose(cx);
                let to = with_non_plane(from, end, tag.plane);
                self.tool = self.tool.map(|_| to);
                cx.out.push(line_canon(&tag, from, to, rapid, feed).value);
            } else if let Some(last) = self.window.back_mut() {
                // A18: any number of blocks without plane motion — bounded, so memory is too.
                if last.events.len() >= MAX_EVENTS {
                    return Err(cx.err(
                        "axioma::comp-too-many-events",
                        format!("more than {MAX_EVENTS} blocks without motion in the plane between two compensated elements"),
                        at,
                    ));
                }
                last.events.push(ev);
            }
            return Ok(());
        }
        self.tip = tip;
        let seg = Seg2::Line { a: s, b: e };
        let kind = if self.entry_pending {
            let from = self.tool_pose(cx).to_array();
            let (a, b, _) = tag.plane.axes();
            let from = [from[a] - tip[0], from[b] - tip[1]];
            if dist2(from, e) <= r + LEN_EPS && r > 0.0 {
                return Err(cx
                    .err("axioma::comp-entry-too-close", "the entry block ends within one tool radius of its start", at)
                    .with_note("on entry the distance to the contour must be greater than the tool radius (spec axioma-3 §4.3)"));
            }
            self.entry_pending = false;
            self.head = Head::Own;
            Kind::Entry { from }
        } else if self.exit_pending {
            Kind::Exit
        } else {
            Kind::Contour
        };
        let mut elem = Elem {
            seg,
            kind,
            d,
            end,
            rapid,
            feed,
            tag,
            events: Vec::new(),
        };
        if self.free_start {
            self.free_start = false;
            self.head = Head::Own;
            let here = self.plane_tool(cx, tag);
            if dist2(contour::own_start(&elem), here) > 1e-3 {
                elem.kind = Kind::Entry { from: here };
            }
            self.offset = [0.0, 0.0];
        }
        if self.tool.is_none() {
            self.tool = Some(self.tool_pose(cx));
        }
        let exit = elem.kind == Kind::Exit;
        self.window.push_back(elem);
        if exit {
            self.flush(cx.block.span())?;
            self.exit_pending = false;
            self.tool = None;
            self.offset = [0.0, 0.0];
            // Nothing of the finished contour is needed any more (keeps the per-block backup small).
            self.last = None;
            self.head = Head::Own;
        } else {
            self.advance(cx.block.span(), cx.fe.params.comp_depth)?;
        }
        Ok(())
    }

    fn last_side(&self) -> f64 {
        self.window
            .back()
            .or(self.last.as_deref())
            .map(|e| e.d.signum())
            .unwrap_or(1.0)
    }

    /// Tool position in the plane, minus the edge vector (the path's own coordinates).
    fn plane_tool(&self, cx: &Ctx<'_>, tag: Tag) -> P2 {
        let p = self.tool_pose(cx).to_array();
        let (a, b, _) = tag.plane.axes();
        [p[a] - self.tip[0], p[b] - self.tip[1]]
    }

    /// A G02/G03 block while compensation is active.
    #[allow(clippy::too_many_arguments)]
    pub fn arc(
        cx: &mut Ctx<'_>,
        ccw: bool,
        start: Pose,
        end: Pose,
        planar: PlanarArc,
        feed: f64,
        at: ColSpan,
    ) -> Result<(), Diagnostic> {
        cx.apply_pending_tlo();
        let c = &cx.fe.ext.comp;
        let why = match c.mode {
            CompMode::Inside => Some("G02/G03 are not allowed while G144 is active"),
            CompMode::Outside => Some("G02/G03 are not allowed while G143 is active (spec A11)"),
            CompMode::Off if !c.exit_pending => {
                Some("G02/G03 while G40 has not yet removed the G143/G144 offset of an axis")
            }
            _ if c.entry_pending => {
                Some("the entry into radius compensation must be a linear block (G00/G01)")
            }
            _ if c.exit_pending => {
                Some("the exit from radius compensation must be a linear block (G00/G01)")
            }
            _ if planar.turns > 1 => Some("arcs with additional turns cannot be compensated"),
            _ => None,
        };
        if let Some(why) = why {
            return Err(cx.err("axioma::comp-arc", why, at));
        }
        let (r, tip) = Self::radius(cx, at)?;
        let (a, b, _) = cx.st.plane.axes();
        let (p0, p1) = (start.to_array(), end.to_array());
        let (s, e) = ([p0[a], p0[b]], [p1[a], p1[b]]);
        let seg = Seg2::arc_through(planar.centre, s, e, ccw, true);
        let d = if cx.fe.ext.comp.mode == CompMode::Right {
            -r
        } else {
            r
        };
        if seg.offset_left(d).is_none() {
            return Err(cx
                .err("axioma::comp-radius", "the arc radius cannot be compensated: the tool does not fit inside it", at)
                .with_note(format!("arc radius {:.4} mm ≤ tool radius {r:.4} mm on the concave side (spec axioma-3 §4.5.3)", dist2(planar.centre, s))));
        }
        let tag = Self::tag(cx);
        let elem = Elem {
            seg,
            kind: Kind::Contour,
            d,
            end,
            rapid: false,
            feed,
            tag,
            events: Vec::new(),
        };
        let mut c = std::mem::take(&mut cx.fe.ext.comp);
        let result = (|| {
            c.tip = tip;
            if c.free_start {
                c.free_start = false;
                c.head = Head::Own;
                let here = c.plane_tool(cx, tag);
                if dist2(contour::own_start(&elem), here) > 1e-3 {
                    return Err(cx.err("axioma::comp-switch-position", "after G143/G144 the compensated arc must start at the current tool position", at));
                }
                c.offset = [0.0, 0.0];
            }
            if c.tool.is_none() {
                c.tool = Some(c.tool_pose(cx));
            }
            c.window.push_back(elem);
            c.advance(cx.block.span(), cx.fe.params.comp_depth)
        })();
        cx.fe.ext.comp = c;
        result?;
        cx.st.position = cx.st.frame.to_machine(&end);
        Ok(())
    }

    /// Finalises front elements while the window holds `depth` of them.
    fn advance(&mut self, span: Span, machine_depth: usize) -> Result<(), Diagnostic> {
        let depth = self.depth.unwrap_or(machine_depth).max(2);
        let mut guard = 0;
        while self.window.len() >= depth && guard < 10_000 {
            self.finalise_front(depth, span)?;
            guard += 1;
        }
        Ok(())
    }

    /// Ends the path: every element is finalised, the last one at its perpendicular point.
    fn flush(&mut self, span: Span) -> Result<(), Diagnostic> {
        let mut guard = 0;
        while !self.window.is_empty() && guard < 10_000 {
            let n = self.window.len();
            self.finalise_front(n, span)?;
            guard += 1;
        }
        Ok(())
    }

    fn finalise_front(&mut self, depth: usize, span: Span) -> Result<(), Diagnostic> {
        let n = depth.min(self.window.len());
        let window = self.window.make_contiguous();
        let fin = contour::finalise(&window[..n], &self.head).map_err(|e| match e {
            ContourError::NoIntersection { at } => diag(
                "axioma::comp-no-intersection",
                format!("radius compensation: the equidistants do not intersect at the inner corner ({:.4}, {:.4})", at[0], at[1]),
                span,
            ),
            ContourError::EntryTooClose => diag(
                "axioma::comp-entry-too-close",
                "radius compensation: the entry point lies behind the start point (start closer than the tool radius to the contour)",
                span,
            ),
            ContourError::TooNarrow { span: owner } => diag(
                "axioma::comp-contour-violation",
                format!("radius compensation: the contour at line {} is narrower than the tool and the look-ahead window does not bypass it", owner.line),
                span,
            )
            .with_note("increase the look-ahead depth with M905 N1=… or use a smaller tool (spec axioma-3 §4.6)"),
        })?;
        let Some(front) = self.window.pop_front() else {
            return Ok(());
        };
        self.emit(&front, &fin.path)?;
        for _ in 0..fin.dropped {
            if let Some(dropped) = self.window.pop_front() {
                self.emit_events(&dropped);
            }
        }
        self.head = fin.next_head;
        self.last = Some(Box::new(front));
        Ok(())
    }

    fn emit(&mut self, e: &Elem, path: &[contour::PathSeg]) -> Result<(), Diagnostic> {
        let (a, b, _) = e.tag.plane.axes();
        let mut tool = self.tool.unwrap_or(e.end);
        for ps in path {
            let mut to = if ps.main {
                e.end.to_array()
            } else {
                tool.to_array()
            };
            let end = ps.seg.end();
            let tip = if e.kind == Kind::Exit && ps.main {
                [0.0, 0.0]
            } else {
                self.tip
            };
            to[a] = end[0] + tip[0];
            to[b] = end[1] + tip[1];
            let to = Pose::from_array(to);
            let canon = match ps.seg {
                Seg2::Line { .. } => line_canon(&e.tag, tool, to, e.rapid, e.feed),
                Seg2::Arc { c, sweep, .. } => {
                    if e.rapid && e.feed <= 0.0 {
                        return Err(diag("axioma::comp-rapid-corner", "a compensated rapid move turns an outer corner: program a feed F for its corner arc", e.tag.span));
                    }
                    arc_canon(
                        &e.tag,
                        tool,
                        to,
                        [c[0] + self.tip[0], c[1] + self.tip[1]],
                        sweep > 0.0,
                        e.feed,
                    )
                }
            };
            self.ready.push((e.tag.slot, canon));
            tool = to;
        }
        self.tool = Some(tool);
        self.emit_events(e);
        Ok(())
    }

    fn emit_events(&mut self, e: &Elem) {
        for ev in &e.events {
            let from = self.tool.unwrap_or(ev.end);
            let to = with_non_plane(from, ev.end, ev.tag.plane);
            self.ready.push((
                ev.tag.slot,
                line_canon(&ev.tag, from, to, ev.rapid, ev.feed),
            ));
            self.tool = Some(to);
        }
    }

    /// M02/M30 or the end of the text: the path ends; a warning if G40 is missing.
    pub fn end_of_program(
        &mut self,
        span: Span,
        warnings: &mut Vec<Diagnostic>,
    ) -> Result<(), Diagnostic> {
        if matches!(self.mode, CompMode::Left | CompMode::Right) && !self.window.is_empty() {
            warnings.push(
                Diagnostic::warning(
                    "axioma::comp-active-at-end",
                    "the program ends with radius compensation G41/G42 active",
                    span,
                )
                .with_note("program G40 with an exit block before the end (spec axioma-3 §4.1)"),
            );
        }
        self.flush(span)
    }

    /// End of the program text (fragment without M30).
    pub fn flush_at_end(&mut self, warnings: &mut Vec<Diagnostic>) -> Result<(), Diagnostic> {
        let span = self.window.back().map(|e| e.tag.span).unwrap_or_default();
        self.end_of_program(span, warnings)
    }

    /// M905 [N1=n | H1=n]: the look-ahead depth (forbidden inside the compensated contour).
    pub fn set_depth(cx: &mut Ctx<'_>, depth: Option<f64>, at: ColSpan) -> Result<(), Diagnostic> {
        if cx.fe.ext.comp.in_contour() {
            return Err(cx.err(
                "axioma::m905-in-contour",
                "M905 cannot change the look-ahead depth inside the compensated contour",
                at,
            ));
        }
        cx.fe.ext.comp.depth = match depth {
            None => None,
            Some(v) if v.fract() == 0.0 && (2.0..=64.0).contains(&v) => Some(v as usize),
            Some(v) => {
                return Err(cx
                    .err(
                        "axioma::m905-depth",
                        format!("M905: look-ahead depth {v} is not allowed"),
                        at,
                    )
                    .with_note("the depth is a whole number of blocks, 2 … 64"))
            }
        };
        Ok(())
    }
}
