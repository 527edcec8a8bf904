//! The milling model: the stock as vertical dexels (a Z-dexel grid), cut by swept tools.
//!
//! ## Why Z dexels (ARCHITECTURE.md, "stanok-stock")
//! The solid is exact along Z and sampled in X and Y at the resolution. One swept tool needs one
//! line–solid intersection per line it covers (closed form, `sweep.rs`), so a 0.5 mm finishing
//! block of a Ø6 ball at 0.1 mm touches ~3 900 lines; memory is 16 bytes a line (16 MB per
//! 100 × 100 mm at 0.1 mm) whatever the program. Tri-dexels (adding X and Y lines) would make
//! vertical walls exact instead of within a cell, at three times the work per sweep; sparse
//! voxels would quantise Z as well and cost a voxel per 0.001 mm³. Measured in docs/performance.md.
//!
//! ## One sweep ([`MillModel::apply`])
//! 1. The cutter's footprint: the XY box of its primitives at both ends of the sweep.
//! 2. Culling: with a vertical axis, each row of lines is clipped to the chord of the capsule of
//!    the tool's widest radius around the tip's path (a diagonal move touches a band, not its
//!    box); a line whose top is below the swept cutter's lowest point is skipped. With a tilted
//!    axis each primitive is clipped to its own band and skipped on the lines where its lowest
//!    possible point is above the material (`tilted.rs`, which states both bounds). The grid is tiled
//!    ([`TILE`]² lines); each tile keeps an upper bound of its highest material point (recomputed
//!    after a cut touched it), which culls the bodies' checks of step 4. A sweep whose clipped
//!    rows hold at least [`PARALLEL_LINES`] lines is cut by two threads (`rayon::join`), each on
//!    its own half of the tile rows, so they never share a line or a tile flag. The count is of
//!    the lines the bands give (one pass over the rows, no line visited), not of the footprint's
//!    box: a leaning tool's box is mostly air, and a join costs as much CPU as a few thousand
//!    line visits (waking the other worker, its spinning; measured in docs/performance.md), so
//!    only sweeps far larger than that are split.
//! 3. Each remaining line: the union of its chords with the cutter's primitives (the vertical
//!    fast path when the axis is +Z), removed; the removed length is volume × cell area, the
//!    longest removed length the depth of cut, the lowest removed point the engagement of the tip.
//!    The primitives are visited from the lowest up; with a vertical axis, once one starts above
//!    the line's top, the line is cut from the lowest chord up to its top (everything above the
//!    lower primitives' chords is inside the swept body).
//! 4. Checks: the bodies above the flutes (flute extension, shank, holder) are intersected with what
//!    is left; the longest overlap on a line is the collision depth. A body whose lowest point is
//!    above the stock's initial top is skipped without looking at a line.

use crate::dexel::{Dexel, DexelGrid, Span};
use crate::sweep::{chord_vertical, Prim, Sweep};
use crate::tilted::TiltedPrim;
use crate::tool::MillTool;
use crate::vec3::{add, scale, V3};

/// Lines per tile side (module doc).
pub const TILE: usize = 8;

/// What one sweep did to the stock (module doc); lengths mm, volume mm³.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SweepHits {
    /// Volume removed.
    pub removed: f64,
    /// Longest length removed on one line (the depth of cut along Z).
    pub depth: f64,
    /// Lowest point removed (∞ if nothing).
    pub lowest_removed: f64,
    /// Longest overlap of the part above the flutes (within the cutter radius) with material.
    pub flute: f64,
    /// Longest overlap of the shank (where wider than the cutter) with material.
    pub shank: f64,
    /// Longest overlap of the holder with material.
    pub holder: f64,
}

impl SweepHits {
    /// Both together (volumes add, depths take the larger, lowest the lower).
    fn merge(&self, o: &SweepHits) -> SweepHits {
        SweepHits {
            removed: self.removed + o.removed,
            depth: self.depth.max(o.depth),
            lowest_removed: self.lowest_removed.min(o.lowest_removed),
            flute: self.flute.max(o.flute),
            shank: self.shank.max(o.shank),
            holder: self.holder.max(o.holder),
        }
    }
}

/// Sweeps that can touch at least this many lines are cut by two threads (rows split in half;
/// module doc, step 2).
pub const PARALLEL_LINES: usize = 16_000;

