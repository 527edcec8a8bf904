//! 2P32 (spec lab-collection §3) and the MC2101 notation (§3.10): every `corpus/labs/2p32-*` and
//! `mc2101-*` fixture with the numbers its header states. The 2P32 files' header lines are the
//! dialect's own `( … )` comments: the parser reads them.

mod labs_support;

use labs_support::*;
use stanok_canon::{Canon, Plane, SpindleDirection};
use stanok_syntax::labs::words::{parse_line, Item, Profile, Value};
use stanok_syntax::labs::LineAt;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

/// Correctors of program 1 (§3.7): D16 = +42 mm (Z), D17 = +28 mm (X).
fn p2p32(name: &str) -> Run {
    run(name, Dialect::P2p32, |o| {
        o.labs.correctors.insert(16, 42.0);
        o.labs.correctors.insert(17, 28.0);
        o.initial_position = at(170.0, 0.0, 431.0);
    })
}

#[test]
fn setup_fragment_rapid_z_x_with_correctors_then_feed_and_home() {
    let r = p2p32("2p32-lab3-setup-fragment.nc");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    // N05: rapid Z −200 with corrector 16 added; N06: rapid X −150 with corrector 17, M07.
    assert!(matches!(r.motions_of(5)[0], Canon::StraightTraverse(_)));
    xz(r.end_of(5), 170.0, 431.0 - 200.0 + 42.0, TOL, "N05");
    assert!(matches!(r.motions_of(6)[0], Canon::StraightTraverse(_)));
    xz(r.end_of(6), 170.0 - 150.0 + 28.0, 273.0, TOL, "N06");
    assert!(r.commands_of(6).contains(&&Canon::Mist { on: true }));
    // N07: linear Z −22 at 30 mm/min.
    let Canon::StraightFeed(m) = r.motions_of(7)[0] else {
        panic!("G01")
    };
    xz(m.end, 48.0, 251.0, TOL, "N07");
    near(m.feed, 30.0, TOL, "F30");
    // N24: home = the start; corrections cancelled; spindle stop. N25 M02 ends the run.
    assert!(matches!(r.motions_of(24)[0], Canon::StraightTraverse(_)));
    assert_eq!(r.end_of(24), at(170.0, 0.0, 431.0));
    assert_eq!(r.state.axis_correction[0], (0, None));
    assert!(r
        .commands_of(24)
        .contains(&&Canon::StopSpindle { spindle: 0 }));
    assert!(r.commands_of(25).contains(&&Canon::ProgramEnd));
    // N04: 2000 rpm counter-clockwise, tool T01 already at turret position 1.
    assert!(r.commands_of(4).contains(&&Canon::SetSpindleSpeed {
        spindle: 0,
        rpm: 2000.0
    }));
    assert!(r.commands_of(4).contains(&&Canon::StartSpindle {
        spindle: 0,
        direction: SpindleDirection::CounterClockwise
    }));
    assert_eq!(r.state.tool, Some(1));
}

#[test]
fn stepped_shaft_program1_trace_of_the_header() {
    let r = p2p32("2p32-stepped-shaft-program1.nc");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    // Slides travel the programmed value plus the corrector: Z −208.5 + 42, X −153.4 + 28.
    xz(r.end_of(5), 170.0, 431.0 - 166.5, TOL, "N5");
    xz(r.end_of(6), 170.0 - 125.4, 264.5, TOL, "N6");
    // From here the header's tool-tip trace: P0 = (r 16.6, z +2) after N6.
    let p0 = r.end_of(6);
    let tip = |n: u32| {
        let e = r.end_of(n);
        (e.x - p0.x + 16.6, e.z - p0.z + 2.0)
    };
    for (n, rr, zz) in [
        (7, 16.6, -20.0),
        (8, 17.1, -20.0),
        (9, 17.1, -40.0),
        (10, 27.1, -40.0),
        (11, 27.1, 2.0),
        (12, 17.1, 2.0),
        (13, 4.1, 0.1),
        (14, 4.1, -0.1),
        (15, 11.7, -0.1),
        (16, 12.0, -0.4),
        (18, 12.0, -20.1),
        (19, 16.7, -20.1),
        (20, 17.0, -20.4),
        (22, 17.0, -40.1),
        (23, 27.0, -40.1),
    ] {
        let (a, b) = tip(n);
        near(a, rr, 1e-9, &format!("N{n} r"));
        near(b, zz, 1e-9, &format!("N{n} z"));
    }
    // G4 X+4000 is a dwell (4 s at 0.001 s per count), not a move.
    for n in [17, 21] {
        assert!(r.motions_of(n).is_empty(), "N{n} does not move");
        assert!(r.commands_of(n).contains(&&Canon::Dwell { seconds: 4.0 }));
    }
    // N15 F 70 = 70 mm/min (spaces inside the word).
    let Canon::StraightFeed(m) = r.motions_of(15)[0] else {
        panic!()
    };
    near(m.feed, 70.0, TOL, "N15 F");
    // Part: Ø24.0 and Ø34.0 steps (radius 12.0, 17.0).
    near(tip(18).0 * 2.0, 24.0, 1e-9, "first step diameter");
    near(tip(22).0 * 2.0, 34.0, 1e-9, "second step diameter");
    assert_eq!(r.end_of(24), at(170.0, 0.0, 431.0), "N24 home");
}

