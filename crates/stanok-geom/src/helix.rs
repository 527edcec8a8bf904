//! Circular, helical and spiral arcs in space: the XYZ part of a Canon `ArcMove`.
//!
//! ## Model
//!
//! ```text
//!            axis â (unit)            p(θ) = C + â·h(θ) + r(θ)·(û cos θ + v̂ sin θ),  θ ∈ [0, S]
//!              ^                       h(θ) = h_s + (h_e − h_s)·θ/S       (axial: linear, helix)
//!              |   . end               r(θ) = r_s + (r_e − r_s)·θ/S       (radius: linear, spiral)
//!              | .                     û = start's radial direction, v̂ = â × û (CCW about â)
//!              C------> û (start)
//! ```
//! The frame comes from splitting `start − centre` and `end − centre` into an axial part (h) and a
//! radial part (r, direction). The planar sweep is the counter-clockwise angle from the start's to the
//! end's radial direction in (0, 2π] — 2π when the projections coincide (within 1e-9 mm) or lie on the
//! same ray — plus (turns − 1)·2π. `point_at(1)` is `end` exactly, `point_at(0)` is `start` exactly.
//!
//! ## Length
//!
//! With t = θ/S, |dp/dt|² = (S·r(t))² + Δr² + Δh², so L = ∫₀¹ √((S·r(t))² + q) dt with q = Δr² + Δh².
//! Constant radius: L = √((r·S)² + Δh²). Spiral: substituting x = S·r(t) gives the closed form
//! L = [G(S·r_e) − G(S·r_s)] / (S·Δr) with G(x) = ½(x·√(x² + q) + q·asinh(x/√q)). That quotient loses
//! digits when Δr is tiny, so below |Δr| ≤ 1e-6·r the constant formula with the mean radius is used
//! (its relative error is of order (Δr/r)² ≤ 1e-12).
//!
//! ## Bounding box
//!
//! Coordinate i is extreme at the ends or where dp_i/dθ = 0. For constant radius
//! dp_i/dθ = â_i·h' − r·ρ_i·sin(θ − φ_i) with û_i = ρ_i cos φ_i, v̂_i = ρ_i sin φ_i, so the stationary
//! angles are φ_i + asin(s) and φ_i + π − asin(s), s = â_i·h'/(r·ρ_i), repeated every turn. Because the
//! axial drift is linear, successive maxima (and minima) grow by the same step each turn: only the
//! first and the last turn can hold the extremes, so at most eight angles per coordinate are examined,
//! for any axis direction and any number of turns (exact). Near-constant radii use the mean radius for
//! the angles and evaluate the true curve there (the value is stationary, so the error is second order).
//! A genuine spiral (|Δr| > 1e-6·r) is handled numerically: dp_i/dθ is sampled every 2π/64 (at most
//! 65 536 samples, so spirals of more than 1 024 turns are sampled more coarsely) and each sign change
//! is refined by bisection.
//!
//! ## Tessellation
//!
//! For a curve sampled at equal parameter steps δ, the distance from the curve to its chord is at most
//! δ²/8 · max|p''| (linear interpolation error, valid for vector functions). Here
//! |d²p/dθ²| = √(4·r'² + r²) ≤ √(4·r'² + r_max²) with r' = Δr/S, so δ = √(8·tol / that) keeps every
//! chord within `tol`. For a circle this is the familiar sagitta rule r(1 − cos(δ/2)) ≤ tol to first
//! order. The step count is capped at 100 000; only then can a chord deviate by more than `tol`.
//!
//! Degenerate input never panics: a zero or non-finite axis is taken as +Z; a start on the axis takes
//! the end's radial direction (and if both are on the axis, any direction perpendicular to it); NaN
//! coordinates give NaN points, never an unbounded loop.

use crate::arc2d::positive_angle;
use crate::vec3::{add, cross, dot, norm, normalize, scale, sub, Vec3};
use std::f64::consts::TAU;

