//! The RS274/NGC front end: what the driver calls (`stanok_interp_core::FrontEnd`).
//!
//! ```text
//!  next_unit: a line ─▶ `%` delimiters ─▶ O-word control flow (flow.rs: skip, seek, call a file,
//!             return, M73 restore, the end of a G7x profile) ─▶ block delete ─▶ Execute
//!  begin:     journals of the RS274/NGC modes and the parameters; a copy of the commands cutter
//!             compensation holds (the next block may move their corner)
//!  execute:   words (expressions against the parameters), assignments (evaluated with the old
//!             values), the line's comment, then `execute` in LinuxCNC's order (lib.rs)
//!  commit:    parameters kept, assignments written, a G7x call starts its profile (lathe.rs)
//!  held:      the compensated corner and what follows it; a G7x profile's commands
//! ```

use crate::cutter_comp;
use crate::flow::{self, Flow, FlowAction};
use crate::lathe::LatheCapture;
use crate::lathe_cycles::LatheCall;
use crate::params::{self, Parameters, Slot};
use crate::Rs274State;
use stanok_canon::{Canon, Diagnostic, LengthUnits, Spanned};
use stanok_interp_core::{
    Core, CoreOptions, Emitter, FrontEnd, Hooks, Journalled, ModalState, MotionMode, Outcome,
    Parts, Read, Repeated, Unit, WordRules,
};
use stanok_syntax::{Block, CommentKind};
use std::collections::VecDeque;
use std::io::{BufRead, Seek};

/// RS274/NGC's options beside the common ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rs274Options {
    /// Arc tolerance T in mm; `None` = the document's 0.0005 in / 0.005 mm by units, or
    /// LinuxCNC 2.9's with `linuxcnc_arc_tolerance`.
    pub arc_tolerance_mm: Option<f64>,
    /// LinuxCNC 2.9's default arc tolerance (0.002828 in / 0.02828 mm) instead of the document's.
    pub linuxcnc_arc_tolerance: bool,
    /// User M codes M100–M199 passed to the machine as auxiliary functions (else refused as
    /// "Unknown m code", as LinuxCNC without an executable of that name).
    pub user_m_codes: bool,
    /// The machine's length unit (LinuxCNC `[TRAJ]LINEAR_UNITS`), in which numbered parameters
    /// hold lengths.
    pub machine_units: LengthUnits,
    /// G92 offsets survive M2/M30 and the run (LinuxCNC's default); false is LinuxCNC's
    /// `DISABLE_G92_PERSISTENCE`.
    pub g92_persistence: bool,
}

impl Default for Rs274Options {
    fn default() -> Self {
        Rs274Options {
            arc_tolerance_mm: None,
            linuxcnc_arc_tolerance: false,
            user_m_codes: false,
            machine_units: LengthUnits::Millimetres,
            g92_persistence: true,
        }
    }
}

/// The part of the front end a block's context carries (`cx.fe`).
#[derive(Debug)]
pub struct Rs274Part {
    /// RS274/NGC's modes beyond the common state (journalled with the block).
    pub modes: Journalled<Rs274State>,
    /// A G70–G72 block leaves its call here; after the block commits the front end runs the
    /// profile subroutine (cleared if the block fails). Kept out of the modes, which every
    /// block may copy, so that ordinary blocks do not pay for it.
    pub lathe_call: Option<LatheCall>,
    /// The words of a G7x profile's motion blocks, recorded while it runs
    /// (`lathe_cycles::profile_block`) and read by the cycle at its end (`lathe.rs`).
    pub profile_blocks: Vec<crate::lathe_cycles::ProfileBlock>,
    /// The running block recorded one of them (taken back if the block fails).
    pub profile_block_pushed: bool,
    /// Options.
    pub opts: Rs274Options,
}

impl Hooks for Rs274Part {
    #[inline(always)]
    fn programmed_point(&self) -> Option<[f64; 2]> {
        cutter_comp::programmed_point(&self.modes)
    }

    fn unused_word_message(&self, letter: u8) -> String {
        format!("{} word with no g code that uses it", letter as char)
    }

