//! The block transaction, for every front end: after each kind of state change a front end has,
//! a block that changes the same kind of state and then fails leaves the whole state as it was —
//! the common modal state, the commands not yet released (queue and staging), the stored control
//! data and the front end's own state (`Interpreter::state_dump`) — and emits nothing.
//!
//! Each failing block fails at its dialect's *last* check (a word nothing used, or the motion),
//! so every step of the block before it has run and changed what it changes: the test fails if
//! any of those changes escapes the undo. The error's code and line are asserted, so that a case
//! cannot pass by failing early.

#[path = "common/mod.rs"]
mod common;

use stanok_canon::setup::{Tool, ToolEdge};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

/// Runs `prefix` unit by unit, then `failing` (its last line): the state dump before the failing
/// unit and after it must be equal, and the error must be `code` on the failing line.
fn check(opts: InterpOptions, prefix: &str, failing: &str, code: &str) {
    let line = prefix.lines().count() as u32 + failing.lines().count() as u32;
    check_at(opts, prefix, failing, code, line);
}

/// [`check`] with the failing block on line `line` (a subroutine's line, run by a call).
fn check_at(opts: InterpOptions, prefix: &str, failing: &str, code: &str, line: u32) {
    let text = format!("{prefix}{failing}\n");
    let mut it = Interpreter::from_text(&text, opts);
    for _ in 0..10_000 {
        let before = it.state_dump();
        match it.step_unit() {
            Ok(false) => continue,
            Ok(true) => panic!("the program ended without an error:\n{text}"),
            Err(d) => {
                assert_eq!(
                    (d.code.to_string().as_str(), d.span.line),
                    (code, line),
                    "{d:?}\nin:\n{text}"
                );
                let after = it.state_dump();
                if before != after {
                    let diff: Vec<String> = before
                        .lines()
                        .zip(after.lines())
                        .filter(|(a, b)| a != b)
                        .map(|(a, b)| format!("before: {a}\nafter:  {b}"))
                        .collect();
                    panic!(
                        "the failing block changed the state:\n{}\nin:\n{text}",
                        diff.join("\n")
                    );
                }
                return;
            }
        }
    }
    panic!("no error after 10000 units:\n{text}");
}

const RS274_START: &str = "G21 G17 G90 G94 F100\nT1 M6\nG43 H1\nS1000 M3\n";

fn rs274(prefix: &str, failing: &str, code: &str) {
    let opts = common::options(Dialect::Rs274ngc);
    check(opts, &format!("{RS274_START}{prefix}"), failing, code);
}

const RS274_UNUSED: &str = "interp::unused-word";

#[test]
fn rs274_modal_groups() {
    rs274(
        "G91\nG20\nG18\nG64 P0.01 Q0.01\nG99\n",
        "G17 G21 G90 G95 F0.2 S800 G61 G98 M8 G7 G90.1 G1 X1 Y1 Q5",
        RS274_UNUSED,
    );
    rs274("G95 F0.1\nG93\n", "G94 F300 G1 X5 Q5", RS274_UNUSED);
}

#[test]
fn rs274_work_offsets_and_frames() {
    let offsets = "G10 L2 P2 X5 Y5 R30\nG55\nG92 X1\nG52 Z1\n";
    rs274(offsets, "G10 L2 P2 X7 Q1", RS274_UNUSED);
    rs274(offsets, "G10 L20 P2 X7 Q1", RS274_UNUSED);
    rs274(offsets, "G92 X3 Q1", RS274_UNUSED);
    rs274(offsets, "G92.1 Q1", RS274_UNUSED);
    rs274(offsets, "G52 X3 Q1", RS274_UNUSED);
    rs274(offsets, "G54 G1 X1 Q1", RS274_UNUSED);
    rs274(offsets, "G28.1 Q1", RS274_UNUSED);
}

#[test]
fn rs274_tools() {
    rs274("T2 M6\nG43 H2\n", "T10 M6 G43 H10 G1 X1 Q5", RS274_UNUSED);
    rs274("G43.1 Z1\n", "G49 G1 X1 Q5", RS274_UNUSED);
    rs274("", "G10 L1 P10 Z1 R1 K5", RS274_UNUSED);
    rs274("", "T2 M61 Q2 G1 X1 E5", RS274_UNUSED);
}

#[test]
fn rs274_parameters() {
    rs274(
        "#1 = 5\n#<_g> = 3\n#<loc> = 2\n",
        "#1 = 6 #<_g> = 4 #2 = 1 #<loc> = 7 G1 X#1 Q1",
        RS274_UNUSED,
    );
    rs274("M70\n", "M73 G91 G20 G1 X1 Q1", RS274_UNUSED);
    rs274("M70\n", "M72 G1 X1 Q1", RS274_UNUSED);
}

