//! Reading and comparing canonical-command traces in LinuxCNC's `rs274 -g` format: the one
//! comparison behind every LinuxCNC parity check (the golden tests of `stanok-interp`, the sample
//! programs of `stanok`, the differential runner `stanok-parity`).
//!
//! ## The rules
//! A trace is a list of call lines (`N..... STRAIGHT_FEED(…)`, the counter column dropped and the
//! two `ON_RESET()` lines rs274 prints when it exits removed) and, when the run stopped, an error:
//! its message, and the block it was found in (rs274 prints the block's text, Stanok a
//! `file:line:column` location).
//!
//! Two traces agree when
//! 1. every line that both have is the same text with the numbers within [`TOL`] (both sides
//!    print 4 decimals, so two values a rounding apart differ by 1e-4 exactly);
//! 2. neither stopped, and they have the same number of lines; or
//! 3. both stopped, with messages whose text up to the first `:` is the same, on the same block
//!    (when both locations are known), and what LinuxCNC printed beyond Stanok's last line moves
//!    nothing. LinuxCNC prints the calls of the failing block up to its error; Stanok commits a
//!    block all or nothing (ARCHITECTURE.md, invariant 4), so its trace ends one block earlier.
//!
//! Parsing never fails: a line that is not a call line is part of the error text.

/// Two numbers agree within this (4 printed decimals, and a rounding apart).
pub const TOL: f64 = 1.0001e-4;

/// A trace read from rs274's output or from `stanok canon`'s.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trace {
    /// The call lines, `N..... CALL(…)`, without the counter column and the exit `ON_RESET`s.
    pub lines: Vec<String>,
    /// The first error's message, if the run stopped.
    pub error: Option<String>,
    /// The text of the block the error was found in (rs274 prints it after the message).
    pub error_block: Option<String>,
    /// The 1-based line of the error (Stanok's `[file:line:column]`).
    pub error_line: Option<usize>,
}

/// `"   12 N..... CALL(…)"` → `Some("N..... CALL(…)")`; None for any other line.
fn call_line(raw: &str) -> Option<&str> {
    let t = raw.trim_start();
    let (n, rest) = t.split_once(' ')?;
    if n.is_empty() || !n.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    (rest.len() > 7 && rest.starts_with('N')).then_some(rest)
}

/// Reads a trace: rs274's output file followed by its standard error, or `stanok canon`'s
/// standard output followed by its standard error (a miette report).
pub fn parse(text: &str) -> Trace {
    let mut t = Trace::default();
    let mut after_error = false;
    // A miette report (`× message`) may wrap the message over several lines before its location.
    let mut miette_message = false;
    // rs274's message may run over several lines (`num_spindles =1. $=1`): the block is the last.
    let mut rs274_message = false;
    for raw in text.lines() {
        if let Some(call) = call_line(raw) {
            let body = &call[7..];
            if let Some(rest) = body.strip_prefix("ON_RESET()") {
                // rs274 writes "executing" (or its message) right after its last ON_RESET().
                let rest = rest.trim();
                if !after_error {
                    t.lines.push(format!("{}ON_RESET()", &call[..7]));
                }
                if t.error.is_none() && !rest.is_empty() && rest != "executing" {
                    t.error = Some(rest.to_string());
                    after_error = true;
                    rs274_message = true;
                }
            } else if !after_error {
                t.lines.push(call.to_string());
            }
            continue;
        }
        let s = raw.trim();
        if s.is_empty() || s == "executing" || s.starts_with("error[") {
            continue;
        }
        if t.error.is_none() {
            miette_message = s.starts_with('×');
            rs274_message = !miette_message;
            t.error = Some(s.trim_start_matches('×').trim().to_string());
            after_error = true;
        } else if miette_message && !s.starts_with("╭─[") && t.error_line.is_none() {
            if let Some(e) = t.error.as_mut() {
                e.push(' ');
                e.push_str(s);
            }
        } else if rs274_message {
            t.error_block = Some(s.to_string());
        } else if t.error_line.is_none() && t.error_block.is_none() {
            // miette: "╭─[prog.ngc:4:1]"; rs274: the block's text on the next line.
            if let Some(loc) = s.strip_prefix("╭─[").and_then(|l| l.strip_suffix(']')) {
                let mut parts = loc.rsplitn(3, ':');
                let _column = parts.next();
                t.error_line = parts.next().and_then(|l| l.parse().ok());
                miette_message = false;
            } else if !s.starts_with('│') && !s.starts_with('·') && !s.starts_with('╰') {
                t.error_block = Some(s.to_string());
            }
        }
    }
    // rs274 prints ON_RESET() twice when it exits; the printer of `stanok canon` does too.
    for _ in 0..2 {
        if t.lines.last().is_some_and(|l| l.ends_with("ON_RESET()")) {
            t.lines.pop();
        }
    }
    t
}

