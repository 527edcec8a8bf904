//! AxiOMA tool data: T and D with M06/M66 (spec axioma-2 §3.9–§3.10) and tool length compensation
//! G43/G44/G45/G49 with the plane and tool-type assignment of L1–L3 (spec axioma-3 §3). Fixtures
//! s6_10*, s6_11*, s9_1_*; tool table set-ups as the fixture comments state (T1: drill, L1 = 20).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind};
use stanok_canon::{Canon, DiagCode, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn tools() -> ControlData {
    let mut c = ControlData::default();
    let edge = |l1: f64| ToolEdge {
        length: [l1, 0.0, 0.0],
        ..Default::default()
    };
    c.tools.tools.insert(
        1,
        Tool {
            number: 1,
            kind: ToolKind::Drilling,
            edges: vec![edge(20.0)],
            ..Default::default()
        },
    );
    c.tools.tools.insert(
        2,
        Tool {
            number: 2,
            kind: ToolKind::Milling,
            edges: vec![edge(50.0), edge(55.0)],
            ..Default::default()
        },
    );
    c
}

fn run_tools(text: &str) -> (Vec<Spanned<Canon>>, Option<stanok_canon::Diagnostic>) {
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.control = tools();
    let mut out = Vec::new();
    for item in Interpreter::from_text(text, opts) {
        match item {
            Ok(c) => out.push(c),
            Err(d) => return (out, Some(d)),
        }
    }
    (out, None)
}

fn ends_by_n(cmds: &[Spanned<Canon>]) -> Vec<(u32, [f64; 3])> {
    cmds.iter()
        .filter_map(|c| {
            c.value
                .motion()
                .map(|m| (c.block_number.unwrap_or(0), m.end().xyz()))
        })
        .collect()
}

#[track_caller]
fn assert_end(ends: &[(u32, [f64; 3])], n: u32, want: [f64; 3]) {
    let got = ends
        .iter()
        .rev()
        .find(|e| e.0 == n)
        .unwrap_or_else(|| panic!("no move in N{n}"))
        .1;
    assert!(
        (0..3).all(|k| (got[k] - want[k]).abs() < TOL),
        "N{n}: got {got:?}, want {want:?}"
    );
}

fn fixture(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap()
}

#[test]
fn s9_1_2_length_compensation_follows_the_plane() {
    let (cmds, err) = run_tools(&fixture(
        "s9_1_2-g43-g44-g49-length-comp-planes-example-9_1.nc",
    ));
    assert!(err.is_none(), "{err:?}");
    let e = ends_by_n(&cmds);
    // The manual's block comments: G17 → Z+20; G18 → Y+20; G19 → X+20; G44 → X−20; G49 → 0.
    assert_end(&e, 40, [0.0, 0.0, 20.0]);
    assert_end(&e, 60, [0.0, 20.0, 0.0]);
    assert_end(&e, 80, [20.0, 0.0, 0.0]);
    assert_end(&e, 100, [-20.0, 0.0, 0.0]);
    assert_end(&e, 120, [0.0, 0.0, 0.0]);
}

#[test]
fn s9_1_2_g45_keeps_the_tool_along_z_in_g18() {
    let (cmds, err) = run_tools(&fixture("s9_1_2-g45-fixed-base-orientation-example-9_2.nc"));
    assert!(err.is_none(), "{err:?}");
    let e = ends_by_n(&cmds);
    assert_end(&e, 40, [0.0, 0.0, 20.0]);
    assert_end(&e, 50, [60.0, 0.0, 20.0]);
    let arc = cmds
        .iter()
        .find_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(a.clone()),
            _ => None,
        })
        .unwrap();
    assert!(
        (arc.centre[0] - 30.0).abs() < TOL && (arc.centre[2] - 20.0).abs() < TOL,
        "{:?}",
        arc.centre
    );
    assert!(arc.axis[1].abs() > 0.99, "a semicircle in the ZX plane");
}

#[test]
fn s6_10_t0_switches_length_compensation_off() {
    let (cmds, err) = run_tools(&fixture("s6_10-tool-number-t-example-6_6.nc"));
    assert!(err.is_none(), "{err:?}");
    let e = ends_by_n(&cmds);
    // N40 moves with T2's L1 = 50 on Z although Z is not programmed; N60 without offset.
    assert_end(&e, 40, [10.0, 10.0, 50.0]);
    assert_end(&e, 60, [0.0, 0.0, 0.0]);
}

