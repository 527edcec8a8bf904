//! AxiOMA's C-like high-level language (HLL): control flow over the streamed program.
//!
//! The program is never held in memory: lines come one at a time from the `BlockReader`, and a
//! loop goes round by seeking back to its header line, as RS274/NGC O-word loops do (`flow.rs`).
//! The parser gives each HLL line as a list of items (`stanok_syntax::hll::HItem`); this module
//! pairs headers with their bodies and braces as they stream past:
//!
//! * **frames** — a stack of open constructs: `Body` (a `{ … }` being executed, with the
//!   construct that owns it: if, else, loop, or a plain block) and `Loop` (a `for`/`while`/`do`
//!   with the position of its header: line start + item index, and its iteration count);
//! * **expect** — what the next item must or may be: the body of a header just read (run it or
//!   skip it), an optional `else` after an `if` statement ended, the `while (c);` that ends a
//!   `do` body;
//! * **skip** — when a body is not to run (false condition, `break`, `continue`) the items are
//!   read without executing, counting braces, until the `}` that closes it; then the owner is
//!   closed as if the body had run.
//!
//! Closing a loop body seeks back to the loop's header item with `reenter` set: the header then
//! runs its step and condition instead of its initialisation. A body is `{ … }` or one simple
//! statement (expression, `break`, `continue`, `;`, or one ISO block on its own line); a nested
//! header as an unbraced body is refused (except `else if`), so that every construct ends at a
//! known item.
//!
//! ISO blocks execute through the normal AxiOMA path, with word expressions (`X=ii*10`)
//! evaluated when the block executes. Bounds: every loop counts its passes against
//! `InterpOptions::max_loop_iterations`, and the driver's block counter bounds the whole run.
//! A failing HLL line restores the control state and undoes its variable writes (journal in
//! `eval.rs`); the run stops there.

mod builtins;
mod driver;
pub mod eval;
pub mod format;
pub mod value;

use eval::{Env, Vars};

use stanok_canon::{Diagnostic, Span};
use stanok_syntax::hll::{HItem, HllLine};
use stanok_syntax::SourcePos;

pub use driver::{HllStep, OwnerToken};

/// Which construct a body belongs to, i.e. what happens when it ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Owner {
    /// An `if` (taken or not): an `else` may follow.
    If { taken: bool },
    /// An `else`.
    Else,
    /// A loop pass: go round (or to the `do`'s condition).
    Loop,
    /// A loop that ends (false condition or `break`).
    LoopEnd,
    /// A plain `{ … }`.
    Plain,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LoopKind {
    For,
    While,
    Do,
}

#[derive(Debug, Clone)]
struct LoopFrame {
    kind: LoopKind,
    /// The header's line and its index among the line's items.
    header: SourcePos,
    item: usize,
    iterations: u64,
    span: Span,
    /// A scope was opened for the `for` initialisation.
    scoped: bool,
}

#[derive(Debug, Clone)]
enum Frame {
    Body { owner: Owner, open: Span },
    Loop(LoopFrame),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    Nothing,
    Body {
        run: bool,
        owner: Owner,
        header: Span,
    },
    ElseOrNot {
        run_else: bool,
    },
    DoWhileCond,
    IgnoreWhile,
}

#[derive(Debug, Clone, Copy)]
struct Skip {
    /// `}` still to pass before the owner closes.
    closes: u32,
    /// `{` opened inside the skipped text.
    nested: u32,
    then: Owner,
    open: Span,
}

/// The HLL state of a run. Created at the first HLL line or expression, so that programs
/// without HLL never pay for it.
#[derive(Debug, Clone)]
pub struct Hll {
    /// The variables.
    pub vars: Vars,
    control: Control,
}

/// The control-flow state (frames, expectation, skipping, where to resume).
#[derive(Debug, Clone)]
struct Control {
    frames: Vec<Frame>,
    expect: Expect,
    skip: Option<Skip>,
    /// After a seek: the line (offset) and the item to resume at.
    resume: Option<(u64, usize)>,
    /// The seek goes back to a loop header to run its step and condition.
    reenter: bool,
    max_iterations: u64,
}

/// What an item asks of the driver.
type Jump = Option<SourcePos>;

type R<T> = Result<T, Diagnostic>;

impl Hll {
    fn new(max_iterations: u64) -> Self {
        Hll {
            vars: Vars::default(),
            control: Control {
                frames: Vec::new(),
                expect: Expect::Nothing,
                skip: None,
                resume: None,
                reenter: false,
                max_iterations,
            },
        }
    }

