//! Motion, modes and coordinate systems with hand-computed numbers
//! (`docs/dialects/mazatrol-eia.md` §4–§7). The plain mill has no offsets: machine = program.

mod common;
use common::*;
use stanok_canon::{Canon, Pose};

fn arcs(r: &Run) -> Vec<stanok_canon::ArcMove> {
    r.canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(a.clone()),
            _ => None,
        })
        .collect()
}

fn err(text: &str) -> (String, String) {
    let r = run(text, &mill());
    let e = r.error.expect("an error");
    (e.code.to_string(), e.message)
}

#[test]
fn issue_22_item_12_r_is_the_radius() {
    // G02 X10 Y0 R5 from (0, 0): the half circle about (5, 0), over the top.
    let r = run("G17 G90 G00 X0 Y0\nG02 X10 Y0 R5 F100\n", &mill());
    r.ok();
    let a = &arcs(&r)[0];
    assert_eq!(a.centre, [5.0, 0.0, 0.0]);
    assert_eq!(a.axis, [0.0, 0.0, -1.0], "clockwise about +Z");
    assert_eq!(
        a.end,
        Pose {
            x: 10.0,
            ..Pose::ZERO
        }
    );
}

#[test]
fn arcs_in_the_three_forms() {
    // R < 0: the 270° arc from (0,0) to (5,5) with |R| 5: centre (5, 0) for G03 (counter-clockwise
    // the long way round: the centre is right of the chord).
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12);
    let r = run("G00 X0 Y0\nG03 X5. Y5. R-5. F100\n", &mill());
    r.ok();
    assert!(
        close(arcs(&r)[0].centre, [5.0, 0.0, 0.0]),
        "{:?}",
        arcs(&r)[0].centre
    );
    // R > 0 takes the short one: centre (0, 5).
    let r = run("G00 X0 Y0\nG03 X5. Y5. R5. F100\n", &mill());
    assert!(
        close(arcs(&r)[0].centre, [0.0, 5.0, 0.0]),
        "{:?}",
        arcs(&r)[0].centre
    );
    // I J: relative to the start in G90 and G91 alike; a full circle when start = end.
    let r = run("G00 X10. Y0\nG91 G02 X0 Y0 I-10. J0 F100\n", &mill());
    r.ok();
    let a = &arcs(&r)[0];
    assert_eq!(a.centre, [0.0, 0.0, 0.0]);
    assert_eq!((a.start.x, a.end.x), (10.0, 10.0));
    // A helix: Z moves with the angle.
    let r = run("G00 X10. Y0 Z0\nG03 X-10. Y0 Z-5. I-10. F100\n", &mill());
    r.ok();
    assert_eq!(arcs(&r)[0].end.z, -5.0);
    // G18: the centre in Z and X (I, K).
    let r = run("G18 G00 X0 Z0\nG02 X10. Z10. I10. K0 F100\n", &mill());
    r.ok();
    let a = &arcs(&r)[0];
    assert_eq!(a.centre, [10.0, 0.0, 0.0]);
    assert_eq!(a.axis, [0.0, -1.0, 0.0], "G02 in G18: clockwise about +Y");
}

#[test]
fn arc_refusals_name_the_numbers() {
    let (c, m) = err("G00 X0 Y0\nG02 X10.2 Y0 I5. J0 F100\n");
    assert_eq!(c, "mazatrol::arc-radius");
    assert_eq!(
        m,
        "start radius 5.0000 and end radius 5.2000 differ by more than the arc tolerance 0.0100"
    );
    let (c, m) = err("G00 X0 Y0\nG02 X20. Y0 R5. F100\n");
    assert_eq!(c, "mazatrol::arc-radius");
    assert_eq!(
        m,
        "the end point is 20.0000 mm from the start, more than the diameter 10.0000 of R5"
    );
    let (_, m) = err("G00 X0 Y0\nG02 X0 Y0 R5. F100\n");
    assert_eq!(m, "R cannot describe a full circle: use I J K");
}

