//! The syntax tree of one block.
//!
//! A [`Block`] is what the parser makes of one line: its N label, its words in written order, its
//! comments, and (RS274/NGC) its parameter assignments and O-word. The tree says what was written,
//! not what it means: `G2`, `X10` and `CR=-30` are just addresses with values; which modal group a G
//! code belongs to is the interpreter's business.
//!
//! Representation choices, made for speed (the parser must run at hundreds of MB/s):
//! * a `Block` is reused from line to line: the parser clears and refills its vectors, so steady-state
//!   parsing allocates nothing;
//! * spans inside a block are [`ColSpan`]s, byte ranges into [`Block::text`]; [`Block::span_of`] turns
//!   one into an absolute [`Span`] for a diagnostic;
//! * expressions live in the block's arena ([`Block::exprs`]) and are referred to by [`ExprId`].

use stanok_canon::Span;

/// Which control's language a program is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dialect {
    /// AxiOMA Control: ISO-7bit with Sinumerik-style keywords (`.nc` and everything else).
    Axioma,
    /// LinuxCNC RS274/NGC (`.ngc`).
    Rs274ngc,
    /// Elektronika NC-31 on the 16K20F3 lathe: one address per frame, `*` groups (spec
    /// lab-collection §2). Read by the lab front end (`stanok_syntax::labs::nc31`).
    Nc31,
    /// 2P32 turning-milling centre: integers in 0.001 mm, X on the radius (spec lab-collection §3).
    P2p32,
    /// Elektronika MC2101 notation of the lab collection: 6-digit increments in 0.01 mm (§3.10).
    Mc2101,
    /// The unnamed GOST 20999-83 control of the lab collection's section 6.3 (spec §4).
    Gost20999,
    /// Mazatrol EIA/ISO, Mazak's Fanuc-compatible language with tool tip point control
    /// G43.4/G43.5 (chosen with `--dialect mazatrol`; lexed by `fanuc.rs`: `O` program numbers,
    /// `;` end of block, `#` variables, `[ ]` expressions, custom macro statements).
    Mazatrol,
    /// Balt-System NC, 5-axis CVU=1/CVU=3 programs (chosen with `--dialect balt`).
    Balt,
}

impl Dialect {
    /// The dialect a file name implies: `.ngc` is RS274/NGC; a name starting with a lab dialect's
    /// id and `-` or `_` (`nc31-…`, `2p32-…`, `mc2101-…`, `gost20999-…`, the lab corpus's
    /// convention) is that dialect; anything else AxiOMA.
    pub fn from_path(path: &std::path::Path) -> Dialect {
        if let Some(name) = path.file_name().and_then(|n| n.to_str()) {
            let lower = name.to_ascii_lowercase();
            for d in Dialect::LABS {
                if let Some(rest) = lower.strip_prefix(d.id()) {
                    if rest.starts_with('-') || rest.starts_with('_') {
                        return d;
                    }
                }
            }
        }
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("ngc") => Dialect::Rs274ngc,
            _ => Dialect::Axioma,
        }
    }

    /// The lab-collection dialects, read by the lab front ends instead of [`crate::BlockParser`].
    pub const LABS: [Dialect; 4] = [
        Dialect::Nc31,
        Dialect::P2p32,
        Dialect::Mc2101,
        Dialect::Gost20999,
    ];

    /// The dialect's id on the command line and in reports.
    pub fn id(self) -> &'static str {
        match self {
            Dialect::Axioma => "axioma",
            Dialect::Rs274ngc => "rs274ngc",
            Dialect::Nc31 => "nc31",
            Dialect::P2p32 => "2p32",
            Dialect::Mc2101 => "mc2101",
            Dialect::Gost20999 => "gost20999",
            Dialect::Mazatrol => "mazatrol",
            Dialect::Balt => "balt",
        }
    }

    /// True for the lab-collection dialects (NC-31, 2P32, MC2101, GOST-20999).
    pub fn is_lab(self) -> bool {
        !matches!(
            self,
            Dialect::Axioma | Dialect::Rs274ngc | Dialect::Mazatrol | Dialect::Balt
        )
    }
}

/// A byte range within [`Block::text`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ColSpan {
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
}

impl ColSpan {
    /// Builds a range.
    pub fn new(start: usize, end: usize) -> Self {
        ColSpan {
            start: start as u32,
            end: end as u32,
        }
    }
}

/// Index of an expression node in [`Block::exprs`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExprId(pub u32);

