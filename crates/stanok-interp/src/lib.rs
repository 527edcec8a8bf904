//! # stanok-interp: blocks to the Canon stream
//!
//! The interpreter reads a program block by block (streaming, in bounded memory) and produces the
//! [`Canon`] commands that a control would execute: an iterator of
//! `Result<Spanned<Canon>, Diagnostic>`. It knows the modal state, units, the work frame, arcs,
//! RS274/NGC parameters, expressions and O-word control flow; it knows nothing of time,
//! acceleration or joints.
//!
//! ```text
//!  BlockReader ──Block──▶ Words::fill (STEP 2: evaluate, sort)
//!                              │
//!                  rs274::execute / axioma::execute on the live state (STEP 3+4), its undo
//!                  taken first (state::ModalState::begin_block, state::Journalled)
//!                              │ Ok: commit state + commands        Err: roll back, yield the diagnostic, stop
//!                              ▼
//!                        queue of Spanned<Canon> ──▶ Iterator::next
//! ```
//!
//! Architecture invariants (each has a test):
//! * a block commits all of its modal changes and commands, or none;
//! * every command carries its block's span and N label;
//! * after the first error nothing more is produced (unless `continue_after_error` is set, which
//!   `stanok check` uses to list every error: the bad block is skipped, the state is unchanged);
//! * loops, calls and the number of executed blocks are bounded, so no input hangs.
#![deny(missing_docs)]

mod arc;
mod axioma;
mod axioma_chain;
mod balt;
mod balt_arc;
mod balt_spline;
mod ctx;
mod flow;
mod frame;
mod hll;
mod labs;
mod lathe;
mod mazatrol;
mod mazatrol_arc;
mod mazatrol_tlo;
mod options;
mod params;
mod predefined;
mod queries;
mod rs274;
mod state;
mod subfiles;
mod words;

pub use axioma::mtable::{MEntry, MGroup, MKind, MTable};
pub use axioma::probe::ProbeLatch;
pub use axioma::{css_rpm, AxiomaMachineParams};
pub use hll::value::HVal;
pub use labs::{LabMachineParams, LabState};
pub use options::{
    InterpOptions, DEFAULT_MAX_BLOCKS, DEFAULT_MAX_DIAGNOSTICS_PER_LINE, DEFAULT_MAX_NESTING,
    DEFAULT_MAX_REPEATED_LINES, DEFAULT_MAX_TOTAL_LOOP_ITERATIONS,
};
pub use params::{normalise_name, Parameters, MAX_PARAMETERS};
pub use state::{DistanceMode, LengthComp, ModalState, MotionMode, PathMode, Polar, WorkFrame};

use ctx::Ctx;
use flow::{Flow, FlowAction};
use rs274::Outcome;
use stanok_canon::{Canon, Diagnostic, FeedMode, LengthUnits, Plane, Spanned};
use stanok_syntax::{Block, BlockReader, CommentKind, Dialect, SourcePos};
use std::collections::VecDeque;
use std::io::{BufRead, Seek};
use words::Words;

/// Most warnings one run keeps (see `Interpreter::admit_warnings`).
pub const MAX_WARNINGS: usize = 1000;

/// Sets the note `and K more warning(s) …` on `d` (replacing an earlier one of its kind).
fn note_more(d: &mut Diagnostic, k: usize, where_: &str) {
    let note = format!("and {k} more warning(s) {where_}");
    match d
        .notes
        .iter_mut()
        .find(|n| n.starts_with("and ") && n.ends_with(where_))
    {
        Some(n) => *n = note,
        None => d.notes.push(note),
    }
}

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

