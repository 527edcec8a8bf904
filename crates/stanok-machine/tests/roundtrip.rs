//! Property tests: stored data written in each format reads back to the same data, and no text
//! makes a reader panic.

use proptest::collection::{btree_map, vec};
use proptest::prelude::*;
use stanok_canon::setup::{
    ControlData, OffsetTables, Tool, ToolEdge, ToolKind, ToolTable, WorkpieceFrame, ZeroOffset,
    PAGES, WORKPIECE_SYSTEMS, ZERO_OFFSET_SYSTEMS,
};
use stanok_canon::{LengthUnits, Pose};
use stanok_machine::control::{control_to_toml, is_offset_parameter, MAX_PARAMETER};
use stanok_machine::linuxcnc::{
    parse_tool_table, parse_var_file, write_tool_table, write_var_file,
};
use stanok_machine::{offsets_from_toml_str, tools_from_toml_str, MachineData, StoredOffsets};
use std::collections::BTreeMap;

/// A finite number: mostly the kind people type, sometimes any finite f64 at all.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-100_000i64..100_000).prop_map(|i| i as f64 / 1000.0),
        2 => -1e4..1e4f64,
        1 => any::<f64>().prop_filter("finite", |v| v.is_finite()),
    ]
}

/// Mostly zero, as real tables are.
fn sparse() -> impl Strategy<Value = f64> {
    prop_oneof![2 => Just(0.0), 1 => number()]
}

fn pose() -> impl Strategy<Value = Pose> {
    proptest::array::uniform9(sparse()).prop_map(Pose::from_array)
}

fn kind() -> impl Strategy<Value = ToolKind> {
    prop_oneof![
        Just(ToolKind::Milling),
        Just(ToolKind::Drilling),
        Just(ToolKind::Special),
        Just(ToolKind::Turning),
        Just(ToolKind::Grinding),
    ]
}

fn edge() -> impl Strategy<Value = ToolEdge> {
    (
        proptest::array::uniform3(sparse()),
        proptest::array::uniform3(sparse()),
        // A LinuxCNC table stores the diameter 2·r: keep r where 2·r is finite.
        sparse().prop_map(|r| r.abs().min(1e300)),
        sparse(),
        pose(),
        0u8..=9,
        sparse(),
        sparse(),
    )
        .prop_map(
            |(length, length_wear, radius, radius_wear, offset, orientation, front, back)| {
                ToolEdge {
                    length,
                    length_wear,
                    radius,
                    radius_wear,
                    offset,
                    orientation,
                    front_angle: front,
                    back_angle: back,
                }
            },
        )
}

/// Any tool body (the stock simulation's keys), each key present or not.
fn body() -> impl Strategy<Value = stanok_canon::setup::ToolBody> {
    use proptest::option::of;
    use stanok_canon::setup::{CutterShape, HolderSection, ToolBody};
    let shape = prop_oneof![
        Just(CutterShape::Flat),
        Just(CutterShape::Ball),
        Just(CutterShape::Bull),
        Just(CutterShape::Drill),
        Just(CutterShape::Insert),
    ];
    let len = || 0.001..500.0f64;
    let holder = (len(), 0.0..80.0f64, 0.001..80.0f64).prop_map(|(length, b, t)| HolderSection {
        length,
        bottom_diameter: b,
        top_diameter: t,
    });
    (
        (of(shape), of(0.0..5.0f64), of(1.0..179.0f64), of(len())),
        (of(len()), of(len()), of(any::<bool>()), of(0.0..90.0f64)),
        (of(len()), vec(holder, 0..3)),
    )
        .prop_map(
            |((cutter, corner, point, flute), (shank, reach, centre, ramp), (insert, holder))| {
                ToolBody {
                    cutter,
                    corner_radius: corner,
                    point_angle: point,
                    flute_length: flute,
                    shank_diameter: shank,
                    reach,
                    centre_cutting: centre,
                    ramp_angle: ramp,
                    insert_length: insert,
                    holder,
                }
            },
        )
}

