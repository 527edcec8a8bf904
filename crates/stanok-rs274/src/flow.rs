//! RS274/NGC O-word control flow: subroutines, if/elseif/else, while, do-while, repeat, break,
//! continue — executed the way LinuxCNC does it, by moving the read position in the program
//! text (the program is never held in memory).
//!
//! State:
//! * `subs`: label → position of the line after `oN sub`, learnt when a definition is passed (its body
//!   is skipped, not executed) or found by a forward scan when a call precedes the definition;
//! * `calls`: one frame per active call, with the return position and the saved `#1…#30`;
//! * `loops`: one frame per active loop, with where to jump back to and an iteration counter;
//! * `ifs`: the labels of the active if-constructs;
//! * `skip`: while set, lines are read but not executed until the O-word it waits for.
//!
//! Bounds: call depth ≤ `max_call_depth`, iterations of any loop ≤ `max_loop_iterations`; an
//! unterminated construct at end of file is an error. Together with the driver's block limit no
//! program can make the interpreter hang.

use crate::params::{normalise_name, Evaluator, Slot};
use stanok_canon::{Diagnostic, Span};
use stanok_interp_core::CoreOptions as InterpOptions;
use stanok_syntax::{Block, OKind, OLabel, SourcePos};
use std::collections::HashMap;

mod skipping;

/// What the driver does with the current line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FlowAction {
    /// An ordinary block: execute it.
    Execute,
    /// Read past it.
    Skip,
    /// An O-word line that was acted on (apply its parameter operations).
    Handled,
    /// Continue reading at this position.
    Seek(SourcePos),
    /// Call a subroutine kept in its own file (`o<name> call` with `name.ngc` on the subroutine
    /// path): the driver opens it and reads the body after its `o<name> sub` line.
    CallFile {
        /// The file.
        path: std::path::PathBuf,
        /// The label as written in the file's `sub` line (normalised, with `<>`).
        label: String,
    },
    /// Return from a subroutine file: close it and continue in the caller at this position.
    ReturnFromFile(SourcePos),
}

/// A parameter operation requested by a call or return.
#[derive(Debug, Clone, PartialEq)]
pub enum ParamOp {
    /// Write a parameter.
    Write(Slot),
    /// Enter a local scope.
    PushScope,
    /// Leave it.
    PopScope,
}

#[derive(Debug, Clone)]
enum Skip {
    Sub(String),
    FindSub {
        label: String,
        args: Vec<f64>,
        return_pos: SourcePos,
        /// The call (for the error if the definition never comes) and the files tried.
        call: Span,
        tried: Vec<std::path::PathBuf>,
    },
    IfBranch(String),
    ToEndIf(String),
    /// To the end of a loop left (a `break`, a false `while`, a repeat count below 1): its
    /// `endwhile`, `endrepeat` or a do's `while`, with the frame of the loop a `break` left
    /// (LinuxCNC loops back into it if a `continue` is pending, `Flow::doing_continue`).
    LoopEnd(String, Option<LoopFrame>),
    /// To the `while` line that ends do-loop `label` (a `continue`), which then runs as usual.
    DoEnd(String),
}

/// A call about to be entered.
struct Call {
    label: String,
    args: Vec<f64>,
    return_pos: SourcePos,
    file: bool,
}

impl Call {
    fn new(label: String, args: Vec<f64>, return_pos: SourcePos, file: bool) -> Self {
        Call {
            label,
            args,
            return_pos,
            file,
        }
    }
}

