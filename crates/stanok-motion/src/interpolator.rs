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
//! ## Bounded work for long steady phases (optional)
//! With [`Interpolator::set_skip_steady`] (the simulated machine turns it on when no observer
//! needs every setpoint), a stretch where nothing changes but the position along a straight line
//! — a dwell, a standstill, the constant-speed cruise of a line — is not stepped one period at a
//! time: after emitting a setpoint inside it, the grid jumps to four instants before its end and
//! goes on from there. Every emitted setpoint is still exact for its time; a consumer sees a gap
//! in `t` (the monitor restarts its finite differences after one), and the work of a 1,000,000 s
//! dwell is a handful of setpoints instead of 10⁹. Arcs, blends and a pending feed hold are
//! always stepped, and so is everything while an override can change (a connected switch, a
//! scheduled change ahead). With [`Interpolator::set_time_limit`] the interpolator stops at the first grid
//! instant past the limit and emits nothing more ([`Interpolator::stopped_at`]).
//!
//! ## Invariants
//! * Per setpoint: a fixed amount of arithmetic, no allocation, no loop that depends on the input
//!   (the caller's sink decides what to do with it).
//! * The profile never leaves the piece (s clamped to [0, length]); a piece's last point is its
//!   exact `end`.

use crate::hold::{FeedHold, HoldSwitch, Phase, OPEN_STANDSTILL};
use crate::overrides::{OverrideChange, OverrideInput, OverrideSwitch};
use crate::piece::{Overrides, Shape};
use crate::planner::{PlannedPiece, Planner};
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
    /// The programmed segment the piece belongs to (the stage's running number, see
    /// [`crate::path::PathBuilder::next_seq`]).
    pub seq: u64,
    /// The piece is a blend joining two programmed segments (a junction).
    pub junction: bool,
    /// Serial number of the Canon command of the piece ([`crate::MotionStage::commands`]): the
    /// setpoints of command n run under every state change of the commands before n.
    pub command: u64,
    /// Commanded speed of each spindle (0 = main) at this instant, rev/min (under G96 the law
    /// evaluated at `position`; times the spindle override), whether it turns or not.
    pub spindle_rpm: [f64; 4],
    /// How each spindle turns: +1 clockwise (M3), −1 counter-clockwise (M4), 0 stopped.
    pub spindle_dir: [i8; 4],
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

    /// Arc length at the end of the profile (less than the piece's length when it stalls).
    pub fn reached(&self) -> f64 {
        match self {
            Profile::Trapezoid(p) => p.reached(),
            Profile::SCurve(p) => p.reached(),
            Profile::Dwell(_) => 0.0,
        }
    }

    /// The profile of the rest of a piece, `rest` long, from `v0` to `v1` at its limits.
    pub fn rest_of(pc: &crate::piece::Piece, rest: f64, v0: f64, v1: f64) -> Profile {
        if pc.soft {
            Profile::SCurve(SCurve::new(rest, v0, v1, pc.v_max, pc.a_max, pc.j_max))
        } else {
            Profile::Trapezoid(Trapezoid::new(rest, v0, v1, pc.v_max, pc.a_max))
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
        seq: pc.seq,
        junction: pc.junction,
        command: pc.command,
        spindle_rpm: [0.0; 4],
        spindle_dir: pc.spindles.directions(),
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

/// How a piece ran: its time and what its setpoints were doing (for the report's limiting factor,
/// [`crate::timing`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PieceRun {
    /// Time from the piece's start to its end (to the next grid instant after a stop), s.
    pub duration: f64,
    /// Setpoints at constant path speed.
    pub cruising: u64,
    /// Setpoints speeding up or slowing down (and the wait for the grid at a stop).
    pub ramping: u64,
    /// Setpoints standing in a feed hold or a zero-override stall.
    pub standing: u64,
}

/// Samples released pieces on the servo grid (module doc).
#[derive(Debug, Clone)]
pub struct Interpolator {
    period: f64,
    tick: u64,
    piece_start: f64,
    end: Point9,
    line: u32,
    seq: u64,
    command: u64,
    spindles: Spindles,
    hold: FeedHold,
    switch: Option<Arc<HoldSwitch>>,
    overrides: OverrideInput,
    /// A zero override stalled the machine and nothing can raise it again: the rest of the run
    /// is not executed (the machine stands where it stopped).
    stalled_for_good: bool,
    /// Skip steady stretches (module doc).
    skip_steady: bool,
    /// Stop at the first grid instant past this time, s.
    time_limit: f64,
    /// The time it stopped at, once it has.
    stopped_at: Option<f64>,
}

/// The stretch of a phase, from its start, where the path speed is constant, s.
fn steady_stretch(phase: &Phase) -> Option<(f64, f64)> {
    match phase {
        Phase::Run {
            profile: Profile::Trapezoid(p),
            ..
        } => Some(p.cruise()),
        Phase::Run {
            profile: Profile::SCurve(p),
            ..
        } => Some(p.cruise()),
        Phase::Run {
            profile: Profile::Dwell(d),
            ..
        } => Some((0.0, *d)),
        Phase::Stand { seconds, .. } => Some((0.0, *seconds)),
        Phase::Brake { .. } | Phase::Stall { .. } | Phase::Reset { .. } => None,
    }
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
            seq: 0,
            command: 0,
            spindles: Spindles::default(),
            hold: FeedHold::default(),
            switch: None,
            overrides: OverrideInput::default(),
            stalled_for_good: false,
            skip_steady: false,
            time_limit: f64::INFINITY,
            stopped_at: None,
        }
    }

    /// Skips steady stretches (module doc): for a consumer that does not need every setpoint.
    pub fn set_skip_steady(&mut self, on: bool) {
        self.skip_steady = on;
    }

    /// Stops at the first grid instant past `seconds` of simulated time (module doc).
    pub fn set_time_limit(&mut self, seconds: f64) {
        self.time_limit = seconds;
    }

    /// The time at which the limit stopped it.
    pub fn stopped_at(&self) -> Option<f64> {
        self.stopped_at
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

    /// Connects the operator's override knobs, read at every servo instant (see
    /// [`crate::overrides`]).
    pub fn set_override_switch(&mut self, switch: Arc<OverrideSwitch>) {
        self.overrides.set_switch(switch);
    }

    /// Timed override changes (machine time; see [`crate::overrides`]).
    pub fn schedule_overrides(&mut self, changes: &[OverrideChange]) {
        self.overrides.schedule(changes);
    }

    /// The override factors wanted from the next servo instant on.
    pub fn set_overrides(&mut self, overrides: Overrides) {
        self.overrides.set(overrides);
    }

    /// True if a zero override stopped the machine for good (nothing could raise it): the rest of
    /// the run did not execute.
    pub fn stalled_for_good(&self) -> bool {
        self.stalled_for_good
    }

    /// An override change at state `k` of `phase` (module doc of [`crate::overrides`]): the phase
    /// to switch to, or None (the current phase goes on; the change waits or only re-planned the
    /// pieces ahead).
    fn override_change(
        &mut self,
        wanted: Overrides,
        piece: &mut PlannedPiece,
        phase: &Phase,
        k: Kinematics,
        planner: &mut Planner,
    ) -> Option<Phase> {
        let pc = &piece.piece;
        match *phase {
            Phase::Run { profile, .. } => {
                if let Profile::Dwell(_) = profile {
                    planner.replan_overrides(wanted, pc, 0.0);
                    return None;
                }
                if pc.soft && k.a < 0.0 {
                    // A SOFT deceleration ramp ends at zero acceleration: the change waits.
                    return None;
                }
                if pc.soft && k.a > 0.0 {
                    let j = pc.j_max;
                    let reset = Phase::Reset {
                        s0: k.s,
                        v0: k.v,
                        a0: k.a,
                        j,
                    };
                    // Only if the reset ends on this piece; otherwise the piece ends first, at
                    // zero acceleration, and the next one takes the change.
                    if j > 0.0 && reset.at(reset.duration()).s < pc.length {
                        return Some(reset);
                    }
                    return None;
                }
                Some(self.rerun(wanted, piece, k.s, k.v, planner))
            }
            Phase::Stall { s0 } => Some(self.rerun(wanted, piece, s0, 0.0, planner)),
            Phase::Brake { .. } | Phase::Stand { .. } => {
                // A hold is under way: the pieces ahead get the new speeds; the hold's resume
                // catches up with the new plan.
                let cap = pc.programmed_speed(&wanted);
                piece.piece.set_limits(cap, 0.0, planner.axes());
                let mut rest = piece.piece.clone();
                rest.length = (rest.length - k.s).max(0.0);
                piece.v_exit = planner.replan_overrides(wanted, &rest, 0.0);
                None
            }
            Phase::Reset { .. } => None,
        }
    }

    /// The rest of `piece` from arc length `s` at speed `v` (zero acceleration) under the
    /// override factors `wanted`: new limits, the window re-planned, the new profile.
    fn rerun(
        &mut self,
        wanted: Overrides,
        piece: &mut PlannedPiece,
        s: f64,
        v: f64,
        planner: &mut Planner,
    ) -> Phase {
        let cap = piece.piece.programmed_speed(&wanted);
        piece.piece.set_limits(cap, v, planner.axes());
        let rest = (piece.piece.length - s).max(0.0);
        let mut rest_piece = piece.piece.clone();
        rest_piece.length = rest;
        let e = planner.replan_overrides(wanted, &rest_piece, v);
        piece.v_exit = e;
        self.hold.replanned();
        Phase::Run {
            profile: Profile::rest_of(&piece.piece, rest, v, e),
            s0: s,
            planned: true,
            v_exit: e,
        }
    }

    /// Samples one piece: every grid instant in its time interval goes to `out`. Override
    /// changes re-plan what `planner` still holds.
    pub fn push(
        &mut self,
        mut piece: PlannedPiece,
        planner: &mut Planner,
        out: &mut impl FnMut(&Setpoint),
    ) -> PieceRun {
        let started = self.piece_start;
        let mut run = PieceRun::default();
        if self.stalled_for_good || self.stopped_at.is_some() {
            return run;
        }
        let straight = matches!(piece.piece.shape, Shape::Line { .. } | Shape::Dwell { .. });
        let mut phase = self.hold.first_phase(&piece);
        let mut phase_start = self.piece_start;
        loop {
            let duration = phase.duration();
            let mut phase_end = phase_start + duration;
            let stall = phase.stalls_at(&piece);
            let last = phase.is_last(&piece) && stall.is_none();
            if let (Phase::Stall { .. }, false) =
                (phase, self.overrides.can_change(planner.overrides()))
            {
                // Nothing can raise the override again: the machine stands here for good.
                self.stalled_for_good = true;
                self.end = piece.piece.shape.at(phase.at(0.0).s).position;
                self.line = piece.piece.line;
                self.seq = piece.piece.seq;
                self.spindles = piece.piece.spindles;
                self.piece_start = self.tick as f64 * self.period;
                run.duration = self.piece_start - started;
                return run;
            }
            if last && phase.exit_speed(&piece) == 0.0 {
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
                if let Some(wanted) = self.overrides.poll(t, planner.overrides()) {
                    if let Some(next) = self.override_change(wanted, &mut piece, &phase, k, planner)
                    {
                        switched = Some((next, t));
                        break;
                    }
                }
                if let Some(switch) = &self.switch {
                    if switch.is_held() {
                        self.hold.press(t);
                    } else if matches!(phase, Phase::Stand { seconds, .. } if seconds >= OPEN_STANDSTILL)
                    {
                        switched = Some((self.hold.next_phase(&phase, t, &piece), t));
                        break;
                    } else {
                        self.hold.withdraw();
                    }
                }
                if let Some(next) = self.hold.trigger(t, &phase, k, &piece) {
                    switched = Some((next, t));
                    break;
                }
                match phase {
                    Phase::Stall { .. } | Phase::Stand { .. } => run.standing += 1,
                    _ if k.a == 0.0 && k.v > 0.0 => run.cruising += 1,
                    _ => run.ramping += 1,
                }
                let mut sp = sample(&piece, k, t);
                sp.soft &= phase.is_smooth();
                let spindle = planner.overrides().spindle;
                if spindle != 1.0 {
                    sp.spindle_rpm = sp.spindle_rpm.map(|n| n * spindle);
                }
                if t > self.time_limit {
                    // Stand where the limit caught the machine: `finish` ends the trace there.
                    self.stopped_at = Some(t);
                    self.end = sp.position;
                    self.line = piece.piece.line;
                    self.seq = piece.piece.seq;
                    self.spindles = piece.piece.spindles;
                    self.piece_start = t;
                    run.duration = t - started;
                    return run;
                }
                out(&sp);
                self.tick += 1;
                if self.skip_steady
                    && self.switch.is_none()
                    && self.hold.is_idle()
                    && !self.overrides.can_change(planner.overrides())
                {
                    let before = self.tick;
                    self.skip_within(&phase, phase_start, phase_end, straight, t);
                    // The instants skipped are steady ones of this sample's kind: the block's
                    // timing counts them as if they had been sampled.
                    let skipped = self.tick.saturating_sub(before);
                    match phase {
                        Phase::Stall { .. } | Phase::Stand { .. } => run.standing += skipped,
                        _ if k.a == 0.0 && k.v > 0.0 => run.cruising += skipped,
                        _ => run.ramping += skipped,
                    }
                }
            }
            match switched {
                Some((next, t)) => {
                    phase = next;
                    phase_start = t;
                }
                None if last => {
                    self.hold.carry(&phase, &piece);
                    self.piece_start = phase_end;
                    break;
                }
                None => {
                    phase = match (phase, stall) {
                        (_, Some(s0)) => Phase::Stall { s0 },
                        (Phase::Reset { .. }, _) => {
                            // The acceleration is zero: the waiting override change applies.
                            let k = phase.at(phase.duration());
                            let wanted = self
                                .overrides
                                .poll(phase_end, planner.overrides())
                                .unwrap_or(planner.overrides());
                            self.rerun(wanted, &mut piece, k.s, k.v, planner)
                        }
                        _ => self.hold.next_phase(&phase, phase_end, &piece),
                    };
                    phase_start = phase_end;
                }
            }
        }
        self.end = piece.piece.end;
        self.line = piece.piece.line;
        self.seq = piece.piece.seq;
        self.command = piece.piece.command;
        self.spindles = piece.piece.spindles;
        run.duration = self.piece_start - started;
        run
    }

    /// After a setpoint at `t` inside a steady stretch of `phase`, moves the grid to four instants
    /// before the stretch ends (module doc). Positions move only along a straight line there (or
    /// not at all), so no limit can be reached in the instants skipped that the emitted ones do
    /// not show.
    fn skip_within(
        &mut self,
        phase: &Phase,
        phase_start: f64,
        phase_end: f64,
        straight: bool,
        t: f64,
    ) {
        let standing = matches!(phase, Phase::Stand { .. })
            || matches!(
                phase,
                Phase::Run {
                    profile: Profile::Dwell(_),
                    ..
                }
            );
        if !(straight || standing) {
            return;
        }
        let Some((from, to)) = steady_stretch(phase) else {
            return;
        };
        // Never past the time limit: the stop must happen at its first instant.
        let (from, to) = (
            phase_start + from,
            (phase_start + to).min(phase_end).min(self.time_limit),
        );
        if !(t >= from && t < to) {
            return;
        }
        // The last grid instant strictly inside the stretch, minus three: four consecutive
        // setpoints lead out of it, so the finite differences are whole again at its end.
        let last = (to / self.period).ceil() - 1.0;
        let resume = last - 3.0;
        if resume.is_finite() && resume > self.tick as f64 + 8.0 && resume < u64::MAX as f64 {
            self.tick = resume as u64;
        }
    }

    /// The last setpoint: at the end point, at rest, on the first grid instant at or after the
    /// end of the last piece. Returns the trace duration (that instant), s.
    pub fn finish(&mut self, out: &mut impl FnMut(&Setpoint)) -> f64 {
        let t = self.tick as f64 * self.period;
        if self.stalled_for_good {
            self.piece_start = t;
        }
        out(&Setpoint {
            t,
            position: self.end,
            velocity: [0.0; 9],
            acceleration: [0.0; 9],
            jerk: [0.0; 9],
            soft: false,
            line: self.line,
            seq: self.seq,
            junction: false,
            command: self.command,
            spindle_rpm: self.spindles.rpm_at(&self.end),
            spindle_dir: self.spindles.directions(),
        });
        self.tick += 1;
        t
    }
}
