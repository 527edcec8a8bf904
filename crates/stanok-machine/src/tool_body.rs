//! The tool-body keys of `[[tool]]`: what the stock-removal simulation and its collision checks
//! need beyond an edge's radius (`machines/README.md`, "Tool body").
//!
//! ```toml
//! [[tool]]
//! number = 3
//! cutter = "bull"         # flat | ball | bull | drill | insert (default: from kind)
//! corner_radius = 1.0     # bull: mm
//! point_angle = 118.0     # drill: included angle, degrees
//! flute_length = 20.0     # cutting length from the tip, mm
//! shank_diameter = 10.0   # mm
//! reach = 40.0            # tip → holder (stick-out), mm
//! centre_cutting = true   # may plunge
//! ramp_angle = 2.0        # non-centre-cutting: steepest descent in material, degrees
//! insert_length = 10.0    # turning insert: cutting-edge length from the nose, mm
//! holder = [ { diameter = 32.0, length = 40.0 }, { diameter = [32.0, 50.0], length = 20.0 } ]
//! ```
//!
//! Every key is optional; the values are kept as written (`ToolBody`), the defaults are the
//! simulation's (`stanok-stock`), so that `machine show --toml` writes back only what was given.

use crate::data::Invalid;
use serde::Deserialize;
use stanok_canon::setup::{CutterShape, HolderSection, ToolBody};
use std::fmt::Write as _;
use toml::Spanned;

/// The tool-body keys of one `[[tool]]`, as read (fields of `RawTool`: serde cannot flatten into
/// a table that refuses unknown keys).
pub(crate) struct RawToolBody<'a> {
    pub cutter: &'a Option<Spanned<String>>,
    pub corner_radius: &'a Option<Spanned<f64>>,
    pub point_angle: &'a Option<Spanned<f64>>,
    pub flute_length: &'a Option<Spanned<f64>>,
    pub shank_diameter: &'a Option<Spanned<f64>>,
    pub reach: &'a Option<Spanned<f64>>,
    pub centre_cutting: Option<bool>,
    pub ramp_angle: &'a Option<Spanned<f64>>,
    pub insert_length: &'a Option<Spanned<f64>>,
    pub holder: &'a Option<Spanned<Vec<Spanned<RawHolder>>>>,
}

/// One holder section: `{ diameter = D | [bottom, top], length = L }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawHolder {
    diameter: Spanned<RawDiameter>,
    length: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawDiameter {
    One(f64),
    Two(Vec<f64>),
}

const SHAPES: [(&str, CutterShape); 5] = [
    ("flat", CutterShape::Flat),
    ("ball", CutterShape::Ball),
    ("bull", CutterShape::Bull),
    ("drill", CutterShape::Drill),
    ("insert", CutterShape::Insert),
];

/// The TOML name of a cutter shape.
pub(crate) fn shape_name(s: CutterShape) -> &'static str {
    SHAPES
        .iter()
        .find(|(_, k)| *k == s)
        .map_or("flat", |(n, _)| n)
}

/// A length or angle key: finite and within `range` (inclusive lower bound when `zero_ok`).
fn value(
    v: &Option<Spanned<f64>>,
    what: &str,
    positive: bool,
    max: f64,
) -> Result<Option<f64>, Invalid> {
    let Some(v) = v else { return Ok(None) };
    let x = *v.get_ref();
    let ok = x.is_finite() && if positive { x > 0.0 } else { x >= 0.0 } && x <= max;
    if ok {
        Ok(Some(x))
    } else {
        let low = if positive {
            "more than 0"
        } else {
            "at least 0"
        };
        Err((
            format!("{what} must be {low} and at most {max}, not {x}"),
            v.span(),
        ))
    }
}