/// An AxiOMA keyword (always upper case here; the source may use any case).
///
/// Misprinted spellings of the manual are accepted by the parser and mapped to the canonical variant
/// (`ORIXES` → `OriAxes`, `ORIIMKS` → `OriMks`, `TRAF0FF`/`TRAFOOF`/`TRAFFOFF` → `TrafOff`,
/// `CUT3DFE` → `Cut3dff`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(missing_docs)]
pub enum Keyword {
    // Modal keywords without a value.
    Brisk,
    Soft,
    Traori,
    TrafOff,
    OriEuler,
    OriRpy,
    OriAxes,
    OriVect,
    OriWks,
    OriMks,
    Cut2df,
    Cut3dc,
    Cut3dcc,
    Cut3dccd,
    Cut3df,
    Cut3dfs,
    Cut3dff,
    Aspline,
    Bspline,
    Cspline,
    Splbreak,
    // Keyword addresses that take a value (`CR=-30`, `PW=2`, `LMAXS 5000`, `LMAXS2=4500`).
    /// Arc radius with sign (`CR=`).
    Cr,
    /// NURBS weight.
    Pw,
    /// NURBS knot increment.
    Pl,
    /// Spline degree.
    Sd,
    /// Spindle speed upper limit for G96.
    Lmaxs,
    /// Spindle speed lower limit for G96.
    Lmins,
    /// Reference axis for G96.
    Refax,
    /// Lead angle.
    Lead,
    /// Tilt angle.
    Tilt,
    /// Feed table lookup (`FTABLE`).
    Ftable,
    /// Spindle-speed table lookup (`STABLE`).
    Stable,
    /// Insertion depth of 3D tool compensation (`ISD=`, CUT3DC).
    Isd,
    // Balt-System assignment statements (`CVU=1`, `MOVST=2`).
    Cvu,
    Movst,
}

impl Keyword {
    /// True for keywords that are written with a value (`CR=…`); false for modal switches (`BRISK`).
    pub fn takes_value(self) -> bool {
        matches!(
            self,
            Keyword::Cr
                | Keyword::Pw
                | Keyword::Pl
                | Keyword::Sd
                | Keyword::Lmaxs
                | Keyword::Lmins
                | Keyword::Refax
                | Keyword::Lead
                | Keyword::Tilt
                | Keyword::Ftable
                | Keyword::Stable
                | Keyword::Isd
                | Keyword::Cvu
                | Keyword::Movst
        )
    }
}

/// What a word addresses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Address {
    /// A single letter, upper case (`b'X'`).
    Letter(u8),
    /// AxiOMA extended address `<letter><index>=` (`S2=1000`, `T2=3`, `D2=1`, `A3=0.5`, `H1=1`, `Q5=1`).
    Indexed {
        /// Upper-case letter.
        letter: u8,
        /// The index written after the letter.
        index: u8,
    },
    /// An AxiOMA keyword, with the index of `LMAXS2=` style forms.
    Keyword {
        /// Which keyword.
        keyword: Keyword,
        /// Index written after the keyword (`LMAXS2` → 2).
        index: Option<u8>,
    },
}

/// The value of a word.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A bare keyword (`BRISK`) has none.
    None,
    /// A literal number.
    Number(f64),
    /// An RS274/NGC real value that is not a plain number (`[1+2]`, `#5`, `-#<x>`, `sin[30]`).
    Expr(ExprId),
    /// An AxiOMA high-level-language expression (`X=ii*10`, `F=$iPerm[1]`), in [`Block::hll`].
    Hll(crate::hll::HExprId),
}

/// One word: an address and its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// What it addresses.
    pub address: Address,
    /// Its value.
    pub value: Value,
    /// The whole word in the block text (`CR=-34.913`).
    pub span: ColSpan,
}

/// How a comment was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CommentKind {
    /// `( … )`.
    Paren,
    /// RS274/NGC `(MSG, …)`: an operator message.
    Msg,
    /// RS274/NGC `(DEBUG, …)`.
    Debug,
    /// RS274/NGC `(PRINT, …)`.
    Print,
    /// `;` to end of line (AxiOMA also `*` at the start of a line, and `//`).
    Line,
    /// AxiOMA `/* … */` (possibly continuing over several lines; the part on this line).
    Block,
    /// AxiOMA `%` program header: the rest of the line.
    Header,
}

/// A comment. `text` excludes the delimiters and, for MSG/DEBUG/PRINT, the keyword and its comma.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Comment {
    /// How it was written.
    pub kind: CommentKind,
    /// The comment text.
    pub text: ColSpan,
}

/// An RS274/NGC parameter reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamRef {
    /// `#5`, `#[expr]`: the number is an expression.
    Numbered(ExprId),
    /// `#<name>`; `global` when the name starts with `_`. `name` spans the text between `<` and `>`
    /// (LinuxCNC ignores case and spaces in names: the interpreter normalises).
    Named {
        /// Between the angle brackets.
        name: ColSpan,
        /// True for `#<_name>`.
        global: bool,
    },
}

