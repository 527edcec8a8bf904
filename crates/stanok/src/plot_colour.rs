//! `plot --color speed|limit`: the path coloured by block.
//!
//! The program runs on the simulated machine (as `stanok run`, without a trace) and its block
//! times (`stanok_motion::timing`) are gathered per source line:
//! * **limit**: the limit that held the line's blocks longest (summed over the line's blocks, so
//!   a line run many times — a loop, a subprogram — gets the limit of most of its time);
//! * **speed**: the line's mean path speed, its length over its planned time (mm/min), in six
//!   equal bands from 0 to the fastest line; slow is red, fast is blue.
//!
//! Dwells and lines that did not move get no colour (they draw nothing anyway); a line without
//! one is drawn in its layer's own look. A run that stops at an error colours what ran before it.
//! The sheet draws each motion with its line's colour (`Sheet::draw_styled`) and lists the
//! classes in its legend.

use crate::cli::PlotColor;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_machine::{MachineData, SimMachine};
use stanok_plot::Colour;
use std::collections::BTreeMap;

/// A colour per source line and the legend of the colours.
#[derive(Debug, Clone, Default)]
pub struct Colouring {
    /// The legend: label and colour, in key order.
    pub legend: Vec<(String, Colour)>,
    /// Colour of each source line that has one.
    pub line_colour: BTreeMap<u32, Colour>,
}

/// Every limit `run` reports, in the legend's order, with its colour.
const LIMIT_COLOURS: [(&str, [u8; 3]); 10] = [
    ("programmed feed", [0x2f, 0x9e, 0x44]),
    ("axis velocity", [0x1c, 0x7e, 0xd6]),
    ("axis acceleration", [0xf5, 0x9f, 0x00]),
    ("jerk", [0xe8, 0x59, 0x0c]),
    ("curvature", [0xae, 0x3e, 0xc9]),
    ("blend tolerance", [0xd6, 0x33, 0x6c]),
    ("exact stop", [0xc9, 0x2a, 0x2a]),
    ("look-ahead window", [0x5f, 0x3d, 0xc4]),
    ("override", [0x86, 0x8e, 0x96]),
    ("dwell", [0x34, 0x3a, 0x40]),
];

/// Speed bands, slow (red) to fast (blue).
const SPEED_COLOURS: [[u8; 3]; 6] = [
    [0xd7, 0x30, 0x27],
    [0xf4, 0x6d, 0x43],
    [0xfd, 0xae, 0x61],
    [0x74, 0xad, 0xd1],
    [0x45, 0x75, 0xb4],
    [0x31, 0x36, 0x95],
];

/// Per line: planned time, length, time per limit.
type LineTimes = (f64, f64, BTreeMap<&'static str, f64>);

/// The colouring of the program whose commands `commands` yields, run on `machine` (module doc).
pub fn colouring(
    commands: impl Iterator<Item = Result<Spanned<Canon>, Diagnostic>>,
    machine: &MachineData,
    by: PlotColor,
) -> Colouring {
    let mut sim = SimMachine::new(machine.clone());
    for cmd in commands {
        let Ok(cmd) = cmd else { break };
        if sim.apply(&cmd).is_err() {
            break;
        }
    }
    let report = sim.finish();
    let mut lines: BTreeMap<u32, LineTimes> = BTreeMap::new();
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
                    .and_then(|(l, _)| LIMIT_COLOURS.iter().position(|c| c.0 == *l))
            };
            let line_limit: BTreeMap<u32, usize> = lines
                .iter()
                .filter_map(|(line, v)| Some((*line, limit_of(&v.2)?)))
                .collect();
            let legend = (0..LIMIT_COLOURS.len())
                .filter(|k| line_limit.values().any(|l| l == k))
                .map(|k| (LIMIT_COLOURS[k].0.to_string(), Colour(LIMIT_COLOURS[k].1)))
                .collect();
            Colouring {
                legend,
                line_colour: line_limit
                    .into_iter()
                    .map(|(line, k)| (line, Colour(LIMIT_COLOURS[k].1)))
                    .collect(),
            }
        }
        PlotColor::Speed => {
            let speed = |v: &LineTimes| if v.0 > 0.0 { v.1 / v.0 * 60.0 } else { 0.0 };
            let fastest = lines.values().map(speed).fold(0.0, f64::max);
            let band = nice_band(fastest / SPEED_COLOURS.len() as f64);
            let band_of = |v: &LineTimes| ((speed(v) / band).floor() as usize).min(5);
            Colouring {
                legend: SPEED_COLOURS
                    .iter()
                    .enumerate()
                    .map(|(k, c)| {
                        let (lo, hi) = (band * k as f64, band * (k + 1) as f64);
                        (format!("{lo}–{hi} mm/min"), Colour(*c))
                    })
                    .collect(),
                line_colour: lines
                    .iter()
                    .map(|(line, v)| (*line, Colour(SPEED_COLOURS[band_of(v)])))
                    .collect(),
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
