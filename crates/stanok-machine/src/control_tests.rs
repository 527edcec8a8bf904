//! Tests of `control.rs` (kept apart so that the module stays readable).
use super::*;
use crate::{offsets_from_toml_str, tools_from_toml_str, MachineData, BAD_DATA};
use stanok_canon::Diagnostic;

const HEAD: &str = "name = \"m\"\nrapid_rate = 1.0\nmax_feed = 1.0\narc_tolerance = 0.0\n\
                    [[axis]]\nname = \"X\"\nkind = \"linear\"\nmin = -1.0\nmax = 1.0\n\
                    max_velocity = 1.0\nmax_acceleration = 1.0\nmax_jerk = 1.0\n";

/// Line of the first line after HEAD.
const FIRST: u32 = 13;

fn machine(sections: &str) -> Result<MachineData, Diagnostic> {
    MachineData::from_toml_str(&format!("{HEAD}{sections}"), "m.toml")
}

/// The error for `sections`, with its (line relative to the sections, column).
fn err(sections: &str) -> (String, u32, u32) {
    let d = machine(sections).unwrap_err();
    assert_eq!(d.code.to_string(), BAD_DATA);
    assert_eq!(d.notes, vec!["in machine data file m.toml".to_string()]);
    (d.message, d.span.line + 1 - FIRST, d.span.column)
}

#[test]
fn the_example_file_has_every_section() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../machines/example-offsets-tools.toml"
    );
    let m = MachineData::load(path).unwrap();
    let o = &m.control.offsets;
    assert_eq!(o.active_system, 1);
    assert_eq!(o.zero_offset(1, 1).unwrap().offset.x, 100.0);
    assert_eq!(o.zero_offset(1, 1).unwrap().offset.y, 50.0);
    let g56 = o.zero_offset(3, 12).unwrap();
    assert_eq!(
        (g56.offset.x, g56.offset.y, g56.offset.z),
        (-200.0, 120.5, -15.0)
    );
    assert_eq!(o.zero_offset(9, 1).unwrap().rotation_xy, 90.0);
    assert_eq!(nonzero_zero_offsets(o).count(), 3);
    let w = o.workpiece_frame(4, 6).unwrap();
    assert_eq!((w.origin, w.euler), ([0.0, 0.0, 50.0], [0.0, 30.0, 0.0]));
    assert_eq!(o.workpiece_frame(1, 1).unwrap().euler, [90.0, 0.0, 0.0]);
    assert_eq!(o.home[0].unwrap().z, 250.0);
    assert_eq!(o.home[1].unwrap().x, 450.0);
    assert!(o.home[2].is_none());
    assert_eq!((o.g28.z, o.g30.x, o.g92_applied), (250.0, 450.0, false));
    assert_eq!(m.control.parameters.get(&31), Some(&2.5));
    let t10 = m.control.tools.get(10).unwrap();
    assert_eq!(t10.kind, ToolKind::Turning);
    assert_eq!(t10.edges.len(), 2);
    assert_eq!(t10.edges[0].length, [250.0, 40.0, 0.0]);
    assert_eq!((t10.edges[0].radius, t10.edges[0].radius_wear), (0.8, 0.3));
    assert_eq!(t10.edges[1].orientation, 4);
    assert_eq!(t10.edges[1].back_angle, 155.0);
    let t1 = m.control.tools.get(1).unwrap();
    assert_eq!(t1.edges[0].length, [120.0, 0.0, 0.0]);
    assert_eq!(t1.edges[0].offset.z, 120.0);
    assert_eq!(t1.comment, "end mill 6 mm");
    // Written back sparsely, it reads back the same.
    assert_eq!(
        MachineData::from_toml_str(&m.to_toml(), "again.toml"),
        Ok(m)
    );
}

