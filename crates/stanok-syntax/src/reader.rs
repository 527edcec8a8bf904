//! Streaming: blocks out of any `BufRead + Seek`, one line at a time, in bounded memory.
//!
//! [`BlockReader`] keeps one line buffer (reused), the byte offset and number of the next line, and
//! a [`BlockParser`] with its cross-line state. Lines end with LF; a CR before the LF is dropped; the
//! last line may have no terminator. A line longer than [`MAX_LINE_BYTES`] is cut there (an error
//! says so) and the rest of it is skipped, so one huge line cannot exhaust memory.
//!
//! Invalid UTF-8 is replaced by U+FFFD (lossy) and reported once per line at the first bad byte;
//! after that point of such a line, `ColSpan`s index the repaired text, so their file offsets may be
//! off by a few bytes (the line and the block stay usable).
//!
//! [`SourcePos`] = offset + line number + parser state at the start of a line. `position()` before
//! `next_block()` and a later `seek()` to it re-read that line exactly as the first time, also when
//! it lies inside a multi-line AxiOMA `/* … */`: this is how the interpreter jumps back (loops,
//! subroutine calls) without keeping the program in memory.

use crate::ast::{Block, ColSpan, Dialect};
use crate::BlockParser;
use stanok_canon::Diagnostic;
use std::io::{BufRead, ErrorKind, Seek, SeekFrom};

/// Longest line kept by default (1 MiB); the rest of a longer line is skipped with an error.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Most bytes of a program read by default (1 GiB: a 10-million-block CAM program is about
/// 300 MB). Past it the reader stops with `syntax::program-too-large`: `/dev/zero` or a runaway
/// generator ends in about a second instead of never.
pub const MAX_PROGRAM_BYTES: u64 = 1 << 30;

/// Where a line starts, plus the parser's cross-line state there (AxiOMA `/* */` open across
/// lines), so that the interpreter can jump back to a line (RS274/NGC loops and subroutine calls).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SourcePos {
    /// Byte offset of the line's first byte.
    pub offset: u64,
    /// 1-based line number.
    pub line: u32,
    /// The line starts inside an AxiOMA `/* … */` comment.
    in_comment: bool,
}

impl SourcePos {
    /// The start of a program: offset 0, line 1, no open comment.
    pub fn start() -> Self {
        SourcePos {
            offset: 0,
            line: 1,
            in_comment: false,
        }
    }
}

/// Streams blocks out of any `BufRead + Seek` (a file, or `std::io::Cursor<&[u8]>`), line by line,
/// in bounded memory.
pub struct BlockReader<R: BufRead + Seek> {
    reader: R,
    parser: BlockParser,
    buf: Vec<u8>,
    offset: u64,
    line: u32,
    /// Longest line kept (`MAX_LINE_BYTES` unless set).
    max_line: usize,
    /// Most bytes read (`MAX_PROGRAM_BYTES` unless set).
    max_bytes: u64,
    /// The size bound was reached: everything after it is not read.
    exhausted: bool,
}

impl<R: BufRead + Seek> BlockReader<R> {
    /// A reader at the current position of `reader`, which is taken to be the start of the program
    /// (offset 0, line 1).
    pub fn new(reader: R, dialect: Dialect) -> Self {
        BlockReader {
            reader,
            parser: BlockParser::new(dialect),
            buf: Vec::new(),
            offset: 0,
            line: 1,
            max_line: MAX_LINE_BYTES,
            max_bytes: MAX_PROGRAM_BYTES,
            exhausted: false,
        }
    }

    /// Sets the longest line kept (at least 1 byte) and the most bytes of the program read.
    pub fn set_limits(&mut self, max_line_bytes: usize, max_program_bytes: u64) {
        self.max_line = max_line_bytes.max(1);
        self.max_bytes = max_program_bytes;
    }

    /// The dialect being read.
    pub fn dialect(&self) -> Dialect {
        self.parser.dialect()
    }

