//! The servo-rate interpolator: planned pieces → axis setpoints every servo period.
//!
//! ## Algorithm
//! Time runs on one global grid t_k = k·T (T = servo period). A released piece occupies
//! [t_start, t_start + duration) of the timeline, with its profile (trapezoid for BRISK, S-curve
//! for SOFT, standstill for a dwell); every grid instant inside that interval is sampled at
//! τ = t_k − t_start: path position s(τ), speed, acceleration and jerk from the profile, then the
//! point, tangent and curvature of the piece's shape at s. Axis quantities follow by the chain rule:
//! * velocity_i = v·t_i
//! * acceleration_i = a·t_i + v²·κ_i
//! * jerk_i = j·t_i + 3·v·a·κ_i + v³·q_i (κ = d²p/ds², |κ| = 1/r on arcs, 0 on lines;
//!   q = d³p/ds³ = −|κ|²·t + κ'·n, −t/r² on arcs, with κ' the clothoid's curvature rate).
//!
//! A piece that ends at rest (an exact stop, a dwell, the end) is stretched to the next grid
//! instant: the machine waits there, so the trace contains the stop point exactly, at rest, and
//! the next piece starts on the grid. This costs less than one period per stop.
//!
//! [`Interpolator::finish`] emits one more setpoint at the first grid instant at or after the end
//! of the last piece, exactly at that piece's end point and at rest. So the trace starts at t = 0,
//! has one setpoint per period, and its duration is the planned time rounded up to a whole period.
//!
//! ## Invariants
//! * Per setpoint: a fixed amount of arithmetic, no allocation, no loop that depends on the input
//!   (the caller's sink decides what to do with it).
//! * The profile never leaves the piece (s clamped to [0, length]); a piece's last point is its
//!   exact `end`.

use crate::hold::{FeedHold, HoldSwitch, Phase, OPEN_STANDSTILL};
use crate::piece::Shape;
use crate::planner::PlannedPiece;
use crate::profile_scurve::SCurve;
use crate::profile_trapezoid::{Kinematics, Trapezoid};
use crate::segment::{Point9, Spindles};
use std::sync::Arc;

/// One servo-period setpoint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setpoint {
    /// Time from the start of the run, s.
    pub t: f64,
    /// Axis positions, mm/deg (X Y Z A B C U V W).
    pub position: Point9,
    /// Analytic axis velocities, unit/s.
    pub velocity: Point9,
    /// Analytic axis accelerations, unit/s².
    pub acceleration: Point9,
    /// Analytic axis jerks, unit/s³ (meaningful in SOFT; BRISK switches acceleration instantly).
    pub jerk: Point9,
    /// The piece runs a SOFT profile.
    pub soft: bool,
    /// Source line of the piece.
    pub line: u32,
    /// Serial number of the Canon command of the piece ([`crate::MotionStage::commands`]): the
    /// setpoints of command n run under every state change of the commands before n.
    pub command: u64,
    /// Commanded speed of each spindle (0 = main) at this instant, rev/min (under G96 the law
    /// evaluated at `position`).
    pub spindle_rpm: [f64; 4],
}

/// The time law of one piece.
#[derive(Debug, Clone, Copy)]
pub enum Profile {
    /// BRISK.
    Trapezoid(Trapezoid),
    /// SOFT.
    SCurve(SCurve),
    /// Standing still, s.
    Dwell(f64),
}

impl Profile {
    /// The profile of a planned piece.
    pub fn of(p: &PlannedPiece) -> Profile {
        let pc = &p.piece;
        match pc.shape {
            Shape::Dwell { seconds, .. } => Profile::Dwell(seconds),
            _ if pc.soft => Profile::SCurve(SCurve::new(
                pc.length, p.v_entry, p.v_exit, pc.v_max, pc.a_max, pc.j_max,
            )),
            _ => Profile::Trapezoid(Trapezoid::new(
                pc.length, p.v_entry, p.v_exit, pc.v_max, pc.a_max,
            )),
        }
    }

    /// Duration, s.
    pub fn duration(&self) -> f64 {
        match self {
            Profile::Trapezoid(t) => t.duration(),
            Profile::SCurve(s) => s.duration(),
            Profile::Dwell(d) => *d,
        }
    }

    /// State at `t` from the piece start.
    #[inline]
    pub fn at(&self, t: f64) -> Kinematics {
        match self {
            Profile::Trapezoid(p) => p.at(t),
            Profile::SCurve(p) => p.at(t),
            Profile::Dwell(_) => Kinematics::default(),
        }
    }
}

/// The setpoint of a piece at path state `k` (module doc).
#[inline]
pub fn sample(piece: &PlannedPiece, k: Kinematics, t: f64) -> Setpoint {
    let pc = &piece.piece;
    let s = k.s.clamp(0.0, pc.length);
    let pt = if s >= pc.length {
        None
    } else {
        Some(pc.shape.at(s))
    };
    let mut sp = Setpoint {
        t,
        position: pc.end,
        velocity: [0.0; 9],
        acceleration: [0.0; 9],
        jerk: [0.0; 9],
        soft: pc.soft,
        line: pc.line,
        command: pc.command,
        spindle_rpm: [0.0; 4],
    };
    let pt = pt.unwrap_or_else(|| {
        let mut end = pc.shape.at(pc.length);
        end.position = pc.end;
        end
    });
    sp.position = pt.position;
    sp.spindle_rpm = pc.spindles.rpm_at(&sp.position);
    let (v, a, j) = (k.v, k.a, k.j);
    for i in 0..9 {
        let (ti, ki, qi) = (pt.tangent[i], pt.curvature[i], pt.third[i]);
        sp.velocity[i] = v * ti;
        sp.acceleration[i] = a * ti + v * v * ki;
        sp.jerk[i] = j * ti + 3.0 * v * a * ki + v * v * v * qi;
    }
    sp
}