#[test]
fn zero_offset_errors_point_at_the_value() {
    let (m, line, col) = err("[[zero_offset]]\ncode = \"G54\"\npage = 33\n");
    assert!(m.contains("page 33 is outside 1…32"), "{m}");
    assert_eq!((line, col), (3, 8));
    let (m, line, _) = err("[[zero_offset]]\ncode = \"G60\"\n");
    assert!(m.contains("\"G60\""), "{m}");
    assert_eq!(line, 2);
    let (m, line, _) =
        err("[[zero_offset]]\ncode = \"G54\"\n[[zero_offset]]\ncode = \"g54\"\npage = 1\n");
    assert!(m.contains("G54 page 1 is defined twice"), "{m}");
    assert_eq!(line, 4);
    let (m, line, col) = err("[[zero_offset]]\ncode = \"G55\"\nz = nan\n");
    assert!(m.contains("G55 z must be a finite number"), "{m}");
    assert_eq!((line, col), (3, 5));
    let (m, _, _) = err("[[zero_offset]]\ncode = \"G55\"\nq = 1.0\n");
    assert!(m.contains("unknown field `q`"), "{m}");
    let (m, _, _) = err("[[zero_offset]]\ncode = \"G55\"\nrotation = inf\n");
    assert!(m.contains("rotation"), "{m}");
    let d = MachineData::from_toml_str(&format!("active_system = \"G53\"\n{HEAD}"), "m.toml");
    assert!(d.unwrap_err().message.contains("active_system"));
    // Pages are fine up to 32, the LinuxCNC systems too.
    let ok = MachineData::from_toml_str(
        &format!(
            "active_system = \"G59.2\"\n{HEAD}[[zero_offset]]\ncode = \"G59\"\npage = 32\nw = 1\n"
        ),
        "m.toml",
    )
    .unwrap();
    assert_eq!(ok.control.offsets.zero[5][31].offset.w, 1.0);
    assert_eq!(ok.control.offsets.active_system, 8);
}

#[test]
fn workpiece_and_home_errors() {
    let (m, line, _) = err("[[workpiece]]\ncode = \"G154\"\norigin = [1.0, 2.0]\n");
    assert!(m.contains("exactly 3 numbers, not 2"), "{m}");
    assert_eq!(line, 3);
    let (m, line, col) = err("[[workpiece]]\ncode = \"G159\"\neuler = [0.0, 190.0, 0.0]\n");
    assert!(m.contains("euler[1] = 190° is outside −180…180°"), "{m}");
    assert_eq!((line, col), (3, 15));
    let (m, _, _) = err("[[workpiece]]\ncode = \"G54\"\n");
    assert!(m.contains("G154…G159"), "{m}");
    let (m, _, _) = err("[[workpiece]]\ncode = \"G154\"\npage = 0\n");
    assert!(m.contains("page 0"), "{m}");
    let (m, line, col) = err("[[home]]\nnumber = 9\n");
    assert!(m.contains("home position number 9 is outside 1…8"), "{m}");
    assert_eq!((line, col), (2, 10));
    let (m, line, _) = err("[[home]]\nnumber = 2\n[[home]]\nnumber = 2\n");
    assert!(m.contains("H2 is defined twice"), "{m}");
    assert_eq!(line, 4);
    let (m, line, _) = err("[g92]\napplied = 1\n");
    assert!(m.contains("expected a boolean"), "{m}");
    assert_eq!(line, 2);
}

#[test]
fn tool_body_errors_point_at_the_value() {
    let edge = "[[tool.edge]]\nradius = 1.0\n";
    let (m, line, col) = err(&format!("[[tool]]\nnumber = 2\ncutter = \"cone\"\n{edge}"));
    assert!(
        m.contains("T2 cutter must be flat, ball, bull, drill or insert"),
        "{m}"
    );
    assert_eq!((line, col), (3, 10));
    let (m, line, col) = err(&format!("[[tool]]\nnumber = 2\nflute_length = 0.0\n{edge}"));
    assert!(m.contains("T2 flute_length must be more than 0"), "{m}");
    assert_eq!((line, col), (3, 16));
    let (m, _, _) = err(&format!(
        "[[tool]]\nnumber = 2\npoint_angle = 180.0\n{edge}"
    ));
    assert!(
        m.contains("point_angle must be more than 0 and at most 179"),
        "{m}"
    );
    let (m, line, _) = err(&format!(
        "[[tool]]\nnumber = 2\nholder = [{{ diameter = [1.0, 2.0, 3.0], length = 5.0 }}]\n{edge}"
    ));
    assert!(
        m.contains("holder diameter must be a number or [bottom, top]"),
        "{m}"
    );
    assert_eq!(line, 3);
    let (m, _, _) = err(&format!(
        "[[tool]]\nnumber = 2\nholder = [{{ diameter = 20.0, length = -1.0 }}]\n{edge}"
    ));
    assert!(m.contains("T2 holder length must be more than 0"), "{m}");
    let (m, _, _) = err(&format!(
        "[[tool]]\nnumber = 2\nholder = [{{ diameter = 20.0, length = 1.0, colour = 1 }}]\n{edge}"
    ));
    assert!(m.contains("colour"), "{m}");
}

