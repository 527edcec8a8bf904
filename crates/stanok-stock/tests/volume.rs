//! The volume model against formulas: one straight move (flat and ball end mills) and one arc,
//! fed as servo setpoints through [`StockSim`] (so the chains and sweeps are the ones a run makes),
//! and the sequencing of state changes by command serial.

use proptest::prelude::*;
use stanok_canon::setup::{CutterShape, Tool, ToolBody, ToolEdge, ToolTable};
use stanok_canon::{Canon, LengthUnits, LineMove, Pose};
use stanok_motion::Setpoint;
use stanok_stock::report::CollisionKind;
use stanok_stock::sim::{StockConfig, StockSim};
use stanok_stock::spec::{StockFrame, StockShape};
use std::f64::consts::PI;

fn tools(shape: CutterShape, radius: f64) -> ToolTable {
    let mut t = ToolTable::default();
    t.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius,
                ..Default::default()
            }],
            body: ToolBody {
                cutter: Some(shape),
                flute_length: Some(40.0),
                reach: Some(60.0),
                ..Default::default()
            },
            ..Default::default()
        },
    );
    t
}

/// A simulation of the box `[lo, hi]` × z −40…0 with tool 1 in the spindle, spindle on, feed
/// mode; the next command serial to use is 5.
fn sim_in(
    shape: CutterShape,
    radius: f64,
    resolution: f64,
    lo: [f64; 2],
    hi: [f64; 2],
) -> StockSim {
    let mut s = StockSim::new(StockConfig {
        shape: StockShape::Box {
            min: [lo[0], lo[1], -40.0],
            max: [hi[0], hi[1], 0.0],
        },
        frame: StockFrame::Machine,
        resolution: Some(resolution),
        tools: tools(shape, radius),
        kinematics: None,
        lathe: false,
        fixture_z: None,
    })
    .unwrap();
    s.command(
        1,
        &Canon::Init {
            position: Pose::ZERO,
            units: LengthUnits::Millimetres,
            g5x_index: 1,
            g5x_offset: Pose::ZERO,
            g92_offset: Pose::ZERO,
            xy_rotation: 0.0,
        },
    );
    s.command(2, &Canon::ChangeTool { tool: 1, slot: 1 });
    s.command(
        3,
        &Canon::StartSpindle {
            spindle: 0,
            direction: stanok_canon::SpindleDirection::Clockwise,
        },
    );
    let line = LineMove {
        start: Pose::ZERO,
        end: Pose::ZERO,
        feed: 1000.0,
        law: Default::default(),
    };
    s.command(4, &Canon::StraightFeed(line));
    s
}

/// [`sim_in`] on a box that holds every point of `path` with the tool around it.
fn sim(shape: CutterShape, radius: f64, resolution: f64, path: &[[f64; 3]]) -> StockSim {
    let m = radius + 1.0;
    let lo = [
        path.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min) - m,
        path.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min) - m,
    ];
    let hi = [
        path.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max) + m,
        path.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max) + m,
    ];
    sim_in(shape, radius, resolution, lo, hi)
}