fn tools(max_edges: usize, any_comment: bool) -> impl Strategy<Value = ToolTable> {
    let comment = if any_comment {
        ".{0,12}".boxed()
    } else {
        // What a .tbl line can carry: no line break, no blanks at the ends.
        "([a-zA-Z0-9#();é.-][a-zA-Z0-9 #();é.-]{0,10}[a-zA-Z0-9#();é.-])?".boxed()
    };
    let tool = (
        1u32..=u32::MAX,
        any::<u32>(),
        kind(),
        vec(edge(), 1..=max_edges),
        comment,
        body(),
    );
    vec(tool, 0..5).prop_map(move |list| {
        let mut t = ToolTable::default();
        for (number, pocket, kind, edges, comment, body) in list {
            let kind = if any_comment { kind } else { ToolKind::Milling };
            // A LinuxCNC table (the case without free comments) holds no body.
            let body = if any_comment {
                body
            } else {
                Default::default()
            };
            t.tools.insert(
                number,
                Tool {
                    number,
                    pocket,
                    kind,
                    edges,
                    comment,
                    body,
                },
            );
        }
        t
    })
}

fn parameters() -> impl Strategy<Value = BTreeMap<u32, f64>> {
    btree_map(
        (1..=MAX_PARAMETER).prop_filter("not an offset", |n| !is_offset_parameter(*n)),
        number(),
        0..5,
    )
}

/// Any offsets: every page, workpiece frames, home positions.
fn offsets() -> impl Strategy<Value = OffsetTables> {
    let zero = (0..ZERO_OFFSET_SYSTEMS, 0..PAGES, pose(), sparse());
    let frame = (
        0..WORKPIECE_SYSTEMS,
        0..PAGES,
        proptest::array::uniform3(sparse()),
        proptest::array::uniform3(-180.0..=180.0f64),
    );
    (
        vec(zero, 0..4),
        vec(frame, 0..3),
        vec(proptest::option::of(pose()), 8),
        (pose(), pose(), pose(), any::<bool>(), 1u8..=9),
    )
        .prop_map(|(zeros, frames, home, (g28, g30, g92, applied, active))| {
            let mut t = OffsetTables::default();
            for (s, p, offset, rotation_xy) in zeros {
                t.zero[s][p] = ZeroOffset {
                    offset,
                    rotation_xy,
                };
            }
            for (s, p, origin, euler) in frames {
                t.workpiece[s][p] = WorkpieceFrame { origin, euler };
            }
            t.home = home;
            (t.g28, t.g30, t.g92, t.g92_applied, t.active_system) =
                (g28, g30, g92, applied, active);
            t
        })
}