/// Splits a line into its text with numbers replaced by `#`, and the numbers. A digit inside an
/// identifier (`CANON_PLANE_XY`, `G5X`) is text.
pub fn split_numbers(line: &str) -> (String, Vec<f64>) {
    let b = line.as_bytes();
    let mut skeleton = String::new();
    let mut nums = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts_number =
            b[i].is_ascii_digit() || (b[i] == b'-' && i + 1 < b.len() && b[i + 1].is_ascii_digit());
        let in_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if starts_number && !in_word {
            let start = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                i += 1;
            }
            // Text that only looks like a number ("1.7.2008" in a comment) stays text.
            match line[start..i].parse() {
                Ok(v) => {
                    nums.push(v);
                    skeleton.push('#');
                }
                Err(_) => skeleton.push_str(&line[start..i]),
            }
        } else {
            let ch = line[i..].chars().next().unwrap_or(' ');
            skeleton.push(ch);
            i += ch.len_utf8().max(1);
        }
    }
    (skeleton, nums)
}

/// True if two trace lines agree: the same text, the numbers within `tol`.
pub fn same_line(a: &str, b: &str, tol: f64) -> bool {
    let (sa, na) = split_numbers(a);
    let (sb, nb) = split_numbers(b);
    sa == sb && na.len() == nb.len() && na.iter().zip(&nb).all(|(x, y)| (x - y).abs() <= tol)
}

/// The name of the call on a trace line (`STRAIGHT_FEED`), for grouping differences.
pub fn call_name(line: &str) -> &str {
    let body = line.get(7..).unwrap_or(line);
    body.split('(').next().unwrap_or(body).trim()
}

/// How two traces differ.
#[derive(Debug, Clone, PartialEq)]
pub enum Difference {
    /// Line `index` (0-based) differs.
    Line {
        /// 0-based index into both traces.
        index: usize,
        /// Stanok's line.
        ours: String,
        /// LinuxCNC's line.
        theirs: String,
    },
    /// Neither stopped, but one trace is longer.
    Length {
        /// Stanok's number of lines.
        ours: usize,
        /// LinuxCNC's.
        theirs: usize,
    },
    /// Stanok stopped, LinuxCNC ran the program.
    OnlyStanokStopped(String),
    /// LinuxCNC stopped, Stanok ran the program.
    OnlyLinuxCncStopped(String),
    /// Both stopped, with different messages.
    Message {
        /// Stanok's message.
        ours: String,
        /// LinuxCNC's.
        theirs: String,
    },
    /// Both stopped with the same message, on different blocks.
    Block {
        /// The block Stanok stopped at.
        ours: String,
        /// The block LinuxCNC stopped at.
        theirs: String,
    },
    /// LinuxCNC moved in the failing block before its error, Stanok not.
    MovedBeforeError(String),
}