#[derive(Debug, Clone)]
struct CallFrame {
    label: String,
    return_pos: SourcePos,
    /// The subroutine is a file of its own (the driver reads it with a reader of its own).
    file: bool,
    saved: [f64; 30],
    loops: usize,
    ifs: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum LoopKind {
    While,
    Do,
    Repeat(u64),
}

#[derive(Debug, Clone)]
struct LoopFrame {
    label: String,
    kind: LoopKind,
    /// `while`: the `while` line itself (re-evaluated); `do`/`repeat`: the first body line.
    target: SourcePos,
    /// The line number of the loop's first line (`while`, `do`, `repeat`).
    line: u32,
    /// Where that line starts (a pending continue sends a finished repeat loop back to it).
    head: SourcePos,
    iterations: u64,
}

/// Control-flow state of one run.
#[derive(Debug, Default)]
pub struct Flow {
    subs: HashMap<String, SourcePos>,
    calls: Vec<CallFrame>,
    loops: Vec<LoopFrame>,
    ifs: Vec<String>,
    skip: Option<Skip>,
    ops: Vec<(ParamOp, f64)>,
    /// Which file lines come from: 0 = the program, n = the n-th nested subroutine file. Keys of
    /// `subs` carry it, so positions of one file are never used in another.
    source: usize,
    /// Loop passes of the run, all loops together (`max_total_loop_iterations`).
    total_iterations: u64,
    /// LinuxCNC's `doing_break` and `doing_continue` (`interp_o_word.cc`): a `break` sets the
    /// first and only the end of a do-loop (its `while` line) clears it — so a break out of a
    /// while or repeat loop leaves it set, and the next do-loop end met does not loop back. A
    /// `continue` sets the second and only an `endwhile`/`endrepeat` reached while skipping
    /// clears it — so a continue in a do-loop leaves it set, and the next break out of a while
    /// or repeat loop loops back to that loop's start instead of leaving it.
    doing_break: bool,
    doing_continue: bool,
    /// LinuxCNC's `sub_name` left set at level 0: a return from a call sets it to the caller's
    /// (non-null) name and only the end of a subroutine definition clears it. While it is set, a
    /// stray `endsub` at level 0 is "Not in subroutine definition" and a stray `return` is ignored.
    returned_to_top: bool,
}

/// The file holding subroutine `label` (`<name>` → `name.ngc`) on the search path, if any.
fn subroutine_file(label: &str, opts: &InterpOptions) -> Option<std::path::PathBuf> {
    subroutine_candidates(label, opts)
        .into_iter()
        .find(|p| p.is_file())
}

/// Where subroutine `label` may be kept: `name.ngc` in each directory of the search path (none
/// for a numbered subroutine, which has no file of its own).
fn subroutine_candidates(label: &str, opts: &InterpOptions) -> Vec<std::path::PathBuf> {
    let Some(name) = label.strip_prefix('<').and_then(|l| l.strip_suffix('>')) else {
        return Vec::new();
    };
    opts.subroutine_path
        .iter()
        .map(|dir| dir.join(format!("{name}.ngc")))
        .collect()
}

impl Flow {
    /// The driver switched to reading file `source` (0 = the program).
    pub fn set_source(&mut self, source: usize) {
        self.source = source;
    }

    /// Key of a label in `subs`: the file it belongs to and the label.
    fn sub_key(&self, label: &str) -> String {
        format!("{}:{label}", self.source)
    }
}

/// The normalised text of a label (`<name>` or the number), as `FlowAction::CallFile` names it.
pub fn label_text(block: &Block, l: &OLabel) -> String {
    label_key(block, l)
}

fn label_key(block: &Block, l: &OLabel) -> String {
    match l {
        OLabel::Number(n) => n.to_string(),
        OLabel::Name(s) => format!("<{}>", normalise_name(block.slice(*s))),
    }
}

fn flow_err(block: &Block, code: &'static str, msg: String) -> Diagnostic {
    let span = block
        .oword
        .as_ref()
        .map(|o| block.span_of(o.span))
        .unwrap_or_else(|| block.span());
    // Control flow cannot be followed past its errors: they end even a check run.
    Diagnostic::error(code, msg, span).fatal()
}

impl Flow {
    /// `#<_value>` and `#<_value_returned>` after an endsub or return.
    fn push_returned_value(&mut self, value: Option<f64>) {
        let returned = value.is_some();
        self.ops.push((
            ParamOp::Write(Slot::Named {
                name: "_value".into(),
                global: true,
            }),
            value.unwrap_or(0.0),
        ));
        self.ops.push((
            ParamOp::Write(Slot::Named {
                name: "_value_returned".into(),
                global: true,
            }),
            if returned { 1.0 } else { 0.0 },
        ));
    }

    /// Whether lines are being skipped (and for what).
    pub fn skipping(&self) -> Option<()> {
        self.skip.as_ref().map(|_| ())
    }

