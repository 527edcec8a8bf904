//! Level of detail of the preview path: a program of any length reaches the page as at most
//! [`PathLod::budget`] points, within a stated distance of the programmed path.
//!
//! ## Algorithm (streaming, bounded memory)
//! The path arrives as polylines (rapid or feed; a new one wherever the kind changes or the path
//! jumps). Each polyline is simplified as it streams, with a tolerance ε:
//! * the last kept point is the **anchor** A; the points received since are **pending**;
//! * a new point P extends the run if every pending point lies within ε of the segment A→P and
//!   fewer than [`MAX_PENDING`] points are pending; otherwise the last pending point is kept (it
//!   becomes the anchor) and P starts the next run.
//!
//! So every dropped point is within ε of the kept polyline, and the work per point is bounded by
//! `MAX_PENDING` distance tests. ε starts at [`INITIAL_TOLERANCE`] (far below anything the view
//! shows). Whenever the kept points exceed the budget, ε is doubled and the kept points themselves
//! are simplified again with the new ε (the error of the result is then at most ε + ε/2 + … < 2ε,
//! which is the tolerance reported). If even a tolerance of [`MAX_TOLERANCE_FRACTION`] of the
//! path's extent leaves too many points — many tiny separate polylines (a million drilled holes) —
//! the path is cut there and marked truncated (the page says so).

use serde::Serialize;

/// Tolerance the simplification starts with, mm.
pub const INITIAL_TOLERANCE: f64 = 1e-4;

/// Points tested against a run's chord at most (bounds the work per point).
pub const MAX_PENDING: usize = 64;

/// Largest tolerance used, as a fraction of the largest extent of the path so far.
pub const MAX_TOLERANCE_FRACTION: f64 = 1.0 / 500.0;

/// Default point budget of a preview.
pub const DEFAULT_BUDGET: usize = 300_000;

/// One polyline of the preview, points flattened (`x0 y0 z0 x1 y1 z1 …`, machine mm).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PathPiece {
    /// Rapid (drawn dashed) or feed.
    pub rapid: bool,
    /// Source line of its first point.
    pub line: u32,
    /// X Y Z of each point, flattened.
    pub points: Vec<f32>,
}

/// The streaming simplifier of the module doc.
#[derive(Debug)]
pub struct PathLod {
    budget: usize,
    tolerance: f64,
    done: Vec<PathPiece>,
    kept: usize,
    current: Option<Run>,
    truncated_at: Option<u32>,
    points_in: u64,
    lo: [f64; 3],
    hi: [f64; 3],
}

/// The polyline being built.
#[derive(Debug)]
struct Run {
    rapid: bool,
    line: u32,
    kept: Vec<[f64; 3]>,
    pending: Vec<[f64; 3]>,
}

/// Distance from `p` to the segment a–b.
fn distance_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if len2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

impl Run {
    /// Adds a point (module doc); returns how many points were kept by it (0 or 1).
    fn add(&mut self, p: [f64; 3], tolerance: f64) -> usize {
        let a = *self.kept.last().expect("a run starts with a kept point");
        let fits = self.pending.len() < MAX_PENDING
            && self
                .pending
                .iter()
                .all(|q| distance_to_segment(*q, a, p) <= tolerance);
        if fits {
            self.pending.push(p);
            0
        } else {
            let last = *self.pending.last().expect("a non-empty run");
            self.kept.push(last);
            self.pending.clear();
            self.pending.push(p);
            1
        }
    }

    /// The last point received.
    fn end(&self) -> [f64; 3] {
        *self
            .pending
            .last()
            .or(self.kept.last())
            .expect("a run starts with a kept point")
    }

    /// The kept points plus the pending end.
    fn points(&self) -> impl Iterator<Item = [f64; 3]> + '_ {
        self.kept
            .iter()
            .copied()
            .chain(self.pending.last().copied())
    }
}

