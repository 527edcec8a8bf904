//! Mazatrol G43/G44 tool length offset and its switching with tool tip point control (spec
//! mazatrol-tool-tip-control.md §3, §10, §11; fixtures g43_4-switch-g43-direct.nc and
//! g43_4-switch-g43-via-g49.nc), and the type-1 start with motion (g43_4-type1-start-move.nc)
//! on each built-in machine that has the rotary axes it writes. The source's placeholders are
//! filled with numbers; the machine positions are derived by hand in the comments (§8.2: B head
//! `m = t + (Lp + L)·v(B) − Lp·ẑ`, G43 `m = P + w + L·ẑ`) and asserted to 1e-6 mm / deg.
//!
//! The §3-3 examples run on `5axis-bc-head-table` (an M-series B head + C table, Lp = 150) with
//! T01 L = 100, T02 L = 80 and the work offset w = (0, 0, −300); `T01 T02 M6` puts tool 01's
//! length in force (F93 bit 3 = 1, Note 1 of the examples).

mod five_axis_harness;
use five_axis_harness::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind, ZeroOffset};
use stanok_canon::{Canon, Pose};
use stanok_kin::Kinematics;
use stanok_machine::MachineData;
use stanok_syntax::Dialect;

const A: usize = 3;
const B: usize = 4;
const C: usize = 5;
const TOL: f64 = 1e-6;
/// sin 30°, cos 30° times Lp + L = 250.
const S30: f64 = 125.0;
const C30: f64 = 216.506_350_946_109_66;