/// Projections closer than this (mm) are the same point: the sweep is a full turn.
const SAME_POINT_MM: f64 = 1e-9;
/// Radii that differ by at most this fraction are treated as constant (see the module doc).
const CONSTANT_RADIUS_REL: f64 = 1e-6;
/// Upper bound of the points [`Helix::tessellate`] appends.
const MAX_TESSELLATION_POINTS: usize = 100_000;
/// Derivative samples per turn, and in all, for a spiral's bounding box.
const SPIRAL_SAMPLES_PER_TURN: f64 = 64.0;
const SPIRAL_MAX_SAMPLES: usize = 65_536;

/// A circular/helical/spiral arc in 3D, as in stanok-canon's ArcMove (XYZ part only).
///
/// Rotation is counter-clockwise (right-handed) about `axis` through `centre`; see the module doc for
/// the exact model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Helix {
    /// Start point, mm.
    pub start: Vec3,
    /// End point, mm.
    pub end: Vec3,
    /// A point on the rotation axis, mm.
    pub centre: Vec3,
    /// Direction of the rotation axis (unit; normalised again here, +Z if zero).
    pub axis: Vec3,
    /// 1 = the arc only, n = the arc plus n − 1 full turns (0 is read as 1).
    pub turns: u32,
}

/// The arc in its own cylindrical frame (module doc: p(θ) = C + â·h(θ) + r(θ)·(û cos θ + v̂ sin θ)),
/// for callers that evaluate it themselves (the motion planner's exact arcs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelixFrame {
    /// A point on the axis, mm.
    pub centre: Vec3,
    /// Unit axis â.
    pub a: Vec3,
    /// Unit radial direction of the start, û.
    pub u: Vec3,
    /// â × û.
    pub v: Vec3,
    /// Radius at the start, mm.
    pub r_s: f64,
    /// Radius at the end, mm.
    pub r_e: f64,
    /// Axial coordinate of the start, mm.
    pub h_s: f64,
    /// Axial coordinate of the end, mm.
    pub h_e: f64,
    /// Total swept angle, radians, > 0.
    pub sweep: f64,
}

type Frame = HelixFrame;

impl Frame {
    /// The point at swept angle `theta` (radians from the start).
    fn point(&self, theta: f64) -> Vec3 {
        let t = theta / self.sweep;
        let r = self.r_s + (self.r_e - self.r_s) * t;
        let h = self.h_s + (self.h_e - self.h_s) * t;
        let radial = add(
            scale(self.u, r * theta.cos()),
            scale(self.v, r * theta.sin()),
        );
        add(add(self.centre, scale(self.a, h)), radial)
    }

    fn is_constant_radius(&self) -> bool {
        (self.r_e - self.r_s).abs() <= CONSTANT_RADIUS_REL * self.r_s.max(self.r_e)
    }

    /// dp_i/dθ at `theta` for coordinate `i`.
    fn derivative(&self, i: usize, theta: f64) -> f64 {
        let t = theta / self.sweep;
        let r = self.r_s + (self.r_e - self.r_s) * t;
        let dr = (self.r_e - self.r_s) / self.sweep;
        let dh = (self.h_e - self.h_s) / self.sweep;
        let (s, c) = theta.sin_cos();
        self.a[i] * dh + dr * (c * self.u[i] + s * self.v[i]) + r * (c * self.v[i] - s * self.u[i])
    }

    /// Stationary angles of coordinate `i` in the first and last turn (constant radius, module doc).
    fn push_helix_extrema(&self, i: usize, out: &mut Vec<f64>) {
        let r = 0.5 * (self.r_s + self.r_e);
        let rho = self.u[i].hypot(self.v[i]);
        let amplitude = r * rho;
        if amplitude.is_nan() || amplitude <= 1e-300 {
            return; // coordinate i does not oscillate: its extremes are at the ends
        }
        let phi = self.v[i].atan2(self.u[i]);
        let dh = (self.h_e - self.h_s) / self.sweep;
        let s = self.a[i] * dh / amplitude;
        if s.is_nan() || s.abs() > 1.0 {
            return; // monotonic
        }
        let last_turn = (self.sweep - TAU).max(0.0);
        for base in [phi + s.asin(), phi + std::f64::consts::PI - s.asin()] {
            let b = base.rem_euclid(TAU);
            if b <= self.sweep {
                out.push(b);
            }
            let n0 = ((last_turn - b) / TAU).ceil().max(1.0);
            for n in [n0, n0 + 1.0] {
                let theta = b + n * TAU;
                if theta >= last_turn && theta <= self.sweep {
                    out.push(theta);
                }
            }
        }
    }

