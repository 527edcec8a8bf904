//! Property tests of the spline constructions: Akima and cubic splines pass through their points
//! exactly; a NURBS with all weights 1 is the B-spline of an independent Cox–de Boor evaluation;
//! tessellation stays within its chord tolerance of the exact curve.

use proptest::prelude::*;
use stanok_geom::akima::{akima_beziers, bezier_derivatives, Window};
use stanok_geom::cubic_spline::{solve_tangents, windowed_tangents};
use stanok_geom::{
    bezier_knots, bezier_pieces, bezier_point, hermite_bezier, norm, sub, Nurbs, Vec3,
};

/// Points with consecutive chords of at least 0.5 mm (the interpreter removes repeats).
fn polyline() -> impl Strategy<Value = Vec<Vec3>> {
    prop::collection::vec((-100.0f64..100.0, -100.0f64..100.0, -20.0f64..20.0), 2..14)
        .prop_map(|v| {
            let mut out: Vec<Vec3> = Vec::new();
            for (x, y, z) in v {
                let p = [x, y, z];
                if out.last().is_none_or(|q| norm(sub(p, *q)) >= 0.5) {
                    out.push(p);
                }
            }
            out
        })
        .prop_filter("two points at least", |v| v.len() >= 2)
}

fn close(a: Vec3, b: Vec3, tol: f64) -> bool {
    norm(sub(a, b)) <= tol
}