/// Where the lines are.
#[derive(Debug, Clone, Copy)]
struct GridGeometry {
    origin: [f64; 2],
    cell: [f64; 2],
    n0: usize,
    tiles0: usize,
}

impl GridGeometry {
    /// The lines of a row whose centres lie in `[xa, xb]`, within `within`.
    #[inline]
    fn index_range(
        &self,
        xa: f64,
        xb: f64,
        within: std::ops::Range<usize>,
    ) -> std::ops::Range<usize> {
        let a = ((xa - self.origin[0]) / self.cell[0] - 0.5)
            .ceil()
            .max(within.start as f64);
        let b = (((xb - self.origin[0]) / self.cell[0] - 0.5).floor() + 1.0).min(within.end as f64);
        if a >= b || a.is_nan() || b.is_nan() {
            return 0..0;
        }
        a as usize..b as usize
    }
}

/// Whole tile rows of the grid, from line row `j0`: what one thread may change.
struct Band<'a> {
    lines: &'a mut [Dexel],
    dirty: &'a mut [bool],
    j0: usize,
}

impl<'a> Band<'a> {
    /// The rows before `mid` (a multiple of [`TILE`]) and from it.
    fn split(self, mid: usize, n0: usize, tiles0: usize) -> (Band<'a>, Band<'a>) {
        let (la, lb) = self.lines.split_at_mut((mid - self.j0) * n0);
        let (da, db) = self.dirty.split_at_mut((mid - self.j0) / TILE * tiles0);
        (
            Band {
                lines: la,
                dirty: da,
                j0: self.j0,
            },
            Band {
                lines: lb,
                dirty: db,
                j0: mid,
            },
        )
    }
}

/// The cutter's part of a sweep (module doc, steps 1–3).
struct CutterPass<'a> {
    prims: &'a [Prim],
    /// Lowest point of each primitive over the sweep (the stack is sorted by it).
    lows: &'a [f64],
    sw: &'a Sweep,
    vertical: bool,
    /// The primitives prepared for a tilted axis (`tilted.rs`), else empty.
    tilted: &'a [TiltedPrim],
    z_low: f64,
    radius: f64,
    ir: std::ops::Range<usize>,
    grid: GridGeometry,
}

