//! Mazatrol tool tip point control (corpus/mazatrol): the oracle fixtures on the machines their
//! headers state (built-in `millturn-bc` for oracles A, B, C; `5axis-ac-table` for oracle D), with
//! H1 = 100 mm and the headers' work offsets, through interpreter → simulated machine → servo
//! trace. Asserted: the machine positions of the headers (1e-6; X of the mill-turn is a diameter),
//! the tip held in rotary-only blocks (1e-6 mm), the alarms of the error fixtures, and zero limit
//! violations.

mod five_axis_harness;
use five_axis_harness::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind, ZeroOffset};
use stanok_canon::Pose;
use stanok_kin::Kinematics;
use stanok_kin::TtpcFrame;
use stanok_machine::MachineData;
use stanok_syntax::Dialect;

const A: usize = 3;
const B: usize = 4;
const C: usize = 5;
const TOL: f64 = 1e-6;

fn control(work_offset: [f64; 3]) -> ControlData {
    let mut c = ControlData::default();
    c.tools.tools.insert(
        1,
        Tool {
            number: 1,
            kind: ToolKind::Milling,
            edges: vec![ToolEdge {
                length: [100.0, 0.0, 0.0],
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    c.offsets.zero[0][0] = ZeroOffset {
        offset: Pose {
            x: work_offset[0],
            y: work_offset[1],
            z: work_offset[2],
            ..Pose::ZERO
        },
        rotation_xy: 0.0,
    };
    c
}

fn fixture(name: &str, machine: &str, w: [f64; 3], start: Pose) -> Run {
    run(
        &corpus_text(&format!("mazatrol/{name}")),
        Dialect::Mazatrol,
        machine,
        control(w),
        start,
    )
}

fn millturn(name: &str, start: Pose) -> Run {
    fixture(name, "millturn-bc", [0.0, 0.0, -400.0], start)
}

fn pose(x: f64, y: f64, z: f64, a: f64, b: f64, c: f64) -> Pose {
    Pose {
        x,
        y,
        z,
        a,
        b,
        c,
        ..Pose::ZERO
    }
}

#[test]
fn oracle_a_type1_millturn() {
    let r = millturn(
        "g43_4-type1-oracle-millturn-bc.nc",
        pose(0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    );
    r.ok();
    assert_axes(
        r.end_of("N20"),
        [-145.7395026, 20.0, -368.3697513],
        &[(B, 45.0), (C, 0.0)],
        TOL,
        "N20",
    );
    assert_axes(
        r.end_of("N30"),
        [-185.7395026, 0.0, -378.3697513],
        &[(B, 45.0), (C, 90.0)],
        TOL,
        "N30",
    );
    assert_axes(
        r.end_of("N40"),
        [-39.0, 0.0, -555.5],
        &[(B, 90.0), (C, 90.0)],
        TOL,
        "N40",
    );
    assert_axes(
        r.end_of("N50"),
        [-239.0, 0.0, -555.5],
        &[(B, 90.0), (C, 90.0)],
        TOL,
        "N50",
    );
    // N30 at s = 0.5: Xm −174.0237739, Ym 14.1421356 (C 45), not the joint-linear (−165.74, 10).
    let mid = r
        .block("N30")
        .into_iter()
        .min_by(|a, b| {
            (a.joints[C] - 45.0)
                .abs()
                .total_cmp(&(b.joints[C] - 45.0).abs())
        })
        .unwrap();
    assert!((mid.joints[C] - 45.0).abs() < 0.2, "{mid:?}");
    let tool = r.machine.five_axis().unwrap().with_tool_length(100.0);
    // C is linear in the path parameter s = C/90; the tip is at table (0, 20, 5 − 10 s).
    let s = mid.joints[C] / 90.0;
    let want = tool
        .inverse(&pose(
            0.0,
            20.0,
            -395.0 - 10.0 * s,
            0.0,
            45.0,
            mid.joints[C],
        ))
        .unwrap();
    assert_axes(
        mid.joints,
        [want[0], want[1], want[2]],
        &[],
        1e-6,
        "N30 middle",
    );
    assert_axes(
        mid.joints,
        [-174.0237739, 14.1421356, -373.3697513],
        &[],
        0.5,
        "N30 middle",
    );
    // N40 turns B with the tip held at table (0, 20, −5).
    for sp in r.block("N40") {
        let tip = tool.forward(&sp.joints).unwrap();
        assert!(
            (tip.y - 20.0).abs() < 1e-6 && tip.x.abs() < 1e-6 && (tip.z + 405.0).abs() < 1e-6,
            "{tip:?}"
        );
    }
    // N30: C needs 9000 deg/min at F1000; its 3600 deg/min limit stretches the block to ≥ 1.5 s
    // (the kin stage plans C at 90 % of its limit with half its acceleration: about 1.83 s).
    let d = r.duration_of("N30");
    assert!((1.5..2.0).contains(&d), "N30 lasts {d} s");
}

#[test]
fn oracle_b_type2_millturn() {
    let r = millturn("g43_5-type2-oracle-millturn-bc.nc", Pose::ZERO);
    r.ok();
    assert_axes(
        r.end_of("N20"),
        [-145.7395026, 20.0, -368.3697513],
        &[(B, 45.0), (C, 0.0)],
        TOL,
        "N20",
    );
    assert_axes(
        r.end_of("N30"),
        [-105.7395026, 0.0, -368.3697513],
        &[(B, 45.0), (C, -90.0)],
        TOL,
        "N30",
    );
    assert_axes(
        r.end_of("N40"),
        [-185.7395026, 0.0, -368.3697513],
        &[(B, 45.0), (C, -90.0)],
        TOL,
        "N40",
    );
    assert_axes(
        r.end_of("N50"),
        [-327.1608589, 0.0, -439.0804294],
        &[(B, 45.0), (C, -90.0)],
        TOL,
        "N50",
    );
    // N40: 40 mm at F1000 = 2.4 s.
    let d = r.duration_of("N40");
    assert!((2.4..2.5).contains(&d), "N40 lasts {d} s");
}

#[test]
fn type2_omitted_components_and_ignored_rotary_words() {
    let r = millturn("g43_5-type2-omission-and-rotary-ignored.nc", Pose::ZERO);
    r.ok();
    assert_axes(
        r.end_of("N20"),
        [-145.7395026, 20.0, -368.3697513],
        &[(B, 45.0), (C, 0.0)],
        TOL,
        "N20",
    );
    // B90 is not executed.
    assert_axes(
        r.end_of("N30"),
        [-145.7395026, 10.0, -368.3697513],
        &[(B, 45.0), (C, 0.0)],
        TOL,
        "N30",
    );
    assert_axes(
        r.end_of("N40"),
        [-125.7395026, 0.0, -368.3697513],
        &[(B, 45.0), (C, -90.0)],
        TOL,
        "N40",
    );
}

#[test]
fn oracle_c_independent_start_and_cancel() {
    let r = millturn(
        "g43_4-type1-oracle-independent-start.nc",
        pose(-100.0, 0.0, -300.0, 0.0, 30.0, 0.0),
    );
    r.ok();
    assert_axes(
        r.end_of("N20"),
        [0.0, 0.0, -213.3974596],
        &[(B, 30.0), (C, 0.0)],
        TOL,
        "N20",
    );
    assert_axes(
        r.end_of("N30"),
        [-100.0, 0.0, -300.0],
        &[(B, 30.0)],
        TOL,
        "N30",
    );
}

#[test]
fn oracle_d_trunnion_g91_and_note_6() {
    let r = fixture(
        "g43_4-type1-oracle-trunnion-ac.nc",
        "5axis-ac-table",
        [500.0, 250.0, -450.0],
        pose(500.0, 250.0, -200.0, 0.0, 0.0, 0.0),
    );
    assert_axes(
        r.end_of("N20"),
        [500.0, 250.0, -300.0],
        &[(A, 0.0), (C, 0.0)],
        TOL,
        "N20",
    );
    assert_axes(
        r.end_of("N30"),
        [500.0, 208.6602540, -308.3974596],
        &[(A, 30.0), (C, 0.0)],
        TOL,
        "N30",
    );
    assert_axes(
        r.end_of("N40"),
        [480.0, 200.0, -313.3974596],
        &[(A, 30.0), (C, 90.0)],
        TOL,
        "N40",
    );
    assert_axes(
        r.end_of("N50"),
        [480.0, 250.0, -300.0],
        &[(A, 0.0), (C, 90.0)],
        TOL,
        "N50",
    );
    // N30 at s = 0.5 (A15, tip (0, 5, 50)): 500, 228.9477246, −302.1133221.
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let mid = kin
        .inverse(&pose(500.0, 255.0, -400.0, 15.0, 0.0, 0.0))
        .unwrap();
    assert_axes(
        mid,
        [500.0, 228.9477246, -302.1133221],
        &[],
        TOL,
        "N30 middle",
    );
    assert!(r
        .block("N30")
        .iter()
        .any(|s| (s.joints[A] - 15.0).abs() < 0.2 && (s.joints[1] - 228.9477246).abs() < 0.3));
    // N50 holds the tip at table (0, 20, 50) while A turns.
    for sp in r.block("N50") {
        let tip = kin.forward(&sp.joints).unwrap();
        assert!(
            (tip.x - 500.0).abs() < 1e-6
                && (tip.y - 270.0).abs() < 1e-6
                && (tip.z + 400.0).abs() < 1e-6,
            "{tip:?}"
        );
    }
    // N60: C45 while the tool is parallel to C → ILLEGAL NUMBER INPUT, no motion.
    let d = r.error.as_ref().expect("Note 6 alarm");
    assert_eq!(d.code.to_string(), "mazatrol::illegal-number-input");
    assert_eq!(d.span.line, r.line_of("N60"));
    assert!(r.block("N60").is_empty());
    assert_eq!(r.report.violation_count, 0);
}

fn error_of(name: &str) -> (Run, stanok_canon::Diagnostic) {
    let r = millturn(name, Pose::ZERO);
    let d = r
        .error
        .clone()
        .unwrap_or_else(|| panic!("{name}: no error"));
    (r, d)
}

#[test]
fn alarms_of_the_error_fixtures() {
    for (name, code, block) in [
        (
            "err-g43_4-with-other-gcode.nc",
            "mazatrol::ttpc-with-other-g-code",
            "N20",
        ),
        ("err-g49-not-alone.nc", "mazatrol::g49-not-alone", "N30"),
        (
            "err-tseries-g02-in-ttpc.nc",
            "mazatrol::code-not-allowed-in-ttpc",
            "N30",
        ),
        (
            "err-type2-reverse-direction.nc",
            "mazatrol::illegal-number-input",
            "N30",
        ),
    ] {
        let (r, d) = error_of(name);
        assert_eq!(d.code.to_string(), code, "{name}: {d:?}");
        assert_eq!(d.span.line, r.line_of(block), "{name}");
        // Nothing of the bad block moved.
        assert!(r.block(block).is_empty(), "{name}");
    }
}

#[test]
fn ttpc_on_a_three_axis_machine_is_refused() {
    let r = run(
        "G01 F1000\nG43.4 X0 Y0 Z50. H1\n",
        Dialect::Mazatrol,
        "mill",
        control([0.0; 3]),
        Pose::ZERO,
    );
    let d = r.error.expect("option alarm");
    assert_eq!(d.code.to_string(), "mazatrol::option-not-installed");
}

#[test]
fn workpiece_frame_versus_table_frame() {
    // §4: parameter 0 (table frame) and 1 (workpiece frame, `ttpc_frame = "workpiece"`) on the
    // A/C trunnion, w = (500, 250, −450), L = 100. Workpiece frame: every block's X Y Z is the
    // physical tip in W at the block's end table pose, so G(r)·(table-frame tip) − w = P (1e-9);
    // table frame: the table-frame tip − w = P. G91 adds in the frame programmed. During a block
    // the tip moves on a straight line relative to the table in both (1e-6 mm), which is what F
    // is the speed of (§9).
    // (A tilts first: C with the tool along C's axis is R-06.)
    let text = "N10 G43.4 H1\nN15 G01 A30 F1000\nN20 X10 Y0 Z0 C90\nN30 G91 X5\nN40 G90 X15 Y0 Z0 A20\nN50 G49\nM30\n";
    let w = [500.0, 250.0, -450.0];
    let wanted = [
        ("N20", [10.0, 0.0, 0.0]),
        ("N30", [15.0, 0.0, 0.0]),
        ("N40", [15.0, 0.0, 0.0]),
    ];
    let mut joints = Vec::new();
    for frame in [TtpcFrame::Table, TtpcFrame::Workpiece] {
        let mut m = MachineData::builtin("5axis-ac-table").unwrap();
        m.kinematics.as_mut().unwrap().ttpc_frame = frame;
        m.control = control(w);
        let r = run_on(
            text,
            Dialect::Mazatrol,
            m,
            pose(500.0, 250.0, -200.0, 0.0, 0.0, 0.0),
        );
        r.ok();
        let base = r.machine.five_axis().unwrap();
        let tool = base.clone().with_tool_length(100.0);
        for (n, p) in wanted {
            let q = r.end_of(n);
            let t = tool.forward(&q).unwrap();
            let tip = match frame {
                TtpcFrame::Table => t.xyz(),
                TtpcFrame::Workpiece => base.table_at(&t, t.xyz()),
            };
            for i in 0..3 {
                assert!(
                    (tip[i] - w[i] - p[i]).abs() < 1e-9,
                    "{frame:?} {n}: tip {tip:?}, want {p:?} + w"
                );
            }
            joints.push(q);
            // Straight relative to the table: every setpoint's table-frame tip on the chord.
            let sps = r.block(n);
            let (a, b) = (
                tool.forward(&sps[0].joints).unwrap().xyz(),
                tool.forward(&sps[sps.len() - 1].joints).unwrap().xyz(),
            );
            for sp in &sps {
                let x = tool.forward(&sp.joints).unwrap().xyz();
                let d = stanok_geom::distance_to_segment(x, a, b);
                assert!(d < 1e-6, "{frame:?} {n}: {d} mm off the line");
            }
        }
    }
    // The two frames differ once the table has turned (N20 at A30 C90).
    assert!((0..3).any(|i| (joints[0][i] - joints[3][i]).abs() > 1.0));
}

#[test]
fn feed_modes_in_ttpc() {
    // §9: G94 (feed per minute) is accepted in and out of TTPC; G95 in TTPC is not allowed
    // (the compatibility tables' "no"), G93 runs in and out of it (M-series, table 12.2).
    let run_text = |text: &str| {
        run(
            text,
            Dialect::Mazatrol,
            "5axis-ac-table",
            control([500.0, 250.0, -450.0]),
            pose(500.0, 250.0, -200.0, 0.0, 0.0, 0.0),
        )
    };
    run_text("G94 G01 X10 F500\nG43.4 H1\nG94 G01 X20 F500\nG49\nM30\n").ok();
    let e = run_text("G43.4 H1\nG95 G01 X20 F0.1\n").error.expect("G95");
    assert_eq!(e.code.to_string(), "mazatrol::code-not-allowed-in-ttpc");
    assert_eq!((e.span.line, e.span.column), (2, 1));
    // G93 (inverse time, docs/dialects/mazatrol-eia.md §6.4) runs, in TTPC too on the M-series.
    run_text("G93 G01 X20 F600\nG43.4 H1\nG01 X30 F600\nG49\nM30\n").ok();
}

#[test]
fn m_series_arc_in_ttpc_with_the_workpiece_frame() {
    // corpus m-g02-arc-type1-wcs.nc on the B head + C table (`5axis-bc-head-table`, at B0 the
    // machine point is tip + (0, 0, L)), L = 100, w = (−300, −200, −400):
    // * F85 bit 2 = 1 (workpiece frame): N30 is the clockwise half circle centre (10, 0) from
    //   (0, 0, 10) to (20, 0, 10) — at every setpoint the tip is on it (1 µm: the arc runs as
    //   chords of ≤ 1 µm sag) on the +Y side, the axes are m = tip + w + (0, 0, L) (1e-9) so the
    //   half-way point is m = (−290, −190, −290); N40 carries B → mazatrol::rotary-word-in-arc.
    // * F85 bit 2 = 0 (table frame), or G43.5: N30 is code-not-allowed-in-ttpc.
    let text = corpus_text("mazatrol/m-g02-arc-type1-wcs.nc");
    let w = [-300.0, -200.0, -400.0];
    let start = pose(-300.0, -200.0, -200.0, 0.0, 0.0, 0.0);
    let machine = |frame| {
        let mut m = MachineData::builtin("5axis-bc-head-table").unwrap();
        m.kinematics.as_mut().unwrap().ttpc_frame = frame;
        m.control = control(w);
        m
    };
    let r = run_on(
        &text,
        Dialect::Mazatrol,
        machine(TtpcFrame::Workpiece),
        start,
    );
    let e = r.error.clone().expect("N40 is an error");
    assert_eq!(e.code.to_string(), "mazatrol::rotary-word-in-arc", "{e:?}");
    assert_eq!(e.span.line, r.line_of("N40"));
    assert_eq!(r.report.violation_count, 0);
    let sps = r.block("N30");
    assert!(sps.len() > 50);
    for sp in &sps {
        let q = sp.joints;
        let tip = [q[0] - w[0], q[1] - w[1], q[2] - 100.0 - w[2]];
        let radius = (tip[0] - 10.0).hypot(tip[1]);
        assert!(
            (radius - 10.0).abs() < 1e-3 && (tip[2] - 10.0).abs() < 1e-9,
            "{tip:?}"
        );
        assert!(tip[1] > -1e-6, "{tip:?}");
        assert!(q[4].abs() < 1e-9 && q[5].abs() < 1e-9, "{q:?}");
    }
    // The setpoint nearest the half-way point (within 0.05 mm in X) is at m ≈ (−290, −190, −290).
    let mid = sps
        .iter()
        .min_by(|p, q| {
            (p.joints[0] + 290.0)
                .abs()
                .total_cmp(&(q.joints[0] + 290.0).abs())
        })
        .unwrap()
        .joints;
    assert!((mid[0] + 290.0).abs() < 0.05, "{mid:?}");
    assert!(
        (mid[1] + 190.0).abs() < 1e-3 && (mid[2] + 290.0).abs() < 1e-9,
        "{mid:?}"
    );
    assert_axes(
        r.end_of("N30"),
        [-280.0, -200.0, -290.0],
        &[(B, 0.0), (C, 0.0)],
        TOL,
        "N30",
    );
    for (frame, program) in [
        (TtpcFrame::Table, text.clone()),
        (
            TtpcFrame::Workpiece,
            text.replace("G43.4 X0 Y0 Z10. B0 H1", "G43.5 X0 Y0 Z10. I0 J0 K1 H1"),
        ),
    ] {
        let r = run_on(&program, Dialect::Mazatrol, machine(frame), start);
        let e = r.error.clone().expect("N30 refused");
        assert_eq!(
            e.code.to_string(),
            "mazatrol::code-not-allowed-in-ttpc",
            "{frame:?}"
        );
        assert_eq!(e.span.line, r.line_of("N30"), "{frame:?}");
    }
}

/// A document-example fixture with its placeholders replaced (longest names first), run on
/// `5axis-ab-head` with H1 = L = 100 and no work offset, from the machine pose `start`.
fn document_example(name: &str, values: &[(&str, &str)], start: Pose) -> Run {
    let mut text = corpus_text(&format!("mazatrol/{name}"));
    let mut sorted = values.to_vec();
    sorted.sort_by_key(|(k, _)| std::cmp::Reverse(k.len()));
    let body: String = text
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
    text = format!("G01 F1000;\n{body}M30;\n");
    let r = run(
        &text,
        Dialect::Mazatrol,
        "5axis-ab-head",
        control([0.0; 3]),
        start,
    );
    r.ok();
    r
}

#[test]
fn document_examples_with_their_placeholders_filled() {
    // The source's examples with placeholders (x, y1, h …) filled in, each asserting the rule
    // its header states (1e-6 mm / 1e-9 for exact algebra): independent start moves the axes +L
    // along the tool axis (§5.1); G49 moves them back (§6); a rotary-only or vector-only block
    // holds the tip at every setpoint (§7); start with motion puts the tip and the orientation
    // where programmed (§5.2); G91 linear + rotary / vector blocks keep the tip on the straight
    // line between the programmed points (§7.3). Machine 5axis-ab-head, L = 100.
    let start = pose(10.0, 20.0, 300.0, 0.0, 30.0, 0.0);
    let kin = MachineData::builtin("5axis-ab-head")
        .unwrap()
        .five_axis()
        .unwrap();
    let tool = kin.clone().with_tool_length(100.0);
    let t0 = kin.tool_vector(&start);
    let lines = |r: &Run| -> Vec<u32> {
        let mut l: Vec<u32> = r.setpoints.iter().map(|s| s.line).collect();
        l.dedup();
        l
    };
    let tip_of = |q: &[f64; 9]| tool.forward(q).unwrap().xyz();
    let last = |r: &Run| r.setpoints.last().unwrap().joints;
    // §5.1 independent start, both types, and §6 G49 cancel.
    for name in ["g43_4-type1-start.nc", "g43_5-type2-start.nc"] {
        let r = document_example(name, &[("h", "1")], start);
        let q = last(&r);
        for i in 0..3 {
            let want = start.to_array()[i] + 100.0 * t0[i];
            assert!((q[i] - want).abs() < 1e-6, "{name}: {q:?}");
        }
    }
    let r = run(
        "G43.4 H1;\nG49 ;\nM30;\n",
        Dialect::Mazatrol,
        "5axis-ab-head",
        control([0.0; 3]),
        start,
    );
    r.ok();
    let q = last(&r);
    assert!(
        (0..6).all(|i| (q[i] - start.to_array()[i]).abs() < 1e-6),
        "G49: {q:?}"
    );
    // §7: rotary-only (type 1) and vector-only (type 2) blocks hold the tip.
    for (name, values) in [
        (
            "g43_4-type1-rotary-only.nc",
            vec![("Hh", "H1"), ("Aa", "A20")],
        ),
        (
            "g43_5-type2-vector-only.nc",
            vec![
                ("i1", "0"),
                ("j1", "0.5"),
                ("k1", "0.8660254"),
                ("i2", "0.3"),
                ("j2", "0.3"),
                ("k2", "0.9055385"),
                ("h", "1"),
            ],
        ),
    ] {
        let r = document_example(name, &values, start);
        let line = *lines(&r).last().unwrap();
        let sps: Vec<_> = r.setpoints.iter().filter(|s| s.line == line).collect();
        assert!(sps.len() > 5, "{name}");
        let tip = tip_of(&sps[0].joints);
        for sp in sps {
            let p = tip_of(&sp.joints);
            assert!(
                (0..3).all(|i| (p[i] - tip[i]).abs() < 1e-6),
                "{name}: {p:?} vs {tip:?}"
            );
        }
        if name.contains("type2") {
            let t = kin.tool_vector(&tool.forward(&last(&r)).unwrap());
            let want = [0.3, 0.3, 0.9055385];
            let n = (want.iter().map(|v| v * v).sum::<f64>()).sqrt();
            assert!((0..3).all(|i| (t[i] - want[i] / n).abs() < 1e-9), "{t:?}");
        }
    }
    // §5.2 start with motion, type 2.
    let r = document_example(
        "g43_5-type2-start-move.nc",
        &[
            ("Xx", "X15"),
            ("Yy", "Y-10"),
            ("Zz", "Z50"),
            ("Ii", "I0"),
            ("Jj", "J-0.6"),
            ("Kk", "K0.8"),
            ("Hh", "H1"),
        ],
        start,
    );
    let q = last(&r);
    let p = tip_of(&q);
    assert!(
        (0..3).all(|i| (p[i] - [15.0, -10.0, 50.0][i]).abs() < 1e-6),
        "{p:?}"
    );
    let t = kin.tool_vector(&Pose::from_array(q));
    assert!(
        (0..3).all(|i| (t[i] - [0.0, -0.6, 0.8][i]).abs() < 1e-9),
        "{t:?}"
    );
    // §7.3: G91 blocks, linear + rotary (type 1) and linear + vector (type 2): the tip on the
    // straight line between the block's programmed ends at every setpoint.
    for (name, values) in [
        (
            "g43_4-type1-linear-rotary.nc",
            vec![
                ("y1", "10"),
                ("z1", "-20"),
                ("a1", "10"),
                ("y2", "15"),
                ("a2", "15"),
                ("y3", "-5"),
                ("a3", "-10"),
                ("h", "1"),
            ],
        ),
        (
            "g43_5-type2-linear-vector.nc",
            vec![
                ("y1", "10"),
                ("z1", "-20"),
                ("i1", "0"),
                ("j1", "-0.2"),
                ("k1", "0.9797959"),
                ("y2", "15"),
                ("i2", "0.1"),
                ("j2", "-0.3"),
                ("k2", "0.9486833"),
                ("y3", "-5"),
                ("i3", "0"),
                ("j3", "0"),
                ("k3", "1"),
                ("h", "1"),
            ],
        ),
    ] {
        let r = document_example(name, &values, start);
        // The type-2 example has no H word: L stays 0 (no length offset in force).
        let length = if name.contains("type2") { 0.0 } else { 100.0 };
        let tool = kin.clone().with_tool_length(length);
        let tip_of = |q: &[f64; 9]| tool.forward(q).unwrap().xyz();
        let ls = lines(&r);
        let blocks = &ls[ls.len() - 2..];
        for &line in blocks {
            let sps: Vec<_> = r.setpoints.iter().filter(|s| s.line == line).collect();
            // The programmed tip ends: the block's Canon line (table frame).
            let m = r
                .canon
                .iter()
                .zip(&r.lines)
                .filter(|(_, &l)| l == line)
                .find_map(|(c, _)| c.motion())
                .unwrap();
            let (a, b) = (m.start().xyz(), m.end().xyz());
            assert!((a[1] - b[1]).abs() > 1.0, "{name}: line {line} moves in Y");
            for sp in sps {
                let d = stanok_geom::distance_to_segment(tip_of(&sp.joints), a, b);
                assert!(d < 1e-6, "{name} line {line}: {d} mm off the line");
            }
        }
    }
}
