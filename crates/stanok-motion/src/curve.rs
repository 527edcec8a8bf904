//! Exact arcs (circles, helices, spirals) and the smooth blends at the junctions they take part in.
//!
//! ## Exact arcs
//! An arc is interpolated on its programmed curve, not as chords: with the arc's cylindrical frame
//! (centre C, unit axis â, start direction û, v̂ = â × û, [`stanok_geom::HelixFrame`]) and the
//! swept angle θ ∈ [0, S],
//!
//! ```text
//!   p(θ) = O + θ·w + r(θ)·(û cos θ + v̂ sin θ),   r(θ) = r_s + r'·θ
//! ```
//! in the 9-D axis space: O = C + â·h_s (and the other axes' start values), w = â·h' (and the
//! other axes' rates per radian, so that they move linearly with the swept angle). The path
//! parameter is s = ρ·θ with ρ = (9-D length)/S, the mean of |dp/dθ| — exactly |dp/dθ| for a
//! circle or helix, so s is the arc length there; on a spiral (radii differing within the
//! interpreter's arc tolerance) the speed along the curve differs from the planned one by the
//! factor |dp/dθ|/ρ, which the limits below include. Every setpoint is a point of the formula:
//! on the programmed circle to rounding, at any feed.
//!
//! With R = û cos θ + v̂ sin θ and T = −û sin θ + v̂ cos θ:
//! p_θ = w + r'·R + r·T, p_θθ = 2r'·T − r·R, p_θθθ = −3r'·R − r·T; derivatives along s divide by
//! ρ, ρ², ρ³.
//!
//! **Limits** ([`bounded_limits`]): per axis i, with |R_i|, |T_i| ≤ ρ_i = √(û_i² + v̂_i²) and
//! r_max the largest radius on the piece: |p'_i| ≤ (|w_i| + (|r'| + r_max)·ρ_i)/ρ = B1_i,
//! |p''_i| ≤ (2|r'| + r_max)·ρ_i/ρ² = B2_i, |p'''_i| ≤ (3|r'| + r_max)·ρ_i/ρ³ = B3_i. The axis
//! acceleration a·p'_i + v²·p''_i stays within A_i when v²·B2_i ≤ 0.95·A_i (the centripetal share,
//! [`crate::piece::CENTRIPETAL_SHARE`]) and a ≤ (A_i − v²·B2_i)/B1_i; in SOFT the axis jerk
//! j·p'_i + 3·v·a·p''_i + v³·p'''_i stays within J_i when v³·B3_i ≤ ½·J_i and the rest is shared
//! half and half by 3·v·a·B2_i and j·B1_i.
//!
//! ## Smooth blends
//! Where an arc meets another piece with a corner (G64), or — in SOFT — tangentially but with a
//! different curvature (a line entering a circle: the axis acceleration would step by v²/r), the
//! two curves are blended over [−d, d] around the junction J:
//!
//! ```text
//!   q(σ) = c1(σ) + β(x)·(c2(σ) − c1(σ)),   x = (σ + d)/(2d),   β(x) = x³(10 − 15x + 6x²)
//! ```
//! c1 is the incoming curve through J, continued past it (a line along its direction, an arc on
//! its circle), c2 the outgoing one continued backwards, both parameterised by their own s with
//! σ = 0 at J. β is the quintic smooth step: β = β′ = β″ = 0 at x = 0, and β = 1, β′ = β″ = 0 at
//! x = 1, so q starts as c1 and ends as c2 with equal position, tangent and curvature: the axis accelerations never step, BRISK or SOFT, at any junction involving an arc.
//! The blend's parameter σ is not its arc length; its speed along the curve is |q′| times the
//! planned one, so the programmed feed is divided by max |q′|.
//!
//! **Tolerance.** For σ ≤ 0, c1(σ) lies on the programmed path, so the blend is within
//! β·|Δ(σ)| of it (Δ = c2 − c1); for σ ≥ 0 within (1 − β)·|Δ| of c2(σ). With
//! |Δ(σ)| ≤ |σ|·|t2 − t1| + σ²·(K1 + K2)/2 + |σ|³·(T1 + T2)/6 (t the unit tangents at J, K and T
//! the largest |c″|, |c‴| on [−d, d]) and m_k = max over x ∈ [0, ½] of β(x)·(1 − 2x)^k
//! (0.07055, 0.02666, 0.01316; the same by symmetry for σ ≥ 0), the blend is within
//! g(d) = m1·d·|t2 − t1| + m2·d²·(K1 + K2)/2 + m3·d³·(T1 + T2)/6 of the path. g grows with d, so
//! the largest d ≤ half of each piece with g(d) ≤ e is found by bisection.
//!
//! **Limits.** q′, q″, q‴ are sampled at [`BLEND_SAMPLES`] points; their per-axis maxima, raised by
//! [`SAMPLE_MARGIN`] for what lies between samples (the functions are smooth polynomials times
//! sines over a short interval: the sampling error is of order 1e-4), are B1, B2, B3 above. The
//! programmed feed is divided by max |q′| — the largest sample raised to the vertex of the
//! parabola through it and its neighbours, and by [`FEED_SAMPLE_MARGIN`] — not by the 1 %: the
//! feed is no machine limit, and the axis velocities keep their 1 % through B1.
//!
//! ## Invariants
//! * An arc piece's points are the formula's: on the programmed curve to rounding.
//! * A blend starts exactly where the incoming piece, trimmed by d, ends, and ends where the
//!   outgoing one, trimmed by d, starts (the same expression evaluates both); tangent and
//!   curvature are continuous there.
//! * No allocation per setpoint; a blend is built once per junction (one bisection, 65 samples).