#[test]
fn s6_11_edges_select_compensation_values() {
    let (cmds, err) = run_tools(&fixture("s6_11-cutting-edge-d0-example-6_8.nc"));
    assert!(err.is_none(), "{err:?}");
    let e = ends_by_n(&cmds);
    assert_end(&e, 40, [10.0, 10.0, 50.0]);
    assert_end(&e, 60, [0.0, 0.0, 0.0]);
    // T1, then T2 D2, then D1 of T2: two tool changes; D alone changes no tool.
    let (cmds, err) = run_tools(&fixture("s6_11-cutting-edge-d-example-6_7.nc"));
    assert!(err.is_none(), "{err:?}");
    let changes: Vec<(u32, u32)> = cmds
        .iter()
        .filter_map(|c| match c.value {
            Canon::ChangeTool { tool, .. } => Some((c.block_number.unwrap_or(0), tool)),
            _ => None,
        })
        .collect();
    assert_eq!(changes, [(20, 1), (40, 2)]);
    // With G43 the edge's own length applies: D2 of T2 is 55, D1 is 50.
    let (cmds, _) =
        run_tools("G17 G90 F100\nG43\nN10 T2 D2 M06\nN20 G01 X1\nN30 D1 M06\nN40 G01 X2\nM30\n");
    let e = ends_by_n(&cmds);
    assert_end(&e, 20, [1.0, 0.0, 55.0]);
    assert_end(&e, 40, [2.0, 0.0, 50.0]);
}

#[test]
fn tool_errors() {
    for (block, code) in [
        ("D2\n", "axioma::d-without-tool-change"),
        ("T1 D2 M06\n", "axioma::edge-missing"),
        ("T1 D5 M06\n", "axioma::edge-range"),
    ] {
        let (_, err) = run_tools(&format!("G17 G90\n{block}M30\n"));
        let err = err.unwrap_or_else(|| panic!("{block}: no error"));
        assert_eq!(err.code, DiagCode::Stanok(code), "{block}: {err}");
    }
    // A tool missing from the table is a warning: it counts as length 0.
    let mut it = Interpreter::from_text(
        "G43\nT9 M06\nG00 X1\nM30\n",
        InterpOptions::new(Dialect::Axioma),
    );
    let ends: Vec<f64> = it
        .by_ref()
        .filter_map(|c| c.ok()?.value.motion().map(|m| m.end().z))
        .collect();
    assert_eq!(ends, [0.0]);
    assert!(it
        .warnings()
        .iter()
        .any(|w| w.code == DiagCode::Stanok("axioma::tool-not-in-table")));
}

// ------------------------------------------------------------------ G28 / G29 home positions

fn homes() -> ControlData {
    let mut c = tools();
    c.offsets.home[0] = Some(stanok_canon::Pose {
        x: 100.0,
        y: 200.0,
        z: 300.0,
        ..Default::default()
    });
    c.offsets.home[1] = Some(stanok_canon::Pose {
        x: -50.0,
        y: -60.0,
        z: 250.0,
        ..Default::default()
    });
    c
}

fn run_homes(text: &str) -> (Vec<Spanned<Canon>>, Option<stanok_canon::Diagnostic>, usize) {
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.control = homes();
    let mut it = Interpreter::from_text(text, opts);
    let mut out = Vec::new();
    for item in it.by_ref() {
        match item {
            Ok(c) => out.push(c),
            Err(d) => return (out, Some(d), 0),
        }
    }
    let warnings = it.warnings().len();
    (out, None, warnings)
}

#[test]
fn s6_9_home_position_via_intermediate_point_and_back() {
    let (cmds, err, warnings) = run_homes(&fixture("s6_9-home-position-g28-g29-example-6_5.nc"));
    assert!(err.is_none(), "{err:?}");
    // `G28 N1 Z77`: N1 read as H1, with a warning.
    assert!(warnings >= 1);
    let path: Vec<[f64; 3]> = cmds
        .iter()
        .filter_map(|c| c.value.motion().map(|m| m.end().xyz()))
        .collect();
    let home = [100.0, 200.0, 300.0];
    assert_eq!(
        path,
        [
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 77.0],
            home,
            [0.0, 0.0, 77.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 77.0],
            home,
            [0.0, 0.0, 77.0],
            [0.0, 0.0, 0.0],
        ]
    );
    assert!(cmds
        .iter()
        .filter(|c| c.value.motion().is_some())
        .all(|c| matches!(c.value, Canon::StraightTraverse(_))));
}

