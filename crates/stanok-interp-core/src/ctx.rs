//! The context a block executes in, and the pieces of execution every front end shares: end points
//! from axis words, straight moves, arcs, feed for the Canon stream.
//!
//! A block executes on the live modal state, its undo taken first, and appends its commands to the
//! output queue behind a mark; the driver keeps the changes only if the whole block succeeded and
//! otherwise rolls the state back and truncates the queue to the mark (invariant: a block commits
//! all of its modal changes and commands or none — grbl's STEP 3/STEP 4 split, `driver.rs`).
//!
//! [`Ctx`] is generic over the front end's own part `X` (its modes, per-run state, options), so
//! that front-end code reads `cx.fe.…` beside the common `cx.st.…`; the shared helpers ask `X`
//! through [`Hooks`] where a dialect changes them (diameter words, a programmed point under
//! compensation, a pending tool offset, wording).

use crate::arc::PlanarArc;
use crate::options::CoreOptions;
use crate::state::{DistanceMode, ModalState};
use crate::words::{letter_bit, Val, Words};
use stanok_canon::{ArcMove, Canon, Diagnostic, FeedMode, LineMove, Plane, Pose, Span, Spanned};
use stanok_syntax::{Block, ColSpan};
use std::collections::VecDeque;

/// Appends a block's commands, each with the block's span and N label, to the output queue.
pub struct Emitter<'a> {
    /// The interpreter's output queue.
    pub queue: &'a mut VecDeque<Spanned<Canon>>,
    /// The block's span.
    pub span: Span,
    /// The block's N label.
    pub number: Option<u32>,
    /// Digits of the N label as written (0 = natural width).
    pub label_digits: u8,
}

impl<'a> Emitter<'a> {
    /// An emitter of `block`'s commands into `queue`: its span, N label and the label's digits.
    #[inline(always)]
    pub fn for_block(queue: &'a mut VecDeque<Spanned<Canon>>, block: &Block) -> Self {
        let label_digits = block.number_span.map_or(0, |s| {
            block
                .slice(s)
                .bytes()
                .filter(u8::is_ascii_digit)
                .count()
                .min(9) as u8
        });
        Emitter {
            queue,
            span: block.span(),
            number: block.number,
            label_digits,
        }
    }

    /// Calls `f` on the last `n` motion commands in the queue, oldest first; its flag is true for
    /// the oldest (RS274/NGC cutter compensation moves a held corner; the commands are still in
    /// the queue because the driver holds them back while compensation is on).
    pub fn edit_last_motions(&mut self, n: usize, mut f: impl FnMut(&mut Canon, bool)) {
        let mut idx = Vec::with_capacity(n);
        for (i, c) in self.queue.iter().enumerate().rev() {
            if idx.len() == n {
                break;
            }
            if c.value.motion().is_some() {
                idx.push(i);
            }
        }
        for (k, &i) in idx.iter().rev().enumerate() {
            f(&mut self.queue[i].value, k == 0);
        }
    }

    /// Queues one command of the current block. Inlined, so that the command is built where
    /// the `Spanned` is and not copied into it (a copy of ~240 bytes per command, callgrind).
    #[inline(always)]
    pub fn push(&mut self, value: Canon) {
        self.queue.push_back(Spanned {
            span: self.span,
            block_number: self.number,
            label_digits: self.label_digits,
            value,
        });
    }
}

/// Letters of the nine axes, in `Pose` order.
pub const AXIS_WORDS: [u8; 9] = [b'X', b'Y', b'Z', b'A', b'B', b'C', b'U', b'V', b'W'];

/// Each axis word's bit in `Words::written`, and all of them.
const AXIS_BITS: [u32; 9] = {
    let mut bits = [0; 9];
    let mut i = 0;
    while i < 9 {
        bits[i] = letter_bit(AXIS_WORDS[i]);
        i += 1;
    }
    bits
};
const AXIS_BITS_ALL: u32 = {
    let mut all = 0;
    let mut i = 0;
    while i < 9 {
        all |= AXIS_BITS[i];
        i += 1;
    }
    all
};
/// LinuxCNC's polar words `@` and `^`.
const POLAR_BITS: u32 = letter_bit(b'@') | letter_bit(b'^');

/// True for the linear axes (converted by the length unit).
pub fn is_linear(axis: usize) -> bool {
    !matches!(axis, 3..=5)
}