fn sp(t: f64, p: [f64; 3], line: u32, command: u64) -> Setpoint {
    Setpoint {
        t,
        position: [p[0], p[1], p[2], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        velocity: [0.0; 9],
        acceleration: [0.0; 9],
        jerk: [0.0; 9],
        soft: false,
        line,
        command,
        seq: 0,
        junction: false,
        spindle_rpm: [0.0; 4],
        spindle_dir: [0; 4],
    }
}

/// Feeds the points as setpoints of command 4 (one servo period apart).
fn feed(s: &mut StockSim, points: impl IntoIterator<Item = [f64; 3]>) {
    for (k, p) in points.into_iter().enumerate() {
        s.setpoint(&sp(k as f64 * 1e-3, p, 7, 4));
    }
}

/// Area of the circular segment of a circle of radius r below a chord at distance d from the
/// centre (d > 0: the centre above the chord).
fn segment(r: f64, d: f64) -> f64 {
    r * r * (d / r).clamp(-1.0, 1.0).acos() - d * (r * r - d * d).max(0.0).sqrt()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// A straight move at depth h: flat end mill h·(2R·L + πR²); ball end mill the circular
    /// segment times L plus one spherical cap of height h (deeper than R: a half disk and a
    /// rectangle, a hemisphere and a cylinder). Within 0.5 %.
    #[test]
    fn one_straight_move(
        angle in 0.0..std::f64::consts::TAU, len in 5.0..30.0f64, r in 2.0..5.0f64,
        depth in 0.5..4.0f64, ball in any::<bool>(), x0 in -20.0..20.0f64, y0 in -20.0..20.0f64,
    ) {
        let shape = if ball { CutterShape::Ball } else { CutterShape::Flat };
        let dir = [angle.cos(), angle.sin()];
        let n = (len / 0.05).ceil() as usize;
        let path: Vec<[f64; 3]> = (0..=n).map(|k| {
            let f = len * k as f64 / n as f64;
            [x0 + f * dir[0], y0 + f * dir[1], -depth]
        }).collect();
        let mut s = sim(shape, r, 0.05, &path);
        feed(&mut s, path);
        let rep = s.finish();
        let want = if ball && depth <= r {
            // The ball alone: a segment along the move, a cap at the two ends together.
            segment(r, r - depth) * len + PI * depth * depth * (3.0 * r - depth) / 3.0
        } else if ball {
            // Deeper than the radius: the cylinder above the ball cuts too.
            (PI * r * r / 2.0 + 2.0 * r * (depth - r)) * len
                + 2.0 / 3.0 * PI * r.powi(3)
                + PI * r * r * (depth - r)
        } else {
            depth * (2.0 * r * len + PI * r * r)
        };
        let got = rep.removed_volume_mm3.total;
        prop_assert!((got - want).abs() / want < 0.005, "{got} vs {want}");
        prop_assert!((rep.initial_volume_mm3 - rep.final_volume_mm3 - got).abs() < 1e-6 * rep.initial_volume_mm3);
        prop_assert!(rep.collisions.is_empty(), "{:?}", rep.collisions);
    }

    /// A flat end mill along an arc of radius Ra through angle θ at depth h:
    /// h·(2·θ·Ra·R + πR²) (the annular sector and the two outer half disks). Within 0.5 %.
    #[test]
    fn one_arc_move(
        ra in 6.0..25.0f64, theta in 0.3..4.5f64, r in 2.0..5.0f64, depth in 0.5..4.0f64,
        start in 0.0..std::f64::consts::TAU, ccw in any::<bool>(),
    ) {
        prop_assume!((std::f64::consts::TAU - theta) * ra > 2.0 * r + 0.5);
        let n = (theta * ra / 0.05).ceil() as usize;
        let sign = if ccw { 1.0 } else { -1.0 };
        let path: Vec<[f64; 3]> = (0..=n).map(|k| {
            let a = start + sign * theta * k as f64 / n as f64;
            [ra * a.cos(), ra * a.sin(), -depth]
        }).collect();
        let mut s = sim(CutterShape::Flat, r, 0.05, &path);
        feed(&mut s, path);
        let rep = s.finish();
        let want = depth * (2.0 * theta * ra * r + PI * r * r);
        let got = rep.removed_volume_mm3.total;
        prop_assert!((got - want).abs() / want < 0.005, "{got} vs {want}");
        // Chords merged: far fewer sweeps than setpoints.
        prop_assert!(rep.sweeps * 3 < n as u64, "{} sweeps for {n} setpoints", rep.sweeps);
    }
}

/// A spindle stop queued while the cut's setpoints are still to come applies only to the
/// setpoints of the commands after it.
#[test]
fn a_state_change_applies_to_the_setpoints_after_its_command() {
    let mut s = sim_in(CutterShape::Flat, 3.0, 0.1, [-40.0, -10.0], [40.0, 10.0]);
    // Command 4 cuts from x −30 to 0; command 5 stops the spindle; command 6 cuts on to x 30.
    s.command(5, &Canon::StopSpindle { spindle: 0 });
    let mut t = 0.0;
    for k in 0..=300 {
        t += 1e-3;
        s.setpoint(&sp(t, [-30.0 + 0.1 * k as f64, 0.0, -2.0], 7, 4));
    }
    for k in 1..=300 {
        t += 1e-3;
        s.setpoint(&sp(t, [0.1 * k as f64, 0.0, -2.0], 9, 6));
    }
    let rep = s.finish();
    let stopped: Vec<_> = rep
        .collisions
        .iter()
        .filter(|c| c.kind == CollisionKind::SpindleStopped)
        .collect();
    assert_eq!(stopped.len(), 1, "{:?}", rep.collisions);
    assert_eq!(stopped[0].line, 9);
    assert!((stopped[0].depth_mm - 2.0).abs() < 1e-4);
    assert!(stopped[0].position[0] >= -1e-9, "{:?}", stopped[0].position);
    // Both blocks removed their share: 30 × 6 × 2 each, the plunge disk once.
    let per_line: Vec<(u32, f64)> = rep.blocks.iter().map(|b| (b.line, b.removed_mm3)).collect();
    assert_eq!(per_line.len(), 2);
    assert!(
        (per_line[0].1 - 2.0 * (180.0 + PI * 9.0)).abs() < 2.0,
        "{per_line:?}"
    );
    assert!((per_line[1].1 - 2.0 * 180.0).abs() < 2.0, "{per_line:?}");
}
