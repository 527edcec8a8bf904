//! Machine data: what a machine can do and what its control stores, read from TOML.
//!
//! ## Schema
//!
//! ```toml
//! name = "mill"                 # required, non-empty
//! description = "…"             # optional
//! rapid_rate = 10000.0          # mm/min, > 0
//! max_feed = 5000.0             # mm/min, > 0
//! arc_tolerance = 0.01          # mm, ≥ 0
//! path_tolerance = 0.05         # mm, > 0, optional (G64 without a programmed tolerance)
//! linuxcnc_units = "mm"         # optional, "mm" | "inch": units of LinuxCNC .tbl/.var files
//! rs274_arc_tolerance = "document" # optional, "document" | "linuxcnc": RS274/NGC's arc-end rule
//! m_functions = "generic"       # optional, AxiOMA M-function profile: "generic" | "beavermill"
//! [channel]                     # optional AxiOMA channel parameters (`data/channel.rs`)
//! [[axis]]                      # one table per axis, at least one
//! name = "X"                    # X Y Z U V W (linear, mm) or A B C (rotary, deg); no duplicates
//! kind = "linear"               # "linear" | "rotary", must match the letter
//! min = -500.0                  # mm | deg, ≤ max (±inf allowed: an endless rotary axis)
//! max = 500.0
//! max_velocity = 10000.0        # mm/min | deg/min, > 0
//! max_acceleration = 1000.0     # mm/s² | deg/s², > 0
//! max_jerk = 20000.0            # mm/s³ | deg/s³, > 0
//! ```
//! plus the optional stored-data sections of [`crate::control`] (`active_system`, `[[zero_offset]]`,
//! `[[workpiece]]`, `[[home]]`, `[g28]`, `[g30]`, `[g92]`, `[parameters]`, `[[tool]]`).
//! `machines/mill.toml` at the repository root is a commented example, equal to the built-in `mill`;
//! `machines/example-offsets-tools.toml` shows every section; `machines/README.md` documents every
//! key.
//!
//! ## Reading
//!
//! 1. `toml` parses the text into private `Raw*` structs whose fields are `toml::Spanned`, so every
//!    value keeps the byte range it was written at. Unknown keys are errors (a typo must not be
//!    silently ignored on a machine).
//! 2. Validation walks the rules above and stops at a violation (of the sections, the one first in
//!    the file).
//! 3. Any failure becomes a [`Diagnostic`] with code `machine::bad-data`, the byte range converted to
//!    a 1-based line and column, and a note naming the file. Nothing here panics on any input.
//!
//! A tool or offset file given to `stanok --tools/--offsets` is the same TOML holding only the
//! `[[tool]]` sections, or only the offset sections ([`tools_from_toml_str`],
//! [`offsets_from_toml_str`]).

use crate::control::{control_toml_parts, toml_float, toml_string, RawControl};
use crate::control::{RawG92, RawHome, RawPose, RawTool, RawWorkpiece, RawZeroOffset};
use serde::{Deserialize, Serialize};
use stanok_canon::setup::ControlData;
use stanok_canon::{Diagnostic, LengthUnits, Span, AXIS_LETTERS};
use stanok_kin::{FiveAxis, KinematicsData};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

mod builtins;
mod channel;
mod mazatrol;
mod sections;
mod stock;
mod stored;
mod to_toml;
pub use channel::ChannelData;
pub use mazatrol::{MazatrolData, MazatrolFeedMode, MazatrolSeries};
pub use sections::PATH_TOLERANCE;
use sections::{rate_table, tolerance, validate_kinematics};
pub use stock::StockData;
pub use stored::{
    offsets_from_toml_str, perm_from_toml_str, tools_from_toml_str, PermParameters, StoredOffsets,
};

/// Diagnostic code of every machine-data problem.
pub const BAD_DATA: &str = "machine::bad-data";

