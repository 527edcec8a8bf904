//! AxiOMA radius-compensation activation rule (spec axioma-3 §4.3 rule 1, error [D]): after
//! G41/G42/G143/G144 is switched on from G40 — or G40 ends G41/G42 — a G00/G01 block (modally
//! active counts) must come in the same or the next block.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

fn run_r5(text: &str) -> Option<stanok_canon::Diagnostic> {
    let mut c = ControlData::default();
    c.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: 5.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.control = c;
    run_with(text, opts).1
}

const HEAD: &str = "G17 G90 G71 G40 G01 F1000\nT1 M06 D1\nG00 X-10 Y-10\n";

#[test]
fn g41_is_realised_by_a_linear_block_in_the_same_or_the_next_block() {
    // Same block, next block, and modal G01 (example 9.4's `G41 X0 Y0`): all fine.
    const SQUARE: &str = "X0 Y100\nX100 Y100\nX100 Y0\nX0 Y0\n";
    for (entry, exit) in [
        ("G41 G01 X0 Y0\n", "G40 X-10 Y-10\n"),
        ("G41\nG01 X0 Y0\n", "G40\nG01 X-10 Y-10\n"),
        ("G01 X-10 Y-5\nG41 X0 Y0\n", "G40 X-10 Y-10\n"),
    ] {
        let body = format!("{entry}{SQUARE}{exit}");
        let err = run_r5(&format!("{HEAD}{body}M30\n"));
        assert!(err.is_none(), "{body}: {err:?}");
    }
    // A block without motion between the selection and the first move: error at that block.
    let err = run_r5(&format!(
        "{HEAD}G41\nM08\nG01 X0 Y0\n{SQUARE}G40 X-10 Y-10\nM30\n"
    ))
    .unwrap();
    assert_eq!(err.code.to_string(), "axioma::comp-linear-due");
    assert_eq!(err.span.line, 5, "{err}");
    // The same after G40 ends G41.
    let err = run_r5(&format!(
        "{HEAD}G41 G01 X0 Y0\n{SQUARE}G40\nM09\nG01 X-10 Y-10\nM30\n"
    ))
    .unwrap();
    assert_eq!(err.code.to_string(), "axioma::comp-linear-due");
    assert_eq!(err.span.line, 10, "{err}");
}
