//! Every AxiOMA fixture of the pipeline-foundation scope (corpus/axioma s2_*, s4_7_*, s4_8_*, s5_1*,
//! s5_2*, s5_3*, s5_6*) run through the interpreter, with the end points, centres, radii, sweeps,
//! lengths and times its header states asserted. Tolerance 1e-3 mm (1e-3 s, 0.01° for sweeps given
//! to two decimals) unless a test says otherwise. Lathe fixtures (G18) state points as (X, Z).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{Canon, Plane, Spanned};
use stanok_geom::Helix;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-3;

#[derive(Debug, Clone)]
struct Mv {
    /// N label of the block.
    n: Option<u32>,
    rapid: bool,
    arc: Option<Arc>,
    start: [f64; 3],
    end: [f64; 3],
    feed: f64,
}

#[derive(Debug, Clone, Copy)]
struct Arc {
    centre: [f64; 3],
    /// Signed sweep in degrees: positive = counter-clockwise about the plane normal.
    sweep_deg: f64,
    radius: f64,
    length: f64,
}

impl Mv {
    fn length(&self) -> f64 {
        match self.arc {
            Some(a) => a.length,
            None => (0..3)
                .map(|k| (self.end[k] - self.start[k]).powi(2))
                .sum::<f64>()
                .sqrt(),
        }
    }
    /// Nominal time of a feed move, s.
    fn time(&self) -> f64 {
        self.length() / self.feed * 60.0
    }
}

fn program(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn run_fixture(name: &str) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run(&program(name), Dialect::Axioma);
    if let Some(e) = err {
        panic!("{name}: unexpected error {e}");
    }
    cmds
}

fn motions(cmds: &[Spanned<Canon>]) -> Vec<Mv> {
    cmds.iter()
        .filter_map(|c| {
            let n = c.block_number;
            match &c.value {
                Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Some(Mv {
                    n,
                    rapid: matches!(c.value, Canon::StraightTraverse(_)),
                    arc: None,
                    start: m.start.xyz(),
                    end: m.end.xyz(),
                    feed: m.feed,
                }),
                Canon::ArcFeed(a) => {
                    let h = Helix {
                        start: a.start.xyz(),
                        end: a.end.xyz(),
                        centre: a.centre,
                        axis: a.axis,
                        turns: a.turns,
                    };
                    let normal = match a.plane {
                        Plane::XY => a.axis[2],
                        Plane::ZX => a.axis[1],
                        Plane::YZ => a.axis[0],
                    };
                    Some(Mv {
                        n,
                        rapid: false,
                        arc: Some(Arc {
                            centre: a.centre,
                            sweep_deg: h.sweep().to_degrees() * normal.signum(),
                            radius: h.start_radius(),
                            length: h.length(),
                        }),
                        start: a.start.xyz(),
                        end: a.end.xyz(),
                        feed: a.feed,
                    })
                }
                _ => None,
            }
        })
        .collect()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[track_caller]
fn assert_xyz(got: [f64; 3], want: [f64; 3], tol: f64) {
    assert!(
        (0..3).all(|k| close(got[k], want[k], tol)),
        "got {got:?}, want {want:?} (±{tol})"
    );
}

/// Lathe point (X, Z) as machine XYZ.
fn xz(x: f64, z: f64) -> [f64; 3] {
    [x, 0.0, z]
}

fn by_n(mvs: &[Mv], n: u32) -> &Mv {
    mvs.iter()
        .find(|m| m.n == Some(n))
        .unwrap_or_else(|| panic!("no motion in N{n}: {mvs:#?}"))
}

fn ends(mvs: &[Mv]) -> Vec<[f64; 3]> {
    mvs.iter().map(|m| m.end).collect()
}

#[track_caller]
fn assert_path(mvs: &[Mv], want: &[[f64; 3]]) {
    let got = ends(mvs);
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert_xyz(*g, *w, TOL);
    }
}

// ---------------------------------------------------------------------------------------- §2

