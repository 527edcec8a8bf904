//! SOFT: the jerk-limited S-curve profile of one piece, with non-zero boundary speeds.
//!
//! ## Shape
//! Every piece starts and ends with zero acceleration (so pieces join with continuous acceleration
//! whatever their limits), and is: a speed ramp v0 → vp, a cruise at vp, a ramp vp → v1. A ramp of
//! Δv with acceleration limit a and jerk limit j (spec axioma-2 §3.5):
//! * Δv ≥ a²/j: jerk for a/j, constant a for Δv/a − a/j, jerk back for a/j; T = Δv/a + a/j;
//! * otherwise: peak acceleration √(Δv·j) < a, two jerk phases of √(Δv/j); T = 2√(Δv/j).
//!
//! The ramp is point-symmetric about its middle, so its distance is exactly the mean speed times
//! its duration: D(u → w) = (u + w)/2 · T(|w − u|). D grows with the higher speed, so the peak vp is
//! the largest value in [max(v0, v1), v_max] with D(v0 → vp) + D(vp → v1) ≤ L, found by bisection
//! (60 halvings: ~1e-18 relative). The planner only hands pieces with D(v0 → v1) ≤ L ([`reach`]).
//!
//! ## Limits
//! |acceleration| ≤ a and |jerk| ≤ j everywhere inside the profile, exactly (up to rounding): the
//! phases are built from them. Known limit: zero acceleration at every piece boundary makes SOFT
//! slower than necessary on paths of many tiny pieces (each piece ramps on its own).

use crate::profile_trapezoid::Kinematics;

/// One speed ramp (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Ramp {
    from: f64,
    /// +1 speeding up, −1 slowing down.
    sign: f64,
    jerk: f64,
    peak_a: f64,
    t_jerk: f64,
    t_const: f64,
}

impl Ramp {
    fn new(from: f64, to: f64, a: f64, j: f64) -> Self {
        let dv = (to - from).abs();
        let sign = if to >= from { 1.0 } else { -1.0 };
        if dv <= 0.0 {
            return Ramp {
                from,
                sign,
                ..Default::default()
            };
        }
        if dv >= a * a / j {
            Ramp {
                from,
                sign,
                jerk: j,
                peak_a: a,
                t_jerk: a / j,
                t_const: dv / a - a / j,
            }
        } else {
            let t_jerk = (dv / j).sqrt();
            Ramp {
                from,
                sign,
                jerk: j,
                peak_a: j * t_jerk,
                t_jerk,
                t_const: 0.0,
            }
        }
    }

    fn duration(&self) -> f64 {
        2.0 * self.t_jerk + self.t_const
    }

    /// The state at `t` ∈ [0, duration] from the ramp start.
    fn at(&self, t: f64) -> Kinematics {
        let (u, sg, jk, ap, tj) = (self.from, self.sign, self.jerk, self.peak_a, self.t_jerk);
        if t <= tj {
            return Kinematics {
                s: u * t + sg * jk * t * t * t / 6.0,
                v: u + sg * 0.5 * jk * t * t,
                a: sg * jk * t,
                j: sg * jk,
            };
        }
        let s1 = u * tj + sg * jk * tj * tj * tj / 6.0;
        let v1 = u + sg * 0.5 * jk * tj * tj;
        let tau = t - tj;
        if tau <= self.t_const {
            return Kinematics {
                s: s1 + v1 * tau + sg * 0.5 * ap * tau * tau,
                v: v1 + sg * ap * tau,
                a: sg * ap,
                j: 0.0,
            };
        }
        let tc = self.t_const;
        let s2 = s1 + v1 * tc + sg * 0.5 * ap * tc * tc;
        let v2 = v1 + sg * ap * tc;
        let tau = (tau - tc).min(tj);
        Kinematics {
            s: s2 + v2 * tau + sg * (0.5 * ap * tau * tau - jk * tau * tau * tau / 6.0),
            v: v2 + sg * (ap * tau - 0.5 * jk * tau * tau),
            a: sg * (ap - jk * tau),
            j: -sg * jk,
        }
    }
}

/// Duration of a ramp between speeds `u` and `w`.
fn ramp_time(u: f64, w: f64, a: f64, j: f64) -> f64 {
    let dv = (w - u).abs();
    if dv >= a * a / j {
        dv / a + a / j
    } else {
        2.0 * (dv / j).sqrt()
    }
}

