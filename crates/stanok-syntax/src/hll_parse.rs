//! Parser of AxiOMA's high-level language (the tree is in `hll.rs`).
//!
//! Algorithm: a hand-written lexer yields one token at a time from a byte position (no token
//! vector), and a precedence-climbing parser builds expressions into the line's arena. C's
//! precedence, highest first: postfix (`x++` `x--` `a[i]` `f(…)`), prefix (`-` `+` `!` `~` `++`
//! `--`), `* / %`, `+ -`, `<< >>`, `< <= > >=`, `== !=`, `&`, `^`, `|`, `&&`, `||`, `?:`,
//! assignment (`= += -= *= /= %=`, right to left).
//!
//! Two modes:
//! * **statement** (an HLL line): items up to the end of the line; `//` and `/* … */` are comments,
//!   recorded in the block; every statement ends with `;` as in C;
//! * **word value** (`X=<expr>` in an ISO block, `MSG(<expr>)`): one expression; it ends at the
//!   first token that cannot continue it, so `X = a * 2 Y10` reads `a * 2`. A `;` or comment ends
//!   it (they are ISO comments there), and a call needs its `(` right after the name, so that
//!   `X=ii (comment)` stays a variable followed by an ISO comment.
//!
//! Invariants: the parser never panics and never recurses deeper than [`MAX_DEPTH`] (an error
//! says so); on an error it records one diagnostic and gives up on the rest of the line (the
//! interpreter stops there anyway), still keeping the `/* … */` state right.

use crate::ast::{Block, ColSpan, Comment, CommentKind};
use crate::hll::{HBinOp, HExpr, HExprId, HUnOp};
use crate::lexer::{char_end, find, is_blank, Pendings};

mod statements;

