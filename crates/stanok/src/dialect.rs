//! Which dialect a program is written in, and why.
//!
//! `--dialect` decides when given. Otherwise, in this order:
//! 1. **The file name**: a lab corpus prefix (`nc31-`, `2p32-`, `mc2101-`, `gost20999-` followed
//!    by `-` or `_`) is that lab dialect; `.ngc` is RS274/NGC; `.mpf`/`.spf` (Sinumerik-style main
//!    and subprograms) are AxiOMA; `.eia` (Mazak's name for EIA/ISO programs) is Mazatrol.
//! 2. **The text**, when the name cannot say (`.nc`, `.gcode`, `.tap`, `.cnc`, `.txt`, no
//!    extension, standard input): the first [`SCAN_BYTES`] are read, comments left out, and the
//!    first line with a word only one dialect has decides, by precedence: Balt-System (`CVU=`,
//!    `MOVST=`), Mazatrol (`G43.4`, `G43.5`, and the Fanuc family's program number `O1000` on a
//!    line of its own, `M98 P…`, `G65 P…`), RS274/NGC (an O-word with its keyword, `o100 sub`,
//!    `o<name> call` …, or a `#<named>` parameter), AxiOMA (its keywords: `TRAORI`, `BRISK`,
//!    `SOFT`, `MSG(`, `CR=`, `$iPerm`, `G153`…`G159`, `G193`…`G195`, the spline and compensation
//!    keywords …). A higher dialect wins over a lower one found earlier in the text: Balt and
//!    Mazatrol programs use ISO words the others share.
//! 3. Nothing specific: AxiOMA, the default.
//!
//! The choice comes with its reason, which `check` and `run` print (`dialect: rs274ngc (extension
//! .ngc)`). When a guessed dialect gives many errors, `check` tries the others (`hint_for`) and
//! names one that reads the program with far fewer.

use crate::source::Program;
use stanok_syntax::Dialect;

/// How much of a program the text rules look at.
pub const SCAN_BYTES: usize = 64 * 1024;

/// A dialect and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Choice {
    /// The dialect.
    pub dialect: Dialect,
    /// Why, for people: `extension .ngc`, `` `CVU=1` on line 4 ``, …
    pub reason: String,
    /// Neither `--dialect` nor the file name decided: the text did, or the default.
    pub guessed: bool,
}

/// The dialect of `program` (see the module doc).
pub fn choose(given: Option<Dialect>, program: &Program) -> Choice {
    if let Some(dialect) = given {
        return Choice {
            dialect,
            reason: "--dialect".into(),
            guessed: false,
        };
    }
    if let Some(name) = program.file_name() {
        if let Some((dialect, reason)) = from_name(&name) {
            return Choice {
                dialect,
                reason,
                guessed: false,
            };
        }
    }
    let head = program.head(SCAN_BYTES);
    let (dialect, reason) = from_text(&String::from_utf8_lossy(&head)).unwrap_or((
        Dialect::Axioma,
        "the default: nothing in the text belongs to one dialect only".into(),
    ));
    let reason = match program.path.as_ref().and_then(|p| p.extension()) {
        Some(ext) => format!(
            "{reason}; .{} is used by several controls",
            ext.to_string_lossy()
        ),
        None => reason,
    };
    Choice {
        dialect,
        reason,
        guessed: true,
    }
}

/// What the file name alone says.
fn from_name(name: &str) -> Option<(Dialect, String)> {
    let lower = name.to_ascii_lowercase();
    for d in Dialect::LABS {
        if let Some(rest) = lower.strip_prefix(d.id()) {
            if rest.starts_with('-') || rest.starts_with('_') {
                return Some((d, format!("file name prefix {}{}", d.id(), &rest[..1])));
            }
        }
    }
    let ext = lower.rsplit_once('.').map(|(_, e)| e)?;
    match ext {
        "ngc" => Some((Dialect::Rs274ngc, "extension .ngc".into())),
        "mpf" | "spf" => Some((Dialect::Axioma, format!("extension .{ext}"))),
        "eia" => Some((Dialect::Mazatrol, "extension .eia (Mazak EIA/ISO)".into())),
        _ => None,
    }
}

/// The RS274/NGC O-word keywords.
const O_KEYWORDS: [&str; 15] = [
    "sub",
    "endsub",
    "call",
    "if",
    "elseif",
    "else",
    "endif",
    "while",
    "endwhile",
    "do",
    "repeat",
    "endrepeat",
    "break",
    "continue",
    "return",
];