impl CutterPass<'_> {
    /// The lines of row `j` (at height `y`) the swept cutter can touch: with a vertical axis the
    /// capsule of its widest radius around the tip's path; with a tilted one the union of each
    /// primitive's band, which `prim_ir` receives (module doc, step 2). Empty when none.
    #[inline]
    fn row_lines(&self, y: f64, prim_ir: &mut [std::ops::Range<usize>]) -> std::ops::Range<usize> {
        let g = self.grid;
        let (p0, d) = (self.sw.p0, self.sw.d);
        if self.vertical {
            return match crate::lathe::capsule_chord(
                [p0[1], p0[0]],
                [p0[1] + d[1], p0[0] + d[0]],
                self.radius,
                y,
            ) {
                Some((xa, xb)) => g.index_range(xa, xb, self.ir.clone()),
                None => 0..0,
            };
        }
        let (mut a, mut b) = (usize::MAX, 0);
        for (k, tp) in self.tilted.iter().enumerate() {
            prim_ir[k] = match tp.x_range(y) {
                Some((xa, xb)) => g.index_range(xa, xb, self.ir.clone()),
                None => 0..0,
            };
            if !prim_ir[k].is_empty() {
                a = a.min(prim_ir[k].start);
                b = b.max(prim_ir[k].end);
            }
        }
        if a >= b {
            0..0
        } else {
            a..b
        }
    }

    /// How many lines of rows `rows` [`CutterPass::row_lines`] gives: the work of the sweep.
    fn count_lines(&self, rows: std::ops::Range<usize>) -> usize {
        let g = self.grid;
        let mut prim_ir: Vec<std::ops::Range<usize>> = vec![0..0; self.tilted.len()];
        rows.map(|j| {
            let y = g.origin[1] + (j as f64 + 0.5) * g.cell[1];
            self.row_lines(y, &mut prim_ir).len()
        })
        .sum()
    }

    /// Cuts the lines of rows `rows` (inside `band`).
    fn run(&self, band: Band<'_>, rows: std::ops::Range<usize>) -> SweepHits {
        let mut hits = SweepHits {
            lowest_removed: f64::INFINITY,
            ..Default::default()
        };
        let g = self.grid;
        let area = g.cell[0] * g.cell[1];
        // Per row, the lines each tilted primitive's band covers.
        let mut prim_ir: Vec<std::ops::Range<usize>> = vec![0..0; self.tilted.len()];
        for j in rows {
            let y = g.origin[1] + (j as f64 + 0.5) * g.cell[1];
            let ir = self.row_lines(y, &mut prim_ir);
            if ir.is_empty() {
                continue;
            }
            let row = (j - band.j0) * g.n0;
            for i in ir {
                let line = &mut band.lines[row + i];
                let top = match line.top() {
                    Some(top) if (top as f64) >= self.z_low => top as f64,
                    _ => continue,
                };
                let c = [g.origin[0] + (i as f64 + 0.5) * g.cell[0], y];
                // The primitives that reach below the top; with a vertical axis, one that does
                // not means everything above the lower ones is air: cut to the top.
                let mut range: Option<(f64, f64)> = None;
                let mut open_top = false;
                for (k, (p, &low)) in self.prims.iter().zip(self.lows).enumerate() {
                    let chord = if self.vertical {
                        if low > top {
                            open_top = true;
                            break;
                        }
                        chord_vertical(p, self.sw, c[0], c[1])
                    } else {
                        // Tilted: outside its band or above the material, a primitive cuts
                        // nothing the others do not (tilted.rs).
                        let tp = &self.tilted[k];
                        if low > top || !prim_ir[k].contains(&i) || tp.bound.above(c, top) {
                            continue;
                        }
                        tp.chord(c)
                    };
                    if let Some((a, b)) = chord {
                        range = Some(range.map_or((a, b), |(x, y)| (x.min(a), y.max(b))));
                    }
                }
                let Some((a, mut b)) = range else { continue };
                if open_top {
                    b = f64::INFINITY;
                }
                let (removed, lowest) = line.cut(a, b);
                if removed > 0.0 {
                    hits.removed += removed * area;
                    hits.depth = hits.depth.max(removed);
                    hits.lowest_removed = hits.lowest_removed.min(lowest);
                    band.dirty[(j - band.j0) / TILE * g.tiles0 + i / TILE] = true;
                }
            }
        }
        hits
    }
}

/// The stock of a mill (module doc).
#[derive(Debug, Clone)]
pub struct MillModel {
    /// The vertical dexels, stock frame.
    pub grid: DexelGrid,
    tiles: [usize; 2],
    tile_top: Vec<f32>,
    tile_dirty: Vec<bool>,
    /// The highest material point at the start (an upper bound for ever after).
    initial_top: f64,
    /// Lowest material point at the start.
    initial_bottom: f64,
}

/// The lowest point of a primitive with the tool tip at `p` and unit axis `a`.
pub fn prim_lowest(p: &Prim, tip: V3, a: V3) -> f64 {
    let tilt = (1.0 - a[2] * a[2]).max(0.0).sqrt();
    match *p {
        Prim::Frustum { h0, h1, r0, r1 } => {
            let z0 = tip[2] + h0 * a[2] - r0 * tilt;
            let z1 = tip[2] + h1 * a[2] - r1 * tilt;
            z0.min(z1)
        }
        Prim::Sphere { hc, r } => tip[2] + hc * a[2] - r,
    }
}

/// The XY box of a primitive over a sweep.
fn prim_box(p: &Prim, sw: &Sweep) -> ([f64; 2], [f64; 2]) {
    let (h0, h1) = match *p {
        Prim::Frustum { h0, h1, .. } => (h0, h1),
        Prim::Sphere { hc, .. } => (hc, hc),
    };
    let r = p.max_radius();
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let p1 = add(sw.p0, sw.d);
    for tip in [sw.p0, p1] {
        for h in [h0, h1] {
            let c = add(tip, scale(sw.axis, h));
            for k in 0..2 {
                lo[k] = lo[k].min(c[k] - r);
                hi[k] = hi[k].max(c[k] + r);
            }
        }
    }
    (lo, hi)
}

