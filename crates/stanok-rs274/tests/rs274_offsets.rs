//! RS274/NGC offsets and tool data where there is no LinuxCNC golden to compare with: the spec's
//! choices where it differs from LinuxCNC 2.9, Stanok's block atomicity for parameter and tool-table
//! writes, the stored data a run hands back (`.var` persistence), and the options.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{Canon, LengthUnits, Pose};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

/// Runs to the end and returns the interpreter; the program must not fail.
fn run_to_end(text: &str, opts: InterpOptions) -> Interpreter<std::io::Cursor<&[u8]>> {
    let mut it = Interpreter::from_text(text, opts);
    for c in it.by_ref() {
        if let Err(d) = c {
            panic!("{d}\n{text}");
        }
    }
    it
}

fn rs274() -> InterpOptions {
    options(Dialect::Rs274ngc)
}

#[test]
fn a_failing_block_writes_no_parameter_and_no_tool() {
    // Each bad block writes first (G10 L2, G92, G10 L1, G28.1) and fails afterwards on a word
    // nothing uses; `check` mode goes on, so the state after it shows whether anything stuck.
    let mut opts = rs274();
    opts.continue_after_error = true;
    let text = "G21\nG0 X1 Y2\nG10 L2 P2 X5 D3\nG92 X0 D3\nG10 L1 P1 Z1 D3\nG28.1 D3\nM2\n";
    let mut it = Interpreter::from_text(text, opts);
    let errors = it.by_ref().filter(|c| c.is_err()).count();
    assert_eq!(errors, 4);
    let p = it.parameters().unwrap();
    assert_eq!(p.get(5241), 0.0);
    assert_eq!(p.get(5210), 0.0);
    assert_eq!(p.get(5211), 0.0);
    assert_eq!(p.get(5161), 0.0);
    assert_eq!(p.tools().edge(1, 1).unwrap().offset.z, -1.5 * 25.4);
    assert_eq!(*it.state().frame.shift(), Pose::ZERO);
}

#[test]
fn g43_1_with_a_motion_on_the_line_is_an_error() {
    // The document (spec §4.24): "a motion command on the same line" is an error. LinuxCNC 2.9 runs
    // `G43.1 Z1 G0 X1` and takes X1 as a tool offset *and* as the move's end point.
    let (cmds, err) = run("G21\nG43.1 Z1 G0 X1\nM2\n", Dialect::Rs274ngc);
    let err = err.expect("an error");
    assert_eq!(
        err.message,
        "Cannot use two g codes that both use axis values"
    );
    assert_eq!(err.span.line, 2);
    assert!(!cmds
        .iter()
        .any(|c| matches!(c.value, Canon::UseToolLengthOffset { .. })));
    // Without a motion code on the line the modal motion is suspended, as in LinuxCNC.
    let (cmds, err) = run("G21\nG0 X0\nG43.1 Z1\nM2\n", Dialect::Rs274ngc);
    assert!(err.is_none());
    let moves = cmds.iter().filter(|c| c.value.motion().is_some()).count();
    assert_eq!(moves, 1);
}

#[test]
fn t_m6_g43_on_one_line_uses_the_new_tool_and_keeps_the_machine_position() {
    // The spec (§4.12, corpus g10-l10-example-1): the controlled point stays at machine Z2 and reads
    // 2 − (−1.5) = 3.5 in. rs274 resynchronises after M6 and would read 2.
    let it = run_to_end("%\nG20\nG0 Z2\nT1 M6 G43\n%\n", rs274());
    assert!((it.state().position.z - 2.0 * 25.4).abs() < 1e-9);
    assert!((it.state().program_position().z - 3.5 * 25.4).abs() < 1e-9);
}

