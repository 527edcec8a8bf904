//! The Mazatrol front end: what the driver calls (`stanok_interp_core::FrontEnd`). A line is a
//! block; the tool-tip-control modes are journalled, so a failing block leaves them as they were.

use crate::MazatrolState;
use stanok_canon::Diagnostic;
use stanok_interp_core::{
    Core, CoreOptions, FrontEnd, Hooks, Journalled, ModalState, NoExpressions, Outcome, Parts,
    Read, Repeated, Unit, WordRules,
};
use std::io::{BufRead, Seek};

/// The part of the front end a block's context carries (`cx.fe`).
#[derive(Debug, Default)]
pub struct MazatrolPart {
    /// Tool tip point control and tool length offset (journalled).
    pub modes: Journalled<MazatrolState>,
    /// TTPC programs X Y Z in the workpiece frame (parameter 1, spec mazatrol §4.2) instead of
    /// the table frame (0, the default).
    pub ttpc_workpiece_frame: bool,
}

impl Hooks for MazatrolPart {}

/// A repeated letter is an error, except the second T of `T01 T02 M6` (the tool prepared next).
const WORD_RULES: WordRules = WordRules {
    repeated: Repeated::Refuse("rs274::multiple-words"),
    second_word: Some(b'T'),
};

/// The Mazatrol EIA/ISO front end.
#[derive(Debug)]
pub struct Mazatrol {
    part: MazatrolPart,
}

impl Mazatrol {
    /// The front end at power-on; the work offset of G54 (page 1) is in force from the start.
    pub fn new(opts: &CoreOptions, ttpc_workpiece_frame: bool, state: &mut ModalState) -> Self {
        state.g5x_index = 1;
        if let Some(z) = opts.control.offsets.zero.first().and_then(|p| p.first()) {
            state.frame.set_origin(z.offset);
        }
        Mazatrol {
            part: MazatrolPart {
                modes: Journalled::default(),
                ttpc_workpiece_frame,
            },
        }
    }

    /// The tool-tip-control modes after the blocks run so far.
    pub fn modes(&self) -> &MazatrolState {
        &self.part.modes
    }
}

impl FrontEnd for Mazatrol {
    type Undo = ();

    fn next_unit<R: BufRead + Seek>(&mut self, core: &mut Core<R>) -> Result<Unit, Diagnostic> {
        match core.read_line()? {
            Read::Line(_) => {}
            Read::EndOfInput | Read::EndOfFile => return Ok(Unit::EndOfInput),
        }
        if let Some(e) = core.take_syntax(false) {
            return Err(e);
        }
        core.count_block()?;
        Ok(Unit::Execute)
    }

    fn begin<R: BufRead + Seek>(&mut self, _core: &Core<R>) {
        self.part.modes.begin_block();
    }

    fn execute(&mut self, parts: Parts<'_>) -> Result<Outcome, Diagnostic> {
        // Macro variables come with the complete EIA/ISO language (issue 18); until then an
        // assignment is refused like an expression word.
        if let Some(a) = parts.block.assignments.first() {
            return Err(Diagnostic::error(
                "interp::unsupported",
                "parameters and expressions are not supported by the Mazatrol front end",
                parts.block.span_of(parts.block.expr_span(a.value)),
            ));
        }
        parts.words.fill(
            parts.block,
            &NoExpressions("Mazatrol"),
            &WORD_RULES,
            parts.warnings,
        )?;
        let mut cx = parts.with(&mut self.part);
        crate::execute(&mut cx)
    }

    fn rollback<R: BufRead + Seek>(&mut self, _undo: (), _core: &mut Core<R>) {
        self.part.modes.rollback();
    }

    fn commit<R: BufRead + Seek>(
        &mut self,
        _core: &mut Core<R>,
        _outcome: Outcome,
    ) -> Result<(), Diagnostic> {
        Ok(())
    }

    fn finish<R: BufRead + Seek>(&mut self, _core: &mut Core<R>) -> Result<(), Diagnostic> {
        Ok(())
    }
}
