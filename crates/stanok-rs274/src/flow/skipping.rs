//! O-word lines met while skipping (`Flow::skip`): which of them ends the skip, and what it does
//! then (a branch of an if taken, a loop left, a subroutine's definition learnt or entered).

use super::{Call, Flow, FlowAction, LoopKind, Skip};
use crate::params::Evaluator;
use stanok_canon::Diagnostic;
use stanok_interp_core::CoreOptions as InterpOptions;
use stanok_syntax::{Block, OKind, SourcePos};

impl Flow {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn while_skipping(
        &mut self,
        skip: Skip,
        block: &Block,
        eval: &Evaluator<'_>,
        kind: &OKind,
        label: String,
        next: SourcePos,
        opts: &InterpOptions,
    ) -> Result<FlowAction, Diagnostic> {
        match skip {
            Skip::Sub(l) => {
                if l == label && matches!(kind, OKind::EndSub(_)) {
                    self.skip = None;
                    self.returned_to_top = false;
                }
                Ok(FlowAction::Skip)
            }
            Skip::FindSub {
                label: wanted,
                args,
                return_pos,
                ..
            } => {
                if matches!(kind, OKind::Sub) {
                    let key = self.sub_key(&label);
                    self.subs.insert(key, next);
                    if label == wanted {
                        self.skip = None;
                        self.enter(block, eval, Call::new(label, args, return_pos, false), opts)?;
                        return Ok(FlowAction::Handled);
                    }
                }
                Ok(FlowAction::Skip)
            }
            Skip::IfBranch(l) if l == label => match kind {
                OKind::ElseIf(c) => {
                    if eval.eval(*c)? != 0.0 {
                        self.skip = None;
                    }
                    Ok(FlowAction::Handled)
                }
                OKind::Else => {
                    self.skip = None;
                    Ok(FlowAction::Handled)
                }
                OKind::EndIf => {
                    self.skip = None;
                    self.ifs.pop();
                    Ok(FlowAction::Handled)
                }
                _ => Ok(FlowAction::Skip),
            },
            Skip::ToEndIf(l) if l == label && matches!(kind, OKind::EndIf) => {
                self.skip = None;
                self.ifs.pop();
                Ok(FlowAction::Handled)
            }
            Skip::LoopEnd(l, frame)
                if l == label
                    && matches!(kind, OKind::EndWhile | OKind::EndRepeat | OKind::While(_)) =>
            {
                self.skip = None;
                if matches!(kind, OKind::While(_)) {
                    // A do-loop's end after its break.
                    self.doing_break = false;
                    return Ok(FlowAction::Handled);
                }
                if !std::mem::take(&mut self.doing_continue) {
                    return Ok(FlowAction::Handled);
                }
                // A continue pending from a do-loop: LinuxCNC loops back to the start of the
                // loop just left (after a false `while` or a count below 1 that start only
                // leads here again).
                match frame {
                    Some(f) if f.kind == LoopKind::While => Ok(FlowAction::Seek(f.target)),
                    _ => Ok(FlowAction::Handled),
                }
            }
            _ => Ok(FlowAction::Skip),
        }
    }
}