/// The interpreter: an iterator of canonical commands over a program source.
pub struct Interpreter<R: BufRead + Seek> {
    reader: BlockReader<R>,
    /// Subroutine files being executed (`o<name> call` of `name.ngc`), innermost last; lines are
    /// read from the last one while it is there.
    files: Vec<subfiles::SubroutineFile>,
    block: Block,
    words: Words,
    opts: InterpOptions,
    state: ModalState,
    params: Parameters,
    flow: Flow,
    queue: VecDeque<Spanned<Canon>>,
    /// AxiOMA: commands of committed blocks held back until cutter compensation has placed the
    /// motions among them (empty whenever no compensated motion is waiting).
    axioma_held: VecDeque<Spanned<Canon>>,
    /// AxiOMA: cutter compensation look-ahead, canned-cycle and output state (not `Copy`).
    axioma: axioma::Extension,
    /// AxiOMA high-level language: variables and control flow; `None` until the first HLL line
    /// or expression, so that programs without HLL keep their speed.
    hll: Option<Box<hll::Hll>>,
    warnings: Vec<Diagnostic>,
    /// Code, span and file of every warning given (`admit_warnings`).
    warning_keys: std::collections::HashSet<(String, u64, u64, Option<String>)>,
    /// Warnings given per line (`admit_warnings`).
    warnings_per_line: std::collections::HashMap<(Option<String>, u32), usize>,
    /// Warnings dropped past [`MAX_WARNINGS`].
    dropped_warnings: usize,
    syntax: Vec<Diagnostic>,
    phase: Phase,
    stats: Stats,
    errors: usize,
    percent_open: bool,
    first_line: bool,
    /// RS274/NGC G70–G72: the profile subroutine being executed (`lathe.rs`).
    lathe: Option<lathe::LatheCapture>,
    /// RS274/NGC G70–G72: the call a committed block left (`Ctx::lathe_call`).
    lathe_call: Option<rs274::lathe_cycles::LatheCall>,
    /// The lab dialects' front end (None for AxiOMA and RS274/NGC).
    lab: Option<Box<labs::LabRun>>,
    /// Lab dialects: the span of the last command produced (where a bound is reported).
    lab_span: stanok_canon::Span,
    /// One past the offset of the furthest line start read in the program (`count_line`).
    high_water: u64,
    /// Lines read again (`count_line`).
    repeated_lines: u64,
}

impl<'a> Interpreter<std::io::Cursor<&'a [u8]>> {
    /// An interpreter over program text held in memory.
    pub fn from_text(text: &'a str, opts: InterpOptions) -> Self {
        Interpreter::new(std::io::Cursor::new(text.as_bytes()), opts)
    }
}

