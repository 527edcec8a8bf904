//! Dexels: material along parallel lines, as sorted disjoint intervals.
//!
//! A [`Dexel`] is the material on one line: empty, one interval (the common case, stored inline)
//! or several (an overhang, a slot under a bridge). A [`DexelGrid`] is a rectangular grid of
//! them, line (i, j) through the centre of its cell. Intervals are `f32` (7 significant digits:
//! 0.01 µm at 100 mm), 8 bytes each, so a grid costs 16 bytes per line plus its extra intervals:
//! memory is bounded by the stock's size over the resolution, never by the program.
//!
//! *Invariants:* intervals sorted, disjoint, each `lo < hi`; an operation that would leave a
//! sliver shorter than [`SLIVER`] drops it (a cut that grazes the surface leaves no film).

use serde::Serialize;

/// Material thinner than this along a line is gone, mm.
pub const SLIVER: f32 = 1e-5;

/// One interval of material, `lo < hi`, mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Span {
    /// Lower end.
    pub lo: f32,
    /// Upper end.
    pub hi: f32,
}

/// The material on one line.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Dexel {
    /// Nothing.
    #[default]
    Empty,
    /// One interval.
    One(Span),
    /// Two or more, sorted and disjoint.
    Many(Box<Vec<Span>>),
}

impl Dexel {
    /// The intervals, lowest first.
    #[inline]
    pub fn spans(&self) -> &[Span] {
        match self {
            Dexel::Empty => &[],
            Dexel::One(s) => std::slice::from_ref(s),
            Dexel::Many(v) => v,
        }
    }

    /// The highest material point, if any.
    #[inline]
    pub fn top(&self) -> Option<f32> {
        self.spans().last().map(|s| s.hi)
    }

    /// Total length of material, mm.
    pub fn length(&self) -> f64 {
        self.spans().iter().map(|s| (s.hi - s.lo) as f64).sum()
    }

    /// Length of material inside `[lo, hi]`, mm.
    #[inline]
    pub fn overlap(&self, lo: f64, hi: f64) -> f64 {
        let mut sum = 0.0;
        for s in self.spans() {
            let a = (s.lo as f64).max(lo);
            let b = (s.hi as f64).min(hi);
            if b > a {
                sum += b - a;
            }
        }
        sum
    }

    fn from_vec(mut v: Vec<Span>) -> Dexel {
        v.retain(|s| s.hi - s.lo >= SLIVER);
        match v.len() {
            0 => Dexel::Empty,
            1 => Dexel::One(v[0]),
            _ => Dexel::Many(Box::new(v)),
        }
    }

    /// A dexel from unsorted, possibly overlapping intervals (their union).
    pub fn union_of(mut v: Vec<Span>) -> Dexel {
        v.retain(|s| s.hi > s.lo);
        v.sort_by(|a, b| a.lo.total_cmp(&b.lo));
        let mut out: Vec<Span> = Vec::with_capacity(v.len());
        for s in v {
            match out.last_mut() {
                Some(last) if s.lo <= last.hi => last.hi = last.hi.max(s.hi),
                _ => out.push(s),
            }
        }
        Dexel::from_vec(out)
    }

