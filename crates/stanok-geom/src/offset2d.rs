//! Planar lines and arcs for cutter radius compensation: offsets (equidistants), intersections of
//! line–line, line–circle and circle–circle, tangents, turn angles and point–segment distance.
//!
//! Plane coordinates `(a, b)` are right-handed as in `arc2d`: counter-clockwise turns from +a
//! towards +b. A segment is either a line `a → b` or an arc given by its centre, radius, start angle
//! and *signed* sweep (positive = counter-clockwise). Every segment has a parameter `t ∈ [0, 1]`
//! from its start to its end (linear in length for a line, in angle for an arc).
//!
//! ```text
//!   offset to the left by d (d < 0 = to the right), tangent t, left normal nL(t) = (−t_b, t_a):
//!     line  P → E          ⇒  P + d·nL(t) → E + d·nL(t)
//!     arc   (C, R, sweep)  ⇒  (C, R − d·sign(sweep), sweep)     (ccw arcs have their centre on the left)
//! ```
//!
//! Tolerances (stated once, used everywhere): [`LEN_EPS`] = 1e-7 mm for lengths and point
//! coincidence, [`PARAM_EPS`] = 1e-9 for segment parameters, [`ANGLE_EPS`] = 1e-9 rad for turn
//! angles. Invariants: no function panics or loops; NaN input gives empty intersection lists or
//! `None`, never a NaN point in an `Some`/non-empty answer.

use std::f64::consts::{PI, TAU};

/// A point or vector in the plane, mm.
pub type P2 = [f64; 2];

/// Length tolerance, mm: points closer than this coincide.
pub const LEN_EPS: f64 = 1e-7;
/// Parameter tolerance on `t ∈ [0, 1]`.
pub const PARAM_EPS: f64 = 1e-9;
/// Angle tolerance, radians: turns smaller than this are tangential (smooth).
pub const ANGLE_EPS: f64 = 1e-9;

/// `a + k·b`.
pub fn add_scaled(a: P2, b: P2, k: f64) -> P2 {
    [a[0] + k * b[0], a[1] + k * b[1]]
}