impl<R: BufRead + Seek> Interpreter<R> {
    /// An interpreter reading `source`.
    pub fn new(mut source: R, opts: InterpOptions) -> Self {
        // The lab dialects hold their (short) program in memory: see `labs`.
        let lab = opts.dialect.is_lab().then(|| {
            // Read one byte past the bound so that `LabRun` sees the program is too large;
            // never more (`/dev/zero` has no end).
            let bound = (labs::MAX_PROGRAM_BYTES as u64).min(opts.max_program_bytes) + 1;
            let mut bytes = Vec::new();
            let _ = std::io::Read::read_to_end(
                &mut std::io::Read::take(&mut source, bound),
                &mut bytes,
            );
            Box::new(labs::LabRun::new(&String::from_utf8_lossy(&bytes), &opts))
        });
        let state = ModalState {
            motion: match opts.dialect {
                Dialect::Rs274ngc => MotionMode::None,
                _ => MotionMode::Rapid,
            },
            plane: Plane::XY,
            distance: DistanceMode::Absolute,
            arc_distance: DistanceMode::Incremental,
            units: match opts.dialect {
                Dialect::Rs274ngc => opts.initial_units,
                _ => LengthUnits::Millimetres,
            },
            feed_mode: FeedMode::UnitsPerMinute,
            feed: 0.0,
            spindle_speed: [0.0; 4],
            spindle_on: [false; 4],
            selected_tool: None,
            current_tool: 0,
            path_mode: PathMode::Continuous {
                blend_tolerance: 0.0,
            },
            soft_acceleration: false,
            retract_to_initial: matches!(opts.dialect, Dialect::Axioma),
            diameter_mode: false,
            mist: false,
            flood: false,
            g5x_index: match opts.dialect {
                Dialect::Rs274ngc | Dialect::Mazatrol | Dialect::Balt => 1,
                _ => 0,
            },
            frame: Default::default(),
            xy_rotation_deg: 0.0,
            axioma: Default::default(),
            axioma_modes: Default::default(),
            mazatrol: Default::default(),
            balt: Default::default(),
            rs274: Default::default(),
            position: opts.initial_position,
        };
        let mut state = state;
        let mut params = Parameters::default();
        if opts.dialect == Dialect::Rs274ngc {
            params.set_machine_units(opts.rs274_machine_units);
            params.preset_from(&opts.control);
            let system = opts.control.offsets.active_system.clamp(1, 9);
            let (offset, rotation) = rs274::g5x_from_params(&params, system);
            state.g5x_index = system;
            state.frame.set_origin(offset);
            if rotation != 0.0 {
                state.frame.set_rotation(frame::rotation(2, rotation));
            }
            state.xy_rotation_deg = rotation;
            if opts.control.offsets.g92_applied {
                state.frame.set_shift(opts.control.offsets.g92);
            }
        }
        if matches!(opts.dialect, Dialect::Mazatrol | Dialect::Balt) {
            // Mazatrol: the work offset of G54 (page 1) is in force from the start.
            if let Some(z) = opts.control.offsets.zero.first().and_then(|p| p.first()) {
                state.frame.set_origin(z.offset);
            }
        }
        let mut reader = BlockReader::new(source, opts.dialect);
        reader.set_limits(opts.max_line_bytes, opts.max_program_bytes);
        Interpreter {
            reader,
            files: Vec::new(),
            block: Block::default(),
            words: Words::default(),
            state,
            params,
            flow: Flow::default(),
            queue: VecDeque::new(),
            axioma_held: VecDeque::new(),
            axioma: axioma::Extension::default(),
            hll: None,
            warnings: Vec::new(),
            warning_keys: Default::default(),
            warnings_per_line: Default::default(),
            dropped_warnings: 0,
            syntax: Vec::new(),
            phase: Phase::Start,
            stats: Stats::default(),
            errors: 0,
            percent_open: false,
            first_line: true,
            lathe: None,
            lathe_call: None,
            lab,
            lab_span: stanok_canon::Span::new(0, 0, 1, 1),
            high_water: 0,
            repeated_lines: 0,
            opts,
        }
    }

    fn init_command(&self) -> Canon {
        Canon::Init {
            position: self.state.position,
            units: self.state.units,
            g5x_index: self.state.g5x_index,
            g5x_offset: *self.state.frame.origin(),
            g92_offset: *self.state.frame.shift(),
            xy_rotation: self.state.xy_rotation_deg,
        }
    }

    /// Where the next line will be read (in the innermost subroutine file, if one is open).
    fn read_position(&self) -> SourcePos {
        match self.files.last() {
            Some(f) => f.reader.position(),
            None => self.reader.position(),
        }
    }

    fn seek_to(&mut self, pos: SourcePos) -> Result<(), Diagnostic> {
        let r = match self.files.last_mut() {
            Some(f) => f.reader.seek(pos),
            None => self.reader.seek(pos),
        };
        r.map_err(|e| {
            Diagnostic::error(
                "io::seek",
                format!("cannot seek in the program: {e}"),
                self.block.span(),
            )
        })
    }

    /// Reads the next line into `self.block`. Ok(false) at end of input.
    fn read(&mut self) -> Result<bool, Diagnostic> {
        self.syntax.clear();
        if !self.files.is_empty() {
            return self.read_subroutine_file();
        }
        let more = self
            .reader
            .next_block(&mut self.block, &mut self.syntax)
            .map_err(|e| {
                Diagnostic::error(
                    "io::read",
                    format!("cannot read the program: {e}"),
                    stanok_canon::Span::default(),
                )
            })?;
        if more {
            self.count_line()?;
        }
        Ok(more)
    }