/// Deepest nesting of an expression (brackets, operators of one precedence chain).
pub const MAX_DEPTH: usize = 64;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Tok {
    Ident,
    Sys,
    Int(i64),
    Float(f64),
    Str,
    Punct(&'static str),
    End,
    Bad(&'static str),
}

/// Two- and three-character operators first, so that the longest match wins.
const PUNCTS: &[&str] = &[
    "<<=", ">>=", "++", "--", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<", ">>", "<=",
    ">=", "==", "!=", "&&", "||", "+", "-", "*", "/", "%", "<", ">", "=", "!", "~", "&", "|", "^",
    "?", ":", "(", ")", "[", "]", "{", "}", ",", ";",
];

struct Parser<'a> {
    b: &'a [u8],
    out: &'a mut Block,
    diags: &'a mut Pendings,
    in_comment: &'a mut bool,
    /// Word-value mode (see the module comment).
    word: bool,
    /// Start of the next token (after blanks and comments).
    pos: usize,
    /// The current token, its span, and whether blanks preceded it.
    tok: Tok,
    span: ColSpan,
    blank_before: bool,
    /// End of the last consumed token.
    last_end: usize,
    depth: usize,
}

type R<T> = Result<T, ()>;

impl<'a> Parser<'a> {
    fn new(
        b: &'a [u8],
        start: usize,
        out: &'a mut Block,
        diags: &'a mut Pendings,
        in_comment: &'a mut bool,
        word: bool,
    ) -> Self {
        let mut p = Parser {
            b,
            out,
            diags,
            in_comment,
            word,
            pos: start,
            tok: Tok::End,
            span: ColSpan::new(start, start),
            blank_before: false,
            last_end: start,
            depth: 0,
        };
        p.advance();
        p
    }

    fn text(&self, c: ColSpan) -> &'a [u8] {
        &self.b[c.start as usize..c.end as usize]
    }

    fn is_kw(&self, kw: &str) -> bool {
        self.tok == Tok::Ident && self.text(self.span) == kw.as_bytes()
    }

    fn is(&self, p: &str) -> bool {
        matches!(self.tok, Tok::Punct(q) if q == p)
    }

    /// Reads the next token into `tok`/`span`.
    fn advance(&mut self) {
        self.last_end = self.span.end as usize;
        let b = self.b;
        let start_pos = self.pos;
        let mut p = self.pos;
        loop {
            while p < b.len() && is_blank(b[p]) {
                p += 1;
            }
            if p + 1 < b.len() && b[p] == b'/' && (b[p + 1] == b'/' || b[p + 1] == b'*') {
                if self.word {
                    // The ISO parser reads the comment itself.
                    self.set(Tok::End, p, p, start_pos);
                    self.pos = p;
                    return;
                }
                if b[p + 1] == b'/' {
                    self.out.comments.push(Comment {
                        kind: CommentKind::Line,
                        text: ColSpan::new(p + 2, b.len()),
                    });
                    p = b.len();
                    continue;
                }
                match find(b, p + 2, b"*/") {
                    Some(q) => {
                        self.out.comments.push(Comment {
                            kind: CommentKind::Block,
                            text: ColSpan::new(p + 2, q),
                        });
                        p = q + 2;
                        continue;
                    }
                    None => {
                        self.out.comments.push(Comment {
                            kind: CommentKind::Block,
                            text: ColSpan::new(p + 2, b.len()),
                        });
                        *self.in_comment = true;
                        p = b.len();
                        continue;
                    }
                }
            }
            break;
        }
        if p >= b.len() || (self.word && b[p] == b';') {
            self.set(Tok::End, p, p, start_pos);
            self.pos = p;
            return;
        }
        let c = b[p];
        let (tok, end) = if c.is_ascii_alphabetic() || c == b'_' || c == b'$' {
            let mut q = p + 1;
            while q < b.len() && (b[q].is_ascii_alphanumeric() || b[q] == b'_') {
                q += 1;
            }
            if c == b'$' {
                if q == p + 1 {
                    (
                        Tok::Bad("`$` must be followed by a system variable name"),
                        q,
                    )
                } else {
                    (Tok::Sys, q)
                }
            } else {
                (Tok::Ident, q)
            }
        } else if c.is_ascii_digit() || (c == b'.' && b.get(p + 1).is_some_and(u8::is_ascii_digit))
        {
            number(b, p)
        } else if c == b'"' {
            let mut q = p + 1;
            let mut closed = false;
            while q < b.len() {
                match b[q] {
                    b'\\' => q += 2,
                    b'"' => {
                        closed = true;
                        break;
                    }
                    _ => q += 1,
                }
            }
            if closed {
                (Tok::Str, q + 1)
            } else {
                (
                    Tok::Bad("unterminated string: `\"` has no closing `\"` on this line"),
                    b.len(),
                )
            }
        } else {
            match PUNCTS.iter().find(|s| b[p..].starts_with(s.as_bytes())) {
                Some(s) => (Tok::Punct(s), p + s.len()),
                None => (Tok::Bad("unexpected character"), char_end(b, p)),
            }
        };
        self.set(tok, p, end.min(b.len()), start_pos);
        self.pos = end.min(b.len());
    }

    fn set(&mut self, tok: Tok, start: usize, end: usize, before: usize) {
        self.tok = tok;
        self.span = ColSpan::new(start, end);
        self.blank_before = start > before && is_blank(self.b[start - 1]);
    }

    fn error(&mut self, code: &'static str, message: String, span: ColSpan) {
        self.diags
            .error(code, message, span.start as usize, span.end as usize);
    }

    /// Error at the current token: "expected X".
    fn expected(&mut self, what: &str) -> R<()> {
        let span = self.span;
        match self.tok {
            Tok::Bad(m) => {
                let code = if m.starts_with("unterminated") {
                    "syntax::unclosed-string"
                } else {
                    "hll::syntax"
                };
                self.error(code, m.to_string(), span)
            }
            Tok::End => self.error(
                "hll::syntax",
                format!("expected {what} before the end of the line"),
                span,
            ),
            _ => {
                let got = String::from_utf8_lossy(self.text(span)).into_owned();
                self.error(
                    "hll::syntax",
                    format!("expected {what}, found `{got}`"),
                    span,
                )
            }
        }
        Err(())
    }

    fn eat(&mut self, p: &str) -> R<()> {
        if self.is(p) {
            self.advance();
            Ok(())
        } else {
            self.expected(&format!("`{p}`"))
        }
    }

    fn node(&mut self, e: HExpr, start: usize) -> HExprId {
        let end = self.last_end.max(start);
        self.out.hll_mut().push(e, ColSpan::new(start, end))
    }

    // ------------------------------------------------------------------ expressions

    fn expr(&mut self) -> R<HExprId> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            let span = self.span;
            self.error(
                "hll::too-deep",
                format!("expression nested deeper than {MAX_DEPTH} levels"),
                span,
            );
            return Err(());
        }
        let r = self.assignment();
        self.depth -= 1;
        r
    }

    fn assignment(&mut self) -> R<HExprId> {
        let start = self.span.start as usize;
        let lhs = self.conditional()?;
        let op = match self.tok {
            Tok::Punct("=") => None,
            Tok::Punct("+=") => Some(HBinOp::Add),
            Tok::Punct("-=") => Some(HBinOp::Sub),
            Tok::Punct("*=") => Some(HBinOp::Mul),
            Tok::Punct("/=") => Some(HBinOp::Div),
            Tok::Punct("%=") => Some(HBinOp::Rem),
            Tok::Punct("&=") => Some(HBinOp::BitAnd),
            Tok::Punct("|=") => Some(HBinOp::BitOr),
            Tok::Punct("^=") => Some(HBinOp::BitXor),
            Tok::Punct("<<=") => Some(HBinOp::Shl),
            Tok::Punct(">>=") => Some(HBinOp::Shr),
            _ => return Ok(lhs),
        };
        if !self.lvalue(lhs) {
            let span = self.out.hll().expr_span(lhs);
            self.error(
                "hll::not-assignable",
                "only a variable or an array element can be assigned to".into(),
                span,
            );
            return Err(());
        }
        self.advance();
        let rhs = self.expr()?;
        Ok(self.node(HExpr::Assign(op, lhs, rhs), start))
    }

    fn lvalue(&self, id: HExprId) -> bool {
        matches!(
            self.out.hll().expr(id),
            HExpr::Var(_) | HExpr::Index(..) | HExpr::System(_)
        )
    }

    fn conditional(&mut self) -> R<HExprId> {
        let start = self.span.start as usize;
        let c = self.binary(0)?;
        if !self.is("?") {
            return Ok(c);
        }
        self.advance();
        let a = self.expr()?;
        self.eat(":")?;
        let b = self.expr()?;
        Ok(self.node(HExpr::Cond(c, a, b), start))
    }

    /// Precedence climbing over the binary operators, level 0 = `||` (lowest).
    fn binary(&mut self, level: usize) -> R<HExprId> {
        const LEVELS: &[&[(&str, HBinOp)]] = &[
            &[("||", HBinOp::Or)],
            &[("&&", HBinOp::And)],
            &[("|", HBinOp::BitOr)],
            &[("^", HBinOp::BitXor)],
            &[("&", HBinOp::BitAnd)],
            &[("==", HBinOp::Eq), ("!=", HBinOp::Ne)],
            &[
                ("<", HBinOp::Lt),
                ("<=", HBinOp::Le),
                (">", HBinOp::Gt),
                (">=", HBinOp::Ge),
            ],
            &[("<<", HBinOp::Shl), (">>", HBinOp::Shr)],
            &[("+", HBinOp::Add), ("-", HBinOp::Sub)],
            &[("*", HBinOp::Mul), ("/", HBinOp::Div), ("%", HBinOp::Rem)],
        ];
        if level == LEVELS.len() {
            return self.unary();
        }
        let start = self.span.start as usize;
        let mut lhs = self.binary(level + 1)?;
        loop {
            let Tok::Punct(p) = self.tok else {
                return Ok(lhs);
            };
            let Some(&(_, op)) = LEVELS[level].iter().find(|(s, _)| *s == p) else {
                return Ok(lhs);
            };
            self.advance();
            let rhs = self.binary(level + 1)?;
            lhs = self.chain_node(HExpr::Binary(op, lhs, rhs), start)?;
        }
    }

    /// A node built by a loop (a binary chain, `a[i][j]…`): the loop reads a chain of any
    /// length, and the tree it builds is as deep, so a chain too deep for the evaluator (see
    /// `MAX_EXPR_HEIGHT`) stops here.
    fn chain_node(&mut self, e: HExpr, start: usize) -> R<HExprId> {
        let id = self.node(e, start);
        if self.out.hll().height(id) <= crate::MAX_EXPR_HEIGHT {
            return Ok(id);
        }
        let span = self.out.hll().expr_span(id);
        let max = crate::MAX_EXPR_HEIGHT;
        self.error(
            "hll::too-long",
            format!(
                "expression more than {max} operations deep (a chain of more than {max} \
                 operands): split it over several variables"
            ),
            span,
        );
        Err(())
    }

    fn unary(&mut self) -> R<HExprId> {
        let start = self.span.start as usize;
        let op = match self.tok {
            Tok::Punct("-") => Some(HUnOp::Neg),
            Tok::Punct("+") => Some(HUnOp::Plus),
            Tok::Punct("!") => Some(HUnOp::Not),
            Tok::Punct("~") => Some(HUnOp::BitNot),
            Tok::Punct(p @ ("++" | "--")) => {
                self.advance();
                let target = self.nested(Self::unary)?;
                return self.incdec(p == "++", true, target, start);
            }
            _ => None,
        };
        match op {
            Some(op) => {
                self.advance();
                let e = self.nested(Self::unary)?;
                Ok(self.node(HExpr::Unary(op, e), start))
            }
            None => self.postfix(),
        }
    }

    /// Runs a recursive step with the depth bound.
    fn nested(&mut self, f: fn(&mut Self) -> R<HExprId>) -> R<HExprId> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            let span = self.span;
            self.error(
                "hll::too-deep",
                format!("expression nested deeper than {MAX_DEPTH} levels"),
                span,
            );
            return Err(());
        }
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn incdec(&mut self, inc: bool, prefix: bool, target: HExprId, start: usize) -> R<HExprId> {
        if !self.lvalue(target) {
            let span = self.out.hll().expr_span(target);
            self.error(
                "hll::not-assignable",
                format!(
                    "`{}` needs a variable or an array element",
                    if inc { "++" } else { "--" }
                ),
                span,
            );
            return Err(());
        }
        Ok(self.node(
            HExpr::IncDec {
                inc,
                prefix,
                target,
            },
            start,
        ))
    }

    fn postfix(&mut self) -> R<HExprId> {
        let start = self.span.start as usize;
        let mut e = self.primary()?;
        loop {
            match self.tok {
                Tok::Punct("[") => {
                    self.advance();
                    let i = self.expr()?;
                    self.eat("]")?;
                    e = self.chain_node(HExpr::Index(e, i), start)?;
                }
                Tok::Punct(p @ ("++" | "--")) => {
                    self.advance();
                    e = self.incdec(p == "++", false, e, start)?;
                }
                _ => return Ok(e),
            }
        }
    }

    fn primary(&mut self) -> R<HExprId> {
        let start = self.span.start as usize;
        let span = self.span;
        match self.tok {
            Tok::Int(v) => {
                self.advance();
                Ok(self.node(HExpr::Int(v), start))
            }
            Tok::Float(v) => {
                self.advance();
                Ok(self.node(HExpr::Float(v), start))
            }
            Tok::Str => {
                self.advance();
                let inner = ColSpan::new(span.start as usize + 1, span.end as usize - 1);
                Ok(self.node(HExpr::Str(inner), start))
            }
            Tok::Sys => {
                self.advance();
                let name = ColSpan::new(span.start as usize + 1, span.end as usize);
                Ok(self.node(HExpr::System(name), start))
            }
            Tok::Ident => {
                let text = self.text(span);
                if text == b"true" || text == b"false" {
                    self.advance();
                    return Ok(self.node(HExpr::Bool(text == b"true"), start));
                }
                self.advance();
                if self.is("(") && !(self.word && self.blank_before) {
                    self.advance();
                    let mut args = Vec::new();
                    if !self.is(")") {
                        loop {
                            args.push(self.expr()?);
                            if self.is(",") {
                                self.advance();
                                continue;
                            }
                            break;
                        }
                    }
                    self.eat(")")?;
                    return Ok(self.node(HExpr::Call(span, args), start));
                }
                Ok(self.node(HExpr::Var(span), start))
            }
            Tok::Punct("(") => {
                self.advance();
                let e = self.expr()?;
                self.eat(")")?;
                // The parenthesised expression keeps its own node; its span now covers the brackets.
                self.out.hll_mut().exprs[e.0 as usize].1 = ColSpan::new(start, self.last_end);
                Ok(e)
            }
            _ => {
                self.expected("a value")?;
                Err(())
            }
        }
    }
}