/// Cox–de Boor basis N_{i,p}(u) by the recursive definition (0/0 = 0; the last span closed).
fn basis(i: usize, p: usize, u: f64, t: &[f64]) -> f64 {
    if p == 0 {
        let last = t[t.len() - 1];
        let inside = t[i] <= u && u < t[i + 1];
        let at_end = u == last && t[i] < t[i + 1] && t[i + 1] == last;
        return if inside || at_end { 1.0 } else { 0.0 };
    }
    let mut v = 0.0;
    let d1 = t[i + p] - t[i];
    if d1 > 0.0 {
        v += (u - t[i]) / d1 * basis(i, p - 1, u, t);
    }
    let d2 = t[i + p + 1] - t[i + 1];
    if d2 > 0.0 {
        v += (t[i + p + 1] - u) / d2 * basis(i + 1, p - 1, u, t);
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn akima_interpolates_every_point_with_c1_joints(pts in polyline()) {
        let b = akima_beziers(&pts);
        prop_assert_eq!(b.len(), pts.len() - 1);
        for (i, seg) in b.iter().enumerate() {
            prop_assert!(close(bezier_point(seg, 0.0), pts[i], 1e-9));
            prop_assert!(close(bezier_point(seg, 1.0), pts[i + 1], 1e-9));
        }
        for i in 0..b.len().saturating_sub(1) {
            let h0 = norm(sub(pts[i + 1], pts[i]));
            let h1 = norm(sub(pts[i + 2], pts[i + 1]));
            let t0 = bezier_derivatives(&b[i], 1.0).0.map(|v| v / h0);
            let t1 = bezier_derivatives(&b[i + 1], 0.0).0.map(|v| v / h1);
            prop_assert!(close(t0, t1, 1e-7), "joint {}: {:?} {:?}", i + 1, t0, t1);
        }
    }

    #[test]
    fn akima_window_equals_whole_spline(pts in polyline(), cut in 0usize..10) {
        // Tangent i from the window P_{i−3} … P_{i+3} (with the real ends flagged) is the
        // whole-spline tangent (inner tangents need P_{i−2} … P_{i+2}, the natural end tangents
        // one more): the locality the interpreter's bounded buffer relies on.
        let whole = Window::whole(&pts);
        let i = cut.min(pts.len() - 1);
        let lo = i.saturating_sub(3);
        let hi = (i + 3).min(pts.len() - 1);
        let w = Window { points: &pts[lo..=hi], starts: lo == 0, ends: hi == pts.len() - 1 };
        prop_assert!(close(w.tangent(i - lo), whole.tangent(i), 1e-9));
    }

    #[test]
    fn cubic_interpolates_and_is_c2_globally(pts in polyline()) {
        let t = solve_tangents(&pts, None);
        let segs: Vec<[Vec3; 4]> = (0..pts.len() - 1)
            .map(|i| hermite_bezier(pts[i], t[i], pts[i + 1], t[i + 1]))
            .collect();
        for (i, seg) in segs.iter().enumerate() {
            prop_assert!(close(bezier_point(seg, 0.0), pts[i], 1e-9));
            prop_assert!(close(bezier_point(seg, 1.0), pts[i + 1], 1e-9));
        }
        for i in 0..segs.len().saturating_sub(1) {
            let h0 = norm(sub(pts[i + 1], pts[i]));
            let h1 = norm(sub(pts[i + 2], pts[i + 1]));
            let k0 = bezier_derivatives(&segs[i], 1.0).1.map(|v| v / (h0 * h0));
            let k1 = bezier_derivatives(&segs[i + 1], 0.0).1.map(|v| v / (h1 * h1));
            let scale = norm(k0).max(norm(k1)).max(1.0);
            prop_assert!(norm(sub(k0, k1)) <= 1e-6 * scale, "joint {}", i + 1);
        }
        // A window wider than the spline is the global spline.
        let w = windowed_tangents(&pts, pts.len() + 1);
        for (a, b) in w.iter().zip(&t) {
            prop_assert!(close(*a, *b, 1e-7));
        }
    }

    #[test]
    fn nurbs_with_unit_weights_is_the_cox_de_boor_b_spline(
        pts in prop::collection::vec((-50.0f64..50.0, -50.0f64..50.0, -50.0f64..50.0), 4..10),
        incs in prop::collection::vec(0.1f64..2.0, 10),
        degree in 1usize..4,
        us in prop::collection::vec(0.0f64..=1.0, 8),
    ) {
        let cps: Vec<Vec3> = pts.iter().map(|&(x, y, z)| [x, y, z]).collect();
        let n = cps.len();
        prop_assume!(n > degree);
        let mut knots = vec![0.0; degree + 1];
        for inc in &incs[..n - degree - 1] {
            let last = knots[knots.len() - 1];
            knots.push(last + inc);
        }
        let end = knots[knots.len() - 1] + incs[9];
        knots.extend(std::iter::repeat_n(end, degree + 1));
        let w = vec![1.0; n];
        let c = Nurbs::new(degree as u8, &cps, &w, &knots);
        prop_assert!(c.validate().is_ok());
        for u in us {
            let u = u * end;
            let mut want = [0.0; 3];
            for (i, p) in cps.iter().enumerate() {
                let b = basis(i, degree, u, &knots);
                for k in 0..3 {
                    want[k] += b * p[k];
                }
            }
            prop_assert!(close(c.point_at(u), want, 1e-9), "u {}: {:?} vs {:?}", u, c.point_at(u), want);
        }
    }

    #[test]
    fn tessellation_stays_within_the_chord_tolerance(pts in polyline(), tol_exp in 1u32..4) {
        let tol = 10f64.powi(-(tol_exp as i32));
        let knots = bezier_knots(3);
        let w = [1.0; 4];
        for seg in akima_beziers(&pts) {
            let c = Nurbs::new(3, &seg, &w, &knots);
            let mut poly = Vec::new();
            c.tessellate(tol, &mut poly);
            prop_assert!(close(poly[0], seg[0], 1e-9) && close(poly[poly.len() - 1], seg[3], 1e-9));
            // Every exact point lies within tol of the polyline (sampled finely).
            for k in 0..=400 {
                let p = c.point_at(k as f64 / 400.0);
                let d = poly
                    .windows(2)
                    .map(|s| stanok_geom::distance_to_segment(p, s[0], s[1]))
                    .fold(f64::INFINITY, f64::min);
                prop_assert!(d <= tol * 1.000001, "deviation {} > {}", d, tol);
            }
        }
    }

    #[test]
    fn bezier_pieces_are_the_same_curve(
        pts in prop::collection::vec((-50.0f64..50.0, -50.0f64..50.0, -50.0f64..50.0), 4..10),
        ws in prop::collection::vec(0.2f64..3.0, 10),
        incs in prop::collection::vec(prop_oneof![Just(0.0), 0.1f64..2.0], 10),
        degree in 2usize..4,
        us in prop::collection::vec(0.0f64..=1.0, 6),
    ) {
        let cps: Vec<Vec3> = pts.iter().map(|&(x, y, z)| [x, y, z]).collect();
        let n = cps.len();
        prop_assume!(n > degree);
        // Inner knots with multiplicity ≤ degree (runs of zero increments shorter than degree).
        let mut knots = vec![0.0; degree + 1];
        let mut run = 0;
        // (Clamped ends: the first inner increment is not 0, as the AxiOMA knot rules demand.)
        for (j, inc) in incs[..n - degree - 1].iter().enumerate() {
            let inc = if *inc == 0.0 && (j == 0 || run + 2 > degree) { 1.0 } else { *inc };
            run = if inc == 0.0 { run + 1 } else { 0 };
            let last = knots[knots.len() - 1];
            knots.push(last + inc);
        }
        let end = knots[knots.len() - 1] + 1.0;
        knots.extend(std::iter::repeat_n(end, degree + 1));
        let w = &ws[..n];
        let c = Nurbs::new(degree as u8, &cps, w, &knots);
        prop_assert!(c.validate().is_ok(), "{:?}", knots);
        let pieces = bezier_pieces(degree as u8, &cps, w, &knots);
        let spans = knots.windows(2).filter(|k| k[1] > k[0]).count();
        prop_assert_eq!(pieces.len(), spans);
        let bk = bezier_knots(degree);
        for piece in &pieces {
            let b = Nurbs::new(degree as u8, &piece.points, &piece.weights, &bk);
            for &s in &us {
                let u = piece.from + s * (piece.to - piece.from);
                prop_assert!(close(b.point_at(s), c.point_at(u), 1e-7), "u {}", u);
            }
        }
        // Consecutive pieces join.
        for pair in pieces.windows(2) {
            prop_assert!(close(pair[0].points[degree], pair[1].points[0], 1e-7));
        }
    }
}

/// The case the property test once drew (to the printed 3 decimals): a cubic piece that turns
/// sharply, where the sampled flatness test let a chord deviate 0.109 mm at a 0.1 mm tolerance.
/// With the convex-hull bound no point of the curve is farther than the tolerance from the chords.
#[test]
fn a_sharply_turning_piece_stays_within_the_chord_tolerance() {
    let pts: Vec<Vec3> = vec![
        [-8.797, -41.097, 0.0],
        [18.089, -29.136, -6.176],
        [-72.062, 85.509, 9.823],
        [27.797, -39.214, -9.129],
        [0.0, 0.0, 0.0],
    ];
    let knots = bezier_knots(3);
    let w = [1.0; 4];
    for tol in [0.1, 0.01, 0.001] {
        for seg in akima_beziers(&pts) {
            let c = Nurbs::new(3, &seg, &w, &knots);
            let mut poly = Vec::new();
            c.tessellate(tol, &mut poly);
            let mut worst: f64 = 0.0;
            for k in 0..=20_000 {
                let p = c.point_at(k as f64 / 20_000.0);
                let d = poly
                    .windows(2)
                    .map(|s| stanok_geom::distance_to_segment(p, s[0], s[1]))
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(d);
            }
            assert!(worst <= tol, "deviation {worst} > {tol}");
        }
    }
}