/// What a LinuxCNC parameter file holds: page 1 of the nine systems and the stored positions.
fn var_offsets() -> impl Strategy<Value = StoredOffsets> {
    (
        vec((pose(), sparse()), 9),
        (pose(), pose(), pose()),
        (any::<bool>(), 1u8..=9),
        parameters(),
    )
        .prop_map(|(page1, (g28, g30, g92), (applied, active), parameters)| {
            let mut t = OffsetTables::default();
            for (s, (offset, rotation_xy)) in page1.into_iter().enumerate() {
                t.zero[s][0] = ZeroOffset {
                    offset,
                    rotation_xy,
                };
            }
            (t.g28, t.g30, t.g92, t.g92_applied, t.active_system) =
                (g28, g30, g92, applied, active);
            StoredOffsets {
                offsets: t,
                parameters,
            }
        })
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

fn poses_close(a: &Pose, b: &Pose) -> bool {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .all(|(x, y)| close(*x, y))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn machine_toml_round_trips(
        tools in tools(4, true),
        offsets in offsets(),
        parameters in parameters(),
        inch in any::<bool>(),
    ) {
        let mut m = MachineData::default_mill();
        m.linuxcnc_units = if inch { LengthUnits::Inches } else { LengthUnits::Millimetres };
        m.control = ControlData { tools, offsets, parameters, ..Default::default() };
        let text = m.to_toml();
        let back = MachineData::from_toml_str(&text, "m.toml");
        prop_assert_eq!(back.as_ref(), Ok(&m), "{}", text);
        // The same sections read as tool and offset files.
        let control = control_to_toml(&m.control);
        let (keys, tables) = control.split_at(control.find("[[tool]]").unwrap_or(control.len()));
        prop_assert_eq!(tools_from_toml_str(tables, "t.toml"), Ok(m.control.tools.clone()));
        let o = offsets_from_toml_str(keys, "o.toml").unwrap();
        prop_assert_eq!(o.offsets, m.control.offsets);
        prop_assert_eq!(o.parameters, m.control.parameters);
    }

    #[test]
    fn tool_table_round_trips_in_mm(table in tools(1, false)) {
        // What a LinuxCNC table holds: no AxiOMA lengths or wear.
        let mut table = table;
        for t in table.tools.values_mut() {
            for e in &mut t.edges {
                (e.length, e.length_wear, e.radius_wear) = ([0.0; 3], [0.0; 3], 0.0);
            }
        }
        let text = write_tool_table(&table, LengthUnits::Millimetres);
        let back = parse_tool_table(&text, "t.tbl", LengthUnits::Millimetres);
        prop_assert_eq!(back, Ok(table), "{}", text);
    }

    #[test]
    fn tool_table_round_trips_in_inches(table in tools(1, false)) {
        let mut table = table;
        for t in table.tools.values_mut() {
            for e in &mut t.edges {
                (e.length, e.length_wear, e.radius_wear) = ([0.0; 3], [0.0; 3], 0.0);
            }
        }
        let text = write_tool_table(&table, LengthUnits::Inches);
        let back = parse_tool_table(&text, "t.tbl", LengthUnits::Inches).unwrap();
        prop_assert_eq!(back.tools.len(), table.tools.len());
        for (a, b) in table.tools.values().zip(back.tools.values()) {
            prop_assert_eq!((a.number, a.pocket, &a.comment), (b.number, b.pocket, &b.comment));
            let (ea, eb) = (a.edges[0], b.edges[0]);
            prop_assert!(poses_close(&ea.offset, &eb.offset), "{}", text);
            prop_assert!(close(ea.radius, eb.radius), "{} {}", ea.radius, eb.radius);
            prop_assert_eq!((ea.orientation, ea.front_angle, ea.back_angle), (eb.orientation, eb.front_angle, eb.back_angle));
        }
    }

    #[test]
    fn var_file_round_trips(data in var_offsets(), inch in any::<bool>()) {
        let units = if inch { LengthUnits::Inches } else { LengthUnits::Millimetres };
        let text = write_var_file(&data, units);
        let back = parse_var_file(&text, "p.var", units).unwrap();
        prop_assert_eq!(&back.parameters, &data.parameters);
        if inch {
            let (a, b) = (&data.offsets, &back.offsets);
            prop_assert!(poses_close(&a.g28, &b.g28) && poses_close(&a.g30, &b.g30) && poses_close(&a.g92, &b.g92));
            for s in 0..ZERO_OFFSET_SYSTEMS {
                prop_assert!(poses_close(&a.zero[s][0].offset, &b.zero[s][0].offset));
                prop_assert_eq!(a.zero[s][0].rotation_xy, b.zero[s][0].rotation_xy);
            }
            prop_assert_eq!((a.g92_applied, a.active_system), (b.g92_applied, b.active_system));
        } else {
            prop_assert_eq!(back, data, "{}", text);
        }
    }

    #[test]
    fn readers_never_panic(text in "[ -~\t\n;#é]{0,200}") {
        let _ = parse_tool_table(&text, "t.tbl", LengthUnits::Inches);
        let _ = parse_var_file(&text, "p.var", LengthUnits::Inches);
        let _ = MachineData::from_toml_str(&text, "m.toml");
        let _ = tools_from_toml_str(&text, "t.toml");
    }

    #[test]
    fn tool_table_word_soup_never_panics(words in vec("[TPXYZABCUVWDIJQK;tq]{1,2}[-+0-9.eE]{0,6}", 0..12)) {
        let text = words.join(" ");
        let _ = parse_tool_table(&text, "t.tbl", LengthUnits::Millimetres);
        let _ = parse_var_file(&text, "p.var", LengthUnits::Millimetres);
    }
}
