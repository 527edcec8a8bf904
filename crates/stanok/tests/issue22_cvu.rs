//! Issue 22 (conformance audit), Balt-System CVU items 13–16 (cvu-five-axis.md), on the built-in
//! TT head `5axis-cvu-tt` (FAT=C,0,0,0,A,0,0,0: C outer, A inner): machine axes at block ends
//! (1e-4 mm/deg) or the error code.

mod five_axis_harness;
use five_axis_harness::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind};
use stanok_canon::{DiagCode, Pose};
use stanok_machine::MachineData;
use stanok_syntax::Dialect;

const A: usize = 3;
const C: usize = 5;
const TOL: f64 = 1e-4;

/// Correctors 1 and 2 with tool length `l`.
fn control(l: f64) -> ControlData {
    let mut c = ControlData::default();
    for n in [1, 2] {
        c.tools.tools.insert(
            n,
            Tool {
                number: n,
                kind: ToolKind::Milling,
                edges: vec![ToolEdge {
                    length: [l, 0.0, 0.0],
                    ..Default::default()
                }],
                ..Default::default()
            },
        );
    }
    c
}

fn cvu(text: &str, l: f64) -> Run {
    run(text, Dialect::Balt, "5axis-cvu-tt", control(l), Pose::ZERO)
}

#[test]
fn issue22_cvu0_with_the_tool_tilted_is_a_format_error() {
    let r = cvu(
        "T2.2 M6\nCVU=1\nG1 X10 F1000\nG1 A20\nCVU=0\nG1 X20\nM30\n",
        50.0,
    );
    let err = r.error.as_ref().expect("CVU=0 at A20 must be refused");
    assert_eq!(
        err.code,
        DiagCode::Stanok("balt::cvu-precondition"),
        "{err}"
    );
    assert!(err.message.starts_with("Format error"), "{err}");
    assert_eq!(err.span.line, 5);
    // Back at A0 first: accepted, and X20 is a 3-axis move of the tip.
    let r = cvu(
        "T2.2 M6\nCVU=1\nG1 X10 F1000\nG1 A20\nG1 A0\nCVU=0\nN10 G1 X20\nM30\n",
        50.0,
    );
    r.ok();
    // Z was never programmed: the machine Z stays at its start, 0.
    assert_axes(r.end_of("N10"), [20.0, 0.0, 0.0], &[(A, 0.0)], TOL, "N10");
}

#[test]
fn issue22_cvu_ijk_takes_the_least_angular_travel() {
    // §5.8: from A30 C170, u = (0.3, −0.2, 0.8): S1 = (A24.2608, C56.3099) travels
    // 5.7392 + 113.6901 = 119.43°; S2 = (A−24.2608, C236.3099) 54.26 + 66.31 = 120.57°.
    let r = cvu(
        "T1.1 M6\nCVU=1\nG1 X0 Y0 Z0 F1000\nG1 A30 C170\nN10 G1 X6 I0.3 J-0.2 K0.8\nM30\n",
        100.0,
    );
    r.ok();
    let q = r.end_of("N10");
    assert!((q[A] - 24.2608).abs() < TOL, "A {}", q[A]);
    assert!((q[C] - 56.3099).abs() < TOL, "C {}", q[C]);
}