/// AxiOMA's own words (upper case; matched as whole words outside comments).
const AXIOMA_WORDS: [&str; 33] = [
    "TRAORI", "TRAFOOF", "ORIWKS", "ORIMKS", "ORIEULER", "ORIRPY", "ORIAXES", "ORIVECT", "BRISK",
    "SOFT", "CUT2DF", "CUT3DC", "CUT3DF", "ASPLINE", "CSPLINE", "BSPLINE", "SPLBREAK", "FTABLE",
    "STABLE", "LMAXS", "LMINS", "REFAX", "G153", "G154", "G155", "G156", "G157", "G158", "G159",
    "G191", "G193", "G194", "G195",
];

/// A line without its comments: `( … )` (RS274/NGC, ISO), `;` and `//` to the end of the line.
/// Quoted strings (AxiOMA `MSG("…")`) are kept as they are.
fn code_of(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut depth = 0;
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if quoted {
            quoted = c != '"';
            out.push(c);
            continue;
        }
        match c {
            '"' if depth == 0 => {
                quoted = true;
                out.push(c);
            }
            '(' if depth > 0 || !out.trim_end().to_ascii_uppercase().ends_with("MSG") => {
                depth += 1;
            }
            ')' if depth > 0 => depth -= 1,
            ';' if depth == 0 => break,
            '/' if depth == 0 && chars.peek() == Some(&'/') => break,
            _ if depth > 0 => {}
            _ => out.push(c),
        }
    }
    out
}

/// True when `word` occurs in `text` with no letter or digit right before or after it.
fn has_word(text: &str, word: &str) -> bool {
    let bytes = text.as_bytes();
    let mut from = 0;
    while let Some(i) = text[from..].find(word) {
        let at = from + i;
        let end = at + word.len();
        let before_ok = at == 0 || !bytes[at - 1].is_ascii_alphanumeric();
        let after_ok = end >= bytes.len()
            || !(bytes[end].is_ascii_alphanumeric()
                || (bytes[end] == b'.' && word.starts_with('G')));
        if before_ok && after_ok {
            return true;
        }
        from = at + 1;
    }
    false
}

/// An RS274/NGC O-word with its keyword at the start of the line (after an optional N number).
fn o_word(code: &str) -> Option<String> {
    let t = code.trim_start();
    let t = match t.strip_prefix(['N', 'n']) {
        Some(rest) if rest.starts_with(|c: char| c.is_ascii_digit()) => rest
            .trim_start_matches(|c: char| c.is_ascii_digit())
            .trim_start(),
        _ => t,
    };
    let rest = t.strip_prefix(['o', 'O'])?;
    let label_end = if rest.starts_with('<') {
        rest.find('>')? + 1
    } else {
        let n = rest.chars().take_while(|c| c.is_ascii_digit()).count();
        if n == 0 {
            return None;
        }
        n
    };
    let keyword: String = rest[label_end..]
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_alphabetic())
        .collect::<String>()
        .to_ascii_lowercase();
    O_KEYWORDS
        .contains(&keyword.as_str())
        .then(|| format!("o{} {keyword}", &rest[..label_end]))
}

/// Words of the Fanuc family, whose one dialect here is Mazatrol EIA/ISO: a line that is only a
/// program number (`O1000`, `O0001 (PART)`: an RS274/NGC O-word always has its keyword, the other
/// dialects number programs otherwise), a subprogram call `M98 P…` or a macro call `G65 P…`
/// (RS274/NGC has neither; AxiOMA calls by name).
fn fanuc_evidence(upper: &str) -> Option<String> {
    let t = upper.trim();
    if let Some(rest) = t.strip_prefix('O') {
        if !rest.is_empty() && rest.len() <= 5 && rest.bytes().all(|b| b.is_ascii_digit()) {
            return Some(format!("program number O{rest}"));
        }
    }
    let compact: String = t.chars().filter(|c| !c.is_whitespace()).collect();
    for call in ["M98P", "G65P"] {
        if let Some(i) = compact.find(call) {
            let before_ok = i == 0 || !compact.as_bytes()[i - 1].is_ascii_digit();
            let digit_after = compact[i + call.len()..].starts_with(|c: char| c.is_ascii_digit());
            if before_ok && digit_after {
                return Some(format!("{} P…", &call[..3]));
            }
        }
    }
    None
}

