//! Tests of `linuxcnc.rs` (kept apart so that the module stays readable).
use super::*;
use crate::BAD_DATA;

const MM: LengthUnits = LengthUnits::Millimetres;
const INCH: LengthUnits = LengthUnits::Inches;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn tbl_err(text: &str) -> (String, u32, u32) {
    let d = parse_tool_table(text, "t.tbl", MM).unwrap_err();
    assert_eq!(d.code.to_string(), BAD_DATA);
    assert_eq!(d.notes, vec!["in LinuxCNC tool table t.tbl".to_string()]);
    (d.message, d.span.line, d.span.column)
}

fn var_err(text: &str) -> (String, u32, u32) {
    let d = parse_var_file(text, "p.var", MM).unwrap_err();
    assert_eq!(
        d.notes,
        vec!["in LinuxCNC parameter file p.var".to_string()]
    );
    (d.message, d.span.line, d.span.column)
}

#[test]
fn the_corpus_tool_table_is_in_inches() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus/rs274ngc/tool.tbl"
    );
    let text = std::fs::read_to_string(path).unwrap();
    let t = parse_tool_table(&text, path, INCH).unwrap();
    assert_eq!(t.tools.keys().copied().collect::<Vec<_>>(), vec![1, 2, 10]);
    let t1 = t.get(1).unwrap();
    assert_eq!((t1.pocket, t1.comment.as_str()), (1, "tool 1"));
    assert_eq!(t1.edges.len(), 1);
    let e = t1.edges[0];
    // Z-1.5 and D0.25 in inches, converted from their decimal text: the nearest f64.
    assert_eq!((e.offset.z, e.radius), (-38.1, 3.175));
    assert_eq!((e.offset.x, e.length, e.orientation), (0.0, [0.0; 3], 0));
    let t10 = t.get(10).unwrap();
    assert!(close(t10.edges[0].offset.z, 2.54));
    assert!(close(t10.edges[0].radius, 6.35));
    assert_eq!(t10.comment, "tool 10");
    // In mm the same file means what it says.
    let mm = parse_tool_table(&text, path, MM).unwrap();
    assert_eq!(mm.edge(1, 1).unwrap().offset.z, -1.5);
    assert_eq!(mm.edge(1, 1).unwrap().radius, 0.125);
    // Written back in inches, it is LinuxCNC's own text.
    assert_eq!(
        write_tool_table(&t, INCH),
        "T1   P1   D+0.250000 Z-1.500000 ;tool 1\n\
         T2   P2   D+0.100000 ;tool 2\n\
         T10  P10  D+0.500000 Z+0.100000 ;tool 10\n"
    );
}

#[test]
fn tool_table_words_in_any_order_and_case() {
    let text = "; a comment line\n\n  t7 q3 x1 y2 z3 a4 b5 c6 u7 v8 w9 i10 j-20 d4 p12   ;  lathe tool  \r\nT8\n";
    let t = parse_tool_table(text, "t.tbl", MM).unwrap();
    let e = t.edge(7, 1).unwrap();
    assert_eq!(
        e.offset.to_array(),
        [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]
    );
    assert_eq!(
        (e.front_angle, e.back_angle, e.orientation, e.radius),
        (10.0, -20.0, 3, 2.0)
    );
    assert_eq!(t.get(7).unwrap().pocket, 12);
    assert_eq!(t.get(7).unwrap().comment, "lathe tool");
    assert_eq!(t.get(8).unwrap().edges, vec![ToolEdge::default()]);
    // Rotary offsets are degrees whatever the unit.
    let inch = parse_tool_table(text, "t.tbl", INCH).unwrap();
    assert_eq!(inch.edge(7, 1).unwrap().offset.a, 4.0);
    assert!(close(inch.edge(7, 1).unwrap().offset.u, 7.0 * 25.4));
}

