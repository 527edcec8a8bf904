//! The AxiOMA front end: what the driver calls (`stanok_interp_core::FrontEnd`).
//!
//! ```text
//!  next_unit: a line ─▶ HLL (a statement, or the ISO block a construct runs: hll/) ─▶ the word
//!             expressions and MSG(expr) of the block, journalled ─▶ Execute
//!  begin:     journals of the chain and the modes; a copy of the per-run `Extension`
//!  execute:   words (repeats: the last one wins, with a warning), then `execute` in the manual's
//!             prefix/postfix order (lib.rs); commands go to `staging`
//!  commit:    `Extension::release` moves to the queue what no look-ahead can change any more;
//!             the construct the block was the body of goes on
//!  rollback:  the chain, the modes, the Extension copy, the HLL writes of the block
//! ```

use crate::chain::AxiomaChain;
use crate::cycles::CycleState;
use crate::extension::{AxiomaMachineParams, Extension};
use crate::hll::{self, Hll, HllStep, OwnerToken};
use crate::modes::AxiomaModes;
use crate::probe::{ProbeLatch, ProbeState};
use crate::technology::Technology;
use stanok_canon::{Diagnostic, Pose};
use stanok_interp_core::{
    Core, CoreOptions, FrontEnd, Hooks, Journalled, ModalState, Outcome, Parts, Read, Repeated,
    Unit, WordRules, WordValues,
};
use stanok_syntax::{Block, ColSpan, ExprId};
use std::io::{BufRead, Seek};

/// The part of the front end a block's context carries (`cx.fe`).
#[derive(Debug)]
pub struct AxiomaPart {
    /// The chain of frames, shift, zero-offset and workpiece selections (journalled).
    pub chain: Journalled<AxiomaChain>,
    /// Polar programming, tool length compensation, edges, G28/G29, diameter axes (journalled).
    pub modes: Journalled<AxiomaModes>,
    /// The active canned cycle and its Q parameters (journalled).
    pub cycle: Journalled<CycleState>,
    /// G96/G97 per spindle (journalled).
    pub tech: Journalled<Technology>,
    /// G75 mode and the last probe latch (journalled).
    pub probe: Journalled<ProbeState>,
    /// Compensation look-ahead, M functions, splines, orientation (copied per block: restored
    /// from the copy if the block fails). The parts above are `Copy` and journalled instead: a
    /// block copies them only when it writes them, which most blocks do not (the copy of 600
    /// bytes per block was measured, docs/performance.md).
    pub ext: Extension,
    /// The machine parameters of the AxiOMA functions.
    pub params: AxiomaMachineParams,
    /// `MSG(expr)`: the message text the high-level language evaluated for this block; `None`
    /// outside a block that has one.
    pub message: Option<String>,
    /// The spline whose error was reported (span of its first point): diagnostic bookkeeping that
    /// survives the failed block's rollback on purpose, so that a run continuing after errors
    /// reports a bad spline once (`SplineState::flush_once`).
    pub reported_spline: Option<stanok_canon::Span>,
}

impl Hooks for AxiomaPart {
    #[inline(always)]
    fn diameter_words(&self) -> Option<&[bool; 9]> {
        Some(&self.modes.axioma_diameter)
    }

    #[inline(always)]
    fn take_pending_tlo(&mut self) -> Option<Pose> {
        // Tested before `take`: the `&mut` access journals the modes, and almost every motion
        // has nothing pending.
        if self.modes.pending_tlo.is_some() {
            self.modes.pending_tlo.take()
        } else {
            None
        }
    }
}

/// How AxiOMA sorts words: only the last of a repeated letter takes effect (the manual), with a
/// warning.
const WORD_RULES: WordRules = WordRules {
    repeated: Repeated::LastWins("axioma::repeated-word"),
    second_word: None,
};

/// The values the HLL computed for a block's expression words.
struct HllValues<'a>(&'a [(u32, f64)]);

impl WordValues for HllValues<'_> {
    fn expr(&self, block: &Block, _e: ExprId, at: ColSpan) -> Result<f64, Diagnostic> {
        // The AxiOMA reader writes no RS274/NGC expressions.
        Err(Diagnostic::error(
            "interp::bad-value",
            "not an AxiOMA expression",
            block.span_of(at),
        ))
    }

    #[inline(always)]
    fn hll(&self, id: u32) -> Option<f64> {
        self.0.iter().find(|(i, _)| *i == id).map(|&(_, v)| v)
    }
}

/// The AxiOMA Control front end.
#[derive(Debug)]
pub struct Axioma {
    pub(crate) part: AxiomaPart,
    /// The high-level language: variables and control flow; `None` until the first HLL line
    /// or expression, so that programs without HLL keep their speed.
    pub(crate) hll: Option<Box<Hll>>,
    /// The construct the executing ISO block is the single-statement body of.
    owner: Option<OwnerToken>,
    /// The executing block evaluated HLL expressions (their writes are undone if it fails).
    pub(crate) hll_block: bool,
    /// Their values.
    pub(crate) hll_values: Vec<(u32, f64)>,
}

