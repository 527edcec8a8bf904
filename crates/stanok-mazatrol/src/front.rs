//! The Mazatrol front end: what the driver calls (`stanok_interp_core::FrontEnd`).
//!
//! ```text
//!  next_unit: read a line ─▶ tape (`%`), program headers (`O`), block skip
//!               ├─ a macro statement: GOTO / IF … GOTO / WHILE … DO / DO / END move the reader
//!               │   (flow.rs); IF … THEN runs its assignments as a unit
//!               ├─ a block that calls or returns (M98, M99, G65, G66, G70–G73): its target is
//!               │   found now (so a missing one fails before anything of the block runs)
//!               └─ Execute
//!  execute:   words (vacant dropped, decimal point type), the block (block.rs) — on the live
//!             state, every change journalled
//!  commit:    the call, return or modal call the block asked for (the reader moves)
//! ```
//!
//! *Invariants:* a unit's changes — core state, modes, variables, tables — are all undone when it
//! fails (`begin`/`rollback`); the reader moves only in `next_unit` (before the unit) and
//! `commit` (after it), never during `execute`; every line that runs counts as a block.

use crate::calls::{has_code, may_jump};
use crate::codes::Series;
use crate::eval::Env;
use crate::flow::{self, CallKind, Flow, Frame, Program};
use crate::macro_b::MVal;
use crate::modes::Modes;
use crate::tables::Tables;
use crate::vars::Variables;
use crate::MazatrolState;
use stanok_canon::{Canon, Diagnostic, Span};
use stanok_interp_core::{
    Core, CoreOptions, FrontEnd, Hooks, Journalled, ModalState, Outcome, Parts, Read, Unit,
};
use stanok_syntax::SourcePos;
use std::cell::RefCell;
use std::io::{BufRead, Seek};

/// The Mazatrol control's machine parameters (machine data `[mazatrol]`, `docs` §1).
#[derive(Debug, Clone, PartialEq)]
pub struct MazatrolParams {
    /// The series.
    pub series: Series,
    /// Decimal point type 1 or 2.
    pub decimal_point_type: u8,
    /// G73 / G83 clearance d, mm.
    pub peck_clearance: f64,
    /// G76 / G78 pull-out angle, degrees.
    pub thread_chamfer_angle: f64,
    /// G60 final approach, mm.
    pub g60_overshoot: f64,
    /// F93 bit 3.
    pub tool_data_length: bool,
    /// G49 moves the axes.
    pub g49_moves: bool,
    /// G53.5 origin, machine mm (None: the G54 offset).
    pub mazatrol_wpc: Option<[f64; 3]>,
    /// TTPC programs in the workpiece frame (F85 bit 2 / P12 bit 7 = 1).
    pub ttpc_workpiece_frame: bool,
    /// G95 (true) or G94 (false) at power-on; `None`: G95 on the T-series, G94 on the M-series
    /// (machine data `[mazatrol] power_on_feed`).
    pub power_on_feed_per_revolution: Option<bool>,
}

impl MazatrolParams {
    /// Whether the control powers on (and resets) in G95.
    pub fn power_on_feed_per_revolution(&self) -> bool {
        self.power_on_feed_per_revolution
            .unwrap_or(self.series == Series::T)
    }
}

impl Default for MazatrolParams {
    fn default() -> Self {
        MazatrolParams {
            series: Series::M,
            decimal_point_type: 2,
            peck_clearance: 1.0,
            thread_chamfer_angle: 45.0,
            g60_overshoot: 1.0,
            tool_data_length: false,
            g49_moves: true,
            mazatrol_wpc: None,
            ttpc_workpiece_frame: false,
            power_on_feed_per_revolution: None,
        }
    }
}

/// A program found for a call: where it is and where the call enters it.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// The program.
    pub program: Program,
    /// The first line run (after the `O` line, or the `H` sequence number).
    pub entry: SourcePos,
}

