//! Rational B-splines (NURBS) in 3-D: evaluation, tessellation, length.
//!
//! ## The curve
//!
//! For control points P_0…P_{n−1} with weights w_i > 0, degree p and a non-decreasing knot vector
//! t_0…t_{n+p}, the curve on u ∈ [t_p, t_n] is
//!
//! ```text
//!   C(u) = Σ N_{i,p}(u) w_i P_i / Σ N_{i,p}(u) w_i
//! ```
//!
//! **Evaluation** is de Boor's algorithm in homogeneous coordinates (w·x, w·y, w·z, w): find the span
//! k with t_k ≤ u < t_{k+1} (k clamped to p…n−1 so that u = t_n uses the last span), take the p+1
//! points P_{k−p}…P_k and blend them p times with α = (u − t_j) / (t_{j+p+1−r} − t_j); divide by the
//! weight at the end. A zero denominator (repeated knots) blends with α = 0. Cost O(p²) per point,
//! no allocation (degree ≤ [`MAX_DEGREE`]).
//!
//! **Tessellation** cuts the curve into its rational Bézier pieces (one per non-empty knot span,
//! [`crate::bezier_pieces`]) and halves each piece by de Casteljau's algorithm in homogeneous
//! coordinates until every control point of the sub-piece lies within the chord tolerance of the
//! chord between its end points (depth ≤ 24, so it always ends). With positive weights a rational
//! Bézier piece lies in the convex hull of its control points, and the distance to a segment is a
//! convex function, so the curve's deviation from the chord is at most the control points' largest:
//! the bound is rigorous, not sampled (a sampled test missed a 9 % overshoot on a sharply turning
//! cubic, found by the property test), and the control polygon converges to the curve
//! quadratically, so it costs few extra chords.
//!
//! Invalid data (wrong lengths, decreasing knots, a non-positive or non-finite weight, degree 0 or
//! above [`MAX_DEGREE`]) is reported by [`Nurbs::validate`]; the other methods never panic on it and
//! fall back to the control polygon.
use crate::vec3::{add, norm, scale, sub, Vec3};

/// Highest degree supported (LinuxCNC's G5.2 allows order L up to its point count; controls use 2–5).
pub const MAX_DEGREE: usize = 15;

/// What is wrong with a NURBS description.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NurbsError {
    /// Degree 0 or above [`MAX_DEGREE`].
    Degree,
    /// Fewer control points than degree + 1.
    TooFewPoints,
    /// Weights and points differ in number.
    WeightCount,
    /// A weight is not a positive finite number.
    Weight,
    /// `knots.len() != points + degree + 1`.
    KnotCount,
    /// Knots decrease, are not finite, or the domain is empty.
    Knots,
}

/// A borrowed NURBS curve (see the module doc).
#[derive(Debug, Clone, Copy)]
pub struct Nurbs<'a> {
    degree: usize,
    points: &'a [Vec3],
    weights: &'a [f64],
    knots: &'a [f64],
}

/// The clamped knot vector of a single Bézier piece of `degree`: p+1 zeros then p+1 ones.
pub fn bezier_knots(degree: usize) -> Vec<f64> {
    let mut k = vec![0.0; degree + 1];
    k.extend(std::iter::repeat_n(1.0, degree + 1));
    k
}

impl<'a> Nurbs<'a> {
    /// Wraps the data; nothing is checked here (see [`Nurbs::validate`]).
    pub fn new(degree: u8, points: &'a [Vec3], weights: &'a [f64], knots: &'a [f64]) -> Self {
        Nurbs {
            degree: degree as usize,
            points,
            weights,
            knots,
        }
    }

