//! Path pieces: what the planner times. A programmed segment becomes one or more pieces; every
//! piece is a straight line, a circular arc (BRISK blends) or a symmetric clothoid pair (SOFT
//! blends, [`crate::clothoid`]) in the 9-D axis space, joined to its neighbours with a continuous
//! tangent (or at a stop), so that a profile with continuous path speed gives continuous axis
//! velocities — and in SOFT also with continuous curvature, so that the axis accelerations are
//! continuous too.

use crate::clothoid::Clothoid;
use crate::curve::{bounded_limits, Blend, HelixCurve};
use crate::limits::AxisLimit;
use crate::segment::{Point9, SpeedClass, Spindles};

/// The geometry of a piece, parameterised by s ∈ [0, length] (the arc length, except on a
/// spiral, where it is proportional to the swept angle, and on a smooth blend: see
/// [`crate::curve`]; the derivatives of [`PathPoint`] are along s either way).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// p(s) = start + s·dir, `dir` a unit vector.
    Line {
        /// Start point.
        start: Point9,
        /// Unit direction.
        dir: Point9,
    },
    /// p(s) = centre + radius·(cos φ·e1 + sin φ·e2), φ = s / radius; e1, e2 orthonormal.
    Arc {
        /// Centre.
        centre: Point9,
        /// Unit vector from the centre to the start.
        e1: Point9,
        /// Unit tangent at the start.
        e2: Point9,
        /// Radius, > 0.
        radius: f64,
    },
    /// A SOFT corner blend: two clothoid halves, curvature 0 → 2φ/ℓ → 0 (see [`crate::clothoid`]).
    Clothoid(Clothoid),
    /// A programmed arc, exact ([`crate::curve`]): θ = `theta` + s/ρ.
    Helix {
        /// The arc.
        curve: HelixCurve,
        /// Its angle at the piece's start.
        theta: f64,
    },
    /// A smooth blend at a junction with an arc, or a SOFT curvature step ([`crate::curve`]).
    Blend(std::sync::Arc<Blend>),
    /// All axes stand still at `at` for `seconds` (a G4 dwell), length 0.
    Dwell {
        /// Where the machine stands.
        at: Point9,
        /// How long, s.
        seconds: f64,
    },
}

/// Position, unit tangent, curvature vector (d²p/ds²) and its derivative (d³p/ds³) at one arc
/// length.
#[derive(Debug, Clone, Copy)]
pub struct PathPoint {
    /// Position.
    pub position: Point9,
    /// Unit tangent dp/ds.
    pub tangent: Point9,
    /// d²p/ds² (zero on lines; centripetal, magnitude 1/radius, on arcs).
    pub curvature: Point9,
    /// d³p/ds³ = −κ²·T + κ'·N (zero on lines, −T/r² on arcs): with path speed v, acceleration a
    /// and jerk j the axis jerk is j·T + 3·v·a·p'' + v³·p'''.
    pub third: Point9,
}

impl Shape {
    /// The point at arc length `s` (clamped to the piece by the caller).
    #[inline]
    pub fn at(&self, s: f64) -> PathPoint {
        let mut p = PathPoint {
            position: [0.0; 9],
            tangent: [0.0; 9],
            curvature: [0.0; 9],
            third: [0.0; 9],
        };
        match self {
            Shape::Line { start, dir } => {
                for i in 0..9 {
                    p.position[i] = start[i] + s * dir[i];
                    p.tangent[i] = dir[i];
                }
            }
            Shape::Arc {
                centre,
                e1,
                e2,
                radius,
            } => {
                let (sn, cs) = (s / radius).sin_cos();
                for i in 0..9 {
                    let radial = cs * e1[i] + sn * e2[i];
                    p.position[i] = centre[i] + radius * radial;
                    p.tangent[i] = -sn * e1[i] + cs * e2[i];
                    p.curvature[i] = -radial / radius;
                    p.third[i] = -p.tangent[i] / (radius * radius);
                }
            }
            Shape::Clothoid(c) => {
                let q = c.at(s);
                p.position = q.position;
                p.tangent = q.tangent;
                p.curvature = q.curvature;
                p.third = q.third;
            }
            Shape::Helix { curve, theta } => {
                let q = curve.at(theta + s / curve.rho);
                p.position = q.p;
                p.tangent = q.d1;
                p.curvature = q.d2;
                p.third = q.d3;
            }
            Shape::Blend(b) => {
                let q = b.at(s);
                p.position = q.p;
                p.tangent = q.d1;
                p.curvature = q.d2;
                p.third = q.d3;
            }
            Shape::Dwell { at, .. } => p.position = *at,
        }
        p
    }
}

