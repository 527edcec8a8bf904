//! Decimal numbers of G-code, parsed by hand.
//!
//! Grammar (both dialects): `[+|-] digits [ . [digits] ]` or `[+|-] . digits`, at least one digit,
//! no exponent (`E` is an address letter). RS274/NGC also ignores blanks anywhere inside a number
//! (`1 . 5` is `1.5`, because LinuxCNC deletes all blanks outside comments); AxiOMA does not.
//!
//! Algorithm (Clinger's fast path): the digits before and after the point are accumulated into one
//! `u64` mantissa `m`; `f` is the number of digits after the point. With at most 15 digits in all,
//! `m < 10^15 < 2^52` and `f <= 15`, so both `m` and `10^f` are exactly representable as `f64`
//! and the single IEEE division `m / 10^f` rounds once: the correctly rounded result,
//! bit-identical to `str::parse::<f64>` (the proptests check this). Longer numbers (16+ digits,
//! leading zeros included: rare in G-code) fall back to `str::parse::<f64>` on the same text, also
//! correctly rounded; that path may allocate when the number contains blanks (RS274/NGC
//! `1 2 . 5`, read by `parse_spaced`). Digits past the 19th wrap the `u64` mantissa, which is then
//! unused; `integer` is only given for at most 19 digits.
//!
//! `str::parse` is not used on the hot path because it is several times slower than this loop on
//! the short numbers of G-code (`12.345`, `-6.789`, `1200`).

/// A number read from the text.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Number {
    /// Its value (`-0.0` for `-0`).
    pub value: f64,
    /// One past its last digit or point (blanks after it are not included).
    pub end: usize,
    /// `end` moved past the blanks that follow the number (where the next item starts).
    pub next: usize,
    /// `Some(n)` when it was written as unsigned digits only (no sign, no point) and fits a `u64`:
    /// such a number can be an index (`S2=`), a block number or an O-word label.
    pub integer: Option<u64>,
}

/// Exact powers of ten representable in an `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `m as f64` for `m < 2^52`, exactly, without `cvtsi2sd`: that instruction only writes the low
/// half of its register and so waits for the previous number's division (a false dependency that
/// serialised consecutive numbers: measured ~25% of the parse). `2^52 + m` has `m` as its
/// mantissa bits; subtracting `2^52` is exact.
#[inline(always)]
fn exact_f64(m: u64) -> f64 {
    const TWO_52: u64 = 0x4330_0000_0000_0000; // 2^52 as f64 bits
    f64::from_bits(TWO_52 | m) - 4_503_599_627_370_496.0
}

/// Reads digits with at most one point in them, starting at `p`, into one mantissa (wrapping past
/// 19 digits; the caller checks the count). Returns the mantissa, the end of the run and where the
/// point is (`usize::MAX` for none).
///
/// Two plain loops, one per half of the number, each with a single induction variable: a digit
/// costs a load, a compare, the multiply-add and the bounds check that is the loop condition. (A
/// plain byte loop: measured faster here than an 8-bytes-at-a-time (SWAR) version, whose multiply
/// chains and end-of-line handling cost more than they save on numbers as short as G-code's.)
#[inline(always)]
fn mantissa_run(b: &[u8], start: usize) -> (u64, usize, usize) {
    let mut m: u64 = 0;
    let mut p = start;
    while p < b.len() {
        let d = b[p].wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        m = m.wrapping_mul(10).wrapping_add(d as u64);
        p += 1;
    }
    if p >= b.len() || b[p] != b'.' {
        return (m, p, usize::MAX);
    }
    let point_at = p;
    p += 1;
    while p < b.len() {
        let d = b[p].wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        m = m.wrapping_mul(10).wrapping_add(d as u64);
        p += 1;
    }
    (m, p, point_at)
}