impl Difference {
    /// A short key saying what kind of difference this is (the calls or messages involved), the
    /// same for a program and the smaller programs that keep its difference.
    pub fn signature(&self) -> String {
        match self {
            Difference::Line { ours, theirs, .. } => {
                format!("line {} / {}", call_name(ours), call_name(theirs))
            }
            Difference::Length { ours, theirs } => {
                format!("length {}", if ours < theirs { "short" } else { "long" })
            }
            Difference::OnlyStanokStopped(m) => format!("stanok stopped: {m}"),
            Difference::OnlyLinuxCncStopped(m) => format!("linuxcnc stopped: {m}"),
            Difference::Message { ours, theirs } => format!("message {ours} / {theirs}"),
            Difference::Block { .. } => "block".into(),
            Difference::MovedBeforeError(l) => format!("moved {}", call_name(l)),
        }
    }
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Difference::Line {
                index,
                ours,
                theirs,
            } => write!(
                f,
                "line {}: stanok {ours:?}, linuxcnc {theirs:?}",
                index + 1
            ),
            Difference::Length { ours, theirs } => {
                write!(f, "stanok printed {ours} lines, linuxcnc {theirs}")
            }
            Difference::OnlyStanokStopped(m) => write!(f, "stanok stopped: {m}"),
            Difference::OnlyLinuxCncStopped(m) => {
                write!(f, "linuxcnc stopped ({m}), stanok ran it")
            }
            Difference::Message { ours, theirs } => {
                write!(f, "error {ours:?}, linuxcnc {theirs:?}")
            }
            Difference::Block { ours, theirs } => {
                write!(f, "error on block {ours:?}, linuxcnc on {theirs:?}")
            }
            Difference::MovedBeforeError(l) => write!(f, "linuxcnc moved before its error: {l}"),
        }
    }
}

fn moves(line: &str) -> bool {
    line.contains("STRAIGHT_") || line.contains("ARC_FEED") || line.contains("NURBS")
}

