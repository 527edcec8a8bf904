//! The lab's tables as data: `data/turning.toml`, compiled into the crate and parsed once per
//! calculation. Every row keeps the printed value; OCR doubts travel with it (`doubt`), so the
//! calculation can print them next to the cell it used.

use serde::{Deserialize, Serialize};

/// The tables of Lab 2 (spec §5).
#[derive(Debug, Clone, Deserialize)]
pub struct Tables {
    /// Where the data comes from.
    pub source: String,
    /// Table 2.2.
    pub tool_material: Vec<ToolMaterialRow>,
    /// Tool grades and their class (carbide / HSS).
    pub grade: Vec<Grade>,
    /// Holder section by centre height.
    pub holder: Vec<HolderRow>,
    /// Table 2.3.
    pub cutter: Vec<Cutter>,
    /// Table 2.4.
    pub rough_feed: Rows<RoughFeedRow>,
    /// Table 2.5.
    pub finish_feed: FinishFeed,
    /// Table 2.6.
    pub cv: Vec<CvRow>,
    /// Tables 2.7 and 2.8.
    pub kmv: Vec<KmvRow>,
    /// K_nv.
    pub knv: Vec<KnvRow>,
    /// Table 2.9.
    pub kuv: Rows<KuvRow>,
}

/// A table given as `[name]` with `rows = [ … ]` (inline rows keep a table readable as printed).
#[derive(Debug, Clone, Deserialize)]
pub struct Rows<T> {
    /// The rows.
    pub rows: Vec<T>,
}

/// A row of table 2.2: recommended grades per work-material column.
#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct ToolMaterialRow {
    /// Type of work, as printed (translated).
    pub work: String,
    /// Key: rough_interrupted, rough_continuous, finish_interrupted, precision_interrupted,
    /// precision_continuous, parting.
    pub kind: String,
    /// Carbon and alloy steel.
    pub steel: Vec<String>,
    /// Hardened steel.
    pub hardened_steel: Vec<String>,
    /// Cast iron HB 240.
    pub cast_iron_hb240: Vec<String>,
    /// Cast iron HB 400–700.
    pub cast_iron_hb400_700: Vec<String>,
}

/// A tool grade and its class.
#[derive(Debug, Clone, Deserialize)]
pub struct Grade {
    /// Transliterated name (T15K6, VK6, P6M5 …).
    pub name: String,
    /// `carbide` or `hss`.
    pub class: String,
    /// Remark.
    #[serde(default)]
    pub note: Option<String>,
}

/// Holder section from the centre height.
#[derive(Debug, Clone, Deserialize)]
pub struct HolderRow {
    /// Centre height band, mm (inclusive).
    pub centre_height: [f64; 2],
    /// Sections B × H, mm.
    pub sections: Vec<String>,
    /// Remark.
    #[serde(default)]
    pub note: Option<String>,
}

/// A bent through cutter of table 2.3.
#[derive(Debug, Clone, Deserialize, Serialize)]
pub struct Cutter {
    /// GOST designation.
    pub designation: String,
    /// Shank height H, mm.
    pub h: f64,
    /// Shank width B, mm.
    pub b: f64,
    /// Length, mm.
    pub length: f64,
    /// Insert form (GOST 2209-69).
    pub insert: String,
}

/// A cell of table 2.4.
#[derive(Debug, Clone, Deserialize)]
pub struct RoughFeedRow {
    /// Diameter band (over, up to], mm.
    pub d: [f64; 2],
    /// Depth band (over, up to], mm.
    pub t: [f64; 2],
    /// `steel` or `cast_iron`.
    pub group: String,
    /// Feed range, mm/rev.
    pub s: [f64; 2],
    /// OCR doubt.
    #[serde(default)]
    pub doubt: Option<String>,
}

/// Table 2.5.
#[derive(Debug, Clone, Deserialize)]
pub struct FinishFeed {
    /// Column heads: nose radius r, mm.
    pub nose_radius: Vec<f64>,
    /// Rows by roughness.
    pub rows: Vec<FinishFeedRow>,
}

