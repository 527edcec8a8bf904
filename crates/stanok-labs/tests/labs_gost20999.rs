//! The GOST-20999 control of the lab collection (spec §4): every `corpus/labs/gost20999-*`
//! fixture with the numbers its header states. Fragments start where the header's derivation puts
//! them (P0), given as the initial position.

mod labs_support;

use labs_support::*;
use stanok_canon::{Canon, Plane};
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn gost(name: &str, p0: [f64; 3]) -> Run {
    run(name, Dialect::Gost20999, |o| {
        o.initial_position = at(p0[0], p0[1], p0[2])
    })
}

fn gost_text(text: &str, p0: [f64; 3]) -> Run {
    run_text(text, Dialect::Gost20999, |o| {
        o.initial_position = at(p0[0], p0[1], p0[2])
    })
}

fn arc_of(r: &Run, n: u32) -> stanok_canon::ArcMove {
    match r.motions_of(n).first() {
        Some(Canon::ArcFeed(a)) => *a,
        other => panic!("N{n}: arc expected, got {other:?}"),
    }
}

#[test]
fn linear_g1_absolute_and_incremental_reach_p1() {
    for name in [
        "gost20999-linear-g1-absolute.nc",
        "gost20999-linear-g1-incremental.nc",
    ] {
        let r = gost(name, [72.4, 11.274, 0.0]);
        assert!(r.errors.is_empty(), "{name}: {:?}", r.errors);
        assert!(matches!(r.motions_of(25)[0], Canon::StraightFeed(_)));
        xy(r.end_of(25), 12.146, 90.7, 1e-9, name);
    }
}

#[test]
fn arc_ijk_fixtures_are_refused_for_their_radius_mismatch() {
    for name in [
        "gost20999-arc-ijk-absolute.nc",
        "gost20999-arc-ijk-incremental.nc",
    ] {
        // Strict word rules (J20 = 0.020 mm): still no arc.
        let r = gost(name, [31.278, 20.0, 0.0]);
        assert_eq!(r.error_codes(), ["lab::arc-radius"], "{name}");
        assert!(r.moves().is_empty(), "{name}: nothing of the block runs");
    }
    // With the evident millimetres the document's numbers: start radius 34.999, end 43.582.
    let r = gost_text(
        "N31 G2 G17 G90 X40. Y78.722 I28.722 J20.\n",
        [31.278, 20.0, 0.0],
    );
    assert_eq!(r.error_codes(), ["lab::arc-radius"]);
    let note = &r.errors[0].notes[0];
    assert!(
        note.contains("34.9993") && note.contains("43.5820"),
        "{note}"
    );
    // Printed Y68.722 instead would be a consistent 90° clockwise arc about (60, 40).
    let r = gost_text(
        "N31 G2 G17 G90 X40. Y68.722 I28.722 J20.\n",
        [31.278, 20.0, 0.0],
    );
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let a = arc_of(&r, 31);
    near(a.centre[0], 60.0, TOL, "cx");
    near(a.centre[1], 40.0, TOL, "cy");
    assert_eq!(a.axis, [0.0, 0.0, -1.0]);
}