impl Axioma {
    /// The front end at power-on; sets the common state's AxiOMA defaults (G98).
    pub fn new(_opts: &CoreOptions, params: AxiomaMachineParams, state: &mut ModalState) -> Self {
        state.retract_to_initial = true;
        Axioma {
            part: AxiomaPart {
                chain: Journalled::default(),
                modes: Journalled::default(),
                cycle: Journalled::default(),
                tech: Journalled::default(),
                probe: Journalled::default(),
                ext: Extension::default(),
                params,
                message: None,
                reported_spline: None,
            },
            hll: None,
            owner: None,
            hll_block: false,
            hll_values: Vec::new(),
        }
    }

    /// The chain of frames as the blocks run so far left it.
    pub fn chain(&self) -> &AxiomaChain {
        &self.part.chain
    }

    /// AxiOMA's own modes (polar, tool length compensation, edges …).
    pub fn modes(&self) -> &AxiomaModes {
        &self.part.modes
    }

    /// The value of a high-level-language variable (a scalar) visible now.
    pub fn hll_variable(&self, name: &str) -> Option<hll::value::HVal> {
        self.hll.as_deref()?.vars.get(name).cloned()
    }

    /// The M vector ("active functions" screen): each modal M group's name and the function it
    /// shows (spec axioma-2 §4.1, §5).
    pub fn m_vector(&self) -> Vec<(String, u32)> {
        self.part.ext.m.display(&self.part.params.m_table)
    }

    /// The result of the last G75 (or batch-mode) probe move.
    pub fn probe_latch(&self) -> Option<ProbeLatch> {
        self.part.probe.latch
    }

    /// A line once the program has HLL (or its first HLL line): statements, control flow and
    /// the ISO blocks inside it.
    #[cold]
    #[inline(never)]
    fn hll_line<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        here: stanok_syntax::SourcePos,
        first_error: Option<Diagnostic>,
    ) -> Result<Unit, Diagnostic> {
        match self.hll_step(core, here, first_error)? {
            HllStep::Done => Ok(Unit::Skip),
            HllStep::Execute(owner) => {
                self.prepare(core)?;
                self.owner = owner;
                Ok(Unit::Execute)
            }
        }
    }

    /// The block's HLL expression words, evaluated before it executes (journalled).
    #[inline(always)]
    fn prepare<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<(), Diagnostic> {
        // Invariant: a line of a program without HLL has no HLL box at all (`Block::hll`), so
        // this is one pointer test for every block.
        if core.block.has_hll_exprs() {
            self.hll_prepare_block(core)?;
        }
        Ok(())
    }
}

impl FrontEnd for Axioma {
    /// The per-run state before the block.
    type Undo = Extension;
    const STAGES_OUTPUT: bool = true;

    #[inline(always)]
    fn next_unit<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<Unit, Diagnostic> {
        let here = match core.read_line()? {
            Read::Line(here) => here,
            Read::EndOfInput | Read::EndOfFile => return Ok(Unit::EndOfInput),
        };
        let first_error = core.take_syntax(false);
        if self.hll.is_some() || core.block.hll().statement {
            // Out of line: the HLL path must not enlarge the per-block path of plain programs.
            return self.hll_line(core, here, first_error);
        }
        if let Some(e) = first_error {
            return Err(e);
        }
        self.prepare(core)?;
        Ok(Unit::Execute)
    }

    #[inline(always)]
    fn begin<R: BufRead + Seek>(&mut self, _core: &Core<R>) -> Self::Undo {
        self.part.chain.begin_block();
        self.part.modes.begin_block();
        self.part.cycle.begin_block();
        self.part.tech.begin_block();
        self.part.probe.begin_block();
        self.part.ext.clone()
    }

    #[inline(always)]
    fn execute(&mut self, parts: Parts<'_>) -> Result<Outcome, Diagnostic> {
        parts.words.fill(
            parts.block,
            &HllValues(&self.hll_values),
            &WORD_RULES,
            parts.warnings,
        )?;
        let mut cx = parts.with(&mut self.part);
        crate::execute(&mut cx)
    }

    #[cold]
    fn rollback<R: BufRead + Seek>(&mut self, undo: Self::Undo, core: &mut Core<R>) {
        self.part.chain.rollback();
        self.part.modes.rollback();
        self.part.cycle.rollback();
        self.part.tech.rollback();
        self.part.probe.rollback();
        self.part.ext = undo;
        self.part.message = None;
        self.owner = None;
        if std::mem::take(&mut self.hll_block) {
            self.hll_values.clear();
            self.hll_rollback(core);
        }
    }

    #[inline(always)]
    fn commit<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        outcome: Outcome,
    ) -> Result<(), Diagnostic> {
        // A block counts once it has run (`Core::count_block`).
        core.count_block();
        self.part.ext.release(&mut core.staging, &mut core.queue);
        if self.hll_block {
            self.hll_block = false;
            self.hll_values.clear();
            self.part.message = None;
        }
        if let Some(owner) = self.owner.take() {
            if outcome != Outcome::End {
                self.hll_after_iso(core, owner)?;
            }
        }
        Ok(())
    }

    fn finish<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<(), Diagnostic> {
        // A fragment without M30 ends with compensation still looking ahead: finish its path.
        self.part.ext.finish(
            &self.part.params,
            &mut core.staging,
            &mut core.queue,
            &mut core.warnings,
            &mut self.part.reported_spline,
        )?;
        self.hll_end_of_input(core)
    }
}