/// What a machine is and can do, and what its control stores. All values are in the units their
/// docs give; positions are machine coordinates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MachineData {
    /// Short name, as given to `--machine` (e.g. `mill`).
    pub name: String,
    /// One line for people.
    pub description: String,
    /// Rapid (G0) path rate of the channel, mm/min.
    pub rapid_rate: f64,
    /// Highest programmable path feed, mm/min; a higher F is clamped to it.
    pub max_feed: f64,
    /// How far the end of a programmed arc may miss the circle, mm (AxiOMA 621/622/623; spec
    /// axioma-2 §2.3.8).
    pub arc_tolerance: f64,
    /// The path tolerance of continuous-path mode without a programmed one (AxiOMA G64, whose
    /// tolerance is machine data; RS274/NGC G64 without P; the lab controls), mm.
    pub path_tolerance: f64,
    /// The axes, in file order.
    pub axes: Vec<AxisData>,
    /// Length unit of the LinuxCNC tool tables (`.tbl`) and parameter files (`.var`) this machine
    /// exchanges: LinuxCNC writes them in the machine's units (its `[TRAJ] LINEAR_UNITS`). Stanok's
    /// own data is always mm.
    pub linuxcnc_units: LengthUnits,
    /// RS274/NGC's arc-end tolerance is LinuxCNC 2.9's default (0.002828 in / 0.02828 mm), not
    /// the document's (0.0005 in / 0.005 mm; spec rs274ngc §4.3.1 and ambiguity 1).
    pub rs274_linuxcnc_arc_tolerance: bool,
    /// The stored data the interpreter reads: tool table, offset tables, preset parameters.
    pub control: ControlData,
    /// The AxiOMA M-function profile of the channel (spec axioma-2 §4, §5): one of
    /// [`M_FUNCTION_PROFILES`]; the interpreter holds the tables themselves.
    pub m_functions: String,
    /// The machine's kinematics (`[kinematics]`); None = Cartesian (3-axis, or rotary axes
    /// without tool-centre-point control).
    pub kinematics: Option<KinematicsData>,
    /// AxiOMA channel feed table (`FTABLE(i)`, `[feed_table]` with `i = mm/min`, i = 0…127):
    /// the entries that replace the manual's defaults; the others keep them.
    pub feed_table: BTreeMap<u32, f64>,
    /// AxiOMA channel spindle-speed table (`STABLE(i)`, `[speed_table]`, rev/min), as `feed_table`.
    pub speed_table: BTreeMap<u32, f64>,
    /// AxiOMA channel parameters (`[channel]`: encoder, PLC outputs, compensation depth, edge
    /// positions); absent keys keep the control's defaults.
    pub channel: ChannelData,
    /// The Mazatrol EIA/ISO control's parameters (`[mazatrol]`); None = the defaults.
    pub mazatrol: Option<MazatrolData>,
    /// The stock-removal simulation's data (`[stock]`): stock, its frame, resolution, fixture.
    pub stock: Option<StockData>,
}

/// The built-in 5-axis machines (`--machine NAME`), each a TOML file of `machines/`.
pub const BUILTIN_FIVE_AXIS: [(&str, &str); 8] = [
    (
        "5axis-bc-head",
        include_str!("../../../machines/5axis-bc-head.toml"),
    ),
    (
        "5axis-ab-head",
        include_str!("../../../machines/5axis-ab-head.toml"),
    ),
    (
        "5axis-ac-table",
        include_str!("../../../machines/5axis-ac-table.toml"),
    ),
    (
        "5axis-bc-head-table",
        include_str!("../../../machines/5axis-bc-head-table.toml"),
    ),
    (
        "millturn-bc",
        include_str!("../../../machines/millturn-bc.toml"),
    ),
    (
        "5axis-cvu-tt",
        include_str!("../../../machines/5axis-cvu-tt.toml"),
    ),
    ("mazak-m", include_str!("../../../machines/mazak-m.toml")),
    ("mazak-t", include_str!("../../../machines/mazak-t.toml")),
];

/// The names of the built-in machines (`--machine NAME`), in the order `stanok machine list`
/// shows them; [`MachineData::builtin`] knows each.
pub const BUILTIN_MACHINES: [&str; 12] = [
    "mill",
    "lathe",
    "beavermill",
    "linuxcnc",
    "5axis-bc-head",
    "5axis-ab-head",
    "5axis-ac-table",
    "5axis-bc-head-table",
    "millturn-bc",
    "5axis-cvu-tt",
    "mazak-m",
    "mazak-t",
];

