//! The control's stored data in machine-data TOML: zero-offset tables, workpiece frames, home
//! positions, the LinuxCNC stored positions, preset parameters and the tool table.
//!
//! The schema, key by key with units, is in `machines/README.md`; `machines/example-offsets-tools.toml`
//! shows every section. In short (all optional; lengths mm, angles degrees, machine frame):
//!
//! ```toml
//! active_system = "G54"   # LinuxCNC system selected at start (#5220), G54…G59.3
//!
//! [[zero_offset]]         # G54…G59 (AxiOMA pages 1…32), G59.1…G59.3 (LinuxCNC)
//! code = "G54"
//! page = 1                # 1…32, default 1
//! x = 100.0               # any of x y z u v w (mm) and a b c (deg); absent = 0
//! rotation = 0.0          # deg about Z, counter-clockwise (LinuxCNC G10 L2 R)
//!
//! [[workpiece]]           # AxiOMA G154…G159
//! code = "G154"
//! page = 1
//! origin = [100.0, 0.0, 0.0]   # mm, machine coordinates
//! euler = [90.0, 0.0, 0.0]     # φ θ ψ, ZY'Z'', deg, each in −180…180
//!
//! [[home]]                # AxiOMA H1…H8 (G28/G29)
//! number = 1
//! x = 0.0                 # axes as in [[zero_offset]]
//!
//! [g28]                   # LinuxCNC stored positions (#5161…, #5181…), axes as above
//! [g30]
//! [g92]                   # LinuxCNC G92 offset (#5211…) and `applied = true` (#5210)
//!
//! [parameters]            # other numbered parameters to preset: 31 = 2.5
//!
//! [[tool]]
//! number = 10             # T, ≥ 1, unique
//! pocket = 10             # magazine pocket, ≥ 0, default 0
//! kind = "turning"        # milling | drilling | special | turning | grinding (default milling)
//! comment = "…"
//! [[tool.edge]]           # D1, D2, … in order: 1…4 edges
//! length = [250.0, 40.0]  # L1 L2 L3, mm (1…3 values, the rest 0)
//! length_wear = [0.0]     # wear of L1…L3, mm
//! radius = 0.8            # r1, mm, ≥ 0
//! radius_wear = 0.3       # mm
//! orientation = 3         # lathe cutting-edge position 0…9
//! front_angle = 0.0       # deg (LinuxCNC I)
//! back_angle = 0.0        # deg (LinuxCNC J)
//! offset = { z = -1.5 }   # LinuxCNC per-axis tool offset, axes as above
//! ```
//!
//! Reading keeps every value's byte range (`toml::Spanned`) so that a validation failure points at
//! the value; writing ([`control_to_toml`]) is sparse: only what differs from the empty control.

use crate::data::Invalid;
use serde::Deserialize;
use stanok_canon::setup::{
    ControlData, OffsetTables, Tool, ToolEdge, ToolKind, ToolTable, WorkpieceFrame, ZeroOffset,
    HOME_POSITIONS, PAGES,
};
use stanok_canon::{Pose, AXIS_LETTERS};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::ops::Range;
use toml::Spanned;

/// Codes of the zero-offset systems, by index of `OffsetTables::zero`.
pub const ZERO_OFFSET_CODES: [&str; 9] = [
    "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
];

/// Codes of the workpiece systems, by index of `OffsetTables::workpiece`.
pub const WORKPIECE_CODES: [&str; 6] = ["G154", "G155", "G156", "G157", "G158", "G159"];

/// Most cutting edges a tool may have (AxiOMA D1…D4).
pub const MAX_EDGES: usize = 4;

/// Highest lathe cutting-edge position code (LinuxCNC `Q`).
pub const MAX_ORIENTATION: u8 = 9;

/// Index (0 = G54 … 8 = G59.3) of a zero-offset code; `None` if it is not one.
pub fn zero_offset_index(code: &str) -> Option<usize> {
    let code = code.trim().to_ascii_uppercase();
    ZERO_OFFSET_CODES.iter().position(|c| *c == code)
}

