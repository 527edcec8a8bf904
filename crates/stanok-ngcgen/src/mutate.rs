//! The second, independent style of program: LinuxCNC's own sample programs, mutated.
//!
//! The section generator (`sections.rs`) writes programs the way this crate's authors think of
//! the language; its blind spots are Stanok's blind spots. Mutants start from programs written by
//! LinuxCNC's users and developers (`/usr/share/linuxcnc/ncfiles`, the sample configurations'
//! programs) and break them the way edits break real programs, without tracking any state:
//!
//! * **number**: a number of an axis, centre, radius, feed or parameter word is scaled, shifted,
//!   negated, rounded, zeroed or converted between mm and inch;
//! * **swap**, **duplicate**, **delete** a block;
//! * **insert** a state switch mid-program: units, distance and arc-distance modes, plane, path
//!   mode, coordinate system, G92/G52 offsets, tool length offsets, spindle, coolant, feed mode,
//!   lathe diameter mode, modal state save/restore, a tool change;
//! * **join** two blocks into one (words of two blocks combined: new conflicts, new orders);
//! * **wrap** a run of blocks in O-word control flow (`if`, `repeat`, `do`/`while`);
//! * **surface**: a block in lower case, or without its spaces.
//!
//! ## Reproducibility and invariants
//! Mutant `index` of run `seed` is drawn from the ChaCha8 stream `Rng::new(seed, index, 0)` over
//! the *sorted, de-duplicated* list of sources the caller passes (the same LinuxCNC package gives
//! the same mutants). Blocks that end the program (`M2`, `M30`, `%`) and O-word lines are never
//! moved, deleted or joined, so a mutant keeps its end and the nesting of its control flow; the
//! mutations may make it invalid, which is part of the test (both must then stop at the same block
//! with the same message). Every operation is bounded: 1–4 mutations, each O(lines).

use crate::rng::Rng;

/// A mutated sample program.
#[derive(Debug, Clone)]
pub struct Mutant {
    /// The program text.
    pub text: String,
    /// Index of the source in the list given to [`mutate`].
    pub source: usize,
    /// The mutations applied, in order.
    pub ops: Vec<&'static str>,
}

/// The blocks [`mutate`] inserts: state switches a program's author did not plan for.
const SWITCHES: &[&str] = &[
    "G20",
    "G21",
    "G90",
    "G91",
    "G90.1",
    "G91.1",
    "G17",
    "G18",
    "G19",
    "G61",
    "G61.1",
    "G64",
    "G64 P0.01 Q0.005",
    "G54",
    "G55",
    "G59.3",
    "G92 X1 Y-2",
    "G92.1",
    "G92.2",
    "G92.3",
    "G52 X2 Y1",
    "G52 X0 Y0 Z0",
    "G43 H1",
    "G43.1 Z0.1",
    "G49",
    "G40",
    "G80",
    "M3 S1000",
    "M4 S400",
    "M5",
    "M7",
    "M8",
    "M9",
    "G93",
    "G94",
    "F25",
    "S1500",
    "G7",
    "G8",
    "M70",
    "M72",
    "M73",
    "T2 M6",
    "T1",
    "M6",
    "G10 L2 P2 X1 Y1 Z0",
    "G10 L20 P1 X0 Y0",
    "G59",
    "G4 P0.1",
    "G98",
    "G99",
    "M48",
    "M49",
    "G96 S100 D2000",
    "G97",
];

/// Letters whose numbers [`mutate`] changes (positions, centres, radius, feed, speeds, P/Q).
const NUMBER_LETTERS: &[u8] = b"xyzabcijkrfpq";

/// The code part of a line (comments dropped), lower case, without spaces.
fn code(line: &str) -> String {
    let mut out = String::new();
    let mut depth = 0;
    for ch in line.chars() {
        match ch {
            '(' => depth += 1,
            ')' if depth > 0 => depth -= 1,
            ';' if depth == 0 => break,
            c if depth == 0 && !c.is_whitespace() => out.push(c.to_ascii_lowercase()),
            _ => {}
        }
    }
    out
}

