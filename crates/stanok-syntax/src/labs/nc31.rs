//! One Elektronika NC-31 frame per line (spec lab-collection §2.2, §2.3).
//!
//! Grammar read here (the spec's lenient fixture grammar, both notations of the document):
//!
//! ```text
//! line     = frame-no [ body ]          | "L" digits (subprogram header) | blank
//! frame-no = "N" digits                 ("№" is typography; fixtures write N)
//! body     = [ chamfer ] [ "~" ] address [ label ] [ value ] { suffix }
//! chamfer  = ("+" | "-" | "~") "45" [ "°" ]
//! address  = G F X Z P M S T L R
//! label    = "1" | "2" directly after P and before a sign ("P1+53000": first/second P)
//! value    = [ "+" | "-" ] digits        (blanks allowed between address, sign and digits)
//! suffix   = "*" (group) | "#" (incremental) | "BX" (rapid) | "(OACO)" | "(ОАСО)" (incremental)
//! ```
//!
//! Blanks may stand between any two items. The NC-31 has no comment syntax: anything else on the
//! line is an `nc31::syntax` error at that character (the frame read so far is kept, as every
//! reader here does; the interpreter refuses a frame with an error).

use super::{char_end, skip_blanks, LineAt};
use stanok_canon::{Diagnostic, Span};

/// The ±45° chamfer flag of a single-axis frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Chamfer {
    /// `+45`: the other axis moves in its plus direction.
    Plus,
    /// `-45` / `-45°`: the other axis moves in its minus direction.
    Minus,
    /// `~45°` (flange listing N144): printed once, meaning unknown.
    Unknown,
}

/// The part of a frame after its number.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// The chamfer flag, if any.
    pub chamfer: Option<Chamfer>,
    /// RAPID (`~` before the address, `BX` after the value).
    pub rapid: bool,
    /// The address letter (upper case ASCII).
    pub address: u8,
    /// Where the address is.
    pub address_span: Span,
    /// `P1` / `P2` label of a P frame (the Lab 3 sample), not part of the value.
    pub label: Option<u8>,
    /// The signed integer value; None when the frame has none (`~X`).
    pub value: Option<i64>,
    /// Where the value is (the address when there is none).
    pub value_span: Span,
    /// `*`: the frame continues a group.
    pub group: bool,
    /// ОАСО (`(OACO)`, `(ОАСО)`, `#`): the value is an increment.
    pub incremental: bool,
}

/// What one line holds.
#[derive(Debug, Clone, PartialEq)]
pub enum Line {
    /// Nothing (blank, or blanked-out fixture comments).
    Empty,
    /// `L01`: the first line of a subprogram (its number).
    Header {
        /// Subprogram number.
        number: u32,
        /// The header's text.
        span: Span,
    },
    /// A frame.
    Frame {
        /// Its N number.
        number: u32,
        /// The whole frame's text.
        span: Span,
        /// Address, value and flags; None for an empty frame (`N195`).
        body: Option<Body>,
    },
}

/// Largest frame number (spec §2.2: 249, raised by a machine parameter to at most 999).
pub const MAX_FRAME_NUMBER: u32 = 999;

/// Largest magnitude of a value (spec §2.2: ±999999).
pub const MAX_VALUE: i64 = 999_999;

