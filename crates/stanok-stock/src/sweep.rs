//! The swept volume of a tool moving straight, cut by a line: the one geometric question the
//! material models ask.
//!
//! ## The tool
//! A tool is a stack of convex solids of revolution about its axis ([`Prim`]): cone frustums
//! (cylinders when both radii agree; a drill point when the lower radius is 0) and spheres (a
//! ball end). Heights `h` are measured along the axis from the tip. A bull-nose corner is a few
//! frustums inscribed in its torus (`tool.rs`, within a sagitta of a tenth of the resolution).
//!
//! ## The sweep
//! Between two consecutive model updates the tool translates: tip `p(t) = p0 + t·d`, t ∈ [0, 1],
//! axis `a` fixed (a rotating axis is cut into sub-steps small enough that its far end moves
//! less than the tolerance, `sim.rs`). A translated convex solid sweeps a convex solid (the
//! Minkowski sum with the segment), so its intersection with a line is one interval: the set of
//! `s` for which the point `o + s·u` lies in the solid at some `t`.
//!
//! ## The generic solution ([`chord`])
//! With `w(s, t) = o + s·u − p0 − t·d`, height `h = w·a` and radial vector `w⊥ = w − h·a` are affine
//! in (s, t). A frustum is `|w⊥|² ≤ r(h)²` with `h0 ≤ h ≤ h1`; a sphere `|w − hc·a|² ≤ r²`. So in
//! the (s, t) plane the swept primitive is a convex region bounded by one quadric `Q(s, t) ≤ 0` and
//! straight lines (`t = 0`, `t = 1`, `h = h0`, `h = h1`). Its extent in `s` is attained at one of:
//! a vertex of the lines inside the quadric; a crossing of a line with `Q = 0`; or a point of
//! `Q = 0` where its tangent is parallel to the t axis (`∂Q/∂t = 0`). All three are closed-form
//! (2×2 solves and quadratics); the chord is the smallest and largest `s` among the candidates that
//! satisfy every constraint (tolerance [`EPS`]).
//!
//! ## The vertical fast path ([`chord_vertical`])
//! On a 3-axis machine the axis is +Z and the model's lines are vertical. Then a line at `(x, y)`
//! is at horizontal distance `ρ(t) = |c − t·e|` from the axis (c = (x, y) − p0, e = d's XY part),
//! the primitive covers heights `[lo(ρ), hi(ρ)]` there, and the chord is
//! `[min_t (t·dz + lo(ρ(t))), max_t (t·dz + hi(ρ(t)))] + p0z` over the t where `ρ(t) ≤ r_max`. `lo`
//! is convex and `hi` concave in ρ, so each extreme is at an end of that t interval, where ρ
//! crosses a kink of the profile, or at the stationary point of the smooth part (a closed form per
//! primitive, below). `tests::vertical_path_agrees_with_the_generic_solution` holds the two
//! together.

use crate::vec3::{dot, sub, V3};

/// Tolerance of the constraint checks in the generic solution, mm (and mm² for quadrics, scaled).
pub const EPS: f64 = 1e-9;

/// A convex solid of revolution about the tool axis, in the tool frame (h from the tip).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Prim {
    /// A cone frustum between heights `h0 < h1`, radius `r0` at `h0` and `r1` at `h1` (both ≥ 0):
    /// a cylinder when they agree.
    Frustum {
        /// Lower height, mm.
        h0: f64,
        /// Upper height, mm.
        h1: f64,
        /// Radius at `h0`, mm.
        r0: f64,
        /// Radius at `h1`, mm.
        r1: f64,
    },
    /// A sphere of radius `r` centred on the axis at height `hc`.
    Sphere {
        /// Height of the centre, mm.
        hc: f64,
        /// Radius, mm.
        r: f64,
    },
}

impl Prim {
    /// A cylinder of radius `r` between two heights.
    pub fn cylinder(h0: f64, h1: f64, r: f64) -> Prim {
        Prim::Frustum {
            h0,
            h1,
            r0: r,
            r1: r,
        }
    }

    /// Largest distance of a point of the primitive from the axis, mm.
    pub fn max_radius(&self) -> f64 {
        match *self {
            Prim::Frustum { r0, r1, .. } => r0.max(r1),
            Prim::Sphere { r, .. } => r,
        }
    }