/// Compares Stanok's trace with LinuxCNC's by the rules above. `program` (the program's text)
/// lets the error blocks be compared: Stanok's error line is looked up in it.
pub fn compare(ours: &Trace, theirs: &Trace, program: Option<&str>) -> Result<(), Difference> {
    for (index, (a, b)) in ours.lines.iter().zip(&theirs.lines).enumerate() {
        if !same_line(a, b, TOL) {
            return Err(Difference::Line {
                index,
                ours: a.clone(),
                theirs: b.clone(),
            });
        }
    }
    match (&ours.error, &theirs.error) {
        (None, None) if ours.lines.len() == theirs.lines.len() => Ok(()),
        (None, None) => Err(Difference::Length {
            ours: ours.lines.len(),
            theirs: theirs.lines.len(),
        }),
        (Some(e), None) => Err(Difference::OnlyStanokStopped(e.clone())),
        (None, Some(e)) => Err(Difference::OnlyLinuxCncStopped(e.clone())),
        (Some(our_msg), Some(their_msg)) => {
            let head = their_msg.split(':').next().unwrap_or("");
            if !our_msg.starts_with(head) {
                return Err(Difference::Message {
                    ours: our_msg.clone(),
                    theirs: their_msg.clone(),
                });
            }
            if let (Some(text), Some(line), Some(block)) =
                (program, ours.error_line, &theirs.error_block)
            {
                let our_block = text.lines().nth(line.saturating_sub(1)).unwrap_or("");
                // A call of a subroutine that is nowhere: LinuxCNC shows the last block it read
                // while seeking it (the file's end) and names the call's line in the message;
                // Stanok points at the call. The same block, named two ways.
                let names_our_line = their_msg
                    .rsplit_once("from line: ")
                    .and_then(|(_, n)| n.trim().parse::<usize>().ok())
                    == Some(line);
                if our_block.trim() != block.trim() && !names_our_line {
                    return Err(Difference::Block {
                        ours: our_block.trim().to_string(),
                        theirs: block.trim().to_string(),
                    });
                }
            }
            if ours.lines.len() > theirs.lines.len() {
                return Err(Difference::Length {
                    ours: ours.lines.len(),
                    theirs: theirs.lines.len(),
                });
            }
            match theirs.lines[ours.lines.len()..].iter().find(|l| moves(l)) {
                Some(l) => Err(Difference::MovedBeforeError(l.clone())),
                None => Ok(()),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RS274: &str = "    1 N..... DWELL(1.0000)\n    2 N..... STRAIGHT_FEED(1.0000, 2.0000)\n    3 N..... ON_RESET()\n    4 N..... ON_RESET()executing\nBad thing: here\nG1 X\n";

    #[test]
    fn a_missing_subroutine_is_the_same_block_when_the_message_names_the_call_line() {
        let theirs = Trace {
            lines: vec![],
            error: Some("EOF in file:p.ngc seeking o-word: o<x> from line: 2".into()),
            error_block: Some("M2".into()),
            error_line: None,
        };
        let ours = |line| Trace {
            lines: vec![],
            error: Some("EOF in file seeking o-word: o<x> from line: 2".into()),
            error_block: None,
            error_line: Some(line),
        };
        let text = "G0 X1\no<x> call\nM2\n";
        assert_eq!(compare(&ours(2), &theirs, Some(text)), Ok(()));
        assert!(matches!(
            compare(&ours(1), &theirs, Some(text)),
            Err(Difference::Block { .. })
        ));
    }

    #[test]
    fn the_block_of_a_message_over_several_lines_is_its_last_line() {
        let t = parse("    1 N..... ON_RESET()executing\nSpindle ($) number out of range in M5 Command\nnum_spindles =1. $=1\n\n$1 M5\n");
        assert_eq!(
            t.error.as_deref(),
            Some("Spindle ($) number out of range in M5 Command")
        );
        assert_eq!(t.error_block.as_deref(), Some("$1 M5"));
    }

    #[test]
    fn reads_an_rs274_error_run() {
        let t = parse(RS274);
        assert_eq!(
            t.lines,
            vec![
                "N..... DWELL(1.0000)",
                "N..... STRAIGHT_FEED(1.0000, 2.0000)"
            ]
        );
        assert_eq!(t.error.as_deref(), Some("Bad thing: here"));
        assert_eq!(t.error_block.as_deref(), Some("G1 X"));
    }

    #[test]
    fn reads_a_stanok_error_run() {
        let text = "    1 N..... DWELL(1.0000)\n    2 N..... ON_RESET()\n    3 N..... ON_RESET()\nerror[rs274::x]\n\n  × Bad thing\n   ╭─[p.ngc:3:1]\n 2 │ G4 P1\n 3 │ G1 X\n";
        let t = parse(text);
        assert_eq!(t.lines, vec!["N..... DWELL(1.0000)"]);
        assert_eq!(t.error.as_deref(), Some("Bad thing"));
        assert_eq!(t.error_line, Some(3));
        let program = "G21\nG4 P1\nG1 X\n";
        // LinuxCNC moved in the failing block before it stopped: not the same.
        assert!(matches!(
            compare(&t, &parse(RS274), Some(program)),
            Err(Difference::MovedBeforeError(_))
        ));
        let theirs = parse(&RS274.replace(
            "STRAIGHT_FEED(1.0000, 2.0000)",
            "SELECT_PLANE(CANON_PLANE_XY)",
        ));
        assert_eq!(compare(&t, &theirs, Some(program)), Ok(()));
        let wrong = Trace {
            error_line: Some(2),
            ..t.clone()
        };
        assert!(matches!(
            compare(&wrong, &theirs, Some(program)),
            Err(Difference::Block { .. })
        ));
    }

    #[test]
    fn the_comparison_can_fail() {
        let t = |l: &str| Trace {
            lines: vec![l.to_string()],
            ..Trace::default()
        };
        let a = t("N..... STRAIGHT_FEED(1.0000, 2.0000)");
        assert!(compare(&a, &t("N..... STRAIGHT_FEED(1.0000, 2.0002)"), None).is_err());
        assert!(compare(&a, &t("N..... STRAIGHT_FEED(1.0000, 2.0001)"), None).is_ok());
        assert!(compare(&a, &t("N..... STRAIGHT_TRAVERSE(1.0000, 2.0000)"), None).is_err());
        let stopped = Trace {
            error: Some("X".into()),
            ..a.clone()
        };
        assert!(matches!(
            compare(&stopped, &a, None),
            Err(Difference::OnlyStanokStopped(_))
        ));
        assert!(same_line(
            "N..... SELECT_PLANE(CANON_PLANE_XY)",
            "N..... SELECT_PLANE(CANON_PLANE_XY)",
            TOL
        ));
        assert!(!same_line(
            "N..... SELECT_PLANE(CANON_PLANE_XY)",
            "N..... SELECT_PLANE(CANON_PLANE_XZ)",
            TOL
        ));
        assert!(same_line(
            "N0020  COMMENT(\"Date: 1.7.2008\")",
            "N0020  COMMENT(\"Date: 1.7.2008\")",
            TOL
        ));
        assert!(same_line(
            "N..... STRAIGHT_FEED(-0.0000)",
            "N..... STRAIGHT_FEED(0.0000)",
            TOL
        ));
    }
}
