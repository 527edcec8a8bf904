//! The contour error measured on the trace: the distance of every setpoint from the programmed
//! path, split into junctions (the blends that join two programmed segments) and elsewhere.
//!
//! ## What is measured
//! The stage registers every programmed segment under its running number ([`crate::path::
//! PathBuilder::next_seq`]) with its programmed geometry: the line between its ends, the arc (its
//! cylindrical frame, [`stanok_geom::HelixFrame`]), or a spline's points (a tessellation of the
//! NURBS within [`SPLINE_REFERENCE_TOLERANCE`], finer than the path's own chords). Every setpoint
//! carries the number of the segment its piece belongs to and whether that piece is a junction
//! blend. The distance, in X Y Z (mm; the tool tip under tool-centre-point control, whose
//! setpoints are measured before the kin stage), is taken to that segment — and, on a junction,
//! to the segment before it too, the smaller one counting. This is the trace against the
//! programmed geometry, not a bound: a planner fault that left the path would show here.
//!
//! ## Distances
//! * Line: to the segment (clamped projection).
//! * Arc: the angle of the point's projection on the arc's plane gives a candidate on each turn
//!   (for a circle the nearest point exactly); the best is refined by Newton's method on
//!   |p(θ) − q|² (three steps, clamped to the sweep), and compared with both ends.
//! * Spline: to the nearest chord of the reference, searched around the last nearest chord (the
//!   trace moves forward), the whole polyline when that search finds nothing close.
//!
//! Memory: the segments from the one before the current setpoint's to the last registered — the
//! planner's look-ahead window.

use crate::segment::Point9;
use std::collections::VecDeque;
use std::sync::Arc;

/// Chord tolerance of a spline's reference polyline, mm.
pub const SPLINE_REFERENCE_TOLERANCE: f64 = 1e-5;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
fn xyz(p: &Point9) -> V3 {
    [p[0], p[1], p[2]]
}

/// Distance from `q` to the segment a–b.
fn to_segment(q: V3, a: V3, b: V3) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(sub(q, a), ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(
        q,
        [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]],
    ))
}

/// The programmed geometry of one segment, X Y Z.
#[derive(Debug, Clone)]
pub enum Reference {
    /// A straight move.
    Line {
        /// Start.
        a: V3,
        /// End.
        b: V3,
    },
    /// A circle, helix or spiral.
    Arc(stanok_geom::HelixFrame),
    /// A spline's points, in path order.
    Polyline(Arc<Vec<V3>>),
}

impl Reference {
    /// Distance of `q` from the geometry; `hint` is the nearest chord of a polyline found last.
    fn distance(&self, q: V3, hint: &mut usize) -> f64 {
        match self {
            Reference::Line { a, b } => to_segment(q, *a, *b),
            Reference::Arc(f) => arc_distance(f, q),
            Reference::Polyline(points) => polyline_distance(points, q, hint),
        }
    }
}

fn arc_point(f: &stanok_geom::HelixFrame, th: f64) -> (V3, V3, V3) {
    let t = th / f.sweep;
    let r = f.r_s + (f.r_e - f.r_s) * t;
    let dr = (f.r_e - f.r_s) / f.sweep;
    let dh = (f.h_e - f.h_s) / f.sweep;
    let h = f.h_s + dh * th;
    let (s, c) = th.sin_cos();
    let rad: V3 = std::array::from_fn(|i| c * f.u[i] + s * f.v[i]);
    let tan: V3 = std::array::from_fn(|i| -s * f.u[i] + c * f.v[i]);
    let p = std::array::from_fn(|i| f.centre[i] + f.a[i] * h + r * rad[i]);
    let d1 = std::array::from_fn(|i| f.a[i] * dh + dr * rad[i] + r * tan[i]);
    let d2 = std::array::from_fn(|i| 2.0 * dr * tan[i] - r * rad[i]);
    (p, d1, d2)
}