/// What the driver lends a front end for one block: everything of [`Ctx`] but the front end's
/// own part, which the front end adds ([`Parts::with`]).
pub struct Parts<'a> {
    /// The parsed block.
    pub block: &'a Block,
    /// Its words (the front end fills them: [`Words::fill`]).
    pub words: &'a mut Words,
    /// The live modal state (its undo is taken).
    pub st: &'a mut ModalState,
    /// Where the block's commands go (truncated again if the block fails).
    pub out: Emitter<'a>,
    /// Options.
    pub opts: &'a CoreOptions,
    /// Warnings (reported whether or not the block commits).
    pub warnings: &'a mut Vec<Diagnostic>,
}

impl<'a> Parts<'a> {
    /// The block's context with the front end's part `fe`.
    #[inline(always)]
    pub fn with<X>(self, fe: &'a mut X) -> Ctx<'a, X> {
        Ctx {
            block: self.block,
            words: self.words,
            st: self.st,
            out: self.out,
            opts: self.opts,
            warnings: self.warnings,
            fe,
        }
    }
}

/// Where the shared helpers of [`Ctx`] depend on the dialect; every method has the neutral
/// default, so a front end overrides only what its language changes. Monomorphised: a default
/// costs nothing on the per-block path.
pub trait Hooks {
    /// Under cutter compensation the programmed point of the plane's two axes (a, b), which is
    /// not where the tool is (RS274/NGC): end points of incremental words start from it.
    #[inline(always)]
    fn programmed_point(&self) -> Option<[f64; 2]> {
        None
    }
    /// Axes whose words are diameters (halved before use; AxiOMA G10).
    #[inline(always)]
    fn diameter_words(&self) -> Option<&[bool; 9]> {
        None
    }
    /// A tool length offset the next motion applies (AxiOMA): taken by the motion.
    #[inline(always)]
    fn take_pending_tlo(&mut self) -> Option<Pose> {
        None
    }
    /// The message for a word no function of the block consumed.
    fn unused_word_message(&self, letter: u8) -> String {
        format!("{} has no meaning in this block", letter as char)
    }
    /// The message for a word of an axis the machine lacks.
    fn axis_not_configured_message(&self, letter: u8) -> String {
        format!("{} axis is not configured on this machine", letter as char)
    }
}

impl Hooks for () {}

/// Everything a block's execution may read or change: the common parts and the front end's own
/// part `fe`.
pub struct Ctx<'a, X> {
    /// The parsed block.
    pub block: &'a Block,
    /// Its evaluated words.
    pub words: &'a mut Words,
    /// The live modal state (its undo is taken).
    pub st: &'a mut ModalState,
    /// Where the block's commands go (truncated again if the block fails).
    pub out: Emitter<'a>,
    /// Options.
    pub opts: &'a CoreOptions,
    /// Warnings (reported whether or not the block commits).
    pub warnings: &'a mut Vec<Diagnostic>,
    /// The front end's own part: its modes (journalled), per-run state and options.
    pub fe: &'a mut X,
}