    /// Removes `[lo, hi]`; returns the length removed, mm, and the lowest point removed.
    #[inline]
    pub fn cut(&mut self, lo: f64, hi: f64) -> (f64, f64) {
        let (lo32, hi32) = (lo as f32, hi as f32);
        match self {
            Dexel::Empty => (0.0, f64::INFINITY),
            Dexel::One(s) => {
                if hi32 <= s.lo || lo32 >= s.hi {
                    return (0.0, f64::INFINITY);
                }
                let a = s.lo.max(lo32);
                let b = s.hi.min(hi32);
                let removed = (b - a) as f64;
                let below = Span { lo: s.lo, hi: lo32 };
                let above = Span { lo: hi32, hi: s.hi };
                let keep_below = below.hi - below.lo >= SLIVER;
                let keep_above = above.hi - above.lo >= SLIVER;
                *self = match (keep_below, keep_above) {
                    (false, false) => Dexel::Empty,
                    (true, false) => Dexel::One(below),
                    (false, true) => Dexel::One(above),
                    (true, true) => Dexel::Many(Box::new(vec![below, above])),
                };
                (removed, a as f64)
            }
            Dexel::Many(v) => {
                let mut removed = 0.0;
                let mut lowest = f64::INFINITY;
                let mut out = Vec::with_capacity(v.len() + 1);
                for s in v.iter() {
                    if hi32 <= s.lo || lo32 >= s.hi {
                        out.push(*s);
                        continue;
                    }
                    let a = s.lo.max(lo32);
                    let b = s.hi.min(hi32);
                    removed += (b - a) as f64;
                    lowest = lowest.min(a as f64);
                    out.push(Span { lo: s.lo, hi: lo32 });
                    out.push(Span { lo: hi32, hi: s.hi });
                }
                if removed > 0.0 {
                    *self = Dexel::from_vec(out);
                }
                (removed, lowest)
            }
        }
    }
}

/// A rectangular grid of parallel dexels (module doc): line (i, j) at
/// `origin + ((i + ½)·cell[0], (j + ½)·cell[1])`.
#[derive(Debug, Clone, PartialEq)]
pub struct DexelGrid {
    /// Corner of cell (0, 0), mm.
    pub origin: [f64; 2],
    /// Cell size, mm.
    pub cell: [f64; 2],
    /// Cells in each direction.
    pub n: [usize; 2],
    /// Lines, row-major (i fastest).
    pub lines: Vec<Dexel>,
}

impl DexelGrid {
    /// An empty grid covering `[lo, hi]` with cells of at most `resolution`: the cell size is
    /// adjusted so that a whole number of cells spans the range exactly.
    pub fn new(lo: [f64; 2], hi: [f64; 2], resolution: f64) -> DexelGrid {
        let count = |k: usize| (((hi[k] - lo[k]) / resolution).ceil() as usize).max(1);
        let n = [count(0), count(1)];
        DexelGrid {
            origin: lo,
            cell: [(hi[0] - lo[0]) / n[0] as f64, (hi[1] - lo[1]) / n[1] as f64],
            n,
            lines: vec![Dexel::Empty; n[0] * n[1]],
        }
    }