impl RawToolBody<'_> {
    /// The body as written, each value checked (lengths positive, angles in range).
    pub(crate) fn validate(&self, number: u32) -> Result<ToolBody, Invalid> {
        let what = |key: &str| format!("T{number} {key}");
        let cutter = match self.cutter {
            None => None,
            Some(c) => Some(
                SHAPES
                    .iter()
                    .find(|(n, _)| *n == c.get_ref().as_str())
                    .map(|(_, s)| *s)
                    .ok_or_else(|| {
                        (
                            format!(
                                "T{number} cutter must be flat, ball, bull, drill or insert, not \"{}\"",
                                c.get_ref()
                            ),
                            c.span(),
                        )
                    })?,
            ),
        };
        const LONG: f64 = 10_000.0;
        let mut holder = Vec::new();
        for h in self.holder.iter().flat_map(|v| v.get_ref()) {
            let h = h.get_ref();
            let (bottom, top) = match h.diameter.get_ref() {
                RawDiameter::One(d) => (*d, *d),
                RawDiameter::Two(v) if v.len() == 2 => (v[0], v[1]),
                RawDiameter::Two(_) => {
                    return Err((
                        format!("T{number} holder diameter must be a number or [bottom, top]"),
                        h.diameter.span(),
                    ))
                }
            };
            if !(bottom.is_finite() && top.is_finite() && bottom >= 0.0 && top >= 0.0)
                || bottom.max(top) <= 0.0
                || bottom.max(top) > LONG
            {
                return Err((
                    format!(
                        "T{number} holder diameters must be at least 0, not both 0, at most {LONG}"
                    ),
                    h.diameter.span(),
                ));
            }
            let length =
                value(&Some(h.length.clone()), &what("holder length"), true, LONG)?.unwrap_or(0.0);
            holder.push(HolderSection {
                length,
                bottom_diameter: bottom,
                top_diameter: top,
            });
        }
        Ok(ToolBody {
            cutter,
            corner_radius: value(self.corner_radius, &what("corner_radius"), false, LONG)?,
            point_angle: value(self.point_angle, &what("point_angle"), true, 179.0)?,
            flute_length: value(self.flute_length, &what("flute_length"), true, LONG)?,
            shank_diameter: value(self.shank_diameter, &what("shank_diameter"), true, LONG)?,
            reach: value(self.reach, &what("reach"), true, LONG)?,
            centre_cutting: self.centre_cutting,
            ramp_angle: value(self.ramp_angle, &what("ramp_angle"), false, 90.0)?,
            insert_length: value(self.insert_length, &what("insert_length"), true, LONG)?,
            holder,
        })
    }
}

/// The body's keys for `[[tool]]`, sparse (only what was written).
pub(crate) fn write_body(out: &mut String, b: &ToolBody, float: impl Fn(f64) -> String) {
    if let Some(c) = b.cutter {
        let _ = writeln!(out, "cutter = \"{}\"", shape_name(c));
    }
    for (key, v) in [
        ("corner_radius", b.corner_radius),
        ("point_angle", b.point_angle),
        ("flute_length", b.flute_length),
        ("shank_diameter", b.shank_diameter),
        ("reach", b.reach),
    ] {
        if let Some(v) = v {
            let _ = writeln!(out, "{key} = {}", float(v));
        }
    }
    if let Some(c) = b.centre_cutting {
        let _ = writeln!(out, "centre_cutting = {c}");
    }
    for (key, v) in [
        ("ramp_angle", b.ramp_angle),
        ("insert_length", b.insert_length),
    ] {
        if let Some(v) = v {
            let _ = writeln!(out, "{key} = {}", float(v));
        }
    }
    if !b.holder.is_empty() {
        let sections: Vec<String> = b
            .holder
            .iter()
            .map(|h| {
                let d = if h.bottom_diameter == h.top_diameter {
                    float(h.bottom_diameter)
                } else {
                    format!("[{}, {}]", float(h.bottom_diameter), float(h.top_diameter))
                };
                format!("{{ diameter = {d}, length = {} }}", float(h.length))
            })
            .collect();
        let _ = writeln!(out, "holder = [{}]", sections.join(", "));
    }
}
