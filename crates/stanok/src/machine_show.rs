//! `stanok machine show`: the effective machine data as text or JSON.
//!
//! Text lists what is there and leaves out what is zero (a table of 9 × 32 zero offsets is mostly
//! empty); JSON has the same entries with every field, in mm and degrees.

use serde::Serialize;
use stanok_canon::setup::{Tool, ToolEdge};
use stanok_canon::{LengthUnits, Pose, AXIS_LETTERS};
use stanok_machine::control::{
    nonzero_workpiece_frames, nonzero_zero_offsets, tool_kind_name, WORKPIECE_CODES,
    ZERO_OFFSET_CODES,
};
use stanok_machine::files::DataFileKind;
use stanok_machine::{AxisData, MachineData};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

/// Where a part of the stored data came from.
#[derive(Debug, Clone, Serialize)]
pub struct DataSource {
    /// `machine` (the machine's own data) or the file's path.
    pub from: String,
    /// What the file is (`LinuxCNC tool table`, …), or `machine data`.
    pub kind: String,
    /// Units of a LinuxCNC file (`mm`, `inch`); None for Stanok data (always mm).
    pub units: Option<&'static str>,
}

impl DataSource {
    /// A `--tools` / `--offsets` file.
    pub fn file(path: &Path, kind: Option<DataFileKind>, units: LengthUnits) -> DataSource {
        let linuxcnc = matches!(
            kind,
            Some(DataFileKind::LinuxCncToolTable | DataFileKind::LinuxCncParameters)
        );
        DataSource {
            from: path.display().to_string(),
            kind: kind.map_or("data file", DataFileKind::describe).to_string(),
            units: linuxcnc.then_some(units_name(units)),
        }
    }

    fn describe(&self) -> String {
        match self.units {
            Some(u) => format!("{} ({}, {u})", self.from, self.kind),
            None => format!("{} ({})", self.from, self.kind),
        }
    }
}

/// Where the tools and the offsets came from.
#[derive(Debug, Clone, Serialize)]
pub struct Sources {
    /// The tool table.
    pub tools: DataSource,
    /// Offsets and preset parameters.
    pub offsets: DataSource,
}

impl Sources {
    /// Both from the machine called `name`.
    pub fn machine(name: &str) -> Sources {
        let own = DataSource {
            from: format!("machine {name}"),
            kind: "machine data".into(),
            units: None,
        };
        Sources {
            tools: own.clone(),
            offsets: own,
        }
    }
}

fn units_name(u: LengthUnits) -> &'static str {
    match u {
        LengthUnits::Millimetres => "mm",
        LengthUnits::Inches => "inch",
    }
}