    /// Centre of line (i, j).
    #[inline]
    pub fn centre(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.origin[0] + (i as f64 + 0.5) * self.cell[0],
            self.origin[1] + (j as f64 + 0.5) * self.cell[1],
        ]
    }

    /// The range of cell indices whose centres lie in `[lo, hi]` on axis `k` (may be empty).
    #[inline]
    pub fn index_range(&self, k: usize, lo: f64, hi: f64) -> std::ops::Range<usize> {
        if lo.is_nan() || hi.is_nan() {
            return 0..0;
        }
        let a = ((lo - self.origin[k]) / self.cell[k] - 0.5).ceil().max(0.0);
        let b = ((hi - self.origin[k]) / self.cell[k] - 0.5).floor() + 1.0;
        let b = b.min(self.n[k] as f64);
        if !(a.is_finite() && b.is_finite()) || b <= a {
            return 0..0;
        }
        a as usize..b as usize
    }

    /// Area of one cell, mm².
    #[inline]
    pub fn cell_area(&self) -> f64 {
        self.cell[0] * self.cell[1]
    }

    /// Material volume, mm³.
    pub fn volume(&self) -> f64 {
        self.lines.iter().map(Dexel::length).sum::<f64>() * self.cell_area()
    }

    /// The line nearest to `(x, y)`, if inside the grid.
    pub fn nearest(&self, x: f64, y: f64) -> Option<usize> {
        let i = ((x - self.origin[0]) / self.cell[0]).floor();
        let j = ((y - self.origin[1]) / self.cell[1]).floor();
        (i >= 0.0 && j >= 0.0 && (i as usize) < self.n[0] && (j as usize) < self.n[1])
            .then(|| j as usize * self.n[0] + i as usize)
    }

    /// Every `stride`-th line of a grid (the one at the centre of each block of stride² lines).
    pub fn coarse(&self, stride: usize) -> DexelGrid {
        let s = stride.max(1);
        if s == 1 {
            return self.clone();
        }
        let n = [self.n[0].div_ceil(s), self.n[1].div_ceil(s)];
        let mut out = DexelGrid {
            origin: self.origin,
            cell: [self.cell[0] * s as f64, self.cell[1] * s as f64],
            n,
            lines: Vec::with_capacity(n[0] * n[1]),
        };
        for j in 0..n[1] {
            for i in 0..n[0] {
                let (si, sj) = (
                    (i * s + s / 2).min(self.n[0] - 1),
                    (j * s + s / 2).min(self.n[1] - 1),
                );
                out.lines.push(self.lines[sj * self.n[0] + si].clone());
            }
        }
        out
    }

    /// Bytes the grid holds (lines and their extra intervals).
    pub fn memory_bytes(&self) -> usize {
        self.lines.len() * std::mem::size_of::<Dexel>()
            + self
                .lines
                .iter()
                .map(|d| match d {
                    Dexel::Many(v) => v.capacity() * std::mem::size_of::<Span>(),
                    _ => 0,
                })
                .sum::<usize>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn span(lo: f32, hi: f32) -> Span {
        Span { lo, hi }
    }

    #[test]
    fn cutting_the_middle_splits_and_the_top_shortens() {
        let mut d = Dexel::One(span(-30.0, 0.0));
        assert_eq!(d.cut(-10.0, -5.0), (5.0, -10.0));
        assert_eq!(d.spans(), &[span(-30.0, -10.0), span(-5.0, 0.0)]);
        assert_eq!(d.cut(-7.0, 100.0).0, 5.0);
        assert_eq!(d, Dexel::One(span(-30.0, -10.0)));
        assert_eq!(d.cut(-100.0, 100.0).0, 20.0);
        assert_eq!(d, Dexel::Empty);
        assert_eq!(d.cut(0.0, 1.0), (0.0, f64::INFINITY));
    }

    #[test]
    fn index_ranges_cover_the_centres_inside() {
        let g = DexelGrid::new([0.0, 0.0], [10.0, 5.0], 0.1);
        assert_eq!(g.n, [100, 50]);
        assert_eq!(g.index_range(0, 0.0, 0.05), 0..1);
        assert_eq!(g.index_range(0, 0.06, 0.14), 0..0);
        assert_eq!(g.index_range(0, -5.0, 100.0), 0..100);
        assert_eq!(g.index_range(1, 4.95, 9.0), 49..50);
        assert_eq!(g.index_range(1, f64::NAN, 9.0), 0..0);
    }

    proptest! {
        /// A cut removes exactly the overlap, and what is left is the set difference.
        #[test]
        fn a_cut_removes_the_overlap(
            spans in proptest::collection::vec((-50.0..50.0f32, 0.01..20.0f32), 0..5),
            lo in -60.0..60.0f64, len in 0.0..40.0f64,
        ) {
            let mut d = Dexel::union_of(spans.iter().map(|&(a, l)| span(a, a + l)).collect());
            let before = d.length();
            let inside = d.overlap(lo, lo + len);
            let (removed, _) = d.cut(lo, lo + len);
            prop_assert!((removed - inside).abs() < 1e-3, "{removed} {inside}");
            prop_assert!(d.overlap(lo + 1e-4, lo + len - 1e-4) < 1e-3);
            prop_assert!((d.length() - (before - removed)).abs() < 1e-3);
            let s = d.spans();
            prop_assert!(s.windows(2).all(|w| w[0].hi < w[1].lo) && s.iter().all(|x| x.lo < x.hi));
        }
    }
}