/// The AxiOMA M-function profiles a machine may name (`m_functions`): the generic table 2.2 and
/// the BeaverMill BVR B-110 of table 2.3 / §8.1.
pub const M_FUNCTION_PROFILES: [&str; 2] = ["generic", "beavermill"];

/// Linear or rotary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AxisKind {
    /// Positions in mm (X Y Z U V W).
    Linear,
    /// Positions in degrees (A B C).
    Rotary,
}

/// One axis. "unit" below is mm for a linear axis and degrees for a rotary one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisData {
    /// Axis letter, one of X Y Z A B C U V W.
    pub name: char,
    /// Linear or rotary (fixed by the letter).
    pub kind: AxisKind,
    /// Lower travel (software) limit, unit.
    pub min: f64,
    /// Upper travel limit, unit.
    pub max: f64,
    /// Maximum velocity, unit/min.
    pub max_velocity: f64,
    /// Maximum acceleration, unit/s² (used by the planner).
    pub max_acceleration: f64,
    /// Maximum jerk, unit/s³ (used by the planner in SOFT mode).
    pub max_jerk: f64,
    /// A lathe's transverse (cross) axis: it may be programmed as a diameter (AxiOMA G10).
    pub transverse: bool,
}

impl AxisData {
    /// Index of this axis in `Pose::to_array` order (X Y Z A B C U V W).
    pub fn pose_index(&self) -> usize {
        letter_index(self.name).unwrap_or(0)
    }
}

fn letter_index(letter: char) -> Option<usize> {
    AXIS_LETTERS.iter().position(|&l| l == letter)
}

fn kind_of(letter: char) -> AxisKind {
    if matches!(letter, 'A' | 'B' | 'C') {
        AxisKind::Rotary
    } else {
        AxisKind::Linear
    }
}

/// Every key a machine-data file may have; which are required depends on the file's use.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    name: Option<Spanned<String>>,
    description: Option<Spanned<String>>,
    rapid_rate: Option<Spanned<f64>>,
    max_feed: Option<Spanned<f64>>,
    arc_tolerance: Option<Spanned<f64>>,
    path_tolerance: Option<Spanned<f64>>,
    linuxcnc_units: Option<Spanned<String>>,
    rs274_arc_tolerance: Option<Spanned<String>>,
    m_functions: Option<Spanned<String>>,
    feed_table: Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    speed_table: Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    // Not `Spanned`: toml cannot give a span to a table created implicitly by its sub-table
    // (`[channel.edge_positions]` alone).
    channel: Option<channel::RawChannel>,
    axis: Option<Spanned<Vec<RawAxis>>>,
    active_system: Option<Spanned<String>>,
    zero_offset: Option<Spanned<Vec<Spanned<RawZeroOffset>>>>,
    workpiece: Option<Spanned<Vec<Spanned<RawWorkpiece>>>>,
    home: Option<Spanned<Vec<Spanned<RawHome>>>>,
    g28: Option<Spanned<RawPose>>,
    g30: Option<Spanned<RawPose>>,
    g92: Option<Spanned<RawG92>>,
    parameters: Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    iperm: Option<Spanned<BTreeMap<Spanned<String>, Spanned<i64>>>>,
    dperm: Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    tool: Option<Spanned<Vec<Spanned<RawTool>>>>,
    kinematics: Option<Spanned<KinematicsData>>,
    mazatrol: Option<Spanned<MazatrolData>>,
    stock: Option<Spanned<stock::RawStock>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxis {
    name: Spanned<String>,
    kind: Spanned<AxisKind>,
    min: Spanned<f64>,
    max: Spanned<f64>,
    max_velocity: Spanned<f64>,
    max_acceleration: Spanned<f64>,
    max_jerk: Spanned<f64>,
    #[serde(default)]
    transverse: Option<Spanned<bool>>,
}

/// A validation failure: message and the byte range to blame.
pub(crate) type Invalid = (String, Range<usize>);

fn positive(value: &Spanned<f64>, what: &str, unit: &str) -> Result<f64, Invalid> {
    let v = *value.get_ref();
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err((
            format!("{what} must be a positive number of {unit}, not {v}"),
            value.span(),
        ))
    }
}

