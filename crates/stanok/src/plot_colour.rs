//! `plot --color speed|limit`: the path coloured by block.
//!
//! The program runs on the simulated machine (as `stanok run`, without a trace) and its block
//! times (`stanok_motion::timing`) are gathered per source line:
//! * **limit**: the limit that held the line's blocks longest (summed over the line's blocks, so
//!   a line run many times — a loop, a subprogram — gets the limit of most of its time);
//! * **speed**: the line's mean path speed, its length over its planned time (mm/min), in six
//!   equal bands from 0 to the fastest line; slow is red, fast is blue.
//!
//! Dwells and lines that did not move get no class (they draw nothing anyway). A run that stops
//! at an error colours what ran before it.

use crate::cli::PlotColor;
use stanok_canon::{Canon, Spanned};
use stanok_machine::{MachineData, SimMachine};
use stanok_plot::Colouring;
use std::collections::BTreeMap;

/// Every limit `run` reports, in the key's order, with its colour.
const LIMIT_COLOURS: [(&str, &str); 10] = [
    ("programmed feed", "#2f9e44"),
    ("axis velocity", "#1c7ed6"),
    ("axis acceleration", "#f59f00"),
    ("jerk", "#e8590c"),
    ("curvature", "#ae3ec9"),
    ("blend tolerance", "#d6336c"),
    ("exact stop", "#c92a2a"),
    ("look-ahead window", "#5f3dc4"),
    ("override", "#868e96"),
    ("dwell", "#343a40"),
];

/// Speed bands, slow (red) to fast (blue).
const SPEED_COLOURS: [&str; 6] = [
    "#d73027", "#f46d43", "#fdae61", "#74add1", "#4575b4", "#313695",
];

/// The colouring of `commands` run on `machine` (module doc).
pub fn colouring(commands: &[Spanned<Canon>], machine: &MachineData, by: PlotColor) -> Colouring {
    let mut sim = SimMachine::new(machine.clone());
    for cmd in commands {
        if sim.apply(cmd).is_err() {
            break;
        }
    }
    let report = sim.finish();
    // Per line: planned time, length, time per limit.
    let mut lines: BTreeMap<u32, (f64, f64, BTreeMap<&'static str, f64>)> = BTreeMap::new();
    for b in report.block_times.iter().filter(|b| b.length_mm > 0.0) {
        let e = lines.entry(b.line).or_default();
        e.0 += b.planned_s;
        e.1 += b.length_mm;
        *e.2.entry(b.limit).or_default() += b.planned_s;
    }
    match by {
        PlotColor::Limit => {
            let limit_of = |times: &BTreeMap<&'static str, f64>| {
                times
                    .iter()
                    .max_by(|a, b| a.1.total_cmp(b.1))
                    .map(|(l, _)| *l)
            };
            let used: Vec<usize> = (0..LIMIT_COLOURS.len())
                .filter(|&k| {
                    lines
                        .values()
                        .any(|v| limit_of(&v.2) == Some(LIMIT_COLOURS[k].0))
                })
                .collect();
            let line_class = lines
                .iter()
                .filter_map(|(line, v)| {
                    let limit = limit_of(&v.2)?;
                    let class = used.iter().position(|&k| LIMIT_COLOURS[k].0 == limit)?;
                    Some((*line, class))
                })
                .collect();
            Colouring {
                title: "limit".into(),
                classes: used
                    .iter()
                    .map(|&k| {
                        (
                            LIMIT_COLOURS[k].0.to_string(),
                            LIMIT_COLOURS[k].1.to_string(),
                        )
                    })
                    .collect(),
                line_class,
            }
        }
        PlotColor::Speed => {
            let speed = |v: &(f64, f64, BTreeMap<&'static str, f64>)| {
                if v.0 > 0.0 {
                    v.1 / v.0 * 60.0
                } else {
                    0.0
                }
            };
            let fastest = lines.values().map(speed).fold(0.0, f64::max);
            let band = nice_band(fastest / SPEED_COLOURS.len() as f64);
            let line_class = lines
                .iter()
                .map(|(line, v)| {
                    let k = (speed(v) / band).floor() as usize;
                    (*line, k.min(SPEED_COLOURS.len() - 1))
                })
                .collect();
            Colouring {
                title: "mean speed mm/min".into(),
                classes: SPEED_COLOURS
                    .iter()
                    .enumerate()
                    .map(|(k, c)| {
                        let (lo, hi) = (band * k as f64, band * (k + 1) as f64);
                        (format!("{lo}–{hi}"), c.to_string())
                    })
                    .collect(),
                line_class,
            }
        }
    }
}

/// The smallest 1, 2 or 5 × 10ⁿ at least `x` (at least 1 mm/min).
fn nice_band(x: f64) -> f64 {
    let x = x.max(1.0);
    let decade = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * decade)
        .find(|&b| b >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade)
}

#[cfg(test)]
mod tests {
    use super::nice_band;

    #[test]
    fn bands_are_round() {
        assert_eq!(nice_band(0.2), 1.0);
        assert_eq!(nice_band(150.0), 200.0);
        assert_eq!(nice_band(1000.0), 1000.0);
        assert_eq!(nice_band(1001.0), 2000.0);
        assert_eq!(nice_band(3000.0), 5000.0);
    }
}
