//! The interpreter's architecture invariants, each asserted (ARCHITECTURE.md lists them):
//! atomic blocks, spans on every command, nothing after an error, bounded loops and recursion,
//! streaming over a seekable source, no panic on any input.

mod common;
use common::*;
use proptest::prelude::*;
use stanok_canon::{Canon, DiagCode};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

#[test]
fn a_failing_block_commits_nothing() {
    // Line 3 sets F, plane, units and moves, but its arc is invalid: none of it may appear, and the
    // run ends there although line 4 is valid.
    let text = "G21 F100\nG1 X10\nG20 G18 F7 G2 X1 Z1\nG1 X0\nM2\n";
    let (cmds, err) = run(text, Dialect::Rs274ngc);
    let err = err.expect("the arc has no centre");
    assert_eq!(err.span.line, 3);
    assert!(cmds.iter().all(|c| c.span.line < 3), "{cmds:#?}");
    assert!(!cmds.iter().any(|c| matches!(c.value, Canon::SelectPlane { .. } | Canon::UseLengthUnits { .. } if c.span.line == 3)));
}

/// Runs RS274/NGC text in check mode (every error reported, the bad block skipped): the lines of
/// the errors, and every straight feed as (line, end X, end Y).
fn run_checking_every_block(text: &str) -> (Vec<u32>, Vec<(u32, f64, f64)>) {
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.continue_after_error = true;
    let mut errors = Vec::new();
    let mut ends = Vec::new();
    for item in Interpreter::from_text(text, opts) {
        match item {
            Ok(c) => {
                if let Canon::StraightFeed(m) = c.value {
                    ends.push((c.span.line, m.end.x, m.end.y));
                }
            }
            Err(d) => errors.push(d.span.line),
        }
    }
    (errors, ends)
}

#[test]
fn check_mode_reports_every_error_and_keeps_state() {
    let text = "G21 F100\nG1 X10 X11\nG1 X20\nG2 X1\nG1 Y5\nM2\n";
    let (errors, ends) = run_checking_every_block(text);
    assert_eq!(errors, [2, 4]);
    assert_eq!(ends, [(3, 20.0, 0.0), (5, 20.0, 5.0)]);
}

#[test]
fn every_command_carries_its_block_span_and_number() {
    let text = "N5 G21 F100\nN10 G1 X1 (c)\nG0 Y2\nN20 M2\n";
    let (cmds, err) = run(text, Dialect::Rs274ngc);
    assert!(err.is_none());
    for c in &cmds[1..] {
        let line = text.lines().nth(c.span.line as usize - 1).unwrap();
        assert_eq!(&text[c.span.start as usize..c.span.end as usize], line);
        let n = line
            .strip_prefix('N')
            .map(|r| r.split(' ').next().unwrap().parse::<u32>().unwrap());
        assert_eq!(c.block_number, n, "{line}");
    }
}

#[test]
fn endless_loops_and_runaway_recursion_stop_with_a_diagnostic() {
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_loop_iterations = 1000;
    let endless = "o1 while [1]\no1 endwhile\nM2\n";
    let last = Interpreter::from_text(endless, opts.clone())
        .last()
        .unwrap();
    let d = last.unwrap_err();
    assert_eq!(d.code, DiagCode::Stanok("flow::too-many-iterations"));
    let recursive = "o1 sub\no1 call\no1 endsub\no1 call\nM2\n";
    let d = Interpreter::from_text(recursive, opts.clone())
        .last()
        .unwrap()
        .unwrap_err();
    assert_eq!(d.code, DiagCode::Stanok("flow::call-depth"));
    let missing = "o9 call\nM2\n";
    let d = Interpreter::from_text(missing, opts)
        .last()
        .unwrap()
        .unwrap_err();
    assert_eq!(d.code, DiagCode::Stanok("flow::unterminated"));
    assert!(d.message.contains("o9"), "{d}");
}

#[test]
fn block_limit_bounds_total_work() {
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_blocks = 50;
    let text = "#1=0\no1 while [#1 lt 1000]\n#1=[#1+1]\no1 endwhile\nM2\n";
    let d = Interpreter::from_text(text, opts)
        .last()
        .unwrap()
        .unwrap_err();
    assert_eq!(d.code, DiagCode::Stanok("interp::too-many-blocks"));
}

#[test]
fn streams_a_large_program_from_a_seekable_source() {
    // 20 000 blocks through a Cursor: the interpreter reads line by line and yields as it goes.
    let mut text = String::from("G21 G17 F1000\n");
    for i in 0..10_000 {
        text.push_str(&format!(
            "G1 X{} Y{}\nG2 X{} Y{} R5\n",
            i % 50,
            i % 7,
            i % 50 + 1,
            i % 7
        ));
    }
    text.push_str("M2\n");
    let mut it = Interpreter::from_text(&text, InterpOptions::new(Dialect::Rs274ngc));
    let first_motion = it
        .by_ref()
        .find_map(|c| c.ok()?.value.motion().map(|m| m.end()));
    assert!(first_motion.is_some());
    let rest = it
        .filter(|c| {
            c.as_ref()
                .map(|c| c.value.motion().is_some())
                .unwrap_or(true)
        })
        .count();
    assert_eq!(rest + 1, 20_000);
}