/// A unary function of RS274/NGC expressions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum UnaryFn {
    Abs,
    Acos,
    Asin,
    Cos,
    Exp,
    Fix,
    Fup,
    Ln,
    Round,
    Sin,
    Sqrt,
    Tan,
    /// Unary minus.
    Neg,
    /// Unary plus (kept so that spans stay exact).
    Plus,
}

/// A binary operator of RS274/NGC expressions, listed by precedence group (highest first):
/// `**`; `* / MOD`; `+ -`; `EQ NE GT GE LT LE`; `AND OR XOR`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum BinOp {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

/// One node of an expression tree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExprNode {
    /// A literal.
    Number(f64),
    /// A parameter read.
    Param(ParamRef),
    /// `f[arg]`, or unary minus/plus.
    Unary(UnaryFn, ExprId),
    /// `lhs op rhs`.
    Binary(BinOp, ExprId, ExprId),
    /// `ATAN[y]/[x]`.
    Atan(ExprId, ExprId),
    /// `EXISTS[#<name>]`.
    Exists(ParamRef),
}

/// `#… = expr` (RS274/NGC). Assignments take effect after the whole line has been read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assignment {
    /// The parameter written.
    pub target: ParamRef,
    /// The value.
    pub value: ExprId,
    /// The whole assignment.
    pub span: ColSpan,
}

/// The label of an O-word: `o100` or `o<name>`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OLabel {
    /// `o100`.
    Number(u32),
    /// `o<name>`: the span covers the text between `<` and `>`.
    Name(ColSpan),
}

/// What an O-word line does (RS274/NGC control flow).
#[derive(Debug, Clone, PartialEq)]
#[allow(missing_docs)]
pub enum OKind {
    Sub,
    EndSub(Option<ExprId>),
    /// `oN call [a] [b] …`.
    Call(Vec<ExprId>),
    Return(Option<ExprId>),
    If(ExprId),
    ElseIf(ExprId),
    Else,
    EndIf,
    While(ExprId),
    EndWhile,
    Do,
    Repeat(ExprId),
    EndRepeat,
    Break,
    Continue,
}

/// An O-word line.
#[derive(Debug, Clone, PartialEq)]
pub struct OWord {
    /// Its label.
    pub label: OLabel,
    /// Its statement.
    pub kind: OKind,
    /// The whole O-word statement.
    pub span: ColSpan,
}

/// What a Fanuc-style custom macro control statement does (Mazatrol EIA/ISO, `fanuc.rs`). The
/// assignments of a line (`#1 = …`, also the one after `THEN`) are in [`Block::assignments`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MacroKind {
    /// `GOTO n`: the sequence number is a number, `#i` or `[expression]`.
    Goto(ExprId),
    /// `IF [condition] GOTO n`.
    IfGoto {
        /// The bracketed condition.
        condition: ExprId,
        /// The sequence number jumped to.
        target: ExprId,
    },
    /// `IF [condition] THEN #i = …`: the line's assignments run only when the condition holds.
    IfThen {
        /// The bracketed condition.
        condition: ExprId,
    },
    /// `WHILE [condition] DO m`.
    While {
        /// The bracketed condition.
        condition: ExprId,
        /// The identification number m (as written; the interpreter checks its range).
        label: u32,
    },
    /// `DO m` without `WHILE`: a loop that only a `GOTO` leaves.
    Do {
        /// The identification number m.
        label: u32,
    },
    /// `END m`: the end of the loop `DO m`.
    End {
        /// The identification number m.
        label: u32,
    },
}

/// A Fanuc-style custom macro control statement and where it was written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MacroStatement {
    /// What it does.
    pub kind: MacroKind,
    /// The whole statement (`IF [#1 GT 0] GOTO 10`).
    pub span: ColSpan,
    /// The loop number of `WHILE … DO m`, `DO m`, `END m` (for diagnostics); `None` otherwise.
    pub label_span: Option<ColSpan>,
}