#[test]
fn tool_table_errors_have_line_and_column() {
    let (m, line, col) = tbl_err("T1 P1\nT2 P2 K5 ;x\n");
    assert!(m.contains("unknown word \"K5\""), "{m}");
    assert_eq!((line, col), (2, 7));
    let (m, line, col) = tbl_err("T1 P1\n  P2 Z1 ;no number\n");
    assert!(m.contains("needs a T word"), "{m}");
    assert_eq!((line, col), (2, 3));
    let (m, line, col) = tbl_err("T1 P1\nT3 P3\nT1 P4\n");
    assert!(
        m.contains("tool T1 is defined twice (first on line 1)"),
        "{m}"
    );
    assert_eq!((line, col), (3, 1));
    let (m, line, col) = tbl_err("T1 Z1.5.3\n");
    assert!(
        m.contains("Z (tool offset) needs a number, not \"1.5.3\""),
        "{m}"
    );
    assert_eq!((line, col), (1, 4));
    let (m, _, _) = tbl_err("T1 Z\n");
    assert!(m.contains("not \"\""), "{m}");
    let (m, _, _) = tbl_err("T1 Znan\n");
    assert!(m.contains("needs a number"), "{m}");
    let (m, _, _) = tbl_err("T0 P1\n");
    assert!(m.contains("T (tool number) must be 1…"), "{m}");
    let (m, _, _) = tbl_err("T1.5\n");
    assert!(m.contains("whole number"), "{m}");
    let (m, _, _) = tbl_err("T1 P-1\n");
    assert!(m.contains("P (pocket)"), "{m}");
    let (m, _, _) = tbl_err("T1 Q10\n");
    assert!(m.contains("Q (orientation) must be 0…9, not 10"), "{m}");
    let (m, _, _) = tbl_err("T1 D-2\n");
    assert!(m.contains("D (diameter) must not be negative"), "{m}");
    let (m, line, col) = tbl_err("T1 Z1 z2\n");
    assert!(m.contains("word Z is given twice"), "{m}");
    assert_eq!((line, col), (1, 7));
    let (_, line, col) = tbl_err("T1 ; é\nTé\n");
    assert_eq!((line, col), (2, 1));
    assert!(parse_tool_table("", "t.tbl", MM).unwrap().tools.is_empty());
}

#[test]
fn var_file_maps_the_offsets() {
    let text = "31\t2.500000\n5161\t1.000000\n5164\t90.000000\n5183\t-2.000000\n5210\t1.000000\n\
                5213\t0.500000\n5220\t2.000000\n5221\t100.000000\n5222\t50.000000\n5230\t90.000000\n\
                5231\t7.000000\n5243\t-3.000000\n5389\t4.000000\n5390\t-45.000000\n";
    let o = parse_var_file(text, "p.var", INCH).unwrap();
    let t = &o.offsets;
    assert!(close(t.g28.x, 25.4));
    assert_eq!(t.g28.a, 90.0); // degrees stay degrees
    assert!(close(t.g30.z, -50.8));
    assert!(t.g92_applied);
    assert!(close(t.g92.z, 12.7));
    assert_eq!(t.active_system, 2);
    assert!(close(t.zero_offset(1, 1).unwrap().offset.x, 2540.0));
    assert!(close(t.zero_offset(1, 1).unwrap().offset.y, 1270.0));
    assert_eq!(t.zero_offset(1, 1).unwrap().rotation_xy, 90.0);
    assert!(close(t.zero_offset(2, 1).unwrap().offset.z, -76.2));
    assert!(close(t.zero_offset(9, 1).unwrap().offset.w, 101.6));
    assert_eq!(t.zero_offset(9, 1).unwrap().rotation_xy, -45.0);
    assert_eq!(t.zero_offset(1, 2).unwrap().offset, Pose::ZERO);
    // Not offsets: kept as written, no unit conversion.
    assert_eq!(o.parameters, BTreeMap::from([(31, 2.5), (5231, 7.0)]));
}

