//! Known numbers: single moves, corners, stops, the report/trace relations.

mod common;
use common::*;
use stanok_canon::{AccelerationProfile::*, PathMode};

const G64: PathMode = PathMode::Continuous { tolerance: 0.05 };

#[test]
fn hundred_mm_line_at_f6000_takes_1_1_s() {
    let cfg = mill();
    let (trace, mon, t) = run(
        &cfg,
        p3(0.0, 0.0, 0.0),
        vec![line(
            p3(0.0, 0.0, 0.0),
            p3(100.0, 0.0, 0.0),
            6000.0,
            G64,
            Brisk,
        )],
    );
    // Trapezoid: 100/100 + 100/1000 = 1.1 s; the trace lasts exactly that (a whole number of ms).
    assert!((t - 1.1).abs() < 1e-9, "{t}");
    assert_eq!(trace.len(), 1101);
    assert_eq!(trace.last().unwrap().position, p3(100.0, 0.0, 0.0));
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
    assert!((mon.peaks[0].velocity - 100.0).abs() < 1e-9);
    assert!((mon.peaks[0].acceleration - 1000.0).abs() < 1e-9);
}

#[test]
fn exact_stop_corner_stops_at_the_corner() {
    let cfg = mill();
    let a = p3(0.0, 0.0, 0.0);
    let b = p3(10.0, 0.0, 0.0);
    let c = p3(10.0, 10.0, 0.0);
    let (trace, mon, t) = run(
        &cfg,
        a,
        vec![
            line(a, b, 6000.0, PathMode::ExactStop, Brisk),
            line(b, c, 6000.0, PathMode::ExactStop, Brisk),
        ],
    );
    // Each 10 mm leg rest to rest: triangle, peak 100 mm/s: 0.2 s each.
    assert!((t - 0.4).abs() < 1e-9, "{t}");
    let at_corner = trace.iter().find(|s| (s.t - 0.2).abs() < 1e-9).unwrap();
    assert!(
        dist(&at_corner.position, &b) < 1e-12,
        "{:?}",
        at_corner.position
    );
    assert!(at_corner.velocity.iter().all(|v| v.abs() < 1e-9));
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
}

#[test]
fn g64_corner_is_blended_within_tolerance_and_faster() {
    let cfg = mill();
    let a = p3(0.0, 0.0, 0.0);
    let b = p3(50.0, 0.0, 0.0);
    let c = p3(50.0, 50.0, 0.0);
    let (trace, mon, t) = run(
        &cfg,
        a,
        vec![
            line(a, b, 3000.0, G64, Brisk),
            line(b, c, 3000.0, G64, Brisk),
        ],
    );
    let (_, _, t_stop) = run(
        &cfg,
        a,
        vec![
            line(a, b, 3000.0, PathMode::ExactStop, Brisk),
            line(b, c, 3000.0, PathMode::ExactStop, Brisk),
        ],
    );
    // 90° corner, P = 0.05: d = P/tan(22.5°) = 0.1207 mm cut from each leg, blend radius
    // r = d/tan(45°) = 0.1207 mm, corner speed √(0.95·1000·r) = 10.71 mm/s instead of 0: the
    // saving is the braking from 50 to 10.7 mm/s and back, ≈ 2·(v²/2a)/v … a few ms.
    assert!(t < t_stop - 0.004, "blended {t} vs stopped {t_stop}");
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
    let worst = trace
        .iter()
        .map(|s| dist_to_polyline(&s.position, &[a, b, c]))
        .fold(0.0, f64::max);
    assert!(worst <= 0.05 + 1e-9, "{worst}");
    // Speed never reaches zero at the corner.
    let min_speed_mid = trace
        .iter()
        .filter(|s| s.t > 0.2 && s.t < t - 0.2)
        .map(|s| s.velocity[0].hypot(s.velocity[1]))
        .fold(f64::INFINITY, f64::min);
    let r = 0.05 / (std::f64::consts::PI / 8.0).tan();
    let v_corner = (0.95 * 1000.0 * r).sqrt();
    assert!(
        (min_speed_mid - v_corner).abs() < 0.05,
        "{min_speed_mid} vs {v_corner}"
    );
    assert_eq!(trace.last().unwrap().position, c);
}

#[test]
fn feed_hold_brakes_on_the_path_stands_and_resumes() {
    let cfg = mill();
    let (a, b) = (p3(0.0, 0.0, 0.0), p3(100.0, 0.0, 0.0));
    // Hold at 0.5 s (cruising at 100 mm/s, s = 45 mm): 0.1 s of braking to s = 50 mm at 0.6 s,
    // 1 s standing, then 50 mm from rest to rest: 0.5 + 0.1 s. Total 2.2 s.
    let (trace, mon, t) = run_with_hold(&cfg, a, vec![line(a, b, 6000.0, G64, Brisk)], 0.5, 1.0);
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
    assert!((t - 2.2).abs() < 2e-3, "{t}");
    for sp in trace.iter().filter(|s| s.t > 0.601 && s.t < 1.599) {
        assert!(
            (sp.position[0] - 50.0).abs() < 1e-9 && sp.velocity[0] == 0.0,
            "{sp:?}"
        );
    }
    assert_eq!(trace.last().unwrap().position, b);
}

