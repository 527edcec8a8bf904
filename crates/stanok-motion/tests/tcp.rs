//! The kin stage (tool-centre-point control): the tip of every servo setpoint stays on the
//! programmed segment (1e-6 mm) while the machine axes follow curves, and no machine axis exceeds
//! its velocity or acceleration limit.

use proptest::prelude::*;
use stanok_canon::{Canon, LineMove, OrientationInterpolation, Pose};
use stanok_kin::{head_head, table_table, FiveAxis, Kinematics, RotaryPair};
use stanok_motion::monitor::TraceMonitor;
use stanok_motion::{AxisLimit, MotionConfig, MotionStage, Setpoint};

/// X Y Z 10 000 mm/min, 1000 mm/s²; A B C 3600 deg/min, 720 deg/s²; servo 1 ms.
fn config(kin: FiveAxis) -> MotionConfig {
    let mut axes = [AxisLimit::UNLIMITED; 9];
    for a in axes.iter_mut().take(3) {
        *a = AxisLimit::from_machine(10_000.0, 1000.0, 20_000.0);
    }
    for a in axes.iter_mut().skip(3).take(3) {
        *a = AxisLimit::from_machine(3600.0, 720.0, 14_400.0);
    }
    let mut c = MotionConfig::new(axes, 10_000.0, 5_000.0);
    c.kinematics = Some(kin);
    c
}

fn pose(x: f64, y: f64, z: f64, a: f64, b: f64, c: f64) -> Pose {
    Pose {
        x,
        y,
        z,
        a,
        b,
        c,
        ..Pose::ZERO
    }
}

/// Runs Init (joints of `start`) → TCP on → one feed move → TCP off → end, and returns the
/// setpoints of the move (the machine axes).
fn run(
    kin: &FiveAxis,
    tool: f64,
    start: Pose,
    end: Pose,
    feed: f64,
    mode: OrientationInterpolation,
) -> (Vec<Setpoint>, TraceMonitor) {
    let cfg = config(kin.clone());
    let with_tool = kin.clone().with_tool_length(tool);
    let mut stage = MotionStage::new(&cfg);
    let mut monitor = TraceMonitor::new(cfg.axes, cfg.servo_period);
    let mut sps = Vec::new();
    let joints = Pose::from_array(with_tool.inverse(&start).unwrap());
    let cmds = [
        Canon::Init {
            position: joints,
            units: stanok_canon::LengthUnits::Millimetres,
            g5x_index: 1,
            g5x_offset: Pose::ZERO,
            g92_offset: Pose::ZERO,
            xy_rotation: 0.0,
        },
        Canon::SetOrientationInterpolation { mode },
        Canon::SetToolCentrePoint {
            active: true,
            tool_offset: [0.0, 0.0, tool],
        },
        Canon::StraightFeed(LineMove {
            start,
            end,
            feed,
            law: stanok_canon::FeedLaw::PerMinute,
        }),
        Canon::SetToolCentrePoint {
            active: false,
            tool_offset: [0.0; 3],
        },
    ];
    let mut sink = |sp: &Setpoint| {
        monitor.observe(sp);
        if sp.line == 4 {
            sps.push(*sp);
        }
    };
    for (i, c) in cmds.iter().enumerate() {
        stage.apply(c, i as u32 + 1, &mut sink);
    }
    stage.finish(&mut sink);
    (sps, monitor)
}