/// What `commit` does after a block.
#[derive(Debug, Clone, PartialEq)]
pub enum Request {
    /// Run a program (M98, G65, G66's call).
    Call {
        /// The target.
        target: Target,
        /// L.
        repeats: u32,
        /// The kind.
        kind: CallKind,
        /// G65/G66: the new locals.
        args: Option<Box<[MVal; 33]>>,
    },
    /// M99 (to the caller, or to `N p` of it).
    Return(Option<SourcePos>),
    /// G71–G73: go on after the profile's last block (N nf).
    Jump(SourcePos),
    /// G70: run N ns … N nf, then back.
    Profile {
        /// The line of N ns.
        first: SourcePos,
        /// N nf.
        last: u32,
        /// Where the tool returns, program coordinates.
        back_to: [f64; 9],
    },
}

/// What `next_unit` resolved for the block about to execute.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Prepared {
    /// M98 / G65 / G66 target.
    pub call: Option<Target>,
    /// M99 P n target in the caller.
    pub ret: Option<SourcePos>,
    /// G70's N ns.
    pub profile_first: Option<SourcePos>,
    /// G71 / G72 / G73: the profile's blocks, read.
    pub profile: Option<Vec<crate::turning::Step>>,
    /// G71 / G72 / G73: the line after the profile's last block (the program goes on there).
    pub profile_after: Option<SourcePos>,
    /// The block is a G66.1 call (its words are the arguments).
    pub every_block_call: bool,
}

/// Warnings given once per run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Once {
    /// `mazatrol::machine-m-code` for M codes below 1000 (bit per code / 64 chunks are overkill:
    /// the first 256 codes).
    pub m_codes: [u64; 4],
    /// `mazatrol::single-system`.
    pub single_system: bool,
    /// `mazatrol::not-modelled` (G62).
    pub g62: bool,
}

/// The expression evaluator's reusable stack: storage, not state.
#[derive(Default)]
pub struct Scratch(pub RefCell<Vec<MVal>>);

impl std::fmt::Debug for Scratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Scratch")
    }
}

/// The part of the front end a block's context carries (`cx.fe`).
#[derive(Debug)]
pub struct MazatrolPart {
    /// Machine parameters.
    pub params: MazatrolParams,
    /// Tool tip point control and tool length offset (journalled).
    pub modes: Journalled<MazatrolState>,
    /// The other Mazatrol modes (journalled).
    pub m: Journalled<Modes>,
    /// User variables (journalled).
    pub vars: Variables,
    /// Tools and offsets (copy-on-write undo).
    pub tables: Tables,
    /// Evaluator scratch (no state: left out of the state dump).
    pub scratch: Scratch,
    /// What the block asks `commit` to do.
    pub request: Option<Request>,
    /// What `next_unit` resolved for the block.
    pub prepared: Prepared,
    /// Warnings given once.
    pub once: Once,
    /// TTPC programs in the workpiece frame (the existing TTPC code reads this name).
    pub ttpc_workpiece_frame: bool,
    /// Cutter / nose radius compensation (journalled).
    pub comp: Journalled<crate::compensate::CompState>,
    /// The pending compensated command before this block edited it (restored on failure).
    pub comp_backup: Option<(usize, stanok_canon::Spanned<Canon>)>,
    /// M98 levels in progress.
    pub sub_depth: usize,
}

impl Hooks for MazatrolPart {
    fn unused_word_message(&self, letter: u8) -> String {
        format!("{} is not used by any code of this block", letter as char)
    }
}

impl MazatrolPart {
    /// The variable environment of the block (read-only).
    pub fn env<'a>(&'a self, st: &'a ModalState) -> Env<'a> {
        Env {
            vars: &self.vars,
            modes: &self.m,
            ttpc: &self.modes,
            st,
            tables: &self.tables,
            scratch: &self.scratch.0,
        }
    }
}

/// The Mazatrol EIA/ISO front end.
#[derive(Debug)]
pub struct Mazatrol {
    pub(crate) part: MazatrolPart,
    pub(crate) flow: Flow,
}

