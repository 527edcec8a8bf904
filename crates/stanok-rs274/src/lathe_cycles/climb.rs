//! The final pass of G71.1/G72.1 (no pockets), as LinuxCNC 2.9 runs it: every element of the
//! offset profile, in order, is *climbed from the tool's level* (read off `rs274` traces; the
//! rule is LinuxCNC's `climb_only` in `interp_g7x.cc`).
//!
//! Canonical frame as in `lathe_cycles` (the pass runs towards +c, S on the +l side). The tool is
//! at L (first P0'); for each element E, with the crossings of E with the level l = L.l:
//!
//! ```text
//!   line falling (end.l < start.l)             → skipped (the tool stays at L)
//!   no crossing with l                         → skipped
//!   line rising or level                       → feed to its crossing X (a level line: its
//!                                                start), feed to its end
//!   arc turning left (ccw, climbing where c > centre.c):
//!     X = its crossing of greatest c; X.c < centre.c → skipped
//!     else feed to X, then the arc to its end (not printed when X is within 0.001 mm of it)
//!   arc turning right (cw, climbing where c < centre.c):
//!     X = its crossing of least c;    X.c > centre.c → skipped
//!     else feed to X, then the arc to its end, or to its top (centre.c, centre.l + r) when it
//!     ends past the top (not printed when X is within 0.001 mm of that point)
//! ```
//!
//! The feed to X is what looks like a repeated start (X is the element's start when the tool is
//! there already: a zero-length feed) and like a bridge over a pocket (the elements going down
//! into it are skipped; the first one coming up through l is fed to along the level). The
//! closing move up to S's level is an element like the others (a rising line), left out when the
//! profile already ends there. Crossings use the arc's `Seg2` circle (for arcs ending off their
//! radius the circle `arcs.rs` chose), with LinuxCNC's tolerance of 10⁻⁶ mm on the level.
//!
//! Invariants: every element is visited once, in order; the tool never moves down (every feed
//! is along a level or along a rising part of the profile); the moves form a connected path.

use super::Move;
use stanok_geom::offset2d::{dist2, Seg2, P2};
use std::f64::consts::TAU;

/// Level tolerance (LinuxCNC's), mm.
const LEVEL_TOL: f64 = 1e-6;
/// How far a line's ends may differ in l and the line still count as level, mm.
const LEVEL_ROUNDING: f64 = 1e-9;
/// An arc whose remaining piece is shorter than this (chord) is not printed (LinuxCNC), mm.
const MIN_ARC: f64 = 1e-3;

/// The G7x.1 final pass along `prof` (canonical, whole elements), from `from` (P0'), then up the
/// closing line `close` unless it has no length.
pub(super) fn climb_pass(moves: &mut Vec<Move>, prof: &[Seg2], from: P2, close: Seg2) {
    let mut at = from;
    let closing = (close.length() > LEVEL_TOL).then_some(close);
    let elements: Vec<Seg2> = prof.iter().chain(closing.iter()).copied().collect();
    for (i, seg) in elements.iter().enumerate() {
        // An arc's own end is where the next element starts (`arcs.rs`).
        let end = match elements.get(i + 1) {
            Some(next) if super::arcs::joins(seg, next) => next.start(),
            _ => seg.end(),
        };
        climb(moves, seg, end, &mut at);
    }
}

/// One element, ending at `end`, climbed from the tool's position `at` (module comment).
fn climb(moves: &mut Vec<Move>, seg: &Seg2, end: P2, at: &mut P2) {
    let level = at[1];
    let start = seg.start();
    let crossings = crossings_at(seg, level);
    let (x, until) = match *seg {
        Seg2::Line { .. } => {
            // Falling: a level line stays (its offset ends are computed apart, so they may
            // differ by rounding where LinuxCNC's are exactly level).
            if end[1] < start[1] - LEVEL_ROUNDING {
                return;
            }
            // A level line crosses with both ends: the first is its start.
            let Some(&x) = crossings.first() else {
                return;
            };
            (x, end)
        }
        Seg2::Arc { c, r, sweep, .. } => {
            if sweep > 0.0 {
                let Some(&x) = crossings.last() else {
                    return;
                };
                if x < c[0] {
                    return;
                }
                (x, end)
            } else {
                let Some(&x) = crossings.first() else {
                    return;
                };
                if x > c[0] {
                    return;
                }
                let top = if end[0] > c[0] { [c[0], c[1] + r] } else { end };
                (x, top)
            }
        }
    };
    let onto = [x, level];
    moves.push(Move::Feed(Seg2::Line { a: *at, b: onto }));
    *at = onto;
    match *seg {
        Seg2::Line { .. } => {
            moves.push(Move::Feed(Seg2::Line { a: onto, b: until }));
            *at = until;
        }
        Seg2::Arc { c, sweep, .. } => {
            if dist2(onto, until) > MIN_ARC {
                moves.push(Move::Feed(Seg2::arc_through(
                    c,
                    onto,
                    until,
                    sweep > 0.0,
                    false,
                )));
            }
            *at = until;
        }
    }
}

/// The crossings of `seg` with level `l` (first-axis coordinates, ascending), within LinuxCNC's
/// level tolerance: a level line gives both its ends, in the order it runs; a circle passing
/// within the tolerance below `l` touches it at its top.
fn crossings_at(seg: &Seg2, l: f64) -> Vec<f64> {
    match *seg {
        Seg2::Line { a, b } => {
            if a[1].min(b[1]) > l + LEVEL_TOL || a[1].max(b[1]) < l - LEVEL_TOL {
                Vec::new()
            } else if (a[1] - b[1]).abs() < LEVEL_TOL {
                vec![a[0], b[0]]
            } else {
                vec![a[0] + (l - a[1]) / (b[1] - a[1]) * (b[0] - a[0])]
            }
        }
        Seg2::Arc { c, r, start, sweep } => {
            let dl = l - c[1];
            let s2 = r * r - dl * dl;
            if s2 < -LEVEL_TOL {
                return Vec::new();
            }
            let half = s2.max(0.0).sqrt();
            let tol = LEVEL_TOL / r.max(LEVEL_TOL);
            let on_arc = |x: f64| {
                let phi = dl.atan2(x - c[0]);
                let u = ((phi - start) * sweep.signum()).rem_euclid(TAU);
                u <= sweep.abs() + tol || u >= TAU - tol
            };
            // Both points, even where they coincide (a circle touching the level).
            [c[0] - half, c[0] + half]
                .into_iter()
                .filter(|&x| on_arc(x))
                .collect()
        }
    }
}