#[test]
fn rs274_cutter_compensation_look_ahead() {
    let comp = "G0 X0 Y0\nG41 D1 G1 X10 Y0\nG1 X10 Y10\n";
    rs274(comp, "G1 X0 Y10 Q1", RS274_UNUSED);
    rs274(comp, "G3 X0 Y0 R8 Q1", RS274_UNUSED);
    rs274(comp, "G40 G1 X0 Y20 Q1", RS274_UNUSED);
}

#[test]
fn rs274_cycles_splines_and_spindle() {
    rs274(
        "G0 Z5\nG81 X1 Y1 Z-1 R1\n",
        "G82 X2 Y2 Z-2 R2 P1 E1",
        RS274_UNUSED,
    );
    rs274("G5.2 X0 Y0 P1 L3\nX1 Y1 P1\n", "X2 Y0 P1 Q9", RS274_UNUSED);
    rs274("G96 S100 D2000\n", "S200 G1 X1 Q1", RS274_UNUSED);
    // (M48 and M49 are one modal group: one of them.)
    rs274("M50 P0\n", "M5 M49 G1 X1 Q1", RS274_UNUSED);
}

#[test]
fn rs274_inside_a_subroutine_and_a_lathe_profile() {
    let start = RS274_START.lines().count() as u32;
    // The failing block is the subroutine's second line, run by the call.
    check_at(
        common::options(Dialect::Rs274ngc),
        &format!("{RS274_START}o100 sub\n#1 = 2\nG91 G1 X1 Q1\no100 endsub\n"),
        "o100 call [7]",
        RS274_UNUSED,
        start + 3,
    );
    // A G70 profile: its commands are captured (held) while it runs.
    check_at(
        common::options(Dialect::Rs274ngc),
        &format!(
            "{RS274_START}G18 G0 X30 Z30\no100 sub\nG0 X10 Z0\nG1 Z-10\nG1 X14 Q1\no100 endsub\n"
        ),
        "G70 Q100 X20 Z5",
        RS274_UNUSED,
        start + 5,
    );
}

fn axioma(prefix: &str, failing: &str, code: &str) {
    let mut opts = common::options(Dialect::Axioma);
    // Tools 1 and 2: milling cutters of radius 5 and 3.
    for (t, radius) in [(1, 5.0), (2, 3.0)] {
        opts.control.tools.tools.insert(
            t,
            Tool {
                number: t,
                edges: vec![ToolEdge {
                    radius,
                    ..Default::default()
                }],
                ..Default::default()
            },
        );
    }
    check(
        opts,
        &format!("G71 G90 G17 G94 F100\n{prefix}"),
        failing,
        code,
    );
}

const AXIOMA_UNUSED: &str = "interp::unused-word";

#[test]
fn axioma_modal_groups_and_technology() {
    axioma(
        "S1000 M3\nG91\nG18\nSOFT\nG60\n",
        "G90 G17 G70 G95 F0.1 BRISK G64 G99 G191 G1 X1 Y1 E5",
        AXIOMA_UNUSED,
    );
    axioma("M3 S1000\nM8\n", "M4 S500 M9 G1 X1 E5", AXIOMA_UNUSED);
    axioma(
        "G18 G01 X50 Z0\nG96 S300 LMAXS 5000 LMINS 150 REFAX 1\n",
        "G97 S300 G1 X40 E5",
        AXIOMA_UNUSED,
    );
}

#[test]
fn axioma_frames_and_offsets() {
    let frames = "G54\nG73 X-1\nG173 X2 Y1 I0 J0\nG273 Q30\nG193 X1\n";
    axioma(frames, "G55 G1 X1 E5", AXIOMA_UNUSED);
    axioma(frames, "G72 E5", AXIOMA_UNUSED);
    axioma(frames, "G172 E5", AXIOMA_UNUSED);
    axioma(frames, "G272 E5", AXIOMA_UNUSED);
    axioma(frames, "G195 X3 E5", AXIOMA_UNUSED);
    axioma("G16\n", "G15 G1 X1 E5", AXIOMA_UNUSED);
}

#[test]
fn axioma_tools() {
    axioma("T1 M06\nG43\n", "T2 M06 G44 G1 X1 E5", AXIOMA_UNUSED);
}

