//! The bound on simulated machine time, and the warning for a block that runs longer than an hour.
//!
//! A program can ask for any amount of machine time: `G1 X100 F0.0000001` (about 1,900 years),
//! `G4 P1000000000`. The simulated machine runs it faster than real time, but not infinitely
//! faster, so without a bound `stanok run` would never end. Two guards:
//! 1. **Before a command runs** (`SimMachine::apply`), its nominal time ([`nominal_seconds`]:
//!    length / feed, the dwell's seconds — a lower bound of the real time, see
//!    `stanok_motion::nominal`) is added to the run's; past [`SimOptions::max_machine_time_s`]
//!    the command is refused with `machine::time-limit` at its block, nothing of it executed.
//! 2. **While the motion runs**, the interpolator stops at the first servo instant past the same
//!    bound (acceleration, a feed override below 100 %, slow axes and 5-axis joint limits make the
//!    real time longer than the nominal one); the run then stops with the same diagnostic at the
//!    block that was moving.
//!
//! A block whose nominal time is over [`LONG_BLOCK_S`] (an hour) gets the warning
//! `machine::long-block` — from `stanok check` too, which runs no machine: [`long_block`] needs
//! only the command and the machine data.
//!
//! [`SimOptions::max_machine_time_s`]: crate::SimOptions::max_machine_time_s

use crate::data::MachineData;
use stanok_canon::{Canon, Diagnostic, Span};
use stanok_motion::nominal::{self, AxisLimits};

/// Default bound on simulated machine time per run: 100 hours.
pub const DEFAULT_MAX_MACHINE_TIME_S: f64 = 100.0 * 3600.0;

/// A block running longer than this (nominal) gets a warning, s.
pub const LONG_BLOCK_S: f64 = 3600.0;

/// Nominal seconds of one command on `machine` (0 for commands that take no time): the same
/// rules as the run report's `nominal_time_s` (feeds clamped to the machine's `max_feed`, rapids
/// at `rapid_rate` slowed to the axes' velocities); a spline's length is its control polygon's,
/// which is at least the curve's.
pub fn nominal_seconds(machine: &MachineData, cmd: &Canon) -> f64 {
    let clamp = |f: f64| {
        if f > machine.max_feed {
            machine.max_feed
        } else {
            f
        }
    };
    match cmd {
        Canon::StraightTraverse(m) => {
            let (s, e) = (m.start.to_array(), m.end.to_array());
            let deltas: Vec<f64> = s.iter().zip(&e).map(|(a, b)| b - a).collect();
            let mut limits = [AxisLimits {
                max_velocity_per_min: 0.0,
            }; 9];
            for a in &machine.axes {
                limits[a.pose_index()].max_velocity_per_min = a.max_velocity;
            }
            nominal::rapid_time(path_length(&s, &e), &deltas, machine.rapid_rate, &limits)
        }
        Canon::StraightFeed(m) => nominal::feed_time(
            path_length(&m.start.to_array(), &m.end.to_array()),
            clamp(m.feed),
        ),
        Canon::StraightProbe { motion, .. } => nominal::feed_time(
            path_length(&motion.start.to_array(), &motion.end.to_array()),
            clamp(motion.feed),
        ),
        Canon::ArcFeed(a) => {
            let helix = stanok_geom::Helix {
                start: a.start.xyz(),
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
                turns: a.turns,
            };
            nominal::feed_time(helix.length(), clamp(a.feed))
        }
        Canon::SplineFeed(sp) => {
            let polygon: f64 = sp
                .control_points
                .windows(2)
                .map(|w| stanok_geom::norm(stanok_geom::sub(w[1], w[0])))
                .sum();
            nominal::feed_time(polygon, clamp(sp.feed))
        }
        Canon::Dwell { seconds } => nominal::dwell_time(*seconds),
        _ => 0.0,
    }
}

/// The length a rate applies to (XYZ, else UVW, else ABC; `sim.rs` module doc).
fn path_length(s: &[f64; 9], e: &[f64; 9]) -> f64 {
    let len = |r: std::ops::Range<usize>| r.map(|i| (e[i] - s[i]).powi(2)).sum::<f64>().sqrt();
    let (xyz, abc, uvw) = (len(0..3), len(3..6), len(6..9));
    if xyz > 0.0 {
        xyz
    } else if uvw > 0.0 {
        uvw
    } else {
        abc
    }
}

/// `machine::long-block` for a command whose nominal time is over an hour, at `span`.
pub fn long_block(machine: &MachineData, cmd: &Canon, span: Span) -> Option<Diagnostic> {
    let t = nominal_seconds(machine, cmd);
    if t <= LONG_BLOCK_S {
        return None;
    }
    let what = match cmd {
        Canon::Dwell { .. } => "dwells".to_string(),
        Canon::StraightTraverse(_) => "is a rapid that runs".to_string(),
        Canon::StraightFeed(m) => format!("moves at F {} mm/min for", m.feed),
        Canon::ArcFeed(a) => format!("moves at F {} mm/min for", a.feed),
        Canon::SplineFeed(s) => format!("moves at F {} mm/min for", s.feed),
        _ => "runs".to_string(),
    };
    Some(
        Diagnostic::warning(
            "machine::long-block",
            format!("this block {what} {} (more than an hour)", duration(t)),
            span,
        )
        .with_note(
            "check the feed (F) and the dwell time (G4): a typo can make a block run for days",
        ),
    )
}

/// `machine::time-limit`: the run would pass the bound.
pub fn time_limit(bound_s: f64, at_s: f64, span: Span) -> Diagnostic {
    Diagnostic::error(
        "machine::time-limit",
        format!(
            "this block would take the simulated machine past its time bound of {} (at {})",
            duration(bound_s),
            duration(at_s)
        ),
        span,
    )
    .with_note(
        "the bound is the option --max-machine-time (hours, default 100): raise it for a \
         longer program",
    )
}

/// A duration for people: seconds, minutes, hours or years.
pub fn duration(seconds: f64) -> String {
    if !seconds.is_finite() {
        return "forever".into();
    }
    if seconds < 120.0 {
        format!("{seconds:.1} s")
    } else if seconds < 7200.0 {
        format!("{:.1} min", seconds / 60.0)
    } else if seconds < 2.0 * 365.25 * 86400.0 {
        format!("{:.1} h", seconds / 3600.0)
    } else {
        format!("{:.3e} years", seconds / (365.25 * 86400.0))
    }
}