    /// True while items are read without executing.
    pub fn skipping(&self) -> bool {
        self.control.skip.is_some()
    }
}

impl Control {
    /// Runs the items of an HLL line (`here` = where the line starts).
    fn line(&mut self, env: &mut Env<'_>, here: SourcePos) -> R<Jump> {
        let first = match self.resume.take() {
            Some((offset, item)) if offset == here.offset => item,
            _ => 0,
        };
        let block = env.block;
        let hll: &HllLine = block.hll();
        for (idx, (item, span)) in hll.items.iter().enumerate().skip(first) {
            let span = block.span_of(*span);
            if let Some(jump) = self.item(env, here, idx, item, span)? {
                return Ok(Some(jump));
            }
        }
        Ok(None)
    }

    fn item(
        &mut self,
        env: &mut Env<'_>,
        here: SourcePos,
        idx: usize,
        item: &HItem,
        span: Span,
    ) -> R<Jump> {
        if let Some(skip) = &mut self.skip {
            match item {
                HItem::Open => skip.nested += 1,
                HItem::Close if skip.nested > 0 => skip.nested -= 1,
                HItem::Close => {
                    skip.closes -= 1;
                    if skip.closes == 0 {
                        let then = skip.then;
                        self.skip = None;
                        return self.close_owner(env, then, span);
                    }
                }
                _ => {}
            }
            return Ok(None);
        }
        match std::mem::replace(&mut self.expect, Expect::Nothing) {
            Expect::Nothing => {}
            Expect::ElseOrNot { run_else } => {
                if *item == HItem::Else {
                    self.expect = Expect::Body {
                        run: run_else,
                        owner: Owner::Else,
                        header: span,
                    };
                    return Ok(None);
                }
            }
            Expect::IgnoreWhile => {
                if matches!(item, HItem::While { .. }) {
                    return Ok(None);
                }
            }
            Expect::DoWhileCond => {
                let HItem::While { cond, .. } = item else {
                    return Err(Diagnostic::error(
                        "hll::expected-while",
                        "the body of `do` must be followed by `while (condition);`",
                        span,
                    ));
                };
                if env.truth(*cond)? {
                    let (header, item) = self.count_pass()?;
                    self.reenter = true;
                    self.resume = Some((header.offset, item));
                    return Ok(Some(header));
                }
                self.end_loop(env);
                return Ok(None);
            }
            Expect::Body { run, owner, header } => match item {
                HItem::Open if run => {
                    self.frames.push(Frame::Body { owner, open: span });
                    env.vars.push_scope();
                    return Ok(None);
                }
                HItem::Open => {
                    self.skip = Some(Skip {
                        closes: 1,
                        nested: 0,
                        then: owner,
                        open: span,
                    });
                    return Ok(None);
                }
                HItem::If(_) if owner == Owner::Else && !run => {
                    // `else if` of an else that does not run: its if and else are skipped too.
                    self.expect = Expect::Body {
                        run: false,
                        owner: Owner::If { taken: true },
                        header: span,
                    };
                    return Ok(None);
                }
                HItem::If(_) if owner == Owner::Else => {}
                HItem::Expr(_) | HItem::Empty | HItem::Break | HItem::Continue if !run => {
                    return self.close_owner(env, owner, span);
                }
                HItem::Expr(_) | HItem::Empty => {
                    self.simple(env, item)?;
                    return self.close_owner(env, owner, span);
                }
                HItem::Break | HItem::Continue => {}
                _ => {
                    return Err(Diagnostic::error(
                        "hll::body",
                        "the body of `if`, `else`, `for`, `while` or `do` must be one statement or `{ … }`: put a nested construct in braces",
                        span,
                    )
                    .with_note(format!("the construct starts at line {}", header.line)))
                }
            },
        }
        match item {
            HItem::Decl { .. } | HItem::Expr(_) | HItem::Empty => {
                self.simple(env, item)?;
                Ok(None)
            }
            HItem::Open => {
                self.frames.push(Frame::Body {
                    owner: Owner::Plain,
                    open: span,
                });
                env.vars.push_scope();
                Ok(None)
            }
            HItem::Close => match self.frames.pop() {
                Some(Frame::Body { owner, .. }) => {
                    env.vars.pop_scope();
                    self.close_owner(env, owner, span)
                }
                other => {
                    if let Some(f) = other {
                        self.frames.push(f);
                    }
                    Err(Diagnostic::error(
                        "hll::unmatched-brace",
                        "`}` without a matching `{`",
                        span,
                    ))
                }
            },
            HItem::If(cond) => {
                let taken = env.truth(*cond)?;
                self.expect = Expect::Body {
                    run: taken,
                    owner: Owner::If { taken },
                    header: span,
                };
                Ok(None)
            }
            HItem::Else => Err(Diagnostic::error(
                "hll::else-without-if",
                "`else` without an `if` before it",
                span,
            )),
            HItem::While { cond, terminated } => {
                self.enter_loop(env, LoopKind::While, here, idx, span)?;
                if *terminated {
                    // `while (c);`: the empty statement is the body — go round right here.
                    while env.truth(*cond)? {
                        self.count_pass()?;
                    }
                    self.end_loop(env);
                    return Ok(None);
                }
                let run = env.truth(*cond)?;
                self.loop_body(run, span);
                Ok(None)
            }
            HItem::For { init, cond, step } => {
                if self.enter_loop(env, LoopKind::For, here, idx, span)? {
                    if let Some(init) = init {
                        self.simple(env, init)?;
                    }
                } else if let Some(step) = step {
                    env.eval(*step)?;
                }
                let run = match cond {
                    Some(c) => env.truth(*c)?,
                    None => true,
                };
                self.loop_body(run, span);
                Ok(None)
            }
            HItem::Do => {
                self.enter_loop(env, LoopKind::Do, here, idx, span)?;
                self.loop_body(true, span);
                Ok(None)
            }
            HItem::Break | HItem::Continue => {
                let Some(k) = self
                    .frames
                    .iter()
                    .rposition(|f| matches!(f, Frame::Loop(_)))
                else {
                    return Err(Diagnostic::error(
                        "hll::outside-loop",
                        format!(
                            "`{}` outside a loop",
                            if *item == HItem::Break {
                                "break"
                            } else {
                                "continue"
                            }
                        ),
                        span,
                    ));
                };
                let mut closes = 0;
                let mut open = span;
                while self.frames.len() > k + 1 {
                    if let Some(Frame::Body { open: o, .. }) = self.frames.pop() {
                        open = o;
                    }
                    env.vars.pop_scope();
                    closes += 1;
                }
                let then = if *item == HItem::Break {
                    Owner::LoopEnd
                } else {
                    Owner::Loop
                };
                if closes == 0 {
                    return self.close_owner(env, then, span);
                }
                self.skip = Some(Skip {
                    closes,
                    nested: 0,
                    then,
                    open,
                });
                Ok(None)
            }
        }
    }