impl RawAxis {
    fn validate(&self, seen: &[AxisData]) -> Result<AxisData, Invalid> {
        let text = self.name.get_ref();
        let mut chars = text.chars();
        let letter = match (chars.next(), chars.next()) {
            (Some(c), None) if letter_index(c).is_some() => c,
            _ => {
                return Err((
                    format!("axis name must be one of X Y Z A B C U V W, not \"{text}\""),
                    self.name.span(),
                ))
            }
        };
        if seen.iter().any(|a| a.name == letter) {
            return Err((format!("axis {letter} is defined twice"), self.name.span()));
        }
        let kind = *self.kind.get_ref();
        let (unit, per_min, per_s2, per_s3) = match kind_of(letter) {
            AxisKind::Linear => ("mm", "mm/min", "mm/s²", "mm/s³"),
            AxisKind::Rotary => ("deg", "deg/min", "deg/s²", "deg/s³"),
        };
        if kind != kind_of(letter) {
            let want = if kind_of(letter) == AxisKind::Rotary {
                "rotary"
            } else {
                "linear"
            };
            return Err((
                format!("axis {letter} is {want} (its positions are in {unit})"),
                self.kind.span(),
            ));
        }
        let (min, max) = (*self.min.get_ref(), *self.max.get_ref());
        if min.is_nan() {
            return Err((
                format!("axis {letter}: min is not a number"),
                self.min.span(),
            ));
        }
        if max.is_nan() || min > max {
            return Err((
                format!("axis {letter}: min {min} {unit} is greater than max {max} {unit}"),
                self.max.span(),
            ));
        }
        let transverse = match &self.transverse {
            Some(t) if *t.get_ref() && kind != AxisKind::Linear => {
                return Err((
                    format!(
                    "axis {letter}: only a linear axis can be transverse (diameter programming)"
                ),
                    t.span(),
                ))
            }
            Some(t) => *t.get_ref(),
            None => false,
        };
        Ok(AxisData {
            name: letter,
            kind,
            min,
            max,
            max_velocity: positive(&self.max_velocity, "max_velocity", per_min)?,
            max_acceleration: positive(&self.max_acceleration, "max_acceleration", per_s2)?,
            max_jerk: positive(&self.max_jerk, "max_jerk", per_s3)?,
            transverse,
        })
    }
}

fn required<T>(value: Option<Spanned<T>>, key: &str) -> Result<Spanned<T>, Invalid> {
    value.ok_or_else(|| {
        (
            format!("missing field `{key}` (machine data needs it)"),
            0..0,
        )
    })
}

/// `linuxcnc_units = "mm" | "inch"`.
fn units(value: &Option<Spanned<String>>) -> Result<LengthUnits, Invalid> {
    match value {
        None => Ok(LengthUnits::Millimetres),
        Some(v) => match v.get_ref().as_str() {
            "mm" => Ok(LengthUnits::Millimetres),
            "inch" => Ok(LengthUnits::Inches),
            other => Err((
                format!("linuxcnc_units must be \"mm\" or \"inch\", not \"{other}\""),
                v.span(),
            )),
        },
    }
}

/// What a tool or offset file (`--tools`, `--offsets`) may hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Fragment {
    Tools,
    Offsets,
    Perm,
}

impl RawFile {
    fn parse(text: &str, file_name: &str) -> Result<RawFile, Diagnostic> {
        toml::from_str(text)
            .map_err(|e| bad_data(text, &data_note(file_name), e.message(), e.span()))
    }