#[test]
fn axioma_compensation_look_ahead_and_splines() {
    axioma(
        "T1 M06\nG0 X0 Y0\nG41 G1 X10 Y0\nG1 X10 Y10\n",
        "G1 X0 Y10 E5",
        AXIOMA_UNUSED,
    );
    axioma("ASPLINE X0 Y0\nX1 Y1\n", "X2 Y0 E5", AXIOMA_UNUSED);
    axioma(
        "G99\nZ20\nG81 X0 Y0 Z0 Q3=100 Q5=-10\n",
        "G83 X1 Y1 Z0 Q3=100 Q5=-5 Q7=2 E5",
        AXIOMA_UNUSED,
    );
}

#[test]
fn axioma_probe_mode_and_latch() {
    // G75 and its latch are journalled (not copied with the Extension): a failing probe block
    // after a probe move leaves the mode and the latch as they were.
    axioma(
        "G0 X0 Y0 Z10\nG75 G1 X5 Y0 Z0\n",
        "G75 G1 X10 Y5 Z0 E5",
        AXIOMA_UNUSED,
    );
    axioma("G75 G1 X5 Y0 Z0\n", "G1 X10 E5", AXIOMA_UNUSED);
}

#[test]
fn axioma_high_level_language() {
    axioma("int aa = 1;\n", "X=aa++ Y=aa E5", AXIOMA_UNUSED);
}

fn five_axis() -> stanok_kin::FiveAxis {
    stanok_kin::from_fat("C,0,0,0,A,0,0,0").unwrap()
}

#[test]
fn balt_spline_buffer_and_cvu() {
    let opts = || {
        let mut o = InterpOptions::new(Dialect::Balt);
        o.five_axis = Some(five_axis());
        o
    };
    // The spline definition of a failing block (issue 22 item 20: it survived the failure).
    check(
        opts(),
        "G1 F1000\n",
        "(BSP,X,Y,0) G1 X0 Y0 Z0 Q5",
        RS274_UNUSED,
    );
    check(
        opts(),
        "G1 F1000\n(BSP,X,Y,0)\nG1 X0 Y0 Z0\n",
        "G06 X1 Y1 Z0 Q5",
        RS274_UNUSED,
    );
    check(opts(), "G1 F1000\n", "CVU=1 G1 X1 Q5", RS274_UNUSED);
}

/// Issue 22 item 20: a Balt block that fails after `(BSP,…)` or `(ESP)` leaves the spline
/// buffer as it was (it used to live in the AxiOMA state, backed up only for AxiOMA).
#[test]
fn issue22_failing_balt_block_after_bsp_or_esp_leaves_the_spline_buffer() {
    let opts = || {
        let mut o = InterpOptions::new(Dialect::Balt);
        o.five_axis = Some(five_axis());
        o
    };
    // Opening a definition, opening one while another is open, adding nodes, closing it.
    check(
        opts(),
        "G1 F1000\n",
        "(BSP,X,Y,0) G1 X0 Y0 Z0 Q5",
        RS274_UNUSED,
    );
    let open = "G1 F1000\n(BSP,X,Y,0)\nG1 X0 Y0 Z0\nG06 X1 Y1 Z0\nX2 Y0 Z0\n";
    check(opts(), open, "G06 X3 Y1 Z0 Q5", RS274_UNUSED);
    check(opts(), open, "(ESP) Q5", RS274_UNUSED);
    check(opts(), open, "(ESP) G1 X4 Y0 Z0 Q5", RS274_UNUSED);
}

#[test]
fn mazatrol_tool_length_and_tool_tip_control() {
    let opts = || {
        let mut o = InterpOptions::new(Dialect::Mazatrol);
        o.five_axis = Some(five_axis());
        o
    };
    check(
        opts(),
        "G1 F1000\n",
        "T01 T02 M6 G43 H1 G1 X1 Q5",
        RS274_UNUSED,
    );
    check(opts(), "G1 F1000\nG43 H1\n", "G91 G1 X1 Q5", RS274_UNUSED);
    check(opts(), "G1 F1000\n", "G43.4 H1 X1 A10 Q5", RS274_UNUSED);
}

/// Mazatrol EIA/ISO on an M-series mill with tools 1–3 (radius 5, 3, 5) and a subprogram O100
/// after the main program's M30.
fn mazatrol(prefix: &str, failing: &str, code: &str) {
    mazatrol_on(InterpOptions::new(Dialect::Mazatrol), prefix, failing, code);
}

fn mazatrol_on(mut opts: InterpOptions, prefix: &str, failing: &str, code: &str) {
    for (t, radius, length) in [(1, 5.0, 100.0), (2, 3.0, 80.0), (3, 5.0, 90.0)] {
        opts.control.tools.tools.insert(
            t,
            Tool {
                number: t,
                edges: vec![ToolEdge {
                    radius,
                    length: [length, 0.0, 0.0],
                    ..Default::default()
                }],
                ..Default::default()
            },
        );
    }
    let start = "G21 G17 G90 G94 F100\n";
    let line = (start.lines().count() + prefix.lines().count() + failing.lines().count()) as u32;
    check_at(
        opts,
        &format!("{start}{prefix}"),
        &format!("{failing}\nM30\nO100\nG91 G01 X1.\nM99\n"),
        code,
        line,
    );
}

