//! Cutting conditions for turning, the way the lab collection teaches them (Lab 2 of seed
//! `003_…txt`; spec `lab-collection-nc31-2p32-cutting.md` §5).
//!
//! The method, one pass at a time (spec §5.6):
//!
//! ```text
//! 0. tool: grade (table 2.2 recommendations), holder section from the centre height, table 2.3
//! 1. passes: t_i = the given depth, or the allowance split 0.7/0.3 (0.7/0.2/0.1); D_i shrinks by 2·t
//! 2. S_i: rough from table 2.4 (D, t, material group), finish from table 2.5 (roughness, r);
//!    a range gives its lower bound unless --feed; then DOWN to the machine's feeds (≤)
//! 3. Cv, x, y, m: table 2.6 row (material group, operation, S band)
//! 4. Kv = K_mv·K_nv·K_uv (tables 2.7/2.8, the surface list, table 2.9); after the first pass K_nv = 1
//! 5. v = Cv/(T^m·t^x·S^y)·Kv (formula 2 for parting/grooving/form turning: no t^x)
//! 6. n = 1000·v/(π·D); n_act = the largest machine speed ≤ n; v_act = π·D·n_act/1000
//! ```
//!
//! Every table cell and every default the calculation uses is recorded in its [`Step`]s, so a
//! student can check each number by hand; [`text`] prints them, and the whole [`Calculation`] is
//! serialisable (the command line's `--json`). What the document does not give (power, force,
//! machining time, Cv for malleable iron or HSS tools) is said, never invented.
#![deny(missing_docs)]

mod calc;
pub mod tables;
mod text;

pub use calc::{calculate, cutting_speed_m_min, spindle_speed_rpm};
pub use tables::Tables;
pub use text::text;

use serde::Serialize;

/// The work material and its strength.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum WorkMaterial {
    /// Carbon steel, C < 0.6 %.
    CarbonSteel {
        /// Ultimate strength σ_B, MPa.
        sigma_b_mpa: f64,
    },
    /// Carbon steel, C > 0.6 %.
    HighCarbonSteel {
        /// σ_B, MPa.
        sigma_b_mpa: f64,
    },
    /// Free-machining and high-machinability steel; chromium steel.
    FreeMachiningSteel {
        /// σ_B, MPa.
        sigma_b_mpa: f64,
    },
    /// Chromium-nickel, chromium-molybdenum-vanadium steel.
    CrNiSteel {
        /// σ_B, MPa.
        sigma_b_mpa: f64,
    },
    /// Grey cast iron.
    GreyIron {
        /// Brinell hardness.
        hb: f64,
    },
    /// Malleable cast iron (table 2.6 has no Cv row for it).
    MalleableIron {
        /// Brinell hardness.
        hb: f64,
    },
}

impl WorkMaterial {
    /// The key of tables 2.7/2.8.
    fn kmv_key(&self) -> &'static str {
        match self {
            WorkMaterial::CarbonSteel { .. } => "carbon_steel",
            WorkMaterial::HighCarbonSteel { .. } => "high_carbon_steel",
            WorkMaterial::FreeMachiningSteel { .. } => "free_machining_steel",
            WorkMaterial::CrNiSteel { .. } => "cr_ni_steel",
            WorkMaterial::GreyIron { .. } => "grey_iron",
            WorkMaterial::MalleableIron { .. } => "malleable_iron",
        }
    }

    /// σ_B for steels.
    fn sigma_b(&self) -> Option<f64> {
        match *self {
            WorkMaterial::CarbonSteel { sigma_b_mpa }
            | WorkMaterial::HighCarbonSteel { sigma_b_mpa }
            | WorkMaterial::FreeMachiningSteel { sigma_b_mpa }
            | WorkMaterial::CrNiSteel { sigma_b_mpa } => Some(sigma_b_mpa),
            _ => None,
        }
    }

    /// HB for cast irons.
    fn hb(&self) -> Option<f64> {
        match *self {
            WorkMaterial::GreyIron { hb } | WorkMaterial::MalleableIron { hb } => Some(hb),
            _ => None,
        }
    }

    fn is_steel(&self) -> bool {
        self.sigma_b().is_some()
    }

    /// A readable name with its strength.
    pub fn describe(&self) -> String {
        match *self {
            WorkMaterial::CarbonSteel { sigma_b_mpa } => {
                format!("carbon steel C < 0.6 %, σ_B = {sigma_b_mpa} MPa")
            }
            WorkMaterial::HighCarbonSteel { sigma_b_mpa } => {
                format!("carbon steel C > 0.6 %, σ_B = {sigma_b_mpa} MPa")
            }
            WorkMaterial::FreeMachiningSteel { sigma_b_mpa } => {
                format!("free-machining or chromium steel, σ_B = {sigma_b_mpa} MPa")
            }
            WorkMaterial::CrNiSteel { sigma_b_mpa } => {
                format!("Cr-Ni / Cr-Mo-V steel, σ_B = {sigma_b_mpa} MPa")
            }
            WorkMaterial::GreyIron { hb } => format!("grey cast iron HB {hb}"),
            WorkMaterial::MalleableIron { hb } => format!("malleable cast iron HB {hb}"),
        }
    }
}

