//! Property tests of the RS274/NGC coordinate chain (spec rs274ngc §3.1):
//! `machine = Rz(R)·(p + g92) + g5x + tlo` and its inverse, through the interpreter — random G54
//! origin and rotation (G10 L2), G52/G92 vector, tool length offset (G43.1) and point:
//! * the machine end point of `G0` is the forward chain, computed here independently;
//! * the program position the interpreter derives back from the machine (what `#5420…` read, what
//!   the LinuxCNC printer re-expresses) is the programmed point;
//! * G92, G10 L20 and G49 change that program position as the spec says and never move the machine.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use proptest::prelude::*;
use stanok_canon::Canon;
use stanok_interp::Interpreter;
use stanok_syntax::Dialect;

/// The spec's forward chain for X, Y, Z.
fn forward(p: [f64; 3], g5x: [f64; 3], r_deg: f64, g92: [f64; 3], tlo: [f64; 3]) -> [f64; 3] {
    let (s, c) = r_deg.to_radians().sin_cos();
    let q = [p[0] + g92[0], p[1] + g92[1], p[2] + g92[2]];
    [
        q[0] * c - q[1] * s + g5x[0] + tlo[0],
        q[0] * s + q[1] * c + g5x[1] + tlo[1],
        q[2] + g5x[2] + tlo[2],
    ]
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

fn v3() -> impl Strategy<Value = [f64; 3]> {
    prop::array::uniform3(-200.0f64..200.0)
}

/// Runs `text` and returns the interpreter's final state: (machine, program) X Y Z.
fn final_state(text: &str) -> ([f64; 3], [f64; 3]) {
    let mut it = Interpreter::from_text(text, options(Dialect::Rs274ngc));
    for c in it.by_ref() {
        if let Err(d) = c {
            panic!("{d}\n{text}");
        }
    }
    let st = it.state();
    (st.position.xyz(), st.program_position().xyz())
}

fn fmt3(letters: &str, v: [f64; 3]) -> String {
    letters
        .chars()
        .zip(v)
        .map(|(l, x)| format!("{l}{x:.6}"))
        .collect::<Vec<_>>()
        .join(" ")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]

    #[test]
    fn chain_then_inverse_returns_the_point(
        g5x in v3(), r in -360.0f64..360.0, g92 in v3(), tlo in v3(), p in v3(),
    ) {
        // Values go through the text with six decimals: use the rounded ones.
        let round = |v: [f64; 3]| v.map(|x| (x * 1e6).round() / 1e6);
        let (g5x, g92, tlo, p) = (round(g5x), round(g92), round(tlo), round(p));
        let r = (r * 1e6).round() / 1e6;
        let text = format!(
            "G21\nG10 L2 P1 {} R{r:.6}\nG52 {}\nG43.1 {}\nG0 {}\nM2\n",
            fmt3("XYZ", g5x), fmt3("XYZ", g92), fmt3("XYZ", tlo), fmt3("XYZ", p)
        );
        let (cmds, err) = run(&text, Dialect::Rs274ngc);
        prop_assert!(err.is_none(), "{err:?}");
        let end = cmds.iter().find_map(|c| match &c.value {
            Canon::StraightTraverse(m) => Some(m.end.xyz()),
            _ => None,
        }).unwrap();
        prop_assert!(close(end, forward(p, g5x, r, g92, tlo), 1e-9), "{end:?}");
        // Back through the interpreter's inverse (before M2 resets the system: stop there).
        let text = text.replace("M2\n", "%\n");
        let text = format!("%\n{text}");
        let (machine, program) = final_state(&text);
        prop_assert!(close(machine, end, 1e-9));
        prop_assert!(close(program, p, 1e-7), "{program:?} vs {p:?}");
    }

    #[test]
    fn g92_g10_l20_and_g49_change_the_reading_not_the_machine(
        g5x in v3(), r in -180.0f64..180.0, tlo in v3(), p in v3(), q in v3(), w in v3(),
    ) {
        let round = |v: [f64; 3]| v.map(|x| (x * 1e4).round() / 1e4);
        let (g5x, tlo, p, q, w) = (round(g5x), round(tlo), round(p), round(q), round(w));
        let r = (r * 1e4).round() / 1e4;
        let head = format!(
            "%\nG21\nG10 L2 P1 {} R{r:.4}\nG43.1 {}\nG0 {}\n",
            fmt3("XYZ", g5x), fmt3("XYZ", tlo), fmt3("XYZ", p)
        );
        let (m0, p0) = final_state(&format!("{head}%\n"));
        prop_assert!(close(p0, p, 1e-7));
        // G92: the current point reads q.
        let (m1, p1) = final_state(&format!("{head}G92 {}\n%\n", fmt3("XYZ", q)));
        prop_assert!(close(m1, m0, 1e-12));
        prop_assert!(close(p1, q, 1e-7), "{p1:?} vs {q:?}");
        // G10 L20 on the active system: the current point reads w.
        let (m2, p2) = final_state(&format!("{head}G10 L20 P1 {}\n%\n", fmt3("XYZ", w)));
        prop_assert!(close(m2, m0, 1e-12));
        prop_assert!(close(p2, w, 1e-7), "{p2:?} vs {w:?}");
        // G49: the reading grows by the offset taken away (rotated into the program frame).
        let (m3, p3) = final_state(&format!("{head}G49\n%\n"));
        prop_assert!(close(m3, m0, 1e-12));
        let (s, c) = (-r).to_radians().sin_cos();
        let d = [tlo[0] * c - tlo[1] * s, tlo[0] * s + tlo[1] * c, tlo[2]];
        prop_assert!(close(p3, [p[0] + d[0], p[1] + d[1], p[2] + d[2]], 1e-7), "{p3:?}");
    }
}

#[test]
fn the_chain_matches_a_hand_computed_point() {
    // G54 origin (10, 5, 0) rotated 90°, G52 (1, 0, 0), tool offset Z −2: program (1, 2, 3) →
    // rotate (2, 2) by 90° = (−2, 2) → + origin = (8, 7); Z 3 − 2 = 1.
    let (machine, program) =
        final_state("%\nG21\nG10 L2 P1 X10 Y5 R90\nG52 X1\nG43.1 Z-2\nG0 X1 Y2 Z3\n%\n");
    assert!(close(machine, [8.0, 7.0, 1.0], 1e-9), "{machine:?}");
    assert!(close(program, [1.0, 2.0, 3.0], 1e-9), "{program:?}");
}