/// Samples released pieces on the servo grid (module doc).
#[derive(Debug, Clone)]
pub struct Interpolator {
    period: f64,
    tick: u64,
    piece_start: f64,
    end: Point9,
    line: u32,
    command: u64,
    spindles: Spindles,
    hold: FeedHold,
    switch: Option<Arc<HoldSwitch>>,
}

impl Interpolator {
    /// Starts at t = 0 standing at `at`.
    pub fn new(period: f64, at: Point9) -> Self {
        Interpolator {
            period,
            tick: 0,
            piece_start: 0.0,
            end: at,
            line: 0,
            command: 0,
            spindles: Spindles::default(),
            hold: FeedHold::default(),
            switch: None,
        }
    }

    /// Where the machine stands once every piece received so far has run.
    pub fn end(&self) -> Point9 {
        self.end
    }

    /// Moves the standing point (before any motion: the program's initial position).
    pub fn set_position(&mut self, at: Point9) {
        self.end = at;
    }

    /// Planned time of the pieces received so far, s (not rounded to the period).
    pub fn planned_time(&self) -> f64 {
        self.piece_start
    }

    /// Setpoints emitted so far.
    pub fn ticks(&self) -> u64 {
        self.tick
    }

    /// The servo period, s.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Requests a feed hold: from the first servo instant at or after `at` (s), the machine brakes
    /// along the path at each piece's acceleration limit, stands still for `standstill` seconds,
    /// then resumes (see [`crate::hold`]).
    pub fn request_hold(&mut self, at: f64, standstill: f64) {
        self.hold.request(at, standstill);
    }

    /// Connects the operator's feed-hold button, read at every servo instant (see [`crate::hold`]).
    pub fn set_hold_switch(&mut self, switch: Arc<HoldSwitch>) {
        self.switch = Some(switch);
    }

    /// Samples one piece: every grid instant in its time interval goes to `out`.
    pub fn push(&mut self, piece: &PlannedPiece, out: &mut impl FnMut(&Setpoint)) {
        let mut phase = self.hold.first_phase(piece);
        let mut phase_start = self.piece_start;
        loop {
            let duration = phase.duration();
            let mut phase_end = phase_start + duration;
            let last = phase.is_last(piece);
            if last && phase.exit_speed(piece) == 0.0 {
                // A stop: the machine stands at the exact end until the next servo instant, so
                // that the trace holds the stop point itself (and the next piece starts on the
                // grid).
                let ticks = (phase_end / self.period).ceil();
                if ticks.is_finite() && ticks >= 0.0 {
                    phase_end = ticks * self.period;
                }
            }
            let mut switched = None;
            loop {
                let t = self.tick as f64 * self.period;
                if t >= phase_end {
                    break;
                }
                let k = phase.at(t - phase_start);
                if let Some(switch) = &self.switch {
                    if switch.is_held() {
                        self.hold.press(t);
                    } else if matches!(phase, Phase::Stand { seconds, .. } if seconds >= OPEN_STANDSTILL)
                    {
                        switched = Some((self.hold.next_phase(&phase, t, piece), t));
                        break;
                    } else {
                        self.hold.withdraw();
                    }
                }
                if let Some(next) = self.hold.trigger(t, &phase, k, piece) {
                    switched = Some((next, t));
                    break;
                }
                let mut sp = sample(piece, k, t);
                sp.soft &= phase.is_planned();
                out(&sp);
                self.tick += 1;
            }
            match switched {
                Some((next, t)) => {
                    phase = next;
                    phase_start = t;
                }
                None if last => {
                    self.hold.carry(&phase, piece);
                    self.piece_start = phase_end;
                    break;
                }
                None => {
                    phase = self.hold.next_phase(&phase, phase_end, piece);
                    phase_start = phase_end;
                }
            }
        }
        self.end = piece.piece.end;
        self.line = piece.piece.line;
        self.command = piece.piece.command;
        self.spindles = piece.piece.spindles;
    }

    /// The last setpoint: at the end point, at rest, on the first grid instant at or after the
    /// end of the last piece. Returns the trace duration (that instant), s.
    pub fn finish(&mut self, out: &mut impl FnMut(&Setpoint)) -> f64 {
        let t = self.tick as f64 * self.period;
        out(&Setpoint {
            t,
            position: self.end,
            velocity: [0.0; 9],
            acceleration: [0.0; 9],
            jerk: [0.0; 9],
            soft: false,
            line: self.line,
            command: self.command,
            spindle_rpm: self.spindles.rpm_at(&self.end),
        });
        self.tick += 1;
        t
    }
}
