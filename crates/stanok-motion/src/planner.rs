//! The look-ahead planner: speeds at every piece boundary over a bounded window.
//!
//! ```text
//!                 window (at most `lookahead` pieces)
//!   released ◀── [ front | … | planned | … | … | tail ] ◀── push(piece)
//!   (final)        locked     optimal up to here      exit of tail = 0
//! ```
//!
//! ## Algorithm (in the manner of grbl's planner.c)
//! Every piece in the window has a *maximum entry speed* (`entry_max`) and a planned entry speed
//! (`entry`). `entry_max` is 0 when the piece starts from rest (an exact stop), otherwise the lower
//! of the two pieces' `v_max` — pieces join with a continuous tangent (the path builder blended the
//! corners), so the speed only has to be continuous. Speeds are related by the piece's reach
//! function: BRISK √(v² + 2aL), SOFT the S-curve distance inverted and made
//! monotone ([`crate::profile_scurve::reach`]: the exact S-curve reach falls as the start speed
//! rises below a²/2j, which would let a later raise lower an earlier, already released bound).
//! Both passes and the locking below rely on reach being non-decreasing in v.
//!
//! On every push:
//! 1. **Reverse pass**, from the tail (whose exit is 0: the path may end there) back to the piece
//!    after `planned`: entry[k] = min(entry_max[k], reach(entry[k+1], piece k)). It stops early as
//!    soon as an entry does not change: nothing before it can change either.
//! 2. **Forward pass**, from `planned` to the tail: if a piece cannot reach the next entry from its
//!    own, the next entry is lowered to what it can reach. A piece whose entry is at its maximum,
//!    or was just lowered by the forward pass, cannot improve any more: `planned` moves to it.
//! 3. **Release.** When the window holds more than `lookahead` pieces, the front one goes to the
//!    interpolator with entry = entry[front] and exit = entry[front + 1]. That next entry is then
//!    locked: later pushes only *raise* reverse-pass limits, so a locked entry stays reachable and
//!    stoppable. A piece that starts from rest makes everything before it final: all of it is
//!    released (an exact stop empties the window). Release is a pull ([`Planner::pop_ready`]):
//!    the interpolator takes the next piece when it has run the previous one, so that every piece
//!    not yet running is still in the window, where an override can re-plan it.
//!
//! ## Overrides
//! Every piece keeps its programmed speed(s) and which override scales each (feed, rapid,
//! spindle, none); its speed limit is min(programmed × factor, axis and curvature limits)
//! ([`Piece::set_limits`]). When the factors change while the machine runs
//! ([`Planner::replan_overrides`], called by the interpolator at the servo instant of the change),
//! every piece in the window is limited anew and the window planned again — the path stays, only
//! the speeds along it change. The piece being executed has left the window: from its state
//! (s, v) it can end at any speed in [brake(v, rest), reach(v, rest)], and the front entry is put
//! into that range. Raising the factors only raises limits. Lowering them may leave the machine
//! faster than the new limits: it cannot slow down sooner than its acceleration allows, so the
//! forward pass keeps every entry at least at brake(previous entry) and marks such entries as
//! forced (`entry_min`, kept by later passes). A forced entry is never above the speed the plan
//! before the change had there (by induction: the executing piece was at or below its plan, and
//! braking from at or below a plan stays at or below it, since the plan itself brakes no harder
//! than a), so no physical limit is exceeded; a curved piece entered above its new limit gets the
//! acceleration of that higher speed (the centripetal share grows with v). The profiles start
//! with a deceleration when entered above their limit ([`crate::profile_trapezoid`],
//! [`crate::profile_scurve`]). A factor of 0 gives a limit of 0: the machine brakes on the path
//! and stands (the interpolator's stall) until a factor rises.
//!
//! ## Invariants
//! * For every released piece: v_entry ≤ its entry_max, v_exit ≤ the next entry_max,
//!   v_entry ≤ reach(v_exit) and v_exit ≤ reach(v_entry): a profile exists that respects the
//!   piece's speed, acceleration (and jerk) limits; and the tail of the window can always stop.
//! * Memory: `lookahead` pieces. Work per push: amortised O(1) in steady state (the passes stop at
//!   `planned` or at the first unchanged entry), O(lookahead) at worst.
//! * Units: path units (mm and deg in the 9-D path metric), seconds.
//!
//! ## Known limits
//! * A window shorter than the braking distance at full speed slows the machine (it must be able
//!   to stop at the window's end). With 1024 pieces this only happens on very short chords.
//! * The time is optimal per piece for the trapezoid/S-curve shape, not globally: the S-curve
//!   starts and ends every piece with zero acceleration.