/// Whether `code` holds word `w` (a letter and a number, e.g. "m2") not followed by more digits.
fn has_word(code: &str, w: &str) -> bool {
    code.match_indices(w).any(|(i, _)| {
        let before_ok = i == 0 || !code.as_bytes()[i - 1].is_ascii_alphabetic();
        let after = &code[i + w.len()..];
        before_ok && !after.starts_with(|c: char| c.is_ascii_digit() || c == '.')
    })
}

/// A line that must stay where it is: a program end, a `%` fence, an O-word or an empty line.
fn fixed(line: &str) -> bool {
    let c = code(line);
    c.is_empty()
        || c.starts_with('%')
        || c.starts_with('o')
        || c.starts_with("/o")
        || has_word(&c, "m2")
        || has_word(&c, "m02")
        || has_word(&c, "m30")
}

/// Indices of the lines a mutation may move or change.
fn movable(lines: &[String]) -> Vec<usize> {
    (0..lines.len()).filter(|&i| !fixed(&lines[i])).collect()
}

/// A new value for a number of a program: one of the edits a hand makes.
fn new_number(rng: &mut Rng, v: f64) -> f64 {
    let r = match rng.below(8) {
        0 => v * rng.value(0.5, 2.0),
        1 => v + rng.signed(0.1, 5.0),
        2 => -v,
        3 => v.round(),
        4 => 0.0,
        5 => v / 25.4,
        6 => v * 25.4,
        _ => v * 10.0,
    };
    (r * 10_000.0).round() / 10_000.0
}

/// Changes one plain number after a letter of [`NUMBER_LETTERS`] outside comments.
fn mutate_number(rng: &mut Rng, line: &str) -> Option<String> {
    let b = line.as_bytes();
    let mut spots = Vec::new(); // (start, end) of the number text
    let (mut depth, mut name) = (0, false); // inside a comment; inside a `#<name>`
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'(' => depth += 1,
            b')' if depth > 0 => depth -= 1,
            b';' if depth == 0 => break,
            b'<' => name = true,
            b'>' => name = false,
            c if depth == 0 && !name && NUMBER_LETTERS.contains(&c.to_ascii_lowercase()) => {
                // Not part of a keyword (e.g. the `r` of `repeat`, the `f` of `if`).
                let word_start = i == 0 || !b[i - 1].is_ascii_alphabetic();
                let mut j = i + 1;
                while j < b.len() && b[j] == b' ' {
                    j += 1;
                }
                let start = j;
                if j < b.len() && (b[j] == b'-' || b[j] == b'+') {
                    j += 1;
                }
                while j < b.len() && (b[j].is_ascii_digit() || b[j] == b'.') {
                    j += 1;
                }
                let next_alpha = j < b.len() && b[j].is_ascii_alphabetic();
                if word_start && j > start && !next_alpha {
                    spots.push((start, j));
                }
            }
            _ => {}
        }
        i += 1;
    }
    if spots.is_empty() {
        return None;
    }
    let (s, e) = *rng.pick(&spots);
    let v: f64 = line[s..e].parse().ok()?;
    let n = new_number(rng, v);
    let text = if n == 0.0 {
        "0".to_string()
    } else {
        format!("{n}")
    };
    Some(format!("{}{}{}", &line[..s], text, &line[e..]))
}