/// A numeric literal at `p`: decimal or `0x` integer, or a floating number (`1.5`, `.5`, `2e-3`,
/// `1.`). Integers that overflow i64 are read as floating.
fn number(b: &[u8], p: usize) -> (Tok, usize) {
    if b[p] == b'0' && matches!(b.get(p + 1), Some(b'x' | b'X')) {
        let mut q = p + 2;
        while q < b.len() && b[q].is_ascii_hexdigit() {
            q += 1;
        }
        let s = std::str::from_utf8(&b[p + 2..q]).unwrap_or("");
        return match i64::from_str_radix(s, 16) {
            Ok(v) => (Tok::Int(v), q),
            Err(_) => (Tok::Bad("malformed hexadecimal number"), q),
        };
    }
    let mut q = p;
    while q < b.len() && b[q].is_ascii_digit() {
        q += 1;
    }
    let mut float = false;
    if q < b.len() && b[q] == b'.' {
        float = true;
        q += 1;
        while q < b.len() && b[q].is_ascii_digit() {
            q += 1;
        }
    }
    if q < b.len() && matches!(b[q], b'e' | b'E') {
        let mut r = q + 1;
        if r < b.len() && matches!(b[r], b'+' | b'-') {
            r += 1;
        }
        if r < b.len() && b[r].is_ascii_digit() {
            float = true;
            while r < b.len() && b[r].is_ascii_digit() {
                r += 1;
            }
            q = r;
        }
    }
    if q < b.len() && (b[q].is_ascii_alphabetic() || b[q] == b'_') {
        let mut r = q;
        while r < b.len() && (b[r].is_ascii_alphanumeric() || b[r] == b'_') {
            r += 1;
        }
        return (Tok::Bad("malformed number"), r);
    }
    let s = std::str::from_utf8(&b[p..q]).unwrap_or("0");
    if !float {
        if let Ok(v) = s.parse::<i64>() {
            return (Tok::Int(v), q);
        }
    }
    match s.parse::<f64>() {
        Ok(v) => (Tok::Float(v), q),
        Err(_) => (Tok::Bad("malformed number"), q),
    }
}