    /// Lowest and highest height along the axis, mm.
    pub fn heights(&self) -> (f64, f64) {
        match *self {
            Prim::Frustum { h0, h1, .. } => (h0, h1),
            Prim::Sphere { hc, r } => (hc - r, hc + r),
        }
    }
}

/// A straight motion of a tool: tip from `p0` to `p0 + d`, unit axis `axis` (tip → holder).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweep {
    /// Tip at the start, mm.
    pub p0: V3,
    /// Displacement of the tip, mm.
    pub d: V3,
    /// Unit tool axis.
    pub axis: V3,
}

/// `Q(s, t) = ss·s² + 2·st·s·t + tt·t² + 2·s1·s + 2·t1·t + c`.
#[derive(Debug, Clone, Copy)]
struct Quad {
    ss: f64,
    st: f64,
    tt: f64,
    s1: f64,
    t1: f64,
    c: f64,
}

impl Quad {
    #[inline]
    fn at(&self, s: f64, t: f64) -> f64 {
        self.ss * s * s
            + 2.0 * self.st * s * t
            + self.tt * t * t
            + 2.0 * self.s1 * s
            + 2.0 * self.t1 * t
            + self.c
    }

    /// The quadratic along the line `(s, t) = (s0 + σ·ds, t0 + σ·dt)`: coefficients of σ², σ, 1.
    #[inline]
    fn along(&self, s0: f64, t0: f64, ds: f64, dt: f64) -> (f64, f64, f64) {
        let a = self.ss * ds * ds + 2.0 * self.st * ds * dt + self.tt * dt * dt;
        let b = 2.0
            * (self.ss * s0 * ds
                + self.st * (s0 * dt + t0 * ds)
                + self.tt * t0 * dt
                + self.s1 * ds
                + self.t1 * dt);
        (a, b, self.at(s0, t0))
    }
}

/// A half-plane `a·s + b·t + c ≤ 0`.
#[derive(Debug, Clone, Copy)]
struct Lin {
    a: f64,
    b: f64,
    c: f64,
}

impl Lin {
    #[inline]
    fn at(&self, s: f64, t: f64) -> f64 {
        self.a * s + self.b * t + self.c
    }
}

/// Real roots of `a·x² + b·x + c` (a linear or constant polynomial gives its own roots).
#[inline]
fn roots(a: f64, b: f64, c: f64, out: &mut [f64; 2]) -> usize {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 || !scale.is_finite() {
        return 0;
    }
    if a.abs() <= 1e-14 * scale {
        if b.abs() <= 1e-14 * scale {
            return 0;
        }
        out[0] = -c / b;
        return 1;
    }
    let disc = b * b - 4.0 * a * c;
    // A tangency within rounding still counts (a chord that degenerates to a point).
    if disc < -1e-9 * (b * b + (4.0 * a * c).abs()) {
        return 0;
    }
    let sq = disc.max(0.0).sqrt();
    // The numerically stable pair.
    let q = -0.5 * (b + b.signum() * sq);
    if q == 0.0 {
        out[0] = 0.0;
        return 1;
    }
    out[0] = q / a;
    out[1] = c / q;
    2
}

