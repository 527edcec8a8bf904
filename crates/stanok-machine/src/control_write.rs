//! Writing the stored control data back as TOML, sparsely: only non-zero entries, in the order
//! of `machines/README.md`, with floats in the shortest text that reads back to the same value (so
//! that reading what was written gives the same data — property-tested).

use stanok_canon::setup::{ControlData, Tool, ToolKind};
use stanok_canon::{Pose, AXIS_LETTERS};
use std::fmt::Write;

use crate::control::{
    nonzero_workpiece_frames, nonzero_zero_offsets, tool_kind_name, WORKPIECE_CODES,
    ZERO_OFFSET_CODES,
};

/// A float as TOML writes it, exactly (`Debug` is the shortest text that reads back to the same
/// value: `1.0`, `-38.1`, `1e-7`, `inf`).
pub(crate) fn toml_float(v: f64) -> String {
    format!("{v:?}")
}

/// A string as a TOML basic string, escaped.
pub(crate) fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// `x = 1.0, z = -2.5` for the non-zero axes of `p`.
fn axis_pairs(p: &Pose) -> Vec<String> {
    p.to_array()
        .iter()
        .zip(AXIS_LETTERS)
        .filter(|(v, _)| **v != 0.0)
        .map(|(v, l)| format!("{} = {}", l.to_ascii_lowercase(), toml_float(*v)))
        .collect()
}

fn write_axis_lines(out: &mut String, p: &Pose) {
    for pair in axis_pairs(p) {
        let _ = writeln!(out, "{pair}");
    }
}

fn toml_array(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| toml_float(*x)).collect();
    format!("[{}]", items.join(", "))
}

/// The control data as machine-data TOML sections, sparse: only what differs from
/// `ControlData::default()` is written. [`crate::MachineData::from_toml_str`] (or a tool/offset
/// fragment reader) reads it back to the same data.
pub fn control_to_toml(c: &ControlData) -> String {
    let (mut keys, tables) = control_toml_parts(c);
    if !keys.is_empty() {
        keys.push('\n');
    }
    keys + &tables
}

/// The `[iperm]` / `[dperm]` sections of `c` alone: what `perm_from_toml_str` reads back.
pub fn perm_to_toml(c: &ControlData) -> String {
    control_to_toml(&ControlData {
        perm_int: c.perm_int.clone(),
        perm_double: c.perm_double.clone(),
        ..ControlData::default()
    })
}

/// The top-level keys (which TOML wants before any table) and the tables of [`control_to_toml`].
pub(crate) fn control_toml_parts(c: &ControlData) -> (String, String) {
    let mut keys = String::new();
    let mut out = String::new();
    let o = &c.offsets;
    if o.active_system != 1 {
        let code = ZERO_OFFSET_CODES
            .get(usize::from(o.active_system).wrapping_sub(1))
            .copied()
            .unwrap_or("G54");
        let _ = writeln!(keys, "active_system = \"{code}\"");
    }
    for (s, p, z) in nonzero_zero_offsets(o) {
        let _ = writeln!(
            out,
            "[[zero_offset]]\ncode = \"{}\"\npage = {}",
            ZERO_OFFSET_CODES[s],
            p + 1
        );
        write_axis_lines(&mut out, &z.offset);
        if z.rotation_xy != 0.0 {
            let _ = writeln!(out, "rotation = {}", toml_float(z.rotation_xy));
        }
        out.push('\n');
    }
    for (s, p, w) in nonzero_workpiece_frames(o) {
        let _ = writeln!(
            out,
            "[[workpiece]]\ncode = \"{}\"\npage = {}\norigin = {}\neuler = {}\n",
            WORKPIECE_CODES[s],
            p + 1,
            toml_array(&w.origin),
            toml_array(&w.euler)
        );
    }
    for (i, h) in o.home.iter().enumerate() {
        if let Some(h) = h {
            let _ = writeln!(out, "[[home]]\nnumber = {}", i + 1);
            write_axis_lines(&mut out, h);
            out.push('\n');
        }
    }
    for (name, p) in [("g28", &o.g28), ("g30", &o.g30)] {
        if *p != Pose::ZERO {
            let _ = writeln!(out, "[{name}]");
            write_axis_lines(&mut out, p);
            out.push('\n');
        }
    }
    if o.g92 != Pose::ZERO || o.g92_applied {
        out.push_str("[g92]\n");
        if o.g92_applied {
            out.push_str("applied = true\n");
        }
        write_axis_lines(&mut out, &o.g92);
        out.push('\n');
    }
    if !c.parameters.is_empty() {
        out.push_str("[parameters]\n");
        for (n, v) in &c.parameters {
            let _ = writeln!(out, "{n} = {}", toml_float(*v));
        }
        out.push('\n');
    }
    if !c.perm_int.is_empty() {
        out.push_str("[iperm]\n");
        for (n, v) in &c.perm_int {
            let _ = writeln!(out, "{n} = {v}");
        }
        out.push('\n');
    }
    if !c.perm_double.is_empty() {
        out.push_str("[dperm]\n");
        for (n, v) in &c.perm_double {
            let _ = writeln!(out, "{n} = {}", toml_float(*v));
        }
        out.push('\n');
    }
    for t in c.tools.tools.values() {
        write_tool(&mut out, t);
    }
    (keys, out)
}

fn write_tool(out: &mut String, t: &Tool) {
    let _ = writeln!(out, "[[tool]]\nnumber = {}", t.number);
    if t.pocket != 0 {
        let _ = writeln!(out, "pocket = {}", t.pocket);
    }
    if t.kind != ToolKind::default() {
        let _ = writeln!(out, "kind = \"{}\"", tool_kind_name(t.kind));
    }
    if !t.comment.is_empty() {
        let _ = writeln!(out, "comment = {}", toml_string(&t.comment));
    }
    crate::tool_body::write_body(out, &t.body, toml_float);
    for e in &t.edges {
        out.push_str("[[tool.edge]]\n");
        if e.length != [0.0; 3] {
            let _ = writeln!(out, "length = {}", toml_array(&e.length));
        }
        if e.length_wear != [0.0; 3] {
            let _ = writeln!(out, "length_wear = {}", toml_array(&e.length_wear));
        }
        for (key, v) in [
            ("radius", e.radius),
            ("radius_wear", e.radius_wear),
            ("front_angle", e.front_angle),
            ("back_angle", e.back_angle),
        ] {
            if v != 0.0 {
                let _ = writeln!(out, "{key} = {}", toml_float(v));
            }
        }
        if e.orientation != 0 {
            let _ = writeln!(out, "orientation = {}", e.orientation);
        }
        if e.offset != Pose::ZERO {
            let _ = writeln!(out, "offset = {{ {} }}", axis_pairs(&e.offset).join(", "));
        }
    }
    out.push('\n');
}
