//! Property tests of AxiOMA arcs: the centre from `CR=` (signed radius) and back — the arc ends on
//! its circle, its sweep is ≤ 180° for CR > 0 and > 180° for CR < 0, and G02/G03 turn the way the
//! manual says (G03 counter-clockwise seen from +Z in G17).

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
        let a = cmds.iter().find_map(|c| match &c.value { Canon::ArcFeed(a) => Some(*a), _ => None }).unwrap();
        let h = Helix { start: a.start.xyz(), end: a.end.xyz(), centre: a.centre, axis: a.axis, turns: a.turns };
        prop_assert!((h.start_radius() - r).abs() < 1e-5, "start radius {} r {r}", h.start_radius());
        prop_assert!((h.end_radius() - r).abs() < 1e-5, "end radius {} r {r}", h.end_radius());
        let pi = std::f64::consts::PI;
        if major { prop_assert!(h.sweep() >= pi - 1e-9) } else { prop_assert!(h.sweep() <= pi + 1e-9) }
        prop_assert_eq!(a.axis[2] > 0.0, ccw);
    }
}
