//! G41/G42: the equidistant path of a chain of elements, with look-ahead and bottle-neck removal
//! (spec axioma-3 §4.5, §4.6).
//!
//! ```text
//!  element = one block's in-plane line or arc (programmed, plane coordinates, mm) with its
//!            signed offset d (+r left = G41, −r right = G42) and the non-plane moves (events) that
//!            follow it. Entry/exit elements are the lines that join and leave the equidistant.
//!  junction(e1, e2) at P = e1.end = e2.start, turn θ from t1 to t2, side s = sign(d):
//!     |θ| ≤ ε                 smooth: e1 ends at P + d·n1 (= e2's offset start)
//!     s·θ < 0 or reversal     outer:  e1 ends at P + d·n1, arc (P, |d|) to P + d·n2 — owned by e2
//!     otherwise               inner:  both offsets trimmed at their intersection nearest to
//!                                     P + d·n1 (none → error, A14)
//!  window: the front element is finalised when `depth` elements are known (M905); its path
//!  segments are intersected with every later, non-adjacent segment of the window; the first
//!  intersection along the front element (ties: the farthest later segment) cuts the loop out:
//!  the path jumps onto the later segment, the elements in between emit no motion (their events
//!  still run). A reversed (over-trimmed) segment that no cut removes is an error: never a gouge.
//! ```
//! Invariants: elements are finalised strictly in order; every emitted move starts where the
//! previous one ended (the tool pose is carried); the loop over segments is bounded by the window
//! (≤ depth elements, ≤ 2 segments each).

use stanok_canon::{Plane, Pose, Span};
use stanok_geom::offset2d::{
    add_scaled, cross2, curve_intersections, dist2, dot2, left_normal, segment_intersections, sub2,
    turn_angle, Seg2, ANGLE_EPS, LEN_EPS, P2, PARAM_EPS,
};

use crate::state::WorkFrame;

/// Where a compensated motion came from (its block), for the Canon it becomes.
#[derive(Debug, Clone, Copy)]
pub struct Tag {
    pub span: Span,
    pub number: Option<u32>,
    pub slot: u64,
    pub frame: WorkFrame,
    pub plane: Plane,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// Entry line from the tool position `from` (plane, already shifted by the edge vector).
    Entry { from: P2 },
    /// An element of the contour.
    Contour,
    /// Exit line: ends at the programmed point.
    Exit,
}

/// A non-plane motion (e.g. a Z move) programmed between two elements.
#[derive(Debug, Clone, Copy)]
pub struct Event {
    pub end: Pose,
    pub rapid: bool,
    pub feed: f64,
    pub tag: Tag,
}

#[derive(Debug, Clone)]
pub struct Elem {
    pub seg: Seg2,
    pub kind: Kind,
    pub d: f64,
    /// Programmed end, program coordinates (all axes).
    pub end: Pose,
    pub rapid: bool,
    pub feed: f64,
    pub tag: Tag,
    pub events: Vec<Event>,
}

/// One piece of the tool-centre path.
#[derive(Debug, Clone, Copy)]
pub struct PathSeg {
    pub seg: Seg2,
    /// Owning element (index in the window).
    pub owner: usize,
    /// The element's own offset (false: an inserted corner arc).
    pub main: bool,
    /// Over-trimmed: runs against its element (a narrowing the tool cannot follow).
    pub reversed: bool,
}

/// How the front element starts.
#[derive(Debug, Clone, Default)]
pub enum Head {
    /// Entry element, or the first element after G143/G144 (starts at its own offset start).
    #[default]
    Own,
    /// After the finalised element `prev` (the junction decides the lead).
    After(Box<Elem>),
    /// After a bottle-neck cut: the front element's path starts on its segment `index` at `at`.
    Cut {
        prev: Box<Elem>,
        index: usize,
        at: P2,
    },
}

#[derive(Debug, Clone, Copy)]
enum Junction {
    Smooth,
    Outer(Seg2),
    Inner(P2),
}

/// Errors of the geometry, turned into diagnostics by the caller (at the block that made the
/// situation visible).
#[derive(Debug, Clone, PartialEq)]
pub enum ContourError {
    /// No intersection of the equidistants at an inner corner (A14).
    NoIntersection { at: P2 },
    /// The entry/exit intersection lies behind the start point (A17).
    EntryTooClose,
    /// The contour is narrower than the tool and the look-ahead window did not remove it (A16).
    TooNarrow { span: Span },
}

