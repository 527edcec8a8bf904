//! Macro control statements (`docs/dialects/mazatrol-eia.md` §15.5): GOTO, IF … GOTO,
//! IF … THEN, WHILE … DO, DO, END — the reader moves in `next_unit`, before any block runs.

use crate::flow::{self, Loop};
use crate::front::{err, Mazatrol, Prepared};
use stanok_canon::{Diagnostic, Span};
use stanok_interp_core::{Core, Unit};
use stanok_syntax::{MacroKind, SourcePos};
use std::io::{BufRead, Seek};

impl Mazatrol {
    /// A macro statement (`docs` §15.5). `Some(unit)` when the line must execute (IF … THEN).
    pub(crate) fn statement<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        kind: MacroKind,
        pos: SourcePos,
        next_line: SourcePos,
    ) -> Result<Option<Unit>, Diagnostic> {
        let span = core.block.span();
        let at =
            |core: &Core<R>, c: stanok_syntax::ExprId| core.block.span_of(core.block.expr_span(c));
        let truth = |this: &Self, core: &Core<R>, c| -> Result<bool, Diagnostic> {
            Ok(this
                .part
                .env(&core.state)
                .value(&core.block, c)?
                .is_some_and(|v| v != 0.0))
        };
        match kind {
            MacroKind::Goto(t) => {
                let target_at = at(core, t);
                self.goto(core, t, target_at, pos)?;
                Ok(None)
            }
            MacroKind::IfGoto { condition, target } => {
                if truth(self, core, condition)? {
                    let target_at = at(core, target);
                    self.goto(core, target, target_at, pos)?;
                }
                Ok(None)
            }
            MacroKind::IfThen { condition } => {
                if truth(self, core, condition)? {
                    self.part.prepared = Prepared::default();
                    return Ok(Some(Unit::Execute));
                }
                Ok(None)
            }
            MacroKind::While { condition, label } => {
                self.check_label(core, label)?;
                let go = truth(self, core, condition)?;
                self.loop_head(core, label, go, pos, next_line, span)?;
                Ok(None)
            }
            MacroKind::Do { label } => {
                self.check_label(core, label)?;
                self.loop_head(core, label, true, pos, next_line, span)?;
                Ok(None)
            }
            MacroKind::End { label } => {
                match self.flow.loops.last() {
                    Some(l) if l.label == label => {
                        let start = l.start;
                        core.seek(start)?;
                    }
                    _ => {
                        return Err(err(
                            "mazatrol::loop-mismatch",
                            format!("END {label} without its WHILE … DO {label} (or DO {label})"),
                            span,
                        ))
                    }
                }
                Ok(None)
            }
        }
    }

    pub(crate) fn check_label<R: BufRead + Seek>(
        &self,
        core: &Core<R>,
        label: u32,
    ) -> Result<(), Diagnostic> {
        if label == 0 || label > flow::MAX_LOOP_NUMBER {
            let at = core
                .block
                .statement
                .and_then(|s| s.label_span)
                .map_or(core.block.span(), |s| core.block.span_of(s));
            return Err(err(
                "mazatrol::loop-number",
                format!(
                    "DO {label}: loop numbers are 1 to {}",
                    flow::MAX_LOOP_NUMBER
                ),
                at,
            ));
        }
        Ok(())
    }

    /// WHILE / DO: enter, go round, or leave the loop.
    pub(crate) fn loop_head<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        label: u32,
        go: bool,
        pos: SourcePos,
        next_line: SourcePos,
        span: Span,
    ) -> Result<(), Diagnostic> {
        let same = self.flow.loops.last().is_some_and(|l| l.start == pos);
        if !go {
            let after = if same {
                self.flow.loops.pop().map(|l| l.after)
            } else {
                flow::find_end(core, &mut self.flow, label, pos)?
            };
            let Some(after) = after else {
                return Err(err(
                    "mazatrol::loop-mismatch",
                    format!("DO {label} has no END {label} in this program"),
                    span,
                ));
            };
            return core.seek(after);
        }
        if same {
            let l = self.flow.loops.last_mut().expect("checked");
            l.passes += 1;
            if l.passes > core.opts.max_loop_iterations {
                return Err(err(
                    "interp::loop-limit",
                    format!(
                        "the loop DO {label} went round more than {} times (--max-loop-iterations)",
                        core.opts.max_loop_iterations
                    ),
                    span,
                ));
            }
            return core.seek(next_line);
        }
        if self.flow.loops.iter().any(|l| l.label == label) {
            return Err(err(
                "mazatrol::loop-mismatch",
                format!("DO {label} is already open: nested loops need different numbers"),
                span,
            ));
        }
        if self.flow.loops.len() >= flow::MAX_LOOP_DEPTH {
            return Err(err(
                "mazatrol::loop-nesting",
                format!(
                    "WHILE … DO loops nested deeper than {}",
                    flow::MAX_LOOP_DEPTH
                ),
                span,
            ));
        }
        let Some(after) = flow::find_end(core, &mut self.flow, label, pos)? else {
            return Err(err(
                "mazatrol::loop-mismatch",
                format!("DO {label} has no END {label} in this program"),
                span,
            ));
        };
        self.flow.loops.push(Loop {
            label,
            start: pos,
            after,
            passes: 1,
        });
        core.seek(next_line)
    }

    /// GOTO n: jump, leaving the loops the target is not in.
    pub(crate) fn goto<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        target: stanok_syntax::ExprId,
        at: Span,
        pos: SourcePos,
    ) -> Result<(), Diagnostic> {
        let v = self.part.env(&core.state).value(&core.block, target)?;
        let n = match v {
            Some(x) if x.fract() == 0.0 && (1.0..=99_999.0).contains(&x) => x as u32,
            Some(x) => {
                return Err(err(
                    "mazatrol::goto-target",
                    format!("GOTO {x}: a sequence number is a whole number from 1 to 99999"),
                    at,
                ))
            }
            None => {
                return Err(err(
                    "mazatrol::goto-target",
                    "GOTO: the sequence number is vacant",
                    at,
                ))
            }
        };
        let Some(p) = flow::find_sequence(core, &mut self.flow, n, pos)? else {
            return Err(err(
                "mazatrol::goto-target",
                format!("GOTO {n}: no block N{n} in this program"),
                at,
            ));
        };
        while let Some(l) = self.flow.loops.last() {
            if p.offset >= l.start.offset && p.offset < l.after.offset {
                break;
            }
            self.flow.loops.pop();
        }
        core.seek(p)
    }
}