impl Mazatrol {
    /// The front end at power-on: G54 in force, the series' power-on modes (`docs` §3.1).
    pub fn new(opts: &CoreOptions, params: MazatrolParams, state: &mut ModalState) -> Self {
        state.g5x_index = 1;
        if let Some(z) = opts.control.offsets.zero.first().and_then(|p| p.first()) {
            state.frame.set_origin(z.offset);
        }
        if params.series == Series::T {
            state.plane = stanok_canon::Plane::ZX;
        }
        if params.power_on_feed_per_revolution() {
            state.feed_mode = stanok_canon::FeedMode::UnitsPerRevolution;
        }
        state.motion = stanok_interp_core::MotionMode::Rapid;
        let vars = Variables::new(&opts.control.perm_double);
        Mazatrol {
            part: MazatrolPart {
                ttpc_workpiece_frame: params.ttpc_workpiece_frame,
                m: Journalled::new(Modes::power_on(params.series)),
                params,
                modes: Journalled::default(),
                vars,
                tables: Tables::new(&opts.control),
                scratch: Scratch::default(),
                request: None,
                prepared: Prepared::default(),
                once: Once::default(),
                comp: Journalled::default(),
                comp_backup: None,
                sub_depth: 0,
            },
            flow: Flow::default(),
        }
    }

    /// The tool-tip-control modes after the blocks run so far.
    pub fn modes(&self) -> &MazatrolState {
        &self.part.modes
    }

    /// The Mazatrol modes after the blocks run so far.
    pub fn dialect_modes(&self) -> &Modes {
        &self.part.m
    }

    /// The non-volatile variables #500–#999 to store after the run.
    pub fn stored_variables(&self) -> std::collections::BTreeMap<u32, f64> {
        self.part.vars.stored()
    }

    /// A user variable's value (tests, queries).
    pub fn variable(&self, n: u32) -> MVal {
        crate::vars::kind(n).and_then(|k| self.part.vars.get(k))
    }

    /// The tools and offsets as the program left them.
    pub fn tables(&self) -> &Tables {
        &self.part.tables
    }
}

pub(crate) fn err(code: &'static str, msg: impl Into<String>, at: Span) -> Diagnostic {
    Diagnostic::error(code, msg, at)
}

impl Mazatrol {
    /// Reads and acts on lines until one must execute.
    fn next<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<Unit, Diagnostic> {
        loop {
            let pos = match core.read_line()? {
                Read::Line(p) => p,
                Read::EndOfInput => return Ok(Unit::EndOfInput),
                Read::EndOfFile => {
                    // A subprogram file ended without M99: return as M99 would.
                    self.end_without_m99(core)?;
                    continue;
                }
            };
            let next_line = core.source.position();
            if !self.flow.started {
                if core.block.percent {
                    self.flow.started = true;
                    core.syntax.clear();
                    continue;
                }
                if core.block.is_empty() && core.syntax.is_empty() {
                    continue;
                }
                self.flow.started = true;
            }
            if let Some(e) = core.take_syntax(false) {
                return Err(e);
            }
            if core.block.percent {
                if self.flow.frames.is_empty() {
                    return Ok(Unit::End);
                }
                self.end_without_m99(core)?;
                continue;
            }
            if let Some(o) = flow::program_number(&core.block) {
                if self.flow.frames.is_empty() && !self.flow.main_header_seen {
                    self.flow.main_header_seen = true;
                    self.flow.program = Some(pos);
                    self.part.m.program = Some(f64::from(o));
                    continue;
                }
                if self.flow.frames.is_empty() {
                    core.warnings.push(Diagnostic::warning(
                        "mazatrol::missing-program-end",
                        format!(
                            "the main program ends at the next program's O{o:04} without M02/M30"
                        ),
                        core.block.span(),
                    ));
                    return Ok(Unit::End);
                }
                self.end_without_m99(core)?;
                continue;
            }
            if core.block.block_delete && core.opts.block_delete {
                continue;
            }
            if let Some(s) = core.block.statement {
                match self.statement(core, s.kind, pos, next_line)? {
                    // An IF … THEN whose block runs counts in `commit`, as every block.
                    Some(unit) => return Ok(unit),
                    // A control statement has run here.
                    None => {
                        core.count_block();
                        continue;
                    }
                }
            }
            if core.block.words.is_empty() && core.block.assignments.is_empty() {
                continue;
            }
            self.part.prepared = Prepared::default();
            let level = self.part.vars.level();
            let modal_here = self.part.m.modal_call.filter(|c| c.level == level);
            if modal_here.is_some_and(|c| c.every_block)
                && core.block.assignments.is_empty()
                && ![2u32, 30, 98, 99]
                    .iter()
                    .any(|&m| has_code(&core.block, b'M', m))
                && !has_code(&core.block, b'G', 670)
            {
                self.part.prepared.every_block_call = true;
            }
            if may_jump(&core.block) || modal_here.is_some() {
                if let Err(e) = self.prepare(core, pos, next_line) {
                    self.part.prepared = Prepared::default();
                    return Err(e);
                }
            }
            return Ok(Unit::Execute);
        }
    }
}

