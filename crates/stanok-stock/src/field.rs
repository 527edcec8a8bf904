//! The stock as a light picture for a live view (the panel's 3D view): a height field of at most
//! `max_side` × `max_side` cells sampled from the mill's dexels, or a lathe's outer profile of at
//! most `max_side`² rows, with heights quantised to 16 bits.
//!
//! *Sampling:* cell (i, j) of the field shows the line at the centre of its block of
//! `stride × stride` model lines (as `DexelGrid::coarse` does for meshes), so a field is a subset of
//! the model, never an average that shows material where there is none. Its top is the height of
//! that line's highest material (a Z-dexel's overhangs are not drawn).
//!
//! *Quantisation:* a height `z` in `[lo, hi]` (the stock as it was made: its bottom and top, or
//! radius 0 and the bar's radius) is `round((z − lo) / (hi − lo) · 65534)`; [`EMPTY`] marks a
//! line without material. 50 mm of stock is drawn in steps of 0.8 µm. The size of a field is
//! bounded by `max_side` whatever the stock or the resolution: 2 bytes a cell.

use crate::dexel::Dexel;
use crate::lathe::LatheModel;
use crate::mill::MillModel;
use crate::sim::{Model, StockSim};
use serde::Serialize;

/// A cell without material.
pub const EMPTY: u16 = u16::MAX;
/// Highest quantised height (the stock's initial top).
pub const TOP: u16 = u16::MAX - 1;

/// What a live view draws of the stock (module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StockField {
    /// `mill` (a height field over X, Y) or `lathe` (radii along Z about the spindle axis).
    pub kind: &'static str,
    /// Mill: the corner of cell (0, 0) in the stock frame, mm. Lathe: the spindle axis (X, Y).
    pub origin: [f64; 2],
    /// Mill: cell size in X and Y, mm. Lathe: row height along Z, and 0.
    pub cell: [f64; 2],
    /// Mill: cells in X and Y. Lathe: rows, and 1.
    pub n: [usize; 2],
    /// Lathe: Z of the lower edge of row 0, mm (mill: 0).
    pub z0: f64,
    /// The quantisation range: height (mill Z, lathe radius) of 0 and of [`TOP`], mm.
    pub range: [f64; 2],
    /// Quantised heights, row-major (i fastest); [`EMPTY`] = no material.
    #[serde(skip)]
    pub heights: Vec<u16>,
    /// Stock frame → machine: `machine = R_z(rotation_deg)·q + offset`.
    pub rotation_deg: f64,
    /// See `rotation_deg`, mm.
    pub offset: [f64; 3],
    /// Material removed so far, mm³ (the cut sweeps; the open chain is not yet cut).
    pub removed_mm3: f64,
    /// Volume of the stock as it was made, mm³.
    pub initial_mm3: f64,
}

fn quantise(z: f64, range: [f64; 2]) -> u16 {
    let span = (range[1] - range[0]).max(1e-9);
    ((z - range[0]) / span * TOP as f64)
        .round()
        .clamp(0.0, TOP as f64) as u16
}

/// The field of a mill model, in the stock frame (module doc).
pub fn mill_field(m: &MillModel, max_side: usize) -> StockField {
    let g = &m.grid;
    let stride = g.n[0].max(g.n[1]).div_ceil(max_side.max(2)).max(1);
    let n = [g.n[0].div_ceil(stride), g.n[1].div_ceil(stride)];
    let (bottom, top) = m.initial_z();
    let range = [bottom, top];
    let mut heights = Vec::with_capacity(n[0] * n[1]);
    for j in 0..n[1] {
        let sj = (j * stride + stride / 2).min(g.n[1] - 1);
        for i in 0..n[0] {
            let si = (i * stride + stride / 2).min(g.n[0] - 1);
            heights.push(match g.lines[sj * g.n[0] + si].top() {
                Some(z) => quantise(z as f64, range),
                None => EMPTY,
            });
        }
    }
    StockField {
        kind: "mill",
        origin: g.origin,
        cell: [g.cell[0] * stride as f64, g.cell[1] * stride as f64],
        n,
        z0: 0.0,
        range,
        heights,
        rotation_deg: 0.0,
        offset: [0.0; 3],
        removed_mm3: 0.0,
        initial_mm3: 0.0,
    }
}

