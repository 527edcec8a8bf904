//! SOFT corner blends: a symmetric pair of clothoids (Euler spirals) in the plane of two chords.
//!
//! ## Why
//! A circular blend between two straight chords makes the path curvature jump from 0 to 1/r where
//! the line meets the arc; at speed v the axis acceleration then steps by v²/r, and a servo-rate
//! trace shows that step as a jerk spike of about v²/(r·T). SOFT promises a jerk limit, so its
//! blends must be curvature-continuous: they start and end with zero curvature.
//!
//! ## Geometry
//! A clothoid has curvature linear in arc length. One half of the blend, of length ℓ, starts at
//! P1 on the incoming chord with the chord's direction t1 and curvature 0, and turns towards the
//! inward normal n1 (in the plane of both chords) with κ(s) = 2φ·s/ℓ², so that its heading
//! ψ(s) = φ·(s/ℓ)² reaches φ = θ/2 (half the turning angle θ) at s = ℓ, with κ_max = 2φ/ℓ. The
//! other half is its mirror image about the corner's bisector, traversed the other way: it ends at
//! P2 on the outgoing chord with direction t2 and curvature 0. In the frame (t1, n1), with x = s/ℓ:
//!
//!   X(s) = ℓ·x·Fc(φx²),  Y(s) = ℓ·x·Fs(φx²),
//!   Fc(w) = Σ_k (−1)^k w^{2k} / ((2k)!·(4k+1)),  Fs(w) = Σ_k (−1)^k w^{2k+1} / ((2k+1)!·(4k+3))
//!
//! (the Fresnel-type integrals ∫₀¹ cos(w·u²) du and ∫₀¹ sin(w·u²) du, with x factored out). As
//! φ ≤ π/2 the argument w = φx² ≤ π/2 and [`SERIES_TERMS`] terms leave a remainder below 1e-20; the
//! truncated series is a polynomial, so the position is an analytic function of s: no piecewise
//! approximation noise reaches the trace's third differences (at T = 1 ms a position error ε shows
//! as ~8ε/T³ of jerk).
//!
//! The whole shape scales with ℓ for a given θ. With the corner C, P1 = C − d·t1, P2 = C + d·t2:
//! * the mid point (x = 1) lies on the bisector: d = ℓ·(Fc(φ) + Fs(φ)·tan φ) = ℓ·D(φ);
//! * every point of the first half is within Y(s) ≤ Y(ℓ) = ℓ·Fs(φ) of the incoming chord, and its
//!   foot on the chord's line, at X(s) ≤ ℓ·Fc(φ) ≤ d from P1, lies on the chord (between P1 and
//!   C); the second half likewise for the outgoing chord. So the blend's distance from the
//!   programmed path is at most ℓ·Fs(φ), reached at the mid point;
//! * the mid point is also the point nearest to C, at ℓ·Fs(φ)/cos φ (the circular blend's rule
//!   measures that distance; the clothoid's bound is the distance from the path itself, which is
//!   what G64's tolerance limits, and for a right angle lets the blend be √2 times longer).
//!
//! So the path builder computes the [`UnitShape`] once per corner and takes
//! ℓ = min(e/Fs(φ), L_in/(2D), L_out/(2D)): within the tolerance e, and at most half of each chord.
//!
//! ## Evaluation
//! The first half is evaluated from P1 in the frame (t1, n1) with n1 = (t2 − cos θ·t1)/sin θ, the
//! second from P2 in the frame (−t2, m2) with m2 = (cos θ·t2 − t1)/sin θ, the inward normal at
//! P2, and u = (L − s)/ℓ. So both
//! end points are exact (X(0) = Y(0) = 0), and the halves meet at the mid point to rounding.
//! Derivatives along the path (T tangent, N normal, κ' = dκ/ds = ±2φ/ℓ²): p' = T, p'' = κ·N,
//! p''' = −κ²·T + κ'·N.
//!
//! ## Invariants
//! * κ = 0 at both ends: a line joins a clothoid with continuous curvature, hence continuous axis
//!   acceleration (the S-curve starts and ends every piece with zero path acceleration).
//! * Evaluation: a fixed amount of arithmetic (two polynomials of [`SERIES_TERMS`] terms, one
//!   sin_cos), no allocation.

use crate::segment::Point9;

/// Terms of each Fresnel-type series: at w ≤ π/2 the first term left out is below 1e-20.
pub const SERIES_TERMS: usize = 14;

const fn fc_coefficients() -> [f64; SERIES_TERMS] {
    // c_k = (−1)^k / ((2k)!·(4k+1))
    let mut c = [0.0; SERIES_TERMS];
    let mut factorial = 1.0; // (2k)!
    let mut k = 0;
    while k < SERIES_TERMS {
        if k > 0 {
            factorial *= ((2 * k - 1) * (2 * k)) as f64;
        }
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        c[k] = sign / (factorial * (4 * k + 1) as f64);
        k += 1;
    }
    c
}

