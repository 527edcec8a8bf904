//! Sweeps per second of the milling model: a Ø6 ball finishing in 0.1 mm steps across a 100 × 100
//! mm stock at 0.1 mm (the shape of the 1 M-block finishing program of docs/performance.md), a
//! flat Ø10 roughing slot 5 deep, and a Ø6 ball tilted 15° (the generic 5-axis path).

use criterion::{criterion_group, criterion_main, Criterion};
use stanok_canon::setup::{CutterShape, Tool, ToolBody, ToolEdge, ToolTable};
use stanok_stock::mill::{MillModel, SweepHits};
use stanok_stock::sweep::Sweep;
use stanok_stock::tool::{resolve, MillTool, ToolShape};

fn tool(shape: CutterShape, r: f64) -> MillTool {
    let mut t = ToolTable::default();
    t.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: r,
                ..Default::default()
            }],
            body: ToolBody {
                cutter: Some(shape),
                flute_length: Some(25.0),
                reach: Some(40.0),
                ..Default::default()
            },
            ..Default::default()
        },
    );
    match resolve(1, &t, false, 0.01).0 {
        ToolShape::Mill(m) => m,
        ToolShape::Insert(_) => unreachable!(),
    }
}

/// A closure that applies the next sweep of a raster across the stock on each call.
fn raster(
    tool: &MillTool,
    axis: [f64; 3],
    step: f64,
    depth: f64,
) -> impl FnMut() -> SweepHits + '_ {
    let mut m = MillModel::new_box([0.0, 0.0, -50.0], [100.0, 100.0, 0.0], 0.1);
    let mut x = 10.0;
    let mut y = 10.0;
    move || {
        let sw = Sweep {
            p0: [x, y, -depth],
            d: [step, 0.0, 0.0],
            axis,
        };
        x += step;
        if x > 90.0 {
            x = 10.0;
            y = if y > 90.0 { 10.0 } else { y + 0.1 };
        }
        m.apply(tool, &sw)
    }
}

fn bench(c: &mut Criterion) {
    let ball = tool(CutterShape::Ball, 3.0);
    let flat = tool(CutterShape::Flat, 5.0);
    let mut g = c.benchmark_group("sweep");
    let mut f = raster(&ball, [0.0, 0.0, 1.0], 0.1, 2.0);
    g.bench_function("ball Ø6 0.1 mm step, 2 deep", |b| b.iter(&mut f));
    let mut f = raster(&flat, [0.0, 0.0, 1.0], 1.0, 5.0);
    g.bench_function("flat Ø10 1 mm step, 5 deep", |b| b.iter(&mut f));
    let (s, co) = 15f64.to_radians().sin_cos();
    let mut f = raster(&ball, [s, 0.0, co], 0.1, 2.0);
    g.bench_function("ball Ø6 tilted 15°, 0.1 mm step", |b| b.iter(&mut f));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