    fn axis_not_configured_message(&self, letter: u8) -> String {
        bad_axis_message(letter)
    }
}

/// LinuxCNC's wording for an axis the machine lacks: its reader does not know the letter.
fn bad_axis_message(letter: u8) -> String {
    format!(
        "Bad character '{}' used ({} axis is not configured on this machine)",
        (letter as char).to_ascii_lowercase(),
        letter as char
    )
}

/// How RS274/NGC sorts words: a repeated letter is an error.
pub(crate) const WORD_RULES: WordRules = WordRules {
    repeated: Repeated::Refuse("rs274::multiple-words"),
    second_word: None,
};

/// LinuxCNC's M-code modal groups (`Interp::ems`), −1: not an M code of 2.9 (index = code).
const M_GROUPS: [i8; 100] = [
    4, 4, 4, 7, 7, 7, 6, 8, 8, 8, // 0-9
    -1, -1, -1, -1, -1, -1, -1, -1, -1, 7, // 10-19
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, // 20-29
    4, -1, -1, -1, -1, -1, -1, -1, -1, -1, // 30-39
    -1, -1, -1, -1, -1, -1, -1, -1, 9, 9, // 40-49
    9, 9, 9, 9, -1, -1, -1, -1, -1, -1, // 50-59
    4, 6, 5, 5, 5, 5, 5, 5, 5, -1, // 60-69
    7, 7, 7, 7, -1, -1, -1, -1, -1, -1, // 70-79
    -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, // 80-89
    -1, -1, -1, -1, -1, -1, -1, -1, -1, 4, // 90-99
];

/// The modal group LinuxCNC reads M code `m` into (M100–M199: 10), if it knows the code.
fn m_group(m: f64) -> Option<i8> {
    if m.fract() != 0.0 || !(0.0..200.0).contains(&m) {
        return None;
    }
    let m = m as usize;
    let g = if m >= 100 { 10 } else { M_GROUPS[m] };
    (g >= 0).then_some(g)
}

/// LinuxCNC reads a block's words left to right and stops at the first one it cannot take —
/// a second G or M code of a modal group, a repeated letter, a value it cannot evaluate — before
/// it executes anything. Stanok finds these in another order (the word table, then the G codes,
/// then the M codes, then the block's meaning): `e` is the error Stanok found; this returns the
/// first reading conflict in text order instead, if there is one before it. `at_word`: `e` was
/// found reading the word at its span (an evaluation or word-table error), so only conflicts
/// before that word count — and a repeated letter at it (LinuxCNC checks the letter before it
/// evaluates the value); else any conflict in the block comes first.
#[cold]
fn first_reading_error(
    block: &Block,
    axes: &[bool; 9],
    e: Diagnostic,
    at_word: bool,
) -> Diagnostic {
    use stanok_syntax::{Address, Value};
    // The reader's own errors (a line it could not read whole, a bound) come first.
    let code = e.code.to_string();
    if code.starts_with("syntax::") || code.starts_with("flow::") {
        return e;
    }
    let mut letters = 0u32;
    let mut g_groups = Vec::new();
    let mut m_groups = Vec::new();
    for w in &block.words {
        let Address::Letter(l) = w.address else {
            continue;
        };
        let span = block.span_of(w.span);
        let at_error = at_word && span.start >= e.span.start;
        if at_word && span.start > e.span.start {
            break;
        }
        let axis = stanok_interp_core::ctx::AXIS_WORDS
            .iter()
            .position(|&a| a == l);
        let conflict = match (l, w.value) {
            // An axis the machine lacks: LinuxCNC's reader stops at the letter.
            _ if axis.is_some_and(|i| !axes[i]) => {
                Some(("interp::axis-not-configured", bad_axis_message(l)))
            }
            (b'G', _) | (b'M', _) if at_error => None,
            (b'G', Value::Number(v)) => {
                crate::group_of((v * 10.0).round() as u32).and_then(|group| {
                    (g_groups.contains(&group))
                        .then_some((
                            "rs274::two-g-codes-same-group",
                            "Two g codes used from same modal group".to_string(),
                        ))
                        .or_else(|| {
                            g_groups.push(group);
                            None
                        })
                })
            }
            (b'M', Value::Number(v)) => m_group(v).and_then(|group| {
                (m_groups.contains(&group))
                    .then_some((
                        "rs274::two-m-codes-same-group",
                        "Two m codes used from same modal group".to_string(),
                    ))
                    .or_else(|| {
                        m_groups.push(group);
                        None
                    })
            }),
            (b'A'..=b'Z', _) if l != b'G' && l != b'M' => {
                let bit = 1 << (l - b'A');
                let repeated = letters & bit != 0;
                letters |= bit;
                repeated.then(|| {
                    (
                        "rs274::multiple-words",
                        format!(
                            "Multiple {} words on one line",
                            (l as char).to_ascii_lowercase()
                        ),
                    )
                })
            }
            _ => None,
        };
        if let Some((code, message)) = conflict {
            if e.code == stanok_canon::DiagCode::Stanok(code) && e.span.start == span.start {
                return e;
            }
            return Diagnostic::error(code, message, span);
        }
        if at_error {
            break;
        }
    }
    e
}

