//! The AxiOMA M-function model (spec axioma-2 §4, §5) on the corpus fixtures s7* and s8_*: the
//! order of prefix and postfix functions within a block, the words that travel with them, the
//! spindle functions of spindles 1–4, and the M vector of the generic and the BeaverMill profile.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{AuxTiming, Canon, Spanned, SpindleDirection};
use stanok_interp::{InterpOptions, Interpreter, MTable};
use stanok_syntax::Dialect;

fn program(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn opts(table: MTable) -> InterpOptions {
    let mut o = options(Dialect::Axioma);
    o.axioma.m_table = table;
    o
}

fn run_ok(text: &str, table: MTable) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run_with(text, opts(table));
    assert!(err.is_none(), "unexpected error {err:?}");
    cmds
}

/// The commands as short names, in stream order (state items that every block may carry left out).
fn names(cmds: &[Spanned<Canon>]) -> Vec<String> {
    cmds.iter()
        .filter_map(|c| {
            Some(match &c.value {
                Canon::SetSpindleSpeed { spindle, rpm } => format!("S{}={rpm}", spindle + 1),
                Canon::StartSpindle { spindle, direction } => format!(
                    "spindle{} {}",
                    spindle + 1,
                    match direction {
                        SpindleDirection::Clockwise => "cw",
                        SpindleDirection::CounterClockwise => "ccw",
                    }
                ),
                Canon::StopSpindle { spindle } => format!("spindle{} stop", spindle + 1),
                Canon::OrientSpindle {
                    spindle, degrees, ..
                } => format!("spindle{} orient {degrees}", spindle + 1),
                Canon::Flood { on } => format!("flood {}", if *on { "on" } else { "off" }),
                Canon::Mist { on } => format!("mist {}", if *on { "on" } else { "off" }),
                Canon::SelectTool { tool } => format!("T{tool}"),
                Canon::ChangeTool { tool, .. } => format!("M6 T{tool}"),
                Canon::ChangeSpindleTool { spindle, tool } => format!("M6 T{}={tool}", spindle + 1),
                Canon::AuxiliaryFunction { number, timing } => format!(
                    "M{number} {}",
                    match timing {
                        AuxTiming::Prefix => "prefix",
                        AuxTiming::Postfix => "postfix",
                    }
                ),
                Canon::ProgramStop { optional } => {
                    format!("stop{}", if *optional { " optional" } else { "" })
                }
                Canon::ProgramEnd => "end".into(),
                Canon::Dwell { seconds } => format!("dwell {seconds}"),
                Canon::StraightTraverse(_) | Canon::StraightFeed(_) => "move".into(),
                _ => return None,
            })
        })
        .collect()
}

/// The M vector after the program's lines up to and including the one labelled `N<n>`.
fn m_vector_after(text: &str, n: u32, table: MTable) -> Vec<(String, u32)> {
    let mut kept = String::new();
    for line in text.lines() {
        kept.push_str(line);
        kept.push('\n');
        if line.starts_with(&format!("N{n} ")) {
            break;
        }
    }
    let mut it = Interpreter::from_text(&kept, opts(table));
    for item in it.by_ref() {
        item.unwrap_or_else(|e| panic!("N{n}: {e}"));
    }
    it.axioma_m_vector()
}

fn shown(vector: &[(String, u32)], group: &str) -> u32 {
    vector
        .iter()
        .find(|(g, _)| g == group)
        .unwrap_or_else(|| panic!("no group {group} in {vector:?}"))
        .1
}

// ---------------------------------------------------------------------------------------- §7 order

#[test]
fn s7_order_in_separate_blocks_is_program_order() {
    let cmds = run_ok(
        &program("s7-mfunction-order-separate-blocks-fragment.nc"),
        MTable::generic(),
    );
    assert_eq!(
        names(&cmds),
        [
            "mist off",
            "flood off",
            "T2",
            "M6 T2",
            "S1=500",
            "spindle1 cw",
            "mist on"
        ]
    );
}