impl<X: Hooks> Ctx<'_, X> {
    /// An error at a word.
    pub fn err(&self, code: &'static str, msg: impl Into<String>, at: ColSpan) -> Diagnostic {
        Diagnostic::error(code, msg, self.block.span_of(at))
    }

    /// An error carrying the manual's number, at a word.
    pub fn manual(&self, number: u32, msg: impl Into<String>, at: ColSpan) -> Diagnostic {
        Diagnostic::manual(number, msg, self.block.span_of(at))
    }

    /// The whole block's range.
    pub fn whole(&self) -> ColSpan {
        ColSpan::new(0, self.block.text.len())
    }

    /// Program units → mm.
    pub fn mm(&self, v: f64) -> f64 {
        v * self.st.units.mm_per_unit()
    }

    /// Reads the axis words (marking them used) and returns the end point in program coordinates
    /// (mm/deg), honouring G90/G91, and which axes were written.
    pub fn end_point(&mut self) -> Result<(Pose, [bool; 9]), Diagnostic> {
        if let Some((a, b)) = self.opts.coupled_coordinates {
            let has = |set: [bool; 9]| (0..9).any(|i| set[i] && self.words.has(AXIS_WORDS[i]));
            if has(a) && has(b) {
                return Err(self
                    .manual(
                        653,
                        "coordinates that depend on each other through the kinematic transformation are mixed in one block",
                        self.whole(),
                    )
                    .with_note("program either the Cartesian coordinates or the directly mapped ones"));
            }
        }
        let mut p = self.programmed_position().to_array();
        let mut given = [false; 9];
        // LinuxCNC polar words: `@` radius, `^` angle (degrees) about the origin of the XY
        // plane; under G91 they add to the current point's own radius and angle.
        let written = self.words.written();
        if written & POLAR_BITS != 0 {
            let radius = self.words.take(b'@');
            let angle = self.words.take(b'^');
            if let Some(w) = self.words.take(b'X').or_else(|| self.words.take(b'Y')) {
                return Err(self.err(
                    "rs274::polar-and-xy",
                    "Cannot use polar coordinates with X or Y words",
                    w.span,
                ));
            }
            let (r0, t0) = (p[0].hypot(p[1]), p[1].atan2(p[0]));
            let rw = radius.map(|w| self.mm(w.v));
            let tw = angle.map(|w| w.v.to_radians());
            let (r, t) = match self.st.distance {
                DistanceMode::Absolute => (rw.unwrap_or(r0), tw.unwrap_or(t0)),
                DistanceMode::Incremental => (r0 + rw.unwrap_or(0.0), t0 + tw.unwrap_or(0.0)),
            };
            p[0] = r * t.cos();
            p[1] = r * t.sin();
            given[0] = true;
            given[1] = true;
        }
        // In axis order (the first unconfigured axis is the one reported), stopping after the
        // last written one: a block writes two or three of the nine.
        let mut left = written & AXIS_BITS_ALL;
        for (i, &l) in AXIS_WORDS.iter().enumerate() {
            if left == 0 {
                break;
            }
            left &= !AXIS_BITS[i];
            let Some(val) = self.words.take(l) else {
                continue;
            };
            if !self.opts.axes[i] {
                return Err(self.err(
                    "interp::axis-not-configured",
                    self.fe.axis_not_configured_message(l),
                    val.span,
                ));
            }
            let mut v = if is_linear(i) { self.mm(val.v) } else { val.v };
            // Diameter programming (AxiOMA G10): positions and increments are diameters (§14).
            if self.fe.diameter_words().is_some_and(|d| d[i]) {
                v /= 2.0;
            }
            p[i] = match self.st.distance {
                DistanceMode::Absolute => v,
                DistanceMode::Incremental => p[i] + v,
            };
            given[i] = true;
        }
        Ok((Pose::from_array(p), given))
    }

    /// Where the program thinks the tool is: the tool position in program coordinates, except
    /// under (RS274/NGC) cutter compensation, where the plane coordinates are the programmed point.
    pub fn programmed_position(&self) -> Pose {
        let p = self.st.program_position();
        match self.fe.programmed_point() {
            Some(q) => {
                let (a, b, _) = self.st.plane.axes();
                let mut v = p.to_array();
                v[a] = q[0];
                v[b] = q[1];
                Pose::from_array(v)
            }
            None => p,
        }
    }

    /// True if any axis word is present (not marking them used).
    pub fn has_axis_words(&self) -> bool {
        self.words.any(&AXIS_WORDS) || self.words.any(b"@^")
    }

    /// Emits a straight move to `end` (program coordinates) and moves the state there.
    pub fn straight(&mut self, rapid: bool, end: Pose, feed: f64) {
        self.apply_pending_tlo();
        let end_m = self.st.frame.to_machine(&end);
        // Each variant built in place (not a `LineMove` moved into one): a copy less per move.
        let start = self.st.position;
        let law = stanok_canon::FeedLaw::PerMinute;
        self.out.push(if rapid {
            Canon::StraightTraverse(LineMove {
                start,
                end: end_m,
                feed: 0.0,
                law,
            })
        } else {
            Canon::StraightFeed(LineMove {
                start,
                end: end_m,
                feed,
                law,
            })
        });
        self.st.position = end_m;
    }

    /// Emits an arc to `end` (program coordinates) about the planar centre, and moves there.
    pub fn arc(&mut self, plane: Plane, ccw: bool, end: Pose, arc: PlanarArc, feed: f64) {
        self.apply_pending_tlo();
        let (a, b, n) = plane.axes();
        let mut centre = self.st.program_position().to_array();
        centre[a] = arc.centre[0];
        centre[b] = arc.centre[1];
        let centre_m = self.st.frame.to_machine(&Pose::from_array(centre)).xyz();
        let mut normal = [0.0; 3];
        normal[n] = if ccw { 1.0 } else { -1.0 };
        // The rotation axis maps with the frame's linear part; a mirror (negative determinant)
        // reverses the sense of rotation, so the axis flips (spec axioma-1 §11.2).
        let axis = self.st.frame.arc_axis_to_machine(normal);
        let end_m = self.st.frame.to_machine(&end);
        self.out.push(Canon::ArcFeed(ArcMove {
            start: self.st.position,
            end: end_m,
            centre: centre_m,
            axis,
            turns: arc.turns,
            plane,
            feed,
            law: stanok_canon::FeedLaw::PerMinute,
        }));
        self.st.position = end_m;
    }

    /// An arc whose machine-frame centre is already known (AxiOMA arcs under unequal in-plane scale
    /// factors, where the frame does not map circles to circles).
    pub fn arc_with_centre(
        &mut self,
        plane: Plane,
        ccw: bool,
        end: Pose,
        centre_m: [f64; 3],
        turns: u32,
        feed: f64,
    ) {
        self.apply_pending_tlo();
        let (_, _, n) = plane.axes();
        let mut normal = [0.0; 3];
        normal[n] = if ccw { 1.0 } else { -1.0 };
        let axis = self.st.frame.arc_axis_to_machine(normal);
        let end_m = self.st.frame.to_machine(&end);
        self.out.push(Canon::ArcFeed(ArcMove {
            start: self.st.position,
            end: end_m,
            centre: centre_m,
            axis,
            turns,
            plane,
            feed,
            law: stanok_canon::FeedLaw::PerMinute,
        }));
        self.st.position = end_m;
    }

    /// The path feed in mm/min for a feed move of `length_mm`, from the feed mode:
    /// G94 the F value, G95 F × the main spindle's commanded speed, G93 length × F.
    pub fn path_feed(&self, length_mm: f64) -> f64 {
        match self.st.feed_mode {
            FeedMode::UnitsPerMinute => self.st.feed,
            FeedMode::UnitsPerRevolution => self.st.feed * self.st.spindle_speed[0],
            FeedMode::InverseTime => self.st.feed * length_mm,
        }
    }

    /// A tool length offset waiting for motion (AxiOMA) goes into the frame now: the end point of
    /// this move is computed with it, on every axis.
    #[inline(always)]
    pub fn apply_pending_tlo(&mut self) {
        if let Some(t) = self.fe.take_pending_tlo() {
            self.st.frame.set_tlo(t);
        }
    }

    /// M7 (mist on), M8 (flood on), M9 (both off) — the same in every ISO dialect.
    pub fn coolant(&mut self, code: u32) {
        match code {
            7 => {
                self.st.mist = true;
                self.out.push(Canon::Mist { on: true });
            }
            8 => {
                self.st.flood = true;
                self.out.push(Canon::Flood { on: true });
            }
            _ => {
                self.st.mist = false;
                self.st.flood = false;
                self.out.push(Canon::Mist { on: false });
                self.out.push(Canon::Flood { on: false });
            }
        }
    }

    /// Reports the first word nothing consumed (LinuxCNC: "… word with no G code that uses it").
    /// Inlined test, out-of-line report: every block of every dialect ends here.
    #[inline(always)]
    pub fn check_all_used(&self) -> Result<(), Diagnostic> {
        if self.words.all_used() {
            return Ok(());
        }
        self.report_unused()
    }

    #[cold]
    #[inline(never)]
    fn report_unused(&self) -> Result<(), Diagnostic> {
        if let Some((l, v)) = self.words.first_unused() {
            let msg = self.fe.unused_word_message(l);
            return Err(self.err("interp::unused-word", msg, v.span));
        }
        Ok(())
    }

    /// A letter's value that must be a non-negative integer (P turns, T numbers…).
    pub fn non_negative_integer(&self, v: Val, what: &str) -> Result<u32, Diagnostic> {
        let r = v.v.round();
        if (v.v - r).abs() > 1e-6 || r < 0.0 || r > u32::MAX as f64 {
            return Err(self.err(
                "interp::not-an-integer",
                format!("{what} must be a non-negative integer, got {}", v.v),
                v.span,
            ));
        }
        Ok(r as u32)
    }
}