/// Index (0 = G154 … 5 = G159) of a workpiece-system code; `None` if it is not one.
pub fn workpiece_index(code: &str) -> Option<usize> {
    let code = code.trim().to_ascii_uppercase();
    WORKPIECE_CODES.iter().position(|c| *c == code)
}

/// The TOML name of a tool kind.
pub fn tool_kind_name(kind: ToolKind) -> &'static str {
    match kind {
        ToolKind::Milling => "milling",
        ToolKind::Drilling => "drilling",
        ToolKind::Special => "special",
        ToolKind::Turning => "turning",
        ToolKind::Grinding => "grinding",
    }
}

fn tool_kind(name: &str) -> Option<ToolKind> {
    [
        ToolKind::Milling,
        ToolKind::Drilling,
        ToolKind::Special,
        ToolKind::Turning,
        ToolKind::Grinding,
    ]
    .into_iter()
    .find(|k| tool_kind_name(*k) == name)
}

/// The zero offsets that differ from zero: (system index, page index, offset), systems then pages.
pub fn nonzero_zero_offsets(t: &OffsetTables) -> impl Iterator<Item = (usize, usize, &ZeroOffset)> {
    t.zero.iter().enumerate().flat_map(|(s, pages)| {
        pages
            .iter()
            .enumerate()
            .filter(|(_, z)| **z != ZeroOffset::default())
            .map(move |(p, z)| (s, p, z))
    })
}

/// The workpiece frames that differ from the identity: (system index, page index, frame).
pub fn nonzero_workpiece_frames(
    t: &OffsetTables,
) -> impl Iterator<Item = (usize, usize, &WorkpieceFrame)> {
    t.workpiece.iter().enumerate().flat_map(|(s, pages)| {
        pages
            .iter()
            .enumerate()
            .filter(|(_, w)| **w != WorkpieceFrame::default())
            .map(move |(p, w)| (s, p, w))
    })
}

/// Declares a raw TOML table that may carry the nine axis keys `x y z a b c u v w`.
macro_rules! with_axes {
    ($(#[$meta:meta])* struct $name:ident { $($field:ident : $ty:ty,)* }) => {
        $(#[$meta])*
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        pub(crate) struct $name {
            $($field: $ty,)*
            x: Option<Spanned<f64>>,
            y: Option<Spanned<f64>>,
            z: Option<Spanned<f64>>,
            a: Option<Spanned<f64>>,
            b: Option<Spanned<f64>>,
            c: Option<Spanned<f64>>,
            u: Option<Spanned<f64>>,
            v: Option<Spanned<f64>>,
            w: Option<Spanned<f64>>,
        }

        impl $name {
            /// The axis values, absent = 0, each finite.
            fn pose(&self, what: &str) -> Result<Pose, Invalid> {
                let axes = [
                    &self.x, &self.y, &self.z, &self.a, &self.b, &self.c, &self.u, &self.v, &self.w,
                ];
                let mut v = [0.0; 9];
                for (i, axis) in axes.into_iter().enumerate() {
                    if let Some(value) = axis {
                        let letter = AXIS_LETTERS[i].to_ascii_lowercase();
                        v[i] = finite(value, &format!("{what} {letter}"))?;
                    }
                }
                Ok(Pose::from_array(v))
            }
        }
    };
}

with_axes! {
    /// `[[zero_offset]]`.
    struct RawZeroOffset {
        code: Spanned<String>,
        page: Option<Spanned<i64>>,
        rotation: Option<Spanned<f64>>,
    }
}

with_axes! {
    /// `[[home]]`.
    struct RawHome {
        number: Spanned<i64>,
    }
}

with_axes! {
    /// `[g28]`, `[g30]`, an edge's `offset`.
    struct RawPose {}
}

with_axes! {
    /// `[g92]`.
    struct RawG92 {
        applied: Option<bool>,
    }
}

/// `[[workpiece]]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawWorkpiece {
    code: Spanned<String>,
    page: Option<Spanned<i64>>,
    origin: Option<Spanned<Vec<Spanned<f64>>>>,
    euler: Option<Spanned<Vec<Spanned<f64>>>>,
}

/// `[[tool]]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTool {
    number: Spanned<i64>,
    pocket: Option<Spanned<i64>>,
    kind: Option<Spanned<String>>,
    comment: Option<String>,
    edge: Option<Spanned<Vec<Spanned<RawEdge>>>>,
}