    /// Stationary angles of coordinate `i` found numerically (spiral, module doc).
    fn push_spiral_extrema(&self, i: usize, out: &mut Vec<f64>) {
        let samples = (self.sweep / TAU * SPIRAL_SAMPLES_PER_TURN).ceil() as usize;
        let samples = samples.clamp(16, SPIRAL_MAX_SAMPLES);
        let step = self.sweep / samples as f64;
        let mut lo = 0.0;
        let mut g_lo = self.derivative(i, lo);
        for k in 1..=samples {
            let hi = step * k as f64;
            let g_hi = self.derivative(i, hi);
            if g_hi == 0.0 {
                out.push(hi);
            } else if g_lo * g_hi < 0.0 {
                out.push(self.bisect(i, lo, hi, g_lo));
            }
            lo = hi;
            g_lo = g_hi;
        }
    }

    /// A root of the derivative of coordinate `i` in [lo, hi], where it changes sign.
    fn bisect(&self, i: usize, mut lo: f64, mut hi: f64, mut g_lo: f64) -> f64 {
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let g_mid = self.derivative(i, mid);
            if g_mid == 0.0 {
                return mid;
            }
            if (g_mid < 0.0) == (g_lo < 0.0) {
                lo = mid;
                g_lo = g_mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// Any unit vector perpendicular to the unit vector `a`.
fn perpendicular(a: Vec3) -> Vec3 {
    // Cross with the coordinate axis least aligned with `a`: never near-parallel.
    let k = (0..3)
        .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    normalize(cross(a, e)).unwrap_or([1.0, 0.0, 0.0])
}

impl Helix {
    /// The arc's cylindrical frame (see [`HelixFrame`]).
    pub fn frame(&self) -> HelixFrame {
        let a = normalize(self.axis).unwrap_or([0.0, 0.0, 1.0]);
        let ds = sub(self.start, self.centre);
        let de = sub(self.end, self.centre);
        let (h_s, h_e) = (dot(ds, a), dot(de, a));
        let radial_s = sub(ds, scale(a, h_s));
        let radial_e = sub(de, scale(a, h_e));
        let u = normalize(radial_s)
            .or_else(|| normalize(radial_e))
            .unwrap_or_else(|| perpendicular(a));
        let v = cross(a, u);
        let planar = if norm(sub(radial_e, radial_s)) <= SAME_POINT_MM {
            TAU
        } else {
            positive_angle(dot(radial_e, v).atan2(dot(radial_e, u)))
        };
        let extra_turns = f64::from(self.turns.max(1) - 1);
        Frame {
            centre: self.centre,
            a,
            u,
            v,
            r_s: norm(radial_s),
            r_e: norm(radial_e),
            h_s,
            h_e,
            sweep: planar + extra_turns * TAU,
        }
    }

    /// Total swept angle, radians, > 0.
    pub fn sweep(&self) -> f64 {
        self.frame().sweep
    }

    /// Distance of the start from the axis, mm.
    pub fn start_radius(&self) -> f64 {
        self.frame().r_s
    }

    /// Distance of the end from the axis, mm.
    pub fn end_radius(&self) -> f64 {
        self.frame().r_e
    }

    /// Signed displacement along the axis, end − start, mm.
    pub fn axial_travel(&self) -> f64 {
        let f = self.frame();
        f.h_e - f.h_s
    }

    /// Spatial path length, mm (closed form for helices and spirals; see the module doc).
    pub fn length(&self) -> f64 {
        let f = self.frame();
        let dh = f.h_e - f.h_s;
        let dr = f.r_e - f.r_s;
        if f.is_constant_radius() {
            let r = 0.5 * (f.r_s + f.r_e);
            return (r * f.sweep).hypot(dh);
        }
        let q = dr * dr + dh * dh;
        let sq = q.sqrt();
        let g = |x: f64| 0.5 * (x * (x * x + q).sqrt() + q * (x / sq).asinh());
        (g(f.sweep * f.r_e) - g(f.sweep * f.r_s)) / (f.sweep * dr)
    }

    /// The point at `fraction` of the sweep; 0 gives `start` and 1 gives `end` exactly (clamped).
    pub fn point_at(&self, fraction: f64) -> Vec3 {
        if fraction <= 0.0 {
            return self.start;
        }
        if fraction >= 1.0 {
            return self.end;
        }
        let f = self.frame();
        f.point(fraction * f.sweep)
    }

    /// The tight axis-aligned box `(min, max)` of the arc, mm: the ends plus every extreme of each
    /// coordinate inside the sweep (exact for circles and helices about any axis; numeric for spirals,
    /// see the module doc).
    pub fn bounding_box(&self) -> (Vec3, Vec3) {
        let f = self.frame();
        let mut angles = Vec::new();
        for i in 0..3 {
            if f.is_constant_radius() {
                f.push_helix_extrema(i, &mut angles);
            } else {
                f.push_spiral_extrema(i, &mut angles);
            }
        }
        let mut lo = self.start;
        let mut hi = self.start;
        let points = angles
            .iter()
            .filter(|&&theta| theta > 0.0 && theta < f.sweep)
            .map(|&theta| f.point(theta))
            .chain(std::iter::once(self.end));
        for p in points {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        (lo, hi)
    }

    /// Appends points along the arc, excluding start, including end, so that no chord deviates from
    /// the true arc by more than `chord_tolerance` (mm). Bounded: never more than 100_000 points (a
    /// non-positive or NaN tolerance gets the maximum).
    pub fn tessellate(&self, chord_tolerance: f64, out: &mut Vec<Vec3>) {
        let f = self.frame();
        let tol = if chord_tolerance > 0.0 {
            chord_tolerance
        } else {
            0.0
        };
        let dr = (f.r_e - f.r_s) / f.sweep;
        let curvature_bound = (4.0 * dr * dr + f.r_s.max(f.r_e).powi(2)).sqrt();
        let step = (8.0 * tol / curvature_bound).sqrt();
        // `as` saturates: ∞ → usize::MAX, NaN → 0; the clamp bounds both.
        let n = ((f.sweep / step).ceil() as usize).clamp(1, MAX_TESSELLATION_POINTS);
        out.reserve(n);
        for k in 1..n {
            out.push(f.point(f.sweep * k as f64 / n as f64));
        }
        out.push(self.end);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn xy_arc(start: Vec3, end: Vec3, centre: Vec3, ccw: bool, turns: u32) -> Helix {
        let axis = if ccw {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 0.0, -1.0]
        };
        Helix {
            start,
            end,
            centre,
            axis,
            turns,
        }
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn helix_lengths_of_known_cases() {
        // AxiOMA Ex. 5.14: G02 X0 Y0 Z0 I20 P4 from (0,0,80): 5 turns of r = 20 over 80 mm.
        let h = xy_arc(
            [0.0, 0.0, 80.0],
            [0.0, 0.0, 0.0],
            [20.0, 0.0, 80.0],
            false,
            5,
        );
        assert!(close(h.sweep(), 5.0 * TAU, 1e-12));
        assert!(close(h.axial_travel(), 80.0, 1e-12));
        let expected = (20.0 * 10.0 * PI).hypot(80.0);
        assert!(close(h.length(), expected, 1e-9), "{}", h.length());
        assert!(close(h.length(), 633.391, 5e-4));
        // A quarter circle of r = 20.
        let q = xy_arc([20.0, 0.0, 0.0], [0.0, 20.0, 0.0], [0.0; 3], true, 1);
        assert!(close(q.length(), 31.416, 5e-4));
        assert!(close(q.sweep(), FRAC_PI_2, 1e-15));
        // The same points clockwise: three quarters.
        let q = xy_arc([20.0, 0.0, 0.0], [0.0, 20.0, 0.0], [0.0; 3], false, 1);
        assert!(close(q.sweep(), 3.0 * FRAC_PI_2, 1e-15));
    }

    #[test]
    fn spiral_length_matches_numeric_integration() {
        // From r = 5 to r = 15 in 1.25 turns, rising 7 mm.
        let h = xy_arc([5.0, 0.0, 0.0], [0.0, 15.0, 7.0], [0.0; 3], true, 2);
        assert!(close(h.sweep(), 2.5 * PI, 1e-12));
        let n = 200_000;
        let mut sum = 0.0;
        let mut prev = h.point_at(0.0);
        for k in 1..=n {
            let p = h.point_at(k as f64 / n as f64);
            sum += norm(sub(p, prev));
            prev = p;
        }
        assert!(close(h.length(), sum, 1e-6), "{} vs {}", h.length(), sum);
    }

    #[test]
    fn ends_are_exact_and_full_circle_when_coincident() {
        let h = xy_arc([10.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0; 3], true, 1);
        assert_eq!(h.sweep(), TAU);
        assert_eq!(h.point_at(0.0), h.start);
        assert_eq!(h.point_at(1.0), h.end);
        let mid = h.point_at(0.5);
        assert!(close(mid[0], -10.0, 1e-12) && close(mid[1], 0.0, 1e-12));
    }

    #[test]
    fn bounding_box_of_full_circle_and_quarter() {
        let h = xy_arc(
            [15.0, 5.0, 1.0],
            [15.0, 5.0, 1.0],
            [5.0, 5.0, 1.0],
            false,
            1,
        );
        let (lo, hi) = h.bounding_box();
        for (got, want) in lo.iter().zip([-5.0, -5.0, 1.0]) {
            assert!(close(*got, want, 1e-12), "{lo:?}");
        }
        for (got, want) in hi.iter().zip([15.0, 15.0, 1.0]) {
            assert!(close(*got, want, 1e-12), "{hi:?}");
        }
        // Quarter from (10,0) to (0,10) about the origin, clockwise: bulges to x,y = −10.
        let h = xy_arc([10.0, 0.0, 0.0], [0.0, 10.0, 0.0], [0.0; 3], false, 1);
        let (lo, hi) = h.bounding_box();
        assert!(close(lo[0], -10.0, 1e-12) && close(lo[1], -10.0, 1e-12));
        assert!(close(hi[0], 10.0, 1e-12) && close(hi[1], 10.0, 1e-12));
        // Counter-clockwise it stays in the first quadrant.
        let h = xy_arc([10.0, 0.0, 0.0], [0.0, 10.0, 0.0], [0.0; 3], true, 1);
        let (lo, hi) = h.bounding_box();
        assert_eq!((lo, hi), ([0.0, 0.0, 0.0], [10.0, 10.0, 0.0]));
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        let nan = [f64::NAN; 3];
        let cases = [
            Helix {
                start: [1.0, 0.0, 0.0],
                end: [0.0, 1.0, 0.0],
                centre: [0.0; 3],
                axis: [0.0; 3],
                turns: 0,
            },
            Helix {
                start: [0.0, 0.0, 0.0],
                end: [0.0, 0.0, 5.0],
                centre: [0.0; 3],
                axis: [0.0, 0.0, 1.0],
                turns: 1,
            },
            Helix {
                start: nan,
                end: nan,
                centre: nan,
                axis: nan,
                turns: u32::MAX,
            },
        ];
        for h in cases {
            let _ = (h.sweep(), h.length(), h.bounding_box(), h.point_at(0.3));
            let mut out = Vec::new();
            h.tessellate(0.01, &mut out);
            assert!(!out.is_empty() && out.len() <= MAX_TESSELLATION_POINTS);
            out.clear();
            h.tessellate(f64::NAN, &mut out);
            assert!(out.len() <= MAX_TESSELLATION_POINTS);
        }
    }

    /// Distance from `p` to the segment a–b.
    fn dist_to_segment(p: Vec3, a: Vec3, b: Vec3) -> f64 {
        let ab = sub(b, a);
        let len2 = dot(ab, ab);
        let t = if len2 > 0.0 {
            (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        norm(sub(p, add(a, scale(ab, t))))
    }

    /// Checks the chord error of `h` at `tol` by sampling each chord's stretch of the true curve.
    fn check_tessellation(h: &Helix, tol: f64) -> Result<(), TestCaseError> {
        let mut pts = vec![h.start];
        h.tessellate(tol, &mut pts);
        prop_assert_eq!(*pts.last().unwrap(), h.end);
        let n = pts.len() - 1;
        for seg in 0..n {
            for k in 0..=16 {
                let t = (seg as f64 + k as f64 / 16.0) / n as f64;
                let d = dist_to_segment(h.point_at(t), pts[seg], pts[seg + 1]);
                prop_assert!(
                    d <= tol * (1.0 + 1e-9) + 1e-12,
                    "chord error {} > {}",
                    d,
                    tol
                );
            }
        }
        Ok(())
    }

    fn unit(v: Vec3) -> Vec3 {
        normalize(v).unwrap_or([0.0, 0.0, 1.0])
    }

    proptest! {
        #[test]
        fn tessellation_stays_within_tolerance(
            r_s in 0.1..50.0f64, r_e_rel in 0.8..1.2f64, rise in -30.0..30.0f64,
            end_angle in 0.0..TAU, turns in 1u32..4, tol in 0.001..0.5f64,
            ax in -1.0..1.0f64, ay in -1.0..1.0f64, az in 0.2..1.0f64,
        ) {
            let a = unit([ax, ay, az]);
            let u = unit(cross(a, perpendicular(a)));
            let v = cross(a, u);
            let r_e = r_s * r_e_rel;
            let centre = [3.0, -2.0, 1.0];
            let start = add(centre, scale(u, r_s));
            let end = add(
                add(centre, scale(a, rise)),
                add(scale(u, r_e * end_angle.cos()), scale(v, r_e * end_angle.sin())),
            );
            let h = Helix { start, end, centre, axis: a, turns };
            check_tessellation(&h, tol)?;
        }

        #[test]
        fn bounding_box_contains_the_curve_and_is_tight(
            r in 0.5..50.0f64, r_e_rel in prop_oneof![Just(1.0), 0.5..2.0f64],
            rise in -30.0..30.0f64, end_angle in 0.0..TAU, turns in 1u32..3,
            ax in -1.0..1.0f64, ay in -1.0..1.0f64, az in -1.0..1.0f64,
        ) {
            let a = unit([ax, ay, az]);
            let u = perpendicular(a);
            let v = cross(a, u);
            let centre = [10.0, 20.0, -5.0];
            let start = add(centre, scale(u, r));
            let r_e = r * r_e_rel;
            let end = add(
                add(centre, scale(a, rise)),
                add(scale(u, r_e * end_angle.cos()), scale(v, r_e * end_angle.sin())),
            );
            let h = Helix { start, end, centre, axis: a, turns };
            let (lo, hi) = h.bounding_box();
            let n = 20_000;
            let mut slo = [f64::INFINITY; 3];
            let mut shi = [f64::NEG_INFINITY; 3];
            for k in 0..=n {
                let p = h.point_at(k as f64 / n as f64);
                for i in 0..3 {
                    prop_assert!(p[i] >= lo[i] - 1e-9 && p[i] <= hi[i] + 1e-9,
                        "point {:?} outside box {:?} {:?}", p, lo, hi);
                    slo[i] = slo[i].min(p[i]);
                    shi[i] = shi[i].max(p[i]);
                }
            }
            // Tight: dense sampling gets within the sampling error of every face.
            let slack = 1e-3 * (r + r_e + 1.0);
            for i in 0..3 {
                prop_assert!(slo[i] - lo[i] <= slack && hi[i] - shi[i] <= slack,
                    "box {:?} {:?} not tight vs samples {:?} {:?}", lo, hi, slo, shi);
            }
        }
    }
}
