//! AxiOMA splines (spec axioma-2 §2.4) on the corpus fixtures s5_4_*: the curve points, C¹/C²
//! joints and natural ends of ASPLINE/CSPLINE, the NURBS circle of example 5.16, the BSPLINE knot
//! rules and errors, SPLBREAK and the other break points, and bounded buffering.
//! Tolerances: points 1e-9 mm where the construction is exact, else as stated.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{Canon, Spanned, SplineMove};
use stanok_geom::akima::{akima_beziers, bezier_derivatives};
use stanok_geom::{bezier_knots, bezier_pieces, norm, sub, BezierPiece, Nurbs, Vec3};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

fn program(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn ok_with(text: &str, o: InterpOptions) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run_with(text, o);
    assert!(err.is_none(), "unexpected error {err:?}");
    cmds
}

fn ok(text: &str) -> Vec<Spanned<Canon>> {
    ok_with(text, options(Dialect::Axioma))
}

fn splines(cmds: &[Spanned<Canon>]) -> Vec<(Option<u32>, SplineMove)> {
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::SplineFeed(s) => Some((c.block_number, (**s).clone())),
            _ => None,
        })
        .collect()
}

fn bez(s: &SplineMove) -> [Vec3; 4] {
    assert_eq!(s.degree, 3);
    assert_eq!(s.knots, [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
    assert_eq!(s.weights, [1.0; 4]);
    [
        s.control_points[0],
        s.control_points[1],
        s.control_points[2],
        s.control_points[3],
    ]
}

fn close3(a: Vec3, b: Vec3, tol: f64) -> bool {
    norm(sub(a, b)) <= tol
}

/// Derivatives with respect to the chord-length parameter s (u = s/h) at u = 0 and u = 1.
fn ds(b: &[Vec3; 4], u: f64) -> (Vec3, Vec3) {
    let h = norm(sub(b[3], b[0]));
    let (d1, d2) = bezier_derivatives(b, u);
    (d1.map(|v| v / h), d2.map(|v| v / (h * h)))
}

const AKIMA_POINTS: [[f64; 2]; 11] = [
    [0.0, 0.0],
    [20.0, 10.0],
    [30.0, 10.0],
    [40.0, 50.0],
    [50.0, 15.0],
    [55.0, 70.0],
    [60.0, 20.0],
    [65.0, 20.0],
    [70.0, 0.0],
    [80.0, 10.0],
    [90.0, 0.0],
];

#[test]
fn s5_4_1_aspline_through_every_point_c1_natural_ends() {
    let s = splines(&ok(&program("s5_4_1-aspline-akima-example-5_15.nc")));
    assert_eq!(s.len(), 10);
    let b: Vec<[Vec3; 4]> = s.iter().map(|(_, m)| bez(m)).collect();
    for (i, seg) in b.iter().enumerate() {
        let [x0, y0] = AKIMA_POINTS[i];
        let [x1, y1] = AKIMA_POINTS[i + 1];
        assert!(close3(seg[0], [x0, y0, 0.0], 1e-9), "{i}: {seg:?}");
        assert!(close3(seg[3], [x1, y1, 0.0], 1e-9), "{i}: {seg:?}");
        assert_eq!(s[i].1.feed, 1500.0);
        // Each segment belongs to the block of its end point (N20 … N100).
        assert_eq!(s[i].0, Some(10 * (i as u32 + 1)));
    }
    // C¹: the unit-speed tangent is continuous at every inner point.
    for i in 0..9 {
        let (out, _) = ds(&b[i], 1.0);
        let (inn, _) = ds(&b[i + 1], 0.0);
        assert!(
            close3(out, inn, 1e-9),
            "joint {}: {out:?} vs {inn:?}",
            i + 1
        );
    }
    // Zero curvature at both ends.
    assert!(norm(ds(&b[0], 0.0).1) < 1e-9);
    assert!(norm(ds(&b[9], 1.0).1) < 1e-9);
    // The bounded window gives exactly the whole-spline construction.
    let pts: Vec<Vec3> = AKIMA_POINTS.iter().map(|p| [p[0], p[1], 0.0]).collect();
    for (got, want) in b.iter().zip(akima_beziers(&pts)) {
        for k in 0..4 {
            assert!(close3(got[k], want[k], 1e-9));
        }
    }
}

#[test]
fn s5_4_3_cspline_c2_within_its_zone_of_influence() {
    let text = program("s5_4_3-cspline-cubic-example-5_17.nc");
    let mut pts = AKIMA_POINTS;
    pts[3] = [40.0, 5.0];
    pts[5] = [55.0, 7.0];
    for (window, c2_tol) in [(8usize, 0.05), (100, 1e-9)] {
        let mut o = options(Dialect::Axioma);
        o.axioma.cspline_window = window;
        let s = splines(&ok_with(&text, o));
        assert_eq!(s.len(), 10);
        let b: Vec<[Vec3; 4]> = s.iter().map(|(_, m)| bez(m)).collect();
        for (i, seg) in b.iter().enumerate() {
            assert!(close3(seg[0], [pts[i][0], pts[i][1], 0.0], 1e-9));
            assert!(close3(seg[3], [pts[i + 1][0], pts[i + 1][1], 0.0], 1e-9));
        }
        for i in 0..9 {
            let (t_out, k_out) = ds(&b[i], 1.0);
            let (t_in, k_in) = ds(&b[i + 1], 0.0);
            assert!(close3(t_out, t_in, 1e-9), "W{window} C¹ at {}", i + 1);
            // C² defect relative to the curvature scale of the joint.
            let scale = norm(k_out).max(norm(k_in)).max(1e-3);
            let defect = norm(sub(k_out, k_in)) / scale;
            assert!(defect <= c2_tol, "W{window} C² at {}: {defect}", i + 1);
        }
        assert!(norm(ds(&b[0], 0.0).1) < 1e-9);
        assert!(norm(ds(&b[9], 1.0).1) < 1e-9);
    }
}

/// The expected BSPLINE output: the rational Bézier pieces of the NURBS with these control points,
/// weights and knots (an independent construction from the expected knot vector).
fn expected_pieces(degree: u8, cps: &[Vec3], weights: &[f64], knots: &[f64]) -> Vec<BezierPiece> {
    let c = Nurbs::new(degree, cps, weights, knots);
    assert!(c.validate().is_ok(), "{knots:?}");
    bezier_pieces(degree, cps, weights, knots)
}

#[track_caller]
fn assert_same_pieces(got: &[SplineMove], want: &[BezierPiece]) {
    assert_eq!(got.len(), want.len(), "{got:#?}");
    for (g, w) in got.iter().zip(want) {
        assert_eq!(g.knots, bezier_knots(g.degree as usize));
        for (a, b) in g.control_points.iter().zip(&w.points) {
            assert!(close3(*a, *b, 1e-9), "{a:?} vs {b:?}");
        }
        for (a, b) in g.weights.iter().zip(&w.weights) {
            assert!((a - b).abs() < 1e-12);
        }
    }
}

#[test]
fn s5_4_2_nurbs_circle_radius_30() {
    let cmds = ok(&program("s5_4_2-bspline-nurbs-circle-example-5_16.nc"));
    let s = splines(&cmds);
    // Knots [0,0,0,.25,.25,.5,.5,.75,.75,1,1,1]: four quarter circles, owned by N20, N40, N60, N80.
    let blocks: Vec<Option<u32>> = s.iter().map(|p| p.0).collect();
    assert_eq!(blocks, [Some(20), Some(40), Some(60), Some(80)]);
    let w = 0.707;
    let cps: Vec<Vec3> = [
        [30.0, 0.0],
        [30.0, 30.0],
        [0.0, 30.0],
        [-30.0, 30.0],
        [-30.0, 0.0],
        [-30.0, -30.0],
        [0.0, -30.0],
        [30.0, -30.0],
        [30.0, 0.0],
    ]
    .iter()
    .map(|p| [p[0], p[1], 0.0])
    .collect();
    let weights = [1.0, w, 1.0, w, 1.0, w, 1.0, w, 1.0];
    let knots = [
        0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
    ];
    let pieces: Vec<SplineMove> = s.iter().map(|p| p.1.clone()).collect();
    assert_same_pieces(&pieces, &expected_pieces(2, &cps, &weights, &knots));
    let mut length = 0.0;
    for m in &pieces {
        assert_eq!((m.degree, m.feed), (2, 1500.0));
        let c = Nurbs::new(m.degree, &m.control_points, &m.weights, &m.knots);
        for k in 0..=500 {
            let p = c.point_at(k as f64 / 500.0);
            let r = p[0].hypot(p[1]);
            assert!((r - 30.0).abs() <= 0.0008, "r {r}");
        }
        length += c.length();
    }
    // u = 0.125 of the circle = the middle of the first quarter piece.
    let first = &pieces[0];
    let q = Nurbs::new(2, &first.control_points, &first.weights, &first.knots).point_at(0.5);
    assert!(
        (q[0] - 21.21265).abs() < 1e-4 && (q[1] - 21.21265).abs() < 1e-4,
        "{q:?}"
    );
    // CCW through (0,30) (−30,0) (0,−30) and back to (30,0).
    let ends: Vec<Vec3> = pieces.iter().map(|m| m.end.xyz()).collect();
    for (e, want) in ends.iter().zip([
        [0.0, 30.0, 0.0],
        [-30.0, 0.0, 0.0],
        [0.0, -30.0, 0.0],
        [30.0, 0.0, 0.0],
    ]) {
        assert!(close3(*e, want, 1e-9), "{e:?}");
    }
    assert!((length - 188.5).abs() < 0.05, "{length}");
    // Then N100 G01 back to the centre.
    let last = cmds
        .iter()
        .rev()
        .find_map(|c| match &c.value {
            Canon::StraightFeed(l) => Some(l.end.xyz()),
            _ => None,
        })
        .unwrap();
    assert_eq!(last, [0.0, 0.0, 0.0]);
}

#[test]
fn s5_4_2_too_few_points_for_degree_3_is_an_error_at_the_breaking_block() {
    let text = program("s5_4_2-bspline-too-few-points-error-fragment.nc");
    let (cmds, err) = run(&text, Dialect::Axioma);
    let err = err.expect("two blocks cannot make a degree-3 curve");
    assert_eq!(err.code.to_string(), "axioma::bspline");
    let n40 = text.lines().position(|l| l.starts_with("N40")).unwrap() as u32 + 1;
    assert_eq!(err.span.line, n40);
    assert!(splines(&cmds).is_empty());
}

fn pieces_of(text: &str) -> Vec<SplineMove> {
    splines(&ok(text)).into_iter().map(|p| p.1).collect()
}

fn xyz_points(p: &[[f64; 3]]) -> Vec<Vec3> {
    let mut v = vec![[0.0; 3]];
    v.extend_from_slice(p);
    v
}

#[test]
fn s5_4_2_knot_increments_degree_3_and_2() {
    // The fragments lack a feed; with one, the knots follow the manual's comments: the first
    // p+1 knots automatic, then PL of N20 (SD 3) / N10 (SD 2), …, the last p knots automatic.
    // (With the fixture's PL=.10 on N100 the SD-3 vector is [0⁴, .1, .15, .25, .4⁴]; the spec's
    // "COMPUTED" line assumed .2 there.) The output is compared with the Bézier pieces of the
    // NURBS built from the expected knot vector.
    let pts = xyz_points(&[
        [16.535, -16.769, 95.0],
        [21.392, -18.854, 95.0],
        [26.942, -21.238, 95.0],
        [39.971, -28.441, 92.743],
        [35.962, -26.72, 94.165],
        [33.909, -25.838, 94.559],
    ]);
    let ones = [1.0; 7];
    let d3 = format!(
        "F1000\n{}",
        program("s5_4_2-bspline-degree3-knot-increments-fragment.nc")
    );
    let got = pieces_of(&d3);
    assert_same_pieces(
        &got,
        &expected_pieces(
            3,
            &pts,
            &ones,
            &[0.0, 0.0, 0.0, 0.0, 0.1, 0.15, 0.25, 0.4, 0.4, 0.4, 0.4],
        ),
    );
    assert!(close3(got[got.len() - 1].end.xyz(), pts[6], 1e-9));
    let d2 = format!(
        "F1000\n{}",
        program("s5_4_2-bspline-degree2-knot-increments-fragment.nc")
    );
    assert_same_pieces(
        &pieces_of(&d2),
        &expected_pieces(
            2,
            &pts,
            &ones,
            &[0.0, 0.0, 0.0, 1.0, 1.1, 1.15, 1.25, 1.4, 1.4, 1.4],
        ),
    );
    // The forbidden zeros of the comments.
    for (prog, what) in [
        (d3.replace("N20 PL=0.10", "N20 PL=0"), "first"),
        (d3.replace("N110 PL=.15", "N110 PL=0"), "last"),
        (d2.replace("Z95.PL=1", "Z95. PL=0"), "first"),
    ] {
        let (_, err) = run(&prog, Dialect::Axioma);
        let err = err.unwrap_or_else(|| panic!("{what} zero increment accepted"));
        assert_eq!(err.code.to_string(), "axioma::bspline");
        assert!(err.message.contains(what), "{err}");
    }
    // Multiplicity: SD 3 allows two zero increments in a row (triple knot), not three.
    let base = "F100 BSPLINE SD=3 X1\nX2 PL=1\nX3 PL=0\nX4 PL=0\nX5 PL=1\nX6\nX7\nG01 X0\n";
    assert!(run(base, Dialect::Axioma).1.is_none());
    let (_, err) = run(&base.replace("X5 PL=1", "X5 PL=0"), Dialect::Axioma);
    assert!(err.unwrap().message.contains("at most SD = 3"));
    // Word ranges.
    for (bad, code) in [
        ("F100 BSPLINE SD=4 X1\n", "axioma::bspline-degree"),
        ("F100 BSPLINE X1 PW=3.5\n", "axioma::bspline-weight"),
        ("F100 BSPLINE X1 PL=-1\n", "axioma::bspline-increment"),
        (
            "F100 ASPLINE X1 PW=2\n",
            "axioma::nurbs-word-outside-bspline",
        ),
    ] {
        assert_eq!(
            run(bad, Dialect::Axioma).1.unwrap().code.to_string(),
            code,
            "{bad}"
        );
    }
}

fn with_c_axis() -> InterpOptions {
    let mut o = options(Dialect::Axioma);
    o.axes[3] = true;
    o.axes[4] = true;
    o.axes[5] = true;
    o
}

#[test]
fn s5_4_2_extra_axes_on_points_without_an_interval() {
    let text = program("s5_4_2-bspline-extra-axes-rules-error-fragment.nc");
    let line = |n: &str| text.lines().position(|l| l.starts_with(n)).unwrap() as u32 + 1;
    let (_, err) = run_with(&text, with_c_axis());
    let err = err.unwrap();
    assert_eq!(
        (err.code.to_string().as_str(), err.span.line),
        ("axioma::bspline", line("N30"))
    );
    // Without N30's C: N80 (orientation words on the last point) is the next error.
    let no_c = text.replace("X10 Y10 C45", "X10 Y10");
    let (_, err) = run_with(&no_c, with_c_axis());
    assert_eq!(err.unwrap().span.line, line("N80"));
    // An additional axis on the last point is refused when the spline ends (at N90's M3).
    let c_last = no_c.replace("X30 Y20 A2=30 B2=45", "X30 Y20 C10");
    let (_, err) = run_with(&c_last, with_c_axis());
    let err = err.unwrap();
    assert_eq!(err.code.to_string(), "axioma::bspline");
    assert!(err.message.contains("last"), "{err}");
    // Both fixed: the knots of the spec [0,0,0,0,1,1,2,3,3,3,3] with N50's double knot: N40's
    // interval moves C to 30, N50's empty interval moves C alone to 90, N60 and N70 (the last
    // interval, ending at N80's point) carry C to 70 and 0.
    let valid = no_c.replace("X30 Y20 A2=30 B2=45", "X30 Y20");
    let cmds = ok_with(&valid, with_c_axis());
    let seq: Vec<(&str, Vec3, f64)> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::SplineFeed(s) => Some(("spline", s.end.xyz(), s.end.c)),
            Canon::StraightFeed(l) if c.block_number != Some(10) => {
                Some(("line", l.end.xyz(), l.end.c))
            }
            _ => None,
        })
        .collect();
    let pts = xyz_points(&[
        [10.0, 10.0, 0.0],
        [20.0, 0.0, 0.0],
        [20.0, 0.0, 0.0],
        [20.0, 0.0, 0.0],
        [20.0, 0.0, 0.0],
        [30.0, 20.0, 0.0],
    ]);
    let want = expected_pieces(
        3,
        &pts,
        &[1.0; 7],
        &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
    );
    assert_eq!(want.len(), 3);
    assert_eq!(seq.len(), 4, "{seq:?}");
    assert_eq!((seq[0].0, seq[0].2), ("spline", 30.0));
    assert_eq!((seq[1].0, seq[1].2), ("line", 90.0));
    assert!(close3(seq[1].1, seq[0].1, 1e-12), "C moves alone");
    assert_eq!((seq[2].0, seq[2].2), ("spline", 70.0));
    assert_eq!((seq[3].0, seq[3].2), ("spline", 0.0));
    assert!(close3(seq[0].1, want[0].points[3], 1e-9));
    assert!(close3(seq[3].1, [30.0, 20.0, 0.0], 1e-9));
}