/// A number for people: up to six decimals, no trailing zeros (`-38.1`, `3.175`, `0`).
fn num(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// `X100 Y50` for the non-zero axes, `0` if none.
fn pose(p: &Pose) -> String {
    let parts: Vec<String> = p
        .to_array()
        .iter()
        .zip(AXIS_LETTERS)
        .filter(|(v, _)| **v != 0.0)
        .map(|(v, l)| format!("{l}{}", num(*v)))
        .collect();
    if parts.is_empty() {
        "0".into()
    } else {
        parts.join(" ")
    }
}

fn triple(v: &[f64; 3]) -> String {
    format!("{} {} {}", num(v[0]), num(v[1]), num(v[2]))
}

fn axes_table(s: &mut String, axes: &[AxisData]) {
    let _ = writeln!(
        s,
        "Axes        axis  kind    {:>10} {:>10} {:>13} {:>16} {:>10}",
        "min", "max", "velocity/min", "acceleration/s²", "jerk/s³"
    );
    for a in axes {
        let (kind, unit) = match a.kind {
            stanok_machine::AxisKind::Linear => ("linear", "mm"),
            stanok_machine::AxisKind::Rotary => ("rotary", "deg"),
        };
        let _ = writeln!(
            s,
            "            {:<4}  {kind}  {:>10} {:>10} {:>13} {:>16} {:>10}  {unit}",
            a.name,
            num(a.min),
            num(a.max),
            num(a.max_velocity),
            num(a.max_acceleration),
            num(a.max_jerk)
        );
    }
}

fn edge_text(e: &ToolEdge) -> String {
    let mut parts = Vec::new();
    if e.length != [0.0; 3] {
        parts.push(format!("L1 L2 L3 {} mm", triple(&e.length)));
    }
    if e.length_wear != [0.0; 3] {
        parts.push(format!("wear {} mm", triple(&e.length_wear)));
    }
    if e.radius != 0.0 {
        parts.push(format!("radius {} mm", num(e.radius)));
    }
    if e.radius_wear != 0.0 {
        parts.push(format!("radius wear {} mm", num(e.radius_wear)));
    }
    if e.offset != Pose::ZERO {
        parts.push(format!("offset {}", pose(&e.offset)));
    }
    if e.orientation != 0 {
        parts.push(format!("edge position {}", e.orientation));
    }
    if e.front_angle != 0.0 || e.back_angle != 0.0 {
        parts.push(format!(
            "angles front {}° back {}°",
            num(e.front_angle),
            num(e.back_angle)
        ));
    }
    if parts.is_empty() {
        "all zero".into()
    } else {
        parts.join(", ")
    }
}

fn tool_text(s: &mut String, t: &Tool) {
    let comment = if t.comment.is_empty() {
        String::new()
    } else {
        format!("  \"{}\"", t.comment)
    };
    let _ = writeln!(
        s,
        "  T{:<5} pocket {:<4} {}{comment}",
        t.number,
        t.pocket,
        tool_kind_name(t.kind)
    );
    for (i, e) in t.edges.iter().enumerate() {
        let _ = writeln!(s, "      D{}  {}", i + 1, edge_text(e));
    }
}

/// The text form.
pub fn text(m: &MachineData, sources: &Sources) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Machine     {}", m.name);
    if !m.description.is_empty() {
        let _ = writeln!(s, "            {}", m.description);
    }
    let _ = writeln!(
        s,
        "Rates       rapid {} mm/min, max feed {} mm/min",
        num(m.rapid_rate),
        num(m.max_feed)
    );
    let _ = writeln!(s, "Arcs        tolerance {} mm", num(m.arc_tolerance));
    let _ = writeln!(
        s,
        "Path        tolerance {} mm (G64 without a programmed one)",
        num(m.path_tolerance)
    );
    let _ = writeln!(
        s,
        "LinuxCNC    .tbl/.var files in {}",
        units_name(m.linuxcnc_units)
    );
    let _ = writeln!(s, "M functions {} profile (AxiOMA)", m.m_functions);
    for (label, table, unit) in [
        ("FTABLE", &m.feed_table, "mm/min"),
        ("STABLE", &m.speed_table, "rev/min"),
    ] {
        if !table.is_empty() {
            let entries: Vec<String> = table
                .iter()
                .map(|(i, v)| format!("{i}: {}", num(*v)))
                .collect();
            let _ = writeln!(
                s,
                "{label}      {} {unit} (others: the manual's defaults)",
                entries.join(", ")
            );
        }
    }
    axes_table(&mut s, &m.axes);

    let o = &m.control.offsets;
    let _ = writeln!(s, "\nOffsets     from {}", sources.offsets.describe());
    let active = ZERO_OFFSET_CODES
        .get(usize::from(o.active_system).wrapping_sub(1))
        .copied()
        .unwrap_or("?");
    let _ = writeln!(s, "  active system {active}");
    let zeros: Vec<_> = nonzero_zero_offsets(o).collect();
    if zeros.is_empty() {
        let _ = writeln!(s, "  zero offsets: all zero");
    } else {
        let _ = writeln!(
            s,
            "  zero offsets (code, page; mm/deg, machine coordinates):"
        );
        for (sys, page, z) in zeros {
            let rot = if z.rotation_xy != 0.0 {
                format!("  rotation {}°", num(z.rotation_xy))
            } else {
                String::new()
            };
            let code = format!("{} P{}", ZERO_OFFSET_CODES[sys], page + 1);
            let _ = writeln!(s, "    {code:<11} {}{rot}", pose(&z.offset));
        }
    }
    let frames: Vec<_> = nonzero_workpiece_frames(o).collect();
    if frames.is_empty() {
        let _ = writeln!(s, "  workpiece frames: none");
    } else {
        let _ = writeln!(s, "  workpiece frames (origin mm, Euler ZY'Z'' deg):");
        for (sys, page, w) in frames {
            let code = format!("{} P{}", WORKPIECE_CODES[sys], page + 1);
            let _ = writeln!(
                s,
                "    {code:<11} origin {}  euler {}",
                triple(&w.origin),
                triple(&w.euler)
            );
        }
    }
    let homes: Vec<_> = o
        .home
        .iter()
        .enumerate()
        .filter_map(|(i, h)| h.as_ref().map(|h| (i, h)))
        .collect();
    if homes.is_empty() {
        let _ = writeln!(s, "  home positions: none");
    } else {
        let _ = writeln!(s, "  home positions (machine coordinates):");
        for (i, h) in homes {
            let _ = writeln!(s, "    H{:<10} {}", i + 1, pose(h));
        }
    }
    let applied = if o.g92_applied {
        "applied"
    } else {
        "not applied"
    };
    let _ = writeln!(s, "  G28 {}   G30 {}", pose(&o.g28), pose(&o.g30));
    let _ = writeln!(s, "  G92 {} ({applied})", pose(&o.g92));
    if !m.control.parameters.is_empty() {
        let list: Vec<String> = m
            .control
            .parameters
            .iter()
            .map(|(n, v)| format!("#{n} = {}", num(*v)))
            .collect();
        let _ = writeln!(s, "  parameters {}", list.join(", "));
    }

    let tools = &m.control.tools.tools;
    let _ = writeln!(
        s,
        "\nTools       {} from {}",
        tools.len(),
        sources.tools.describe()
    );
    for t in tools.values() {
        tool_text(&mut s, t);
    }
    s
}