    /// One more line read (executed, control flow or skipped): the run's work bound
    /// `max_blocks` counts them all, so a loop whose body is skipped or only control flow still
    /// ends.
    ///
    /// A line read *again* — below the furthest point read in the program (a loop pass, a call,
    /// a jump back), or in a subroutine file — also counts against `max_repeated_lines`: a long
    /// program read once may have tens of millions of lines, but a runaway loop is work done
    /// again, and that bound stops it within seconds.
    #[inline]
    fn count_line(&mut self) -> Result<(), Diagnostic> {
        self.stats.lines_read += 1;
        if self.stats.lines_read > self.opts.max_blocks {
            return Err(self.too_many_blocks(self.block.span()));
        }
        if !self.files.is_empty() || self.block.offset < self.high_water {
            self.repeated_lines += 1;
            if self.repeated_lines > self.opts.max_repeated_lines {
                return Err(self.too_many_repeated_lines());
            }
        } else {
            self.high_water = self.block.offset + 1;
        }
        Ok(())
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
    }

    #[cold]
    fn too_many_blocks(&self, span: stanok_canon::Span) -> Diagnostic {
        Diagnostic::error(
            "interp::too-many-blocks",
            format!(
                "more than {} lines read: stopping (endless loop?)",
                self.opts.max_blocks
            ),
            span,
        )
        .with_note(
            "the bound counts every line read, loops and skipped lines included: the option \
             --max-blocks",
        )
    }

    /// Executes one line. Ok(true) when the program is over.
    fn step(&mut self) -> Result<bool, Diagnostic> {
        if self.lab.is_some() {
            return self.lab_step();
        }
        let here = self.read_position();
        if !self.read()? {
            return self.end_of_input();
        }
        // Syntax problems: warnings are kept, the first error stops here.
        let mut first_error = None;
        // Most lines have no syntax diagnostics: skip setting up the drain then.
        if !self.syntax.is_empty() {
            for d in self.syntax.drain(..) {
                if d.is_error() {
                    first_error.get_or_insert(d);
                } else if self.flow.skipping().is_none() {
                    self.warnings.push(d);
                }
            }
        }
        let dialect = self.opts.dialect;
        // RS274/NGC program delimiters.
        if dialect == Dialect::Rs274ngc && self.block.percent {
            let first = std::mem::replace(&mut self.first_line, false);
            if first {
                self.percent_open = true;
                return Ok(false);
            }
            if self.percent_open && self.flow.skipping().is_none() {
                // The closing `%` without a program end: LinuxCNC's FINISH.
                self.queue
                    .push_back(Spanned::new(self.block.span(), Canon::Finish));
                return Ok(true);
            }
            return Ok(false);
        }
        // Only the first non-blank line matters here: do not scan every line's text.
        if self.first_line && !self.block.text.trim().is_empty() {
            self.first_line = false;
        }
        // O-word control flow decides whether this line runs at all.
        if dialect == Dialect::Rs274ngc {
            let action = {
                let eval = params::Evaluator {
                    block: &self.block,
                    params: &self.params,
                    state: &self.state,
                };
                if let Some(e) = first_error.take() {
                    if self.flow.skipping().is_some() {
                        // Errors in skipped text do not count (LinuxCNC reads it the same way).
                        None
                    } else {
                        return Err(e);
                    }
                } else {
                    Some(self.flow.on_line(
                        &self.block,
                        &eval,
                        here,
                        self.read_position(),
                        &self.opts,
                    )?)
                }
            };
            match action {
                None | Some(FlowAction::Skip) => return Ok(false),
                Some(FlowAction::Seek(pos)) => {
                    self.seek_to(pos)?;
                    self.count_block();
                    self.apply_flow_params();
                    self.finish_lathe_capture()?;
                    return Ok(false);
                }
                Some(FlowAction::CallFile { path, label }) => {
                    self.open_subroutine_file(&path, &label)?;
                    self.count_block();
                    self.apply_flow_params();
                    return Ok(false);
                }
                Some(FlowAction::ReturnFromFile(pos)) => {
                    self.files.pop();
                    self.flow.set_source(self.files.len());
                    self.seek_to(pos)?;
                    self.count_block();
                    self.apply_flow_params();
                    self.finish_lathe_capture()?;
                    return Ok(false);
                }
                Some(FlowAction::Handled) => {
                    self.count_block();
                    self.apply_flow_params();
                    return Ok(false);
                }
                Some(FlowAction::Execute) => {}
            }
            if self.block.block_delete && self.opts.block_delete {
                return Ok(false);
            }
        } else if self.hll.is_some() || self.block.hll().statement {
            // Out of line: the HLL path must not enlarge `step`, which every block of every
            // program runs (a second inlined `execute_block` here cost plain programs registers).
            return self.hll_line(here, first_error);
        } else if let Some(e) = first_error {
            return Err(e);
        }
        let done = self.execute_block()?;
        self.count_block();
        Ok(done)
    }