use crate::limits::AxisLimit;
use crate::piece::{CENTRIPETAL_SHARE, SOFT_TURN_JERK_SHARE};
use crate::segment::Point9;

/// Samples of a blend's derivatives for its limits.
pub const BLEND_SAMPLES: usize = 65;
/// Relative margin on sampled maxima of the derivatives (for the axis limits).
pub const SAMPLE_MARGIN: f64 = 0.01;
/// Relative margin on the maximum of |q′| for the programmed feed (the sampled maximum refined by
/// the parabola through it and its neighbours, module doc, Limits): the feed is a target, not a
/// machine limit. With the axes' 1 % a near-tangent blend of two arcs — every junction of a
/// spiral made of arcs — ran 1 % below the feed over its whole length.
pub const FEED_SAMPLE_MARGIN: f64 = 1e-6;
/// max over x ∈ [0, ½] of β(x)·(1 − 2x)^k, k = 1, 2, 3, rounded up.
const SMOOTH_STEP_MOMENTS: [f64; 3] = [0.070_553, 0.026_658, 0.013_159];

/// An exact arc of the 9-D path (module doc), parameterised by s = ρ·θ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelixCurve {
    /// O: the point at θ = 0 less the radial part (axis point at the start height; other axes'
    /// start values).
    pub origin: Point9,
    /// û (XYZ).
    pub u: [f64; 3],
    /// v̂ = â × û (XYZ).
    pub v: [f64; 3],
    /// w: the linear part's rate per radian (axial rise in XYZ, the other axes' rates).
    pub rise: Point9,
    /// Radius at θ = 0.
    pub r0: f64,
    /// r′: radius change per radian (0 for circles and helices).
    pub dr: f64,
    /// ρ: path parameter per radian.
    pub rho: f64,
}

/// A point of a curve with its first three derivatives along its parameter.
#[derive(Debug, Clone, Copy)]
pub struct CurvePoint {
    /// Position.
    pub p: Point9,
    /// First derivative.
    pub d1: Point9,
    /// Second derivative.
    pub d2: Point9,
    /// Third derivative.
    pub d3: Point9,
}

impl HelixCurve {
    /// The curve of an arc segment from `start` to `end` (9-D) whose XYZ part is `helix`, and its
    /// total sweep S (the segment is θ ∈ [0, S]). None if degenerate (zero radius and length).
    pub fn of_segment(
        helix: &stanok_geom::Helix,
        start: &Point9,
        end: &Point9,
    ) -> Option<(HelixCurve, f64)> {
        let f = helix.frame();
        let sweep = f.sweep;
        let xyz_len = helix.length();
        let other: f64 = (3..9).map(|i| (end[i] - start[i]).powi(2)).sum();
        let len = (xyz_len * xyz_len + other).sqrt();
        if !(sweep.is_finite() && sweep > 0.0 && len.is_finite() && len > 0.0) {
            return None;
        }
        let dh = (f.h_e - f.h_s) / sweep;
        let mut origin = [0.0; 9];
        let mut rise = [0.0; 9];
        for i in 0..3 {
            origin[i] = f.centre[i] + f.a[i] * f.h_s;
            rise[i] = f.a[i] * dh;
        }
        for i in 3..9 {
            origin[i] = start[i];
            rise[i] = (end[i] - start[i]) / sweep;
        }
        let c = HelixCurve {
            origin,
            u: f.u,
            v: f.v,
            rise,
            r0: f.r_s,
            dr: (f.r_e - f.r_s) / sweep,
            rho: len / sweep,
        };
        c.rho.is_finite().then_some((c, sweep))
    }

