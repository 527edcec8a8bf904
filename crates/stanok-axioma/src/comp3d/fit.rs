//! A compensated tip path as Canon: the path is a function λ ∈ [0, 1] ↦ pose (tip X Y Z plus the
//! rotary and other axes, which always move linearly in λ).
//!
//! ```text
//!  f(¼), f(½), f(¾) on the straight line start → end, at their fractions   → one straight move
//!  else, other axes constant and f(¼), f(¾) on the circle through
//!        f(0), f(½), f(1) (radius and plane within 1e-9)                    → one arc
//!  else  8 chords, each halved until its midpoint is within CHORD_TOL of
//!        f there (at most 2^8 per chord)                                    → straight moves
//! ```
//!
//! So lines, arcs of constant tool and ISD, and the peripheral bypass are exact; paths of a turning
//! tool or a changing normal are polylines whose vertices lie on the exact path.

use stanok_canon::{ArcMove, Canon, LineMove, Plane, Pose, Spanned};
use stanok_geom::{add, cross, dot, norm, normalize, scale, sub, Vec3};

/// Largest distance of a polyline chord's midpoint from the exact compensated path, mm.
pub const CHORD_TOL: f64 = 1e-3;

const EXACT: f64 = 1e-9;
const MAX_DEPTH: u32 = 8;

fn copy_with(tmpl: &Spanned<Canon>, value: Canon) -> Spanned<Canon> {
    let mut s = tmpl.clone();
    s.value = value;
    s
}

fn plane_of(tmpl: &Spanned<Canon>) -> Plane {
    match &tmpl.value {
        Canon::ArcFeed(a) => a.plane,
        Canon::SplineFeed(s) => s.plane,
        _ => Plane::XY,
    }
}

fn line(tmpl: &Spanned<Canon>, start: Pose, end: Pose, rapid: bool, feed: f64) -> Spanned<Canon> {
    let m = LineMove {
        start,
        end,
        feed: if rapid { 0.0 } else { feed },
        // The driver completes the law as it releases the motion.
        law: Default::default(),
    };
    copy_with(
        tmpl,
        if rapid {
            Canon::StraightTraverse(m)
        } else {
            Canon::StraightFeed(m)
        },
    )
}

/// The centre of the circle through three points (None when they are collinear).
pub fn circle_centre(a: Vec3, b: Vec3, c: Vec3) -> Option<Vec3> {
    let u = sub(b, a);
    let v = sub(c, a);
    let w = cross(u, v);
    let ww = dot(w, w);
    if ww < 1e-18 * (dot(u, u) * dot(v, v)).max(1e-300) {
        return None;
    }
    let num = add(scale(cross(v, w), dot(u, u)), scale(cross(w, u), dot(v, v)));
    Some(add(a, scale(num, 1.0 / (2.0 * ww))))
}

fn dist_lerp(f: &dyn Fn(f64) -> Pose, a: f64, b: f64, pa: Vec3, pb: Vec3, l: f64) -> f64 {
    let want = f(a + (b - a) * l).xyz();
    let chord = add(pa, scale(sub(pb, pa), l));
    norm(sub(want, chord))
}

/// The Canon moves of the path `f` from `start` (where the tool is: usually `f(0)`).
pub fn emit_path(
    tmpl: &Spanned<Canon>,
    start: Pose,
    f: &dyn Fn(f64) -> Pose,
    rapid: bool,
    feed: f64,
) -> Vec<Spanned<Canon>> {
    let end = f(1.0);
    let (p0, p1) = (f(0.0).xyz(), end.xyz());
    let len = norm(sub(p1, p0));
    let tol = EXACT * len.max(1.0);
    // A straight line, uniform in λ.
    if [0.25, 0.5, 0.75]
        .iter()
        .all(|&l| dist_lerp(f, 0.0, 1.0, p0, p1, l) <= tol)
    {
        if start == end {
            return Vec::new();
        }
        return vec![line(tmpl, start, end, rapid, feed)];
    }
    // An arc (the other axes standing still).
    let (s_arr, e_arr) = (f(0.0).to_array(), end.to_array());
    let still = (3..9).all(|i| (s_arr[i] - e_arr[i]).abs() < 1e-12);
    if still && !rapid {
        let pm = f(0.5).xyz();
        if let Some(c) = circle_centre(p0, pm, p1) {
            let r = norm(sub(p0, c));
            if let Some(axis) = normalize(cross(sub(p0, c), sub(pm, c))) {
                let on = |l: f64| {
                    let q = f(l).xyz();
                    (norm(sub(q, c)) - r).abs() <= EXACT * r.max(1.0)
                        && dot(sub(q, c), axis).abs() <= EXACT * r.max(1.0)
                };
                if on(0.25) && on(0.75) && on(0.125) && on(0.875) {
                    return vec![copy_with(
                        tmpl,
                        Canon::ArcFeed(ArcMove {
                            start,
                            end,
                            centre: c,
                            axis,
                            turns: 1,
                            plane: plane_of(tmpl),
                            feed,
                            law: Default::default(),
                        }),
                    )];
                }
            }
        }
    }
    // A polyline with its vertices on the path.
    let mut out = Vec::new();
    let mut from = start;
    let mut stack: Vec<(f64, f64, u32)> = (0..8)
        .rev()
        .map(|i| (i as f64 / 8.0, (i + 1) as f64 / 8.0, 0))
        .collect();
    while let Some((a, b, depth)) = stack.pop() {
        let (pa, pb) = (f(a).xyz(), f(b).xyz());
        if depth < MAX_DEPTH && dist_lerp(f, a, b, pa, pb, 0.5) > CHORD_TOL {
            let m = (a + b) / 2.0;
            stack.push((m, b, depth + 1));
            stack.push((a, m, depth + 1));
            continue;
        }
        let to = f(b);
        out.push(line(tmpl, from, to, rapid, feed));
        from = to;
    }
    out
}

/// Straight moves through `points` (poses on the exact path), from `start`.
pub fn emit_points(
    tmpl: &Spanned<Canon>,
    start: Pose,
    points: &[Pose],
    feed: f64,
) -> Vec<Spanned<Canon>> {
    let mut out = Vec::with_capacity(points.len());
    let mut from = start;
    for &to in points {
        if to != from {
            out.push(line(tmpl, from, to, false, feed));
            from = to;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_through_three_points() {
        let c = circle_centre([1.0, 0.0, 5.0], [0.0, 1.0, 5.0], [-1.0, 0.0, 5.0]).unwrap();
        assert!(norm(sub(c, [0.0, 0.0, 5.0])) < 1e-12);
        assert!(circle_centre([0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]).is_none());
    }
}