/// The kind of turning (decides the formula and the table 2.6 row).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Operation {
    /// External longitudinal turning (formula 1).
    Longitudinal,
    /// Facing, cross turning (formula 1).
    Facing,
    /// Boring (formula 1).
    Boring,
    /// Parting-off (formula 2).
    PartingOff,
    /// Grooving (formula 2).
    Grooving,
    /// Form turning (formula 2).
    FormTurning,
    /// Thread cutting: table 2.6 has coefficients, the document no formula.
    Threading,
}

impl Operation {
    fn cv_operation(self) -> &'static str {
        match self {
            Operation::Longitudinal | Operation::Facing | Operation::Boring => "turning",
            Operation::PartingOff | Operation::Grooving | Operation::FormTurning => "parting",
            Operation::Threading => "threading",
        }
    }
}

/// Roughing or finishing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PassKind {
    /// Roughing: feed from table 2.4.
    Rough,
    /// Semi-finishing: the middle pass of a three-way split (0.7/0.2/0.1); feed from table 2.5.
    SemiFinish,
    /// Finishing: feed from table 2.5.
    Finish,
}

/// How the depth of cut is given.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum DepthInput {
    /// One pass of depth `t_mm`.
    Pass {
        /// Depth of cut, mm.
        t_mm: f64,
        /// Roughing or finishing.
        pass: PassKind,
    },
    /// An allowance per side split into passes: rough, then finish; of three passes the middle one
    /// is semi-finish.
    Allowance {
        /// Allowance per side, mm.
        allowance_mm: f64,
        /// Shares, summing to 1 (0.7/0.3 or 0.7/0.2/0.1).
        split: Vec<f64>,
    },
}

/// Everything the calculation needs. Optional values take the documented defaults, which the
/// result lists.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TurningInput {
    /// Work material.
    pub material: WorkMaterial,
    /// Blank surface key of the K_nv list (`none`, `rolled`, `forging`, `cu-al`, `casting`,
    /// `casting-dirty`).
    pub surface: String,
    /// K_nv within the row's range (None: the lower bound).
    pub surface_factor: Option<f64>,
    /// Tool grade (T15K6, VK6, …).
    pub tool: String,
    /// Kind of turning.
    pub operation: Operation,
    /// Work diameter before the first pass, mm.
    pub diameter_mm: f64,
    /// Depth per pass or allowance.
    pub depth: DepthInput,
    /// Feed of the single or first (rough) pass, mm/rev (None: from the tables).
    pub feed_mm_rev: Option<f64>,
    /// Feed of the finish passes, mm/rev (None: from table 2.5).
    pub finish_feed_mm_rev: Option<f64>,
    /// Required roughness for table 2.5 (`Ra2.5`, `Rz20`, `Rz40`, `Rz80`).
    pub roughness: Option<String>,
    /// Tool nose radius r for table 2.5, mm.
    pub nose_radius_mm: Option<f64>,
    /// Tool life T, min (None: 60 for turning, 120 for form and thread cutters).
    pub tool_life_min: Option<f64>,
    /// Lathe centre height for the holder choice, mm (None: no holder choice).
    pub centre_height_mm: Option<f64>,
    /// The machine's feeds, mm/rev (empty: the table feed is used as is).
    pub machine_feeds: Vec<f64>,
    /// The machine's spindle speeds, rpm (empty: no n_act).
    pub machine_speeds: Vec<f64>,
}

/// A table cell the calculation read.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cell {
    /// Table name as printed ("2.6", "K_nv").
    pub table: String,
    /// The row.
    pub row: String,
    /// The column.
    pub column: String,
    /// The value (a range's bounds are two cells).
    pub value: f64,
    /// An OCR doubt or merged-cell reading of this value.
    pub note: Option<String>,
}

/// One step of the method: what was looked up and what was computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Step {
    /// The step's title.
    pub title: String,
    /// Table cells used.
    pub cells: Vec<Cell>,
    /// The working, one line per equation or choice.
    pub lines: Vec<String>,
    /// Defaults and spec decisions applied in this step.
    pub defaults: Vec<String>,
}

impl Step {
    fn new(title: impl Into<String>) -> Self {
        Step {
            title: title.into(),
            cells: Vec::new(),
            lines: Vec::new(),
            defaults: Vec::new(),
        }
    }

