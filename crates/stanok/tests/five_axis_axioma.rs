//! AxiOMA TRAORI fixtures (corpus/axioma/s12_*) on the machine their headers assume: the built-in
//! `5axis-bc-head` (C about +Z carrying B about +Y, pivot at the mount point), T2 with length
//! 100 mm, the axes at (0, 0, 100) so that the tip is at the origin. Asserted: the machine axes the
//! headers give (1e-4 mm / deg: the headers print four decimals), that rotate-in-place blocks keep
//! the tip fixed at every servo setpoint (1e-6 mm), block durations from the feed rules, the
//! errors they name, and zero axis-limit violations in every trace.

#![allow(clippy::approx_constant)] // the headers print 1/√2 to four places

mod five_axis_harness;
use five_axis_harness::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind, WorkpieceFrame};
use stanok_canon::Pose;
use stanok_kin::Kinematics;
use stanok_syntax::Dialect;

const B: usize = 4;
const C: usize = 5;
const TOL: f64 = 1e-4;

fn control() -> ControlData {
    let mut c = ControlData::default();
    c.tools.tools.insert(
        2,
        Tool {
            number: 2,
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

fn fixture_with(name: &str, control: ControlData) -> Run {
    let text = corpus_text(&format!("axioma/{name}"));
    run(
        &text,
        Dialect::Axioma,
        "5axis-bc-head",
        control,
        Pose {
            z: 100.0,
            ..Pose::ZERO
        },
    )
}

fn fixture(name: &str) -> Run {
    fixture_with(name, control())
}

/// The tip (forward kinematics with L = 100) of every setpoint of block `n` is `tip` (1e-6 mm).
fn assert_tip_fixed(r: &Run, n: &str, tip: [f64; 3]) {
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let sps = r.block(n);
    assert!(sps.len() > 10, "{n}: {} setpoints", sps.len());
    for sp in sps {
        let t = kin.forward(&sp.joints).unwrap().xyz();
        for i in 0..3 {
            assert!((t[i] - tip[i]).abs() < 1e-6, "{n}: tip {t:?} at t {}", sp.t);
        }
    }
}

#[test]
fn example_12_1_rotate_in_place() {
    let r = fixture("s12_2_2-traori-rotate-in-place-example-12_1.nc");
    r.ok();
    assert_axes(
        r.end_of("N40"),
        [-96.5926, 0.0, 25.8819],
        &[(B, -75.0)],
        TOL,
        "N40",
    );
    // At B −37.5: (−60.8761, 0, 79.3353).
    let mid = r
        .block("N40")
        .into_iter()
        .min_by(|a, b| {
            (a.joints[B] + 37.5)
                .abs()
                .total_cmp(&(b.joints[B] + 37.5).abs())
        })
        .unwrap();
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let want = kin
        .inverse(&Pose {
            b: mid.joints[B],
            ..Pose::ZERO
        })
        .unwrap();
    assert!((mid.joints[B] + 37.5).abs() < 0.1);
    assert_axes(mid.joints, [want[0], 0.0, want[2]], &[], 1e-6, "N40 middle");
    assert_tip_fixed(&r, "N40", [0.0; 3]);
    // F600 is deg/min here: 75° take 7.5 s plus the acceleration (BRISK, 720 deg/s²: ~1 ms).
    let d = r.duration_of("N40");
    assert!((7.5..7.6).contains(&d), "N40 lasts {d} s");
}

#[test]
fn example_12_2_combined_x_and_b() {
    let r = fixture("s12_2_2-traori-combined-x-b-example-12_2.nc");
    r.ok();
    assert_axes(
        r.end_of("N40"),
        [3.4074, 0.0, 25.8819],
        &[(B, -75.0)],
        TOL,
        "N40",
    );
    // The tip runs on the X axis: at (50, 0, 0), B −37.5 → (−10.8761, 0, 79.3353).
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let mut mid_seen = false;
    for sp in r.block("N40") {
        let tip = kin.forward(&sp.joints).unwrap().xyz();
        assert!(tip[1].abs() < 1e-6 && tip[2].abs() < 1e-6, "tip {tip:?}");
        // B follows the path parameter: B = −75·x/100.
        assert!((sp.joints[B] + 0.75 * tip[0]).abs() < 1e-6, "{sp:?}");
        if (tip[0] - 50.0).abs() < 0.05 {
            mid_seen = true;
            let want = kin
                .inverse(&Pose {
                    x: tip[0],
                    b: sp.joints[B],
                    ..Pose::ZERO
                })
                .unwrap();
            assert_axes(sp.joints, [want[0], 0.0, want[2]], &[], 1e-6, "N40 middle");
            assert_axes(sp.joints, [-10.8761, 0.0, 79.3353], &[], 0.1, "N40 middle");
        }
    }
    assert!(mid_seen);
    // F600 mm/min is the tip speed over 100 mm: 10 s.
    let d = r.duration_of("N40");
    assert!((10.0..10.1).contains(&d), "N40 lasts {d} s");
}

#[test]
fn example_12_3_trafooff() {
    let r = fixture("s12_2_3-trafooff-example-12_3.nc");
    r.ok();
    assert_axes(
        r.end_of("N40"),
        [70.7107, 0.0, 70.7107],
        &[(B, 45.0)],
        TOL,
        "N40",
    );
    assert_tip_fixed(&r, "N40", [0.0; 3]);
    // N50 moves nothing; N60 turns B back with X and Z standing.
    assert!(r
        .block("N50")
        .iter()
        .all(|s| (s.joints[0] - 70.7107).abs() < TOL));
    for sp in r.block("N60") {
        assert_axes(sp.joints, [70.7107, 0.0, 70.7107], &[], TOL, "N60");
    }
    assert_axes(
        r.end_of("N60"),
        [70.7107, 0.0, 70.7107],
        &[(B, 0.0)],
        TOL,
        "N60",
    );
    // The program position after TRAFOOF is the axes minus the fixed length: the N60 move in
    // the stream runs between machine positions (TCP off), Z 70.7107 = −29.2893 + 100.
    let n60 = r
        .canon
        .iter()
        .rev()
        .find_map(|c| match c {
            stanok_canon::Canon::StraightFeed(m) => Some(m.clone()),
            _ => None,
        })
        .unwrap();
    assert!((n60.start.z - 70.7107).abs() < TOL && (n60.end.b).abs() < 1e-12);
}

#[test]
fn example_12_4_feed_of_orientation_only_blocks() {
    let r = fixture("s12_2_4-traori-feed-orientation-only-example-12_4.nc");
    r.ok();
    assert_axes(r.end_of("N40"), [0.0, 0.0, 110.0], &[], TOL, "N40");
    assert_axes(
        r.end_of("N60"),
        [70.7107, 0.0, 80.7107],
        &[(B, 45.0)],
        TOL,
        "N60",
    );
    assert_axes(
        r.end_of("N70"),
        [100.0, 0.0, 10.0],
        &[(B, 90.0)],
        TOL,
        "N70",
    );
    assert_tip_fixed(&r, "N60", [0.0, 0.0, 10.0]);
    assert_tip_fixed(&r, "N70", [0.0, 0.0, 10.0]);
    // Z10 equals the position exactly (no re-sync error in the simulation): N60 is
    // orientation-only, like N70: 45° at 600 deg/min = 4.5 s each.
    for n in ["N60", "N70"] {
        let d = r.duration_of(n);
        assert!((4.5..4.6).contains(&d), "{n} lasts {d} s");
    }
}

#[test]
fn example_12_5_direct_rotary_axes() {
    let r = fixture("s12_3_1-direct-rotary-axes-example-12_5.nc");
    r.ok();
    assert_axes(
        r.end_of("N40"),
        [161.2372, 85.3553, 70.7107],
        &[(B, 45.0), (C, 30.0)],
        TOL,
        "N40",
    );
    // F600 on the tip path of 111.8034 mm: 11.18 s.
    let d = r.duration_of("N40");
    assert!((11.18..11.3).contains(&d), "N40 lasts {d} s");
}

#[test]
fn example_12_6_orieuler() {
    let r = fixture("s12_3_2-orieuler-example-12_6.nc");
    r.ok();
    assert_axes(
        r.end_of("N50"),
        [0.0, 70.7107, 70.7107],
        &[(C, 90.0), (B, 45.0)],
        TOL,
        "N50",
    );
    assert_axes(
        r.end_of("N60"),
        [61.2372, 35.3553, 70.7107],
        &[(C, 30.0), (B, 45.0)],
        TOL,
        "N60",
    );
    // The pole: B0, C stays at 30.
    assert_axes(
        r.end_of("N70"),
        [0.0, 0.0, 100.0],
        &[(C, 30.0), (B, 0.0)],
        TOL,
        "N70",
    );
    for n in ["N50", "N60", "N70"] {
        assert_tip_fixed(&r, n, [0.0; 3]);
    }
}

#[test]
fn example_12_7_orirpy() {
    let r = fixture("s12_3_2-orirpy-example-12_7.nc");
    r.ok();
    let n50 = r.end_of("N50");
    assert!(
        (n50[C] - 14.5108).abs() < TOL && (n50[B] - 46.9205).abs() < TOL,
        "{n50:?}"
    );
    let n60 = r.end_of("N60");
    assert!(
        (n60[C] + 18.4349).abs() < TOL && (n60[B] - 52.2388).abs() < TOL,
        "{n60:?}"
    );
    assert_axes(
        r.end_of("N70"),
        [0.0, 0.0, 100.0],
        &[(B, 0.0), (C, -18.4349)],
        TOL,
        "N70",
    );
    for n in ["N50", "N60", "N70"] {
        assert_tip_fixed(&r, n, [0.0; 3]);
    }
}

#[test]
fn example_12_8_orientation_vector() {
    let r = fixture("s12_3_3-orientation-vector-example-12_8.nc");
    r.ok();
    assert_axes(
        r.end_of("N40"),
        [70.7107, 0.0, 70.7107],
        &[(C, 0.0), (B, 45.0)],
        TOL,
        "N40",
    );
    assert_axes(
        r.end_of("N50"),
        [0.0, 0.0, 100.0],
        &[(C, 0.0), (B, 0.0)],
        TOL,
        "N50",
    );
}

#[test]
fn example_12_9_oriwks_and_orimks() {
    // The header's assumption: G155 has Euler angles (0, 30, 0).
    let mut c = control();
    c.offsets.workpiece[1][0] = WorkpieceFrame {
        origin: [0.0; 3],
        euler: [0.0, 30.0, 0.0],
    };
    let r = fixture_with("s12_3_4-oriwks-orimks-example-12_9.nc", c);
    r.ok();
    let n60 = r.end_of("N60");
    assert!(
        (n60[C]).abs() < TOL && (n60[B] - 30.0).abs() < TOL,
        "{n60:?}"
    );
    let n80 = r.end_of("N80");
    assert!((n80[C]).abs() < TOL && n80[B].abs() < TOL, "{n80:?}");
    assert_tip_fixed(&r, "N60", [0.0; 3]);
    assert_tip_fixed(&r, "N80", [0.0; 3]);
}

#[test]
fn example_12_3_5_mixing_methods_is_error_653() {
    let r = fixture("s12_3_5-mixing-orientation-methods-not-for-execution.nc");
    let d = r.error.as_ref().expect("653 expected");
    assert_eq!(d.code, stanok_canon::DiagCode::Manual(653), "{d:?}");
    assert_eq!(d.span.line, r.line_of("N80"));
    // The blocks before ran (no TRAORI: the axes go to the orientation's solution, spec A-7).
    assert_axes(
        r.end_of("N70"),
        [0.0, 0.0, 100.0],
        &[(B, 15.0), (C, 75.0)],
        TOL,
        "N70",
    );
    // N20: ORIEULER A2=−170 B2=30 → t (−0.4924, −0.0868, 0.8660). Of its solutions C−170 B30
    // and C10 B−30 the least-time rule (spec §5.7) takes C10 B−30 from C0 B0.
    let n20 = r.end_of("N20");
    assert!(
        (n20[B] + 30.0).abs() < TOL && (n20[C] - 10.0).abs() < TOL,
        "{n20:?}"
    );
    let t = r
        .machine
        .five_axis()
        .unwrap()
        .tool_vector(&Pose::from_array(n20));
    assert!(
        (t[0] + 0.4924).abs() < TOL && (t[1] + 0.0868).abs() < TOL && (t[2] - 0.8660).abs() < TOL
    );
    // N40 ORIRPY A2=45 C2=45 → (0.5, −0.5, 0.7071); N50 vector → (−0.5774, −0.5774, 0.5774);
    // N60 ORIRPY A2=60 → (0, −0.8660, 0.5).
    for (n, want) in [
        ("N40", [0.5, -0.5, 0.7071]),
        ("N50", [-0.5774, -0.5774, 0.5774]),
        ("N60", [0.0, -0.8660, 0.5]),
    ] {
        let t = r
            .machine
            .five_axis()
            .unwrap()
            .tool_vector(&Pose::from_array(r.end_of(n)));
        for i in 0..3 {
            assert!((t[i] - want[i]).abs() < TOL, "{n}: t {t:?}");
        }
    }
    // N90 alone is 653 too.
    let text = r.text.replace("N80 A2=30 A3=-1", "N80");
    let r2 = run(
        &text,
        Dialect::Axioma,
        "5axis-bc-head",
        control(),
        Pose {
            z: 100.0,
            ..Pose::ZERO
        },
    );
    let d = r2.error.clone().expect("653 at N90");
    assert_eq!(d.code, stanok_canon::DiagCode::Manual(653));
    assert_eq!(d.span.line, r2.line_of("N90"));
}

#[test]
fn example_12_10_oriaxes_short_solution() {
    let r = fixture("s12_4_1-oriaxes-example-12_10.nc");
    r.ok();
    assert_axes(
        r.end_of("N40"),
        [70.7107, 0.0, 70.7107],
        &[(C, 0.0), (B, 45.0)],
        TOL,
        "N40",
    );
    // V2 = (0.5, −0.8660, 0): C −60 B90 (not C300 nor C120 B−90); machine = L·t.
    assert_axes(
        r.end_of("N50"),
        [50.0, -86.6025, 0.0],
        &[(C, -60.0), (B, 90.0)],
        TOL,
        "N50",
    );
    // ORIAXES: the axes are linear; at C −30 B 67.5, t = (0.8001, −0.4619, 0.3827).
    let mid = r
        .block("N50")
        .into_iter()
        .min_by(|a, b| {
            (a.joints[C] + 30.0)
                .abs()
                .total_cmp(&(b.joints[C] + 30.0).abs())
        })
        .unwrap();
    assert!((mid.joints[B] - (45.0 + 45.0 * mid.joints[C] / -60.0)).abs() < 1e-6);
    assert_tip_fixed(&r, "N50", [0.0; 3]);
}

#[test]
fn example_12_11_orivect_great_circle() {
    let r = fixture("s12_4_2-orivect-example-12_11.nc");
    r.ok();
    assert_axes(
        r.end_of("N50"),
        [50.0, -86.6025, 0.0],
        &[(C, -60.0), (B, 90.0)],
        TOL,
        "N50",
    );
    // On the way: (C, B) = (−20.069, 53.455), (−35.657, 64.547), (−48.459, 76.992) at s = ¼, ½, ¾.
    let kin = r.machine.five_axis().unwrap();
    let sps = r.block("N50");
    for (c, b) in [(-20.069, 53.455), (-35.657, 64.547), (-48.459, 76.992)] {
        let near = sps
            .iter()
            .min_by(|x, y| (x.joints[C] - c).abs().total_cmp(&(y.joints[C] - c).abs()))
            .unwrap();
        assert!(
            (near.joints[B] - b).abs() < 0.02,
            "at C {c}: B {}",
            near.joints[B]
        );
    }
    // Every tool vector lies on the V1–V2 great circle (within the 0.5° polyline step).
    let v1 = [0.5f64.sqrt(), 0.0, 0.5f64.sqrt()];
    let v2 = [0.5, -(0.75f64.sqrt()), 0.0];
    let n = [
        v1[1] * v2[2] - v1[2] * v2[1],
        v1[2] * v2[0] - v1[0] * v2[2],
        v1[0] * v2[1] - v1[1] * v2[0],
    ];
    let norm = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    for sp in &sps {
        let t = kin.tool_vector(&Pose::from_array(sp.joints));
        let off = (t[0] * n[0] + t[1] * n[1] + t[2] * n[2]) / norm;
        assert!(off.abs() < 2e-4, "{t:?} off the great circle by {off}");
    }
    assert_tip_fixed(&r, "N50", [0.0; 3]);
    // F600 is the vector's angular speed on its 69.2952° arc: 6.93 s.
    let d = r.duration_of("N50");
    assert!((6.93..7.0).contains(&d), "N50 lasts {d} s");
}

#[test]
fn example_12_12_orivect_the_long_way() {
    let r = fixture("s12_4_2-orivect-long-path-example-12_12.nc");
    r.ok();
    assert_axes(
        r.end_of("N50"),
        [-50.0, 86.6025, 0.0],
        &[(C, 120.0), (B, 90.0)],
        TOL,
        "N50",
    );
    let v12 = r.end_of("N60");
    assert!(
        (v12[C] - 210.0).abs() < TOL && (v12[B] - 135.0).abs() < TOL,
        "{v12:?}"
    );
    let n70 = r.end_of("N70");
    assert!(
        (n70[C] - 300.0).abs() < TOL && (n70[B] - 90.0).abs() < TOL,
        "{n70:?}"
    );
}

#[test]
fn traori_on_a_three_axis_machine_is_error_654() {
    let text = corpus_text("axioma/s12_2_2-traori-rotate-in-place-example-12_1.nc");
    let r = run(&text, Dialect::Axioma, "mill", control(), Pose::ZERO);
    let d = r.error.clone().expect("654");
    assert_eq!(d.code, stanok_canon::DiagCode::Manual(654));
    assert_eq!(d.span.line, r.line_of("N30"));
}

#[test]
fn orientation_change_under_radius_compensation_is_error_656() {
    let text = "T2 M6\nG43\nTRAORI\nG01 G41 X10 Y0 F600\nX20 B10\nM30\n";
    let mut c = control();
    c.tools.tools.get_mut(&2).unwrap().edges[0].radius = 5.0;
    let r = run(
        text,
        Dialect::Axioma,
        "5axis-bc-head",
        c,
        Pose {
            z: 100.0,
            ..Pose::ZERO
        },
    );
    let d = r.error.clone().expect("656");
    assert_eq!(d.code, stanok_canon::DiagCode::Manual(656), "{d:?}");
    assert_eq!(d.span.line, 5);
}

#[test]
fn example_12_10_fragments_direct_axes() {
    // Fragments (no tool, no TRAORI): the axes move as programmed; both end at V2 = (0.5, −0.866,
    // 0); fragment b turns C the long way, its middle (C150 B67.5) is t = (−0.8001, 0.4619, 0.3827).
    for (name, c_end) in [
        ("s12_4_1-oriaxes-equivalent-axes-fragment-a.nc", -60.0),
        ("s12_4_1-oriaxes-equivalent-axes-fragment-b.nc", 300.0),
    ] {
        let r = fixture_with(name, ControlData::default());
        r.ok();
        let end = r.end_of("N50");
        assert!(
            (end[C] - c_end).abs() < 1e-9 && (end[B] - 90.0).abs() < 1e-9,
            "{end:?}"
        );
        let kin = r.machine.five_axis().unwrap();
        let t = kin.tool_vector(&Pose::from_array(end));
        assert!((t[0] - 0.5).abs() < TOL && (t[1] + 0.8660).abs() < TOL && t[2].abs() < TOL);
        if c_end > 0.0 {
            let mid = kin.tool_vector(&Pose {
                b: 67.5,
                c: 150.0,
                ..Pose::ZERO
            });
            assert!((mid[0] + 0.8001).abs() < TOL && (mid[1] - 0.4619).abs() < TOL);
            // The trace passes there: C and B move linearly together.
            assert!(r
                .block("N50")
                .iter()
                .any(|s| (s.joints[C] - 150.0).abs() < 1.0 && (s.joints[B] - 67.5).abs() < 0.5));
        }
    }
}

#[test]
fn plot_draws_tool_axis_ticks_under_traori() {
    // Example 12.1 plotted on the 5-axis head: the tip path (a point) and five tool-axis ticks of
    // 10 mm.
    let dir = std::env::temp_dir().join("stanok-five-axis-plot");
    std::fs::create_dir_all(&dir).unwrap();
    let tools = dir.join("tools.toml");
    std::fs::write(
        &tools,
        "[[tool]]\nnumber = 2\nkind = \"milling\"\n[[tool.edge]]\nlength = [100.0, 0.0, 0.0]\n",
    )
    .unwrap();
    let out = dir.join("rot.svg");
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus/axioma/s12_2_2-traori-rotate-in-place-example-12_1.nc"
    );
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_stanok"))
        .args(["plot", file, "-o"])
        .arg(&out)
        .args(["--machine", "5axis-bc-head", "--tools"])
        .arg(&tools)
        .status()
        .unwrap();
    assert!(status.success());
    let svg = std::fs::read_to_string(&out).unwrap();
    // One tool-axis path per view (four views) and the legend's sample; the ticks' geometry is
    // unit-tested in `tool_axis.rs` (the last one from (0, 0, −100) to (−9.659258, 0, −97.411810)).
    assert_eq!(svg.matches("class=\"tool-axis\"").count(), 4 + 1, "{svg}");
    // Without the 5-axis machine there is no tick (and TRAORI is refused: 654).
    let plain = dir.join("plain.svg");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_stanok"))
        .args(["plot", file, "-o"])
        .arg(&plain)
        .status()
        .unwrap();
    assert!(!status.success());
    assert!(!std::fs::read_to_string(&plain)
        .unwrap()
        .contains("tool-axis"));
}
