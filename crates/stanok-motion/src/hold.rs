//! Feed hold: brake to a stop on the path, stand, resume — inside the interpolator.
//!
//! ## Algorithm
//! A piece normally runs its planned profile. A hold requested for time t_h takes effect at the
//! first servo instant t ≥ t_h: from the state (s, v) there the machine **brakes** linearly at the
//! piece's tangential acceleration limit a (spec axioma-2 §3.5: operator interventions change the
//! speed linearly, in BRISK and SOFT alike), s(τ) = s + vτ − ½aτ². If the piece ends first, braking
//! goes on in the next piece from the speed reached, with that piece's a. Because the planned
//! profile obeys the same per-piece limit, the braking speed is never above the planned one at the
//! same path position: every speed limit still holds, and the planned profile (which can always
//! stop within the look-ahead window) guarantees that braking ends before the path does.
//!
//! At rest the machine **stands** for the requested time, then **resumes**: the rest of the piece
//! runs a profile from 0 to min(planned exit, reach(0, rest)) and each following piece from the
//! speed actually reached to min(planned exit, reach(entry)) — "catching up" with the plan, never
//! above it, so the planner's deceleration guarantees carry over. Once a piece ends at its planned
//! exit speed, the plan is followed again.
//!
//! Known limits: a hold in a SOFT piece switches acceleration instantly (the braking is
//! trapezoidal); catch-up profiles are trapezoids in BRISK and S-curves in SOFT. One hold at a
//! time.
//!
//! ## The operator's button ([`HoldSwitch`])
//! A planned hold (`request(at, standstill)`, the CLI's `--feed-hold`) knows its standstill in
//! advance. An operator's hold does not: the panel (`stanok-serve`) shares a [`HoldSwitch`] with the
//! interpolator, which reads it at every servo instant. Pressed, it starts a hold with an open
//! standstill ([`OPEN_STANDSTILL`]); released, it ends the standstill at that instant and the
//! resume above runs unchanged. The switch is an atomic flag: the other thread never waits for the
//! servo loop, nor the servo loop for it.

use crate::interpolator::Profile;
use crate::planner::{reach, PlannedPiece};
use crate::profile_scurve::SCurve;
use crate::profile_trapezoid::{Kinematics, Trapezoid};
use std::sync::atomic::{AtomicBool, Ordering};

/// The standstill of an operator's hold, s: long enough to mean "until released" (31 years), finite
/// so that every phase keeps a finite duration.
pub const OPEN_STANDSTILL: f64 = 1e9;

/// The operator's feed-hold button, shared between the panel's thread and the interpolator (module
/// doc).
#[derive(Debug, Default)]
pub struct HoldSwitch {
    held: AtomicBool,
}

impl HoldSwitch {
    /// Presses (true) or releases (false) feed hold.
    pub fn set(&self, held: bool) {
        self.held.store(held, Ordering::Relaxed);
    }

    /// True while feed hold is pressed.
    pub fn is_held(&self) -> bool {
        self.held.load(Ordering::Relaxed)
    }
}

/// What runs on (part of) a piece.
#[derive(Debug, Clone, Copy)]
pub enum Phase {
    /// A profile over the rest of the piece from arc length `s0` (the planned one when `planned`).
    Run {
        /// The time law, from s0.
        profile: Profile,
        /// Where it starts on the piece.
        s0: f64,
        /// The planner's own profile (false: a catch-up after a hold).
        planned: bool,
        /// Speed at the piece end.
        v_exit: f64,
    },
    /// Linear braking from `v0` at `a`, from `s0`; ends at rest or at the piece end.
    Brake {
        /// Where it starts.
        s0: f64,
        /// Speed there.
        v0: f64,
        /// Deceleration.
        a: f64,
        /// Length of the piece.
        length: f64,
    },
    /// Standing at `s0` for `seconds`.
    Stand {
        /// Where.
        s0: f64,
        /// How long.
        seconds: f64,
    },
    /// Standing at `s0` because the override in force gives the piece a speed of 0 (see
    /// [`crate::overrides`]), until it rises.
    Stall {
        /// Where.
        s0: f64,
    },
    /// SOFT: the acceleration `a0` > 0 brought to zero at jerk −`j`, before an override change
    /// applies (see [`crate::overrides`]).
    Reset {
        /// Where it starts.
        s0: f64,
        /// Speed there.
        v0: f64,
        /// Acceleration there, > 0.
        a0: f64,
        /// Jerk, > 0.
        j: f64,
    },
}