use crate::limits::{AxisLimit, MotionConfig};
use crate::piece::{Overrides, Piece};
use crate::{profile_scurve, profile_trapezoid};
use std::collections::VecDeque;

/// A piece with its final boundary speeds.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedPiece {
    /// The piece.
    pub piece: Piece,
    /// Speed at its start.
    pub v_entry: f64,
    /// Speed at its end.
    pub v_exit: f64,
    /// Released while the window was full, with an exit speed set by the window's end (it had to
    /// be able to stop there): the look-ahead window limited it.
    pub lookahead: bool,
}

#[derive(Debug, Clone)]
struct Entry {
    piece: Piece,
    entry: f64,
    entry_max: f64,
    /// The lowest entry the machine can still reach (0 unless an override was lowered while the
    /// machine ran faster than the new speeds allow: see "Overrides" in the module doc).
    entry_min: f64,
    /// The entry was set by the reverse pass from the window's end (as far as the last pass
    /// went): a longer window could raise it.
    tail_bound: bool,
}

/// The highest speed one can reach from `v` over the piece (or slow down from to `v`).
#[inline]
pub fn reach(v: f64, p: &Piece) -> f64 {
    if p.length <= 0.0 {
        return v;
    }
    if p.soft {
        profile_scurve::reach(v, p.length, p.a_max, p.j_max)
    } else {
        profile_trapezoid::reach(v, p.length, p.a_max)
    }
}

/// How [`feasible_exit`] met a wanted exit speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExitFit {
    /// As wanted.
    Same(f64),
    /// Lower than wanted (SOFT: the wanted speed lay in the gap a ramp cannot end in).
    Lowered(f64),
    /// Higher than wanted: the piece cannot slow down further.
    Forced(f64),
}

impl ExitFit {
    /// The speed.
    pub fn speed(self) -> f64 {
        match self {
            ExitFit::Same(v) | ExitFit::Lowered(v) | ExitFit::Forced(v) => v,
        }
    }
}

/// The exit speed nearest to `wanted` (≤ [`reach`]`(v)`, which the caller ensures) that a piece
/// entered at `v` can really end at.
///
/// BRISK: any speed down to √(v² − 2aL); below that the exit is forced up to it.
///
/// SOFT: a slow-down must fit into the piece as one S-curve ramp (zero acceleration at both
/// ends), of distance D(u → v). D is not monotone in the exit u: it rises from u = 0 to a hump,
/// then falls to 0 at u = v. So the exits that fit are [0, u_a] ∪ [u*, v] when the hump is above
/// L, and [0, v] otherwise (exactly; the monotone reach would refuse some of them). A wanted exit
/// in the gap (u_a, u*) is lowered to u_a, which is always safe (slower); only if not even a stop
/// fits (D(0 → v) > L: no [0, u_a]) is it forced up to u*. Both crossings by bisection, whose
/// invariant (one end fits, the other not) holds across the one boundary in between.
pub fn feasible_exit(v: f64, p: &Piece, wanted: f64) -> ExitFit {
    let wanted = wanted.max(0.0);
    if p.length <= 0.0 || wanted >= v {
        return ExitFit::Same(wanted);
    }
    if !p.soft {
        let lo = (v * v - 2.0 * p.a_max * p.length).max(0.0).sqrt();
        return if wanted >= lo {
            ExitFit::Same(wanted)
        } else {
            ExitFit::Forced(lo)
        };
    }
    let d = |u: f64| profile_scurve::ramp_distance(u, v, p.a_max, p.j_max);
    let fits = |u: f64| d(u) <= p.length;
    if fits(wanted) {
        return ExitFit::Same(wanted);
    }
    // A stop that fits to rounding is a stop: the profile is clamped at the piece end, where its
    // speed is ~0. Any other exit must fit exactly (a clamp there would stop a moving machine for
    // a moment: a third difference of (excess)/T³).
    let (mut lo, mut hi) = if d(0.0) <= p.length * (1.0 + 1e-9) {
        (0.0, wanted)
    } else {
        (v, wanted)
    };
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if lo < wanted {
        ExitFit::Lowered(lo)
    } else {
        ExitFit::Forced(lo)
    }
}

