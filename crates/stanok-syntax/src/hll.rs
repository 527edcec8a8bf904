//! The syntax tree of AxiOMA's C-like high-level language (HLL) on one line.
//!
//! AxiOMA part programs mix ISO blocks with statements of a C-like language (spec `axioma-1` §3
//! proposal 1: a line is either an ISO block or HLL statements; `;` and `*` start comments only in
//! ISO blocks). The HLL manual is not available, so the language is what a C programmer expects;
//! the reference is docs/axioma.md, "The high-level language".
//!
//! A line of HLL is a sequence of [`HItem`]s: declarations, expression statements, the *headers*
//! of `if`/`else`/`for`/`while`/`do`, and the braces `{` `}`. Control structure that spans lines
//! (a `for` header here, its `{` on the next line, ISO blocks, its `}` later) is not assembled by
//! the parser — the parser sees one line at a time (streaming); the interpreter pairs headers with
//! braces as it executes, and jumps back with the reader's seek.
//!
//! Expressions of a line live in its arena ([`HllLine::exprs`]) and are referred to by
//! [`HExprId`]; an ISO word can carry one as its value (`X=ii*10`, `F=$iPerm[1]`), and `MSG(str)`
//! its message expression. Everything is cleared and refilled per line, so the vectors keep
//! their capacity; lines without HLL never touch them.

use crate::ast::ColSpan;

/// Index of an expression node in [`HllLine::exprs`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HExprId(pub u32);

/// A declared type. `float` is read as `double`, `char` is not offered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HType {
    /// 32-bit signed integer (C `int`).
    Int,
    /// 64-bit signed integer (C `long` on the 64-bit control).
    Long,
    /// IEEE double (also `float`).
    Double,
    /// `true`/`false`.
    Bool,
    /// A text of at most 256 characters (the MSG limit).
    String,
}

impl HType {
    /// The C name of the type.
    pub fn name(self) -> &'static str {
        match self {
            HType::Int => "int",
            HType::Long => "long",
            HType::Double => "double",
            HType::Bool => "bool",
            HType::String => "string",
        }
    }
}

/// A unary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HUnOp {
    /// `-x`.
    Neg,
    /// `+x`.
    Plus,
    /// `!x`.
    Not,
    /// `~x` (integers).
    BitNot,
}

/// A binary operator (C's, without the comma operator).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum HBinOp {
    Mul,
    Div,
    Rem,
    Add,
    Sub,
    Shl,
    Shr,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    BitAnd,
    BitXor,
    BitOr,
    And,
    Or,
}

impl HBinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            HBinOp::Mul => "*",
            HBinOp::Div => "/",
            HBinOp::Rem => "%",
            HBinOp::Add => "+",
            HBinOp::Sub => "-",
            HBinOp::Shl => "<<",
            HBinOp::Shr => ">>",
            HBinOp::Lt => "<",
            HBinOp::Le => "<=",
            HBinOp::Gt => ">",
            HBinOp::Ge => ">=",
            HBinOp::Eq => "==",
            HBinOp::Ne => "!=",
            HBinOp::BitAnd => "&",
            HBinOp::BitXor => "^",
            HBinOp::BitOr => "|",
            HBinOp::And => "&&",
            HBinOp::Or => "||",
        }
    }
}

/// One expression node.
#[derive(Debug, Clone, PartialEq)]
pub enum HExpr {
    /// Integer literal (decimal or `0x…`).
    Int(i64),
    /// Floating literal.
    Float(f64),
    /// `true` / `false`.
    Bool(bool),
    /// String literal: the span between the quotes, escapes (`\"`, `\\`, `\n`, `\t`) not yet
    /// resolved.
    Str(ColSpan),
    /// A variable by name.
    Var(ColSpan),
    /// A system variable `$name` (the span excludes the `$`): `$iPerm`, `$dPerm`.
    System(ColSpan),
    /// `base[index]`.
    Index(HExprId, HExprId),
    /// A unary operator.
    Unary(HUnOp, HExprId),
    /// A binary operator (`&&`/`||` short-circuit).
    Binary(HBinOp, HExprId, HExprId),
    /// `target = value` (None) or a compound `target op= value`.
    Assign(Option<HBinOp>, HExprId, HExprId),
    /// `++x`, `x++`, `--x`, `x--`.
    IncDec {
        /// `++` (true) or `--`.
        inc: bool,
        /// Written before the operand.
        prefix: bool,
        /// The variable or element.
        target: HExprId,
    },
    /// `c ? a : b`.
    Cond(HExprId, HExprId, HExprId),
    /// `name(args…)`: a built-in function.
    Call(ColSpan, Vec<HExprId>),
}

