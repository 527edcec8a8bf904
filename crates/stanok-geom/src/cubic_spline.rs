//! Parametric C² cubic spline through 3-D points (AxiOMA CSPLINE, spec axioma-2 §2.4.3).
//!
//! ## Algorithm
//!
//! Chord-length parameter (h_i = |P_{i+1} − P_i|, m_i = (P_{i+1} − P_i)/h_i) and Hermite segments
//! (the Bézier form is [`crate::hermite_bezier`]). The tangents T solve the C² conditions:
//!
//! ```text
//!   interior knot i:  T_{i−1}/h_{i−1} + 2T_i(1/h_{i−1} + 1/h_i) + T_{i+1}/h_i = 3(m_{i−1}/h_{i−1} + m_i/h_i)
//!   natural start:    2T_0 + T_1 = 3m_0          natural end: T_{n−1} + 2T_n = 3m_{n−1}
//!   clamped start:    T_0 given
//! ```
//!
//! [`solve_tangents`] solves that tridiagonal system (Thomas algorithm, per coordinate; the
//! matrix is strictly diagonally dominant for positive h, so no pivoting is needed) on a window of
//! points with the start natural or clamped and the far end natural. The whole natural spline is
//! one call with `start = None`; the control's finite zone of influence W (default 8) is the
//! sliding solve of the spec:
//!
//! ```text
//!   T_0 := solve on P_0 … P_min(W, n), natural start
//!   T_i := solve on P_{i−1} … P_min(i−1+W, n) with T_{i−1} clamped   (i = 1 … n)
//! ```
//!
//! The influence of a far point decays by ≈ 0.268 per knot, so the windowed curve differs from the
//! global one by a small C² defect only. Points with h = 0 must be removed by the caller (h is
//! floored at 1e-12 so nothing divides by zero).

use crate::vec3::{add, norm, scale, sub, Vec3};

/// Tangents at every point of `points`: natural start if `start` is None, else `start` at
/// `points[0]`; natural far end. Fewer than two points: zero tangents.
pub fn solve_tangents(points: &[Vec3], start: Option<Vec3>) -> Vec<Vec3> {
    let n1 = points.len();
    if n1 < 2 {
        return vec![[0.0; 3]; n1];
    }
    let n = n1 - 1;
    let h: Vec<f64> = (0..n)
        .map(|i| norm(sub(points[i + 1], points[i])).max(1e-12))
        .collect();
    let m: Vec<Vec3> = (0..n)
        .map(|i| scale(sub(points[i + 1], points[i]), 1.0 / h[i]))
        .collect();
    // Rows a_i T_{i−1} + b_i T_i + c_i T_{i+1} = d_i, i = 0 … n.
    let mut a = vec![0.0; n1];
    let mut b = vec![0.0; n1];
    let mut c = vec![0.0; n1];
    let mut d = vec![[0.0; 3]; n1];
    match start {
        Some(t) => {
            b[0] = 1.0;
            d[0] = t;
        }
        None => {
            b[0] = 2.0;
            c[0] = 1.0;
            d[0] = scale(m[0], 3.0);
        }
    }
    for i in 1..n {
        a[i] = 1.0 / h[i - 1];
        b[i] = 2.0 * (1.0 / h[i - 1] + 1.0 / h[i]);
        c[i] = 1.0 / h[i];
        d[i] = scale(
            add(scale(m[i - 1], 1.0 / h[i - 1]), scale(m[i], 1.0 / h[i])),
            3.0,
        );
    }
    a[n] = 1.0;
    b[n] = 2.0;
    d[n] = scale(m[n - 1], 3.0);
    // Thomas algorithm: forward sweep, back substitution.
    let mut cp = vec![0.0; n1];
    let mut dp = vec![[0.0; 3]; n1];
    cp[0] = c[0] / b[0];
    dp[0] = scale(d[0], 1.0 / b[0]);
    for i in 1..n1 {
        let den = b[i] - a[i] * cp[i - 1];
        let den = if den.abs() < 1e-300 { 1e-300 } else { den };
        cp[i] = c[i] / den;
        dp[i] = scale(sub(d[i], scale(dp[i - 1], a[i])), 1.0 / den);
    }
    let mut t = vec![[0.0; 3]; n1];
    t[n] = dp[n];
    for i in (0..n).rev() {
        t[i] = sub(dp[i], scale(t[i + 1], cp[i]));
    }
    t
}

/// The tangents of the windowed CSPLINE over a whole point list (zone of influence `window` ≥ 1
/// points after a knot), as the control computes them one knot at a time.
pub fn windowed_tangents(points: &[Vec3], window: usize) -> Vec<Vec3> {
    let w = window.max(1);
    let n1 = points.len();
    if n1 < 2 {
        return vec![[0.0; 3]; n1];
    }
    let n = n1 - 1;
    let mut t = Vec::with_capacity(n1);
    t.push(solve_tangents(&points[..=w.min(n)], None)[0]);
    for i in 1..=n {
        let hi = (i - 1 + w).min(n);
        let sol = solve_tangents(&points[i - 1..=hi], Some(t[i - 1]));
        t.push(sol[1]);
    }
    t
}