/// The RS274/NGC (LinuxCNC) front end.
#[derive(Debug)]
pub struct Rs274 {
    pub(crate) part: Rs274Part,
    /// Numbered and named parameters, the tool table, M70 contexts.
    pub(crate) params: Parameters,
    /// O-word control flow.
    pub(crate) flow: Flow,
    /// G70–G72: the profile subroutine being executed (`lathe.rs`).
    pub(crate) lathe: Option<LatheCapture>,
    /// The program started with `%`: the next `%` ends it.
    percent_open: bool,
    /// No non-blank line read yet (a `%` there opens the program).
    first_line: bool,
    /// The block's assignments, evaluated with the old values, written when it commits.
    pending: Vec<(Slot, f64)>,
    /// Cutter compensation: the queue length at the block's start and how many commands of
    /// earlier blocks were held then (for `restamp_released`).
    held_at_begin: Option<(usize, usize)>,
}

impl Rs274 {
    /// Cutter compensation: commands an earlier block produced and this one released (the held
    /// commands before the block's own that are no longer held) carry this block's N label, as
    /// rs274 prints them: LinuxCNC issues a queued compensated move while it executes the block
    /// that completes its corner, and prints the label of the line it executes.
    #[cold]
    fn restamp_released<R: BufRead + Seek>(&self, core: &mut Core<R>, mark: usize, held: usize) {
        let still_held = self.held(&core.queue, false);
        let first_kept = core.queue.len().saturating_sub(still_held);
        let number = core.block.number;
        let digits = core.block.number_span.map_or(0, |s| {
            core.block
                .slice(s)
                .bytes()
                .filter(u8::is_ascii_digit)
                .count()
                .min(9) as u8
        });
        for c in core
            .queue
            .range_mut(mark.saturating_sub(held)..mark.min(first_kept))
        {
            c.block_number = number;
            c.label_digits = digits;
        }
    }

    /// The front end at power-on; sets the common state's RS274/NGC defaults (no motion mode,
    /// the machine's units, the stored G5x system with its rotation, G92).
    pub fn new(opts: &CoreOptions, rs: Rs274Options, state: &mut ModalState) -> Self {
        state.motion = MotionMode::None;
        state.units = opts.initial_units;
        let mut params = Parameters::default();
        params.set_machine_units(rs.machine_units);
        params.preset_from(&opts.control);
        let system = opts.control.offsets.active_system.clamp(1, 9);
        let (offset, rotation) = crate::g5x_from_params(&params, system);
        state.g5x_index = system;
        state.frame.set_origin(offset);
        if rotation != 0.0 {
            state
                .frame
                .set_rotation(stanok_interp_core::frame::rotation(2, rotation));
        }
        state.xy_rotation_deg = rotation;
        if opts.control.offsets.g92_applied {
            state.frame.set_shift(opts.control.offsets.g92);
        }
        Rs274 {
            part: Rs274Part {
                modes: Journalled::default(),
                lathe_call: None,
                profile_blocks: Vec::new(),
                profile_block_pushed: false,
                opts: rs,
            },
            params,
            flow: Flow::default(),
            lathe: None,
            percent_open: false,
            first_line: true,
            pending: Vec::new(),
            held_at_begin: None,
        }
    }

