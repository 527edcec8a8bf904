//! The converted RS274/NGC programs are real LinuxCNC programs: LinuxCNC 2.9's own interpreter
//! (`rs274 -g`) read each of them, and its traces are the goldens in `tests/linuxcnc/`
//! (`scripts/convert-linuxcnc-goldens.sh` makes them; this test needs no LinuxCNC). Here Stanok
//! converts the same sources again, interprets the converted text and prints it in LinuxCNC's
//! format: every line must match LinuxCNC's, numbers within 1.0001e-4 (both print 4 decimals).
//! With the round-trip test this closes the loop: source → converted program → LinuxCNC reads the
//! same canonical calls as Stanok, which are the source's motions.

use stanok_canon::linuxcnc::LinuxCncPrinter;
use stanok_canon::setup::{Tool, ToolEdge, ToolTable};
use stanok_convert::{convert, ConvertOptions, Target};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;
use std::io::Cursor;
use std::path::PathBuf;

const TOL: f64 = 1.0001e-4;

/// (golden name, source dialect, source relative to the repository) — the list of the script.
const CASES: &[(&str, Dialect, &str)] = &[
    ("demo-plate", Dialect::Axioma, "examples/demo-plate.nc"),
    (
        "demo-bolt-circle",
        Dialect::Rs274ngc,
        "examples/demo-bolt-circle.ngc",
    ),
    (
        "planes-helices-splines",
        Dialect::Rs274ngc,
        "crates/stanok-convert/tests/programs/planes-helices-splines.ngc",
    ),
    (
        "technology-frames-cycles",
        Dialect::Rs274ngc,
        "crates/stanok-convert/tests/programs/technology-frames-cycles.ngc",
    ),
    (
        "lathe-cycles-g70-g72",
        Dialect::Rs274ngc,
        "crates/stanok-convert/tests/programs/lathe-cycles-g70-g72.ngc",
    ),
    (
        "axioma-aspline",
        Dialect::Axioma,
        "../shared/corpus/axioma/s5_4_1-aspline-akima-example-5_15.nc",
    ),
    (
        "axioma-g42-turning",
        Dialect::Axioma,
        "../shared/corpus/axioma/s9_2_1-g42-turning-contour-example-9_7.nc",
    ),
    (
        "axioma-g387-pocket",
        Dialect::Axioma,
        "../shared/corpus/axioma/s11_8_1-g387-rectangular-pocket-example-11_12.nc",
    ),
];

fn repo(rel: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join(rel)
}

/// The trace without its counter column and without rs274's closing `executing`.
fn calls(text: &str) -> Vec<String> {
    text.lines()
        .map(|l| l.trim_start())
        .filter(|l| !l.is_empty() && *l != "executing")
        .map(|l| match l.split_once(' ') {
            Some((n, rest)) if n.bytes().all(|b| b.is_ascii_digit()) => rest.trim().to_string(),
            _ => l.to_string(),
        })
        .collect()
}

/// Same text, numbers within `TOL`.
fn same_line(a: &str, b: &str) -> bool {
    let split = |s: &str| -> Vec<String> {
        s.split(|c: char| c == ',' || c == '(' || c == ')' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .map(str::to_string)
            .collect()
    };
    let (ta, tb) = (split(a), split(b));
    ta.len() == tb.len()
        && ta
            .iter()
            .zip(&tb)
            .all(|(x, y)| match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(u), Ok(v)) => (u - v).abs() <= TOL,
                _ => x == y,
            })
}

/// The tool table `rs274` uses when given none (`-t` absent), as the goldens were made: tools 1, 2
/// and 3 in slots 1, 2 and 3, all of zero size (it prints `CHANGE_TOOL(slot)`; T4 is "not found").
fn rs274_default_tools() -> ToolTable {
    let mut table = ToolTable::default();
    for number in 1..=3 {
        table.tools.insert(
            number,
            Tool {
                number,
                pocket: number,
                edges: vec![ToolEdge::default()],
                ..Tool::default()
            },
        );
    }
    table
}

#[test]
fn linuxcnc_reads_the_converted_programs_as_stanok_does() {
    let mut failures = Vec::new();
    for &(name, dialect, rel) in CASES {
        let path = repo(rel);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{rel}: {e}"));
        let file_name = path.file_name().unwrap().to_string_lossy().into_owned();
        let mut opts = InterpOptions::new(dialect);
        opts.subroutine_path = vec![path.parent().unwrap().to_path_buf()];
        let source: Vec<_> = Interpreter::new(Cursor::new(text.into_bytes()), opts)
            .map_while(Result::ok)
            .collect();
        let dialect_name = format!("{dialect:?}").to_lowercase();
        let (converted, _) = convert(
            &source,
            ConvertOptions::new(Target::Rs274ngc, &file_name, &dialect_name),
        );
        let mut printer = LinuxCncPrinter::new();
        let mut ours = String::new();
        let mut opts = InterpOptions::new(Dialect::Rs274ngc);
        opts.control.tools = rs274_default_tools();
        for item in Interpreter::new(Cursor::new(converted.clone().into_bytes()), opts) {
            match item {
                Ok(cmd) => ours.push_str(printer.print(&cmd)),
                Err(d) => {
                    failures.push(format!("{name}: converted program fails: {}", d.message));
                    break;
                }
            }
        }
        ours.push_str(printer.finish());
        let golden_path = repo(&format!(
            "crates/stanok-convert/tests/linuxcnc/{name}.canon.txt"
        ));
        let golden = std::fs::read_to_string(&golden_path)
            .unwrap_or_else(|e| panic!("{}: {e}", golden_path.display()));
        let (want, got) = (calls(&golden), calls(&ours));
        if let Some(i) = (0..want.len().max(got.len())).find(|&i| match (want.get(i), got.get(i)) {
            (Some(a), Some(b)) => !same_line(a, b),
            _ => true,
        }) {
            failures.push(format!(
                "{name}: call {} differs:\n  LinuxCNC: {}\n  Stanok:   {}",
                i + 1,
                want.get(i).map_or("(none)", String::as_str),
                got.get(i).map_or("(none)", String::as_str)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
