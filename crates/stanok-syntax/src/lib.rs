//! # stanok-syntax: program text to blocks
//!
//! Lexing and parsing only; no meaning. One line of program text becomes one [`Block`]: its N label,
//! its words in written order, its comments, and for RS274/NGC its parameter assignments, O-word
//! and expression trees. Which modal group `G2` belongs to, whether `X` is an axis, what `CR=` means:
//! all of that is the interpreter's business.
//!
//! ## Entry points
//!
//! * [`BlockParser::parse_line`]: one line into a reused [`Block`]. The fast path: no allocation
//!   in steady state (the block's vectors keep their capacity; letters are compared byte by byte;
//!   numbers are parsed by hand, see `number.rs`).
//! * [`BlockReader`]: streams blocks out of any `BufRead + Seek`, with [`SourcePos`] to jump back.
//! * [`parse`]: a whole text into a [`Program`] (tests, small programs).
//!
//! ## Architecture invariants
//!
//! * **Parsing never fails and never panics.** Every problem is a [`Diagnostic`] with a span on the
//!   offending text; the parser skips the offending word (AxiOMA) or the rest of the line
//!   (RS274/NGC, whose reference interpreter rejects a line at its first error) and keeps what it
//!   read before. Nesting of expressions is bounded, so no input can overflow the stack.
//! * **One line at a time.** The only state carried between lines is the AxiOMA "inside
//!   `/* … */`" flag, which [`SourcePos`] captures.
//! * **Spans are exact.** Every [`ColSpan`] is a byte range of [`Block::text`] on character
//!   boundaries; [`Block::span_of`] gives file offset, line and column.
//!
//! ## Performance
//!
//! The hot path is `<letter><number>` followed by blanks: it is tested first in each dialect's loop,
//! the number is read inline (`number.rs`), and cold paths (keywords, comments, errors, O-words)
//! are kept out of line. `tests/alloc.rs` checks that steady-state parsing makes no allocation;
//! `tests/throughput.rs` measures MB/s (`cargo test --release -p stanok-syntax --test throughput
//! -- --ignored --nocapture`).
//!
//! ## Files
//!
//! `lexer.rs` (byte helpers, pending diagnostics), `number.rs` (numbers), `axioma.rs` (AxiOMA lines),
//! `rs274.rs` (RS274/NGC lines and O-words), `expr.rs` (RS274/NGC real values and expressions),
//! `fanuc.rs` / `fanuc_expr.rs` (Mazatrol EIA/ISO: Fanuc-style lines, program numbers, custom macro
//! statements, and its expressions with Fanuc precedence, read without recursion),
//! `hll.rs` / `hll_parse.rs` (the AxiOMA high-level language: tree and parser), `balt.rs`
//! (Balt-System CVU lines: letters without digits, words run together, `CVU=`/`MOVST=`, mnemonic
//! blocks as comments), `labs/` (the lab-collection readers: NC-31 frames, the 2P32/MC2101/GOST-20999
//! word lines, fixture-comment stripping; they share nothing with [`BlockParser`] but its rule that
//! reading never fails), `ast.rs` (blocks, words, [`Dialect`]),
//! `reader.rs` (streaming and seeking).
//!
//! ## Diagnostic codes
//!
//! | code | severity | when |
//! |---|---|---|
//! | `syntax::unclosed-comment` | error | `(` without `)` on the line |
//! | `syntax::nested-comment` | error | RS274/NGC `(` inside a `( … )` comment |
//! | `syntax::unclosed-string` | error | AxiOMA `MSG("…` without the closing quote |
//! | `syntax::bad-number` | error | malformed number (`X-`, `X.`), block number or index too large |
//! | `syntax::missing-value` | error | an address or keyword without its value (`X`, `CR=`) |
//! | `syntax::unknown-word` | error | an unknown multi-letter word, or unknown RS274/NGC function |
//! | `syntax::misplaced-word` | error | AxiOMA `FTABLE`/`STABLE` outside `F=`/`S=` |
//! | `syntax::bad-message` | error | AxiOMA `MSG` not followed by `(` |
//! | `hll::syntax` | error | AxiOMA high-level language: a token where C expects another |
//! | `hll::unsupported` | error | AxiOMA HLL keywords Stanok does not offer (`switch`, `goto`, …) |
//! | `hll::not-assignable` | error | assignment or `++`/`--` to something not a variable |
//! | `hll::too-deep` | error | an HLL expression nested deeper than 64 levels |
//! | `hll::too-long` | error | an HLL expression more than [`MAX_EXPR_HEIGHT`] operations deep (a long chain) |
//! | `syntax::unexpected-character` | error | a character that cannot start an item there |
//! | `syntax::unbalanced-brackets` | error | `[` without `]`, stray `]`, `MSG(` without `)` |
//! | `syntax::expression-too-deep` | error | RS274/NGC expression nested deeper than 64 levels; Mazatrol brackets deeper than 5 |
//! | `syntax::expression-too-long` | error | RS274/NGC expression more than [`MAX_EXPR_HEIGHT`] operations deep (a long chain) |
//! | `syntax::bad-function` | error | RS274/NGC function without `[`, `ATAN` without `/[x]`, bad `EXISTS` |
//! | `syntax::bad-parameter` | error | RS274/NGC `#<` without `>`, empty name |
//! | `syntax::bad-assignment` | error | RS274/NGC `#…` item without `=` |
//! | `syntax::bad-oword` | error | malformed O-word line, or an O-word that is not first |
//! | `syntax::mixed-block` | error | Mazatrol: NC words and a macro statement or assignment in one block |
//! | `syntax::chained-comparison` | error | Mazatrol: `[a LT b LT c]` (bracket each comparison) |
//! | `syntax::block-skip-ignored` | warning | AxiOMA `/` block skip (not supported, block runs) |
//! | `syntax::invalid-utf8` | error | [`BlockReader`]: bytes that are not UTF-8 (replaced) |
//! | `syntax::too-many-words` | error | a block with more than [`MAX_WORDS_PER_BLOCK`] words (the lab controls' parser; the interpreter core for the others) |
//! | `syntax::line-too-long` | error | [`BlockReader`]: line longer than [`MAX_LINE_BYTES`] (or the bound set) |
//! | `syntax::program-too-large` | error | [`BlockReader`]: program longer than [`MAX_PROGRAM_BYTES`] (or the bound set) |
#![deny(missing_docs)]