/// `[[tool.edge]]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawEdge {
    length: Option<Spanned<Vec<Spanned<f64>>>>,
    length_wear: Option<Spanned<Vec<Spanned<f64>>>>,
    radius: Option<Spanned<f64>>,
    radius_wear: Option<Spanned<f64>>,
    orientation: Option<Spanned<i64>>,
    front_angle: Option<Spanned<f64>>,
    back_angle: Option<Spanned<f64>>,
    offset: Option<RawPose>,
}

/// The control-data keys of a machine-data file (all optional), as read.
pub(crate) struct RawControl<'a> {
    pub active_system: &'a Option<Spanned<String>>,
    pub zero_offset: &'a Option<Spanned<Vec<Spanned<RawZeroOffset>>>>,
    pub workpiece: &'a Option<Spanned<Vec<Spanned<RawWorkpiece>>>>,
    pub home: &'a Option<Spanned<Vec<Spanned<RawHome>>>>,
    pub g28: &'a Option<Spanned<RawPose>>,
    pub g30: &'a Option<Spanned<RawPose>>,
    pub g92: &'a Option<Spanned<RawG92>>,
    pub parameters: &'a Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    pub tool: &'a Option<Spanned<Vec<Spanned<RawTool>>>>,
}

fn finite(value: &Spanned<f64>, what: &str) -> Result<f64, Invalid> {
    let v = *value.get_ref();
    if v.is_finite() {
        Ok(v)
    } else {
        Err((
            format!("{what} must be a finite number, not {v}"),
            value.span(),
        ))
    }
}

fn opt_finite(value: &Option<Spanned<f64>>, what: &str) -> Result<f64, Invalid> {
    value.as_ref().map_or(Ok(0.0), |v| finite(v, what))
}

/// Page index 0…31 from `page = 1…32` (absent = page 1).
fn page_index(page: &Option<Spanned<i64>>, code: &str) -> Result<usize, Invalid> {
    let Some(page) = page else { return Ok(0) };
    let p = *page.get_ref();
    if (1..=PAGES as i64).contains(&p) {
        Ok(p as usize - 1)
    } else {
        Err((
            format!("{code}: page {p} is outside 1…{PAGES}"),
            page.span(),
        ))
    }
}

/// `min_len` to 3 numbers (the rest 0), each finite; absent = all 0.
fn triple(
    values: &Option<Spanned<Vec<Spanned<f64>>>>,
    what: &str,
    min_len: usize,
) -> Result<[f64; 3], Invalid> {
    let mut out = [0.0; 3];
    let Some(values) = values else {
        return Ok(out);
    };
    let n = values.get_ref().len();
    if n < min_len || n > 3 {
        let want = if min_len == 3 {
            "exactly 3".to_string()
        } else {
            format!("{min_len} to 3")
        };
        return Err((
            format!("{what} needs {want} numbers, not {n}"),
            values.span(),
        ));
    }
    for (i, v) in values.get_ref().iter().enumerate() {
        out[i] = finite(v, &format!("{what}[{i}]"))?;
    }
    Ok(out)
}

/// Remembers where each key of a table (code and page, H number, T number) was first written.
struct Seen<K: Ord>(BTreeMap<K, Range<usize>>);

impl<K: Ord> Seen<K> {
    fn new() -> Self {
        Seen(BTreeMap::new())
    }

    fn check(
        &mut self,
        key: K,
        span: Range<usize>,
        what: impl FnOnce() -> String,
    ) -> Result<(), Invalid> {
        if self.0.contains_key(&key) {
            return Err((format!("{} is defined twice", what()), span));
        }
        self.0.insert(key, span);
        Ok(())
    }
}

