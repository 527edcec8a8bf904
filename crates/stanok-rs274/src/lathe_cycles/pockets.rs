//! The final pass of G71/G72 and G71.2/G72.2 along the offset profile, with LinuxCNC's pockets
//! (type-2 profiles: the profile dips back towards the levels' side and comes up again).
//!
//! Canonical frame as in `lathe_cycles` (the pass runs towards +c, S on the +l side). Arcs are
//! first split where l turns, so a dip always starts at an element boundary. Walking the profile:
//!
//! ```text
//!   l ▲        A ●━━━━━━━ pocket level l_A (if on the grid) ━━━━━━● B (first crossing of l_A after A)
//!     │   ━━━━━━━╲   ← cut along +c from the wall to the first crossing, retract like a level,  ╱
//!     │           ╲     rapid back, *feed* onto the wall, feed down the wall to the next level ╱
//!     │            ╲━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━╱
//!     │              bottom: levels stop above it; the pass then follows the floor and the far wall
//! ```
//!
//! * G71/G72: pocket levels are the cycle's grid S.l − k·I at or below l_A and above the pocket's
//!   bottom; G7x.2 (no main levels) steps l_A − k·I from the outermost pocket's top instead. A dip
//!   inside a pocket is a pocket of its own (on the same grid) when the walk reaches it.
//! * G7x.1 (no pockets) does not come here: its pass climbs every element from the tool's level
//!   (`climb.rs`), which bridges the dips.
//! * The closing move up to S's level is left out when it has no length (as LinuxCNC).
//!
//! Bounds: every level and every element is visited a bounded number of times (`MAX_LEVELS`).

use super::{LatheCall, Move, MAX_LEVELS};
use stanok_geom::chain2d::level_crossings;
use stanok_geom::offset2d::{Seg2, LEN_EPS, P2};

const EPS: f64 = 1e-7;

/// `s` from its start to `p` (a point on it).
fn piece_to(s: &Seg2, p: P2) -> Seg2 {
    match *s {
        Seg2::Line { a, .. } => Seg2::Line { a, b: p },
        Seg2::Arc { c, sweep, .. } => Seg2::arc_through(c, s.start(), p, sweep > 0.0, false),
    }
}

/// `s` from `p` (a point on it) to its end.
fn piece_from(s: &Seg2, p: P2) -> Seg2 {
    match *s {
        Seg2::Line { b, .. } => Seg2::Line { a: p, b },
        Seg2::Arc { c, sweep, .. } => Seg2::arc_through(c, p, s.end(), sweep > 0.0, false),
    }
}

/// The chain with every arc split where its l coordinate turns (angles π/2 + nπ).
pub(super) fn split_at_turns(chain: &[Seg2]) -> Vec<Seg2> {
    let mut out = Vec::with_capacity(chain.len());
    for s in chain {
        let Seg2::Arc { c, r, start, sweep } = *s else {
            out.push(*s);
            continue;
        };
        let mut rest = *s;
        let (lo, hi) = if sweep > 0.0 {
            (start, start + sweep)
        } else {
            (start + sweep, start)
        };
        let half_pi = std::f64::consts::FRAC_PI_2;
        let mut turns: Vec<f64> = Vec::new();
        let mut k = ((lo - half_pi) / std::f64::consts::PI).floor() + 1.0;
        for _ in 0..4 {
            let phi = half_pi + k * std::f64::consts::PI;
            if phi >= hi - 1e-9 {
                break;
            }
            if phi > lo + 1e-9 {
                turns.push(phi);
            }
            k += 1.0;
        }
        if sweep < 0.0 {
            turns.reverse();
        }
        for phi in turns {
            let p = [c[0] + r * phi.cos(), c[1] + r * phi.sin()];
            out.push(piece_to(&rest, p));
            rest = piece_from(&rest, p);
        }
        out.push(rest);
    }
    out.retain(|s| s.length() > LEN_EPS);
    out
}

/// Where the walk is: element `i` of the chain, of which `rest` (if any) is still to go.
struct At {
    i: usize,
    rest: Option<Seg2>,
}

impl At {
    fn seg(&self, prof: &[Seg2]) -> Seg2 {
        self.rest.unwrap_or(prof[self.i])
    }
}

/// Feeds from the walk's position along the chain to `target`, on element `j` (≥ the current).
fn feed_to(moves: &mut Vec<Move>, prof: &[Seg2], at: &mut At, target: P2, j: usize) {
    while at.i < j {
        moves.push(Move::Feed(at.seg(prof)));
        at.i += 1;
        at.rest = None;
    }
    let seg = at.seg(prof);
    let piece = piece_to(&seg, target);
    // A zero-length piece of a line is fed (LinuxCNC prints it), of an arc it is not.
    if matches!(piece, Seg2::Line { .. }) || piece.length() > LEN_EPS {
        moves.push(Move::Feed(piece));
    }
    at.rest = Some(piece_from(&seg, target));
}

/// The first crossing of level `l` with the chain at c > `after` (+ EPS), with its element.
fn crossing_after(prof: &[Seg2], l: f64, after: f64) -> Option<(f64, usize)> {
    level_crossings(prof, l)
        .into_iter()
        .find(|&(c, _)| c > after + EPS)
}

