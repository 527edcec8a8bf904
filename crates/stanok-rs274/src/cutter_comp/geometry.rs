//! Plane geometry of cutter compensation: 2-D vector helpers, arc tangents, LinuxCNC's
//! `find_turn`, the offset line, and where two offset lines cross.

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

/// Where the offsets (signed offset `off`: + left) of two programmed lines cross — LinuxCNC's
/// retreat along the first (`convert_straight_comp2`) reaches the same point; parallel ones
/// join where the new one starts, `new_start`. (A corner with an arc: `join.rs`.)
pub(super) fn meet_lines(
    (from, to): ([f64; 2], [f64; 2]),
    (f2, t2): ([f64; 2], [f64; 2]),
    off: f64,
    new_start: [f64; 2],
) -> [f64; 2] {
    let (p1, d1) = offset_line(from, to, off);
    let (p2, d2) = offset_line(f2, t2, off);
    let den = cross(d1, d2);
    if den.abs() < 1e-12 {
        return new_start;
    }
    let t = cross(sub(p2, p1), d2) / den;
    add(p1, scale(d1, t))
}
