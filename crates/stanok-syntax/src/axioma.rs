//! The AxiOMA Control line parser (ISO-7bit with Sinumerik-style keywords).
//!
//! Rules (spec `axioma-1` §1–§4, §21 A23–A25; `axioma-2` §0):
//!
//! 1. **Cross-line state.** The only state carried from line to line is "inside a `/* … */`
//!    comment" (`in_comment`). A line that starts inside one is comment up to `*/`; the block may
//!    continue after it. The state lives in `BlockParser` and in `SourcePos`.
//! 2. **Line-start forms** (first non-blank character of a line that does not start inside a
//!    comment): `%` → the rest is a Header comment; `*` → the rest is a Line comment; `/` not
//!    followed by `/` or `*` → block skip, which AxiOMA does not support: `block_delete` is set and a
//!    warning says the block runs anyway.
//! 3. **Block number.** `N<digits>` or `:<digits>` as the first item (after a `/`) is the label;
//!    `N1=` is an indexed word even there; a later `N1` is an ordinary `N` word.
//! 4. **Words.** A letter run decides the item: one letter is an address (`X105.5`, `G01X10`),
//!    several letters are a keyword looked up case-insensitively in [`KEYWORDS`] (`CUT` and `TRAF`
//!    continue through a digit, for `CUT3DCCD` and the misprint `TRAF0FF`). Maximal runs mean a
//!    keyword must be followed by a non-letter. After an address, unsigned digits followed (blanks
//!    allowed) by `=` are an index (`S2=1000`, `S2 = 100`); `F=`/`S=`/`S2=` also accept
//!    `FTABLE(n)`/`STABLE(n)` (a table lookup, stored as the `Ftable`/`Stable` keyword word whose
//!    value is the table index). Value keywords take `=` and/or blanks before the value, and an index
//!    before `=` (`LMAXS2=4500`, `LMAXS 5000`).
//! 5. **Comments.** `( … )` closed on the same line, `;` and `//` to the end of the line, `/* … */`.
//! 6. **High-level language** (spec §3 proposal 1, parsed by `hll_parse.rs`). A line whose
//!    first item (after an optional block number) is `{`, `}`, `$…`, an HLL keyword (`int`,
//!    `for`, `if`, `else`, `do`, `while`, `break`, …), a multi-letter name followed by `(`, `[`,
//!    `=`, `++`/`--`, or a one-letter name followed by `++ -- += -= *= /= %= [` is an HLL line:
//!    its statements go to `Block::hll`, `;` ends a statement there and is no comment. A plain
//!    `i = 5` stays the ISO word `I=5` (one-letter names are address letters). In ISO blocks a
//!    value after `=` that is not a plain number (`X=ii*10`, `F=$iPerm[1]`, `X=1/z`,
//!    `X=(a+b)*2`) is an HLL expression (`Value::Hll`), and `MSG(expr)` takes an expression.
//!
//! Recovery: an error skips the offending word (up to the next blank or comment) and parsing goes
//! on; an unclosed `(` or string ends the line. Nothing here allocates unless a diagnostic is made.

use crate::ast::{Address, Block, ColSpan, Comment, CommentKind, Keyword, Value, Word};
use crate::lexer::{
    char_end, digits_end, excerpt, find, find_byte, is_blank, letters_end, skip_blanks, Pendings,
};
use crate::number::parse_number;