/// Simplifies a flattened polyline again with `tolerance`.
fn resimplify(piece: &mut PathPiece, tolerance: f64) {
    let pts: Vec<[f64; 3]> = piece
        .points
        .chunks_exact(3)
        .map(|c| [c[0] as f64, c[1] as f64, c[2] as f64])
        .collect();
    if pts.len() <= 2 {
        return;
    }
    let mut run = Run {
        rapid: piece.rapid,
        line: piece.line,
        kept: vec![pts[0]],
        pending: Vec::new(),
    };
    for p in &pts[1..] {
        run.add(*p, tolerance);
    }
    piece.points = run.points().flat_map(|p| p.map(|v| v as f32)).collect();
}

impl PathLod {
    /// At most `budget` points.
    pub fn new(budget: usize) -> Self {
        PathLod {
            budget: budget.max(16),
            tolerance: INITIAL_TOLERANCE,
            done: Vec::new(),
            kept: 0,
            current: None,
            truncated_at: None,
            points_in: 0,
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
        }
    }

    /// The point budget.
    pub fn budget(&self) -> usize {
        self.budget
    }

    /// True once the path was cut (see [`PathLod::truncated_at`]).
    pub fn truncated_at(&self) -> Option<u32> {
        self.truncated_at
    }

    /// Adds a move of `line` from `start` through `points` (its end last).
    pub fn push(&mut self, rapid: bool, line: u32, start: [f64; 3], points: &[[f64; 3]]) {
        for p in std::iter::once(&start).chain(points) {
            for (i, v) in p.iter().enumerate() {
                self.lo[i] = self.lo[i].min(*v);
                self.hi[i] = self.hi[i].max(*v);
            }
        }
        self.points_in += points.len() as u64;
        if self.truncated_at.is_some() {
            return;
        }
        let continues = self
            .current
            .as_ref()
            .is_some_and(|r| r.rapid == rapid && r.end() == start);
        if !continues {
            self.close_run();
            self.current = Some(Run {
                rapid,
                line,
                kept: vec![start],
                pending: Vec::new(),
            });
            self.kept += 1;
        }
        let tolerance = self.tolerance;
        let run = self.current.as_mut().expect("opened above");
        for p in points {
            self.kept += run.add(*p, tolerance);
        }
        // The run's pending end and the next run's start are not counted yet: two of room.
        if self.kept + 2 > self.budget {
            self.coarsen(line);
        }
    }

    fn close_run(&mut self) {
        if let Some(run) = self.current.take() {
            self.kept -= run.kept.len();
            let piece = PathPiece {
                rapid: run.rapid,
                line: run.line,
                points: run.points().flat_map(|p| p.map(|v| v as f32)).collect(),
            };
            self.kept += piece.points.len() / 3;
            self.done.push(piece);
        }
    }

    /// Doubles the tolerance and simplifies what is kept until it is within half the budget
    /// (module doc); cuts the path when the tolerance would pass its largest value.
    fn coarsen(&mut self, line: u32) {
        self.close_run();
        let extent = (0..3)
            .map(|i| self.hi[i] - self.lo[i])
            .fold(0.0f64, f64::max);
        let limit = (extent * MAX_TOLERANCE_FRACTION).max(INITIAL_TOLERANCE);
        while self.kept > self.budget / 2 {
            if self.tolerance * 2.0 > limit {
                self.truncated_at = Some(line);
                return;
            }
            self.tolerance *= 2.0;
            for piece in &mut self.done {
                resimplify(piece, self.tolerance);
            }
            self.kept = self.done.iter().map(|p| p.points.len() / 3).sum();
        }
    }

    /// The path, the tolerance it keeps (every programmed point within it), points received.
    pub fn finish(mut self) -> LodPath {
        self.close_run();
        let points = self.done.iter().map(|p| p.points.len() / 3).sum();
        let extents = self.lo[0].is_finite().then_some((self.lo, self.hi));
        LodPath {
            pieces: self.done,
            tolerance_mm: if self.tolerance > INITIAL_TOLERANCE {
                2.0 * self.tolerance
            } else {
                self.tolerance
            },
            points_in: self.points_in,
            points,
            truncated_at: self.truncated_at,
            extents,
        }
    }
}