const fn fs_coefficients() -> [f64; SERIES_TERMS] {
    // d_k = (−1)^k / ((2k+1)!·(4k+3))
    let mut c = [0.0; SERIES_TERMS];
    let mut factorial = 1.0; // (2k+1)!
    let mut k = 0;
    while k < SERIES_TERMS {
        if k > 0 {
            factorial *= ((2 * k) * (2 * k + 1)) as f64;
        }
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        c[k] = sign / (factorial * (4 * k + 3) as f64);
        k += 1;
    }
    c
}

const FC: [f64; SERIES_TERMS] = fc_coefficients();
const FS: [f64; SERIES_TERMS] = fs_coefficients();

/// (Fc(w), Fs(w)) of the module doc: ∫₀¹ cos(w·u²) du and ∫₀¹ sin(w·u²) du, by Horner's rule
/// in w². Meant for 0 ≤ w ≤ π/2.
#[inline]
pub fn fresnel_unit(w: f64) -> (f64, f64) {
    let w2 = w * w;
    let (mut c, mut s) = (0.0, 0.0);
    for k in (0..SERIES_TERMS).rev() {
        c = c * w2 + FC[k];
        s = s * w2 + FS[k];
    }
    (c, w * s)
}

/// A corner blend of half length ℓ = 1 (module doc): everything else scales with ℓ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitShape {
    /// D(φ): the length cut from each chord is d = ℓ·D.
    pub cut: f64,
    /// Fs(φ): the largest distance of the blend from the two chords is ℓ·Fs.
    pub from_chords: f64,
    /// Fs(φ)/cos φ: the distance of the blend from the corner is ℓ·Fs/cos φ.
    pub from_corner: f64,
}

/// The unit shape of a corner blend for half-turning angle φ ∈ (0, π/2) (module doc).
pub fn unit_shape(phi: f64) -> UnitShape {
    let (fc, fs) = fresnel_unit(phi);
    let (sn, cs) = phi.sin_cos();
    UnitShape {
        cut: fc + fs * sn / cs,
        from_chords: fs,
        from_corner: fs / cs,
    }
}

/// One symmetric clothoid blend (module doc), arc-length parameterised over [0, 2·half].
///
/// Stored as the corner and the two chord directions (the normals follow from them), so that a
/// piece stays small: the planner's window holds a thousand of them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clothoid {
    /// The corner C the blend cuts.
    pub corner: Point9,
    /// Unit direction of the incoming chord.
    pub t1: Point9,
    /// Unit direction of the outgoing chord.
    pub t2: Point9,
    /// Length cut from each chord: the blend runs from C − d·t1 to C + d·t2.
    pub cut: f64,
    /// Length ℓ of each half, > 0.
    pub half: f64,
    /// Half the turning angle, φ ∈ (0, π/2).
    pub phi: f64,
    /// cos θ = t1·t2.
    pub cos_turn: f64,
    /// sin θ > 0.
    pub sin_turn: f64,
}

/// Position and the first three arc-length derivatives of a clothoid at one point.
#[derive(Debug, Clone, Copy)]
pub struct ClothoidPoint {
    /// p(s).
    pub position: Point9,
    /// p'(s) = T.
    pub tangent: Point9,
    /// p''(s) = κ·N.
    pub curvature: Point9,
    /// p'''(s) = −κ²·T + κ'·N.
    pub third: Point9,
}

impl Clothoid {
    /// Total length 2ℓ.
    pub fn length(&self) -> f64 {
        2.0 * self.half
    }

    /// Start point P1 = C − d·t1 (bit for bit where the incoming line piece ends).
    pub fn start(&self) -> Point9 {
        std::array::from_fn(|i| self.corner[i] - self.cut * self.t1[i])
    }

    /// End point P2 = C + d·t2 (bit for bit where the outgoing line piece starts).
    pub fn end(&self) -> Point9 {
        std::array::from_fn(|i| self.corner[i] + self.cut * self.t2[i])
    }

    /// Largest curvature (at the mid point), 2φ/ℓ.
    pub fn max_curvature(&self) -> f64 {
        2.0 * self.phi / self.half
    }

    /// |dκ/ds|, 2φ/ℓ² (constant on each half).
    pub fn curvature_rate(&self) -> f64 {
        2.0 * self.phi / (self.half * self.half)
    }

    /// Unit inward normal at the start, n1 = (t2 − cos θ·t1)/sin θ, component `i`.
    #[inline]
    pub fn n1(&self, i: usize) -> f64 {
        (self.t2[i] - self.cos_turn * self.t1[i]) / self.sin_turn
    }