    /// Parameter operations to apply after a `Handled` line.
    pub fn take_param_writes(&mut self) -> Vec<(ParamOp, f64)> {
        std::mem::take(&mut self.ops)
    }

    /// How many subroutine calls are active.
    pub fn depth(&self) -> usize {
        self.calls.len()
    }

    /// Calls subroutine `label` (normalised, e.g. `100`) with `args`, returning to `next`: the
    /// O-word `call` and the lathe cycles' profile (`G71 Q100` calls `o100`) both come here.
    pub fn call(
        &mut self,
        block: &Block,
        eval: &Evaluator<'_>,
        label: String,
        args: Vec<f64>,
        next: SourcePos,
        opts: &InterpOptions,
    ) -> Result<FlowAction, Diagnostic> {
        if let Some(&pos) = self.subs.get(&self.sub_key(&label)) {
            self.enter(block, eval, Call::new(label, args, next, false), opts)?;
            Ok(FlowAction::Seek(pos))
        } else if let Some(path) = subroutine_file(&label, opts) {
            self.enter(
                block,
                eval,
                Call::new(label.clone(), args, next, true),
                opts,
            )?;
            Ok(FlowAction::CallFile { path, label })
        } else {
            let tried = subroutine_candidates(&label, opts);
            let call = block
                .oword
                .as_ref()
                .map(|o| block.span_of(o.span))
                .unwrap_or_else(|| block.span());
            self.skip = Some(Skip::FindSub {
                label,
                args,
                return_pos: next,
                call,
                tried,
            });
            Ok(FlowAction::Skip)
        }
    }