#[test]
fn s5_4_4_splbreak_makes_two_independent_splines() {
    let cmds = ok(&program("s5_4_4-splbreak-example-5_18.nc"));
    let s = splines(&cmds);
    assert_eq!(s.len(), 8);
    let b: Vec<[Vec3; 4]> = s.iter().map(|(_, m)| bez(m)).collect();
    let one: Vec<Vec3> = [[0., 0.], [10., 0.], [20., 20.], [30., 0.], [40., 20.]]
        .iter()
        .map(|p| [p[0], p[1], 0.0])
        .collect();
    let two: Vec<Vec3> = [[40., 20.], [50., 0.], [60., 20.], [70., 0.], [80., 20.]]
        .iter()
        .map(|p| [p[0], p[1], 0.0])
        .collect();
    let want: Vec<[Vec3; 4]> = akima_beziers(&one)
        .into_iter()
        .chain(akima_beziers(&two))
        .collect();
    for (g, w) in b.iter().zip(&want) {
        for k in 0..4 {
            assert!(close3(g[k], w[k], 1e-9), "{g:?} vs {w:?}");
        }
    }
    // No continuity condition at the common point: both sides end with zero curvature.
    assert!(norm(ds(&b[3], 1.0).1) < 1e-9 && norm(ds(&b[4], 0.0).1) < 1e-9);
    assert!(s.iter().all(|(_, m)| m.feed == 1000.0));
    assert_eq!(b[7][3], [80.0, 20.0, 0.0]);
}

