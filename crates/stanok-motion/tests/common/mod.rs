//! Helpers shared by the motion tests: a 3-axis machine, segment builders, a run that collects the
//! trace, distances to the programmed path.
#![allow(dead_code)]

use stanok_canon::{AccelerationProfile, PathMode};
use stanok_motion::monitor::TraceMonitor;
use stanok_motion::segment::{PathSegment, PlannerInput, Point9, SegmentGeometry};
use stanok_motion::{AxisLimit, MotionConfig, MotionStage, Setpoint};

/// X Y Z: 10 000 mm/min, 1000 mm/s², 20 000 mm/s³ (the built-in mill); other axes absent.
pub fn mill() -> MotionConfig {
    let mut axes = [AxisLimit::UNLIMITED; 9];
    for a in axes.iter_mut().take(3) {
        *a = AxisLimit::from_machine(10_000.0, 1000.0, 20_000.0);
    }
    MotionConfig::new(axes, 10_000.0, 5_000.0)
}

pub fn p3(x: f64, y: f64, z: f64) -> Point9 {
    let mut p = [0.0; 9];
    p[0] = x;
    p[1] = y;
    p[2] = z;
    p
}

/// A straight feed segment at `feed` mm/min (path speed = feed for XYZ-only moves).
pub fn line(
    a: Point9,
    b: Point9,
    feed: f64,
    mode: PathMode,
    profile: AccelerationProfile,
) -> PlannerInput {
    PlannerInput::Segment(PathSegment {
        acceleration_cap: f64::INFINITY,
        velocity_cap: f64::INFINITY,
        speed_class: Default::default(),
        start: a,
        end: b,
        geometry: SegmentGeometry::Line,
        path_speed: feed / 60.0,
        rapid: false,
        path_mode: mode,
        profile,
        line: 1,
        command: 0,
        spindles: Default::default(),
    })
}

/// Runs the inputs from `start`; returns the trace, the monitor and the cycle time.
pub fn run(
    config: &MotionConfig,
    start: Point9,
    inputs: Vec<PlannerInput>,
) -> (Vec<Setpoint>, TraceMonitor, f64) {
    let mut stage = MotionStage::new(config);
    let mut trace = Vec::new();
    let mut monitor = TraceMonitor::new(config.axes, config.servo_period);
    let mut sink = |sp: &Setpoint| {
        monitor.observe(sp);
        trace.push(*sp);
    };
    stage.set_position(start, &mut sink);
    for i in inputs {
        stage.push_input(i, &mut sink);
    }
    let t = stage.finish(&mut sink);
    (trace, monitor, t)
}

/// As [`run`], with a feed hold at `at` s standing `standstill` s.
pub fn run_with_hold(
    config: &MotionConfig,
    start: Point9,
    inputs: Vec<PlannerInput>,
    at: f64,
    standstill: f64,
) -> (Vec<Setpoint>, TraceMonitor, f64) {
    let mut stage = MotionStage::new(config);
    let mut trace = Vec::new();
    let mut monitor = TraceMonitor::new(config.axes, config.servo_period);
    let mut sink = |sp: &Setpoint| {
        monitor.observe(sp);
        trace.push(*sp);
    };
    stage.set_position(start, &mut sink);
    stage.feed_hold(at, standstill);
    for i in inputs {
        stage.push_input(i, &mut sink);
    }
    let t = stage.finish(&mut sink);
    (trace, monitor, t)
}

pub fn dist(a: &Point9, b: &Point9) -> f64 {
    (0..9).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// Distance from `q` to the segment a–b.
pub fn dist_to_segment(q: &Point9, a: &Point9, b: &Point9) -> f64 {
    let ab: Vec<f64> = (0..9).map(|i| b[i] - a[i]).collect();
    let len2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if len2 > 0.0 {
        ((0..9).map(|i| (q[i] - a[i]) * ab[i]).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let proj: Point9 = std::array::from_fn(|i| a[i] + t * ab[i]);
    dist(q, &proj)
}

/// Distance from `q` to the polyline through `points`.
pub fn dist_to_polyline(q: &Point9, points: &[Point9]) -> f64 {
    points
        .windows(2)
        .map(|w| dist_to_segment(q, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// Distance to a polyline for a point moving forward along it: searches the chords near the
/// last closest one (the trace advances at most a few hundred fine chords per servo period).
pub struct PathCursor<'a> {
    points: &'a [Point9],
    at: usize,
}

impl<'a> PathCursor<'a> {
    pub fn new(points: &'a [Point9]) -> Self {
        PathCursor { points, at: 0 }
    }

    /// The distance from `q` to the polyline, exact when it is at most `bound`: the window search
    /// can only over-estimate (it takes a minimum over real chords, but may miss the nearest one
    /// where the path passes near an earlier part of itself), so a result above `bound` is
    /// checked against every chord.
    pub fn distance_within(&mut self, q: &Point9, bound: f64) -> f64 {
        let d = self.distance(q);
        if d <= bound {
            d
        } else {
            dist_to_polyline(q, self.points)
        }
    }

    pub fn distance(&mut self, q: &Point9) -> f64 {
        let n = self.points.len();
        if n < 2 {
            return self.points.first().map_or(f64::INFINITY, |p| dist(q, p));
        }
        // Search forward in windows of 64 chords while the best one is at the window's far end.
        let mut lo = self.at.saturating_sub(8);
        let mut best = (f64::INFINITY, self.at);
        loop {
            let hi = (lo + 64).min(n - 1);
            for k in lo..hi {
                let d = dist_to_segment(q, &self.points[k], &self.points[k + 1]);
                if d < best.0 {
                    best = (d, k);
                }
            }
            if best.1 + 1 < hi || hi == n - 1 {
                break;
            }
            lo = hi;
        }
        self.at = best.1;
        best.0
    }
}
