//! Custom macro B and subprograms (`docs/dialects/mazatrol-eia.md` §14, §15): variables, vacant,
//! control statements, calls, alarms, messages, system variables, the refusals.

mod common;
use common::*;
use stanok_canon::Canon;

fn xs(r: &Run) -> Vec<f64> {
    r.ends().iter().map(|p| p.x).collect()
}

fn err(text: &str) -> stanok_canon::Diagnostic {
    run(text, &mill()).error.expect("an error")
}

#[test]
fn assignments_and_vacant_words() {
    // #1 vacant: X#1 is dropped (Y still moves); #2 = #1 stays vacant; #3 = #1 * 5 is 0.
    let r = run(
        "G00 X7. Y0\n#2 = #1\n#3 = #1 * 5\nX#1 Y1.\nX#2 Y2.\nX#3 Y3.\n#4 = 1 #5 = #4 + 1\nX#5\n",
        &mill(),
    );
    r.ok();
    assert_eq!(xs(&r), vec![7.0, 7.0, 7.0, 0.0, 2.0]);
}

#[test]
fn goto_if_and_while() {
    // Sum 1 … 10 with WHILE, then move X to it; a GOTO skips a block.
    let text = "#1 = 0\n#2 = 1\nWHILE [#2 LE 10] DO 1\n#1 = #1 + #2\n#2 = #2 + 1\nEND 1\nG00 X#1\nGOTO 20\nX999.\nN20 IF [#1 EQ 55] GOTO 30\nX888.\nN30 IF [#1 GT 50] THEN #3 = 7\nY#3\nM30\n";
    let r = run(text, &mill());
    r.ok();
    let e = r.ends();
    assert_eq!(e[0].x, 55.0);
    assert_eq!(e.len(), 2, "{e:?}");
    assert_eq!(e[1].y, 7.0);
    // DO without WHILE, left by a GOTO.
    let r = run(
        "#1 = 0\nDO 1\n#1 = #1 + 1\nIF [#1 GE 3] GOTO 9\nEND 1\nN9 G00 X#1\n",
        &mill(),
    );
    r.ok();
    assert_eq!(xs(&r), vec![3.0]);
    // Nested loops with different numbers; the inner loop is entered again each outer pass.
    let text = "#1 = 0\n#10 = 0\nWHILE [#10 LT 3] DO 1\n#11 = 0\nWHILE [#11 LT 4] DO 2\n#1 = #1 + 1\n#11 = #11 + 1\nEND 2\n#10 = #10 + 1\nEND 1\nG00 X#1\n";
    let r = run(text, &mill());
    r.ok();
    assert_eq!(xs(&r), vec![12.0]);
}

#[test]
fn control_flow_refusals() {
    let e = err("GOTO 120\nN10 M30\n");
    assert_eq!(e.code.to_string(), "mazatrol::goto-target");
    assert_eq!(e.message, "GOTO 120: no block N120 in this program");
    let e = err("WHILE [1 EQ 1] DO 1\nM30\n");
    assert_eq!(e.code.to_string(), "mazatrol::loop-mismatch");
    assert_eq!(e.message, "DO 1 has no END 1 in this program");
    assert_eq!(err("END 2\n").code.to_string(), "mazatrol::loop-mismatch");
    assert_eq!(
        err("DO 128\nEND 128\n").code.to_string(),
        "mazatrol::loop-number"
    );
    // 28 nested loops.
    let mut text = String::new();
    for i in 1..=28 {
        text.push_str(&format!("DO {i}\n"));
    }
    for i in (1..=28).rev() {
        text.push_str(&format!("END {i}\n"));
    }
    let e = err(&text);
    assert_eq!(e.code.to_string(), "mazatrol::loop-nesting");
    assert_eq!(e.message, "WHILE … DO loops nested deeper than 27");
    assert_eq!(e.span.line, 28);
    // An endless loop stops at the iteration limit.
    let mut m = mill();
    m.opts.max_loop_iterations = 1000;
    let e = run("DO 1\nEND 1\n", &m).error.unwrap();
    assert_eq!(e.code.to_string(), "interp::loop-limit");
    // Bad expressions stop at their block.
    let e = err("G00 X1.\n#1 = SQRT[-4]\nG00 X2.\n");
    assert_eq!(e.code.to_string(), "mazatrol::bad-argument");
    assert_eq!(e.span.line, 2);
    assert_eq!(
        err("#1 = 1 / 0\n").code.to_string(),
        "mazatrol::division-by-zero"
    );
    assert_eq!(
        err("#34 = 1\n").code.to_string(),
        "mazatrol::variable-range"
    );
    assert_eq!(
        err("#0 = 1\n").code.to_string(),
        "mazatrol::read-only-variable"
    );
    assert_eq!(
        err("#5001 = 1\n").code.to_string(),
        "mazatrol::read-only-variable"
    );
}