/// What the text says (see the module doc), with the evidence.
pub fn from_text(text: &str) -> Option<(Dialect, String)> {
    // Precedence: a dialect found later but ranked higher replaces one found earlier.
    let rank = |d: Dialect| match d {
        Dialect::Balt => 4,
        Dialect::Mazatrol => 3,
        Dialect::Rs274ngc => 2,
        _ => 1,
    };
    let mut best: Option<(Dialect, String)> = None;
    for (i, line) in text.lines().enumerate() {
        let code = code_of(line);
        let upper = code.to_ascii_uppercase();
        let at = |what: &str| format!("`{what}` on line {}", i + 1);
        let found = if let Some(w) = ["CVU=", "MOVST="].iter().find(|w| upper.contains(**w)) {
            Some((Dialect::Balt, at(w)))
        } else if let Some(w) = ["G43.4", "G43.5"].iter().find(|w| has_word(&upper, w)) {
            Some((Dialect::Mazatrol, at(w)))
        } else if let Some(w) = fanuc_evidence(&upper) {
            Some((Dialect::Mazatrol, at(&w)))
        } else if let Some(o) = o_word(&code) {
            Some((Dialect::Rs274ngc, format!("O-word {}", at(&o))))
        } else if code.contains("#<") {
            Some((Dialect::Rs274ngc, format!("named parameter {}", at("#<…>"))))
        } else if let Some(w) = AXIOMA_WORDS.iter().find(|w| has_word(&upper, w)) {
            Some((Dialect::Axioma, at(w)))
        } else if upper.contains("MSG(")
            || upper.contains("CR=")
            || upper.contains("$IPERM")
            || upper.contains("$DPERM")
        {
            let w = ["MSG(", "CR=", "$IPERM", "$DPERM"]
                .into_iter()
                .find(|w| upper.contains(w))
                .unwrap_or("MSG(");
            Some((Dialect::Axioma, at(w)))
        } else {
            None
        };
        if let Some((d, why)) = found {
            if best.as_ref().is_none_or(|(b, _)| rank(d) > rank(*b)) {
                best = Some((d, format!("text: {why}")));
            }
            if rank(d) == 4 {
                break;
            }
        }
    }
    best
}

/// The dialects `check` tries when a guess gives many errors, in the order they are preferred on
/// a tie.
pub const ALTERNATIVES: [Dialect; 8] = [
    Dialect::Axioma,
    Dialect::Rs274ngc,
    Dialect::Balt,
    Dialect::Mazatrol,
    Dialect::Gost20999,
    Dialect::Nc31,
    Dialect::P2p32,
    Dialect::Mc2101,
];

/// Errors from a guessed dialect after which another is worth trying.
pub const MANY_ERRORS: usize = 3;

