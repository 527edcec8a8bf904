//! Elektronika NC-31 (spec lab-collection §2): every `corpus/labs/nc31-*` fixture, with the numbers
//! its header states. Canon X is the radius (the NC-31's X values are diameters in 0.01 mm).

mod labs_support;

use labs_support::*;
use stanok_canon::{Canon, FeedMode, Plane, SpindleDirection};
use stanok_syntax::labs::nc31::{parse_line, Chamfer, Line};
use stanok_syntax::labs::LineAt;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn nc31(name: &str) -> Run {
    run(name, Dialect::Nc31, |_| {})
}

/// Start S = (radius 10, Z 5) mm for the fragments whose start the document leaves open.
fn from_s(name: &str, prefix: &str) -> Run {
    let text = format!("{prefix}{}", fixture(name));
    run_text(&text, Dialect::Nc31, |o| {
        o.initial_position = at(10.0, 0.0, 5.0)
    })
}

#[test]
fn absolute_xz_moves_go_to_diameter_150_then_z_150() {
    let r = nc31("nc31-absolute-xz-moves.nc");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let m = r.moves();
    assert_eq!(m.len(), 2);
    // N3 X15000: Ø150 = radius 75 mm, feed move (no G1 in NC-31).
    assert!(matches!(r.motions_of(3)[0], Canon::StraightFeed(_)));
    xz(r.end_of(3), 75.0, 0.0, TOL, "N3");
    assert!(matches!(r.motions_of(4)[0], Canon::StraightFeed(_)));
    xz(r.end_of(4), 75.0, 150.0, TOL, "N4");
    // G95 at power-on, no S: the run says the feed is not usable (once).
    assert_eq!(r.state.feed_mode, FeedMode::UnitsPerRevolution);
    assert_eq!(r.warnings.len(), 1);
    assert_eq!(r.warnings[0].code.to_string(), "lab::no-feed");
}

#[test]
fn rapid_flag_moves_x_at_rapid_and_z_at_the_feed() {
    let r = nc31("nc31-rapid-flag.nc");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert!(matches!(r.motions_of(5)[0], Canon::StraightTraverse(_)));
    xz(r.end_of(5), 75.0, 0.0, TOL, "N5");
    assert!(matches!(r.motions_of(6)[0], Canon::StraightFeed(_)));
    xz(r.end_of(6), 75.0, 150.0, TOL, "N6");
}

#[test]
fn two_axis_group_with_oaco_is_one_incremental_line() {
    let r = from_s("nc31-two-axis-group-relative.nc", "");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let m = r.moves();
    assert_eq!(m.len(), 1, "X* Z is one simultaneous move");
    assert!(matches!(r.motions_of(4)[0], Canon::StraightFeed(_)));
    // +150.00 mm of diameter = +75 mm radius, +150 mm Z, both incremental (flag on the first frame).
    xz(m[0].1, 10.0 + 75.0, 5.0 + 150.0, TOL, "N4-N5");
}

#[test]
fn feed_g94_standalone_is_200_mm_per_min() {
    let r = nc31("nc31-feed-g94-standalone.nc");
    assert!(r.errors.is_empty());
    assert_eq!(r.state.feed_mode, FeedMode::UnitsPerMinute);
    near(r.state.feed, 200.0, TOL, "modal F");
    assert!(r
        .commands_of(12)
        .contains(&&Canon::SetFeedRate { feed: 200.0 }));
}

#[test]
fn feed_g95_standalone_is_1_5_mm_per_rev() {
    let r = nc31("nc31-feed-g95-standalone.nc");
    assert!(r.errors.is_empty());
    assert_eq!(r.state.feed_mode, FeedMode::UnitsPerRevolution);
    near(r.state.feed, 1.5, TOL, "modal F");
}