    /// Declarations and expression statements.
    fn simple(&mut self, env: &mut Env<'_>, item: &HItem) -> R<()> {
        match item {
            HItem::Decl { ty, vars } => {
                for d in vars {
                    env.declare(*ty, d)?;
                }
            }
            HItem::Expr(e) => {
                env.eval(*e)?;
            }
            _ => {}
        }
        Ok(())
    }

    /// A loop header: pushes its frame the first time (true) or counts a pass on re-entry.
    fn enter_loop(
        &mut self,
        env: &mut Env<'_>,
        kind: LoopKind,
        here: SourcePos,
        idx: usize,
        span: Span,
    ) -> R<bool> {
        let again = std::mem::replace(&mut self.reenter, false)
            && matches!(self.frames.last(), Some(Frame::Loop(l)) if l.header == here && l.item == idx);
        if again {
            if kind != LoopKind::Do {
                self.count_pass()?;
            }
            return Ok(false);
        }
        let scoped = kind == LoopKind::For;
        if scoped {
            env.vars.push_scope();
        }
        self.frames.push(Frame::Loop(LoopFrame {
            kind,
            header: here,
            item: idx,
            iterations: 0,
            span,
            scoped,
        }));
        Ok(true)
    }

    fn loop_body(&mut self, run: bool, header: Span) {
        self.expect = Expect::Body {
            run,
            owner: if run { Owner::Loop } else { Owner::LoopEnd },
            header,
        };
    }

