//! Tools, offsets and compensation (`docs/dialects/mazatrol-eia.md` §8, §9): the M-series G43
//! and G45–G48, G41/G42 on a square, the T-series turret, G96 and G50 S, nose radius with G46.

mod common;
use common::*;
use stanok_canon::{Canon, Pose};

#[test]
fn g43_and_g49_on_the_m_series() {
    let m = mazak_m();
    // G43 H1 Z20: machine Z = 20 − 200 + 150; G44 H1 Z20: 20 − 200 − 150.
    let r = run("G43 H1 Z20.\nG49\nG00 Z20.\nG44 H1 Z20.\n", &m);
    r.ok();
    let z: Vec<f64> = r.ends().iter().map(|p| p.z).collect();
    assert_eq!(z[0], -30.0);
    assert_eq!(*z.last().unwrap(), -330.0);
    // T… M6: with F93 bit 3 the tool's length comes in force.
    let mut m2 = mazak_m();
    m2.params.tool_data_length = true;
    let r = run("T02 M06\nG00 Z0\n", &m2);
    r.ok();
    assert_eq!(r.ends()[0].z, -200.0 + 120.0);
}

#[test]
fn g45_to_g48_lengthen_and_shorten_one_move() {
    // D3 = radius 5: G45 X10 → 15, G46 X10 → 5, G47 → 20, G48 → 0 (from X0, G91).
    let m = mazak_m();
    for (code, want) in [(45, 15.0), (46, 5.0), (47, 20.0), (48, 0.0)] {
        let r = run(
            &format!("G00 X0 Y0 Z0\nG91 G{code} G01 X10. D3 F100.\n"),
            &m,
        );
        r.ok();
        assert_eq!(r.ends()[1].x - 100.0, want, "G{code}");
    }
}

fn tool_path(r: &Run) -> Vec<[f64; 2]> {
    r.ends().iter().map(|p| [p.x, p.y]).collect()
}

fn near2(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
}

#[test]
fn cutter_compensation_around_a_square() {
    // A 40 × 40 square (0,0)…(40,40) clockwise, G41 (tool left = outside), D3 r 5, from (-20, 0).
    let text = "G00 X-20. Y0 Z0\nG41 G01 X0 Y0 D3 F500.\nY40.\nX40.\nY0\nX0\nG40 X-20.\nM30\n";
    let r = run(text, &mill_with_tools());
    r.ok();
    let p = tool_path(&r);
    // Start-up (type A) to (−5, 0): perpendicular to the first side (X0 → Y40).
    assert!(near2(p[1], [-5.0, 0.0]), "{p:?}");
    // The first side ends at (−5, 40), then a convex arc about (0, 40) to (0, 45).
    assert!(near2(p[2], [-5.0, 40.0]), "{p:?}");
    assert!(near2(p[3], [0.0, 45.0]), "{p:?}");
    let arcs: Vec<[f64; 3]> = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(a.centre),
            _ => None,
        })
        .collect();
    assert_eq!(arcs[0], [0.0, 40.0, 0.0]);
    assert_eq!(arcs.len(), 3, "three convex corners before the cancel");
    // The last side ends at its perpendicular point (0, −5); the cancel goes to (−20, 0).
    let n = p.len();
    assert!(near2(p[n - 2], [0.0, -5.0]), "{p:?}");
    assert!(near2(p[n - 1], [-20.0, 0.0]), "{p:?}");
    // G42 (inside): concave corners meet at the intersections (5, 35), (35, 35), (35, 5).
    let text = "G00 X-20. Y0 Z0\nG42 G01 X0 Y0 D3 F500.\nY40.\nX40.\nY0\nX0\nG40 X-20.\nM30\n";
    let r = run(text, &mill_with_tools());
    r.ok();
    let p = tool_path(&r);
    assert!(near2(p[1], [5.0, 0.0]), "{p:?}");
    assert!(near2(p[2], [5.0, 35.0]), "{p:?}");
    assert!(near2(p[3], [35.0, 35.0]), "{p:?}");
    assert!(near2(p[4], [35.0, 5.0]), "{p:?}");
}

#[test]
fn a_move_off_the_plane_ends_the_look_ahead_with_a_warning() {
    // The Z move between Y40. and X40. ends the first side at its perpendicular point (−5, 40)
    // and the next side starts again from there (to the offset start (0, 45) of the side after).
    let text = "G00 X-20. Y0 Z0\nG41 G01 X0 Y0 D3 F500.\nY40.\nZ-1.\nX40.\nY0\nG40 X-20.\nM30\n";
    let r = run(text, &mill_with_tools());
    r.ok();
    assert!(
        r.warnings
            .iter()
            .any(|w| w.code.to_string() == "mazatrol::compensation-gap"),
        "{:?}",
        r.warnings
    );
    let p = tool_path(&r);
    assert!(near2(p[2], [-5.0, 40.0]), "{p:?}");
    // Without the Z move there is no warning.
    let r = run(
        "G00 X-20. Y0 Z0\nG41 G01 X0 Y0 D3 F500.\nY40.\nX40.\nG40 X60.\nM30\n",
        &mill_with_tools(),
    );
    assert!(r.ok().warnings.is_empty(), "{:?}", r.warnings);
}

