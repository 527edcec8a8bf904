//! `sprintf` formats, as C's printf: `%[flags][width][.precision]conversion` with the flags
//! `-` (left-justify), `+` (always a sign), ` ` (blank for plus), `0` (zero padding), `#` (keep
//! the point / trailing zeros of %g), and the conversions `d i` (integer), `u`, `x X o`, `f F`,
//! `e E`, `g G`, `s`, `c` (an integer's character) and `%%`. `*` widths are not offered.
//!
//! Differences from C, all diagnostics instead of undefined behaviour: a conversion whose argument
//! has the wrong kind (a string for `%d`, a number for `%s`; a double for `%d` — C would print
//! garbage), too few arguments, an unknown conversion. Extra arguments are ignored, as in C.

use super::value::HVal;

/// Formats `args` by `fmt`. Err with the reason.
pub fn sprintf(fmt: &str, args: &[HVal]) -> Result<String, String> {
    let mut out = String::new();
    let mut chars = fmt.chars().peekable();
    let mut next = args.iter();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        let mut left = false;
        let mut plus = false;
        let mut space = false;
        let mut zero = false;
        let mut alt = false;
        while let Some(&f) = chars.peek() {
            match f {
                '-' => left = true,
                '+' => plus = true,
                ' ' => space = true,
                '0' => zero = true,
                '#' => alt = true,
                _ => break,
            }
            chars.next();
        }
        let mut width = 0usize;
        while let Some(d) = chars.peek().and_then(|c| c.to_digit(10)) {
            width = (width * 10 + d as usize).min(512);
            chars.next();
        }
        let mut precision = None;
        if chars.peek() == Some(&'.') {
            chars.next();
            let mut p = 0usize;
            while let Some(d) = chars.peek().and_then(|c| c.to_digit(10)) {
                p = (p * 10 + d as usize).min(64);
                chars.next();
            }
            precision = Some(p);
        }
        // Length modifiers mean nothing here (all integers are 64-bit): skip them.
        while matches!(chars.peek(), Some('l' | 'h' | 'L')) {
            chars.next();
        }
        let Some(conv) = chars.next() else {
            return Err("the format ends inside a `%` conversion".into());
        };
        if conv == '%' {
            out.push('%');
            continue;
        }
        let arg = next
            .next()
            .ok_or_else(|| format!("`%{conv}` has no argument"))?;
        let number = |arg: &HVal| {
            arg.number()
                .ok_or_else(|| format!("`%{conv}` needs a number, not a string"))
        };
        let integer = |arg: &HVal| match arg {
            HVal::Int(i) => Ok(*i),
            HVal::Bool(b) => Ok(*b as i64),
            _ => Err(format!(
                "`%{conv}` needs an integer, not a {} (use %f for doubles)",
                arg.kind()
            )),
        };
        let (sign, body) = match conv {
            'd' | 'i' => {
                let i = integer(arg)?;
                let mut digits = i.unsigned_abs().to_string();
                if let Some(p) = precision {
                    digits = format!("{digits:0>p$}");
                }
                (sign_of(i < 0, plus, space), digits)
            }
            'u' => (String::new(), (integer(arg)? as u64).to_string()),
            'x' => (
                String::new(),
                prefixed(alt, "0x", format!("{:x}", integer(arg)?)),
            ),
            'X' => (
                String::new(),
                prefixed(alt, "0X", format!("{:X}", integer(arg)?)),
            ),
            'o' => (
                String::new(),
                prefixed(alt, "0", format!("{:o}", integer(arg)?)),
            ),
            'c' => {
                let i = integer(arg)?;
                let ch = u32::try_from(i)
                    .ok()
                    .and_then(char::from_u32)
                    .ok_or_else(|| format!("`%c`: {i} is no character"))?;
                (String::new(), ch.to_string())
            }
            's' => match arg {
                HVal::Str(s) => {
                    let s = match precision {
                        Some(p) => s.chars().take(p).collect(),
                        None => s.clone(),
                    };
                    (String::new(), s)
                }
                _ => return Err(format!("`%s` needs a string, not a {}", arg.kind())),
            },
            'f' | 'F' | 'e' | 'E' | 'g' | 'G' => {
                let v = number(arg)?;
                let p = precision.unwrap_or(6);
                let body = match conv {
                    'f' | 'F' => {
                        let s = format!("{:.p$}", v.abs());
                        if alt && p == 0 {
                            s + "."
                        } else {
                            s
                        }
                    }
                    'e' | 'E' => exponential(v.abs(), p, conv == 'E'),
                    _ => general(v.abs(), p, alt, conv == 'G'),
                };
                (sign_of(v.is_sign_negative() && v != 0.0, plus, space), body)
            }
            other => return Err(format!("`%{other}` is not a known conversion")),
        };
        let len = sign.chars().count() + body.chars().count();
        let pad = width.saturating_sub(len);
        if left {
            out.push_str(&sign);
            out.push_str(&body);
            out.extend(std::iter::repeat_n(' ', pad));
        } else if zero && conv != 's' && conv != 'c' {
            out.push_str(&sign);
            out.extend(std::iter::repeat_n('0', pad));
            out.push_str(&body);
        } else {
            out.extend(std::iter::repeat_n(' ', pad));
            out.push_str(&sign);
            out.push_str(&body);
        }
    }
    Ok(out)
}