    fn control(&self) -> RawControl<'_> {
        RawControl {
            active_system: &self.active_system,
            zero_offset: &self.zero_offset,
            workpiece: &self.workpiece,
            home: &self.home,
            g28: &self.g28,
            g30: &self.g30,
            g92: &self.g92,
            parameters: &self.parameters,
            iperm: &self.iperm,
            dperm: &self.dperm,
            tool: &self.tool,
        }
    }

    /// The keys present, with where they start, as (key, byte range).
    fn present_keys(&self) -> Vec<(&'static str, Range<usize>)> {
        fn at<T>(v: &Option<Spanned<T>>) -> Option<Range<usize>> {
            v.as_ref().map(Spanned::span)
        }
        let keys = [
            ("name", at(&self.name)),
            ("description", at(&self.description)),
            ("rapid_rate", at(&self.rapid_rate)),
            ("max_feed", at(&self.max_feed)),
            ("arc_tolerance", at(&self.arc_tolerance)),
            ("path_tolerance", at(&self.path_tolerance)),
            ("linuxcnc_units", at(&self.linuxcnc_units)),
            ("rs274_arc_tolerance", at(&self.rs274_arc_tolerance)),
            ("m_functions", at(&self.m_functions)),
            ("feed_table", at(&self.feed_table)),
            ("speed_table", at(&self.speed_table)),
            ("channel", self.channel.as_ref().map(|_| 0..0)),
            ("axis", at(&self.axis)),
            ("active_system", at(&self.active_system)),
            ("zero_offset", at(&self.zero_offset)),
            ("workpiece", at(&self.workpiece)),
            ("home", at(&self.home)),
            ("g28", at(&self.g28)),
            ("g30", at(&self.g30)),
            ("g92", at(&self.g92)),
            ("parameters", at(&self.parameters)),
            ("iperm", at(&self.iperm)),
            ("dperm", at(&self.dperm)),
            ("tool", at(&self.tool)),
            ("mazatrol", at(&self.mazatrol)),
        ];
        keys.into_iter()
            .filter_map(|(k, r)| r.map(|r| (k, r)))
            .collect()
    }

    /// Refuses the keys a fragment of this kind must not hold (the first one in the file).
    fn check_fragment(&self, kind: Fragment) -> Result<(), Invalid> {
        let allowed: &[&str] = match kind {
            Fragment::Tools => &["tool"],
            Fragment::Offsets => &[
                "active_system",
                "zero_offset",
                "workpiece",
                "home",
                "g28",
                "g30",
                "g92",
                "parameters",
            ],
            Fragment::Perm => &["iperm", "dperm"],
        };
        let wrong = self
            .present_keys()
            .into_iter()
            .filter(|(k, _)| !allowed.contains(k))
            .min_by_key(|(_, r)| r.start);
        match (wrong, kind) {
            (None, _) => Ok(()),
            (Some((key, range)), Fragment::Tools) => Err((
                format!("a tool file holds only [[tool]] sections, not `{key}`"),
                range,
            )),
            (Some((key, range)), Fragment::Offsets) => Err((
                format!(
                    "an offset file holds only active_system, [[zero_offset]], [[workpiece]], \
                     [[home]], [g28], [g30], [g92] and [parameters], not `{key}`"
                ),
                range,
            )),
            (Some((key, range)), Fragment::Perm) => Err((
                format!("a permanent-parameter file holds only [iperm] and [dperm], not `{key}`"),
                range,
            )),
        }
    }

    fn validate(self) -> Result<MachineData, Invalid> {
        let control = self.control().validate();
        let machine = self.validate_machine();
        match (machine, control) {
            (Ok(mut m), Ok(c)) => {
                m.control = c;
                Ok(m)
            }
            (Err(a), Err(b)) => Err(if b.1.start < a.1.start { b } else { a }),
            (Err(e), _) | (_, Err(e)) => Err(e),
        }
    }

    fn validate_machine(&self) -> Result<MachineData, Invalid> {
        let name = required(self.name.clone(), "name")?;
        if name.get_ref().trim().is_empty() {
            return Err(("machine name is empty".into(), name.span()));
        }
        let rapid_rate = positive(
            &required(self.rapid_rate.clone(), "rapid_rate")?,
            "rapid_rate",
            "mm/min",
        )?;
        let max_feed = positive(
            &required(self.max_feed.clone(), "max_feed")?,
            "max_feed",
            "mm/min",
        )?;
        let arc = required(self.arc_tolerance.clone(), "arc_tolerance")?;
        let tol = tolerance(&arc, "arc_tolerance", 0.0)?;
        let path_tolerance = self
            .path_tolerance
            .as_ref()
            .map_or(Ok(PATH_TOLERANCE), |t| {
                tolerance(t, "path_tolerance", f64::MIN_POSITIVE)
            })?;
        let linuxcnc_units = units(&self.linuxcnc_units)?;
        let rs274_linuxcnc_arc_tolerance = match &self.rs274_arc_tolerance {
            None => false,
            Some(v) => match v.get_ref().as_str() {
                "document" => false,
                "linuxcnc" => true,
                other => {
                    return Err((
                        format!(
                        "rs274_arc_tolerance must be \"document\" or \"linuxcnc\", not \"{other}\""
                    ),
                        v.span(),
                    ))
                }
            },
        };
        let m_functions = match &self.m_functions {
            None => "generic".to_string(),
            Some(p) if M_FUNCTION_PROFILES.contains(&p.get_ref().as_str()) => p.get_ref().clone(),
            Some(p) => {
                return Err((
                    format!(
                        "m_functions must be one of {}, not {:?}",
                        M_FUNCTION_PROFILES.join(", "),
                        p.get_ref()
                    ),
                    p.span(),
                ))
            }
        };
        let feed_table = rate_table(&self.feed_table, "feed_table")?;
        let speed_table = rate_table(&self.speed_table, "speed_table")?;
        let channel = match &self.channel {
            Some(c) => c.validate()?,
            None => ChannelData::default(),
        };
        let Some(raw_axes) = &self.axis else {
            return Err((
                "missing field `axis` (a machine needs at least one [[axis]])".into(),
                0..0,
            ));
        };
        let mut axes = Vec::new();
        for raw in raw_axes.get_ref() {
            let axis = raw.validate(&axes)?;
            axes.push(axis);
        }
        if axes.is_empty() {
            return Err((
                "a machine needs at least one [[axis]]".into(),
                raw_axes.span(),
            ));
        }
        let kinematics = match &self.kinematics {
            None => None,
            Some(k) => Some(validate_kinematics(k, &axes)?),
        };
        let mazatrol = match &self.mazatrol {
            None => None,
            Some(m) => Some(mazatrol::validate_mazatrol(m)?),
        };
        Ok(MachineData {
            name: name.into_inner(),
            description: self
                .description
                .as_ref()
                .map(|d| d.get_ref().clone())
                .unwrap_or_default(),
            rapid_rate,
            max_feed,
            arc_tolerance: tol,
            path_tolerance,
            axes,
            linuxcnc_units,
            rs274_linuxcnc_arc_tolerance,
            control: ControlData::default(),
            m_functions,
            kinematics,
            feed_table,
            speed_table,
            channel,
            mazatrol,
            stock: self
                .stock
                .as_ref()
                .map(stock::RawStock::validate)
                .transpose()?,
        })
    }
}

