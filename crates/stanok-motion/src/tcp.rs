//! # The kin stage: tool-centre-point control between the planned path and the machine axes
//!
//! While `Canon::SetToolCentrePoint { active: true, .. }` is in force, the positions the planner
//! moves along are **tool poses**: the tip X Y Z in the workpiece-fixed frame and the rotary axis
//! values. The planner times the path as usual, so F is the tip speed, or the rotary speed of an
//! orientation-only block (the adapter's feed-length rule, which is also spec axioma-4 §4.8 and
//! cvu-five-axis.md's). Three things make the machine axes follow:
//!
//! 1. **Limits** ([`limit_segment`], called by the adapter for every segment). The segment is
//!    sampled at n poses (n grows with the rotary travel); the inverse kinematics gives the joints,
//!    and first and second differences give, per joint k, q'_k = max|dq_k/ds| and
//!    q''_k = max|d²q_k/ds²| (s = the planner's path length). A joint moves at q'_k·v and
//!    accelerates at q'_k·a + q''_k·v², so with each acceleration budget A_k split in halves:
//!    ```text
//!      v ≤ V_k / q'_k        v² ≤ (A_k / 2) / q''_k        a ≤ (A_k / 2) / q'_k
//!    ```
//!    each times [`SAFETY`] for what the samples miss. The first two cap the segment's path
//!    speed ([`crate::segment::PathSegment::velocity_cap`], which no override raises), the third its
//!    path acceleration ([`crate::segment::PathSegment::acceleration_cap`]).
//! 2. **Orientation** ([`vector_polyline`]): under ORIVECT the tool vector turns on the great
//!    circle, so the segment becomes a polyline whose rotary values follow the great circle,
//!    sampled every [`ORIVECT_STEP_DEG`] and solved by continuity with the previous sample (the
//!    tip points stay on the programmed line). An orientation-only block then runs at F as the
//!    vector's angular speed: duration Ω / F (spec axioma-4 §4.8 [P]). Under ORIAXES the rotary
//!    values are already linear.
//! 3. **Every servo cycle** ([`TcpMap::joints`], called by the stage on each setpoint): the pose
//!    goes through the inverse kinematics; joint velocity = J·v and acceleration = J·a + vᵀ∇²q·v,
//!    by central differences of the inverse kinematics along v and a (step [`FD_STEP_S`]); jerk
//!    is approximated by J·j.
//!
//! Decision: under tool-centre-point control every block ends with an exact stop (blending in the
//! mixed mm/deg pose space would let the joints see accelerations the caps above do not bound).
//!
//! Invariant (tested in `tests/tcp.rs`): the tip of every setpoint (forward kinematics of its
//! joints) lies on the programmed segment within 1e-6 mm, and no joint exceeds its limits.

use crate::interpolator::Setpoint;
use crate::limits::AxisLimit;
use crate::segment::{PathSegment, Point9, SegmentGeometry};
use stanok_canon::Pose;
use stanok_kin::{FiveAxis, Kinematics};

/// Share of each limit the caps use (the rest covers what the samples miss).
pub const SAFETY: f64 = 0.9;
/// Great-circle step of the ORIVECT polyline, degrees.
pub const ORIVECT_STEP_DEG: f64 = 0.5;
/// Time step of the central differences of the per-cycle joint derivatives, s.
pub const FD_STEP_S: f64 = 1e-4;

/// Pose → joints for the setpoints of the kin stage.
#[derive(Debug, Clone, PartialEq)]
pub struct TcpMap {
    kin: FiveAxis,
}

fn q(kin: &FiveAxis, p: &Point9) -> Point9 {
    kin.inverse(&Pose::from_array(*p)).unwrap_or(*p)
}

fn along(p: &Point9, d: &Point9, h: f64) -> Point9 {
    std::array::from_fn(|i| p[i] + h * d[i])
}

impl TcpMap {
    /// The map of a machine with its active tool offset applied.
    pub fn new(kin: FiveAxis) -> Self {
        TcpMap { kin }
    }

    /// The kinematics.
    pub fn kinematics(&self) -> &FiveAxis {
        &self.kin
    }

    /// The setpoint of the machine axes for a setpoint of the tool pose (module doc, step 3).
    pub fn joints(&self, sp: &Setpoint) -> Setpoint {
        let h = FD_STEP_S;
        let p = &sp.position;
        let q0 = q(&self.kin, p);
        let qp = q(&self.kin, &along(p, &sp.velocity, h));
        let qm = q(&self.kin, &along(p, &sp.velocity, -h));
        let ap = q(&self.kin, &along(p, &sp.acceleration, h));
        let am = q(&self.kin, &along(p, &sp.acceleration, -h));
        let jp = q(&self.kin, &along(p, &sp.jerk, h));
        let jm = q(&self.kin, &along(p, &sp.jerk, -h));
        Setpoint {
            position: q0,
            velocity: std::array::from_fn(|i| (qp[i] - qm[i]) / (2.0 * h)),
            acceleration: std::array::from_fn(|i| {
                (ap[i] - am[i]) / (2.0 * h) + (qp[i] - 2.0 * q0[i] + qm[i]) / (h * h)
            }),
            jerk: std::array::from_fn(|i| (jp[i] - jm[i]) / (2.0 * h)),
            ..*sp
        }
    }
}

