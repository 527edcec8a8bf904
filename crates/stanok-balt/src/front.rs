//! The Balt-System front end: what the driver calls (`stanok_interp_core::FrontEnd`). A line is a
//! block; the CVU modes are journalled and the open `(BSP …)` spline definition is copied per
//! block, so a failing block leaves both as they were.

use crate::spline::SplineBuffer;
use crate::BaltState;
use stanok_canon::Diagnostic;
use stanok_interp_core::{
    Core, CoreOptions, FrontEnd, Hooks, Journalled, ModalState, NoExpressions, Outcome, Parts,
    Read, Repeated, Unit, WordRules,
};
use std::io::{BufRead, Seek};

/// The part of the front end a block's context carries (`cx.fe`).
#[derive(Debug, Default)]
pub struct BaltPart {
    /// CVU, MOVST, the local frame, the tool length, the `(DPI …)` plane, G06 (journalled).
    pub modes: Journalled<BaltState>,
    /// The `(BSP …)` nodes not yet emitted (copied per block).
    pub spline: SplineBuffer,
}

impl Hooks for BaltPart {}

/// A repeated letter is an error (as in RS274/NGC).
const WORD_RULES: WordRules = WordRules {
    repeated: Repeated::Refuse("rs274::multiple-words"),
    second_word: None,
};

/// The Balt-System CVU front end.
#[derive(Debug)]
pub struct Balt {
    part: BaltPart,
}

impl Balt {
    /// The front end at power-on; the work offset of G54 (page 1) is in force from the start.
    pub fn new(opts: &CoreOptions, state: &mut ModalState) -> Self {
        state.g5x_index = 1;
        if let Some(z) = opts.control.offsets.zero.first().and_then(|p| p.first()) {
            state.frame.set_origin(z.offset);
        }
        Balt {
            part: BaltPart::default(),
        }
    }

    /// The CVU modes after the blocks run so far.
    pub fn modes(&self) -> &BaltState {
        &self.part.modes
    }
}

impl FrontEnd for Balt {
    /// The spline definition before the block.
    type Undo = SplineBuffer;

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

    fn begin<R: BufRead + Seek>(&mut self, _core: &Core<R>) -> Self::Undo {
        self.part.modes.begin_block();
        self.part.spline.clone()
    }

    fn execute(&mut self, parts: Parts<'_>) -> Result<Outcome, Diagnostic> {
        parts.words.fill(
            parts.block,
            &NoExpressions("Balt-System"),
            &WORD_RULES,
            parts.warnings,
        )?;
        let mut cx = parts.with(&mut self.part);
        crate::execute(&mut cx)
    }

    fn rollback<R: BufRead + Seek>(&mut self, undo: Self::Undo, _core: &mut Core<R>) {
        self.part.modes.rollback();
        self.part.spline = undo;
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
