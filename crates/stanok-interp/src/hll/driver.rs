//! The interpreter driver's side of the HLL: which AxiOMA lines run, seeking for loops, word
//! expressions and `MSG(expr)` before a block executes, and undoing them when the block fails.
//!
//! Invariant: programs without any HLL never reach this file — `Interpreter::hll` stays `None`
//! and an ISO block without expression words takes the unchanged path (`execute_words(&[])`).

use super::eval::Env;
use super::value::HVal;
use super::{Hll, IsoAction, Owner};
use crate::Interpreter;
use stanok_canon::Diagnostic;
use stanok_syntax::{SourcePos, Value};
use std::io::{BufRead, Seek};

/// What the driver does with an AxiOMA line once the HLL has seen it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HllStep {
    /// Nothing more (an HLL line ran, or a skipped line).
    Done,
    /// Execute the ISO block; then close the body it was (if `Some`).
    Execute(Option<OwnerToken>),
}

/// The construct an ISO block was the single-statement body of (opaque to the driver).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OwnerToken(Owner);

impl<R: BufRead + Seek> Interpreter<R> {
    fn hll_state(&mut self) -> &mut Hll {
        let opts = &self.opts;
        self.hll.get_or_insert_with(|| Box::new(Hll::new(opts)))
    }

    /// An AxiOMA line while the HLL is in use (or the line is HLL). `first_error` is the line's
    /// first syntax error: ignored in skipped text.
    pub(crate) fn hll_step(
        &mut self,
        here: SourcePos,
        first_error: Option<Diagnostic>,
    ) -> Result<HllStep, Diagnostic> {
        if let Some(e) = first_error {
            if self.hll_state().skipping() {
                return Ok(HllStep::Done);
            }
            return Err(e);
        }
        let statement = self.block.hll().statement;
        // A statement line counts once it has run (as every block: `Stats::blocks_executed`).
        let counts = statement && !self.hll_state().skipping();
        self.hll_state();
        let Some(hll) = self.hll.as_deref_mut() else {
            return Ok(HllStep::Done);
        };
        let Hll { vars, control } = hll;
        let mut env = Env {
            block: &self.block,
            vars,
            control: &mut self.opts.control,
            machine: &self.opts.axioma,
        };
        let jump = if statement {
            let snapshot = control.clone();
            let scopes = env.vars.scopes_snapshot();
            env.vars.begin();
            match control.line(&mut env, here) {
                Ok(j) => j,
                Err(d) => {
                    env.vars.rollback(env.control);
                    env.vars.restore_scopes(scopes);
                    *control = snapshot;
                    return Err(d);
                }
            }
        } else {
            let empty = self.block.is_empty();
            match control.iso(&mut env, empty, self.block.span())? {
                IsoAction::Skip(j) => j,
                IsoAction::Execute(owner) => return Ok(HllStep::Execute(owner.map(OwnerToken))),
            }
        };
        if counts {
            self.count_block();
        }
        if let Some(pos) = jump {
            self.seek_to(pos)?;
        }
        Ok(HllStep::Done)
    }

    /// After an ISO block that was the single-statement body of a construct ran.
    pub(crate) fn hll_after_iso(&mut self, owner: OwnerToken) -> Result<(), Diagnostic> {
        let Some(hll) = self.hll.as_deref_mut() else {
            return Ok(());
        };
        let Hll { vars, control } = hll;
        let mut env = Env {
            block: &self.block,
            vars,
            control: &mut self.opts.control,
            machine: &self.opts.axioma,
        };
        let span = self.block.span();
        if let Some(pos) = control.close_owner(&mut env, owner.0, span)? {
            self.seek_to(pos)?;
        }
        Ok(())
    }

    /// Evaluates the expression words (`X=ii*10`, in written order) and `MSG(expr)` of the ISO
    /// block about to execute. Their writes (`X=i++`) are journalled: `hll_rollback` undoes them.
    pub(crate) fn hll_prepare_block(&mut self) -> Result<Vec<(u32, f64)>, Diagnostic> {
        self.hll_state();
        let Some(hll) = self.hll.as_deref_mut() else {
            return Ok(Vec::new());
        };
        let block = &self.block;
        let mut env = Env {
            block,
            vars: &mut hll.vars,
            control: &mut self.opts.control,
            machine: &self.opts.axioma,
        };
        env.vars.begin();
        let mut values = Vec::new();
        let mut message = None;
        let result = (|| {
            for w in &block.words {
                if let Value::Hll(e) = w.value {
                    values.push((e.0, env.number(e)?));
                }
            }
            if let Some(m) = block.hll().message {
                match env.eval(m)? {
                    HVal::Str(s) => message = Some(s),
                    v => {
                        return Err(Diagnostic::error(
                            "hll::type-mismatch",
                            format!("MSG needs a string, not a {}", v.kind()),
                            block.span_of(block.hll().expr_span(m)),
                        )
                        .with_note("format numbers with sprintf"))
                    }
                }
            }
            Ok(())
        })();
        if let Err(d) = result {
            env.vars.rollback(env.control);
            return Err(d);
        }
        // Taken by the AxiOMA executor; reset after the block (`execute_block_with_expressions`).
        self.words.message = message;
        Ok(values)
    }

    /// Undoes the HLL writes of a failing block.
    pub(crate) fn hll_rollback(&mut self) {
        self.words.message = None;
        if let Some(hll) = self.hll.as_deref_mut() {
            hll.vars.rollback(&mut self.opts.control);
        }
    }

    /// End of the program: open constructs are an error.
    pub(crate) fn hll_end_of_input(&self) -> Result<(), Diagnostic> {
        match self.hll.as_deref() {
            Some(h) => h.control.end_of_input(self.block.span()),
            None => Ok(()),
        }
    }
}
