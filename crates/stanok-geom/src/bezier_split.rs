//! Splitting a clamped NURBS into its rational Bézier pieces, one per non-empty knot span.
//!
//! ## Algorithm (Boehm knot insertion in homogeneous coordinates)
//!
//! Every inner knot value u of multiplicity s < p is inserted p − s times. One insertion of u in
//! span k (t_k ≤ u < t_{k+1}) replaces the control points P^w_{k−p+1} … P^w_k by
//!
//! ```text
//!   Q_i = α_i P^w_i + (1 − α_i) P^w_{i−1},   α_i = (u − t_i)/(t_{i+p} − t_i)
//! ```
//!
//! (points before keep, points after shift by one) and adds u to the knot vector; the curve does
//! not change. When every inner knot has multiplicity p, span j is the Bézier curve of control
//! points j·p … j·p + p. Work: at most p insertions per inner knot, each O(n).
//!
//! Input must be valid (see [`crate::Nurbs::validate`]); otherwise the result is empty. Weights of
//! the pieces stay positive (convex combinations of positive weights).

use crate::nurbs::Nurbs;
use crate::vec3::Vec3;

/// One rational Bézier piece: degree + 1 control points and weights, on the knot interval
/// `[from, to]` of the original curve.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPiece {
    /// Control points.
    pub points: Vec<Vec3>,
    /// Weights.
    pub weights: Vec<f64>,
    /// The interval of the original parameter.
    pub from: f64,
    /// See `from`.
    pub to: f64,
}

/// The Bézier pieces of a clamped NURBS, in parameter order (empty spans produce none).
pub fn bezier_pieces(
    degree: u8,
    points: &[Vec3],
    weights: &[f64],
    knots: &[f64],
) -> Vec<BezierPiece> {
    if Nurbs::new(degree, points, weights, knots)
        .validate()
        .is_err()
    {
        return Vec::new();
    }
    let p = degree as usize;
    let mut t: Vec<f64> = knots.to_vec();
    let mut q: Vec<[f64; 4]> = points
        .iter()
        .zip(weights)
        .map(|(x, &w)| [x[0] * w, x[1] * w, x[2] * w, w])
        .collect();
    let (lo, hi) = (t[p], t[t.len() - 1 - p]);
    // Distinct inner knot values with their multiplicities.
    let mut inner: Vec<(f64, usize)> = Vec::new();
    for &u in &t[p + 1..t.len() - p - 1] {
        match inner.last_mut() {
            Some((v, m)) if *v == u => *m += 1,
            _ => inner.push((u, 1)),
        }
    }
    for (u, mult) in inner {
        if u <= lo || u >= hi {
            continue;
        }
        for _ in mult..p {
            // Span k with t_k ≤ u < t_{k+1}.
            let Some(k) = (p..t.len() - p - 1).rev().find(|&k| t[k] <= u) else {
                break;
            };
            let mut next = Vec::with_capacity(q.len() + 1);
            next.extend_from_slice(&q[..=k - p]);
            for i in k - p + 1..=k {
                let den = t[i + p] - t[i];
                let a = if den > 0.0 { (u - t[i]) / den } else { 0.0 };
                let (pi, pm) = (q[i], q[i - 1]);
                next.push(std::array::from_fn(|c| a * pi[c] + (1.0 - a) * pm[c]));
            }
            next.extend_from_slice(&q[k..]);
            q = next;
            t.insert(k + 1, u);
        }
    }
    // Now every inner knot has multiplicity p: walk the non-empty spans.
    let mut out = Vec::new();
    let mut first = 0usize;
    let mut k = p;
    while k + 1 < t.len() - p {
        if t[k + 1] > t[k] {
            let piece = &q[first..(first + p + 1).min(q.len())];
            if piece.len() == p + 1 {
                out.push(BezierPiece {
                    points: piece
                        .iter()
                        .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
                        .collect(),
                    weights: piece.iter().map(|h| h[3]).collect(),
                    from: t[k],
                    to: t[k + 1],
                });
            }
            first += p;
        }
        k += 1;
    }
    out
}