    /// Counts one more pass of the innermost loop against the limit; returns its header.
    fn count_pass(&mut self) -> R<(SourcePos, usize)> {
        let max = self.max_iterations;
        let Some(Frame::Loop(l)) = self.frames.last_mut() else {
            return Err(Diagnostic::error(
                "hll::internal",
                "loop state lost",
                Span::default(),
            ));
        };
        // `iterations` counts the passes after the first: pass `iterations + 1` is about to run.
        l.iterations += 1;
        if l.iterations >= max {
            return Err(Diagnostic::error(
                "hll::loop-limit",
                format!("the loop ran more than {max} times: stopped (endless loop?)"),
                l.span,
            )
            .with_note("the limit is the interpreter option `max_loop_iterations`"));
        }
        Ok((l.header, l.item))
    }

    /// Pops the innermost loop (and the scope of a `for`).
    fn end_loop(&mut self, env: &mut Env<'_>) -> Option<LoopKind> {
        match self.frames.pop() {
            Some(Frame::Loop(l)) => {
                if l.scoped {
                    env.vars.pop_scope();
                }
                Some(l.kind)
            }
            Some(other) => {
                self.frames.push(other);
                None
            }
            None => None,
        }
    }

    /// A body of `owner` has ended (run or skipped).
    fn close_owner(&mut self, env: &mut Env<'_>, owner: Owner, at: Span) -> R<Jump> {
        match owner {
            Owner::If { taken } => self.expect = Expect::ElseOrNot { run_else: !taken },
            Owner::Else | Owner::Plain => {}
            Owner::LoopEnd => {
                if self.end_loop(env) == Some(LoopKind::Do) {
                    self.expect = Expect::IgnoreWhile;
                }
            }
            Owner::Loop => {
                let Some(Frame::Loop(l)) = self.frames.last() else {
                    return Err(Diagnostic::error("hll::internal", "loop state lost", at));
                };
                if l.kind == LoopKind::Do {
                    self.expect = Expect::DoWhileCond;
                } else {
                    self.reenter = true;
                    self.resume = Some((l.header.offset, l.item));
                    return Ok(Some(l.header));
                }
            }
        }
        Ok(None)
    }

    /// An ISO block (or an empty line) arrives: whether it runs, and which body it completes.
    fn iso(&mut self, env: &mut Env<'_>, empty: bool, at: Span) -> R<IsoAction> {
        if self.skip.is_some() {
            return Ok(IsoAction::Skip(None));
        }
        if empty {
            return Ok(IsoAction::Execute(None));
        }
        match std::mem::replace(&mut self.expect, Expect::Nothing) {
            Expect::Nothing | Expect::ElseOrNot { .. } | Expect::IgnoreWhile => {
                Ok(IsoAction::Execute(None))
            }
            Expect::DoWhileCond => Err(Diagnostic::error(
                "hll::expected-while",
                "the body of `do` must be followed by `while (condition);`",
                at,
            )),
            Expect::Body {
                run: true, owner, ..
            } => Ok(IsoAction::Execute(Some(owner))),
            Expect::Body { owner, .. } => Ok(IsoAction::Skip(self.close_owner(env, owner, at)?)),
        }
    }

    /// End of the program text: every construct must be closed.
    fn end_of_input(&self, at: Span) -> R<()> {
        if let Some(s) = self.skip {
            return Err(unclosed(s.open));
        }
        for f in self.frames.iter().rev() {
            match f {
                Frame::Body { open, .. } => return Err(unclosed(*open)),
                Frame::Loop(l) => {
                    if !matches!(self.expect, Expect::Nothing) || l.kind == LoopKind::Do {
                        return Err(Diagnostic::error(
                            "hll::missing-body",
                            "the program ends before this loop is complete",
                            l.span,
                        ));
                    }
                }
            }
        }
        match self.expect {
            Expect::Body { header, .. } => Err(Diagnostic::error(
                "hll::missing-body",
                "the program ends before the body of this statement",
                header,
            )),
            Expect::DoWhileCond => Err(Diagnostic::error(
                "hll::expected-while",
                "the program ends before the `while (condition);` of a `do` loop",
                at,
            )),
            _ => Ok(()),
        }
    }
}

fn unclosed(open: Span) -> Diagnostic {
    Diagnostic::error(
        "hll::unclosed-brace",
        "`{` has no closing `}` before the end of the program",
        open,
    )
}

/// What to do with an ISO line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum IsoAction {
    /// Do not execute it; seek if skipping it completed a loop body.
    Skip(Jump),
    /// Execute it; afterwards close the owner whose single-statement body it was.
    Execute(Option<Owner>),
}