#[test]
fn feed_g94_in_a_group_is_0_01_mm_per_min_per_unit_and_local() {
    let r = nc31("nc31-feed-g94-group.nc");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let Canon::StraightFeed(m) = r.motions_of(12)[0] else {
        panic!("feed move expected")
    };
    // X2000 = Ø20.00 = radius 10; F1000 in a group = 10 mm/min.
    xz(m.end, 10.0, 0.0, TOL, "N12-N13");
    near(m.feed, 10.0, TOL, "group feed mm/min");
    // The group's F does not become modal.
    near(r.state.feed, 0.0, TOL, "modal F after the group");
}

#[test]
fn spindle_variable_drive_560_rpm_clockwise() {
    let r = nc31("nc31-spindle-variable-drive.nc");
    assert!(r.errors.is_empty());
    assert_eq!(r.state.spindle, Some(SpindleDirection::Clockwise));
    near(r.state.spindle_rpm, 560.0, TOL, "S");
    assert!(r.commands_of(11).contains(&&Canon::SetSpindleSpeed {
        spindle: 0,
        rpm: 560.0
    }));
}

#[test]
fn spindle_gearbox_code_7_is_560_rpm_and_duplicate_n11_is_accepted() {
    let r = nc31("nc31-spindle-gearbox-code.nc");
    assert!(
        r.errors.is_empty(),
        "duplicate frame numbers are allowed: {:?}",
        r.errors
    );
    assert_eq!(r.state.gear_range, Some(38));
    near(r.state.spindle_rpm, 560.0, TOL, "gearbox code 7");
    // The code table is machine data: another table gives another speed.
    let r2 = run("nc31-spindle-gearbox-code.nc", Dialect::Nc31, |o| {
        o.labs.nc31_gearbox_rpm[7] = 630.0
    });
    near(r2.state.spindle_rpm, 630.0, TOL, "machine table");
}

#[test]
fn arc_g2_group_centre_radius_sweep_and_sense() {
    // S100 before the fragment so that the group's 0.25 mm/rev shows as mm/min.
    let r = from_s("nc31-arc-g2-group.nc", "N20 S100\n");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let Canon::ArcFeed(a) = r.motions_of(22)[0] else {
        panic!("arc expected")
    };
    // E = S + (dr 0.10, dz 0.10); C = S + (0.20, −0.10).
    xz(a.end, 10.10, 5.10, 1e-12, "end");
    near(a.centre[0], 10.20, 1e-12, "centre r");
    near(a.centre[2], 4.90, 1e-12, "centre z");
    let r_s = (a.start.x - a.centre[0]).hypot(a.start.z - a.centre[2]);
    let r_e = (a.end.x - a.centre[0]).hypot(a.end.z - a.centre[2]);
    near(r_s, 0.2236, 1e-4, "start radius");
    near(r_e, 0.2236, 1e-4, "end radius");
    // Counter-clockwise in the Z-right/X-up view = about +Y, 36.87°.
    assert_eq!(a.axis, [0.0, 1.0, 0.0]);
    assert_eq!(a.plane, Plane::ZX);
    let ang = |x: f64, z: f64| (x - a.centre[0]).atan2(z - a.centre[2]);
    let sweep = (ang(a.end.x, a.end.z) - ang(a.start.x, a.start.z)).to_degrees();
    near(sweep, 36.87, 0.01, "sweep deg");
    near(
        a.feed,
        25.0,
        1e-9,
        "F25 in the group = 0.25 mm/rev at 100 rpm",
    );
}

#[test]
fn rounding_g13_quarter_circle_about_rs_ze() {
    let r = from_s("nc31-rounding-g13-group.nc", "N20 S100\n");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let Canon::ArcFeed(a) = r.motions_of(22)[0] else {
        panic!("arc expected")
    };
    xz(a.end, 9.90, 4.90, 1e-12, "end");
    // Centre (r_S, z_E), radius 0.10, clockwise in the Z-right/X-up view (about −Y).
    near(a.centre[0], 10.0, 1e-12, "centre r");
    near(a.centre[2], 4.90, 1e-12, "centre z");
    near(
        (a.start.x - a.centre[0]).hypot(a.start.z - a.centre[2]),
        0.10,
        1e-12,
        "R",
    );
    assert_eq!(a.axis, [0.0, -1.0, 0.0]);
    near(a.feed, 10.0, 1e-9, "F10 = 0.10 mm/rev at 100 rpm");
}

