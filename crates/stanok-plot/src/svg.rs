//! Small SVG writing helpers: number formatting, text escaping, path data.
//!
//! Invariants: every number written is finite and has at most two decimals (0.01 px is far below
//! what any screen or printer shows), so the same input always gives byte-identical output; every
//! text written goes through [`escape`].

use std::fmt::Write;

/// A number for an SVG attribute: two decimals, trailing zeros dropped, never `-0`, NaN or ∞.
pub(crate) fn num(v: f64) -> String {
    if !v.is_finite() {
        return "0".into();
    }
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// Escapes text for element content and attribute values.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            // Control characters are not allowed in XML 1.0.
            c if c.is_control() && !matches!(c, '\t' | '\n' | '\r') => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

/// Builds one `d` attribute: `M` only where the pen has to jump.
#[derive(Default)]
pub(crate) struct PathData {
    d: String,
    pen: Option<[f64; 2]>,
}

impl PathData {
    /// Puts the pen at `p`, drawing nothing; a no-op when it is already there (to 0.005 px).
    pub(crate) fn start_at(&mut self, p: [f64; 2]) {
        let here = self
            .pen
            .is_some_and(|q| (q[0] - p[0]).abs() < 0.005 && (q[1] - p[1]).abs() < 0.005);
        if !here {
            let _ = write!(self.d, "M{} {}", num(p[0]), num(p[1]));
            self.pen = Some(p);
        }
    }

    /// A straight line from the pen to `p`.
    pub(crate) fn line_to(&mut self, p: [f64; 2]) {
        let _ = write!(self.d, "L{} {}", num(p[0]), num(p[1]));
        self.pen = Some(p);
    }

    /// A circular arc of radius `r` (px) of at most 180° from the pen to `p`; `sweep_flag` 1 runs
    /// clockwise on screen.
    pub(crate) fn arc_to(&mut self, r: f64, sweep_flag: u8, p: [f64; 2]) {
        let r = num(r);
        let _ = write!(
            self.d,
            "A{r} {r} 0 0 {sweep_flag} {} {}",
            num(p[0]),
            num(p[1])
        );
        self.pen = Some(p);
    }

    /// True when nothing was drawn.
    pub(crate) fn is_empty(&self) -> bool {
        self.d.is_empty()
    }

    /// The finished `d` attribute; the builder starts over.
    pub(crate) fn take(&mut self) -> String {
        self.pen = None;
        std::mem::take(&mut self.d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(1.256), "1.26");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(f64::NAN), "0");
        assert_eq!(num(120.5), "120.5");
    }

    #[test]
    fn escaping() {
        assert_eq!(
            escape("<a href=\"x\">&'\u{1}"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;\u{fffd}"
        );
    }

    #[test]
    fn path_data_jumps_only_when_needed() {
        let mut p = PathData::default();
        p.start_at([0.0, 0.0]);
        p.line_to([10.0, 0.0]);
        p.start_at([10.0, 0.001]);
        p.arc_to(5.0, 0, [20.0, 0.0]);
        p.start_at([30.0, 0.0]);
        p.line_to([40.0, 0.0]);
        assert_eq!(p.take(), "M0 0L10 0A5 5 0 0 0 20 0M30 0L40 0");
        assert!(p.is_empty());
    }
}