impl Phase {
    /// Duration, s.
    pub fn duration(&self) -> f64 {
        let d = match *self {
            Phase::Run { profile, .. } => profile.duration(),
            Phase::Brake { s0, v0, a, length } => {
                let rest = (length - s0).max(0.0);
                if brake_stops_within(v0, a, rest) {
                    v0 / a
                } else {
                    (v0 - (v0 * v0 - 2.0 * a * rest).max(0.0).sqrt()) / a
                }
            }
            Phase::Stand { seconds, .. } => seconds,
            Phase::Stall { .. } => OPEN_STANDSTILL,
            Phase::Reset { a0, j, .. } => a0 / j,
        };
        if d.is_finite() && d >= 0.0 {
            d
        } else {
            0.0
        }
    }

    /// State at `t` from the phase start (arc length from the piece start).
    pub fn at(&self, t: f64) -> Kinematics {
        match *self {
            Phase::Run { profile, s0, .. } => {
                let mut k = profile.at(t);
                k.s += s0;
                k
            }
            Phase::Brake { s0, v0, a, .. } => {
                let t = t.clamp(0.0, self.duration());
                Kinematics {
                    s: s0 + v0 * t - 0.5 * a * t * t,
                    v: (v0 - a * t).max(0.0),
                    a: -a,
                    j: 0.0,
                }
            }
            Phase::Stand { s0, .. } | Phase::Stall { s0 } => Kinematics {
                s: s0,
                ..Default::default()
            },
            Phase::Reset { s0, v0, a0, j } => {
                let t = t.clamp(0.0, a0 / j);
                Kinematics {
                    s: s0 + v0 * t + 0.5 * a0 * t * t - j * t * t * t / 6.0,
                    v: v0 + a0 * t - 0.5 * j * t * t,
                    a: a0 - j * t,
                    j: -j,
                }
            }
        }
    }

    /// True if the phase is smooth enough for SOFT's jerk check (the planned profile, an
    /// override's profile, the acceleration reset); false for a hold's trapezoidal braking and
    /// its catch-up.
    pub fn is_smooth(&self) -> bool {
        matches!(
            self,
            Phase::Run { planned: true, .. } | Phase::Reset { .. } | Phase::Stall { .. }
        )
    }

    /// True if the phase is a profile that comes to rest before the piece ends (a zero override):
    /// a stall follows it, at the returned arc length.
    pub fn stalls_at(&self, piece: &PlannedPiece) -> Option<f64> {
        match *self {
            Phase::Run { profile, s0, .. } => {
                let reached = s0 + profile.reached();
                (reached < piece.piece.length * (1.0 - 1e-12) - 1e-12).then_some(reached)
            }
            _ => None,
        }
    }

    /// True for the planner's own profile.
    pub fn is_planned(&self) -> bool {
        matches!(self, Phase::Run { planned: true, .. })
    }

    /// Speed at the end of the phase.
    pub fn exit_speed(&self, piece: &PlannedPiece) -> f64 {
        match *self {
            Phase::Run { v_exit, .. } => v_exit,
            Phase::Brake { s0, v0, a, length } => {
                if brake_stops_within(v0, a, length - s0) {
                    0.0
                } else {
                    (v0 * v0 - 2.0 * a * (length - s0).max(0.0)).max(0.0).sqrt()
                }
            }
            Phase::Stand { .. } | Phase::Stall { .. } => 0.0,
            Phase::Reset { .. } => self.at(self.duration()).v,
        }
        .max(0.0)
        .min(if piece.piece.length > 0.0 {
            f64::INFINITY
        } else {
            0.0
        })
    }

    /// True if the piece ends with this phase.
    pub fn is_last(&self, piece: &PlannedPiece) -> bool {
        match self {
            Phase::Run { .. } => true,
            Phase::Brake { s0, v0, a, length } => {
                !brake_stops_within(*v0, *a, length - s0) || piece.piece.length <= 0.0
            }
            Phase::Stand { .. } | Phase::Stall { .. } | Phase::Reset { .. } => false,
        }
    }
}

