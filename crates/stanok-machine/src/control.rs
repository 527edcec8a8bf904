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
//! The tool-body keys of `[[tool]]` (cutter shape, flute length, shank, holder…) are read by
//! `tool_body.rs`.
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
    cutter: Option<Spanned<String>>,
    corner_radius: Option<Spanned<f64>>,
    point_angle: Option<Spanned<f64>>,
    flute_length: Option<Spanned<f64>>,
    shank_diameter: Option<Spanned<f64>>,
    reach: Option<Spanned<f64>>,
    centre_cutting: Option<bool>,
    ramp_angle: Option<Spanned<f64>>,
    insert_length: Option<Spanned<f64>>,
    holder: Option<Spanned<Vec<Spanned<crate::tool_body::RawHolder>>>>,
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
    /// AxiOMA `$iPerm[n]`: `[iperm]` with `n = value`.
    pub iperm: &'a Option<Spanned<BTreeMap<Spanned<String>, Spanned<i64>>>>,
    /// AxiOMA `$dPerm[n]`: `[dperm]` with `n = value`.
    pub dperm: &'a Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    pub tool: &'a Option<Spanned<Vec<Spanned<RawTool>>>>,
}

/// `[iperm]` / `[dperm]`: AxiOMA permanent parameters `n = value`, n = 0…999.
fn perm<T, V>(
    table: &Option<Spanned<BTreeMap<Spanned<String>, Spanned<V>>>>,
    name: &str,
    into: &mut BTreeMap<u32, T>,
    value: impl Fn(&Spanned<V>) -> Result<T, Invalid>,
) -> Result<(), Invalid> {
    for (key, v) in table.iter().flat_map(|p| p.get_ref()) {
        let text = key.get_ref();
        let n = text
            .trim()
            .parse::<u32>()
            .ok()
            .filter(|n| *n <= 999)
            .ok_or_else(|| {
                (
                    format!("[{name}] index must be 0…999, not \"{text}\""),
                    key.span(),
                )
            })?;
        if into.insert(n, value(v)?).is_some() {
            return Err((format!("[{name}] {n} is defined twice"), key.span()));
        }
    }
    Ok(())
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

/// The (system, page) slot an entry of a paged table names, checked for a known code, a page in
/// 1…32 and no duplicate; with the canonical code for messages.
fn table_slot(
    code: &Spanned<String>,
    page: &Option<Spanned<i64>>,
    seen: &mut Seen<(usize, usize)>,
    index: fn(&str) -> Option<usize>,
    names: &[&'static str],
    expected: &str,
) -> Result<(usize, usize, &'static str), Invalid> {
    let text = code.get_ref();
    let s = index(text).ok_or_else(|| (format!("{expected}, not \"{text}\""), code.span()))?;
    let name = names[s];
    let p = page_index(page, name)?;
    seen.check((s, p), code.span(), || format!("{name} page {}", p + 1))?;
    Ok((s, p, name))
}

impl RawZeroOffset {
    fn validate(
        &self,
        into: &mut OffsetTables,
        seen: &mut Seen<(usize, usize)>,
    ) -> Result<(), Invalid> {
        let (s, p, name) = table_slot(
            &self.code,
            &self.page,
            seen,
            zero_offset_index,
            &ZERO_OFFSET_CODES,
            "zero offset code must be one of G54…G59, G59.1…G59.3",
        )?;
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
        let (s, p, name) = table_slot(
            &self.code,
            &self.page,
            seen,
            workpiece_index,
            &WORKPIECE_CODES,
            "workpiece system code must be one of G154…G159",
        )?;
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
                body: crate::tool_body::RawToolBody {
                    cutter: &self.cutter,
                    corner_radius: &self.corner_radius,
                    point_angle: &self.point_angle,
                    flute_length: &self.flute_length,
                    shank_diameter: &self.shank_diameter,
                    reach: &self.reach,
                    centre_cutting: self.centre_cutting,
                    ramp_angle: &self.ramp_angle,
                    insert_length: &self.insert_length,
                    holder: &self.holder,
                }
                .validate(number)?,
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
            perm(self.iperm, "iperm", &mut control.perm_int, |v| {
                Ok(*v.get_ref())
            }),
            perm(self.dperm, "dperm", &mut control.perm_double, |v| {
                finite(v, "a $dPerm value")
            }),
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

pub use crate::control_write::control_to_toml;
pub(crate) use crate::control_write::{control_toml_parts, toml_float, toml_string};

#[cfg(test)]
#[path = "control_tests.rs"]
mod tests;