#[test]
fn spiral_g02_1() {
    // From (10, 0) about (0, 0) to (-20, 0): radius 10 → 20 over a half turn, plus one turn (L1).
    let r = run("G00 X10. Y0\nG03.1 X-20. Y0 I-10. J0 L1 F100\n", &mill());
    r.ok();
    let a = &arcs(&r)[0];
    assert_eq!(a.centre, [0.0, 0.0, 0.0]);
    assert_eq!(a.turns, 2);
    assert_eq!(a.end.x, -20.0);
}

#[test]
fn dwell_in_its_three_forms() {
    let dwells = |text: &str| -> Vec<f64> {
        run(text, &mill())
            .canon
            .iter()
            .filter_map(|c| match c.value {
                Canon::Dwell { seconds } => Some(seconds),
                _ => None,
            })
            .collect()
    };
    assert_eq!(dwells("G04 X1.5\nG04 P2500\nG04 X2\n"), vec![1.5, 2.5, 2.0]);
    let mut m = mill();
    m.params.decimal_point_type = 1;
    let r = run("G04 X1500\nG04 X1.5\n", &m);
    let d: Vec<f64> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::Dwell { seconds } => Some(seconds),
            _ => None,
        })
        .collect();
    assert_eq!(d, vec![1.5, 1.5]);
    assert_eq!(err("G04 X1. P100\n").0, "mazatrol::repeated-word");
}

#[test]
fn decimal_point_types_and_inches() {
    let mut m = mill();
    m.params.decimal_point_type = 1;
    let r = run("G00 X10 Y10. Z-5\n", &m);
    r.ok();
    let e = r.ends()[0];
    assert!((e.x - 0.01).abs() < 1e-12 && e.y == 10.0 && (e.z + 0.005).abs() < 1e-12);
    // Inch: 1 in = 25.4 mm; type 1 without a point: 0.0001 in.
    let r = run("G20\nG00 X1. Y10000\n", &m);
    r.ok();
    let e = r.ends()[0];
    assert!(
        (e.x - 25.4).abs() < 1e-9 && (e.y - 25.4).abs() < 1e-9,
        "{e:?}"
    );
    assert_eq!(err("G20 G00 X1.\n").0, "mazatrol::units-not-alone");
}

#[test]
fn absolute_and_incremental() {
    let r = run("G90 G00 X10. Y5.\nG91 X10. Y-5.\nG90 X1.\n", &mill());
    let e = r.ends();
    assert_eq!((e[1].x, e[1].y), (20.0, 0.0));
    assert_eq!(e[2].x, 1.0);
}

#[test]
fn work_offsets_local_and_g92() {
    let m = mazak_m();
    // G54 = (100, 50, -200): X0 Y0 Z0 is machine (100, 50, -200).
    let r = run("G00 X0 Y0 Z0\nG52 X10.\nX0\nG52 X0\nG92 X5.\nX5.\n", &m);
    r.ok();
    let e = r.ends();
    assert_eq!((e[0].x, e[0].y, e[0].z), (100.0, 50.0, -200.0));
    assert_eq!(e[1].x, 110.0, "G52 X10 shifts the origin");
    // G52 X0 cancels (the tool stays at machine 110, now X10); G92 X5 makes that point X5, so
    // X5 is machine 110.
    assert_eq!(e[2].x, 110.0);
}

