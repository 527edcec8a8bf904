//! AxiOMA coordinate chain (spec axioma-1 §8–§14): every s4_1 … s4_6 fixture yields the machine
//! coordinates its header states (assert them; where the header lists two readings, the one the spec
//! chooses), with the test set-ups the spec suggests for the table offsets. Tolerance 1e-4 mm.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::setup::{ControlData, WorkpieceFrame};
use stanok_canon::{Canon, DiagCode, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

const TOL: f64 = 1e-4;

fn run_with(text: &str, control: ControlData) -> Vec<Spanned<Canon>> {
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.control = control;
    let mut out = Vec::new();
    for item in Interpreter::from_text(text, opts) {
        out.push(item.unwrap_or_else(|d| panic!("unexpected error {d}")));
    }
    out
}

fn fixture(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap()
}

/// (N label, end point, centre if an arc, counter-clockwise about +Z).
type Move = (Option<u32>, [f64; 3], Option<([f64; 3], bool)>);

fn moves(cmds: &[Spanned<Canon>]) -> Vec<Move> {
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => {
                Some((c.block_number, m.end.xyz(), None))
            }
            Canon::ArcFeed(a) => Some((
                c.block_number,
                a.end.xyz(),
                Some((a.centre, a.axis[2] > 0.0)),
            )),
            _ => None,
        })
        .collect()
}

#[track_caller]
fn assert_ends(mvs: &[Move], want: &[(u32, [f64; 2])]) {
    for &(n, xy) in want {
        let m = mvs
            .iter()
            .find(|m| m.0 == Some(n))
            .unwrap_or_else(|| panic!("no move in N{n}"));
        assert!(
            (m.1[0] - xy[0]).abs() < TOL && (m.1[1] - xy[1]).abs() < TOL,
            "N{n}: got {:?}, want {xy:?}",
            m.1
        );
    }
}

#[test]
fn s4_1_zero_offsets_with_pages() {
    // Spec §20 set-up: G54/1 = (100, 50, 0), G56/12 = (−30, 20, 0).
    let mut c = ControlData::default();
    c.offsets.zero[0][0].offset.x = 100.0;
    c.offsets.zero[0][0].offset.y = 50.0;
    c.offsets.zero[2][11].offset.x = -30.0;
    c.offsets.zero[2][11].offset.y = 20.0;
    let mvs = moves(&run_with(
        &fixture("s4_1-zero-offset-g54-g59-example-4_1.nc"),
        c,
    ));
    let ends: Vec<[f64; 3]> = mvs.iter().map(|m| m.1).collect();
    assert_eq!(
        ends,
        [
            [0.0, 0.0, 0.0],
            [100.0, 50.0, 0.0],
            [-30.0, 20.0, 0.0],
            [0.0, 0.0, 0.0]
        ]
    );
}

#[test]
fn s4_2_workpiece_systems_rotate_and_shift() {
    // Spec §20: G154/1 O = (100,0,0), φ = 90° → (20,20) lands at (80,20). G157/6: O = (0,50,0),
    // φ = 0 → (20,70).
    let mut c = ControlData::default();
    c.offsets.workpiece[0][0] = WorkpieceFrame {
        origin: [100.0, 0.0, 0.0],
        euler: [90.0, 0.0, 0.0],
    };
    c.offsets.workpiece[3][5] = WorkpieceFrame {
        origin: [0.0, 50.0, 0.0],
        euler: [0.0, 0.0, 0.0],
    };
    let mvs = moves(&run_with(
        &fixture("s4_2-workpiece-cs-g154-g159-example-4_2.nc"),
        c,
    ));
    let xy: Vec<[f64; 2]> = mvs.iter().map(|m| [m.1[0], m.1[1]]).collect();
    for (got, want) in xy
        .iter()
        .zip([[0.0, 0.0], [80.0, 20.0], [20.0, 70.0], [0.0, 0.0]])
    {
        assert!(
            (got[0] - want[0]).abs() < TOL && (got[1] - want[1]).abs() < TOL,
            "{xy:?}"
        );
    }
    assert_eq!(xy.len(), 4);
}