#[test]
fn tool_errors() {
    let edge = "[[tool.edge]]\nradius = 1.0\n";
    let (m, line, col) = err(&format!("[[tool]]\nnumber = 0\n{edge}"));
    assert!(m.contains("tool number must be 1…"), "{m}");
    assert_eq!((line, col), (2, 10));
    let (m, line, _) = err(&format!(
        "[[tool]]\nnumber = 3\n{edge}[[tool]]\nnumber = 3\n{edge}"
    ));
    assert!(m.contains("tool T3 is defined twice"), "{m}");
    assert_eq!(line, 6);
    let (m, line, _) = err("[[tool]]\nnumber = 4\n");
    assert!(m.contains("T4 needs at least one [[tool.edge]]"), "{m}");
    assert_eq!(line, 2);
    let (m, _, _) = err("[[tool]]\nnumber = 4\nedge = []\n");
    assert!(m.contains("at least one edge"), "{m}");
    let (m, line, col) = err(&format!("[[tool]]\nnumber = 5\n{}", edge.repeat(5)));
    assert!(m.contains("T5 has more than 4 edges"), "{m}");
    assert_eq!((line, col), (11, 1));
    let (m, line, col) = err("[[tool]]\nnumber = 6\n[[tool.edge]]\norientation = 10\n");
    assert!(
        m.contains("T6 D1 orientation (cutting-edge position) must be 0…9, not 10"),
        "{m}"
    );
    assert_eq!((line, col), (4, 15));
    let (m, _, _) = err("[[tool]]\nnumber = 6\n[[tool.edge]]\norientation = -1\n");
    assert!(m.contains("not -1"), "{m}");
    let (m, line, _) = err("[[tool]]\nnumber = 7\n[[tool.edge]]\n[[tool.edge]]\nradius = -0.5\n");
    assert!(m.contains("T7 D2 radius must not be negative"), "{m}");
    assert_eq!(line, 5);
    let (m, _, _) = err("[[tool]]\nnumber = 8\n[[tool.edge]]\nlength = [1.0, 2.0, 3.0, 4.0]\n");
    assert!(
        m.contains("T8 D1 length needs 1 to 3 numbers, not 4"),
        "{m}"
    );
    let (m, _, _) = err("[[tool]]\nnumber = 8\n[[tool.edge]]\nlength_wear = [-inf]\n");
    assert!(m.contains("length_wear[0] must be a finite number"), "{m}");
    let (m, _, _) = err("[[tool]]\nnumber = 8\nkind = \"lathe\"\n[[tool.edge]]\n");
    assert!(m.contains("kind must be milling"), "{m}");
    let (m, _, _) = err("[[tool]]\nnumber = 8\npocket = -2\n[[tool.edge]]\n");
    assert!(m.contains("pocket"), "{m}");
    let (m, _, _) = err("[[tool]]\nnumber = 8\n[[tool.edge]]\noffset = { z = nan }\n");
    assert!(m.contains("T8 D1 offset z must be a finite number"), "{m}");
    // Radius wear may be negative: it is a correction.
    let ok =
        machine("[[tool]]\nnumber = 9\n[[tool.edge]]\nradius = 1\nradius_wear = -0.1\n").unwrap();
    assert_eq!(ok.control.tools.edge(9, 1).unwrap().radius_wear, -0.1);
}

#[test]
fn parameter_errors() {
    let (m, line, _) = err("[parameters]\n5221 = 1.0\n");
    assert!(m.contains("parameter 5221 is a stored offset"), "{m}");
    assert_eq!(line, 2);
    let (m, _, _) = err("[parameters]\n5602 = 1.0\n");
    assert!(m.contains("1…5601"), "{m}");
    let (m, _, _) = err("[parameters]\nabc = 1.0\n");
    assert!(m.contains("\"abc\""), "{m}");
    let (m, _, _) = err("[parameters]\n31 = 1.0\n\"031\" = 2.0\n");
    assert!(m.contains("parameter 31 is defined twice"), "{m}");
    let ok = machine("[parameters]\n5231 = 1.0\n4999 = -2\n").unwrap();
    assert_eq!(ok.control.parameters.len(), 2);
}

#[test]
fn the_first_error_in_the_file_is_reported() {
    let (m, line, _) = err("[[home]]\nnumber = 0\n[[zero_offset]]\ncode = \"G54\"\npage = 40\n");
    assert!(m.contains("home"), "{m}");
    assert_eq!(line, 2);
}

#[test]
fn offset_parameter_numbers() {
    for n in [
        5161, 5169, 5181, 5189, 5210, 5219, 5220, 5221, 5230, 5241, 5250, 5381, 5390,
    ] {
        assert!(is_offset_parameter(n), "{n}");
    }
    for n in [
        5160, 5170, 5180, 5190, 5209, 5231, 5240, 5251, 5391, 5400, 31,
    ] {
        assert!(!is_offset_parameter(n), "{n}");
    }
}

