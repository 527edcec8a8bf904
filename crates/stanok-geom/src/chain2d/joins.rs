//! How the pieces of an offset chain are joined: trimming a piece to a point of its curve, the
//! crossing of two overlapping pieces, and leaving out the elements an offset swallows (see the
//! parent module's comment), with the check that the result keeps its distance.

use crate::offset2d::{curve_intersections, dist2, wrap_pi, Seg2, LEN_EPS, P2, PARAM_EPS};
use std::f64::consts::FRAC_PI_2;

/// Whether every piece of `offset` stays at least `d` (less 10⁻⁶ mm) from every element of
/// `chain`, sampled at 65 points per piece (ends included: the joints, where a left-out element
/// comes nearest; between samples the distance to a line or an arc can dip by at most
/// h²/(8ρ) for spacing h and curvature radius ρ, far below the tolerance for profile-sized
/// elements).
pub(super) fn keeps_distance(offset: &[Seg2], chain: &[Seg2], d: f64) -> bool {
    offset.iter().all(|s| {
        (0..=64).all(|k| {
            let q = s.point(k as f64 / 64.0);
            chain.iter().all(|e| e.distance_to(q) >= d - 1e-6)
        })
    })
}

/// How two overlapping offset pieces meet (`join_overlapping`).
pub(super) enum Joined {
    /// Both trimmed to their crossing.
    Both(Seg2, Seg2),
    /// The first piece would run backwards to reach the crossing: the offset swallowed it.
    LastSwallowed,
    /// The second one would.
    NextSwallowed,
}

/// Trims `last` (ending) and `next` (starting) to the crossing of their curves nearest
/// `reference` — with `any_valid`, the nearest at which neither runs backwards, if there is one
/// (a circle crosses a line twice, and after a swallowed element the reference may lie as near
/// one as the other). The verdict is taken at the nearest crossing otherwise. None: the curves
/// do not cross.
pub(super) fn join_overlapping(
    last: &Seg2,
    next: &Seg2,
    reference: P2,
    any_valid: bool,
) -> Option<Joined> {
    let mut crossings = curve_intersections(last, next);
    crossings.sort_by(|a, b| dist2(*a, reference).total_cmp(&dist2(*b, reference)));
    let verdict = |p: P2| {
        let (a, b) = (trim_end(last, p), trim_start(next, p));
        if !same_sense(last, &a) {
            Joined::LastSwallowed
        } else if !same_sense(next, &b) {
            Joined::NextSwallowed
        } else {
            Joined::Both(a, b)
        }
    };
    if any_valid {
        if let Some(both) = crossings
            .iter()
            .map(|p| verdict(*p))
            .find(|j| matches!(j, Joined::Both(..)))
        {
            return Some(both);
        }
    }
    Some(verdict(*crossings.first()?))
}

/// Joins `next` to the last piece of `out`, where their curves cross nearest `reference`; while
/// that piece would have to run backwards (the offset swallowed it too), it is dropped and the
/// one before it tried. Returns `next` trimmed to the joint, or `Some(None)` if `next` would
/// itself run backwards (it is swallowed: the caller leaves it out). None: no crossing, nothing
/// left to join to, or a piece on an end circle (`end_radius`) would have to move.
pub(super) fn join_after_swallowed_or_keep(
    out: &mut Vec<Seg2>,
    source: &mut Vec<Option<usize>>,
    end_radius: &mut Vec<Option<f64>>,
    next: Seg2,
    reference: P2,
) -> Option<Option<Seg2>> {
    for _ in 0..=out.len() {
        if end_radius.last() != Some(&None) {
            return None;
        }
        let last = out.last_mut()?;
        match join_overlapping(last, &next, reference, true)? {
            Joined::Both(a, b) => {
                *last = a;
                return Some(Some(b));
            }
            Joined::NextSwallowed => return Some(None),
            Joined::LastSwallowed => {
                if out.len() < 2 {
                    return None;
                }
                out.pop();
                source.pop();
                end_radius.pop();
            }
        }
    }
    None
}

/// [`join_after_swallowed_or_keep`] once the last piece of `out` is known to be swallowed: it
/// is dropped first.
pub(super) fn join_after_swallowed(
    out: &mut Vec<Seg2>,
    source: &mut Vec<Option<usize>>,
    end_radius: &mut Vec<Option<f64>>,
    next: Seg2,
    reference: P2,
) -> Option<Option<Seg2>> {
    if out.len() < 2 {
        return None;
    }
    out.pop();
    source.pop();
    end_radius.pop();
    join_after_swallowed_or_keep(out, source, end_radius, next, reference)
}

/// The foot of the perpendicular from `p` to the line through `a` and `b` (`a` if they coincide).
pub(super) fn foot_on_line(p: P2, a: P2, b: P2) -> P2 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    if l2 < 1e-300 || !l2.is_finite() {
        return a;
    }
    let t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2;
    [a[0] + t * d[0], a[1] + t * d[1]]
}

/// Whether `trimmed`, a piece of `s`'s curve, still runs the way `s` does (and is no longer).
pub(super) fn same_sense(s: &Seg2, trimmed: &Seg2) -> bool {
    match (*s, *trimmed) {
        (Seg2::Line { a, b }, Seg2::Line { a: p, b: q }) => {
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [q[0] - p[0], q[1] - p[1]]);
            u[0] * v[0] + u[1] * v[1] >= -LEN_EPS * LEN_EPS
        }
        (Seg2::Arc { sweep: s0, .. }, Seg2::Arc { sweep: s1, .. }) => {
            // Shorter, or a little longer (pieces extended to meet), never reversed.
            s1.abs() <= s0.abs() + FRAC_PI_2 && (s1.abs() < PARAM_EPS || s1.signum() == s0.signum())
        }
        _ => false,
    }
}

/// `s` with its end moved to `p` (a point on its curve, possibly a little beyond the end: arcs
/// change their sweep by the wrapped angle from the old end to `p`, so they never wrap round).
pub(super) fn trim_end(s: &Seg2, p: P2) -> Seg2 {
    match *s {
        Seg2::Line { a, .. } => Seg2::Line { a, b: p },
        Seg2::Arc { c, r, start, sweep } => {
            let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
            Seg2::Arc {
                c,
                r,
                start,
                sweep: sweep + wrap_pi(phi - (start + sweep)),
            }
        }
    }
}

/// `s` with its start moved to `p` (a point on its curve; see `trim_end`).
pub(super) fn trim_start(s: &Seg2, p: P2) -> Seg2 {
    match *s {
        Seg2::Line { b, .. } => Seg2::Line { a: p, b },
        Seg2::Arc { c, r, start, sweep } => {
            let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
            let delta = wrap_pi(phi - start);
            Seg2::Arc {
                c,
                r,
                start: start + delta,
                sweep: sweep - delta,
            }
        }
    }
}