/// Mutant `index` of run `seed` from `sources` (non-empty): 1–4 mutations of one source.
pub fn mutate(sources: &[String], seed: u64, index: u64) -> Mutant {
    let mut rng = Rng::new(seed, index, 0);
    let source = rng.below(sources.len() as u64) as usize;
    let mut lines: Vec<String> = sources[source].lines().map(str::to_string).collect();
    let mut ops = Vec::new();
    let mut label = 9001;
    for _ in 0..rng.int(1, 4) {
        let spots = movable(&lines);
        if spots.is_empty() {
            break;
        }
        let at = *rng.pick(&spots);
        let op = match rng.below(20) {
            0..=5 => match mutate_number(&mut rng, &lines[at]) {
                Some(l) => {
                    lines[at] = l;
                    "number"
                }
                None => continue,
            },
            6 | 7 => {
                let next = spots.iter().copied().find(|&j| j > at);
                match next {
                    Some(j) => {
                        lines.swap(at, j);
                        "swap"
                    }
                    None => continue,
                }
            }
            8 => {
                let l = lines[at].clone();
                lines.insert(at, l);
                "duplicate"
            }
            9 => {
                lines.remove(at);
                "delete"
            }
            10..=13 => {
                let s = rng.pick(SWITCHES);
                lines.insert(at, s.to_string());
                "insert a state switch"
            }
            14 | 15 => {
                let next = at + 1;
                if next >= lines.len() || fixed(&lines[next]) {
                    continue;
                }
                // A `;` comment would swallow the second block: keep only the first's code.
                let first = lines[at].split(';').next().unwrap_or("").to_string();
                let second = lines.remove(next);
                lines[at] = format!("{first} {second}");
                "join two blocks"
            }
            16 | 17 => {
                // A run of consecutive movable lines from `at`.
                let mut end = at;
                let want = rng.int(0, 4) as usize;
                while end + 1 < lines.len() && !fixed(&lines[end + 1]) && end - at < want {
                    end += 1;
                }
                let (open, close) = match rng.below(3) {
                    0 => (
                        format!("o{label} if [#<_x> GT -1000000]"),
                        format!("o{label} endif"),
                    ),
                    1 => (
                        format!("o{label} repeat [{}]", rng.int(0, 2)),
                        format!("o{label} endrepeat"),
                    ),
                    _ => (format!("o{label} do"), format!("o{label} while [0]")),
                };
                label += 1;
                lines.insert(end + 1, close);
                lines.insert(at, open);
                "wrap in O-word control flow"
            }
            18 => {
                lines[at] = lines[at].to_ascii_lowercase();
                "lower case"
            }
            _ => {
                lines[at] = lines[at].replace(' ', "");
                "no spaces"
            }
        };
        ops.push(op);
    }
    Mutant {
        text: lines.join("\n") + "\n",
        source,
        ops,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "%\n(a sample)\nG21 G90\nG0 X1 Y2\nG1 X3 F100 ; cut\no100 if [1]\nG2 X4 Y2 I0.5 J0\no100 endif\nM2\n%\n";

    #[test]
    fn mutants_are_reproducible_and_differ() {
        let src = vec![SAMPLE.to_string()];
        let a = mutate(&src, 5, 3);
        let b = mutate(&src, 5, 3);
        assert_eq!(a.text, b.text);
        let changed = (0..20)
            .filter(|&i| mutate(&src, 5, i).text != SAMPLE)
            .count();
        assert!(changed >= 15, "only {changed} of 20 mutants changed");
    }

    #[test]
    fn program_ends_and_o_words_stay() {
        let src = vec![SAMPLE.to_string()];
        for i in 0..200 {
            let m = mutate(&src, 11, i);
            let l: Vec<&str> = m.text.lines().collect();
            assert_eq!(l.first(), Some(&"%"), "{}", m.text);
            assert_eq!(&l[l.len() - 2..], &["M2", "%"], "{}", m.text);
            assert_eq!(m.text.matches("o100 if").count(), 1, "{}", m.text);
            assert_eq!(m.text.matches("o100 endif").count(), 1, "{}", m.text);
            assert!(!m.ops.is_empty() || m.text == SAMPLE);
        }
    }

    #[test]
    fn numbers_change_outside_comments_and_keywords_only() {
        let mut rng = Rng::new(1, 1, 0);
        for _ in 0..50 {
            let l = mutate_number(&mut rng, "G1 X1.5 (X9) F100 ; Y7").unwrap();
            assert!(l.contains("(X9)") && l.ends_with("; Y7"), "{l}");
        }
        assert_eq!(mutate_number(&mut rng, "o1 repeat [2] (r5)"), None);
        assert_eq!(mutate_number(&mut rng, "#<x1> = 2"), None);
    }
}
