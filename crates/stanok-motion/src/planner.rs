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
//!    released at once (an exact stop empties the window).
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

use crate::piece::Piece;
use crate::{profile_scurve, profile_trapezoid};
use std::collections::VecDeque;

/// A piece with its final boundary speeds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedPiece {
    /// The piece.
    pub piece: Piece,
    /// Speed at its start.
    pub v_entry: f64,
    /// Speed at its end.
    pub v_exit: f64,
}

#[derive(Debug, Clone, Copy)]
struct Entry {
    piece: Piece,
    entry: f64,
    entry_max: f64,
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

/// The look-ahead planner (module doc).
#[derive(Debug, Clone)]
pub struct Planner {
    window: VecDeque<Entry>,
    capacity: usize,
    planned: usize,
    /// `v_max` of the last piece pushed (for the next junction, even after it was released).
    last_v_max: f64,
}

impl Planner {
    /// An empty planner holding at most `lookahead` (≥ 2) pieces.
    pub fn new(lookahead: usize) -> Self {
        let capacity = lookahead.max(2);
        Planner {
            window: VecDeque::with_capacity(capacity + 1),
            capacity,
            planned: 0,
            last_v_max: 0.0,
        }
    }

    /// Pieces held.
    pub fn len(&self) -> usize {
        self.window.len()
    }

    /// True when no piece is held.
    pub fn is_empty(&self) -> bool {
        self.window.is_empty()
    }

    /// Adds a piece; pieces whose plan became final go to `out`, in order.
    pub fn push(&mut self, piece: Piece, out: &mut impl FnMut(PlannedPiece)) {
        let entry_max = if piece.entry_stop || self.window.is_empty() && self.last_v_max == 0.0 {
            0.0
        } else {
            piece.v_max.min(self.last_v_max)
        };
        self.last_v_max = if piece.length > 0.0 { piece.v_max } else { 0.0 };
        if entry_max == 0.0 {
            // Everything before a stop is final.
            self.release_all(out);
        }
        self.window.push_back(Entry {
            piece,
            entry: 0.0,
            entry_max,
        });
        self.replan();
        while self.window.len() > self.capacity {
            self.release_front(out);
        }
    }

    /// The path ends (or the caller wants everything): releases every piece, the last one ending
    /// at rest.
    pub fn flush(&mut self, out: &mut impl FnMut(PlannedPiece)) {
        self.release_all(out);
        self.last_v_max = 0.0;
    }

    fn release_all(&mut self, out: &mut impl FnMut(PlannedPiece)) {
        while !self.window.is_empty() {
            self.release_front(out);
        }
    }

    fn release_front(&mut self, out: &mut impl FnMut(PlannedPiece)) {
        let Some(front) = self.window.pop_front() else {
            return;
        };
        let v_exit = self.window.front().map_or(0.0, |e| e.entry);
        self.planned = self.planned.saturating_sub(1);
        out(PlannedPiece {
            piece: front.piece,
            v_entry: front.entry,
            v_exit,
        });
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
        while k >= first {
            let e = &mut w[k];
            let v = e.entry_max.min(reach(next_entry, &e.piece));
            if v == e.entry && k < n - 1 {
                break;
            }
            e.entry = v;
            next_entry = v;
            k -= 1;
        }
        // Forward pass.
        for k in self.planned..n - 1 {
            let (cur_entry, cur_piece) = (w[k].entry, w[k].piece);
            let next = &mut w[k + 1];
            if cur_entry < next.entry {
                let v = reach(cur_entry, &cur_piece);
                if v < next.entry {
                    next.entry = v;
                    self.planned = k + 1;
                }
            }
            if next.entry == next.entry_max {
                self.planned = k + 1;
            }
        }
    }
}