#[test]
fn alarms_and_messages() {
    let r = run("G00 X1.\n#3000 = 12 (TOOL BROKEN)\nG00 X2.\n", &mill());
    let e = r.error.clone().unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::macro-alarm");
    assert_eq!(e.message, "MACRO ALARM 3012: TOOL BROKEN");
    assert_eq!(e.span.line, 2);
    assert_eq!(xs(&r), vec![1.0], "nothing after the alarm");
    let r = run("#3006 = 1 (CHECK THE PART)\nM30\n", &mill());
    r.ok();
    let v: Vec<&Canon> = r.canon.iter().map(|c| &c.value).collect();
    assert!(v.iter().any(|c| **c
        == Canon::Message {
            text: "CHECK THE PART".into()
        }));
    assert!(v.contains(&&Canon::ProgramStop { optional: false }));
}

#[test]
fn g65_arguments_and_levels() {
    // A→#1, B→#2, X→#24; the caller's #1 is back after M99.
    let text = "#1 = 100\nG65 P9100 A1. B2. X3.\nG00 X#1\nM30\nO9100\nG00 X#1\nY#2\nZ#24\n#100 = #5\nM99\n";
    let r = run(text, &mill());
    r.ok();
    let e = r.ends();
    assert_eq!(e[0].x, 1.0);
    assert_eq!(e[1].y, 2.0);
    assert_eq!(e[2].z, 3.0);
    assert_eq!(e[3].x, 100.0);
    // L repeats.
    let r = run(
        "#100 = 0\nG65 P9100 L3\nG00 X#100\nM30\nO9100\n#100 = #100 + 1\nM99\n",
        &mill(),
    );
    r.ok();
    assert_eq!(xs(&r), vec![3.0]);
    // Five levels: the fifth call is refused.
    let text = "G65 P1 A0\nM30\nO1\nG65 P1 A[#1+1]\nM99\n";
    let e = err(text);
    assert_eq!(e.code.to_string(), "mazatrol::call-nesting");
    assert_eq!(e.message, "macro calls nested deeper than 4");
    // Other G codes in a G65 block.
    let e = err("G65 G01 P1\nM30\nO1\nM99\n");
    assert_eq!(e.code.to_string(), "mazatrol::macro-call");
}

#[test]
fn g66_calls_after_each_move() {
    // The macro records where it was called: #100 counts, #101 sums X.
    let text = "#100 = 0\n#101 = 0\nG66 P9200 A1.\nG00 X1.\nX2.\nG67\nX3.\nG00 Y#100 Z#101\nM30\nO9200\n#100 = #100 + #1\n#101 = #101 + #5001\nM99\n";
    let r = run(text, &mill());
    r.ok();
    let last = *r.ends().last().unwrap();
    assert_eq!((last.y, last.z), (2.0, 3.0));
    // G66.1: each block is a call with its words as arguments; it does not move itself.
    let text =
        "#100 = 0\nG66.1 P9300\nX5.\nX7.\nG67\nG00 Y#100\nM30\nO9300\n#100 = #100 + #24\nM99\n";
    let r = run(text, &mill());
    r.ok();
    assert_eq!(r.ends().len(), 1);
    assert_eq!(r.ends()[0].y, 12.0);
}

#[test]
fn subprograms() {
    // M98 P L and a return to a sequence number of the caller.
    let text = "#100 = 0\nM98 P1000 L3\nG00 X#100\nM98 P1001\nX111.\nN50 Y5.\nM30\nO1000\n#100 = #100 + 1\nM99\nO1001\nM99 P50\n";
    let r = run(text, &mill());
    r.ok();
    let e = r.ends();
    assert_eq!(e[0].x, 3.0);
    assert_eq!(e.len(), 2, "X111. is skipped by M99 P50: {e:?}");
    assert_eq!(e[1].y, 5.0);
    // H: start at a sequence number of the subprogram.
    let r = run(
        "M98 P1000 H20\nM30\nO1000\nG00 X1.\nN20 X2.\nM99\n",
        &mill(),
    );
    r.ok();
    assert_eq!(xs(&r), vec![2.0]);
    // Refusals.
    let e = err("M99\n");
    assert_eq!(e.code.to_string(), "mazatrol::m99-without-caller");
    assert_eq!(e.message, "M99 without a caller: this is the main program");
    let e = err("M98 P4444\n");
    assert_eq!(e.code.to_string(), "mazatrol::program-not-found");
    assert_eq!(
        e.message,
        "program O4444 is in neither this file nor --subroutine-path"
    );
    let e = err("M98 P1000 H7\nM30\nO1000\nM99\n");
    assert_eq!(e.code.to_string(), "mazatrol::sequence-not-found");
    let e = err("M98 P1\nM30\nO1\nM98 P1\nM99\n");
    assert_eq!(e.code.to_string(), "mazatrol::call-nesting");
    assert_eq!(e.message, "subprogram calls nested deeper than 8");
}