    /// Decides what happens with the line just read. `here` is where it starts, `next` where the
    /// following line starts.
    pub fn on_line(
        &mut self,
        block: &Block,
        eval: &Evaluator<'_>,
        here: SourcePos,
        next: SourcePos,
        opts: &InterpOptions,
    ) -> Result<FlowAction, Diagnostic> {
        let Some(o) = &block.oword else {
            return Ok(if self.skip.is_some() {
                FlowAction::Skip
            } else {
                FlowAction::Execute
            });
        };
        let label = label_key(block, &o.label);
        let name = match &o.label {
            OLabel::Number(n) => format!("o{n}"),
            OLabel::Name(_) => format!("o{label}"),
        };
        if let Some(skip) = self.skip.clone() {
            match skip {
                // The do-loop's end after a `continue`: evaluated as if reached normally.
                Skip::DoEnd(l) if l == label && matches!(o.kind, OKind::While(_)) => {
                    self.skip = None;
                }
                Skip::DoEnd(_) => return Ok(FlowAction::Skip),
                _ => return self.while_skipping(skip, block, eval, &o.kind, label, next, opts),
            }
        }
        match &o.kind {
            OKind::Sub => {
                self.subs.insert(self.sub_key(&label), next);
                self.skip = Some(Skip::Sub(label));
                Ok(FlowAction::Skip)
            }
            OKind::EndSub(v) | OKind::Return(v) => {
                let value = match v {
                    Some(e) => Some(eval.eval(*e)?),
                    None => None,
                };
                if self.calls.is_empty() && self.returned_to_top {
                    if matches!(o.kind, OKind::Return(_)) {
                        // Ignored, but its value is still set as returned.
                        self.push_returned_value(value);
                        return Ok(FlowAction::Handled);
                    }
                    return Err(flow_err(
                        block,
                        "flow::return-outside-sub",
                        "Not in subroutine definition".into(),
                    ));
                }
                let Some(frame) = self.calls.pop() else {
                    return Err(flow_err(
                        block,
                        "flow::return-outside-sub",
                        // LinuxCNC's words: the line number and the line as written.
                        format!(
                            "{}: not in a subroutine definition: '{}'",
                            block.line,
                            block.text.trim_end()
                        ),
                    ));
                };
                // `return` may carry the label of the if or loop it sits in (LinuxCNC's
                // retval.ngc: `o1010 return` inside `o1010 if`); `endsub` must name the sub.
                let is_return = matches!(o.kind, OKind::Return(_));
                if frame.label != label && !is_return {
                    self.calls.push(frame);
                    return Err(flow_err(
                        block,
                        "flow::label-mismatch",
                        format!("{name} does not match the active subroutine"),
                    ));
                }
                self.returned_to_top |= self.calls.is_empty();
                self.loops.truncate(frame.loops);
                self.ifs.truncate(frame.ifs);
                self.ops.push((ParamOp::PopScope, 0.0));
                for (i, v) in frame.saved.iter().enumerate() {
                    self.ops.push((ParamOp::Write(Slot::Numbered(i + 1)), *v));
                }
                self.push_returned_value(value);
                if frame.file {
                    Ok(FlowAction::ReturnFromFile(frame.return_pos))
                } else {
                    Ok(FlowAction::Seek(frame.return_pos))
                }
            }
            OKind::Call(args) => {
                let mut values = Vec::with_capacity(args.len());
                for a in args {
                    values.push(eval.eval(*a)?);
                }
                if values.len() > 30 {
                    return Err(flow_err(
                        block,
                        "flow::too-many-arguments",
                        format!("{name} call has more than 30 arguments"),
                    ));
                }
                self.call(block, eval, label, values, next, opts)
            }
            OKind::If(c) => {
                let cond = eval.eval(*c)? != 0.0;
                self.check_nesting(block, opts)?;
                self.ifs.push(label.clone());
                if !cond {
                    self.skip = Some(Skip::IfBranch(label));
                }
                Ok(FlowAction::Handled)
            }
            OKind::ElseIf(_) | OKind::Else => {
                if self.ifs.last() != Some(&label) {
                    return Err(flow_err(
                        block,
                        "flow::else-without-if",
                        // LinuxCNC's words: it looks the label up among the open ifs.
                        format!(
                            "{}: undefined O-word label: '{}'",
                            block.line,
                            block.text.trim()
                        ),
                    ));
                }
                self.skip = Some(Skip::ToEndIf(label));
                Ok(FlowAction::Handled)
            }
            OKind::EndIf => {
                if self.ifs.last() != Some(&label) {
                    return Err(flow_err(
                        block,
                        "flow::endif-without-if",
                        // LinuxCNC's words: it looks the label up among the open ifs.
                        format!(
                            "{}: undefined O-word label: '{}'",
                            block.line,
                            block.text.trim()
                        ),
                    ));
                }
                self.ifs.pop();
                Ok(FlowAction::Handled)
            }
            OKind::While(c) => {
                let cond = eval.eval(*c)? != 0.0;
                match self.loops.last_mut() {
                    Some(f) if f.label == label && f.kind == LoopKind::Do => {
                        if cond && !self.doing_break {
                            f.iterations += 1;
                            check_iterations(block, f, &mut self.total_iterations, opts)?;
                            Ok(FlowAction::Seek(f.target))
                        } else {
                            self.doing_break = false;
                            self.loops.pop();
                            Ok(FlowAction::Handled)
                        }
                    }
                    Some(f)
                        if f.label == label && f.kind == LoopKind::While && f.target == here =>
                    {
                        if cond {
                            f.iterations += 1;
                            check_iterations(block, f, &mut self.total_iterations, opts)?;
                        } else {
                            self.loops.pop();
                            self.skip = Some(Skip::LoopEnd(label, None));
                        }
                        Ok(FlowAction::Handled)
                    }
                    _ => {
                        if cond {
                            self.check_nesting(block, opts)?;
                            self.loops.push(LoopFrame {
                                label,
                                kind: LoopKind::While,
                                target: here,
                                line: block.line,
                                head: here,
                                iterations: 1,
                            });
                        } else {
                            self.skip = Some(Skip::LoopEnd(label, None));
                        }
                        Ok(FlowAction::Handled)
                    }
                }
            }
            OKind::EndWhile => match self.loops.last() {
                Some(f) if f.label == label && f.kind == LoopKind::While => {
                    Ok(FlowAction::Seek(f.target))
                }
                _ => Err(flow_err(
                    block,
                    "flow::endwhile-without-while",
                    format!("{name} endwhile without a matching while"),
                )),
            },
            OKind::Do => {
                self.check_nesting(block, opts)?;
                self.loops.push(LoopFrame {
                    label,
                    kind: LoopKind::Do,
                    target: next,
                    line: block.line,
                    head: here,
                    iterations: 1,
                });
                Ok(FlowAction::Handled)
            }
            OKind::Repeat(n) => {
                let n = eval.eval(*n)?.round();
                if n < 1.0 {
                    self.skip = Some(Skip::LoopEnd(label, None));
                } else {
                    self.check_nesting(block, opts)?;
                    self.loops.push(LoopFrame {
                        label,
                        kind: LoopKind::Repeat(n.min(u64::MAX as f64) as u64),
                        target: next,
                        line: block.line,
                        head: here,
                        iterations: 1,
                    });
                }
                Ok(FlowAction::Handled)
            }
            OKind::EndRepeat => self.end_repeat(block, &label, &name, opts),
            OKind::Break | OKind::Continue
                if self
                    .loops
                    .last()
                    .is_some_and(|f| f.label == label && matches!(f.kind, LoopKind::Repeat(_))) =>
            {
                // LinuxCNC leaves only while and do loops with break and continue.
                let line = self.loops.last().map_or(0, |f| f.line);
                Err(flow_err(
                    block,
                    "flow::not-while-or-do",
                    format!(
                        "{}: no matching while/do label: '{}' (found 'repeat' in line {line})",
                        block.line,
                        block.text.trim()
                    ),
                ))
            }
            OKind::Break => match self.loops.last() {
                Some(f) if f.label == label => {
                    let frame = self.loops.pop();
                    self.doing_break = true;
                    self.skip = Some(Skip::LoopEnd(label, frame));
                    Ok(FlowAction::Handled)
                }
                _ => Err(flow_err(
                    block,
                    "flow::break-outside-loop",
                    format!("{name} break outside its loop"),
                )),
            },
            OKind::Continue => match self.loops.last().map(|f| f.kind) {
                Some(LoopKind::Do) if self.loops.last().map(|f| &f.label) == Some(&label) => {
                    // LinuxCNC skips to the loop's `while` line, which tests the condition.
                    self.doing_continue = true;
                    self.skip = Some(Skip::DoEnd(label));
                    Ok(FlowAction::Handled)
                }
                Some(_) if self.loops.last().map(|f| &f.label) == Some(&label) => {
                    let f = self.loops.last_mut().expect("checked");
                    f.iterations += 1;
                    check_iterations(block, f, &mut self.total_iterations, opts)?;
                    Ok(FlowAction::Seek(f.target))
                }
                _ => Err(flow_err(
                    block,
                    "flow::continue-outside-loop",
                    format!("{name} continue outside its loop"),
                )),
            },
        }
    }