/// The override factors in force (fractions: 1 = 100 %), see [`crate::overrides`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overrides {
    /// Feed override, 0…2.
    pub feed: f64,
    /// Rapid override, 0…1.
    pub rapid: f64,
    /// Spindle override, 0.5…1.2 (it scales spindle-synchronised moves too).
    pub spindle: f64,
}

impl Default for Overrides {
    fn default() -> Self {
        Overrides {
            feed: 1.0,
            rapid: 1.0,
            spindle: 1.0,
        }
    }
}

impl Overrides {
    /// The factor that scales a speed of class `class`.
    #[inline]
    pub fn factor(&self, class: SpeedClass) -> f64 {
        match class {
            SpeedClass::Feed => self.feed,
            SpeedClass::Rapid => self.rapid,
            SpeedClass::Spindle => self.spindle,
            SpeedClass::Fixed => 1.0,
        }
    }

    /// The same factors brought into their ranges (NaN → 100 %).
    pub fn clamped(self) -> Self {
        let c = |x: f64, lo: f64, hi: f64| if x.is_nan() { 1.0 } else { x.clamp(lo, hi) };
        Overrides {
            feed: c(self.feed, 0.0, 2.0),
            rapid: c(self.rapid, 0.0, 1.0),
            spindle: c(self.spindle, 0.5, 1.2),
        }
    }
}

/// A programmed speed before any override: the speed, unit/s along the path, and which override
/// scales it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProgrammedSpeed {
    /// Unit/s (feed or rapid rate, clamped to the machine's maximum, as a path speed).
    pub speed: f64,
    /// Which override applies.
    pub class: SpeedClass,
}

/// One piece of path with its speed limits (all in path units: unit/s, unit/s², unit/s³).
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// Geometry.
    pub shape: Shape,
    /// Exact end point (where the next piece starts; the programmed end before a stop).
    pub end: Point9,
    /// Arc length, unit (0 only for a dwell).
    pub length: f64,
    /// The programmed speeds it runs at: the lower of the two, each times its override (a blend
    /// joins two blocks; any other piece has the same speed twice).
    pub speeds: [ProgrammedSpeed; 2],
    /// Highest path speed the kinematics allow whatever the feed (tool-centre-point control's
    /// joint-rate cap; ∞ otherwise), unit/s.
    pub velocity_cap: f64,
    /// Highest path acceleration the kinematics allow (tool-centre-point control; ∞ otherwise).
    pub accel_cap: f64,
    /// Highest path speed anywhere on the piece (feed × override, axis velocities, curvature).
    pub v_max: f64,
    /// Highest tangential acceleration (axis accelerations, minus the centripetal share on arcs).
    pub a_max: f64,
    /// Highest tangential jerk (SOFT).
    pub j_max: f64,
    /// SOFT (jerk-limited S-curve) or BRISK (trapezoid).
    pub soft: bool,
    /// The piece starts from standstill (an exact stop before it).
    pub entry_stop: bool,
    /// It starts or ends at a stop of its path mode (G60/G61, an exact-path corner), not a
    /// forced one (program start and end, M0, tool change…): for the report's limiting factor.
    pub exact_stop: bool,
    /// Source line.
    pub line: u32,
    /// The programmed segment it belongs to (the stage's running number; a blend belongs to the
    /// segment it leads into).
    pub seq: u64,
    /// A blend joining two programmed segments (a junction), as opposed to a piece of one.
    pub junction: bool,
    /// The spindles' speeds on this piece (evaluated per setpoint under G96).
    pub spindles: Spindles,
    /// Upper bound of the distance of any point of the piece from the programmed path, unit.
    pub deviation: f64,
    /// The distance allowed (the G64 tolerance in force, or the internal tolerance), unit.
    pub tolerance: f64,
}

impl Piece {
    /// The speed the programmed feeds allow under `overrides` (before axis limits), unit/s.
    #[inline]
    pub fn programmed_speed(&self, overrides: &Overrides) -> f64 {
        let [a, b] = self.speeds;
        (a.speed * overrides.factor(a.class))
            .min(b.speed * overrides.factor(b.class))
            .min(self.velocity_cap)
            .max(0.0)
    }