#[test]
fn issue22_cvu1_keeps_the_meaning_of_z() {
    // L = 50: Z5 is the tip before, during and after CVU=1 — machine Z 55 at A0 each time.
    let r = cvu(
        "T1.1 M6\nN10 G0 X0 Y0 Z5\nCVU=1\nN20 G1 Z5 F1000\nN30 G1 X10\nCVU=0\nN40 G0 Z5\nN50 G0 Z20\nM30\n",
        50.0,
    );
    r.ok();
    assert_axes(r.end_of("N10"), [0.0, 0.0, 55.0], &[(A, 0.0)], TOL, "N10");
    assert_axes(r.end_of("N20"), [0.0, 0.0, 55.0], &[(A, 0.0)], TOL, "N20");
    assert_axes(r.end_of("N30"), [10.0, 0.0, 55.0], &[(A, 0.0)], TOL, "N30");
    assert_axes(r.end_of("N40"), [10.0, 0.0, 55.0], &[(A, 0.0)], TOL, "N40");
    assert_axes(r.end_of("N50"), [10.0, 0.0, 70.0], &[(A, 0.0)], TOL, "N50");
    // No block moves Z between N10 and N40: no jump at either switch.
    let z_moves: Vec<_> = r
        .setpoints
        .windows(2)
        .filter(|w| (w[1].joints[2] - w[0].joints[2]).abs() > 1e-9)
        .filter(|w| w[0].line > r.line_of("N10") && w[1].line < r.line_of("N50"))
        .collect();
    assert!(z_moves.is_empty(), "{:?}", &z_moves[..z_moves.len().min(3)]);
}

#[test]
fn issue22_cvu_half_circle_needs_r_minus() {
    let r = cvu("G1 X0 Y0 F100\nG2 X20 Y0 R10\nM30\n", 0.0);
    let err = r.error.as_ref().expect("R+ for 180° must be refused");
    assert_eq!(err.code, DiagCode::Stanok("balt::arc"), "{err}");
    assert_eq!(err.span.line, 2);
    // R− is the 180° arc; R+ just under 180° (chord 19.99) stays allowed.
    cvu("G1 X0 Y0 F100\nN10 G2 X20 Y0 R-10\nM30\n", 0.0).ok();
    cvu("G1 X0 Y0 F100\nN10 G2 X19.99 Y0 R10\nM30\n", 0.0).ok();
}

#[test]
fn issue22_fat_axis_missing_from_the_machine_is_error_169() {
    let text = include_str!("../../../machines/5axis-cvu-tt.toml")
        .replace("fat = \"C,0,0,0,A,0,0,0\"", "fat = \"C,0,0,0,B,0,0,0\"");
    let err = MachineData::from_toml_str(&text, "tt.toml").unwrap_err();
    assert!(err.message.contains("FAT error 169"), "{err}");
}

/// §6.4: "If d > 2r, raise an error" — for R+ and R− alike, naming the distance and the
/// diameter (the message once printed the geometry error's Debug form for R−, and "sweeps 180° or
/// more" for R+, which is not the fault).
#[test]
fn cvu_arc_whose_end_is_beyond_the_diameter_is_refused_for_both_signs() {
    for r in ["R10", "R-10"] {
        let run = cvu(&format!("G1 X0 Y0 F100\nG2 X30 Y0 {r}\nM30\n"), 0.0);
        let err = run
            .error
            .as_ref()
            .expect("d = 30 > 2r = 20 must be refused");
        assert_eq!(err.code, DiagCode::Stanok("balt::arc"), "{err}");
        assert_eq!(err.span.line, 2);
        assert!(
            err.message.contains("30.0000 mm") && err.message.contains("20.0000 mm"),
            "{err}"
        );
        assert!(!err.message.contains('{'), "no Debug form: {err}");
    }
}

/// A feed move without F outside CVU=1 says so without blaming CVU=1.
#[test]
fn cvu_feed_missing_note_names_cvu_only_under_cvu() {
    let run = cvu("G1 X1\nM30\n", 0.0);
    let err = run.error.as_ref().expect("no feed");
    assert_eq!(err.code, DiagCode::Stanok("balt::feed-missing"), "{err}");
    assert!(!format!("{err:?}").contains("CVU=1"), "{err:?}");
    let run = cvu("CVU=1\nG1 X1\nCVU=0\nM30\n", 0.0);
    let err = run.error.as_ref().expect("no feed after CVU=1");
    assert!(format!("{err:?}").contains("after CVU=1"), "{err:?}");
}
