//! Drawing a path of any length into memory bounded by the picture.
//!
//! Every layer of every view (rapids, feeds, the programmed contour, … in one colour) owns one
//! [`LayerPath`]: the SVG path data it has written and a small look-back of the points it has not
//! written yet. Points arrive in screen px, one move after the other, and go through two filters:
//!
//! 1. **Simplification** (always). The layer keeps an *anchor* (the last vertex it wrote, or the
//!    start of the polyline) and the *run* of points read since. A new point joins the run while
//!    every point of the run lies within `tolerance` px of the segment anchor → new point; when one
//!    would not, the previous point is written as a vertex and becomes the anchor. The run holds at
//!    most [`MAX_RUN`] points, so a point costs O(`MAX_RUN`) at worst. The written polyline stays
//!    within `tolerance` of the input polyline and keeps its vertices' positions (it only leaves
//!    vertices out). Tolerance: [`EXACT_TOLERANCE`] px while the sheet is small, [`DENSE_TOLERANCE`]
//!    px once it is dense.
//! 2. **Coverage** (once the sheet is dense). When the vertices written on the whole sheet pass
//!    `dense_after`, every layer gets a bitmap of [`CELL`] × [`CELL`] px cells over its view. A
//!    segment is written only if it passes through at least one cell its layer has not passed
//!    through yet; otherwise it would only ink pixels that are already inked, and it is left out
//!    (the pen jumps over it). So from then on every written segment marks at least one new cell,
//!    and the number of segments is bounded by the number of cells — by the picture, not by the
//!    program.
//!
//! A hard cap (`max_bytes` of path data over the sheet) stops writing altogether if even that is
//! too much (a picture so large that its cells alone would pass it); the sheet then says so.
//!
//! Invariants: the path data of a layer is a valid SVG `d` attribute at any moment after
//! [`LayerPath::flush`]; memory per layer = its path data + `MAX_RUN` points + its bitmap.

use crate::svg::num;
use crate::Style;
use std::fmt::Write;

/// Largest number of unwritten points a layer looks back over.
pub(crate) const MAX_RUN: usize = 32;
/// Simplification tolerance before the sheet is dense, px: far below what a 1.5 px stroke shows.
pub(crate) const EXACT_TOLERANCE: f64 = 0.1;
/// Simplification tolerance once the sheet is dense, px.
pub(crate) const DENSE_TOLERANCE: f64 = 0.5;
/// Side of a coverage cell, px.
pub(crate) const CELL: f64 = 2.0;

/// What the whole sheet has written so far, shared by its layers.
#[derive(Debug, Clone)]
pub(crate) struct Budget {
    /// Vertices written (M and L and A commands).
    pub(crate) vertices: usize,
    /// Bytes of path data written.
    pub(crate) bytes: usize,
    /// Vertices after which the sheet turns dense.
    pub(crate) dense_after: usize,
    /// Bytes after which nothing more is written.
    pub(crate) max_bytes: usize,
    /// Coverage filtering is on.
    pub(crate) dense: bool,
    /// Something was left out because of `max_bytes`.
    pub(crate) truncated: bool,
    /// Segments left out by the coverage filter (they would only have inked inked pixels).
    pub(crate) covered: u64,
}

impl Budget {
    pub(crate) fn new(dense_after: usize, max_bytes: usize) -> Self {
        Budget {
            vertices: 0,
            bytes: 0,
            dense_after,
            max_bytes,
            dense: false,
            truncated: false,
            covered: 0,
        }
    }

    fn tolerance(&self) -> f64 {
        if self.dense {
            DENSE_TOLERANCE
        } else {
            EXACT_TOLERANCE
        }
    }

    /// Counts a written command of `len` bytes.
    fn wrote(&mut self, len: usize) {
        self.vertices += 1;
        self.bytes += len;
        if self.vertices > self.dense_after {
            self.dense = true;
        }
        if self.bytes > self.max_bytes {
            self.truncated = true;
        }
    }
}

/// Which cells of a view a layer has passed through.
#[derive(Debug, Clone)]
struct Coverage {
    origin: [f64; 2],
    columns: usize,
    rows: usize,
    bits: Vec<u64>,
}

impl Coverage {
    fn new(area: [f64; 4]) -> Self {
        let columns = (area[2] / CELL).ceil().max(1.0) as usize;
        let rows = (area[3] / CELL).ceil().max(1.0) as usize;
        Coverage {
            origin: [area[0], area[1]],
            columns,
            rows,
            bits: vec![0; (columns * rows).div_ceil(64)],
        }
    }