#[test]
fn var_file_errors_have_line_and_column() {
    let (m, line, col) = var_err("5161\t0.0\n5162 1.0 extra\n");
    assert!(m.contains("a number and a value"), "{m}");
    assert_eq!((line, col), (2, 10));
    let (m, line, col) = var_err("5161\t0.0\n5162\n");
    assert!(m.contains("a number and a value"), "{m}");
    assert_eq!((line, col), (2, 1));
    let (m, line, col) = var_err("5221\t1.0\n5161\t0.0\n");
    assert!(m.contains("5161 comes after 5221 (line 1)"), "{m}");
    assert_eq!((line, col), (2, 1));
    let (m, _, _) = var_err("5221\t1.0\n5221\t2.0\n");
    assert!(m.contains("comes after"), "{m}");
    let (m, line, col) = var_err("5221\tabc\n");
    assert!(
        m.contains("parameter 5221 needs a finite number, not \"abc\""),
        "{m}"
    );
    assert_eq!((line, col), (1, 6));
    let (m, _, _) = var_err("5221\tinf\n");
    assert!(m.contains("finite"), "{m}");
    let (m, _, _) = var_err("0\t1.0\n");
    assert!(m.contains("1…5601"), "{m}");
    let (m, _, _) = var_err("5602\t1.0\n");
    assert!(m.contains("1…5601"), "{m}");
    let (m, _, _) = var_err("-5\t1.0\n");
    assert!(m.contains("\"-5\""), "{m}");
    let (m, _, _) = var_err("5220\t10.000000\n");
    assert!(
        m.contains("5220 (active coordinate system) must be 1…9"),
        "{m}"
    );
    let (m, _, _) = var_err("5220\t1.5\n");
    assert!(m.contains("not 1.5"), "{m}");
    let (m, _, _) = var_err("5210\t0.5\n");
    assert!(m.contains("5210 (G92 applied) must be 0 or 1"), "{m}");
    // Comments and blank lines are skipped.
    let ok = parse_var_file("# saved by hand\n\n; also\n5220 3\n", "p.var", MM).unwrap();
    assert_eq!(ok.offsets.active_system, 3);
}

#[test]
fn var_writer_writes_what_linuxcnc_keeps() {
    let mut data = StoredOffsets::default();
    data.offsets.zero[0][0].offset.x = 100.0;
    data.offsets.zero[0][0].rotation_xy = 0.1 + 0.2; // not exact in six decimals
    data.offsets.zero[0][5].offset.x = 9.0; // page 6: no LinuxCNC parameter
    data.parameters.insert(31, 2.5);
    let text = write_var_file(&data, MM);
    let lines: Vec<&str> = text.lines().collect();
    // 9 + 9 + 1 + 9 + 1 + 9 × 10 parameters LinuxCNC keeps, and #31.
    assert_eq!(lines.len(), 9 + 9 + 1 + 9 + 1 + 90 + 1);
    assert_eq!(lines[0], "31\t2.500000");
    assert_eq!(lines[1], "5161\t0.000000");
    assert!(lines.contains(&"5220\t1.000000"));
    assert!(lines.contains(&"5221\t100.000000"));
    assert!(lines.contains(&"5230\t0.30000000000000004"));
    assert_eq!(*lines.last().unwrap(), "5390\t0.000000");
    let back = parse_var_file(&text, "p.var", MM).unwrap();
    assert_eq!(back.offsets.zero[0][0], data.offsets.zero[0][0]);
    assert_eq!(back.offsets.zero[0][5].offset.x, 0.0);
    assert_eq!(back.parameters, data.parameters);
}

#[test]
fn inch_lengths_are_converted_from_their_text() {
    for (text, mm) in [
        ("1.5", 38.1),
        ("-1.5", -38.1),
        (".25", 6.35),
        ("+2.5E-1", 6.35),
        ("1e2", 2540.0),
        ("0.1", 2.54),
        ("-0", 0.0),
        ("3.", 76.2),
        ("0.000001", 0.0000254),
    ] {
        assert_eq!(read_length(text, INCH), Some(mm), "{text}");
    }
    assert_eq!(read_length("1.5", MM), Some(1.5));
    for bad in [
        "", "-", ".", "e5", "1e", "abc", "inf", "nan", "1e400", "1.2.3",
    ] {
        assert_eq!(read_length(bad, INCH), None, "{bad}");
    }
    // Forms f64 reads but the decimal path does not still convert.
    assert_eq!(read_length("infinity", INCH), None);
    let long = format!("0.{}", "3".repeat(400));
    assert!(close(read_length(&long, INCH).unwrap(), 25.4 / 3.0));
}

#[test]
fn never_panics_on_odd_text() {
    for text in [
        "\u{feff}T1",
        "T",
        "TT",
        ";",
        "T1 ;",
        "é",
        "T1\tD1",
        "\r\n\r",
        "T99999999999",
    ] {
        let _ = parse_tool_table(text, "t.tbl", MM);
        let _ = parse_var_file(text, "p.var", MM);
    }
}
