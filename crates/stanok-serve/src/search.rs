//! Block search: start a program at line N with the state a full run has there.
//!
//! The interpreter runs the whole program from its start (so parameters, subroutines, loops,
//! offsets and tools come out exactly as in a full run); [`BlockSearch::filter`] sits between it
//! and the machine:
//! 1. **Before line N** every command that sets state goes to the machine (spindle, coolant, tool,
//!    offsets, feed, modes: they are what the later blocks rely on), motion does not: only its end
//!    point is remembered. Dwells, program stops, messages and log output are dropped — they act
//!    in time or on the operator, not on the state.
//! 2. **At the first command of line N** (the first time the interpreter reaches it, loops
//!    included) the machine first *approaches* the remembered position with one rapid from where
//!    it stands, then everything runs normally.
//!
//! Invariant: the [`MachineState`](crate::state::MachineState) when line N's first command reaches
//! the machine equals a full run's at the same command, and so does the state at the end
//! (`tests/block_search.rs`, every corpus program that moves). Known simplification: the approach
//! is one straight rapid in machine coordinates (a control would retract the tool axis first).

use stanok_canon::{Canon, LineMove, Pose, Spanned};

/// The filter of the module doc.
#[derive(Debug, Clone)]
pub struct BlockSearch {
    line: u32,
    reached: bool,
    /// Where the machine stands (the last command passed on that moved it).
    machine_at: Option<Pose>,
    /// Where the program has the tool (end of the last motion, passed on or not).
    program_at: Option<Pose>,
}

impl BlockSearch {
    /// A search for the 1-based source line `line`.
    pub fn new(line: u32) -> Self {
        BlockSearch {
            line,
            reached: false,
            machine_at: None,
            program_at: None,
        }
    }

    /// The line searched for.
    pub fn line(&self) -> u32 {
        self.line
    }

    /// True once line N came.
    pub fn reached(&self) -> bool {
        self.reached
    }

    /// What of `cmd` goes to the machine (module doc): the approach, when line N has just come,
    /// then the commands, in order.
    pub fn filter(&mut self, cmd: Spanned<Canon>) -> (Option<Spanned<Canon>>, Vec<Spanned<Canon>>) {
        if self.reached {
            return (None, vec![cmd]);
        }
        if cmd.span.line == self.line {
            self.reached = true;
            let approach = match (self.machine_at, self.program_at) {
                (Some(from), Some(to)) if from != to => Some(Spanned {
                    value: Canon::StraightTraverse(LineMove {
                        start: from,
                        end: to,
                        feed: 0.0,
                        law: stanok_canon::FeedLaw::PerMinute,
                    }),
                    ..cmd.clone()
                }),
                _ => None,
            };
            return (approach, vec![cmd]);
        }
        (None, self.before(cmd))
    }

    /// A command before line N.
    fn before(&mut self, cmd: Spanned<Canon>) -> Vec<Spanned<Canon>> {
        match &cmd.value {
            Canon::Init { position, .. } => {
                self.machine_at = Some(*position);
                self.program_at = Some(*position);
                vec![cmd]
            }
            Canon::StraightProbe {
                motion, contact, ..
            } => {
                self.program_at = Some(motion.stopped_at(contact.as_deref().copied()).end);
                vec![]
            }
            Canon::Dwell { .. }
            | Canon::ProgramStop { .. }
            | Canon::Message { .. }
            | Canon::Log { .. }
            | Canon::Comment { .. }
            | Canon::PalletShuttle
            | Canon::WaitInput { .. } => vec![],
            // Spindle synchronisation belongs to the threading moves that are skipped with it.
            Canon::StartSpindleSync { .. } | Canon::StopSpindleSync => vec![],
            other => match other.motion() {
                Some(m) => {
                    self.program_at = Some(m.end());
                    vec![]
                }
                None => vec![cmd],
            },
        }
    }
}
