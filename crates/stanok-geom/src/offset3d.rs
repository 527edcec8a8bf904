//! 3D tool radius compensation geometry (AxiOMA §13, spec axioma-4 §7): where the tool tip Q must
//! be so that a flat, ball or torus (bull-nose) cutter touches a programmed contour point P.
//!
//! Conventions: every vector is in machine X Y Z; `t` is the unit tool vector from the tip towards
//! the holder; `p` the unit contour tangent; `n` the unit surface normal (pointing out of the
//! material, towards the tool); `side` is +1 for G41 (tool left of the path seen along the tool
//! from its base to its tip) and −1 for G42. A cutter is its radius R and its corner radius r
//! (0 flat, R ball, in between torus).
//!
//! ```text
//!  peripheral (CUT3DC):   u = side·unit(t × p)             Q = P + R·u − ISD·t
//!  limiting surface (CC): cos α = n·t > 0, sin α = |n − (n·t)t|
//!                         δ = [r(1 − cos α) + (R − r) sin α − R (n·u)] / cos α
//!                         Q = P + R·u + δ·t
//!  face (CUT3DF/FS/FF):   b = unit(p × n); t' = unit(t − (t·b)b); n⊥ = n − (n·t')t'
//!                         w = unit(n⊥) (0 when n ∥ t');  Q = P + r(n − t') + (R − r)·w
//! ```
//!
//! Corners (spec §7.10, §7.12): peripheral σ = t·(p1 × p2), outer when side·σ < 0; face
//! κ1 = n1·p2, κ2 = n2·p1, outer when κ1 < 0 < κ2. Inner corners are resolved by
//! [`intersect_projected`]: the last crossing of the two compensated tip curves projected on a
//! plane (⟂ t peripheral, span(n1, p1) face). Every function is total: degenerate input gives
//! `None` or a documented fallback, loops are bounded.

use crate::vec3::{add, cross, dot, norm, normalize, scale, sub, Vec3};

/// Parallel / coplanar tolerance of the corner tests (spec A-25).
pub const EPS: f64 = 1e-6;

/// A milling cutter for 3D compensation: radius R and corner radius r (0 ≤ r ≤ R).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cutter {
    /// Cutter radius R, mm.
    pub radius: f64,
    /// Corner (edge rounding) radius r, mm: 0 flat end, R ball end, in between torus.
    pub corner: f64,
}

/// Rodrigues: `v` turned by `angle` (radians) about the unit `axis`, right-handed.
pub fn rotate(v: Vec3, axis: Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    add(
        add(scale(v, c), scale(cross(axis, v), s)),
        scale(axis, dot(axis, v) * (1.0 - c)),
    )
}

/// Great-circle interpolation of unit vectors (the normals of §13.4 "rotate uniformly in the
/// plane of the two vectors"); `None` for antiparallel ends (no plane).
pub fn slerp(a: Vec3, b: Vec3, s: f64) -> Option<Vec3> {
    let c = dot(a, b).clamp(-1.0, 1.0);
    if c > 1.0 - 1e-15 {
        return Some(a);
    }
    let axis = normalize(cross(a, b))?;
    let angle = c.acos();
    Some(rotate(a, axis, angle * s))
}

/// Peripheral offset `Q − P` of CUT3DC: `R·u − isd·t`; `None` when the tool axis is parallel to
/// the path (spec E_3D_OFFSET_UNDEFINED).
pub fn peripheral_offset(p: Vec3, t: Vec3, radius: f64, side: f64, isd: f64) -> Option<Vec3> {
    let u = peripheral_direction(p, t, side)?;
    Some(sub(scale(u, radius), scale(t, isd)))
}

/// `side·unit(t × p)`, the direction from the contour to the tool axis in the plane ⟂ t.
pub fn peripheral_direction(p: Vec3, t: Vec3, side: f64) -> Option<Vec3> {
    let k = cross(t, p);
    if norm(k) < EPS {
        return None;
    }
    normalize(k).map(|u| scale(u, side))
}

