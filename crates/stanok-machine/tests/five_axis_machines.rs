//! The built-in 5-axis machines: each loads, builds its kinematics, survives a TOML round trip,
//! and reproduces a spec oracle where one exists.

use stanok_canon::Pose;
use stanok_kin::Kinematics;
use stanok_machine::{MachineData, BUILTIN_FIVE_AXIS};

#[test]
fn every_builtin_five_axis_machine_loads_builds_and_round_trips() {
    for (name, text) in BUILTIN_FIVE_AXIS {
        let m = MachineData::from_toml_str(text, name).unwrap_or_else(|d| panic!("{name}: {d:?}"));
        assert_eq!(m.name, name);
        assert!(m.five_axis().is_some(), "{name}: no kinematics");
        assert_eq!(MachineData::builtin(name).as_ref(), Some(&m));
        let again = MachineData::from_toml_str(&m.to_toml(), name).unwrap();
        assert_eq!(again, m, "{name}: TOML round trip");
        // The rotary limits come from the [[axis]] entries.
        for r in &m.kinematics.as_ref().unwrap().rotary {
            let axis = m.axis(r.name).unwrap();
            assert_eq!((r.min, r.max), (axis.min, axis.max), "{name} {}", r.name);
        }
    }
}

#[test]
fn the_bc_head_is_the_axioma_examples_machine() {
    // Example 12.2 end: tip (100, 0, 0), B −75, L = 100 → mount point (3.4074, 0, 25.8819).
    let k = MachineData::builtin("5axis-bc-head")
        .unwrap()
        .five_axis()
        .unwrap()
        .with_tool_length(100.0);
    let j = k
        .inverse(&Pose {
            x: 100.0,
            b: -75.0,
            ..Pose::ZERO
        })
        .unwrap();
    assert!((j[0] - 3.4074).abs() < 1e-4 && j[1].abs() < 1e-9 && (j[2] - 25.8819).abs() < 1e-4);
}

#[test]
fn the_millturn_reproduces_mazatrol_oracle_a_after_n40() {
    // Tip at table (0, 20, −5) with the workpiece origin at z −400, B90 C90, H1 = 100:
    // Xm −39 (diameter), Ym 0, Zm −555.5.
    let k = MachineData::builtin("millturn-bc")
        .unwrap()
        .five_axis()
        .unwrap()
        .with_tool_length(100.0);
    let j = k
        .inverse(&Pose {
            y: 20.0,
            z: -405.0,
            b: 90.0,
            c: 90.0,
            ..Pose::ZERO
        })
        .unwrap();
    assert!(
        (j[0] + 39.0).abs() < 1e-6 && j[1].abs() < 1e-6 && (j[2] + 555.5).abs() < 1e-6,
        "{j:?}"
    );
}

#[test]
fn kinematics_naming_a_missing_axis_is_refused() {
    let text = BUILTIN_FIVE_AXIS[0].1.replace(
        "name = \"C\"\nkind = \"rotary\"",
        "name = \"A\"\nkind = \"rotary\"",
    );
    let err = MachineData::from_toml_str(&text, "x.toml").unwrap_err();
    assert!(format!("{err:?}").contains("rotary axis C"), "{err:?}");
}
