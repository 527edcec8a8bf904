//! Line readers of the lab-collection controls (spec `lab-collection-nc31-2p32-cutting.md`).
//!
//! These languages are far from ISO: the NC-31 writes one address per line with flags around it
//! (`~X 34000*`, `Z -5000#`, `-45° X 32000`), the 2P32 and MC2101 write spaces inside words
//! (`Z - 200000`, `Y+ 012000`) and the GOST-20999 control has `R1#39.` assignments and `X-R1`
//! variable values. Each gets its own small reader here; they share nothing with
//! [`crate::BlockParser`] except the rule that **reading never fails**: a line always yields a
//! result plus diagnostics with exact spans.
//!
//! * [`nc31`] — one NC-31 frame per line ([`nc31::parse_line`]).
//! * [`words`] — the word-address lines of the 2P32, MC2101 and GOST-20999 controls
//!   ([`words::parse_line`] with a [`words::Profile`]).
//! * [`strip_fixture_comments`] — the lab corpus's conventions (`;` header lines, `//`
//!   annotations), which are *not* program text of any of these controls: the tests, and the CLI's
//!   `--strip-fixture-comments`, remove them before a reader sees the program.

pub mod nc31;
pub mod words;

use stanok_canon::Span;

/// The text with the lab fixtures' annotations blanked out: a line whose first non-blank
/// character is `;`, and `//` with everything after it on a line, become blanks — one space per
/// byte, so that every byte offset, line and column of the remaining program text is the file's
/// (diagnostics point into the file as it is).
pub fn strip_fixture_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for (i, line) in text.split('\n').enumerate() {
        if i > 0 {
            out.push('\n');
        }
        let cut = if line.trim_start().starts_with(';') {
            0
        } else {
            line.find("//").unwrap_or(line.len())
        };
        out.push_str(&line[..cut]);
        out.push_str(&" ".repeat(line.len() - cut));
    }
    out
}

/// Where a line of a lab program lies in its file: 1-based line number and the byte offset of its
/// first byte. Spans of a line's items are built from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LineAt {
    /// 1-based line number.
    pub line: u32,
    /// Byte offset of the line's first byte in the file.
    pub offset: u64,
}

impl LineAt {
    /// The span of `text[start..end]` (byte indices on character boundaries).
    pub fn span(&self, text: &str, start: usize, end: usize) -> Span {
        let column = text[..start].chars().count() as u32 + 1;
        Span::new(
            self.offset + start as u64,
            self.offset + end as u64,
            self.line,
            column,
        )
    }
}

/// The spans of one line's items, each in O(1): the character column of every byte index is
/// counted once per line. `LineAt::span` counts the characters before its start, so a line of
/// many words — a 1 MiB line holds 170,000 `G1 X1` — would cost the square of its length (a
/// minute of CPU, found by the mutation campaign).
pub(crate) struct LineSpans {
    at: LineAt,
    /// The whole line is ASCII: the column is the byte index + 1.
    ascii: bool,
    /// Otherwise: the number of characters that start before each byte index.
    chars_before: Vec<u32>,
}

impl LineSpans {
    /// Counts `text`'s columns once.
    pub(crate) fn new(at: LineAt, text: &str) -> Self {
        if text.is_ascii() {
            return LineSpans {
                at,
                ascii: true,
                chars_before: Vec::new(),
            };
        }
        let mut chars_before = Vec::with_capacity(text.len() + 1);
        let mut n = 0u32;
        for b in text.bytes() {
            chars_before.push(n);
            // A UTF-8 continuation byte (10xxxxxx) does not start a character.
            if b & 0xC0 != 0x80 {
                n += 1;
            }
        }
        chars_before.push(n);
        LineSpans {
            at,
            ascii: false,
            chars_before,
        }
    }

    /// The span of `text[start..end]`, as [`LineAt::span`] gives it (`text` is the line given to
    /// [`LineSpans::new`]; it stays a parameter so that both read alike).
    pub(crate) fn span(&self, _text: &str, start: usize, end: usize) -> Span {
        let column = if self.ascii {
            start as u32 + 1
        } else {
            self.chars_before[start] + 1
        };
        Span::new(
            self.at.offset + start as u64,
            self.at.offset + end as u64,
            self.at.line,
            column,
        )
    }
}

/// Skips ASCII blanks (space, tab) from `i`.
pub(crate) fn skip_blanks(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && (b[i] == b' ' || b[i] == b'\t') {
        i += 1;
    }
    i
}

/// The end of the character starting at byte `i` (for spans of unexpected characters).
pub(crate) fn char_end(text: &str, i: usize) -> usize {
    text[i..].chars().next().map_or(i, |c| i + c.len_utf8())
}
