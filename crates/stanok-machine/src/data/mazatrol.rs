//! The `[mazatrol]` section of machine data: the Mazatrol EIA/ISO control's parameters
//! (`docs/dialects/mazatrol-eia.md` §1). The machine crate only reads and checks them; the
//! command line hands them to the Mazatrol front end.
//!
//! ```toml
//! [mazatrol]
//! series = "T"              # "M" machining centre (table 12.2) | "T" mill-turn (table 12.1)
//! decimal_point_type = 2    # 1: X10 = 0.010 mm (least input increment) | 2: X10 = 10 mm
//! peck_clearance = 1.0      # mm, G73 retract / G83 re-approach d
//! thread_chamfer_angle = 45 # deg, G76/G78 pull-out
//! g60_overshoot = 1.0       # mm, G60 final approach
//! tool_data_length = false  # F93 bit 3: T…M6 puts the tool's length in force
//! g49_moves = true          # P12 bit 6 / F114 bit 1 = 0: G49 moves the axes
//! mazatrol_wpc = [0, 0, 0]  # G53.5 workpiece origin, machine mm (default: the G54 offset)
//! power_on_feed = "G95"     # feed mode at power-on and reset (default: G95 on T, G94 on M)
//! ```

use super::Invalid;
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// The control series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
pub enum MazatrolSeries {
    /// Machining centre (M640M Pro, MATRIX M).
    M,
    /// Mill-turn (M640MT 5X, M640MT Pro, MATRIX T).
    T,
}

/// A feed mode a control powers on in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
pub enum MazatrolFeedMode {
    /// Feed per minute.
    G94,
    /// Feed per revolution.
    G95,
}

/// The `[mazatrol]` section, checked.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MazatrolData {
    /// The series; absent: T when the kinematics type is `mill-turn`, else M.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub series: Option<MazatrolSeries>,
    /// Decimal point type 1 (least input increment) or 2 (units).
    #[serde(default = "two")]
    pub decimal_point_type: u8,
    /// G73 retract / G83 re-approach distance, mm (> 0).
    #[serde(default = "one")]
    pub peck_clearance: f64,
    /// G76/G78 pull-out angle, degrees (0 < a < 90).
    #[serde(default = "forty_five")]
    pub thread_chamfer_angle: f64,
    /// G60 final approach distance, mm (≥ 0).
    #[serde(default = "one")]
    pub g60_overshoot: f64,
    /// F93 bit 3: a tool change puts the new tool's length in force.
    #[serde(default)]
    pub tool_data_length: bool,
    /// G49 moves the axes to remove the offset (P12 bit 6 / F114 bit 1 = 0).
    #[serde(default = "yes")]
    pub g49_moves: bool,
    /// G53.5's workpiece origin, machine mm; absent: the G54 offset.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mazatrol_wpc: Option<[f64; 3]>,
    /// The feed mode at power-on; absent: G95 on the T-series (Fanuc's lathe default), G94 on
    /// the M-series. A machine whose programs feed in mm/min without writing G94 (the TTPC
    /// specification's mill-turn, `millturn-bc`) says `"G94"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub power_on_feed: Option<MazatrolFeedMode>,
}

fn two() -> u8 {
    2
}
fn one() -> f64 {
    1.0
}
fn forty_five() -> f64 {
    45.0
}
fn yes() -> bool {
    true
}

impl Default for MazatrolData {
    fn default() -> Self {
        MazatrolData {
            series: None,
            decimal_point_type: 2,
            peck_clearance: 1.0,
            thread_chamfer_angle: 45.0,
            g60_overshoot: 1.0,
            tool_data_length: false,
            g49_moves: true,
            mazatrol_wpc: None,
            power_on_feed: None,
        }
    }
}

/// The section checked: values in their ranges (errors at the section).
pub(super) fn validate_mazatrol(s: &Spanned<MazatrolData>) -> Result<MazatrolData, Invalid> {
    let d = s.get_ref().clone();
    let bad = |m: String| Err((format!("[mazatrol] {m}"), s.span()));
    if !matches!(d.decimal_point_type, 1 | 2) {
        return bad(format!(
            "decimal_point_type must be 1 or 2, not {}",
            d.decimal_point_type
        ));
    }
    if !(d.peck_clearance.is_finite() && d.peck_clearance > 0.0) {
        return bad(format!(
            "peck_clearance must be a positive number of mm, not {}",
            d.peck_clearance
        ));
    }
    if !(d.thread_chamfer_angle > 0.0 && d.thread_chamfer_angle < 90.0) {
        return bad(format!(
            "thread_chamfer_angle must be between 0 and 90 degrees, not {}",
            d.thread_chamfer_angle
        ));
    }
    if !(d.g60_overshoot.is_finite() && d.g60_overshoot >= 0.0) {
        return bad(format!(
            "g60_overshoot must be zero or a positive number of mm, not {}",
            d.g60_overshoot
        ));
    }
    if let Some(w) = d.mazatrol_wpc {
        if w.iter().any(|x| !x.is_finite()) {
            return bad("mazatrol_wpc must be three finite numbers of mm".into());
        }
    }
    Ok(d)
}