#[test]
fn s7_order_in_one_block_is_prefix_by_group_then_postfix() {
    // Manual: 1) M3 S500 (prefix, group 1) 2) M7 (prefix, group 2) 3) M6 T2 (prefix, group 3)
    // 4) M9 (postfix, group 2). Final: spindle on, T2, coolant off.
    let text = program("s7-mfunction-order-single-block-fragment.nc");
    let cmds = run_ok(&text, MTable::generic());
    assert_eq!(
        names(&cmds),
        [
            "S1=500",
            "spindle1 cw",
            "mist on",
            "T2",
            "M6 T2",
            "mist off",
            "flood off"
        ]
    );
    let mut it = Interpreter::from_text(&text, opts(MTable::generic()));
    for c in it.by_ref() {
        c.unwrap();
    }
    let st = it.state();
    assert!(st.spindle_on[0] && st.spindle_speed[0] == 500.0);
    assert_eq!(st.current_tool, 2);
    assert!(!st.mist && !st.flood);
    let v = it.axioma_m_vector();
    assert_eq!(shown(&v, "M_SpnCtrl"), 3);
    assert_eq!(shown(&v, "M_Ctrl"), 9);
}

// ---------------------------------------------------------------------------------------- §7.3

#[test]
fn s7_3_spindle_syntax_s_is_speed_except_with_m19() {
    let text = program("s7_3-spindle-syntax-examples.nc");
    let mut it = Interpreter::from_text(&text, opts(MTable::generic()));
    let cmds: Vec<_> = it.by_ref().map(|c| c.unwrap()).collect();
    assert_eq!(
        names(&cmds),
        [
            "S1=2500",
            "spindle1 cw",
            "S1=2500",
            "flood on",
            "spindle1 cw",
            "spindle1 orient 90"
        ]
    );
    // The angle does not overwrite the stored speed (PROPOSAL §4.3).
    assert_eq!(it.state().spindle_speed[0], 2500.0);
}

#[test]
fn s7_3_two_spindles_in_one_block_then_m30() {
    let cmds = run_ok(
        &program("s7_3-spindle-on-two-spindles-example-7_1.nc"),
        MTable::generic(),
    );
    assert_eq!(
        names(&cmds),
        [
            "S1=2500",
            "spindle1 cw",
            "S2=3000",
            "spindle2 cw",
            "spindle1 stop",
            "spindle2 stop",
            "end"
        ]
    );
}

#[test]
fn s7_3_separate_blocks_spindle2_counter_clockwise() {
    let cmds = run_ok(
        &program("s7_3-spindle-on-separate-blocks-example-7_2.nc"),
        MTable::generic(),
    );
    assert_eq!(
        names(&cmds),
        [
            "S1=2500",
            "spindle1 cw",
            "S2=3000",
            "spindle2 ccw",
            "spindle1 stop",
            "spindle2 stop",
            "end"
        ]
    );
}

#[test]
fn s7_3_spindle_off_examples() {
    let one = run_ok(
        &program("s7_3-spindle-off-example-7_3.nc"),
        MTable::generic(),
    );
    assert_eq!(names(&one), ["spindle1 stop", "end"]);
    let two = run_ok(
        &program("s7_3-spindle-off-two-spindles-example-7_4.nc"),
        MTable::generic(),
    );
    assert_eq!(names(&two), ["spindle1 stop", "spindle2 stop", "end"]);
}

#[test]
fn s7_3_coolant_and_spindle() {
    let both = run_ok(
        &program("s7_3-coolant-and-spindle-on-example-7_5.nc"),
        MTable::generic(),
    );
    assert_eq!(
        names(&both),
        [
            "S1=2500",
            "flood on",
            "spindle1 cw",
            "S2=3000",
            "flood on",
            "spindle2 cw",
            "spindle1 stop",
            "spindle2 stop",
            "flood off",
            "end"
        ]
    );
    let separate = run_ok(
        &program("s7_3-coolant-and-spindle-separate-blocks-example-7_6.nc"),
        MTable::generic(),
    );
    assert_eq!(
        names(&separate),
        [
            "S1=2500",
            "flood on",
            "spindle1 cw",
            "S2=3000",
            "flood on",
            "spindle2 ccw",
            "spindle1 stop",
            "spindle2 stop",
            "flood off",
            "end"
        ]
    );
}

