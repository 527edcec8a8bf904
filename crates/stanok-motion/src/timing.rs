//! "Why is it slow here": per block, the planned time, the nominal time and the limit that set its
//! speed.
//!
//! ## Algorithm
//! Every piece the interpolator runs reports its duration and how many setpoints it spent
//! cruising (constant path speed), ramping (speeding up, slowing down, waiting for the grid at a
//! stop) and standing (a feed hold, a zero-override stall) — [`crate::interpolator::PieceRun`].
//! Each class of time has one cause:
//! * **cruising**: what set the piece's speed limit v_max — the programmed feed
//!   ([`Limit::ProgrammedFeed`]) when v_max is the programmed speed times the override, the
//!   override ([`Limit::Override`]) when that is below 100 %, otherwise the shape's own limit:
//!   an axis velocity on a line (or a joint rate under tool-centre-point control), the curvature
//!   on an arc (and on the blends inside a spline), the blend tolerance on a junction blend
//!   (whose curvature the tolerance sets);
//! * **ramping**: an exact stop of the path mode where the piece starts or ends at one
//!   ([`Limit::ExactStop`]), the look-ahead window where the planner released it with an exit
//!   speed set by the window's end ([`Limit::Lookahead`]), otherwise the axis acceleration, or in
//!   SOFT the jerk when its ramps are too short to reach the acceleration limit;
//! * **standing**: the operator ([`Limit::Override`]); a dwell's whole time is [`Limit::Dwell`].
//!
//! A block is a run of pieces of one source line (a canned cycle's moves together; a blend
//! belongs to the block it leads into). Its limit is the cause with the most time; its planned
//! time the sum of its pieces' durations; its nominal time length / programmed speed at 100 %,
//! summed over its pieces (dwells at their programmed time).
//!
//! ## Memory
//! The first [`MAX_BLOCKS`] blocks are kept for `run --json` (then `truncated`); the
//! [`SLOWEST`] blocks that lose the most time against nominal are kept whatever the length.

use crate::interpolator::PieceRun;
use crate::piece::{Overrides, Shape};
use crate::planner::PlannedPiece;

/// Blocks kept for the JSON report.
pub const MAX_BLOCKS: usize = 100_000;
/// Blocks kept as the slowest.
pub const SLOWEST: usize = 10;

/// What set a block's speed (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Limit {
    /// The programmed feed (or rapid rate).
    ProgrammedFeed,
    /// An axis' velocity limit (or a joint's, under tool-centre-point control).
    AxisVelocity,
    /// An axis' acceleration limit: too short to reach the feed, or slowing down for what
    /// follows.
    AxisAcceleration,
    /// SOFT: the jerk limit (ramps too short to reach the acceleration limit).
    Jerk,
    /// The curvature of an arc (centripetal acceleration, in SOFT also its jerk).
    Curvature,
    /// A junction blend, whose curvature the path tolerance sets.
    BlendTolerance,
    /// An exact stop of the path mode (G60/G61, an exact-path corner).
    ExactStop,
    /// The look-ahead window: the planner had to be able to stop at its end.
    Lookahead,
    /// Feed or rapid override below 100 %, a feed hold, a zero-override stall.
    Override,
    /// A programmed dwell.
    Dwell,
}

impl Limit {
    /// Every limit, in report order.
    pub const ALL: [Limit; 10] = [
        Limit::ProgrammedFeed,
        Limit::AxisVelocity,
        Limit::AxisAcceleration,
        Limit::Jerk,
        Limit::Curvature,
        Limit::BlendTolerance,
        Limit::ExactStop,
        Limit::Lookahead,
        Limit::Override,
        Limit::Dwell,
    ];

    /// The name used in reports and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Limit::ProgrammedFeed => "programmed feed",
            Limit::AxisVelocity => "axis velocity",
            Limit::AxisAcceleration => "axis acceleration",
            Limit::Jerk => "jerk",
            Limit::Curvature => "curvature",
            Limit::BlendTolerance => "blend tolerance",
            Limit::ExactStop => "exact stop",
            Limit::Lookahead => "look-ahead window",
            Limit::Override => "override",
            Limit::Dwell => "dwell",
        }
    }

    fn index(self) -> usize {
        Limit::ALL.iter().position(|l| *l == self).unwrap_or(0)
    }
}

/// One block's times and limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockTime {
    /// Source line.
    pub line: u32,
    /// Planned (executed) time, s.
    pub planned_s: f64,
    /// Length / programmed speed, s.
    pub nominal_s: f64,
    /// Path length, mm (in the 9-D pose space of the pieces; 0 for a dwell).
    pub length_mm: f64,
    /// What set its speed for most of its time.
    pub limit: Limit,
}

impl BlockTime {
    /// Time lost against nominal, s.
    pub fn lost_s(&self) -> f64 {
        self.planned_s - self.nominal_s
    }
}

#[derive(Debug, Clone, Copy)]
struct Open {
    line: u32,
    seq: u64,
    planned: f64,
    nominal: f64,
    length: f64,
    by_cause: [f64; 10],
}