/// The dialect to suggest, when `errors` errors followed a guess of `chosen`: the one with the
/// fewest errors (`count` gives them), if it has at most a quarter as many.
pub fn hint_for(
    chosen: Dialect,
    errors: usize,
    mut count: impl FnMut(Dialect) -> usize,
) -> Option<(Dialect, usize)> {
    if errors < MANY_ERRORS {
        return None;
    }
    ALTERNATIVES
        .iter()
        .filter(|&&d| d != chosen)
        .map(|&d| (d, count(d)))
        .min_by_key(|&(_, n)| n)
        .filter(|&(_, n)| n * 4 <= errors)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(t: &str) -> Option<Dialect> {
        from_text(t).map(|(d, _)| d)
    }

    #[test]
    fn names_decide_first() {
        assert_eq!(from_name("a.ngc").unwrap().0, Dialect::Rs274ngc);
        assert_eq!(from_name("A.NGC").unwrap().0, Dialect::Rs274ngc);
        assert_eq!(from_name("nc31-flange.nc").unwrap().0, Dialect::Nc31);
        assert_eq!(from_name("2p32_x.txt").unwrap().0, Dialect::P2p32);
        assert_eq!(from_name("main.mpf").unwrap().0, Dialect::Axioma);
        for ambiguous in ["a.nc", "a.gcode", "a.tap", "a", "nc31.nc"] {
            assert_eq!(from_name(ambiguous), None, "{ambiguous}");
        }
    }

    #[test]
    fn the_text_decides_by_its_words() {
        assert_eq!(
            text("N1 X0 Y0 Z0 A0 C0\nCVU=1\nG1 A30\n"),
            Some(Dialect::Balt)
        );
        assert_eq!(text("G90\nG43.4 H1\n"), Some(Dialect::Mazatrol));
        assert_eq!(text("G01 G43.5 X0 I0 J0 K1 H1\n"), Some(Dialect::Mazatrol));
        assert_eq!(
            text("o100 sub\nG1 X1\no100 endsub\n"),
            Some(Dialect::Rs274ngc)
        );
        assert_eq!(text("N10 o<probe> call [1]\n"), Some(Dialect::Rs274ngc));
        assert_eq!(
            text("#<depth> = 3\nG1 Z-#<depth>\n"),
            Some(Dialect::Rs274ngc)
        );
        assert_eq!(text("G64 BRISK\nG1 X1\n"), Some(Dialect::Axioma));
        assert_eq!(text("MSG(\"hello\")\n"), Some(Dialect::Axioma));
        assert_eq!(text("G2 X1 Y1 CR=5\n"), Some(Dialect::Axioma));
        assert_eq!(text("G90 G54 G1 X1 F100\nM30\n"), None);
        // A Balt or Mazatrol word wins over a more common one found before it.
        assert_eq!(text("G64 BRISK\nG43.4 H1\n"), Some(Dialect::Mazatrol));
        assert_eq!(text("#<a>=1\nCVU=1\n"), Some(Dialect::Balt));
    }

    #[test]
    fn fanuc_style_programs_are_mazatrol() {
        let fanuc = "O1000 (PART 7)\nG21 G90 G54\nT1 M6\nG81 X10. Y10. Z-5. R2. F100\nM30\n%\n";
        assert_eq!(text(fanuc), Some(Dialect::Mazatrol));
        assert_eq!(
            from_text(fanuc).unwrap().1,
            "text: `program number O1000` on line 1"
        );
        assert_eq!(text("G90\nM98 P2000 L3\nM30\n"), Some(Dialect::Mazatrol));
        assert_eq!(text("G90\nM98P2000\nM30\n"), Some(Dialect::Mazatrol));
        assert_eq!(text("G65 P9010 A1. B2.\n"), Some(Dialect::Mazatrol));
        // RS274/NGC's O-words keep their keyword; a number in another word is not a call.
        assert_eq!(
            text("o100 sub\nG1 X1\no100 endsub\n"),
            Some(Dialect::Rs274ngc)
        );
        assert_eq!(text("G1 X1 M198 P2\n"), None);
        assert_eq!(text("(O1000 in a comment)\nG1 X1\n"), None);
        assert_eq!(from_name("job.EIA").unwrap().0, Dialect::Mazatrol);
    }

    #[test]
    fn comments_do_not_count() {
        assert_eq!(text("(uses CVU=1 on the Balt control)\nG1 X1\n"), None);
        assert_eq!(text("G1 X1 ; BRISK would be nice\n"), None);
        assert_eq!(text("G1 X1 // TRAORI\n"), None);
        assert_eq!(text("(G43.4 in a comment)\n"), None);
        assert_eq!(text("o100 (not a keyword) G1\n"), None);
        // A G43.4x or BRISKY is not the word.
        assert_eq!(text("G43.45 X1\nBRISKY\n"), None);
    }

    #[test]
    fn the_reason_names_the_evidence() {
        let (_, why) = from_text("G0 X0\nG0 Y0\nCVU=1\n").unwrap();
        assert_eq!(why, "text: `CVU=` on line 3");
        let (_, why) = from_text("o100 sub\n").unwrap();
        assert_eq!(why, "text: O-word `o100 sub` on line 1");
    }

    #[test]
    fn a_hint_needs_many_errors_and_a_much_better_reading() {
        let counts = |d: Dialect| match d {
            Dialect::Balt => 0,
            Dialect::Rs274ngc => 5,
            _ => 9,
        };
        assert_eq!(
            hint_for(Dialect::Axioma, 8, counts),
            Some((Dialect::Balt, 0))
        );
        assert_eq!(hint_for(Dialect::Axioma, 2, counts), None);
        assert_eq!(hint_for(Dialect::Axioma, 8, |_| 3), None);
    }
}