#[test]
fn axioma_block_skip_is_ignored_with_a_warning() {
    let text = "G17 G90 F100\n/N10 G01 X10\nM30\n";
    let mut it = Interpreter::from_text(text, InterpOptions::new(Dialect::Axioma));
    let moves: Vec<_> = it
        .by_ref()
        .filter_map(|c| c.ok()?.value.motion().map(|m| m.end().x))
        .collect();
    assert_eq!(moves, [10.0]);
    assert!(it.warnings().iter().any(|w| w.span.line == 2));
}

fn word_soup() -> impl Strategy<Value = String> {
    let word = prop_oneof![
        Just("G0".to_string()),
        Just("G1".to_string()),
        Just("G2".to_string()),
        Just("G3".to_string()),
        Just("G17".to_string()),
        Just("G18".to_string()),
        Just("G19".to_string()),
        Just("G20".to_string()),
        Just("G91".to_string()),
        Just("G90.1".to_string()),
        Just("G4".to_string()),
        Just("M2".to_string()),
        Just("M3".to_string()),
        Just("M6".to_string()),
        Just("o1 while [1]".to_string()),
        Just("o1 endwhile".to_string()),
        Just("o2 call".to_string()),
        Just("o2 sub".to_string()),
        Just("o2 endsub".to_string()),
        Just("#1=[#1+1]".to_string()),
        Just("CR=-5".to_string()),
        Just("G190".to_string()),
        Just("G95".to_string()),
        Just("(".to_string()),
        Just("[".to_string()),
        (
            prop::sample::select(vec![
                'X', 'Y', 'Z', 'I', 'J', 'K', 'R', 'P', 'F', 'S', 'T', 'E', 'A'
            ]),
            -1e4f64..1e4
        )
            .prop_map(|(l, v)| format!("{l}{v:.3}")),
    ];
    prop::collection::vec(
        prop::collection::vec(word, 0..6).prop_map(|w| w.join(" ")),
        0..30,
    )
    .prop_map(|lines| lines.join("\n"))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn never_panics_on_word_soup(text in word_soup(), rs274 in any::<bool>()) {
        let dialect = if rs274 { Dialect::Rs274ngc } else { Dialect::Axioma };
        let mut opts = InterpOptions::new(dialect);
        opts.max_loop_iterations = 200;
        opts.max_blocks = 10_000;
        opts.continue_after_error = true;
        let n = Interpreter::from_text(&text, opts).take(100_000).count();
        prop_assert!(n < 100_000);
    }

    #[test]
    fn never_panics_on_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400), rs274 in any::<bool>()) {
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let dialect = if rs274 { Dialect::Rs274ngc } else { Dialect::Axioma };
        let mut opts = InterpOptions::new(dialect);
        opts.max_blocks = 10_000;
        let n = Interpreter::from_text(&text, opts).take(100_000).count();
        prop_assert!(n < 100_000);
    }

    /// Centre from R and back: the arc through the programmed end has radius R (rs274 radius format).
    #[test]
    fn radius_format_centre_is_at_distance_r(x in -50.0f64..50.0, y in -50.0f64..50.0, extra in 0.01f64..40.0, major in any::<bool>(), ccw in any::<bool>()) {
        let chord = (x * x + y * y).sqrt();
        prop_assume!(chord > 0.01);
        let r = chord / 2.0 + extra;
        let text = format!("G21 G17 F100\nG{} X{x:.6} Y{y:.6} R{}\nM2\n", if ccw { 3 } else { 2 }, if major { -r } else { r });
        let (cmds, err) = run(&text, Dialect::Rs274ngc);
        prop_assert!(err.is_none(), "{err:?}");
        let arc = cmds.iter().find_map(|c| match &c.value { Canon::ArcFeed(a) => Some(a.clone()), _ => None }).unwrap();
        let rs = arc.centre[0].hypot(arc.centre[1]);
        let re = (arc.end.x - arc.centre[0]).hypot(arc.end.y - arc.centre[1]);
        prop_assert!((rs - r).abs() < 1e-4 && (re - r).abs() < 1e-4, "rs {rs} re {re} r {r}");
        let h = stanok_geom::Helix { start: arc.start.xyz(), end: arc.end.xyz(), centre: arc.centre, axis: arc.axis, turns: arc.turns };
        if major { prop_assert!(h.sweep() >= std::f64::consts::PI - 1e-9) } else { prop_assert!(h.sweep() <= std::f64::consts::PI + 1e-9) }
    }
}

#[test]
fn a_failing_block_leaves_the_work_frame_and_the_dialect_state_as_they_were() {
    // Line 4 selects G55 (offset X100, rotated 30°) and starts cutter compensation, then fails on
    // its arc: both live in journalled parts of the modal state (the frame, the RS274/NGC state),
    // which the block changed before failing. Line 5 must still move in G54, uncompensated.
    let text = "G21 F100\nG10 L2 P2 X100 R30\nG1 X10\nG55 G2 X1\nG1 X30\nM2\n";
    let (errors, ends) = run_checking_every_block(text);
    assert_eq!(errors, [4]);
    assert_eq!(ends, [(3, 10.0, 0.0), (5, 30.0, 0.0)]);

    // The same through G55 committed: the frame does change (so the test above can fail).
    let text = "G21 F100\nG10 L2 P2 X100 R30\nG55\nG1 X30\nM2\n";
    let (cmds, err) = run(text, Dialect::Rs274ngc);
    assert!(err.is_none());
    let end = cmds
        .iter()
        .find_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some(m.end),
            _ => None,
        })
        .unwrap();
    assert!(end.x > 99.0 && end.y > 1.0, "{end:?}");
}
