//! BRISK: the trapezoidal speed profile of one piece (acceleration-limited).
//!
//! ```text
//!   v ^      vp ______________
//!     |       /              \          phase 1: v0 → vp at +a   (t1 = (vp − v0)/a)
//!  v0 |______/                \         phase 2: cruise at vp    (t2 = d2 / vp)
//!     |                        \___ v1  phase 3: vp → v1 at −a   (t3 = (vp − v1)/a)
//!     +----------------------------> t
//! ```
//! vp = min(v_max, √((2aL + v0² + v1²)/2)) — the highest speed from which the piece can still end
//! at v1; d1 = (vp² − v0²)/2a, d3 = (vp² − v1²)/2a, d2 = L − d1 − d3 ≥ 0.
//!
//! The planner guarantees |v1² − v0²| ≤ 2aL; if rounding breaks that by a hair, the ramps are
//! squeezed into L with a correspondingly (by ~1e-15) higher acceleration rather than overshooting
//! the piece. Example: L = 100 mm, v0 = v1 = 0, v_max = 100 mm/s, a = 1000 mm/s²: t1 = t3 = 0.1 s,
//! d1 = d3 = 5 mm, t2 = 0.9 s, total 1.1 s = L/v + v/a.

/// Samples of a profile at one instant: path position, speed, acceleration, jerk.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Kinematics {
    /// Arc length from the piece start.
    pub s: f64,
    /// ds/dt.
    pub v: f64,
    /// d²s/dt².
    pub a: f64,
    /// d³s/dt³ (0 inside BRISK phases).
    pub j: f64,
}

/// A trapezoidal profile (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trapezoid {
    v0: f64,
    vp: f64,
    a_up: f64,
    a_down: f64,
    t1: f64,
    t2: f64,
    t3: f64,
    d1: f64,
    d2: f64,
    length: f64,
}

impl Trapezoid {
    /// The profile of a piece of `length` entered at `v0`, left at `v1`, at most `v_max`, with
    /// acceleration `a` (all ≥ 0; a > 0 unless the piece is empty).
    ///
    /// Entered above `v_max` (an override was lowered, see [`crate::planner`]), the first phase
    /// slows down to max(v_max, v1) at −a instead. With v_max = 0 and v1 = 0 the profile comes to
    /// rest before the piece ends, at [`Trapezoid::reached`] (the interpolator then stalls there).
    pub fn new(length: f64, v0: f64, v1: f64, v_max: f64, a: f64) -> Self {
        let length = length.max(0.0);
        let a = if a.is_finite() && a > 0.0 { a } else { 1e12 };
        let (v0, v1) = (v0.max(0.0), v1.max(0.0));
        let v_max = v_max.max(0.0);
        let vp = if v0 > v_max.max(v1) {
            v_max.max(v1)
        } else {
            let v_max = v_max.max(v0).max(v1);
            let peak_sq = (2.0 * a * length + v0 * v0 + v1 * v1) * 0.5;
            v_max.min(peak_sq.sqrt()).max(v0).max(v1)
        };
        let first_sign = if vp >= v0 { 1.0 } else { -1.0 };
        let mut d1 = (vp * vp - v0 * v0) / (2.0 * a) * first_sign;
        let mut d3 = (vp * vp - v1 * v1) / (2.0 * a);
        let (mut a_up, mut a_down) = (a * first_sign, a);
        if d1 + d3 > length {
            let k = if d1 + d3 > 0.0 {
                length / (d1 + d3)
            } else {
                0.0
            };
            d1 *= k;
            d3 *= k;
            if d1 > 0.0 {
                a_up = (vp * vp - v0 * v0) / (2.0 * d1);
            }
            if d3 > 0.0 {
                a_down = (vp * vp - v1 * v1) / (2.0 * d3);
            }
        }
        // At vp = 0 nothing moves between the phases: the profile stops short (a stall).
        let d2 = if vp > 0.0 {
            (length - d1 - d3).max(0.0)
        } else {
            0.0
        };
        let t1 = if vp != v0 && a_up != 0.0 {
            (vp - v0) / a_up
        } else {
            0.0
        };
        let t3 = if vp > v1 { (vp - v1) / a_down } else { 0.0 };
        let t2 = if vp > 0.0 { d2 / vp } else { 0.0 };
        Trapezoid {
            v0,
            vp,
            a_up,
            a_down,
            t1,
            t2,
            t3,
            d1,
            d2,
            length,
        }
    }

    /// Arc length at the end of the profile: the piece's length, or less when it stalls (the
    /// module doc of [`Trapezoid::new`]).
    pub fn reached(&self) -> f64 {
        if self.vp > 0.0 {
            self.length
        } else {
            self.d1.min(self.length)
        }
    }

