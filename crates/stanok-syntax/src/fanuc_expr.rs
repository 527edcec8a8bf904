//! Fanuc-style custom macro expressions (Mazatrol EIA/ISO), read into the block's expression
//! arena without recursion.
//!
//! Grammar (`docs/dialects/mazatrol-eia.md` §2.5; blanks are ignored between tokens):
//!
//! ```text
//! expression := operand (binop operand)*
//! operand    := ('-' | '+')* primary
//! primary    := number | '#' variable | '[' expression ']'
//!             | FUNC '[' expression ']'                -- SIN COS TAN ASIN ACOS SQRT ABS ROUND FIX FUP LN EXP
//!             | 'ATAN' '[' expression ']' [ '/' '[' expression ']' ]
//!             | 'ATAN' '[' expression ',' expression ']'
//! variable   := digits | '[' expression ']'            -- no `##`, no `#<name>`, no sign
//! ```
//!
//! Precedence (Fanuc's, not LinuxCNC's), highest first, left-associative within a level:
//! functions and signs; `*` `/` `AND` `MOD`; `+` `-` `OR` `XOR`; `EQ NE GT GE LT LE`. A
//! comparison may not be chained (`[1 LT 2 LT 3]`): brackets are required.
//!
//! Algorithm: shunting-yard with an explicit operator stack. `ops` holds openers (`[`, `#[`,
//! `SIN[`, `ATAN[` and ATAN's second argument), pending signs and binary operators; `vals` the
//! arena ids of finished operands. An operand is finished by a number, a variable number or a
//! closing bracket; the signs directly below it on `ops` are applied at once (a sign binds
//! tightest). A binary operator first reduces every operator of the same or higher precedence on
//! top of `ops`. `]` reduces down to its opener and wraps the result as the opener says.
//! *Invariant:* nodes are pushed children first and every subtree occupies a contiguous range of
//! the arena ending at its root, so the interpreter can evaluate an expression in one forward
//! pass over that range, and nothing here recurses: a line of any length cannot overflow the
//! stack. Brackets nest at most [`MAX_BRACKETS`] deep (the control's limit).
//!
//! Three reading modes: `Bracketed` (an IF/WHILE condition: exactly one `[ … ]`), `Open` (the
//! right side of an assignment: ends where an operator is expected and none follows) and
//! `Operand` (a word's value, a GOTO target: one operand, its signs included, and no binary
//! operator outside brackets — Fanuc requires `X[#1+#2]`, not `X#1+#2`).

use crate::ast::{BinOp, ColSpan, ExprId, ExprNode, ParamRef, UnaryFn};
use crate::fanuc::{Fx, R};
use crate::lexer::{excerpt, skip_blanks};
use crate::number::{parse_digits, parse_number};

/// Deepest nesting of brackets (plain, `#[`, function) in one expression: Fanuc's five levels.
pub(crate) const MAX_BRACKETS: usize = 5;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Bracketed,
    Open,
    Operand,
}

/// What an opening bracket will make of its content.
#[derive(Debug, Clone, Copy)]
enum Opener {
    Bracket,
    Hash,
    Func(UnaryFn),
    Atan,
    /// `ATAN[y,` — the first argument is finished.
    AtanComma(ExprId),
    /// `ATAN[y]/[` — the first argument is finished.
    AtanSlash(ExprId),
}

#[derive(Debug, Clone, Copy)]
enum Op {
    /// An opener and where its text starts (the `[`, the `#`, the function name).
    Open(Opener, usize),
    /// A sign and where it is.
    Sign(UnaryFn, usize),
    Binary(BinOp),
}

/// Function names; `None` for names Fanuc has that Stanok does not offer.
const FUNCTIONS: &[(&[u8], Option<Opener>)] = &[
    (b"SIN", Some(Opener::Func(UnaryFn::Sin))),
    (b"COS", Some(Opener::Func(UnaryFn::Cos))),
    (b"TAN", Some(Opener::Func(UnaryFn::Tan))),
    (b"ASIN", Some(Opener::Func(UnaryFn::Asin))),
    (b"ACOS", Some(Opener::Func(UnaryFn::Acos))),
    (b"ATAN", Some(Opener::Atan)),
    (b"SQRT", Some(Opener::Func(UnaryFn::Sqrt))),
    (b"ABS", Some(Opener::Func(UnaryFn::Abs))),
    (b"ROUND", Some(Opener::Func(UnaryFn::Round))),
    (b"FIX", Some(Opener::Func(UnaryFn::Fix))),
    (b"FUP", Some(Opener::Func(UnaryFn::Fup))),
    (b"LN", Some(Opener::Func(UnaryFn::Ln))),
    (b"EXP", Some(Opener::Func(UnaryFn::Exp))),
    (b"BIN", None),
    (b"BCD", None),
    (b"ADP", None),
    (b"POW", None),
];