#[test]
fn s4_3_1_mirror_contours() {
    let mvs = moves(&run_with(
        &fixture("s4_3_1-mirror-example-4_3.nc"),
        ControlData::default(),
    ));
    assert_ends(
        &mvs,
        &[
            (10, [60.0, 60.0]),
            (20, [100.0, 60.0]),
            (30, [100.0, 100.0]),
            (40, [60.0, 60.0]),
            // X inverted about X = 50.
            (60, [40.0, 60.0]),
            (70, [0.0, 60.0]),
            (80, [0.0, 100.0]),
            (90, [40.0, 60.0]),
            // X and Y inverted.
            (110, [40.0, 40.0]),
            (120, [0.0, 40.0]),
            (130, [0.0, 0.0]),
            (140, [40.0, 40.0]),
            // `G73 Y-1` leaves X inverted: the text's per-axis rule (spec A1), not the manual's
            // explanation of (4) — so contour (4) repeats (3).
            (160, [40.0, 40.0]),
            (170, [0.0, 40.0]),
            (180, [0.0, 0.0]),
            (190, [40.0, 40.0]),
        ],
    );
}

#[test]
fn s4_3_1_single_block_mirror_does_not_move() {
    let text = format!(
        "{}N20 G01 X10 Y5 F100\nM30\n",
        fixture("s4_3_1-mirror-single-block-fragment.nc")
    );
    let mvs = moves(&run_with(&text, ControlData::default()));
    // `N10 G190 G73 X-1 I0`: X inverted about X = 0, no motion of its own.
    assert_eq!(mvs.len(), 1);
    assert_ends(&mvs, &[(20, [-10.0, 5.0])]);
}

#[test]
fn s4_3_2_scale_doubles_the_square() {
    let mvs = moves(&run_with(
        &fixture("s4_3_2-scale-example-4_4.nc"),
        ControlData::default(),
    ));
    assert_ends(
        &mvs,
        &[
            (50, [10.0, 0.0]),
            (60, [10.0, 10.0]),
            (140, [20.0, 0.0]),
            (150, [20.0, 20.0]),
            (160, [0.0, 20.0]),
            (170, [0.0, 0.0]),
        ],
    );
}

#[test]
fn s4_3_3_relative_rotation_table() {
    let mvs = moves(&run_with(
        &fixture("s4_3_3-rotation-relative-example-4_5.nc"),
        ControlData::default(),
    ));
    assert_ends(
        &mvs,
        &[
            (10, [60.0, 60.0]),
            (20, [100.0, 60.0]),
            (30, [100.0, 100.0]),
            (60, [40.0, 60.0]),
            (70, [40.0, 100.0]),
            (80, [0.0, 100.0]),
            (110, [40.0, 40.0]),
            (120, [0.0, 40.0]),
            (130, [0.0, 0.0]),
            (160, [60.0, 40.0]),
            (170, [60.0, 0.0]),
            (180, [100.0, 0.0]),
        ],
    );
}