    /// The point at angle `theta`.
    #[inline]
    pub fn point(&self, theta: f64) -> Point9 {
        let (sn, cs) = theta.sin_cos();
        let r = self.r0 + self.dr * theta;
        std::array::from_fn(|i| {
            let radial = if i < 3 {
                self.u[i] * cs + self.v[i] * sn
            } else {
                0.0
            };
            self.origin[i] + theta * self.rise[i] + r * radial
        })
    }

    /// The point at angle `theta` with its derivatives along s = ρ·θ.
    #[inline]
    pub fn at(&self, theta: f64) -> CurvePoint {
        let (sn, cs) = theta.sin_cos();
        let r = self.r0 + self.dr * theta;
        let (k1, k2, k3) = (
            1.0 / self.rho,
            1.0 / (self.rho * self.rho),
            1.0 / self.rho.powi(3),
        );
        let mut out = CurvePoint {
            p: [0.0; 9],
            d1: [0.0; 9],
            d2: [0.0; 9],
            d3: [0.0; 9],
        };
        for i in 0..9 {
            let (rad, tan) = if i < 3 {
                (
                    self.u[i] * cs + self.v[i] * sn,
                    -self.u[i] * sn + self.v[i] * cs,
                )
            } else {
                (0.0, 0.0)
            };
            out.p[i] = self.origin[i] + theta * self.rise[i] + r * rad;
            out.d1[i] = (self.rise[i] + self.dr * rad + r * tan) * k1;
            out.d2[i] = (2.0 * self.dr * tan - r * rad) * k2;
            out.d3[i] = (-3.0 * self.dr * rad - r * tan) * k3;
        }
        out
    }

    /// Largest |r| over [θa, θb] (r is linear in θ).
    pub fn max_radius(&self, theta_a: f64, theta_b: f64) -> f64 {
        (self.r0 + self.dr * theta_a)
            .abs()
            .max((self.r0 + self.dr * theta_b).abs())
    }

    /// Per-axis bounds B1, B2, B3 of |p′|, |p″|, |p‴| over [θa, θb] (module doc, Limits).
    pub fn bounds(&self, theta_a: f64, theta_b: f64) -> [Point9; 3] {
        let r = self.max_radius(theta_a, theta_b);
        let dr = self.dr.abs();
        let w = |i: usize| {
            if i < 3 {
                self.u[i].hypot(self.v[i])
            } else {
                0.0
            }
        };
        [
            std::array::from_fn(|i| (self.rise[i].abs() + (dr + r) * w(i)) / self.rho),
            std::array::from_fn(|i| (2.0 * dr + r) * w(i) / (self.rho * self.rho)),
            std::array::from_fn(|i| (3.0 * dr + r) * w(i) / self.rho.powi(3)),
        ]
    }

    /// Largest |p″| and |p‴| (as vectors) over [θa, θb]: the K and T of the blend tolerance.
    fn curvature_bounds(&self, theta_a: f64, theta_b: f64) -> (f64, f64) {
        let r = self.max_radius(theta_a, theta_b);
        let dr = self.dr.abs();
        (
            (2.0 * dr + r) / (self.rho * self.rho),
            (3.0 * dr + r) / self.rho.powi(3),
        )
    }
}

/// One side of a blend: a curve through the junction, parameterised by its own path parameter σ
/// with σ = 0 at the junction (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlendSide {
    /// A straight line through `at` along the unit vector `dir`.
    Line {
        /// The junction.
        at: Point9,
        /// Unit direction.
        dir: Point9,
    },
    /// An arc, reaching the junction at angle `theta`.
    Helix {
        /// The arc.
        curve: HelixCurve,
        /// Its angle at the junction.
        theta: f64,
    },
}

