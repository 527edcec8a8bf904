//! Random RS274/NGC programs built from the whole vocabulary of the language issue — canned
//! cycles, G33/G76, probing, splines, cutter compensation, M70–M73, polar words, mode switches —
//! with random (often wrong) values:
//! * the interpreter never panics and always stops (an error is fine; a panic or hang is not);
//! * every motion it emits starts where the previous one ended (exceptions: G74/G84 in G18/G19,
//!   whose feeds LinuxCNC rotates — and a probe, M6 or M61 after one with no move between, which
//!   rereads the rotated point as the position —, and G88, whose retract is the operator's, as in
//!   LinuxCNC), and every coordinate is finite.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use stanok_canon::Canon;
use stanok_syntax::Dialect;

/// One block from the vocabulary, with `v` supplying the numbers.
fn block(kind: usize, v: &[f64; 6]) -> String {
    let [a, b, c, d, e, f] = *v;
    match kind {
        0 => format!("G0 X{a:.3} Y{b:.3} Z{c:.3}"),
        1 => format!("G1 X{a:.3} Y{b:.3} F{:.1}", d.abs() * 100.0 + 1.0),
        2 => format!("G2 X{a:.3} Y{b:.3} R{:.3}", c.abs() + 30.0),
        3 => format!("G3 X{a:.3} Y{b:.3} R{:.3}", e.abs() + 0.5),
        4 => format!(
            "G98 G81 X{a:.3} Y{b:.3} Z{:.3} R{:.3} F100",
            -c.abs(),
            d.abs()
        ),
        5 => format!(
            "G99 G83 X{a:.3} Z{:.3} R{:.3} Q{:.3} F100",
            -c.abs(),
            d.abs(),
            e.abs() + 0.05
        ),
        6 => format!(
            "G91 G73 X{a:.3} Z{:.3} R{:.3} Q{:.3} L{} F50",
            -c.abs(),
            d.abs(),
            e.abs() + 0.05,
            (f.abs() * 3.0) as u32 + 1
        ),
        7 => "G90 G80".to_string(),
        8 => "S500 M3".to_string(),
        9 => format!("G84 X{a:.3} Y{b:.3} Z{:.3} R{:.3} F100", -c.abs(), d.abs()),
        10 => format!("G86 X{a:.3} Z{:.3} R{:.3} P0.1 F100", -c.abs(), d.abs()),
        11 => format!(
            "G87 X{a:.3} Y{b:.3} Z{:.3} R{:.3} I0.2 J0.1 K{:.3} F100",
            -c.abs(),
            d.abs(),
            -c.abs() / 2.0
        ),
        12 => format!("G88 X{a:.3} Z{:.3} R{:.3} P0.1 F100", -c.abs(), d.abs()),
        13 => format!("G41 D{}", (f.abs() * 2.0) as u32 % 3),
        14 => format!("G42.1 D{:.3}", e.abs()),
        15 => "G40".to_string(),
        16 => format!("G38.2 Z{c:.3} F100"),
        17 => format!("G38.3 X{a:.3} F100"),
        18 => format!("G5 I{a:.3} J{b:.3} P{c:.3} Q{d:.3} X{e:.3} Y{f:.3} F100"),
        19 => format!("G5.1 X{a:.3} Y{b:.3} I{c:.3} J{d:.3} F100"),
        20 => format!(
            "G5.2 P1 L{}\nX{a:.3} Y{b:.3}\nX{c:.3} Y{d:.3} P{:.2}\nX{e:.3} Y{f:.3}\nG5.3",
            2 + (f.abs() as u32 % 3),
            e.abs() + 0.1
        ),
        21 => "M70".to_string(),
        22 => "M70\nG91 G20\nM72".to_string(),
        23 => "M71".to_string(),
        24 => format!("G18 G33 X{a:.3} Z{c:.3} K{:.3}", d.abs() + 0.1),
        25 => format!(
            "G18 G0 X{:.3} Z{:.3}\nG76 P0.1 Z{:.3} I-0.2 J0.05 K0.3 Q29 L{} E0.2",
            a.abs() + 1.0,
            c,
            c - 2.0,
            (f.abs() as u32) % 4
        ),
        26 => "G17".to_string(),
        27 => format!("G1 @{:.3} ^{:.3} F200", a.abs(), b * 30.0),
        28 => format!("G64 P{:.3} Q{:.3}", a.abs(), b.abs()),
        29 => "G61".to_string(),
        30 => format!("G96 S{:.1} D2000", a.abs() * 10.0 + 1.0),
        31 => "G97 S800".to_string(),
        32 => format!("G20 G91 G1 X{a:.3} F10"),
        33 => "G21 G90".to_string(),
        34 => format!("G33.1 Z{:.3} K0.05", -c.abs()),
        35 => "M62 P1\nM64 P2\nM48\nM50 P0".to_string(),
        _ => format!("M19 R{a:.1} P1"),
    }
}