#[test]
fn s6_9_block_forms_and_return_via_b() {
    let (cmds, err, _) = run_homes(&fixture("s6_9_1-g28-block-forms-fragment.nc"));
    assert!(err.is_none(), "{err:?}");
    let path: Vec<[f64; 3]> = cmds
        .iter()
        .filter_map(|c| c.value.motion().map(|m| m.end().xyz()))
        .collect();
    // Lines 1 and 2 are the same (order of H and axes does not matter); line 3 uses H1.
    assert_eq!(
        path,
        [
            [50.0, 40.0, 0.0],
            [-50.0, -60.0, 250.0],
            [50.0, 40.0, 250.0],
            [-50.0, -60.0, 250.0],
            [20.0, 30.0, 250.0],
            [100.0, 200.0, 300.0],
        ]
    );
    let (cmds, err, _) = run_homes(&fixture("s6_9_2-g28-tool-change-g29-fragment.nc"));
    assert!(err.is_none(), "{err:?}");
    let path: Vec<[f64; 3]> = cmds
        .iter()
        .filter_map(|c| c.value.motion().map(|m| m.end().xyz()))
        .collect();
    // To H1 via B (1000, 500), tool change, back via B to C (1300, 200).
    assert_eq!(
        path,
        [
            [1000.0, 500.0, 0.0],
            [100.0, 200.0, 300.0],
            [1000.0, 500.0, 0.0],
            [1300.0, 200.0, 0.0]
        ]
    );
    assert!(cmds
        .iter()
        .any(|c| matches!(c.value, Canon::ChangeTool { tool: 1, .. })));
}

#[test]
fn home_errors() {
    for (block, code) in [
        ("G28 H3\n", "axioma::home-undefined"),
        ("G28 H9\n", "axioma::home-range"),
        ("G29 X0\n", "axioma::g29-without-g28"),
    ] {
        let (_, err, _) = run_homes(&format!("G17 G90\n{block}M30\n"));
        let err = err.unwrap_or_else(|| panic!("{block}: no error"));
        assert_eq!(err.code, DiagCode::Stanok(code), "{block}: {err}");
    }
}

#[test]
fn s6_9_s6_10_s6_11_syntax_fragments_and_two_spindles() {
    // G28 H2 directly; G29 without G28 (the fragment alone) is an error.
    let (cmds, err, _) = run_homes(&fixture("s6_9_1-g28-syntax-example.nc"));
    assert!(err.is_none(), "{err:?}");
    let ends: Vec<[f64; 3]> = cmds
        .iter()
        .filter_map(|c| c.value.motion().map(|m| m.end().xyz()))
        .collect();
    assert_eq!(ends, [[-50.0, -60.0, 250.0]]);
    let (_, err, _) = run_homes(&fixture("s6_9_2-g29-block-fragment.nc"));
    assert_eq!(
        err.map(|d| d.code),
        Some(DiagCode::Stanok("axioma::g29-without-g28"))
    );
    // Tool selections: T10 M66, T2=10 M06 (spindle 2); T1, T3, then T2 and T2=3.
    let changes = |text: &str| -> Vec<String> {
        let (cmds, err) = run_tools(text);
        assert!(err.is_none(), "{err:?}");
        cmds.iter()
            .filter_map(|c| match c.value {
                Canon::ChangeTool { tool, .. } => Some(format!("T{tool}")),
                Canon::ChangeSpindleTool { spindle, tool } => {
                    Some(format!("S{}:T{tool}", spindle + 1))
                }
                _ => None,
            })
            .collect()
    };
    assert_eq!(
        changes(&fixture("s6_10-tool-number-syntax-examples.nc")),
        ["T10", "S2:T10"]
    );
    assert_eq!(
        changes(&fixture("s6_10-tool-select-fragments.nc")),
        ["T1", "T3", "T2", "S2:T3"]
    );
    // D alone changes no tool.
    assert_eq!(
        changes(&fixture("s6_11-cutting-edge-syntax-examples.nc")),
        Vec::<String>::new()
    );
    assert_eq!(
        changes(&fixture("s6_11-two-spindle-tool-edge-example-6_9.nc")),
        ["T1", "S2:T2", "T2", "S2:T3", "T0", "S2:T0"]
    );
}