impl BlendSide {
    /// The point at σ with its derivatives.
    #[inline]
    pub fn at(&self, sigma: f64) -> CurvePoint {
        match self {
            BlendSide::Line { at, dir } => CurvePoint {
                p: std::array::from_fn(|i| at[i] + sigma * dir[i]),
                d1: *dir,
                d2: [0.0; 9],
                d3: [0.0; 9],
            },
            BlendSide::Helix { curve, theta } => curve.at(theta + sigma / curve.rho),
        }
    }

    /// Largest |c″| and |c‴| over σ ∈ [−d, d].
    fn curvature_bounds(&self, d: f64) -> (f64, f64) {
        match self {
            BlendSide::Line { .. } => (0.0, 0.0),
            BlendSide::Helix { curve, theta } => {
                curve.curvature_bounds(theta - d / curve.rho, theta + d / curve.rho)
            }
        }
    }
}

/// A smooth blend of two curves over [−d, d] (module doc), with its sampled bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct Blend {
    /// The incoming curve, continued past the junction.
    pub c1: BlendSide,
    /// The outgoing curve, continued back before the junction.
    pub c2: BlendSide,
    /// Half length, in the curves' parameter.
    pub d: f64,
    /// Per-axis bounds of |q′|, |q″|, |q‴|.
    pub bounds: [Point9; 3],
    /// 1 / max |q′|: the factor from the programmed speed along the path to the planner's speed
    /// along σ.
    pub speed_scale: f64,
    /// Bound of the distance from the programmed path, g(d).
    pub deviation: f64,
}

/// β and its first three derivatives at x.
#[inline]
fn smooth_step(x: f64) -> [f64; 4] {
    let x2 = x * x;
    [
        x2 * x * (10.0 - 15.0 * x + 6.0 * x2),
        30.0 * x2 * (1.0 - x) * (1.0 - x),
        60.0 * x * (1.0 - x) * (1.0 - 2.0 * x),
        60.0 * (1.0 - 6.0 * x + 6.0 * x2),
    ]
}