    /// Checks the description.
    pub fn validate(&self) -> Result<(), NurbsError> {
        let p = self.degree;
        if p == 0 || p > MAX_DEGREE {
            return Err(NurbsError::Degree);
        }
        if self.points.len() < p + 1 {
            return Err(NurbsError::TooFewPoints);
        }
        if self.weights.len() != self.points.len() {
            return Err(NurbsError::WeightCount);
        }
        if self.weights.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
            return Err(NurbsError::Weight);
        }
        if self.knots.len() != self.points.len() + p + 1 {
            return Err(NurbsError::KnotCount);
        }
        if self.knots.iter().any(|k| !k.is_finite())
            || self.knots.windows(2).any(|w| w[1] < w[0])
            || self.knots[self.points.len()] <= self.knots[p]
        {
            return Err(NurbsError::Knots);
        }
        Ok(())
    }

    fn valid(&self) -> bool {
        self.validate().is_ok()
    }

    /// The parameter domain [t_p, t_n].
    pub fn domain(&self) -> (f64, f64) {
        if !self.valid() {
            return (0.0, 1.0);
        }
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// The point at parameter `u` (clamped to the domain). Invalid data: the point at fraction `u`
    /// of the control polygon's index range.
    pub fn point_at(&self, u: f64) -> Vec3 {
        if !self.valid() {
            return self.polygon_point(u);
        }
        let p = self.degree;
        let n = self.points.len();
        let (lo, hi) = self.domain();
        let u = if u.is_nan() { lo } else { u.clamp(lo, hi) };
        // Span k: t_k <= u < t_{k+1}, k in p..=n-1.
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= u {
            k += 1;
        }
        let mut d = [[0.0f64; 4]; MAX_DEGREE + 1];
        for (j, dj) in d.iter_mut().enumerate().take(p + 1) {
            let i = k - p + j;
            let w = self.weights[i];
            let q = self.points[i];
            *dj = [q[0] * w, q[1] * w, q[2] * w, w];
        }
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = k - p + j;
                let den = self.knots[i + p + 1 - r] - self.knots[i];
                let alpha = if den > 0.0 {
                    (u - self.knots[i]) / den
                } else {
                    0.0
                };
                let prev = d[j - 1];
                for (c, value) in d[j].iter_mut().enumerate() {
                    *value = (1.0 - alpha) * prev[c] + alpha * *value;
                }
            }
        }
        let h = d[p];
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    fn polygon_point(&self, u: f64) -> Vec3 {
        match self.points.len() {
            0 => [0.0; 3],
            1 => self.points[0],
            n => {
                let f = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) } * (n - 1) as f64;
                let i = (f.floor() as usize).min(n - 2);
                let t = f - i as f64;
                add(
                    self.points[i],
                    scale(sub(self.points[i + 1], self.points[i]), t),
                )
            }
        }
    }

    /// Appends points along the curve, first and last included, so that no chord deviates from the
    /// curve by more than `chord_tolerance` (mm; floored at 1e-9). Invalid data: the control polygon.
    pub fn tessellate(&self, chord_tolerance: f64, out: &mut Vec<Vec3>) {
        if !self.valid() {
            out.extend_from_slice(self.points);
            return;
        }
        let tol = if chord_tolerance.is_finite() {
            chord_tolerance.max(1e-9)
        } else {
            1e-3
        };
        out.push(self.point_at(self.knots[self.degree]));
        for piece in crate::bezier_pieces(self.degree as u8, self.points, self.weights, self.knots)
        {
            let mut h = [[0.0; 4]; MAX_DEGREE + 1];
            let n = piece.points.len().min(MAX_DEGREE + 1);
            for (hi, (q, w)) in h.iter_mut().zip(piece.points.iter().zip(&piece.weights)) {
                *hi = [w * q[0], w * q[1], w * q[2], *w];
            }
            subdivide_bezier(&h[..n], tol, 0, out);
        }
    }

    /// Arc length, from a tessellation at a chord tolerance of 0.1 nm: a chord of sagitta s on a
    /// curve of radius R is shorter than the curve by ≈ 8s²/(3c) with c = √(8Rs), so the relative
    /// error is about 1e-9 for R ≈ 30 mm.
    pub fn length(&self) -> f64 {
        let mut pts = Vec::new();
        self.tessellate(1e-7, &mut pts);
        pts.windows(2).map(|w| norm(sub(w[1], w[0]))).sum()
    }

    /// Axis-aligned box around the curve (from a 1 µm tessellation), (min, max).
    pub fn bounding_box(&self) -> (Vec3, Vec3) {
        let mut pts = Vec::new();
        self.tessellate(1e-3, &mut pts);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for q in &pts {
            for i in 0..3 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
        (lo, hi)
    }
}