    /// Sets `v_max`, `a_max`, `j_max` for a programmed speed `cap` (see
    /// [`Piece::programmed_speed`]): v_max ≤ cap and the shape's limits. `floor` is the highest
    /// speed the piece may actually run at when that is above v_max (a piece entered faster than
    /// a lowered override allows, see [`crate::planner`]): on a curve the tangential acceleration
    /// left beside the centripetal one shrinks with the speed, so a and j are those at
    /// max(v_max, floor). A dwell keeps zeros.
    pub fn set_limits(&mut self, cap: f64, floor: f64, axes: &[AxisLimit; 9]) {
        if let Shape::Dwell { .. } = self.shape {
            return;
        }
        let (v, a, j) = shape_limits(&self.shape, self.length, self.soft, cap, axes);
        let (a, j) = if floor > v {
            let (_, a, j) = shape_limits(&self.shape, self.length, self.soft, floor, axes);
            (a, j)
        } else {
            (a, j)
        };
        let (a, j) = cap_acceleration(a, j, self.accel_cap);
        self.v_max = v;
        self.a_max = a;
        self.j_max = j;
    }
}

/// A piece's acceleration limited to `cap` (a segment under tool-centre-point control, see
/// [`crate::tcp`]); the jerk shrinks in the same ratio so the S-curve keeps its shape.
pub fn cap_acceleration(a_max: f64, j_max: f64, cap: f64) -> (f64, f64) {
    if cap.is_finite() && cap > 0.0 && cap < a_max {
        (cap, j_max * cap / a_max)
    } else {
        (a_max, j_max)
    }
}

/// The limits (v, a, j) of a shape `length` long run at programmed speed `speed` (module
/// functions below, [`bounded_limits`]).
pub fn shape_limits(
    shape: &Shape,
    length: f64,
    soft: bool,
    speed: f64,
    axes: &[AxisLimit; 9],
) -> (f64, f64, f64) {
    match shape {
        Shape::Line { dir, .. } => line_limits(dir, speed, axes),
        Shape::Arc { e1, e2, radius, .. } => arc_limits(e1, e2, *radius, speed, false, axes),
        Shape::Clothoid(c) => {
            let n1: Point9 = std::array::from_fn(|i| c.n1(i));
            clothoid_limits(
                &c.t1,
                &n1,
                c.max_curvature(),
                c.curvature_rate(),
                speed,
                axes,
            )
        }
        Shape::Helix { curve, theta } => bounded_limits(
            &curve.bounds(*theta, theta + length / curve.rho),
            speed,
            soft,
            axes,
        ),
        Shape::Blend(b) => bounded_limits(&b.bounds, speed * b.speed_scale, soft, axes),
        Shape::Dwell { .. } => (0.0, 0.0, 0.0),
    }
}

/// Centripetal acceleration may use this share of an arc's acceleration budget; the rest is kept
/// for speeding up and slowing down on it.
pub const CENTRIPETAL_SHARE: f64 = 0.95;
/// In SOFT, v³/r² (the jerk of turning at constant speed) may use this share of the jerk budget.
pub const SOFT_TURN_JERK_SHARE: f64 = 0.5;
/// On a SOFT clothoid blend, v³·√(κ_max⁴ + κ'²) (the jerk of turning at constant speed) may use
/// this share of the jerk budget. A blend is short and the planner nearly always runs it at
/// constant speed (the S-curve's boundary accelerations are zero and the blend's own speed limit
/// is the lower one at both its ends), so most of the budget goes to the turn.
pub const CLOTHOID_TURN_JERK_SHARE: f64 = 0.8;

fn guard(x: f64) -> f64 {
    if x.is_finite() && x > 0.0 {
        x
    } else if x == f64::INFINITY {
        1e12
    } else {
        0.0
    }
}

/// Limits of a line with unit direction `dir` at programmed path speed `speed`:
/// v ≤ min_i V_i/|u_i|, a ≤ min_i A_i/|u_i|, j ≤ min_i J_i/|u_i|.
pub fn line_limits(dir: &Point9, speed: f64, axes: &[AxisLimit; 9]) -> (f64, f64, f64) {
    let (mut v, mut a, mut j) = (speed, f64::INFINITY, f64::INFINITY);
    for i in 0..9 {
        let u = dir[i].abs();
        if u > 0.0 {
            v = v.min(axes[i].velocity / u);
            a = a.min(axes[i].acceleration / u);
            j = j.min(axes[i].jerk / u);
        }
    }
    (guard(v), guard(a), guard(j))
}