/// Is `n` one of the LinuxCNC parameters that [`OffsetTables`] holds (5161…5169, 5181…5189,
/// 5210…5220, and 5221…5230 + 20·k for the nine systems)?
pub fn is_offset_parameter(n: u32) -> bool {
    matches!(n, 5161..=5169 | 5181..=5189 | 5210..=5220)
        || ((5221..=5390).contains(&n) && (n - 5221) % 20 < 10)
}

/// Highest LinuxCNC parameter number (`RS274NGC_MAX_PARAMETERS` − 1).
pub const MAX_PARAMETER: u32 = 5601;

impl RawZeroOffset {
    fn validate(
        &self,
        into: &mut OffsetTables,
        seen: &mut Seen<(usize, usize)>,
    ) -> Result<(), Invalid> {
        let code = self.code.get_ref();
        let s = zero_offset_index(code).ok_or_else(|| {
            (
                format!("zero offset code must be one of G54…G59, G59.1…G59.3, not \"{code}\""),
                self.code.span(),
            )
        })?;
        let name = ZERO_OFFSET_CODES[s];
        let p = page_index(&self.page, name)?;
        seen.check((s, p), self.code.span(), || {
            format!("{name} page {}", p + 1)
        })?;
        into.zero[s][p] = ZeroOffset {
            offset: self.pose(name)?,
            rotation_xy: opt_finite(&self.rotation, &format!("{name} rotation"))?,
        };
        Ok(())
    }
}

impl RawWorkpiece {
    fn validate(
        &self,
        into: &mut OffsetTables,
        seen: &mut Seen<(usize, usize)>,
    ) -> Result<(), Invalid> {
        let code = self.code.get_ref();
        let s = workpiece_index(code).ok_or_else(|| {
            (
                format!("workpiece system code must be one of G154…G159, not \"{code}\""),
                self.code.span(),
            )
        })?;
        let name = WORKPIECE_CODES[s];
        let p = page_index(&self.page, name)?;
        seen.check((s, p), self.code.span(), || {
            format!("{name} page {}", p + 1)
        })?;
        let origin = triple(&self.origin, &format!("{name} origin"), 3)?;
        let euler = triple(&self.euler, &format!("{name} euler"), 3)?;
        if let Some(angles) = &self.euler {
            for (i, a) in euler.iter().enumerate() {
                if a.abs() > 180.0 {
                    return Err((
                        format!("{name} euler[{i}] = {a}° is outside −180…180°"),
                        angles.get_ref()[i].span(),
                    ));
                }
            }
        }
        into.workpiece[s][p] = WorkpieceFrame { origin, euler };
        Ok(())
    }
}

impl RawHome {
    fn validate(&self, into: &mut OffsetTables, seen: &mut Seen<usize>) -> Result<(), Invalid> {
        let n = *self.number.get_ref();
        if !(1..=HOME_POSITIONS as i64).contains(&n) {
            return Err((
                format!("home position number {n} is outside 1…{HOME_POSITIONS}"),
                self.number.span(),
            ));
        }
        let i = n as usize - 1;
        seen.check(i, self.number.span(), || format!("home position H{n}"))?;
        into.home[i] = Some(self.pose(&format!("H{n}"))?);
        Ok(())
    }
}

impl RawEdge {
    fn validate(&self, tool: u32, d: usize) -> Result<ToolEdge, Invalid> {
        let what = format!("T{tool} D{d}");
        let radius = opt_finite(&self.radius, &format!("{what} radius"))?;
        if radius < 0.0 {
            let span = self.radius.as_ref().map(Spanned::span).unwrap_or_default();
            return Err((
                format!("{what} radius must not be negative, not {radius} mm"),
                span,
            ));
        }
        let orientation = match &self.orientation {
            None => 0,
            Some(q) => match u8::try_from(*q.get_ref()) {
                Ok(q) if q <= MAX_ORIENTATION => q,
                _ => {
                    return Err((
                        format!(
                            "{what} orientation (cutting-edge position) must be 0…{MAX_ORIENTATION}, not {}",
                            q.get_ref()
                        ),
                        q.span(),
                    ))
                }
            },
        };
        Ok(ToolEdge {
            length: triple(&self.length, &format!("{what} length"), 1)?,
            length_wear: triple(&self.length_wear, &format!("{what} length_wear"), 1)?,
            radius,
            radius_wear: opt_finite(&self.radius_wear, &format!("{what} radius_wear"))?,
            offset: match &self.offset {
                Some(o) => o.pose(&format!("{what} offset"))?,
                None => Pose::ZERO,
            },
            orientation,
            front_angle: opt_finite(&self.front_angle, &format!("{what} front_angle"))?,
            back_angle: opt_finite(&self.back_angle, &format!("{what} back_angle"))?,
        })
    }
}