/// Axial correction δ of CUT3DCC/CUT3DCCD: the lowest point of the cutter's end touches the
/// plane through P with normal `n` while its side passes through P; `None` when t·n ≤ 0.
pub fn limiting_delta(cutter: Cutter, u: Vec3, t: Vec3, n: Vec3) -> Option<f64> {
    let cos_a = dot(n, t);
    if cos_a <= EPS {
        return None;
    }
    let sin_a = norm(sub(n, scale(t, cos_a)));
    let (big, r) = (cutter.radius, cutter.corner);
    Some((r * (1.0 - cos_a) + (big - r) * sin_a - big * dot(n, u)) / cos_a)
}

/// Offset `Q − P` of CUT3DCC/CUT3DCCD (`None`: tool parallel to the path or not above the
/// surface).
pub fn limiting_offset(p: Vec3, t: Vec3, n: Vec3, cutter: Cutter, side: f64) -> Option<Vec3> {
    let u = peripheral_direction(p, t, side)?;
    let d = limiting_delta(cutter, u, t, n)?;
    Some(add(scale(u, cutter.radius), scale(t, d)))
}

/// Face offset `v = Q − P` of CUT3DF/FS/FF (spec §7.11): the cutter considered in the (p, n)
/// plane.
pub fn face_offset(p: Vec3, t: Vec3, n: Vec3, cutter: Cutter) -> Vec3 {
    let tp = match normalize(cross(p, n)) {
        Some(b) => normalize(sub(t, scale(b, dot(t, b)))).unwrap_or(t),
        None => t,
    };
    let n_perp = sub(n, scale(tp, dot(n, tp)));
    let w = if norm(n_perp) < 1e-12 {
        [0.0; 3]
    } else {
        normalize(n_perp).unwrap_or([0.0; 3])
    };
    add(
        scale(sub(n, tp), cutter.corner),
        scale(w, cutter.radius - cutter.corner),
    )
}

/// What happens where two compensated blocks meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    /// Tangent joint: no corner.
    Smooth,
    /// Convex: a bypass is inserted.
    Outer,
    /// Concave: both blocks are shortened to the crossing of their tip curves.
    Inner,
    /// The tool lies in the plane of the corner, or the normals give no side (error).
    Undetermined,
    /// The surface flips across the corner (face modes, error).
    Flip,
}

/// Peripheral corner type (spec §7.10): `p1` end tangent of the first block, `p2` start tangent
/// of the second, `t` the tool at the joint.
pub fn peripheral_corner(p1: Vec3, p2: Vec3, t: Vec3, side: f64) -> Corner {
    let k = cross(p1, p2);
    if norm(k) <= EPS && dot(p1, p2) > 0.0 {
        return Corner::Smooth;
    }
    let sigma = dot(t, k);
    if sigma.abs() <= EPS {
        return Corner::Undetermined;
    }
    if side * sigma < 0.0 {
        Corner::Outer
    } else {
        Corner::Inner
    }
}

/// Face corner type (spec §7.12) from the tangents and normals at the joint.
pub fn face_corner(p1: Vec3, n1: Vec3, p2: Vec3, n2: Vec3) -> Corner {
    if norm(cross(p1, p2)) <= EPS && dot(p1, p2) > 0.0 && norm(sub(n1, n2)) <= EPS {
        return Corner::Smooth;
    }
    let (k1, k2) = (dot(n1, p2), dot(n2, p1));
    if k1.abs() <= EPS && k2.abs() <= EPS {
        return Corner::Undetermined;
    }
    if k1 <= EPS && k2 >= -EPS {
        Corner::Outer
    } else if k1 >= -EPS && k2 <= EPS {
        Corner::Inner
    } else {
        Corner::Flip
    }
}

/// A programmed path element in machine X Y Z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Curve3 {
    /// Straight line a → b.
    Line {
        /// Start.
        a: Vec3,
        /// End.
        b: Vec3,
    },
    /// Circular (helical) arc: counter-clockwise about the unit `axis` through `centre` by
    /// `sweep` radians from `start`, rising `rise` mm along the axis.
    Arc {
        /// A point of the axis in the plane of `start`.
        centre: Vec3,
        /// Unit rotation axis.
        axis: Vec3,
        /// Start point.
        start: Vec3,
        /// Swept angle, radians (> 0).
        sweep: f64,
        /// Travel along the axis, mm.
        rise: f64,
    },
    /// Cubic Bézier.
    Bezier {
        /// Control points.
        p: [Vec3; 4],
    },
}

