//! # stanok-interp: blocks to the Canon stream — the registry of front ends
//!
//! The interpreter reads a program block by block (streaming, in bounded memory) and produces the
//! [`Canon`] commands that a control would execute: an iterator of
//! `Result<Spanned<Canon>, Diagnostic>`. It knows the modal state, units, the work frame, arcs,
//! parameters, expressions and control flow of each dialect; it knows nothing of time,
//! acceleration or joints.
//!
//! This crate is the **registry**: the one place that lists the front ends. The work is done by
//! the dialect-free core (`stanok-interp-core`: the driver, the block transaction, the output
//! queue, words, frames, arcs) and one crate per front end (`stanok-rs274`, `stanok-axioma`,
//! `stanok-mazatrol`, `stanok-balt`, `stanok-labs`), each implementing
//! `stanok_interp_core::FrontEnd`:
//!
//! ```text
//!  InterpOptions ─▶ registry (Dialect → front end) ─▶ Driver<R, front end>: Iterator
//!                   `registry!` below                    ├ Source ─line─▶ FrontEnd::next_unit
//!                                                        ├ begin / execute / commit | rollback
//!                                                        └ queue ─(minus held)─▶ next()
//! ```
//!
//! [`Interpreter`] is an enum of monomorphised drivers: one predictable branch per command, and
//! every call into a front end is static (the per-block cost of one dialect's own driver).
//!
//! Architecture invariants (each has a test):
//! * a block commits all of its modal changes and commands, or none;
//! * every command carries its block's span and N label;
//! * after the first error nothing more is produced (unless `continue_after_error` is set, which
//!   `stanok check` uses to list every error: the bad block is skipped, the state is unchanged);
//! * loops, calls and the number of executed blocks are bounded, so no input hangs.
#![deny(missing_docs)]

mod options;
mod queries;

pub use options::InterpOptions;
pub use stanok_axioma::mtable::{MEntry, MGroup, MKind, MTable};
pub use stanok_axioma::{
    css_rpm, AxiomaChain, AxiomaMachineParams, AxiomaModes, HVal, LengthComp, Polar, ProbeLatch,
};
pub use stanok_interp_core::{DistanceMode, ModalState, MotionMode, PathMode, Stats, WorkFrame};
pub use stanok_interp_core::{
    DEFAULT_MAX_BLOCKS, DEFAULT_MAX_DIAGNOSTICS_PER_LINE, DEFAULT_MAX_NESTING,
    DEFAULT_MAX_REPEATED_LINES, DEFAULT_MAX_TOTAL_LOOP_ITERATIONS, MAX_WARNINGS,
};
pub use stanok_labs::{LabMachineParams, LabState};
pub use stanok_mazatrol::codes::Series as MazatrolSeries;
pub use stanok_mazatrol::MazatrolParams;
pub use stanok_rs274::{normalise_name, Parameters, MAX_PARAMETERS};

use stanok_axioma::Axioma;
use stanok_balt::Balt;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp_core::{Core, Driver, ModalState as State, Next};
use stanok_labs::Labs;
use stanok_mazatrol::Mazatrol;
use stanok_rs274::Rs274;
use stanok_syntax::Dialect;
use std::io::{BufRead, Seek};

/// Declares the registry: for each dialect (a pattern over [`Dialect`]) its front end's variant
/// of [`Run`], the front end's type, and the function that builds its driver. The dispatch of
/// every driver method is generated from the same list.
macro_rules! registry {
    ($($dialect:pat => $variant:ident($fe:ty) = $build:ident;)*) => {
        /// One run: the driver of the program's front end. Built once per run and not moved
        /// afterwards, so the variants' sizes do not matter; boxing them would add a pointer
        /// chase to every command.
        #[allow(clippy::large_enum_variant)]
        enum Run<R: BufRead + Seek> {
            $($variant(Driver<R, $fe>),)*
        }

        impl<R: BufRead + Seek> Run<R> {
            fn new(source: R, opts: InterpOptions) -> Self {
                match opts.dialect {
                    $($dialect => Run::$variant($build(source, opts)),)*
                }
            }

            /// `Driver::next` split at its pop (`Driver::advance`): the dialect's arm makes the
            /// command ready, the one pop below moves it into the result (no copy per arm).
            #[inline(always)]
            fn next(&mut self) -> Option<Result<Spanned<Canon>, Diagnostic>> {
                let next = match self {
                    $(Run::$variant(d) => d.advance(),)*
                };
                match next {
                    Next::Command => match self.core_mut().queue.pop_front() {
                        Some(c) => Some(Ok(c)),
                        None => None,
                    },
                    Next::Done => None,
                    Next::Error(d) => Some(Err(d)),
                }
            }

            fn core(&self) -> &Core<R> {
                match self {
                    $(Run::$variant(d) => d.core(),)*
                }
            }

            #[inline(always)]
            fn core_mut(&mut self) -> &mut Core<R> {
                match self {
                    $(Run::$variant(d) => d.core_mut(),)*
                }
            }

            fn step_unit(&mut self) -> Result<bool, Diagnostic> {
                match self {
                    $(Run::$variant(d) => d.step_unit(),)*
                }
            }

            fn front_end_state(&self) -> String {
                match self {
                    $(Run::$variant(d) => format!("{:#?}", d.front_end()),)*
                }
            }
        }
    };
}