/// Parses the HLL statements of a line from `start` into `out.hll` (marking the line as HLL).
/// Returns the end of the line.
pub(crate) fn statements(
    b: &[u8],
    start: usize,
    out: &mut Block,
    diags: &mut Pendings,
    in_comment: &mut bool,
) -> usize {
    out.hll_mut().statement = true;
    let mut p = Parser::new(b, start, out, diags, in_comment, false);
    if p.items().is_err() {
        let from = p.span.end.max(p.span.start) as usize;
        p.out.hll_mut().items.clear();
        p.skip_rest(from);
    }
    b.len()
}

/// Parses one expression at `start` in word-value mode. Returns it and the position after it, or
/// None after recording a diagnostic.
pub(crate) fn word_value(
    b: &[u8],
    start: usize,
    out: &mut Block,
    diags: &mut Pendings,
) -> Option<(HExprId, usize)> {
    let mut in_comment = false;
    let mut p = Parser::new(b, start, out, diags, &mut in_comment, true);
    let e = p.expr().ok()?;
    Some((e, p.last_end))
}

/// Parses `expr )` at `start` (the argument of `MSG(`). Returns it and the position after `)`.
pub(crate) fn message_arg(
    b: &[u8],
    start: usize,
    out: &mut Block,
    diags: &mut Pendings,
) -> Option<(HExprId, usize)> {
    let mut in_comment = false;
    let mut p = Parser::new(b, start, out, diags, &mut in_comment, true);
    let e = p.expr().ok()?;
    p.eat(")").ok()?;
    Some((e, p.last_end))
}