    /// Marks the cells the segment a → b passes through (a DDA: one sample per cell along its
    /// longer direction); true if one of them was new.
    fn mark(&mut self, a: [f64; 2], b: [f64; 2]) -> bool {
        let longer = (b[0] - a[0]).abs().max((b[1] - a[1]).abs());
        // A segment is at most the view's diagonal long; the cap only guards against nonsense.
        let steps = ((longer / CELL).ceil() as usize).clamp(1, 1 << 16);
        let mut new = false;
        for k in 0..=steps {
            let f = k as f64 / steps as f64;
            let x = a[0] + (b[0] - a[0]) * f - self.origin[0];
            let y = a[1] + (b[1] - a[1]) * f - self.origin[1];
            if !(x >= 0.0 && y >= 0.0) {
                continue;
            }
            let (c, r) = ((x / CELL) as usize, (y / CELL) as usize);
            if c >= self.columns || r >= self.rows {
                continue;
            }
            let i = r * self.columns + c;
            let (word, bit) = (i / 64, 1u64 << (i % 64));
            if self.bits[word] & bit == 0 {
                self.bits[word] |= bit;
                new = true;
            }
        }
        new
    }
}

/// Distance from `p` to the segment a → b, px.
fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
}

fn same(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < 0.005 && (a[1] - b[1]).abs() < 0.005
}

/// One layer of one view (see the module doc).
#[derive(Debug, Clone)]
pub(crate) struct LayerPath {
    pub(crate) style: Style,
    /// The path data written so far.
    pub(crate) d: String,
    /// Where the SVG pen is (the end of the last written command).
    pen: Option<[f64; 2]>,
    /// The last point read.
    cursor: Option<[f64; 2]>,
    /// The last written vertex, or the start of the current polyline.
    anchor: [f64; 2],
    /// Points read after the anchor and not written yet.
    run: Vec<[f64; 2]>,
    /// The view's cell, for the coverage bitmap: x, y, w, h px.
    area: [f64; 4],
    coverage: Option<Coverage>,
}

impl LayerPath {
    pub(crate) fn new(style: Style, area: [f64; 4]) -> Self {
        LayerPath {
            style,
            d: String::new(),
            pen: None,
            cursor: None,
            anchor: [0.0; 2],
            run: Vec::with_capacity(MAX_RUN),
            area,
            coverage: None,
        }
    }

    /// Puts the cursor at `p` without drawing (nothing happens if it is already there).
    pub(crate) fn move_to(&mut self, p: [f64; 2], budget: &mut Budget) {
        if self.cursor.is_some_and(|c| same(c, p)) {
            return;
        }
        self.flush(budget);
        self.cursor = Some(p);
        self.anchor = p;
    }

    /// A straight line from the cursor to `p`.
    pub(crate) fn line_to(&mut self, p: [f64; 2], budget: &mut Budget) {
        let Some(cursor) = self.cursor else {
            self.move_to(p, budget);
            return;
        };
        if same(cursor, p) {
            return;
        }
        self.cursor = Some(p);
        self.run.push(p);
        let tolerance = budget.tolerance();
        let fits = self.run[..self.run.len() - 1]
            .iter()
            .all(|&q| distance_to_segment(q, self.anchor, p) <= tolerance);
        if !fits {
            let vertex = self.run[self.run.len() - 2];
            self.emit_line(vertex, budget);
            self.anchor = vertex;
            self.run.clear();
            self.run.push(p);
        }
        if self.run.len() >= MAX_RUN {
            self.flush(budget);
        }
    }

    /// A circular arc of radius `r` px (at most 180°) from the cursor to `p`; `sweep_flag` 1 runs
    /// clockwise on screen. Only used while the sheet is not dense (see `Sheet`).
    pub(crate) fn arc_to(&mut self, r: f64, sweep_flag: u8, p: [f64; 2], budget: &mut Budget) {
        self.flush(budget);
        let from = self.cursor.unwrap_or(p);
        self.cursor = Some(p);
        self.anchor = p;
        if budget.truncated {
            return;
        }
        let before = self.d.len();
        self.pen_to(from, budget);
        let r = num(r);
        let _ = write!(
            self.d,
            "A{r} {r} 0 0 {sweep_flag} {} {}",
            num(p[0]),
            num(p[1])
        );
        self.pen = Some(p);
        budget.wrote(self.d.len() - before);
    }

