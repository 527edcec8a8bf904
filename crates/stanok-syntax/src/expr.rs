//! RS274/NGC real values and bracketed expressions, read into the block's expression arena.
//!
//! Grammar (LinuxCNC `read_real_value` / `read_real_expression`, blanks ignored everywhere):
//!
//! ```text
//! real_value := number                      -- `1`, `-1.5`, `+.5` (sign directly before digits)
//!             | '[' expression ']'
//!             | '#' param                   -- `#5`, `##5`, `#[expr]`, `#<name>`, `#<_global>`
//!             | ('-' | '+') real_value      -- any other signed value: `-#1`, `-[1]`, `-sin[1]`
//!             | function '[' expression ']' -- ABS ACOS ASIN COS EXP FIX FUP LN ROUND SIN SQRT TAN
//!             | 'ATAN' '[' expression ']' '/' '[' expression ']'
//!             | 'EXISTS' '[' '#' '<' name '>' ']'
//! expression := real_value (binop real_value)*
//! param      := '<' name '>' | real_value   -- the parameter number is itself a real value
//! ```
//!
//! Binary operators by precedence, highest first (left-associative within a level, as LinuxCNC
//! evaluates them): `**` (4); `*` `/` `MOD` (3); `+` `-` (2); `EQ NE GT GE LT LE` (1);
//! `AND OR XOR` (0). Precedence climbing builds the tree: `binary(min)` reads an operand, then
//! while the next operator binds at least as tightly as `min`, reads the right side with
//! `binary(prec + 1)`. Sign binds tightest (it belongs to the value), so `-2**2` is `4`, as in
//! LinuxCNC. Operator and function names are matched as prefixes (as LinuxCNC does), so
//! `[1mod2]` and `[1 MOD 2]` are the same.
//!
//! Arena: nodes are pushed children first; a node's span is the text it came from, and the root of a
//! bracketed expression is widened to include its brackets. A plain literal that is a word's whole
//! value never gets a node (`X1.5` is `Value::Number`): [`Operand`] defers that decision.
//!
//! Height: a left-associative chain (`[1+1+1…]`, `[1 AND 1 AND …]`) is read by the loop in
//! [`Rs::binary`], not by recursion, but it builds a tree as deep as the chain is long, and the
//! interpreter evaluates the tree recursively. Every node records its height
//! (`Block::expr_heights`, a leaf is 1); a chain node higher than [`MAX_EXPR_HEIGHT`] stops the
//! line with `syntax::expression-too-long`. Together with the depth bound below, no expression of
//! any length makes a consumer recurse more than a few hundred levels.
//!
//! Depth: every nested real value (bracket, sign, function, parameter) counts one level; beyond
//! [`MAX_DEPTH`] the line is rejected with `syntax::expression-too-deep`, so `[[[[…` of any length
//! cannot overflow the stack (each level costs a bounded number of frames: at most five
//! precedence levels per bracket).

use crate::ast::{BinOp, ColSpan, ExprId, ExprNode, ParamRef, UnaryFn};
use crate::lexer::{excerpt, find_byte, is_blank, letters_end};
use crate::number::parse_number;
use crate::rs274::{Operand, Rs, R};

/// Maximum nesting of real values (brackets, signs, functions, parameters).
pub(crate) const MAX_DEPTH: u32 = 64;

/// Highest expression tree a line may hold (RS274/NGC and AxiOMA HLL): a chain of at most this
/// many operands. Evaluators recurse on the tree, so this bounds their stack (see
/// `docs/robustness.md`: the limit is fixed, not an option, because it protects the stack).
pub const MAX_EXPR_HEIGHT: u16 = 256;

/// What a function name introduces.
#[derive(Debug, Clone, Copy)]
enum Func {
    Unary(UnaryFn),
    Atan,
    Exists,
}