/// Reads one line. Never fails: problems are diagnostics (errors) next to what was read.
pub fn parse_line(text: &str, at: LineAt) -> (Line, Vec<Diagnostic>) {
    let at = super::LineSpans::new(at, text);
    let mut diags = Vec::new();
    let b = text.as_bytes();
    let start = skip_blanks(b, 0);
    let end = text.trim_end().len();
    if start >= end {
        return (Line::Empty, diags);
    }
    let whole = at.span(text, start, end);
    let err = |diags: &mut Vec<Diagnostic>, s: usize, e: usize, msg: String| {
        diags.push(Diagnostic::error("nc31::syntax", msg, at.span(text, s, e)));
    };
    // Subprogram header `L01`.
    if b[start] == b'L' {
        let d = digits(b, start + 1);
        if d > start + 1 && skip_blanks(b, d) >= end {
            let number = text[start + 1..d].parse().unwrap_or(u32::MAX);
            return (
                Line::Header {
                    number,
                    span: whole,
                },
                diags,
            );
        }
    }
    let mut i = start;
    if text[i..].starts_with('№') {
        i += '№'.len_utf8();
    } else if b[i] == b'N' {
        i += 1;
    } else {
        err(
            &mut diags,
            start,
            char_end(text, start),
            "an NC-31 frame starts with its number N".into(),
        );
        return (Line::Empty, diags);
    }
    let d = digits(b, i);
    if d == i || d - i > 4 {
        err(
            &mut diags,
            start,
            d.max(i),
            "frame number N needs 1 to 4 digits".into(),
        );
        return (Line::Empty, diags);
    }
    let number: u32 = text[i..d].parse().unwrap_or(0);
    // Frame numbers run 0…249, a machine parameter raises the maximum to 999 (§2.2; the flange
    // listing uses N99…N321, so the raised maximum is the one that reads the lab's programs).
    if number > MAX_FRAME_NUMBER {
        err(
            &mut diags,
            start,
            d,
            format!("frame number N{number} is above {MAX_FRAME_NUMBER}, the NC-31's largest"),
        );
        return (Line::Empty, diags);
    }
    i = skip_blanks(b, d);
    if i >= end {
        return (
            Line::Frame {
                number,
                span: whole,
                body: None,
            },
            diags,
        );
    }
    // Chamfer flag.
    let mut chamfer = None;
    if matches!(b[i], b'+' | b'-' | b'~') && text[i + 1..].starts_with("45") {
        chamfer = Some(match b[i] {
            b'+' => Chamfer::Plus,
            b'-' => Chamfer::Minus,
            _ => Chamfer::Unknown,
        });
        i += 3;
        if text[i..].starts_with('°') {
            i += '°'.len_utf8();
        }
        i = skip_blanks(b, i);
    }
    let mut rapid = false;
    if i < end && b[i] == b'~' {
        rapid = true;
        i = skip_blanks(b, i + 1);
    }
    if i >= end || !b"GFXZPMSTLR".contains(&b[i]) {
        let e = if i >= end { end } else { char_end(text, i) };
        err(
            &mut diags,
            i.min(end),
            e,
            "expected one of the NC-31 addresses G F X Z P M S T L R".into(),
        );
        return (
            Line::Frame {
                number,
                span: whole,
                body: None,
            },
            diags,
        );
    }
    let address = b[i];
    let address_span = at.span(text, i, i + 1);
    i += 1;
    let mut label = None;
    if address == b'P'
        && i + 1 < end
        && matches!(b[i], b'1' | b'2')
        && matches!(b[i + 1], b'+' | b'-')
    {
        label = Some(b[i] - b'0');
        i += 1;
    }
    // Value: [sign] blanks digits.
    let mut value = None;
    let mut value_span = address_span;
    let vs = skip_blanks(b, i);
    let mut j = vs;
    let mut negative = false;
    if j < end && matches!(b[j], b'+' | b'-') {
        negative = b[j] == b'-';
        j = skip_blanks(b, j + 1);
    }
    let de = digits(b, j);
    if de > j {
        value_span = at.span(text, vs, de);
        match text[j..de].parse::<i64>() {
            Ok(v) if v <= MAX_VALUE => value = Some(if negative { -v } else { v }),
            _ => err(
                &mut diags,
                vs,
                de,
                format!("a value is at most {MAX_VALUE} in magnitude"),
            ),
        }
        i = de;
    } else if j > vs {
        err(&mut diags, vs, j, "a sign without digits".into());
        i = j;
    }
    // Suffixes.
    let mut group = false;
    let mut incremental = false;
    loop {
        i = skip_blanks(b, i);
        if i >= end {
            break;
        }
        let rest = &text[i..];
        if b[i] == b'*' {
            group = true;
            i += 1;
        } else if b[i] == b'#' {
            incremental = true;
            i += 1;
        } else if rest.starts_with("BX") {
            rapid = true;
            i += 2;
        } else if let Some(n) = ["(OACO)", "(ОАСО)"]
            .iter()
            .find(|f| rest.starts_with(**f))
            .map(|f| f.len())
        {
            incremental = true;
            i += n;
        } else {
            err(
                &mut diags,
                i,
                char_end(text, i),
                format!(
                    "unexpected `{}`: an NC-31 frame holds one address and its flags",
                    rest.chars().next().unwrap_or(' ')
                ),
            );
            break;
        }
    }
    let body = Body {
        chamfer,
        rapid,
        address,
        address_span,
        label,
        value,
        value_span,
        group,
        incremental,
    };
    (
        Line::Frame {
            number,
            span: whole,
            body: Some(body),
        },
        diags,
    )
}

/// One past the last ASCII digit from `i`.
fn digits(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    i
}
