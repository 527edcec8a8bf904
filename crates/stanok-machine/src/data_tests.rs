//! Tests of machine data: reading, validation errors with positions, the built-in machines.
use super::*;

const GOOD: &str = r#"
name = "tiny"
rapid_rate = 6000
max_feed = 3000.0
arc_tolerance = 0.002
[[axis]]
name = "X"
kind = "linear"
min = -10.0
max = 10.0
max_velocity = 6000.0
max_acceleration = 500.0
max_jerk = 5000.0
[[axis]]
name = "C"
kind = "rotary"
min = -inf
max = inf
max_velocity = 3600.0
max_acceleration = 360.0
max_jerk = 3600.0
"#;

fn err(text: &str) -> Diagnostic {
    MachineData::from_toml_str(text, "m.toml").unwrap_err()
}

#[test]
fn reads_a_good_file() {
    let m = MachineData::from_toml_str(GOOD, "m.toml").unwrap();
    assert_eq!(m.name, "tiny");
    assert_eq!(m.rapid_rate, 6000.0); // an integer is accepted for a float
    assert_eq!(m.axes.len(), 2);
    assert_eq!(m.axis('C').unwrap().kind, AxisKind::Rotary);
    assert_eq!(m.axis('C').unwrap().pose_index(), 5);
    assert_eq!(m.axis('C').unwrap().max, f64::INFINITY);
    assert_eq!(m.description, "");
    let mut mask = [false; 9];
    (mask[0], mask[5]) = (true, true);
    assert_eq!(m.axis_mask(), mask);
}

#[test]
fn every_listed_builtin_machine_loads_and_names_itself() {
    for name in BUILTIN_MACHINES {
        let m = MachineData::builtin(name).unwrap_or_else(|| panic!("{name}"));
        assert_eq!(m.name, name);
        assert!(!m.description.is_empty(), "{name}");
    }
    assert!(MachineData::builtin("lathe").unwrap().is_lathe());
    assert!(!MachineData::builtin("mill").unwrap().is_lathe());
    assert!(!MachineData::builtin("millturn-bc").unwrap().is_lathe());
}

#[test]
fn machines_mill_toml_equals_the_builtin() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../machines/mill.toml");
    assert_eq!(MachineData::load(path), Ok(MachineData::default_mill()));
    assert_eq!(
        MachineData::builtin("mill"),
        Some(MachineData::default_mill())
    );
    assert_eq!(MachineData::builtin("drill"), None);
    let lathe = concat!(env!("CARGO_MANIFEST_DIR"), "/../../machines/lathe.toml");
    assert_eq!(MachineData::load(lathe), Ok(MachineData::default_lathe()));
    assert!(MachineData::default_lathe().diameter_axes()[0]);
    assert_eq!(MachineData::default_mill().diameter_axes(), [false; 9]);
}

#[test]
fn syntax_errors_have_line_and_column() {
    let d = err("name = \"m\"\nrapid_rate = = 3\n");
    assert_eq!(d.code.to_string(), BAD_DATA);
    assert_eq!((d.span.line, d.span.column), (2, 14), "{d}");
    assert_eq!(d.notes, vec!["in machine data file m.toml".to_string()]);
}

#[test]
fn unknown_keys_and_kinds_are_errors() {
    let d = err(&GOOD.replace("max_feed", "max_fed"));
    assert!(d.message.contains("max_fed"), "{d}");
    assert_eq!(d.span.line, 4);
    let d = err(&GOOD.replace("\"linear\"", "\"linaer\""));
    assert!(d.message.contains("linaer"), "{d}");
    assert_eq!((d.span.line, d.span.column), (8, 8), "{d}");
    let d = err(&GOOD.replace("min = -inf\n", ""));
    assert!(d.message.contains("min"), "{d}");
}