/// How a declared variable starts.
#[derive(Debug, Clone, PartialEq)]
pub enum HInit {
    /// No initialiser: 0, false, "" (Stanok's choice: C leaves it undefined).
    None,
    /// `= expr`.
    Expr(HExprId),
    /// `= {a, b, …}` (arrays).
    List(Vec<HExprId>),
}

/// One declarator of a declaration (`ii = 0`, `pts[8]`).
#[derive(Debug, Clone, PartialEq)]
pub struct HDecl {
    /// The variable's name.
    pub name: ColSpan,
    /// `[n]`: a fixed-size array of n elements.
    pub len: Option<HExprId>,
    /// Its initialiser.
    pub init: HInit,
    /// The whole declarator.
    pub span: ColSpan,
}

/// One item of an HLL line.
#[derive(Debug, Clone, PartialEq)]
pub enum HItem {
    /// `type a = 1, b[3];`.
    Decl {
        /// The declared type.
        ty: HType,
        /// The declarators.
        vars: Vec<HDecl>,
    },
    /// `expr;` (assignments, `++`, calls such as `sprintf(…)`).
    Expr(HExprId),
    /// `if (cond)`: the next statement or `{ … }` is the body.
    If(HExprId),
    /// `else`.
    Else,
    /// `while (cond)`; `terminated` when a `;` follows directly (the end of `do { … } while (c);`).
    While {
        /// The condition.
        cond: HExprId,
        /// A `;` follows the `)`.
        terminated: bool,
    },
    /// `do`.
    Do,
    /// `for (init; cond; step)`.
    For {
        /// A declaration or expression run once.
        init: Option<Box<HItem>>,
        /// Tested before every pass; none = true.
        cond: Option<HExprId>,
        /// Run after every pass.
        step: Option<HExprId>,
    },
    /// `{`.
    Open,
    /// `}`.
    Close,
    /// `break;`.
    Break,
    /// `continue;`.
    Continue,
    /// `;` alone.
    Empty,
}

/// The HLL content of one line: its items (an HLL line) and the expression arena (also used by
/// ISO words with expression values and `MSG(expr)`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HllLine {
    /// True when the line is an HLL line (items, no ISO words).
    pub statement: bool,
    /// The items in written order, each with its text.
    pub items: Vec<(HItem, ColSpan)>,
    /// Expression arena.
    pub exprs: Vec<(HExpr, ColSpan)>,
    /// `MSG(expr)`: the message is the value of this (string) expression.
    pub message: Option<HExprId>,
}

/// [`crate::Block::hll`]: the HLL content of a line, allocated on the first line that has some
/// (see the field's invariant). Compares as the content it stands for: no box equals an empty one.
#[derive(Debug, Clone, Default)]
pub struct HllSlot(pub Option<Box<HllLine>>);

/// What [`HllSlot::get`] returns for a line of a program without HLL.
static NO_HLL: HllLine = HllLine::EMPTY;

impl HllSlot {
    /// The content (empty when nothing was allocated).
    #[inline]
    pub fn get(&self) -> &HllLine {
        self.0.as_deref().unwrap_or(&NO_HLL)
    }
}

impl PartialEq for HllSlot {
    fn eq(&self, other: &Self) -> bool {
        self.get() == other.get()
    }
}

impl HllLine {
    /// A line without HLL (what [`crate::Block::hll`] returns when the line has none).
    pub const EMPTY: HllLine = HllLine {
        statement: false,
        items: Vec::new(),
        exprs: Vec::new(),
        message: None,
    };

    /// Clears everything but keeps the allocations. Called for every line of every program:
    /// lines without HLL (all but a few) leave everything empty, so one test skips the rest.
    #[inline(always)]
    pub fn clear(&mut self) {
        if self.exprs.is_empty() && self.items.is_empty() {
            self.statement = false;
            self.message = None;
            return;
        }
        self.clear_used();
    }

    #[cold]
    #[inline(never)]
    fn clear_used(&mut self) {
        self.statement = false;
        self.items.clear();
        self.exprs.clear();
        self.message = None;
    }

    /// An expression node.
    pub fn expr(&self, id: HExprId) -> &HExpr {
        &self.exprs[id.0 as usize].0
    }

    /// The text an expression came from.
    pub fn expr_span(&self, id: HExprId) -> ColSpan {
        self.exprs[id.0 as usize].1
    }

    pub(crate) fn push(&mut self, e: HExpr, span: ColSpan) -> HExprId {
        self.exprs.push((e, span));
        HExprId(self.exprs.len() as u32 - 1)
    }
}