#[test]
fn s2_2_block_words() {
    let cmds = run_fixture("s2_2-block-words-example.nc");
    let mvs = motions(&cmds);
    let arc = by_n(&mvs, 10).arc.unwrap();
    assert_xyz(arc.centre, [25.0, 0.0, 0.0], TOL);
    assert!(close(arc.radius, 25.0, TOL));
    assert!(close(arc.sweep_deg, -180.0, 1e-6), "{}", arc.sweep_deg);
    assert_xyz(by_n(&mvs, 10).end, [50.0, 0.0, 0.0], TOL);
    assert!(close(by_n(&mvs, 10).feed, 2000.0, 1e-9));
    // M06 and M03 are prefix functions: both act before the arc; spindle group (1) before tool (3).
    let kinds: Vec<&str> = cmds
        .iter()
        .filter(|c| c.block_number == Some(10))
        .map(|c| match c.value {
            Canon::SetSpindleSpeed { rpm, .. } => {
                assert_eq!(rpm, 10000.0);
                "S"
            }
            Canon::StartSpindle { .. } => "M3",
            Canon::SelectTool { tool } => {
                assert_eq!(tool, 2);
                "T"
            }
            Canon::ChangeTool { tool, .. } => {
                assert_eq!(tool, 2);
                "M6"
            }
            Canon::ArcFeed(_) => "G02",
            Canon::SetFeedRate { .. } => "F",
            _ => "other",
        })
        .collect();
    assert_eq!(kinds, ["F", "S", "M3", "T", "M6", "G02"]);
}

#[test]
fn s2_3_msg_and_dwell() {
    let cmds = run_fixture("s2_3-msg-example-2_1.nc");
    let seq: Vec<String> = cmds
        .iter()
        .filter_map(|c| {
            let n = c.block_number?;
            Some(match &c.value {
                Canon::Message { text } => format!("N{n} MSG {text:?}"),
                Canon::Dwell { seconds } => format!("N{n} G04 {seconds}"),
                Canon::StraightTraverse(m) => format!("N{n} G00 {:?}", m.end.xyz()),
                Canon::StraightFeed(m) => format!("N{n} G01 {:?} F{}", m.end.xyz(), m.feed),
                Canon::ChangeTool { tool, .. } => format!("N{n} M6 T{tool}"),
                Canon::ProgramEnd => format!("N{n} M30"),
                _ => return None,
            })
        })
        .collect();
    assert_eq!(
        seq,
        [
            "N10 G00 [50.0, 0.0, 0.0]",
            "N20 M6 T3",
            "N30 MSG \"Tool T3 is active\"",
            "N40 G04 5",
            "N50 G00 [50.0, 0.0, -38.0]",
            "N60 G01 [30.0, 0.0, -38.0] F500",
            "N70 MSG \"\"",
            "N80 G04 10",
            "N90 M30",
        ]
    );
}

#[test]
fn s2_3_sprintf_formats_the_message_value_50() {
    // `string str; long num = 50; sprintf(str, "value: %d", num); N10 MSG(str)`: the operator
    // message "value: 50" at N10 (line 19), and nothing else.
    let (cmds, err) = run(&program("s2_3-sprintf-msg-fragment.nc"), Dialect::Axioma);
    assert!(err.is_none(), "{err:?}");
    let messages: Vec<(u32, Option<u32>, &str)> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::Message { text } => Some((c.span.line, c.block_number, text.as_str())),
            _ => None,
        })
        .collect();
    assert_eq!(messages, [(19, Some(10), "value: 50")]);
    assert!(motions(&cmds).is_empty());
}

// ---------------------------------------------------------------------------------------- §4.7

const RECTANGLE: [[f64; 3]; 5] = [
    [60.0, 80.0, 0.0],
    [140.0, 80.0, 0.0],
    [140.0, 20.0, 0.0],
    [60.0, 20.0, 0.0],
    [60.0, 80.0, 0.0],
];

#[test]
fn s4_7_absolute_and_incremental_milling_draw_the_same_rectangle() {
    for name in [
        "s4_7_1-absolute-milling-example-4_13.nc",
        "s4_7_2-incremental-milling-example-4_15.nc",
    ] {
        let mvs = motions(&run_fixture(name));
        assert_path(&mvs, &RECTANGLE);
        assert!(
            mvs[0].rapid && mvs[1..].iter().all(|m| !m.rapid && m.feed == 1000.0),
            "{name}"
        );
    }
}

#[test]
fn s4_7_absolute_and_incremental_turning_give_the_same_contour() {
    let want = [
        xz(12.5, 0.0),
        xz(12.5, -7.5),
        xz(20.0, -15.0),
        xz(20.0, -25.0),
        xz(30.0, -35.0),
    ];
    for name in [
        "s4_7_1-absolute-turning-example-4_14.nc",
        "s4_7_2-incremental-turning-example-4_16.nc",
    ] {
        assert_path(&motions(&run_fixture(name)), &want);
    }
}