#[test]
fn subprogram_files_on_the_path() {
    let dir = std::env::temp_dir().join(format!("stanok-mazatrol-sub-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("O2000.nc"),
        "O2000 (DRILL)\nG00 X#24\n#100 = #100 + 1\nM99\n",
    )
    .unwrap();
    std::fs::write(dir.join("O2001"), "G00 Y9.\nM99\n").unwrap();
    let mut m = mill();
    m.opts.subroutine_path = vec![dir.clone()];
    let r = run(
        "#100 = 0\n#24 = 4.\nM98 P2000 L2\nM98 P2001\nG00 Z#100\nM30\n",
        &m,
    );
    r.ok();
    let e = r.ends();
    assert_eq!(e[0].x, 4.0);
    assert_eq!(e.last().unwrap().z, 2.0);
    assert!(e.iter().any(|p| p.y == 9.0));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn system_variables() {
    let m = mazak_m();
    // #5001…: the block end in work coordinates; #5021…: machine; #5221…: G54; #2201: length H1.
    let text = "G00 X10. Y20. Z30.\n#1 = #5001\n#2 = #5022\n#3 = #5223\n#4 = #2201\n#5 = #4001\n#6 = #4003\nG91 G00 X#1 Y#2 Z#3\nG90 X#4\nY#5\nZ#6\n";
    let r = run(text, &m);
    r.ok();
    let e = r.ends();
    // Increments: X +10, Y +70 (machine Y 70), Z −200 (the G54 Z).
    assert_eq!((e[1].x, e[1].y, e[1].z), (120.0, 140.0, -370.0));
    assert_eq!(e[2].x, 250.0, "X150: the length of tool 1");
    assert_eq!(e[3].y, 50.0, "#4001 = 0 (G00)");
    assert_eq!(e[4].z, -200.0 + 90.0, "#4003 = 90");
    // Writing #5221 moves the G54 origin at once.
    let r = run("#5221 = 0\n#5222 = 0\n#5223 = 0\nG00 X1. Y1. Z1.\n", &m);
    r.ok();
    assert_eq!(r.ends()[0].x, 1.0);
    // Tool offsets by variable: #2201 = 50 is tool 1's length.
    let r = run("#2201 = 50.\nG00 Z0\nG43 H1 Z0\n", &m);
    r.ok();
    assert_eq!(r.ends().last().unwrap().z, -150.0);
    // Clocks are refused.
    let e = run("#1 = #3001\n", &m).error.unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::not-simulated");
}

#[test]
fn non_volatile_variables_persist() {
    use stanok_interp_core::{Driver, ModalState};
    use stanok_mazatrol::Mazatrol;
    let mut m = mill();
    m.opts.control.perm_double.insert(500, 2.5);
    let text = "#501 = #500 * 2\n#100 = 1\nM30\n";
    let mut state = ModalState::power_on(&m.opts);
    let fe = Mazatrol::new(&m.opts, m.params.clone(), &mut state);
    let mut d = Driver::new(
        std::io::Cursor::new(text.as_bytes()),
        m.opts.clone(),
        state,
        fe,
    );
    for c in d.by_ref() {
        c.unwrap();
    }
    let stored = d.front_end().stored_variables();
    assert_eq!(stored.get(&500), Some(&2.5));
    assert_eq!(stored.get(&501), Some(&5.0));
    assert_eq!(stored.get(&100), None);
}

#[test]
fn a_failing_block_leaves_nothing() {
    use stanok_interp_core::{Driver, ModalState};
    use stanok_mazatrol::Mazatrol;
    let m = mazak_m();
    let mut opts = m.opts.clone();
    opts.continue_after_error = true;
    // Each second block changes state, then fails; the third reads it back.
    for (change, probe) in [
        ("#1 = 5 #2 = 1/0", "#500 = #1"),
        ("G10 L2 P1 X1. G123", "#500 = #5221"),
        ("G52 X5. Q1.", "#500 = #5001"),
        ("G91 G01 X1. G123", "#500 = #4003"),
        ("G51 X0 Y0 P2. G123", "#500 = #4011"),
        ("#2201 = 1. #2 = SQRT[-1]", "#500 = #2201"),
    ] {
        let text = format!("#1 = 0\n{change}\n{probe}\nM30\n");
        let mut state = ModalState::power_on(&opts);
        let fe = Mazatrol::new(&opts, m.params.clone(), &mut state);
        let mut d = Driver::new(
            std::io::Cursor::new(text.into_bytes()),
            opts.clone(),
            state,
            fe,
        );
        let mut errors = 0;
        for c in d.by_ref() {
            if c.is_err() {
                errors += 1;
            }
        }
        assert_eq!(errors, 1, "{change}");
        let v = d.front_end().variable(500);
        let want = match probe {
            "#500 = #1" => Some(0.0),
            "#500 = #5221" => Some(100.0),
            "#500 = #5001" => Some(-100.0),
            "#500 = #4003" => Some(90.0),
            "#500 = #4011" => Some(50.0),
            _ => Some(150.0),
        };
        assert_eq!(v, want, "{change}");
    }
}
