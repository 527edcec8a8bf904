//! Shared helpers of the interpreter's golden tests: running a program to a list of commands or an
//! error, printing it in LinuxCNC's format, and comparing traces numerically.
#![allow(dead_code)]

use stanok_canon::setup::{Tool, ToolEdge, ToolTable};
use stanok_canon::{linuxcnc::LinuxCncPrinter, Canon, Diagnostic, LengthUnits, Spanned};
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

/// The corpus tool table `rs274ngc/tool.tbl` (inches), read by a parser just big enough for its
/// `T… P… Z… D…` lines: stanok-interp must not depend on stanok-machine, whose `.tbl` reader is
/// the real one (and is tested there).
pub fn corpus_tool_table() -> ToolTable {
    let text = std::fs::read_to_string(corpus("rs274ngc").join("tool.tbl")).unwrap();
    let mut table = ToolTable::default();
    for line in text.lines() {
        let words = line.split(';').next().unwrap_or("");
        let mut tool = Tool::default();
        let mut e = ToolEdge::default();
        for w in words.split_whitespace() {
            let (letter, value) = w.split_at(1);
            let v: f64 = value.parse().unwrap_or_else(|_| panic!("tool.tbl: {w}"));
            match letter {
                "T" => tool.number = v as u32,
                "P" => tool.pocket = v as u32,
                "Z" => e.offset.z = v * 25.4,
                "D" => e.radius = v * 25.4 / 2.0,
                _ => panic!("tool.tbl: unexpected word {w}"),
            }
        }
        if tool.number > 0 {
            tool.edges.push(e);
            table.tools.insert(tool.number, tool);
        }
    }
    table
}

/// Options that reproduce LinuxCNC's standalone `rs274 -t tool.tbl` for RS274/NGC: the corpus
/// tool table, and parameters in inches (its simulated machine's units).
pub fn options(dialect: Dialect) -> InterpOptions {
    let mut opts = InterpOptions::new(dialect);
    if dialect == Dialect::Rs274ngc {
        opts.control.tools = corpus_tool_table();
        opts.rs274_machine_units = LengthUnits::Inches;
    }
    opts
}

/// Runs a program; returns the commands before the first error and that error.
pub fn run(text: &str, dialect: Dialect) -> (Vec<Spanned<Canon>>, Option<Diagnostic>) {
    run_with(text, options(dialect))
}

/// Runs a program with the given options.
pub fn run_with(text: &str, opts: InterpOptions) -> (Vec<Spanned<Canon>>, Option<Diagnostic>) {
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

/// The comparison rules of every LinuxCNC parity check (`stanok_canon::linuxcnc_trace`).
#[allow(unused_imports)]
pub use stanok_canon::linuxcnc_trace::same_line;

/// An rs274 trace file split into canon lines (counter stripped, exit ON_RESET pair removed), the
/// error message and the offending block (both empty when the run succeeded).
pub struct Trace {
    pub lines: Vec<String>,
    pub error: Option<(String, String)>,
}

pub fn read_trace(text: &str) -> Trace {
    let t = stanok_canon::linuxcnc_trace::parse(text);
    Trace {
        lines: t.lines,
        error: t.error.map(|m| (m, t.error_block.unwrap_or_default())),
    }
}