/// A row of table 2.5.
#[derive(Debug, Clone, Deserialize)]
pub struct FinishFeedRow {
    /// `Ra2.5`, `Rz20`, `Rz40`, `Rz80`.
    pub roughness: String,
    /// Feeds per nose radius, mm/rev.
    pub s: Vec<f64>,
}

/// A row of table 2.6.
#[derive(Debug, Clone, Deserialize)]
pub struct CvRow {
    /// `steel` or `grey_iron`.
    pub group: String,
    /// The reference material of the row.
    pub reference: String,
    /// `turning`, `parting` or `threading`.
    pub operation: String,
    /// The row's tool grade.
    pub tool: String,
    /// Applies for S ≤ this, mm/rev.
    #[serde(default)]
    pub feed_max: Option<f64>,
    /// Applies for S > this, mm/rev.
    #[serde(default)]
    pub feed_over: Option<f64>,
    /// C_v.
    pub cv: f64,
    /// Exponent of t (formula 1 only).
    #[serde(default)]
    pub x: Option<f64>,
    /// Exponent of S.
    #[serde(default)]
    pub y: Option<f64>,
    /// Exponent of T.
    pub m: f64,
    /// 1 = v = Cv/(T^m t^x S^y) Kv; 2 = without t^x; 0 = no formula in the document.
    pub formula: u8,
    /// Cells read from a merged neighbour.
    #[serde(default)]
    pub merged: Vec<String>,
    /// OCR doubt.
    #[serde(default)]
    pub doubt: Option<String>,
}

/// A row of tables 2.7/2.8.
#[derive(Debug, Clone, Deserialize)]
pub struct KmvRow {
    /// Material key.
    pub material: String,
    /// The printed row (translated).
    pub row: String,
    /// σ_B band (over, up to], MPa; absent = any.
    #[serde(default)]
    pub sigma_b: Option<[f64; 2]>,
    /// K_r for HSS tools (steel only).
    #[serde(default)]
    pub kr_hss: Option<f64>,
    /// K_r for carbide tools (steel only).
    #[serde(default)]
    pub kr_carbide: Option<f64>,
    /// n_v for HSS tools.
    pub nv_hss: f64,
    /// n_v for carbide tools.
    pub nv_carbide: f64,
    /// Cells read from a merged neighbour.
    #[serde(default)]
    pub merged: Vec<String>,
    /// OCR doubt.
    #[serde(default)]
    pub doubt: Option<String>,
    /// The cell the doubt is about (`nv_hss`, `nv_carbide`).
    #[serde(default)]
    pub doubt_column: Option<String>,
}

/// A row of the K_nv list.
#[derive(Debug, Clone, Deserialize)]
pub struct KnvRow {
    /// Key used on the command line.
    pub surface: String,
    /// The printed row (translated).
    pub row: String,
    /// Range (equal bounds = one value).
    pub k: [f64; 2],
}

/// A row of table 2.9.
#[derive(Debug, Clone, Deserialize)]
pub struct KuvRow {
    /// Work-material group.
    pub group: String,
    /// Tool grade.
    pub tool: String,
    /// K_uv.
    pub k: f64,
    /// OCR doubt.
    #[serde(default)]
    pub doubt: Option<String>,
}

/// The tables file as compiled in.
pub const TURNING_TOML: &str = include_str!("../data/turning.toml");

impl Tables {
    /// The lab's tables (the data file compiled into the crate).
    pub fn lab() -> Tables {
        // The file is part of the crate and checked by the tests; a parse failure is a build bug.
        Self::parse(TURNING_TOML).expect("data/turning.toml is valid (tested)")
    }

    /// Parses a tables file.
    pub fn parse(text: &str) -> Result<Tables, String> {
        toml::from_str(text).map_err(|e| e.to_string())
    }

    /// The class (`carbide` / `hss`) of a grade, by case-insensitive name.
    pub fn grade(&self, name: &str) -> Option<&Grade> {
        self.grade
            .iter()
            .find(|g| g.name.eq_ignore_ascii_case(name))
    }
}
