//! Checking setpoints against the axis limits: analytic values and finite differences.
//!
//! ## What is measured
//! For every axis, on every setpoint:
//! * the **analytic** velocity, acceleration and (SOFT pieces) jerk the interpolator computed from
//!   the profile and the geometry;
//! * the **finite differences** of the positions at the servo period T:
//!   v ≈ (p_k − p_{k−1})/T, a ≈ (p_k − 2p_{k−1} + p_{k−2})/T², j ≈ third difference / T³.
//!
//! A first difference is the mean of the velocity over the period, and a second difference the
//! mean of the acceleration weighted by a triangle kernel of unit mass, so for a trajectory whose
//! axis positions are C¹ (the path builder's invariant) the finite differences can never exceed the
//! analytic peaks: the velocity and acceleration checks apply to both, with a relative slack of
//! [`RELATIVE_SLACK`] and an absolute slack for rounding in the positions (8 ulp of the largest
//! coordinate, divided by T, T², T³).
//!
//! Jerk: BRISK has no jerk limit (acceleration switches instantly, the finite-difference jerk is
//! a spike of Δa/T at every switch): reported, not checked. SOFT: the analytic axis jerk is
//! checked on every SOFT setpoint, and the finite-difference jerk on every setpoint whose third
//! difference spans SOFT setpoints only (it and the three before it), with the same relative slack
//! and an absolute one of 8·(8 ulp)/T³. A third difference is the mean of the jerk weighted by a
//! quadratic B-spline kernel of unit mass, so it is bounded by the analytic peak wherever the axis
//! positions are C² — which SOFT paths are: every SOFT piece starts and ends with zero path
//! acceleration, and SOFT corners are clothoid blends whose curvature is zero where they meet
//! lines (see [`crate::clothoid`]), so no axis acceleration steps at a join. (Circular blends made
//! the centripetal acceleration step by v²/r, a spike of about v²/(r·T); that is why SOFT no longer
//! uses them.)
//!
//! Gaps: a setpoint more than 1.5 periods after the previous one follows a stretch the
//! interpolator skipped (a dwell, a straight cruise: see `interpolator.rs`). The finite differences
//! then start again from it (they would divide a gap's displacement by one period), and the count
//! of setpoints includes the instants skipped, so it stays one per period.
//!
//! Known limit: a BRISK piece shorter than one servo period between two SOFT ones would put its
//! acceleration steps inside a window of four SOFT setpoints; a program would have to switch to
//! BRISK for a sub-millisecond move at speed under G64 for that to happen.

use crate::interpolator::Setpoint;
use crate::limits::AxisLimit;
use crate::segment::Point9;

/// Relative slack of every limit check.
pub const RELATIVE_SLACK: f64 = 1e-6;
/// Most violations kept (the count goes on).
const MAX_KEPT: usize = 100;

/// Peaks of one axis, absolute values, unit/s, unit/s², unit/s³.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AxisPeaks {
    /// Analytic velocity.
    pub velocity: f64,
    /// Analytic acceleration.
    pub acceleration: f64,
    /// Analytic jerk (SOFT pieces only).
    pub jerk: f64,
    /// Finite-difference velocity.
    pub fd_velocity: f64,
    /// Finite-difference acceleration.
    pub fd_acceleration: f64,
    /// Finite-difference jerk.
    pub fd_jerk: f64,
}

/// A limit exceeded.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    /// Time, s.
    pub t: f64,
    /// Source line of the setpoint.
    pub line: u32,
    /// Axis index (X = 0 … W = 8).
    pub axis: usize,
    /// What: "velocity", "acceleration", "jerk", with "(finite difference)" when measured on the
    /// positions.
    pub what: &'static str,
    /// Measured value.
    pub value: f64,
    /// The limit.
    pub limit: f64,
}

/// Watches a stream of setpoints (module doc).
#[derive(Debug, Clone)]
pub struct TraceMonitor {
    limits: [AxisLimit; 9],
    period: f64,
    history: [Point9; 3],
    soft_history: [bool; 3],
    seen: u64,
    /// Consecutive setpoints in the history (at most 3 are used).
    run: u64,
    /// Peaks per axis.
    pub peaks: [AxisPeaks; 9],
    /// The first violations (at most 100).
    pub violations: Vec<Violation>,
    /// All violations.
    pub violation_count: u64,
    /// The last setpoint's time, s.
    pub last_t: f64,
    /// The last setpoint's position.
    pub last_position: Point9,
}

