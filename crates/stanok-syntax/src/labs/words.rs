//! Word-address lines of the 2P32, MC2101 and GOST-20999 controls (spec lab-collection §3, §4).
//!
//! A line is `[/] [N… | :…] word…` where a word is a letter, optional blanks, an optional sign,
//! optional blanks and a number with an optional decimal point (`Z - 200000`, `X-126.`, `X.14`),
//! or a variable (`X-R1`, `FR4`). The number is kept *as written* (value of its digits and whether
//! it had a point): what a digit is worth (0.001 mm, 0.01 mm, mm) is the interpreter's business.
//!
//! Per control ([`Profile`]):
//! * GOST-20999: `R<n>#<value>` assigns a variable; `:` main frame; `/` block skip; no comments
//!   (a `(` is an error).
//! * 2P32: `( … )` comments; `%n` program start; the document's `ПС` line (line feed) is an empty
//!   line; `R<n> <signed value>` assigns a parameter (`R27 - 4910`, `R25+1`, as printed); `ω`
//!   (Greek omega, jump conditions) is read as a word letter.
//! * MC2101: `( … )` holds the printed alternatives (`( R+53000)`), read as comments; `LF` ends the
//!   block.
//!
//! Reading never fails: an unreadable character is an `lab::syntax` error and the rest of the line
//! is dropped.

use super::{char_end, skip_blanks, LineAt};
use stanok_canon::{Diagnostic, Span};

/// Which control's conventions apply.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// The GOST 20999-83 control of section 6.3.
    Gost20999,
    /// The 2P32 turning-milling centre.
    P2p32,
    /// The Elektronika MC2101 notation.
    Mc2101,
}

/// A number as written: the value of its digits (`39.` → 39, `4910` → 4910, `.14` → 0.14) with its
/// sign, and whether it had a decimal point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number {
    /// Signed value of the digits.
    pub value: f64,
    /// A decimal point was written.
    pub point: bool,
}

/// A word's value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A number.
    Number(Number),
    /// A variable: `R<n>`, negated when written `-R<n>`.
    Variable {
        /// Variable number.
        number: u32,
        /// `-R1`.
        negative: bool,
    },
}

/// One word.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// Its letter (upper case; `ω` for the 2P32 jump condition).
    pub letter: char,
    /// Its value; None for a bare letter (the 2P32's `G` = G0).
    pub value: Option<Value>,
    /// The word's text.
    pub span: Span,
}

/// `R<n>#<value>` (GOST-20999) or `R<n> <signed value>` (2P32).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assignment {
    /// Variable number.
    pub number: u32,
    /// The value assigned.
    pub value: Number,
    /// The assignment's text.
    pub span: Span,
}

/// An item of a line in written order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Item {
    /// A word.
    Word(Word),
    /// A variable assignment.
    Assign(Assignment),
}

/// What a line holds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LabBlock {
    /// `/` block skip.
    pub skip: bool,
    /// `:` main frame (restart point) instead of N.
    pub main_frame: bool,
    /// The frame number (N or `:`).
    pub number: Option<u32>,
    /// `%n`: a program start line, with its number.
    pub percent: Option<u32>,
    /// Words and assignments in written order (N excluded).
    pub items: Vec<Item>,
    /// The comments' texts (2P32, MC2101).
    pub comments: Vec<String>,
    /// The line's text without its terminator.
    pub span: Span,
}

impl LabBlock {
    /// True when the line holds nothing to execute.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty() && self.number.is_none() && self.percent.is_none()
    }
}