impl FrontEnd for Mazatrol {
    type Undo = ();

    fn next_unit<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<Unit, Diagnostic> {
        self.next(core)
    }

    fn begin<R: BufRead + Seek>(&mut self, _core: &Core<R>) {
        self.part.modes.begin_block();
        self.part.m.begin_block();
        self.part.comp.begin_block();
        self.part.comp_backup = None;
        self.part.vars.begin();
        self.part.tables.begin();
        self.part.request = None;
    }

    fn execute(&mut self, parts: Parts<'_>) -> Result<Outcome, Diagnostic> {
        let mut cx = parts.with(&mut self.part);
        crate::block::execute(&mut cx)
    }

    fn rollback<R: BufRead + Seek>(&mut self, _undo: (), core: &mut Core<R>) {
        self.part.modes.rollback();
        self.part.m.rollback();
        self.part.comp.rollback();
        crate::compensate::restore(self.part.comp_backup.take(), &mut core.queue);
        self.part.vars.rollback();
        self.part.tables.rollback();
        self.part.request = None;
        self.part.prepared = Prepared::default();
    }

    #[inline(always)]
    fn commit<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        outcome: Outcome,
    ) -> Result<(), Diagnostic> {
        // A block counts once it has run (`Core::count_block`).
        core.count_block();
        self.part.vars.commit();
        match self.part.request.take() {
            Some(Request::Call {
                target,
                repeats,
                kind,
                args,
            }) => self.call(core, target, repeats, kind, args)?,
            Some(Request::Return(to)) => self.return_from_call(core, to)?,
            Some(Request::Jump(to)) => core.seek(to)?,
            Some(Request::Profile {
                first,
                last,
                back_to,
            }) => {
                let entry = first;
                let target = Target {
                    program: Program {
                        file: self.flow.file.clone(),
                        header: self.flow.program.unwrap_or_else(SourcePos::start),
                    },
                    entry,
                };
                let span = core.block.span();
                let number = core.block.number;
                self.call(
                    core,
                    target,
                    1,
                    CallKind::Profile {
                        last,
                        back_to,
                        span,
                        number,
                    },
                    None,
                )?;
            }
            None => {}
        }
        // G70's profile ends with its last block: back to the cycle's start point.
        if let Some(Frame {
            kind:
                CallKind::Profile {
                    last,
                    back_to,
                    span,
                    number,
                },
            ..
        }) = self.flow.frames.last().cloned()
        {
            if core.block.number == Some(last) {
                let back = stanok_canon::Pose::from_array(back_to);
                {
                    let st = &mut core.state;
                    let end = st.frame.to_machine(&back);
                    let m = stanok_canon::LineMove {
                        start: st.position,
                        end,
                        feed: 0.0,
                        law: stanok_canon::FeedLaw::PerMinute,
                    };
                    st.position = end;
                    core.queue.push_back(stanok_canon::Spanned {
                        span,
                        block_number: number,
                        label_digits: 0,
                        value: Canon::StraightTraverse(m),
                    });
                }
                self.return_from_call(core, None)?;
            }
        }
        if outcome == Outcome::End {
            self.part.vars.reset();
        }
        // What `next_unit` resolved, and the pending command's backup, served this block only.
        self.part.prepared = Prepared::default();
        self.part.comp_backup = None;
        Ok(())
    }

    fn held(
        &self,
        queue: &std::collections::VecDeque<stanok_canon::Spanned<Canon>>,
        done: bool,
    ) -> usize {
        if done {
            return 0;
        }
        crate::compensate::held(&self.part.comp, queue.len())
    }

    fn released(&mut self) {
        if self.part.comp.pending.is_some() {
            crate::compensate::released(&mut self.part.comp);
        }
    }

    fn finish<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<(), Diagnostic> {
        core.warnings.push(Diagnostic::warning(
            "mazatrol::missing-program-end",
            "the program ends without M02/M30",
            core.block.span(),
        ));
        Ok(())
    }
}