/// The pose at fraction `f` ∈ [0, 1] of a segment's path (by the planner's 9-D length).
fn pose_at(seg: &PathSegment, f: f64) -> Point9 {
    let lerp = |i: usize| seg.start[i] + (seg.end[i] - seg.start[i]) * f;
    match &seg.geometry {
        SegmentGeometry::Line => std::array::from_fn(lerp),
        SegmentGeometry::Arc(h) => {
            let xyz = h.point_at(f);
            std::array::from_fn(|i| if i < 3 { xyz[i] } else { lerp(i) })
        }
        SegmentGeometry::Polyline(points) => polyline_at(points, f),
    }
}

fn dist9(a: &Point9, b: &Point9) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn polyline_at(points: &[Point9], f: f64) -> Point9 {
    let total: f64 = points.windows(2).map(|w| dist9(&w[0], &w[1])).sum();
    let mut want = f * total;
    for w in points.windows(2) {
        let l = dist9(&w[0], &w[1]);
        if want <= l && l > 0.0 {
            let g = want / l;
            return std::array::from_fn(|i| w[0][i] + (w[1][i] - w[0][i]) * g);
        }
        want -= l;
    }
    *points.last().unwrap_or(&[0.0; 9])
}

/// The 9-D length of a segment (as the path builder measures it, up to chords).
fn segment_length(seg: &PathSegment, samples: &[Point9]) -> f64 {
    match &seg.geometry {
        SegmentGeometry::Line => dist9(&seg.start, &seg.end),
        _ => samples.windows(2).map(|w| dist9(&w[0], &w[1])).sum(),
    }
}

/// How many samples a segment needs: 64, and 4 per degree of rotary travel, at most 4096.
fn sample_count(seg: &PathSegment) -> usize {
    let rotary: f64 = (3..6).map(|i| (seg.end[i] - seg.start[i]).abs()).sum();
    ((4.0 * rotary).ceil() as usize).clamp(64, 4096)
}

/// Caps a segment's path speed and acceleration so that no machine axis exceeds its limits
/// (module doc, step 1), and makes its end an exact stop.
pub fn limit_segment(seg: &mut PathSegment, kin: &FiveAxis, axes: &[AxisLimit; 9]) {
    seg.path_mode = stanok_canon::PathMode::ExactStop;
    let n = sample_count(seg);
    let samples: Vec<Point9> = (0..=n).map(|k| pose_at(seg, k as f64 / n as f64)).collect();
    let length = segment_length(seg, &samples);
    if !(length.is_finite() && length > 0.0) {
        return;
    }
    let ds = length / n as f64;
    let joints: Vec<Point9> = samples.iter().map(|p| q(kin, p)).collect();
    let mut rate = [0.0f64; 9];
    let mut curve = [0.0f64; 9];
    for k in 1..joints.len() {
        for i in 0..9 {
            rate[i] = rate[i].max((joints[k][i] - joints[k - 1][i]).abs() / ds);
            if k + 1 < joints.len() {
                let second = joints[k + 1][i] - 2.0 * joints[k][i] + joints[k - 1][i];
                curve[i] = curve[i].max(second.abs() / (ds * ds));
            }
        }
    }
    let mut v_cap = f64::INFINITY;
    let mut a_cap = f64::INFINITY;
    for i in 0..9 {
        let lim = &axes[i];
        if rate[i] > 1e-12 {
            v_cap = v_cap.min(SAFETY * lim.velocity / rate[i]);
            a_cap = a_cap.min(SAFETY * 0.5 * lim.acceleration / rate[i]);
        }
        if curve[i] > 1e-9 {
            v_cap = v_cap.min((SAFETY * 0.5 * lim.acceleration / curve[i]).sqrt());
        }
    }
    if v_cap.is_finite() && v_cap > 0.0 {
        seg.velocity_cap = seg.velocity_cap.min(v_cap);
    }
    if a_cap.is_finite() && a_cap > 0.0 {
        seg.acceleration_cap = seg.acceleration_cap.min(a_cap);
    }
}

/// The ORIVECT form of a straight or circular segment (module doc, step 2): a polyline whose tip
/// points follow the programmed curve and whose rotary values follow the great circle of the tool
/// vector, and the great-circle angle Ω in degrees. None when the orientation does not change or
/// cannot be followed (the axes then move linearly, as under ORIAXES).
pub fn vector_polyline(seg: &PathSegment, kin: &FiveAxis) -> Option<(SegmentGeometry, f64)> {
    let start = Pose::from_array(seg.start);
    let end = Pose::from_array(seg.end);
    let t0 = vec3(kin.tool_vector(&start));
    let t1 = vec3(kin.tool_vector(&end));
    let omega = stanok_kin::orientation::angle_between(&t0, &t1);
    if omega < 1e-9 {
        return None;
    }
    let n = ((omega / ORIVECT_STEP_DEG).ceil() as usize).max(2);
    let mut points = Vec::with_capacity(n + 1);
    let mut current = start;
    points.push(seg.start);
    for k in 1..n {
        let f = k as f64 / n as f64;
        let t = stanok_kin::orientation::slerp(&t0, &t1, f, None);
        current = kin.orient(t.into(), &current).ok()?;
        let mut p = pose_at(seg, f);
        p[3..6].copy_from_slice(&current.to_array()[3..6]);
        points.push(p);
    }
    // The great circle must arrive on the branch the interpreter chose for the end.
    let last = kin.orient(t1.into(), &current).ok()?;
    if (3..6).any(|i| (last.to_array()[i] - seg.end[i]).abs() > 1e-6) {
        return None;
    }
    points.push(seg.end);
    Some((SegmentGeometry::Polyline(points), omega))
}

fn vec3(v: [f64; 3]) -> stanok_kin::orientation::Vector3<f64> {
    stanok_kin::orientation::Vector3::from(v)
}