impl MillModel {
    /// A model of the given lines (`grid.lines` filled).
    pub fn from_grid(grid: DexelGrid) -> MillModel {
        let tiles = [grid.n[0].div_ceil(TILE), grid.n[1].div_ceil(TILE)];
        let mut m = MillModel {
            tile_top: vec![f32::NEG_INFINITY; tiles[0] * tiles[1]],
            tile_dirty: vec![true; tiles[0] * tiles[1]],
            tiles,
            grid,
            initial_top: f64::NEG_INFINITY,
            initial_bottom: f64::INFINITY,
        };
        for d in &m.grid.lines {
            if let (Some(first), Some(top)) = (d.spans().first(), d.top()) {
                m.initial_top = m.initial_top.max(top as f64);
                m.initial_bottom = m.initial_bottom.min(first.lo as f64);
            }
        }
        for t in 0..m.tile_top.len() {
            m.refresh_tile(t);
        }
        m
    }

    /// A box `[lo, hi]` (stock frame).
    pub fn new_box(lo: V3, hi: V3, resolution: f64) -> MillModel {
        let mut grid = DexelGrid::new([lo[0], lo[1]], [hi[0], hi[1]], resolution);
        let span = Span {
            lo: lo[2] as f32,
            hi: hi[2] as f32,
        };
        grid.lines.fill(Dexel::One(span));
        MillModel::from_grid(grid)
    }

    /// A cylinder along Z (axis through `centre`), from `z0` to `z1`, with an optional bore.
    pub fn new_cylinder(
        centre: [f64; 2],
        z: [f64; 2],
        diameter: f64,
        bore: f64,
        resolution: f64,
    ) -> MillModel {
        let r = diameter / 2.0;
        let mut grid = DexelGrid::new(
            [centre[0] - r, centre[1] - r],
            [centre[0] + r, centre[1] + r],
            resolution,
        );
        let span = Span {
            lo: z[0] as f32,
            hi: z[1] as f32,
        };
        for j in 0..grid.n[1] {
            for i in 0..grid.n[0] {
                let c = grid.centre(i, j);
                let rho = ((c[0] - centre[0]).powi(2) + (c[1] - centre[1]).powi(2)).sqrt();
                if rho <= r && rho >= bore / 2.0 {
                    grid.lines[j * grid.n[0] + i] = Dexel::One(span);
                }
            }
        }
        MillModel::from_grid(grid)
    }

    /// The lowest and highest material of the stock as it was made.
    pub fn initial_z(&self) -> (f64, f64) {
        (self.initial_bottom, self.initial_top)
    }

    fn refresh_tile(&mut self, t: usize) {
        let (ti, tj) = (t % self.tiles[0], t / self.tiles[0]);
        let mut top = f32::NEG_INFINITY;
        for j in tj * TILE..((tj + 1) * TILE).min(self.grid.n[1]) {
            let row = j * self.grid.n[0];
            for i in ti * TILE..((ti + 1) * TILE).min(self.grid.n[0]) {
                if let Some(z) = self.grid.lines[row + i].top() {
                    top = top.max(z);
                }
            }
        }
        self.tile_top[t] = top;
        self.tile_dirty[t] = false;
    }

    /// Visits the lines of the box `[lo, hi]` whose tile may hold material above `z_min`,
    /// refreshing stale tile bounds first. `f` gets the line index and its centre.
    fn for_lines(
        &mut self,
        lo: [f64; 2],
        hi: [f64; 2],
        z_min: f64,
        mut f: impl FnMut(&mut DexelGrid, usize, [f64; 2]) -> bool,
    ) {
        let ir = self.grid.index_range(0, lo[0], hi[0]);
        let jr = self.grid.index_range(1, lo[1], hi[1]);
        if ir.is_empty() || jr.is_empty() {
            return;
        }
        let n0 = self.grid.n[0];
        for tj in jr.start / TILE..=(jr.end - 1) / TILE {
            for ti in ir.start / TILE..=(ir.end - 1) / TILE {
                let t = tj * self.tiles[0] + ti;
                if self.tile_dirty[t] {
                    self.refresh_tile(t);
                }
                if (self.tile_top[t] as f64) < z_min {
                    continue;
                }
                let mut touched = false;
                for j in (tj * TILE).max(jr.start)..((tj + 1) * TILE).min(jr.end) {
                    for i in (ti * TILE).max(ir.start)..((ti + 1) * TILE).min(ir.end) {
                        let c = self.grid.centre(i, j);
                        touched |= f(&mut self.grid, j * n0 + i, c);
                    }
                }
                if touched {
                    self.tile_dirty[t] = true;
                }
            }
        }
    }