/// Reads a number starting exactly at `start` (no leading blanks are skipped). With `blanks`, blanks
/// between the sign, the digits and the point are skipped (RS274/NGC). `None` when there is no
/// digit (a lone sign or point, or no number at all).
///
/// The fast path reads contiguous text in one tight loop ([`mantissa_run`]); only when `blanks` is
/// set and a blank is followed by more of the number does [`parse_spaced`] run.
#[inline(always)]
pub(crate) fn parse_number(b: &[u8], start: usize, blanks: bool) -> Option<Number> {
    let first = b.get(start).copied().unwrap_or(0);
    let negative = first == b'-';
    let signed = negative | (first == b'+');
    let digits_start = start + signed as usize;
    let (mantissa, end, point_at) = mantissa_run(b, digits_start);
    let point = point_at != usize::MAX;
    let next = crate::lexer::skip_blanks(b, end);
    // Usually a letter follows (`X1 Y2`): `<= b'9'` rules letters out with one compare.
    if blanks && next > end && next < b.len() && b[next] <= b'9' && continues_number(b[next], point)
    {
        // More of the number after blanks (`1 . 5`, `- 2`): take the general path.
        return parse_spaced(b, start);
    }
    let digits = end - digits_start - point as usize;
    if digits == 0 {
        return None;
    }
    let frac_digits = if point { end - point_at - 1 } else { 0 };
    // At most 15 digits: `m < 10^15 < 2^52` and `f <= 15`, so `m` and `10^f` are exact.
    let value = if digits <= 15 {
        // `frac_digits <= digits <= 15`: the mask only spares the bounds check.
        let v = exact_f64(mantissa) / POW10[frac_digits & 15];
        if negative {
            -v
        } else {
            v
        }
    } else {
        slow_parse(&b[start..end], false)
    };
    Some(Number {
        value,
        end,
        next,
        integer: (!signed && !point && digits <= 19).then_some(mantissa),
    })
}

/// True when `c`, found after blanks that follow a number, continues that number (RS274/NGC reads
/// `1 . 5` as `1.5`): a digit, or a point if the number has none yet.
#[inline(always)]
fn continues_number(c: u8, point: bool) -> bool {
    c.is_ascii_digit() || (c == b'.' && !point)
}

/// The general form of [`parse_number`] with blanks allowed inside the number (same fast path).
#[cold]
fn parse_spaced(b: &[u8], start: usize) -> Option<Number> {
    let len = b.len();
    let mut p = start;
    let negative = b.get(p) == Some(&b'-');
    let signed = negative || b.get(p) == Some(&b'+');
    p += signed as usize;
    let mut digits = 0usize;
    let mut frac_digits = 0usize;
    let mut mantissa: u64 = 0;
    let mut point = false;
    let mut end = p;
    while p < len {
        let c = b[p];
        if c.is_ascii_digit() {
            digits += 1;
            frac_digits += point as usize;
            mantissa = mantissa.wrapping_mul(10).wrapping_add((c - b'0') as u64);
            p += 1;
            end = p;
        } else if c == b'.' && !point {
            point = true;
            p += 1;
            end = p;
        } else if crate::lexer::is_blank(c) {
            // Only part of the number if a digit or the point follows.
            let q = crate::lexer::skip_blanks(b, p);
            if q < len && (b[q].is_ascii_digit() || (b[q] == b'.' && !point)) {
                p = q;
            } else {
                break;
            }
        } else {
            break;
        }
    }
    if digits == 0 {
        return None;
    }
    let value = if digits <= 15 {
        let v = exact_f64(mantissa) / POW10[frac_digits];
        if negative {
            -v
        } else {
            v
        }
    } else {
        slow_parse(&b[start..end], true)
    };
    Some(Number {
        value,
        end,
        next: crate::lexer::skip_blanks(b, end),
        integer: (!signed && !point && digits <= 19).then_some(mantissa),
    })
}

/// Reads unsigned digits starting exactly at `start` (with `blanks`, blanks between digits are
/// skipped). Returns the value (`None` if it does not fit a `u64`) and the end of the last digit;
/// `None` when there is no digit.
pub(crate) fn parse_digits(b: &[u8], start: usize, blanks: bool) -> Option<(Option<u64>, usize)> {
    let mut p = start;
    let mut value: Option<u64> = Some(0);
    let mut end = start;
    while p < b.len() {
        let c = b[p];
        if c.is_ascii_digit() {
            value = value
                .and_then(|v| v.checked_mul(10))
                .and_then(|v| v.checked_add((c - b'0') as u64));
            p += 1;
            end = p;
        } else if blanks && crate::lexer::is_blank(c) {
            p += 1;
        } else {
            break;
        }
    }
    (end > start).then_some((value, end))
}