/// The offset curve an element's tool path follows (entry/exit lines: the parallel line).
fn offset(e: &Elem) -> Seg2 {
    e.seg.offset_left(e.d).unwrap_or(e.seg)
}

fn junction(e1: &Elem, e2: &Elem) -> Result<Junction, ContourError> {
    let t1 = e1.seg.tangent(1.0);
    let t2 = e2.seg.tangent(0.0);
    let p = e2.seg.start();
    let d = e2.d;
    let theta = turn_angle(t1, t2);
    let reversal = dot2(t1, t2) < -1.0 + 1e-12 && cross2(t1, t2).abs() < 1e-9;
    if !reversal && theta.abs() <= ANGLE_EPS {
        return Ok(Junction::Smooth);
    }
    let side = d.signum();
    if reversal || side * theta < 0.0 {
        let sweep = if reversal {
            -side * std::f64::consts::PI
        } else {
            theta
        };
        let from = add_scaled(p, left_normal(t1), d);
        let start = (from[1] - p[1]).atan2(from[0] - p[0]);
        return Ok(Junction::Outer(Seg2::Arc {
            c: p,
            r: d.abs(),
            start,
            sweep,
        }));
    }
    let (o1, o2) = (offset(e1), offset(e2));
    let reference = o1.end();
    curve_intersections(&o1, &o2)
        .into_iter()
        .min_by(|x, y| dist2(*x, reference).total_cmp(&dist2(*y, reference)))
        .map(Junction::Inner)
        .ok_or(ContourError::NoIntersection { at: p })
}

/// The path segments of element `e` between its predecessor (`head`) and successor (`next`, None
/// = the path ends at the perpendicular point).
fn segments(
    e: &Elem,
    head: &Head,
    next: Option<&Elem>,
    owner: usize,
) -> Result<Vec<PathSeg>, ContourError> {
    let prev = match head {
        Head::Own => None,
        Head::After(p) | Head::Cut { prev: p, .. } => Some(&**p),
    };
    let lead = match (prev, e.kind) {
        (Some(p), Kind::Contour | Kind::Exit) => Some(junction(p, e)?),
        _ => None,
    };
    let tail = match next {
        Some(n) => Some(junction(e, n)?),
        None => None,
    };
    let mut out = Vec::with_capacity(2);
    let off = offset(e);
    if let Some(Junction::Outer(arc)) = lead {
        out.push(PathSeg {
            seg: arc,
            owner,
            main: false,
            reversed: false,
        });
    }
    let end_point = match tail {
        Some(Junction::Inner(x)) => Some(x),
        _ => None,
    };
    let main = match e.kind {
        Kind::Entry { from } => {
            let to = end_point.unwrap_or(off.end());
            if end_point.is_some() && dot2(sub2(to, from), e.seg.tangent(0.0)) <= LEN_EPS {
                return Err(ContourError::EntryTooClose);
            }
            Seg2::Line { a: from, b: to }
        }
        Kind::Exit => {
            let from = match lead {
                Some(Junction::Inner(x)) => x,
                _ => off.start(),
            };
            Seg2::Line {
                a: from,
                b: e.seg.end(),
            }
        }
        Kind::Contour => {
            let t0 = match lead {
                Some(Junction::Inner(x)) => off.param_near(x, 0.0),
                _ => 0.0,
            };
            let t1 = match end_point {
                Some(x) => off.param_near(x, 1.0),
                None => 1.0,
            };
            let reversed = t1 - t0 < -PARAM_EPS && off.length() * (t0 - t1) > LEN_EPS;
            let piece = off.piece(t0, t1);
            out.push(PathSeg {
                seg: piece,
                owner,
                main: true,
                reversed,
            });
            return Ok(finish_cut(out, head));
        }
    };
    out.push(PathSeg {
        seg: main,
        owner,
        main: true,
        reversed: false,
    });
    Ok(finish_cut(out, head))
}

/// Drops zero-length pieces; after a bottle-neck cut keeps only the part from the cut point on.
fn finish_cut(mut segs: Vec<PathSeg>, head: &Head) -> Vec<PathSeg> {
    segs.retain(|s| s.seg.length() > LEN_EPS);
    if let Head::Cut { index, at, .. } = head {
        let i = (*index).min(segs.len().saturating_sub(1));
        segs.drain(..i);
        if let Some(first) = segs.first_mut() {
            let t = first.seg.param_near(*at, 0.0).clamp(0.0, 1.0);
            first.seg = first.seg.piece(t, 1.0);
        }
        segs.retain(|s| s.seg.length() > LEN_EPS);
    }
    segs
}

