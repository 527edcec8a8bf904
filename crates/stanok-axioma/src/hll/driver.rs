//! The front end's side of the HLL: which AxiOMA lines run, seeking for loops, word expressions
//! and `MSG(expr)` before a block executes, and undoing them when the block fails.
//!
//! Invariant: programs without any HLL never reach this file — `Axioma::hll` stays `None` and an
//! ISO block without expression words takes the unchanged path.

use super::eval::Env;
use super::value::HVal;
use super::{Hll, IsoAction, Owner};
use crate::Axioma;
use stanok_canon::Diagnostic;
use stanok_interp_core::Core;
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

impl Axioma {
    fn hll_state(&mut self, max_iterations: u64) -> &mut Hll {
        self.hll
            .get_or_insert_with(|| Box::new(Hll::new(max_iterations)))
    }

    /// An AxiOMA line while the HLL is in use (or the line is HLL). `first_error` is the line's
    /// first syntax error: ignored in skipped text.
    pub(crate) fn hll_step<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        here: SourcePos,
        first_error: Option<Diagnostic>,
    ) -> Result<HllStep, Diagnostic> {
        let max = core.opts.max_loop_iterations;
        if let Some(e) = first_error {
            if self.hll_state(max).skipping() {
                return Ok(HllStep::Done);
            }
            return Err(e);
        }
        let statement = core.block.hll().statement;
        if statement && !self.hll_state(max).skipping() {
            core.count_block()?;
        }
        self.hll_state(max);
        let Some(hll) = self.hll.as_deref_mut() else {
            return Ok(HllStep::Done);
        };
        let Hll { vars, control } = hll;
        let mut env = Env {
            block: &core.block,
            vars,
            control: &mut core.opts.control,
            machine: &self.part.params,
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
            let empty = core.block.is_empty();
            match control.iso(&mut env, empty, core.block.span())? {
                IsoAction::Skip(j) => j,
                IsoAction::Execute(owner) => return Ok(HllStep::Execute(owner.map(OwnerToken))),
            }
        };
        if let Some(pos) = jump {
            core.seek(pos)?;
        }
        Ok(HllStep::Done)
    }

    /// After an ISO block that was the single-statement body of a construct ran.
    pub(crate) fn hll_after_iso<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        owner: OwnerToken,
    ) -> Result<(), Diagnostic> {
        let Some(hll) = self.hll.as_deref_mut() else {
            return Ok(());
        };
        let Hll { vars, control } = hll;
        let mut env = Env {
            block: &core.block,
            vars,
            control: &mut core.opts.control,
            machine: &self.part.params,
        };
        let span = core.block.span();
        if let Some(pos) = control.close_owner(&mut env, owner.0, span)? {
            core.seek(pos)?;
        }
        Ok(())
    }

    /// Evaluates the expression words (`X=ii*10`, in written order) and `MSG(expr)` of the ISO
    /// block about to execute, into `hll_values` and the part's `message`. Their writes
    /// (`X=i++`) are journalled: `hll_rollback` undoes them.
    pub(crate) fn hll_prepare_block<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
    ) -> Result<(), Diagnostic> {
        self.hll_state(core.opts.max_loop_iterations);
        self.hll_values.clear();
        let Some(hll) = self.hll.as_deref_mut() else {
            return Ok(());
        };
        let block = &core.block;
        let mut env = Env {
            block,
            vars: &mut hll.vars,
            control: &mut core.opts.control,
            machine: &self.part.params,
        };
        env.vars.begin();
        let values = &mut self.hll_values;
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
        // Taken by the executor (`cx.fe.message`); reset when the block ends.
        self.part.message = message;
        self.hll_block = true;
        Ok(())
    }

    /// Undoes the HLL writes of a failing block.
    pub(crate) fn hll_rollback<R: BufRead + Seek>(&mut self, core: &mut Core<R>) {
        if let Some(hll) = self.hll.as_deref_mut() {
            hll.vars.rollback(&mut core.opts.control);
        }
    }

    /// End of the program: open constructs are an error.
    pub(crate) fn hll_end_of_input<R: BufRead + Seek>(
        &self,
        core: &Core<R>,
    ) -> Result<(), Diagnostic> {
        match self.hll.as_deref() {
            Some(h) => h.control.end_of_input(core.block.span()),
            None => Ok(()),
        }
    }
}