/// Word operators.
const WORD_OPS: &[(&[u8], BinOp)] = &[
    (b"AND", BinOp::And),
    (b"MOD", BinOp::Mod),
    (b"OR", BinOp::Or),
    (b"XOR", BinOp::Xor),
    (b"EQ", BinOp::Eq),
    (b"NE", BinOp::Ne),
    (b"GT", BinOp::Gt),
    (b"GE", BinOp::Ge),
    (b"LT", BinOp::Lt),
    (b"LE", BinOp::Le),
];

/// Fanuc's precedence levels (higher binds tighter).
fn precedence(op: BinOp) -> u8 {
    match op {
        BinOp::Pow => 4,
        BinOp::Mul | BinOp::Div | BinOp::And | BinOp::Mod => 3,
        BinOp::Add | BinOp::Sub | BinOp::Or | BinOp::Xor => 2,
        BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Ge | BinOp::Lt | BinOp::Le => 1,
    }
}

/// What a `]` finished.
enum Closed {
    /// The whole bracketed expression.
    Whole(ExprId),
    /// An operand inside the expression.
    Operand,
    /// ATAN's first argument; its second `[` is open now.
    Reopened,
}

/// The operator stack, the finished operands (with "is an unbracketed comparison") and the
/// number of open brackets.
#[derive(Default)]
struct Stacks {
    ops: Vec<Op>,
    vals: Vec<(ExprId, bool)>,
    open: usize,
}