/// The outer profile of a lathe model, at most `max_side`² rows (module doc).
pub fn lathe_field(l: &LatheModel, max_side: usize) -> StockField {
    let rows = l.rows.len().max(1);
    let side = max_side.max(2);
    let stride = rows.div_ceil(side * side).max(1);
    let n = l.rows.len().div_ceil(stride);
    let range = [0.0, l.initial_radius];
    let heights = (0..n)
        .map(
            |k| match &l.rows[(k * stride + stride / 2).min(l.rows.len() - 1)] {
                Dexel::Empty => EMPTY,
                d => quantise(d.top().map_or(0.0, f64::from), range),
            },
        )
        .collect();
    StockField {
        kind: "lathe",
        origin: l.axis,
        cell: [l.dz * stride as f64, 0.0],
        n: [n, 1],
        z0: l.z0,
        range,
        heights,
        rotation_deg: 0.0,
        offset: [0.0; 3],
        removed_mm3: 0.0,
        initial_mm3: 0.0,
    }
}

impl StockSim {
    /// The stock now as a field of at most `max_side` cells a side (module doc), with the
    /// placement that draws it in machine coordinates and the volumes so far; None before the
    /// first motion (the model does not exist yet).
    pub fn field(&self, max_side: usize) -> Option<StockField> {
        let mut f = match self.model()? {
            Model::Mill(m) => mill_field(m, max_side),
            Model::Lathe(l) => lathe_field(l, max_side),
        };
        f.offset = self.to_machine([0.0; 3]);
        let ex = self.to_machine([1.0, 0.0, 0.0]);
        f.rotation_deg = (ex[1] - f.offset[1])
            .atan2(ex[0] - f.offset[0])
            .to_degrees();
        f.removed_mm3 = self.removed_mm3();
        f.initial_mm3 = self.initial_volume_mm3();
        Some(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_field_samples_the_model_and_quantises_its_tops() {
        let mut m = MillModel::new_box([0.0, 0.0, -10.0], [100.0, 50.0, 0.0], 0.1);
        // A 5 mm deep pocket over the left half.
        for j in 0..m.grid.n[1] {
            for i in 0..500 {
                m.grid.lines[j * m.grid.n[0] + i].cut(-5.0, 1.0);
            }
        }
        let f = mill_field(&m, 128);
        assert_eq!(f.n, [125, 63]); // stride 8
        assert!((f.cell[0] - 0.8).abs() < 1e-12);
        assert_eq!(f.heights.len(), 125 * 63);
        assert_eq!(f.heights[0], quantise(-5.0, [-10.0, 0.0]));
        assert_eq!(f.heights[124], TOP);
        assert!(f.heights.len() * 2 <= 128 * 128 * 2);
    }

    #[test]
    fn a_lathe_field_is_the_outer_radius_of_its_rows() {
        // Ø50 × 80 bar at 0.1 mm: 800 rows, all of them within 128².
        let l = LatheModel::new_cylinder([0.0, 0.0], [-80.0, 0.0], 50.0, 0.0, 0.1);
        let f = lathe_field(&l, 128);
        assert_eq!((f.kind, f.n), ("lathe", [800, 1]));
        assert_eq!(f.range, [0.0, 25.0]);
        assert!(f.heights.iter().all(|&h| h == TOP));
        assert!((f.z0 + 80.0).abs() < 1e-9 && (f.cell[0] - 0.1).abs() < 1e-9);
        // A bound of 8² rows samples every 13th.
        assert_eq!(lathe_field(&l, 8).n, [62, 1]);
    }
}
