//! Numbers and text as the target dialects read them.

/// Decimal places of every coordinate, centre offset and feed written: 1e-6 mm, below every
/// control's resolution, so the converted path is the Canon path to ±5e-7 mm.
pub const DECIMALS: usize = 6;

/// `v` with [`DECIMALS`] places, trailing zeros and a lone point dropped, and never `-0`.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return "0".into();
    }
    let mut s = format!("{v:.DECIMALS$}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".into();
    }
    s
}

/// Text safe inside an RS274/NGC comment: no parentheses (they would end it), one line.
pub fn rs274_comment_text(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '(' => '[',
            ')' => ']',
            '\n' | '\r' => ' ',
            c => c,
        })
        .collect()
}

/// Text safe inside an AxiOMA `MSG("…")` or `;` comment: no double quotes, one line.
pub fn axioma_text(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '"' => '\'',
            '\n' | '\r' => ' ',
            c => c,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_exact_to_the_micrometre() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0000004), "0");
        assert_eq!(num(12.3456789), "12.345679");
        assert_eq!(num(-2.5), "-2.5");
        assert_eq!(num(f64::NAN), "0");
    }
}
