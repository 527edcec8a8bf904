//! RS274/NGC splines: the curve points the corpus headers give (`NURBS_FEED` in LinuxCNC's trace
//! carries no coordinates, so the traces cannot check them), evaluated on the Canon spline with
//! stanok-geom. Tolerance 1e-9 in (all programs are G20; positions are compared in inches).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{Canon, SplineMove};
use stanok_geom::Nurbs;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn splines(program: &str) -> Vec<SplineMove> {
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    cmds.into_iter()
        .filter_map(|c| match c.value {
            Canon::SplineFeed(s) => Some(*s),
            _ => None,
        })
        .collect()
}

/// The point at parameter u, in inches.
fn at(s: &SplineMove, u: f64) -> [f64; 2] {
    let c = Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots);
    let p = c.point_at(u);
    [p[0] / 25.4, p[1] / 25.4]
}

fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < TOL && (a[1] - b[1]).abs() < TOL
}

#[test]
fn g5_cubic_passes_through_the_header_points() {
    // g05-cubic-spline-example-1: B(0.5) = (0.5, 0.5), B(0.25) = (0.15625, 1.0), ends at (1, 1).
    let s = splines("G20 F10\nG90 G17\nG0 X0 Y0\nG5 I0 J3 P0 Q-3 X1 Y1\nM2\n");
    assert_eq!(s.len(), 1);
    assert_eq!(s[0].degree, 3);
    assert!(close(at(&s[0], 0.5), [0.5, 0.5]));
    assert!(close(at(&s[0], 0.25), [0.15625, 1.0]));
    assert!(close(at(&s[0], 1.0), [1.0, 1.0]));
}

#[test]
fn g5_without_ij_continues_tangentially() {
    // g05-cubic-spline-example-2: the second G5 takes I, J = −(previous P, Q) = (0, 3).
    let s = splines("G20 F10\nG90 G17\nG0 X0 Y0\nG5 I0 J3 P0 Q-3 X1 Y1\nG5 P0 Q-3 X2 Y2\nM2\n");
    assert_eq!(s.len(), 2);
    let p = &s[1].control_points;
    assert!(close([p[1][0] / 25.4, p[1][1] / 25.4], [1.0, 4.0]));
    // End tangent of the first equals start tangent of the second (both along +Y).
    let q = &s[0].control_points;
    let t0 = [q[3][0] - q[2][0], q[3][1] - q[2][1]];
    let t1 = [p[1][0] - p[0][0], p[1][1] - p[0][1]];
    assert!((t0[0] * t1[1] - t0[1] * t1[0]).abs() < 1e-9 && t0[1] > 0.0 && t1[1] > 0.0);
    assert!(close(at(&s[1], 1.0), [2.0, 2.0]));
}

#[test]
fn g5_first_without_ij_starts_along_no_tangent() {
    // LinuxCNC 2.9 (rs274) takes I, J from its last G5's P, Q, 0 before any: the first control
    // point is the start point.
    let s = splines("G20 F10 G17\nG5 P0 Q-3 X1 Y1\nM2\n");
    let p = &s[0].control_points;
    assert!(close([p[1][0], p[1][1]], [p[0][0], p[0][1]]));
    let (_, err) = run("G20 F10 G17\nG5 I1 P0 Q-3 X1 Y1\nM2\n", Dialect::Rs274ngc);
    assert_eq!(
        err.unwrap().message,
        "Must specify both I and J, or neither"
    );
}

#[test]
fn g5_1_quadratic_is_the_parabola() {
    // g05.1-quadratic-spline-example-1: from (−2, 4), control (0, −4), to (2, 4): y = x².
    let s = splines("G20 F10\nG90 G17\nG0 X-2 Y4\nG5.1 X2 I2 J-8\nM2\n");
    assert_eq!(s[0].degree, 2);
    for i in 0..=20 {
        let p = at(&s[0], i as f64 / 20.0);
        assert!((p[1] - p[0] * p[0]).abs() < TOL, "{p:?}");
    }
}

#[test]
fn g5_2_nurbs_has_the_header_points() {
    // g05.2-nurbs-example-1: knots [0,0,0,1,2,3,3,3], weights 1,1,1,1,2.
    let s = splines(
        "G20\nG0 X0 Y0\nF10\nG5.2 P1 L3\n X0 Y1 P1\n X2 Y2 P1\n X2 Y0 P1\n X0 Y0 P2\nG5.3\nM2\n",
    );
    assert_eq!(s[0].knots, vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]);
    assert_eq!(s[0].weights, vec![1.0, 1.0, 1.0, 1.0, 2.0]);
    for (u, want) in [
        (0.0, [0.0, 0.0]),
        (0.5, [0.25, 0.875]),
        (1.0, [1.0, 1.5]),
        (1.5, [1.75, 1.625]),
        (2.0, [2.0, 1.0]),
        (2.5, [1.2, 0.2]),
        (3.0, [0.0, 0.0]),
    ] {
        assert!(close(at(&s[0], u), want), "u={u}: {:?}", at(&s[0], u));
    }
}

#[test]
fn a_feed_set_to_zero_before_g5_3_cuts_the_nurbs_at_zero() {
    // LinuxCNC checks a NURBS's feed on its G5.2 blocks only (golden
    // stanok-parity-g5-3-zero-feed): F0 after the points, alone or on the G5.3 line, cuts the
    // curve at feed 0 with every point collected; an F on the G5.3 line is its feed.
    for (end, feed) in [
        ("F0\nG5.3", 0.0),
        ("G5.3 F0", 0.0),
        ("F0\nF10 G5.3", 10.0 * 25.4),
    ] {
        let s = splines(&format!(
            "G20 F5\nG0 X0 Y0\nG5.2 L3\n X0 Y1 P1\n X2 Y2 P1\n{end}\nM2\n"
        ));
        assert_eq!(s.len(), 1, "{end}");
        assert_eq!(s[0].control_points.len(), 3, "{end}");
        assert!((s[0].feed - feed).abs() < 1e-9, "{end}: feed {}", s[0].feed);
    }
    // On a G5.2 block a zero feed is LinuxCNC's error.
    let (_, err) = run(
        "G20 F0\nG0 X0 Y0\nG5.2 L3\n X0 Y1 P1\n X2 Y2 P1\nG5.3\nM2\n",
        Dialect::Rs274ngc,
    );
    assert!(err.unwrap().message.contains("NURBS with 0 feedrate"));
}