#[test]
fn rounding_with_unequal_travel_is_refused() {
    let r = run_text(
        "N1 G13*\nN2 X-20*\nN3 Z-30*\nN4 F10\n",
        Dialect::Nc31,
        |_| {},
    );
    assert_eq!(r.error_codes(), ["nc31::rounding-not-quarter"]);
    assert!(r.moves().is_empty(), "nothing of the bad group runs");
    assert_eq!(r.errors[0].span.line, 1);
}

#[test]
fn frame_structure_sample_reads_as_a_g3_group_with_p1_p2_labels() {
    let text = fixture("nc31-frame-structure-arc-group.nc");
    let mut frames = Vec::new();
    let mut offset = 0;
    for (i, line) in text.split('\n').enumerate() {
        let (l, d) = parse_line(
            line,
            LineAt {
                line: i as u32 + 1,
                offset,
            },
        );
        offset += line.len() as u64 + 1;
        assert!(d.is_empty(), "{d:?}");
        if let Line::Frame {
            number,
            body: Some(b),
            ..
        } = l
        {
            frames.push((number, b.address, b.label, b.value, b.group));
        }
    }
    assert_eq!(
        frames,
        [
            (5, b'G', None, Some(3), true),
            (6, b'X', None, Some(53000), true),
            (7, b'Z', None, Some(-53000), true),
            (8, b'P', Some(1), Some(53000), true),
            (9, b'P', Some(2), Some(53000), true),
            (10, b'F', None, Some(30), false),
        ]
    );
}