#[test]
fn g10_sets_offsets_and_tools() {
    let m = mazak_m();
    let r = run(
        "G10 L2 P1 X10. Y20. Z30.\nG00 X0 Y0 Z0\nG91 G10 L2 P1 X1.\nG90 X0\nG10 L20 P3 X-5.\nG54.1 P3\nX0\n",
        &m,
    );
    r.ok();
    let e = r.ends();
    assert_eq!((e[0].x, e[0].y, e[0].z), (10.0, 20.0, 30.0));
    assert_eq!(e[1].x, 11.0, "G91 adds to the offset");
    assert_eq!(e[2].x, -5.0, "G54.1 P3");
    // L10 / L12: tool geometry; G43 H2 then uses the new length.
    let r = run("G10 L10 P2 R50.\nG00 Z0\nG43 H2 Z0\n", &m);
    r.ok();
    assert_eq!(r.ends().last().unwrap().z, -200.0 + 50.0);
    assert!(run("G10 L2 P7 X1.\n", &m).error.is_some());
    assert_eq!(
        run("G10 L50 P1\n", &m).error.unwrap().code.to_string(),
        "mazatrol::not-simulated"
    );
}

#[test]
fn scaling_mirror_and_rotation() {
    // G51 P2 about (0, 0): X10 → 20.
    let r = run("G51 X0 Y0 P2.\nG00 X10. Y5.\nG50\nX10.\n", &mill());
    r.ok();
    let e = r.ends();
    assert_eq!((e[0].x, e[0].y), (20.0, 10.0));
    assert_eq!(e[1].x, 10.0);
    // G51.1 X0: X mirrored, and a G02 becomes clockwise → counter-clockwise.
    let r = run("G51.1 X0\nG00 X10. Y0\nG02 X10. Y0 I-10. F100\n", &mill());
    r.ok();
    assert_eq!(r.ends()[0].x, -10.0);
    assert_eq!(arcs(&r)[0].axis, [0.0, 0.0, 1.0]);
    // G68 R90 about (0, 0): X10 → Y10.
    let r = run("G68 X0 Y0 R90.\nG00 X10. Y0\n", &mill());
    r.ok();
    let e = r.ends()[0];
    assert!(e.x.abs() < 1e-12 && (e.y - 10.0).abs() < 1e-12, "{e:?}");
    // G68.5 about +Z by 90 through the origin: the same.
    let r = run("G68.5 X0 Y0 Z0 I0 J0 K1 R90.\nG00 X10. Y0\n", &mill());
    r.ok();
    let e = r.ends()[0];
    assert!(e.x.abs() < 1e-12 && (e.y - 10.0).abs() < 1e-12, "{e:?}");
}

#[test]
fn reference_points() {
    let m = mazak_m();
    // G28 via the intermediate point: work Z0 (machine -200), then machine Z0; G29 back.
    let r = run("G00 X0 Y0 Z-10.\nG28 Z0\nG29 Z5.\nG30 P3 Z0\n", &m);
    r.ok();
    let e = r.ends();
    assert_eq!(e[1].z, -200.0);
    assert_eq!(e[2].z, 0.0);
    assert_eq!(e[3].z, -200.0, "G29 via the intermediate point");
    assert_eq!(e[4].z, -195.0);
    assert_eq!(
        e.last().unwrap().z,
        20.0,
        "reference point 3 at machine Z 20"
    );
    let r = run("G00 Z0\nG27 Z0\n", &m);
    let e = r.error.unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::reference-check");
    assert_eq!(e.message, "G27: Z is 200.0000 mm from the reference point");
}

#[test]
fn g53_and_g60() {
    let m = mazak_m();
    let r = run("G53 X1. Z-2.\nG60 X10. Y10.\n", &m);
    r.ok();
    let e = r.ends();
    assert_eq!((e[0].x, e[0].z), (1.0, -2.0));
    // G60: to 1 mm before the end on each named axis, then to the end.
    assert_eq!((e[1].x, e[1].y), (109.0, 59.0));
    assert_eq!((e[2].x, e[2].y), (110.0, 60.0));
}