    /// AxiOMA: a line once the program has HLL (or its first HLL line): statements, control flow
    /// and the ISO blocks inside it.
    #[cold]
    #[inline(never)]
    fn hll_line(
        &mut self,
        here: SourcePos,
        first_error: Option<Diagnostic>,
    ) -> Result<bool, Diagnostic> {
        match self.hll_step(here, first_error)? {
            hll::HllStep::Done => Ok(false),
            hll::HllStep::Execute(owner) => {
                let end = self.execute_block()?;
                self.count_block();
                if let Some(owner) = owner {
                    if !end {
                        self.hll_after_iso(owner)?;
                    }
                }
                Ok(end)
            }
        }
    }

    /// Lab dialects: one execution unit of the front end (an NC-31 group, or one block).
    #[cold]
    fn lab_step(&mut self) -> Result<bool, Diagnostic> {
        let Some(lab) = self.lab.as_deref_mut() else {
            return Ok(true);
        };
        let (done, units) = lab.step(&mut self.queue, &mut self.warnings, &self.opts)?;
        self.stats.lines_read += units;
        self.stats.blocks_executed += units;
        if let Some(c) = self.queue.back() {
            self.lab_span = c.span;
        }
        if self.stats.lines_read > self.opts.max_blocks {
            // Where the last unit that produced a command was (line 1 before any): the lab
            // front ends keep no block of their own here.
            return Err(self.too_many_blocks(self.lab_span));
        }
        Ok(done)
    }

    /// Lab dialects (NC-31, 2P32, MC2101, GOST-20999): their modal state after the commands
    /// produced so far. None for AxiOMA and RS274/NGC.
    pub fn lab_state(&self) -> Option<&LabState> {
        self.lab.as_deref().map(labs::LabRun::state)
    }

    /// One step, then the bounds on its warnings (`admit_warnings`).
    #[inline]
    fn step_admitting_warnings(&mut self) -> Result<bool, Diagnostic> {
        let from = self.warnings.len();
        let r = self.step();
        if self.warnings.len() > from {
            self.admit_warnings(from);
        }
        r
    }

    /// Bounds the warnings a step added (`warnings[from..]`), so that their number — and the
    /// text a caller prints for them — grows at most linearly with the program:
    /// * a warning already given (same code and span: a loop passing the line again) is dropped;
    /// * at most `max_diagnostics_per_line` per line; the last one kept gets a note counting the
    ///   rest (`and K more on this line`);
    /// * at most [`MAX_WARNINGS`] in all, the last one noting how many more there were.
    #[cold]
    #[inline(never)]
    fn admit_warnings(&mut self, from: usize) {
        let added: Vec<Diagnostic> = self.warnings.drain(from..).collect();
        let per_line = self.opts.max_diagnostics_per_line.max(1);
        for w in added {
            if self.warnings.len() >= MAX_WARNINGS {
                // Full: count, remember nothing more (memory stays bounded too).
                self.dropped_warnings += 1;
                let n = self.dropped_warnings;
                if let Some(last) = self.warnings.last_mut() {
                    note_more(last, n, "in the run (at most 1000 warnings are kept)");
                }
                continue;
            }
            let key = (w.code.to_string(), w.span.start, w.span.end, w.file.clone());
            if !self.warning_keys.insert(key) {
                continue;
            }
            let count = self
                .warnings_per_line
                .entry((w.file.clone(), w.span.line))
                .or_insert(0);
            *count += 1;
            if *count > per_line {
                let more = *count - per_line;
                if let Some(last) = self
                    .warnings
                    .iter_mut()
                    .rev()
                    .find(|k| k.span.line == w.span.line && k.file == w.file)
                {
                    note_more(last, more, "on this line (--max-diagnostics-per-line)");
                }
                continue;
            }
            self.warnings.push(w);
        }
    }