impl TraceMonitor {
    /// A monitor for setpoints every `period` seconds.
    pub fn new(limits: [AxisLimit; 9], period: f64) -> Self {
        TraceMonitor {
            limits,
            period,
            history: [[0.0; 9]; 3],
            soft_history: [false; 3],
            seen: 0,
            run: 0,
            peaks: [AxisPeaks::default(); 9],
            violations: Vec::new(),
            violation_count: 0,
            last_t: 0.0,
            last_position: [0.0; 9],
        }
    }

    /// Setpoints seen.
    pub fn count(&self) -> u64 {
        self.seen
    }

    fn flag(
        &mut self,
        sp: &Setpoint,
        axis: usize,
        what: &'static str,
        value: f64,
        limit: f64,
        abs_slack: f64,
    ) {
        if value > limit * (1.0 + RELATIVE_SLACK) + abs_slack {
            self.violation_count += 1;
            if self.violations.len() < MAX_KEPT {
                self.violations.push(Violation {
                    t: sp.t,
                    line: sp.line,
                    axis,
                    what,
                    value,
                    limit,
                });
            }
        }
    }

    /// Looks at the next setpoint.
    pub fn observe(&mut self, sp: &Setpoint) {
        let p = sp.position;
        let t = self.period;
        if self.seen >= 1 && sp.t - self.last_t > 1.5 * t {
            // A skipped stretch (module doc): count its instants, restart the differences.
            let skipped = ((sp.t - self.last_t) / t).round() - 1.0;
            if skipped.is_finite() && skipped > 0.0 {
                self.seen = self.seen.saturating_add(skipped as u64);
            }
            self.run = 0;
        }
        let scale = p
            .iter()
            .chain(self.history[0].iter())
            .fold(1.0f64, |m, x| m.max(x.abs()));
        let ulp8 = 8.0 * scale * f64::EPSILON;
        // The third difference spans this setpoint and the three before it: checked when all four
        // ran a SOFT profile.
        let all_soft = sp.soft && self.soft_history.iter().all(|s| *s);
        for i in 0..9 {
            let lim = self.limits[i];
            let (v, a, j) = (
                sp.velocity[i].abs(),
                sp.acceleration[i].abs(),
                sp.jerk[i].abs(),
            );
            let pk = &mut self.peaks[i];
            pk.velocity = pk.velocity.max(v);
            pk.acceleration = pk.acceleration.max(a);
            if sp.soft {
                pk.jerk = pk.jerk.max(j);
            }
            self.flag(sp, i, "velocity", v, lim.velocity, 0.0);
            self.flag(sp, i, "acceleration", a, lim.acceleration, 0.0);
            if sp.soft {
                self.flag(sp, i, "jerk", j, lim.jerk, 0.0);
            }
            let h = &self.history;
            if self.run >= 1 {
                let fv = ((p[i] - h[0][i]) / t).abs();
                self.peaks[i].fd_velocity = self.peaks[i].fd_velocity.max(fv);
                self.flag(
                    sp,
                    i,
                    "velocity (finite difference)",
                    fv,
                    lim.velocity,
                    2.0 * ulp8 / t,
                );
            }
            let h = &self.history;
            if self.run >= 2 {
                let fa = ((p[i] - 2.0 * h[0][i] + h[1][i]) / (t * t)).abs();
                self.peaks[i].fd_acceleration = self.peaks[i].fd_acceleration.max(fa);
                self.flag(
                    sp,
                    i,
                    "acceleration (finite difference)",
                    fa,
                    lim.acceleration,
                    4.0 * ulp8 / (t * t),
                );
            }
            let h = &self.history;
            if self.run >= 3 {
                let fj = ((p[i] - 3.0 * h[0][i] + 3.0 * h[1][i] - h[2][i]) / (t * t * t)).abs();
                self.peaks[i].fd_jerk = self.peaks[i].fd_jerk.max(fj);
                if all_soft {
                    self.flag(
                        sp,
                        i,
                        "jerk (finite difference)",
                        fj,
                        lim.jerk,
                        8.0 * ulp8 / (t * t * t),
                    );
                }
            }
        }
        self.history = [p, self.history[0], self.history[1]];
        self.soft_history = [sp.soft, self.soft_history[0], self.soft_history[1]];
        self.seen += 1;
        self.run += 1;
        self.last_t = sp.t;
        self.last_position = p;
    }
}