/// The look-ahead planner (module doc).
#[derive(Debug, Clone)]
pub struct Planner {
    window: VecDeque<Entry>,
    capacity: usize,
    planned: usize,
    /// `v_max` of the last piece pushed (for the next junction, even after it was released).
    last_v_max: f64,
    /// Pieces at the front whose plan is final (a stop follows them, or the path was flushed):
    /// released even while the window is not full.
    final_count: usize,
    axes: [AxisLimit; 9],
    /// The override factors in force.
    overrides: Overrides,
    /// The factors the path builder limited the pieces with.
    built_with: Overrides,
}

impl Planner {
    /// An empty planner holding at most `lookahead` (≥ 2) pieces, for pieces limited with the
    /// default overrides and no axis limits known (it then never limits a piece again: overrides
    /// need [`Planner::with_config`]).
    pub fn new(lookahead: usize) -> Self {
        let capacity = lookahead.max(2);
        Planner {
            window: VecDeque::with_capacity(capacity + 1),
            capacity,
            planned: 0,
            last_v_max: 0.0,
            final_count: 0,
            axes: [AxisLimit::UNLIMITED; 9],
            overrides: Overrides::default(),
            built_with: Overrides::default(),
        }
    }

    /// The planner of a run: its look-ahead, axis limits and initial overrides.
    pub fn with_config(config: &MotionConfig) -> Self {
        let mut p = Planner::new(config.lookahead);
        p.axes = config.axes;
        p.overrides = config.overrides();
        p.built_with = p.overrides;
        p
    }

    /// Pieces held.
    pub fn len(&self) -> usize {
        self.window.len()
    }

    /// True when no piece is held.
    pub fn is_empty(&self) -> bool {
        self.window.is_empty()
    }

    /// The override factors in force.
    pub fn overrides(&self) -> Overrides {
        self.overrides
    }

    /// The machine's axis limits.
    pub fn axes(&self) -> &[AxisLimit; 9] {
        &self.axes
    }

    /// Adds a piece; pieces whose plan became final go to `out`, in order.
    pub fn push(&mut self, piece: Piece, out: &mut impl FnMut(PlannedPiece)) {
        self.push_piece(piece);
        while let Some(pp) = self.pop_ready() {
            out(pp);
        }
    }

    /// Adds a piece without releasing any (the caller takes them with [`Planner::pop_ready`]).
    pub fn push_piece(&mut self, mut piece: Piece) {
        if self.overrides != self.built_with {
            let cap = piece.programmed_speed(&self.overrides);
            piece.set_limits(cap, 0.0, &self.axes);
        }
        let entry_max = if piece.entry_stop || self.window.is_empty() && self.last_v_max == 0.0 {
            0.0
        } else {
            piece.v_max.min(self.last_v_max)
        };
        self.last_v_max = if piece.length > 0.0 { piece.v_max } else { 0.0 };
        if entry_max == 0.0 {
            // Everything before a stop is final.
            self.final_count = self.window.len();
        }
        self.window.push_back(Entry {
            piece,
            entry: 0.0,
            entry_max,
            entry_min: 0.0,
            tail_bound: false,
        });
        self.replan();
    }

    /// The front piece, if its plan is final: a stop follows it, the path was flushed, or the
    /// window holds more than `lookahead` pieces. Its exit speed is the next piece's entry, which
    /// is then locked (module doc, step 3).
    pub fn pop_ready(&mut self) -> Option<PlannedPiece> {
        if self.final_count == 0 && self.window.len() <= self.capacity {
            return None;
        }
        let by_capacity = self.final_count == 0;
        let front = self.window.pop_front()?;
        self.final_count = self.final_count.saturating_sub(1);
        let v_exit = self.window.front().map_or(0.0, |e| e.entry);
        let lookahead = by_capacity && self.window.front().is_some_and(|e| e.tail_bound);
        self.planned = self.planned.saturating_sub(1);
        Some(PlannedPiece {
            piece: front.piece,
            v_entry: front.entry,
            v_exit,
            lookahead,
        })
    }

    /// The path ends (or the caller wants everything): releases every piece, the last one ending
    /// at rest.
    pub fn flush(&mut self, out: &mut impl FnMut(PlannedPiece)) {
        self.finish_window();
        while let Some(pp) = self.pop_ready() {
            out(pp);
        }
    }

    /// Marks every piece held as final (the path ends at the last one); [`Planner::pop_ready`]
    /// then releases them all.
    pub fn finish_window(&mut self) {
        self.final_count = self.window.len();
        self.last_v_max = 0.0;
    }

