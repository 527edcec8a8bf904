//! Byte-level helpers shared by both dialects, and the pending-diagnostic record.
//!
//! Why bytes: every character that has a meaning outside comments and strings is ASCII in both
//! dialects, so the parsers walk `&[u8]` and compare case-insensitively byte by byte (no
//! `to_uppercase()`, no allocation). Non-ASCII bytes (UTF-8 Cyrillic in comments) are only ever
//! skipped over or reported; since every position where a parser stops is at an ASCII byte (or at
//! the end of the line), every `ColSpan` produced lies on UTF-8 character boundaries.
//!
//! Diagnostics are collected as [`Pending`] records holding a [`ColSpan`], because the line's text
//! is moved out of the `Block` while the parser fills the block's vectors (so that the text can be
//! read while the vectors are mutated). Once the text is back, `BlockParser` turns each record into
//! a [`stanok_canon::Diagnostic`] with `Block::span_of`.

use crate::ast::ColSpan;
use stanok_canon::Severity;
use std::borrow::Cow;

/// A diagnostic found while parsing a line, not yet attached to an absolute span.
#[derive(Debug, Clone)]
pub(crate) struct Pending {
    pub severity: Severity,
    pub code: &'static str,
    pub message: Cow<'static, str>,
    pub span: ColSpan,
}

/// The diagnostics of one line, in the order found.
#[derive(Debug, Default)]
pub(crate) struct Pendings(pub Vec<Pending>);

impl Pendings {
    /// Records an error on bytes `start..end` of the line.
    pub fn error(
        &mut self,
        code: &'static str,
        message: impl Into<Cow<'static, str>>,
        start: usize,
        end: usize,
    ) {
        self.0.push(Pending {
            severity: Severity::Error,
            code,
            message: message.into(),
            span: ColSpan::new(start, end.max(start)),
        });
    }

    /// Records a warning on bytes `start..end` of the line.
    pub fn warning(
        &mut self,
        code: &'static str,
        message: impl Into<Cow<'static, str>>,
        start: usize,
        end: usize,
    ) {
        self.0.push(Pending {
            severity: Severity::Warning,
            code,
            message: message.into(),
            span: ColSpan::new(start, end.max(start)),
        });
    }
}

/// Blank characters that separate words (space, tab, and the other ASCII whitespace; a stray
/// carriage return inside a line counts as blank too).
#[inline(always)]
pub(crate) fn is_blank(c: u8) -> bool {
    // A table: one load and test where space-or-TAB…CR (9..=13) took two compares and a branch
    // on every character after a number (the usual case: not blank).
    BLANK[c as usize]
}

/// Space and TAB LF VT FF CR (9..=13).
const BLANK: [bool; 256] = {
    let mut t = [false; 256];
    t[b' ' as usize] = true;
    let mut c = b'\t';
    while c <= b'\r' {
        t[c as usize] = true;
        c += 1;
    }
    t
};

/// The first position at or after `p` that is not blank.
#[inline(always)]
pub(crate) fn skip_blanks(b: &[u8], mut p: usize) -> usize {
    while p < b.len() && is_blank(b[p]) {
        p += 1;
    }
    p
}

/// The end of the run of ASCII letters starting at `p`.
#[inline(always)]
pub(crate) fn letters_end(b: &[u8], mut p: usize) -> usize {
    while p < b.len() && b[p].is_ascii_alphabetic() {
        p += 1;
    }
    p
}

/// The end of the run of ASCII digits starting at `p`.
#[inline(always)]
pub(crate) fn digits_end(b: &[u8], mut p: usize) -> usize {
    while p < b.len() && b[p].is_ascii_digit() {
        p += 1;
    }
    p
}

/// The position of the first occurrence of `needle` in `b` at or after `from`.
pub(crate) fn find(b: &[u8], from: usize, needle: &[u8]) -> Option<usize> {
    if from > b.len() || needle.is_empty() {
        return None;
    }
    let first = needle[0];
    let mut i = from;
    while i + needle.len() <= b.len() {
        match b[i..].iter().position(|&c| c == first) {
            None => return None,
            Some(k) => {
                i += k;
                if i + needle.len() <= b.len() && &b[i..i + needle.len()] == needle {
                    return Some(i);
                }
                i += 1;
            }
        }
    }
    None
}

/// The position of the first byte `c` at or after `from`.
#[inline]
pub(crate) fn find_byte(b: &[u8], from: usize, c: u8) -> Option<usize> {
    b.get(from..)?
        .iter()
        .position(|&x| x == c)
        .map(|k| k + from)
}

/// `b[start..end]` shown in a message: at most 24 characters, cut on a character boundary.
pub(crate) fn excerpt(b: &[u8], start: usize, end: usize) -> String {
    let s = String::from_utf8_lossy(&b[start.min(b.len())..end.min(b.len())]);
    let mut out: String = s.chars().take(24).collect();
    if s.chars().count() > 24 {
        out.push('…');
    }
    out
}

/// The end of the UTF-8 character that starts at `p` (so that a skipped run never splits one).
pub(crate) fn char_end(b: &[u8], p: usize) -> usize {
    let mut q = p + 1;
    while q < b.len() && (b[q] & 0xC0) == 0x80 {
        q += 1;
    }
    q.min(b.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blanks() {
        let blanks: Vec<u8> = (0..=255u8).filter(|&c| is_blank(c)).collect();
        assert_eq!(blanks, b"\t\n\x0b\x0c\r ");
    }

    #[test]
    fn find_finds_needles() {
        assert_eq!(find(b"ab*/cd*/", 0, b"*/"), Some(2));
        assert_eq!(find(b"ab*/cd*/", 3, b"*/"), Some(6));
        assert_eq!(find(b"ab*", 0, b"*/"), None);
        assert_eq!(find(b"", 0, b"*/"), None);
        assert_eq!(find(b"ab", 5, b"*/"), None);
        assert_eq!(find(b"**/", 0, b"*/"), Some(1));
    }

    #[test]
    fn excerpt_is_short_and_char_safe() {
        let s = "Ж".repeat(40);
        let e = excerpt(s.as_bytes(), 0, s.len());
        assert_eq!(e.chars().count(), 25);
        assert!(e.ends_with('…'));
    }

    #[test]
    fn char_end_skips_continuation_bytes() {
        let s = "aЖb".as_bytes();
        assert_eq!(char_end(s, 0), 1);
        assert_eq!(char_end(s, 1), 3);
        assert_eq!(char_end(s, 3), 4);
    }
}