mod ast;
mod axioma;
mod balt;
mod expr;
mod fanuc;
mod fanuc_expr;
pub mod hll;
mod hll_parse;
pub mod labs;
mod lexer;
mod number;
mod reader;
mod rs274;
mod seekbuf;

pub use ast::*;
pub use expr::MAX_EXPR_HEIGHT;

/// Most words one block may hold. No control's block comes near it (LinuxCNC reads 256
/// characters a line); a line of a megabyte of words is refused at its 1,001st word, so that work
/// per word that looks back along the line (a diagnostic's column) stays bounded.
pub const MAX_WORDS_PER_BLOCK: usize = 1000;
pub use reader::{BlockReader, SourcePos, MAX_LINE_BYTES, MAX_PROGRAM_BYTES};
pub use seekbuf::SeekBufReader;

use lexer::Pendings;
use stanok_canon::{Diagnostic, Severity};

/// The per-dialect line parser, with the state carried from line to line.
#[derive(Debug)]
pub struct BlockParser {
    dialect: Dialect,
    /// AxiOMA: the previous line ended inside `/* … */`.
    in_block_comment: bool,
    /// Diagnostics of the current line, reused.
    pending: Pendings,
}

impl BlockParser {
    /// A parser at the start of a program.
    pub fn new(dialect: Dialect) -> Self {
        BlockParser {
            dialect,
            in_block_comment: false,
            pending: Pendings::default(),
        }
    }