/// The final pass along `prof` (canonical, arcs split at their turns) and then `close`.
/// None: too many levels.
pub(super) fn final_pass(
    moves: &mut Vec<Move>,
    call: &LatheCall,
    s: P2,
    prof: &[Seg2],
    close: Seg2,
) -> Option<()> {
    let first = moves.len();
    walk(moves, call, s, prof, close)?;
    // Arcs were split where l turns; where no pocket came between the pieces, they are one arc
    // again (LinuxCNC never splits an arc at the bottom of a pocket).
    // (At a pocket's top they stay split: LinuxCNC stops there.)
    let tail: Vec<Move> = moves.drain(first..).collect();
    for m in tail {
        if let (Some(Move::Feed(prev)), Move::Feed(next)) = (moves.last_mut(), &m) {
            if let Some(joined) = join_at_bottom(prev, next) {
                *prev = joined;
                continue;
            }
        }
        moves.push(m);
    }
    Some(())
}

/// `prev` and `next` as one arc, if they are pieces of one arc meeting where l is lowest.
fn join_at_bottom(prev: &Seg2, next: &Seg2) -> Option<Seg2> {
    let (
        &Seg2::Arc { c, r, start, sweep },
        &Seg2::Arc {
            c: c2,
            r: r2,
            sweep: s2,
            ..
        },
    ) = (prev, next)
    else {
        return None;
    };
    let same = (c[0] - c2[0]).abs() < 1e-9 && (c[1] - c2[1]).abs() < 1e-9 && (r - r2).abs() < 1e-9;
    let bottom = prev.end()[1] < prev.start()[1] && next.end()[1] > next.start()[1];
    let touching = (prev.end()[0] - next.start()[0]).abs() < 1e-7
        && (prev.end()[1] - next.start()[1]).abs() < 1e-7;
    (same && bottom && touching && sweep.signum() == s2.signum()).then_some(Seg2::Arc {
        c,
        r,
        start,
        sweep: sweep + s2,
    })
}

fn walk(moves: &mut Vec<Move>, call: &LatheCall, s: P2, prof: &[Seg2], close: Seg2) -> Option<()> {
    let mut at = At { i: 0, rest: None };
    // Descents already cut are not cut again.
    let mut cut_descent = false;
    // G7x.2: the grid of the outermost pocket the walk is in (nested ones keep it).
    let mut anchor: Option<f64> = None;
    let mut budget = 4 * MAX_LEVELS + 4 * prof.len();
    while at.i < prof.len() {
        budget = budget.checked_sub(1)?;
        let seg = at.seg(prof);
        // Pieces are monotonic in l (arcs split at their turns): compare the ends.
        let dl = seg.end()[1] - seg.start()[1];
        if dl > 1e-9 {
            cut_descent = false;
        }
        if dl < -1e-9 && !cut_descent {
            let a = seg.start();
            if let Some((_, j)) = crossing_after(prof, a[1], a[0]) {
                cut_descent = true;
                let top = if call.code % 10 == 2 {
                    *anchor.get_or_insert(a[1])
                } else {
                    s[1]
                };
                pocket(moves, call, top, prof, &mut at, a, j, &mut budget)?;
                continue;
            }
        }
        moves.push(Move::Feed(seg));
        at.i += 1;
        at.rest = None;
        if anchor.is_some_and(|t| seg.end()[1] >= t - 1e-9) {
            anchor = None;
        }
    }
    // The closing move up to S's level; none when the profile already ends there — rs274
    // prints nothing then, in every variant.
    if close.length() > LEN_EPS {
        moves.push(Move::Feed(close));
    }
    Some(())
}

/// The levels (grid `top` − k·I) of the pocket that starts at `a` (the walk's position) and
/// closes on element `j`.
#[allow(clippy::too_many_arguments)]
fn pocket(
    moves: &mut Vec<Move>,
    call: &LatheCall,
    top: f64,
    prof: &[Seg2],
    at: &mut At,
    a: P2,
    j: usize,
    budget: &mut usize,
) -> Option<()> {
    let bottom = (at.i..=j.min(prof.len() - 1))
        .flat_map(|k| [prof[k].start()[1], prof[k].end()[1]])
        .fold(a[1], f64::min);
    let mut pos = a;
    // `top`: G71/G72 stay on their grid S.l − k·I; G7x.2 (no main levels) steps down from the
    // top of the outermost pocket.
    for k in 0..=MAX_LEVELS {
        *budget = budget.checked_sub(1)?;
        let l = top - k as f64 * call.i;
        if l > a[1] + 1e-9 {
            continue;
        }
        if l <= bottom + 1e-9 {
            break;
        }
        // Down the wall to this level (at l_A a feed where the tool is already, as LinuxCNC).
        let (cw, jw) = level_crossings(prof, l)
            .into_iter()
            .find(|&(c, _)| c >= pos[0] - EPS)?;
        let w = [cw, l];
        feed_to(moves, prof, at, w, jw);
        pos = w;
        let Some((ce, _)) = crossing_after(prof, l, cw) else {
            break;
        };
        let half = (ce - cw) / 2.0;
        let r = if call.r < 0.0 { half } else { call.r.min(half) };
        moves.push(Move::Feed(Seg2::Line { a: w, b: [ce, l] }));
        moves.push(Move::Rapid([ce - r, l + r]));
        moves.push(Move::Rapid([cw + r, l + r]));
        moves.push(Move::Feed(Seg2::Line {
            a: [cw + r, l + r],
            b: w,
        }));
    }
    Some(())
}