    /// The nesting bound: open if and loop constructs (calls have their own, `max_call_depth`).
    fn check_nesting(&self, block: &Block, opts: &InterpOptions) -> Result<(), Diagnostic> {
        if self.ifs.len() + self.loops.len() >= opts.max_nesting {
            return Err(flow_err(
                block,
                "flow::too-deep",
                format!(
                    "more than {} if/loop constructs open at once",
                    opts.max_nesting
                ),
            )
            .with_note("the bound is the option --max-nesting"));
        }
        Ok(())
    }

    fn end_repeat(
        &mut self,
        block: &Block,
        label: &str,
        name: &str,
        opts: &InterpOptions,
    ) -> Result<FlowAction, Diagnostic> {
        match self.loops.last_mut() {
            Some(f) if f.label == label => {
                let LoopKind::Repeat(remaining) = f.kind else {
                    return Err(flow_err(
                        block,
                        "flow::endrepeat-without-repeat",
                        format!("{name} endrepeat without a matching repeat"),
                    ));
                };
                if remaining > 1 {
                    f.kind = LoopKind::Repeat(remaining - 1);
                    f.iterations += 1;
                    check_iterations(block, f, &mut self.total_iterations, opts)?;
                    Ok(FlowAction::Seek(f.target))
                } else {
                    let head = f.head;
                    self.loops.pop();
                    if std::mem::take(&mut self.doing_continue) {
                        // LinuxCNC goes back to the `repeat` line, finds the count spent, skips
                        // to `endrepeat` — where the continue pending from a do-loop sends it
                        // back again, to a count evaluated anew: the loop runs once more.
                        return Ok(FlowAction::Seek(head));
                    }
                    Ok(FlowAction::Handled)
                }
            }
            _ => Err(flow_err(
                block,
                "flow::endrepeat-without-repeat",
                format!("{name} endrepeat without a matching repeat"),
            )),
        }
    }

