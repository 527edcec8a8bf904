//! Property tests of AxiOMA arcs: the centre from `CR=` (signed radius) and back — the arc ends on
//! its circle, its sweep is ≤ 180° for CR > 0 and > 180° for CR < 0, and G02/G03 turn the way the
//! manual says (G03 counter-clockwise seen from +Z in G17).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use proptest::prelude::*;
use stanok_canon::Canon;
use stanok_geom::Helix;
use stanok_syntax::Dialect;

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]

    #[test]
    fn cr_centre_round_trip(x in -80.0f64..80.0, y in -80.0f64..80.0, extra in 0.01f64..50.0,
                            major in any::<bool>(), ccw in any::<bool>()) {
        let chord = x.hypot(y);
        prop_assume!(chord > 0.05);
        let r = chord / 2.0 + extra;
        let cr = if major { -r } else { r };
        let text = format!("G17 G90 G191 G71 F500\nN10 G0{} X{x:.6} Y{y:.6} CR={cr:.6}\nM30\n", if ccw { 3 } else { 2 });
        let (cmds, err) = run(&text, Dialect::Axioma);
        prop_assert!(err.is_none(), "{err:?}");
        let a = cmds.iter().find_map(|c| match &c.value { Canon::ArcFeed(a) => Some(a.clone()), _ => None }).unwrap();
        let h = Helix { start: a.start.xyz(), end: a.end.xyz(), centre: a.centre, axis: a.axis, turns: a.turns };
        prop_assert!((h.start_radius() - r).abs() < 1e-5, "start radius {} r {r}", h.start_radius());
        prop_assert!((h.end_radius() - r).abs() < 1e-5, "end radius {} r {r}", h.end_radius());
        let pi = std::f64::consts::PI;
        if major { prop_assert!(h.sweep() >= pi - 1e-9) } else { prop_assert!(h.sweep() <= pi + 1e-9) }
        prop_assert_eq!(a.axis[2] > 0.0, ccw);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, .. ProptestConfig::default() })]

    /// Mirror, scale and rotation act in the fixed order M → S → Rot whatever order the program
    /// switches them on in (spec axioma-1 §11.5), and the point maps back through the inverse.
    #[test]
    fn frames_apply_in_fixed_order(order in Just([0usize, 1, 2]).prop_shuffle(),
                                   mx in any::<bool>(), my in any::<bool>(),
                                   k in 0.25f64..4.0, q in -180.0f64..180.0,
                                   pole in prop::array::uniform2(-50.0f64..50.0),
                                   x in -100.0f64..100.0, y in -100.0f64..100.0) {
        let blocks = [
            format!("G73 X{} Y{} I{:.4} J{:.4}\n", if mx { -1 } else { 1 }, if my { -1 } else { 1 }, pole[0], pole[1]),
            format!("G173 P{k:.4} I{:.4} J{:.4}\n", pole[0], pole[1]),
            format!("G273 Q{q:.4} I{:.4} J{:.4}\n", pole[0], pole[1]),
        ];
        let mut text = String::from("G17 G90 G190 F100\n");
        for &i in &order {
            text.push_str(&blocks[i]);
        }
        text.push_str(&format!("G01 X{x:.4} Y{y:.4}\nM30\n"));
        let (cmds, err) = run(&text, Dialect::Axioma);
        prop_assert!(err.is_none(), "{err:?}");
        let end = cmds.iter().rev().find_map(|c| c.value.motion().map(|m| m.end())).unwrap();
        // Reference: the formula of §11 with the rounded values the program carries.
        let r4 = |v: f64| (v * 1e4).round() / 1e4;
        let (px, py, k, q) = (r4(pole[0]), r4(pole[1]), r4(k), r4(q));
        let (x, y) = (r4(x), r4(y));
        let (mxv, myv) = (if mx { -1.0 } else { 1.0 }, if my { -1.0 } else { 1.0 });
        let (ax, ay) = (px + mxv * (x - px), py + myv * (y - py));
        let (bx, by) = (px + k * (ax - px), py + k * (ay - py));
        let (s, c) = q.to_radians().sin_cos();
        let (ex, ey) = (px + (bx - px) * c - (by - py) * s, py + (bx - px) * s + (by - py) * c);
        prop_assert!((end.x - ex).abs() < 1e-6 && (end.y - ey).abs() < 1e-6, "{:?} vs ({ex}, {ey})", end);
    }
}