#[test]
fn s7_3_orientation_of_two_spindles() {
    let cmds = run_ok(
        &program("s7_3-spindle-orientation-m19-example-7_7.nc"),
        MTable::generic(),
    );
    assert_eq!(
        names(&cmds),
        [
            "spindle1 orient 90",
            "spindle2 orient 180",
            "spindle2 stop",
            "end"
        ]
    );
    // Without an encoder M19 is refused (PROPOSAL §4.3).
    let mut o = opts(MTable::generic());
    o.axioma.spindle_encoder = false;
    let (_, err) = run_with("M19 S90\n", o);
    assert_eq!(
        err.unwrap().code.to_string(),
        "axioma::orient-without-encoder"
    );
}

// ---------------------------------------------------------------------------------------- §7.4, §7.5, §7.7

#[test]
fn s7_4_axis_mode_functions() {
    for (name, want) in [
        ("s7_4-m70-axis-mode-fragment.nc", "M70 prefix"),
        ("s7_4-m902-axis-mode-fragment.nc", "M902 prefix"),
        ("s7_4-m903-spindle-mode-fragment.nc", "M903 postfix"),
    ] {
        let cmds = run_ok(&program(name), MTable::generic());
        assert_eq!(names(&cmds), [want], "{name}");
    }
    let (_, err) = run("M902 H1=5\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "axioma::spindle-number");
    let (_, err) = run("M903\n", Dialect::Axioma);
    assert_eq!(
        err.unwrap().code.to_string(),
        "axioma::spindle-number-missing"
    );
}

#[test]
fn s7_5_m905_is_a_postfix_function() {
    let cmds = run_ok(
        &program("s7_5-m905-compensation-depth-fragment.nc"),
        MTable::generic(),
    );
    let n = names(&cmds);
    assert_eq!(n.first().map(String::as_str), Some("M905 postfix"));
    assert_eq!(n.last().map(String::as_str), Some("M905 postfix"));
}

#[test]
fn s7_7_tool_change_in_two_spindles() {
    let cmds = run_ok(
        &program("s7_7-automatic-tool-change-two-spindles-example-7_8.nc"),
        MTable::generic(),
    );
    let changes: Vec<String> = names(&cmds)
        .into_iter()
        .filter(|n| n.starts_with("M6"))
        .collect();
    assert_eq!(
        changes,
        ["M6 T1", "M6 T2=2", "M6 T2", "M6 T2=3", "M6 T0", "M6 T2=0"]
    );
}

#[test]
fn m00_always_stops_m01_only_with_the_switch() {
    let (cmds, _) = run("M00\nM01\nM30\n", Dialect::Axioma);
    assert_eq!(names(&cmds), ["stop", "stop optional", "end"]);
    let mut o = options(Dialect::Axioma);
    o.optional_stop = false;
    let (cmds, _) = run_with("M00\nM01\nM30\n", o);
    assert_eq!(names(&cmds), ["stop", "end"]);
}

#[test]
fn m99_moves_to_the_configured_waiting_position() {
    let mut o = options(Dialect::Axioma);
    o.axioma.m_table.waiting_position = Some(2);
    o.control.offsets.home[1] = Some(stanok_canon::Pose::default().with_xyz([100.0, 50.0, 20.0]));
    let (cmds, err) = run_with("G01 X10 F100\nM99\n", o);
    assert!(err.is_none());
    let last_move = cmds
        .iter()
        .rev()
        .filter_map(|c| match &c.value {
            Canon::StraightTraverse(m) => Some(m.end.xyz()),
            _ => None,
        })
        .next()
        .unwrap();
    assert_eq!(last_move, [100.0, 50.0, 20.0]);
    assert_eq!(names(&cmds).last().map(String::as_str), Some("end"));
}

#[test]
fn generic_m_vector_defaults() {
    let mut it = Interpreter::from_text("G01 X1 F1\n", opts(MTable::generic()));
    for c in it.by_ref() {
        c.unwrap();
    }
    let v = it.axioma_m_vector();
    for (group, m) in [
        ("M_SpnCtrl", 5),
        ("M_Spn2Ctrl", 205),
        ("M_Spn3Ctrl", 305),
        ("M_Spn4Ctrl", 405),
        ("M_Ctrl", 9),
        ("M_ClampLock", 22),
        ("M_ChipConveyorCtrl", 51),
        ("M_SafeguardCtrl", 55),
        ("M_BatchProbe", 911),
    ] {
        assert_eq!(shown(&v, group), m, "{group}");
    }
}

// ---------------------------------------------------------------------------------------- §8 BeaverMill

#[test]
fn s8_1_beavermill_is_configuration_not_code() {
    // The generic table has no M10/M73/M115: the BeaverMill programs are refused there.
    for name in [
        "s8_1-beavermill-coolant-m7-m710-example.nc",
        "s8_1-beavermill-probe-switch-m73-m75-example.nc",
        "s8_1-beavermill-rotary-table-clamp-m115-m123-example.nc",
    ] {
        let (_, err) = run_with(&program(name), opts(MTable::generic()));
        assert_eq!(
            err.map(|e| e.code.to_string()),
            Some("axioma::unknown-m-function".into()),
            "{name}"
        );
        run_ok(&program(name), MTable::beavermill());
    }
}

#[test]
fn s8_1_beavermill_coolant_group() {
    let text = program("s8_1-beavermill-coolant-m7-m710-example.nc");
    for (n, m) in [
        (10, 7),
        (30, 8),
        (50, 9),
        (70, 10),
        (90, 708),
        (110, 710),
        (130, 9),
    ] {
        let v = m_vector_after(&text, n, MTable::beavermill());
        assert_eq!(shown(&v, "M_Cool_AirCool"), m, "N{n}");
    }
    // M7 … M710 are prefix, M9 postfix; M30 switches all cooling off as M9 does.
    let cmds = run_ok(&text, MTable::beavermill());
    let aux: Vec<String> = names(&cmds)
        .into_iter()
        .filter(|n| n.starts_with('M'))
        .collect();
    assert_eq!(
        aux,
        [
            "M7 prefix",
            "M8 prefix",
            "M9 postfix",
            "M10 prefix",
            "M708 prefix",
            "M710 prefix",
            "M9 postfix"
        ]
    );
    let after_end = {
        let mut it = Interpreter::from_text("M708\nM30\n", opts(MTable::beavermill()));
        let cmds: Vec<_> = it.by_ref().map(|c| c.unwrap()).collect();
        assert_eq!(names(&cmds), ["M708 prefix", "M9 postfix", "end"]);
        it.axioma_m_vector()
    };
    assert_eq!(shown(&after_end, "M_Cool_AirCool"), 9);
}

#[test]
fn s8_1_beavermill_probe_switch() {
    let text = program("s8_1-beavermill-probe-switch-m73-m75-example.nc");
    // N110: the group rule gives M73 (the manual's MSG text "M75" is its own error, spec A40).
    for (n, m) in [(10, 73), (30, 74), (50, 73), (70, 75), (90, 74), (110, 73)] {
        let v = m_vector_after(&text, n, MTable::beavermill());
        assert_eq!(shown(&v, "M_ProbeSwitch"), m, "N{n}");
    }
}

#[test]
fn s8_1_beavermill_rotary_table_clamps() {
    let text = program("s8_1-beavermill-rotary-table-clamp-m115-m123-example.nc");
    for (n, m) in [(10, 116), (30, 122), (50, 115), (70, 120), (90, 116)] {
        let v = m_vector_after(&text, n, MTable::beavermill());
        assert_eq!(shown(&v, "MSwivelRotaryTable"), m, "N{n}");
    }
    // A command that changes nothing is "meaningless": executed, with a warning (spec §5.3).
    let mut it = Interpreter::from_text("M116\nM120\nM30\n", opts(MTable::beavermill()));
    for c in it.by_ref() {
        c.unwrap();
    }
    let w: Vec<String> = it.warnings().iter().map(|w| w.code.to_string()).collect();
    assert_eq!(w, ["axioma::meaningless-clamp"]);
    assert_eq!(shown(&it.axioma_m_vector(), "MSwivelRotaryTable"), 116);
}

#[test]
fn profiles_by_name() {
    assert_eq!(MTable::profile("BeaverMill").unwrap().profile, "beavermill");
    assert_eq!(MTable::profile("generic").unwrap().profile, "generic");
    assert!(MTable::profile("unknown").is_none());
}
