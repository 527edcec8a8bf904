//! Checks of machine-data sections that refer to the rest of the file: `[kinematics]` against the
//! `[[axis]]` list, and the AxiOMA rate tables `[feed_table]` / `[speed_table]`; and of the
//! tolerances.

use super::{AxisData, Invalid};
use stanok_kin::KinematicsData;
use std::collections::BTreeMap;
use toml::Spanned;

/// `path_tolerance` when the file has none, mm: G64 without P runs within 0.05 mm.
pub const PATH_TOLERANCE: f64 = 0.05;

/// A tolerance key (`arc_tolerance`, `path_tolerance`): a finite number of mm, at least `min`.
pub(super) fn tolerance(value: &Spanned<f64>, key: &str, min: f64) -> Result<f64, Invalid> {
    let t = *value.get_ref();
    if t.is_finite() && t >= min {
        return Ok(t);
    }
    let what = if min > 0.0 {
        "a positive"
    } else {
        "zero or a positive"
    };
    Err((
        format!("{key} must be {what} number of mm, not {t}"),
        value.span(),
    ))
}

/// The `[kinematics]` section checked against the machine type and the `[[axis]]` list: every
/// rotary orientation axis must be an axis of the machine, and takes its travel limits and
/// velocity from there (so they are given once).
pub(super) fn validate_kinematics(
    k: &Spanned<KinematicsData>,
    axes: &[AxisData],
) -> Result<KinematicsData, Invalid> {
    let mut data = k.get_ref().clone();
    if let (Some(fat), true) = (&data.fat, data.rotary.is_empty()) {
        let machine = stanok_kin::from_fat(fat).map_err(|e| {
            (
                format!("kinematics: FAT error {}: {}", e.code, e.message),
                k.span(),
            )
        })?;
        data.rotary = machine.rotary_axes().cloned().collect();
    }
    for r in &mut data.rotary {
        let Some(axis) = axes.iter().find(|a| a.name == r.name.to_ascii_uppercase()) else {
            return Err((
                format!(
                    "kinematics: rotary axis {} is not one of the machine's [[axis]] entries",
                    r.name
                ),
                k.span(),
            ));
        };
        r.min = axis.min;
        r.max = axis.max;
        r.max_velocity = axis.max_velocity;
    }
    data.build()
        .map_err(|e| (format!("kinematics: {e}"), k.span()))?;
    Ok(data)
}

/// `[feed_table]` / `[speed_table]`: `i = value`, i = 0…127 (the AxiOMA channel tables have 128
/// entries), value a positive finite rate.
pub(super) fn rate_table(
    table: &Option<Spanned<BTreeMap<Spanned<String>, Spanned<f64>>>>,
    name: &str,
) -> Result<BTreeMap<u32, f64>, Invalid> {
    let mut out = BTreeMap::new();
    for (key, v) in table.iter().flat_map(|t| t.get_ref()) {
        let text = key.get_ref();
        let i = text
            .trim()
            .parse::<u32>()
            .ok()
            .filter(|i| *i <= 127)
            .ok_or_else(|| {
                (
                    format!("[{name}] index must be 0…127, not \"{text}\""),
                    key.span(),
                )
            })?;
        let value = *v.get_ref();
        if !(value.is_finite() && value > 0.0) {
            return Err((
                format!("[{name}] {i} must be a positive number, not {value}"),
                v.span(),
            ));
        }
        if out.insert(i, value).is_some() {
            return Err((format!("[{name}] {i} is defined twice"), key.span()));
        }
    }
    Ok(out)
}