fn program() -> impl Strategy<Value = String> {
    prop::collection::vec((0usize..37, prop::array::uniform6(-20.0f64..20.0)), 1..40).prop_map(
        |blocks| {
            let mut text = String::from("G21 G17 G90 F100\nT1 M6\nS500 M3\n");
            for (kind, v) in blocks {
                text.push_str(&block(kind, &v));
                text.push('\n');
            }
            text.push_str("M2\n");
            text
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn random_programs_never_panic_and_move_continuously(text in program()) {
        moves_continuously(&text)?;
    }
}

/// The continuity law of the module comment, on one program.
fn moves_continuously(text: &str) -> Result<(), TestCaseError> {
    let (cmds, _err) = run(text, Dialect::Rs274ngc);
    let mut prev: Option<[f64; 9]> = None;
    let mut after_g88 = false;
    // G74/G84 in G18/G19 feed to LinuxCNC's plane-rotated points (cycles.rs `tap_feed`):
    // jumps are allowed from the overrides' disabling to the first move after re-enabling.
    let mut plane_xy = true;
    let mut rotated_tap = false;
    // A rotated tap happened, and a probe or tool change may reread its point (lib.rs
    // `TapApart`); `reread`: an M6/M61 asked for it before the next motion.
    let mut apart = false;
    let mut reread = false;
    for c in &cmds {
        if let Canon::ProgramStop { .. } = c.value {
            // G88 stops for the operator, who retracts by hand.
            after_g88 = true;
        }
        match c.value {
            Canon::SelectPlane { plane } => plane_xy = plane == stanok_canon::Plane::XY,
            Canon::SetFeedOverrideEnabled { enabled: false } if !plane_xy => {
                rotated_tap = true;
                apart = true;
            }
            Canon::ChangeTool { .. } | Canon::SetCurrentTool { .. } if apart => reread = true,
            Canon::SetFeedOverrideEnabled { enabled: true } if rotated_tap => {
                after_g88 = true;
                rotated_tap = false;
            }
            _ => {}
        }
        if rotated_tap {
            after_g88 = true;
        }
        let Some(m) = c.value.motion() else { continue };
        if apart && (reread || matches!(c.value, Canon::StraightProbe { .. })) {
            after_g88 = true;
            reread = false;
        }
        let (s, e) = (m.start().to_array(), m.end().to_array());
        prop_assert!(s.iter().chain(e.iter()).all(|x| x.is_finite()), "{}", text);
        if let Some(p) = prev {
            let jump = (0..9).map(|k| (p[k] - s[k]).abs()).fold(0.0, f64::max);
            prop_assert!(
                after_g88 || jump < 1e-6,
                "jump {jump} before {:?}\n{text}",
                c.value
            );
        }
        after_g88 = false;
        prev = Some(e);
    }
    Ok(())
}

/// The soup's shrunk case (found by the parity helper): a rigid tap after a G84 in G18 leaves
/// the position where the G84 believed it, and the probe after it rereads the rotated point, as
/// rs274 does (its trace is the same: `STRAIGHT_PROBE(1.0000, 2.0000, -5.0000, …)` after
/// `RIGID_TAP(1.0000, 2.0000, -2.0000)`).
#[test]
fn a_probe_after_a_rotated_tap_may_start_from_the_rotated_point() {
    let text = "G21 G17 G90 F100\nT1 M6\nS500 M3\nG18 G33 X1 Z-2 K1\nG84 X1 Y2 Z-3 R2 F100\n\
                G33.1 Z-2 K0.05\nG38.2 Z-5 F100\nM2\n";
    moves_continuously(text).unwrap();
}