#[test]
fn skip_stops_at_the_probe_surface() {
    let mut m = mill();
    m.opts
        .control
        .probe_surfaces
        .push(stanok_canon::setup::ProbeSurface {
            axis: 2,
            at_or_below: true,
            value: -3.2,
        });
    let r = run("G00 Z10.\nG31 Z-10. F100\n#100 = #5063\nG01 X1.\n", &m);
    r.ok();
    let probe = r
        .canon
        .iter()
        .find_map(|c| match &c.value {
            Canon::StraightProbe { contact, .. } => Some(contact.as_deref().copied()),
            _ => None,
        })
        .unwrap();
    assert!((probe.unwrap().z + 3.2).abs() < 1e-12);
    // The next move starts at the contact.
    assert!((r.ends().last().unwrap().z + 3.2).abs() < 1e-12);
}

#[test]
fn the_stroke_check_refuses_a_move_into_the_area() {
    // From (0, 0) to (30, 20): y = 2x/3 is inside 10 < y < 20 for 15 < x < 20.
    let r = run(
        "G22 X10. Y10. Z-10. I20. J20. K10.\nG00 X0 Y0 Z0\nX30. Y20.\n",
        &mill(),
    );
    let e = r.error.unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::stroke-check");
    assert_eq!(e.span.line, 3);
    // G23: off.
    run(
        "G22 X10. Y10. Z-10. I20. J20. K10.\nG23\nG00 X30. Y20.\n",
        &mill(),
    )
    .ok();
}

#[test]
fn threads() {
    let m = mazak_t();
    let r = run("G97 S500 M03\nG00 X20. Z5.\nG32 Z-10. F1.5\n", &m);
    r.ok();
    let sync: Vec<f64> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::StartSpindleSync { pitch, .. } => Some(pitch),
            _ => None,
        })
        .collect();
    assert_eq!(sync, vec![1.5]);
    // G34: F2 K0.5 over 10 mm: pieces of lead 2.25 2.75 3.25 3.75.
    let r = run("G97 S500 M03\nG00 X20. Z0\nG34 Z-10. F2. K0.5\n", &m);
    r.ok();
    let sync: Vec<f64> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::StartSpindleSync { pitch, .. } => Some(pitch),
            _ => None,
        })
        .collect();
    assert_eq!(sync, vec![2.25, 2.75, 3.25, 3.75]);
    assert_eq!(
        run("G32 Z-10. F1.5\n", &m).error.unwrap().code.to_string(),
        "mazatrol::thread"
    );
}

#[test]
fn modal_conflicts_unknown_codes_and_unused_words() {
    let (c, m) = err("G01 G02 X1.\n");
    assert_eq!(c, "mazatrol::modal-conflict");
    assert_eq!(
        m,
        "G01 and G02 are both group 01 motion codes: one per block"
    );
    let (c, m) = err("G123\n");
    assert_eq!(c, "mazatrol::unknown-code");
    assert_eq!(m, "G123 is not a G code of the M-series (table 12.2)");
    let (c, m) = err("G06.2 X1.\n");
    assert_eq!(c, "mazatrol::not-simulated");
    assert_eq!(m, "G06.2 (NURBS interpolation) is not simulated by Stanok");
    let (c, _) = err("G00 X1. X2.\n");
    assert_eq!(c, "mazatrol::repeated-word");
    let (c, m) = err("G00 X1. Q2.\n");
    assert_eq!(c, "interp::unused-word");
    assert_eq!(m, "Q is not used by any code of this block");
    let (c, _) = err("M03 M08 M07 M09\n");
    assert_eq!(c, "mazatrol::too-many-m-codes");
}

#[test]
fn machine_m_codes_pass_with_one_warning() {
    let r = run("M50\nM50\nM51\n", &mill());
    r.ok();
    let aux: Vec<u32> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::AuxiliaryFunction { number, .. } => Some(number),
            _ => None,
        })
        .collect();
    assert_eq!(aux, vec![50, 50, 51]);
    let w: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.code.to_string() == "mazatrol::machine-m-code")
        .collect();
    assert_eq!(w.len(), 2);
}