#[test]
fn t_words_are_checked_only_against_a_tool_table() {
    let (_, err) = run("G21\nT7\nM2\n", Dialect::Rs274ngc);
    assert_eq!(
        err.unwrap().message,
        "Requested tool 7 not found in the tool table"
    );
    // A machine without tool data has nothing to check T against.
    let (cmds, err) = run_with("G21\nT7 M6\nM2\n", InterpOptions::new(Dialect::Rs274ngc));
    assert!(err.is_none(), "{err:?}");
    assert!(cmds
        .iter()
        .any(|c| matches!(c.value, Canon::ChangeTool { tool: 7, .. })));
    // …but G43 H7 needs the tool's data.
    let (_, err) = run_with("G21\nG43 H7\nM2\n", InterpOptions::new(Dialect::Rs274ngc));
    assert!(err.is_some());
}

#[test]
fn g53_shares_group_0_with_g92_and_g10() {
    for line in ["G53 G92 X1", "G92 X1 G53", "G53 G10 L2 P1 X1"] {
        let (_, err) = run(&format!("G21\n{line}\nM2\n"), Dialect::Rs274ngc);
        assert_eq!(
            err.map(|e| e.message),
            Some("Two g codes used from same modal group".to_string()),
            "{line}"
        );
    }
}

#[test]
fn g92_persistence_can_be_disabled() {
    let text = "G21\nG0 X4\nG92 X7\nM2\n";
    let it = run_to_end(text, rs274());
    assert_eq!(it.state().frame.shift().x, -3.0);
    assert_eq!(it.parameters().unwrap().get(5210), 1.0);
    let mut opts = rs274();
    opts.g92_persistence = false;
    let it = run_to_end(text, opts);
    assert_eq!(*it.state().frame.shift(), Pose::ZERO);
    assert_eq!(it.parameters().unwrap().get(5210), 0.0);
    assert_eq!(it.parameters().unwrap().get(5211), 0.0);
}

#[test]
fn the_run_hands_back_its_stored_data_in_mm() {
    // What `stanok --var` writes back: offsets, G28/G30, G92, the active system, preset
    // parameters and the tool table as the program left them, in mm whatever the machine units.
    let mut opts = rs274();
    opts.control.parameters.insert(100, 1.0);
    opts.control.parameters.insert(5399, 0.0);
    let text = "%\nG20\nG10 L2 P2 X1 R10\nG0 X2\nG28.1\nG92 X1\nG10 L1 P1 Z-2\n#100 = 42\n#101 = 7\nG55\n%\n";
    let it = run_to_end(text, opts);
    let c = it.control_data();
    let z = c.offsets.zero_offset(2, 1).unwrap();
    assert!((z.offset.x - 25.4).abs() < 1e-9);
    assert_eq!(z.rotation_xy, 10.0);
    assert!((c.offsets.g28.x - 2.0 * 25.4).abs() < 1e-9);
    assert!((c.offsets.g92.x - 25.4).abs() < 1e-9);
    assert!(c.offsets.g92_applied);
    assert_eq!(c.offsets.active_system, 2);
    assert_eq!(c.parameters.get(&100), Some(&42.0));
    // Only the parameters the run started with are kept (LinuxCNC writes back its file's).
    assert_eq!(c.parameters.get(&101), None);
    assert!((c.tools.edge(1, 1).unwrap().offset.z + 2.0 * 25.4).abs() < 1e-9);
}

#[test]
fn parameters_are_in_the_machine_units() {
    // A mm machine reads its stored lengths in mm, an inch machine in inches, whatever G20/G21.
    for (units, expect) in [(LengthUnits::Millimetres, 25.4), (LengthUnits::Inches, 1.0)] {
        let mut opts = rs274();
        opts.rs274_machine_units = units;
        let it = run_to_end("%\nG20\nG10 L2 P1 X1\nG21\n#1 = #5221\n%\n", opts);
        assert!(
            (it.parameters().unwrap().get(1) - expect).abs() < 1e-9,
            "{units:?}"
        );
    }
}

#[test]
fn g7_halves_every_x_word_but_not_arc_centres() {
    // LinuxCNC halves X words as it reads them (positions, G92, G10, G43.1 alike); I/K stay radii.
    let it = run_to_end("%\nG21 G18\nG7\nG0 X10\nG43.1 X4\n%\n", rs274());
    assert!((it.state().frame.tlo().x - 2.0).abs() < 1e-12);
    assert!((it.state().position.x - 5.0).abs() < 1e-12);
}
