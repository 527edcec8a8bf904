//! The operator's feed-hold button (`HoldSwitch`): pressed from the setpoint consumer's side at
//! 0.5 s and released at 1.6 s, it must give exactly the planned hold of
//! `feed_hold_brakes_on_the_path_stands_and_resumes` (brake to 50 mm at 0.6 s, stand 1 s, resume),
//! whatever thread presses it.

mod common;
use common::*;
use stanok_canon::AccelerationProfile::Brisk;
use stanok_canon::PathMode;
use stanok_motion::hold::HoldSwitch;
use stanok_motion::monitor::TraceMonitor;
use stanok_motion::{MotionStage, Setpoint};
use std::sync::Arc;

const G64: PathMode = PathMode::Continuous { tolerance: 0.05 };

#[test]
fn the_hold_button_brakes_stands_until_released_and_resumes() {
    let cfg = mill();
    let (a, b) = (p3(0.0, 0.0, 0.0), p3(100.0, 0.0, 0.0));
    let switch = Arc::new(HoldSwitch::default());
    let mut stage = MotionStage::new(&cfg);
    stage.set_hold_switch(switch.clone());
    let mut trace: Vec<Setpoint> = Vec::new();
    let mut monitor = TraceMonitor::new(cfg.axes, cfg.servo_period);
    let mut sink = |sp: &Setpoint| {
        monitor.observe(sp);
        trace.push(*sp);
        // The panel's thread would do this; the interpolator reads the switch at the next instant.
        if (sp.t - 0.499).abs() < 1e-9 {
            switch.set(true);
        }
        if (sp.t - 1.599).abs() < 1e-9 {
            switch.set(false);
        }
    };
    stage.set_position(a, &mut sink);
    stage.push_input(line(a, b, 6000.0, G64, Brisk), &mut sink);
    let t = stage.finish(&mut sink);
    assert_eq!(monitor.violation_count, 0, "{:?}", monitor.violations);
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
fn a_machine_held_before_it_starts_does_not_move_until_released() {
    let cfg = mill();
    let (a, b) = (p3(0.0, 0.0, 0.0), p3(10.0, 0.0, 0.0));
    let switch = Arc::new(HoldSwitch::default());
    switch.set(true);
    let mut stage = MotionStage::new(&cfg);
    stage.set_hold_switch(switch.clone());
    let mut trace: Vec<Setpoint> = Vec::new();
    let mut sink = |sp: &Setpoint| {
        trace.push(*sp);
        if (sp.t - 0.3).abs() < 1e-9 {
            switch.set(false);
        }
    };
    stage.set_position(a, &mut sink);
    stage.push_input(line(a, b, 6000.0, G64, Brisk), &mut sink);
    stage.finish(&mut sink);
    for sp in trace.iter().filter(|s| s.t <= 0.3 + 1e-9) {
        assert_eq!(sp.position[0], 0.0, "{sp:?}");
    }
    assert!(trace.iter().any(|s| s.t > 0.3 && s.position[0] > 0.0));
    assert_eq!(trace.last().unwrap().position, b);
}