    /// Parameters and tool table as the blocks run so far left them.
    pub fn parameters(&self) -> &Parameters {
        &self.params
    }

    /// The same, mutable (e.g. to preset values before a run).
    pub fn parameters_mut(&mut self) -> &mut Parameters {
        &mut self.params
    }

    /// RS274/NGC's modes beyond the common state.
    pub fn modes(&self) -> &Rs274State {
        &self.part.modes
    }

    /// The O-word line in `core.block` and what the control flow made of it.
    fn control_flow<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        here: stanok_syntax::SourcePos,
        first_error: Option<Diagnostic>,
    ) -> Result<Option<FlowAction>, Diagnostic> {
        if let Some(e) = first_error {
            if self.flow.skipping().is_some() {
                // Errors in skipped text do not count (LinuxCNC reads it the same way).
                return Ok(None);
            }
            return Err(e);
        }
        let eval = params::Evaluator {
            block: &core.block,
            params: &self.params,
            state: &core.state,
            modes: &self.part.modes,
        };
        let next = core.source.position();
        self.flow
            .on_line(&core.block, &eval, here, next, &core.opts)
            .map(Some)
    }

    /// Parameter writes a control-flow line requested (call arguments, return values).
    pub(crate) fn apply_flow_params<R: BufRead + Seek>(&mut self, core: &mut Core<R>) {
        for (slot, v) in self.flow.take_param_writes() {
            match slot {
                flow::ParamOp::Write(slot) => self.params.write(&slot, v),
                flow::ParamOp::PushScope => self.params.push_scope(),
                flow::ParamOp::PopScope => {
                    if let Some(saved) = self.params.pop_scope() {
                        // M73: the subroutine returns, its caller's modal state comes back
                        // (commands carry the `endsub`/`return` line's span).
                        let (span, number) = (core.block.span(), core.block.number);
                        let mut cx = core.parts(span, number).with(&mut self.part);
                        crate::modal_context::restore(&mut cx, &mut self.params, &saved);
                    }
                }
            }
        }
    }

    /// The current line's comment as LinuxCNC keeps it (one per line: the last one).
    fn comment(
        &self,
        block: &Block,
        out: &mut Emitter<'_>,
        eval: &params::Evaluator<'_>,
    ) -> Result<(), Diagnostic> {
        let Some(c) = block.comments.iter().rev().find(|c| {
            matches!(
                c.kind,
                CommentKind::Paren | CommentKind::Msg | CommentKind::Debug
            )
        }) else {
            return Ok(());
        };
        let text = block.slice(c.text);
        // (ABORT, text): LinuxCNC stops the program with the text, parameters substituted, before
        // anything of the block runs.
        if c.kind == CommentKind::Paren {
            let t = text.trim_start();
            // (`get`: the comment may start with any character; "abort," is ASCII, so after it
            // byte 6 is a character boundary.)
            if t.get(..6).is_some_and(|p| p.eq_ignore_ascii_case("abort,")) {
                let rest = t.get(6..).unwrap_or("").trim_start();
                let message = crate::subfiles::substitute_parameters(rest, eval);
                return Err(
                    Diagnostic::error("rs274::abort", message, block.span_of(c.text)).fatal(),
                );
            }
        }
        let cmd = match c.kind {
            CommentKind::Msg => Some(Canon::Message {
                text: text.to_string(),
            }),
            // #5599 = 0 silences (DEBUG,…) (LinuxCNC; 1 at start).
            CommentKind::Debug if self.params.get(5599) == 0.0 => None,
            CommentKind::Debug => Some(Canon::Message {
                text: crate::subfiles::substitute_parameters(text, eval),
            }),
            // rs274 drops the blanks a comment starts with; LOG… comments are LinuxCNC's
            // program log, PRINT goes to its console (not a command).
            _ => crate::subfiles::log_command(text.trim_start(), eval).unwrap_or_else(|| {
                Some(Canon::Comment {
                    text: text.trim_start().to_string(),
                })
            }),
        };
        if let Some(cmd) = cmd {
            out.push(cmd);
        }
        Ok(())
    }

    #[cold]
    pub(crate) fn held_when_compensating(
        &self,
        queue: &VecDeque<Spanned<Canon>>,
        done: bool,
    ) -> usize {
        let n = crate::held_motions(&self.part.modes);
        if n == 0 || done {
            return 0;
        }
        let mut seen = 0;
        for (i, c) in queue.iter().enumerate().rev() {
            if c.value.motion().is_some() {
                seen += 1;
                if seen == n {
                    return queue.len() - i;
                }
            }
        }
        queue.len()
    }
}