/// Braking from `v0` at `a` comes to rest within `rest` (one test, used everywhere, so that the
/// phase's duration, end speed and "is it the last phase" never disagree by rounding).
fn brake_stops_within(v0: f64, a: f64, rest: f64) -> bool {
    v0 * v0 <= 2.0 * a * rest.max(0.0)
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum State {
    Idle,
    Requested {
        at: f64,
        standstill: f64,
    },
    Braking {
        v: f64,
        standstill: f64,
    },
    /// After a hold, the next piece may start below its planned speed.
    CatchingUp {
        v: f64,
    },
}

/// The hold state machine (module doc).
#[derive(Debug, Clone, Copy)]
pub struct FeedHold {
    state: State,
}

impl Default for FeedHold {
    fn default() -> Self {
        FeedHold { state: State::Idle }
    }
}

fn run_from(piece: &PlannedPiece, s0: f64, v_in: f64) -> Phase {
    let pc = &piece.piece;
    let rest = (pc.length - s0).max(0.0);
    let mut rest_piece = pc.clone();
    rest_piece.length = rest;
    let v_exit = piece.v_exit.min(reach(v_in, &rest_piece));
    let profile = if pc.soft {
        Profile::SCurve(SCurve::new(
            rest, v_in, v_exit, pc.v_max, pc.a_max, pc.j_max,
        ))
    } else {
        Profile::Trapezoid(Trapezoid::new(rest, v_in, v_exit, pc.v_max, pc.a_max))
    };
    Phase::Run {
        profile,
        s0,
        planned: false,
        v_exit,
    }
}

impl FeedHold {
    /// A hold from `at` (s) with `standstill` seconds at rest.
    pub fn request(&mut self, at: f64, standstill: f64) {
        let standstill = if standstill.is_finite() && standstill > 0.0 {
            standstill
        } else {
            0.0
        };
        if at.is_finite() {
            self.state = State::Requested { at, standstill };
        }
    }

    /// The operator pressed hold at `t`: a hold with an open standstill, unless one is already
    /// under way.
    pub fn press(&mut self, t: f64) {
        if matches!(self.state, State::Idle | State::CatchingUp { .. }) {
            self.state = State::Requested {
                at: t,
                standstill: OPEN_STANDSTILL,
            };
        }
    }

    /// The planner re-planned from the machine's actual state (an override change): nothing is
    /// left to catch up with.
    pub fn replanned(&mut self) {
        if let State::CatchingUp { .. } = self.state {
            self.state = State::Idle;
        }
    }

    /// True while a hold brakes or stands (an override change then waits for the resume).
    pub fn is_holding(&self) -> bool {
        matches!(self.state, State::Braking { .. })
    }

    /// The operator released hold before it took effect: the open request is withdrawn.
    pub fn withdraw(&mut self) {
        if let State::Requested { standstill, .. } = self.state {
            if standstill >= OPEN_STANDSTILL {
                self.state = State::Idle;
            }
        }
    }

    /// How a newly released piece starts.
    pub fn first_phase(&mut self, piece: &PlannedPiece) -> Phase {
        let pc = &piece.piece;
        match self.state {
            State::Braking { v, .. } if pc.length > 0.0 => Phase::Brake {
                s0: 0.0,
                v0: v.min(piece.v_entry),
                a: pc.a_max,
                length: pc.length,
            },
            State::CatchingUp { v } if pc.length > 0.0 && v < piece.v_entry => {
                let phase = run_from(piece, 0.0, v);
                let reached = phase.exit_speed(piece);
                self.state = if reached >= piece.v_exit {
                    State::Idle
                } else {
                    State::CatchingUp { v: reached }
                };
                phase
            }
            _ => {
                if let State::CatchingUp { .. } = self.state {
                    self.state = State::Idle;
                }
                Phase::Run {
                    profile: Profile::of(piece),
                    s0: 0.0,
                    planned: true,
                    v_exit: piece.v_exit,
                }
            }
        }
    }

    /// Called at every servo instant with the state there: the phase to switch to, if a
    /// requested hold starts now.
    pub fn trigger(
        &mut self,
        t: f64,
        phase: &Phase,
        k: Kinematics,
        piece: &PlannedPiece,
    ) -> Option<Phase> {
        let State::Requested { at, standstill } = self.state else {
            return None;
        };
        if t < at || !matches!(phase, Phase::Run { .. }) || piece.piece.length <= 0.0 {
            return None;
        }
        self.state = State::Braking { v: k.v, standstill };
        let pc = &piece.piece;
        Some(Phase::Brake {
            s0: k.s.min(pc.length),
            v0: k.v,
            a: pc.a_max,
            length: pc.length,
        })
    }

    /// The phase after `phase` ended at `t` on the same piece.
    pub fn next_phase(&mut self, phase: &Phase, _t: f64, piece: &PlannedPiece) -> Phase {
        match (*phase, self.state) {
            (Phase::Brake { .. }, State::Braking { standstill, .. }) => {
                let s0 = phase.at(phase.duration()).s;
                self.state = State::CatchingUp { v: 0.0 };
                Phase::Stand {
                    s0,
                    seconds: standstill,
                }
            }
            (Phase::Stand { s0, .. }, _) => {
                let phase = run_from(piece, s0, 0.0);
                let reached = phase.exit_speed(piece);
                self.state = if reached >= piece.v_exit {
                    State::Idle
                } else {
                    State::CatchingUp { v: reached }
                };
                phase
            }
            // Not reached (a Run phase is always the last); finish the piece at rest.
            _ => Phase::Stand {
                s0: piece.piece.length,
                seconds: 0.0,
            },
        }
    }

    /// Braking that crossed into the next piece carries its speed there.
    pub fn carry(&mut self, phase: &Phase, piece: &PlannedPiece) {
        if let (Phase::Brake { .. }, State::Braking { standstill, .. }) = (*phase, self.state) {
            self.state = State::Braking {
                v: phase.exit_speed(piece),
                standstill,
            };
        }
    }
}
