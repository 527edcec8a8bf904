//! Parametric Akima spline through 3-D points (AxiOMA ASPLINE, spec axioma-2 §2.4.2).
//!
//! ## Algorithm (chord-length parameter, the spec's reference)
//!
//! ```text
//!   h_i = |P_{i+1} − P_i|,  m_i = (P_{i+1} − P_i)/h_i                      (i = 0 … n−1)
//!   beyond the ends:  m_{−1} = 2m_0 − m_1,  m_{−2} = 2m_{−1} − m_0,
//!                     m_n = 2m_{n−1} − m_{n−2},  m_{n+1} = 2m_n − m_{n−1}
//!   interior tangent: wa = |m_{i+1} − m_i|, wb = |m_{i−1} − m_{i−2}|
//!                     T_i = (wa·m_{i−1} + wb·m_i)/(wa + wb)   (wa + wb ≈ 0: the mean of the two)
//!   natural ends:     T_0 = (3m_0 − T_1)/2,  T_n = (3m_{n−1} − T_{n−1})/2   (n = 1: T = m_0)
//!   segment i:        Hermite on s ∈ [0, h_i]  =  cubic Bézier
//!                     P_i,  P_i + T_i·h_i/3,  P_{i+1} − T_{i+1}·h_i/3,  P_{i+1}
//! ```
//!
//! Locality: T_i depends on P_{i−2} … P_{i+2} only (plus the end rules), so a curve can be built
//! in a sliding window. [`Window`] describes such a window: `starts`/`ends` say whether its first /
//! last point is the spline's real start / end. Slopes the window does not hold and that are not
//! beyond a real end are taken from the nearest held slope (a caller that keeps two points on each
//! side of the tangents it needs never hits that case).
//!
//! Invariants: the curve passes through every point (Bézier end points are the points
//! themselves); C¹ at every inner point; zero curvature at both ends. Consecutive equal points
//! (h = 0) must be removed by the caller: their slope is taken as zero.

use crate::vec3::{add, norm, scale, sub, Vec3};

/// Consecutive points of a spline, possibly a window of a longer one.
#[derive(Debug, Clone, Copy)]
pub struct Window<'a> {
    /// The points.
    pub points: &'a [Vec3],
    /// `points[0]` is the spline's first point.
    pub starts: bool,
    /// The last point is the spline's last point.
    pub ends: bool,
}

impl Window<'_> {
    /// A whole spline.
    pub fn whole(points: &[Vec3]) -> Window<'_> {
        Window {
            points,
            starts: true,
            ends: true,
        }
    }

    fn held_slopes(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// Slope m_k of the window (k may be outside: end extension or the nearest held slope).
    fn slope(&self, k: isize) -> Vec3 {
        let n = self.held_slopes() as isize;
        if n == 0 {
            return [0.0; 3];
        }
        if (0..n).contains(&k) {
            let (a, b) = (self.points[k as usize], self.points[k as usize + 1]);
            let h = norm(sub(b, a));
            return if h > 0.0 {
                scale(sub(b, a), 1.0 / h)
            } else {
                [0.0; 3]
            };
        }
        if n == 1 {
            return self.slope(0);
        }
        // Bounded: |k| ≤ n + 2 for every call below, each step moves one towards the held range.
        if k < 0 {
            if !self.starts || k < -2 {
                return self.slope(0);
            }
            // m_{k} = 2 m_{k+1} − m_{k+2}
            return sub(scale(self.slope(k + 1), 2.0), self.slope(k + 2));
        }
        if !self.ends || k > n + 1 {
            return self.slope(n - 1);
        }
        sub(scale(self.slope(k - 1), 2.0), self.slope(k - 2))
    }

    fn interior_tangent(&self, i: isize) -> Vec3 {
        let (m2, m1, m0, p1) = (
            self.slope(i - 2),
            self.slope(i - 1),
            self.slope(i),
            self.slope(i + 1),
        );
        let wa = norm(sub(p1, m0));
        let wb = norm(sub(m1, m2));
        if wa + wb <= 1e-12 {
            scale(add(m1, m0), 0.5)
        } else {
            scale(add(scale(m1, wa), scale(m0, wb)), 1.0 / (wa + wb))
        }
    }

    /// Tangent T_i at point i of the window.
    pub fn tangent(&self, i: usize) -> Vec3 {
        let n = self.held_slopes();
        if n == 0 {
            return [0.0; 3];
        }
        if n == 1 && self.starts && self.ends {
            return self.slope(0);
        }
        let i = i.min(n) as isize;
        if self.starts && i == 0 {
            let t1 = self.interior_tangent(1);
            return scale(sub(scale(self.slope(0), 3.0), t1), 0.5);
        }
        if self.ends && i == n as isize {
            let t = self.interior_tangent(i - 1);
            return scale(sub(scale(self.slope(i - 1), 3.0), t), 0.5);
        }
        self.interior_tangent(i)
    }
}

/// The cubic Bézier control points of the Hermite segment from `a` (tangent `ta`) to `b`
/// (tangent `tb`) with the chord-length parameter (unit-speed tangents).
pub fn hermite_bezier(a: Vec3, ta: Vec3, b: Vec3, tb: Vec3) -> [Vec3; 4] {
    let h = norm(sub(b, a));
    [a, add(a, scale(ta, h / 3.0)), sub(b, scale(tb, h / 3.0)), b]
}

/// All Bézier segments of the Akima spline through `points` (a whole spline).
pub fn akima_beziers(points: &[Vec3]) -> Vec<[Vec3; 4]> {
    let w = Window::whole(points);
    let t: Vec<Vec3> = (0..points.len()).map(|i| w.tangent(i)).collect();
    (0..points.len().saturating_sub(1))
        .map(|i| hermite_bezier(points[i], t[i], points[i + 1], t[i + 1]))
        .collect()
}

/// Point of a cubic Bézier at u ∈ [0, 1] (de Casteljau).
pub fn bezier_point(b: &[Vec3; 4], u: f64) -> Vec3 {
    let lerp = |p: Vec3, q: Vec3| add(p, scale(sub(q, p), u));
    let (a, c, d) = (lerp(b[0], b[1]), lerp(b[1], b[2]), lerp(b[2], b[3]));
    let (e, f) = (lerp(a, c), lerp(c, d));
    lerp(e, f)
}

/// First and second derivatives of a cubic Bézier at u ∈ [0, 1].
pub fn bezier_derivatives(b: &[Vec3; 4], u: f64) -> (Vec3, Vec3) {
    let d: [Vec3; 3] = [sub(b[1], b[0]), sub(b[2], b[1]), sub(b[3], b[2])];
    let first = scale(
        add(
            add(
                scale(d[0], (1.0 - u) * (1.0 - u)),
                scale(d[1], 2.0 * u * (1.0 - u)),
            ),
            scale(d[2], u * u),
        ),
        3.0,
    );
    let second = scale(
        add(scale(sub(d[1], d[0]), 1.0 - u), scale(sub(d[2], d[1]), u)),
        6.0,
    );
    (first, second)
}
