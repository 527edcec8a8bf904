//! AxiOMA PLC outputs G110/G111 (spec axioma-3 §5, manual 10): fixtures s10_* with the output
//! states of spec W.5, the queueing with the block's motion, and the errors of §5.3.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{Canon, DiagCode, Spanned};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;
use std::collections::BTreeMap;

fn fixture(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap()
}

/// Output image after the commands (all outputs 0 at power-on): index → state, and whether every
/// switching command is synchronised with motion.
fn outputs(cmds: &[Spanned<Canon>]) -> (BTreeMap<u32, bool>, bool) {
    let mut image = BTreeMap::new();
    let mut synced = true;
    for c in cmds {
        if let Canon::DigitalOutput {
            index,
            on,
            synchronised,
        } = c.value
        {
            image.insert(index, on);
            synced &= synchronised;
        }
    }
    (image, synced)
}

fn on_off(image: &BTreeMap<u32, bool>) -> (Vec<u32>, Vec<u32>) {
    let on = image.iter().filter(|e| *e.1).map(|e| *e.0).collect();
    let off = image.iter().filter(|e| !*e.1).map(|e| *e.0).collect();
    (on, off)
}

fn run_ok(name: &str) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run(&fixture(name), Dialect::Axioma);
    assert!(err.is_none(), "{name}: {err:?}");
    cmds
}

#[test]
fn example_10_1_sets_0_and_33_resets_22() {
    let (image, synced) = outputs(&run_ok("s10_1_3-g110-g111-example-10_1.nc"));
    assert!(synced);
    assert_eq!(on_off(&image), (vec![0, 33], vec![22]));
}

#[test]
fn example_10_2_outputs_with_rapid_moves() {
    let cmds = run_ok("s10_1_3-g110-g111-with-rapid-moves-example-10_2.nc");
    assert_eq!(on_off(&outputs(&cmds).0), (vec![13, 21], vec![26]));
    // Each output is queued before its block's rapid move (it switches with the start of it).
    let n20: Vec<&Canon> = cmds
        .iter()
        .filter(|c| c.block_number == Some(20))
        .map(|c| &c.value)
        .collect();
    assert!(matches!(
        n20[0],
        Canon::DigitalOutput {
            index: 26,
            on: false,
            ..
        }
    ));
    assert!(matches!(n20[1], Canon::StraightTraverse(m) if (m.end.x - 160.0).abs() < 1e-9));
    let last = cmds.iter().rev().find_map(|c| c.value.motion()).unwrap();
    let end = last.end();
    assert!((end.x - 160.0).abs() < 1e-9 && (end.y - 155.0).abs() < 1e-9);
}

#[test]
fn example_10_3_outputs_with_feed_moves_and_arcs() {
    let cmds = run_ok("s10_1_3-g110-g111-with-feed-moves-example-10_3.nc");
    assert_eq!(on_off(&outputs(&cmds).0), (vec![13, 22], vec![5, 21, 26]));
    // N40: output 5 on, then the CW semicircle to (0,0); the path is not broken (no dwell/stop).
    let n40: Vec<&Canon> = cmds
        .iter()
        .filter(|c| c.block_number == Some(40))
        .map(|c| &c.value)
        .collect();
    assert!(matches!(
        n40[0],
        Canon::DigitalOutput {
            index: 5,
            on: true,
            synchronised: true
        }
    ));
    assert!(matches!(n40[1], Canon::ArcFeed(a) if a.end.x.abs() < 1e-9 && a.end.y.abs() < 1e-9));
    assert!(!cmds
        .iter()
        .any(|c| matches!(c.value, Canon::Dwell { .. } | Canon::ProgramStop { .. })));
}

#[test]
fn example_10_4_alternating_blocks() {
    let (image, synced) = outputs(&run_ok("s10_1_3-g110-g111-alternating-example-10_4.nc"));
    assert!(synced);
    assert_eq!(
        on_off(&image),
        (vec![3, 4, 5, 13, 21, 22, 23, 35], vec![7, 8, 11, 26])
    );
}

#[test]
fn fragment_with_offset_in_a_second_n_word() {
    // Index = 8·offset + address: the bit number from the machine parameter's base (spec §5.3).
    let (image, _) = outputs(&run_ok("s10_1_1-g110-set-outputs-fragment.nc"));
    assert_eq!(
        on_off(&image),
        (vec![256000 * 8 + 6, 256000 * 8 + 7], vec![])
    );
    let (cmds, err) = run("G110 H2 Q1=3\nM30\n", Dialect::Axioma);
    assert!(err.is_none());
    assert_eq!(on_off(&outputs(&cmds).0), (vec![19], vec![]));
}

#[test]
fn invalid_output_words_are_errors_and_emit_nothing() {
    let cases: [(&str, &str); 6] = [
        ("G110 Q1=3 Q1=4\n", "axioma::output-index-repeated"),
        ("G110 Q33=3\n", "axioma::output-index"),
        ("G110 Q1=2.5\n", "interp::not-an-integer"),
        ("G110 Q1=-1\n", "interp::not-an-integer"),
        ("G110 Q1=64\n", "axioma::output-address-range"),
        ("G110 G111 Q1=1\n", "axioma::outputs-twice"),
    ];
    for (text, code) in cases {
        let (cmds, err) = run(&format!("G01 X1 F100\n{text}M30\n"), Dialect::Axioma);
        let err = err.unwrap_or_else(|| panic!("{text}: no error"));
        assert_eq!(err.code, DiagCode::Stanok(code), "{text}: {err}");
        assert!(!cmds
            .iter()
            .any(|c| matches!(c.value, Canon::DigitalOutput { .. })));
        assert!(cmds.iter().all(|c| c.span.line != 2), "{text}");
    }
    // The configured number of outputs bounds the addresses (Example 10.4: 40 outputs).
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.axioma.plc_outputs = 40;
    let (_, err) = run_with("G110 Q1=39\nG110 Q1=40\nM30\n", opts);
    assert_eq!(err.unwrap().span.line, 2);
}
