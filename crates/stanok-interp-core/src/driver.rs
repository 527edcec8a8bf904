//! The driver: an iterator of canonical commands over a program, running a front end's units as
//! transactions (`frontend.rs` has the contract).
//!
//! ```text
//!  Phase::Start ─▶ Canon::Init from the power-on state
//!  Phase::Running: while the queue has nothing releasable, step():
//!      fe.next_unit ─▶ Execute ─▶ run_unit: begin ─▶ execute ─▶ commit | rollback
//!  the queue releases everything but the front end's held tail (look-ahead); each released
//!      motion gets its feed law (`feed_law.rs`)
//!  an error: yielded; the run stops there (nothing of the unit or after it), unless
//!      continue_after_error and the error is not fatal — then the unit is skipped, state unchanged
//! ```
//!
//! Generic over the front end, so every call into it is static and inlined: the per-block path
//! costs what a driver written for one dialect would.
//!
//! The bounds that keep any input from hanging a run live here, so that every front end has
//! them: [`Core::read_line`] counts every line read against `max_blocks` (the work of the run)
//! and every line read *again* against `max_repeated_lines` (the work a loop, call or jump back
//! repeats); `Source` bounds line length and program size; `warnings.rs` bounds the warnings
//! of a line and of the run. Blocks are counted once they have run ([`Core::count_block`]).

use crate::ctx::{Emitter, Parts};
use crate::feed_law::FeedLaws;
use crate::frontend::{FrontEnd, Outcome, Unit};
use crate::options::CoreOptions;
use crate::source::{Read, Source};
use crate::state::ModalState;
use crate::words::Words;
use stanok_canon::{Canon, Diagnostic, Span, Spanned};
use stanok_syntax::{Block, SourcePos};
use std::collections::VecDeque;
use std::io::{BufRead, Seek};

/// Counters of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Lines read (including skipped ones).
    pub lines_read: u64,
    /// Blocks executed to completion (loop bodies count every time; a block that fails is not
    /// counted, in every dialect).
    pub blocks_executed: u64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Start,
    Running,
    Done,
}

/// The dialect-free part of a run, lent to the front end.
pub struct Core<R: BufRead + Seek> {
    /// Where lines come from.
    pub source: Source<R>,
    /// The current line.
    pub block: Block,
    /// Its words (filled by the front end's `execute`).
    pub words: Words,
    /// The current line's syntax diagnostics (see [`Core::take_syntax`]).
    pub syntax: Vec<Diagnostic>,
    /// Options common to all front ends.
    pub opts: CoreOptions,
    /// The common modal state.
    pub state: ModalState,
    /// Commands of committed units, released in order (minus the front end's held tail).
    pub queue: VecDeque<Spanned<Canon>>,
    /// Commands a staging front end holds until it releases them into `queue`
    /// ([`FrontEnd::STAGES_OUTPUT`]); empty for the others.
    pub staging: VecDeque<Spanned<Canon>>,
    /// Warnings (they never stop the run).
    pub warnings: Vec<Diagnostic>,
    /// Counters.
    pub stats: Stats,
    /// One past the offset of the furthest line start read in the program (`count_line`).
    high_water: u64,
    /// Lines read again (`count_line`).
    repeated_lines: u64,
    /// What `warnings.rs` remembers to bound the warnings.
    pub(crate) admitted: crate::warnings::Admitted,
}

impl<R: BufRead + Seek> Core<R> {
    /// Reads the next line into `block` (counting it against the run's bounds, see
    /// [`Core::count_line`]); Ok(Read::Line(start)) with the position the line started at.
    #[inline(always)]
    pub fn read_line(&mut self) -> Result<Read, Diagnostic> {
        self.syntax.clear();
        let r = self.source.read(&mut self.block, &mut self.syntax)?;
        if let Read::Line(_) = r {
            self.count_line()?;
        }
        Ok(r)
    }