    /// The dialect it parses.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Parses one line (text WITHOUT its line terminator; a trailing `'\r'` is tolerated and
    /// dropped) into `block`, which it clears first, then sets text/line/offset. Problems go to
    /// `diags`; parsing never fails or panics: on an error it records a diagnostic, skips the
    /// offending word (or the rest of the line) and keeps what it could parse.
    pub fn parse_line(
        &mut self,
        text: &str,
        line: u32,
        offset: u64,
        block: &mut Block,
        diags: &mut Vec<Diagnostic>,
    ) {
        let text = text.strip_suffix('\n').unwrap_or(text);
        let text = text.strip_suffix('\r').unwrap_or(text);
        block.clear();
        block.text.push_str(text);
        block.line = line;
        block.offset = offset;
        // Parse from the caller's text: no need to move the block's copy out and back.
        self.parse_bytes(text.as_bytes(), block);
        self.flush_pending(block, diags);
    }

    /// [`BlockParser::parse_line`] for a line already in `block.text` (without its LF): used by
    /// [`BlockReader`], which hands over its line buffer instead of copying it.
    pub(crate) fn parse_text_in_place(
        &mut self,
        line: u32,
        offset: u64,
        block: &mut Block,
        diags: &mut Vec<Diagnostic>,
    ) {
        // Move the text out so that it can be read while the block's vectors are filled.
        let mut owned = std::mem::take(&mut block.text);
        if owned.ends_with('\r') {
            owned.pop();
        }
        block.clear();
        block.line = line;
        block.offset = offset;
        self.parse_bytes(owned.as_bytes(), block);
        block.text = owned;
        self.flush_pending(block, diags);
    }

    /// Parses `text` (the line, without terminator) into `block` (cleared, line and offset set).
    /// Diagnostics wait in `pending` until `block.text` holds the line: then `flush_pending`.
    #[inline]
    fn parse_bytes(&mut self, text: &[u8], block: &mut Block) {
        self.pending.0.clear();
        match self.dialect {
            Dialect::Axioma => {
                axioma::parse_line(text, block, &mut self.pending, &mut self.in_block_comment)
            }
            Dialect::Balt => balt::parse_line(text, block, &mut self.pending),
            Dialect::Mazatrol => fanuc::parse_line(text, block, &mut self.pending),
            // The lab dialects are read by their own front ends (`labs`); a block parser made
            // for one reads ISO words as RS274/NGC does. One call site: `rs274::parse_line` is
            // inlined here.
            Dialect::Rs274ngc
            | Dialect::Nc31
            | Dialect::P2p32
            | Dialect::Mc2101
            | Dialect::Gost20999 => rs274::parse_line(text, block, &mut self.pending),
        }
    }

    /// Turns the line's pending diagnostics into [`Diagnostic`]s (spans need `block.text`).
    #[inline(always)]
    fn flush_pending(&mut self, block: &Block, diags: &mut Vec<Diagnostic>) {
        if !self.pending.0.is_empty() {
            self.flush_pending_cold(block, diags);
        }
    }

    #[cold]
    #[inline(never)]
    fn flush_pending_cold(&mut self, block: &Block, diags: &mut Vec<Diagnostic>) {
        for p in self.pending.0.drain(..) {
            let span = block.span_of(p.span);
            diags.push(match p.severity {
                Severity::Error => Diagnostic::error(p.code, p.message, span),
                Severity::Warning => Diagnostic::warning(p.code, p.message, span),
            });
        }
    }

    pub(crate) fn in_block_comment(&self) -> bool {
        self.in_block_comment
    }

    pub(crate) fn set_in_block_comment(&mut self, on: bool) {
        self.in_block_comment = on;
    }
}

/// A whole program, parsed (the convenience layer for tests and small programs).
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// The dialect it was parsed as.
    pub dialect: Dialect,
    /// One block per line, in order (empty lines give empty blocks).
    pub blocks: Vec<Block>,
}

/// Parses a whole text: one block per line (LF or CRLF; no block after a final line terminator).
pub fn parse(text: &str, dialect: Dialect) -> (Program, Vec<Diagnostic>) {
    let mut parser = BlockParser::new(dialect);
    let mut diags = Vec::new();
    let mut blocks = Vec::new();
    let mut offset = 0u64;
    for (i, piece) in text.split_inclusive('\n').enumerate() {
        let mut block = Block::default();
        let line = u32::try_from(i + 1).unwrap_or(u32::MAX);
        parser.parse_line(piece, line, offset, &mut block, &mut diags);
        blocks.push(block);
        offset += piece.len() as u64;
    }
    (Program { dialect, blocks }, diags)
}