// ---------------------------------------------------------------------------------------- §4.8

#[test]
fn s4_8_absolute_and_relative_centre_full_circle() {
    for name in [
        "s4_8_1-absolute-centre-milling-example-4_17.nc",
        "s4_8_2-relative-centre-milling-example-4_19.nc",
    ] {
        let mvs = motions(&run_fixture(name));
        let m = by_n(&mvs, 30);
        let a = m.arc.unwrap();
        assert_xyz(a.centre, [60.0, 40.0, 0.0], TOL);
        assert!(close(a.radius, 20.0, TOL));
        assert!(close(a.sweep_deg, -360.0, 1e-6), "{name}: {}", a.sweep_deg);
        assert_xyz(m.end, [40.0, 40.0, 0.0], TOL);
    }
}

/// Examples 4.18, 4.20 and 5.6 (the same arc with an absolute or a relative centre) and 5.8 (R30).
#[test]
fn turning_arc_x35_z75_all_forms() {
    for name in [
        "s4_8_1-absolute-centre-turning-example-4_18.nc",
        "s4_8_2-relative-centre-turning-example-4_20.nc",
        "s5_3_1-arc-centre-ijk-relative-turning-example-5_6.nc",
        "s5_3_2-arc-radius-turning-example-5_8.nc",
    ] {
        let mvs = motions(&run_fixture(name));
        let m = by_n(&mvs, 40);
        let a = m.arc.unwrap();
        // The centre words give (X13.33, Z−54.25) with radii 30.0009/30.0025; Stanok moves the
        // centre onto the bisector of the chord (spec axioma-2 §2.3.8), which for R30 is
        // (X13.3336, Z−54.2499): all four forms agree within 0.01 mm.
        assert_xyz(a.centre, xz(13.3336, -54.2499), 0.01);
        assert!(close(a.radius, 30.0, 0.002), "{name}: r {}", a.radius);
        assert!(
            close(a.sweep_deg, 120.92, 0.02),
            "{name}: sweep {}",
            a.sweep_deg
        );
        assert_xyz(m.end, xz(35.0, -75.0), TOL);
        // Highest point of the arc: X = 13.33 + 30 = 43.33 at Z −54.25.
        let top = 13.3336 + a.radius;
        assert!(close(top, 43.33, 0.01));
        assert_xyz(by_n(&mvs, 50).end, xz(35.0, -95.0), TOL);
        if name.contains("5_8") {
            assert!(close(a.length, 63.315, TOL), "{}", a.length);
        }
    }
}

// ---------------------------------------------------------------------------------------- §5.1, §5.2

#[test]
fn s5_1_rapid_milling() {
    let mvs = motions(&run_fixture(
        "s5_1-rapid-positioning-milling-example-5_1.nc",
    ));
    let last = mvs.last().unwrap();
    assert!(last.rapid);
    assert_xyz(last.end, [50.0, 50.0, 0.0], TOL);
}

/// Examples 5.2 and 5.4: G94 then G95 (F0.2 mm/rev × 500 rpm = 100 mm/min).
#[test]
fn s5_1_and_s5_2_turning_feed_types_and_times() {
    for name in [
        "s5_1-rapid-positioning-turning-example-5_2.nc",
        "s5_2-linear-interpolation-turning-example-5_4.nc",
    ] {
        let mvs = motions(&run_fixture(name));
        assert_xyz(by_n(&mvs, 15).end, xz(60.0, 20.0), TOL);
        assert_xyz(by_n(&mvs, 20).end, xz(12.5, 5.0), TOL);
        let n30 = by_n(&mvs, 30);
        assert!(close(n30.feed, 1000.0, 1e-9) && close(n30.time(), 0.300, TOL));
        let n40 = by_n(&mvs, 40);
        assert!(close(n40.feed, 100.0, 1e-9), "{name}: {}", n40.feed);
        assert!(close(n40.time(), 4.500, TOL));
        assert!(close(by_n(&mvs, 50).length(), 32.596, TOL));
        assert!(close(by_n(&mvs, 50).time(), 19.558, TOL));
        assert!(close(by_n(&mvs, 60).time(), 9.000, TOL));
        assert!(by_n(&mvs, 70).rapid, "G95 does not affect G00");
        assert_xyz(mvs.last().unwrap().end, xz(60.0, 20.0), TOL);
    }
}

