//! The Fanuc-style EIA/ISO line parser (Mazatrol EIA/ISO; `docs/dialects/mazatrol-eia.md` §2).
//!
//! Mazak's EIA/ISO language is Fanuc-compatible. It shares the word grammar of RS274/NGC
//! (`<letter><number>`, blanks ignored, `( … )` comments) but differs where LinuxCNC's lexer would
//! misread it, so it has its own line parser:
//!
//! | text | here | RS274/NGC lexer |
//! |---|---|---|
//! | `O1234`, `:1234` | program number: an `O` word, alone on its line (with comments) | an O-word |
//! | `;` | end of block; the rest of the line is a comment | a comment |
//! | `#1 = #2 + 3 * SIN[30]` | an unbracketed expression (Fanuc precedence) | one real value |
//! | `#[#1 + 1] = …` | indirect variable | the same |
//! | `##1`, `#<name>` | refused (Fanuc has neither) | accepted |
//! | `X SIN[30]` | refused: a word's value is a number, `[-]#i` or `[-][expr]` | accepted |
//! | `IF [..] GOTO n`, `IF [..] THEN #i=..`, `GOTO n`, `WHILE [..] DO m`, `DO m`, `END m` | a [`MacroStatement`] | an error |
//! | `/`, `/1` … `/9` | optional block skip (one switch) | `/` only |
//! | `,C`, `,R` chamfer / corner words | refused with a note | an error |
//!
//! Line structure, in order: a lone `%` (tape start/end, comments after it allowed); `/` and an
//! optional level digit; `N<digits>` (no fraction); then either a program number (alone), or a
//! macro statement (alone), or assignments `#i = expr` (one or more, executed left to right by
//! the interpreter), or NC words. NC words and macro statements never share a block (Fanuc's
//! "NC and macro statement in the same block"): the second kind is `syntax::mixed-block`.
//! `( … )` comments may stand anywhere between items; `;` ends the block.
//!
//! A letter followed by another letter starts a keyword (`GOTO` is `G` + `O`, `IF` is `I` + `F`):
//! a word's letter is always followed by its value (a digit, sign, point, `#` or `[`), so the two
//! never collide. Expressions are read by `fanuc_expr.rs` (non-recursive, Fanuc precedence).
//!
//! Recovery: as in the RS274/NGC lexer, the rest of the line is skipped after the first error
//! (`Stop`); what was read before stays in the block. Parsing never fails or panics.

use crate::ast::{
    Address, Assignment, Block, ColSpan, Comment, CommentKind, MacroKind, MacroStatement, ParamRef,
    Value, Word,
};
use crate::lexer::{char_end, excerpt, find_byte, letters_end, skip_blanks, Pendings};
use crate::number::{parse_digits, parse_number};

/// A diagnostic has been recorded; the rest of the line is not parsed.
#[derive(Debug)]
pub(crate) struct Stop;

/// The result of every reader.
pub(crate) type R<T> = Result<T, Stop>;

/// The cursor over one line and the block being filled.
pub(crate) struct Fx<'a> {
    pub b: &'a [u8],
    pub pos: usize,
    pub out: &'a mut Block,
    pub diags: &'a mut Pendings,
    /// The block has NC words.
    nc: bool,
    /// The block has macro assignments.
    assigns: bool,
}

/// Parses one Mazatrol EIA/ISO line into `out` (already cleared, text set).
pub(crate) fn parse_line(b: &[u8], out: &mut Block, diags: &mut Pendings) {
    let mut fx = Fx {
        b,
        pos: 0,
        out,
        diags,
        nc: false,
        assigns: false,
    };
    let _ = fx.line();
}

/// The statement keywords that may begin a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Keyword {
    If,
    Goto,
    While,
    Do,
    End,
}