impl RawTool {
    fn validate(&self, into: &mut ToolTable, seen: &mut Seen<u32>) -> Result<(), Invalid> {
        let n = *self.number.get_ref();
        let number = u32::try_from(n).ok().filter(|n| *n >= 1).ok_or_else(|| {
            (
                format!("tool number must be 1…{}, not {n}", u32::MAX),
                self.number.span(),
            )
        })?;
        seen.check(number, self.number.span(), || format!("tool T{number}"))?;
        let pocket = match &self.pocket {
            None => 0,
            Some(p) => u32::try_from(*p.get_ref()).map_err(|_| {
                (
                    format!(
                        "T{number} pocket must be 0…{}, not {}",
                        u32::MAX,
                        p.get_ref()
                    ),
                    p.span(),
                )
            })?,
        };
        let kind = match &self.kind {
            None => ToolKind::default(),
            Some(k) => tool_kind(k.get_ref()).ok_or_else(|| {
                (
                    format!(
                        "T{number} kind must be milling, drilling, special, turning or grinding, not \"{}\"",
                        k.get_ref()
                    ),
                    k.span(),
                )
            })?,
        };
        let Some(edges) = &self.edge else {
            return Err((
                format!("T{number} needs at least one [[tool.edge]] (D1)"),
                self.number.span(),
            ));
        };
        if edges.get_ref().is_empty() {
            return Err((
                format!("T{number} needs at least one edge (D1)"),
                edges.span(),
            ));
        }
        if let Some(extra) = edges.get_ref().get(MAX_EDGES) {
            return Err((
                format!("T{number} has more than {MAX_EDGES} edges (D1…D{MAX_EDGES})"),
                extra.span(),
            ));
        }
        let edges = edges
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, e)| e.get_ref().validate(number, i + 1))
            .collect::<Result<Vec<_>, _>>()?;
        into.tools.insert(
            number,
            Tool {
                number,
                pocket,
                kind,
                edges,
                comment: self.comment.clone().unwrap_or_default(),
            },
        );
        Ok(())
    }
}

/// Validates each section on its own and returns the error that comes first in the file.
fn first_error(results: impl IntoIterator<Item = Result<(), Invalid>>) -> Result<(), Invalid> {
    results
        .into_iter()
        .filter_map(Result::err)
        .min_by_key(|(_, r)| r.start)
        .map_or(Ok(()), Err)
}