/// Line and column (1-based, column in characters) of byte `offset` in `text`.
pub(crate) fn line_column(text: &str, offset: usize) -> (u32, u32) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(column).unwrap_or(u32::MAX),
    )
}

fn data_note(file_name: &str) -> String {
    format!("in machine data file {file_name}")
}

/// A `machine::bad-data` error at byte range `range` of `text`, with `note` (which file).
pub(crate) fn bad_data(
    text: &str,
    note: &str,
    message: &str,
    range: Option<Range<usize>>,
) -> Diagnostic {
    let span = match range {
        Some(r) => {
            let (line, column) = line_column(text, r.start);
            Span::new(r.start as u64, r.end as u64, line, column)
        }
        None => Span::default(),
    };
    Diagnostic::error(BAD_DATA, message.trim_end(), span).with_note(note)
}

/// Reads a whole file for machine data; `what` names it in the error ("machine data file").
pub(crate) fn read_text(path: &Path, what: &str) -> Result<String, Diagnostic> {
    std::fs::read_to_string(path).map_err(|e| {
        Diagnostic::error(
            BAD_DATA,
            format!("cannot read {what} {}: {e}", path.display()),
            Span::default(),
        )
    })
}

impl MachineData {
    /// The built-in machine called `name` (`"mill"`), if there is one.
    pub fn builtin(name: &str) -> Option<MachineData> {
        match name {
            "mill" => Some(Self::default_mill()),
            "lathe" => Some(Self::default_lathe()),
            "beavermill" => Self::from_toml_str(
                include_str!("../../../machines/beavermill.toml"),
                "beavermill",
            )
            .ok(),
            "linuxcnc" => Self::linuxcnc(),
            _ => BUILTIN_FIVE_AXIS
                .iter()
                .find(|(n, _)| *n == name)
                .and_then(|(n, text)| Self::from_toml_str(text, n).ok()),
        }
    }