impl Curve3 {
    /// The point at parameter `s` ∈ [0, 1].
    pub fn point(&self, s: f64) -> Vec3 {
        match *self {
            Curve3::Line { a, b } => add(a, scale(sub(b, a), s)),
            Curve3::Arc {
                centre,
                axis,
                start,
                sweep,
                rise,
            } => add(
                add(centre, rotate(sub(start, centre), axis, sweep * s)),
                scale(axis, rise * s),
            ),
            Curve3::Bezier { p } => {
                let u = 1.0 - s;
                let w = [u * u * u, 3.0 * u * u * s, 3.0 * u * s * s, s * s * s];
                (0..4).fold([0.0; 3], |acc, i| add(acc, scale(p[i], w[i])))
            }
        }
    }

    /// The derivative dP/ds.
    pub fn derivative(&self, s: f64) -> Vec3 {
        match *self {
            Curve3::Line { a, b } => sub(b, a),
            Curve3::Arc {
                centre,
                axis,
                start,
                sweep,
                rise,
            } => {
                let r = rotate(sub(start, centre), axis, sweep * s);
                add(scale(cross(axis, r), sweep), scale(axis, rise))
            }
            Curve3::Bezier { p } => {
                let u = 1.0 - s;
                let w = [
                    -3.0 * u * u,
                    3.0 * u * (1.0 - 3.0 * s),
                    3.0 * s * (2.0 - 3.0 * s),
                    3.0 * s * s,
                ];
                (0..4).fold([0.0; 3], |acc, i| add(acc, scale(p[i], w[i])))
            }
        }
    }

    /// The unit tangent at `s` (`None` where the curve stands still).
    pub fn tangent(&self, s: f64) -> Option<Vec3> {
        let d = self.derivative(s);
        if norm(d) < 1e-12 {
            // A Bézier with a doubled end control point: look a little inside.
            let inner = if s < 0.5 { s + 1e-6 } else { s - 1e-6 };
            return normalize(self.derivative(inner));
        }
        normalize(d)
    }

    /// Approximate length (exact for lines and arcs).
    pub fn length(&self) -> f64 {
        match *self {
            Curve3::Line { a, b } => norm(sub(b, a)),
            Curve3::Arc {
                centre,
                start,
                sweep,
                rise,
                ..
            } => (norm(sub(start, centre)) * sweep).hypot(rise),
            Curve3::Bezier { .. } => {
                let mut len = 0.0;
                let mut prev = self.point(0.0);
                for i in 1..=32 {
                    let q = self.point(i as f64 / 32.0);
                    len += norm(sub(q, prev));
                    prev = q;
                }
                len
            }
        }
    }
}

/// Samples per curve in the crossing search of [`intersect_projected`].
const SAMPLES: usize = 96;