    /// New override factors while the machine runs (module doc, "Overrides"): every piece held
    /// gets the speed limits of its programmed speed under `overrides`, and the window is planned
    /// again. `current` is the rest of the piece being executed (from where the machine is, with
    /// its new limits) and `v` the speed there: the front's entry is what that rest can end at
    /// ([`feasible_exit`]). Returns the front's entry: the exit speed the executing piece must
    /// now end at (0 when the window is empty).
    pub fn replan_overrides(&mut self, overrides: Overrides, current: &Piece, v: f64) -> f64 {
        self.overrides = overrides.clamped();
        let axes = self.axes;
        let n = self.window.len();
        let mut prev_v_max = current.v_max.max(v);
        for k in 0..n {
            let e = &mut self.window[k];
            let cap = e.piece.programmed_speed(&self.overrides);
            e.piece.set_limits(cap, 0.0, &axes);
            e.entry_min = 0.0;
            e.entry_max = if e.piece.entry_stop {
                0.0
            } else {
                e.piece.v_max.min(prev_v_max)
            };
            prev_v_max = if e.piece.length > 0.0 {
                e.piece.v_max
            } else {
                0.0
            };
        }
        self.last_v_max = match self.window.back() {
            Some(e) if e.piece.length > 0.0 => e.piece.v_max,
            Some(_) => 0.0,
            None => self.last_v_max.min(current.v_max),
        };
        if n == 0 {
            return 0.0;
        }
        // Reverse pass over the whole window: the tail's exit is 0.
        let w = &mut self.window;
        let mut next_entry = 0.0;
        for k in (0..n).rev() {
            let e = w[k].entry_max.min(reach(next_entry, &w[k].piece));
            w[k].entry = e;
            next_entry = e;
        }
        // Forward pass from the machine's state: every entry what the previous piece can reach
        // and really end at. Entries changed from the wanted ones (lowered into a SOFT ramp's
        // reach, forced up where the machine cannot slow down sooner) freeze the plan up to the
        // piece after them, so that later pushes, which plan with the monotone reach, leave
        // those pairs alone.
        let mut frozen = 0;
        for k in 0..n {
            let (from, piece) = if k == 0 {
                (v, current)
            } else {
                if w[k - 1].entry_min > 0.0 {
                    let cap = w[k - 1].piece.programmed_speed(&self.overrides);
                    let floor = w[k - 1].entry_min;
                    w[k - 1].piece.set_limits(cap, floor, &axes);
                }
                (w[k - 1].entry, &w[k - 1].piece)
            };
            if w[k].piece.entry_stop {
                // Starts from rest: the plan before the change stopped here, and the machine is at
                // or below it, so it can stop too.
                w[k].entry = 0.0;
                continue;
            }
            let wanted = w[k].entry.min(reach(from, piece));
            let fit = feasible_exit(from, piece, wanted);
            w[k].entry = fit.speed();
            match fit {
                ExitFit::Same(_) => {}
                ExitFit::Lowered(_) => frozen = k + 1,
                ExitFit::Forced(u) => {
                    w[k].entry_min = u;
                    w[k].entry_max = w[k].entry_max.max(u);
                    frozen = k + 1;
                }
            }
        }
        if w[n - 1].entry_min > 0.0 {
            let cap = w[n - 1].piece.programmed_speed(&self.overrides);
            let floor = w[n - 1].entry_min;
            w[n - 1].piece.set_limits(cap, floor, &axes);
        }
        self.planned = frozen.min(n - 1);
        w[0].entry
    }

    /// Steps 1 and 2 of the module doc.
    fn replan(&mut self) {
        let n = self.window.len();
        if n < 2 {
            self.planned = 0;
            return;
        }
        let w = &mut self.window;
        // Reverse pass: the tail's exit is 0.
        let mut next_entry = 0.0;
        let first = self.planned + 1;
        let mut k = n - 1;
        let mut bound = true;
        while k >= first {
            let e = &mut w[k];
            let reached = reach(next_entry, &e.piece);
            let v = e.entry_max.min(reached).max(e.entry_min);
            if v == e.entry && k < n - 1 {
                break;
            }
            bound &= reached < e.entry_max;
            e.tail_bound = bound;
            e.entry = v;
            next_entry = v;
            k -= 1;
        }
        // Forward pass.
        for k in self.planned..n - 1 {
            let cur_entry = w[k].entry;
            if cur_entry < w[k + 1].entry {
                let v = reach(cur_entry, &w[k].piece);
                let next = &mut w[k + 1];
                if v < next.entry {
                    next.entry = v.max(next.entry_min);
                    self.planned = k + 1;
                }
            }
            if w[k + 1].entry == w[k + 1].entry_max {
                self.planned = k + 1;
            }
        }
    }
}
