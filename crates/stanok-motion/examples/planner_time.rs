//! Plans a polyline and prints its BRISK time: the Stanok side of `scripts/planner-vs-toppra.py`.
//!
//! ```text
//! cargo run --release -p stanok-motion --example planner_time -- POINTS.csv FEED_MM_MIN MODE [P]
//! ```
//! POINTS.csv: one `x,y,z` per line (mm). MODE: `exact` (G61/G60: stop at every point) or `g64`
//! (blend within P mm). Machine: the built-in mill (X Y Z 10 000 mm/min, 1000 mm/s²), 1 ms servo
//! period. Prints one JSON object: planned time (trace duration), analytic sum, setpoints,
//! violations.

use stanok_canon::{AccelerationProfile, PathMode};
use stanok_motion::monitor::TraceMonitor;
use stanok_motion::segment::{PathSegment, PlannerInput, Point9, SegmentGeometry};
use stanok_motion::{AxisLimit, MotionConfig, MotionStage, Setpoint};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!("usage: planner_time POINTS.csv FEED_MM_MIN exact|g64 [P]");
        std::process::exit(2);
    }
    let text = std::fs::read_to_string(&args[1]).unwrap_or_default();
    let feed: f64 = args[2].parse().unwrap_or(5000.0);
    let mode = match args[3].as_str() {
        "exact" => PathMode::ExactStop,
        _ => PathMode::Continuous {
            tolerance: args.get(4).and_then(|p| p.parse().ok()).unwrap_or(0.0),
        },
    };
    let points: Vec<Point9> = text
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').filter_map(|c| c.trim().parse().ok()).collect();
            (v.len() >= 3).then(|| {
                let mut p = [0.0; 9];
                p[..3].copy_from_slice(&v[..3]);
                p
            })
        })
        .collect();
    let mut axes = [AxisLimit::UNLIMITED; 9];
    for a in axes.iter_mut().take(3) {
        *a = AxisLimit::from_machine(10_000.0, 1000.0, 20_000.0);
    }
    let config = MotionConfig::new(axes, 10_000.0, 5_000.0);
    let mut stage = MotionStage::new(&config);
    let mut monitor = TraceMonitor::new(config.axes, config.servo_period);
    let mut sink = |sp: &Setpoint| monitor.observe(sp);
    let started = std::time::Instant::now();
    if let Some(first) = points.first() {
        stage.set_position(*first, &mut sink);
    }
    for (k, w) in points.windows(2).enumerate() {
        let seg = PathSegment {
            acceleration_cap: f64::INFINITY,
            velocity_cap: f64::INFINITY,
            speed_class: Default::default(),
            start: w[0],
            end: w[1],
            geometry: SegmentGeometry::Line,
            path_speed: feed / 60.0,
            rapid: false,
            path_mode: mode,
            profile: AccelerationProfile::Brisk,
            line: k as u32 + 1,
            command: 0,
            spindles: Default::default(),
        };
        stage.push_input(PlannerInput::Segment(seg), &mut sink);
    }
    let analytic = {
        stage.drain(&mut sink);
        stage.planned_time()
    };
    let time = stage.finish(&mut sink);
    println!(
        "{{\"time_s\": {time}, \"analytic_time_s\": {analytic}, \"segments\": {}, \"setpoints\": {}, \"violations\": {}, \"wall_s\": {}}}",
        points.len().saturating_sub(1),
        monitor.count(),
        monitor.violation_count,
        started.elapsed().as_secs_f64()
    );
}