#[test]
fn full_circle_absolute_strict_reading_is_r80_about_130_60_06() {
    let r = gost("gost20999-full-circle-absolute.nc", [50.0, 60.0, 0.0]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let a = arc_of(&r, 51);
    xy(a.end, 50.0, 60.0, TOL, "end = start");
    near(a.centre[0], 130.0, TOL, "cx");
    near(a.centre[1], 60.06, TOL, "cy (J60 = 0.060 mm)");
    near(
        (a.start.x - a.centre[0]).hypot(a.start.y - a.centre[1]),
        80.0,
        1e-4,
        "R",
    );
    assert_eq!(a.axis, [0.0, 0.0, -1.0], "G2 clockwise");
    // The intended millimetres: centre (130, 120), R 100.
    let r = gost_text("N51 G2 G90 X50. Y60. I80. J60.\n", [50.0, 60.0, 0.0]);
    let a = arc_of(&r, 51);
    near(a.centre[1], 120.0, TOL, "cy");
    near(
        (a.start.x - a.centre[0]).hypot(a.start.y - a.centre[1]),
        100.0,
        TOL,
        "R",
    );
}

#[test]
fn full_circle_incremental_without_end_words() {
    let r = gost("gost20999-full-circle-incremental.nc", [10.0, 20.0, 0.0]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let a = arc_of(&r, 51);
    xy(a.end, 10.0, 20.0, TOL, "end = start");
    // I30 without a point = 0.030 mm (strict rule).
    near(a.centre[0], 10.03, TOL, "cx");
    near(a.centre[1], 20.0, TOL, "cy");
}

#[test]
fn full_circle_with_r_is_error_28() {
    let r = gost_text("N1 G2 G90 X10. Y10. R5.\n", [10.0, 10.0, 0.0]);
    assert_eq!(r.error_codes(), ["E28"]);
}

#[test]
fn arc_by_radius_90_ccw_then_270_cw() {
    for name in [
        "gost20999-arc-radius-absolute.nc",
        "gost20999-arc-radius-incremental.nc",
    ] {
        let r = gost(name, [210.0, 130.0, 0.0]);
        assert!(r.errors.is_empty(), "{name}: {:?}", r.errors);
        let a = arc_of(&r, 20);
        xy(a.end, 170.0, 90.0, 1e-9, "N20 end");
        near(a.centre[0], 210.0, 1e-9, "N20 cx");
        near(a.centre[1], 90.0, 1e-9, "N20 cy");
        assert_eq!(a.axis, [0.0, 0.0, 1.0], "G3");
        let b = arc_of(&r, 21);
        xy(b.end, 120.0, 140.0, 1e-9, "N21 end");
        near(b.centre[0], 120.0, 1e-9, "N21 cx");
        near(b.centre[1], 90.0, 1e-9, "N21 cy");
        assert_eq!(b.axis, [0.0, 0.0, -1.0], "G2");
        // 270° clockwise: from (170, 90) at 0° about (120, 90) down and round to 90°.
        let s = (b.start.y - b.centre[1]).atan2(b.start.x - b.centre[0]);
        let e = (b.end.y - b.centre[1]).atan2(b.end.x - b.centre[0]);
        let cw = (s - e).rem_euclid(std::f64::consts::TAU).to_degrees();
        near(cw, 270.0, 1e-9, "N21 sweep");
    }
}

#[test]
fn helix_two_and_a_half_turns_with_the_document_feed_split() {
    let r = gost("gost20999-helical.nc", [100.0, 50.0, 0.0]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let a = arc_of(&r, 17);
    assert_eq!(a.end, at(70.0, 50.0, 25.0));
    near(a.centre[0], 85.0, TOL, "cx");
    near(a.centre[1], 50.0, TOL, "cy");
    assert_eq!(a.turns, 3, "half a turn + 2 full turns (LinuxCNC's count)");
    assert_eq!(a.axis, [0.0, 0.0, 1.0]);
    assert_eq!(a.plane, Plane::XY);
    // F100 along the arc (235.619 mm): Z runs at F_L = 10.61 mm/min.
    let planar = 2.5 * std::f64::consts::TAU * 15.0;
    near(planar, 235.619, 1e-3, "arc length");
    let helix = planar.hypot(25.0);
    near(a.feed * planar / helix, 100.0, 1e-9, "feed along the arc");
    near(a.feed * 25.0 / helix, 10.61, 5e-3, "Z feed F_L");
}

#[test]
fn helix_whose_pitch_misses_the_end_is_refused() {
    let r = gost_text("N1 G91 G3 X-30. R15. K10. Z27. F100\n", [0.0; 3]);
    assert_eq!(r.error_codes(), ["lab::helix-pitch"]);
}

#[test]
fn modal_feed_holds_over_the_next_block() {
    let r = gost("gost20999-feed-modal.nc", [1.0, 2.0, 3.0]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    for (n, end) in [(43, at(6.0, 2.0, 23.0)), (44, at(7.5, 3.2, 23.0))] {
        let Canon::StraightFeed(m) = r.motions_of(n)[0] else {
            panic!("feed move")
        };
        assert_eq!(m.end, end, "N{n}");
        near(m.feed, 80.0, TOL, "F80 mm/min");
    }
}

#[test]
fn g28_homes_the_named_axes_to_parameters_163_166() {
    let r = run(
        "gost20999-reference-return-g28.nc",
        Dialect::Gost20999,
        |o| {
            o.initial_position = at(40.0, -30.0, 60.0);
            o.labs.home = [-5.0, 7.0, -9.0, 0.0];
        },
    );
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert!(matches!(r.motions_of(15)[0], Canon::StraightTraverse(_)));
    // X and Z searched in −, Y in +: from (40, −30, 60) that is where the home lies.
    assert_eq!(r.end_of(15), at(-5.0, 7.0, -9.0));
}

#[test]
fn work_systems_g54_g55_g92_g53_give_a_b_c_d() {
    let r = run(
        "gost20999-work-coordinate-systems.nc",
        Dialect::Gost20999,
        |o| o.labs.work_offsets = [[30.0, 30.0, 0.0, 0.0], [10.0, 20.0, 0.0, 0.0]],
    );
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    xy(r.end_of(20), 80.0, 60.0, TOL, "A");
    assert!(r.motions_of(21).is_empty(), "G92 does not move");
    xy(r.end_of(22), 60.0, 40.0, TOL, "B");
    xy(r.end_of(23), 50.0, 50.0, TOL, "C");
    xy(r.end_of(24), 20.0, 30.0, TOL, "D");
    assert_eq!(r.state.work_system, 2, "G55 stays selected");
    assert_eq!(r.state.g92_shift[..2], [30.0, 20.0]);
}

#[test]
fn g43_g44_in_one_block_move_x_15_9_and_z_minus_19_3() {
    let r = run(
        "gost20999-tool-length-g43-g44.nc",
        Dialect::Gost20999,
        |o| {
            o.labs.correctors.insert(1, 0.5);
            o.labs.correctors.insert(2, -1.2);
        },
    );
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let e = r.end_of(15);
    near(e.x, 15.9, 1e-12, "X");
    near(e.z, -19.3, 1e-12, "Z");
}

#[test]
fn table_8_per_axis_binding() {
    let r = run(
        "gost20999-tool-length-table-8.nc",
        Dialect::Gost20999,
        |o| {
            o.initial_position = at(3.0, 4.0, 0.0);
            for (d, v) in [(1, 0.1), (2, 0.2), (12, 0.3), (15, 0.0)] {
                o.labs.correctors.insert(d, v);
            }
        },
    );
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    for (n, x, y) in [
        (2, 1.1, 0.2),
        (3, 0.7, 0.9),
        (4, 0.6, 1.5),
        (5, -0.19, 3.0),
        (6, 2.0, 8.0),
    ] {
        // N1 G92 X0 Y0 made the start (3, 4) the origin of the table's coordinates.
        let e = r.end_of(n);
        xy(at(e.x - 3.0, e.y - 4.0, 0.0), x, y, 1e-12, &format!("N{n}"));
    }
    assert_eq!(r.state.axis_correction[0], (0, None), "G49 cleared X");
}

#[test]
fn g49_with_a_corrector_is_refused() {
    let r = gost_text("N1 G1 G49 D2 X1.\n", [0.0; 3]);
    assert_eq!(r.error_codes(), ["lab::g49-with-correction"]);
}

#[test]
fn contour_break_program_with_a_zero_radius_runs_the_programmed_rhombus() {
    let p0 = [200.0, 100.0, 50.0];
    let r = gost("gost20999-cutter-comp-contour-break.nc", p0);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let s = (p0[0] - 42.0, p0[1]);
    xy(r.end_of(1), s.0, s.1, TOL, "N1 at S");
    near(r.end_of(2).z, p0[2] - 45.0, TOL, "N2 break: Z down");
    xy(r.end_of(3), s.0 - 126.0, s.1 - 73.67, TOL, "N3");
    xy(r.end_of(4), s.0 - 252.0, s.1, TOL, "N4");
    xy(r.end_of(5), s.0 - 126.0, s.1 + 73.67, TOL, "N5");
    xy(r.end_of(6), s.0, s.1, TOL, "N6");
    // N8: G40 exit back to P0: net displacement 0 on all axes.
    let end = r.end_of(8);
    xy(end, p0[0], p0[1], 1e-9, "N8 back at P0");
    near(end.z, p0[2], 1e-9, "N8 Z");
    let Canon::StraightFeed(m) = r.motions_of(3)[0] else {
        panic!()
    };
    near(m.feed, 300.0, TOL, "F300");
    assert!(r.commands_of(8).contains(&&Canon::ProgramEnd));
}

fn comp_run(radius: f64) -> Run {
    run(
        "gost20999-cutter-comp-contour-break.nc",
        Dialect::Gost20999,
        |o| {
            o.initial_position = at(200.0, 100.0, 50.0);
            o.labs.correctors.insert(30, radius);
        },
    )
}

fn continuous(r: &Run) {
    let mut last = None;
    for c in &r.commands {
        if let Some(m) = c.value.motion() {
            if let Some(p) = last {
                assert_eq!(m.start(), p, "continuous at {:?}", c.block_number);
            }
            last = Some(m.end());
        }
    }
}

#[test]
fn contour_break_program_offsets_the_rhombus_by_r() {
    let s = (158.0, 100.0);
    // Side tangents and left normals (G41: the offset points left of the motion).
    let (a, b): (f64, f64) = (126.0, 73.67);
    let l = a.hypot(b);
    let (ca, sb) = (a / l, b / l); // 0.8633, 0.5047
    for radius in [1.0, 2.0] {
        let r = comp_run(radius);
        assert!(r.errors.is_empty(), "{:?}", r.errors);
        continuous(&r);
        // N1: internal start-up, straight from P0 to S3 = S + R (0.5047, −0.8633).
        let n1 = r.motions_of(1);
        assert_eq!(n1.len(), 1);
        let e = r.end_of(1);
        xy(
            e,
            s.0 + radius * 0.5047,
            s.1 - radius * 0.8633,
            1e-4 * radius,
            "N1 S3",
        );
        // N2: the break runs at S3.
        let e2 = r.end_of(2);
        xy(e2, e.x, e.y, TOL, "N2 at S3");
        near(e2.z, 5.0, TOL, "N2 Z");
        // N3 ends at its S1 = P3 + R (0.5047, −0.8633); N4 starts with the inserted S1 → S2 → S3.
        let p3 = (s.0 - a, s.1 - b);
        let e3 = r.end_of(3);
        xy(e3, p3.0 + radius * sb, p3.1 - radius * ca, 1e-9, "N3 S1");
        let n4 = r.motions_of(4);
        assert_eq!(n4.len(), 3, "S1→S2, S2→S3, then N4");
        let s2 = n4[0].motion().unwrap().end();
        near(
            (s2.x - e3.x).hypot(s2.y - e3.y),
            radius * (60.63f64 / 2.0).to_radians().tan(),
            1e-3,
            "|S1S2| at 119.4°",
        );
        let s3 = n4[1].motion().unwrap().end();
        xy(s3, p3.0 - radius * sb, p3.1 - radius * ca, 1e-9, "N4 S3");
        // Left vertex, 60.6° on the part side: |S1S2| = 1.710 R ≤ R + 1 mm only for R = 1.
        let n5 = r.motions_of(5);
        if radius == 1.0 {
            assert_eq!(n5.len(), 3, "S1 → S2 → S3");
            let (p, q) = (n5[0].motion().unwrap(), n5[0].motion().unwrap().end());
            near(
                (q.x - p.start().x).hypot(q.y - p.start().y),
                1.710,
                1e-3,
                "|S1S2|",
            );
        } else {
            assert_eq!(n5.len(), 4, "S1 → S4 → S5 → S3");
            let p = n5[0].motion().unwrap();
            near(
                (p.end().x - p.start().x).hypot(p.end().y - p.start().y),
                radius,
                1e-9,
                "|S1S4| = R",
            );
        }
        // N6 ends at its own S1 (internal corner with the exit); the break N7 runs there.
        let e6 = r.end_of(6);
        xy(e6, s.0 + radius * sb, s.1 + radius * ca, 1e-9, "N6 S1");
        xy(r.end_of(7), e6.x, e6.y, TOL, "N7 at S1");
        // N8: G40 exit straight from S1 to P0.
        assert_eq!(r.motions_of(8).len(), 1);
        let e8 = r.end_of(8);
        xy(e8, 200.0, 100.0, 1e-9, "N8 at P0");
        near(e8.z, 50.0, 1e-9, "N8 Z");
        // The tool stays outside the rhombus: every corner point is at least R from its vertex.
        for (_, p) in r.moves() {
            for v in [(s.0, s.1), p3, (s.0 - 2.0 * a, s.1), (s.0 - a, s.1 + b)] {
                assert!((p.x - v.0).hypot(p.y - v.1) >= radius - 1e-9);
            }
        }
    }
}

#[test]
fn error_19_for_a_short_block_between_internal_corners() {
    // A notch narrower than the tool: the 1 mm bottom between two internal corners with R = 2.
    let text = "N1 G1 G90 G17 G41 D1 X10. Y0 F100\nN2 X20.\nN3 Y-5.\nN4 X21.\nN5 Y0\nN6 X30.\nN7 G40 X30. Y10.\n";
    let r = run_text(text, Dialect::Gost20999, |o| {
        o.labs.correctors.insert(1, 2.0);
    });
    assert_eq!(r.error_codes(), ["E19"]);
}

#[test]
fn tangent_arc_under_compensation_is_offset_by_r() {
    // Outer contour, counter-clockwise, G42 (tool right = outside): line, quarter arc R5, line.
    let text = "N1 G1 G90 G17 G42 D1 X0 Y0 F100\nN2 X10.\nN3 G3 X15. Y5. R5.\nN4 G1 Y10.\nN5 G40 X20. Y20.\n";
    let r = run_text(text, Dialect::Gost20999, |o| {
        o.initial_position = at(-10.0, -10.0, 0.0);
        o.labs.correctors.insert(1, 1.0);
    });
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    continuous(&r);
    let a = arc_of(&r, 3);
    // Tangent junctions are smooth: no inserted moves; the arc runs on radius 5 + 1.
    assert_eq!(r.motions_of(3).len(), 1);
    xy(a.start, 10.0, -1.0, 1e-9, "arc start");
    xy(a.end, 16.0, 5.0, 1e-9, "arc end");
    near(a.centre[0], 10.0, TOL, "centre x");
    near(a.centre[1], 5.0, TOL, "centre y");
    // N4 ends at its S1 (the exit turns 26.57° inwards: an internal corner).
    xy(r.end_of(4), 16.0, 10.0, 1e-9, "N4 at its S1");
    xy(r.end_of(5), 20.0, 20.0, TOL, "exit at the programmed point");
    // The same contour with G41 puts the tool inside: the concave offset of R5 with R = 6 is error 19.
    let r = run_text(&text.replace("G42 D1", "G41 D1"), Dialect::Gost20999, |o| {
        o.initial_position = at(-10.0, -10.0, 0.0);
        o.labs.correctors.insert(1, 6.0);
    });
    assert_eq!(r.error_codes(), ["E19"]);
}

#[test]
fn arcs_in_compensation_start_up_or_exit_are_error_35() {
    let r = gost_text("N1 G2 G91 G17 G41 D1 X10. Y10. R10. F100\n", [0.0; 3]);
    assert_eq!(r.error_codes(), ["E35"]);
    let r = gost_text(
        "N1 G1 G91 G41 D1 X10. F100\nN2 G40 G3 X10. Y10. R10.\n",
        [0.0; 3],
    );
    assert_eq!(r.error_codes(), ["E35"]);
    assert_eq!(r.errors[0].span.line, 2);
}

/// The start-up block's requirements (§4.9 [doc]): D with the radius corrector and a move in the
/// plane; the G40 block holds a coordinate of the plane. Each broken requirement stops the run at
/// its block with nothing of it executed; the corrected block runs.
#[test]
fn start_up_and_exit_blocks_need_d_and_a_move_in_the_plane() {
    let bad = [
        ("N1 G1 G91 G17 G41 X10. F100\n", "lab::startup-without-d", 1),
        (
            "N1 G1 G91 G17 G41 D1 Z10. F100\n",
            "lab::startup-without-plane-motion",
            1,
        ),
        (
            "N1 G1 G91 G17 G41 D1 F100\n",
            "lab::startup-without-plane-motion",
            1,
        ),
        (
            "N1 G1 G91 G17 G41 D1 X10. F100\nN2 X10.\nN3 G40 Z5.\n",
            "lab::g40-without-plane-coordinate",
            3,
        ),
        (
            "N1 G1 G91 G18 G42 D1 X10. Z2. F100\nN2 Z10.\nN3 G40 Y5.\n",
            "lab::g40-without-plane-coordinate",
            3,
        ),
    ];
    for (text, code, line) in bad {
        let r = gost_text(text, [0.0; 3]);
        assert_eq!(r.error_codes(), [code], "{text}");
        assert_eq!(r.errors[0].span.line, line, "{text}");
        assert!(
            r.moves().iter().all(|(l, _)| l.is_none_or(|l| l < line)),
            "nothing of the failing block ran: {text}"
        );
    }
    let good = [
        "N1 G1 G91 G17 G41 D1 X10. F100\nN2 X10.\nN3 G40 Y5.\n",
        "N1 G1 G91 G18 G42 D1 Z10. F100\nN2 Z10.\nN3 G40 X5. Y2.\n",
    ];
    for text in good {
        let r = gost_text(text, [0.0; 3]);
        assert!(r.errors.is_empty(), "{text}: {:?}", r.errors);
    }
}

/// The rounded rectangle of subprogram 01 run by a main program, from P0 = (0, 0).
fn rectangle(main: &str) -> Run {
    run(main, Dialect::Gost20999, |o| {
        o.subroutine_path = vec![LABS.into()];
        o.strip_fixture_comments = true;
    })
}

fn check_rectangle(r: &Run, r1: f64, r2: f64, r3: f64, feed: f64) {
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let arcs: Vec<_> = r
        .commands
        .iter()
        .filter_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(*a),
            _ => None,
        })
        .collect();
    assert_eq!(arcs.len(), 4);
    let centres: Vec<(f64, f64)> = arcs.iter().map(|a| (a.centre[0], a.centre[1])).collect();
    let expect = [(-r1, -r2), (-r1, -r2 - r3), (0.0, -r2 - r3), (0.0, -r2)];
    for (c, e) in centres.iter().zip(expect) {
        near(c.0, e.0, 1e-9, "corner centre x");
        near(c.1, e.1, 1e-9, "corner centre y");
    }
    for a in &arcs {
        assert_eq!(a.axis, [0.0, 0.0, 1.0], "counter-clockwise corners");
        near(a.feed, feed, 1e-9, "feed");
        near(
            (a.start.x - a.centre[0]).hypot(a.start.y - a.centre[1]),
            r2,
            1e-9,
            "corner R",
        );
    }
    let moves = r.moves();
    let xs: Vec<f64> = moves.iter().map(|m| m.1.x).collect();
    let ys: Vec<f64> = moves.iter().map(|m| m.1.y).collect();
    let w =
        xs.iter().cloned().fold(f64::MIN, f64::max) - xs.iter().cloned().fold(f64::MAX, f64::min);
    let h =
        ys.iter().cloned().fold(f64::MIN, f64::max) - ys.iter().cloned().fold(f64::MAX, f64::min);
    near(w, r1 + 2.0 * r2, 1e-9, "width");
    near(h, r3 + 2.0 * r2, 1e-9, "height");
    assert_eq!(moves.last().unwrap().1, at(0.0, 0.0, 0.0), "closed");
}

#[test]
fn fig47_l01_gives_55_by_30_with_r8_corners_at_f300() {
    let r = rectangle("gost20999-main-fig47-call-l01.nc");
    check_rectangle(&r, 39.0, 8.0, 14.0, 300.0);
    assert_eq!(r.state.variables.get(&1), Some(&(39.0, true)));
    assert_eq!(r.state.variables.get(&4), Some(&(300.0, false)));
}

#[test]
fn fig48_l0101_gives_20_by_17_with_r5_corners_at_f120() {
    let r = rectangle("gost20999-main-fig48-call-l0101.nc");
    check_rectangle(&r, 10.0, 5.0, 7.0, 120.0);
}

#[test]
fn call_block_with_variables_runs_subprogram_13_twice() {
    // Subprogram 13 is not in the document: not loaded, the call is refused at its L word.
    let r = gost("gost20999-subprogram-call-with-variables.nc", [0.0; 3]);
    assert_eq!(r.error_codes(), ["lab::no-subprogram"]);
    assert!(
        r.state.variables.is_empty(),
        "the failing block commits nothing"
    );
    // With a subprogram 13 after the main program: G91 modal, R12 = −15.5, R142 = 4.3, two runs.
    let text = format!(
        "{}\nL1300\nN1 G1 X1. F100\nN2 M17\n",
        fixture("gost20999-subprogram-call-with-variables.nc")
    );
    let r = gost_text(&text, [0.0; 3]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert_eq!(r.state.variables.get(&12), Some(&(-15.5, true)));
    assert_eq!(r.state.variables.get(&142), Some(&(4.3, true)));
    assert_eq!(r.moves().len(), 2);
    near(r.moves()[1].1.x, 2.0, TOL, "two incremental runs");
}

#[test]
fn l02_skeleton_called_moves_50_30_at_f40_and_returns() {
    let text = format!(
        "N1 L0201\nN2 G1 G91 X1.\n{}",
        fixture("gost20999-subprogram-l02-skeleton.nc")
    );
    let r = gost_text(&text, [0.0; 3]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let m = r.moves();
    assert_eq!(m[0].1, at(50.0, 0.0, 30.0));
    assert_eq!(m[1].1, at(51.0, 0.0, 30.0), "back in the main program");
    let Canon::StraightFeed(f) = r.motions_of(1)[0] else {
        panic!()
    };
    near(f.feed, 40.0, TOL, "F40");
}

#[test]
fn call_rules_are_enforced() {
    for (text, code) in [
        ("N1 L0200\n", "lab::call-format"),
        ("N1 L010\n", "lab::call-format"),
        ("N1 L0101 G91\n", "lab::call-not-last"),
        ("N1 X1. L0101\n", "lab::call-block"),
        ("N1 M17\n", "lab::m17-in-main"),
        ("N1 G1 X1. X2.\n", "lab::repeated-word"),
        ("N1 G4 G92 X1.\n", "lab::one-shot"),
        ("N1 G0 G1 X1.\n", "lab::g-group"),
        ("N1 G1 X1. F30000\n", "lab::feed-range"),
        ("N1 G1 X-R7\n", "lab::unset-variable"),
    ] {
        let r = gost_text(text, [0.0; 3]);
        assert_eq!(r.error_codes(), [code], "{text}");
        assert!(r.moves().is_empty(), "{text}");
    }
}

/// §4.10: the subprogram's last block holds M17 and no geometric or technological information.
/// The call stops at that block with nothing of it executed (the move before it ran).
#[test]
fn the_m17_block_holds_no_move_or_feed() {
    for (sub_end, word) in [
        ("N2 X2. M17", "X"),
        ("N2 F200 M17", "F"),
        ("N2 M17 S300", "S"),
    ] {
        let text = format!("N1 L0101\nN9 M2\nL0100\nN1 G1 X1. F100\n{sub_end}\n");
        let r = gost_text(&text, [0.0; 3]);
        assert_eq!(r.error_codes(), ["lab::m17-block"], "{text}");
        assert_eq!(r.errors[0].span.line, 5, "{text}");
        assert!(r.errors[0].message.ends_with(word), "{text}");
        assert_eq!(r.moves().len(), 1, "only N1 of the subprogram ran: {text}");
    }
    let r = gost_text("N1 L0101\nN9 M2\nL0100\nN1 G1 X1. F100\nN2 M17\n", [0.0; 3]);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
}

/// §4.3: the largest move in one block is ±9999.999 mm: an absolute end further than that from
/// the start is refused at its block (nothing of it runs); 9999.999 itself moves.
#[test]
fn a_block_moves_at_most_9999_999() {
    let r = gost_text(
        "N1 G91 G1 X9999.999 F1000\nN2 X9999.\nN3 G90 X-9999.\n",
        [0.0; 3],
    );
    assert_eq!(r.error_codes(), ["lab::move-too-long"]);
    assert_eq!(r.errors[0].span.line, 3);
    assert!(
        r.errors[0].message.contains("-29997.999"),
        "{}",
        r.errors[0]
    );
    assert_eq!(r.moves().len(), 2, "N1 and N2 ran, N3 did not");
}

#[test]
fn recursion_is_bounded() {
    let r = gost_text("N1 L0101\nL0100\nN1 L0101\nN2 M17\n", [0.0; 3]);
    assert_eq!(r.error_codes(), ["lab::nesting"]);
}

#[test]
fn decimal_point_rules() {
    // Z15. = Z15.0 = Z15000 = 15 mm; X.14 = X0.14 = X140 = 0.14 mm.
    for (text, x, z) in [
        ("N1 G1 G90 X.14 Z15. F100\n", 0.14, 15.0),
        ("N1 G1 G90 X0.14 Z15.0 F100\n", 0.14, 15.0),
        ("N1 G1 G90 X140 Z15000 F100\n", 0.14, 15.0),
    ] {
        let r = gost_text(text, [0.0; 3]);
        assert!(r.errors.is_empty(), "{text}");
        near(r.end_of(1).x, x, 1e-12, text);
        near(r.end_of(1).z, z, 1e-12, text);
    }
}

#[test]
fn subprogram_l01_rounded_rectangle_in_the_same_text_as_its_caller() {
    // The subprogram after the main program in one text (header L0100), R1..R4 of Fig. 47.
    let text = format!(
        "N20 R1#39. R2#8. R3#14. R4#300\nN21 L01\n{}",
        fixture("gost20999-subprogram-l01-rounded-rectangle.nc")
    );
    let r = gost_text(&text, [0.0; 3]);
    check_rectangle(&r, 39.0, 8.0, 14.0, 300.0);
    // Alone it is only a subprogram: no main program, nothing runs.
    let r = gost("gost20999-subprogram-l01-rounded-rectangle.nc", [0.0; 3]);
    assert!(r.errors.is_empty() && r.commands.len() == 1, "only Init");
}

#[test]
fn g20_with_a_zero_part_radius_is_error_17() {
    let r = gost_text("N1 G20 G1 X1. F100\n", [0.0; 3]);
    assert_eq!(r.error_codes(), ["E17"]);
}

#[test]
fn g9_stops_exactly_at_the_end_of_its_block_only() {
    let r = gost_text("N1 G1 G91 G9 X10. F100\nN2 X10.\n", [0.0; 3]);
    assert!(r.errors.is_empty());
    let n1 = r.commands_of(1);
    let stop = n1
        .iter()
        .position(|c| {
            matches!(
                c,
                Canon::SetPathMode {
                    mode: stanok_canon::PathMode::ExactStop,
                    ..
                }
            )
        })
        .expect("exact stop");
    let motion = n1.iter().position(|c| c.motion().is_some()).unwrap();
    assert!(stop < motion, "set before the move");
    assert!(matches!(
        n1.last(),
        Some(Canon::SetPathMode {
            mode: stanok_canon::PathMode::Continuous { .. },
            ..
        })
    ));
    assert!(!r
        .commands_of(2)
        .iter()
        .any(|c| matches!(c, Canon::SetPathMode { .. })));
}

#[test]
fn a_subprogram_without_m17_is_reported_at_its_end_and_check_goes_on() {
    let text = "N1 L0201\nN2 G1 G91 X1. F100\nL0200\nN1 G1 G91 Y1. F100\n";
    let r = gost_text(text, [0.0; 3]);
    assert_eq!(r.error_codes(), ["lab::no-return"]);
    assert_eq!(r.errors[0].span.line, 4);
    let r = run_text(text, Dialect::Gost20999, |o| o.continue_after_error = true);
    assert_eq!(r.error_codes(), ["lab::no-return"]);
    assert_eq!(r.end_of(2), at(1.0, 1.0, 0.0), "back in the main program");
}

#[test]
fn side_switch_on_the_contour_goes_from_s1_to_s3() {
    let text = "N1 G1 G90 G17 G41 D1 X10. Y0 F100\nN2 X20.\nN3 G42 X30.\nN4 G40 X40. Y10.\n";
    let r = run_text(text, Dialect::Gost20999, |o| {
        o.initial_position = at(0.0, -10.0, 0.0);
        o.labs.correctors.insert(1, 1.0);
    });
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    // N2 ends at its S1 (left, +Y), N3 starts with S1 → S3 (right, −Y) at X20.
    xy(r.end_of(2), 20.0, 1.0, 1e-9, "N2 S1");
    let n3 = r.motions_of(3);
    assert_eq!(n3.len(), 2);
    xy(n3[0].motion().unwrap().end(), 20.0, -1.0, 1e-9, "S3");
}