#[test]
fn m_functions_break_a_spline_and_keep_program_order() {
    let cmds = ok("F500 ASPLINE X10\nX20 Y10\nM3 S100\nX30 Y0\nX40 Y5\nG01 X50\n");
    let seq: Vec<String> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::SplineFeed(s) => Some(format!("spline {:?}", s.end.xyz())),
            Canon::StartSpindle { .. } => Some("M3".into()),
            Canon::StraightFeed(l) => Some(format!("line {:?}", l.end.xyz())),
            _ => None,
        })
        .collect();
    assert_eq!(
        seq,
        [
            "spline [10.0, 0.0, 0.0]",
            "spline [20.0, 10.0, 0.0]",
            "M3",
            "spline [30.0, 0.0, 0.0]",
            "spline [40.0, 5.0, 0.0]",
            "line [50.0, 5.0, 0.0]"
        ]
    );
    // The spline after M3 starts anew at (20, 10): zero curvature there.
    let s = splines(&cmds);
    assert!(norm(ds(&bez(&s[2].1), 0.0).1) < 1e-9);
}

#[test]
fn splines_are_forbidden_under_cutter_compensation() {
    let (_, err) = run(
        "G17 G90 F100 T1 D1 M6\nG41 G01 X10 Y0\nASPLINE X20 Y10\n",
        Dialect::Axioma,
    );
    assert_eq!(
        err.unwrap().code.to_string(),
        "axioma::spline-under-compensation"
    );
}