const MAZATROL_UNUSED: &str = "interp::unused-word";

#[test]
fn mazatrol_eia_modes_offsets_and_tools() {
    mazatrol(
        "G91\nG20\nG18\nG61\nG99\nS1000 M03\nM08\n",
        "G17 G90 G64 G98 G95 F0.1 S500 M04 M09 G01 X1. Y1. Q5",
        MAZATROL_UNUSED,
    );
    let offsets = "G10 L2 P2 X5. Y5.\nG55\nG92 X1.\nG52 Z1.\n";
    mazatrol(offsets, "G10 L2 P2 X7. Q1", MAZATROL_UNUSED);
    mazatrol(offsets, "G10 L10 P2 R7. Q1", MAZATROL_UNUSED);
    mazatrol(offsets, "G92 X3. Q1", MAZATROL_UNUSED);
    mazatrol(offsets, "G52 X3. Q1", MAZATROL_UNUSED);
    mazatrol(offsets, "G54 G01 X1. Q1", MAZATROL_UNUSED);
    mazatrol(offsets, "G51 P2. Q1", MAZATROL_UNUSED);
    mazatrol(offsets, "G68 R30. Q1", MAZATROL_UNUSED);
    mazatrol(
        "T01 M06\nG43 H1\n",
        "T02 T03 M06 G44 H2 G01 X1. Q5",
        MAZATROL_UNUSED,
    );
}

#[test]
fn mazatrol_eia_variables_cycles_and_compensation() {
    // An assignment is a block of its own: the second one fails after the first has run.
    mazatrol(
        "#1=5\n#100=3\n#500=2\n",
        "#1=6 #100=4 #500=7 #2=[1/0]",
        "mazatrol::division-by-zero",
    );
    // A canned cycle drills, then the block fails.
    mazatrol(
        "G00 Z10.\nG81 X0 Y0 Z-5. R2. F100.\n",
        "G82 X5. Y5. Z-6. R2. P100 E5",
        MAZATROL_UNUSED,
    );
    // The pending compensated element's end is moved to the corner, then the block fails.
    let comp = "T03 M06\nG00 X-10. Y0\nG41 D3 G01 X0 Y0\nY10.\n";
    mazatrol(comp, "X10. Q1", MAZATROL_UNUSED);
    mazatrol(comp, "G03 X0 Y20. R10. Q1", MAZATROL_UNUSED);
    mazatrol(comp, "G40 G01 X-10. Q1", MAZATROL_UNUSED);
    // A modal call in force: the move runs and the call is asked for, then the block fails.
    mazatrol("G66 P100 A1.\n", "G01 X5. Q1", MAZATROL_UNUSED);
    mazatrol("", "G66 P100 A1. G01", "mazatrol::macro-call");
}

#[test]
fn mazatrol_eia_inside_a_subprogram() {
    // The failing block is the subprogram's first line, run by M98 (line 5 of the text).
    check_at(
        InterpOptions::new(Dialect::Mazatrol),
        "G21 G90 G94 F100\nM98 P100\nM30\nO100\n",
        "G91 G01 X1. Q1\nM99",
        MAZATROL_UNUSED,
        5,
    );
}

#[test]
fn mazatrol_eia_tool_tip_control_on_the_t_series() {
    let mut opts = InterpOptions::new(Dialect::Mazatrol);
    opts.five_axis = Some(five_axis());
    opts.mazatrol.series = stanok_interp::MazatrolSeries::T;
    mazatrol_on(
        opts,
        "G94\nG43.4 H1 X1. A10.\n",
        "G01 X2. A20. C5. Q1",
        MAZATROL_UNUSED,
    );
}

#[test]
fn lab_controls() {
    // The lab front ends run a unit on a copy of their state (`LabRun::step`).
    let gost = InterpOptions::new(Dialect::Gost20999);
    check(
        gost,
        "N1 G90 G1 X10000 F100\nN2 G91\n",
        "N3 G1 X1. X2.",
        "lab::repeated-word",
    );
    // An NC-31 arc group moves nothing before its last frame shows the arc is wrong.
    let nc31 = InterpOptions::new(Dialect::Nc31);
    check_at(
        nc31,
        "N1 X100\nN2 Z10\n",
        "N3 G2*\nN4 X20*\nN5 Z10*\nN6 P-30*\nN7 P11",
        "nc31::arc-radius",
        3,
    );
}