#[test]
fn compensation_refusals() {
    // A concave arc smaller than the tool.
    let text = "G00 X-20. Y0\nG42 G01 X0 Y0 D3 F500.\nY10.\nG02 X4. Y14. R4.\nG01 X20.\n";
    let e = run(text, &mill_with_tools()).error.unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::compensation");
    // A start-up with an arc.
    let e = run(
        "G00 X0 Y0\nG41 D3\nG02 X10. Y0 R5. F100.\n",
        &mill_with_tools(),
    )
    .error
    .unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::compensation");
    // A cycle under compensation.
    let e = run("G41 D3\nG81 X1. Y1. Z-1. R1. F100.\n", &mill_with_tools())
        .error
        .unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::compensation");
}

/// The plain mill with tool 3 (r 5).
fn mill_with_tools() -> Machine {
    let mut m = mill();
    m.opts.control.tools = mazak_m().opts.control.tools;
    m
}

#[test]
fn the_t_series_turret() {
    let m = mazak_t();
    // T0101: X20 (radius) Z80 offsets; X diameter 60 → radius 30 → machine 50.
    let r = run(
        "T0101\nG00 X60. Z0\nT0100\nG00 X60. Z0\nT0202\nG00 X60. Z0\n",
        &m,
    );
    r.ok();
    let e = r.ends();
    assert_eq!((e[0].x, e[0].z), (50.0, 280.0));
    assert_eq!((e[1].x, e[1].z), (30.0, 200.0));
    assert_eq!((e[2].x, e[2].z), (30.0, 300.0));
    let tools: Vec<u32> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::ChangeTool { tool, .. } => Some(tool),
            _ => None,
        })
        .collect();
    assert_eq!(tools, vec![1, 2]);
    // G122.1: X on the radius; U incremental on the diameter.
    let r = run("T0100\nG122.1\nG00 X60. Z0\nG123.1\nU-20.\n", &m);
    r.ok();
    let e = r.ends();
    assert_eq!(e[0].x, 60.0);
    assert_eq!(e[1].x, 50.0);
    let e = run("G00 X10. U2.\n", &m).error.unwrap();
    assert_eq!(e.message, "X and U both command X");
}

#[test]
fn constant_surface_speed_and_its_clamp() {
    let m = mazak_t();
    // G96 S200 at D62 (radius 31): 200 000 / (π·62) = 1026.806 rpm; at D20: 3183.1 → G50 S2500.
    let r = run("G50 S2500\nG96 S200. M03\nG00 X62. Z0\nX20.\n", &m);
    r.ok();
    let speeds: Vec<f64> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::SetSpindleSpeed { spindle: 0, rpm } => Some(rpm),
            _ => None,
        })
        .collect();
    assert!(
        speeds.iter().any(|v| (v - 1026.806).abs() < 1e-3),
        "{speeds:?}"
    );
    assert!((speeds.last().unwrap() - 2500.0).abs() < 1e-9, "{speeds:?}");
    let law = r.canon.iter().find_map(|c| match &c.value {
        Canon::SetSurfaceSpeedLaw { law: Some(l), .. } => Some(*l),
        _ => None,
    });
    let l = law.unwrap();
    assert_eq!((l.mm_per_min, l.max_rpm), (200_000.0, 2500.0));
    let e = run("G96 M03\n", &m).error.unwrap();
    assert_eq!(e.message, "G96 needs a surface speed S");
}

#[test]
fn nose_radius_compensation_with_g46() {
    let m = mazak_t();
    // Offset 1: nose 0.8, tip 3 (the imaginary tip at (−r, −r) of the centre in (Z, X)).
    // Turning along −Z at X40 (radius 20): G46 picks G42, the centre runs 0.8 above the
    // contour (radius 20.8) and the controlled point is the centre − (0.8, 0.8) in (Z, X):
    // radius 20.0 — on a straight cylinder the imaginary tip stays on the contour.
    let text = "T0101\nG00 X50. Z5.\nG46 G01 X40. Z2. F0.1\nZ-20.\nX50.\nG40 G00 X60.\nM30\n";
    let r = run(text, &m);
    r.ok();
    let e = r.ends();
    // The cylinder Z2 → Z-20 at radius 20: machine X = 20 + 20 (offset) = 40.
    let cyl: Vec<&Pose> = e.iter().filter(|p| (p.x - 40.0).abs() < 1e-9).collect();
    assert!(!cyl.is_empty(), "{e:?}");
}

#[test]
fn g50_and_g92_on_the_t_series() {
    let m = mazak_t();
    // G53 X100. (a diameter like every X) puts the tool at machine radius 50, Z 300; G50 X100.
    // Z50. makes that point program (D100, Z50); X80. Z40. is then radius 40, Z 290.
    let r = run(
        "T0100\nG53 X100. Z300.\nG50 X100. Z50.\nG00 X80. Z40.\n",
        &m,
    );
    r.ok();
    let e = r.ends();
    assert_eq!((e[0].x, e[0].z), (50.0, 300.0));
    assert_eq!((e[1].x, e[1].z), (40.0, 290.0));
}