    /// Writes what the run still holds.
    pub(crate) fn flush(&mut self, budget: &mut Budget) {
        if let Some(&last) = self.run.last() {
            self.emit_line(last, budget);
            self.anchor = last;
            self.run.clear();
        }
    }

    /// Writes the segment anchor → `to`, unless the sheet is full or (dense) it inks nothing new.
    fn emit_line(&mut self, to: [f64; 2], budget: &mut Budget) {
        if budget.truncated {
            return;
        }
        let from = self.anchor;
        if budget.dense {
            let area = self.area;
            let coverage = self.coverage.get_or_insert_with(|| Coverage::new(area));
            if !coverage.mark(from, to) {
                budget.covered += 1;
                return;
            }
        }
        let before = self.d.len();
        self.pen_to(from, budget);
        let _ = write!(self.d, "L{} {}", num(to[0]), num(to[1]));
        self.pen = Some(to);
        budget.wrote(self.d.len() - before);
    }

    /// An `M` to `p` unless the pen is there.
    fn pen_to(&mut self, p: [f64; 2], budget: &mut Budget) {
        if !self.pen.is_some_and(|q| same(q, p)) {
            let before = self.d.len();
            let _ = write!(self.d, "M{} {}", num(p[0]), num(p[1]));
            budget.wrote(self.d.len() - before);
            self.pen = Some(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Layer, Style};

    fn layer() -> LayerPath {
        LayerPath::new(Style::plain(Layer::Feed), [0.0, 0.0, 1000.0, 1000.0])
    }

    #[test]
    fn collinear_points_collapse_to_one_segment() {
        let mut budget = Budget::new(1000, 1 << 20);
        let mut l = layer();
        l.move_to([0.0, 0.0], &mut budget);
        for k in 1..=100 {
            l.line_to([k as f64, 0.0], &mut budget);
        }
        l.line_to([100.0, 50.0], &mut budget);
        l.flush(&mut budget);
        // The run is capped at MAX_RUN points, so the straight part is a few segments at most.
        let segments = l.d.matches('L').count();
        assert!(segments <= 100 / MAX_RUN + 2, "{}", l.d);
        assert!(l.d.starts_with("M0 0L"), "{}", l.d);
        assert!(l.d.ends_with("L100 50"), "{}", l.d);
    }

    #[test]
    fn corners_are_kept() {
        let mut budget = Budget::new(1000, 1 << 20);
        let mut l = layer();
        l.move_to([0.0, 0.0], &mut budget);
        for p in [[10.0, 0.0], [10.0, 10.0], [0.0, 10.0], [0.0, 0.0]] {
            l.line_to(p, &mut budget);
        }
        l.flush(&mut budget);
        assert_eq!(l.d, "M0 0L10 0L10 10L0 10L0 0");
    }

    #[test]
    fn a_dense_layer_writes_a_segment_only_where_it_inks_something_new() {
        let mut budget = Budget::new(0, 1 << 20);
        budget.dense = true;
        let mut l = layer();
        // The same 100 px square 1000 times: only the first round is written.
        l.move_to([100.0, 100.0], &mut budget);
        for _ in 0..1000 {
            for p in [
                [200.0, 100.0],
                [200.0, 200.0],
                [100.0, 200.0],
                [100.0, 100.0],
            ] {
                l.line_to(p, &mut budget);
            }
        }
        l.flush(&mut budget);
        assert_eq!(l.d.matches('L').count(), 4, "{}", l.d);
        assert!(budget.covered > 3000);
    }

    #[test]
    fn the_byte_cap_stops_writing() {
        let mut budget = Budget::new(usize::MAX, 100);
        let mut l = layer();
        l.move_to([0.0, 0.0], &mut budget);
        for k in 0..1000 {
            l.line_to([(k % 2) as f64 * 500.0, k as f64], &mut budget);
        }
        l.flush(&mut budget);
        assert!(budget.truncated);
        assert!(l.d.len() < 130, "{}", l.d.len());
    }

    #[test]
    fn distance_to_a_segment_clamps_at_its_ends() {
        assert_eq!(
            distance_to_segment([5.0, 3.0], [0.0, 0.0], [10.0, 0.0]),
            3.0
        );
        assert_eq!(
            distance_to_segment([13.0, 4.0], [0.0, 0.0], [10.0, 0.0]),
            5.0
        );
        assert_eq!(distance_to_segment([3.0, 4.0], [0.0, 0.0], [0.0, 0.0]), 5.0);
    }
}