fn control(w: [f64; 3]) -> ControlData {
    let mut c = ControlData::default();
    for (n, l) in [(1, 100.0), (2, 80.0)] {
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
    c.offsets.zero[0][0] = ZeroOffset {
        offset: Pose {
            x: w[0],
            y: w[1],
            z: w[2],
            ..Pose::ZERO
        },
        rotation_xy: 0.0,
    };
    c
}

/// The fixture's program lines with the placeholders replaced (longest first).
fn filled(name: &str, values: &[(&str, &str)]) -> String {
    let text = corpus_text(&format!("mazatrol/{name}"));
    let mut sorted = values.to_vec();
    sorted.sort_by_key(|(k, _)| std::cmp::Reverse(k.len()));
    let mut out: String = text
        .lines()
        .filter(|l| !l.starts_with(';'))
        .map(|l| {
            let mut l = l.to_string();
            for (k, v) in &sorted {
                l = l.replace(k, v);
            }
            format!("{l}\n")
        })
        .collect();
    out.push_str("M30\n");
    out
}

fn head_table(text: &str) -> Run {
    run(
        text,
        Dialect::Mazatrol,
        "5axis-bc-head-table",
        control([0.0, 0.0, -300.0]),
        Pose {
            z: 200.0,
            ..Pose::ZERO
        },
    )
}

#[test]
fn direct_switch_between_g43_and_g43_4() {
    // §11.1: N10 replaces G43 by TTPC with motion (the actual tip goes to x1 y1 z1 at B b1), N20
    // replaces TTPC by G43 with motion (the virtual tip at B = 0 goes to x2 y2 z2, B stays).
    let text = filled(
        "g43_4-switch-g43-direct.nc",
        &[
            ("X_Y_Z_F_", "X10 Y20 Z30 F1000"),
            ("X_Y_Z_B_C_", "X0 Y0 Z50 B30 C0"),
            ("X_Y_Z_B0", "X15 Y25 Z70 B0"),
            ("x1", "5"),
            ("y1", "-10"),
            ("z1", "40"),
            ("b1", "30"),
            ("x2", "15"),
            ("y2", "25"),
            ("z2", "60"),
        ],
    );
    let r = head_table(&text);
    r.ok();
    assert!(r.canon.contains(&Canon::ChangeTool { tool: 1, slot: 1 }));
    assert!(r.canon.contains(&Canon::SelectTool { tool: 2 }));
    // N02 under G43 (T01, L = 100): m = P + w + L·ẑ.
    assert_axes(
        r.end_of("N02"),
        [10.0, 20.0, -170.0],
        &[(B, 0.0)],
        TOL,
        "N02",
    );
    // N10: t = (5, −10, 40 − 300); m = t + 250·(sin 30°, 0, cos 30°) − 150·ẑ.
    assert_axes(
        r.end_of("N10"),
        [5.0 + S30, -10.0, -260.0 + C30 - 150.0],
        &[(B, 30.0), (C, 0.0)],
        TOL,
        "N10",
    );
    assert_axes(
        r.end_of("N11"),
        [S30, 0.0, -250.0 + C30 - 150.0],
        &[(B, 30.0), (C, 0.0)],
        TOL,
        "N11",
    );
    // N20: G43 again, H omitted: the length in force (100). B keeps 30.
    assert_axes(
        r.end_of("N20"),
        [15.0, 25.0, 60.0 - 300.0 + 100.0],
        &[(B, 30.0)],
        TOL,
        "N20",
    );
    assert_axes(
        r.end_of("N21"),
        [15.0, 25.0, -130.0],
        &[(B, 0.0)],
        TOL,
        "N21",
    );
}

#[test]
fn direct_switch_without_motion_moves_nothing_and_shifts_the_display() {
    // §11.2: G43 → G43.4 on its own at B = 30: no axis moves; the displayed (program) position
    // changes by +(Lp + L)·(ẑ − v(B)) = (−125, 0, 250 − 216.5063509); back by G43 it changes by
    // the opposite amount.
    let text =
        "N1 T01 M6\nN2 G01 F1000 X0 Y0 Z100 B30\nN3 G43.4\nN4 G91 Z0\nN5 G43\nN6 G91 Z0\nM30\n";
    let r = head_table(text);
    r.ok();
    assert!(r.block("N3").is_empty(), "N3 moved");
    assert!(r.block("N5").is_empty(), "N5 moved");
    let start_of = |n: &str| {
        let line = r.line_of(n);
        let (c, _) = r
            .canon
            .iter()
            .zip(&r.lines)
            .find(|(c, &l)| l == line && c.motion().is_some())
            .unwrap_or_else(|| panic!("{n} has no motion"));
        c.motion().unwrap().start().xyz()
    };
    // Program position = Canon position − w − tlo (TTPC: tlo 0).
    let before = [0.0, 0.0, 100.0];
    let n4 = start_of("N4");
    let shown = [n4[0], n4[1], n4[2] + 300.0];
    let want = [-S30, 0.0, 100.0 + 250.0 - C30];
    for i in 0..3 {
        assert!(
            (shown[i] - want[i]).abs() < TOL,
            "N3 display {shown:?}, want {want:?}"
        );
    }
    // N6 runs under G43 again: the machine never moved, so the display is back at `before`.
    let n6 = start_of("N6");
    let shown = [n6[0], n6[1], n6[2] + 300.0 - 100.0];
    for i in 0..3 {
        assert!((shown[i] - before[i]).abs() < TOL, "N5 display {shown:?}");
    }
    assert_axes(r.end_of("N6"), [0.0, 0.0, -100.0], &[(B, 30.0)], TOL, "N6");
}

#[test]
fn switch_through_g49_at_safe_positions() {
    // §11.3 with F114 bit 1 = 0: each G49 moves the axes −L along the tool axis; the
    // independent G43.4 moves them +L along it; G43 from G49 takes the offset up again (+L on
    // Z). C is 0 whenever TTPC is selected (the table frame glued at C = 0, as in the oracles).
    let text = filled(
        "g43_4-switch-g43-via-g49.nc",
        &[
            ("X_Y_Z_F_", "X10 Y20 Z30 F1000"),
            ("X_Y_Z_B_C_", "X10 Y0 Z100 B30 C0"),
            ("X_Y_Z_B0", "X5 Y5 Z160 B0"),
            ("x1", "0"),
            ("y1", "0"),
            ("z1", "100"),
            ("x2", "0"),
            ("y2", "0"),
            ("z2", "150"),
            ("b2", "30"),
            ("c2", "0"),
            ("x3", "0"),
            ("y3", "0"),
            ("z3", "120"),
            ("b3", "30"),
            ("c3", "0"),
            ("x4", "0"),
            ("y4", "0"),
            ("z4", "150"),
            ("b4", "30"),
            ("c4", "0"),
        ],
    );
    let r = head_table(&text);
    r.ok();
    let cases: [(&str, [f64; 3], f64); 10] = [
        ("N02", [10.0, 20.0, -170.0], 0.0),
        ("N08", [0.0, 0.0, -100.0], 0.0),
        // G49: −L on Z (the holder face goes where the virtual tip was).
        ("N09", [0.0, 0.0, -200.0], 0.0),
        ("N10", [0.0, 0.0, -150.0], 30.0),
        // Independent start: +L·v(30°).
        ("N11", [50.0, 0.0, -150.0 + 86.602_540_378_443_86], 30.0),
        ("N12", [10.0 + S30, 0.0, -200.0 + C30 - 150.0], 30.0),
        ("N18", [S30, 0.0, -180.0 + C30 - 150.0], 30.0),
        // TTPC G49: −L·v(30°).
        (
            "N19",
            [
                S30 - 50.0,
                0.0,
                -180.0 + C30 - 150.0 - 86.602_540_378_443_86,
            ],
            30.0,
        ),
        ("N20", [0.0, 0.0, -150.0], 30.0),
        // G43 (no H) from G49: the spindle tool's length, +L on Z.
        ("N21", [0.0, 0.0, -50.0], 30.0),
    ];
    for (n, xyz, b) in cases {
        assert_axes(r.end_of(n), xyz, &[(B, b), (C, 0.0)], TOL, n);
    }
    assert_axes(r.end_of("N22"), [5.0, 5.0, -40.0], &[(B, 0.0)], TOL, "N22");
    // Both G49 blocks are alone and were accepted.
    assert!(r.error.is_none());
}

#[test]
fn t_series_refuses_the_direct_switch() {
    // AMB-13: on the mill-turn (T-series) G43 ↔ G43.4 must go through G49.
    for (text, code, line, column) in [
        (
            "G43 H1\nG01 F1000 X0 Y0 Z0\nG43.4 X0 Y20 Z5 B45\n",
            "mazatrol::ttpc-not-selectable",
            3,
            1,
        ),
        (
            "G01 F1000\nG43.4 X0 Y20 Z5 B45 H1\n  G43 X0 Y0 Z0\n",
            "mazatrol::code-not-allowed-in-ttpc",
            3,
            3,
        ),
    ] {
        let r = run(
            text,
            Dialect::Mazatrol,
            "millturn-bc",
            control([0.0, 0.0, -400.0]),
            Pose::ZERO,
        );
        let e = r.error.clone().expect("refused");
        assert_eq!(e.code.to_string(), code, "{text}");
        assert_eq!((e.span.line, e.span.column), (line, column), "{text}");
    }
    // Through G49 the same change is accepted.
    let r = run(
        "G43 H1\nG01 F1000 X0 Y0 Z0\nG49\nG43.4 X0 Y20 Z5 B45 H1\nM30\n",
        Dialect::Mazatrol,
        "millturn-bc",
        control([0.0, 0.0, -400.0]),
        Pose::ZERO,
    );
    r.ok();
    // Oracle A's N20 position (spec §17.2).
    assert_axes(
        r.end_at_line(4, "G43.4"),
        [-145.7395026, 20.0, -368.3697513],
        &[(B, 45.0), (C, 0.0)],
        TOL,
        "G43.4",
    );
}

#[test]
fn type1_start_with_motion_on_each_machine() {
    // §5.2: at the end of the block the rotary axes are at the commanded angles and the tip (L
    // along the new tool axis) is at X Y Z. No built-in machine has A, B and C at once (the
    // kinematics takes two rotary axes; the header: "A, B and C are shown together only in the
    // format"), so each machine gets the words of the axes it has.
    let ab = MachineData::builtin("5axis-ab-head").unwrap();
    let tool = ab.five_axis().unwrap().with_tool_length(100.0);
    let text = filled(
        "g43_4-type1-start-move.nc",
        &[
            ("Xx", "X15"),
            ("Yy", "Y-10"),
            ("Zz", "Z50"),
            ("Aa", "A10"),
            ("Bb", "B20"),
            ("Cc", ""),
            ("Hh", "H1"),
        ],
    );
    let r = run(
        &format!("G01 F1000\n{text}"),
        Dialect::Mazatrol,
        "5axis-ab-head",
        control([0.0; 3]),
        Pose {
            z: 300.0,
            ..Pose::ZERO
        },
    );
    r.ok();
    let q = r.end_at_line(2, "G43.4");
    let tip = tool.forward(&q).unwrap().xyz();
    for (i, want) in [15.0, -10.0, 50.0].into_iter().enumerate() {
        assert!((tip[i] - want).abs() < TOL, "tip {tip:?}");
    }
    assert!(
        (q[A] - 10.0).abs() < TOL && (q[B] - 20.0).abs() < TOL,
        "{q:?}"
    );
    // The tool vector is L away from the tip along the head's direction at A10 B20.
    let t = ab.five_axis().unwrap().tool_vector(&Pose::from_array(q));
    let holder = ab.five_axis().unwrap().forward(&q).unwrap().xyz();
    for i in 0..3 {
        assert!(
            (holder[i] - tip[i] - 100.0 * t[i]).abs() < TOL,
            "{holder:?}"
        );
    }
    // Mill-turn B + C (spec §17.2, oracle A's N20) and trunnion A + C (§17.3, oracle D's N20).
    for (machine, w, words, xyz, rot) in [
        (
            "millturn-bc",
            [0.0, 0.0, -400.0],
            [
                ("Xx", "X0"),
                ("Yy", "Y20."),
                ("Zz", "Z5."),
                ("Aa", ""),
                ("Bb", "B45."),
                ("Cc", "C0"),
                ("Hh", "H1"),
            ],
            [-145.7395026, 20.0, -368.3697513],
            [(B, 45.0), (C, 0.0)],
        ),
        (
            "5axis-ac-table",
            [500.0, 250.0, -450.0],
            [
                ("Xx", "X0"),
                ("Yy", "Y0"),
                ("Zz", "Z50."),
                ("Aa", "A0"),
                ("Bb", ""),
                ("Cc", "C0"),
                ("Hh", "H1"),
            ],
            [500.0, 250.0, -300.0],
            [(A, 0.0), (C, 0.0)],
        ),
    ] {
        let text = format!("G01 F1000\n{}", filled("g43_4-type1-start-move.nc", &words));
        let r = run(&text, Dialect::Mazatrol, machine, control(w), Pose::ZERO);
        r.ok();
        assert_axes(r.end_at_line(2, machine), xyz, &rot, TOL, machine);
    }
    // All three rotary words on a machine without C: the C word is refused where it stands.
    let text = filled(
        "g43_4-type1-start-move.nc",
        &[
            ("Xx", "X15"),
            ("Yy", "Y-10"),
            ("Zz", "Z50"),
            ("Aa", "A10"),
            ("Bb", "B20"),
            ("Cc", "C30"),
            ("Hh", "H1"),
        ],
    );
    let r = run(
        &text,
        Dialect::Mazatrol,
        "5axis-ab-head",
        control([0.0; 3]),
        Pose::ZERO,
    );
    let e = r.error.expect("C refused");
    assert_eq!(e.code.to_string(), "interp::axis-not-configured");
    assert_eq!(
        (e.span.line, e.span.column as usize),
        (1, text.find("C30").unwrap() + 1)
    );
}

#[test]
fn g44_and_the_tool_change_in_ttpc() {
    // G44 H2: the virtual tip at B = 0 is L above the holder face: m = P + w − L·ẑ (L = 80).
    let r = head_table("N1 G44 H2\nN2 G01 F1000 X1 Y2 Z3\nN3 G49\nM30\n");
    r.ok();
    assert_axes(r.end_of("N1"), [0.0, 0.0, 120.0], &[], TOL, "N1");
    assert_axes(
        r.end_of("N2"),
        [1.0, 2.0, 3.0 - 300.0 - 80.0],
        &[],
        TOL,
        "N2",
    );
    assert_axes(r.end_of("N3"), [1.0, 2.0, 3.0 - 300.0], &[], TOL, "N3");
    // M6 in TTPC is refused at the M word's block, nothing of it moves.
    let r = head_table("N1 G01 F1000\nN2 G43.4 H1\nN3 T02 M6\nM30\n");
    let e = r.error.clone().expect("M6 refused");
    assert_eq!(e.code.to_string(), "mazatrol::code-not-allowed-in-ttpc");
    assert_eq!((e.span.line, e.span.column), (3, 8));
    assert!(r.block("N3").is_empty());
}