#[test]
fn tool_search_example1_two_steps_counter_clockwise() {
    let r = run("2p32-tool-search-example1.nc", Dialect::P2p32, |o| {
        o.labs.turret_codes = [1, 2, 12, 4, 5, 6, 7, 8, 9, 10, 11, 99];
        o.labs.turret_position = 1;
    });
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert_eq!(r.state.turret_position, 3);
    assert_eq!(r.state.tool, Some(12));
    assert!(r.commands_of(17).contains(&&Canon::Comment {
        text: "turret: position 1 -> 3, 2 step(s) counter-clockwise".into()
    }));
    assert!(r
        .commands_of(17)
        .contains(&&Canon::ChangeTool { tool: 12, slot: 12 }));
}

#[test]
fn tool_search_example2_three_steps_clockwise() {
    let mut codes = [0; 12];
    for (i, c) in codes.iter_mut().enumerate() {
        *c = i as u32 + 1;
    }
    codes[11] = 41;
    let r = run("2p32-tool-search-example2.nc", Dialect::P2p32, |o| {
        o.labs.turret_codes = codes;
        o.labs.turret_position = 3;
    });
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert_eq!(r.state.turret_position, 12);
    assert!(r.commands_of(153).contains(&&Canon::Comment {
        text: "turret: position 3 -> 12, 3 step(s) clockwise".into()
    }));
}

#[test]
fn tool_search_refuses_missing_and_duplicated_codes() {
    let r = run_text("N1 T41\n", Dialect::P2p32, |_| {});
    assert_eq!(r.error_codes(), ["lab::tool-code-not-found"]);
    let r = run_text("N1 T5\n", Dialect::P2p32, |o| {
        o.labs.turret_codes[6] = 5;
    });
    assert_eq!(r.error_codes(), ["lab::tool-code-ambiguous"]);
}

#[test]
fn turn_mill_program3_operations_up_to_the_undocumented_e_words() {
    let r = run("2p32-turn-mill-program3.nc", Dialect::P2p32, |o| {
        o.initial_position = at(170.0, 0.0, 431.0)
    });
    // N121 `E+166 ω02 R25`: jumps whose syntax the document does not give; the run stops there.
    assert_eq!(r.error_codes(), ["lab::unsupported"]);
    assert_eq!(r.errors[0].span.line, 133, "N121");
    let d = |a: u32, b: u32| {
        let (p, q) = (r.end_of(a), r.end_of(b));
        (q.x - p.x, q.z - p.z, q.c - p.c)
    };
    // T1: rough pass Z −66 at 30 mm/min; retract X +1; return Z +66; X −2; finish pass Z −66.
    assert_eq!(d(6, 7), (0.0, -66.0, 0.0));
    assert_eq!(d(7, 8), (1.0, 0.0, 0.0));
    assert_eq!(d(8, 9), (0.0, 66.0, 0.0));
    let (dx, dz, _) = d(12, 13);
    near(dx, -27.0, TOL, "N13 X");
    near(dz, 7.235, TOL, "N13 Z");
    near(
        (dz / dx.abs()).atan().to_degrees(),
        15.0,
        1e-3,
        "15° conical face",
    );
    // N19: two G43/D pairs and a bare G; N24/N33: Y = spindle angle (C) after M89.
    near(d(22, 24).2, -50.0, TOL, "N24 C −50°");
    near(d(32, 33).2, 90.0, TOL, "N33 C +90°");
    assert!(
        matches!(r.motions_of(31)[0], Canon::StraightTraverse(_)),
        "N31 as printed: rapid"
    );
    // T5 polyline N71–N120: X net 0, C −48.66°.
    let (dx, _, dc) = d(70, 120);
    near(dx, 0.0, 1e-9, "polyline X net");
    near(dc, -48.66, 1e-9, "polyline C");
    // N70: X by R27 = −4910 counts = −4.91 mm.
    near(d(69, 70).0, -4.91, TOL, "X+R27");
    // N66: G4 X20 = 0.02 s.
    assert!(r.commands_of(66).contains(&&Canon::Dwell { seconds: 0.02 }));
}

#[test]
fn y_word_needs_the_servo_spindle() {
    let r = run_text("N1 G1 Y1000 F10\n", Dialect::P2p32, |_| {});
    assert_eq!(r.error_codes(), ["lab::y-without-servo"]);
}

