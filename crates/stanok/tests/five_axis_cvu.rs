//! Balt-System CVU=1 (corpus/cvu): the oracles of cvu-five-axis.md §8 on the machines they state
//! (FAT lines; L = 100 from the corrector), through interpreter → simulated machine → servo
//! trace. The fragments of examples 1 and 2 get what their headers say a harness must add: a tool
//! with its corrector, `CVU=1` and an F before them. Asserted: machine positions Q (1e-6), the
//! tip held by rotate-in-place blocks and on the programmed line at every setpoint (1e-6 mm), and
//! zero limit violations.

mod five_axis_harness;
use five_axis_harness::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind};
use stanok_canon::Pose;
use stanok_kin::Kinematics;
use stanok_machine::MachineData;
use stanok_syntax::Dialect;

const A: usize = 3;
const C: usize = 5;
const TOL: f64 = 1e-6;

/// Corrector `c` = tool table entry `c` with L = 100.
fn control(corrector: u32) -> ControlData {
    let mut c = ControlData::default();
    c.tools.tools.insert(
        corrector,
        Tool {
            number: corrector,
            kind: ToolKind::Milling,
            edges: vec![ToolEdge {
                length: [100.0, 0.0, 0.0],
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    c
}

fn machine(fat: &str, corrector: u32) -> MachineData {
    let mut m = MachineData::builtin("5axis-cvu-tt").unwrap();
    let mut k = m.kinematics.clone().unwrap();
    k.fat = Some(fat.to_string());
    k.rotary.clear();
    let data = stanok_kin::from_fat(fat).unwrap();
    k.kind = match (
        data.rotary_axes()
            .filter(|a| a.carrier == stanok_kin::Carrier::Head)
            .count(),
        data.rotary_axes().count(),
    ) {
        (2, _) => stanok_kin::MachineType::HeadHead,
        (0, _) => stanok_kin::MachineType::TableTable,
        _ => stanok_kin::MachineType::HeadTable,
    };
    k.rotary = data.rotary_axes().cloned().collect();
    for r in &mut k.rotary {
        let axis = m.axis(r.name).unwrap();
        (r.min, r.max, r.max_velocity) = (axis.min, axis.max, axis.max_velocity);
    }
    m.kinematics = Some(k);
    m.control = control(corrector);
    m
}

/// The fragment between `CVU=1` and `CVU=0`; the tool goes back along Z before `CVU=0` (AMB-11),
/// as every manual example that ends with CVU=0 does.
fn fragment(name: &str) -> String {
    let body: String = corpus_text(&format!("cvu/{name}"))
        .lines()
        .filter(|l| !l.starts_with(';'))
        .map(|l| format!("{l}\n"))
        .collect();
    format!("T1.1 M6\nCVU=1\nG1 F1000\n{body}G1 A0 C0\nCVU=0\nM30\n")
}

fn at_gauge(z: f64) -> Pose {
    Pose { z, ..Pose::ZERO }
}

#[test]
fn oracle_o1_rotate_in_place_on_every_fat_variant() {
    for (fat, want) in [
        ("C,0,0,0,A,0,0,0", [38.302222, -32.139380, 86.602540]),
        ("C,0,0,20,A,0,-150,0", [111.076444, -73.204203, 66.506351]),
        ("A,1,0,-50,C,1,10,0", [3.572124, 31.634139, 89.471048]),
        ("C,1,10,0,A,0,0,0", [3.572124, -42.339556, 86.602540]),
    ] {
        let r = run_on(
            &fragment("example-1-rotate-a-c.nc"),
            Dialect::Balt,
            machine(fat, 1),
            at_gauge(100.0),
        );
        r.ok();
        assert_axes(
            r.end_of("N1"),
            [0.0, 0.0, 100.0],
            &[(A, 0.0), (C, 0.0)],
            TOL,
            fat,
        );
        assert_axes(r.end_of("N2"), want, &[(A, 30.0), (C, 50.0)], TOL, fat);
        // The tip stays at the part zero at every setpoint of N2.
        let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
        let sps = r.block("N2");
        assert!(sps.len() > 10);
        for sp in sps {
            let tip = kin.forward(&sp.joints).unwrap().xyz();
            assert!(tip.iter().all(|v| v.abs() < 1e-6), "{fat}: tip {tip:?}");
        }
    }
}

#[test]
fn oracle_o2_simultaneous_five_axis_line() {
    let r = run_on(
        &fragment("example-2-simultaneous-five-axis.nc"),
        Dialect::Balt,
        machine("C,0,0,0,A,0,0,0", 1),
        at_gauge(100.0),
    );
    r.ok();
    assert_axes(
        r.end_of("N2"),
        [69.061835, -53.456972, 136.592583],
        &[(A, 15.0), (C, -25.0)],
        TOL,
        "N2",
    );
    // The tip runs on the line (0,0,0)–(80,−30,40); at s = 0.5 Q = (37.174896, −27.743220,
    // 119.144486), 2.6 mm away from the chord of the machine positions.
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let mut seen_mid = false;
    for sp in r.block("N2") {
        let tip = kin.forward(&sp.joints).unwrap().xyz();
        let s = tip[0] / 80.0;
        assert!(
            (tip[1] + 30.0 * s).abs() < 1e-6 && (tip[2] - 40.0 * s).abs() < 1e-6,
            "{tip:?}"
        );
        assert!(
            (sp.joints[A] - 15.0 * s).abs() < 1e-6,
            "A follows the path parameter"
        );
        if (s - 0.5).abs() < 0.002 {
            seen_mid = true;
            let want = kin
                .inverse(&Pose {
                    x: tip[0],
                    y: tip[1],
                    z: tip[2],
                    a: 15.0 * s,
                    c: -25.0 * s,
                    ..Pose::ZERO
                })
                .unwrap();
            assert_axes(sp.joints, [want[0], want[1], want[2]], &[], 1e-6, "middle");
            assert_axes(
                sp.joints,
                [37.174896, -27.743220, 119.144486],
                &[],
                0.2,
                "middle",
            );
        }
    }
    assert!(seen_mid);
}

#[test]
fn oracle_o3_ijk_dome() {
    let text = corpus_text("cvu/example-4-ijk-dome-surface.nc");
    let r = run_on(
        &text,
        Dialect::Balt,
        machine("C,0,0,0,A,0,0,0", 8),
        at_gauge(100.0),
    );
    r.ok();
    for (n, q, a, c) in [
        ("N16", [0.0, 0.0, 100.0], 0.0, 0.0),
        ("N17", [0.0, 0.0, 101.0], 0.0, 0.0),
        ("N19", [0.0, 8.983441, 99.784499], -2.5817, 0.0),
        ("N38", [0.0, 141.244678, 41.494678], -45.0, 0.0),
        ("N39", [-10.076571, 141.052179, 41.302179], -45.0717, 4.0510),
        ("N56", [-141.239338, 99.878775, 0.128775], -59.9975, 54.7315),
        (
            "N69",
            [-141.245250, 22.415257, 39.689069],
            -45.7220,
            80.9982,
        ),
        ("N73", [-141.244678, 0.0, 41.494678], -45.0, 90.0),
        ("N74", [-162.457678, 0.0, 62.707678], -45.0, 90.0),
    ] {
        let got = r.end_of(n);
        assert_axes(got, q, &[], TOL, n);
        assert!(
            (got[A] - a).abs() < 1e-4 && (got[C] - c).abs() < 1e-4,
            "{n}: {got:?}"
        );
    }
}

#[test]
fn fat_variants_are_validated_at_load() {
    let text = include_str!("../../../machines/5axis-cvu-tt.toml")
        .replace("fat = \"C,0,0,0,A,0,0,0\"", "fat = \"C,0,0,0,A,1,0,0\"");
    let err = MachineData::from_toml_str(&text, "x.toml").unwrap_err();
    assert!(format!("{err:?}").contains("FAT error 142"), "{err:?}");
}

#[test]
fn prohibited_codes_and_precondition() {
    let m = || machine("C,0,0,0,A,0,0,0", 1);
    let r = run_on(
        "T1.1 M6\nCVU=1\nG1 G41 X10 F100\n",
        Dialect::Balt,
        m(),
        at_gauge(100.0),
    );
    let d = r.error.clone().expect("G41 under CVU=1");
    assert_eq!(d.code.to_string(), "balt::prohibited-in-cvu");
    assert_eq!(d.span.line, 3);
    // CVU=1 with the tool tilted.
    let r = run_on(
        "T1.1 M6\nG1 A10 F100\nCVU=1\n",
        Dialect::Balt,
        m(),
        at_gauge(100.0),
    );
    let d = r.error.clone().expect("precondition");
    assert_eq!(d.code.to_string(), "balt::cvu-precondition");
    assert_eq!(d.span.line, 3);
}

#[test]
fn g91_moves_xyz_only_and_angles_stay_absolute() {
    let text = "T1.1 M6\nCVU=1\nG1 G91 X10 A20 F1000\nX10 A20\nA0\nCVU=0\n";
    let r = run_on(
        text,
        Dialect::Balt,
        machine("C,0,0,0,A,0,0,0", 1),
        at_gauge(100.0),
    );
    r.ok();
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let want = kin
        .inverse(&Pose {
            x: 20.0,
            a: 20.0,
            ..Pose::ZERO
        })
        .unwrap();
    assert_axes(
        r.end_of("X10 A20"),
        [want[0], want[1], want[2]],
        &[(A, 20.0)],
        TOL,
        "block 4",
    );
}

#[test]
fn oracle_o4_half_circle_on_three_kinematics() {
    // Example 2 of §3.4 (corpus example-5): the tip on a half circle of radius 1 in YZ, A = the
    // polar angle, L = 5 (corrector 4), all axes through the origin, GOST signs. A goes to 180°,
    // so the A travel is opened to ±360° for this run.
    let text = corpus_text("cvu/example-5-circle-yz-a-c.nc");
    let g1_lines: Vec<u32> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with("G1"))
        .map(|(i, _)| i as u32 + 1)
        .collect();
    assert_eq!(g1_lines.len(), 9);
    let tt_dt = [
        [0.0, 0.0, 6.0],
        [0.0, -2.828534, 4.242534],
        [0.0, -4.0, 0.0],
        [0.0, -2.828534, -4.242534],
        [0.0, 0.0, -6.0],
    ];
    let dd = [
        [0.0, 0.0, 6.0],
        [0.0, 0.999849, 5.0],
        [0.0, 0.0, 4.0],
        [0.0, -0.999849, 5.0],
        [0.0, 0.0, 6.0],
    ];
    for (fat, want) in [
        ("C,0,,,A,0,,", tt_dt),
        ("C,1,,,A,0,,", tt_dt),
        ("A,1,,,C,1,,", dd),
    ] {
        let mut m = machine(fat, 4);
        let mut c = ControlData::default();
        c.tools.tools.insert(
            4,
            Tool {
                number: 4,
                kind: ToolKind::Milling,
                edges: vec![ToolEdge {
                    length: [5.0, 0.0, 0.0],
                    ..Default::default()
                }],
                ..Default::default()
            },
        );
        m.control = c;
        for a in m.axes.iter_mut().filter(|a| a.name == 'A') {
            (a.min, a.max) = (-360.0, 360.0);
        }
        for r in &mut m.kinematics.as_mut().unwrap().rotary {
            if r.name == 'A' {
                (r.min, r.max) = (-360.0, 360.0);
            }
        }
        let r = run_on(&text, Dialect::Balt, m, Pose::ZERO);
        r.ok();
        // The way out (points 0…4) and back (5…8 mirror 3…0).
        for (k, line) in g1_lines.iter().enumerate() {
            let point = if k <= 4 { k } else { 8 - k };
            let got = r.end_at_line(*line, &format!("{fat} G1 #{k}"));
            assert_axes(got, want[point], &[(A, 45.0 * point as f64)], 1e-6, fat);
        }
    }
}

/// Source line (1-based) of the first line of `text` whose trimmed text is `block`.
fn line_of_text(text: &str, block: &str) -> u32 {
    text.lines()
        .position(|l| l.trim() == block)
        .unwrap_or_else(|| panic!("no line {block:?}")) as u32
        + 1
}

#[test]
fn oracle_o5_cvu3_tilted_plane_with_movst_2() {
    // corpus example-8: (LCS,1,X30,Y50,Z20,A45,C30), CVU=3, MOVST=2, a 50 × 50 square in the
    // local XY plane; L = 100 (the header's machine data: corrector 1 selected before the
    // program). Oracle O5 of §8: Q on TT C+A (zero offsets) and DD A+C (axes through the origin).
    let text = format!(
        "T1.1 M6\n{}",
        corpus_text("cvu/example-8-cvu3-tilted-plane-lcs.nc")
    );
    let first = line_of_text(&text, "G1XY50ZF1000");
    let orient = line_of_text(&text, "G1A45C30F1000");
    let square = ["G1X50Z", "G1Y0Z", "G1X0Z", "G1XY50Z"].map(|b| line_of_text(&text, b));
    let back = line_of_text(&text, "G1A0C0");
    let last = line_of_text(&text, "G1X0Y0");
    let before = [12.322330, 80.618622, 155.355339];
    for (fat, corners) in [
        (
            "C,0,0,0,A,0,0,0",
            [
                [90.978940, 44.381378, 126.066017],
                [108.656609, 13.762756, 90.710678],
                [65.355339, -11.237244, 90.710678],
                [47.677670, 19.381378, 126.066017],
            ],
        ),
        (
            "A,1,,,C,1,,",
            [
                [100.980762, 84.154156, 94.130116],
                [100.980762, 34.154156, 94.130116],
                [50.980762, 34.154156, 94.130116],
                [50.980762, 84.154156, 94.130116],
            ],
        ),
    ] {
        let r = run_on(&text, Dialect::Balt, machine(fat, 1), Pose::ZERO);
        r.ok();
        let at = |line: u32, what: &str| r.end_at_line(line, &format!("{fat} {what}"));
        assert_axes(
            at(first, "G1XY50Z"),
            before,
            &[(A, 0.0), (C, 0.0)],
            TOL,
            fat,
        );
        // MOVST=2: the linear axes stand still while A and C turn, at every setpoint.
        assert_axes(
            at(orient, "G1A45C30"),
            before,
            &[(A, 45.0), (C, 30.0)],
            TOL,
            fat,
        );
        let sps: Vec<_> = r.setpoints.iter().filter(|s| s.line == orient).collect();
        assert!(sps.len() > 10, "{fat}: {} setpoints", sps.len());
        for sp in sps {
            assert_axes(sp.joints, before, &[], TOL, fat);
        }
        for (k, (&line, want)) in square.iter().zip(corners).enumerate() {
            assert_axes(at(line, "corner"), want, &[(A, 45.0), (C, 30.0)], TOL, fat);
            // Sides 1–3 keep the tip in the local plane z = 0 at every setpoint (R_L's third
            // column is the tool axis u; local z = u·(P − o)). Side 0 starts where MOVST=2 left
            // the tip, off the plane.
            if k == 0 {
                continue;
            }
            let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
            let u = [
                0.353553390593,
                -0.612372435696,
                std::f64::consts::FRAC_1_SQRT_2,
            ];
            for sp in r.setpoints.iter().filter(|s| s.line == line) {
                let p = kin.forward(&sp.joints).unwrap().xyz();
                let z = u[0] * (p[0] - 30.0) + u[1] * (p[1] - 50.0) + u[2] * (p[2] - 20.0);
                assert!(z.abs() < 1e-6, "{fat} side {k}: local z {z}");
            }
        }
        // G1A0C0 under MOVST=2: the linear axes stay at the last corner.
        assert_axes(
            at(back, "G1A0C0"),
            corners[3],
            &[(A, 0.0), (C, 0.0)],
            TOL,
            fat,
        );
        // After CVU=0 the words are machine axes (decision: the frame maps only in CVU=3).
        assert_axes(
            at(last, "G1X0Y0"),
            [0.0, 0.0, corners[3][2]],
            &[(A, 0.0), (C, 0.0)],
            TOL,
            fat,
        );
    }
}

#[test]
fn cvu3_movst_1_keeps_the_tip_and_lcs_errors() {
    // MOVST=1: the orientation block holds the tip at local (0,50,0) → part (12.32, 80.62, 55.36)
    // and the axes end on O5's TT row for (0,50,0).
    let text = "T1.1 M6\nG0X0Y0Z0A0C0\n(LCS,1,X30,Y50,Z20,A45,C30)\nCVU=3\nMOVST=1\nG1XY50ZF1000\nG1A45C30\nG1A0C0\nCVU=0\nM30\n";
    let r = run_on(
        text,
        Dialect::Balt,
        machine("C,0,0,0,A,0,0,0", 1),
        Pose::ZERO,
    );
    r.ok();
    assert_axes(
        r.end_at_line(7, "G1A45C30"),
        [47.677670, 19.381378, 126.066017],
        &[(A, 45.0), (C, 30.0)],
        TOL,
        "MOVST=1",
    );
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    for sp in r.setpoints.iter().filter(|s| s.line == 7) {
        let p = kin.forward(&sp.joints).unwrap().xyz();
        let want = [12.322330, 80.618622, 55.355339];
        assert!((0..3).all(|i| (p[i] - want[i]).abs() < 1e-5), "tip {p:?}");
    }
    // A B angle on an A-C machine, and a bad frame number: named errors at the comment.
    for (bad, col) in [("(LCS,1,X30,B10)", 2), ("(LCS,2)", 2)] {
        let text = format!("T1.1 M6\n{bad}\nM30\n");
        let r = run_on(
            &text,
            Dialect::Balt,
            machine("C,0,0,0,A,0,0,0", 1),
            Pose::ZERO,
        );
        let e = r.error.expect(bad);
        assert_eq!(e.code.to_string(), "balt::lcs", "{bad}: {e:?}");
        assert_eq!((e.span.line, e.span.column), (2, col), "{bad}");
    }
    let r = run_on(
        "MOVST=5\n",
        Dialect::Balt,
        machine("C,0,0,0,A,0,0,0", 1),
        Pose::ZERO,
    );
    assert_eq!(r.error.expect("MOVST=5").code.to_string(), "balt::movst");
}

/// [`machine`] for any FAT pair: a rotary axis the base machine lacks (B) is added as a copy of
/// its A axis, and every rotary travel is opened to ±360° (the half-circle programs turn to 180°).
fn machine_any(fat: &str, corrector: u32) -> MachineData {
    let mut base = MachineData::builtin("5axis-cvu-tt").unwrap();
    for name in ['A', 'B', 'C'] {
        if base.axis(name).is_none() {
            let mut a = base.axis('A').unwrap().clone();
            a.name = name;
            base.axes.push(a);
        }
    }
    base.axes
        .sort_by_key(|a| "XYZABCUVW".find(a.name).unwrap_or(9));
    for a in base.axes.iter_mut().filter(|a| "ABC".contains(a.name)) {
        (a.min, a.max) = (-360.0, 360.0);
    }
    let mut m = base;
    let mut k = m.kinematics.clone().unwrap();
    let chain = stanok_kin::from_fat(fat).unwrap();
    k.fat = Some(fat.to_string());
    k.kind = match (
        chain
            .rotary_axes()
            .filter(|a| a.carrier == stanok_kin::Carrier::Head)
            .count(),
        chain.rotary_axes().count(),
    ) {
        (2, _) => stanok_kin::MachineType::HeadHead,
        (0, _) => stanok_kin::MachineType::TableTable,
        _ => stanok_kin::MachineType::HeadTable,
    };
    k.rotary = chain.rotary_axes().cloned().collect();
    for r in &mut k.rotary {
        let axis = m.axis(r.name).unwrap();
        (r.min, r.max, r.max_velocity) = (axis.min, axis.max, axis.max_velocity);
    }
    m.kinematics = Some(k);
    let mut c = ControlData::default();
    c.tools.tools.insert(
        corrector,
        Tool {
            number: corrector,
            kind: ToolKind::Milling,
            edges: vec![ToolEdge {
                length: [5.0, 0.0, 0.0],
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    m.control = c;
    m
}

/// Runs a §3.4 half-circle program (9 G1 blocks: points 0…4 out, 3…0 back) on each FAT line and
/// asserts Q at every G1 block and the angle axis `angle` at 45° per point (1e-6).
fn half_circle(file: &str, angle: usize, cases: &[(&str, [[f64; 3]; 5])]) {
    let text = corpus_text(&format!("cvu/{file}"));
    let g1_lines: Vec<u32> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with("G1"))
        .map(|(i, _)| i as u32 + 1)
        .collect();
    assert_eq!(g1_lines.len(), 9);
    for (fat, want) in cases {
        let r = run_on(&text, Dialect::Balt, machine_any(fat, 4), Pose::ZERO);
        r.ok();
        for (k, line) in g1_lines.iter().enumerate() {
            let point = if k <= 4 { k } else { 8 - k };
            let got = r.end_at_line(*line, &format!("{fat} G1 #{k}"));
            assert_axes(got, want[point], &[(angle, 45.0 * point as f64)], TOL, fat);
        }
    }
}

#[test]
fn example_6_half_circle_yz_on_a_b_machines() {
    // With B = 0 the tool axis is Rx(A)·e_z on all six FAT lines: A on the head gives the TT/DT
    // column of O4, A on the table its DD column (the header of corpus example-6).
    let head = [
        [0.0, 0.0, 6.0],
        [0.0, -2.828534, 4.242534],
        [0.0, -4.0, 0.0],
        [0.0, -2.828534, -4.242534],
        [0.0, 0.0, -6.0],
    ];
    let table = [
        [0.0, 0.0, 6.0],
        [0.0, 0.999849, 5.0],
        [0.0, 0.0, 4.0],
        [0.0, -0.999849, 5.0],
        [0.0, 0.0, 6.0],
    ];
    half_circle(
        "example-6-circle-yz-a-b.nc",
        A,
        &[
            ("A,0,,,B,0,,", head),
            ("B,0,,,A,0,,", head),
            ("B,1,,,A,0,,", head),
            ("A,1,,,B,0,,", table),
            ("A,1,,,B,1,,", table),
            ("B,1,,,A,1,,", table),
        ],
    );
}

#[test]
fn example_7_half_circle_xz_on_b_c_machines_as_printed() {
    // As printed, C carries the angle and B stays 0 (AMB-18): TT turns the vertical tool about
    // its own axis (no compensation); DT and DD carry the tip round machine Z with the table.
    let tt = [
        [0.0, 0.0, 6.0],
        [0.707, 0.0, 5.707],
        [1.0, 0.0, 5.0],
        [0.707, 0.0, 4.293],
        [0.0, 0.0, 4.0],
    ];
    let table = [
        [0.0, 0.0, 6.0],
        [0.499924, -0.499924, 5.707],
        [0.0, -1.0, 5.0],
        [-0.499924, -0.499924, 4.293],
        [0.0, 0.0, 4.0],
    ];
    half_circle(
        "example-7-circle-xz-b-c.nc",
        C,
        &[
            ("C,0,,,B,0,,", tt),
            ("C,1,,,B,0,,", table),
            ("B,1,,,C,1,,", table),
        ],
    );
}

#[test]
fn cvu1_circle_in_yz_keeps_the_tip_on_the_arc() {
    // §6.4: G02 with R in the (DPI,Y,Z) plane under CVU=1, A turning with the arc parameter —
    // example 5's half circle as one circle block (R−1: exactly 180° takes the minus sign).
    // L = 5. The motion stage runs an arc as chords of at most 1 µm sag (path.rs,
    // INTERNAL_TOLERANCE) with the rotary axes linear in the arc parameter at the chord points,
    // so at every setpoint: the tip in the plane x = 0 (1e-9 mm), within 1e-3 mm of the circle
    // y² + z² = 1 on the +Y side, and A equal to the tip's polar angle within 0.01°; the block
    // ends exactly on O4's point 4 (1e-6).
    let text =
        "T1.4M6\n(DPI,Y,Z)\nCVU=1\nG1 X0 Y0 Z1 A0 C0 F60\nG2 Y0 Z-1 R-1 A180\nG1 A0\nCVU=0\nM30\n";
    for (fat, end) in [
        ("C,0,,,A,0,,", [0.0, 0.0, -6.0]),
        ("A,1,,,C,1,,", [0.0, 0.0, 6.0]),
    ] {
        let r = run_on(text, Dialect::Balt, machine_any(fat, 4), Pose::ZERO);
        r.ok();
        assert_axes(
            r.end_at_line(5, "G2"),
            end,
            &[(A, 180.0), (C, 0.0)],
            TOL,
            fat,
        );
        let kin = r.machine.five_axis().unwrap().with_tool_length(5.0);
        let sps: Vec<_> = r.setpoints.iter().filter(|s| s.line == 5).collect();
        assert!(sps.len() > 100, "{fat}: {} setpoints", sps.len());
        for sp in sps {
            let p = kin.forward(&sp.joints).unwrap().xyz();
            let radius = p[1].hypot(p[2]);
            assert!(
                p[0].abs() < 1e-9 && (radius - 1.0).abs() < 1e-3,
                "{fat}: tip {p:?}"
            );
            assert!(p[1] > -1e-6, "{fat}: tip {p:?} left the +Y half");
            let polar = p[1].max(0.0).atan2(p[2]).to_degrees();
            assert!(
                (sp.joints[A] - polar).abs() < 0.01,
                "{fat}: A {} at {p:?}",
                sp.joints[A]
            );
        }
    }
}

#[test]
fn balt_circle_errors() {
    // A chord longer than 2|R|, a missing R, and G02 in CVU=3: `balt::arc` / unsupported, with
    // the position of the word or block.
    let m = || machine("C,0,0,0,A,0,0,0", 1);
    let cases = [
        ("G1X0Y0Z0F100\nG2X10Y0R2\n", "balt::arc", 2, 8),
        ("G1X0Y0Z0F100\nG3X10Y0\n", "balt::arc", 2, 1),
        (
            "T1.1M6\n(LCS,1,X0,Y0,Z0,A0,C0)\nCVU=3\nG2X10Y0R5F100\n",
            "interp::unsupported",
            4,
            1,
        ),
    ];
    for (text, code, line, column) in cases {
        let r = run_on(text, Dialect::Balt, m(), Pose::ZERO);
        let e = r.error.unwrap_or_else(|| panic!("{text}: no error"));
        assert_eq!(e.code.to_string(), code, "{text}: {e:?}");
        assert_eq!((e.span.line, e.span.column), (line, column), "{text}");
    }
    // A circle without CVU: the centre from R (quarter circle, centre (0,10)).
    let r = run_on(
        "G1X10Y0Z0F600\nG3X0Y10R10\nM30\n",
        Dialect::Balt,
        m(),
        Pose::ZERO,
    );
    r.ok();
    let arc = r
        .canon
        .iter()
        .find_map(|c| match c {
            stanok_canon::Canon::ArcFeed(a) => Some(a.clone()),
            _ => None,
        })
        .unwrap();
    assert!(
        (arc.centre[0]).abs() < 1e-12 && (arc.centre[1]).abs() < 1e-12,
        "{arc:?}"
    );
    assert_eq!(arc.axis, [0.0, 0.0, 1.0]);
}

#[test]
fn example_3_spline_passes_through_every_node() {
    // corpus example-3: (BSP,X,Y,Z,A,C,1), G1 start block, G06 nodes on the unit circle in YZ
    // with A = the node's angle, (ESP). L = 5 (corrector 4 selected first; the header names no
    // tool). Only the nodes are oracles: each node block is one spline piece ending exactly at
    // its node (Canon), the trace reaches the machine axes of that node (harness: last setpoint
    // within 0.01, the inverse kinematics exact), where the tip is the node (1e-9 mm) and the
    // tool axis the GOST u = (0, −sin a, cos a) (1e-9); no limit is exceeded.
    let text = format!(
        "T1.4M6\n{}",
        corpus_text("cvu/example-3-spline-circle-yz.nc")
    );
    let nodes: Vec<(u32, [f64; 3], f64)> = text
        .lines()
        .enumerate()
        .skip_while(|(_, l)| !l.starts_with("G6"))
        .take_while(|(_, l)| !l.starts_with("(ESP)"))
        .map(|(i, l)| {
            let word = |c: char| -> f64 {
                let rest = &l[l.find(c).unwrap() + 1..];
                let num: String = rest
                    .chars()
                    .take_while(|ch| ch.is_ascii_digit() || *ch == '.' || *ch == '-')
                    .collect();
                num.parse().unwrap_or(0.0)
            };
            (i as u32 + 1, [0.0, word('Y'), word('Z')], word('A'))
        })
        .collect();
    assert_eq!(nodes.len(), 10);
    for fat in ["C,0,,,A,0,,", "A,1,,,C,1,,"] {
        let r = run_on(&text, Dialect::Balt, machine_any(fat, 4), Pose::ZERO);
        r.ok();
        let kin = r.machine.five_axis().unwrap().with_tool_length(5.0);
        for &(line, tip, a) in &nodes {
            let pieces: Vec<_> = r
                .canon
                .iter()
                .zip(&r.lines)
                .filter(|(_, &l)| l == line)
                .filter_map(|(c, _)| match c {
                    stanok_canon::Canon::SplineFeed(s) => Some(s),
                    _ => None,
                })
                .collect();
            assert_eq!(pieces.len(), 1, "{fat} line {line}");
            let end = pieces[0].end;
            assert_eq!((end.xyz(), end.a), (tip, a), "{fat} line {line}");
            let q = r.end_at_line(line, &format!("{fat} node line {line}"));
            let p = kin.forward(&q).unwrap().xyz();
            let u = kin.tool_vector(&kin.forward(&q).unwrap());
            let (s, c) = a.to_radians().sin_cos();
            for i in 0..3 {
                assert!((p[i] - tip[i]).abs() < 1e-9, "{fat} line {line}: tip {p:?}");
                assert!(
                    (u[i] - [0.0, -s, c][i]).abs() < 1e-9,
                    "{fat} line {line}: u {u:?}"
                );
            }
        }
    }
}

#[test]
fn spline_errors() {
    // G06 outside a definition, and G02 inside one (the manual's message 477).
    let m = || machine("C,0,0,0,A,0,0,0", 1);
    let r = run_on("G1X0Y0Z0F100\nG6X1Y1\n", Dialect::Balt, m(), Pose::ZERO);
    let e = r.error.expect("G6 outside");
    assert_eq!(e.code.to_string(), "balt::spline");
    assert_eq!(e.span.line, 2);
    let r = run_on(
        "(BSP,X,Y,0)\nG1X0Y0Z0F100\nG6X1Y1\nG2X2Y0R5\n",
        Dialect::Balt,
        m(),
        Pose::ZERO,
    );
    let e = r.error.expect("G2 in spline");
    assert_eq!(e.code.to_string(), "E477", "{e:?}");
    assert_eq!(e.span.line, 4);
}