    /// Reads and parses the next line into `block`. `Ok(false)` at end of input. Lines end with LF
    /// or CRLF. Invalid UTF-8 is replaced (lossy) and reported as a diagnostic on that line.
    pub fn next_block(
        &mut self,
        block: &mut Block,
        diags: &mut Vec<Diagnostic>,
    ) -> std::io::Result<bool> {
        if self.exhausted {
            return Ok(false);
        }
        let (consumed, cut) = self.read_line()?;
        if consumed == 0 {
            return Ok(false);
        }
        let too_large = self.offset + consumed as u64 >= self.max_bytes && !self.at_end()?;
        if too_large {
            self.exhausted = true;
        }
        let line = self.line;
        let offset = self.offset;
        self.offset += consumed as u64;
        self.line = self.line.saturating_add(1);
        // The LF goes here; `parse_line` drops one CR before it (the same rule as `parse`).
        if self.buf.last() == Some(&b'\n') {
            self.buf.pop();
        }
        let first_diag = diags.len();
        let mut bad_at = None;
        // Hand the line buffer to the block as its text (no copy); the block's old text buffer
        // becomes the next line buffer. Both keep their capacity, so nothing is allocated.
        let bytes = std::mem::take(&mut self.buf);
        let mut spare = std::mem::take(&mut block.text).into_bytes();
        spare.clear();
        self.buf = spare;
        match into_string(bytes) {
            Ok(text) => block.text = text,
            Err(e) => {
                let valid = e.utf8_error().valid_up_to();
                let incomplete_tail = e.utf8_error().error_len().is_none();
                let mut bytes = e.into_bytes();
                if cut && incomplete_tail {
                    // The cut split a character: drop its first bytes rather than report them.
                    bytes.truncate(valid);
                } else {
                    bad_at = Some(valid);
                }
                block.text = String::from_utf8_lossy(&bytes).into_owned();
            }
        }
        self.parser.parse_text_in_place(line, offset, block, diags);
        if let Some(at) = bad_at {
            let at = at.min(block.text.len());
            let d = Diagnostic::error(
                "syntax::invalid-utf8",
                "invalid UTF-8: the bad bytes were replaced by `\u{FFFD}`",
                block.span_of(ColSpan::new(at, at + 1)),
            );
            diags.insert(first_diag, d);
        }
        // The bounds come first: they are why the line's text is cut, so the errors the parser
        // found in the cut text (an unclosed comment) are their consequence.
        if cut {
            let end = block.text.len();
            diags.insert(
                first_diag,
                Diagnostic::error(
                    "syntax::line-too-long",
                    format!(
                        "line longer than {} bytes: the rest of it is ignored",
                        self.max_line
                    ),
                    block.span_of(ColSpan::new(end, end)),
                )
                .with_note("the bound is the option --max-line-length (bytes)"),
            );
        }
        if too_large {
            let end = block.text.len();
            diags.insert(
                first_diag,
                Diagnostic::error(
                    "syntax::program-too-large",
                    format!(
                        "the program is larger than {} bytes: nothing after this point is read",
                        self.max_bytes
                    ),
                    block.span_of(ColSpan::new(end, end)),
                )
                .with_note("the bound is the option --max-program-size (bytes)")
                .fatal(),
            );
        }
        Ok(true)
    }

    /// The position of the NEXT line.
    pub fn position(&self) -> SourcePos {
        SourcePos {
            offset: self.offset,
            line: self.line,
            in_comment: self.parser.in_block_comment(),
        }
    }

    /// Moves to `pos` (got from [`BlockReader::position`] on this same input).
    pub fn seek(&mut self, pos: SourcePos) -> std::io::Result<()> {
        self.reader.seek(SeekFrom::Start(pos.offset))?;
        self.exhausted = false;
        self.offset = pos.offset;
        self.line = pos.line;
        self.parser.set_in_block_comment(pos.in_comment);
        Ok(())
    }

    /// True when the input has nothing more.
    fn at_end(&mut self) -> std::io::Result<bool> {
        loop {
            match self.reader.fill_buf() {
                Ok(a) => return Ok(a.is_empty()),
                Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            }
        }
    }