    /// One more block completed: `Stats::blocks_executed` counts a block once it has run, so a
    /// block that fails is not among them, in every dialect (the lab front ends count the units
    /// they complete). Counted after the block; the work bound is `count_line`'s.
    fn count_block(&mut self) {
        self.stats.blocks_executed += 1;
    }

    /// Parameter writes a control-flow line requested (call arguments, return values).
    fn apply_flow_params(&mut self) {
        for (slot, v) in self.flow.take_param_writes() {
            match slot {
                flow::ParamOp::Write(slot) => self.params.write(&slot, v),
                flow::ParamOp::PushScope => self.params.push_scope(),
                flow::ParamOp::PopScope => {
                    if let Some(saved) = self.params.pop_scope() {
                        self.restore_on_return(&saved);
                    }
                }
            }
        }
    }

    /// M73: the subroutine returns, its caller's modal state comes back (commands carry the
    /// `endsub`/`return` line's span).
    fn restore_on_return(&mut self, saved: &rs274::modal_context::SavedContext) {
        let out = ctx::Emitter {
            queue: &mut self.queue,
            span: self.block.span(),
            number: self.block.number,
            label_digits: 0,
        };
        let mut cx = Ctx {
            block: &self.block,
            words: &mut self.words,
            st: &mut self.state,
            out,
            opts: &self.opts,
            warnings: &mut self.warnings,
            axioma: &mut self.axioma,
            lathe_call: &mut self.lathe_call,
        };
        rs274::modal_context::restore(&mut cx, &mut self.params, saved);
    }

    #[inline(always)]
    fn execute_block(&mut self) -> Result<bool, Diagnostic> {
        // AxiOMA words with HLL expressions are evaluated first (journalled, undone on failure);
        // every other block goes straight on. Invariant: a line of a program without HLL has no
        // HLL box at all (`Block::hll`), so this is one pointer test for every RS274/NGC block.
        if !self.block.has_hll_exprs() {
            return self.execute_words(&[]);
        }
        self.execute_block_with_expressions()
    }

    #[cold]
    #[inline(never)]
    fn execute_block_with_expressions(&mut self) -> Result<bool, Diagnostic> {
        // Sets `words.message` for `MSG(expr)`: `Words::fill` leaves it alone, the AxiOMA
        // executor takes it. Invariant: `words.message` is `None` outside this function, so the
        // per-block path neither clears nor tests it.
        let values = self.hll_prepare_block()?;
        let result = self.execute_words(&values);
        self.words.message = None;
        if result.is_err() {
            self.hll_rollback();
        }
        result
    }

