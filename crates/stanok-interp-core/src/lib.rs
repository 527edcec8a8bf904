//! # stanok-interp-core: the dialect-free interpreter core
//!
//! Everything the front ends share and nothing that belongs to one of them: the compiler keeps it
//! that way, since this crate depends on no front end (they depend on it, and the registry
//! `stanok-interp` lists them).
//!
//! ```text
//!  Source (program + files a call opened) ──line──▶ FrontEnd::next_unit (control flow, statements)
//!                                                        │ Execute
//!          undo: ModalState::begin_block + FrontEnd::begin
//!          FrontEnd::execute(Parts → Ctx<its part>): Words::fill (STEP 2), the block (STEP 3/4)
//!                 │ Ok: FrontEnd::commit                  Err: rollback both, truncate the output
//!                 ▼
//!          queue of Spanned<Canon> ──(minus FrontEnd::held)──▶ Driver: Iterator
//! ```
//!
//! * `driver.rs` — [`Driver`] (the iterator, the unit transaction, the error policy) and [`Core`]
//!   (what a front end is lent: source, block, words, state, queues, warnings, counters);
//! * `frontend.rs` — the [`FrontEnd`] contract, [`Unit`], [`Outcome`];
//! * `source.rs` — the program's reader and the stack of files calls opened;
//! * `ctx.rs` — [`Ctx`] (a block's context, generic over the front end's own part), [`Emitter`],
//!   the shared helpers (end points, straight and arc emission, feed) and their [`Hooks`];
//! * `words.rs` — STEP 2: a block's words evaluated and sorted ([`Words`], [`WordRules`]);
//! * `state.rs` — the common [`ModalState`] and [`Journalled`], the per-block undo of large parts;
//! * `frame.rs` — the work frame `origin + R·(F(p) + shift) + tlo` and its inverse;
//! * `codes.rs` — [`code_table!`]: a dialect's codes (value, name, group, handler) in one table;
//! * `arc.rs` — arcs in the programming plane ([`arc::PlanarArc`], [`arc::ArcError`]);
//! * `feed_law.rs` — [`FeedLaws`]: every released motion completed with its feed law;
//! * `options.rs` — [`CoreOptions`], the settings every front end reads, and the defaults of
//!   the run's bounds;
//! * `warnings.rs` — the bounds on warnings (per line, per run, repeats).
//!
//! Architecture invariants (each has a test in the registry's suite):
//! * a unit commits all of its modal changes and commands, or none;
//! * every command carries its block's span and N label;
//! * after the first error nothing more is produced (unless `continue_after_error` is set, which
//!   `stanok check` uses to list every error: the bad unit is skipped, the state is unchanged);
//! * loops, calls and the number of executed blocks are bounded, so no input hangs: the core
//!   bounds what every front end shares (lines read and read again, line length and program
//!   size, warnings), the front ends their own constructs (loop passes, nesting, call depth),
//!   with the limits of [`CoreOptions`].
#![deny(missing_docs)]

pub mod arc;
pub mod codes;
pub mod ctx;
pub mod driver;
pub mod feed_law;
pub mod frame;
pub mod frontend;
pub mod options;
pub mod source;
pub mod state;
mod warnings;
pub mod words;

pub use ctx::{is_linear, Ctx, Emitter, Hooks, Parts, AXIS_WORDS};
pub use driver::{Core, Driver, Next, Stats};
pub use feed_law::FeedLaws;
pub use frontend::{FrontEnd, Outcome, Unit};
pub use options::{
    CoreOptions, DEFAULT_MAX_BLOCKS, DEFAULT_MAX_DIAGNOSTICS_PER_LINE, DEFAULT_MAX_NESTING,
    DEFAULT_MAX_REPEATED_LINES, DEFAULT_MAX_TOTAL_LOOP_ITERATIONS,
};
pub use source::{OpenFile, Read, Source};
pub use state::{
    DistanceMode, Journalled, ModalSnapshot, ModalState, MotionMode, PathMode, WorkFrame,
};
pub use warnings::MAX_WARNINGS;
pub use words::{NoExpressions, Repeated, Val, WordRules, WordValues, Words};