/// Reads one line.
pub fn parse_line(text: &str, at: LineAt, profile: Profile) -> (LabBlock, Vec<Diagnostic>) {
    let at = super::LineSpans::new(at, text);
    let mut block = LabBlock {
        span: at.span(text, 0, text.len()),
        ..LabBlock::default()
    };
    let mut diags = Vec::new();
    let b = text.as_bytes();
    let end = text.trim_end().len();
    let mut i = skip_blanks(b, 0).min(end);
    let err = |diags: &mut Vec<Diagnostic>, s: usize, e: usize, msg: &str| {
        diags.push(Diagnostic::error(
            "lab::syntax",
            msg.to_string(),
            at.span(text, s, e),
        ));
    };
    if profile == Profile::P2p32 && text[i..end].starts_with("ПС") {
        // The document's notation of the leading line feed (spec §3.2).
        i = skip_blanks(b, i + "ПС".len());
    }
    if i < end && b[i] == b'%' {
        let s = skip_blanks(b, i + 1);
        let d = digits(b, s);
        block.percent = Some(text[s..d].parse().unwrap_or(0));
        i = d;
    }
    if i < end && b[i] == b'/' {
        block.skip = true;
        i = skip_blanks(b, i + 1);
    }
    if i < end && (b[i] == b'N' || b[i] == b':') {
        block.main_frame = b[i] == b':';
        let s = skip_blanks(b, i + 1);
        let d = digits(b, s);
        if d == s || d - s > 4 {
            err(
                &mut diags,
                i,
                d.max(i + 1),
                "a frame number needs 1 to 4 digits",
            );
            return (block, diags);
        }
        block.number = text[s..d].parse().ok();
        i = d;
    }
    while i < end {
        i = skip_blanks(b, i);
        if i >= end {
            break;
        }
        if block.items.len() >= crate::MAX_WORDS_PER_BLOCK {
            diags.push(Diagnostic::error(
                "syntax::too-many-words",
                format!(
                    "more than {} words in one block",
                    crate::MAX_WORDS_PER_BLOCK
                ),
                at.span(text, i, end),
            ));
            break;
        }
        let c = b[i];
        if c == b'(' && profile != Profile::Gost20999 {
            match text[i..end].find(')') {
                Some(close) => {
                    block.comments.push(text[i + 1..i + close].to_string());
                    i += close + 1;
                    continue;
                }
                None => {
                    err(&mut diags, i, end, "`(` without `)`");
                    break;
                }
            }
        }
        if profile == Profile::Mc2101 && text[i..end].starts_with("LF") {
            // End of block; nothing may follow it.
            let after = skip_blanks(b, i + 2);
            if after < end {
                err(&mut diags, after, end, "text after the end of block LF");
            }
            break;
        }
        let (letter, len) = if c.is_ascii_alphabetic() {
            (c.to_ascii_uppercase() as char, 1)
        } else if text[i..].starts_with('ω') {
            ('ω', 'ω'.len_utf8())
        } else {
            err(
                &mut diags,
                i,
                char_end(text, i),
                "expected a word: a letter and a number",
            );
            break;
        };
        let ws = i;
        i += len;
        // Assignments: `R12#-15.5` (GOST-20999), `R27 - 4910` / `R25+1` (2P32).
        if letter == 'R' {
            let d = digits(b, i);
            if d > i {
                let n: u32 = text[i..d].parse().unwrap_or(u32::MAX);
                let after = skip_blanks(b, d);
                let gost = profile == Profile::Gost20999 && after < end && b[after] == b'#';
                let p2p32 =
                    profile == Profile::P2p32 && after < end && matches!(b[after], b'+' | b'-');
                if gost || p2p32 {
                    let vs = if gost { after + 1 } else { after };
                    match number(text, vs, end) {
                        Some((value, e)) => {
                            block.items.push(Item::Assign(Assignment {
                                number: n,
                                value,
                                span: at.span(text, ws, e),
                            }));
                            i = e;
                        }
                        None => {
                            err(
                                &mut diags,
                                ws,
                                end.min(vs + 1),
                                "an assignment needs a value",
                            );
                            break;
                        }
                    }
                    continue;
                }
            }
        }
        // A word's value: [sign] (number | R<n>).
        let mut j = skip_blanks(b, i);
        let mut negative = false;
        let signed = j < end && matches!(b[j], b'+' | b'-');
        if signed {
            negative = b[j] == b'-';
            j = skip_blanks(b, j + 1);
        }
        if j < end && b[j] == b'R' && j + 1 < end && b[j + 1].is_ascii_digit() && letter != 'R' {
            let d = digits(b, j + 1);
            let n = text[j + 1..d].parse().unwrap_or(u32::MAX);
            block.items.push(Item::Word(Word {
                letter,
                value: Some(Value::Variable {
                    number: n,
                    negative,
                }),
                span: at.span(text, ws, d),
            }));
            i = d;
            continue;
        }
        match number(text, if signed { i } else { j }, end) {
            Some((n, e)) => {
                block.items.push(Item::Word(Word {
                    letter,
                    value: Some(Value::Number(n)),
                    span: at.span(text, ws, e),
                }));
                i = e;
            }
            None if signed => {
                err(&mut diags, ws, j.max(ws + len), "a sign without digits");
                break;
            }
            None => {
                block.items.push(Item::Word(Word {
                    letter,
                    value: None,
                    span: at.span(text, ws, ws + len),
                }));
            }
        }
    }
    (block, diags)
}

/// A signed number from `i` (blanks allowed after the sign): its value and end. None without
/// digits.
fn number(text: &str, i: usize, end: usize) -> Option<(Number, usize)> {
    let b = text.as_bytes();
    let mut j = skip_blanks(b, i);
    let mut negative = false;
    if j < end && matches!(b[j], b'+' | b'-') {
        negative = b[j] == b'-';
        j = skip_blanks(b, j + 1);
    }
    let s = j;
    let d = digits(b, j);
    let mut e = d;
    let mut point = false;
    if e < end && b[e] == b'.' {
        point = true;
        e = digits(b, e + 1);
    }
    if d == s && e <= d + 1 {
        return None;
    }
    let v: f64 = text[s..e].parse().ok()?;
    Some((
        Number {
            value: if negative { -v } else { v },
            point,
        },
        e,
    ))
}

/// One past the last ASCII digit from `i`.
fn digits(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    i
}
