//! Exact arcs (issue 24): away from junction blends every setpoint of an arc lies on the
//! programmed circle, helix or spiral to 1 µm (in fact to rounding) at every feed, in any plane and
//! under any frame (any axis direction); junction blends stay within the path tolerance; every
//! planner guarantee holds (axis limits analytic and by finite differences, SOFT jerk included,
//! the trace ends at the last point and lasts the cycle time).

mod common;
use common::*;
use proptest::prelude::*;
use stanok_canon::{AccelerationProfile, PathMode};
use stanok_geom::Helix;
use stanok_motion::segment::{PathSegment, PlannerInput, Point9, SegmentGeometry};
use stanok_motion::Setpoint;

fn arc(
    s: Point9,
    e: Point9,
    helix: Helix,
    feed: f64,
    mode: PathMode,
    profile: AccelerationProfile,
) -> PlannerInput {
    PlannerInput::Segment(PathSegment {
        acceleration_cap: f64::INFINITY,
        velocity_cap: f64::INFINITY,
        speed_class: Default::default(),
        start: s,
        end: e,
        geometry: SegmentGeometry::Arc(helix),
        path_speed: feed / 60.0,
        rapid: false,
        path_mode: mode,
        profile,
        line: 2,
        spindles: Default::default(),
    })
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Distance of `p` from the helix about `axis` through `centre` with radius `r` at the start,
/// `r_end` at the end, rising `rise` per radian: radial error and axial error at the point's own
/// angle, measured on the nearest turn.
#[allow(clippy::too_many_arguments)]
fn helix_error(
    p: &Point9,
    centre: [f64; 3],
    axis: [f64; 3],
    u: [f64; 3],
    rise: f64,
    r: f64,
    r_end: f64,
    sweep: f64,
) -> f64 {
    let v = cross(axis, u);
    let d = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
    let (x, y, h) = (
        d[0] * u[0] + d[1] * u[1] + d[2] * u[2],
        d[0] * v[0] + d[1] * v[1] + d[2] * v[2],
        d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2],
    );
    let base = y.atan2(x).rem_euclid(std::f64::consts::TAU);
    let mut best = f64::INFINITY;
    for k in 0..20 {
        let th = base + k as f64 * std::f64::consts::TAU;
        if th > sweep + 1e-9 {
            break;
        }
        let rr = r + (r_end - r) * th / sweep;
        let e = ((x.hypot(y) - rr).powi(2) + (h - rise * th).powi(2)).sqrt();
        best = best.min(e);
    }
    // Near the start the angle may wrap to just below 2π·k.
    let e0 = ((x.hypot(y) - r).powi(2) + h.powi(2)).sqrt();
    best.min(e0)
}

/// The case: a full circle r 10 (G2 with I10) between two lines under G64 without P (the
/// default 0.05 mm) at F100, F600 and F3000, BRISK and SOFT. Before, it ran 0.025 mm inside (chords
/// blended within 0.05 mm); now every setpoint of the arc outside its junction blends is on the
/// circle to 1e-9 mm.
#[test]
fn a_full_circle_is_on_its_circle_at_every_feed() {
    let cfg = mill();
    let g64 = PathMode::Continuous { tolerance: 0.0 };
    for profile in [AccelerationProfile::Brisk, AccelerationProfile::Soft] {
        for feed in [100.0, 600.0, 3000.0] {
            let s = p3(0.0, 0.0, 0.0);
            let helix = Helix {
                start: [0.0, 0.0, 0.0],
                end: [0.0, 0.0, 0.0],
                centre: [10.0, 0.0, 0.0],
                axis: [0.0, 0.0, -1.0],
                turns: 1,
            };
            let inputs = vec![
                line(p3(-20.0, 0.0, 0.0), s, feed, g64, profile),
                arc(s, s, helix, feed, g64, profile),
                line(s, p3(0.0, 20.0, 0.0), feed, g64, profile),
            ];
            let (trace, mon, t) = run(&cfg, p3(-20.0, 0.0, 0.0), inputs);
            assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
            assert_eq!(trace.last().unwrap().t, t);
            assert_eq!(trace.last().unwrap().position, p3(0.0, 20.0, 0.0));
            let on_arc: Vec<&Setpoint> = trace
                .iter()
                .filter(|sp| sp.seq == 2 && !sp.junction)
                .collect();
            assert!(
                on_arc.len() as f64 > 0.8 * 62.83 / (feed / 60.0) / 1e-3,
                "{}",
                on_arc.len()
            );
            for sp in on_arc {
                let r = (sp.position[0] - 10.0).hypot(sp.position[1]);
                assert!(
                    (r - 10.0).abs() < 1e-9,
                    "F{feed} {profile:?}: r {r} at t {}",
                    sp.t
                );
            }
            // The junction blends stay within the default tolerance of the path.
            for sp in trace.iter().filter(|sp| sp.junction) {
                let p = &sp.position;
                let to_circle = ((p[0] - 10.0).hypot(p[1]) - 10.0).abs();
                let to_lines = if p[1] <= 0.0 { p[1].abs() } else { p[0].abs() };
                assert!(to_circle.min(to_lines) <= 0.05 + 1e-12, "{p:?}");
            }
        }
    }
}

