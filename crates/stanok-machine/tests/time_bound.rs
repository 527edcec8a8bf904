//! Issue 17 item 3: the bound on simulated machine time, the long-block warning, and the
//! interpolator skipping steady stretches (`time_bound.rs`, `stanok_motion::interpolator`).

use stanok_canon::{Canon, LengthUnits, LineMove, Pose, Span, Spanned};
use stanok_machine::{MachineData, SimMachine, SimOptions};
use std::cell::Cell;
use std::rc::Rc;

fn at(line: u32, value: Canon) -> Spanned<Canon> {
    Spanned::new(Span::new(0, 0, line, 1), value)
}

fn p(x: f64) -> Pose {
    Pose::ZERO.with_xyz([x, 0.0, 0.0])
}

fn init() -> Canon {
    Canon::Init {
        position: Pose::ZERO,
        units: LengthUnits::Millimetres,
        g5x_index: 1,
        g5x_offset: Pose::ZERO,
        g92_offset: Pose::ZERO,
        xy_rotation: 0.0,
    }
}

fn feed(from: f64, to: f64, f: f64) -> Canon {
    Canon::StraightFeed(LineMove {
        start: p(from),
        end: p(to),
        feed: f,
        law: stanok_canon::FeedLaw::PerMinute,
    })
}

/// A machine whose progress sink counts its calls.
fn counted(options: SimOptions) -> (SimMachine, Rc<Cell<u64>>) {
    let mut sim = SimMachine::with_options(MachineData::default_mill(), options);
    let calls = Rc::new(Cell::new(0u64));
    let c = calls.clone();
    sim.set_progress_sink(Box::new(move |_| c.set(c.get() + 1)));
    (sim, calls)
}

/// `G1 X100 F0.0000001` (1,900 years) and `G4 P1000000000`: refused at the block, before any of
/// it runs, at once.
#[test]
fn a_block_past_the_bound_is_refused_before_it_runs() {
    for cmd in [feed(0.0, 100.0, 1e-7), Canon::Dwell { seconds: 1e9 }] {
        let (mut sim, calls) = counted(SimOptions::default());
        sim.apply(&at(1, init())).unwrap();
        let d = sim.apply(&at(2, cmd)).unwrap_err();
        assert_eq!(d.code.to_string(), "machine::time-limit");
        assert_eq!(d.span.line, 2);
        assert!(d.notes.iter().any(|n| n.contains("--max-machine-time")));
        let r = sim.finish();
        assert_eq!(r.nominal_time_s, 0.0);
        assert!(r.cycle_time_s < 0.01, "{}", r.cycle_time_s);
        assert!(calls.get() < 10);
    }
}

/// The bound adds up over blocks: ten 11-hour dwells pass 100 h at the tenth.
#[test]
fn the_bound_is_on_the_whole_run() {
    let (mut sim, _) = counted(SimOptions::default());
    sim.apply(&at(1, init())).unwrap();
    for i in 0..9 {
        sim.apply(&at(
            2 + i,
            Canon::Dwell {
                seconds: 11.0 * 3600.0,
            },
        ))
        .unwrap();
    }
    let d = sim
        .apply(&at(
            11,
            Canon::Dwell {
                seconds: 11.0 * 3600.0,
            },
        ))
        .unwrap_err();
    assert_eq!(d.code.to_string(), "machine::time-limit");
    assert_eq!(d.span.line, 11);
}

/// A 300,000 s dwell (83 h, under the bound) and a 100-minute feed run in a handful of setpoints
/// when only a progress display watches, with the same times as when every period is stepped.
#[test]
fn steady_stretches_are_skipped_without_changing_the_times() {
    let (mut sim, calls) = counted(SimOptions::default());
    sim.apply(&at(1, init())).unwrap();
    sim.apply(&at(2, Canon::Dwell { seconds: 300_000.0 }))
        .unwrap();
    sim.apply(&at(3, feed(0.0, 100.0, 1.0))).unwrap();
    let r = sim.finish();
    assert!(calls.get() < 10_000, "{} setpoints observed", calls.get());
    assert!((r.nominal_time_s - 306_000.0).abs() < 1e-6);
    assert!(
        (r.cycle_time_s - 306_000.0).abs() < 0.01,
        "{}",
        r.cycle_time_s
    );
    // One setpoint per period is still what the report counts.
    let periods = (r.cycle_time_s / r.servo_period_s).round() as u64;
    assert!(
        r.setpoints.abs_diff(periods + 1) <= 2,
        "{} vs {periods}",
        r.setpoints
    );
    assert_eq!(r.violation_count, 0, "{:?}", r.violations);
    let x = r.axes.iter().find(|a| a.axis == 'X').unwrap();
    assert!((x.peak_velocity - 1.0 / 60.0).abs() < 1e-9);
    assert!(
        (x.trace_peak_velocity - 1.0 / 60.0).abs() < 1e-6,
        "{}",
        x.trace_peak_velocity
    );

    // The same program with every setpoint observed (a shorter dwell: it is stepped).
    let mut full = SimMachine::new(MachineData::default_mill());
    let seen = Rc::new(Cell::new(0u64));
    let s = seen.clone();
    full.set_setpoint_sink(Box::new(move |_| s.set(s.get() + 1)));
    full.apply(&at(1, init())).unwrap();
    full.apply(&at(2, Canon::Dwell { seconds: 10.0 })).unwrap();
    let r = full.finish();
    assert_eq!(seen.get(), r.setpoints);
    assert!(seen.get() >= 10_000);
}

/// Guard 2: when the real time outruns the nominal one (here a 10 % feed override), the
/// interpolator stops at the bound and the report says so.
#[test]
fn the_interpolator_stops_at_the_bound() {
    let options = SimOptions {
        feed_override: 0.1,
        max_machine_time_s: 100.0,
        ..SimOptions::default()
    };
    let (mut sim, _) = counted(options);
    sim.apply(&at(1, init())).unwrap();
    // Nominal 60 s (under the bound); at 10 % it would take 600 s.
    sim.apply(&at(2, feed(0.0, 100.0, 100.0))).unwrap();
    let r = sim.finish();
    assert!(r.cycle_time_s <= 100.01, "{}", r.cycle_time_s);
    assert!(
        r.violations
            .iter()
            .any(|v| v.text.contains("bound on simulated machine time")),
        "{:?}",
        r.violations
    );
    assert!(r.violation_count >= 1);
}

/// A block over an hour is warned about (the run goes on); `long_block` is what `check` uses.
#[test]
fn a_block_over_an_hour_is_warned_about() {
    let (mut sim, _) = counted(SimOptions::default());
    sim.apply(&at(1, init())).unwrap();
    sim.apply(&at(2, feed(0.0, 100.0, 0.5))).unwrap();
    sim.apply(&at(3, Canon::Dwell { seconds: 30.0 })).unwrap();
    let w = sim.take_warnings();
    assert_eq!(w.len(), 1);
    assert_eq!(w[0].code.to_string(), "machine::long-block");
    assert_eq!(w[0].span.line, 2);
    assert!(w[0].message.contains("3.3 h"), "{}", w[0].message);
    let m = MachineData::default_mill();
    let d = stanok_machine::time_bound::long_block(
        &m,
        &Canon::Dwell { seconds: 7200.0 },
        Span::new(0, 0, 4, 1),
    )
    .unwrap();
    assert!(d.message.contains("dwells 2.0 h"), "{}", d.message);
    assert!(stanok_machine::time_bound::long_block(
        &m,
        &Canon::Dwell { seconds: 3600.0 },
        Span::new(0, 0, 4, 1)
    )
    .is_none());
}