/// Distance of `p` from the segment a–b.
fn off_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let d: Vec<f64> = (0..3).map(|i| b[i] - a[i]).collect();
    let len2: f64 = d.iter().map(|x| x * x).sum();
    let f = if len2 > 0.0 {
        ((0..3).map(|i| (p[i] - a[i]) * d[i]).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|i| (p[i] - a[i] - f * d[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn machines() -> Vec<FiveAxis> {
    vec![
        head_head(RotaryPair::BC, 0.0).unwrap(),
        head_head(RotaryPair::AB, 120.0).unwrap(),
        table_table(RotaryPair::AC, [0.0, 50.0, -200.0], [20.0, 50.0, 0.0]).unwrap(),
    ]
}

fn check(
    kin: &FiveAxis,
    tool: f64,
    start: Pose,
    end: Pose,
    mode: OrientationInterpolation,
) -> Result<(), TestCaseError> {
    let (sps, monitor) = run(kin, tool, start, end, 2000.0, mode);
    prop_assert!(sps.len() > 2, "no motion");
    let with_tool = kin.clone().with_tool_length(tool);
    for sp in &sps {
        let tip = with_tool.forward(&sp.position).unwrap();
        let off = off_segment(tip.xyz(), start.xyz(), end.xyz());
        prop_assert!(
            off < 1e-6,
            "tip {:?} is {off} mm off the segment at t {}",
            tip.xyz(),
            sp.t
        );
    }
    let last = with_tool.forward(&sps.last().unwrap().position).unwrap();
    for (k, (got, want)) in last.to_array().iter().zip(end.to_array()).enumerate() {
        prop_assert!(
            (got - want).abs() < 1e-6,
            "axis {k}: ends at {got}, programmed {want}"
        );
    }
    prop_assert_eq!(monitor.violation_count, 0, "{:?}", monitor.violations);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Combined linear + rotary moves (ORIAXES): the tip stays on the line at every servo cycle.
    #[test]
    fn tip_stays_on_the_segment_under_oriaxes(
        xyz0 in prop::array::uniform3(-50.0f64..50.0),
        xyz1 in prop::array::uniform3(-50.0f64..50.0),
        r0 in prop::array::uniform2(-60.0f64..60.0),
        r1 in prop::array::uniform2(-60.0f64..60.0),
        which in 0usize..3,
    ) {
        let kin = &machines()[which];
        let slots: Vec<usize> = kin.rotary_axes().map(|a| a.slot()).collect();
        let mut s = pose(xyz0[0], xyz0[1], xyz0[2], 0.0, 0.0, 0.0).to_array();
        let mut e = pose(xyz1[0], xyz1[1], xyz1[2], 0.0, 0.0, 0.0).to_array();
        s[slots[0]] = r0[0];
        s[slots[1]] = r0[1];
        e[slots[0]] = r1[0];
        e[slots[1]] = r1[1];
        check(kin, 100.0, Pose::from_array(s), Pose::from_array(e), OrientationInterpolation::Axes)?;
    }
}

#[test]
fn rotate_in_place_keeps_the_tip_fixed() {
    // AxiOMA Example 12.1 on the C/B head: B 0 → −75 with the tip at the origin.
    let kin = head_head(RotaryPair::BC, 0.0).unwrap();
    let start = Pose::ZERO;
    let end = pose(0.0, 0.0, 0.0, 0.0, -75.0, 0.0);
    let (sps, monitor) = run(
        &kin,
        100.0,
        start,
        end,
        600.0,
        OrientationInterpolation::Axes,
    );
    let last = sps.last().unwrap().position;
    assert!(
        (last[0] + 96.5926).abs() < 1e-4 && (last[2] - 25.8819).abs() < 1e-4,
        "{last:?}"
    );
    // The mid point: B −37.5 → machine (−60.8761, 0, 79.3353).
    let mid = sps
        .iter()
        .min_by(|a, b| {
            (a.position[4] + 37.5)
                .abs()
                .total_cmp(&(b.position[4] + 37.5).abs())
        })
        .unwrap();
    let want_x = -100.0 * mid.position[4].to_radians().sin().abs();
    assert!((mid.position[0] - want_x).abs() < 1e-9);
    // 75° at 600 deg/min: at least 7.5 s (plus acceleration).
    let duration = sps.last().unwrap().t - sps.first().unwrap().t;
    assert!((7.5 - 2e-3..7.8).contains(&duration), "{duration}");
    assert_eq!(monitor.violation_count, 0);
    check(&kin, 100.0, start, end, OrientationInterpolation::Axes).unwrap();
}

#[test]
fn orivect_turns_on_the_great_circle_with_the_tip_fixed() {
    // C/B head, t from (sin 45, 0, cos 45) at C0 B45 to (0, sin 45, cos 45) at C90 B45: under
    // ORIAXES the vector stays on the 45° cone; under ORIVECT it follows the great circle, whose
    // middle (normalised (1,1,√2)/… ) is tilted less than 45°.
    let kin = head_head(RotaryPair::BC, 0.0).unwrap();
    let start = pose(0.0, 0.0, 0.0, 0.0, 45.0, 0.0);
    let end = pose(0.0, 0.0, 0.0, 0.0, 45.0, 90.0);
    let (sps, monitor) = run(
        &kin,
        100.0,
        start,
        end,
        600.0,
        OrientationInterpolation::Vector,
    );
    assert_eq!(monitor.violation_count, 0, "{:?}", monitor.violations);
    let t0 = [0.5f64.sqrt(), 0.0, 0.5f64.sqrt()];
    let t1 = [0.0, 0.5f64.sqrt(), 0.5f64.sqrt()];
    let normal = [
        t0[1] * t1[2] - t0[2] * t1[1],
        t0[2] * t1[0] - t0[0] * t1[2],
        t0[0] * t1[1] - t0[1] * t1[0],
    ];
    let mut min_b = f64::MAX;
    for sp in &sps {
        let t = kin.tool_vector(&Pose::from_array(sp.position));
        let off_plane: f64 = (0..3).map(|i| t[i] * normal[i]).sum();
        // Within the 0.5° polyline step of the great circle.
        assert!(
            off_plane.abs() < 2e-4,
            "{t:?} leaves the great circle by {off_plane}"
        );
        min_b = min_b.min(sp.position[4]);
    }
    // The great circle's middle is at acos(cos45·… ) = 35.26° from Z.
    assert!((min_b - 35.264).abs() < 0.05, "{min_b}");
    check(&kin, 100.0, start, end, OrientationInterpolation::Vector).unwrap();
}