/// A helix (r 10, 3 turns, 2 mm per turn) about a tilted axis (a rotated frame: the axis
/// (1, 1, 1)/√3), with A moving along: on the helix to 1e-9 at every setpoint outside the blends,
/// SOFT and BRISK.
#[test]
fn a_helix_under_a_rotated_frame_is_on_its_helix() {
    let cfg = {
        let mut c = mill();
        c.axes[3] = stanok_motion::AxisLimit::from_machine(3600.0, 500.0, 10_000.0);
        c
    };
    let axis = unit([1.0, 1.0, 1.0]);
    let u = unit(cross(axis, [0.0, 0.0, 1.0]));
    let centre = [5.0, -3.0, 2.0];
    let r = 10.0;
    let turns = 3u32;
    let pitch = 2.0;
    let sweep = std::f64::consts::TAU * turns as f64;
    let rise = pitch / std::f64::consts::TAU;
    let start3 = [
        centre[0] + r * u[0],
        centre[1] + r * u[1],
        centre[2] + r * u[2],
    ];
    let h = pitch * turns as f64;
    let end3 = [
        start3[0] + h * axis[0],
        start3[1] + h * axis[1],
        start3[2] + h * axis[2],
    ];
    let mut s = p3(start3[0], start3[1], start3[2]);
    let mut e = p3(end3[0], end3[1], end3[2]);
    s[3] = 0.0;
    e[3] = 45.0;
    let helix = Helix {
        start: start3,
        end: end3,
        centre,
        axis,
        turns,
    };
    let before = p3(start3[0] - 5.0, start3[1], start3[2]);
    let mut after = p3(end3[0], end3[1] + 5.0, end3[2]);
    after[3] = 45.0;
    for profile in [AccelerationProfile::Brisk, AccelerationProfile::Soft] {
        let g64 = PathMode::Continuous { tolerance: 0.02 };
        let inputs = vec![
            line(before, s, 2000.0, g64, profile),
            arc(s, e, helix, 2000.0, g64, profile),
            line(e, after, 2000.0, g64, profile),
        ];
        let (trace, mon, t) = run(&cfg, before, inputs);
        assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
        assert_eq!(trace.last().unwrap().t, t);
        let mut n = 0;
        for sp in trace.iter().filter(|sp| sp.seq == 2 && !sp.junction) {
            let err = helix_error(&sp.position, centre, axis, u, rise, r, r, sweep);
            assert!(err < 1e-9, "{profile:?}: {err} at t {}", sp.t);
            n += 1;
        }
        assert!(n > 1000);
    }
}