/// The result of finalising the front element.
pub struct Finalised {
    /// Path of the front element (to emit with its tag).
    pub path: Vec<PathSeg>,
    /// Elements (indices 1…k−1 of the window) whose motion the cut dropped.
    pub dropped: usize,
    /// The head of the next front element.
    pub next_head: Head,
}

/// Finalises `window[0]` given the rest of the window (`window[1..]`). `end_here` = there is no
/// element after the window (flush): the last element ends at its perpendicular point.
pub fn finalise(window: &[Elem], head: &Head) -> Result<Finalised, ContourError> {
    let mut all: Vec<Vec<PathSeg>> = Vec::with_capacity(window.len());
    let mut h = head.clone();
    for (j, e) in window.iter().enumerate() {
        all.push(segments(e, &h, window.get(j + 1), j)?);
        h = Head::After(Box::new(e.clone()));
    }
    let front = &all[0];
    let later: Vec<(usize, PathSeg)> = all[1..]
        .iter()
        .flat_map(|v| v.iter().copied().enumerate())
        .collect();
    // First intersection along the front element's path with a non-adjacent later segment.
    let mut cut: Option<(usize, f64, usize, f64, P2)> = None;
    'outer: for (si, s) in front.iter().enumerate() {
        let last_of_front = si + 1 == front.len();
        for (li, (_, l)) in later.iter().enumerate() {
            if last_of_front && li == 0 {
                continue; // the chain neighbour: they share the junction point only
            }
            for (ts, tl, p) in segment_intersections(&s.seg, &l.seg) {
                if ts <= PARAM_EPS * 10.0 || s.seg.length() * ts <= LEN_EPS * 10.0 {
                    continue;
                }
                // A tangential touch is not a crossing: the tool just fits (limiting diameter).
                if cross2(s.seg.tangent(ts), l.seg.tangent(tl)).abs() < 1e-7 {
                    continue;
                }
                let better = match cut {
                    None => true,
                    Some((_, t, lj, _, _)) => ts < t - 1e-9 || (ts <= t + 1e-9 && li > lj),
                };
                if better {
                    cut = Some((si, ts, li, tl, p));
                }
            }
        }
        if cut.is_some() {
            break 'outer;
        }
    }
    if let Some((si, ts, li, _tl, p)) = cut {
        let mut path: Vec<PathSeg> = front[..si].to_vec();
        let mut s = front[si];
        s.seg = s.seg.piece(0.0, ts);
        s.reversed = false;
        path.push(s);
        check(&path, window)?;
        let (index_in_owner, l) = later[li];
        let owner = l.owner;
        return Ok(Finalised {
            path,
            dropped: owner - 1,
            next_head: Head::Cut {
                prev: Box::new(window[owner - 1].clone()),
                index: index_in_owner,
                at: p,
            },
        });
    }
    let path = front.clone();
    check(&path, window)?;
    Ok(Finalised {
        path,
        dropped: 0,
        next_head: Head::After(Box::new(window[0].clone())),
    })
}

/// The front element's path may be emitted: nothing in it is reversed, and no point of it comes
/// closer than |d| to a programmed contour element of the window (a narrowing seen in the window
/// but not removed by a cut). Entry and exit lines are the programmer's (§4.3 rule 3).
fn check(path: &[PathSeg], window: &[Elem]) -> Result<(), ContourError> {
    let fail = |s: &PathSeg| ContourError::TooNarrow {
        span: window[s.owner].tag.span,
    };
    if let Some(s) = path.iter().find(|s| s.reversed) {
        return Err(fail(s));
    }
    for s in path {
        let own = &window[s.owner];
        if own.kind != Kind::Contour {
            continue;
        }
        let r = own.d.abs();
        for e in window.iter().filter(|e| e.kind == Kind::Contour) {
            if min_distance(&s.seg, &e.seg) < r - GOUGE_TOL {
                return Err(fail(s));
            }
        }
    }
    Ok(())
}

/// Gouge tolerance, mm.
const GOUGE_TOL: f64 = 1e-6;