/// Every multi-letter word of the dialect, upper case, with the misprints the manual uses.
const KEYWORDS: &[(&[u8], Keyword)] = &[
    (b"BRISK", Keyword::Brisk),
    (b"SOFT", Keyword::Soft),
    (b"TRAORI", Keyword::Traori),
    (b"TRAFOFF", Keyword::TrafOff),
    (b"TRAF0FF", Keyword::TrafOff),
    (b"TRAFOOF", Keyword::TrafOff),
    (b"TRAFFOFF", Keyword::TrafOff),
    (b"ORIEULER", Keyword::OriEuler),
    (b"ORIRPY", Keyword::OriRpy),
    (b"ORIAXES", Keyword::OriAxes),
    (b"ORIXES", Keyword::OriAxes),
    (b"ORIVECT", Keyword::OriVect),
    (b"ORIWKS", Keyword::OriWks),
    (b"ORIMKS", Keyword::OriMks),
    (b"ORIIMKS", Keyword::OriMks),
    (b"CUT2DF", Keyword::Cut2df),
    (b"CUT3DC", Keyword::Cut3dc),
    (b"CUT3DCC", Keyword::Cut3dcc),
    (b"CUT3DCCD", Keyword::Cut3dccd),
    (b"CUT3DF", Keyword::Cut3df),
    (b"CUT3DFS", Keyword::Cut3dfs),
    (b"CUT3DFF", Keyword::Cut3dff),
    (b"CUT3DFE", Keyword::Cut3dff),
    (b"ASPLINE", Keyword::Aspline),
    (b"BSPLINE", Keyword::Bspline),
    (b"CSPLINE", Keyword::Cspline),
    (b"SPLBREAK", Keyword::Splbreak),
    (b"CR", Keyword::Cr),
    (b"PW", Keyword::Pw),
    (b"PL", Keyword::Pl),
    (b"SD", Keyword::Sd),
    (b"LMAXS", Keyword::Lmaxs),
    (b"LMINS", Keyword::Lmins),
    (b"REFAX", Keyword::Refax),
    (b"LEAD", Keyword::Lead),
    (b"TILT", Keyword::Tilt),
    (b"FTABLE", Keyword::Ftable),
    (b"STABLE", Keyword::Stable),
    (b"ISD", Keyword::Isd),
];

/// Words that can only start a statement of the high-level language.
const HLL_WORDS: &[&[u8]] = &[
    b"INT",
    b"LONG",
    b"DOUBLE",
    b"FLOAT",
    b"BOOL",
    b"CHAR",
    b"STRING",
    b"VOID",
    b"CONST",
    b"IF",
    b"ELSE",
    b"FOR",
    b"WHILE",
    b"DO",
    b"SWITCH",
    b"CASE",
    b"DEFAULT",
    b"BREAK",
    b"CONTINUE",
    b"RETURN",
    b"GOTO",
    b"DEFINE",
    b"STRUCT",
    b"UNSIGNED",
    b"SIGNED",
    b"SHORT",
];

/// A compound assignment operator (`+=`, `<<=`, …) at the start of `rest`.
fn compound(rest: &[u8]) -> bool {
    [
        &b"+="[..],
        b"-=",
        b"*=",
        b"/=",
        b"%=",
        b"&=",
        b"|=",
        b"^=",
        b"<<=",
        b">>=",
    ]
    .iter()
    .any(|op| rest.starts_with(op))
}

/// After a one-letter name at the start of a block: `i++`, `i += 2`, `a[2] = 1` are HLL
/// statements (a plain `i = 5` is the ISO word `I=5`).
fn single_letter_statement(rest: &[u8]) -> bool {
    [b"++", b"--", b"+=", b"-=", b"*=", b"/=", b"%="]
        .iter()
        .any(|op| rest.starts_with(*op))
        || rest.first() == Some(&b'[')
}

/// After a number in `X=<value>`: an operator right after it (`X=1/z`, `Q=90*$dPerm[2]`) makes
/// the value a high-level-language expression; `//` and `/*` are comments.
fn continues_expression(rest: &[u8]) -> bool {
    match rest.first() {
        Some(b'/') => !matches!(rest.get(1), Some(b'/' | b'*')),
        Some(c) => b"*%+-<>=!&|^?[".contains(c),
        None => false,
    }
}

fn keyword(ident: &[u8]) -> Option<Keyword> {
    KEYWORDS
        .iter()
        .find(|(name, _)| name.eq_ignore_ascii_case(ident))
        .map(|&(_, k)| k)
}

