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

impl Flow {
    /// The closing `%` of a `%`-delimited program met while lines are skipped: LinuxCNC ends the
    /// file there (`read_text` returns `INTERP_ENDFILE`) and, still skipping to an O-word, fails
    /// with "Failed to find sub 'O…' before EOF" (`Interp::_read`), whatever it was seeking — a
    /// called subroutine, the end of one being defined, an if's branch, a loop's end. The name is
    /// its `o_name`: a subroutine's label bare (`100`, `name` without `<>`), any other O-word's
    /// prefixed with the subroutine it is in and `#` (`#100` at the top level, `sub#100` in a
    /// call). The error stands on the `%` line, as LinuxCNC's does; the call is named in a note.
    pub fn skipped_to_percent(&self, percent: &Block) -> Option<Diagnostic> {
        let bare = |l: &str| l.trim_start_matches('<').trim_end_matches('>').to_string();
        let local = |l: &str| {
            let sub = self
                .calls
                .last()
                .map(|c| bare(&c.label))
                .unwrap_or_default();
            format!("{sub}#{}", bare(l))
        };
        let (name, call) = match self.skip.as_ref()? {
            Skip::FindSub { label, call, .. } => (bare(label), Some(*call)),
            Skip::Sub(l) => (bare(l), None),
            Skip::IfBranch(l) | Skip::ToEndIf(l) | Skip::LoopEnd(l, _) | Skip::DoEnd(l) => {
                (local(l), None)
            }
        };
        let mut d = Diagnostic::error(
            "flow::unterminated",
            format!("Failed to find sub 'O{name}' before EOF"),
            percent.span(),
        )
        .fatal()
        .with_note("the `%` line ends the program: nothing after it is read");
        if let Some(call) = call {
            d = d.with_note(format!(
                "the subroutine was called on line {} and is not defined before this `%`",
                call.line
            ));
        }
        Some(d)
    }
}