/// Correctly rounded fallback for long numbers. `text` is ASCII digits, sign, point and blanks.
#[cold]
fn slow_parse(text: &[u8], has_blanks: bool) -> f64 {
    let parsed = if has_blanks {
        let s: String = text
            .iter()
            .filter(|c| !crate::lexer::is_blank(**c))
            .map(|&c| c as char)
            .collect();
        s.parse::<f64>()
    } else {
        std::str::from_utf8(text).unwrap_or("").parse::<f64>()
    };
    // The grammar above is a subset of what `str::parse` accepts, so this cannot fail; NaN is the
    // harmless answer if it ever did.
    parsed.unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn num(s: &str) -> Option<(f64, usize, Option<u64>)> {
        parse_number(s.as_bytes(), 0, false).map(|n| (n.value, n.end, n.integer))
    }

    #[test]
    fn word_forms() {
        assert_eq!(num("105.5"), Some((105.5, 5, None)));
        assert_eq!(num(".5"), Some((0.5, 2, None)));
        assert_eq!(num("-.5"), Some((-0.5, 3, None)));
        assert_eq!(num("+05.50"), Some((5.5, 6, None)));
        assert_eq!(num("10"), Some((10.0, 2, Some(10))));
        assert_eq!(num("01"), Some((1.0, 2, Some(1))));
        assert_eq!(num("95.PL"), Some((95.0, 3, None)));
        assert_eq!(num("1.5.5"), Some((1.5, 3, None)));
        assert_eq!(num("-12.345X"), Some((-12.345, 7, None)));
        assert_eq!(num("0"), Some((0.0, 1, Some(0))));
    }

    #[test]
    fn not_numbers() {
        assert_eq!(num(""), None);
        assert_eq!(num("-"), None);
        assert_eq!(num("+"), None);
        assert_eq!(num("."), None);
        assert_eq!(num("-."), None);
        assert_eq!(num("X1"), None);
        assert_eq!(num(" 1"), None);
    }

    #[test]
    fn negative_zero_keeps_its_sign() {
        let n = parse_number(b"-0", 0, false).unwrap();
        assert_eq!(n.value.to_bits(), (-0.0f64).to_bits());
    }

    #[test]
    fn blanks_inside_numbers_for_rs274() {
        let n = parse_number(b"1 . 5 X", 0, true).unwrap();
        assert_eq!((n.value, n.end, n.integer), (1.5, 5, None));
        let n = parse_number(b"- 2 0 Y", 0, true).unwrap();
        assert_eq!((n.value, n.end), (-20.0, 5));
        // Without the flag the blank ends the number.
        let n = parse_number(b"1 . 5", 0, false).unwrap();
        assert_eq!((n.value, n.end), (1.0, 1));
        // A second point is not part of the number, even after a blank.
        let n = parse_number(b"1.5 .5", 0, true).unwrap();
        assert_eq!((n.value, n.end), (1.5, 3));
    }

    #[test]
    fn long_and_tiny_numbers_are_exact() {
        for s in [
            "12345678901234567890123",
            "0.1000000000000000000000001",
            "3.14159265358979323846264338327950288",
            "0.000000000000000000000000000123",
            "9007199254740993",
            "123456789012345678",
            "1.7976931348623157",
        ] {
            let n = parse_number(s.as_bytes(), 0, false).unwrap();
            assert_eq!(
                n.value.to_bits(),
                s.parse::<f64>().unwrap().to_bits(),
                "{s}"
            );
            assert_eq!(n.end, s.len());
        }
        let n = parse_number(b"1 2345678901234567890123", 0, true).unwrap();
        assert_eq!(n.value, "12345678901234567890123".parse::<f64>().unwrap());
    }

    #[test]
    fn mantissa_runs() {
        for s in [
            "",
            "x",
            "1",
            "12",
            "1234567",
            "12345678",
            "123456789",
            "1234567890123456",
            "9x",
            "0012.5",
            "1.5.5",
            ".25",
            "7.",
        ] {
            let (m, end, point_at) = mantissa_run(s.as_bytes(), 0);
            let int: String = s.chars().take_while(char::is_ascii_digit).collect();
            let rest = &s[int.len()..];
            let (frac, point) = match rest.strip_prefix('.') {
                Some(r) => (r.chars().take_while(char::is_ascii_digit).collect(), true),
                None => (String::new(), false),
            };
            assert_eq!(end, int.len() + point as usize + frac.len(), "{s}");
            let expected = if point { Some(int.len()) } else { None };
            assert_eq!(
                (point_at != usize::MAX).then_some(point_at),
                expected,
                "{s}"
            );
            assert_eq!(m, format!("{int}{frac}").parse::<u64>().unwrap_or(0), "{s}");
        }
        // Bytes around the digit range ('/' = 0x2F, ':' = 0x3A, 0xFF) end a run.
        for c in [b'/', b':', 0xFF, 0x80, 0xBA, 0, b' '] {
            let mut text = b"12345".to_vec();
            text.push(c);
            text.extend(b"67");
            let (m, end, _) = mantissa_run(&text, 0);
            assert_eq!((m, end), (12345, 5), "{c:#x}");
        }
    }

    #[test]
    fn exact_conversion_below_2_pow_52() {
        for m in [0u64, 1, 2, 12345, (1 << 52) - 1, 999_999_999_999_999] {
            assert_eq!(exact_f64(m), m as f64);
        }
    }

    #[test]
    fn digits_only() {
        assert_eq!(parse_digits(b"10.5", 0, false), Some((Some(10), 2)));
        assert_eq!(parse_digits(b"1 0 x", 0, true), Some((Some(10), 3)));
        assert_eq!(parse_digits(b"1 0 x", 0, false), Some((Some(1), 1)));
        assert_eq!(parse_digits(b"x", 0, true), None);
        assert_eq!(
            parse_digits(b"99999999999999999999999", 0, true),
            Some((None, 23))
        );
    }

    #[test]
    fn integer_only_when_unsigned_and_without_point() {
        assert_eq!(num("+5").unwrap().2, None);
        assert_eq!(num("5.").unwrap().2, None);
        assert_eq!(num("0007").unwrap().2, Some(7));
        assert_eq!(num("99999999999999999999").unwrap().2, None);
    }

    proptest! {
        #[test]
        fn equals_str_parse(s in "[+-]?[0-9]{0,24}(\\.[0-9]{0,24})?") {
            let expected = s.parse::<f64>().ok().filter(|_| s.bytes().any(|c| c.is_ascii_digit()));
            let got = parse_number(s.as_bytes(), 0, false);
            match (expected, got) {
                (None, None) => {}
                (Some(e), Some(g)) => {
                    prop_assert_eq!(e.to_bits(), g.value.to_bits(), "{}", s);
                    prop_assert_eq!(g.end, s.len());
                }
                (e, g) => prop_assert!(false, "{s}: str::parse {e:?}, ours {g:?}"),
            }
        }

        #[test]
        fn short_numbers_equal_str_parse(int in 0u64..1_000_000_000, frac in 0u64..1_000_000, digits in 0usize..7, neg in any::<bool>()) {
            let s = if digits == 0 {
                format!("{}{}", if neg { "-" } else { "" }, int)
            } else {
                format!("{}{}.{:0width$}", if neg { "-" } else { "" }, int, frac % 10u64.pow(digits as u32), width = digits)
            };
            let got = parse_number(s.as_bytes(), 0, false).unwrap();
            prop_assert_eq!(got.value.to_bits(), s.parse::<f64>().unwrap().to_bits(), "{}", s);
        }

        #[test]
        fn blanks_are_ignored_in_rs274_numbers(s in "[+-]?[0-9]{1,20}(\\.[0-9]{0,20})?", cuts in proptest::collection::vec(0usize..40, 0..4)) {
            let mut spaced = s.clone();
            for c in cuts {
                let at = c.min(spaced.len());
                // Never put a blank before the sign (a number starts exactly at `start`).
                if at > 0 { spaced.insert(at, ' '); }
            }
            let got = parse_number(spaced.as_bytes(), 0, true).unwrap();
            prop_assert_eq!(got.value.to_bits(), s.parse::<f64>().unwrap().to_bits(), "{:?}", spaced);
            prop_assert_eq!(got.end, spaced.trim_end().len());
        }
    }
}
