//! Criterion benchmarks of the motion stage:
//! * `plan/lines_100k` (BRISK, circular blends) and `plan/lines_100k_soft` (SOFT, clothoid
//!   blends): 100 000 short feed lines (a zig-zag of 0.2…1 mm chords with 5…40° corners, G64
//!   P0.01) through the path builder and the look-ahead planner, no interpolation: the planning
//!   throughput (target ≥ 1 M segments/s);
//! * `interpolate/sample_*`: one servo cycle's work — profile evaluation plus geometry for a line
//!   (BRISK) and for a clothoid blend (SOFT, the costliest case: two 14-term series and a
//!   sin_cos) — (target < 20 µs worst case).

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use stanok_canon::{AccelerationProfile, PathMode};
use stanok_motion::interpolator::{sample, Profile};
use stanok_motion::path::PathBuilder;
use stanok_motion::piece::Shape;
use stanok_motion::planner::{PlannedPiece, Planner};
use stanok_motion::segment::{PathSegment, PlannerInput, Point9, SegmentGeometry};
use stanok_motion::{AxisLimit, MotionConfig};

fn config() -> MotionConfig {
    let mut axes = [AxisLimit::UNLIMITED; 9];
    for a in axes.iter_mut().take(3) {
        *a = AxisLimit::from_machine(10_000.0, 1000.0, 20_000.0);
    }
    MotionConfig::new(axes, 10_000.0, 5_000.0)
}

fn zigzag(n: usize, profile: AccelerationProfile) -> Vec<PlannerInput> {
    let mut p: Point9 = [0.0; 9];
    let mut heading: f64 = 0.0;
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let turn = (5.0 + 35.0 * ((k * 7919) % 100) as f64 / 100.0).to_radians();
        heading += if k % 2 == 0 { turn } else { -turn };
        let len = 0.2 + 0.8 * ((k * 104_729) % 100) as f64 / 100.0;
        let mut q = p;
        q[0] += len * heading.cos();
        q[1] += len * heading.sin();
        out.push(PlannerInput::Segment(PathSegment {
            acceleration_cap: f64::INFINITY,
            velocity_cap: f64::INFINITY,
            speed_class: Default::default(),
            start: p,
            end: q,
            geometry: SegmentGeometry::Line,
            path_speed: 5000.0 / 60.0,
            rapid: false,
            path_mode: PathMode::Continuous { tolerance: 0.01 },
            profile,
            line: k as u32,
            spindles: Default::default(),
        }));
        p = q;
    }
    out
}

fn plan(c: &mut Criterion) {
    let cfg = config();
    let mut g = c.benchmark_group("plan");
    g.throughput(Throughput::Elements(100_000));
    g.sample_size(10);
    for (name, profile) in [
        ("lines_100k", AccelerationProfile::Brisk),
        ("lines_100k_soft", AccelerationProfile::Soft),
    ] {
        let inputs = zigzag(100_000, profile);
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut builder = PathBuilder::new(&cfg);
                let mut planner = Planner::new(cfg.lookahead);
                let mut time = 0.0;
                let mut sink = |pp: PlannedPiece| time += pp.v_exit;
                for i in &inputs {
                    builder.push(i.clone(), &mut |piece| planner.push(piece, &mut sink));
                }
                builder.flush(&mut |piece| planner.push(piece, &mut sink));
                planner.flush(&mut sink);
                black_box(time)
            })
        });
    }
    g.finish();
}

fn pieces(profile: AccelerationProfile) -> Vec<PlannedPiece> {
    let cfg = config();
    let mut builder = PathBuilder::new(&cfg);
    let mut planner = Planner::new(cfg.lookahead);
    let mut out = Vec::new();
    for i in zigzag(50, profile) {
        builder.push(i, &mut |piece| planner.push(piece, &mut |pp| out.push(pp)));
    }
    builder.flush(&mut |piece| planner.push(piece, &mut |pp| out.push(pp)));
    planner.flush(&mut |pp| out.push(pp));
    out
}

fn interpolate(c: &mut Criterion) {
    let mut g = c.benchmark_group("interpolate");
    for (name, profile, want_blend) in [
        ("sample_line_brisk", AccelerationProfile::Brisk, false),
        ("sample_clothoid_soft", AccelerationProfile::Soft, true),
    ] {
        let all = pieces(profile);
        let piece = all
            .iter()
            .find(|p| {
                matches!(p.piece.shape, Shape::Clothoid(_)) == want_blend && p.piece.length > 0.0
            })
            .cloned()
            .expect("piece");
        let prof = Profile::of(&piece);
        let d = prof.duration();
        g.bench_function(name, |b| {
            let mut t = 0.0;
            b.iter(|| {
                t += 0.37 * d;
                if t > d {
                    t -= d;
                }
                black_box(sample(&piece, prof.at(black_box(t)), t))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, plan, interpolate);
criterion_main!(benches);