impl RawControl<'_> {
    /// The stored data these sections describe (everything absent is zero / empty).
    pub(crate) fn validate(&self) -> Result<ControlData, Invalid> {
        let mut control = ControlData::default();
        let offsets = &mut control.offsets;
        let results = [
            self.validate_active(offsets),
            self.validate_zero_offsets(offsets),
            self.validate_workpiece_frames(offsets),
            self.validate_homes(offsets),
            self.validate_positions(offsets),
            self.validate_parameters(&mut control.parameters),
            self.validate_tools(&mut control.tools),
        ];
        first_error(results)?;
        Ok(control)
    }

    fn validate_active(&self, offsets: &mut OffsetTables) -> Result<(), Invalid> {
        if let Some(code) = &self.active_system {
            let s = zero_offset_index(code.get_ref()).ok_or_else(|| {
                (
                    format!(
                        "active_system must be one of G54…G59, G59.1…G59.3, not \"{}\"",
                        code.get_ref()
                    ),
                    code.span(),
                )
            })?;
            offsets.active_system = s as u8 + 1;
        }
        Ok(())
    }

    fn validate_zero_offsets(&self, offsets: &mut OffsetTables) -> Result<(), Invalid> {
        let mut seen = Seen::new();
        for z in self.zero_offset.iter().flat_map(|v| v.get_ref()) {
            z.get_ref().validate(offsets, &mut seen)?;
        }
        Ok(())
    }

    fn validate_workpiece_frames(&self, offsets: &mut OffsetTables) -> Result<(), Invalid> {
        let mut seen = Seen::new();
        for w in self.workpiece.iter().flat_map(|v| v.get_ref()) {
            w.get_ref().validate(offsets, &mut seen)?;
        }
        Ok(())
    }

    fn validate_homes(&self, offsets: &mut OffsetTables) -> Result<(), Invalid> {
        let mut seen = Seen::new();
        for h in self.home.iter().flat_map(|v| v.get_ref()) {
            h.get_ref().validate(offsets, &mut seen)?;
        }
        Ok(())
    }

    fn validate_positions(&self, offsets: &mut OffsetTables) -> Result<(), Invalid> {
        if let Some(p) = &self.g28 {
            offsets.g28 = p.get_ref().pose("g28")?;
        }
        if let Some(p) = &self.g30 {
            offsets.g30 = p.get_ref().pose("g30")?;
        }
        if let Some(p) = &self.g92 {
            offsets.g92 = p.get_ref().pose("g92")?;
            offsets.g92_applied = p.get_ref().applied.unwrap_or(false);
        }
        Ok(())
    }

    fn validate_parameters(&self, into: &mut BTreeMap<u32, f64>) -> Result<(), Invalid> {
        for (key, value) in self.parameters.iter().flat_map(|p| p.get_ref()) {
            let text = key.get_ref();
            let n = text
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|n| (1..=MAX_PARAMETER).contains(n))
                .ok_or_else(|| {
                    (
                        format!("parameter number must be 1…{MAX_PARAMETER}, not \"{text}\""),
                        key.span(),
                    )
                })?;
            if is_offset_parameter(n) {
                return Err((
                    format!(
                        "parameter {n} is a stored offset: write it in [[zero_offset]], [g28], [g30], [g92] or active_system"
                    ),
                    key.span(),
                ));
            }
            let v = finite(value, &format!("parameter {n}"))?;
            if into.insert(n, v).is_some() {
                return Err((format!("parameter {n} is defined twice"), key.span()));
            }
        }
        Ok(())
    }

    fn validate_tools(&self, into: &mut ToolTable) -> Result<(), Invalid> {
        let mut seen = Seen::new();
        for t in self.tool.iter().flat_map(|v| v.get_ref()) {
            t.get_ref().validate(into, &mut seen)?;
        }
        Ok(())
    }
}

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

#[cfg(test)]
mod tests {
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
            &format!("active_system = \"G59.2\"\n{HEAD}[[zero_offset]]\ncode = \"G59\"\npage = 32\nw = 1\n"),
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
        let (m, line, _) =
            err("[[tool]]\nnumber = 7\n[[tool.edge]]\n[[tool.edge]]\nradius = -0.5\n");
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
        let ok = machine("[[tool]]\nnumber = 9\n[[tool.edge]]\nradius = 1\nradius_wear = -0.1\n")
            .unwrap();
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
        let (m, line, _) =
            err("[[home]]\nnumber = 0\n[[zero_offset]]\ncode = \"G54\"\npage = 40\n");
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
        let d =
            tools_from_toml_str(&format!("{tools}[[home]]\nnumber = 1\n"), "t.toml").unwrap_err();
        assert!(
            d.message.contains("only [[tool]] sections, not `home`"),
            "{d}"
        );
        assert_eq!(d.span.line, 5);
        let offsets = "active_system = \"G55\"\n[[zero_offset]]\ncode = \"G55\"\nx = 1.5\n[parameters]\n31 = 1\n";
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
}