#[test]
fn s5_2_linear_milling_times_and_postfix_m5() {
    let cmds = run_fixture("s5_2-linear-interpolation-milling-example-5_3.nc");
    let mvs = motions(&cmds);
    assert!(close(by_n(&mvs, 20).time(), 0.9, TOL));
    for n in [30, 40, 50] {
        assert!(close(by_n(&mvs, n).time(), 3.0, TOL), "N{n}");
    }
    assert_xyz(mvs.last().unwrap().end, [0.0, 0.0, 10.0], TOL);
    // M5 is postfix: the spindle stops after the N70 move.
    let n70: Vec<&Canon> = cmds
        .iter()
        .filter(|c| c.block_number == Some(70))
        .map(|c| &c.value)
        .collect();
    assert!(matches!(n70[0], Canon::StraightTraverse(_)));
    assert!(matches!(n70[1], Canon::StopSpindle { spindle: 0 }));
}

// ---------------------------------------------------------------------------------------- §5.3

#[test]
fn s5_3_1_absolute_centre_half_circle() {
    let mvs = motions(&run_fixture(
        "s5_3_1-arc-centre-ijk-absolute-milling-example-5_5.nc",
    ));
    let m = by_n(&mvs, 40);
    let a = m.arc.unwrap();
    assert_xyz(a.centre, [45.0, 45.0, -5.0], TOL);
    assert!(close(a.radius, 25.0, TOL));
    assert!(close(a.sweep_deg, 180.0, 1e-6));
    assert!(close(a.length, 78.540, TOL));
    assert!(close(m.time(), 4.712, TOL));
    assert_xyz(m.end, [45.0, 20.0, -5.0], TOL);
}

#[test]
fn s5_3_2_radius_quarter_arcs() {
    let mvs = motions(&run_fixture("s5_3_2-arc-radius-example-5_7.nc"));
    for (n, centre, end) in [
        (40, [30.0, 60.0], [20.0, 60.0]),
        (60, [30.0, 30.0], [30.0, 20.0]),
    ] {
        let m = by_n(&mvs, n);
        let a = m.arc.unwrap();
        assert_xyz(a.centre, [centre[0], centre[1], -5.0], TOL);
        assert!(close(a.sweep_deg, 90.0, 1e-6), "N{n}: {}", a.sweep_deg);
        assert!(close(a.length, 15.708, TOL));
        assert_xyz(m.end, [end[0], end[1], -5.0], TOL);
    }
}

#[test]
fn s5_3_3_cr_sign_selects_minor_or_major_arc() {
    let mvs = motions(&run_fixture("s5_3_3-arc-cr-signed-radius-example-5_9.nc"));
    let n20 = by_n(&mvs, 20).arc.unwrap();
    assert_xyz(n20.centre, [49.8568, 50.3840, 0.0], TOL);
    assert!(close(n20.sweep_deg, 141.08, 0.01), "{}", n20.sweep_deg);
    assert!(close(n20.length, 85.966, TOL));
    let n40 = by_n(&mvs, 40).arc.unwrap();
    assert_xyz(n40.centre, [34.8462, 68.1560, 0.0], TOL);
    assert!(close(n40.sweep_deg, 218.92, 0.01), "{}", n40.sweep_deg);
    assert!(close(n40.length, 133.399, TOL));
    assert_xyz(by_n(&mvs, 40).end, [17.203, 38.029, 0.0], TOL);
}

#[test]
fn s5_3_3_cr_turning() {
    let mvs = motions(&run_fixture("s5_3_3-arc-cr-turning-example-5_10.nc"));
    let m = by_n(&mvs, 20);
    let a = m.arc.unwrap();
    assert_xyz(a.centre, xz(48.9366, -53.6380), TOL);
    assert!(close(a.sweep_deg, 152.73, 0.01), "{}", a.sweep_deg);
    assert!(close(a.length, 79.971, TOL));
    assert!(close(m.time(), 9.597, TOL));
    assert_xyz(m.end, xz(70.0, -75.0), TOL);
}