#[test]
fn feed_hold_across_blended_corners_keeps_limits_and_tolerance() {
    let cfg = mill();
    let pts: Vec<_> = (0..40)
        .map(|k| p3(2.0 * k as f64, if k % 2 == 0 { 0.0 } else { 1.5 }, 0.0))
        .collect();
    let inputs = pts
        .windows(2)
        .map(|w| line(w[0], w[1], 5000.0, G64, Brisk))
        .collect();
    let (_, _, t_free) = run(
        &cfg,
        pts[0],
        pts.windows(2)
            .map(|w| line(w[0], w[1], 5000.0, G64, Brisk))
            .collect(),
    );
    let (trace, mon, t) = run_with_hold(&cfg, pts[0], inputs, 0.3, 0.5);
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
    assert!(t > t_free + 0.5, "{t} vs {t_free}");
    for sp in &trace {
        assert!(dist_to_polyline(&sp.position, &pts) <= 0.05 + 1e-9);
    }
    // It did stop somewhere after 0.3 s, away from any vertex.
    assert!(trace
        .iter()
        .any(|s| s.t > 0.3 && s.t < t - 0.5 && s.velocity.iter().all(|v| *v == 0.0)));
    assert_eq!(trace.last().unwrap().position, *pts.last().unwrap());
}

#[test]
fn soft_line_is_an_s_curve_with_bounded_jerk() {
    let cfg = mill();
    let (a, b) = (p3(0.0, 0.0, 0.0), p3(100.0, 0.0, 0.0));
    let (trace, mon, t) = run(&cfg, a, vec![line(a, b, 6000.0, PathMode::ExactStop, Soft)]);
    // Ramp 0 → 100 mm/s with a = 1000, j = 20 000: 0.1 + 0.05 = 0.15 s over 7.5 mm, twice;
    // cruise 85 mm at 100 mm/s: 0.85 s. Total 1.15 s.
    assert!((t - 1.15).abs() < 1e-9, "{t}");
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
    assert!(
        (mon.peaks[0].jerk - 20_000.0).abs() < 1e-6,
        "{}",
        mon.peaks[0].jerk
    );
    // Finite differences at 1 ms see the same jerk (the path is C² here), within 1e-6.
    assert!(
        mon.peaks[0].fd_jerk <= 20_000.0 * (1.0 + 1e-6),
        "{}",
        mon.peaks[0].fd_jerk
    );
    assert_eq!(trace.last().unwrap().position, b);
}

#[test]
fn the_window_bounds_memory_and_a_tiny_window_stays_safe() {
    use stanok_motion::path::PathBuilder;
    use stanok_motion::planner::Planner;
    let mut cfg = mill();
    cfg.lookahead = 64;
    let mut builder = PathBuilder::new(&cfg);
    let mut planner = Planner::new(cfg.lookahead);
    let mut released = 0u64;
    let mut most = 0;
    let pts: Vec<_> = (0..20_000)
        .map(|k| {
            p3(
                0.5 * k as f64 % 200.0,
                if k % 2 == 0 { 0.0 } else { 0.4 },
                0.0,
            )
        })
        .collect();
    for w in pts.windows(2) {
        builder.push(line(w[0], w[1], 5000.0, G64, Brisk), &mut |piece| {
            planner.push(piece, &mut |_| released += 1);
            most = most.max(planner.len());
        });
    }
    assert!(most <= 64, "{most}");
    assert!(released > 30_000, "{released}");
    // A window of 2 pieces: slow (it must be able to stop at the window's end) but within limits.
    cfg.lookahead = 2;
    let short: Vec<_> = pts[..200]
        .windows(2)
        .map(|w| line(w[0], w[1], 5000.0, G64, Brisk))
        .collect();
    let long: Vec<_> = pts[..200]
        .windows(2)
        .map(|w| line(w[0], w[1], 5000.0, G64, Brisk))
        .collect();
    let (trace, mon, t_short) = run(&cfg, pts[0], short);
    assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
    assert_eq!(trace.last().unwrap().position, pts[199]);
    let (_, _, t_long) = run(&mill(), pts[0], long);
    assert!(t_short >= t_long, "{t_short} < {t_long}");
}

/// Every setpoint names the Canon command its piece comes from, so that state changes between
/// commands (a spindle stop after a cut still in the look-ahead window) can be applied to exactly
/// the setpoints after them.
#[test]
fn setpoints_carry_the_serial_of_their_command() {
    use stanok_canon::{Canon, LineMove, Pose};
    let cfg = mill();
    let mut stage = stanok_motion::MotionStage::new(&cfg);
    let at = |x: f64| Pose {
        x,
        ..Pose::default()
    };
    let mut seen: Vec<(u64, f64)> = Vec::new();
    let mut out = |sp: &stanok_motion::Setpoint| seen.push((sp.command, sp.position[0]));
    let cmds = [
        Canon::StraightFeed(LineMove {
            start: at(0.0),
            end: at(10.0),
            feed: 3000.0,
            law: Default::default(),
        }),
        Canon::StopSpindle { spindle: 0 },
        Canon::StraightTraverse(LineMove {
            start: at(10.0),
            end: at(20.0),
            feed: 0.0,
            law: Default::default(),
        }),
    ];
    for (i, c) in cmds.iter().enumerate() {
        stage.apply(c, i as u32 + 1, &mut out);
        assert_eq!(stage.commands(), i as u64 + 1);
    }
    stage.finish(&mut out);
    // Nothing is released before the end here (one continuous path within the window).
    assert!(seen.iter().all(|&(c, _)| c == 1 || c == 3), "{seen:?}");
    // Serials never decrease along the trace; the first command's setpoints stay at x ≤ 10 except
    // inside the blend, which belongs to the next command.
    assert!(seen.windows(2).all(|w| w[0].0 <= w[1].0));
    assert!(seen.iter().filter(|s| s.0 == 1).all(|s| s.1 <= 10.0 + 1e-9));
    assert!(seen.iter().filter(|s| s.0 == 3).all(|s| s.1 >= 9.0));
}