impl FrontEnd for Rs274 {
    /// The copies of the commands compensation holds (the block may move their corner).
    type Undo = Vec<Spanned<Canon>>;

    #[inline(always)]
    fn next_unit<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<Unit, Diagnostic> {
        let here = match core.read_line()? {
            Read::Line(here) => here,
            Read::EndOfInput => return Ok(Unit::EndOfInput),
            Read::EndOfFile => return Err(self.file_without_endsub(core)),
        };
        // Syntax problems: warnings are kept, the first error stops here.
        let first_error = core.take_syntax(self.flow.skipping().is_some());
        // Program delimiters.
        if core.block.percent {
            let first = std::mem::replace(&mut self.first_line, false);
            if first {
                self.percent_open = true;
                return Ok(Unit::Skip);
            }
            if self.percent_open {
                if let Some(d) = self.flow.skipped_to_percent(&core.block) {
                    return Err(d);
                }
                // The closing `%` without a program end: LinuxCNC's FINISH.
                core.queue
                    .push_back(Spanned::new(core.block.span(), Canon::Finish));
                return Ok(Unit::End);
            }
            return Ok(Unit::Skip);
        }
        // Only the first non-blank line matters here: do not scan every line's text.
        if self.first_line && !core.block.text.trim().is_empty() {
            self.first_line = false;
        }
        // O-word control flow decides whether this line runs at all.
        match self.control_flow(core, here, first_error)? {
            None | Some(FlowAction::Skip) => return Ok(Unit::Skip),
            Some(FlowAction::Execute) => {}
            Some(action) => {
                self.flow_action(core, action)?;
                return Ok(Unit::Skip);
            }
        }
        if core.block.block_delete && core.opts.block_delete {
            return Ok(Unit::Skip);
        }
        Ok(Unit::Execute)
    }

    #[inline(always)]
    fn begin<R: BufRead + Seek>(&mut self, core: &Core<R>) -> Self::Undo {
        self.part.modes.begin_block();
        // Parameter and tool-table writes of the block are journalled, undone if it fails.
        self.params.begin_block();
        // Commands held for cutter compensation may be edited by this block: keep copies to
        // restore if it fails.
        if self.part.modes.comp.on() {
            let len = core.queue.len();
            let h = self.held(&core.queue, false).min(len);
            self.held_at_begin = Some((len, h));
            core.queue.iter().skip(len - h).cloned().collect()
        } else {
            self.held_at_begin = None;
            Vec::new()
        }
    }

    #[inline(always)]
    fn execute(&mut self, mut parts: Parts<'_>) -> Result<Outcome, Diagnostic> {
        {
            let eval = params::Evaluator {
                block: parts.block,
                params: &self.params,
                state: parts.st,
                modes: &self.part.modes,
            };
            let filled = parts
                .words
                .fill(parts.block, &eval, &WORD_RULES, parts.warnings);
            if let Err(e) = filled {
                return Err(first_reading_error(parts.block, &parts.opts.axes, e, true));
            }
            // Assignments are evaluated with the old values and applied after the line.
            self.pending.clear();
            for a in &parts.block.assignments {
                let v = eval
                    .eval(a.value)
                    .map_err(|e| first_reading_error(parts.block, &parts.opts.axes, e, true))?;
                let slot = eval
                    .assignment_slot(&a.target, a.value)
                    .map_err(|e| first_reading_error(parts.block, &parts.opts.axes, e, true))?;
                self.pending.push((slot, v));
            }
            self.comment(parts.block, &mut parts.out, &eval)?;
        }
        let (block, axes) = (parts.block, &parts.opts.axes);
        let mut cx = parts.with(&mut self.part);
        crate::execute(&mut cx, &mut self.params)
            .map_err(|e| first_reading_error(block, axes, e, false))
    }