    /// One more line read (executed, control flow or skipped): the run's work bound
    /// `max_blocks` counts them all, so a loop whose body is skipped or only control flow still
    /// ends.
    ///
    /// A line read *again* — below the furthest point read in the program (a loop pass, a call,
    /// a jump back), or in a file a call opened — also counts against `max_repeated_lines`: a
    /// long program read once may have tens of millions of lines, but a runaway loop is work
    /// done again, and that bound stops it within seconds.
    #[inline(always)]
    fn count_line(&mut self) -> Result<(), Diagnostic> {
        self.stats.lines_read += 1;
        if self.stats.lines_read > self.opts.max_blocks {
            return Err(self.too_many_blocks(self.block.span()));
        }
        if self.source.depth() > 0 || self.block.offset < self.high_water {
            self.count_repeated()
        } else {
            self.high_water = self.block.offset + 1;
            Ok(())
        }
    }

    /// A line a front end scanned again outside [`Core::read_line`] (RS274/NGC reads a called
    /// file up to its `sub` line each call): counted as read again.
    pub fn count_scanned_line(&mut self) -> Result<(), Diagnostic> {
        self.stats.lines_read += 1;
        if self.stats.lines_read > self.opts.max_blocks {
            return Err(self.too_many_blocks(self.block.span()));
        }
        self.count_repeated()
    }

    #[inline(always)]
    fn count_repeated(&mut self) -> Result<(), Diagnostic> {
        self.repeated_lines += 1;
        if self.repeated_lines > self.opts.max_repeated_lines {
            return Err(self.too_many_repeated_lines());
        }
        Ok(())
    }

    /// Sorts the current line's syntax diagnostics: warnings are kept (unless `skipping`: the
    /// line is not executed), the first error is returned.
    #[inline(always)]
    pub fn take_syntax(&mut self, skipping: bool) -> Option<Diagnostic> {
        // Most lines have no syntax diagnostics: skip setting up the drain then.
        if self.syntax.is_empty() {
            return None;
        }
        self.take_syntax_slow(skipping)
    }

    #[cold]
    fn take_syntax_slow(&mut self, skipping: bool) -> Option<Diagnostic> {
        let mut first_error = None;
        for d in self.syntax.drain(..) {
            if d.is_error() {
                first_error.get_or_insert(d);
            } else if !skipping {
                self.warnings.push(d);
            }
        }
        first_error
    }

    /// One more block completed: [`Stats::blocks_executed`] counts a block once it has run, so
    /// a block that fails is not among them, in every dialect. Front ends call it when they keep
    /// a unit (`commit`) and for the control-flow lines they act on; the work bound is
    /// [`Core::read_line`]'s.
    #[inline(always)]
    pub fn count_block(&mut self) {
        self.stats.blocks_executed += 1;
    }

    /// Counts `n` units a front end completed at once (read from its own program, not through
    /// [`Core::read_line`]): lines and blocks, the lines against `max_blocks`. `at`: where to
    /// report the bound (the last command the units produced).
    pub fn count_units(&mut self, n: u64, at: Span) -> Result<(), Diagnostic> {
        self.stats.lines_read += n;
        self.stats.blocks_executed += n;
        if self.stats.lines_read > self.opts.max_blocks {
            return Err(self.too_many_blocks(at));
        }
        Ok(())
    }

    #[cold]
    fn too_many_blocks(&self, at: Span) -> Diagnostic {
        Diagnostic::error(
            "interp::too-many-blocks",
            format!(
                "more than {} lines read: stopping (endless loop?)",
                self.opts.max_blocks
            ),
            at,
        )
        .with_note(
            "the bound counts every line read, loops and skipped lines included: the option \
             --max-blocks",
        )
        .fatal()
    }

    #[cold]
    fn too_many_repeated_lines(&self) -> Diagnostic {
        Diagnostic::error(
            "interp::too-many-blocks",
            format!(
                "more than {} lines read again (loop passes, calls, jumps back): stopping \
                 (endless loop?)",
                self.opts.max_repeated_lines
            ),
            self.block.span(),
        )
        .with_note("the bound is the option --max-repeated-lines")
        .fatal()
    }

    /// Continues reading at `pos` (an error is located at the current block).
    pub fn seek(&mut self, pos: SourcePos) -> Result<(), Diagnostic> {
        self.source.seek(pos, self.block.span())
    }

