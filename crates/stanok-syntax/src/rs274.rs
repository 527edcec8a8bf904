//! The RS274/NGC (LinuxCNC) line parser: items of a line.
//!
//! LinuxCNC first deletes every blank outside comments and lower-cases the line, then reads it item
//! by item (`read_items` in interp_read.cc). We do the same without copying: the cursor's
//! [`Rs::peek`] skips blanks before every look, and letters are compared case-insensitively, so
//! `G 0 X 1 . 5` is `G0 X1.5`, `s i n[0]` is `sin[0]` and `o100 end sub` is `o100 endsub`. Blanks
//! are kept only inside comments and `#<names>` (the interpreter normalises names).
//!
//! Line structure, in order:
//! 1. a lone `%` (blanks and comments around it allowed) is the program delimiter;
//! 2. `/` first → `block_delete`;
//! 3. `N<digits>[.<digits>]` first → the label (LinuxCNC ignores a fraction; so do we); an `N`
//!    anywhere else is an error, as in LinuxCNC;
//! 4. an O-word line: `o<label> <keyword> [args]`, then only comments (see [`Rs::oword`]);
//! 5. otherwise items: `<letter><real value>` words (and LinuxCNC's `$` spindle selector), `#… =`
//!    assignments, `( … )` comments (MSG/DEBUG/PRINT recognised), `;` to the end of the line.
//!
//! Real values and expressions are read by `expr.rs`. Recovery: LinuxCNC rejects a line at its
//! first error, so after an error the rest of the line is skipped (what was read before stays).
//! Every reader returns `Result<_, Stop>`; `Stop` means "a diagnostic was recorded, stop the line".

use crate::ast::{
    Address, Assignment, Block, ColSpan, Comment, CommentKind, OKind, OLabel, OWord, Value, Word,
};
use crate::lexer::{char_end, excerpt, find_byte, is_blank, letters_end, skip_blanks, Pendings};
use crate::number::{parse_digits, parse_number};

/// For each byte: the upper-case letter if it starts a plain word (`A`…`Z` either case, except `N`
/// and `O`, which have their own rules), else 0. One load instead of four compares per word.
static WORD_LETTER: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut c = b'A';
    while c <= b'Z' {
        if c != b'N' && c != b'O' {
            t[c as usize] = c;
            t[c.to_ascii_lowercase() as usize] = c;
        }
        c += 1;
    }
    t
};

/// A diagnostic has been recorded; the rest of the line is not parsed.
#[derive(Debug)]
pub(crate) struct Stop;

/// The result of every reader.
pub(crate) type R<T> = Result<T, Stop>;

/// The cursor over one line and the block being filled.
pub(crate) struct Rs<'a> {
    pub b: &'a [u8],
    pub pos: usize,
    pub out: &'a mut Block,
    pub diags: &'a mut Pendings,
}

/// Parses one RS274/NGC line into `out` (already cleared, text set). Inlined into its one caller,
/// `BlockParser::parse_bytes`: the call and its frame were ~20 instructions per line.
#[inline(always)]
pub(crate) fn parse_line(b: &[u8], out: &mut Block, diags: &mut Pendings) {
    let mut rs = Rs {
        b,
        pos: 0,
        out,
        diags,
    };
    let _ = rs.line();
}