#[test]
fn extra_axes_move_with_each_akima_piece_and_duplicates_split() {
    let cmds = ok_with(
        "F600 ASPLINE X10 C10\nX20 Y5 C20\nX20 Y5 C40\nX30 Y0 C50\n",
        with_c_axis(),
    );
    let pieces: Vec<(Vec3, f64, bool)> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::SplineFeed(s) => Some((s.end.xyz(), s.end.c, true)),
            Canon::StraightFeed(l) => Some((l.end.xyz(), l.end.c, false)),
            _ => None,
        })
        .collect();
    assert_eq!(
        pieces,
        [
            ([10.0, 0.0, 0.0], 10.0, true),
            ([20.0, 5.0, 0.0], 20.0, true),
            ([20.0, 5.0, 0.0], 40.0, false),
            ([30.0, 0.0, 0.0], 50.0, true)
        ]
    );
}

#[test]
fn a_long_spline_streams_in_a_bounded_window() {
    // ASPLINE: the first segment needs P_3; CSPLINE: P_{1+W} (W = 8). Both leave the interpreter
    // after a handful of lines, and every segment comes out.
    for (keyword, max_lines) in [("ASPLINE", 10u64), ("CSPLINE", 16)] {
        let mut text = format!("F1000 {keyword} X1 Y1\n");
        for i in 2..2000 {
            text.push_str(&format!("X{i} Y{}\n", (i % 7) as f64));
        }
        text.push_str("M30\n");
        let mut it = Interpreter::from_text(&text, options(Dialect::Axioma));
        let mut first_at = None;
        for c in it.by_ref() {
            if matches!(c.unwrap().value, Canon::SplineFeed(_)) {
                first_at = Some(it.stats().lines_read);
                break;
            }
        }
        let first_at = first_at.expect("a spline segment");
        assert!(first_at < max_lines, "{keyword}: {first_at} lines read");
        let rest = it
            .filter(|c| matches!(c.as_ref().map(|c| &c.value), Ok(Canon::SplineFeed(_))))
            .count();
        assert_eq!(rest + 1, 1999, "{keyword}");
    }
}