#[test]
fn s5_3_4_full_circle_both_variants_move_identically() {
    let a = motions(&run_fixture(
        "s5_3_4-full-circle-with-endpoint-example-5_11.nc",
    ));
    let b = motions(&run_fixture("s5_3_4-full-circle-ijk-only-example-5_12.nc"));
    for mvs in [&a, &b] {
        let m = by_n(mvs, 30);
        let arc = m.arc.unwrap();
        assert_xyz(arc.centre, [30.0, 30.0, -5.0], TOL);
        assert!(close(arc.radius, 20.0, TOL));
        assert!(close(arc.sweep_deg, -360.0, 1e-6));
        assert!(close(arc.length, 125.664, TOL));
        assert!(close(m.time(), 7.540, TOL));
    }
    assert_eq!(ends(&a), ends(&b));
}

#[test]
fn s5_3_5_helix_feed_over_spatial_length() {
    let mvs = motions(&run_fixture(
        "s5_3_5-helix-one-turn-example-5_13-reconstructed.nc",
    ));
    let m = by_n(&mvs, 20);
    let a = m.arc.unwrap();
    assert_xyz(a.centre, [30.0, 30.0, 0.0], TOL);
    assert!(close(a.sweep_deg, -360.0, 1e-6));
    assert!(close(a.length, 126.061, TOL));
    assert!(close(m.time(), 7.564, TOL));
    assert_xyz(m.end, [10.0, 30.0, -10.0], TOL);
}

#[test]
fn s5_3_6_helix_extra_turns() {
    let mvs = motions(&run_fixture("s5_3_6-helix-extra-turns-p-example-5_14.nc"));
    let n20 = by_n(&mvs, 20);
    let a = n20.arc.unwrap();
    assert_xyz(a.centre, [20.0, 0.0, 80.0], TOL);
    assert!(close(a.sweep_deg, -1800.0, 1e-6), "{}", a.sweep_deg);
    assert!(close(a.length, 633.391, TOL));
    assert!(close(n20.time(), 21.113, TOL));
    let n40 = by_n(&mvs, 40);
    let a = n40.arc.unwrap();
    assert_xyz(a.centre, [80.0, 0.0, 100.0], TOL);
    assert!(close(a.sweep_deg, 900.0, 1e-6), "{}", a.sweep_deg);
    assert!(close(a.length, 318.113, TOL));
    assert!(close(n40.time(), 10.604, TOL));
    assert_xyz(n40.end, [100.0, 0.0, 50.0], TOL);
}

// ---------------------------------------------------------------------------------------- §5.6

fn dwells(cmds: &[Spanned<Canon>]) -> Vec<f64> {
    cmds.iter()
        .filter_map(|c| match c.value {
            Canon::Dwell { seconds } => Some(seconds),
            _ => None,
        })
        .collect()
}

#[test]
fn s5_6_dwell_x_and_e() {
    assert_eq!(
        dwells(&run_fixture("s5_6-dwell-g04-syntax-examples.nc")),
        [10.5, 0.412]
    );
    let d = dwells(&run_fixture("s5_6-dwell-g04-example-5_21.nc"));
    assert_eq!(d, [11.5, 0.123, 54.0]);
    assert!(close(d.iter().sum::<f64>(), 65.623, 1e-9));
}

// ---------------------------------------------------------------------------------------- errors

#[test]
fn arc_errors_carry_the_manual_numbers() {
    let safety = "G17 G90 G191 G71 F100\n";
    let cases = [
        ("G02 X10 Y0\n", 621u32),      // no centre, no radius
        ("G02 X10 Y1 I5 J0\n", 622),   // end point not on the circle
        ("G02 X10 Y0 R4\n", 623),      // radius shorter than half the chord
        ("G02 X10 Y0 R-5\n", 623),     // R must be unsigned
        ("G02 X0 Y0 CR=5\n", 622),     // radius form cannot make a full circle
        ("G02 X10 Y0 I5 CR=5\n", 621), // centre and radius together
    ];
    for (block, code) in cases {
        let (cmds, err) = run(&format!("{safety}{block}M30\n"), Dialect::Axioma);
        let err = err.unwrap_or_else(|| panic!("{block}: no error"));
        assert_eq!(
            err.code,
            stanok_canon::DiagCode::Manual(code),
            "{block}: {err}"
        );
        assert_eq!(err.span.line, 2, "{block}");
        // Nothing of the bad block (or after it) was produced.
        assert!(motions(&cmds).is_empty(), "{block}");
    }
}