    /// Unit inward normal at the end, m2 = (cos θ·t2 − t1)/sin θ, component `i`.
    #[inline]
    pub fn m2(&self, i: usize) -> f64 {
        (self.cos_turn * self.t2[i] - self.t1[i]) / self.sin_turn
    }

    /// The point at arc length `s` ∈ [0, 2ℓ] (module doc, Evaluation).
    #[inline]
    pub fn at(&self, s: f64) -> ClothoidPoint {
        let l = self.half;
        let first = s <= l;
        let x = if first { s / l } else { (2.0 * l - s) / l }.clamp(0.0, 1.0);
        let psi = self.phi * x * x;
        let (fc, fs) = fresnel_unit(psi);
        let (sn, cs) = psi.sin_cos();
        let kappa = 2.0 * self.phi * x / l;
        let rate = 2.0 * self.phi / (l * l);
        let mut p = ClothoidPoint {
            position: [0.0; 9],
            tangent: [0.0; 9],
            curvature: [0.0; 9],
            third: [0.0; 9],
        };
        let (along, across) = (l * x * fc, l * x * fs);
        for i in 0..9 {
            let (tangent, normal, position, dkappa);
            if first {
                let (t1, n1) = (self.t1[i], self.n1(i));
                position = (self.corner[i] - self.cut * t1) + along * t1 + across * n1;
                tangent = cs * t1 + sn * n1;
                normal = -sn * t1 + cs * n1;
                dkappa = rate;
            } else {
                let (t2, m2) = (self.t2[i], self.m2(i));
                position = (self.corner[i] + self.cut * t2) - along * t2 + across * m2;
                tangent = cs * t2 - sn * m2;
                normal = sn * t2 + cs * m2;
                dkappa = -rate;
            }
            p.position[i] = position;
            p.tangent[i] = tangent;
            p.curvature[i] = kappa * normal;
            p.third[i] = -kappa * kappa * tangent + dkappa * normal;
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn v2(x: f64, y: f64) -> Point9 {
        let mut p = [0.0; 9];
        p[0] = x;
        p[1] = y;
        p
    }

    /// The blend of the corner at (`corner`, 0) from direction (1, 0) turning left by θ, ℓ = 1.
    /// Returns the blend, the cut d, the distance from the corner and from the chords.
    fn blend(theta: f64, corner: f64) -> (Clothoid, f64, f64, f64) {
        let phi = 0.5 * theta;
        let shape = unit_shape(phi);
        let (d, e, from_chords) = (shape.cut, shape.from_corner, shape.from_chords);
        let c = Clothoid {
            corner: v2(corner, 0.0),
            t1: v2(1.0, 0.0),
            t2: v2(theta.cos(), theta.sin()),
            cut: d,
            half: 1.0,
            phi,
            cos_turn: theta.cos(),
            sin_turn: theta.sin(),
        };
        (c, d, e, from_chords)
    }

    /// Simpson's rule of ∫₀¹ f with 20 000 intervals (error ~1e-16 for these smooth integrands),
    /// summed with Neumaier's compensation so that the sum's rounding stays near 1e-16 too.
    fn simpson(f: impl Fn(f64) -> f64) -> f64 {
        let n = 20_000;
        let h = 1.0 / n as f64;
        let (mut sum, mut carry) = (0.0f64, 0.0f64);
        for k in 0..=n {
            let weight = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let term = f(k as f64 * h) * weight * h / 3.0;
            let t = sum + term;
            carry += if sum.abs() >= term.abs() {
                (sum - t) + term
            } else {
                (term - t) + sum
            };
            sum = t;
        }
        sum + carry
    }

    #[test]
    fn the_series_is_the_fresnel_integral() {
        for w in [0.0, 1e-6, 0.1, 0.5, 1.0, 1.3, PI / 2.0] {
            let (c, s) = fresnel_unit(w);
            let (ci, si) = (
                simpson(|u| (w * u * u).cos()),
                simpson(|u| (w * u * u).sin()),
            );
            assert!((c - ci).abs() < 1e-14, "w {w}: Fc {c} vs {ci}");
            assert!((s - si).abs() < 1e-14, "w {w}: Fs {s} vs {si}");
        }
    }

    #[test]
    fn end_points_tangents_curvature_and_turning_angle() {
        for theta in [1e-4, 0.1, 0.7, PI / 2.0, 2.5, PI - 1e-6] {
            let (c, d, e, from_chords) = blend(theta, 3.0);
            let l = c.length();
            let (a, b) = (c.at(0.0), c.at(l));
            let corner = v2(3.0, 0.0);
            for i in 0..9 {
                assert_eq!(a.position[i], c.start()[i]);
                assert_eq!(b.position[i], c.end()[i]);
                assert!((a.tangent[i] - c.t1[i]).abs() < 1e-15);
                assert!((b.tangent[i] - c.t2[i]).abs() < 1e-15, "θ {theta}");
                assert!(a.curvature[i].abs() < 1e-15 && b.curvature[i].abs() < 1e-15);
            }
            // Turning angle: the heading at the end is θ.
            let heading = b.tangent[1].atan2(b.tangent[0]);
            assert!((heading - theta).abs() < 1e-14, "θ {theta}: {heading}");
            // Both halves meet at the mid point, on the bisector, at distance e from the corner,
            // with the largest curvature.
            let (m1, m2) = (c.at(1.0 - 1e-12), c.at(1.0 + 1e-12));
            let mid = c.at(1.0);
            for i in 0..2 {
                assert!((m1.position[i] - m2.position[i]).abs() < 1e-11, "θ {theta}");
            }
            let dist =
                |p: &Point9| ((p[0] - corner[0]).powi(2) + (p[1] - corner[1]).powi(2)).sqrt();
            assert!(
                (dist(&mid.position) - e).abs() < 1e-13 * (1.0 + d),
                "θ {theta}"
            );
            let kmax = (mid.curvature[0].powi(2) + mid.curvature[1].powi(2)).sqrt();
            assert!((kmax - c.max_curvature()).abs() < 1e-13 * kmax, "θ {theta}");
            assert!((kmax - theta).abs() < 1e-13 * kmax); // 2φ/ℓ with ℓ = 1
                                                          // No point nearer the corner than e, none farther than e from its chord; symmetric.
            for k in 0..=1000 {
                let s = l * k as f64 / 1000.0;
                let p = c.at(s).position;
                assert!(dist(&p) >= e * (1.0 - 1e-12), "θ {theta} s {s}");
                let q = c.at(l - s).position;
                // Mirror about the bisector through the corner, direction (cos(φ+π/2)…): reflect p.
                let phi = 0.5 * theta;
                let (bx, by) = (-(phi.sin()), phi.cos()); // bisector direction
                let (rx, ry) = (p[0] - 3.0, p[1]);
                let dot = rx * bx + ry * by;
                let (mx, my) = (2.0 * dot * bx - rx + 3.0, 2.0 * dot * by - ry);
                assert!(
                    (mx - q[0]).abs() < 1e-12 * (1.0 + d) && (my - q[1]).abs() < 1e-12 * (1.0 + d),
                    "θ {theta}: not symmetric at s {s}"
                );
                let to_chord = if s <= 1.0 {
                    p[1]
                } else {
                    let (rx, ry) = (p[0] - c.end()[0], p[1] - c.end()[1]);
                    rx * -c.t2[1] + ry * c.t2[0]
                };
                assert!(
                    to_chord >= -1e-15 && to_chord <= from_chords * (1.0 + 1e-12) + 1e-15,
                    "θ {theta}"
                );
                // The foot on the chord's line lies on the chord: between its start and C.
                let along = if s <= 1.0 {
                    p[0] - c.start()[0]
                } else {
                    let (rx, ry) = (c.end()[0] - p[0], c.end()[1] - p[1]);
                    rx * c.t2[0] + ry * c.t2[1]
                };
                assert!(along >= -1e-15 && along <= d * (1.0 + 1e-12), "θ {theta}");
            }
        }
    }

    #[test]
    fn finite_differences_agree_with_the_analytic_derivatives() {
        let (c, _, _, _) = blend(1.2, 0.0);
        let h = 1e-4;
        for k in 1..40 {
            let s = c.length() * k as f64 / 40.0;
            if (s - c.half).abs() < 4.0 * h {
                continue;
            }
            let p = |s: f64| c.at(s).position;
            let (pm2, pm, p0, pp, pp2) = (p(s - 2.0 * h), p(s - h), p(s), p(s + h), p(s + 2.0 * h));
            let pt = c.at(s);
            for i in 0..2 {
                let d1 = (pp[i] - pm[i]) / (2.0 * h);
                let d2 = (pp[i] - 2.0 * p0[i] + pm[i]) / (h * h);
                let d3 = (pp2[i] - 2.0 * pp[i] + 2.0 * pm[i] - pm2[i]) / (2.0 * h * h * h);
                assert!(
                    (d1 - pt.tangent[i]).abs() < 1e-8,
                    "s {s}: {d1} {}",
                    pt.tangent[i]
                );
                assert!(
                    (d2 - pt.curvature[i]).abs() < 1e-6,
                    "s {s}: {d2} {}",
                    pt.curvature[i]
                );
                assert!(
                    (d3 - pt.third[i]).abs() < 1e-3,
                    "s {s}: {d3} {}",
                    pt.third[i]
                );
            }
            // Arc-length parameterised.
            let speed = (pt.tangent[0].powi(2) + pt.tangent[1].powi(2)).sqrt();
            assert!((speed - 1.0).abs() < 1e-15);
        }
    }
}