#[test]
fn flange_listing_flags_groups_and_per_tool_positions() {
    // Start = the tool-change point at the origin; `stanok check` mode: the undocumented
    // constructs are reported and skipped, the rest runs.
    let r = run("nc31-flange-program.nc", Dialect::Nc31, |o| {
        o.continue_after_error = true
    });
    let first = |n: u32| {
        r.moves()
            .into_iter()
            .find(|(b, _)| *b == Some(n))
            .unwrap_or_else(|| panic!("N{n} has no motion"))
            .1
    };
    let codes = r.error_codes();
    // N100 L0201 (subprogram 02 not loaded), N101 G25 + P2008 (frames N2…N8 do not exist: the
    // spec's "does not fit the aaabbb pattern"), N103–N107 ~S, N144 ~45°, N152 G31, N185 ~S
    // group; N192–N194 repeat N101…N189 12 times; N197's jump back is bounded.
    assert_eq!(codes[0], "nc31::no-subprogram");
    assert_eq!(codes[1], "nc31::no-such-frame");
    assert_eq!(r.errors[1].span.line, 50, "N101");
    assert!(codes.contains(&"nc31::unsupported".to_string()));
    // As printed, N189 ends with `*`: N190 P192 closes the ~S group (refused with it), so the data
    // frame N191 `P 21000` runs as a jump to a frame that does not exist.
    let n191 = r.errors.iter().find(|d| d.span.line == 138).expect("N191");
    assert_eq!(n191.code.to_string(), "nc31::no-such-frame");
    // The G25 repeat ran the body again: T2's facing move N117 comes 1 + 12 times before the
    // first jump back (and again after each jump).
    let m5 = r
        .commands
        .iter()
        .position(|c| c.block_number == Some(196))
        .expect("N196 M5");
    let n117 = r.commands[..m5]
        .iter()
        .filter(|c| c.block_number == Some(117) && c.value.motion().is_some())
        .count();
    assert_eq!(n117, 13, "N117 before N196");
    assert!(codes.contains(&"nc31::unknown-chamfer".to_string()));
    assert!(codes.contains(&"nc31::too-many-jumps".to_string()));
    // T2 (radius = diameter / 2).
    xz(first(113), 170.0, 50.0, TOL, "N113-N114 rapid (Ø340, 50)");
    assert!(matches!(r.motions_of(113)[0], Canon::StraightTraverse(_)));
    xz(first(115), 170.0, 0.0, TOL, "N115 Z -5000#");
    xz(first(117), 50.0, 0.0, TOL, "N117 face to Ø100");
    xz(first(119), 142.5, 0.0, TOL, "N119 back to Ø285");
    xz(
        first(121),
        160.0,
        -17.5,
        TOL,
        "N121 -45° chamfer to (Ø320, -17.5)",
    );
    xz(first(122), 160.0, -107.5, TOL, "N122 turn");
    xz(first(123), 170.0, -107.5, TOL, "N123");
    xz(first(124), 170.0, 42.5, TOL, "N124");
    xz(first(125), -550.0, 590.0, TOL, "N125-N126 as printed");
    // T3 drilling.
    xz(first(130), 0.0, 50.0, TOL, "N130-N131");
    xz(first(132), 0.0, -200.0, TOL, "N132 drill");
    xz(first(133), 0.0, 50.0, TOL, "N133 out");
    // T4 boring.
    xz(first(137), 109.0, 50.0, TOL, "N137-N138");
    xz(first(139), 109.0, 0.0, TOL, "N139");
    xz(first(141), 105.5, -3.5, TOL, "N141 chamfer (Ø211, -3.5)");
    xz(first(142), 105.5, 51.5, TOL, "N142 as printed");
    // T8 grooving and part-off.
    xz(first(164), 170.0, 50.0, TOL, "N164-N165");
    xz(first(166), 170.0, -159.0, TOL, "N166");
    xz(first(167), 95.0, -159.0, TOL, "N167 plunge Ø190");
    xz(first(170), 110.5, -119.0, TOL, "N170 plunge Ø221");
    xz(first(173), 109.5, -79.0, TOL, "N173 plunge Ø219");
    xz(first(175), 109.5, -156.0, TOL, "N175 turn");
    xz(
        first(176),
        105.5,
        -160.0,
        TOL,
        "N176 -45° Z chamfer (Ø211, -160)",
    );
    xz(first(179), 45.0, -160.0, TOL, "N179 part-off Ø90");
    xz(first(181), 45.0, -150.0, TOL, "N181");
    // Value-less ~X / ~Z: back to the start point's axis value.
    xz(first(183), 0.0, 0.0, TOL, "N182-N183");
}

#[test]
fn flange_subprograms_are_pseudo_code_reported_at_their_first_frame() {
    for (name, first) in [
        ("nc31-flange-sub-l01-blank-length.nc", 200),
        ("nc31-flange-sub-l02-blank-diameter.nc", 300),
    ] {
        // Alone, the file is a subprogram (header L01/L02) and the main program is empty.
        let r = nc31(name);
        assert!(r.errors.is_empty() && r.moves().is_empty(), "{name}");
        // Called, its first frame's `#`-assignment pseudo-code is a syntax error there.
        let number = first / 100 - 1;
        let text = format!("N1 L{number:02}01\n{}", fixture(name));
        let r = run_text(&text, Dialect::Nc31, |_| {});
        assert_eq!(r.error_codes(), ["nc31::syntax"], "{name}");
        let line = text
            .lines()
            .position(|l| l.starts_with(&format!("N{first}")))
            .unwrap();
        assert_eq!(r.errors[0].span.line as usize, line + 1, "{name}");
    }
}