/// The crossing of two space curves projected on the plane spanned by the orthonormal `e1`, `e2`:
/// the parameters (s*, σ*) with π(c1(s*)) = π(c2(σ*)), s* ∈ [s0, 1] as large as possible, then σ*
/// as small as possible (the crossing nearest the joint). A polyline search finds the pair of
/// chords that cross, Newton's method refines it to 1e-12 (bounded: 40 steps). `None` when the
/// projections do not cross.
pub fn intersect_projected(
    c1: &dyn Fn(f64) -> Vec3,
    s0: f64,
    c2: &dyn Fn(f64) -> Vec3,
    e1: Vec3,
    e2: Vec3,
) -> Option<(f64, f64)> {
    let proj = |v: Vec3| [dot(v, e1), dot(v, e2)];
    let pa: Vec<(f64, [f64; 2])> = (0..=SAMPLES)
        .map(|i| {
            let s = s0 + (1.0 - s0) * i as f64 / SAMPLES as f64;
            (s, proj(c1(s)))
        })
        .collect();
    let pb: Vec<(f64, [f64; 2])> = (0..=SAMPLES)
        .map(|i| {
            let s = i as f64 / SAMPLES as f64;
            (s, proj(c2(s)))
        })
        .collect();
    let mut best: Option<(f64, f64)> = None;
    for i in (0..SAMPLES).rev() {
        for j in 0..SAMPLES {
            if let Some((x, y)) = seg_cross(pa[i].1, pa[i + 1].1, pb[j].1, pb[j + 1].1) {
                let s = pa[i].0 + x * (pa[i + 1].0 - pa[i].0);
                let sg = pb[j].0 + y * (pb[j + 1].0 - pb[j].0);
                best = Some((s, sg));
                break;
            }
        }
        if best.is_some() {
            break;
        }
    }
    let (mut s, mut sg) = best?;
    // Newton on F(s, σ) = π(c1(s)) − π(c2(σ)).
    let f = |s: f64, sg: f64| {
        let a = proj(c1(s));
        let b = proj(c2(sg));
        [a[0] - b[0], a[1] - b[1]]
    };
    for _ in 0..40 {
        let r = f(s, sg);
        if r[0].hypot(r[1]) < 1e-13 {
            break;
        }
        let h = 1e-7;
        let ds = {
            let (p, m) = (f(s + h, sg), f(s - h, sg));
            [(p[0] - m[0]) / (2.0 * h), (p[1] - m[1]) / (2.0 * h)]
        };
        let dg = {
            let (p, m) = (f(s, sg + h), f(s, sg - h));
            [(p[0] - m[0]) / (2.0 * h), (p[1] - m[1]) / (2.0 * h)]
        };
        let det = ds[0] * dg[1] - ds[1] * dg[0];
        if det.abs() < 1e-18 {
            break;
        }
        let step_s = (r[0] * dg[1] - r[1] * dg[0]) / det;
        let step_g = (ds[0] * r[1] - ds[1] * r[0]) / det;
        s -= step_s;
        sg -= step_g;
    }
    if !(s.is_finite() && sg.is_finite()) {
        return None;
    }
    let tol = 1e-9;
    if s < s0 - tol || s > 1.0 + tol || sg < -tol || sg > 1.0 + tol {
        return None;
    }
    Some((s.clamp(s0, 1.0), sg.clamp(0.0, 1.0)))
}

