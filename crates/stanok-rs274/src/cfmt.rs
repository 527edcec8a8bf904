//! Numbers as LinuxCNC's messages print them with C's `%g`: `precision` significant digits,
//! trailing zeros dropped, exponent form below 10⁻⁴ or from 10^precision on.

/// `printf("%.{precision}g", v)`.
pub(crate) fn g(v: f64, precision: usize) -> String {
    let precision = precision.max(1);
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let sci = format!("{v:.*e}", precision - 1);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let trim = |s: &str| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if exp >= -4 && exp < precision as i32 {
        let decimals = (precision as i32 - 1 - exp).max(0) as usize;
        trim(&format!("{v:.decimals$}"))
    } else {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trim(mantissa), exp.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::g;

    #[test]
    fn like_printf() {
        assert_eq!(g(0.03, 4), "0.03");
        assert_eq!(g(0.0273456, 4), "0.02735");
        assert_eq!(g(-15.45, 6), "-15.45");
        assert_eq!(g(1234567.0, 6), "1.23457e+06");
        assert_eq!(g(0.00001234, 4), "1.234e-05");
        assert_eq!(g(100.0, 6), "100");
        assert_eq!(g(0.0, 6), "0");
    }
}
