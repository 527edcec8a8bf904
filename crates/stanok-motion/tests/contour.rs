//! The contour error measured on the trace (`stanok_motion::contour`): known answers.

mod common;
use common::*;
use stanok_canon::{AccelerationProfile, PathMode};
use stanok_geom::Helix;
use stanok_motion::segment::{PathSegment, PlannerInput, SegmentGeometry};
use stanok_motion::MotionStage;

fn run_contour(inputs: Vec<PlannerInput>) -> MotionStage {
    let cfg = mill();
    let mut stage = MotionStage::new(&cfg);
    let mut sink = |_: &stanok_motion::Setpoint| {};
    stage.set_position(p3(0.0, 0.0, 0.0), &mut sink);
    for i in inputs {
        stage.push_input(i, &mut sink);
    }
    stage.finish(&mut sink);
    stage
}

/// A right-angle corner under G64 P0.05 (BRISK: a circular blend 0.05 from the corner, whose
/// middle lies r·(1 − cos 45°) = 0.0354 from both sides): the largest distance at the junction
/// is that, to the setpoints' spacing (within 3 %); the sides are exact.
#[test]
fn a_square_corner_has_its_error_at_the_junction() {
    let g64 = PathMode::Continuous { tolerance: 0.05 };
    let b = AccelerationProfile::Brisk;
    let stage = run_contour(vec![
        line(p3(0.0, 0.0, 0.0), p3(50.0, 0.0, 0.0), 3000.0, g64, b),
        line(p3(50.0, 0.0, 0.0), p3(50.0, 50.0, 0.0), 3000.0, g64, b),
    ]);
    let c = stage.contour();
    let r = 0.05 / (std::f64::consts::PI / 8.0).tan();
    let middle = r * (1.0 - 0.5f64.sqrt());
    assert!(c.junctions.distance <= middle + 1e-12 && c.junctions.distance > 0.97 * middle);
    assert!(c.elsewhere.distance < 1e-12, "{}", c.elsewhere.distance);
    assert!(
        c.junctions.t > 1.02 && c.junctions.t < 1.06,
        "{}",
        c.junctions.t
    );
}

/// Shrunk from LinuxCNC's comp.ngc (G41 with a tool of radius 0): a compensation corner arc of
/// zero length between two lines. It was registered as the junction's previous segment, so the
/// blend between the two lines was measured against a point: 0.25 mm. A segment that does not
/// move is no side of a junction.
#[test]
fn a_zero_length_arc_is_not_a_side_of_the_junction() {
    let g64 = PathMode::Continuous { tolerance: 0.05 };
    let b = AccelerationProfile::Brisk;
    let corner = p3(5.0, -5.0, 0.0);
    let point_arc = PlannerInput::Segment(PathSegment {
        acceleration_cap: f64::INFINITY,
        velocity_cap: f64::INFINITY,
        speed_class: Default::default(),
        start: corner,
        end: corner,
        geometry: SegmentGeometry::Arc(Helix {
            start: [5.0, -5.0, 0.0],
            end: [5.0, -5.0, 0.0],
            centre: [5.0, -5.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            turns: 1,
        }),
        path_speed: 20.0,
        rapid: false,
        path_mode: g64,
        profile: b,
        line: 2,
        spindles: Default::default(),
    });
    let stage = run_contour(vec![
        line(p3(0.0, 0.0, 0.0), corner, 1200.0, g64, b),
        point_arc,
        line(corner, p3(5.0, 20.0, 0.0), 1200.0, g64, b),
    ]);
    let c = stage.contour();
    assert!(
        c.junctions.distance <= 0.05 + 1e-12,
        "{}",
        c.junctions.distance
    );
    assert!(c.elsewhere.distance < 1e-12);
}