#[derive(Serialize)]
struct JsonMachine<'a> {
    name: &'a str,
    description: &'a str,
    rapid_rate: f64,
    max_feed: f64,
    arc_tolerance: f64,
    path_tolerance: f64,
    linuxcnc_units: &'static str,
    m_functions: &'a str,
    feed_table: &'a BTreeMap<u32, f64>,
    speed_table: &'a BTreeMap<u32, f64>,
    axes: &'a [AxisData],
}

#[derive(Serialize)]
struct JsonZeroOffset<'a> {
    code: &'static str,
    page: usize,
    offset: &'a Pose,
    rotation: f64,
}

#[derive(Serialize)]
struct JsonFrame {
    code: &'static str,
    page: usize,
    origin: [f64; 3],
    euler: [f64; 3],
}

#[derive(Serialize)]
struct JsonHome<'a> {
    number: usize,
    position: &'a Pose,
}

#[derive(Serialize)]
struct JsonShow<'a> {
    machine: JsonMachine<'a>,
    sources: &'a Sources,
    active_system: &'static str,
    zero_offsets: Vec<JsonZeroOffset<'a>>,
    workpiece_frames: Vec<JsonFrame>,
    home: Vec<JsonHome<'a>>,
    g28: &'a Pose,
    g30: &'a Pose,
    g92: &'a Pose,
    g92_applied: bool,
    parameters: &'a BTreeMap<u32, f64>,
    tools: Vec<&'a Tool>,
}

/// The JSON form: one object (mm, degrees; only the non-zero zero offsets and workpiece frames
/// and the used home positions, every field of each).
pub fn json(m: &MachineData, sources: &Sources) -> String {
    let o = &m.control.offsets;
    let show = JsonShow {
        machine: JsonMachine {
            name: &m.name,
            description: &m.description,
            rapid_rate: m.rapid_rate,
            max_feed: m.max_feed,
            arc_tolerance: m.arc_tolerance,
            path_tolerance: m.path_tolerance,
            linuxcnc_units: units_name(m.linuxcnc_units),
            m_functions: &m.m_functions,
            feed_table: &m.feed_table,
            speed_table: &m.speed_table,
            axes: &m.axes,
        },
        sources,
        active_system: ZERO_OFFSET_CODES
            .get(usize::from(o.active_system).wrapping_sub(1))
            .copied()
            .unwrap_or("?"),
        zero_offsets: nonzero_zero_offsets(o)
            .map(|(s, p, z)| JsonZeroOffset {
                code: ZERO_OFFSET_CODES[s],
                page: p + 1,
                offset: &z.offset,
                rotation: z.rotation_xy,
            })
            .collect(),
        workpiece_frames: nonzero_workpiece_frames(o)
            .map(|(s, p, w)| JsonFrame {
                code: WORKPIECE_CODES[s],
                page: p + 1,
                origin: w.origin,
                euler: w.euler,
            })
            .collect(),
        home: o
            .home
            .iter()
            .enumerate()
            .filter_map(|(i, h)| {
                h.as_ref().map(|position| JsonHome {
                    number: i + 1,
                    position,
                })
            })
            .collect(),
        g28: &o.g28,
        g30: &o.g30,
        g92: &o.g92,
        g92_applied: o.g92_applied,
        parameters: &m.control.parameters,
        tools: m.control.tools.tools.values().collect(),
    };
    serde_json::to_string_pretty(&show).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_for_people() {
        assert_eq!(num(-38.099999999999994), "-38.1");
        assert_eq!(num(3.175), "3.175");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(-0.0000001), "0");
        assert_eq!(num(100.0), "100");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(pose(&Pose::ZERO), "0");
        let mut p = Pose::ZERO;
        (p.z, p.c) = (-1.5, 90.0);
        assert_eq!(pose(&p), "Z-1.5 C90");
    }
}