fn sign_of(negative: bool, plus: bool, space: bool) -> String {
    if negative {
        "-".into()
    } else if plus {
        "+".into()
    } else if space {
        " ".into()
    } else {
        String::new()
    }
}

fn prefixed(alt: bool, prefix: &str, digits: String) -> String {
    if alt && digits != "0" {
        format!("{prefix}{digits}")
    } else {
        digits
    }
}

/// `%e` of a non-negative number: `d.ddddde±XX` (at least two exponent digits, as C).
fn exponential(v: f64, p: usize, upper: bool) -> String {
    let s = format!("{v:.p$e}");
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let e = if upper { 'E' } else { 'e' };
    let sign = if exp < 0 { '-' } else { '+' };
    format!("{mantissa}{e}{sign}{:02}", exp.abs())
}

/// `%g`: precision P (0 → 1) significant digits; exponent X of `%e`: `%f` with P−1−X decimals if
/// −4 ≤ X < P, else `%e` with P−1; trailing zeros (and a trailing point) removed unless `#`.
fn general(v: f64, p: usize, alt: bool, upper: bool) -> String {
    let p = p.max(1);
    let e_form = exponential(v, p - 1, upper);
    let x: i32 = e_form
        .rsplit(['e', 'E'])
        .next()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let mut s = if x >= -4 && x < p as i32 {
        let decimals = (p as i32 - 1 - x).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        e_form
    };
    if !alt {
        let (num, exp) = match s.find(['e', 'E']) {
            Some(i) => (s[..i].to_string(), s[i..].to_string()),
            None => (s.clone(), String::new()),
        };
        let num = if num.contains('.') {
            num.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            num
        };
        s = num + &exp;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(fmt: &str, args: &[HVal]) -> String {
        sprintf(fmt, args).unwrap()
    }

    #[test]
    fn c_conversions() {
        let i = HVal::Int;
        let d = HVal::Double;
        assert_eq!(f("value: %d", &[i(50)]), "value: 50");
        assert_eq!(
            f("%i|%5d|%-5d|%05d|%+d", &[i(7), i(-42), i(3), i(-42), i(9)]),
            "7|  -42|3    |-0042|+9"
        );
        assert_eq!(f("%f", &[d(2.71)]), "2.710000");
        assert_eq!(
            f("%.2f|%8.3f|%.0f", &[d(2.345), d(-1.5), d(2.5)]),
            "2.35|  -1.500|2"
        );
        assert_eq!(
            f("%e|%.2E", &[d(12345.678), d(0.000123)]),
            "1.234568e+04|1.23E-04"
        );
        assert_eq!(
            f("%g|%g|%g|%g", &[d(100000.0), d(1e6), d(0.0001), d(0.5)]),
            "100000|1e+06|0.0001|0.5"
        );
        assert_eq!(
            f("%s=%s%%", &[HVal::Str("X".into()), HVal::Str("ok".into())]),
            "X=ok%"
        );
        assert_eq!(f("%x %X %o", &[i(255), i(255), i(8)]), "ff FF 10");
        assert_eq!(f("%f", &[i(2)]), "2.000000");
        assert!(sprintf("%d", &[d(1.5)]).is_err());
        assert!(sprintf("%s", &[i(1)]).is_err());
        assert!(sprintf("%d %d", &[i(1)]).is_err());
        assert!(sprintf("%q", &[i(1)]).is_err());
        assert!(sprintf("50%", &[]).is_err());
    }
}
