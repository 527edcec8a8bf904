//! Unit tests of the simulated machine (`sim.rs`).

use super::*;
use stanok_canon::{LengthUnits, Plane};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};

fn at(line: u32, value: Canon) -> Spanned<Canon> {
    Spanned::new(Span::new(0, 0, line, 1), value)
}

fn p(x: f64, y: f64, z: f64) -> Pose {
    Pose::ZERO.with_xyz([x, y, z])
}

fn init(position: Pose) -> Canon {
    Canon::Init {
        position,
        units: LengthUnits::Millimetres,
        g5x_index: 1,
        g5x_offset: Pose::ZERO,
        g92_offset: Pose::ZERO,
        xy_rotation: 0.0,
    }
}

fn line(start: Pose, end: Pose, feed: f64) -> LineMove {
    LineMove { start, end, feed }
}

/// A 90° counter-clockwise XY arc from (100, 50) centred so that it bulges to x = c + 10.
fn bulging_arc(feed: f64) -> ArcMove {
    let c = [
        100.0 - 10.0 * FRAC_1_SQRT_2,
        50.0 + 10.0 * FRAC_1_SQRT_2,
        0.0,
    ];
    ArcMove {
        start: p(100.0, 50.0, 0.0),
        end: p(100.0, c[1] + 10.0 * FRAC_1_SQRT_2, 0.0),
        centre: c,
        axis: [0.0, 0.0, 1.0],
        turns: 1,
        plane: Plane::XY,
        feed,
    }
}