/// Smallest distance between a path segment and a programmed segment: sampled along the path
/// segment (64 pieces) and at both segments' ends, then refined by a golden-section search on the
/// best piece — exact for lines and accurate to ~1e-9 mm for arcs of the sizes in a program.
fn min_distance(path: &Seg2, contour: &Seg2) -> f64 {
    // Two lines, the common case: exact and in closed form — 0 where they cross, else the
    // nearest of the four end points to the other segment (the minimum of a distance between
    // two segments that do not cross lies at an end point of one of them). The sampling below
    // costs ~190 distance evaluations per pair, which every block pays for its whole window.
    if let (Seg2::Line { a: p0, b: p1 }, Seg2::Line { a: q0, b: q1 }) = (path, contour) {
        let cross = |o: [f64; 2], u: [f64; 2], v: [f64; 2]| {
            (u[0] - o[0]) * (v[1] - o[1]) - (u[1] - o[1]) * (v[0] - o[0])
        };
        let (d1, d2) = (cross(*q0, *q1, *p0), cross(*q0, *q1, *p1));
        let (d3, d4) = (cross(*p0, *p1, *q0), cross(*p0, *p1, *q1));
        if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
            return 0.0;
        }
        return contour
            .distance_to(*p0)
            .min(contour.distance_to(*p1))
            .min(path.distance_to(*q0))
            .min(path.distance_to(*q1));
    }
    const N: usize = 64;
    let f = |t: f64| contour.distance_to(path.point(t));
    let mut best = (f(0.0), 0usize);
    for i in 1..=N {
        let d = f(i as f64 / N as f64);
        if d < best.0 {
            best = (d, i);
        }
    }
    let (mut lo, mut hi) = (
        (best.1.saturating_sub(1)) as f64 / N as f64,
        ((best.1 + 1).min(N)) as f64 / N as f64,
    );
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..60 {
        let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(a) < f(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    let ends = [contour.start(), contour.end()]
        .iter()
        .map(|p| path.distance_to(*p))
        .fold(f64::MAX, f64::min);
    best.0.min(f((lo + hi) / 2.0)).min(ends)
}

/// The offset direction at the end of an element: `d·nL(t_end)` (G41/G42 → G143/G144 switch).
pub fn end_offset(e: &Elem) -> P2 {
    let n = left_normal(e.seg.tangent(1.0));
    [n[0] * e.d, n[1] * e.d]
}

/// The start of an element's own offset (where a G143/G144 → G41/G42 switch must already be).
pub fn own_start(e: &Elem) -> P2 {
    offset(e).start()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: the smallest distance from 20,001 points along `path` to `contour`.
    fn sampled(path: &Seg2, contour: &Seg2) -> f64 {
        (0..=20_000)
            .map(|i| contour.distance_to(path.point(i as f64 / 20_000.0)))
            .fold(f64::MAX, f64::min)
    }

    /// The closed form for two lines agrees with dense sampling (to the sampling's step) on
    /// crossing, touching, parallel, collinear-overlapping and apart segments, and on a seeded
    /// sweep of random pairs.
    #[test]
    fn line_line_distance_is_exact() {
        let line = |a: P2, b: P2| Seg2::Line { a, b };
        let cases = [
            (
                line([0.0, 0.0], [10.0, 10.0]),
                line([0.0, 10.0], [10.0, 0.0]),
                0.0,
            ),
            (
                line([0.0, 0.0], [10.0, 0.0]),
                line([10.0, 0.0], [10.0, 5.0]),
                0.0,
            ),
            (
                line([0.0, 0.0], [10.0, 0.0]),
                line([0.0, 3.0], [10.0, 3.0]),
                3.0,
            ),
            (
                line([0.0, 0.0], [10.0, 0.0]),
                line([5.0, 0.0], [15.0, 0.0]),
                0.0,
            ),
            (
                line([0.0, 0.0], [1.0, 0.0]),
                line([4.0, 4.0], [5.0, 9.0]),
                5.0,
            ),
        ];
        for (p, q, want) in cases {
            assert!((min_distance(&p, &q) - want).abs() < 1e-12, "{p:?} {q:?}");
        }
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut r = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 20_000) as f64 / 1000.0 - 10.0
        };
        for _ in 0..200 {
            let p = line([r(), r()], [r(), r()]);
            let q = line([r(), r()], [r(), r()]);
            let (exact, dense) = (min_distance(&p, &q), sampled(&p, &q));
            assert!(exact <= dense + 1e-12, "{p:?} {q:?}: {exact} > {dense}");
            assert!(dense - exact < 3e-3, "{p:?} {q:?}: {exact} vs {dense}");
        }
    }
}