/// Function names, in an order where no name is a prefix of a later one that should win.
const FUNCTIONS: &[(&[u8], Func)] = &[
    (b"abs", Func::Unary(UnaryFn::Abs)),
    (b"acos", Func::Unary(UnaryFn::Acos)),
    (b"asin", Func::Unary(UnaryFn::Asin)),
    (b"atan", Func::Atan),
    (b"cos", Func::Unary(UnaryFn::Cos)),
    (b"exists", Func::Exists),
    (b"exp", Func::Unary(UnaryFn::Exp)),
    (b"fix", Func::Unary(UnaryFn::Fix)),
    (b"fup", Func::Unary(UnaryFn::Fup)),
    (b"ln", Func::Unary(UnaryFn::Ln)),
    (b"round", Func::Unary(UnaryFn::Round)),
    (b"sin", Func::Unary(UnaryFn::Sin)),
    (b"sqrt", Func::Unary(UnaryFn::Sqrt)),
    (b"tan", Func::Unary(UnaryFn::Tan)),
];

/// Word operators.
const WORD_OPS: &[(&[u8], BinOp)] = &[
    (b"mod", BinOp::Mod),
    (b"and", BinOp::And),
    (b"xor", BinOp::Xor),
    (b"or", BinOp::Or),
    (b"eq", BinOp::Eq),
    (b"ne", BinOp::Ne),
    (b"gt", BinOp::Gt),
    (b"ge", BinOp::Ge),
    (b"lt", BinOp::Lt),
    (b"le", BinOp::Le),
];

fn precedence(op: BinOp) -> u8 {
    match op {
        BinOp::Pow => 4,
        BinOp::Mul | BinOp::Div | BinOp::Mod => 3,
        BinOp::Add | BinOp::Sub => 2,
        BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Ge | BinOp::Lt | BinOp::Le => 1,
        BinOp::And | BinOp::Or | BinOp::Xor => 0,
    }
}