    /// A context for work outside a unit's transaction (after a commit, at a return): commands
    /// go to `queue` with `span` and `number`.
    pub fn parts(&mut self, span: Span, number: Option<u32>) -> Parts<'_> {
        Parts {
            block: &self.block,
            words: &mut self.words,
            st: &mut self.state,
            out: Emitter {
                queue: &mut self.queue,
                span,
                number,
                label_digits: 0,
            },
            opts: &self.opts,
            warnings: &mut self.warnings,
        }
    }
}

/// A run of front end `F` over a program source: an iterator of commands.
pub struct Driver<R: BufRead + Seek, F: FrontEnd> {
    core: Core<R>,
    fe: F,
    phase: Phase,
    errors: usize,
    /// Completes every released motion with its feed law (`feed_law.rs`).
    laws: FeedLaws,
}

impl<R: BufRead + Seek, F: FrontEnd> Driver<R, F> {
    /// A run of `fe` over `source`, starting from `state` (the power-on state the front end set
    /// up: [`ModalState::power_on`] with its own defaults).
    pub fn new(source: R, opts: CoreOptions, state: ModalState, fe: F) -> Self {
        Driver {
            core: Core {
                source: Source::new(source, &opts),
                block: Block::default(),
                words: Words::default(),
                syntax: Vec::new(),
                state,
                queue: VecDeque::new(),
                staging: VecDeque::new(),
                warnings: Vec::new(),
                stats: Stats::default(),
                high_water: 0,
                repeated_lines: 0,
                admitted: Default::default(),
                opts,
            },
            fe,
            phase: Phase::Start,
            errors: 0,
            laws: FeedLaws::default(),
        }
    }

    /// The dialect-free part of the run (state, warnings, counters, options).
    pub fn core(&self) -> &Core<R> {
        &self.core
    }

    /// The same, mutable.
    #[inline(always)]
    pub fn core_mut(&mut self) -> &mut Core<R> {
        &mut self.core
    }

    /// The front end (its own state, for the registry's queries).
    pub fn front_end(&self) -> &F {
        &self.fe
    }

    /// The same, mutable.
    pub fn front_end_mut(&mut self) -> &mut F {
        &mut self.fe
    }

    /// Runs the next unit and releases nothing: Ok(true) when the program is over. For tests
    /// that look at the state between units (the transaction test); `Iterator::next` is the
    /// driver's interface.
    #[doc(hidden)]
    pub fn step_unit(&mut self) -> Result<bool, Diagnostic> {
        if self.phase == Phase::Start {
            self.phase = Phase::Running;
            let init = self.init_command();
            self.core
                .queue
                .push_back(Spanned::new(Default::default(), init));
        }
        self.step_admitting_warnings()
    }

    fn init_command(&self) -> Canon {
        let st = &self.core.state;
        Canon::Init {
            position: st.position,
            units: st.units,
            g5x_index: st.g5x_index,
            g5x_offset: *st.frame.origin(),
            g92_offset: *st.frame.shift(),
            xy_rotation: st.xy_rotation_deg,
        }
    }

    /// Runs the next unit. Ok(true) when the program is over.
    #[inline(always)]
    fn step(&mut self) -> Result<bool, Diagnostic> {
        match self.fe.next_unit(&mut self.core)? {
            Unit::Execute => self.run_unit(),
            Unit::Skip => Ok(false),
            Unit::End => Ok(true),
            Unit::EndOfInput => {
                self.fe.finish(&mut self.core)?;
                Ok(true)
            }
        }
    }

