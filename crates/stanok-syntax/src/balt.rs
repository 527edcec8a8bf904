//! Balt-System NC lexing (cvu-five-axis.md §2), for the 5-axis programs of the CVU manual.
//!
//! * `;` starts a comment to the end of the line.
//! * `N<int>` before the first word is the block number, written with or without a blank after
//!   it (`N9CVU=0`, `N8(DIS,"TEST8")`).
//! * `(…)` is a mnemonic block (`(DIS,"text")`, `(UCG,…)`, `(LCS,…)`, `(BSP,…)`, `(ESP)`): kept as a
//!   `Paren` comment with its text; the interpreter decides what it means.
//! * `CVU=<n>` and `MOVST=<n>` are assignment statements (keywords with a value).
//! * Every other word is a letter and a number; **a letter with no digits means 0** (`GXYZ` is
//!   `G0 X0 Y0 Z0`). Words may run together (`G1XY50ZF1000`). `T8.8` is tool 8, corrector 8 (the
//!   interpreter splits the number).
//!
//! Nothing here panics; an unexpected character is an error at its column and ends the line.

use crate::ast::{Address, Block, ColSpan, Comment, CommentKind, Keyword, Value, Word};
use crate::lexer::{skip_blanks, Pendings};
use crate::number::parse_number;

/// Parses one line into `out`.
pub(crate) fn parse_line(b: &[u8], out: &mut Block, diags: &mut Pendings) {
    let mut p = skip_blanks(b, 0);
    let mut first = true;
    while p < b.len() {
        let c = b[p];
        match c {
            b';' => {
                out.comments.push(Comment {
                    kind: CommentKind::Line,
                    text: ColSpan::new(p + 1, b.len()),
                });
                return;
            }
            b'(' => {
                let Some(close) = b[p..].iter().position(|&x| x == b')') else {
                    diags.error(
                        "balt::unclosed-mnemonic",
                        "a mnemonic block `(` has no closing `)`",
                        p,
                        b.len(),
                    );
                    return;
                };
                out.comments.push(Comment {
                    kind: CommentKind::Paren,
                    text: ColSpan::new(p + 1, p + close),
                });
                p += close + 1;
            }
            _ if c.is_ascii_alphabetic() => {
                let start = p;
                let upper = c.to_ascii_uppercase();
                // Assignment statements.
                for (name, kw) in [(&b"CVU"[..], Keyword::Cvu), (&b"MOVST"[..], Keyword::Movst)] {
                    let end = start + name.len();
                    if b.len() > end
                        && b[start..end].eq_ignore_ascii_case(name)
                        && b[skip_blanks(b, end)] == b'='
                    {
                        let at = skip_blanks(b, skip_blanks(b, end) + 1);
                        let Some(n) = parse_number(b, at, false) else {
                            diags.error(
                                "balt::missing-value",
                                "the assignment has no value",
                                start,
                                at,
                            );
                            return;
                        };
                        out.words.push(Word {
                            address: Address::Keyword {
                                keyword: kw,
                                index: None,
                            },
                            value: Value::Number(n.value),
                            span: ColSpan::new(start, n.end),
                        });
                        p = n.end;
                        first = false;
                        break;
                    }
                }
                if p != start {
                    p = skip_blanks(b, p);
                    continue;
                }
                let at = p + 1;
                let (value, end) = match parse_number(b, at, false) {
                    Some(n) => (n.value, n.end),
                    // A letter without digits means 0 (§2).
                    None => (0.0, at),
                };
                if upper == b'N' && first && out.number.is_none() {
                    if value.fract() != 0.0 || value < 0.0 {
                        diags.error("balt::block-number", "bad block number", start, end);
                        return;
                    }
                    out.number = Some(value as u32);
                    out.number_span = Some(ColSpan::new(start, end));
                } else {
                    out.words.push(Word {
                        address: Address::Letter(upper),
                        value: Value::Number(value),
                        span: ColSpan::new(start, end),
                    });
                    first = false;
                }
                p = end;
            }
            _ => {
                diags.error(
                    "balt::unexpected-character",
                    format!("unexpected character {:?}", c as char),
                    p,
                    p + 1,
                );
                return;
            }
        }
        p = skip_blanks(b, p);
    }
}