/// A simplified path.
#[derive(Debug, Clone, Serialize)]
pub struct LodPath {
    /// The polylines.
    pub pieces: Vec<PathPiece>,
    /// Every programmed point is within this distance of them, mm.
    pub tolerance_mm: f64,
    /// Points received.
    pub points_in: u64,
    /// Points kept.
    pub points: usize,
    /// The path was cut at this line (too many separate pieces for the budget).
    pub truncated_at: Option<u32>,
    /// Smallest and largest X Y Z of every point received (also past a cut), machine mm.
    pub extents: Option<([f64; 3], [f64; 3])>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polyline(pieces: &[PathPiece]) -> Vec<[f64; 3]> {
        pieces
            .iter()
            .flat_map(|p| p.points.chunks_exact(3))
            .map(|c| [c[0] as f64, c[1] as f64, c[2] as f64])
            .collect()
    }

    fn distance_to_polyline(p: [f64; 3], line: &[[f64; 3]]) -> f64 {
        line.windows(2)
            .map(|w| distance_to_segment(p, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn collinear_points_collapse_and_corners_stay() {
        let mut lod = PathLod::new(1000);
        let pts: Vec<[f64; 3]> = (1..=100).map(|i| [i as f64, 0.0, 0.0]).collect();
        lod.push(false, 1, [0.0, 0.0, 0.0], &pts);
        lod.push(false, 2, [100.0, 0.0, 0.0], &[[100.0, 50.0, 0.0]]);
        let out = lod.finish();
        assert_eq!(out.pieces.len(), 1);
        // 64 pending points at most per run: (0,0,0), (64,0,0), (100,0,0), (100,50,0).
        assert_eq!(polyline(&out.pieces).len(), 4);
        assert_eq!(out.points_in, 101);
    }

    #[test]
    fn a_dense_spiral_fits_the_budget_within_the_reported_tolerance() {
        let budget = 2000;
        let mut lod = PathLod::new(budget);
        let n = 200_000;
        let mut all = Vec::with_capacity(n);
        let mut prev = [50.0, 0.0, 0.0];
        // 16 turns from r = 50 to r = 150 mm, points 0.025…0.075 mm apart.
        for i in 1..n {
            let t = i as f64 * 0.0005;
            let r = 50.0 + 0.0005 * i as f64;
            let p = [r * t.cos(), r * t.sin(), -0.0001 * i as f64];
            lod.push(false, i as u32, prev, &[p]);
            all.push(p);
            prev = p;
        }
        let out = lod.finish();
        assert!(out.points <= budget, "{}", out.points);
        assert!(out.truncated_at.is_none());
        let kept = polyline(&out.pieces);
        let worst = all
            .iter()
            .step_by(97)
            .map(|p| distance_to_polyline(*p, &kept))
            .fold(0.0, f64::max);
        // f32 storage adds a few µm at this radius.
        assert!(
            worst <= out.tolerance_mm + 1e-4,
            "{worst} > {}",
            out.tolerance_mm
        );
        assert!(out.tolerance_mm < 2.0, "{}", out.tolerance_mm);
    }

    #[test]
    fn too_many_separate_pieces_are_cut_and_said_so() {
        let mut lod = PathLod::new(100);
        for i in 0..1000u32 {
            let x = i as f64;
            lod.push(true, 2 * i, [x, 0.0, 5.0], &[[x, 0.0, 0.0]]);
            lod.push(false, 2 * i + 1, [x, 0.0, 0.0], &[[x + 1.0, 0.0, 5.0]]);
        }
        let out = lod.finish();
        assert!(out.points <= 100, "{}", out.points);
        assert!(out.truncated_at.is_some());
        // The extents cover the whole program, also past the cut.
        assert_eq!(out.extents.unwrap().1[0], 1000.0);
    }
}