    /// Reads one line (with its LF, if any) into `buf`, keeping at most `max_line` bytes of it
    /// and reading no further than `max_bytes` into the program. Returns the bytes consumed from
    /// the input and whether the line was cut.
    fn read_line(&mut self) -> std::io::Result<(usize, bool)> {
        self.buf.clear();
        let mut consumed = 0;
        let mut cut = false;
        loop {
            let budget = self.max_bytes.saturating_sub(self.offset + consumed as u64);
            if budget == 0 {
                break;
            }
            let available = match self.reader.fill_buf() {
                Ok(a) => a,
                Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            if available.is_empty() {
                break;
            }
            let available = &available[..available
                .len()
                .min(usize::try_from(budget).unwrap_or(usize::MAX))];
            let (chunk, done) = match find_lf(available) {
                Some(i) => (&available[..=i], true),
                None => (available, false),
            };
            let room = self.max_line.saturating_sub(self.buf.len());
            let take = room.min(chunk.len());
            self.buf.extend_from_slice(&chunk[..take]);
            if take < chunk.len() {
                cut = true;
            }
            let n = chunk.len();
            self.reader.consume(n);
            consumed += n;
            if done {
                break;
            }
        }
        Ok((consumed, cut))
    }
}

/// `String::from_utf8`, with a fast path for the usual all-ASCII line: `is_ascii` checks eight bytes
/// at a time, where full UTF-8 validation (needed only for lines with non-ASCII bytes, e.g. Cyrillic
/// comments) costs several instructions per byte.
#[inline]
fn into_string(bytes: Vec<u8>) -> Result<String, std::string::FromUtf8Error> {
    if bytes.is_ascii() {
        // SAFETY: every byte is below 0x80, and an all-ASCII byte string is valid UTF-8.
        return Ok(unsafe { String::from_utf8_unchecked(bytes) });
    }
    String::from_utf8(bytes)
}

/// The index of the first LF in `b`, eight bytes at a time (a byte loop costs ~5 instructions per
/// byte, and every byte of the program passes through here).
///
/// SWAR "has zero byte": with `x = word ^ 0x0a0a…`, an LF byte is a zero byte of `x`, and
/// `(x - 0x0101…) & !x & 0x8080…` has its lowest set bit in the first zero byte (borrows can only
/// mark bytes above a zero byte, never below it).
#[inline]
fn find_lf(b: &[u8]) -> Option<usize> {
    const LO: u64 = 0x0101_0101_0101_0101;
    const HI: u64 = 0x8080_8080_8080_8080;
    let mut chunks = b.chunks_exact(8);
    let mut base = 0;
    for chunk in &mut chunks {
        let mut word = [0u8; 8];
        word.copy_from_slice(chunk);
        let x = u64::from_le_bytes(word) ^ (LO * b'\n' as u64);
        let zero = x.wrapping_sub(LO) & !x & HI;
        if zero != 0 {
            return Some(base + (zero.trailing_zeros() / 8) as usize);
        }
        base += 8;
    }
    chunks
        .remainder()
        .iter()
        .position(|&c| c == b'\n')
        .map(|i| base + i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn find_lf_finds_the_first_lf() {
        for len in 0..40 {
            for at in 0..=len {
                let mut b = vec![b'x'; len];
                // Bytes that a sloppy zero-byte test confuses with LF (0x0b = LF + 1, 0x8a, 0x0a ^ 0x80).
                for (i, c) in b.iter_mut().enumerate() {
                    *c = [b'x', 0x0b, 0x8a, 0x09, 0xff, 0x00][i % 6];
                }
                if at < len {
                    b[at] = b'\n';
                    if at + 1 < len {
                        b[at + 1] = b'\n';
                    }
                }
                let expected = b.iter().position(|&c| c == b'\n');
                assert_eq!(find_lf(&b), expected, "len {len} at {at}");
            }
        }
    }

    #[test]
    fn into_string_accepts_ascii_and_checks_the_rest() {
        assert_eq!(into_string(b"G1 X1".to_vec()).unwrap(), "G1 X1");
        assert_eq!(into_string("(Ж)".as_bytes().to_vec()).unwrap(), "(Ж)");
        assert!(into_string(vec![b'G', 0xff, b'1']).is_err());
    }
}