/// Limits of a circular arc in the plane (e1, e2) of `radius` (module doc of `path`). With
/// ρ_i = √(e1_i² + e2_i²) ≥ |tangent_i|, |normal_i| everywhere on the arc, per-axis acceleration is
/// at most (|a_t| + v²/r)·ρ_i, so with A = min_i A_i/ρ_i: v²/r ≤ c·A (c ≤ [`CENTRIPETAL_SHARE`]) and
/// |a_t| ≤ (1 − c)·A. SOFT: axis jerk ≤ (|j_t| + 3·v·|a_t|/r + v³/r²)·ρ_i, kept within J = min_i J_i/ρ_i
/// by v³/r² ≤ ½J, 3·v·a_t/r ≤ ¼J, j_t ≤ ¼J.
pub fn arc_limits(
    e1: &Point9,
    e2: &Point9,
    radius: f64,
    speed: f64,
    soft: bool,
    axes: &[AxisLimit; 9],
) -> (f64, f64, f64) {
    let (mut vb, mut ab, mut jb) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for i in 0..9 {
        let rho = (e1[i] * e1[i] + e2[i] * e2[i]).sqrt();
        if rho > 0.0 {
            vb = vb.min(axes[i].velocity / rho);
            ab = ab.min(axes[i].acceleration / rho);
            jb = jb.min(axes[i].jerk / rho);
        }
    }
    let (ab, jb) = (guard(ab), guard(jb));
    let mut v = speed.min(vb).min((CENTRIPETAL_SHARE * ab * radius).sqrt());
    if soft {
        v = v.min((SOFT_TURN_JERK_SHARE * jb * radius * radius).cbrt());
    }
    let v = guard(v);
    let c = if ab > 0.0 {
        (v * v / (radius * ab)).min(CENTRIPETAL_SHARE)
    } else {
        1.0
    };
    let mut a = (1.0 - c) * ab;
    let mut j = jb;
    if soft {
        let rest = (1.0 - SOFT_TURN_JERK_SHARE) * jb;
        if v > 0.0 {
            a = a.min(0.5 * rest * radius / (3.0 * v));
        }
        j = 0.5 * rest;
    }
    (v, guard(a), guard(j))
}