/// Distance from `q` to the arc (module doc).
fn arc_distance(f: &stanok_geom::HelixFrame, q: V3) -> f64 {
    let d = sub(q, f.centre);
    let (x, y) = (dot(d, f.u), dot(d, f.v));
    let base = y.atan2(x).rem_euclid(std::f64::consts::TAU);
    let tau = std::f64::consts::TAU;
    // The turns worth trying: all of a few, else those near the axial position.
    let turns = (f.sweep / tau).ceil() as i64;
    let (k0, k1) = if turns <= 8 || f.h_e == f.h_s {
        (0, turns.min(64))
    } else {
        let per_rad = (f.h_e - f.h_s) / f.sweep;
        let th = (dot(d, f.a) - f.h_s) / per_rad;
        let k = ((th - base) / tau).round() as i64;
        ((k - 1).max(0), (k + 1).min(turns))
    };
    let dist = |th: f64| norm(sub(arc_point(f, th).0, q));
    let mut best = (dist(0.0), 0.0);
    let end = dist(f.sweep);
    if end < best.0 {
        best = (end, f.sweep);
    }
    for k in k0..=k1 {
        let th = base + k as f64 * tau;
        if th >= 0.0 && th <= f.sweep {
            let e = dist(th);
            if e < best.0 {
                best = (e, th);
            }
        }
    }
    // Newton on g(θ) = ½|p(θ) − q|²: g′ = (p − q)·p′, g″ = p′·p′ + (p − q)·p″.
    let mut th = best.1;
    for _ in 0..3 {
        let (p, d1, d2) = arc_point(f, th);
        let e = sub(p, q);
        let g1 = dot(e, d1);
        let g2 = dot(d1, d1) + dot(e, d2);
        if g2.is_nan() || g2 <= 0.0 {
            break;
        }
        th = (th - g1 / g2).clamp(0.0, f.sweep);
    }
    best.0.min(dist(th))
}

/// Distance from `q` to the polyline, searching the chords around `hint` first (module doc).
fn polyline_distance(points: &[V3], q: V3, hint: &mut usize) -> f64 {
    let n = points.len();
    if n < 2 {
        return points.first().map_or(f64::INFINITY, |p| norm(sub(q, *p)));
    }
    let chord = |k: usize| to_segment(q, points[k], points[k + 1]);
    let (lo, hi) = (hint.saturating_sub(16), (*hint + 256).min(n - 1));
    let mut best = (f64::INFINITY, *hint);
    for k in lo..hi {
        let d = chord(k);
        if d < best.0 {
            best = (d, k);
        }
    }
    // The window's edge or nothing near: look at every chord.
    if best.1 + 1 >= hi && hi < n - 1 || best.0 > 1e-3 {
        for k in 0..n - 1 {
            let d = chord(k);
            if d < best.0 {
                best = (d, k);
            }
        }
    }
    *hint = best.1;
    best.0
}

/// The largest distance found in one class of setpoints, with where it happened.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContourMax {
    /// Distance from the programmed path, mm.
    pub distance: f64,
    /// Machine time of the setpoint, s.
    pub t: f64,
    /// Source line of its block.
    pub line: u32,
}

impl ContourMax {
    fn take(&mut self, distance: f64, t: f64, line: u32) {
        if distance > self.distance {
            *self = ContourMax { distance, t, line };
        }
    }
}

/// Measures the setpoints against the programmed segments (module doc).
#[derive(Debug, Clone, Default)]
pub struct ContourMonitor {
    refs: VecDeque<(u64, Reference)>,
    hint: usize,
    hint_seq: u64,
    /// On junction blends.
    pub junctions: ContourMax,
    /// Everywhere else (lines, arcs, spline chords, standstill).
    pub elsewhere: ContourMax,
}

impl ContourMonitor {
    /// Registers the programmed geometry of segment `seq` (in increasing order).
    pub fn register(&mut self, seq: u64, reference: Reference) {
        self.refs.push_back((seq, reference));
    }