    /// An upper bound of the material's top over the lines `ir` × `jr` (the tiles' bounds).
    fn top_over(&self, ir: &std::ops::Range<usize>, jr: &std::ops::Range<usize>) -> f64 {
        let mut top = f32::NEG_INFINITY;
        for tj in jr.start / TILE..=(jr.end - 1) / TILE {
            for ti in ir.start / TILE..=(ir.end - 1) / TILE {
                top = top.max(self.tile_top[tj * self.tiles[0] + ti]);
            }
        }
        top as f64
    }

    /// Cuts with `tool` swept along `sw` and checks its other bodies (module doc).
    pub fn apply(&mut self, tool: &MillTool, sw: &Sweep) -> SweepHits {
        let vertical = sw.axis[0].abs() < 1e-12 && sw.axis[1].abs() < 1e-12 && sw.axis[2] > 0.0;
        let p1 = add(sw.p0, sw.d);
        let mut hits = SweepHits {
            lowest_removed: f64::INFINITY,
            ..Default::default()
        };
        // 1–3: the cutter.
        let lows: Vec<f64> = tool
            .cutter
            .iter()
            .map(|p| prim_lowest(p, sw.p0, sw.axis).min(prim_lowest(p, p1, sw.axis)))
            .collect();
        let z_low = lows.iter().copied().fold(f64::INFINITY, f64::min);
        if z_low <= self.initial_top {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for p in &tool.cutter {
                let (a, b) = prim_box(p, sw);
                for k in 0..2 {
                    lo[k] = lo[k].min(a[k]);
                    hi[k] = hi[k].max(b[k]);
                }
            }
            let jr = self.grid.index_range(1, lo[1], hi[1]);
            let ir = self.grid.index_range(0, lo[0], hi[0]);
            if !(jr.is_empty() || ir.is_empty()) {
                let tilted: Vec<TiltedPrim> = if vertical {
                    Vec::new()
                } else {
                    // The highest material under the footprint (tile bounds only fall as the
                    // stock is cut, so a stale one is still an upper bound): each primitive's
                    // band is clipped to where its height bound is below it (tilted.rs).
                    let z_top = self.top_over(&ir, &jr);
                    tool.cutter
                        .iter()
                        .map(|p| TiltedPrim::new(p, sw).below(z_top))
                        .collect()
                };
                let cut = CutterPass {
                    prims: &tool.cutter,
                    lows: &lows,
                    sw,
                    vertical,
                    tilted: &tilted,
                    z_low,
                    radius: tool.cutter.iter().map(Prim::max_radius).fold(0.0, f64::max),
                    ir,
                    grid: GridGeometry {
                        origin: self.grid.origin,
                        cell: self.grid.cell,
                        n0: self.grid.n[0],
                        tiles0: self.tiles[0],
                    },
                };
                // Two halves of the rows on two threads when the lines the cutter can touch are
                // many enough (counted on its clipped bands, not its box: a leaning tool's box is
                // mostly air).
                let parallel = jr.len() >= 2 * TILE
                    && jr.len() * cut.ir.len() >= PARALLEL_LINES
                    && cut.count_lines(jr.clone()) >= PARALLEL_LINES;
                let band = Band {
                    lines: &mut self.grid.lines,
                    dirty: &mut self.tile_dirty,
                    j0: 0,
                };
                let part = if parallel {
                    let mid = (jr.start + jr.len() / 2) / TILE * TILE;
                    let (a, b) = band.split(mid, cut.grid.n0, cut.grid.tiles0);
                    let (x, y) =
                        rayon::join(|| cut.run(a, jr.start..mid), || cut.run(b, mid..jr.end));
                    x.merge(&y)
                } else {
                    cut.run(band, jr)
                };
                hits = hits.merge(&part);
            }
        }
        // 4: the bodies above the flutes.
        let bodies: [(&mut f64, &[Prim]); 3] = [
            (&mut hits.flute, tool.flute_ext.as_slice()),
            (&mut hits.shank, tool.shank.as_slice()),
            (&mut hits.holder, &tool.holder),
        ];
        for (depth, prims) in bodies {
            for p in prims {
                let z_low = prim_lowest(p, sw.p0, sw.axis).min(prim_lowest(p, p1, sw.axis));
                if z_low > self.initial_top {
                    continue;
                }
                let (lo, hi) = prim_box(p, sw);
                let tp = (!vertical).then(|| TiltedPrim::new(p, sw));
                self.for_lines(lo, hi, z_low, |grid, idx, c| {
                    let line = &grid.lines[idx];
                    let Some(top) = line.top().map(f64::from) else {
                        return false;
                    };
                    if top < z_low {
                        return false;
                    }
                    let chord = match &tp {
                        None => chord_vertical(p, sw, c[0], c[1]),
                        Some(tp) if tp.bound.above(c, top) => None,
                        Some(tp) => tp.chord(c),
                    };
                    if let Some((a, b)) = chord {
                        *depth = depth.max(line.overlap(a, b));
                    }
                    false
                });
            }
        }
        hits
    }