/// Collects the blocks' times (module doc).
#[derive(Debug, Clone, Default)]
pub struct BlockTimer {
    open: Option<Open>,
    /// The first blocks, in order (at most [`MAX_BLOCKS`]).
    pub blocks: Vec<BlockTime>,
    /// More blocks ran than `blocks` holds.
    pub truncated: bool,
    /// The blocks losing the most time against nominal, most first (at most [`SLOWEST`]).
    pub slowest: Vec<BlockTime>,
}

/// The cause of a piece's cruising time (module doc).
fn speed_cause(pp: &PlannedPiece, overrides: &Overrides) -> Limit {
    let pc = &pp.piece;
    let cap = pc.programmed_speed(overrides);
    if pc.v_max >= cap * (1.0 - 1e-9) {
        let full = pc.programmed_speed(&Overrides::default());
        return if cap < full * (1.0 - 1e-9) {
            Limit::Override
        } else {
            Limit::ProgrammedFeed
        };
    }
    if pc.v_max >= pc.velocity_cap * (1.0 - 1e-9) {
        return Limit::AxisVelocity;
    }
    match &pc.shape {
        Shape::Line { .. } => Limit::AxisVelocity,
        Shape::Helix { .. } => Limit::Curvature,
        _ if pc.junction => Limit::BlendTolerance,
        _ => Limit::Curvature,
    }
}

/// The cause of a piece's ramping time (module doc).
fn ramp_cause(pp: &PlannedPiece) -> Limit {
    let pc = &pp.piece;
    if pc.exact_stop {
        Limit::ExactStop
    } else if pp.lookahead {
        Limit::Lookahead
    } else if pc.soft && pc.v_max - pp.v_entry.min(pp.v_exit) < pc.a_max * pc.a_max / pc.j_max {
        Limit::Jerk
    } else {
        Limit::AxisAcceleration
    }
}

/// What the timer needs of a piece, taken before it runs ([`PieceInfo::of`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PieceInfo {
    line: u32,
    seq: u64,
    nominal: f64,
    length: f64,
    dwell: bool,
    speed: Limit,
    ramp: Limit,
}

impl PieceInfo {
    /// The piece's block, nominal time and causes under the overrides in force.
    pub fn of(pp: &PlannedPiece, overrides: &Overrides) -> PieceInfo {
        let pc = &pp.piece;
        let (nominal, dwell) = match pc.shape {
            Shape::Dwell { seconds, .. } => (seconds, true),
            _ => {
                let speed = pc.programmed_speed(&Overrides::default());
                (if speed > 0.0 { pc.length / speed } else { 0.0 }, false)
            }
        };
        PieceInfo {
            line: pc.line,
            seq: pc.seq,
            nominal,
            length: if dwell { 0.0 } else { pc.length },
            dwell,
            speed: speed_cause(pp, overrides),
            ramp: ramp_cause(pp),
        }
    }
}

impl BlockTimer {
    /// One piece ran as `run` (module doc).
    pub fn piece(&mut self, info: &PieceInfo, run: &PieceRun) {
        let same = self
            .open
            .as_ref()
            .is_some_and(|o| o.line == info.line && info.seq.saturating_sub(o.seq) <= 1);
        if !same {
            self.close();
            self.open = Some(Open {
                line: info.line,
                seq: info.seq,
                planned: 0.0,
                nominal: 0.0,
                length: 0.0,
                by_cause: [0.0; 10],
            });
        }
        let Some(o) = self.open.as_mut() else {
            return;
        };
        o.seq = info.seq;
        o.planned += run.duration;
        o.nominal += info.nominal;
        o.length += info.length;
        if info.dwell {
            o.by_cause[Limit::Dwell.index()] += run.duration;
            return;
        }
        let ticks = (run.cruising + run.ramping + run.standing).max(1) as f64;
        let per_tick = run.duration / ticks;
        o.by_cause[info.speed.index()] += run.cruising as f64 * per_tick;
        o.by_cause[info.ramp.index()] += run.ramping as f64 * per_tick;
        o.by_cause[Limit::Override.index()] += run.standing as f64 * per_tick;
    }

    /// Closes the block being collected (the run is over, or the next block starts).
    pub fn close(&mut self) {
        let Some(o) = self.open.take() else {
            return;
        };
        let (mut best, mut limit) = (-1.0, Limit::ProgrammedFeed);
        for (k, t) in o.by_cause.iter().enumerate() {
            if *t > best {
                best = *t;
                limit = Limit::ALL[k];
            }
        }
        let b = BlockTime {
            line: o.line,
            planned_s: o.planned,
            nominal_s: o.nominal,
            length_mm: o.length,
            limit,
        };
        if self.blocks.len() < MAX_BLOCKS {
            self.blocks.push(b);
        } else {
            self.truncated = true;
        }
        let lost = b.lost_s();
        if self.slowest.len() < SLOWEST || self.slowest.last().is_some_and(|w| lost > w.lost_s()) {
            let at = self
                .slowest
                .iter()
                .position(|w| lost > w.lost_s())
                .unwrap_or(self.slowest.len());
            self.slowest.insert(at, b);
            self.slowest.truncate(SLOWEST);
        }
    }
}
