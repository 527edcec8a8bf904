//! Surface forms: the same program written differently. RS274/NGC reads letters in either case,
//! ignores spaces and tabs outside comments (also inside words and numbers), allows N words,
//! `/` block-delete marks (rs274 runs them: block delete is off), `;` and `( )` comments, and a
//! program fenced by `%` lines. Comment text is left alone (it is printed in the trace).

use crate::Gen;

/// The forms drawn for one program.
pub struct Forms {
    lower: bool,
    compact: bool,
    spaced: bool,
    numbers: bool,
    block_delete: bool,
    percent: bool,
    comments: bool,
}

impl Forms {
    /// Draws the forms (and tells the random source about case and spacing in numbers).
    pub fn draw(g: &mut Gen) -> Forms {
        let f = Forms {
            lower: g.rng.chance(0.3),
            compact: g.rng.chance(0.15),
            spaced: g.rng.chance(0.12),
            numbers: g.rng.chance(0.3),
            block_delete: g.rng.chance(0.05),
            percent: g.rng.chance(0.1),
            comments: g.rng.chance(0.2),
        };
        g.rng.lower = f.lower;
        g.rng.spaced = false;
        f
    }

    /// The program text: every line in the drawn forms.
    pub fn apply(&self, g: &mut Gen) -> String {
        let lines = std::mem::take(&mut g.lines);
        let mut out = String::new();
        if self.percent {
            g.feat("surface: % fences");
            out.push_str("%\n");
        }
        let mut n = 10;
        for line in lines {
            let mut l = line;
            let is_o = l.trim_start().starts_with(['o', 'O']);
            if self.lower {
                g.feat("surface: lower case");
                l = outside_comments(&l, |s| s.to_ascii_lowercase());
            }
            if self.compact && !l.trim_start().starts_with('(') {
                g.feat("surface: compact (no spaces)");
                l = outside_comments(&l, |s| s.replace([' ', '\t'], ""));
            } else if self.spaced && g.rng.chance(0.5) {
                g.feat("surface: spaces inside words");
                let mut rng_bits: Vec<bool> = Vec::new();
                for _ in 0..l.len() {
                    rng_bits.push(g.rng.chance(0.2));
                }
                l = outside_comments(&l, |s| {
                    let mut t = String::new();
                    for (i, c) in s.chars().enumerate() {
                        t.push(c);
                        // Not inside named parameters' brackets' words? LinuxCNC drops the
                        // spaces there as well.
                        if rng_bits.get(i).copied().unwrap_or(false) && c != '#' {
                            t.push(' ');
                        }
                    }
                    t
                });
            }
            if self.numbers && !is_o && g.rng.chance(0.7) {
                g.feat("surface: N words");
                l = format!("N{n} {l}");
                n += 10;
            }
            if self.block_delete && !is_o && g.rng.chance(0.2) {
                g.feat("surface: / block delete (off)");
                l = format!("/{l}");
            }
            if self.comments && !l.contains(';') && g.rng.chance(0.15) {
                g.feat("surface: ; comment");
                l.push_str(" ; note");
            }
            out.push_str(&l);
            out.push('\n');
        }
        if self.percent {
            out.push_str("%\n");
        }
        out
    }
}

/// Applies `f` to the text outside `( … )` comments and before a `;` comment.
fn outside_comments(line: &str, mut f: impl FnMut(&str) -> String) -> String {
    let mut out = String::new();
    let mut rest = line;
    loop {
        let cut = rest.find(['(', ';']).unwrap_or(rest.len());
        out.push_str(&f(&rest[..cut]));
        rest = &rest[cut..];
        if rest.is_empty() {
            return out;
        }
        if rest.starts_with(';') {
            out.push_str(rest);
            return out;
        }
        let end = rest.find(')').map(|e| e + 1).unwrap_or(rest.len());
        out.push_str(&rest[..end]);
        rest = &rest[end..];
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn comments_keep_their_text() {
        let s = super::outside_comments("G1 X1 (Keep Me) y2 ; Tail", |s| s.to_ascii_lowercase());
        assert_eq!(s, "g1 x1 (Keep Me) y2 ; Tail");
    }
}
