//! Feed, rapid and spindle override acting at the interpolator: on the motion being executed and on
//! everything planned, within 50 ms of machine time.
//!
//! ## Where the factors come from
//! * [`OverrideSwitch`]: the operator's knobs, shared with another thread (the panel) like
//!   [`crate::hold::HoldSwitch`]: three atomics holding the factors' bits, read at every servo
//!   instant. Setting it never waits for the servo loop, nor the servo loop for it.
//! * A schedule of timed changes ([`OverrideChange`] at a machine time, `stanok run
//!   --override-at T:FEED%`), applied at the first servo instant at or after their time.
//! * [`crate::stage::MotionStage::set_feed_override`] and friends: a change at the next servo
//!   instant.
//!
//! With a switch connected the switch's values are the ones wanted (it is the operator's hand on
//! the knob); otherwise the schedule's and the setters'.
//!
//! ## What a change does (the interpolator, [`crate::interpolator`])
//! At the first servo instant where the wanted factors differ from those in force, the piece being
//! executed gets the limits of its programmed speed under the new factors, the planner re-plans
//! its whole window from the machine's state ([`crate::planner::Planner::replan_overrides`]), and
//! the rest of the piece runs a new profile from where the machine is, at the speed it has, to the
//! new exit speed — a change of speed along the path already planned, within each piece's
//! acceleration (and in SOFT jerk) limits. In BRISK that happens at once. In SOFT the profile
//! must start with zero acceleration: while the machine accelerates, the acceleration is first
//! brought to zero at the jerk limit (at most a/j, 50 ms on the built-in mill), then the change
//! applies; while it decelerates the change waits for the ramp to end (the machine is slowing down
//! already; a piece ends every ramp at zero acceleration).
//!
//! A factor of 0 gives feed moves (rapids) a limit of 0: the machine brakes along the path to
//! rest and stands ("stall") until the factor rises, then accelerates from there.
//!
//! Spindle override scales the commanded spindle speed of every setpoint and the speed of
//! spindle-synchronised moves (the axes follow the spindle); other feeds per revolution keep the
//! speed the interpreter computed from the programmed S.

use crate::piece::Overrides;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// Which override a change sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OverrideKind {
    /// Feed override, 0…2.
    Feed,
    /// Rapid override, 0…1.
    Rapid,
    /// Spindle override, 0.5…1.2.
    Spindle,
}

/// One timed change: from machine time `at` (s), override `kind` is `fraction` (1 = 100 %).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OverrideChange {
    /// Machine time, s.
    pub at: f64,
    /// Which override.
    pub kind: OverrideKind,
    /// The new factor (clamped to the override's range).
    pub fraction: f64,
}

/// The operator's override knobs, shared between the panel's thread and the interpolator (module
/// doc). Factors are fractions (1 = 100 %), clamped to feed 0…2, rapid 0…1, spindle 0.5…1.2.
#[derive(Debug)]
pub struct OverrideSwitch {
    feed: AtomicU64,
    rapid: AtomicU64,
    spindle: AtomicU64,
}

impl Default for OverrideSwitch {
    fn default() -> Self {
        let one = 1.0f64.to_bits();
        OverrideSwitch {
            feed: AtomicU64::new(one),
            rapid: AtomicU64::new(one),
            spindle: AtomicU64::new(one),
        }
    }
}

impl OverrideSwitch {
    /// Sets the feed override (fraction, 0…2).
    pub fn set_feed(&self, fraction: f64) {
        let f = Overrides {
            feed: fraction,
            ..Overrides::default()
        }
        .clamped()
        .feed;
        self.feed.store(f.to_bits(), Ordering::Relaxed);
    }

    /// Sets the rapid override (fraction, 0…1).
    pub fn set_rapid(&self, fraction: f64) {
        let f = Overrides {
            rapid: fraction,
            ..Overrides::default()
        }
        .clamped()
        .rapid;
        self.rapid.store(f.to_bits(), Ordering::Relaxed);
    }

    /// Sets the spindle override (fraction, 0.5…1.2).
    pub fn set_spindle(&self, fraction: f64) {
        let f = Overrides {
            spindle: fraction,
            ..Overrides::default()
        }
        .clamped()
        .spindle;
        self.spindle.store(f.to_bits(), Ordering::Relaxed);
    }

    /// The factors set now.
    pub fn get(&self) -> Overrides {
        Overrides {
            feed: f64::from_bits(self.feed.load(Ordering::Relaxed)),
            rapid: f64::from_bits(self.rapid.load(Ordering::Relaxed)),
            spindle: f64::from_bits(self.spindle.load(Ordering::Relaxed)),
        }
    }
}

/// What the interpolator reads at every servo instant: the factors wanted now (module doc).
#[derive(Debug, Clone, Default)]
pub struct OverrideInput {
    switch: Option<Arc<OverrideSwitch>>,
    schedule: Vec<OverrideChange>,
    next: usize,
    wanted: Option<Overrides>,
}

impl OverrideInput {
    /// Connects the operator's knobs; from now on their values are the ones wanted.
    pub fn set_switch(&mut self, switch: Arc<OverrideSwitch>) {
        self.switch = Some(switch);
    }

    /// Adds timed changes (kept sorted by time; changes at equal times apply in the order given).
    pub fn schedule(&mut self, changes: &[OverrideChange]) {
        self.schedule
            .extend(changes.iter().filter(|c| c.at.is_finite()).copied());
        self.schedule.sort_by(|a, b| a.at.total_cmp(&b.at));
    }

    /// Wants `overrides` from the next servo instant on (the setters of the stage).
    pub fn set(&mut self, overrides: Overrides) {
        self.wanted = Some(overrides.clamped());
    }

    /// The factors wanted at machine time `t`, if they differ from `in_force`.
    #[inline]
    pub fn poll(&mut self, t: f64, in_force: Overrides) -> Option<Overrides> {
        while let Some(c) = self.schedule.get(self.next) {
            if c.at > t {
                break;
            }
            let mut w = self.wanted.unwrap_or(in_force);
            match c.kind {
                OverrideKind::Feed => w.feed = c.fraction,
                OverrideKind::Rapid => w.rapid = c.fraction,
                OverrideKind::Spindle => w.spindle = c.fraction,
            }
            self.wanted = Some(w.clamped());
            self.next += 1;
        }
        if let Some(s) = &self.switch {
            self.wanted = Some(s.get());
        }
        match self.wanted {
            Some(w) if w != in_force => Some(w),
            _ => None,
        }
    }

    /// True if the factors can still change from `in_force` (a switch is connected, a scheduled
    /// change is ahead, or a change is wanted but waits to apply): a machine stalled by a zero
    /// override then waits; otherwise it would wait for ever.
    pub fn can_change(&self, in_force: Overrides) -> bool {
        self.switch.is_some()
            || self.next < self.schedule.len()
            || self.wanted.is_some_and(|w| w != in_force)
    }
}