#[test]
fn reader_reads_both_flag_notations() {
    let read = |s: &str| match parse_line(s, LineAt::default()) {
        (Line::Frame { body: Some(b), .. }, d) if d.is_empty() => b,
        other => panic!("{s}: {other:?}"),
    };
    let b = read("N5 X 15000 BX");
    assert!(b.rapid && !b.incremental && b.value == Some(15000));
    let b = read("N113 ~X 34000*");
    assert!(b.rapid && b.group);
    let b = read("N115 Z -5000#");
    assert!(b.incremental && b.value == Some(-5000));
    let b = read("N121 -45° X 32000");
    assert_eq!(b.chamfer, Some(Chamfer::Minus));
    let b = read("N4 X15000 (ОАСО)*");
    assert!(b.incremental && b.group);
    let (_, d) = parse_line("N7 X10 Y20", LineAt::default());
    assert_eq!(d[0].code.to_string(), "nc31::syntax");
    assert_eq!(d[0].span.column, 8);
}

#[test]
fn nc31_refusals_name_their_frame_and_execute_nothing() {
    for (text, code, line) in [
        ("N1 G2\n", "nc31::group-expected", 1),
        ("N1 X100\nN2 X*\nN3 Z10\n", "nc31::missing-value", 2),
        ("N1 X10*\nN2 M3\n", "nc31::bad-group", 2),
        ("N1 M17\n", "nc31::return-in-main", 1),
        ("N1 X10*\n", "nc31::unterminated-group", 1),
        ("N1 P77\n", "nc31::no-such-frame", 1),
        ("N1 G77\n", "nc31::unsupported", 1),
        (
            "N1 G2*\nN2 X20*\nN3 Z10*\nN4 P-30*\nN5 P11\n",
            "nc31::arc-radius",
            1,
        ),
        (
            "N1 G3*\nN2 X0*\nN3 Z-2000*\nN4 P0*\nN5 P1000\n",
            "nc31::arc-too-long",
            1,
        ),
    ] {
        let r = run_text(text, Dialect::Nc31, |_| {});
        assert_eq!(r.error_codes(), [code], "{text}");
        assert_eq!(r.errors[0].span.line, line, "{text}");
    }
    // A refused group leaves the position where it was.
    let r = run_text(
        "N1 X100\nN2 G2*\nN3 X20*\nN4 Z10*\nN5 P-30*\nN6 P11\n",
        Dialect::Nc31,
        |_| {},
    );
    assert_eq!(r.moves().len(), 1);
    xz(r.state.position, 0.5, 0.0, TOL, "after N1 only");
}

#[test]
fn g25_repeats_a_section_k_more_times_then_goes_on() {
    // Frames N2…N3 run once in the program flow, then 3 more times by N4–N6, then N7.
    let text = "N1 X1000\nN2 Z-1000#\nN3 X200#\nN4 G25*\nN5 P002003*\nN6 R3\nN7 Z5000\n";
    let r = run_text(text, Dialect::Nc31, |_| {});
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let zs: Vec<f64> = r.moves().iter().map(|m| m.1.z).collect();
    assert_eq!(
        zs,
        [0.0, -10.0, -10.0, -20.0, -20.0, -30.0, -30.0, -40.0, -40.0, 50.0]
    );
    // X: 5 mm radius, then +1 mm radius per run of N3.
    near(r.moves()[8].1.x, 9.0, TOL, "four runs of N3");
    // A section containing its own G25 group is refused.
    let r = run_text("N1 G25*\nN2 P001003*\nN3 R2\n", Dialect::Nc31, |_| {});
    assert_eq!(r.error_codes(), ["nc31::bad-repeat"]);
}

/// §2.2: frame numbers run 0…249, raised by a machine parameter to at most 999: N1000 is refused
/// at its number, N999 (the raised maximum) reads.
#[test]
fn frame_numbers_above_999_are_refused() {
    let r = run_text("N999 X100\nN1000 X200\n", Dialect::Nc31, |_| {});
    assert_eq!(r.error_codes(), ["nc31::syntax"]);
    assert_eq!(r.errors[0].span.line, 2);
    assert!(r.errors[0].message.contains("N1000"), "{}", r.errors[0]);
}
