//! Source locations.
//!
//! A [`Span`] names a byte range of the program text together with the line and column of its first
//! byte, so that a diagnostic can say `file:line:column` without re-reading the file, and a renderer
//! that does have the text can underline the exact bytes.

use serde::Serialize;

/// A byte range of the program text plus the 1-based line and column (in characters) of its start.
///
/// Invariant: `start <= end`; `line >= 1` and `column >= 1` for every span that came from a real
/// source (the default span, all zeros, means "no location").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
pub struct Span {
    /// Byte offset of the first byte, from the start of the file.
    pub start: u64,
    /// Byte offset one past the last byte.
    pub end: u64,
    /// 1-based line number of `start`.
    pub line: u32,
    /// 1-based column (in Unicode scalar values) of `start` within its line.
    pub column: u32,
}

impl Span {
    /// Builds a span.
    pub fn new(start: u64, end: u64, line: u32, column: u32) -> Self {
        Span {
            start,
            end: end.max(start),
            line,
            column,
        }
    }

    /// Length in bytes.
    pub fn len(&self) -> u64 {
        self.end - self.start
    }

    /// True for an empty range.
    pub fn is_empty(&self) -> bool {
        self.end == self.start
    }
}

/// A value together with the span of the text it came from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Spanned<T> {
    /// Where the value was written (for a `Canon`, the whole block that produced it).
    pub span: Span,
    /// The `N` label of that block, if it had one (printers show it, as LinuxCNC's `rs274` does).
    pub block_number: Option<u32>,
    /// Digits the `N` label was written with, leading zeros included (`N0080` → 4); 0 = as many
    /// as the number needs. LinuxCNC's `rs274` prints the label as written.
    #[serde(skip)]
    pub label_digits: u8,
    /// The value.
    pub value: T,
}

impl<T> Spanned<T> {
    /// Pairs a value with its span (no block number).
    pub fn new(span: Span, value: T) -> Self {
        Spanned {
            span,
            block_number: None,
            label_digits: 0,
            value,
        }
    }
}