    fn cell(&mut self, table: &str, row: &str, column: &str, value: f64, note: Option<&str>) {
        self.cells.push(Cell {
            table: table.into(),
            row: row.into(),
            column: column.into(),
            value,
            note: note.map(str::to_owned),
        });
    }
}

/// The result of one pass.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassResult {
    /// 1-based.
    pub number: usize,
    /// Rough or finish.
    pub kind: PassKind,
    /// Depth of cut t, mm.
    pub depth_mm: f64,
    /// Work diameter D of this pass, mm.
    pub diameter_mm: f64,
    /// Feed range of the table, mm/rev (None: given by the user).
    pub feed_table_range_mm_rev: Option<[f64; 2]>,
    /// Feed before the machine correction, mm/rev.
    pub feed_wanted_mm_rev: f64,
    /// Feed used: the machine's nearest lower one (or the wanted one without a list), mm/rev.
    pub feed_mm_rev: f64,
    /// Formula 1 (with t^x) or 2.
    pub formula: u8,
    /// C_v.
    pub cv: f64,
    /// x (formula 1).
    pub x: Option<f64>,
    /// y.
    pub y: f64,
    /// m.
    pub m: f64,
    /// Tool life T, min.
    pub tool_life_min: f64,
    /// K_mv.
    pub k_mv: f64,
    /// K_nv.
    pub k_nv: f64,
    /// K_uv.
    pub k_uv: f64,
    /// K_v = K_mv·K_nv·K_uv.
    pub k_v: f64,
    /// T^m.
    pub t_pow_m: f64,
    /// t^x (formula 1).
    pub t_pow_x: Option<f64>,
    /// S^y.
    pub s_pow_y: f64,
    /// Cutting speed v, m/min.
    pub v_m_min: f64,
    /// Spindle speed n, rpm.
    pub n_rpm: f64,
    /// The machine's speed, rpm (None without a speed list).
    pub n_act_rpm: Option<f64>,
    /// Actual cutting speed, m/min.
    pub v_act_m_min: Option<f64>,
    /// The working.
    pub steps: Vec<Step>,
}

/// A whole calculation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Calculation {
    /// The data's source.
    pub source: String,
    /// The input as understood.
    pub input: TurningInput,
    /// Step 0: tool material and holder.
    pub tool: Step,
    /// One result per pass.
    pub passes: Vec<PassResult>,
    /// What the document does not give.
    pub not_in_document: Vec<String>,
}

/// Why a calculation cannot be made from the document's data.
#[derive(Debug, Clone, PartialEq)]
pub enum CuttingError {
    /// An input value is out of its domain.
    BadInput(String),
    /// The grade is not in the tables.
    UnknownTool(String),
    /// The surface key is not in the K_nv list.
    UnknownSurface(String),
    /// Table 2.6 has no row for the material and operation.
    NoCvRow(String),
    /// Table 2.9 has no K_uv for the pair.
    NoKuvEntry {
        /// Grade.
        tool: String,
        /// Material group.
        group: String,
    },
    /// Threading: coefficients without a formula.
    NoFormulaForThreading(String),
    /// The feed tables do not cover the case.
    FeedOutsideTable(String),
    /// No machine feed at or below the wanted one.
    NoLowerMachineFeed(f64),
    /// No machine speed at or below n.
    NoLowerMachineSpeed(f64),
}

impl std::fmt::Display for CuttingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CuttingError::BadInput(s) => write!(f, "{s}"),
            CuttingError::UnknownTool(t) => write!(
                f,
                "tool grade `{t}` is not in the lab's tables (known: T5K10, T14K8, T15K6, T30K4, VK3, VK3M, VK4, VK6, VK6M, VK8, P6M5, P18, KhVG)"
            ),
            CuttingError::UnknownSurface(s) => write!(
                f,
                "surface `{s}` is not in the K_nv list (none, rolled, forging, cu-al, casting, casting-dirty)"
            ),
            CuttingError::NoCvRow(s) => write!(f, "no Cv in table 2.6: {s}"),
            CuttingError::NoKuvEntry { tool, group } => write!(
                f,
                "table 2.9 has no K_uv for {tool} on {group}; the document gives none"
            ),
            CuttingError::NoFormulaForThreading(s) => write!(f, "{s}"),
            CuttingError::FeedOutsideTable(s) => write!(f, "{s}"),
            CuttingError::NoLowerMachineFeed(s) => write!(
                f,
                "no machine feed at or below {s:.3} mm/rev in --machine-feeds"
            ),
            CuttingError::NoLowerMachineSpeed(n) => write!(
                f,
                "no machine speed at or below n = {n:.1} rpm in --machine-speeds"
            ),
        }
    }
}

impl std::error::Error for CuttingError {}
