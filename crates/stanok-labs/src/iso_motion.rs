//! The block's motion in the word-address lab dialects: axis words, the work origin, the per-axis
//! correction binding (§4.8), G92, G28, straight moves and arcs. Part of [`super::iso`]'s `Exec`.

use super::iso::{Exec, Gs};
use super::iso_arcs::{arc, ArcInput};
use super::iso_words::{axis_index, checked_dimension, code, correction, err, number, Pending};
use crate::codes::{self, iso as iso_codes, iso::Handler};
use stanok_canon::{ArcMove, Canon, Diagnostic, LineMove, Pose, Span};
use stanok_interp_core::state::MotionMode;
use stanok_syntax::labs::words::{Item, Word};
use stanok_syntax::Dialect;

/// GOST-20999: the largest move of one block, mm or degrees (§4.3).
const MAX_MOVE: f64 = 9999.999;

/// The axes of a `Pose` array, in order.
const AXIS_NAMES: [char; 9] = ['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'];

impl Exec<'_> {
    /// The work origin of `axis` (machine mm): the active G54/G55 offset plus the G92 shift.
    pub(super) fn origin(&self, axis: usize) -> f64 {
        let k = match axis {
            0..=2 => axis,
            3 => 3,
            _ => return 0.0,
        };
        let ws = (self.st.work_system.clamp(1, 2) - 1) as usize;
        self.opts.labs.work_offsets[ws][k] + self.st.g92_shift[k]
    }

    pub(super) fn program_position(&self, axis: usize) -> f64 {
        self.st.position.to_array()[axis] - self.origin(axis) - self.st.applied_correction[axis]
    }

    /// The axis words of the block as (axis index, value, word): lengths in mm, angles in degrees.
    /// 2P32: Y is the spindle angle (C) after M89 (0.001° per count, like a length count).
    pub(super) fn axis_words(&self) -> Result<Vec<(usize, f64, Word)>, Diagnostic> {
        let mut v = Vec::new();
        for w in self.words() {
            let Some(mut axis) = axis_index(w.letter) else {
                continue;
            };
            if self.dialect == Dialect::P2p32 && w.letter == 'Y' {
                if !self.st.servo_spindle {
                    return Err(err(
                        "lab::y-without-servo",
                        "Y (spindle angle) needs the servo spindle mode M89",
                        w.span,
                    ));
                }
                axis = 5;
            }
            if !self.opts.axes[axis] {
                return Err(err(
                    "interp::axis-not-configured",
                    format!("{} axis is not configured on this machine", w.letter),
                    w.span,
                ));
            }
            let n = number(w, self.st)?;
            v.push((axis, checked_dimension(self.dialect, n, w)?, *w));
        }
        Ok(v)
    }

    /// G92: the tool's position in the current work system becomes the programmed values; the
    /// shift applies to both work systems (§4.7). No motion.
    pub(super) fn set_position(&mut self, _at: Span) -> Result<(), Diagnostic> {
        for (axis, v, _) in self.axis_words()? {
            if axis > 3 {
                continue;
            }
            let machine = self.st.position.to_array()[axis];
            let ws = (self.st.work_system.clamp(1, 2) - 1) as usize;
            let base = self.opts.labs.work_offsets[ws][axis];
            self.st.g92_shift[axis] = machine - self.st.applied_correction[axis] - v - base;
        }
        Ok(())
    }

    /// G28: the named axes return home at rapid; the G92 shift is cancelled (§4.4). GOST-20999:
    /// home = parameters 163–166 (machine data); 2P32 and MC2101: the position the program started
    /// from (the set-up examples start at home). 2P32 G28 with G40 also drops the corrections.
    pub(super) fn home(&mut self) -> Result<(), Diagnostic> {
        let words = self.axis_words()?;
        if words.is_empty() {
            return Err(err(
                "lab::home-axes",
                "G28 names the axes to home with axis words",
                self.block.span,
            ));
        }
        let mut end = self.st.position.to_array();
        let start = self.opts.initial_position.to_array();
        for (axis, _, _) in &words {
            let axis = *axis;
            end[axis] = match self.dialect {
                Dialect::Gost20999 if axis < 4 => self.opts.labs.home[axis],
                _ => start[axis],
            };
            self.st.applied_correction[axis] = if self.dialect == Dialect::P2p32 {
                0.0
            } else {
                self.st.applied_correction[axis]
            };
        }
        self.st.g92_shift = [0.0; 4];
        self.traverse(Pose::from_array(end));
        Ok(())
    }

    pub(super) fn motion(&mut self, gs: &Gs, comp_before: i8) -> Result<(), Diagnostic> {
        let comp = self.st.radius_comp.0;
        let starts_comp = comp != 0 && comp_before == 0;
        let ends_comp = comp == 0 && comp_before != 0;
        // Radius corrector: the first D after G41/G42 in the block.
        let mut radius_d = None;
        if gs.comp.is_some_and(|c| c != 0) {
            let mut after_g4x = false;
            let words: Vec<Word> = self.words().copied().collect();
            for w in &words {
                let starts_radius_comp = |g| {
                    codes::lookup(g, iso_codes::g_code)
                        .is_some_and(|c| matches!(c.handler, Handler::SetRadiusComp(1 | -1)))
                };
                if w.letter == 'G'
                    && matches!(w.value.map(|_| code(w, self.st)), Some(Ok(g)) if starts_radius_comp(g))
                {
                    after_g4x = true;
                } else if w.letter == 'D' && after_g4x {
                    radius_d = Some(w.span);
                    let d = code(w, self.st)? as u32;
                    self.st.radius_comp.1 = Some(d);
                    // An unset corrector is radius 0: say so, as AxiOMA does for an unknown
                    // tool (issue 22 item 18).
                    if !self.opts.labs.correctors.contains_key(&d) {
                        self.warnings.push(
                            Diagnostic::warning(
                                "lab::unset-corrector",
                                format!("corrector D{d} is not set: the compensation radius is 0"),
                                w.span,
                            )
                            .with_note(format!("set it with --corrector {d}=<radius mm>")),
                        );
                    }
                    break;
                }
            }
        }
        // Per-axis correction binding, left to right (§4.8).
        let mut pending = self.st.pending;
        let mut had_g49 = false;
        let mut programmed = [None; 9];
        let axis_words = self.axis_words()?;
        for item in &self.block.items {
            let Item::Word(w) = item else { continue };
            match w.letter {
                'G' => match w
                    .value
                    .map(|_| code(w, self.st))
                    .transpose()?
                    .and_then(|g| codes::lookup(g, iso_codes::g_code))
                    .map(|c| c.handler)
                {
                    Some(Handler::LengthBinding(Some(mode))) => pending.mode = Some(mode),
                    Some(Handler::LengthBinding(None)) => {
                        had_g49 = true;
                        self.st.axis_correction = [(0, None); 9];
                        pending = Pending::default();
                    }
                    _ => {}
                },
                'D' if Some(w.span) != radius_d => {
                    pending.corrector = Some(code(w, self.st)? as u32)
                }
                _ => {
                    if let Some((axis, v, _)) =
                        axis_words.iter().find(|(_, _, aw)| aw.span == w.span)
                    {
                        pending.bind(self.st, *axis);
                        programmed[*axis] = Some(*v);
                    }
                }
            }
        }
        if had_g49 && (pending.is_some() || self.words().any(|w| w.letter == 'D')) {
            return Err(err(
                "lab::g49-with-correction",
                "a G49 block must not contain G43, G44 or D",
                self.block.span,
            ));
        }
        let circular = matches!(self.st.motion, MotionMode::ArcCw | MotionMode::ArcCcw);
        if circular && gs.lengths {
            return Err(err(
                "lab::correction-in-arc",
                "no length correction may be set in a circular block (§4.8)",
                self.block.span,
            )
            .with_note("set it in a linear block: the whole contour then shifts"));
        }
        self.st.pending = pending;
        if circular && (starts_comp || ends_comp) {
            return Err(Diagnostic::manual(
                35,
                "G2/G3 in a compensation start-up or G40 block",
                self.block.span,
            )
            .with_note("start and end cutter compensation with a G0 or G1 block"));
        }
        // The start-up and exit blocks of radius compensation (§4.9 [doc]): the start-up block
        // names its corrector with D and moves in the compensation plane; the G40 block holds at
        // least one coordinate of the plane. Without them the control cannot build the offset
        // path's first or last element.
        let (pa, pb, _) = self.st.plane.axes();
        let in_plane = programmed[pa].is_some() || programmed[pb].is_some();
        if starts_comp && radius_d.is_none() {
            return Err(err(
                "lab::startup-without-d",
                "the cutter compensation start-up block needs D with the radius corrector",
                self.block.span,
            )
            .with_note("write G41/G42 followed by D<n> in the same block (§4.9)"));
        }
        if starts_comp && !in_plane {
            return Err(err(
                "lab::startup-without-plane-motion",
                "the cutter compensation start-up block must move in the compensation plane",
                self.block.span,
            )
            .with_note("give an end point in the plane chosen by G17/G18/G19 (§4.9)"));
        }
        if ends_comp && !in_plane {
            return Err(err(
                "lab::g40-without-plane-coordinate",
                "the G40 block must contain a coordinate of the compensation plane",
                self.block.span,
            )
            .with_note("the tool leaves the contour along this block's move in the plane (§4.9)"));
        }
        let any_axis = programmed.iter().any(Option::is_some);
        // G91 full circle: centre words and no end point (`N51 G2 G91 I30`).
        let full_circle_g91 = circular
            && self.st.incremental
            && self.words().any(|w| matches!(w.letter, 'I' | 'J' | 'K'));
        if !any_axis && !full_circle_g91 {
            self.check_unused(circular)?;
            return Ok(());
        }
        if !circular {
            self.check_unused(false)?;
        }
        // End point in machine coordinates.
        let mut end = self.st.position.to_array();
        for (axis, v) in programmed.iter().enumerate() {
            let Some(v) = *v else { continue };
            if gs.g53 {
                end[axis] = if self.st.incremental {
                    end[axis] + v
                } else {
                    v
                };
                self.st.applied_correction[axis] = 0.0;
                continue;
            }
            let p = if self.st.incremental {
                self.program_position(axis) + v
            } else {
                v
            };
            let c = correction(self.st, axis, self.opts);
            self.st.applied_correction[axis] = c;
            end[axis] = p + self.origin(axis) + c;
        }
        // GOST-20999 §4.3: "the largest move in one block is ±9999.999 mm (or degrees)" — the
        // word format's reach, which an absolute end far from the start can exceed.
        if self.dialect == Dialect::Gost20999 {
            let start = self.st.position.to_array();
            if let Some(axis) = (0..9).find(|&k| (end[k] - start[k]).abs() > MAX_MOVE + 1e-9) {
                return Err(err(
                    "lab::move-too-long",
                    format!(
                        "this block moves {} by {:.3}: more than ±{MAX_MOVE:.3}, the largest move of one block",
                        AXIS_NAMES[axis],
                        end[axis] - start[axis]
                    ),
                    self.block.span,
                )
                .with_note("split the move into blocks of at most 9999.999 each (§4.3)"));
            }
        }
        let end = Pose::from_array(end);
        match self.st.motion {
            MotionMode::Rapid | MotionMode::None => self.traverse(end),
            MotionMode::Linear => {
                let feed = self.st.feed;
                let f = self.st.path_feed(feed, self.block.span, self.warnings);
                self.out.push(Canon::StraightFeed(LineMove {
                    start: self.st.position,
                    end,
                    feed: f,
                    law: stanok_canon::FeedLaw::PerMinute,
                }));
                self.st.position = end;
            }
            m => self.arc_move(m == MotionMode::ArcCcw, end)?,
        }
        Ok(())
    }

    /// I, J, K, R words in a block that does not use them.
    pub(super) fn check_unused(&self, circular: bool) -> Result<(), Diagnostic> {
        if circular {
            return Ok(());
        }
        // I/J/K in a G1 block are the compensation's look-ahead over a break (§4.9).
        let comp = self.st.radius_comp.0 != 0;
        for w in self.words() {
            let stray = match w.letter {
                'I' | 'J' | 'K' => !comp,
                'R' => true,
                _ => false,
            };
            if stray {
                return Err(err(
                    "lab::unused-word",
                    format!("{} has no meaning in this block", w.letter),
                    w.span,
                ));
            }
        }
        Ok(())
    }

    pub(super) fn arc_move(&mut self, ccw: bool, end: Pose) -> Result<(), Diagnostic> {
        let mut ijk = [None; 3];
        for (k, l) in ['I', 'J', 'K'].into_iter().enumerate() {
            if let Some(w) = self.word(l) {
                ijk[k] = Some(checked_dimension(self.dialect, number(w, self.st)?, w)?);
            }
        }
        let radius = match self.word('R') {
            Some(w) => Some(checked_dimension(self.dialect, number(w, self.st)?, w)?),
            None => None,
        };
        let plane = self.st.plane;
        let out = arc(&ArcInput {
            ccw,
            plane,
            start: self.st.position.xyz(),
            end: end.xyz(),
            ijk,
            radius,
            unsigned_start_minus_centre: self.dialect == Dialect::Mc2101,
            tol: self.opts.arc_tolerance_mm,
            span: self.block.span,
        })?;
        // F is the feed along the arc (§4.5): the Canon feed is along the whole helix.
        let (_, _, n) = plane.axes();
        let dn = end.xyz()[n] - self.st.position.xyz()[n];
        let helix = out.planar_length.hypot(dn);
        let feed = self.st.feed;
        let mut f = self.st.path_feed(feed, self.block.span, self.warnings);
        if out.planar_length > 0.0 {
            f *= helix / out.planar_length;
        }
        let mut axis = [0.0; 3];
        axis[n] = if ccw { 1.0 } else { -1.0 };
        self.out.push(Canon::ArcFeed(ArcMove {
            start: self.st.position,
            end,
            centre: out.centre,
            axis,
            turns: out.turns,
            plane,
            feed: f,
            law: stanok_canon::FeedLaw::PerMinute,
        }));
        self.st.position = end;
        Ok(())
    }

    pub(super) fn traverse(&mut self, end: Pose) {
        self.out.push(Canon::StraightTraverse(LineMove {
            start: self.st.position,
            end,
            feed: 0.0,
            law: stanok_canon::FeedLaw::PerMinute,
        }));
        self.st.position = end;
    }
}