    /// Total time, s.
    pub fn duration(&self) -> f64 {
        self.t1 + self.t2 + self.t3
    }

    /// Peak speed.
    pub fn peak_speed(&self) -> f64 {
        self.vp
    }

    /// Highest acceleration used (a, or a hair more after squeezing; see the module doc).
    pub fn peak_acceleration(&self) -> f64 {
        let up = if self.t1 > 0.0 { self.a_up.abs() } else { 0.0 };
        let down = if self.t3 > 0.0 { self.a_down } else { 0.0 };
        up.max(down)
    }

    /// The state at time `t` from the piece start (clamped to [0, duration]).
    #[inline]
    pub fn at(&self, t: f64) -> Kinematics {
        let t = t.max(0.0);
        if t < self.t1 {
            return Kinematics {
                s: self.v0 * t + 0.5 * self.a_up * t * t,
                v: self.v0 + self.a_up * t,
                a: self.a_up,
                j: 0.0,
            };
        }
        let t = t - self.t1;
        if t < self.t2 {
            return Kinematics {
                s: self.d1 + self.vp * t,
                v: self.vp,
                a: 0.0,
                j: 0.0,
            };
        }
        let t = (t - self.t2).min(self.t3);
        let s = self.d1 + self.d2 + self.vp * t - 0.5 * self.a_down * t * t;
        Kinematics {
            s: s.min(self.length).max(0.0),
            v: (self.vp - self.a_down * t).max(0.0),
            a: if t < self.t3 { -self.a_down } else { 0.0 },
            j: 0.0,
        }
    }
}

/// The highest speed reachable (or, read backwards, from which one can slow down to `v`) over
/// `length` at acceleration `a`: √(v² + 2aL).
#[inline]
pub fn reach(v: f64, length: f64, a: f64) -> f64 {
    (v * v + 2.0 * a * length).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hundred_mm_at_f6000_with_a1000_takes_1_1_s() {
        let p = Trapezoid::new(100.0, 0.0, 0.0, 100.0, 1000.0);
        assert!((p.duration() - 1.1).abs() < 1e-12, "{}", p.duration());
        assert!((p.at(0.1).s - 5.0).abs() < 1e-12);
        assert!((p.at(0.55).s - 50.0).abs() < 1e-12);
        assert!((p.at(1.1).s - 100.0).abs() < 1e-12);
        assert_eq!(p.at(2.0).v, 0.0);
    }

    #[test]
    fn triangle_when_too_short_to_cruise() {
        // 10 mm from rest to rest at a = 1000: peak √(1000·10) = 100 mm/s, 2·0.1 s.
        let p = Trapezoid::new(10.0, 0.0, 0.0, 500.0, 1000.0);
        assert!((p.peak_speed() - 100.0).abs() < 1e-9);
        assert!((p.duration() - 0.2).abs() < 1e-12);
    }

    #[test]
    fn entered_above_the_limit_it_slows_down_first() {
        // 10 mm entered at 100 mm/s with a limit of 20, left at 10, a = 1000: down to 20 over
        // 4.8 mm in 0.08 s, cruise, down to 10 over 0.15 mm.
        let p = Trapezoid::new(10.0, 100.0, 10.0, 20.0, 1000.0);
        assert!((p.at(0.0).v - 100.0).abs() < 1e-12 && p.at(0.0).a == -1000.0);
        assert!((p.at(0.08).v - 20.0).abs() < 1e-9);
        assert!((p.at(0.08).s - 4.8).abs() < 1e-9);
        let end = p.at(p.duration());
        assert!((end.s - 10.0).abs() < 1e-9 && (end.v - 10.0).abs() < 1e-9);
        assert!((p.duration() - (0.08 + (10.0 - 4.8 - 0.15) / 20.0 + 0.01)).abs() < 1e-9);
        // A limit of 0: to rest after 5 mm and no further (a stall).
        let p = Trapezoid::new(10.0, 100.0, 0.0, 0.0, 1000.0);
        assert!((p.duration() - 0.1).abs() < 1e-12);
        assert!((p.reached() - 5.0).abs() < 1e-12);
        assert!((p.at(1.0).s - 5.0).abs() < 1e-12 && p.at(1.0).v == 0.0);
    }

    #[test]
    fn boundary_speeds_are_kept() {
        let p = Trapezoid::new(5.0, 50.0, 80.0, 100.0, 1000.0);
        assert!((p.at(0.0).v - 50.0).abs() < 1e-12);
        assert!((p.at(p.duration()).v - 80.0).abs() < 1e-9);
        assert!((p.at(p.duration()).s - 5.0).abs() < 1e-12);
        assert!(p.peak_acceleration() <= 1000.0 * (1.0 + 1e-12));
    }
}
