//! `[channel]`: the AxiOMA channel parameters a part program depends on (spec axioma-2 §5.5,
//! axioma-3 §4.5.10, §8.1; issue 22 item 8). Every key is optional: an absent key keeps the
//! control's default, which the interpreter owns (`AxiomaMachineParams`), so the defaults are
//! written once.
//!
//! ```toml
//! [channel]
//! spindle_encoder = true        # a spindle position encoder (G276 threading, M19); false → error 2301
//! plc_outputs = 64              # G110/G111 output addresses 0 … n − 1, n = 1 … 4096
//! compensation_depth = 3        # radius-compensation look-ahead depth (M905 without N1= restores it), 2 … 64
//! [channel.edge_positions]      # lathe cutting-edge positions: code (0 … 9) = [Z, X] from the nose
//! 3 = [-1.0, -1.0]              # centre to the tool tip, in nose radii; unlisted codes keep the default
//! ```

use super::Invalid;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use toml::Spanned;

/// The checked `[channel]` section; `None` = the control's default.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ChannelData {
    /// A spindle position encoder is configured.
    pub spindle_encoder: Option<bool>,
    /// Number of PLC outputs G110/G111 may address.
    pub plc_outputs: Option<u32>,
    /// Look-ahead depth of radius compensation.
    pub compensation_depth: Option<u32>,
    /// Cutting-edge position code → (Z, X) vector from the nose centre to the tip, in nose radii.
    pub edge_positions: BTreeMap<u32, [f64; 2]>,
}

/// `code = [Z, X]` entries, as written.
type RawEdges = Spanned<BTreeMap<Spanned<String>, Spanned<[f64; 2]>>>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawChannel {
    spindle_encoder: Option<bool>,
    plc_outputs: Option<Spanned<i64>>,
    compensation_depth: Option<Spanned<i64>>,
    edge_positions: Option<RawEdges>,
}

fn in_range(
    v: &Option<Spanned<i64>>,
    name: &str,
    lo: i64,
    hi: i64,
) -> Result<Option<u32>, Invalid> {
    match v {
        None => Ok(None),
        Some(n) if (lo..=hi).contains(n.get_ref()) => Ok(Some(*n.get_ref() as u32)),
        Some(n) => Err((
            format!("[channel] {name} must be {lo} … {hi}, not {}", n.get_ref()),
            n.span(),
        )),
    }
}

impl RawChannel {
    pub(super) fn validate(&self) -> Result<ChannelData, Invalid> {
        let mut edge_positions = BTreeMap::new();
        for (key, v) in self.edge_positions.iter().flat_map(|t| t.get_ref()) {
            let text = key.get_ref();
            let code = text
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|c| *c <= 9)
                .ok_or_else(|| {
                    (
                        format!("[channel.edge_positions] code must be 0…9, not \"{text}\""),
                        key.span(),
                    )
                })?;
            let [z, x] = *v.get_ref();
            if !(z.is_finite() && x.is_finite() && z.abs() <= 1.0 && x.abs() <= 1.0) {
                return Err((
                    format!(
                        "[channel.edge_positions] {code}: each component is a fraction of the nose radius, −1 … 1, not [{z}, {x}]"
                    ),
                    v.span(),
                ));
            }
            if edge_positions.insert(code, [z, x]).is_some() {
                return Err((
                    format!("[channel.edge_positions] {code} is defined twice"),
                    key.span(),
                ));
            }
        }
        Ok(ChannelData {
            spindle_encoder: self.spindle_encoder,
            plc_outputs: in_range(&self.plc_outputs, "plc_outputs", 1, 4096)?,
            compensation_depth: in_range(&self.compensation_depth, "compensation_depth", 2, 64)?,
            edge_positions,
        })
    }
}