/// Distance of a ramp between `u` and `w` (module doc).
pub fn ramp_distance(u: f64, w: f64, a: f64, j: f64) -> f64 {
    0.5 * (u + w) * ramp_time(u, w, a, j)
}

fn sane(x: f64) -> f64 {
    if x.is_finite() && x > 0.0 {
        x
    } else {
        1e12
    }
}

/// The planner's reach: the highest speed w ≥ v with D(v → w) ≤ `length` (and so, read
/// backwards, the highest entry speed from which a piece can slow down to v), made monotone.
///
/// ## Why monotone
/// With zero acceleration at both ends of a ramp, the exact reach w(v) is *not* increasing in v:
/// a faster start reaches a lower top speed while v < v*. (Differentiating (w² − v²)/a +
/// (v + w)·a/j = 2L, the full-acceleration ramp, gives dw/dv = 0 at v = a²/2j; differentiating
/// (v + w)·√(w − v) = L·√j, the jerk-only ramp, gives it at w = 3v.) The look-ahead planner needs
/// the opposite: raising a later boundary speed must never lower an earlier one's bound, or a speed
/// it has already released stops being able to slow down to its successor (seen as a piece
/// squeezed out of shape: finite-difference acceleration 2× the limit). So this returns
/// w(max(v, v*)) with v* the minimiser of w, which is
/// * ≤ w(v) — every pair it allows is feasible, since any target in [v, w(v)] is reachable
///   (D grows with the target speed) — and
/// * non-decreasing in v.
///
/// v*: the jerk-only minimum v_j = (L·√j / (4√2))^(2/3) (from w = 3v, Δ = 2v) when its ramp stays
/// below a (2·v_j ≤ a²/j); otherwise the full-acceleration minimum a²/2j.
pub fn reach(v: f64, length: f64, a: f64, j: f64) -> f64 {
    let (a, j) = (sane(a), sane(j));
    if length.is_nan() || length <= 0.0 || !v.is_finite() {
        return v.max(0.0);
    }
    let v_jerk = (length * j.sqrt() / (4.0 * std::f64::consts::SQRT_2)).powf(2.0 / 3.0);
    let v_star = if 2.0 * v_jerk <= a * a / j {
        v_jerk
    } else {
        0.5 * a * a / j
    };
    let w = reach_exact(v.max(v_star), length, a, j);
    // Never below the start speed (a start above v* gives w ≥ v by construction).
    w.max(v.max(0.0))
}

/// The highest speed w ≥ v with D(v → w) ≤ `length` (exact, not monotone in v: see [`reach`]).
/// Closed form, no iteration over the distance:
/// * if L ≥ D at Δ = a²/j (the ramp reaches a): (2v + Δ)(Δ/a + a/j) = 2L, a quadratic in Δ;
/// * otherwise, with x = √(Δ/j) (half the ramp time): j·x³ + 2v·x = L, a convex increasing cubic,
///   solved by Newton's method from min(∛(L/j), L/2v), which lies above the root, so the iterates
///   fall monotonically onto it (8 steps: far below 1e-15 relative).
fn reach_exact(v: f64, length: f64, a: f64, j: f64) -> f64 {
    let (a, j) = (sane(a), sane(j));
    let v = v.max(0.0);
    if length.is_nan() || length <= 0.0 || !v.is_finite() {
        return v;
    }
    let dv_full = a * a / j;
    let d_full = (2.0 * v + dv_full) * (a / j);
    let dv = if length >= d_full {
        let b = a / j + 2.0 * v / a;
        let c = 2.0 * v * a / j - 2.0 * length;
        let disc = (b * b - 4.0 / a * c).max(0.0);
        // Δ = (−b + √disc)·a/2, written without cancellation.
        let root = -2.0 * c / (b + disc.sqrt());
        root.max(dv_full)
    } else {
        let mut x = (length / j).cbrt();
        if v > 0.0 {
            x = x.min(length / (2.0 * v));
        }
        for _ in 0..8 {
            let f = j * x * x * x + 2.0 * v * x - length;
            let df = 3.0 * j * x * x + 2.0 * v;
            if df.is_nan() || df <= 0.0 {
                break;
            }
            x = (x - f / df).max(0.0);
        }
        (j * x * x).min(dv_full)
    };
    let w = v + dv;
    // Rounding must never give a ramp longer than the piece.
    if ramp_distance(v, w, a, j) > length {
        v + dv * (1.0 - 4.0 * f64::EPSILON)
    } else {
        w
    }
}

