//! The contract between the driver and a dialect's front end.
//!
//! The driver (`driver.rs`) owns everything dialect-free — the source, the current block and its
//! words, the common modal state, the output queue, warnings, counters, the error policy — and
//! runs one *unit* at a time as a transaction:
//!
//! ```text
//!  next_unit ──▶ Skip / End / EndOfInput (→ finish)      the front end reads its next unit:
//!     │ Execute                                           a line (its control flow, statements,
//!     ▼                                                   delimiters), or a unit of its own
//!  undo = (state.begin_block(), fe.begin())
//!  fe.execute(parts) ─ Ok(outcome) ─▶ fe.commit(core, outcome)   (release into the queue, …)
//!     │ Err
//!     ▼
//!  output truncated to its mark, state.rollback, fe.rollback(undo): nothing of the unit remains
//! ```
//!
//! Invariants the front end keeps: everything it changes while executing is either in the common
//! state (undone by the driver), or journalled/copied by its `begin` and restored by its
//! `rollback`; it writes commands only through the emitter it is given (the driver truncates that
//! queue); what it still may change of the queued commands (a corner waiting for the next move)
//! it reports by `held`, so that nothing leaves the interpreter that a later block could change.

use crate::ctx::Parts;
use crate::driver::Core;
use stanok_canon::{Canon, Diagnostic, Spanned};
use std::collections::VecDeque;
use std::io::{BufRead, Seek};

/// What the driver does after a unit executed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Go on with the next unit.
    Continue,
    /// The program is over (M2/M30 …).
    End,
}

/// What the front end found as its next unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// Nothing to execute (a skipped line, control flow done): read on.
    Skip,
    /// Execute the unit (the block in `core.block`, or the front end's own unit) as a transaction.
    Execute,
    /// The program is over without executing anything more (a closing `%`).
    End,
    /// The input is exhausted: the driver calls [`FrontEnd::finish`].
    EndOfInput,
}

/// A dialect's front end. One registry (`stanok-interp`) lists the implementations.
pub trait FrontEnd: Sized {
    /// The front end's part of one unit's undo (what `begin` saved).
    type Undo;

    /// The front end's commands go to `core.staging` instead of `core.queue` and are moved to
    /// the queue by `commit` (AxiOMA: its look-ahead inserts motions among commands of committed
    /// blocks later). Monomorphised: costs nothing for the front ends that write directly.
    const STAGES_OUTPUT: bool = false;

    /// Reads the next unit. Line-based front ends read a line with [`Core::read_line`], act on
    /// their control flow, and count what they execute with [`Core::count_block`].
    fn next_unit<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<Unit, Diagnostic>;

    /// Starts a unit: clears journals, copies what cannot be journalled. The queue (and
    /// `staging`) as they are before the unit is readable here.
    fn begin<R: BufRead + Seek>(&mut self, core: &Core<R>) -> Self::Undo;

    /// Executes the unit on the live state: evaluates and sorts the words (STEP 2), then the
    /// block's functions in the dialect's order (STEP 3/4), writing commands through `parts.out`.
    fn execute(&mut self, parts: Parts<'_>) -> Result<Outcome, Diagnostic>;

    /// Undoes a failed unit (the driver has already truncated the output it wrote to —
    /// `core.queue`, or `core.staging` if it stages — to its mark, and restored the common state).
    fn rollback<R: BufRead + Seek>(&mut self, undo: Self::Undo, core: &mut Core<R>);

    /// Keeps a successful unit: applies what waited for success (parameter writes, releases from
    /// `staging`, a called profile …).
    fn commit<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        outcome: Outcome,
    ) -> Result<(), Diagnostic>;

    /// How many commands at the back of `queue` the front end may still change (look-ahead);
    /// `done`: the run is over.
    #[inline(always)]
    fn held(&self, _queue: &VecDeque<Spanned<Canon>>, _done: bool) -> usize {
        0
    }

    /// The front command of the queue is about to leave the interpreter.
    #[inline(always)]
    fn released(&mut self) {}

    /// End of input: what is still held is finished and released; unterminated constructs and a
    /// missing program end are errors.
    fn finish<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<(), Diagnostic>;

    /// True if a diagnostic of this front end ends the run even when the run goes on after
    /// errors (`continue_after_error`): the program cannot be followed past it.
    fn is_fatal(&self, _d: &Diagnostic) -> bool {
        false
    }
}