#[test]
fn validation_errors_point_at_the_value() {
    let d = err(&GOOD.replace("max = 10.0", "max = -20.0"));
    assert!(d.message.contains("greater than max"), "{d}");
    assert_eq!((d.span.line, d.span.column), (10, 7), "{d}");
    let d = err(&GOOD.replace("rapid_rate = 6000", "rapid_rate = -6000"));
    assert!(d.message.contains("rapid_rate"), "{d}");
    assert_eq!((d.span.line, d.span.column), (3, 14), "{d}");
    let d = err(&GOOD.replace("name = \"C\"", "name = \"X\""));
    assert!(d.message.contains("defined twice"), "{d}");
    assert_eq!(d.span.line, 15);
    let d = err(&GOOD.replace("name = \"C\"", "name = \"Q\""));
    assert!(d.message.contains("one of X Y Z"), "{d}");
    let d = err(&GOOD.replace("\"rotary\"", "\"linear\""));
    assert!(d.message.contains("axis C is rotary"), "{d}");
    let d = err(&GOOD.replace("max_jerk = 5000.0", "max_jerk = 0.0"));
    assert!(d.message.contains("max_jerk"), "{d}");
    let d = err(&GOOD.replace("arc_tolerance = 0.002", "arc_tolerance = nan"));
    assert!(d.message.contains("arc_tolerance"), "{d}");
    // path_tolerance: optional (0.05), a positive number of mm.
    let good = MachineData::from_toml_str(GOOD, "m.toml").unwrap();
    assert_eq!(good.path_tolerance, 0.05);
    let with = GOOD.replace(
        "arc_tolerance = 0.002",
        "arc_tolerance = 0.002\npath_tolerance = 0.01",
    );
    let m = MachineData::from_toml_str(&with, "m.toml").unwrap();
    assert_eq!(m.path_tolerance, 0.01);
    assert_eq!(MachineData::from_toml_str(&m.to_toml(), "m.toml"), Ok(m));
    let d = err(&with.replace("path_tolerance = 0.01", "path_tolerance = 0"));
    assert!(
        d.message.contains("path_tolerance must be a positive"),
        "{d}"
    );
    assert_eq!(d.span.line, 6);
    let d = err("name = \"m\"\nrapid_rate = 1.0\nmax_feed = 1.0\narc_tolerance = 0.0\naxis = []\n");
    assert!(d.message.contains("at least one"), "{d}");
    assert_eq!(d.span.line, 5);
}

#[test]
fn never_panics_on_odd_text() {
    for text in [
        "",
        "\u{feff}",
        "name = \"é\"\n[[axis]]\nname = \"ЖЖ\"",
        "[[[",
        "axis = 3",
    ] {
        assert!(MachineData::from_toml_str(text, "x.toml").is_err());
    }
    assert_eq!(line_column("aé\nb", 2), (1, 2)); // inside 'é': backs off to its start
    assert_eq!(line_column("aé\nb", 99), (2, 2));
}

#[test]
fn load_reports_a_missing_file() {
    let d = MachineData::load("/nonexistent/stanok-machine.toml").unwrap_err();
    assert!(d.message.contains("cannot read"), "{d}");
}

#[test]
fn m_function_profile_key_and_the_beavermill_machine() {
    assert_eq!(
        MachineData::from_toml_str(GOOD, "g.toml")
            .unwrap()
            .m_functions,
        "generic"
    );
    let bm = GOOD.replace(
        "arc_tolerance = 0.002",
        "arc_tolerance = 0.002\nm_functions = \"beavermill\"",
    );
    let m = MachineData::from_toml_str(&bm, "b.toml").unwrap();
    assert_eq!(m.m_functions, "beavermill");
    // Written back and read again.
    assert_eq!(
        MachineData::from_toml_str(&m.to_toml(), "w.toml").unwrap(),
        m
    );
    let bad = GOOD.replace(
        "arc_tolerance = 0.002",
        "arc_tolerance = 0.002\nm_functions = \"fanuc\"",
    );
    let d = MachineData::from_toml_str(&bad, "x.toml").unwrap_err();
    assert!(d.message.contains("m_functions"), "{d}");
    let builtin = MachineData::builtin("beavermill").expect("built-in beavermill");
    assert_eq!(builtin.m_functions, "beavermill");
    let names: String = builtin.axes.iter().map(|a| a.name).collect();
    assert_eq!(names, "XYZAC");
    assert_eq!(MachineData::builtin("mill").unwrap().m_functions, "generic");
}

/// The built-in `linuxcnc` machine: rs274's six axes, inch LinuxCNC units, and the sim
/// configurations' tool table (T1 Z0.511 in, D0.125 in; five tools).
#[test]
fn the_builtin_linuxcnc_machine() {
    let m = MachineData::builtin("linuxcnc").expect("built in");
    let names: String = m.axes.iter().map(|a| a.name).collect();
    assert_eq!(names, "XYZABC");
    assert_eq!(m.linuxcnc_units, stanok_canon::LengthUnits::Inches);
    let tools = &m.control.tools.tools;
    assert_eq!(tools.len(), 5);
    let t1 = &tools[&1];
    assert!((t1.edges[0].offset.z - 0.511 * 25.4).abs() < 1e-9);
    assert!((t1.edges[0].radius - 0.125 * 25.4 / 2.0).abs() < 1e-9);
    assert!(tools.contains_key(&99999));
}