fn run(machine: MachineData, cmds: &[Spanned<Canon>]) -> (SimMachine, Option<Diagnostic>) {
    let mut sim = SimMachine::new(machine);
    for c in cmds {
        if let Err(d) = sim.apply(c) {
            return (sim, Some(d));
        }
    }
    (sim, None)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

#[test]
fn rapid_feed_arc_dwell_report() {
    let o = p(0.0, 0.0, 0.0);
    let cmds = [
        at(1, init(o)),
        at(2, Canon::StraightTraverse(line(o, p(100.0, 0.0, 0.0), 0.0))),
        at(
            3,
            Canon::StraightFeed(line(p(100.0, 0.0, 0.0), p(100.0, 50.0, 0.0), 1000.0)),
        ),
        at(4, Canon::ArcFeed(bulging_arc(600.0))),
        at(5, Canon::Dwell { seconds: 2.0 }),
    ];
    let (sim, err) = run(MachineData::default_mill(), &cmds);
    assert_eq!(err, None);
    let r = sim.report();
    assert_eq!(r.machine, "mill");
    assert_eq!(
        (
            r.motion_segments,
            r.rapid_segments,
            r.feed_segments,
            r.arc_segments
        ),
        (3, 1, 1, 1)
    );
    assert!(close(r.rapid_distance_mm, 100.0));
    // 50 mm line + quarter circle of r = 10 (5π mm).
    assert!(
        close(r.feed_distance_mm, 50.0 + 5.0 * PI),
        "{}",
        r.feed_distance_mm
    );
    assert!(close(r.dwell_time_s, 2.0));
    // 100 mm at 10 000 mm/min = 0.6 s; 50 mm at 1000 mm/min = 3 s; 5π mm at 600 mm/min = π/2 s.
    assert!(
        close(r.nominal_time_s, 0.6 + 3.0 + FRAC_PI_2 + 2.0),
        "{}",
        r.nominal_time_s
    );
    let b = r.bounding_box.unwrap();
    assert_eq!(b.min, [0.0, 0.0, 0.0]);
    // The arc's extreme point x = c + r lies beyond both of its end points (x = 100).
    assert!(close(b.max[0], 110.0 - 10.0 * FRAC_1_SQRT_2), "{:?}", b);
    assert!(close(b.max[1], 50.0 + 20.0 * FRAC_1_SQRT_2), "{:?}", b);
    assert_eq!(r.final_position, bulging_arc(0.0).end);
    assert!(!r.program_ended);
}

#[test]
fn arc_bulging_out_of_limits_is_refused() {
    let mut m = MachineData::default_mill();
    m.axes[0].max = 102.0; // end points (x = 100) inside, bulge (x ≈ 102.93) outside
    let start = p(100.0, 50.0, 0.0);
    let cmds = [
        at(1, init(start)),
        at(7, Canon::ArcFeed(bulging_arc(600.0))),
    ];
    let (sim, err) = run(m, &cmds);
    let d = err.expect("travel limit");
    assert_eq!(d.code.to_string(), "machine::travel-limit");
    assert_eq!(d.span.line, 7);
    assert!(
        d.message
            .contains("X would reach 102.9289 mm, beyond its maximum 102.0000 mm"),
        "{d}"
    );
    let r = sim.report();
    assert_eq!((r.arc_segments, r.motion_segments), (0, 0));
    assert_eq!(r.bounding_box, None);
    assert_eq!(r.final_position, start);
}

#[test]
fn straight_moves_and_init_are_checked_too() {
    let o = p(0.0, 0.0, 0.0);
    let cmds = [
        at(1, init(o)),
        at(
            2,
            Canon::StraightTraverse(line(o, p(0.0, 0.0, -300.5), 0.0)),
        ),
    ];
    let d = run(MachineData::default_mill(), &cmds).1.unwrap();
    assert!(
        d.message
            .contains("Z would reach -300.5000 mm, beyond its minimum -300.0000 mm"),
        "{d}"
    );
    let d = run(
        MachineData::default_mill(),
        &[at(1, init(p(501.0, 0.0, 0.0)))],
    )
    .1
    .unwrap();
    assert_eq!(d.code.to_string(), "machine::travel-limit");
    // Exactly at the limit (with interpreter rounding) passes.
    let edge = p(500.0 + 1e-12, -500.0, 300.0);
    assert_eq!(
        run(
            MachineData::default_mill(),
            &[
                at(1, init(o)),
                at(2, Canon::StraightFeed(line(o, edge, 100.0)))
            ]
        )
        .1,
        None
    );
}

#[test]
fn an_axis_the_machine_lacks_must_not_move() {
    let o = p(0.0, 0.0, 0.0);
    let mut turned = o;
    turned.a = 90.0;
    let cmds = [
        at(1, init(o)),
        at(3, Canon::StraightFeed(line(o, turned, 100.0))),
    ];
    let d = run(MachineData::default_mill(), &cmds).1.unwrap();
    assert_eq!(d.code.to_string(), "machine::missing-axis");
    assert!(d.message.contains("no A axis"), "{d}");
}

#[test]
fn feeds_are_clamped_and_zero_feed_takes_no_time() {
    let o = p(0.0, 0.0, 0.0);
    let cmds = [
        at(
            1,
            Canon::StraightFeed(line(o, p(100.0, 0.0, 0.0), 20_000.0)),
        ), // clamped to 5000
        at(2, Canon::StraightFeed(line(p(100.0, 0.0, 0.0), o, 0.0))),
        at(3, Canon::StraightFeed(line(o, o, f64::NAN))),
    ];
    let r = run(MachineData::default_mill(), &cmds).0.report();
    assert!(close(r.nominal_time_s, 1.2), "{}", r.nominal_time_s);
    assert!(close(r.feed_distance_mm, 200.0));
    assert_eq!(r.feed_segments, 3);
}

#[test]
fn rapids_are_slowed_by_axis_velocity() {
    let mut m = MachineData::default_mill();
    m.axes[2].max_velocity = 2_000.0;
    let o = p(0.0, 0.0, 0.0);
    // 100 mm in Z at 2000 mm/min: 3 s instead of 0.6 s.
    let cmds = [at(
        1,
        Canon::StraightTraverse(line(o, p(0.0, 0.0, -100.0), 0.0)),
    )];
    let r = run(m, &cmds).0.report();
    assert!(close(r.nominal_time_s, 3.0), "{}", r.nominal_time_s);
}

#[test]
fn logs_m_functions_tools_and_messages_with_lines() {
    let cmds = [
        at(
            1,
            Canon::Message {
                text: "load part".into(),
            },
        ),
        at(2, Canon::SelectTool { tool: 3 }),
        at(2, Canon::ChangeTool { tool: 3, slot: 3 }),
        at(
            3,
            Canon::SetSpindleSpeed {
                spindle: 0,
                rpm: 1200.0,
            },
        ),
        at(
            3,
            Canon::StartSpindle {
                spindle: 0,
                direction: SpindleDirection::Clockwise,
            },
        ),
        at(4, Canon::Flood { on: true }),
        at(5, Canon::ChangeTool { tool: 7, slot: 7 }),
        at(6, Canon::ChangeTool { tool: 3, slot: 3 }),
        at(
            7,
            Canon::AuxiliaryFunction {
                number: 73,
                timing: AuxTiming::Postfix,
            },
        ),
        at(8, Canon::ProgramStop { optional: true }),
        at(
            9,
            Canon::Message {
                text: String::new(),
            },
        ),
        at(9, Canon::StopSpindle { spindle: 0 }),
        at(9, Canon::Flood { on: false }),
        at(10, Canon::PalletShuttle),
        at(10, Canon::ProgramEnd),
    ];
    let r = run(MachineData::default_mill(), &cmds).0.report();
    assert_eq!(r.tools_used, vec![3, 7]);
    assert_eq!(r.tool_changes, 3);
    assert_eq!(
        r.messages,
        vec![LoggedEvent {
            line: 1,
            text: "load part".into()
        }]
    );
    let log: Vec<(u32, &str)> = r
        .m_functions
        .iter()
        .map(|e| (e.line, e.text.as_str()))
        .collect();
    assert_eq!(
        log,
        vec![
            (2, "M6 tool change to T3"),
            (3, "M3 spindle clockwise, 1200 rpm"),
            (4, "M8 flood on"),
            (5, "M6 tool change to T7"),
            (6, "M6 tool change to T3"),
            (7, "M73 auxiliary function (after motion)"),
            (8, "M1 optional stop"),
            (9, "M5 spindle stop"),
            (9, "M9 coolant off"),
            (10, "pallet shuttle"),
            (10, "M2/M30 program end"),
        ]
    );
    assert!(r.program_ended);
    assert_eq!(r.bounding_box, None);
    assert_eq!(r.nominal_time_s, 0.0);
}

#[test]
fn planned_cycle_time_and_axis_peaks() {
    // 100 mm at F3000 (50 mm/s) with a = 1000 mm/s²: 2 s + 0.05 s, then a 0.5 s dwell; peaks.
    let o = p(0.0, 0.0, 0.0);
    let cmds = [
        at(1, init(o)),
        at(2, Canon::StraightFeed(line(o, p(100.0, 0.0, 0.0), 3000.0))),
        at(3, Canon::Dwell { seconds: 0.5 }),
        at(4, Canon::ProgramEnd),
    ];
    let mut sim = SimMachine::new(MachineData::default_mill());
    for c in &cmds {
        sim.apply(c).unwrap();
    }
    let r = sim.finish();
    assert!((r.cycle_time_s - 2.55).abs() < 1e-9, "{}", r.cycle_time_s);
    assert_eq!(r.setpoints, 2551);
    assert_eq!(r.violation_count, 0, "{:?}", r.violations);
    let x = &r.axes[0];
    assert_eq!(x.axis, 'X');
    assert!((x.peak_velocity - 50.0).abs() < 1e-9 && (x.peak_acceleration - 1000.0).abs() < 1e-9);
    assert!(x.trace_peak_acceleration <= 1000.0 * (1.0 + 1e-6));
    // A second finish changes nothing.
    assert_eq!(sim.finish().setpoints, 2551);
}

#[test]
fn feed_override_scales_the_planned_time() {
    let o = p(0.0, 0.0, 0.0);
    let cmds = [
        at(1, init(o)),
        at(2, Canon::StraightFeed(line(o, p(100.0, 0.0, 0.0), 3000.0))),
    ];
    let options = SimOptions {
        feed_override: 2.0,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(MachineData::default_mill(), options);
    for c in &cmds {
        sim.apply(c).unwrap();
    }
    // 200 % of F3000 = 100 mm/s: 1.1 s, as F6000 at 100 %.
    let r = sim.finish();
    assert!((r.cycle_time_s - 1.1).abs() < 1e-9, "{}", r.cycle_time_s);
    assert_eq!(r.feed_override_percent, 200.0);
}

/// Setpoints released by a drain (an operator's single block or program stop) count like any
/// other: here every setpoint of a G96 cut from X50 to X20 (200 m/min) comes out of the drain, and
/// the report's spindle range spans law(50) = 636.62 … law(20) = 1591.55 rev/min (1e-6). When the
/// drain skipped the tracking, only the final setpoint counted: 1591.55 … 1591.55.
#[test]
fn a_drain_counts_its_setpoints_in_the_spindle_range() {
    let law = |x: f64| 200_000.0 / (2.0 * PI * x);
    let mut sim = SimMachine::new(MachineData::default_mill());
    for c in [
        init(p(50.0, 0.0, 0.0)),
        Canon::SetSpindleSpeed {
            spindle: 0,
            rpm: 500.0,
        },
        Canon::SetSurfaceSpeedLaw {
            spindle: 0,
            law: Some(stanok_canon::SurfaceSpeedLaw {
                mm_per_min: 200_000.0,
                axis: 0,
                centre: 0.0,
                min_rpm: 0.0,
                max_rpm: 3000.0,
            }),
        },
        Canon::StartSpindle {
            spindle: 0,
            direction: stanok_canon::SpindleDirection::Clockwise,
        },
        Canon::StraightFeed(line(p(50.0, 0.0, 0.0), p(20.0, 0.0, 0.0), 600.0)),
    ] {
        sim.apply(&at(1, c)).unwrap();
    }
    sim.drain_motion();
    let report = sim.finish();
    assert_eq!(report.spindles.len(), 1, "{:?}", report.spindles);
    let s = &report.spindles[0];
    assert!((s.min_rpm - law(50.0)).abs() < 1e-6, "{s:?}");
    assert!((s.max_rpm - law(20.0)).abs() < 1e-6, "{s:?}");
}