    /// One unit as a transaction: all of it or nothing.
    #[inline(always)]
    fn run_unit(&mut self) -> Result<bool, Diagnostic> {
        let core = &mut self.core;
        // The unit runs on the live state; a failure restores this copy and the journals.
        let snapshot = core.state.begin_block();
        let undo = self.fe.begin(core);
        let out = if F::STAGES_OUTPUT {
            &mut core.staging
        } else {
            &mut core.queue
        };
        let mark = out.len();
        let parts = Parts {
            block: &core.block,
            words: &mut core.words,
            st: &mut core.state,
            out: Emitter::for_block(out, &core.block),
            opts: &core.opts,
            warnings: &mut core.warnings,
        };
        match self.fe.execute(parts) {
            Ok(outcome) => {
                self.fe.commit(core, outcome)?;
                Ok(outcome == Outcome::End)
            }
            Err(d) => {
                // Nothing of a failing unit leaves the interpreter.
                let out = if F::STAGES_OUTPUT {
                    &mut core.staging
                } else {
                    &mut core.queue
                };
                out.truncate(mark);
                core.state.rollback(snapshot);
                self.fe.rollback(undo, core);
                Err(d)
            }
        }
    }

    /// One step, then the bounds on its warnings (`warnings.rs`).
    #[inline(always)]
    fn step_admitting_warnings(&mut self) -> Result<bool, Diagnostic> {
        let from = self.core.warnings.len();
        let r = self.step();
        if self.core.warnings.len() > from {
            self.core.admit_warnings(from);
        }
        r
    }

    /// How many commands at the back of the queue are held back.
    #[inline(always)]
    fn held(&self) -> usize {
        self.fe.held(&self.core.queue, self.phase == Phase::Done)
    }

    #[cold]
    fn fail(&mut self, d: Diagnostic) -> Diagnostic {
        // An error inside a file a call opened is located in that file.
        let d = match self.core.source.current_file() {
            Some(f) => d.in_file(f.display().to_string()),
            None => d,
        };
        self.errors += 1;
        let go_on = self.core.opts.continue_after_error
            && self.errors < self.core.opts.max_errors
            && !d.fatal;
        if !go_on {
            self.phase = Phase::Done;
            self.core.queue.clear();
        }
        d
    }
}

/// What the next command of a run is, once [`Driver::advance`] has made it ready.
#[derive(Debug)]
pub enum Next {
    /// The front of `Core::queue` (its feed law stamped, the front end told): pop it.
    Command,
    /// The run has ended.
    Done,
    /// An error; the run goes on after it or not (`continue_after_error`).
    Error(Diagnostic),
}

impl<R: BufRead + Seek, F: FrontEnd> Driver<R, F> {
    /// Runs units until a command is releasable (then says [`Next::Command`] and leaves it at the
    /// front of `core.queue`), the run ends, or an error comes. The iterator's `next` is this and
    /// a `pop_front`; the registry (`stanok-interp`) calls the two apart, so that the one pop it
    /// writes for every dialect moves the command straight into its caller's result (a pop in each
    /// dialect's arm left five results to merge: one more copy of the ~280-byte `Spanned<Canon>`
    /// per command, measured with callgrind).
    #[inline(always)]
    pub fn advance(&mut self) -> Next {
        loop {
            if self.core.queue.len() > self.held() {
                // The front end's bookkeeping and the feed law first, the law stamped in place
                // at the front of the queue: with nothing between pop_front and the return, the
                // command moves straight into the result (no extra copy per command).
                self.fe.released();
                if let Some(front) = self.core.queue.front_mut() {
                    self.laws.stamp(&mut front.value);
                }
                return Next::Command;
            }
            match self.phase {
                Phase::Done => return Next::Done,
                Phase::Start => {
                    self.phase = Phase::Running;
                    let init = self.init_command();
                    self.core
                        .queue
                        .push_back(Spanned::new(Default::default(), init));
                }
                Phase::Running => match self.step_admitting_warnings() {
                    Ok(true) => self.phase = Phase::Done,
                    Ok(false) => {}
                    Err(d) => return Next::Error(self.fail(d)),
                },
            }
        }
    }
}

impl<R: BufRead + Seek, F: FrontEnd> Iterator for Driver<R, F> {
    type Item = Result<Spanned<Canon>, Diagnostic>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        match self.advance() {
            // `held() < len`: the queue is not empty.
            Next::Command => self.core.queue.pop_front().map(Ok),
            Next::Done => None,
            Next::Error(d) => Some(Err(d)),
        }
    }
}