    /// Measures one setpoint of segment `seq` at `position` (see the module doc).
    pub fn observe(&mut self, position: &Point9, seq: u64, junction: bool, t: f64, line: u32) {
        // Keep the last segment before `seq` (a junction's other side) and everything after.
        while self.refs.len() >= 2 && self.refs[1].0 < seq {
            self.refs.pop_front();
        }
        if self.refs.is_empty() {
            return;
        }
        // refs[0] is now the last segment before `seq` (or `seq` itself), refs[1] `seq` or later.
        let current = if self.refs.len() > 1 && self.refs[1].0 == seq {
            1
        } else if self.refs[0].0 <= seq {
            0
        } else {
            return;
        };
        if seq != self.hint_seq {
            self.hint = 0;
            self.hint_seq = seq;
        }
        let q = xyz(position);
        let mut d = self.refs[current].1.distance(q, &mut self.hint);
        if junction && current == 1 {
            let mut scratch = usize::MAX / 2;
            d = d.min(self.refs[0].1.distance(q, &mut scratch));
        }
        if !d.is_finite() {
            return;
        }
        if junction {
            self.junctions.take(d, t, line);
        } else {
            self.elsewhere.take(d, t, line);
        }
    }
}

/// The reference of a straight or circular segment from `start` to `end` (X Y Z of 9-D points).
pub fn line_reference(start: &Point9, end: &Point9) -> Reference {
    Reference::Line {
        a: xyz(start),
        b: xyz(end),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_geom::Helix;

    #[test]
    fn distances_to_lines_arcs_and_polylines() {
        let l = Reference::Line {
            a: [0.0, 0.0, 0.0],
            b: [10.0, 0.0, 0.0],
        };
        let mut h = 0;
        assert_eq!(l.distance([5.0, 3.0, 4.0], &mut h), 5.0);
        assert_eq!(l.distance([13.0, 4.0, 0.0], &mut h), 5.0);
        // A helix r 10, 3 turns, 2 mm per turn: a point 0.1 outside at angle 100° of turn 2.
        let helix = Helix {
            start: [10.0, 0.0, 0.0],
            end: [10.0, 0.0, 6.0],
            centre: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            turns: 3,
        };
        let a = Reference::Arc(helix.frame());
        let th = std::f64::consts::TAU + 100f64.to_radians();
        let z = 2.0 * th / std::f64::consts::TAU;
        let q = [10.1 * th.cos(), 10.1 * th.sin(), z];
        let on = [10.0 * th.cos(), 10.0 * th.sin(), z];
        assert!(a.distance(on, &mut h) < 1e-12);
        // Radially out from a helix point, q − p is normal to the helix there: 0.1.
        let d = a.distance(q, &mut h);
        assert!((d - 0.1).abs() < 1e-12, "{d}");
        // Off axially by 0.3 between two turns 2 mm apart: nearer the turn below.
        let d = a.distance([on[0], on[1], z + 0.3], &mut h);
        assert!(d < 0.3 && d > 0.29, "{d}");
        // A polyline: the corner of an L.
        let p = Reference::Polyline(Arc::new(vec![
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            [10.0, 10.0, 0.0],
        ]));
        assert!((p.distance([9.0, 1.0, 0.0], &mut h) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_junction_counts_its_two_segments() {
        let mut m = ContourMonitor::default();
        m.register(
            1,
            Reference::Line {
                a: [0.0, 0.0, 0.0],
                b: [10.0, 0.0, 0.0],
            },
        );
        m.register(
            2,
            Reference::Line {
                a: [10.0, 0.0, 0.0],
                b: [10.0, 10.0, 0.0],
            },
        );
        // Near the corner, inside: 0.1 from the first segment, 0.2 from the second.
        let mut p = [0.0; 9];
        p[0] = 9.8;
        p[1] = 0.1;
        m.observe(&p, 2, true, 1.0, 7);
        assert!((m.junctions.distance - 0.1).abs() < 1e-12);
        assert_eq!((m.junctions.t, m.junctions.line), (1.0, 7));
        // Elsewhere on segment 2 only: 0.2.
        m.observe(&p, 2, false, 2.0, 8);
        assert!((m.elsewhere.distance - 0.2).abs() < 1e-12);
    }
}