#[test]
fn fragments_hold_only_their_sections() {
    let tools = "[[tool]]\nnumber = 2\n[[tool.edge]]\nradius = 2.0\n";
    let t = tools_from_toml_str(tools, "t.toml").unwrap();
    assert_eq!(t.edge(2, 1).unwrap().radius, 2.0);
    let d = tools_from_toml_str(&format!("{tools}[[home]]\nnumber = 1\n"), "t.toml").unwrap_err();
    assert!(
        d.message.contains("only [[tool]] sections, not `home`"),
        "{d}"
    );
    assert_eq!(d.span.line, 5);
    let offsets =
        "active_system = \"G55\"\n[[zero_offset]]\ncode = \"G55\"\nx = 1.5\n[parameters]\n31 = 1\n";
    let o = offsets_from_toml_str(offsets, "o.toml").unwrap();
    assert_eq!(o.offsets.active_system, 2);
    assert_eq!(o.offsets.zero_offset(2, 1).unwrap().offset.x, 1.5);
    assert_eq!(o.parameters.get(&31), Some(&1.0));
    let d = offsets_from_toml_str(&format!("name = \"m\"\n{offsets}"), "o.toml").unwrap_err();
    assert!(d.message.contains("not `name`"), "{d}");
    assert_eq!((d.span.line, d.span.column), (1, 8));
    let d = offsets_from_toml_str(&format!("{offsets}{tools}"), "o.toml").unwrap_err();
    assert!(d.message.contains("not `tool`"), "{d}");
    assert_eq!(d.notes, vec!["in machine data file o.toml".to_string()]);
    // The bad value inside an allowed section is found too.
    let d = tools_from_toml_str(
        "[[tool]]\nnumber = 2\n[[tool.edge]]\nradius = \"x\"\n",
        "t.toml",
    )
    .unwrap_err();
    assert_eq!(d.span.line, 4);
    assert!(tools_from_toml_str("", "t.toml").unwrap().tools.is_empty());
}

#[test]
fn the_writer_is_sparse() {
    assert_eq!(control_to_toml(&ControlData::default()), "");
    let mut c = ControlData::default();
    c.offsets.zero[1][3].offset.y = 2.5;
    c.offsets.active_system = 2;
    let text = control_to_toml(&c);
    assert_eq!(
        text,
        "active_system = \"G55\"\n\n[[zero_offset]]\ncode = \"G55\"\npage = 4\ny = 2.5\n\n"
    );
    assert_eq!(
        offsets_from_toml_str(&text, "x.toml").unwrap().offsets,
        c.offsets
    );
}

#[test]
fn axioma_permanent_parameters_are_read_checked_and_written_back() {
    let m = machine("[iperm]\n1 = 1500\n5 = -2\n[dperm]\n0 = 0.25\n").unwrap();
    assert_eq!(m.control.perm_int.get(&1), Some(&1500));
    assert_eq!(m.control.perm_int.get(&5), Some(&-2));
    assert_eq!(m.control.perm_double.get(&0), Some(&0.25));
    let (msg, line, _) = err("[iperm]\n1000 = 1\n");
    assert!(msg.contains("0…999"), "{msg}");
    assert_eq!(line, 2);
    let (msg, _, _) = err("[dperm]\n\"x\" = 1.0\n");
    assert!(msg.contains("0…999"), "{msg}");
    let text = control_to_toml(&m.control);
    assert!(text.contains("[iperm]\n1 = 1500\n5 = -2\n"), "{text}");
    assert!(text.contains("[dperm]\n0 = 0.25\n"), "{text}");
}

#[test]
fn axioma_feed_and_speed_tables_are_read_checked_and_written_back() {
    let m = machine("[feed_table]\n20 = 4321.0\n127 = 9000.0\n[speed_table]\n2 = 777.0\n").unwrap();
    assert_eq!(m.feed_table.get(&20), Some(&4321.0));
    assert_eq!(m.feed_table.get(&127), Some(&9000.0));
    assert_eq!(m.speed_table.get(&2), Some(&777.0));
    let (msg, line, _) = err("[feed_table]\n128 = 1.0\n");
    assert!(msg.contains("0…127"), "{msg}");
    assert_eq!(line, 2);
    let (msg, line, _) = err("[speed_table]\n3 = 0.0\n");
    assert!(msg.contains("positive"), "{msg}");
    assert_eq!(line, 2);
    // Written sparsely and read back to the same machine.
    let text = m.to_toml();
    assert!(
        text.contains("[feed_table]\n20 = 4321.0\n127 = 9000.0\n"),
        "{text}"
    );
    assert_eq!(MachineData::from_toml_str(&text, "back.toml").unwrap(), m);
    // An offset file may not hold them.
    assert!(offsets_from_toml_str("[feed_table]\n1 = 2.0\n", "o.toml").is_err());
}