/// Distance from `q` to the segment a–b.
pub fn distance_to_segment(q: Vec3, a: Vec3, b: Vec3) -> f64 {
    let ab = sub(b, a);
    let l2 = crate::vec3::dot(ab, ab);
    let t = if l2 > 0.0 {
        (crate::vec3::dot(sub(q, a), ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(q, add(a, scale(ab, t))))
}

/// A homogeneous point (w·x, w·y, w·z, w).
type Homogeneous = [f64; 4];

fn project(h: Homogeneous) -> Vec3 {
    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
}

/// Halves the rational Bézier piece `h` (homogeneous control points, positive weights) until its
/// control polygon lies within `tol` of its chord (module doc), pushing the end of every final
/// sub-piece (the start is already in `out`).
fn subdivide_bezier(h: &[Homogeneous], tol: f64, depth: u32, out: &mut Vec<Vec3>) {
    let n = h.len();
    if n < 2 {
        return;
    }
    let (a, b) = (project(h[0]), project(h[n - 1]));
    let flat = h[1..n - 1]
        .iter()
        .all(|q| distance_to_segment(project(*q), a, b) <= tol);
    if flat || depth >= 24 {
        out.push(b);
        return;
    }
    // de Casteljau at t = 1/2: the first and last points of every level are the two halves.
    let mut work = [[0.0; 4]; MAX_DEGREE + 1];
    work[..n].copy_from_slice(h);
    let mut left = [[0.0; 4]; MAX_DEGREE + 1];
    let mut right = [[0.0; 4]; MAX_DEGREE + 1];
    for r in 0..n {
        left[r] = work[0];
        right[n - 1 - r] = work[n - 1 - r];
        for i in 0..n - 1 - r {
            let next = work[i + 1];
            for (c, value) in work[i].iter_mut().enumerate() {
                *value = 0.5 * (*value + next[c]);
            }
        }
    }
    subdivide_bezier(&left[..n], tol, depth + 1, out);
    subdivide_bezier(&right[..n], tol, depth + 1, out);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3, tol: f64) -> bool {
        norm(sub(a, b)) <= tol
    }

    #[test]
    fn cubic_bezier_of_the_g5_example() {
        // rs274ngc corpus g05-cubic-spline-example-1: P0 (0,0) P1 (0,3) P2 (1,-2) P3 (1,1).
        let pts = [
            [0.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [1.0, -2.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        let w = [1.0; 4];
        let k = bezier_knots(3);
        let c = Nurbs::new(3, &pts, &w, &k);
        assert!(c.validate().is_ok());
        assert!(close(c.point_at(0.5), [0.5, 0.5, 0.0], 1e-12));
        assert!(close(c.point_at(0.25), [0.15625, 1.0, 0.0], 1e-12));
        assert!(close(c.point_at(1.0), [1.0, 1.0, 0.0], 1e-12));
    }

    #[test]
    fn rational_quadratic_of_the_g5_2_example() {
        // rs274ngc corpus g05.2-nurbs-example-1: knots [0,0,0,1,2,3,3,3].
        let pts = [
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        let w = [1.0, 1.0, 1.0, 1.0, 2.0];
        let k = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
        let c = Nurbs::new(2, &pts, &w, &k);
        for (u, want) in [
            (0.0, [0.0, 0.0]),
            (0.5, [0.25, 0.875]),
            (1.0, [1.0, 1.5]),
            (1.5, [1.75, 1.625]),
            (2.0, [2.0, 1.0]),
            (2.5, [1.2, 0.2]),
            (3.0, [0.0, 0.0]),
        ] {
            let p = c.point_at(u);
            assert!(close(p, [want[0], want[1], 0.0], 1e-12), "u={u}: {p:?}");
        }
    }

    #[test]
    fn rational_quadratic_circle_is_round_and_tessellates_within_tolerance() {
        // Quarter circle of radius 30: (30,0) (30,30) w=√½ (0,30).
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let pts = [[30.0, 0.0, 0.0], [30.0, 30.0, 0.0], [0.0, 30.0, 0.0]];
        let w = [1.0, h, 1.0];
        let k = bezier_knots(2);
        let c = Nurbs::new(2, &pts, &w, &k);
        for i in 0..=100 {
            let p = c.point_at(i as f64 / 100.0);
            assert!((norm(p) - 30.0).abs() < 1e-12);
        }
        let mut t = Vec::new();
        c.tessellate(1e-3, &mut t);
        for s in t.windows(2) {
            let mid = scale(add(s[0], s[1]), 0.5);
            // The sagitta of every chord is within the tolerance.
            assert!(30.0 - norm(mid) <= 1e-3 + 1e-12);
        }
        assert!((c.length() - 15.0 * std::f64::consts::PI).abs() < 1e-6);
    }

    #[test]
    fn invalid_data_never_panics() {
        let pts = [[0.0; 3], [1.0, 0.0, 0.0]];
        for (deg, w, k) in [
            (0u8, vec![1.0, 1.0], vec![0.0, 1.0]),
            (3, vec![1.0, 1.0], vec![0.0; 6]),
            (1, vec![1.0], vec![0.0, 0.0, 1.0, 1.0]),
            (1, vec![1.0, -1.0], vec![0.0, 0.0, 1.0, 1.0]),
            (1, vec![1.0, 1.0], vec![0.0, 0.0, 0.0, 0.0]),
            (1, vec![1.0, f64::NAN], vec![0.0, 1.0, 0.5, 1.0]),
        ] {
            let c = Nurbs::new(deg, &pts, &w, &k);
            assert!(c.validate().is_err());
            let _ = c.point_at(0.5);
            let mut out = Vec::new();
            c.tessellate(1e-3, &mut out);
            assert_eq!(out.len(), 2);
        }
    }
}
