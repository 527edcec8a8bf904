//! Shared helpers of the interpreter's golden tests: running a program to a list of commands or an
//! error, printing it in LinuxCNC's format, and comparing traces numerically.
#![allow(dead_code)]

use stanok_canon::{linuxcnc::LinuxCncPrinter, Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;
use std::path::PathBuf;

/// `../shared/corpus/<sub>`, read in place (never copied into the repo).
pub fn corpus(sub: &str) -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus"
    ))
    .join(sub)
}

/// Runs a program; returns the commands before the first error and that error.
pub fn run(text: &str, dialect: Dialect) -> (Vec<Spanned<Canon>>, Option<Diagnostic>) {
    let opts = InterpOptions::new(dialect);
    let mut cmds = Vec::new();
    for item in Interpreter::from_text(text, opts) {
        match item {
            Ok(c) => cmds.push(c),
            Err(d) => return (cmds, Some(d)),
        }
    }
    (cmds, None)
}

/// The LinuxCNC-format lines of a command list (without the exit `ON_RESET` pair).
pub fn linuxcnc_lines(cmds: &[Spanned<Canon>]) -> Vec<String> {
    let mut p = LinuxCncPrinter::new();
    let mut lines = Vec::new();
    for c in cmds {
        lines.extend(p.print(c).lines().map(strip_counter));
    }
    lines
}

/// `"   12 N..... CALL(…)"` → `"N..... CALL(…)"`.
pub fn strip_counter(line: &str) -> String {
    line.trim_start()
        .split_once(' ')
        .map(|(_, rest)| rest.to_string())
        .unwrap_or_default()
}

/// Splits a line into its text with numbers replaced by `#`, and the numbers.
pub fn split_numbers(line: &str) -> (String, Vec<f64>) {
    let b = line.as_bytes();
    let mut skeleton = String::new();
    let mut nums = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts_number =
            b[i].is_ascii_digit() || (b[i] == b'-' && i + 1 < b.len() && b[i + 1].is_ascii_digit());
        // A digit inside an identifier (CANON_PLANE_XY, G5X) is text.
        let in_word = i > 0 && (b[i - 1].is_ascii_alphabetic() || b[i - 1] == b'_');
        if starts_number && !in_word {
            let start = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                i += 1;
            }
            nums.push(line[start..i].parse().unwrap_or(f64::NAN));
            skeleton.push('#');
        } else {
            let ch = line[i..].chars().next().unwrap();
            skeleton.push(ch);
            i += ch.len_utf8();
        }
    }
    (skeleton, nums)
}

/// True if two trace lines agree: same text, numbers within `tol`.
pub fn same_line(a: &str, b: &str, tol: f64) -> bool {
    let (sa, na) = split_numbers(a);
    let (sb, nb) = split_numbers(b);
    sa == sb && na.len() == nb.len() && na.iter().zip(&nb).all(|(x, y)| (x - y).abs() <= tol)
}

/// An rs274 trace file split into canon lines (counter stripped, exit ON_RESET pair removed), the
/// error message and the offending block (both empty when the run succeeded).
pub struct Trace {
    pub lines: Vec<String>,
    pub error: Option<(String, String)>,
}

pub fn read_trace(text: &str) -> Trace {
    let mut lines = Vec::new();
    let mut rest = text.lines();
    for l in rest.by_ref() {
        if l == "executing" {
            break;
        }
        lines.push(strip_counter(l));
    }
    // rs274 prints ON_RESET() twice when it exits.
    for _ in 0..2 {
        if lines.last().map(|l| l.ends_with("ON_RESET()")) == Some(true) {
            lines.pop();
        }
    }
    let msg = rest.next().map(str::to_string);
    let block = rest.next().map(str::to_string);
    Trace {
        lines,
        error: msg.map(|m| (m, block.unwrap_or_default())),
    }
}