    /// Material volume, mm³.
    pub fn volume(&self) -> f64 {
        self.grid.volume()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::tool::{resolve, ToolShape};
    use stanok_canon::setup::{CutterShape, Tool, ToolBody, ToolEdge, ToolTable};

    pub(crate) fn tool(shape: CutterShape, r: f64) -> MillTool {
        let mut t = ToolTable::default();
        t.tools.insert(
            1,
            Tool {
                number: 1,
                edges: vec![ToolEdge {
                    radius: r,
                    ..Default::default()
                }],
                body: ToolBody {
                    cutter: Some(shape),
                    flute_length: Some(40.0),
                    reach: Some(50.0),
                    ..Default::default()
                },
                ..Default::default()
            },
        );
        match resolve(1, &t, false, 0.01).0 {
            ToolShape::Mill(m) => m,
            ToolShape::Insert(_) => unreachable!(),
        }
    }

    #[test]
    fn a_flat_slot_removes_its_stadium() {
        // Ø10 flat end mill, 5 deep, from (20, 40) to (80, 40): 60 × 10 + π·25, times 5.
        let mut m = MillModel::new_box([0.0, 0.0, -30.0], [100.0, 80.0, 0.0], 0.1);
        let before = m.volume();
        assert!((before - 240_000.0).abs() < 1e-6);
        let sw = Sweep {
            p0: [20.0, 40.0, -5.0],
            d: [60.0, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
        };
        let hits = m.apply(&tool(CutterShape::Flat, 5.0), &sw);
        let want = (600.0 + std::f64::consts::PI * 25.0) * 5.0;
        assert!(
            (hits.removed - want).abs() / want < 0.005,
            "{} vs {want}",
            hits.removed
        );
        assert!((before - m.volume() - hits.removed).abs() < 1e-3);
        assert!((hits.depth - 5.0).abs() < 1e-6);
        assert!((hits.lowest_removed + 5.0).abs() < 1e-6);
        assert_eq!((hits.flute, hits.holder), (0.0, 0.0));
    }

    #[test]
    fn side_milling_deeper_than_the_flutes_and_a_holder_into_the_top() {
        let mut m = MillModel::new_box([0.0, 0.0, -100.0], [100.0, 80.0, 0.0], 0.5);
        let t = tool(CutterShape::Flat, 5.0);
        let down = |x: f64, z: f64| Sweep {
            p0: [x, 40.0, 5.0],
            d: [0.0, 0.0, z - 5.0],
            axis: [0.0, 0.0, 1.0],
        };
        // A plunge clears its own column: the part above the flutes slides into the hole.
        let hits = m.apply(&t, &down(30.0, -45.0));
        assert!((hits.depth - 45.0).abs() < 1e-6);
        assert_eq!((hits.flute, hits.holder), (0.0, 0.0), "{hits:?}");
        // Sideways at that depth the flutes end at −5: 5 mm of wall above them.
        let side = Sweep {
            p0: [30.0, 40.0, -45.0],
            d: [20.0, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
        };
        let hits = m.apply(&t, &side);
        assert!((hits.flute - 5.0).abs() < 1e-6, "{hits:?}");
        // The Ø30 holder starts 50 above the tip: at a tip of −55 it is 5 into the top.
        let hits = m.apply(&t, &down(70.0, -55.0));
        assert!((hits.holder - 5.0).abs() < 1e-6, "{hits:?}");
    }
}