/// An S-curve profile (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SCurve {
    up: Ramp,
    down: Ramp,
    vp: f64,
    d_up: f64,
    t_up: f64,
    t_cruise: f64,
    t_down: f64,
    length: f64,
    /// 1, or a hair less if rounding made the ramps longer than the piece.
    squeeze: f64,
}

impl SCurve {
    /// The profile of a piece of `length` from `v0` to `v1`, at most `v_max`, with acceleration
    /// limit `a` and jerk limit `j`.
    pub fn new(length: f64, v0: f64, v1: f64, v_max: f64, a: f64, j: f64) -> Self {
        let (a, j) = (sane(a), sane(j));
        let length = length.max(0.0);
        let (v0, v1) = (v0.max(0.0), v1.max(0.0));
        let need = |vp: f64| ramp_distance(v0, vp, a, j) + ramp_distance(vp, v1, a, j);
        let v_max = v_max.max(0.0);
        let lo_v = v0.max(v1);
        let vp = if v0 > v_max.max(v1) {
            // Entered above the limit (a lowered override): slow down to it first. If the two
            // ramps do not fit, the cruise is lower: the highest in [v1, limit] that fits — one
            // ramp to v1 fits (the planner made v1 reachable), and the two ramps' distance is
            // continuous in the cruise speed, so the bisection keeps a cruise above v1 (and above
            // 0: a piece stalls only where the limit is 0).
            let top = v_max.max(v1);
            if need(top) <= length {
                top
            } else {
                let (mut lo, mut hi) = (v1, top);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if need(mid) <= length {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo
            }
        } else if need(v_max.max(lo_v)) <= length {
            v_max.max(lo_v)
        } else {
            let (mut lo, mut hi) = (lo_v, v_max.max(lo_v));
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if need(mid) <= length {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        let (d_up, d_down) = (ramp_distance(v0, vp, a, j), ramp_distance(vp, v1, a, j));
        let cruise = length - d_up - d_down;
        // Ramps longer than the piece by more than rounding are squeezed into it (scaling the
        // positions, so every speed by the same factor); by a hair (≤ 1e-9, what the planner's
        // "fits to rounding" allows) the profile is only clamped at the piece's end, where the
        // speed left is that hair's: scaling would step every speed by v·1e-9, a third
        // difference of v·1e-9/T² at the join.
        let squeeze = if cruise < 0.0 && d_up + d_down > length * (1.0 + 1e-9) {
            length / (d_up + d_down)
        } else {
            1.0
        };
        let up = Ramp::new(v0, vp, a, j);
        let down = Ramp::new(vp, v1, a, j);
        SCurve {
            up,
            down,
            vp,
            d_up,
            t_up: up.duration(),
            t_cruise: if vp > 0.0 { cruise.max(0.0) / vp } else { 0.0 },
            t_down: down.duration(),
            length,
            squeeze,
        }
    }

    /// Total time, s.
    pub fn duration(&self) -> f64 {
        self.t_up + self.t_cruise + self.t_down
    }

    /// Arc length at the end of the profile: the piece's length, or less when it comes to rest
    /// before the end (v_max = 0: a stall, see [`crate::profile_trapezoid::Trapezoid::new`]).
    pub fn reached(&self) -> f64 {
        if self.vp > 0.0 {
            self.length
        } else {
            (self.d_up * self.squeeze).min(self.length)
        }
    }

    /// The state at time `t` from the piece start (clamped).
    pub fn at(&self, t: f64) -> Kinematics {
        let t = t.max(0.0);
        let mut k = if t < self.t_up {
            self.up.at(t)
        } else if t < self.t_up + self.t_cruise {
            Kinematics {
                s: self.d_up + self.vp * (t - self.t_up),
                v: self.vp,
                a: 0.0,
                j: 0.0,
            }
        } else {
            let tau = (t - self.t_up - self.t_cruise).min(self.t_down);
            let mut k = self.down.at(tau);
            k.s += self.d_up + self.vp * self.t_cruise;
            if tau >= self.t_down {
                k.a = 0.0;
                k.j = 0.0;
            }
            k
        };
        k.s = (k.s * self.squeeze).min(self.length);
        k
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_time_matches_the_spec_formulas() {
        // Δv = 100, a = 1000, j = 20000: a²/j = 50 ≤ 100 → t = 0.1 + 0.05.
        assert!((ramp_time(0.0, 100.0, 1000.0, 20_000.0) - 0.15).abs() < 1e-12);
        // Δv = 20 < 50 → t = 2√(20/20000).
        assert!((ramp_time(10.0, 30.0, 1000.0, 20_000.0) - 2.0 * (0.001f64).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn long_piece_rest_to_rest() {
        // 100 mm at 100 mm/s, a = 1000, j = 20000: ramps 0.15 s over 7.5 mm each; cruise 85 mm.
        let p = SCurve::new(100.0, 0.0, 0.0, 100.0, 1000.0, 20_000.0);
        assert!(
            (p.duration() - (0.3 + 0.85)).abs() < 1e-9,
            "{}",
            p.duration()
        );
        let end = p.at(p.duration());
        assert!((end.s - 100.0).abs() < 1e-9 && end.v.abs() < 1e-9);
        let mut t = 0.0;
        while t < p.duration() {
            let k = p.at(t);
            assert!(k.a.abs() <= 1000.0 * (1.0 + 1e-9) && k.j.abs() <= 20_000.0 * (1.0 + 1e-9));
            t += 1e-4;
        }
    }

    /// The planner's reach is monotone, never above the exact reach (so every pair it allows is
    /// feasible, to 1e-6 of L, unless Δv < 1e-7·v, where Δv itself is rounding), equal to it above v*, and at v = 0 equal to
    /// the exact reach's minimum over all
    /// start speeds (20 000 linear and 300 logarithmic starts) — in both ramp regimes.
    #[test]
    fn reach_is_the_monotone_hull_of_the_exact_reach() {
        for (l, a, j) in [
            (2.683, 883.9, 5000.0), // the blend of the failing arc case: full-acceleration minimum
            (0.01, 1000.0, 20_000.0), // jerk-only minimum
            (100.0, 1000.0, 20_000.0),
            (1e-6, 1000.0, 20_000.0),
            (5.0, 50.0, 1e6),
        ] {
            let mut prev = 0.0;
            let mut min_exact = f64::INFINITY;
            for k in 0..20_000 {
                let v = k as f64 * 0.05;
                let (m, e) = (reach(v, l, a, j), reach_exact(v, l, a, j));
                assert!(
                    m >= prev,
                    "{l} {a} {j}: not monotone at v = {v}: {m} < {prev}"
                );
                assert!(
                    m <= e * (1.0 + 1e-12),
                    "{l} {a} {j}: above the exact reach at {v}"
                );
                assert!(
                    ramp_distance(v, m, a, j) <= l * (1.0 + 1e-6) || m - v <= 1e-7 * v,
                    "{l} {a} {j} v {v}: D {} m {m} e {e}",
                    ramp_distance(v, m, a, j)
                );
                prev = m;
                min_exact = min_exact.min(e);
            }
            // reach(0) is the exact reach's minimum: not above the grid's, and a local minimum.
            let r0 = reach(0.0, l, a, j);
            assert!(
                r0 <= min_exact * (1.0 + 1e-12),
                "{l} {a} {j}: {r0} vs {min_exact}"
            );
            for k in 0..=300 {
                let v = 10f64.powf(-12.0 + k as f64 * 0.05);
                assert!(
                    reach_exact(v, l, a, j) >= r0 * (1.0 - 1e-12),
                    "{l} {a} {j}: below at {v}"
                );
            }
        }
    }

    #[test]
    fn reach_inverts_the_distance() {
        for (v, l) in [
            (20.0, 3.0),
            (0.0, 100.0),
            (0.0, 1e-6),
            (150.0, 0.01),
            (5.0, 7.5),
            (0.0, 7.5),
        ] {
            let w = reach_exact(v, l, 1000.0, 20_000.0);
            let d = ramp_distance(v, w, 1000.0, 20_000.0);
            assert!(d <= l && (d - l).abs() <= 1e-9 * l.max(1.0), "{v} {l}: {d}");
        }
    }
}