    /// True for a lathe: a transverse (cross) axis and no Y axis. Its pictures are turning
    /// drawings (Z right, X up).
    pub fn is_lathe(&self) -> bool {
        self.axes.iter().any(|a| a.transverse) && !self.axes.iter().any(|a| a.name == 'Y')
    }

    /// The built-in `linuxcnc` machine: LinuxCNC's standalone `rs274` as a machine (X Y Z A B C,
    /// inch LinuxCNC units, the tool table of LinuxCNC's sim configurations), so that `stanok canon
    /// --machine linuxcnc` prints what `rs274 -g` prints (`machines/linuxcnc.toml`).
    pub fn linuxcnc() -> Option<MachineData> {
        let mut m =
            Self::from_toml_str(include_str!("../../../machines/linuxcnc.toml"), "linuxcnc")
                .ok()?;
        m.control.tools = crate::linuxcnc::parse_tool_table(
            include_str!("../../../machines/linuxcnc-sim.tbl"),
            "linuxcnc-sim.tbl",
            m.linuxcnc_units,
        )
        .ok()?;
        Some(m)
    }

    /// The machine's kinematics, built: None for a Cartesian machine.
    pub fn five_axis(&self) -> Option<FiveAxis> {
        self.kinematics
            .as_ref()
            .and_then(|k| k.build().ok().flatten())
    }

    /// The kinematics the interpreter may use for tool-centre-point control: the machine's, when
    /// its data allows that control (`tcp_allowed`); None = not allowed (AxiOMA error 654).
    pub fn tcp_kinematics(&self) -> Option<FiveAxis> {
        self.kinematics
            .as_ref()
            .filter(|k| k.tcp_allowed)
            .and_then(|_| self.five_axis())
    }

    /// Mazatrol tool tip point control programs X Y Z in the workpiece frame (machine data
    /// `ttpc_frame = "workpiece"`) rather than the table frame.
    pub fn ttpc_workpiece_frame(&self) -> bool {
        self.kinematics
            .as_ref()
            .is_some_and(|k| k.ttpc_frame == stanok_kin::TtpcFrame::Workpiece)
    }

    /// Parses and validates machine data. `file_name` is only used in the diagnostic's note.
    pub fn from_toml_str(text: &str, file_name: &str) -> Result<MachineData, Diagnostic> {
        RawFile::parse(text, file_name)?
            .validate()
            .map_err(|(message, range)| {
                bad_data(text, &data_note(file_name), &message, Some(range))
            })
    }

    /// Reads machine data from a file.
    pub fn load(path: impl AsRef<Path>) -> Result<MachineData, Diagnostic> {
        let path = path.as_ref();
        let text = read_text(path, "machine data file")?;
        Self::from_toml_str(&text, &path.display().to_string())
    }

    /// Which of X Y Z A B C U V W may be programmed as diameters (AxiOMA G10): the axes marked
    /// `transverse = true`.
    pub fn diameter_axes(&self) -> [bool; 9] {
        let mut mask = [false; 9];
        for a in &self.axes {
            if a.transverse {
                mask[a.pose_index()] = true;
            }
        }
        mask
    }

    /// Which of the nine axes (X Y Z A B C U V W, `Pose::to_array` order) the machine has.
    pub fn axis_mask(&self) -> [bool; 9] {
        let mut mask = [false; 9];
        for a in &self.axes {
            mask[a.pose_index()] = true;
        }
        mask
    }

    /// The Mazatrol series: the `[mazatrol]` section's, else T for a `mill-turn` kinematics, else
    /// M (`docs/dialects/mazatrol-eia.md` §1).
    pub fn mazatrol_series(&self) -> MazatrolSeries {
        if let Some(s) = self.mazatrol.as_ref().and_then(|m| m.series) {
            return s;
        }
        match &self.kinematics {
            Some(k) if k.kind == stanok_kin::MachineType::MillTurn => MazatrolSeries::T,
            _ => MazatrolSeries::M,
        }
    }

    /// The axis with letter `name`, if the machine has it.
    pub fn axis(&self, name: char) -> Option<&AxisData> {
        self.axes.iter().find(|a| a.name == name)
    }
}

#[cfg(test)]
#[path = "data_tests.rs"]
mod tests;