impl Rs<'_> {
    /// The next non-blank byte (the cursor moves past the blanks).
    #[inline(always)]
    pub fn peek(&mut self) -> Option<u8> {
        self.pos = skip_blanks(self.b, self.pos);
        self.b.get(self.pos).copied()
    }

    #[inline(never)]
    /// Records an error on `start..end` and stops the line.
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

    /// Matches `word` (lower case) here, blanks allowed between its letters, ignoring case.
    /// Moves past it on success; leaves the cursor unchanged otherwise.
    pub fn eat_word(&mut self, word: &[u8]) -> bool {
        let save = self.pos;
        for &w in word {
            match self.peek() {
                Some(c) if c.to_ascii_lowercase() == w => self.pos += 1,
                _ => {
                    self.pos = save;
                    return false;
                }
            }
        }
        true
    }

    #[inline(never)]
    /// The "unexpected text" error at the cursor: `what` is expected.
    pub fn unexpected<T>(&mut self, expected: &str) -> R<T> {
        let start = self.pos;
        match self.b.get(start) {
            None => self.fail(
                "syntax::missing-value",
                format!("line ends where {expected} was expected"),
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

    fn line(&mut self) -> R<()> {
        let Some(first) = self.peek() else {
            return Ok(());
        };
        // A line that starts with a plain word (most lines) has none of the prefixes below.
        if WORD_LETTER[first as usize] == 0 {
            if first == b'%' {
                return self.percent_line();
            }
            if first == b'/' {
                self.out.block_delete = true;
                self.pos += 1;
            }
            if matches!(self.peek(), Some(b'n' | b'N')) {
                self.line_number()?;
            }
            if matches!(self.peek(), Some(b'o' | b'O')) {
                return self.oword();
            }
        }
        loop {
            self.plain_words();
            // `plain_words` leaves the cursor past blanks (no second `skip_blanks`).
            let Some(c) = self.b.get(self.pos).copied() else {
                return Ok(());
            };
            match c {
                b'(' => self.paren_comment()?,
                b';' => {
                    self.semicolon_comment();
                    return Ok(());
                }
                b'#' => self.assignment()?,
                b'n' | b'N' => {
                    let start = self.pos;
                    return self.fail(
                        "syntax::unexpected-character",
                        // LinuxCNC's message first (its reader has no `n` word past the start).
                        "Bad character 'n' used: `N` line number must be the first item of the line",
                        start,
                        start + 1,
                    );
                }
                b'o' | b'O' => {
                    let start = self.pos;
                    return self.fail(
                        "syntax::bad-oword",
                        "an O-word must be the first item of the line (after the `N` number)",
                        start,
                        start + 1,
                    );
                }
                b'a'..=b'z' | b'A'..=b'Z' | b'$' | b'@' | b'^' => self.word()?,
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

    /// The hot path: a run of `<letter><number>` words (`G1 X10.5 Y-3`), the bulk of every program.
    /// One tight loop: the number's trailing blanks are skipped once, by `parse_number`, and the
    /// next letter is tested right there. Anything else (N, O, `$`, expressions, comments, a number
    /// the general path must judge) stops the run and goes through [`Rs::line`]'s `match`, where
    /// [`Rs::word`] gives the same result for a word this loop did not take.
    #[inline(always)]
    fn plain_words(&mut self) {
        let b = self.b;
        let mut p = skip_blanks(b, self.pos);
        while let Some(&c) = b.get(p) {
            let letter = WORD_LETTER[c as usize];
            if letter == 0 {
                break;
            }
            let Some(n) = parse_number(b, p + 1, true) else {
                break;
            };
            self.out.words.push(Word {
                address: Address::Letter(letter),
                value: Value::Number(n.value),
                span: ColSpan::new(p, n.end),
            });
            p = n.next;
        }
        self.pos = p;
    }

    #[inline(never)]
    /// `%` alone on its line (comments allowed after it).
    fn percent_line(&mut self) -> R<()> {
        self.pos += 1;
        self.out.percent = true;
        loop {
            match self.peek() {
                None => return Ok(()),
                Some(b'(') => self.paren_comment()?,
                Some(b';') => {
                    self.semicolon_comment();
                    return Ok(());
                }
                Some(_) => {
                    self.out.percent = false;
                    return self.unexpected("nothing after `%` (it must be alone on its line)");
                }
            }
        }
    }

    #[inline(never)]
    /// `N10` (`N10.5`: the fraction is accepted and ignored, as LinuxCNC does).
    fn line_number(&mut self) -> R<()> {
        let start = self.pos;
        self.pos += 1;
        self.peek();
        let Some((value, end)) = parse_digits(self.b, self.pos, true) else {
            return self.fail(
                "syntax::bad-number",
                "`N` must be followed by an unsigned line number",
                start,
                start + 1,
            );
        };
        let Some(value) = value.and_then(|v| u32::try_from(v).ok()) else {
            return self.fail("syntax::bad-number", "line number too large", start, end);
        };
        self.pos = end;
        if self.peek() == Some(b'.') {
            self.pos += 1;
            self.peek();
            match parse_digits(self.b, self.pos, true) {
                Some((_, fraction_end)) => self.pos = fraction_end,
                None => return self.unexpected("digits of the line number fraction"),
            }
        }
        self.out.number = Some(value);
        self.out.number_span = Some(ColSpan::new(start, end));
        Ok(())
    }

    /// `<letter><real value>`.
    #[inline(always)]
    fn word(&mut self) -> R<()> {
        let start = self.pos;
        let letter = self.b[start].to_ascii_uppercase();
        self.pos += 1;
        // Hot path: a plain number right after the letter (`X12.5`, `Y-6`), not continued after a
        // blank by an operator the general path would reject anyway.
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
            Some(b'[' | b'#' | b'+' | b'-' | b'.' | b'0'..=b'9') => {}
            Some(c) if c.is_ascii_alphabetic() && self.function_ahead() => {}
            _ => {
                return self.fail(
                    "syntax::missing-value",
                    format!("`{}` has no value", letter as char),
                    start,
                    start + 1,
                )
            }
        }
        let value = match self.real_value(0)? {
            Operand::Number(v, _) => Value::Number(v),
            Operand::Expr(id) => Value::Expr(id),
        };
        let end = self.pos;
        self.out.words.push(Word {
            address: Address::Letter(letter),
            value,
            span: ColSpan::new(start, end),
        });
        Ok(())
    }

    #[inline(never)]
    /// `#<param> = <real value>`.
    fn assignment(&mut self) -> R<()> {
        let start = self.pos;
        self.pos += 1;
        let target = self.param_after_hash(1)?;
        let target_end = self.pos;
        if self.peek() != Some(b'=') {
            let at = target_end;
            return self.fail(
                "syntax::bad-assignment",
                "a parameter on its own must be assigned: expected `=` (use `#…` as a word's value to read it)",
                start,
                at,
            );
        }
        self.pos += 1;
        if self.peek().is_none() {
            let at = self.pos;
            return self.fail("syntax::missing-value", "`=` has no value", start, at);
        }
        let value = self.real_value(0)?;
        let value = self.operand_expr(value);
        let end = self.pos;
        self.out.assignments.push(Assignment {
            target,
            value,
            span: ColSpan::new(start, end),
        });
        Ok(())
    }

    #[inline(never)]
    /// `( … )`: plain, or `(MSG, …)` / `(DEBUG, …)` / `(PRINT, …)`.
    pub fn paren_comment(&mut self) -> R<()> {
        let b = self.b;
        let start = self.pos;
        let Some(close) = find_byte(b, start + 1, b')') else {
            return self.fail(
                "syntax::unclosed-comment",
                // LinuxCNC's words (the span shows the `(` without its `)`).
                "Unclosed comment found",
                start,
                b.len(),
            );
        };
        if let Some(nested) = find_byte(&b[..close], start + 1, b'(') {
            return self.fail(
                "syntax::nested-comment",
                "Nested comment found",
                nested,
                nested + 1,
            );
        }
        // Recognise the keyword with blanks anywhere before the comma (LinuxCNC convert_comment).
        self.pos = start + 1;
        let mut comment = Comment {
            kind: CommentKind::Paren,
            text: ColSpan::new(start + 1, close),
        };
        for (word, kind) in [
            (&b"msg"[..], CommentKind::Msg),
            (b"debug", CommentKind::Debug),
            (b"print", CommentKind::Print),
        ] {
            if self.eat_word(word) && self.peek() == Some(b',') && self.pos < close {
                comment = Comment {
                    kind,
                    text: ColSpan::new(self.pos + 1, close),
                };
                break;
            }
            self.pos = start + 1;
        }
        self.out.comments.push(comment);
        self.pos = close + 1;
        Ok(())
    }

    #[inline(never)]
    /// `;` to the end of the line.
    fn semicolon_comment(&mut self) {
        let len = self.b.len();
        self.out.comments.push(Comment {
            kind: CommentKind::Line,
            text: ColSpan::new(self.pos + 1, len),
        });
        self.pos = len;
    }

    #[inline(never)]
    /// An O-word line: label, keyword, arguments, then only comments.
    fn oword(&mut self) -> R<()> {
        let b = self.b;
        let start = self.pos;
        self.pos += 1;
        let label = match self.peek() {
            Some(b'<') => {
                let open = self.pos;
                let Some(close) = find_byte(b, open + 1, b'>') else {
                    return self.fail(
                        "syntax::bad-oword",
                        "O-word name: `<` has no `>`",
                        open,
                        b.len(),
                    );
                };
                if b[open + 1..close].iter().all(|&c| is_blank(c)) {
                    return self.fail("syntax::bad-oword", "empty O-word name", start, close + 1);
                }
                self.pos = close + 1;
                OLabel::Name(ColSpan::new(open + 1, close))
            }
            Some(b'0'..=b'9') => match parse_digits(b, self.pos, true) {
                Some((Some(v), end)) if v <= u32::MAX as u64 => {
                    self.pos = end;
                    OLabel::Number(v as u32)
                }
                other => {
                    let end = other.map_or(self.pos + 1, |(_, end)| end);
                    return self.fail(
                        "syntax::bad-oword",
                        "O-word number must be a whole number below 2^32",
                        start,
                        end,
                    );
                }
            },
            Some(b'[' | b'#') => {
                let at = self.pos;
                return self.fail(
                    "syntax::bad-oword",
                    "computed O-word labels are not supported yet",
                    start,
                    at + 1,
                );
            }
            _ => {
                return self.fail(
                    "syntax::bad-oword",
                    "`O` must be followed by a number or a `<name>`",
                    start,
                    start + 1,
                )
            }
        };
        let kw_start = skip_blanks(b, self.pos);
        let kind = self.oword_keyword()?;
        let kind = match kind {
            OKeyword::Sub => OKind::Sub,
            OKeyword::Else => OKind::Else,
            OKeyword::EndIf => OKind::EndIf,
            OKeyword::EndWhile => OKind::EndWhile,
            OKeyword::Do => OKind::Do,
            OKeyword::EndRepeat => OKind::EndRepeat,
            OKeyword::Break => OKind::Break,
            OKeyword::Continue => OKind::Continue,
            OKeyword::EndSub => OKind::EndSub(self.optional_bracket()?),
            OKeyword::Return => OKind::Return(self.optional_bracket()?),
            OKeyword::If => OKind::If(self.condition("if", kw_start)?),
            OKeyword::ElseIf => OKind::ElseIf(self.condition("elseif", kw_start)?),
            OKeyword::While => OKind::While(self.condition("while", kw_start)?),
            OKeyword::Repeat => OKind::Repeat(self.condition("repeat", kw_start)?),
            OKeyword::Call => {
                let mut args = Vec::new();
                while self.peek() == Some(b'[') {
                    args.push(self.bracket(1)?);
                }
                OKind::Call(args)
            }
        };
        let mut end = self.pos;
        while end > start && is_blank(b[end - 1]) {
            end -= 1;
        }
        self.out.oword = Some(OWord {
            label,
            kind,
            span: ColSpan::new(start, end),
        });
        loop {
            match self.peek() {
                None => return Ok(()),
                Some(b'(') => self.paren_comment()?,
                Some(b';') => {
                    self.semicolon_comment();
                    return Ok(());
                }
                Some(_) => {
                    // LinuxCNC's wording.
                    let start = self.pos;
                    let end = char_end(self.b, start);
                    return self.fail(
                        "syntax::unexpected-character",
                        "Unexpected character after O-word".to_string(),
                        start,
                        end,
                    );
                }
            }
        }
    }

    #[inline(never)]
    /// The keyword of an O-word, matched as a prefix with blanks allowed between its letters, as
    /// LinuxCNC's `read_o` does (so `o1 sub` and `o1 s u b` are the same; what follows the keyword
    /// is checked by the caller).
    fn oword_keyword(&mut self) -> R<OKeyword> {
        // Longer names before their prefixes (`elseif` before `else`).
        const WORDS: &[(&[u8], OKeyword)] = &[
            (b"sub", OKeyword::Sub),
            (b"endsub", OKeyword::EndSub),
            (b"call", OKeyword::Call),
            (b"return", OKeyword::Return),
            (b"if", OKeyword::If),
            (b"elseif", OKeyword::ElseIf),
            (b"else", OKeyword::Else),
            (b"endif", OKeyword::EndIf),
            (b"while", OKeyword::While),
            (b"endwhile", OKeyword::EndWhile),
            (b"do", OKeyword::Do),
            (b"repeat", OKeyword::Repeat),
            (b"endrepeat", OKeyword::EndRepeat),
            (b"break", OKeyword::Break),
            (b"continue", OKeyword::Continue),
        ];
        if let Some(&(_, k)) = WORDS.iter().find(|(w, _)| self.eat_word(w)) {
            return Ok(k);
        }
        let start = skip_blanks(self.b, self.pos);
        let end = letters_end(self.b, start);
        if end == start {
            self.pos = start;
            return self.unexpected("an O-word keyword (`sub`, `call`, `if`, `while`, …)");
        }
        self.fail(
            "syntax::bad-oword",
            format!("unknown O-word keyword `{}`", excerpt(self.b, start, end)),
            start,
            end,
        )
    }

    /// The `[condition]` of `if`/`elseif`/`while`/`repeat`.
    fn condition(&mut self, keyword: &str, kw_start: usize) -> R<crate::ast::ExprId> {
        if self.peek() != Some(b'[') {
            let at = self.pos;
            return self.fail(
                "syntax::bad-oword",
                format!("`{keyword}` needs a bracketed expression `[…]`"),
                kw_start,
                at,
            );
        }
        self.bracket(1)
    }

    /// The optional `[value]` of `endsub`/`return`.
    fn optional_bracket(&mut self) -> R<Option<crate::ast::ExprId>> {
        if self.peek() == Some(b'[') {
            Ok(Some(self.bracket(1)?))
        } else {
            Ok(None)
        }
    }
}

/// The O-word keywords.
#[derive(Debug, Clone, Copy)]
enum OKeyword {
    Sub,
    EndSub,
    Call,
    Return,
    If,
    ElseIf,
    Else,
    EndIf,
    While,
    EndWhile,
    Do,
    Repeat,
    EndRepeat,
    Break,
    Continue,
}

/// A real value as read: a plain number stays a number (no arena node) until it must be one.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Operand {
    /// A literal and its span.
    Number(f64, ColSpan),
    /// Anything else, already in the arena.
    Expr(crate::ast::ExprId),
}

#[cfg(test)]
mod tests {
    use super::WORD_LETTER;

    #[test]
    fn word_letters_are_ascii_letters_but_n_and_o() {
        for c in 0..=255u8 {
            let expected = if c.is_ascii_alphabetic() && !matches!(c, b'n' | b'N' | b'o' | b'O') {
                c.to_ascii_uppercase()
            } else {
                0
            };
            assert_eq!(WORD_LETTER[c as usize], expected, "{c:#x}");
        }
    }
}