registry! {
    Dialect::Rs274ngc => Rs274(Rs274) = rs274;
    Dialect::Axioma => Axioma(Axioma) = axioma;
    Dialect::Mazatrol => Mazatrol(Mazatrol) = mazatrol;
    Dialect::Balt => Balt(Balt) = balt;
    Dialect::Nc31 | Dialect::P2p32 | Dialect::Mc2101 | Dialect::Gost20999 => Labs(Labs) = labs;
}

fn rs274<R: BufRead + Seek>(source: R, opts: InterpOptions) -> Driver<R, Rs274> {
    let core = opts.core();
    let mut state = State::power_on(&core);
    let fe = Rs274::new(&core, opts.rs274(), &mut state);
    Driver::new(source, core, state, fe)
}

fn axioma<R: BufRead + Seek>(source: R, opts: InterpOptions) -> Driver<R, Axioma> {
    let core = opts.core();
    let mut state = State::power_on(&core);
    let fe = Axioma::new(&core, opts.axioma, &mut state);
    Driver::new(source, core, state, fe)
}

fn mazatrol<R: BufRead + Seek>(source: R, opts: InterpOptions) -> Driver<R, Mazatrol> {
    let core = opts.core();
    let mut state = State::power_on(&core);
    let fe = Mazatrol::new(&core, opts.mazatrol(), &mut state);
    Driver::new(source, core, state, fe)
}

fn balt<R: BufRead + Seek>(source: R, opts: InterpOptions) -> Driver<R, Balt> {
    let core = opts.core();
    let mut state = State::power_on(&core);
    let fe = Balt::new(&core, &mut state);
    Driver::new(source, core, state, fe)
}

fn labs<R: BufRead + Seek>(mut source: R, opts: InterpOptions) -> Driver<R, Labs> {
    // The lab dialects hold their (short) program in memory: see `stanok_labs`. Read one byte
    // past the bound so that the front end sees the program is too large; never more
    // (`/dev/zero` has no end).
    let bound = (stanok_labs::MAX_PROGRAM_BYTES as u64).min(opts.max_program_bytes) + 1;
    let mut bytes = Vec::new();
    let _ = std::io::Read::read_to_end(&mut std::io::Read::take(&mut source, bound), &mut bytes);
    let fe = Labs::new(&String::from_utf8_lossy(&bytes), opts.lab());
    let core = opts.core();
    let state = State::power_on(&core);
    Driver::new(source, core, state, fe)
}

/// The interpreter: an iterator of canonical commands over a program source.
pub struct Interpreter<R: BufRead + Seek> {
    run: Run<R>,
}

impl<'a> Interpreter<std::io::Cursor<&'a [u8]>> {
    /// An interpreter over program text held in memory.
    pub fn from_text(text: &'a str, opts: InterpOptions) -> Self {
        Interpreter::new(std::io::Cursor::new(text.as_bytes()), opts)
    }
}

impl<R: BufRead + Seek> Interpreter<R> {
    /// An interpreter reading `source` with the front end of `opts.dialect`.
    pub fn new(source: R, opts: InterpOptions) -> Self {
        Interpreter {
            run: Run::new(source, opts),
        }
    }
}

impl<R: BufRead + Seek> Iterator for Interpreter<R> {
    type Item = Result<Spanned<Canon>, Diagnostic>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        self.run.next()
    }
}