/// Limits of a SOFT clothoid blend (see [`crate::clothoid`]) in the plane (t1, n1), with largest
/// curvature `kappa_max` = 2φ/ℓ and curvature rate `kappa_rate` = |dκ/ds| = 2φ/ℓ².
///
/// ## Budget
/// With ρ_i = √(t1_i² + n1_i²) ≥ |T_i|, |N_i| anywhere on the blend (T, N unit vectors in that
/// plane), and A = min_i A_i/ρ_i, J = min_i J_i/ρ_i:
/// * acceleration a·T + v²κ·N: v²κ_max ≤ c·A (c ≤ [`CENTRIPETAL_SHARE`]), |a| ≤ (1 − c)·A — as on
///   an arc of radius 1/κ_max;
/// * jerk j·T + 3·v·a·κ·N + v³·(−κ²·T + κ'·N), per axis at most
///   (|j| + 3·v·|a|·κ_max + v³·√(κ_max⁴ + κ'²))·ρ_i (the component of a vector α·T + β·N of the
///   plane is at most √(α² + β²)·ρ_i): the turn at constant speed, v³·√(κ_max⁴ + κ'²) ≤ c_j·J
///   ([`CLOTHOID_TURN_JERK_SHARE`] c_j; a speed cap v ≤ (c_j·J / √(κ_max⁴ + κ'²))^⅓), then half
///   the rest each: 3·v·|a|·κ_max ≤ ½(1 − c_j)·J and |j| ≤ ½(1 − c_j)·J.
///
/// κ_max and |κ'| are taken together, though κ is largest only at the mid point: conservative, and
/// the shares add up to 1, so no axis can exceed its limit anywhere on the blend.
pub fn clothoid_limits(
    t1: &Point9,
    n1: &Point9,
    kappa_max: f64,
    kappa_rate: f64,
    speed: f64,
    axes: &[AxisLimit; 9],
) -> (f64, f64, f64) {
    let (mut vb, mut ab, mut jb) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for i in 0..9 {
        let rho = (t1[i] * t1[i] + n1[i] * n1[i]).sqrt();
        if rho > 0.0 {
            vb = vb.min(axes[i].velocity / rho);
            ab = ab.min(axes[i].acceleration / rho);
            jb = jb.min(axes[i].jerk / rho);
        }
    }
    let (ab, jb) = (guard(ab), guard(jb));
    let turn = (kappa_max.powi(4) + kappa_rate * kappa_rate).sqrt();
    let v = speed
        .min(vb)
        .min((CENTRIPETAL_SHARE * ab / kappa_max).sqrt())
        .min((CLOTHOID_TURN_JERK_SHARE * jb / turn).cbrt());
    let v = guard(v);
    let c = if ab > 0.0 {
        (v * v * kappa_max / ab).min(CENTRIPETAL_SHARE)
    } else {
        1.0
    };
    let rest = (1.0 - CLOTHOID_TURN_JERK_SHARE) * jb;
    let mut a = (1.0 - c) * ab;
    if v > 0.0 {
        a = a.min(0.5 * rest / (3.0 * v * kappa_max));
    }
    (v, guard(a), guard(0.5 * rest))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clothoid::{unit_shape, Clothoid};

    fn unit(v: [f64; 3]) -> Point9 {
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        std::array::from_fn(|i| if i < 3 { v[i] / n } else { 0.0 })
    }

    /// At the speed, path acceleration and jerk `clothoid_limits` allows — every sign — no axis
    /// exceeds its velocity, acceleration or jerk limit anywhere on the blend (1001 points), for
    /// corners in tilted planes, from 2° to 170°, short and long. (Dropping the v³κ' term from the
    /// budget makes it fail: 5005 mm/s³ against 5000 on Z.)
    #[test]
    fn clothoid_limits_keep_every_axis_within_its_limits() {
        let mut axes = [AxisLimit::UNLIMITED; 9];
        axes[0] = AxisLimit::from_machine(10_000.0, 1000.0, 20_000.0);
        axes[1] = AxisLimit::from_machine(8_000.0, 700.0, 9_000.0);
        axes[2] = AxisLimit::from_machine(5_000.0, 400.0, 5_000.0);
        for (t1, t2) in [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([1.0, 0.3, -0.2], [0.2, 1.0, 0.5]),
            ([0.3, 0.3, 1.0], [1.0, -0.4, 0.1]),
            ([1.0, 0.0, 0.0], [0.9994, 0.0349, 0.0]),
            ([1.0, 0.0, 0.0], [-0.985, 0.174, 0.0]),
        ] {
            let (t1, t2) = (unit(t1), unit(t2));
            let cos: f64 = (0..9).map(|i| t1[i] * t2[i]).sum();
            let perp: Point9 = std::array::from_fn(|i| t2[i] - cos * t1[i]);
            let sin = perp.iter().map(|x| x * x).sum::<f64>().sqrt();
            let n1 = perp.map(|x| x / sin);
            let theta = sin.atan2(cos);
            for half in [0.01, 0.3, 5.0] {
                let c = Clothoid {
                    corner: [0.0; 9],
                    t1,
                    t2,
                    cut: half * unit_shape(0.5 * theta).cut,
                    half,
                    phi: 0.5 * theta,
                    cos_turn: cos,
                    sin_turn: sin,
                };
                let (v, a_max, j_max) =
                    clothoid_limits(&t1, &n1, c.max_curvature(), c.curvature_rate(), 1e9, &axes);
                assert!(v > 0.0 && a_max > 0.0 && j_max > 0.0);
                for k in 0..=1000 {
                    let p = c.at(c.length() * k as f64 / 1000.0);
                    for (a, j) in [(a_max, j_max), (a_max, -j_max), (-a_max, j_max)] {
                        for (i, axis) in axes.iter().enumerate().take(3) {
                            let acc = a * p.tangent[i] + v * v * p.curvature[i];
                            let jerk = j * p.tangent[i]
                                + 3.0 * v * a * p.curvature[i]
                                + v * v * v * p.third[i];
                            assert!(v * p.tangent[i].abs() <= axis.velocity * (1.0 + 1e-12));
                            assert!(
                                acc.abs() <= axis.acceleration * (1.0 + 1e-12),
                                "θ {theta} ℓ {half} axis {i}: a {acc}"
                            );
                            assert!(
                                jerk.abs() <= axis.jerk * (1.0 + 1e-12),
                                "θ {theta} ℓ {half} axis {i}: j {jerk}"
                            );
                        }
                    }
                }
            }
        }
    }
}