/// Parses one AxiOMA line into `out` (already cleared, text set). `b` is the line's text.
pub(crate) fn parse_line(b: &[u8], out: &mut Block, diags: &mut Pendings, in_comment: &mut bool) {
    let mut p = Line {
        b,
        out,
        diags,
        in_comment,
    };
    p.run();
}

struct Line<'a> {
    b: &'a [u8],
    out: &'a mut Block,
    diags: &'a mut Pendings,
    in_comment: &'a mut bool,
}

impl Line<'_> {
    fn comment(&mut self, kind: CommentKind, start: usize, end: usize) {
        self.out.comments.push(Comment {
            kind,
            text: ColSpan::new(start, end),
        });
    }

    #[inline(always)]
    fn word(&mut self, address: Address, value: Value, start: usize, end: usize) {
        self.out.words.push(Word {
            address,
            value,
            span: ColSpan::new(start, end),
        });
    }

    /// True while nothing but a block number has been read (HLL statements start here).
    fn at_block_start(&self) -> bool {
        self.out.words.is_empty() && self.out.message.is_none()
    }

    /// Where a skipped, broken word ends: at the next blank or comment start.
    fn word_end(&self, mut p: usize) -> usize {
        let b = self.b;
        while p < b.len() && !is_blank(b[p]) && !matches!(b[p], b'(' | b';' | b'/') {
            p = char_end(b, p);
        }
        p
    }

    #[inline(never)]
    /// Where a skipped HLL expression value ends: at a blank, `;` or comment outside brackets.
    fn expression_end(&self, mut p: usize) -> usize {
        let b = self.b;
        let mut depth = 0usize;
        while p < b.len() {
            match b[p] {
                b'(' | b'[' => depth += 1,
                b')' | b']' => depth = depth.saturating_sub(1),
                b'/' if matches!(b.get(p + 1), Some(b'/' | b'*')) => break,
                c if depth == 0 && (is_blank(c) || c == b';') => break,
                _ => {}
            }
            p = char_end(b, p);
        }
        p
    }

    #[inline(never)]
    /// Where a skipped table lookup ends: after its `( … )` / `[ … ]` argument if it has one.
    fn bracketed_end(&self, p: usize) -> usize {
        let b = self.b;
        let open = skip_blanks(b, p);
        let close = match b.get(open) {
            Some(b'(') => b')',
            Some(b'[') => b']',
            _ => return self.word_end(p),
        };
        find_byte(b, open + 1, close).map_or(b.len(), |q| q + 1)
    }

    fn run(&mut self) {
        let b = self.b;
        let len = b.len();
        let mut p = 0;
        let mut line_start = true;
        if *self.in_comment {
            match find(b, 0, b"*/") {
                None => {
                    self.comment(CommentKind::Block, 0, len);
                    return;
                }
                Some(i) => {
                    self.comment(CommentKind::Block, 0, i);
                    *self.in_comment = false;
                    p = i + 2;
                    line_start = false;
                }
            }
        }
        p = skip_blanks(b, p);
        if line_start && p < len {
            match b[p] {
                b'%' => {
                    self.comment(CommentKind::Header, p + 1, len);
                    return;
                }
                b'*' => {
                    self.comment(CommentKind::Line, p + 1, len);
                    return;
                }
                b'/' if !matches!(b.get(p + 1), Some(b'/' | b'*')) => {
                    self.out.block_delete = true;
                    self.diags.warning(
                        "syntax::block-skip-ignored",
                        "`/` block skip is not supported by AxiOMA: ignored, block executed",
                        p,
                        p + 1,
                    );
                    p += 1;
                }
                _ => {}
            }
        }
        p = skip_blanks(b, p);
        if p < len && matches!(b[p], b'N' | b'n' | b':') {
            p = self.block_number(p);
        }
        while p < len {
            let c = b[p];
            // Hot path first: blanks, then `<letter><number>` words.
            if c == b' ' || c == b'\t' {
                p += 1;
                continue;
            }
            if c.is_ascii_alphabetic() {
                p = match b.get(p + 1) {
                    Some(n) if n.is_ascii_alphabetic() => self.multi_letter(p),
                    _ => self.address_word(p),
                };
                continue;
            }
            p = self.other_item(p);
        }
    }

    /// Anything but a blank or a word at `p`: comments, `:`, HLL braces, junk.
    #[inline(never)]
    fn other_item(&mut self, p: usize) -> usize {
        let b = self.b;
        let len = b.len();
        let c = b[p];
        {
            match c {
                _ if is_blank(c) => p + 1,
                b'(' => match find_byte(b, p + 1, b')') {
                    Some(q) => {
                        self.comment(CommentKind::Paren, p + 1, q);
                        q + 1
                    }
                    None => {
                        self.diags.error(
                            "syntax::unclosed-comment",
                            "unclosed comment: `(` has no `)` on this line",
                            p,
                            len,
                        );
                        len
                    }
                },
                b';' => {
                    self.comment(CommentKind::Line, p + 1, len);
                    len
                }
                b'/' if b.get(p + 1) == Some(&b'/') => {
                    self.comment(CommentKind::Line, p + 2, len);
                    len
                }
                b'/' if b.get(p + 1) == Some(&b'*') => match find(b, p + 2, b"*/") {
                    Some(q) => {
                        self.comment(CommentKind::Block, p + 2, q);
                        q + 2
                    }
                    None => {
                        self.comment(CommentKind::Block, p + 2, len);
                        *self.in_comment = true;
                        len
                    }
                },
                b':' => p + 1,
                b'{' | b'}' | b'$' if self.at_block_start() => self.hll_statement(p),
                _ => self.unexpected(p),
            }
        }
    }

    /// `N10` / `:10` at the start of a block. Returns the position after it (or `p`).
    #[inline(never)]
    fn block_number(&mut self, p: usize) -> usize {
        let b = self.b;
        if p >= b.len() || !matches!(b[p], b'N' | b'n' | b':') {
            return p;
        }
        let digits = p + 1;
        let end = digits_end(b, digits);
        if end == digits {
            return p; // `N` without digits, `N=…`, `:` alone: not a label
        }
        if b[p] != b':' {
            let q = skip_blanks(b, end);
            if b.get(q) == Some(&b'=') {
                return p; // `N1=3`: indexed word
            }
        }
        if b.get(end) == Some(&b'.') {
            let stop = self.word_end(end);
            self.diags.error(
                "syntax::bad-number",
                "a block number must be a whole number",
                p,
                stop,
            );
            return stop;
        }
        match parse_number(b, digits, false)
            .and_then(|n| n.integer)
            .and_then(|n| u32::try_from(n).ok())
        {
            Some(n) => {
                self.out.number = Some(n);
                self.out.number_span = Some(ColSpan::new(p, end));
            }
            None => self
                .diags
                .error("syntax::bad-number", "block number too large", p, end),
        }
        end
    }

    #[inline(never)]
    /// A run of two or more letters at `start`: a keyword, `MSG(…)`, or an unknown word.
    fn multi_letter(&mut self, start: usize) -> usize {
        let b = self.b;
        let mut end = letters_end(b, start);
        let run = &b[start..end];
        if (run.eq_ignore_ascii_case(b"CUT") || run.eq_ignore_ascii_case(b"TRAF"))
            && b.get(end).is_some_and(u8::is_ascii_digit)
        {
            end = letters_end(b, end + 1);
        }
        let ident = &b[start..end];
        if ident.eq_ignore_ascii_case(b"MSG") {
            return self.message(start, end);
        }
        match keyword(ident) {
            Some(k) if !k.takes_value() => {
                let address = Address::Keyword {
                    keyword: k,
                    index: None,
                };
                self.word(address, Value::None, start, end);
                end
            }
            Some(Keyword::Ftable | Keyword::Stable) => {
                let stop = self.bracketed_end(end);
                self.diags.error(
                    "syntax::misplaced-word",
                    format!(
                        "`{}` is only allowed as the value of `{}=`",
                        excerpt(b, start, end).to_ascii_uppercase(),
                        if ident.eq_ignore_ascii_case(b"FTABLE") {
                            "F"
                        } else {
                            "S"
                        }
                    ),
                    start,
                    stop,
                );
                stop
            }
            Some(k) => self.keyword_value(k, start, end),
            None => self.unknown_word(start, end),
        }
    }

    /// A single-letter address at `start`: `X10`, `S2=1000`, `F=FTABLE(3)`. Returns the position
    /// after the word and the blanks that follow it.
    #[inline(always)]
    fn address_word(&mut self, start: usize) -> usize {
        let b = self.b;
        let letter = b[start].to_ascii_uppercase();
        let p = start + 1;
        match parse_number(b, p, false) {
            Some(n) => {
                let q = n.next;
                if let Some(index) = n.integer {
                    if b.get(q) == Some(&b'=') {
                        return match u8::try_from(index) {
                            Ok(index) => self.value_after_eq(
                                Address::Indexed { letter, index },
                                start,
                                q + 1,
                            ),
                            Err(_) => {
                                let stop = self.word_end(q + 1);
                                self.diags.error(
                                    "syntax::bad-number",
                                    "address index too large (at most 255)",
                                    start,
                                    n.end,
                                );
                                stop
                            }
                        };
                    }
                }
                self.word(
                    Address::Letter(letter),
                    Value::Number(n.value),
                    start,
                    n.end,
                );
                q
            }
            None => {
                let q = skip_blanks(b, p);
                if b.get(q) == Some(&b'=') && b.get(q + 1) != Some(&b'=') {
                    return self.value_after_eq(Address::Letter(letter), start, q + 1);
                }
                if self.at_block_start() && single_letter_statement(&b[q..]) {
                    return self.hll_statement(start);
                }
                self.missing_value(start, p)
            }
        }
    }

    #[inline(never)]
    /// A keyword that takes a value: `CR=-30`, `LMAXS 5000`, `LMAXS2=4500`, `LEAD 10`.
    fn keyword_value(&mut self, keyword: Keyword, start: usize, end: usize) -> usize {
        let b = self.b;
        let mut index = None;
        let mut p = end;
        let digits = digits_end(b, p);
        if digits > p {
            let q = skip_blanks(b, digits);
            if b.get(q) == Some(&b'=') {
                match parse_number(b, p, false)
                    .and_then(|n| n.integer)
                    .and_then(|n| u8::try_from(n).ok())
                {
                    Some(i) => index = Some(i),
                    None => {
                        let stop = self.word_end(q + 1);
                        self.diags.error(
                            "syntax::bad-number",
                            "keyword index too large (at most 255)",
                            start,
                            digits,
                        );
                        return stop;
                    }
                }
                p = q + 1;
            }
        } else {
            let q = skip_blanks(b, p);
            if b.get(q) == Some(&b'=') {
                p = q + 1;
            }
        }
        let written = p;
        let p = skip_blanks(b, p);
        match parse_number(b, p, false) {
            Some(n) => {
                self.word(
                    Address::Keyword { keyword, index },
                    Value::Number(n.value),
                    start,
                    n.end,
                );
                n.end
            }
            None if p < b.len() && matches!(b[p], b'+' | b'-' | b'.') => {
                self.missing_value(start, p)
            }
            None => self.missing_value(start, written),
        }
    }

    #[inline(never)]
    /// The value after `=` of `address` (written from `start`; `p` is just after the `=`).
    fn value_after_eq(&mut self, address: Address, start: usize, eq_end: usize) -> usize {
        let b = self.b;
        let p = skip_blanks(b, eq_end);
        if let Some(n) = parse_number(b, p, false) {
            if !continues_expression(&b[n.end..]) {
                self.word(address, Value::Number(n.value), start, n.end);
                return n.end;
            }
        }
        let ident_end = letters_end(b, p);
        let ident = &b[p..ident_end];
        let (letter, index) = match address {
            Address::Letter(l) => (l, None),
            Address::Indexed { letter, index } => (letter, Some(index)),
            Address::Keyword { .. } => (0, None),
        };
        let table = if ident.eq_ignore_ascii_case(b"FTABLE") && letter == b'F' {
            Some(Keyword::Ftable)
        } else if ident.eq_ignore_ascii_case(b"STABLE") && letter == b'S' {
            Some(Keyword::Stable)
        } else {
            None
        };
        if let Some(keyword) = table {
            // `F=FTABLE(20)`, `S2=STABLE[3]`: the table index in brackets.
            let open = skip_blanks(b, ident_end);
            let close_char = match b.get(open) {
                Some(b'(') => b')',
                Some(b'[') => b']',
                _ => 0,
            };
            let arg = skip_blanks(b, open + 1);
            if close_char != 0 {
                if let Some(n) = parse_number(b, arg, false) {
                    let close = skip_blanks(b, n.end);
                    if b.get(close) == Some(&close_char) {
                        self.word(
                            Address::Keyword { keyword, index },
                            Value::Number(n.value),
                            start,
                            close + 1,
                        );
                        return close + 1;
                    }
                }
            }
            if close_char == b')' {
                // `F=FTABLE(n+1)`: a computed index is a high-level-language call.
                let mut scratch = Pendings(Vec::new());
                if let Some((e, end)) = crate::hll_parse::word_value(b, p, self.out, &mut scratch) {
                    self.word(address, Value::Hll(e), start, end);
                    return end;
                }
            }
            let stop = self.bracketed_end(ident_end);
            self.diags.error(
                "syntax::bad-number",
                format!(
                    "`{}` needs a constant table index in parentheses, e.g. `{}(3)`",
                    excerpt(b, p, ident_end).to_ascii_uppercase(),
                    excerpt(b, p, ident_end).to_ascii_uppercase()
                ),
                start,
                stop.max(ident_end),
            );
            return stop;
        }
        // Nothing, a comment, or the next address word (`S2= M3`: blanks after `=`, then a
        // letter and a number): the value is missing.
        let next_word = p > eq_end
            && ident_end == p + 1
            && b.get(ident_end)
                .is_some_and(|c| c.is_ascii_digit() || matches!(c, b'-' | b'+' | b'.'));
        // `X=(a+b)*2` is an expression; `X= (text)` a missing value and a comment.
        let comment = matches!(b[p.min(b.len() - 1)], b';' | b'/')
            || (b[p.min(b.len() - 1)] == b'(' && p > eq_end);
        if p >= b.len() || comment || next_word {
            return self.missing_value(start, eq_end);
        }
        // `X=ii*10`, `F=$iPerm[1]`, `F=FTABLE(i)`: a high-level-language expression, evaluated
        // when the block executes.
        match crate::hll_parse::word_value(b, p, self.out, self.diags) {
            Some((e, end)) => {
                self.word(address, Value::Hll(e), start, end);
                end
            }
            None => self.expression_end(p).max(p + 1),
        }
    }

    #[inline(never)]
    /// `MSG("text")`, `MSG()`; `MSG(variable)` is high-level language.
    fn message(&mut self, start: usize, end: usize) -> usize {
        let b = self.b;
        let len = b.len();
        let open = skip_blanks(b, end);
        if b.get(open) != Some(&b'(') {
            self.diags.error(
                "syntax::bad-message",
                "`MSG` must be followed by `(\"text\")` or `()`",
                start,
                end,
            );
            return len;
        }
        let p = skip_blanks(b, open + 1);
        let (text, after) = match b.get(p) {
            Some(b')') => (ColSpan::new(p, p), p),
            Some(b'"') => match find_byte(b, p + 1, b'"') {
                Some(q) => (ColSpan::new(p + 1, q), q + 1),
                None => {
                    self.diags.error(
                        "syntax::unclosed-string",
                        "unclosed string: `\"` has no closing `\"` on this line",
                        p,
                        len,
                    );
                    return len;
                }
            },
            _ => return self.message_expression(p),
        };
        let close = skip_blanks(b, after);
        if b.get(p) == Some(&b'"') && b.get(close).is_some_and(|&c| c != b')') {
            // `MSG("a" + s)`: an expression that starts with a string.
            return self.message_expression(p);
        }
        if b.get(close) != Some(&b')') {
            self.diags.error(
                "syntax::unbalanced-brackets",
                "`MSG(` has no closing `)`",
                start,
                close.min(len),
            );
            return self.word_end(close);
        }
        self.out.message = Some(text);
        close + 1
    }

    #[inline(never)]
    /// `MSG(<expr>)`: the message is the value of a high-level-language expression.
    fn message_expression(&mut self, p: usize) -> usize {
        match crate::hll_parse::message_arg(self.b, p, self.out, self.diags) {
            Some((e, end)) => {
                self.out.hll_mut().message = Some(e);
                end
            }
            None => self.b.len(),
        }
    }

    #[inline(never)]
    /// A multi-letter identifier that is no keyword.
    fn unknown_word(&mut self, start: usize, end: usize) -> usize {
        let b = self.b;
        if self.at_block_start() {
            // HLL names may contain digits and `_` (`settable_zs`, `ii2`).
            let mut end = end;
            while end < b.len() && (b[end].is_ascii_alphanumeric() || b[end] == b'_') {
                end += 1;
            }
            let ident = &b[start..end];
            let next = skip_blanks(b, end);
            let call_or_assign = match b.get(next) {
                Some(b'(' | b'[') => true,
                Some(b'=') => b.get(next + 1) != Some(&b'='),
                Some(&c @ (b'+' | b'-')) => b.get(next + 1) == Some(&c) || compound(&b[next..]),
                _ => compound(&b[next..]),
            };
            if call_or_assign || HLL_WORDS.iter().any(|w| w.eq_ignore_ascii_case(ident)) {
                return self.hll_statement(start);
            }
        }
        let stop = self.word_end(end);
        self.diags.error(
            "syntax::unknown-word",
            format!("unknown word `{}`", excerpt(b, start, end)),
            start,
            stop,
        );
        stop
    }

    #[inline(never)]
    /// High-level-language statements from `start` to the end of the line (`hll_parse.rs`).
    fn hll_statement(&mut self, start: usize) -> usize {
        crate::hll_parse::statements(self.b, start, self.out, self.diags, self.in_comment)
    }

    #[inline(never)]
    /// A run of characters that cannot start an item here.
    fn unexpected(&mut self, start: usize) -> usize {
        let b = self.b;
        let mut p = char_end(b, start);
        while p < b.len()
            && !is_blank(b[p])
            && !b[p].is_ascii_alphabetic()
            && !matches!(b[p], b'(' | b';' | b'/' | b':')
        {
            p = char_end(b, p);
        }
        let what = excerpt(b, start, p);
        let message = if b[start] == b'/' {
            "`/` (block skip) is only allowed at the start of a block".to_string()
        } else if b[start].is_ascii_digit() || matches!(b[start], b'.' | b'+' | b'-') {
            format!("number `{what}` without an address letter")
        } else {
            format!("unexpected `{what}`")
        };
        self.diags
            .error("syntax::unexpected-character", message, start, p);
        p
    }

    #[inline(never)]
    /// An address or keyword written without its value.
    fn missing_value(&mut self, start: usize, p: usize) -> usize {
        let b = self.b;
        let stop = if p < b.len() && matches!(b[p], b'+' | b'-' | b'.') {
            self.word_end(p)
        } else {
            p
        };
        let what = excerpt(b, start, stop).to_ascii_uppercase();
        let (code, message) = if stop > p {
            (
                "syntax::bad-number",
                format!("malformed number in `{what}`"),
            )
        } else {
            ("syntax::missing-value", format!("`{what}` has no value"))
        };
        self.diags.error(code, message, start, stop.max(start + 1));
        stop.max(start + 1)
    }
}