    #[cold]
    fn rollback<R: BufRead + Seek>(&mut self, held: Self::Undo, core: &mut Core<R>) {
        self.pending.clear();
        // The block's scratch mark of held commands goes with it.
        self.held_at_begin = None;
        self.part.modes.rollback();
        self.part.lathe_call = None;
        if self.part.profile_block_pushed {
            self.part.profile_blocks.pop();
            self.part.profile_block_pushed = false;
        }
        self.params.rollback();
        // The held commands the block may have moved come back as they were.
        let out = &mut core.queue;
        out.truncate(out.len() - held.len().min(out.len()));
        out.extend(held);
    }

    #[inline(always)]
    fn commit<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        _outcome: Outcome,
    ) -> Result<(), Diagnostic> {
        // A block counts once it has run (`Core::count_block`).
        core.count_block();
        self.params.commit();
        if let Some((mark, held)) = self.held_at_begin.take() {
            if held > 0 {
                self.restamp_released(core, mark, held);
            }
        }
        if !self.pending.is_empty() {
            for (slot, v) in self.pending.drain(..) {
                self.params.write(&slot, v);
            }
        }
        self.part.profile_block_pushed = false;
        if self.part.lathe_call.is_some() {
            self.start_lathe_capture(core)?;
        }
        Ok(())
    }

    #[inline(always)]
    fn held(&self, queue: &VecDeque<Spanned<Canon>>, done: bool) -> usize {
        // A G7x profile's commands never leave (see `lathe.rs`).
        if let Some(c) = &self.lathe {
            return queue.len().saturating_sub(c.before);
        }
        // Compensation off (almost every block): nothing held, nothing to scan.
        if !self.part.modes.comp.on() {
            return 0;
        }
        self.held_when_compensating(queue, done)
    }

    #[inline(always)]
    fn released(&mut self) {
        if let Some(l) = &mut self.lathe {
            l.before = l.before.saturating_sub(1);
        }
    }

    fn finish<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<(), Diagnostic> {
        if let Some(d) = self.flow.unterminated(&core.block) {
            return Err(d);
        }
        if !self.percent_open {
            return Err(Diagnostic::error(
                "rs274::no-program-end",
                "File ended with no percent sign or program end",
                core.block.span(),
            )
            .fatal()
            .with_note("end the program with M2 or M30, or enclose it in % lines"));
        }
        Ok(())
    }
}

impl Rs274 {
    /// An O-word line the control flow acted on: move the read position, open or close a
    /// subroutine file, apply its parameter operations, end a G7x profile.
    #[cold]
    fn flow_action<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        action: FlowAction,
    ) -> Result<(), Diagnostic> {
        match action {
            FlowAction::Seek(pos) => {
                core.seek(pos)?;
                core.count_block();
                self.apply_flow_params(core);
                self.finish_lathe_capture(core)?;
            }
            FlowAction::CallFile { path, label } => {
                self.open_subroutine_file(core, &path, &label)?;
                core.count_block();
                self.apply_flow_params(core);
            }
            FlowAction::ReturnFromFile(pos) => {
                core.source.pop();
                self.flow.set_source(core.source.depth());
                core.seek(pos)?;
                core.count_block();
                self.apply_flow_params(core);
                self.finish_lathe_capture(core)?;
            }
            FlowAction::Handled => {
                core.count_block();
                self.apply_flow_params(core);
            }
            FlowAction::Execute | FlowAction::Skip => {}
        }
        Ok(())
    }
}
