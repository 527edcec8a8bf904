//! Plane geometry of cutter compensation: 2-D vector helpers, the offset line, line–circle and
//! circle–circle intersections, sweeps and turns, and where two offset elements meet.

use super::Element;

pub(super) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
pub(super) fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}
pub(super) fn scale(a: [f64; 2], k: f64) -> [f64; 2] {
    [a[0] * k, a[1] * k]
}
pub(super) fn len(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}
pub(super) fn unit(a: [f64; 2]) -> [f64; 2] {
    let l = len(a);
    if l > 0.0 {
        scale(a, 1.0 / l)
    } else {
        [1.0, 0.0]
    }
}
pub(super) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
pub(super) fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
/// `v` rotated +90°.
pub(super) fn left(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// Tangent of an arc about `c` at point `p`.
pub(super) fn arc_tangent(c: [f64; 2], p: [f64; 2], ccw: bool) -> [f64; 2] {
    let t = left(unit(sub(p, c)));
    if ccw {
        t
    } else {
        scale(t, -1.0)
    }
}

/// LinuxCNC's `find_turn` for a one-turn arc: the signed angle from `a` to `b` about `c`, in
/// (0, 2π] counter-clockwise or [−2π, 0) clockwise.
pub(super) fn find_turn(a: [f64; 2], c: [f64; 2], ccw: bool, b: [f64; 2]) -> f64 {
    use std::f64::consts::TAU;
    let mut alpha = (a[1] - c[1]).atan2(a[0] - c[0]);
    let mut beta = (b[1] - c[1]).atan2(b[0] - c[0]);
    if ccw {
        if beta <= alpha {
            beta += TAU;
        }
    } else if alpha <= beta {
        alpha += TAU;
    }
    beta - alpha
}

/// Offset line of a programmed line: a point and the direction.
pub(super) fn offset_line(from: [f64; 2], to: [f64; 2], off: f64) -> ([f64; 2], [f64; 2]) {
    let d = unit(sub(to, from));
    (add(from, scale(left(d), off)), d)
}

/// How far apart (mm) elements may miss each other and still count as touching: offset paths
/// that are tangent in exact arithmetic (a line running into an arc tangentially) miss by
/// rounding only.
pub(super) const TANGENT_TOLERANCE: f64 = 1e-6;

/// Intersections of a line (point p, unit direction d) with a circle (tangent within
/// [`TANGENT_TOLERANCE`] counts as one double point).
pub(super) fn line_circle(p: [f64; 2], d: [f64; 2], c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    let f = sub(p, c);
    let b = dot(f, d);
    let mut disc = b * b - (dot(f, f) - r * r);
    if disc < 0.0 {
        // The line misses the circle by δ where −disc = 2rδ + δ².
        if -disc > TANGENT_TOLERANCE * (2.0 * r + TANGENT_TOLERANCE) {
            return Vec::new();
        }
        disc = 0.0;
    }
    let q = disc.sqrt();
    vec![add(p, scale(d, -b - q)), add(p, scale(d, -b + q))]
}

/// Intersections of two circles; `same` is returned when they coincide (an arc continued by an
/// arc of the same circle: the corner point is where the new one starts).
pub(super) fn circle_circle(
    c1: [f64; 2],
    r1: f64,
    c2: [f64; 2],
    r2: f64,
    same: [f64; 2],
) -> Vec<[f64; 2]> {
    let d = len(sub(c2, c1));
    if d < TANGENT_TOLERANCE && (r1 - r2).abs() < TANGENT_TOLERANCE {
        return vec![same];
    }
    if d == 0.0 || d > r1 + r2 + TANGENT_TOLERANCE || d < (r1 - r2).abs() - TANGENT_TOLERANCE {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let u = unit(sub(c2, c1));
    let m = add(c1, scale(u, a));
    vec![add(m, scale(left(u), h)), add(m, scale(left(u), -h))]
}

/// Angle swept from `a` to `b` about `c` in the arc's sense, in [0, 2π).
pub(super) fn sweep(c: [f64; 2], a: [f64; 2], b: [f64; 2], ccw: bool) -> f64 {
    let (u, v) = (sub(a, c), sub(b, c));
    let mut t = cross(u, v).atan2(dot(u, v));
    if !ccw {
        t = -t;
    }
    if t < 0.0 {
        t += std::f64::consts::TAU;
    }
    t
}

/// Where the offset of `last` meets the offset of `new` (signed offset `off`: + left).
/// `prev_end` is the last element's offset end, `new_start` the new one's offset start.
pub(super) fn meet(
    last: Element,
    new: Element,
    off: f64,
    prev_end: [f64; 2],
    new_start: [f64; 2],
) -> Option<[f64; 2]> {
    let candidates: Vec<[f64; 2]> = match (last, new) {
        (Element::Line { from, to }, Element::Line { from: f2, to: t2 }) => {
            let (p1, d1) = offset_line(from, to, off);
            let (p2, d2) = offset_line(f2, t2, off);
            let den = cross(d1, d2);
            if den.abs() < 1e-12 {
                return Some(new_start);
            }
            let t = cross(sub(p2, p1), d2) / den;
            vec![add(p1, scale(d1, t))]
        }
        (
            Element::Line { from, to },
            Element::Arc {
                centre,
                tool_radius,
                ..
            },
        ) => {
            let (p, d) = offset_line(from, to, off);
            line_circle(p, d, centre, tool_radius)
        }
        (
            Element::Arc {
                centre,
                tool_radius,
                ..
            },
            Element::Line { from, to },
        ) => {
            let (p, d) = offset_line(from, to, off);
            line_circle(p, d, centre, tool_radius)
        }
        (
            Element::Arc {
                centre: c1,
                tool_radius: r1,
                ..
            },
            Element::Arc {
                centre: c2,
                tool_radius: r2,
                ..
            },
        ) => circle_circle(c1, r1, c2, r2, new_start),
    };
    match last {
        // After a line: the intersection nearest the line's offset end.
        Element::Line { .. } => candidates
            .into_iter()
            .min_by(|a, b| len(sub(*a, prev_end)).total_cmp(&len(sub(*b, prev_end)))),
        // After an arc: the one the tool reaches first along it.
        Element::Arc {
            centre,
            ccw,
            tool_from,
            ..
        } => candidates.into_iter().min_by(|a, b| {
            sweep(centre, tool_from, *a, ccw).total_cmp(&sweep(centre, tool_from, *b, ccw))
        }),
    }
}