/// One block: the parse of one line of the program.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Block {
    /// The line's text without its line terminator.
    pub text: String,
    /// 1-based line number.
    pub line: u32,
    /// Byte offset of the line's first byte in the file.
    pub offset: u64,
    /// The N label, if written.
    pub number: Option<u32>,
    /// The span of the N word.
    pub number_span: Option<ColSpan>,
    /// The line starts with `/` (optional block skip).
    pub block_delete: bool,
    /// RS274/NGC: the line is a lone `%` (program delimiter).
    pub percent: bool,
    /// Words in written order.
    pub words: Vec<Word>,
    /// Comments in written order.
    pub comments: Vec<Comment>,
    /// AxiOMA `MSG("…")`: the span of the text between the quotes (empty span for `MSG()`).
    pub message: Option<ColSpan>,
    /// RS274/NGC parameter assignments, in written order.
    pub assignments: Vec<Assignment>,
    /// RS274/NGC O-word statement.
    pub oword: Option<OWord>,
    /// Mazatrol EIA/ISO (Fanuc-style custom macro): the line's control statement (`GOTO`, `IF`,
    /// `WHILE … DO`, `DO`, `END`). Its program number `O1234` is an `O` word in [`Block::words`].
    pub statement: Option<MacroStatement>,
    /// Expression arena: nodes and the text each came from.
    pub exprs: Vec<(ExprNode, ColSpan)>,
    /// The height of each node of `exprs` (a leaf is 1): the parser keeps it at most
    /// [`crate::MAX_EXPR_HEIGHT`], so that a recursive evaluator's depth is bounded whatever the
    /// length of a left-associative chain such as `[1+1+1…]`.
    pub expr_heights: Vec<u16>,
    /// AxiOMA high-level language: the statements of an HLL line, the expressions of ISO words
    /// and of `MSG(expr)`. Read it with [`Block::hll`], write it with [`Block::hll_mut`].
    ///
    /// Invariant (hot path): `None` on every line until the parser meets the first HLL content
    /// of the reader's program; afterwards the box stays (cleared per line, allocations kept).
    /// Programs without HLL — every RS274/NGC program and most AxiOMA ones — therefore pay one
    /// pointer test per line instead of clearing and copying the HLL arena, and `Block` stays
    /// one pointer larger than before the language existed.
    pub hll: crate::hll::HllSlot,
}

impl Block {
    /// Clears everything but keeps the allocations, for reuse on the next line.
    pub fn clear(&mut self) {
        self.text.clear();
        self.line = 0;
        self.offset = 0;
        self.number = None;
        self.number_span = None;
        self.block_delete = false;
        self.percent = false;
        self.words.clear();
        self.comments.clear();
        self.message = None;
        self.assignments.clear();
        self.oword = None;
        self.statement = None;
        self.exprs.clear();
        self.expr_heights.clear();
        if let Some(hll) = self.hll.0.as_deref_mut() {
            hll.clear();
        }
    }

    /// The HLL content of the line (empty for a line without HLL).
    #[inline]
    pub fn hll(&self) -> &crate::hll::HllLine {
        self.hll.get()
    }

    /// The HLL content of the line, allocated on first use (see the field's invariant).
    #[inline]
    pub fn hll_mut(&mut self) -> &mut crate::hll::HllLine {
        self.hll.0.get_or_insert_with(Default::default)
    }

    /// True when the line has HLL expressions (word values or `MSG(expr)`) or statements.
    #[inline(always)]
    pub fn has_hll_exprs(&self) -> bool {
        self.hll.0.as_deref().is_some_and(|h| !h.exprs.is_empty())
    }

    /// The text a column span covers.
    pub fn slice(&self, c: ColSpan) -> &str {
        self.text
            .get(c.start as usize..c.end as usize)
            .unwrap_or_default()
    }

    /// The absolute span of a range of this block (line, column in characters, file offsets).
    pub fn span_of(&self, c: ColSpan) -> Span {
        let start = (c.start as usize).min(self.text.len());
        let column = self
            .text
            .get(..start)
            .map(|p| p.chars().count())
            .unwrap_or(start)
            + 1;
        Span::new(
            self.offset + c.start as u64,
            self.offset + c.end as u64,
            self.line,
            column as u32,
        )
    }

    /// The span of the whole block.
    #[inline]
    pub fn span(&self) -> Span {
        // Column 1 by definition: no need to count the characters of an empty prefix (this runs
        // for every block).
        Span::new(
            self.offset,
            self.offset + self.text.len() as u64,
            self.line,
            1,
        )
    }

    /// An expression node.
    pub fn expr(&self, id: ExprId) -> &ExprNode {
        &self.exprs[id.0 as usize].0
    }

    /// The text an expression came from.
    pub fn expr_span(&self, id: ExprId) -> ColSpan {
        self.exprs[id.0 as usize].1
    }

    /// True when the block holds nothing the interpreter acts on except, possibly, comments.
    pub fn is_empty(&self) -> bool {
        self.words.is_empty()
            && self.message.is_none()
            && self.assignments.is_empty()
            && self.oword.is_none()
            && self.statement.is_none()
            && self
                .hll
                .0
                .as_deref()
                .is_none_or(|h| !h.statement && h.message.is_none())
    }
}