    fn enter(
        &mut self,
        block: &Block,
        eval: &Evaluator<'_>,
        call: Call,
        opts: &InterpOptions,
    ) -> Result<(), Diagnostic> {
        let Call {
            label,
            args,
            return_pos,
            file,
        } = call;
        if self.calls.len() >= opts.max_call_depth {
            return Err(flow_err(
                block,
                "flow::call-depth",
                format!(
                    "subroutine calls nested deeper than {}",
                    opts.max_call_depth
                ),
            ));
        }
        let mut saved = [0.0; 30];
        for (i, s) in saved.iter_mut().enumerate() {
            *s = eval.params.get(i + 1);
        }
        self.calls.push(CallFrame {
            label,
            return_pos,
            file,
            saved,
            loops: self.loops.len(),
            ifs: self.ifs.len(),
        });
        self.ops.push((ParamOp::PushScope, 0.0));
        for i in 0..30 {
            self.ops.push((
                ParamOp::Write(Slot::Numbered(i + 1)),
                args.get(i).copied().unwrap_or(0.0),
            ));
        }
        Ok(())
    }

    /// The error for a construct still open at end of file, if any.
    pub fn unterminated(&self, last: &Block) -> Option<Diagnostic> {
        let msg = match &self.skip {
            // LinuxCNC's wording, located at the call (the end of the file only shows that the
            // definition never came), with where it was looked for and what to do.
            Some(Skip::FindSub {
                label, call, tried, ..
            }) => {
                let mut d = Diagnostic::error(
                    "flow::unterminated",
                    format!(
                        "EOF in file seeking o-word: o{label} from line: {}",
                        call.line
                    ),
                    *call,
                );
                d = d.with_note(format!(
                    "subroutine o{label} is not defined: looked for `o{label} sub` in the rest of the program{}",
                    if tried.is_empty() {
                        String::new()
                    } else {
                        format!(
                            " and in {}",
                            tried
                                .iter()
                                .map(|p| p.display().to_string())
                                .collect::<Vec<_>>()
                                .join(", ")
                        )
                    }
                ));
                if label.starts_with('<') {
                    let name = label.trim_start_matches('<').trim_end_matches('>');
                    d = d.with_note(format!(
                        "a subroutine in its own file `{name}.ngc` is found with --subroutine-path DIR"
                    ));
                }
                return Some(d);
            }
            // A definition without its endsub swallows the rest of the file; LinuxCNC then
            // reports the missing program end.
            Some(Skip::Sub(l)) => {
                format!("File ended with no percent sign or program end (o{l} sub has no endsub)")
            }
            Some(Skip::IfBranch(l)) | Some(Skip::ToEndIf(l)) => format!("o{l} if has no endif"),
            Some(Skip::LoopEnd(l, _) | Skip::DoEnd(l)) => format!("o{l} loop has no end"),
            None => {
                if let Some(c) = self.calls.last() {
                    format!("file ended inside subroutine o{}", c.label)
                } else if let Some(l) = self.loops.last() {
                    format!("o{} loop has no end", l.label)
                } else if let Some(i) = self.ifs.last() {
                    format!("o{i} if has no endif")
                } else {
                    return None;
                }
            }
        };
        Some(Diagnostic::error("flow::unterminated", msg, last.span()).fatal())
    }
}

fn check_iterations(
    block: &Block,
    f: &LoopFrame,
    total: &mut u64,
    opts: &InterpOptions,
) -> Result<(), Diagnostic> {
    *total += 1;
    if *total > opts.max_total_loop_iterations {
        return Err(flow_err(
            block,
            "flow::too-many-iterations",
            format!(
                "the loops of this run passed more than {} times in all: stopping (runaway \
                 nested loops?)",
                opts.max_total_loop_iterations
            ),
        )
        .with_note("the bound is the option --max-total-loop-iterations"));
    }
    if f.iterations > opts.max_loop_iterations {
        return Err(flow_err(
            block,
            "flow::too-many-iterations",
            format!(
                "loop o{} ran more than {} times: stopping (endless loop?)",
                f.label, opts.max_loop_iterations
            ),
        ));
    }
    Ok(())
}