/// `a − b`.
pub fn sub2(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

/// Dot product.
pub fn dot2(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// 2D cross product `a_a·b_b − a_b·b_a` (> 0: b is counter-clockwise from a).
pub fn cross2(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Euclidean distance.
pub fn dist2(a: P2, b: P2) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Left normal `(−t_b, t_a)`.
pub fn left_normal(t: P2) -> P2 {
    [-t[1], t[0]]
}

/// Signed turn angle from direction `t1` to `t2`, radians in (−π, π] (> 0 = left turn).
pub fn turn_angle(t1: P2, t2: P2) -> f64 {
    cross2(t1, t2).atan2(dot2(t1, t2))
}

/// Angle `x` mapped into (−π, π].
pub fn wrap_pi(x: f64) -> f64 {
    let mut y = x.rem_euclid(TAU);
    if y > PI {
        y -= TAU;
    }
    y
}

/// A planar line or arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Seg2 {
    /// Straight line from `a` to `b`.
    Line {
        /// Start.
        a: P2,
        /// End.
        b: P2,
    },
    /// Circular arc.
    Arc {
        /// Centre.
        c: P2,
        /// Radius, > 0.
        r: f64,
        /// Angle of the start point seen from the centre, radians.
        start: f64,
        /// Signed sweep, radians (> 0 counter-clockwise); |sweep| ≤ 2π.
        sweep: f64,
    },
}

impl Seg2 {
    /// The arc about `c` from `s` to `e` in the given direction; `full` = a whole turn when `s`
    /// and `e` coincide. The radius is the start radius (the end is projected onto the circle).
    pub fn arc_through(c: P2, s: P2, e: P2, ccw: bool, full: bool) -> Seg2 {
        let r = dist2(c, s);
        let a0 = (s[1] - c[1]).atan2(s[0] - c[0]);
        let a1 = (e[1] - c[1]).atan2(e[0] - c[0]);
        let ccw_sweep = (a1 - a0).rem_euclid(TAU);
        let sign = if ccw { 1.0 } else { -1.0 };
        let sweep = if dist2(s, e) < LEN_EPS {
            if full {
                sign * TAU
            } else {
                0.0
            }
        } else if ccw {
            ccw_sweep
        } else {
            -(TAU - ccw_sweep)
        };
        Seg2::Arc {
            c,
            r,
            start: a0,
            sweep,
        }
    }

    /// The point at parameter `t` (not clamped: lines extend, arcs continue round the circle).
    pub fn point(&self, t: f64) -> P2 {
        match *self {
            Seg2::Line { a, b } => add_scaled(a, sub2(b, a), t),
            Seg2::Arc { c, r, start, sweep } => {
                let phi = start + t * sweep;
                [c[0] + r * phi.cos(), c[1] + r * phi.sin()]
            }
        }
    }

    /// Start point.
    pub fn start(&self) -> P2 {
        self.point(0.0)
    }

    /// End point.
    pub fn end(&self) -> P2 {
        match *self {
            Seg2::Line { b, .. } => b,
            _ => self.point(1.0),
        }
    }

    /// Unit tangent (direction of travel) at parameter `t`; a zero-length line gives (0, 0).
    pub fn tangent(&self, t: f64) -> P2 {
        match *self {
            Seg2::Line { a, b } => {
                let d = sub2(b, a);
                let l = d[0].hypot(d[1]);
                if l < 1e-300 || !l.is_finite() {
                    [0.0, 0.0]
                } else {
                    [d[0] / l, d[1] / l]
                }
            }
            Seg2::Arc { start, sweep, .. } => {
                let phi = start + t * sweep;
                let s = if sweep >= 0.0 { 1.0 } else { -1.0 };
                [-s * phi.sin(), s * phi.cos()]
            }
        }
    }

    /// Length, mm.
    pub fn length(&self) -> f64 {
        match *self {
            Seg2::Line { a, b } => dist2(a, b),
            Seg2::Arc { r, sweep, .. } => r * sweep.abs(),
        }
    }

    /// The equidistant at signed distance `d` to the left of the direction of travel (d < 0: right).
    /// None for an arc whose offset radius would be ≤ [`LEN_EPS`] (the tool does not fit).
    pub fn offset_left(&self, d: f64) -> Option<Seg2> {
        match *self {
            Seg2::Line { a, b } => {
                let n = left_normal(self.tangent(0.0));
                Some(Seg2::Line {
                    a: add_scaled(a, n, d),
                    b: add_scaled(b, n, d),
                })
            }
            Seg2::Arc { c, r, start, sweep } => {
                let s = if sweep >= 0.0 { 1.0 } else { -1.0 };
                let rho = r - d * s;
                (rho > LEN_EPS && rho.is_finite()).then_some(Seg2::Arc {
                    c,
                    r: rho,
                    start,
                    sweep,
                })
            }
        }
    }

    /// The piece between parameters `t0` and `t1` (t1 < t0 gives the reversed piece).
    pub fn piece(&self, t0: f64, t1: f64) -> Seg2 {
        match *self {
            Seg2::Line { .. } => Seg2::Line {
                a: self.point(t0),
                b: self.point(t1),
            },
            Seg2::Arc { c, r, start, sweep } => Seg2::Arc {
                c,
                r,
                start: start + t0 * sweep,
                sweep: (t1 - t0) * sweep,
            },
        }
    }

    /// Parameter of the point of the (extended) curve nearest to `p`, chosen near `t_hint`
    /// (0 = near the start, 1 = near the end): for an arc the angle is taken within ±π of the
    /// hint's angle, so a point slightly before the start gives a small negative parameter.
    pub fn param_near(&self, p: P2, t_hint: f64) -> f64 {
        match *self {
            Seg2::Line { a, b } => {
                let d = sub2(b, a);
                let l2 = dot2(d, d);
                if l2 < 1e-300 {
                    return t_hint;
                }
                dot2(sub2(p, a), d) / l2
            }
            Seg2::Arc {
                c, start, sweep, ..
            } => {
                if sweep.abs() < 1e-300 {
                    return t_hint;
                }
                let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
                let hint_phi = start + t_hint * sweep;
                let phi = hint_phi + wrap_pi(phi - hint_phi);
                (phi - start) / sweep
            }
        }
    }

    /// Parameters `t` of this segment at which the point `p` (known to be on its curve) lies, if it
    /// is within the segment (±`PARAM_EPS` and ±`LEN_EPS`).
    fn param_on(&self, p: P2) -> Option<f64> {
        match *self {
            Seg2::Line { .. } => {
                let t = self.param_near(p, 0.0);
                let l = self.length().max(1e-300);
                let tol = PARAM_EPS + LEN_EPS / l;
                (t >= -tol && t <= 1.0 + tol).then_some(t.clamp(0.0, 1.0))
            }
            Seg2::Arc { c, r, start, sweep } => {
                let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
                let u = ((phi - start) * sweep.signum()).rem_euclid(TAU);
                let total = sweep.abs();
                let tol = PARAM_EPS * total.max(1e-12) + LEN_EPS / r.max(1e-300);
                if u <= total + tol {
                    Some((u / total.max(1e-300)).clamp(0.0, 1.0))
                } else if TAU - u <= tol {
                    Some(0.0)
                } else {
                    None
                }
            }
        }
    }

    /// Distance from `p` to the segment (not its extension), mm.
    pub fn distance_to(&self, p: P2) -> f64 {
        match *self {
            Seg2::Line { a, .. } => {
                let t = self.param_near(p, 0.0).clamp(0.0, 1.0);
                if self.length() < 1e-300 {
                    return dist2(a, p);
                }
                dist2(self.point(t), p)
            }
            Seg2::Arc { c, r, .. } => {
                let d = dist2(c, p);
                let on = if d < 1e-300 {
                    None
                } else {
                    self.param_on(add_scaled(c, sub2(p, c), r / d))
                };
                match on {
                    Some(_) => (d - r).abs(),
                    None => dist2(self.start(), p).min(dist2(self.end(), p)),
                }
            }
        }
    }
}

/// Intersections of the full curves (infinite lines, whole circles) of two segments; tangent
/// contacts (within [`LEN_EPS`]) count once. Parallel or coincident lines and concentric circles
/// give none.
pub fn curve_intersections(s1: &Seg2, s2: &Seg2) -> Vec<P2> {
    let out = match (*s1, *s2) {
        (Seg2::Line { a: p, b: q }, Seg2::Line { a: u, b: v }) => {
            let d1 = sub2(q, p);
            let d2 = sub2(v, u);
            let den = cross2(d1, d2);
            if den.abs() < 1e-12 * (d1[0].hypot(d1[1]) * d2[0].hypot(d2[1])).max(1e-300) {
                Vec::new()
            } else {
                let t = cross2(sub2(u, p), d2) / den;
                vec![add_scaled(p, d1, t)]
            }
        }
        (Seg2::Line { a, b }, Seg2::Arc { c, r, .. })
        | (Seg2::Arc { c, r, .. }, Seg2::Line { a, b }) => line_circle(a, b, c, r),
        (Seg2::Arc { c: c1, r: r1, .. }, Seg2::Arc { c: c2, r: r2, .. }) => {
            circle_circle(c1, r1, c2, r2)
        }
    };
    out.into_iter()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect()
}

fn line_circle(a: P2, b: P2, c: P2, r: f64) -> Vec<P2> {
    let d = sub2(b, a);
    let l = d[0].hypot(d[1]);
    if l < 1e-300 || !l.is_finite() {
        return Vec::new();
    }
    let t = [d[0] / l, d[1] / l];
    // Foot of the perpendicular from the centre.
    let s = dot2(sub2(c, a), t);
    let foot = add_scaled(a, t, s);
    let h = dist2(foot, c);
    if h > r + LEN_EPS {
        return Vec::new();
    }
    let w = (r * r - h * h).max(0.0).sqrt();
    if w < LEN_EPS {
        return vec![foot];
    }
    vec![add_scaled(foot, t, -w), add_scaled(foot, t, w)]
}

fn circle_circle(c1: P2, r1: f64, c2: P2, r2: f64) -> Vec<P2> {
    let d = dist2(c1, c2);
    if d < LEN_EPS || d > r1 + r2 + LEN_EPS || d < (r1 - r2).abs() - LEN_EPS {
        return Vec::new();
    }
    // Distance from c1 along the centre line to the chord of the intersections.
    let x = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    let h = (r1 * r1 - x * x).max(0.0).sqrt();
    let u = [(c2[0] - c1[0]) / d, (c2[1] - c1[1]) / d];
    let m = add_scaled(c1, u, x);
    if h < LEN_EPS {
        return vec![m];
    }
    let n = left_normal(u);
    vec![add_scaled(m, n, h), add_scaled(m, n, -h)]
}

/// Intersections of two segments within their extents: `(t1, t2, point)`, sorted by `t1`.
pub fn segment_intersections(s1: &Seg2, s2: &Seg2) -> Vec<(f64, f64, P2)> {
    let mut v: Vec<(f64, f64, P2)> = curve_intersections(s1, s2)
        .into_iter()
        .filter_map(|p| Some((s1.param_on(p)?, s2.param_on(p)?, p)))
        .collect();
    v.sort_by(|x, y| x.0.total_cmp(&y.0));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-9;

    fn close(a: P2, b: P2) -> bool {
        dist2(a, b) < TOL
    }

    #[test]
    fn line_offsets_left_and_right() {
        let l = Seg2::Line {
            a: [0.0, 0.0],
            b: [10.0, 0.0],
        };
        let left = l.offset_left(2.0).unwrap();
        assert!(close(left.start(), [0.0, 2.0]) && close(left.end(), [10.0, 2.0]));
        let right = l.offset_left(-2.0).unwrap();
        assert!(close(right.start(), [0.0, -2.0]));
    }

    #[test]
    fn arc_offsets_shrink_on_the_concave_side() {
        // CCW arc: centre on the left, so a left offset shrinks it.
        let a = Seg2::arc_through([0.0, 0.0], [10.0, 0.0], [0.0, 10.0], true, false);
        match a.offset_left(3.0).unwrap() {
            Seg2::Arc { r, sweep, .. } => {
                assert!((r - 7.0).abs() < TOL && (sweep - PI / 2.0).abs() < TOL)
            }
            _ => unreachable!(),
        }
        // CW arc: right offset (G42) shrinks it; a radius ≤ offset gives None.
        let cw = Seg2::arc_through([0.0, 0.0], [0.0, 10.0], [10.0, 0.0], false, false);
        assert!(cw.offset_left(-10.0).is_none());
        match cw.offset_left(-4.0).unwrap() {
            Seg2::Arc { r, sweep, .. } => {
                assert!((r - 6.0).abs() < TOL && (sweep + PI / 2.0).abs() < TOL)
            }
            _ => unreachable!(),
        }
    }

    #[test]
    fn full_circles_sweep_a_whole_turn() {
        let cw = Seg2::arc_through([0.0, 0.0], [0.0, 50.0], [0.0, 50.0], false, true);
        assert!(matches!(cw, Seg2::Arc { sweep, .. } if (sweep + TAU).abs() < TOL));
        assert!(close(cw.point(0.25), [50.0, 0.0]));
        // Tangent of a CW circle at its top runs towards +a.
        assert!(close(cw.tangent(0.0), [1.0, 0.0]));
    }

    #[test]
    fn intersections_line_line_line_circle_circle_circle() {
        let l1 = Seg2::Line {
            a: [0.0, 0.0],
            b: [10.0, 10.0],
        };
        let l2 = Seg2::Line {
            a: [0.0, 10.0],
            b: [10.0, 0.0],
        };
        let x = segment_intersections(&l1, &l2);
        assert_eq!(x.len(), 1);
        assert!(close(x[0].2, [5.0, 5.0]) && (x[0].0 - 0.5).abs() < TOL);
        // The bottle-neck corner arcs of spec axioma-3 W.4 (r = 6): (100 ± √11, 65).
        let a1 = Seg2::arc_through([100.0, 60.0], [106.0, 60.0], [100.0, 66.0], true, false);
        let a2 = Seg2::arc_through([100.0, 70.0], [100.0, 64.0], [106.0, 70.0], true, false);
        let x = segment_intersections(&a1, &a2);
        assert_eq!(x.len(), 1, "{x:?}");
        assert!(close(x[0].2, [100.0 + 11f64.sqrt(), 65.0]), "{x:?}");
        let c = curve_intersections(&a1, &a2);
        assert_eq!(c.len(), 2);
        // Line through a circle.
        let l = Seg2::Line {
            a: [90.0, 65.0],
            b: [110.0, 65.0],
        };
        let x = segment_intersections(&l, &a1);
        assert_eq!(x.len(), 1);
        assert!(close(x[0].2, [100.0 + 11f64.sqrt(), 65.0]));
        // Tangent circles touch once.
        let t = curve_intersections(
            &Seg2::arc_through([0.0, 0.0], [5.0, 0.0], [5.0, 0.0], true, true),
            &Seg2::arc_through([10.0, 0.0], [15.0, 0.0], [15.0, 0.0], true, true),
        );
        assert_eq!(t.len(), 1);
        assert!(close(t[0], [5.0, 0.0]));
    }

    #[test]
    fn parameters_near_the_ends_extend_the_segment() {
        let a = Seg2::arc_through([0.0, 0.0], [10.0, 0.0], [0.0, 10.0], true, false);
        let before = [10.0 * (-0.1f64).cos(), 10.0 * (-0.1f64).sin()];
        assert!(a.param_near(before, 0.0) < 0.0);
        let after = [10.0 * (PI / 2.0 + 0.1).cos(), 10.0 * (PI / 2.0 + 0.1).sin()];
        assert!(a.param_near(after, 1.0) > 1.0);
    }

    #[test]
    fn distance_to_line_and_arc() {
        let a = Seg2::arc_through([0.0, 0.0], [10.0, 0.0], [0.0, 10.0], true, false);
        assert!((a.distance_to([20.0, 20.0]) - (800f64.sqrt() - 10.0)).abs() < TOL);
        assert!((a.distance_to([0.0, -5.0]) - 125f64.sqrt()).abs() < TOL);
        let l = Seg2::Line {
            a: [0.0, 0.0],
            b: [10.0, 0.0],
        };
        assert!((l.distance_to([5.0, 3.0]) - 3.0).abs() < TOL);
        assert!((l.distance_to([13.0, 4.0]) - 5.0).abs() < TOL);
    }

    #[test]
    fn turn_angles_are_signed() {
        assert!((turn_angle([1.0, 0.0], [0.0, 1.0]) - PI / 2.0).abs() < TOL);
        assert!((turn_angle([1.0, 0.0], [0.0, -1.0]) + PI / 2.0).abs() < TOL);
        assert!((turn_angle([1.0, 0.0], [-1.0, 0.0]) - PI).abs() < TOL);
    }
}