/// The s extent of `{Q ≤ 0} ∩ {every lin ≤ 0}` (module doc), or None if it is empty.
fn s_range(q: &Quad, lins: &[Lin], qscale: f64) -> Option<(f64, f64)> {
    let qtol = EPS * qscale.max(1.0);
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let inside = |s: f64, t: f64, skip: [usize; 2]| -> bool {
        if !(s.is_finite() && t.is_finite()) {
            return false;
        }
        lins.iter()
            .enumerate()
            .all(|(k, l)| skip.contains(&k) || l.at(s, t) <= EPS * (1.0 + s.abs()))
    };
    let mut take = |s: f64| {
        lo = lo.min(s);
        hi = hi.max(s);
    };
    // (1) Vertices of the lines inside the quadric.
    for i in 0..lins.len() {
        for j in i + 1..lins.len() {
            let (l1, l2) = (lins[i], lins[j]);
            let det = l1.a * l2.b - l1.b * l2.a;
            if det.abs() < 1e-14 {
                continue;
            }
            let s = (-l1.c * l2.b + l1.b * l2.c) / det;
            let t = (-l1.a * l2.c + l1.c * l2.a) / det;
            if q.at(s, t) <= qtol && inside(s, t, [i, j]) {
                take(s);
            }
        }
    }
    // (2) Each line against Q = 0.
    let mut r = [0.0; 2];
    for (i, l) in lins.iter().enumerate() {
        // A point on the line and its direction.
        let (s0, t0, ds, dt) = if l.b.abs() >= l.a.abs() {
            (0.0, -l.c / l.b, 1.0, -l.a / l.b)
        } else {
            (-l.c / l.a, 0.0, -l.b / l.a, 1.0)
        };
        let (a, b, c) = q.along(s0, t0, ds, dt);
        let n = roots(a, b, c, &mut r);
        for &x in &r[..n] {
            let (s, t) = (s0 + x * ds, t0 + x * dt);
            if inside(s, t, [i, usize::MAX]) {
                take(s);
            }
        }
    }
    // (3) Points of Q = 0 with a tangent parallel to t: ∂Q/∂t = st·s + tt·t + t1 = 0.
    let (a, b, c) = (q.st, q.tt, q.t1);
    if a.abs() > 1e-14 || b.abs() > 1e-14 {
        let (s0, t0, ds, dt) = if b.abs() >= a.abs() {
            (0.0, -c / b, 1.0, -a / b)
        } else {
            (-c / a, 0.0, -b / a, 1.0)
        };
        let (qa, qb, qc) = q.along(s0, t0, ds, dt);
        let n = roots(qa, qb, qc, &mut r);
        for &x in &r[..n] {
            let (s, t) = (s0 + x * ds, t0 + x * dt);
            if inside(s, t, [usize::MAX, usize::MAX]) {
                take(s);
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The interval of `s` for which `o + s·u` lies in `prim` swept along `sweep` (module doc).
pub fn chord(prim: &Prim, sweep: &Sweep, o: V3, u: V3) -> Option<(f64, f64)> {
    let a = sweep.axis;
    let d = sweep.d;
    let w0 = sub(o, sweep.p0);
    let t_lines = [
        Lin {
            a: 0.0,
            b: -1.0,
            c: 0.0,
        },
        Lin {
            a: 0.0,
            b: 1.0,
            c: -1.0,
        },
    ];
    match *prim {
        Prim::Sphere { hc, r } => {
            // |W0 + s·u − t·d|² − r², W0 = w0 − hc·a.
            let wc = sub(w0, crate::vec3::scale(a, hc));
            let q = Quad {
                ss: dot(u, u),
                st: -dot(u, d),
                tt: dot(d, d),
                s1: dot(wc, u),
                t1: -dot(wc, d),
                c: dot(wc, wc) - r * r,
            };
            s_range(&q, &t_lines, r * r)
        }
        Prim::Frustum { h0, h1, r0, r1 } => {
            let (ua, da, hw0) = (dot(u, a), dot(d, a), dot(w0, a));
            let perp = |v: V3, va: f64| sub(v, crate::vec3::scale(a, va));
            let (aa, bb, c0) = (perp(u, ua), perp(d, da), perp(w0, hw0));
            let k = if h1 > h0 { (r1 - r0) / (h1 - h0) } else { 0.0 };
            // r(h) = m0 + s·(k·ua) − t·(k·da)
            let m0 = r0 + k * (hw0 - h0);
            let (ms, mt) = (k * ua, -k * da);
            let q = Quad {
                ss: dot(aa, aa) - ms * ms,
                st: -dot(aa, bb) - ms * mt,
                tt: dot(bb, bb) - mt * mt,
                s1: dot(c0, aa) - m0 * ms,
                t1: -dot(c0, bb) - m0 * mt,
                c: dot(c0, c0) - m0 * m0,
            };
            // h0 − h ≤ 0 and h − h1 ≤ 0 with h = hw0 + s·ua − t·da.
            let lins = [
                t_lines[0],
                t_lines[1],
                Lin {
                    a: -ua,
                    b: da,
                    c: h0 - hw0,
                },
                Lin {
                    a: ua,
                    b: -da,
                    c: hw0 - h1,
                },
            ];
            let rmax = r0.max(r1);
            s_range(&q, &lins, rmax * rmax)
        }
    }
}

/// The t interval within [0, 1] where a vertical line is within `rad` of the moving axis:
/// `|c − t·e| ≤ rad` (module doc).
#[inline]
fn t_within(c: [f64; 2], e: [f64; 2], rad: f64) -> Option<(f64, f64)> {
    let ee = e[0] * e[0] + e[1] * e[1];
    let cc = c[0] * c[0] + c[1] * c[1];
    if ee < 1e-18 {
        return (cc <= rad * rad).then_some((0.0, 1.0));
    }
    let ce = c[0] * e[0] + c[1] * e[1];
    let t_star = ce / ee;
    let rho_min2 = (cc - ce * t_star).max(0.0);
    if rho_min2 > rad * rad {
        return None;
    }
    let w = ((rad * rad - rho_min2) / ee).sqrt();
    let (ta, tb) = ((t_star - w).max(0.0), (t_star + w).min(1.0));
    (ta <= tb).then_some((ta, tb))
}

/// Everything about one vertical line and one sweep that the primitives share.
#[derive(Debug, Clone, Copy)]
struct Across {
    c: [f64; 2],
    e: [f64; 2],
    dz: f64,
    ee: f64,
    t_star: f64,
    rho_min2: f64,
}

impl Across {
    #[inline]
    fn rho(&self, t: f64) -> f64 {
        let x = self.c[0] - t * self.e[0];
        let y = self.c[1] - t * self.e[1];
        (x * x + y * y).sqrt()
    }

    /// The t (in [ta, tb]) where ρ(t) = `r`, as candidates.
    #[inline]
    fn crossings(&self, r: f64, ta: f64, tb: f64, out: &mut impl FnMut(f64)) {
        if self.ee < 1e-18 || r * r < self.rho_min2 {
            return;
        }
        let w = ((r * r - self.rho_min2) / self.ee).sqrt();
        for t in [self.t_star - w, self.t_star + w] {
            if t >= ta && t <= tb {
                out(t);
            }
        }
    }
}

/// Extreme over t ∈ [ta, tb] of `t·dz + sign·slope·max(0, ρ(t) − rk)`: the lower surface of a
/// widening frustum (sign +1, minimised) or the upper surface of a narrowing one (sign −1,
/// maximised). Convex (resp. concave) in t: ends, the kink ρ = rk, and the stationary point of
/// `t·dz + sign·slope·ρ(t)`, where `E·u = −sign·(dz/slope)·ρ` (u = t − t*).
#[inline]
fn cone_extreme(x: &Across, ta: f64, tb: f64, rk: f64, slope: f64, sign: f64) -> f64 {
    let f = |t: f64| t * x.dz + sign * slope * (x.rho(t) - rk).max(0.0);
    let better = |a: f64, b: f64| if sign > 0.0 { a.min(b) } else { a.max(b) };
    let mut best = better(f(ta), f(tb));
    x.crossings(rk, ta, tb, &mut |t| best = better(best, f(t)));
    if x.ee >= 1e-18 && slope > 0.0 {
        let g = x.dz / slope;
        if x.ee > g * g {
            let u =
                -sign * g.signum() * g.abs() * x.rho_min2.sqrt() / (x.ee * (x.ee - g * g)).sqrt();
            let t = x.t_star + u;
            if t >= ta && t <= tb {
                best = better(best, f(t));
            }
        }
    }
    best
}

/// Extreme over t ∈ [ta, tb] of `t·dz + sign·√(r² − ρ(t)²)` (a sphere's upper surface, sign +1,
/// maximised; lower, sign −1, minimised): the stationary point has
/// `u² = dz²·(r² − ρ_min²) / (E·(E + dz²))` with u of the sign of `sign·dz`.
#[inline]
fn sphere_extreme(x: &Across, ta: f64, tb: f64, r: f64, sign: f64) -> f64 {
    let f = |t: f64| t * x.dz + sign * (r * r - x.rho(t).powi(2)).max(0.0).sqrt();
    let better = |a: f64, b: f64| if sign < 0.0 { a.min(b) } else { a.max(b) };
    let mut best = better(f(ta), f(tb));
    if x.ee >= 1e-18 {
        let u2 = x.dz * x.dz * (r * r - x.rho_min2).max(0.0) / (x.ee * (x.ee + x.dz * x.dz));
        let t = x.t_star + sign * x.dz.signum() * u2.sqrt();
        if t >= ta && t <= tb {
            best = better(best, f(t));
        }
    }
    best
}

/// [`chord`] for a vertical axis (+Z) and the vertical line through `(x, y)`: the z interval
/// (module doc, fast path).
#[inline]
pub fn chord_vertical(prim: &Prim, sweep: &Sweep, x: f64, y: f64) -> Option<(f64, f64)> {
    let (p, d) = (sweep.p0, sweep.d);
    let c = [x - p[0], y - p[1]];
    let e = [d[0], d[1]];
    let (ta, tb) = t_within(c, e, prim.max_radius())?;
    let ee = e[0] * e[0] + e[1] * e[1];
    let (t_star, rho_min2) = if ee < 1e-18 {
        (0.0, c[0] * c[0] + c[1] * c[1])
    } else {
        let ts = (c[0] * e[0] + c[1] * e[1]) / ee;
        (ts, (c[0] * c[0] + c[1] * c[1] - ts * ts * ee).max(0.0))
    };
    let x = Across {
        c,
        e,
        dz: d[2],
        ee,
        t_star,
        rho_min2,
    };
    let linear_min = (ta * x.dz).min(tb * x.dz);
    let linear_max = (ta * x.dz).max(tb * x.dz);
    let (lo, hi) = match *prim {
        Prim::Frustum { h0, h1, r0, r1 } => {
            let dh = h1 - h0;
            if r1 > r0 {
                let lo = h0 + cone_extreme(&x, ta, tb, r0, dh / (r1 - r0), 1.0);
                (lo, h1 + linear_max)
            } else if r1 < r0 {
                let hi = h1 + cone_extreme(&x, ta, tb, r1, dh / (r0 - r1), -1.0);
                (h0 + linear_min, hi)
            } else {
                (h0 + linear_min, h1 + linear_max)
            }
        }
        Prim::Sphere { hc, r } => (
            hc + sphere_extreme(&x, ta, tb, r, -1.0),
            hc + sphere_extreme(&x, ta, tb, r, 1.0),
        ),
    };
    (lo <= hi).then_some((p[2] + lo, p[2] + hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn prim() -> impl Strategy<Value = Prim> {
        prop_oneof![
            (0.0..20.0f64, 0.1..30.0f64, 0.0..8.0f64, 0.0..8.0f64).prop_map(|(h0, len, r0, r1)| {
                Prim::Frustum {
                    h0,
                    h1: h0 + len,
                    r0,
                    r1: if r0 == 0.0 && r1 == 0.0 { 1.0 } else { r1 },
                }
            }),
            (0.0..20.0f64, 0.1..8.0f64).prop_map(|(hc, r)| Prim::Sphere { hc, r }),
            (0.0..8.0f64).prop_map(|r| Prim::cylinder(0.0, 25.0, r.max(0.05))),
        ]
    }

    fn v3(r: f64) -> impl Strategy<Value = V3> {
        proptest::array::uniform3(-r..r)
    }

    /// A dense reference: the chord at fixed poses (the generic solution with d = 0) at many t.
    fn sampled(prim: &Prim, sw: &Sweep, o: V3, u: V3, n: usize) -> Option<(f64, f64)> {
        let mut out: Option<(f64, f64)> = None;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            let at = Sweep {
                p0: crate::vec3::lerp(sw.p0, crate::vec3::add(sw.p0, sw.d), t),
                d: [0.0; 3],
                axis: sw.axis,
            };
            if let Some((a, b)) = chord(prim, &at, o, u) {
                out = Some(out.map_or((a, b), |(x, y)| (x.min(a), y.max(b))));
            }
        }
        out
    }

    #[test]
    fn a_cylinder_through_its_axis_and_across() {
        let p = Prim::cylinder(0.0, 20.0, 3.0);
        let sw = Sweep {
            p0: [0.0, 0.0, -5.0],
            d: [10.0, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
        };
        // Vertical line inside the slot: the whole height.
        assert_eq!(
            chord(&p, &sw, [5.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            Some((-5.0, 15.0))
        );
        assert_eq!(chord_vertical(&p, &sw, 5.0, 1.0), Some((-5.0, 15.0)));
        // A line along X at z = 0, y = 2: from −√5 to 10 + √5.
        let (a, b) = chord(&p, &sw, [0.0, 2.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((a + 5f64.sqrt()).abs() < 1e-9 && (b - 10.0 - 5f64.sqrt()).abs() < 1e-9);
        assert_eq!(chord_vertical(&p, &sw, 5.0, 3.5), None);
    }

    #[test]
    fn a_ball_moving_down_and_across_is_a_capsule() {
        // Ball r = 2 centred 2 above the tip, tip from (0,0,0) to (10,0,−5).
        let p = Prim::Sphere { hc: 2.0, r: 2.0 };
        let sw = Sweep {
            p0: [0.0; 3],
            d: [10.0, 0.0, -5.0],
            axis: [0.0, 0.0, 1.0],
        };
        // The capsule's axis from (0,0,2) to (10,0,−3): at x = 5 its centre is at z = −0.5 and the
        // vertical chord is ±r/cos(α), tan α = 1/2.
        let half = 2.0 * (1.0f64 + 0.25).sqrt();
        let (a, b) = chord_vertical(&p, &sw, 5.0, 0.0).unwrap();
        assert!(
            (a - (-0.5 - half)).abs() < 1e-9 && (b - (-0.5 + half)).abs() < 1e-9,
            "{a} {b}"
        );
        let (a2, b2) = chord(&p, &sw, [5.0, 0.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
        assert!((a2 - a).abs() < 1e-9 && (b2 - b).abs() < 1e-9);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn vertical_path_agrees_with_the_generic_solution(
            pr in prim(), p0 in v3(10.0), d in v3(12.0), xy in proptest::array::uniform2(-20.0..20.0f64),
        ) {
            let sw = Sweep { p0, d, axis: [0.0, 0.0, 1.0] };
            let fast = chord_vertical(&pr, &sw, xy[0], xy[1]);
            let slow = chord(&pr, &sw, [xy[0], xy[1], 0.0], [0.0, 0.0, 1.0]);
            match (fast, slow) {
                (Some((a, b)), Some((c, e))) => {
                    prop_assert!((a - c).abs() < 1e-6 && (b - e).abs() < 1e-6, "{fast:?} {slow:?}");
                }
                (None, None) => {}
                // A chord of (near) zero length at a tangency may be found by one and not the other.
                (Some((a, b)), None) | (None, Some((a, b))) => prop_assert!(b - a < 1e-4, "{fast:?} {slow:?}"),
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        #[test]
        fn generic_chord_bounds_the_poses_it_sweeps(
            pr in prim(), p0 in v3(10.0), d in v3(10.0), axis in v3(1.0), o in v3(15.0), u in v3(1.0),
        ) {
            let (Some(axis), Some(u)) = (crate::vec3::unit(axis), crate::vec3::unit(u)) else {
                return Ok(());
            };
            let sw = Sweep { p0, d, axis };
            let n = 4000;
            let got = chord(&pr, &sw, o, u);
            let dense = sampled(&pr, &sw, o, u, n);
            // Sampling t can only find less; near a tangency the chord grows like √Δt.
            let r = pr.max_radius() + 1.0;
            let slack = (2.0 * r * crate::vec3::norm(d) / n as f64).sqrt() * 3.0 + 1e-6;
            match (got, dense) {
                (Some((a, b)), Some((c, e))) => {
                    prop_assert!(a <= c + 1e-6 && b >= e - 1e-6, "{got:?} ⊉ {dense:?}");
                    prop_assert!(c - a <= slack && b - e <= slack, "{got:?} vs {dense:?} ({slack})");
                }
                (None, Some((c, e))) => prop_assert!(e - c < 1e-4, "missed {dense:?}"),
                (Some((a, b)), None) => prop_assert!(b - a <= 2.0 * slack, "{got:?} not sampled"),
                (None, None) => {}
            }
        }
    }
}