impl Rs<'_> {
    /// Pushes a node and returns its id.
    fn node(&mut self, node: ExprNode, start: usize, end: usize) -> ExprId {
        let id = ExprId(self.out.exprs.len() as u32);
        let below = match node {
            ExprNode::Number(_) | ExprNode::Exists(_) | ExprNode::Param(ParamRef::Named { .. }) => {
                0
            }
            ExprNode::Param(ParamRef::Numbered(a)) | ExprNode::Unary(_, a) => self.height(a),
            ExprNode::Atan(a, b) | ExprNode::Binary(_, a, b) => self.height(a).max(self.height(b)),
        };
        self.out.exprs.push((node, ColSpan::new(start, end)));
        self.out.expr_heights.push(below.saturating_add(1));
        id
    }

    /// The height of a node (a leaf is 1).
    fn height(&self, id: ExprId) -> u16 {
        self.out.expr_heights[id.0 as usize]
    }

    /// The operand as an arena node (a literal gets its node now).
    pub(crate) fn operand_expr(&mut self, op: Operand) -> ExprId {
        match op {
            Operand::Expr(id) => id,
            Operand::Number(v, span) => {
                self.node(ExprNode::Number(v), span.start as usize, span.end as usize)
            }
        }
    }

    fn operand_start(&self, op: Operand) -> usize {
        match op {
            Operand::Number(_, s) => s.start as usize,
            Operand::Expr(id) => self.out.exprs[id.0 as usize].1.start as usize,
        }
    }

    /// True when a function name starts at the cursor (the cursor does not move).
    pub(crate) fn function_ahead(&mut self) -> bool {
        let save = self.pos;
        let found = FUNCTIONS.iter().any(|(name, _)| {
            let ok = self.eat_word(name);
            self.pos = save;
            ok
        });
        self.pos = save;
        found
    }

    /// One real value at the cursor.
    pub(crate) fn real_value(&mut self, depth: u32) -> R<Operand> {
        let Some(c) = self.peek() else {
            return self.unexpected("a value");
        };
        let start = self.pos;
        if depth > MAX_DEPTH {
            return self.fail(
                "syntax::expression-too-deep",
                format!("expression nested more than {MAX_DEPTH} levels deep"),
                start,
                start + 1,
            );
        }
        match c {
            b'0'..=b'9' | b'.' => self.number(),
            b'+' | b'-' => {
                let next = crate::lexer::skip_blanks(self.b, start + 1);
                if matches!(self.b.get(next), Some(b'0'..=b'9' | b'.')) {
                    return self.number();
                }
                self.pos += 1;
                let inner = self.real_value(depth + 1)?;
                let inner = self.operand_expr(inner);
                let f = if c == b'-' {
                    UnaryFn::Neg
                } else {
                    UnaryFn::Plus
                };
                let end = self.pos;
                Ok(Operand::Expr(self.node(
                    ExprNode::Unary(f, inner),
                    start,
                    end,
                )))
            }
            b'[' => Ok(Operand::Expr(self.bracket(depth + 1)?)),
            b'#' => {
                self.pos += 1;
                let p = self.param_after_hash(depth + 1)?;
                let end = self.pos;
                Ok(Operand::Expr(self.node(ExprNode::Param(p), start, end)))
            }
            b'a'..=b'z' | b'A'..=b'Z' => self.function(depth + 1),
            _ => self.unexpected("a number, `[`, `#` or a function"),
        }
    }

    /// A literal number at the cursor.
    fn number(&mut self) -> R<Operand> {
        let start = self.pos;
        match parse_number(self.b, start, true) {
            Some(n) => {
                self.pos = n.end;
                Ok(Operand::Number(n.value, ColSpan::new(start, n.end)))
            }
            None => {
                let end = (start + 1).min(self.b.len());
                self.fail(
                    "syntax::bad-number",
                    format!("malformed number `{}`", excerpt(self.b, start, end)),
                    start,
                    end,
                )
            }
        }
    }

    /// `[ expression ]` at the cursor; the root node's span includes the brackets.
    pub(crate) fn bracket(&mut self, depth: u32) -> R<ExprId> {
        let start = self.pos;
        if depth > MAX_DEPTH {
            return self.fail(
                "syntax::expression-too-deep",
                format!("expression nested more than {MAX_DEPTH} levels deep"),
                start,
                start + 1,
            );
        }
        self.pos += 1; // '['
        let value = self.binary(0, depth)?;
        match self.peek() {
            Some(b']') => self.pos += 1,
            None => {
                return self.fail(
                    "syntax::unbalanced-brackets",
                    "Unclosed expression",
                    start,
                    start + 1,
                )
            }
            Some(_) => {
                // LinuxCNC reads an operation name here: whatever it is, "Unknown operation".
                let at = self.pos;
                return self.fail(
                    "syntax::unknown-operation",
                    format!(
                        "Unknown operation: expected an operator or `]`, found `{}`",
                        String::from_utf8_lossy(&self.b[at..(at + 1).min(self.b.len())])
                    ),
                    at,
                    at + 1,
                );
            }
        }
        let id = self.operand_expr(value);
        self.out.exprs[id.0 as usize].1 = ColSpan::new(start, self.pos);
        Ok(id)
    }

    /// `lhs (op rhs)*` with operators of precedence `>= min` (precedence climbing).
    fn binary(&mut self, min: u8, depth: u32) -> R<Operand> {
        let mut lhs = self.real_value(depth)?;
        loop {
            let save = self.pos;
            let Some(op) = self.operator() else {
                self.pos = save;
                return Ok(lhs);
            };
            let prec = precedence(op);
            if prec < min {
                self.pos = save;
                return Ok(lhs);
            }
            let start = self.operand_start(lhs);
            let l = self.operand_expr(lhs);
            let rhs = self.binary(prec + 1, depth)?;
            let r = self.operand_expr(rhs);
            let end = self.pos;
            let id = self.node(ExprNode::Binary(op, l, r), start, end);
            if self.height(id) > MAX_EXPR_HEIGHT {
                return self.too_long(start, end);
            }
            lhs = Operand::Expr(id);
        }
    }

    #[cold]
    fn too_long<T>(&mut self, start: usize, end: usize) -> R<T> {
        self.fail(
            "syntax::expression-too-long",
            format!(
                "expression more than {MAX_EXPR_HEIGHT} operations deep (a chain of more than \
                 {MAX_EXPR_HEIGHT} operands): split it over several parameters"
            ),
            start,
            end,
        )
    }

    /// A binary operator at the cursor (consumed), or `None`.
    fn operator(&mut self) -> Option<BinOp> {
        let c = self.peek()?;
        let op = match c {
            b'+' => BinOp::Add,
            b'-' => BinOp::Sub,
            b'/' => BinOp::Div,
            b'*' => {
                self.pos += 1;
                if self.peek() == Some(b'*') {
                    self.pos += 1;
                    return Some(BinOp::Pow);
                }
                return Some(BinOp::Mul);
            }
            b'a'..=b'z' | b'A'..=b'Z' => {
                return WORD_OPS
                    .iter()
                    .find(|(w, _)| self.eat_word(w))
                    .map(|&(_, op)| op);
            }
            _ => return None,
        };
        self.pos += 1;
        Some(op)
    }

    /// A function call at the cursor (a letter).
    fn function(&mut self, depth: u32) -> R<Operand> {
        let start = self.pos;
        let Some(&(name, f)) = FUNCTIONS.iter().find(|(name, _)| self.eat_word(name)) else {
            let end = letters_end(self.b, start).max(start + 1);
            return self.fail(
                "syntax::unknown-word",
                format!("unknown function `{}`", excerpt(self.b, start, end)),
                start,
                end,
            );
        };
        let name_end = self.pos;
        if self.peek() != Some(b'[') {
            let upper = std::str::from_utf8(name).unwrap_or("").to_ascii_uppercase();
            return self.fail(
                "syntax::bad-function",
                format!("`{upper}` must be followed by `[`"),
                start,
                name_end,
            );
        }
        let node = match f {
            Func::Unary(u) => {
                let arg = self.bracket(depth)?;
                ExprNode::Unary(u, arg)
            }
            Func::Atan => {
                let y = self.bracket(depth)?;
                if self.peek() != Some(b'/') {
                    let at = self.pos;
                    return self.fail(
                        "syntax::bad-function",
                        "`ATAN` takes two arguments: `ATAN[y]/[x]`",
                        start,
                        at,
                    );
                }
                self.pos += 1;
                if self.peek() != Some(b'[') {
                    let at = self.pos;
                    return self.fail(
                        "syntax::bad-function",
                        "`ATAN[y]/` must be followed by `[x]`",
                        start,
                        at,
                    );
                }
                let x = self.bracket(depth)?;
                ExprNode::Atan(y, x)
            }
            Func::Exists => {
                let open = self.pos;
                self.pos += 1;
                let param = if self.peek() == Some(b'#') {
                    self.pos += 1;
                    if self.peek() == Some(b'<') {
                        Some(self.param_after_hash(depth)?)
                    } else {
                        None
                    }
                } else {
                    None
                };
                let Some(param) = param.filter(|_| self.peek() == Some(b']')) else {
                    let at = self.pos.max(open + 1);
                    return self.fail(
                        "syntax::bad-function",
                        "`EXISTS` takes a named parameter: `EXISTS[#<name>]`",
                        start,
                        at,
                    );
                };
                self.pos += 1;
                ExprNode::Exists(param)
            }
        };
        let end = self.pos;
        Ok(Operand::Expr(self.node(node, start, end)))
    }

    /// The parameter after `#` (cursor just after the `#`).
    pub(crate) fn param_after_hash(&mut self, depth: u32) -> R<ParamRef> {
        if self.peek() == Some(b'<') {
            let open = self.pos;
            let Some(close) = find_byte(self.b, open + 1, b'>') else {
                return self.fail(
                    "syntax::bad-parameter",
                    "parameter name: `#<` has no `>`",
                    open,
                    self.b.len(),
                );
            };
            let name = &self.b[open + 1..close];
            let Some(first) = name.iter().copied().find(|&c| !is_blank(c)) else {
                return self.fail(
                    "syntax::bad-parameter",
                    "empty parameter name `#<>`",
                    open,
                    close + 1,
                );
            };
            self.pos = close + 1;
            return Ok(ParamRef::Named {
                name: ColSpan::new(open + 1, close),
                global: first == b'_',
            });
        }
        if self.peek().is_none() {
            return self.unexpected("a parameter number or `<name>` after `#`");
        }
        let index = self.real_value(depth)?;
        Ok(ParamRef::Numbered(self.operand_expr(index)))
    }
}