    /// Executes the block with `hll_values`, the values of its HLL expression words.
    fn execute_words(&mut self, hll_values: &[(u32, f64)]) -> Result<bool, Diagnostic> {
        let dialect = self.opts.dialect;
        // The block runs on the live state; a failure restores this copy and the journals of the
        // large parts (see `state::Journalled`).
        let backup = self.state.begin_block();
        // AxiOMA blocks write behind `axioma_held` (compensation may still insert motions among
        // them); committed blocks are released to `queue` below.
        let axioma_backup = (dialect == Dialect::Axioma).then(|| self.axioma.clone());
        // RS274/NGC: commands held for cutter compensation may be edited by this block: keep
        // copies to restore if it fails.
        let held_backup: Vec<Spanned<Canon>> = if self.state.rs274.comp.on() {
            let len = self.queue.len();
            let h = self.held().min(len);
            self.queue.iter().skip(len - h).cloned().collect()
        } else {
            Vec::new()
        };
        let target = match dialect {
            Dialect::Axioma => &mut self.axioma_held,
            _ => &mut self.queue,
        };
        let mark = target.len();
        let span = self.block.span();
        let number = self.block.number;
        let label_digits = self.block.number_span.map_or(0, |s| {
            self.block
                .slice(s)
                .bytes()
                .filter(u8::is_ascii_digit)
                .count()
                .min(9) as u8
        });
        let mut out = ctx::Emitter {
            queue: target,
            span,
            number,
            label_digits,
        };
        let mut pending_params: Vec<(params::Slot, f64)> = Vec::new();
        {
            let eval = params::Evaluator {
                block: &self.block,
                params: &self.params,
                state: &self.state,
            };
            self.words
                .fill(&self.block, &eval, dialect, &mut self.warnings, hll_values)?;
            // Assignments are evaluated with the old values and applied after the line.
            for a in &self.block.assignments {
                let v = eval.eval(a.value)?;
                let slot = eval.assignment_slot(&a.target, a.value)?;
                pending_params.push((slot, v));
            }
            if dialect == Dialect::Rs274ngc {
                // LinuxCNC keeps one comment per line: the last one.
                if let Some(c) = self.block.comments.iter().rev().find(|c| {
                    matches!(
                        c.kind,
                        CommentKind::Paren | CommentKind::Msg | CommentKind::Debug
                    )
                }) {
                    let text = self.block.slice(c.text);
                    let cmd = match c.kind {
                        CommentKind::Msg => Some(Canon::Message {
                            text: text.to_string(),
                        }),
                        // #5599 = 0 silences (DEBUG,…) (LinuxCNC; 1 at start).
                        CommentKind::Debug if self.params.get(5599) == 0.0 => None,
                        CommentKind::Debug => Some(Canon::Message {
                            text: flow::substitute_parameters(text, &eval),
                        }),
                        // rs274 drops the blanks a comment starts with; LOG… comments are
                        // LinuxCNC's program log, PRINT goes to its console (not a command).
                        _ => subfiles::log_command(text.trim_start(), &eval).unwrap_or_else(|| {
                            Some(Canon::Comment {
                                text: text.trim_start().to_string(),
                            })
                        }),
                    };
                    if let Some(cmd) = cmd {
                        out.push(cmd);
                    }
                }
            }
        }
        // Parameter and tool-table writes of the block are journalled, undone if it fails.
        self.params.begin_block();
        let result = {
            let mut cx = Ctx {
                block: &self.block,
                words: &mut self.words,
                st: &mut self.state,
                out,
                opts: &self.opts,
                warnings: &mut self.warnings,
                axioma: &mut self.axioma,
                lathe_call: &mut self.lathe_call,
            };
            match dialect {
                Dialect::Rs274ngc => rs274::execute(&mut cx, &mut self.params),
                Dialect::Mazatrol => mazatrol::execute(&mut cx),
                Dialect::Balt => balt::execute(&mut cx),
                _ => axioma::execute(&mut cx),
            }
        };
        let outcome = match result {
            Ok(o) => o,
            Err(d) => {
                // Nothing of a failing block leaves the interpreter.
                match axioma_backup {
                    Some(b) => {
                        self.axioma_held.truncate(mark);
                        self.axioma = b;
                    }
                    None => {
                        self.queue.truncate(mark - held_backup.len());
                        self.queue.extend(held_backup);
                    }
                }
                self.state.rollback(backup);
                self.lathe_call = None;
                self.params.rollback();
                return Err(d);
            }
        };
        // Commit.
        self.params.commit();
        if dialect == Dialect::Axioma {
            self.axioma.release(&mut self.axioma_held, &mut self.queue);
        }
        for (slot, v) in pending_params {
            self.params.write(&slot, v);
        }
        if self.lathe_call.is_some() {
            self.start_lathe_capture()?;
        }
        Ok(outcome == Outcome::End)
    }