/// Parameters (x, y) ∈ [0,1]² where chord a0a1 crosses chord b0b1, if it does.
fn seg_cross(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> Option<(f64, f64)> {
    let d1 = [a1[0] - a0[0], a1[1] - a0[1]];
    let d2 = [b1[0] - b0[0], b1[1] - b0[1]];
    let den = d1[0] * d2[1] - d1[1] * d2[0];
    if den.abs() < 1e-18 {
        return None;
    }
    let w = [b0[0] - a0[0], b0[1] - a0[1]];
    let x = (w[0] * d2[1] - w[1] * d2[0]) / den;
    let y = (w[0] * d1[1] - w[1] * d1[0]) / den;
    let e = 1e-12;
    ((-e..=1.0 + e).contains(&x) && (-e..=1.0 + e).contains(&y)).then_some((x, y))
}

/// An orthonormal basis (e1, e2) of the plane with unit normal `n`.
pub fn plane_basis(n: Vec3) -> (Vec3, Vec3) {
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = normalize(cross(n, helper)).unwrap_or([1.0, 0.0, 0.0]);
    let e2 = cross(n, e1);
    (e1, e2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3, tol: f64) -> bool {
        norm(sub(a, b)) < tol
    }

    #[test]
    fn peripheral_left_of_x_is_plus_y() {
        let q = peripheral_offset([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 5.0, 1.0, 2.0).unwrap();
        assert!(close(q, [0.0, 5.0, -2.0], 1e-12));
        assert!(peripheral_offset([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], 5.0, 1.0, 0.0).is_none());
    }

    #[test]
    fn limiting_delta_checks_of_the_spec() {
        let c = Cutter {
            radius: 5.0,
            corner: 0.0,
        };
        let z = [0.0, 0.0, 1.0];
        // t ∥ n: δ = 0.
        let u = [0.0, 1.0, 0.0];
        assert!(limiting_delta(c, u, z, z).unwrap().abs() < 1e-12);
        // Flat tool tilted by λ along the wall (in the plane of p and t), floor horizontal: δ = R tan λ.
        let l = 0.3f64;
        let t = [l.sin(), 0.0, l.cos()];
        let u = peripheral_direction([1.0, 0.0, 0.0], t, 1.0).unwrap();
        let d = limiting_delta(c, u, t, z).unwrap();
        assert!((d - 5.0 * l.tan()).abs() < 1e-12, "{d}");
        // Tilted away from the wall (G41, wall at −u side) by τ: δ = 2R tan τ.
        let tau = 0.2f64;
        let t = [0.0, tau.sin(), tau.cos()];
        let u = peripheral_direction([1.0, 0.0, 0.0], t, 1.0).unwrap();
        let d = limiting_delta(c, u, t, z).unwrap();
        assert!((d - 2.0 * 5.0 * tau.tan()).abs() < 1e-12, "{d}");
    }

    #[test]
    fn face_offset_ball_flat_and_parallel() {
        let n = normalize([-1.0, 0.0, 1.0]).unwrap();
        let p = normalize([1.0, 0.0, 1.0]).unwrap();
        let t = [0.0, 0.0, 1.0];
        let ball = Cutter {
            radius: 5.0,
            corner: 5.0,
        };
        assert!(close(
            face_offset(p, t, n, ball),
            [-3.535533905932738, 0.0, -1.4644660940672627],
            1e-12
        ));
        let flat = Cutter {
            radius: 5.0,
            corner: 0.0,
        };
        assert!(close(face_offset(p, t, n, flat), [-5.0, 0.0, 0.0], 1e-12));
        assert!(close(
            face_offset([1.0, 0.0, 0.0], t, t, ball),
            [0.0; 3],
            1e-12
        ));
    }

    #[test]
    fn corners_of_example_13_2_and_13_3() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let z = [0.0, 0.0, 1.0];
        assert_eq!(
            peripheral_corner([s, s, 0.0], [s, -s, 0.0], z, 1.0),
            Corner::Outer
        );
        assert_eq!(
            peripheral_corner([s, s, 0.0], [s, -s, 0.0], z, -1.0),
            Corner::Inner
        );
        assert_eq!(
            peripheral_corner([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], z, 1.0),
            Corner::Smooth
        );
        assert_eq!(
            face_corner([s, 0.0, s], [-s, 0.0, s], [s, 0.0, -s], [s, 0.0, s]),
            Corner::Outer
        );
        assert_eq!(
            face_corner([s, 0.0, -s], [s, 0.0, s], [s, 0.0, s], [-s, 0.0, s]),
            Corner::Inner
        );
        assert_eq!(
            face_corner(
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0, 0.0, 0.0]
            ),
            Corner::Flip
        );
    }

    #[test]
    fn arc_points_and_tangents() {
        let arc = Curve3::Arc {
            centre: [100.0, 0.0, 0.0],
            axis: [0.0, 1.0, 0.0],
            start: [90.0, 0.0, 0.0],
            sweep: std::f64::consts::FRAC_PI_2,
            rise: 0.0,
        };
        assert!(close(arc.point(1.0), [100.0, 0.0, 10.0], 1e-12));
        assert!(close(arc.tangent(0.0).unwrap(), [0.0, 0.0, 1.0], 1e-12));
        assert!((arc.length() - 5.0 * std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn slerp_midpoint_of_example_13_4() {
        let a = normalize([-0.6, 0.0, 0.8]).unwrap();
        let m = slerp(a, [0.0, 0.0, 1.0], 0.5).unwrap();
        assert!(close(m, [-0.316227766, 0.0, 0.948683298], 1e-9));
        assert!(slerp([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 0.5).is_none());
    }

    #[test]
    fn crossing_of_two_lines() {
        let l1 = |s: f64| [s * 10.0, 1.0, 0.0];
        let l2 = |s: f64| [8.0, 5.0 - 10.0 * s, 3.0];
        let (s, g) = intersect_projected(&l1, 0.0, &l2, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]).unwrap();
        assert!((s - 0.8).abs() < 1e-12 && (g - 0.4).abs() < 1e-12);
    }
}