fn mode() -> impl Strategy<Value = PathMode> {
    prop_oneof![
        Just(PathMode::ExactStop),
        Just(PathMode::ExactPath),
        (0.001f64..0.5).prop_map(|tolerance| PathMode::Continuous { tolerance }),
        Just(PathMode::Continuous { tolerance: 0.0 }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, .. ProptestConfig::default() })]

    /// Random arcs — any axis direction, radius, sweep up to two turns, axial rise, a spiral's
    /// radius change up to 5 µm — between random lines, in every path mode and profile: no limit
    /// exceeded; every setpoint of the arc outside its junction blends on the arc to 1 µm; every
    /// setpoint within the tolerance in force of the path; the trace ends at the last point.
    #[test]
    fn random_arcs_are_exact_and_keep_every_guarantee(
        ax in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), r in 0.5f64..40.0, sweep in 0.05f64..12.0,
        rise in -1.0f64..1.0, dr in -0.005f64..0.005, feed in 100.0f64..6000.0, mode in mode(),
        soft in any::<bool>(), before in (-20.0f64..20.0, -20.0f64..20.0, -20.0f64..20.0),
        after in (-20.0f64..20.0, -20.0f64..20.0, -20.0f64..20.0),
    ) {
        let cfg = mill();
        let profile = if soft { AccelerationProfile::Soft } else { AccelerationProfile::Brisk };
        let n = (ax.0 * ax.0 + ax.1 * ax.1 + ax.2 * ax.2).sqrt();
        prop_assume!(n > 0.1);
        let axis = [ax.0 / n, ax.1 / n, ax.2 / n];
        let helper = if axis[2].abs() < 0.9 { [0.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0] };
        let u = unit(cross(axis, helper));
        let v = cross(axis, u);
        let turns = (sweep / std::f64::consts::TAU).floor() as u32 + 1;
        let planar = sweep - (turns - 1) as f64 * std::f64::consts::TAU;
        prop_assume!(planar > 0.01 && planar < std::f64::consts::TAU - 0.01);
        let centre = [1.0, 2.0, 3.0];
        let rise_total = rise * sweep;
        let r_end = r + dr;
        let at = |th: f64, rr: f64, hh: f64| {
            let (c, s) = (th.cos(), th.sin());
            [centre[0] + rr * (c * u[0] + s * v[0]) + hh * axis[0],
             centre[1] + rr * (c * u[1] + s * v[1]) + hh * axis[1],
             centre[2] + rr * (c * u[2] + s * v[2]) + hh * axis[2]]
        };
        let s3 = at(0.0, r, 0.0);
        let e3 = at(sweep, r_end, rise_total);
        let helix = Helix { start: s3, end: e3, centre, axis, turns };
        let (s, e) = (p3(s3[0], s3[1], s3[2]), p3(e3[0], e3[1], e3[2]));
        let b = p3(before.0, before.1, before.2);
        let a = p3(after.0, after.1, after.2);
        let inputs = vec![
            line(b, s, feed, mode, profile),
            arc(s, e, helix, feed, mode, profile),
            line(e, a, feed, mode, profile),
        ];
        let (trace, mon, t) = run(&cfg, b, inputs);
        prop_assert_eq!(mon.violation_count, 0, "{:?}", mon.violations);
        prop_assert_eq!(trace.last().unwrap().t, t);
        prop_assert_eq!(trace.last().unwrap().position, a);
        let rise_per_rad = rise_total / sweep;
        for sp in trace.iter().filter(|sp| sp.seq == 2 && !sp.junction) {
            let err = helix_error(&sp.position, centre, axis, u, rise_per_rad, r, r_end, sweep);
            prop_assert!(err < 1e-6, "{} at t {}", err, sp.t);
        }
        // The whole trace within the tolerance of the programmed path (arc tessellated to 1e-6).
        let mut fine = vec![s3];
        helix.tessellate(1e-6, &mut fine);
        let mut path: Vec<Point9> = vec![b];
        path.extend(fine.iter().map(|q| p3(q[0], q[1], q[2])));
        path.push(a);
        let allowed = match mode {
            PathMode::Continuous { tolerance } if tolerance > 0.0 => tolerance,
            PathMode::Continuous { .. } => cfg.default_tolerance,
            _ => stanok_motion::path::INTERNAL_TOLERANCE,
        };
        let mut cursor = PathCursor::new(&path);
        for sp in &trace {
            let d = cursor.distance_within(&sp.position, allowed + 2e-6);
            prop_assert!(d <= allowed + 2e-6, "{} > {} at t = {}", d, allowed, sp.t);
        }
    }
}

/// A spiral made of arcs (LinuxCNC's arcspiral.ngc: R-format arcs whose radius shrinks a little
/// from one to the next, so consecutive arcs meet at a slight corner and every junction is a long,
/// nearly tangent smooth blend) runs at its programmed feed. The blends' feed scale used to carry
/// the axes' 1 % sampling margin, and the whole spiral ran 1 % slow; now the time above nominal is
/// the start and the stop only.
#[test]
fn a_spiral_of_arcs_runs_at_its_feed() {
    let feed = 609.6; // F24 in/min, as arcspiral.ngc
    let g64 = PathMode::Continuous { tolerance: 0.05 };
    let (mut inputs, mut length) = (Vec::new(), 0.0);
    let point = |k: usize| {
        let (r, th) = (50.0 - 0.05 * k as f64, -(k as f64) * 10f64.to_radians());
        p3(r * th.cos(), r * th.sin(), 0.0)
    };
    for k in 0..72 {
        let (s, e) = (point(k), point(k + 1));
        // The circle of radius R = the start's distance from the origin through s and e, its
        // centre on the origin's side of the chord (a clockwise arc below 180°).
        let radius = 50.0 - 0.05 * k as f64;
        let m = [(s[0] + e[0]) / 2.0, (s[1] + e[1]) / 2.0];
        let c = [e[0] - s[0], e[1] - s[1]];
        let half = 0.5 * c[0].hypot(c[1]);
        let n = [-c[1] / (2.0 * half), c[0] / (2.0 * half)];
        let off = (radius * radius - half * half).sqrt();
        let side = if n[0] * -m[0] + n[1] * -m[1] > 0.0 {
            1.0
        } else {
            -1.0
        };
        let centre = [m[0] + side * off * n[0], m[1] + side * off * n[1], 0.0];
        let helix = Helix {
            start: [s[0], s[1], 0.0],
            end: [e[0], e[1], 0.0],
            centre,
            axis: [0.0, 0.0, -1.0],
            turns: 1,
        };
        length += helix.length();
        inputs.push(arc(s, e, helix, feed, g64, AccelerationProfile::Brisk));
    }
    let (trace, monitor, t) = run(&mill(), point(0), inputs);
    assert!(monitor.violations.is_empty(), "{:?}", monitor.violations);
    let nominal = length / (feed / 60.0);
    // Starting and stopping at 1000 mm/s² cost v/a = 0.01 s; the servo grid 1 ms more.
    assert!(t <= nominal + 0.012, "t {t} nominal {nominal}");
    let end = trace.last().unwrap().position;
    assert!((end[0] - point(72)[0]).abs() < 1e-9 && (end[1] - point(72)[1]).abs() < 1e-9);
}