impl Fx<'_> {
    fn node(&mut self, node: ExprNode, start: usize, end: usize) -> ExprId {
        let id = ExprId(self.out.exprs.len() as u32);
        self.out.exprs.push((node, ColSpan::new(start, end)));
        id
    }

    fn span_of(&self, id: ExprId) -> ColSpan {
        self.out.exprs[id.0 as usize].1
    }

    /// An IF/WHILE condition: one `[ … ]` at the cursor; the root's span includes the brackets.
    pub(crate) fn bracketed(&mut self) -> R<ExprId> {
        self.expression(Mode::Bracketed, "a value")
    }

    /// The right side of an assignment.
    pub(crate) fn open_expression(&mut self) -> R<ExprId> {
        self.expression(Mode::Open, "a value after `=`")
    }

    /// One operand with its signs (a word's value, a GOTO target).
    pub(crate) fn operand_value(&mut self, what: &str) -> R<ExprId> {
        self.expression(Mode::Operand, what)
    }

    /// The variable number after `#` (cursor just after it): digits, or `[expression]`.
    pub(crate) fn variable_after_hash(&mut self) -> R<ExprId> {
        let hash = self.pos.saturating_sub(1);
        match self.peek() {
            Some(b'0'..=b'9') => {
                let start = self.pos;
                let (v, end) = parse_digits(self.b, start, false).unwrap_or((None, start + 1));
                let Some(v) = v.filter(|&v| v <= u32::MAX as u64) else {
                    return self.fail("syntax::bad-number", "variable number too large", hash, end);
                };
                self.pos = end;
                Ok(self.node(ExprNode::Number(v as f64), start, end))
            }
            Some(b'[') => self.bracketed(),
            next => {
                let end = match next {
                    Some(_) => crate::lexer::char_end(self.b, self.pos),
                    None => self.pos,
                };
                self.fail(
                    "syntax::bad-parameter",
                    "a variable is `#` followed by its number or a bracketed expression (`#100`, `#[#1+1]`)",
                    hash,
                    end.max(hash + 1),
                )
            }
        }
    }

    /// The shunting-yard loop (see the module comment).
    fn expression(&mut self, mode: Mode, what: &str) -> R<ExprId> {
        let mut s = Stacks::default();
        if mode == Mode::Bracketed {
            let start = self.pos;
            self.pos += 1;
            s.ops.push(Op::Open(Opener::Bracket, start));
            s.open = 1;
        }
        let mut want_operand = true;
        loop {
            if want_operand {
                self.operand_step(&mut s, what, &mut want_operand)?;
                continue;
            }
            // An operator, a closing bracket, a comma, or the end.
            let c = self.peek();
            let op = match c {
                Some(b'+') => Some((BinOp::Add, 1)),
                Some(b'-') => Some((BinOp::Sub, 1)),
                Some(b'*') => Some((BinOp::Mul, 1)),
                Some(b'/') => Some((BinOp::Div, 1)),
                Some(c) if c.is_ascii_alphabetic() => {
                    let mut buf = [0u8; 8];
                    let (end, n) = self.letter_run(&mut buf);
                    WORD_OPS
                        .iter()
                        .find(|(w, _)| n == w.len() && &buf[..n] == *w)
                        .map(|&(_, op)| (op, end - self.pos))
                }
                _ => None,
            };
            if let Some((op, len)) = op {
                if !(mode == Mode::Operand && s.open == 0) {
                    let at = self.pos;
                    self.pos += len;
                    self.push_binary(&mut s, op, at)?;
                    want_operand = true;
                    continue;
                }
            }
            match c {
                Some(b']') if s.open > 0 => match self.close(&mut s, mode)? {
                    Closed::Whole(done) => return Ok(done),
                    Closed::Operand => {}
                    Closed::Reopened => want_operand = true,
                },
                Some(b',') if s.open > 0 => {
                    self.comma(&mut s)?;
                    want_operand = true;
                }
                _ if s.open > 0 => {
                    if c.is_none() {
                        let start = s
                            .ops
                            .iter()
                            .rev()
                            .find_map(|o| match o {
                                Op::Open(_, at) => Some(*at),
                                _ => None,
                            })
                            .unwrap_or(0);
                        return self.fail(
                            "syntax::unbalanced-brackets",
                            "`[` has no matching `]`",
                            start,
                            start + 1,
                        );
                    }
                    return self.unexpected("an operator or `]`");
                }
                _ => {
                    self.reduce(&mut s, 0);
                    return match s.vals.pop() {
                        Some((v, _)) if s.vals.is_empty() && s.ops.is_empty() => Ok(v),
                        _ => self.unexpected(what),
                    };
                }
            }
        }
    }

    /// One step where an operand is expected: a sign, a number, a variable, an opening bracket
    /// or a function.
    fn operand_step(&mut self, s: &mut Stacks, what: &str, want: &mut bool) -> R<()> {
        let Some(c) = self.peek() else {
            return self.unexpected(what);
        };
        let start = self.pos;
        match c {
            b'0'..=b'9' | b'.' | b'+' | b'-' => {
                if let Some(n) = parse_number(self.b, start, true) {
                    self.pos = n.end;
                    let id = self.node(ExprNode::Number(n.value), start, n.end);
                    self.finish_operand(s, id);
                    *want = false;
                } else if c == b'+' || c == b'-' {
                    let f = if c == b'-' {
                        UnaryFn::Neg
                    } else {
                        UnaryFn::Plus
                    };
                    s.ops.push(Op::Sign(f, start));
                    self.pos += 1;
                } else {
                    return self.fail(
                        "syntax::bad-number",
                        format!("malformed number `{}`", excerpt(self.b, start, start + 1)),
                        start,
                        start + 1,
                    );
                }
            }
            b'#' => {
                self.pos += 1;
                if self.peek() == Some(b'[') {
                    self.open_bracket(s, Opener::Hash, start)?;
                } else {
                    let index = self.variable_after_hash()?;
                    let end = self.pos;
                    let id = self.node(ExprNode::Param(ParamRef::Numbered(index)), start, end);
                    self.finish_operand(s, id);
                    *want = false;
                }
            }
            b'[' => self.open_bracket(s, Opener::Bracket, start)?,
            c if c.is_ascii_alphabetic() => {
                let mut buf = [0u8; 8];
                let (end, n) = self.letter_run(&mut buf);
                let found = FUNCTIONS
                    .iter()
                    .find(|(name, _)| n == name.len() && &buf[..n] == *name);
                let Some(&(name, opener)) = found else {
                    return self.fail(
                        "syntax::unknown-word",
                        format!("unknown function `{}`", excerpt(self.b, start, end)),
                        start,
                        end,
                    );
                };
                let upper = String::from_utf8_lossy(name).into_owned();
                let Some(opener) = opener else {
                    return self.fail(
                        "syntax::unknown-word",
                        format!("the function `{upper}` is not supported"),
                        start,
                        end,
                    );
                };
                self.pos = end;
                if self.peek() != Some(b'[') {
                    return self.fail(
                        "syntax::bad-function",
                        format!("`{upper}` must be followed by `[`"),
                        start,
                        end,
                    );
                }
                self.open_bracket(s, opener, start)?;
            }
            _ => return self.unexpected(&format!("{what}: a number, `#i`, `[` or a function")),
        }
        Ok(())
    }

    /// Pushes an opener; the cursor is on its `[`.
    fn open_bracket(&mut self, s: &mut Stacks, opener: Opener, start: usize) -> R<()> {
        s.open += 1;
        if s.open > MAX_BRACKETS {
            let at = self.pos;
            return self.fail(
                "syntax::expression-too-deep",
                format!("brackets nested more than {MAX_BRACKETS} deep (the control's limit)"),
                at,
                at + 1,
            );
        }
        s.ops.push(Op::Open(opener, start));
        self.pos += 1;
        Ok(())
    }

    /// An operand is finished: the signs directly below it apply now. (A comparison that is
    /// an operand came out of brackets, so it is not a bare one.)
    fn finish_operand(&mut self, s: &mut Stacks, mut id: ExprId) {
        while let Some(&Op::Sign(f, at)) = s.ops.last() {
            s.ops.pop();
            let end = self.span_of(id).end as usize;
            id = self.node(ExprNode::Unary(f, id), at, end);
        }
        s.vals.push((id, false));
    }

    /// Reduces the binary operators of precedence ≥ `min` on top of the stack.
    fn reduce(&mut self, s: &mut Stacks, min: u8) {
        while let Some(&Op::Binary(op)) = s.ops.last() {
            if precedence(op) < min || s.vals.len() < 2 {
                break;
            }
            s.ops.pop();
            let (r, _) = s.vals.pop().unwrap_or((ExprId(0), false));
            let (l, _) = s.vals.pop().unwrap_or((ExprId(0), false));
            let start = self.span_of(l).start as usize;
            let end = self.span_of(r).end as usize;
            let id = self.node(ExprNode::Binary(op, l, r), start, end);
            s.vals.push((id, precedence(op) == 1));
        }
    }

    fn push_binary(&mut self, s: &mut Stacks, op: BinOp, at: usize) -> R<()> {
        let p = precedence(op);
        self.reduce(s, p);
        if p == 1 && s.vals.last().is_some_and(|v| v.1) {
            return self.fail(
                "syntax::chained-comparison",
                "comparisons cannot be chained: bracket each one (`[[#1 LT #2] AND [#2 LT #3]]`)",
                at,
                at + 2,
            );
        }
        s.ops.push(Op::Binary(op));
        Ok(())
    }

    /// `]`: reduce to the opener and wrap.
    fn close(&mut self, s: &mut Stacks, mode: Mode) -> R<Closed> {
        self.reduce(s, 0);
        let close_at = self.pos;
        let (Some(Op::Open(opener, start)), Some((inner, _))) = (s.ops.pop(), s.vals.pop()) else {
            return self.unexpected("a value");
        };
        self.pos += 1;
        let end = self.pos;
        let id = match opener {
            Opener::Bracket => {
                self.out.exprs[inner.0 as usize].1 = ColSpan::new(start, end);
                inner
            }
            Opener::Hash => self.node(ExprNode::Param(ParamRef::Numbered(inner)), start, end),
            Opener::Func(f) => self.node(ExprNode::Unary(f, inner), start, end),
            Opener::Atan => {
                // `ATAN[y]/[x]`: the two-argument form; plain `ATAN[t]` is atan(t) = ATAN[t]/[1].
                let q = skip_blanks(self.b, end);
                if self.b.get(q) == Some(&b'/')
                    && self.b.get(skip_blanks(self.b, q + 1)) == Some(&b'[')
                {
                    self.pos = skip_blanks(self.b, q + 1) + 1;
                    s.ops.push(Op::Open(Opener::AtanSlash(inner), start));
                    return Ok(Closed::Reopened);
                }
                let one = self.node(ExprNode::Number(1.0), close_at, close_at);
                self.node(ExprNode::Atan(inner, one), start, end)
            }
            Opener::AtanComma(y) | Opener::AtanSlash(y) => {
                self.node(ExprNode::Atan(y, inner), start, end)
            }
        };
        s.open -= 1;
        if mode == Mode::Bracketed && s.ops.is_empty() && s.vals.is_empty() {
            return Ok(Closed::Whole(id));
        }
        self.finish_operand(s, id);
        Ok(Closed::Operand)
    }

    /// `,` inside `ATAN[y, x]`.
    fn comma(&mut self, s: &mut Stacks) -> R<()> {
        self.reduce(s, 0);
        match (s.ops.last().copied(), s.vals.last().copied()) {
            (Some(Op::Open(Opener::Atan, start)), Some((y, _))) => {
                s.ops.pop();
                s.vals.pop();
                s.ops.push(Op::Open(Opener::AtanComma(y), start));
                self.pos += 1;
                Ok(())
            }
            _ => {
                let at = self.pos;
                self.fail(
                    "syntax::unexpected-character",
                    "`,` separates the two arguments of `ATAN[y, x]` and nothing else",
                    at,
                    at + 1,
                )
            }
        }
    }
}