#[test]
fn s4_3_3_rotation_loop_cuts_eight_compensated_slots_45_degrees_apart() {
    // Example 4.6: the slot at 0°, then an HLL loop `for(ii=1; ii<8; ii++) { … }` whose ISO
    // blocks rotate by a further 45° (G91 G273 Q45 about the absolute pole (0,0), G190) and cut
    // the slot again: eight slots at 0°, 45°, …, 315°. Tool T2 r = 5, G42 inside the clockwise
    // obround: the compensated path runs at y = ±15 and on arcs of radius 20 − 5 = 15.
    let mut opts = InterpOptions::new(Dialect::Axioma);
    let mut tools = ControlData::default();
    tools.tools.tools.insert(
        2,
        stanok_canon::setup::Tool {
            number: 2,
            edges: vec![stanok_canon::setup::ToolEdge {
                radius: 5.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    opts.control = tools;
    let mut cmds = Vec::new();
    for item in Interpreter::from_text(&fixture("s4_3_3-rotation-loop-slots-example-4_6.nc"), opts)
    {
        cmds.push(item.unwrap_or_else(|d| panic!("unexpected error {d}")));
    }
    let rot = |deg: f64, p: [f64; 2]| {
        let (s, c) = deg.to_radians().sin_cos();
        [c * p[0] - s * p[1], s * p[0] + c * p[1]]
    };
    let mvs = moves(&cmds);
    // The blocks of one slot: the first at N40/N70/N100, the loop's at N160/N190/N220.
    let labels = |approach: u32, back: u32, exit: u32| -> Vec<(u32, [f64; 2])> {
        vec![
            (approach, [80.0, 15.0]),
            (back, [80.0, -15.0]),
            (exit, [80.0, 0.0]),
        ]
    };
    let ends = |n: u32| -> Vec<[f64; 3]> {
        mvs.iter()
            .filter(|m| m.0 == Some(n) && m.2.is_none())
            .map(|m| m.1)
            .collect()
    };
    for (n, p) in labels(40, 70, 100) {
        let e = ends(n);
        let last = e.last().unwrap_or_else(|| panic!("N{n} has no move"));
        assert!(
            (last[0] - p[0]).abs() < TOL && (last[1] - p[1]).abs() < TOL,
            "N{n}: {last:?}"
        );
    }
    for (n, p) in labels(160, 190, 220) {
        let e = ends(n);
        assert_eq!(e.len(), 7, "N{n} runs once per pass ii = 1 … 7: {e:?}");
        for (k, got) in e.iter().enumerate() {
            let want = rot(45.0 * (k + 1) as f64, p);
            assert!(
                (got[0] - want[0]).abs() < TOL && (got[1] - want[1]).abs() < TOL,
                "N{n} pass {}: {got:?} != {want:?}",
                k + 1
            );
            assert!(got[2].abs() < TOL, "N{n} at Z0");
        }
    }
    // 16 arcs, clockwise, radius 15 about the rotated end-circle centres.
    let arcs: Vec<&Move> = mvs.iter().filter(|m| m.2.is_some()).collect();
    assert_eq!(arcs.len(), 16);
    for (i, m) in arcs.iter().enumerate() {
        let slot = (i / 2) as f64;
        let centre = rot(
            45.0 * slot,
            if i % 2 == 0 {
                [180.0, 0.0]
            } else {
                [80.0, 0.0]
            },
        );
        let (c, ccw) = m.2.unwrap();
        assert!(!ccw, "arc {i} is clockwise");
        assert!(
            (c[0] - centre[0]).abs() < TOL && (c[1] - centre[1]).abs() < TOL,
            "arc {i}: centre {c:?} != {centre:?}"
        );
        assert!(((m.1[0] - c[0]).hypot(m.1[1] - c[1]) - 15.0).abs() < TOL);
    }
    // The last slot's retract N230 Z10 at 315°, then G191 G272 and M30.
    let last = mvs.last().unwrap();
    let want = rot(315.0, [80.0, 0.0]);
    assert!((last.1[0] - want[0]).abs() < TOL && (last.1[1] - want[1]).abs() < TOL);
    assert!((last.1[2] - 10.0).abs() < TOL);
    assert!(matches!(
        cmds.last().map(|c| &c.value),
        Some(Canon::ProgramEnd)
    ));
}

#[test]
fn s4_3_4_example_4_7_mirror_scale_rotate_and_arc_direction() {
    // The example also switches cutter compensation (G42/G40), a later issue; the programmed contour
    // and its transformation are checked with those two words removed.
    let text = fixture("s4_3_4-combined-transforms-example-4_7.nc")
        .replace(" G42", "")
        .replace(" G40", "");
    let mvs = moves(&run_with(&text, ControlData::default()));
    let r2 = std::f64::consts::SQRT_2;
    assert_ends(&mvs, &[(15, [50.0, 20.0]), (20, [20.0, 50.0])]);
    // (x,y) → (√2(x+y), √2(x−y)).
    assert_ends(
        &mvs,
        &[
            (115, [40.0 * r2, 0.0]),
            (120, [70.0 * r2, 30.0 * r2]),
            (130, [70.0 * r2, -30.0 * r2]),
        ],
    );
    let (_, _, arc) = mvs.iter().find(|m| m.0 == Some(130)).unwrap();
    let (centre, ccw) = arc.unwrap();
    assert!(
        (centre[0] - 40.0 * r2).abs() < TOL && centre[1].abs() < TOL,
        "{centre:?}"
    );
    // One mirrored in-plane axis: the CCW arc of the original runs clockwise.
    assert!(!ccw);
    let (_, _, original) = mvs.iter().find(|m| m.0 == Some(20)).unwrap();
    assert!(original.unwrap().1);
}

#[test]
fn s4_3_4_example_4_8_pole_table() {
    let mvs = moves(&run_with(
        &fixture("s4_3_4-combined-transforms-pole-example-4_8.nc"),
        ControlData::default(),
    ));
    assert_ends(
        &mvs,
        &[
            (40, [10.0, 0.0]),
            (50, [10.0, 10.0]),
            (60, [0.0, 5.0]),
            (115, [-10.0, 0.0]),
            (120, [-20.0, 0.0]),
            (125, [-20.0, -10.0]),
            (130, [-10.0, -5.0]),
            (220, [-15.0, 0.0]),
            (225, [-35.0, 0.0]),
            (230, [-35.0, -20.0]),
            (235, [-15.0, -10.0]),
            (325, [-5.0, -10.0]),
            (330, [-5.0, -30.0]),
            (335, [15.0, -30.0]),
            (340, [5.0, -10.0]),
        ],
    );
    // Centres (10,5), (−20,−5), (−35,−10), (5,−30); every arc stays counter-clockwise (two mirrored
    // in-plane axes are a rotation, spec A2).
    for (n, c) in [
        (50, [10.0, 5.0]),
        (125, [-20.0, -5.0]),
        (230, [-35.0, -10.0]),
        (335, [5.0, -30.0]),
    ] {
        let (_, _, arc) = mvs.iter().find(|m| m.0 == Some(n)).unwrap();
        let (centre, ccw) = arc.unwrap();
        assert!(
            (centre[0] - c[0]).abs() < TOL && (centre[1] - c[1]).abs() < TOL,
            "N{n}: {centre:?}"
        );
        assert!(ccw, "N{n}");
    }
}

#[test]
fn s4_4_1_relative_zero_shift() {
    // Spec §20: G54 = (100,100,0): circles about A (100,100) and B (300,100), radius 25, depth −2.
    let mut c = ControlData::default();
    c.offsets.zero[0][0].offset.x = 100.0;
    c.offsets.zero[0][0].offset.y = 100.0;
    let mvs = moves(&run_with(
        &fixture("s4_4_1-relative-zero-shift-g194-example-4_9.nc"),
        c,
    ));
    for (n, centre, end) in [
        (35, [100.0, 100.0], [125.0, 100.0]),
        (60, [300.0, 100.0], [325.0, 100.0]),
    ] {
        let (_, e, arc) = mvs.iter().find(|m| m.0 == Some(n)).unwrap();
        let (ctr, ccw) = arc.unwrap();
        assert!(
            (ctr[0] - centre[0]).abs() < TOL && (ctr[1] - centre[1]).abs() < TOL,
            "N{n} {ctr:?}"
        );
        assert!(
            (e[0] - end[0]).abs() < TOL && (e[2] + 2.0).abs() < TOL,
            "N{n} {e:?}"
        );
        assert!(!ccw);
    }
}

#[test]
fn s4_5_inch_and_metric() {
    let cmds = run_with(
        &fixture("s4_5-inch-metric-example-4_10.nc"),
        ControlData::default(),
    );
    let feeds: Vec<(Option<u32>, [f64; 3], f64)> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some((c.block_number, m.end.xyz(), m.feed)),
            _ => None,
        })
        .collect();
    assert_eq!(feeds[0], (Some(20), [100.0, 100.0, 100.0], 500.0));
    assert_eq!(feeds[1].0, Some(40));
    for k in 0..3 {
        assert!((feeds[1].1[k] - 254.0).abs() < 1e-9);
    }
    assert!((feeds[1].2 - 508.0).abs() < 1e-9, "F20 in/min = 508 mm/min");
}

#[test]
fn s4_6_diameter_programming() {
    // Radius values (X, Z) of spec §20.
    let mvs = moves(&run_with(
        &fixture("s4_6-g10-diameter-arc-example-4_11.nc"),
        ControlData::default(),
    ));
    let xz = |m: &Move| [m.1[0], m.1[2]];
    let want = [
        (80, [30.0, -10.0]),
        (90, [30.0, -30.0]),
        (110, [60.0, -60.0]),
        (120, [60.0, -120.0]),
        (140, [70.0, 50.0]),
    ];
    for (n, w) in want {
        let m = mvs.iter().find(|m| m.0 == Some(n)).unwrap();
        assert!(
            (xz(m)[0] - w[0]).abs() < TOL && (xz(m)[1] - w[1]).abs() < TOL,
            "N{n}: {:?}",
            xz(m)
        );
    }
    let (_, _, arc) = mvs.iter().find(|m| m.0 == Some(110)).unwrap();
    let (c, _) = arc.unwrap();
    assert!(
        (c[0] - 30.0).abs() < TOL && (c[2] + 60.0).abs() < TOL,
        "centre {c:?}"
    );
    let mvs = moves(&run_with(
        &fixture("s4_6-g10-diameter-example-4_12.nc"),
        ControlData::default(),
    ));
    let want = [
        (80, [30.0, -10.0]),
        (90, [30.0, -40.0]),
        (110, [45.0, -50.0]),
        (120, [55.0, -50.0]),
        (130, [50.0, 50.0]),
    ];
    for (n, w) in want {
        let m = mvs.iter().find(|m| m.0 == Some(n)).unwrap();
        assert!(
            (xz(m)[0] - w[0]).abs() < TOL && (xz(m)[1] - w[1]).abs() < TOL,
            "N{n}: {:?}",
            xz(m)
        );
    }
    // The per-axis fragment switches modes without moving.
    let (cmds, err) = run(&fixture("s4_6-g10-per-axis-fragment.nc"), Dialect::Axioma);
    assert!(
        err.is_none() || err.as_ref().unwrap().message.contains("transverse"),
        "{err:?}"
    );
    assert!(moves(&cmds).is_empty());
}

#[test]
fn frame_errors() {
    let cases = [
        ("G73 X2 I0\n", "axioma::mirror-factor"),
        ("G173 X0 I0\n", "axioma::scale-factor"),
        ("G173 P2 X3\n", "axioma::scale-p-and-axes"),
        ("G54 P33 X0\n", "axioma::page-range"),
        ("G10 Y1\n", "axioma::g10-axis"),
        ("G10 X2\n", "axioma::g10-value"),
        ("G73 X-1 G173 P2\n", "axioma::frames-in-one-block"),
    ];
    for (block, code) in cases {
        let (_, err) = run(&format!("G17 G90 F100\n{block}M30\n"), Dialect::Axioma);
        let err = err.unwrap_or_else(|| panic!("{block}: no error"));
        assert_eq!(err.code, DiagCode::Stanok(code), "{block}: {err}");
        assert_eq!(err.span.line, 2);
    }
}

// ------------------------------------------------------------------------------------- §4.9 polar

fn path(name: &str) -> Vec<Move> {
    moves(&run_with(&fixture(name), ControlData::default()))
}

#[track_caller]
fn assert_points(mvs: &[Move], want: &[[f64; 2]]) {
    assert_eq!(mvs.len(), want.len(), "{mvs:?}");
    for (i, (m, w)) in mvs.iter().zip(want).enumerate() {
        assert!(
            (m.1[0] - w[0]).abs() < TOL && (m.1[1] - w[1]).abs() < TOL,
            "move {i}: got {:?}, want {w:?}",
            m.1
        );
    }
}

#[test]
fn s4_9_2_polar_lines() {
    assert_points(
        &path("s4_9_2-polar-example-4_21.nc"),
        &[
            [0.0, 0.0],
            [50.0, 30.0],
            [30.0, 50.0],
            [10.0, 30.0],
            [0.0, 0.0],
        ],
    );
    let p = path("s4_9_2-polar-pentagon-example-4_22.nc");
    assert_points(
        &p[1..],
        &[
            [6.1803, 19.0211],
            [-16.1803, 11.7557],
            [-16.1803, -11.7557],
            [6.1803, -19.0211],
            [20.0, 0.0],
        ],
    );
    let h = path("s4_9_2-polar-hexagon-example-4_23.nc");
    let xy: Vec<[f64; 2]> = h.iter().map(|m| [m.1[0], m.1[1]]).collect();
    for w in [
        [5.0, -34.0192],
        [-25.0, -34.0192],
        [-40.0, -60.0],
        [-25.0, -85.9808],
        [5.0, -85.9808],
        [20.0, -60.0],
    ] {
        assert!(
            xy.iter()
                .any(|p| (p[0] - w[0]).abs() < TOL && (p[1] - w[1]).abs() < TOL),
            "{w:?} in {xy:?}"
        );
    }
    assert!((h.last().unwrap().1[0]).abs() < TOL && (h.last().unwrap().1[1]).abs() < TOL);
}

#[test]
fn s4_9_3_polar_arcs() {
    let p = path("s4_9_3-polar-arc-example-4_24.nc");
    assert_points(&p, &[[60.0, 30.0], [35.0, 55.0], [0.0, 0.0]]);
    let (c, ccw) = p[1].2.unwrap();
    assert!((c[0] - 35.0).abs() < TOL && (c[1] - 30.0).abs() < TOL && ccw);
    // YZ plane: CW half circle about (Y50, Z30) from (Y20, Z30) to (Y80, Z30).
    let yz = moves(&run_with(
        &fixture("s4_9_3-polar-arc-yz-example-4_25.nc"),
        ControlData::default(),
    ));
    let arc = yz.iter().find(|m| m.2.is_some()).unwrap();
    assert!(
        (arc.1[1] - 80.0).abs() < TOL && (arc.1[2] - 30.0).abs() < TOL,
        "{:?}",
        arc.1
    );
    let (c, _) = arc.2.unwrap();
    assert!(
        (c[1] - 50.0).abs() < TOL && (c[2] - 30.0).abs() < TOL,
        "{c:?}"
    );
    let centre = path("s4_9_3-polar-arc-centre-example-4_26.nc");
    assert_points(
        &centre[1..],
        &[[38.1596, 18.7939], [51.8404, 18.7939], [38.1596, 18.7939]],
    );
    let (c, ccw) = centre[2].2.unwrap();
    assert!((c[0] - 45.0).abs() < TOL && c[1].abs() < TOL && !ccw);
    let (c, ccw) = centre[3].2.unwrap();
    assert!(
        (c[0] - 45.0).abs() < TOL && (c[1] - 37.5877).abs() < TOL && ccw,
        "{c:?}"
    );
}

#[test]
fn s4_9_4_absolute_and_incremental_polar_programs_agree() {
    let fan = [
        [100.0, 0.0],
        [86.6025, 50.0],
        [43.3013, 25.0],
        [25.0, 43.3013],
        [50.0, 86.6025],
        [0.0, 100.0],
        [0.0, 0.0],
    ];
    let a = path("s4_9_4-polar-absolute-fan-example-4_27.nc");
    let i = path("s4_9_4-polar-incremental-fan-example-4_28.nc");
    assert_points(&a[1..], &fan);
    assert_points(&i[1..], &fan);
    let keyhole = [
        [19.4404, 41.6902],
        [5.3831, 30.5290],
        [2.7784, 15.7569],
        [6.7619, 14.5009],
        [4.2262, 9.0631],
        [-4.2262, 9.0631],
        [-2.7784, 15.7569],
        [-5.3831, 30.5290],
        [-13.1012, 28.0955],
        [-19.4404, 41.6902],
        [19.4404, 41.6902],
    ];
    let ka = path("s4_9_4-polar-absolute-keyhole-example-4_29.nc");
    let ki = path("s4_9_4-polar-incremental-keyhole-example-4_30.nc");
    assert_points(&ka, &keyhole);
    assert_points(&ki, &keyhole);
    // P5 → P6 is the 310° clockwise arc through (0, −10): its sweep, not the short way round.
    let arc = ka[5];
    let (c, ccw) = arc.2.unwrap();
    assert!(!ccw && c[0].abs() < TOL && c[1].abs() < TOL);
    let h = stanok_geom::Helix {
        start: [4.2262, 9.0631, 0.0],
        end: arc.1,
        centre: c,
        axis: [0.0, 0.0, -1.0],
        turns: 1,
    };
    assert!(
        (h.sweep().to_degrees() - 310.0).abs() < 0.01,
        "{}",
        h.sweep().to_degrees()
    );
}

#[test]
fn s3_1_mixed_interdependent_coordinates_is_error_653() {
    // The "biped" configuration: X/Y are produced by V/W. Its kinematics is not supported (spec
    // §7.1); the error the manual states for mixing them is.
    let mut opts = InterpOptions::new(Dialect::Axioma);
    let mut xy = [false; 9];
    (xy[0], xy[1]) = (true, true);
    let mut vw = [false; 9];
    (vw[7], vw[8]) = (true, true);
    opts.coupled_coordinates = Some((xy, vw));
    let mut cmds = Vec::new();
    let mut error = None;
    for item in Interpreter::from_text(
        &fixture("s3_1-mixed-kinematic-coordinates-error-653.nc"),
        opts,
    ) {
        match item {
            Ok(c) => cmds.push(c),
            Err(d) => error = Some(d),
        }
    }
    let d = error.expect("N30 mixes X and V");
    assert_eq!(d.code, DiagCode::Manual(653));
    let n30 = fixture("s3_1-mixed-kinematic-coordinates-error-653.nc")
        .lines()
        .position(|l| l.starts_with("N30"))
        .unwrap() as u32
        + 1;
    assert_eq!(d.span.line, n30);
    // N10 and N20 ran.
    assert_eq!(
        cmds.iter().filter(|c| c.value.motion().is_some()).count(),
        2
    );
}

#[test]
fn unequal_scale_factors_use_the_larger_one_for_arcs() {
    // Spec §11.3: X×2, Y×1 about (0,0). A CCW quarter arc (0,0) → (10,10) about (10,0), r = 10:
    // the end is scaled per axis to (20,10); the radius becomes 2·10 = 20; the centre is 20 from
    // both ends, on the side of the per-axis scaled centre (20,0).
    let text =
        "G17 G90 G191 F100\nG173 X2 Y1 I0 J0\nN10 G03 X10 Y10 I10 J0\nN20 G02 X20 Y10 I5 J0\nM30\n";
    let cmds = run_with(text, ControlData::default());
    let arcs: Vec<stanok_canon::ArcMove> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(a.clone()),
            _ => None,
        })
        .collect();
    let a = arcs[0].clone();
    assert!((a.end.x - 20.0).abs() < TOL && (a.end.y - 10.0).abs() < TOL);
    let rs = (a.start.x - a.centre[0]).hypot(a.start.y - a.centre[1]);
    let re = (a.end.x - a.centre[0]).hypot(a.end.y - a.centre[1]);
    assert!(
        (rs - 20.0).abs() < 1e-9 && (re - 20.0).abs() < 1e-9,
        "{rs} {re}"
    );
    assert!(
        a.centre[1] < 0.0,
        "same side as the scaled centre (20,0): {:?}",
        a.centre
    );
    // Second arc: (10,10) → (20,10) programmed about (15,10), r = 5 → scaled ends (20,10) → (40,10),
    // radius 10: a half circle about (30,10).
    let b = arcs[1].clone();
    assert!(
        (b.centre[0] - 30.0).abs() < 1e-9 && (b.centre[1] - 10.0).abs() < 1e-9,
        "{:?}",
        b.centre
    );
}
