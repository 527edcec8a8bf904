//! The `[mazatrol]` machine-data section: defaults, the series rule, refusals, and the built-in
//! Mazak machines.

use stanok_machine::{MachineData, MazatrolFeedMode, MazatrolSeries};

const BASE: &str = r#"
name = "m"
rapid_rate = 1000.0
max_feed = 1000.0
arc_tolerance = 0.01
[[axis]]
name = "X"
kind = "linear"
min = -100.0
max = 100.0
max_velocity = 1000.0
max_acceleration = 100.0
max_jerk = 1000.0
"#;

fn parse(extra: &str) -> Result<MachineData, stanok_canon::Diagnostic> {
    MachineData::from_toml_str(&format!("{BASE}{extra}"), "m.toml")
}

#[test]
fn defaults_and_series() {
    let m = parse("").unwrap();
    assert!(m.mazatrol.is_none());
    assert_eq!(m.mazatrol_series(), MazatrolSeries::M);
    let m = parse("[mazatrol]\nseries = \"T\"\n").unwrap();
    let s = m.mazatrol.as_ref().unwrap();
    assert_eq!(s.series, Some(MazatrolSeries::T));
    assert_eq!(s.decimal_point_type, 2);
    assert_eq!(s.peck_clearance, 1.0);
    assert_eq!(s.thread_chamfer_angle, 45.0);
    assert!(s.g49_moves && !s.tool_data_length);
    assert_eq!(m.mazatrol_series(), MazatrolSeries::T);
    // A mill-turn kinematics is a T-series control unless the section says otherwise.
    let mt = MachineData::builtin("millturn-bc").unwrap();
    assert_eq!(mt.mazatrol_series(), MazatrolSeries::T);
    // The power-on feed mode: absent means "by series"; millturn-bc (the TTPC oracles' machine,
    // programs in mm/min) says G94, mazak-t G95.
    assert_eq!(s.power_on_feed, None);
    let feed = |m: &MachineData| m.mazatrol.as_ref().and_then(|s| s.power_on_feed);
    assert_eq!(feed(&mt), Some(MazatrolFeedMode::G94));
    let t = MachineData::builtin("mazak-t").unwrap();
    assert_eq!(feed(&t), Some(MazatrolFeedMode::G95));
    let m = parse("[mazatrol]\npower_on_feed = \"G94\"\n").unwrap();
    assert_eq!(feed(&m), Some(MazatrolFeedMode::G94));
}

#[test]
fn refusals_name_the_key() {
    for (extra, text) in [
        (
            "[mazatrol]\ndecimal_point_type = 3\n",
            "decimal_point_type must be 1 or 2",
        ),
        (
            "[mazatrol]\npeck_clearance = 0.0\n",
            "peck_clearance must be a positive",
        ),
        (
            "[mazatrol]\nthread_chamfer_angle = 90.0\n",
            "thread_chamfer_angle must be between",
        ),
        (
            "[mazatrol]\ng60_overshoot = -1.0\n",
            "g60_overshoot must be zero or",
        ),
        ("[mazatrol]\nseries = \"X\"\n", "unknown variant"),
        ("[mazatrol]\nfoo = 1\n", "unknown field"),
        ("[mazatrol]\npower_on_feed = \"G93\"\n", "unknown variant"),
    ] {
        let e = parse(extra).unwrap_err();
        assert!(e.message.contains(text), "{extra}: {}", e.message);
    }
}

#[test]
fn the_built_in_mazak_machines() {
    let m = MachineData::builtin("mazak-m").unwrap();
    assert_eq!(m.mazatrol_series(), MazatrolSeries::M);
    assert!(m.five_axis().is_some());
    let g54 = m.control.offsets.zero_offset(1, 1).unwrap().offset;
    assert_eq!((g54.x, g54.y, g54.z), (100.0, 50.0, -200.0));
    assert_eq!(m.control.tools.get(1).unwrap().edges[0].length[0], 150.0);
    assert_eq!(m.control.tools.get(2).unwrap().edges[0].length[0], 120.0);
    let t = MachineData::builtin("mazak-t").unwrap();
    assert_eq!(t.mazatrol_series(), MazatrolSeries::T);
    assert!(!t.five_axis().unwrap().x_is_diameter());
    let e = &t.control.tools.get(1).unwrap().edges[0];
    assert_eq!(
        (e.length[0], e.length[1], e.radius, e.orientation),
        (20.0, 80.0, 0.8, 3)
    );
    // The TOML round trip keeps the section.
    let again = MachineData::from_toml_str(&t.to_toml(), "t.toml").unwrap();
    assert_eq!(again.mazatrol, t.mazatrol);
}