impl Blend {
    /// The blend of `c1` into `c2` within `tolerance` of the path, at most `d_max` long on each
    /// side, or None if no blend of useful size exists (the caller stops there instead).
    pub fn new(c1: BlendSide, c2: BlendSide, tolerance: f64, d_max: f64) -> Option<Blend> {
        if !(tolerance > 0.0 && d_max > 0.0 && d_max.is_finite()) {
            return None;
        }
        let (a, b) = (c1.at(0.0), c2.at(0.0));
        let unit = |v: &Point9| {
            let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            v.map(|x| x / n)
        };
        let (t1, t2) = (unit(&a.d1), unit(&b.d1));
        let dt = (0..9).map(|i| (t2[i] - t1[i]).powi(2)).sum::<f64>().sqrt();
        let [m1, m2, m3] = SMOOTH_STEP_MOMENTS;
        let g = |d: f64| {
            let (k1, j1) = c1.curvature_bounds(d);
            let (k2, j2) = c2.curvature_bounds(d);
            m1 * d * dt + m2 * d * d * 0.5 * (k1 + k2) + m3 * d * d * d * (j1 + j2) / 6.0
        };
        let d = if g(d_max) <= tolerance {
            d_max
        } else {
            let (mut lo, mut hi) = (0.0, d_max);
            for _ in 0..50 {
                let mid = 0.5 * (lo + hi);
                if g(mid) <= tolerance {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        if d.is_nan() || d <= 1e-9 {
            return None;
        }
        let mut blend = Blend {
            c1,
            c2,
            d,
            bounds: [[0.0; 9]; 3],
            speed_scale: 1.0,
            deviation: g(d),
        };
        let mut b = [[0.0f64; 9]; 3];
        let mut speeds = [0.0f64; BLEND_SAMPLES];
        for (k, speed) in speeds.iter_mut().enumerate() {
            let s = 2.0 * d * k as f64 / (BLEND_SAMPLES - 1) as f64;
            let q = blend.at(s);
            for (bound, d) in b.iter_mut().zip([q.d1, q.d2, q.d3]) {
                for (m, x) in bound.iter_mut().zip(d) {
                    *m = m.max(x.abs());
                }
            }
            *speed = q.d1.iter().map(|x| x * x).sum::<f64>().sqrt();
        }
        // The largest sample, raised to the vertex of the parabola through it and its neighbours
        // (|q′| is smooth: what remains between samples is of third order in the spacing).
        let top = (0..BLEND_SAMPLES)
            .max_by(|&i, &j| speeds[i].total_cmp(&speeds[j]))
            .unwrap_or(0);
        let mut speed = speeds[top];
        if top > 0 && top + 1 < BLEND_SAMPLES {
            let (l, m, r) = (speeds[top - 1], speeds[top], speeds[top + 1]);
            let curvature = l - 2.0 * m + r;
            if curvature < 0.0 {
                speed = speed.max(m - (r - l) * (r - l) / (8.0 * curvature));
            }
        }
        if !(speed.is_finite() && speed > 0.0) {
            return None;
        }
        blend.bounds = b.map(|row| row.map(|x| x * (1.0 + SAMPLE_MARGIN)));
        blend.speed_scale = 1.0 / (speed * (1.0 + FEED_SAMPLE_MARGIN));
        Some(blend)
    }

    /// Length in the blend's parameter, 2d.
    pub fn length(&self) -> f64 {
        2.0 * self.d
    }

    /// The point at s ∈ [0, 2d] (σ = s − d) with its derivatives along s.
    #[inline]
    pub fn at(&self, s: f64) -> CurvePoint {
        let sigma = s - self.d;
        let (a, b) = (self.c1.at(sigma), self.c2.at(sigma));
        let h = 1.0 / (2.0 * self.d);
        let [be, b1, b2, b3] = smooth_step((s * h).clamp(0.0, 1.0));
        let (b1, b2, b3) = (b1 * h, b2 * h * h, b3 * h * h * h);
        let mut out = CurvePoint {
            p: [0.0; 9],
            d1: [0.0; 9],
            d2: [0.0; 9],
            d3: [0.0; 9],
        };
        for i in 0..9 {
            let (e0, e1, e2, e3) = (
                b.p[i] - a.p[i],
                b.d1[i] - a.d1[i],
                b.d2[i] - a.d2[i],
                b.d3[i] - a.d3[i],
            );
            out.p[i] = a.p[i] + be * e0;
            out.d1[i] = a.d1[i] + b1 * e0 + be * e1;
            out.d2[i] = a.d2[i] + b2 * e0 + 2.0 * b1 * e1 + be * e2;
            out.d3[i] = a.d3[i] + b3 * e0 + 3.0 * b2 * e1 + 3.0 * b1 * e2 + be * e3;
        }
        out
    }
}

/// Limits (v, a, j) of a piece whose per-axis derivative bounds are `b` = [B1, B2, B3] (module
/// doc, Limits), at programmed speed `speed` (already in the piece's parameter).
pub fn bounded_limits(
    b: &[Point9; 3],
    speed: f64,
    soft: bool,
    axes: &[AxisLimit; 9],
) -> (f64, f64, f64) {
    let [b1, b2, b3] = b;
    let mut v = speed.max(0.0);
    for i in 0..9 {
        let lim = &axes[i];
        if b1[i] > 0.0 {
            v = v.min(lim.velocity / b1[i]);
        }
        if b2[i] > 0.0 {
            v = v.min((CENTRIPETAL_SHARE * lim.acceleration / b2[i]).sqrt());
        }
        if soft && b3[i] > 0.0 {
            v = v.min((SOFT_TURN_JERK_SHARE * lim.jerk / b3[i]).cbrt());
        }
    }
    let (mut a, mut j) = (f64::INFINITY, f64::INFINITY);
    for i in 0..9 {
        let lim = &axes[i];
        if b1[i] > 0.0 {
            a = a.min((lim.acceleration - v * v * b2[i]).max(0.0) / b1[i]);
        }
        if soft {
            let rest = (lim.jerk - v * v * v * b3[i]).max(0.0);
            if b2[i] > 0.0 && v > 0.0 {
                a = a.min(0.5 * rest / (3.0 * v * b2[i]));
            }
            if b1[i] > 0.0 {
                j = j.min(0.5 * rest / b1[i]);
            }
        } else if b1[i] > 0.0 {
            j = j.min(lim.jerk / b1[i]);
        }
    }
    let guard = |x: f64| {
        if x.is_finite() && x > 0.0 {
            x
        } else if x == f64::INFINITY {
            1e12
        } else {
            0.0
        }
    };
    (guard(v), guard(a), guard(j))
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_geom::Helix;

    fn p9(x: f64, y: f64, z: f64) -> Point9 {
        let mut p = [0.0; 9];
        p[0] = x;
        p[1] = y;
        p[2] = z;
        p
    }

    #[test]
    fn an_arc_is_on_its_circle_and_ends_at_its_end() {
        // r 10 about (5, 0), from (15, 0) counter-clockwise to (5, 10), rising 3 in Z, A 0 → 90.
        let helix = Helix {
            start: [15.0, 0.0, 0.0],
            end: [5.0, 10.0, 3.0],
            centre: [5.0, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            turns: 1,
        };
        let mut s = p9(15.0, 0.0, 0.0);
        let mut e = p9(5.0, 10.0, 3.0);
        s[3] = 0.0;
        e[3] = 90.0;
        let (c, sweep) = HelixCurve::of_segment(&helix, &s, &e).unwrap();
        assert!((sweep - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        for k in 0..=100 {
            let th = sweep * k as f64 / 100.0;
            let p = c.point(th);
            let r = (p[0] - 5.0).hypot(p[1]);
            assert!((r - 10.0).abs() < 1e-12);
            assert!((p[2] - 3.0 * th / sweep).abs() < 1e-12);
            assert!((p[3] - 90.0 * th / sweep).abs() < 1e-12);
            // |p'| = 1: s is the arc length.
            let q = c.at(th);
            let n = q.d1.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((n - 1.0).abs() < 1e-12);
        }
        let end = c.point(sweep);
        for i in 0..9 {
            assert!((end[i] - e[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn derivatives_agree_with_finite_differences() {
        let helix = Helix {
            start: [10.0, 0.0, 0.0],
            end: [-9.99, 0.0, 2.0],
            centre: [0.0, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            turns: 1,
        };
        let (c, _) =
            HelixCurve::of_segment(&helix, &p9(10.0, 0.0, 0.0), &p9(-9.99, 0.0, 2.0)).unwrap();
        let line = BlendSide::Line {
            at: p9(10.0, 0.0, 0.0),
            dir: p9(0.0, 1.0, 0.0),
        };
        let blend = Blend::new(
            line,
            BlendSide::Helix {
                curve: c,
                theta: 0.0,
            },
            0.01,
            3.0,
        )
        .unwrap();
        let h = 1e-4;
        for k in 1..20 {
            let s = blend.length() * k as f64 / 20.0;
            let f = |s: f64| blend.at(s).p;
            let q = blend.at(s);
            let (pm2, pm, p0, pp, pp2) = (f(s - 2.0 * h), f(s - h), f(s), f(s + h), f(s + 2.0 * h));
            for i in 0..3 {
                let d1 = (pp[i] - pm[i]) / (2.0 * h);
                let d2 = (pp[i] - 2.0 * p0[i] + pm[i]) / (h * h);
                let d3 = (pp2[i] - 2.0 * pp[i] + 2.0 * pm[i] - pm2[i]) / (2.0 * h * h * h);
                assert!((d1 - q.d1[i]).abs() < 1e-7, "{d1} {}", q.d1[i]);
                assert!((d2 - q.d2[i]).abs() < 1e-5, "{d2} {}", q.d2[i]);
                assert!((d3 - q.d3[i]).abs() < 1e-2, "{d3} {}", q.d3[i]);
            }
        }
        // Ends: the blend starts on the line and ends on the arc with their tangent and curvature.
        let (a, b) = (blend.at(0.0), blend.at(blend.length()));
        let (l, r) = (line.at(-blend.d), c.at(blend.d / c.rho));
        for i in 0..9 {
            assert_eq!(a.p[i], l.p[i]);
            assert!((a.d1[i] - l.d1[i]).abs() < 1e-15 && a.d2[i].abs() < 1e-15);
            assert!((b.p[i] - r.p[i]).abs() < 1e-15);
            assert!((b.d1[i] - r.d1[i]).abs() < 1e-15 && (b.d2[i] - r.d2[i]).abs() < 1e-15);
        }
        // Within its tolerance of the line and the arc.
        for k in 0..=400 {
            let p = blend.at(blend.length() * k as f64 / 400.0).p;
            let to_line = p[0] - 10.0;
            let to_arc = (p[0].hypot(p[1]) - 10.0).abs();
            assert!(to_line.abs().min(to_arc) <= 0.01 + 1e-12, "{p:?}");
        }
    }
}