#[test]
fn mc2101_linear_a1_a2_a3() {
    let r = run("mc2101-linear-interpolation.nc", Dialect::Mc2101, |o| {
        o.initial_position = at(-20.0, 50.0, 0.0)
    });
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    xy(r.end_of(15), 60.0, -10.0, TOL, "A2");
    xy(r.end_of(16), -50.0, -30.0, TOL, "A3");
    assert!(
        matches!(r.motions_of(16)[0], Canon::StraightFeed(_)),
        "G01 modal"
    );
}

#[test]
fn mc2101_circular_g19_start_minus_centre_unsigned() {
    let r = run("mc2101-circular-interpolation.nc", Dialect::Mc2101, |o| {
        o.initial_position = at(0.0, -120.0, 50.0)
    });
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let arcs: Vec<_> = r
        .commands
        .iter()
        .filter_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some((c.block_number, a.clone())),
            _ => None,
        })
        .collect();
    assert_eq!(arcs.len(), 3);
    for (n, a, yz, centre, cw) in [
        (21, arcs[0].1.clone(), (0.0, 130.0), (0.0, 0.0), true),
        (22, arcs[1].1.clone(), (50.0, 120.0), (0.0, 0.0), true),
        (23, arcs[2].1.clone(), (70.0, 100.0), (130.0, 180.0), false),
    ] {
        assert_eq!(arcs.iter().find(|x| x.0 == Some(n)).map(|x| &x.1), Some(&a));
        near(a.end.y, yz.0, TOL, &format!("N0{n} Y"));
        near(a.end.z, yz.1, TOL, &format!("N0{n} Z"));
        near(a.centre[1], centre.0, TOL, &format!("N0{n} centre Y"));
        near(a.centre[2], centre.1, TOL, &format!("N0{n} centre Z"));
        assert_eq!(a.plane, Plane::YZ);
        assert_eq!(a.axis, [if cw { -1.0 } else { 1.0 }, 0.0, 0.0], "N0{n}");
    }
    near(
        (arcs[0].1.start.y).hypot(arcs[0].1.start.z),
        130.0,
        TOL,
        "R1",
    );
    near(
        (arcs[2].1.end.y - 130.0).hypot(arcs[2].1.end.z - 180.0),
        100.0,
        TOL,
        "R2",
    );
}

#[test]
fn mc2101_frame_structure_reads_every_word_and_the_alternatives_as_comments() {
    let text = fixture("mc2101-frame-structure-example.nc");
    let line = text.lines().find(|l| l.starts_with("N03")).unwrap();
    let (b, d) = parse_line(line, LineAt::default(), Profile::Mc2101);
    assert!(d.is_empty(), "{d:?}");
    assert_eq!(b.number, Some(3));
    let words: Vec<(char, f64)> = b
        .items
        .iter()
        .map(|i| match i {
            Item::Word(w) => match w.value {
                Some(Value::Number(n)) => (w.letter, n.value),
                _ => panic!("number"),
            },
            Item::Assign(_) => panic!("no assignment"),
        })
        .collect();
    assert_eq!(
        words,
        [
            ('G', 3.0),
            ('X', 53000.0),
            ('Z', -53000.0),
            ('I', 53000.0),
            ('J', 53000.0),
            ('F', 30.0),
            ('S', 2000.0),
            ('T', 3.0),
            ('D', 15.0),
            ('M', 3.0)
        ]
    );
    assert_eq!(b.comments, [" C=53000", " R+53000", "S05"]);
}

#[test]
fn reader_reads_spaces_inside_words_and_2p32_parameters() {
    let (b, d) = parse_line(
        "N05 G43 D16 Z - 200000 (Z1)",
        LineAt::default(),
        Profile::P2p32,
    );
    assert!(d.is_empty());
    assert!(matches!(
        b.items[2],
        Item::Word(w) if w.letter == 'Z' && w.value == Some(Value::Number(stanok_syntax::labs::words::Number { value: -200000.0, point: false }))
    ));
    let (b, _) = parse_line("N64 R27 - 4910 R26+0", LineAt::default(), Profile::P2p32);
    assert!(matches!(b.items[0], Item::Assign(a) if a.number == 27 && a.value.value == -4910.0));
    assert!(matches!(b.items[1], Item::Assign(a) if a.number == 26 && a.value.value == 0.0));
    let (b, _) = parse_line("N70 G1 X+R27 F45", LineAt::default(), Profile::P2p32);
    assert!(matches!(
        b.items[1],
        Item::Word(w) if w.value == Some(Value::Variable { number: 27, negative: false })
    ));
    let (b, d) = parse_line("ПС", LineAt::default(), Profile::P2p32);
    assert!(d.is_empty() && b.items.is_empty());
    let (_, d) = parse_line(
        "N1 G1 X1. (no comments here)",
        LineAt::default(),
        Profile::Gost20999,
    );
    assert_eq!(d[0].code.to_string(), "lab::syntax");
}