    /// How many commands at the back of the queue are held back (RS274/NGC cutter compensation
    /// may still move the last compensated corner); none once the run is over.
    #[inline(always)]
    fn held(&self) -> usize {
        // A G7x profile's commands never leave (see `lathe.rs`).
        if let Some(c) = &self.lathe {
            return self.queue.len().saturating_sub(c.before);
        }
        // Compensation off (almost every block): nothing held, nothing to scan.
        if !self.state.rs274.comp.on() {
            return 0;
        }
        self.held_when_compensating()
    }

    #[cold]
    fn held_when_compensating(&self) -> usize {
        let n = rs274::held_motions(&self.state.rs274);
        if n == 0 || self.phase == Phase::Done {
            return 0;
        }
        let mut seen = 0;
        for (i, c) in self.queue.iter().enumerate().rev() {
            if c.value.motion().is_some() {
                seen += 1;
                if seen == n {
                    return self.queue.len() - i;
                }
            }
        }
        self.queue.len()
    }

    fn end_of_input(&mut self) -> Result<bool, Diagnostic> {
        if self.opts.dialect == Dialect::Axioma {
            // A fragment without M30 ends with compensation still looking ahead: finish its path.
            self.axioma.finish(
                &self.opts,
                &mut self.axioma_held,
                &mut self.queue,
                &mut self.warnings,
            )?;
        }
        self.hll_end_of_input()?;
        if let Some(d) = self.flow.unterminated(&self.block) {
            return Err(d);
        }
        if self.opts.dialect == Dialect::Rs274ngc && !self.percent_open {
            return Err(Diagnostic::error(
                "rs274::no-program-end",
                "File ended with no percent sign or program end",
                self.block.span(),
            )
            .with_note("end the program with M2 or M30, or enclose it in % lines"));
        }
        Ok(true)
    }
}

impl<R: BufRead + Seek> Iterator for Interpreter<R> {
    type Item = Result<Spanned<Canon>, Diagnostic>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if self.queue.len() > self.held() {
                // The capture's count first: with nothing between pop_front and the return,
                // the command moves straight into the result (no extra copy of the 260-byte
                // Spanned<Canon> per command, measured with callgrind).
                if let Some(l) = &mut self.lathe {
                    l.before = l.before.saturating_sub(1);
                }
                if let Some(c) = self.queue.pop_front() {
                    return Some(Ok(c));
                }
            }
            match self.phase {
                Phase::Done => return None,
                Phase::Start => {
                    self.phase = Phase::Running;
                    let init = self.init_command();
                    self.queue.push_back(Spanned::new(Default::default(), init));
                }
                Phase::Running => match self.step_admitting_warnings() {
                    Ok(true) => self.phase = Phase::Done,
                    Ok(false) => {}
                    Err(d) => {
                        // An error inside a subroutine file is located in that file.
                        let d = match self.files.last() {
                            Some(f) => d.in_file(f.path.display().to_string()),
                            None => d,
                        };
                        self.errors += 1;
                        let go_on = self.opts.continue_after_error
                            && self.errors < self.opts.max_errors
                            && !matches!(
                                d.code,
                                stanok_canon::DiagCode::Stanok("rs274::no-program-end")
                                    | stanok_canon::DiagCode::Stanok("io::read")
                                    | stanok_canon::DiagCode::Stanok("io::seek")
                                    | stanok_canon::DiagCode::Stanok("interp::too-many-blocks")
                                    | stanok_canon::DiagCode::Stanok("hll::loop-limit")
                                    | stanok_canon::DiagCode::Stanok("hll::nesting-too-deep")
                                    | stanok_canon::DiagCode::Stanok("syntax::program-too-large")
                            )
                            && !d.code.to_string().starts_with("flow::");
                        if !go_on {
                            self.phase = Phase::Done;
                            self.queue.clear();
                        }
                        return Some(Err(d));
                    }
                },
            }
        }
    }
}