impl Fx<'_> {
    /// The next non-blank byte (the cursor moves past the blanks).
    #[inline(always)]
    pub fn peek(&mut self) -> Option<u8> {
        self.pos = skip_blanks(self.b, self.pos);
        self.b.get(self.pos).copied()
    }

    /// Records an error on `start..end` and stops the line.
    #[inline(never)]
    pub fn fail<T>(
        &mut self,
        code: &'static str,
        message: impl Into<std::borrow::Cow<'static, str>>,
        start: usize,
        end: usize,
    ) -> R<T> {
        self.diags.error(code, message, start, end);
        Err(Stop)
    }

    /// The "unexpected text" error at the cursor: `expected` is what should be there.
    #[inline(never)]
    pub fn unexpected<T>(&mut self, expected: &str) -> R<T> {
        let start = self.pos;
        match self.b.get(start) {
            None => self.fail(
                "syntax::missing-value",
                format!("the block ends where {expected} was expected"),
                start,
                start,
            ),
            Some(_) => {
                let end = char_end(self.b, start);
                self.fail(
                    "syntax::unexpected-character",
                    format!(
                        "unexpected `{}`: expected {expected}",
                        excerpt(self.b, start, end)
                    ),
                    start,
                    end,
                )
            }
        }
    }

    /// The run of letters at the cursor, upper-cased into `buf` (at most 8 letters; longer runs
    /// compare unequal to every name). Returns the run's end.
    pub fn letter_run(&self, buf: &mut [u8; 8]) -> (usize, usize) {
        let end = letters_end(self.b, self.pos);
        let n = end - self.pos;
        if n <= buf.len() {
            for (i, &c) in self.b[self.pos..end].iter().enumerate() {
                buf[i] = c.to_ascii_uppercase();
            }
        }
        (end, n)
    }

    fn line(&mut self) -> R<()> {
        let Some(first) = self.peek() else {
            return Ok(());
        };
        if first == b'%' {
            return self.percent_line();
        }
        if first == b'/' {
            self.out.block_delete = true;
            self.pos += 1;
            // `/1` … `/9`: levels of optional block skip; Stanok has one switch (`/` = `/1`).
            if matches!(self.b.get(self.pos), Some(b'1'..=b'9')) {
                self.pos += 1;
            }
        }
        if matches!(self.peek(), Some(b'n' | b'N')) {
            self.sequence_number()?;
        }
        if matches!(self.peek(), Some(b'o' | b'O' | b':')) {
            return self.program_number();
        }
        loop {
            let Some(c) = self.peek() else {
                return Ok(());
            };
            match c {
                b';' => {
                    self.end_of_block();
                    return Ok(());
                }
                b'(' => self.comment()?,
                b'#' => self.assignment()?,
                b'a'..=b'z' | b'A'..=b'Z' => {
                    if let Some(k) = self.keyword_ahead() {
                        return self.statement(k);
                    }
                    self.word()?;
                }
                b',' => {
                    let start = self.pos;
                    let end = letters_end(self.b, start + 1).max(start + 1);
                    self.diags.error(
                        "syntax::unexpected-character",
                        format!(
                            "`{}`: the `,C` / `,R` chamfer and corner rounding words are not supported",
                            excerpt(self.b, start, end)
                        ),
                        start,
                        end,
                    );
                    return Err(Stop);
                }
                b']' => {
                    let start = self.pos;
                    return self.fail(
                        "syntax::unbalanced-brackets",
                        "`]` without a matching `[`",
                        start,
                        start + 1,
                    );
                }
                _ => return self.unexpected("a word, `#`, `(` or `;`"),
            }
        }
    }

    /// `%` on its own line (comments after it allowed).
    #[inline(never)]
    fn percent_line(&mut self) -> R<()> {
        self.pos += 1;
        self.out.percent = true;
        self.rest_is_comments("nothing after `%` (it must be alone on its line)")
    }

    /// Only comments, `;` or the end of the line may follow.
    fn rest_is_comments(&mut self, expected: &str) -> R<()> {
        loop {
            match self.peek() {
                None => return Ok(()),
                Some(b'(') => self.comment()?,
                Some(b';') => {
                    self.end_of_block();
                    return Ok(());
                }
                Some(_) => return self.unexpected(expected),
            }
        }
    }

    /// `N123` (an unsigned integer; no fraction).
    #[inline(never)]
    fn sequence_number(&mut self) -> R<()> {
        let start = self.pos;
        self.pos += 1;
        self.peek();
        let Some((value, end)) = parse_digits(self.b, self.pos, true) else {
            return self.fail(
                "syntax::bad-number",
                "`N` must be followed by an unsigned sequence number",
                start,
                start + 1,
            );
        };
        let Some(value) = value.and_then(|v| u32::try_from(v).ok()) else {
            return self.fail(
                "syntax::bad-number",
                "sequence number too large",
                start,
                end,
            );
        };
        self.pos = end;
        if self.b.get(end) == Some(&b'.') {
            return self.fail(
                "syntax::bad-number",
                "a sequence number has no fraction",
                start,
                end + 1,
            );
        }
        self.out.number = Some(value);
        self.out.number_span = Some(ColSpan::new(start, end));
        Ok(())
    }

    /// `O1234` / `:1234`: the program number, alone on its line (comments allowed).
    #[inline(never)]
    fn program_number(&mut self) -> R<()> {
        let start = self.pos;
        self.pos += 1;
        self.peek();
        let digits = parse_digits(self.b, self.pos, false);
        let Some((Some(value), end)) = digits.filter(|(v, _)| v.is_some_and(|v| v <= 99_999_999))
        else {
            let end = digits.map_or(start + 1, |(_, e)| e);
            return self.fail(
                "syntax::bad-number",
                "a program number is `O` and an unsigned whole number of at most 8 digits",
                start,
                end,
            );
        };
        self.pos = end;
        self.out.words.push(Word {
            address: Address::Letter(b'O'),
            value: Value::Number(value as f64),
            span: ColSpan::new(start, end),
        });
        self.rest_is_comments("nothing but comments after the program number")
    }

    /// `;` (end of block): the rest of the line is a comment.
    fn end_of_block(&mut self) {
        let len = self.b.len();
        self.out.comments.push(Comment {
            kind: CommentKind::Line,
            text: ColSpan::new(self.pos + 1, len),
        });
        self.pos = len;
    }

    /// `( … )`, not nested (the control's rule).
    #[inline(never)]
    fn comment(&mut self) -> R<()> {
        let start = self.pos;
        let Some(close) = find_byte(self.b, start + 1, b')') else {
            return self.fail(
                "syntax::unclosed-comment",
                "unclosed comment: `(` has no `)` on this line",
                start,
                self.b.len(),
            );
        };
        if let Some(nested) = find_byte(&self.b[..close], start + 1, b'(') {
            return self.fail(
                "syntax::nested-comment",
                "nested comment: `(` inside a comment",
                nested,
                nested + 1,
            );
        }
        self.out.comments.push(Comment {
            kind: CommentKind::Paren,
            text: ColSpan::new(start + 1, close),
        });
        self.pos = close + 1;
        Ok(())
    }

    /// A statement keyword at the cursor (a letter followed by letters), not consumed.
    fn keyword_ahead(&self) -> Option<Keyword> {
        let second = self.b.get(self.pos + 1)?;
        if !second.is_ascii_alphabetic() {
            return None;
        }
        let mut buf = [0u8; 8];
        let (_, n) = self.letter_run(&mut buf);
        let run = &buf[..n.min(8)];
        match run {
            b"IF" => Some(Keyword::If),
            b"GOTO" => Some(Keyword::Goto),
            b"WHILE" => Some(Keyword::While),
            b"DO" => Some(Keyword::Do),
            b"END" => Some(Keyword::End),
            _ => None,
        }
    }

    /// Consumes the keyword `word` (upper case) at the cursor, or fails expecting it.
    fn expect_keyword(&mut self, word: &[u8], what: &str) -> R<()> {
        self.peek();
        let mut buf = [0u8; 8];
        let (end, n) = self.letter_run(&mut buf);
        if n == word.len() && &buf[..n] == word {
            self.pos = end;
            return Ok(());
        }
        self.unexpected(what)
    }

    /// A macro statement; nothing but comments may follow it.
    #[inline(never)]
    fn statement(&mut self, k: Keyword) -> R<()> {
        let start = self.pos;
        if self.nc || self.assigns {
            return self.mixed(start, "a macro statement");
        }
        let mut buf = [0u8; 8];
        let (end, _) = self.letter_run(&mut buf);
        self.pos = end;
        let mut label_span = None;
        let kind = match k {
            Keyword::Goto => MacroKind::Goto(self.operand_value("the sequence number after GOTO")?),
            Keyword::If => {
                let condition = self.condition("IF")?;
                self.peek();
                let (end, n) = self.letter_run(&mut buf);
                match &buf[..n.min(8)] {
                    b"GOTO" => {
                        self.pos = end;
                        let target = self.operand_value("the sequence number after GOTO")?;
                        MacroKind::IfGoto { condition, target }
                    }
                    b"THEN" => {
                        self.pos = end;
                        if self.peek() != Some(b'#') {
                            return self.unexpected("an assignment `#i = …` after THEN");
                        }
                        while self.peek() == Some(b'#') {
                            self.assignment()?;
                        }
                        MacroKind::IfThen { condition }
                    }
                    _ => return self.unexpected("GOTO or THEN after the IF condition"),
                }
            }
            Keyword::While => {
                let condition = self.condition("WHILE")?;
                self.expect_keyword(b"DO", "DO after the WHILE condition")?;
                let (label, span) = self.loop_label("DO")?;
                label_span = Some(span);
                MacroKind::While { condition, label }
            }
            Keyword::Do => {
                let (label, span) = self.loop_label("DO")?;
                label_span = Some(span);
                MacroKind::Do { label }
            }
            Keyword::End => {
                let (label, span) = self.loop_label("END")?;
                label_span = Some(span);
                MacroKind::End { label }
            }
        };
        let mut end = self.pos;
        while end > start && crate::lexer::is_blank(self.b[end - 1]) {
            end -= 1;
        }
        self.out.statement = Some(MacroStatement {
            kind,
            span: ColSpan::new(start, end),
            label_span,
        });
        self.rest_is_comments("nothing but comments after a macro statement")
    }

    /// The bracketed condition of IF / WHILE.
    fn condition(&mut self, keyword: &str) -> R<crate::ast::ExprId> {
        if self.peek() != Some(b'[') {
            return self.unexpected(&format!("a bracketed condition `[…]` after {keyword}"));
        }
        self.bracketed()
    }

    /// The loop identification number after DO / END: unsigned digits.
    fn loop_label(&mut self, keyword: &str) -> R<(u32, ColSpan)> {
        self.peek();
        let start = self.pos;
        match parse_digits(self.b, start, false) {
            Some((Some(v), end)) if v <= u32::MAX as u64 => {
                self.pos = end;
                Ok((v as u32, ColSpan::new(start, end)))
            }
            _ => self.unexpected(&format!("the loop number after {keyword} (`{keyword} 1`)")),
        }
    }

    /// The error for NC words and macro statements in one block.
    fn mixed<T>(&mut self, start: usize, what: &str) -> R<T> {
        let end = char_end(self.b, start);
        self.fail(
            "syntax::mixed-block",
            format!("{what} cannot share a block with NC words (write it in a block of its own)"),
            start,
            end,
        )
    }

    /// `#i = expression` (also `#[expr] = …`).
    #[inline(never)]
    fn assignment(&mut self) -> R<()> {
        let start = self.pos;
        if self.nc {
            return self.mixed(start, "a variable assignment");
        }
        self.pos += 1;
        let index = self.variable_after_hash()?;
        if self.peek() != Some(b'=') {
            let at = self.pos;
            return self.fail(
                "syntax::bad-assignment",
                "a variable on its own must be assigned: expected `=` (use `#i` as a word's value to read it)",
                start,
                at.max(start + 1),
            );
        }
        self.pos += 1;
        let value = self.open_expression()?;
        let mut end_trim = self.pos;
        while end_trim > start && crate::lexer::is_blank(self.b[end_trim - 1]) {
            end_trim -= 1;
        }
        self.out.assignments.push(Assignment {
            target: ParamRef::Numbered(index),
            value,
            span: ColSpan::new(start, end_trim),
        });
        self.assigns = true;
        Ok(())
    }

    /// `<letter><value>`: a plain number (the hot path), or `[-]#i`, `[-][expr]`.
    fn word(&mut self) -> R<()> {
        let start = self.pos;
        let letter = self.b[start].to_ascii_uppercase();
        if self.assigns {
            return self.mixed(start, "an NC word");
        }
        if matches!(letter, b'N' | b'O') {
            return self.fail(
                "syntax::unexpected-character",
                if letter == b'N' {
                    "`N` sequence number must be the first item of the block"
                } else {
                    "`O` program number must be alone at the start of its line"
                },
                start,
                start + 1,
            );
        }
        self.pos += 1;
        self.nc = true;
        if let Some(n) = parse_number(self.b, self.pos, true) {
            self.pos = n.next;
            self.out.words.push(Word {
                address: Address::Letter(letter),
                value: Value::Number(n.value),
                span: ColSpan::new(start, n.end),
            });
            return Ok(());
        }
        match self.peek() {
            Some(b'[' | b'#' | b'+' | b'-') => {}
            Some(c) if c.is_ascii_alphabetic() => {
                let end = letters_end(self.b, self.pos);
                let name = excerpt(self.b, self.pos, end);
                self.diags.error(
                    "syntax::missing-value",
                    format!(
                        "`{}` has no value (`{name}` is not a value: write an expression in brackets, e.g. `{}[{name}[…]]`)",
                        letter as char, letter as char
                    ),
                    start,
                    start + 1,
                );
                return Err(Stop);
            }
            _ => {
                return self.fail(
                    "syntax::missing-value",
                    format!(
                    "`{}` has no value (a word is a letter and a number, `#i` or `[expression]`)",
                    letter as char
                ),
                    start,
                    start + 1,
                )
            }
        }
        let id = self.operand_value("a value")?;
        let end = self.out.exprs[id.0 as usize].1.end as usize;
        // A signed literal the fast path did not take (`X - 5`) stays a plain number.
        let value = match self.out.exprs[id.0 as usize].0 {
            crate::ast::ExprNode::Number(v) if self.out.exprs.len() == id.0 as usize + 1 => {
                self.out.exprs.pop();
                Value::Number(v)
            }
            _ => Value::Expr(id),
        };
        self.out.words.push(Word {
            address: Address::Letter(letter),
            value,
            span: ColSpan::new(start, end),
        });
        Ok(())
    }
}
