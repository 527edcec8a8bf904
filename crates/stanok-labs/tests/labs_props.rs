//! Properties of the lab front ends: no input panics or hangs, every diagnostic has a location,
//! motion is continuous, and a failing unit emits nothing (the run stops before it).

use proptest::prelude::*;
use stanok_canon::Canon;
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::labs::{nc31, words, LineAt};
use stanok_syntax::Dialect;

/// Lines made of the lab languages' own pieces, so that most of them get past the readers.
fn lab_line() -> impl Strategy<Value = String> {
    let piece = prop::sample::select(vec![
        "N1", "N2", "N10", " ", "*", "#", "~", "-45° ", "+45", "~45°", "BX", "(OACO)", "G", "G0",
        "G1", "G2", "G3", "G4", "G9", "G12", "G13", "G17", "G18", "G19", "G25", "G28", "G31",
        "G40", "G41", "G42", "G43", "G44", "G49", "G53", "G54", "G55", "G90", "G91", "G92", "G94",
        "G95", "X", "Z", "Y", "P", "F", "S", "T", "M", "L", "R", "I", "J", "K", "D", "E", "ω",
        "10", "-5", "+2000", "15.", ".14", "0100", "0201", "01", "7", "#3.", "R1", "-R2", "M17",
        "M30", "M89", "P1+", "(c)", ":", "/", "%", "LF", "ПС", "9999999",
    ]);
    prop::collection::vec(piece, 0..10).prop_map(|v| v.concat())
}

fn program() -> impl Strategy<Value = String> {
    prop::collection::vec(lab_line(), 0..25).prop_map(|v| v.join("\n"))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn readers_never_panic_and_spans_stay_on_their_line(line in "\\PC{0,40}|[NGXZP0-9 *#~+-]{0,30}") {
        let at = LineAt { line: 3, offset: 100 };
        let (_, diags) = nc31::parse_line(&line, at);
        for d in diags {
            prop_assert_eq!(d.span.line, 3);
            prop_assert!(d.span.start >= 100 && d.span.end <= 100 + line.len() as u64);
        }
        for profile in [words::Profile::Gost20999, words::Profile::P2p32, words::Profile::Mc2101] {
            let (_, diags) = words::parse_line(&line, at, profile);
            for d in diags {
                prop_assert_eq!(d.span.line, 3);
                prop_assert!(d.span.end <= 100 + line.len() as u64);
            }
        }
    }

    #[test]
    fn random_lab_programs_run_without_panic_with_continuous_motion(text in program(), d in 0usize..4) {
        let dialect = Dialect::LABS[d];
        for check_mode in [false, true] {
            let mut opts = InterpOptions::new(dialect);
            opts.continue_after_error = check_mode;
            opts.labs.correctors.insert(1, 0.5);
            let mut last = None;
            let mut errors = 0;
            for item in Interpreter::from_text(&text, opts) {
                match item {
                    Ok(c) => {
                        if let Some(m) = c.value.motion() {
                            if let Some(p) = last {
                                prop_assert_eq!(m.start(), p);
                            }
                            last = Some(m.end());
                        }
                        if let Canon::ArcFeed(a) = &c.value {
                            prop_assert!(a.centre.iter().all(|v| v.is_finite()));
                        }
                    }
                    Err(e) => {
                        errors += 1;
                        prop_assert!(e.span.line >= 1 || e.code.to_string().contains("no-return")
                            || e.code.to_string().contains("too-many"), "{e:?}");
                    }
                }
            }
            if !check_mode {
                prop_assert!(errors <= 1, "a run stops at its first error");
            }
        }
    }
}

#[test]
fn an_endless_nc31_jump_is_stopped() {
    let mut opts = InterpOptions::new(Dialect::Nc31);
    opts.max_blocks = 1_000_000;
    let results: Vec<_> = Interpreter::from_text("N1 X100\nN2 P1\n", opts).collect();
    let err = results
        .iter()
        .find_map(|r| r.as_ref().err())
        .expect("stopped");
    assert_eq!(err.code.to_string(), "nc31::too-many-jumps");
    assert_eq!(err.span.line, 2);
}

fn polyline() -> impl Strategy<Value = (String, f64)> {
    let step = (-50i32..50, -50i32..50, 0u8..8);
    (
        prop::collection::vec(step, 1..12),
        prop::bool::ANY,
        0.0f64..3.0,
    )
        .prop_map(|(steps, left, r)| {
            let mut t = format!(
                "N1 G1 G91 G17 {} D7 X5. Y1. F100\n",
                if left { "G41" } else { "G42" }
            );
            for (k, (x, y, brk)) in steps.into_iter().enumerate() {
                if brk == 0 {
                    t.push_str(&format!("N{} Z-1.\n", k + 2));
                } else if brk >= 6 && (x, y) != (0, 0) {
                    // An arc over the chord, less or more than a half circle.
                    let rad = (x as f64).hypot(y as f64) / 2.0 + 3.0;
                    let g = if brk == 6 { "G2" } else { "G3" };
                    t.push_str(&format!(
                        "N{} {g} X{x}. Y{y}. R{rad:.3}\nN{} G1\n",
                        k + 2,
                        k + 50
                    ));
                } else {
                    t.push_str(&format!("N{} X{x}. Y{y}.\n", k + 2));
                }
            }
            t.push_str("N99 G40 X3. Y-2.\n");
            (t, r)
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Compensated polylines with breaks: continuous, and the exit ends at the programmed point.
    #[test]
    fn compensated_polylines_are_continuous_and_exit_at_the_programmed_point((text, r) in polyline()) {
        let mut opts = InterpOptions::new(Dialect::Gost20999);
        opts.labs.correctors.insert(7, r);
        let mut last = None;
        let mut ok = true;
        for item in Interpreter::from_text(&text, opts.clone()) {
            match item {
                Ok(c) => if let Some(m) = c.value.motion() {
                    if let Some(p) = last {
                        prop_assert_eq!(m.start(), p);
                    }
                    last = Some(m.end());
                },
                Err(e) => {
                    prop_assert!(["E19", "E35"].contains(&e.code.to_string().as_str()), "{e:?}");
                    ok = false;
                }
            }
        }
        if ok {
            // Same program with radius 0 = the programmed end point.
            opts.labs.correctors.insert(7, 0.0);
            let zero = Interpreter::from_text(&text, opts)
                .filter_map(|c| c.ok()?.value.motion().map(|m| m.end()))
                .last();
            let (a, b) = (last.unwrap(), zero.unwrap());
            prop_assert!((a.x - b.x).abs() < 1e-9 && (a.y - b.y).abs() < 1e-9 && (a.z - b.z).abs() < 1e-9);
        }
    }
}

#[test]
fn a_program_beyond_the_memory_bound_is_refused_not_truncated_silently() {
    // 16 MiB + a multi-byte character across the bound.
    let mut text = "N1 X10\n".repeat((16 << 20) / 7);
    while text.len() < (16 << 20) - 1 {
        text.push(' ');
    }
    text.push('°'); // bytes 16 MiB − 1 and 16 MiB: the bound falls inside it
    text.push('\n');
    let first = Interpreter::from_text(&text, InterpOptions::new(Dialect::Nc31))
        .find_map(|r| r.err())
        .expect("refused");
    assert_eq!(first.code.to_string(), "lab::too-large");
}
