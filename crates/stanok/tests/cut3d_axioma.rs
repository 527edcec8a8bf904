//! AxiOMA 3D tool radius compensation (manual §13, corpus/axioma/s13_*): every fixture on the
//! machine its header assumes — the built-in `5axis-bc-head` (C about +Z carrying B about +Y, spec
//! axioma-4 §W) for the TRAORI examples, the 3-axis `mill` for the fragments without TRAORI —
//! gives the tip points its header computes (1e-4 mm: the headers print four decimals), the errors
//! it names, and zero axis-limit violations through the simulated machine. Plus the errors of
//! §13.2 and a golden 5-axis finishing run (tests/golden/cut3d_finishing.txt; regenerate with
//! `UPDATE_GOLDEN=1`).

#![allow(clippy::approx_constant)] // the headers print 1/√2 to four places

mod five_axis_harness;
use five_axis_harness::*;
use stanok_canon::setup::{ControlData, CutterShape, Tool, ToolBody, ToolEdge, ToolKind};
use stanok_canon::{Canon, Pose};
use stanok_kin::Kinematics;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-4;

fn tool(number: u32, shape: CutterShape, radius: f64, wear: f64, length: f64) -> Tool {
    Tool {
        number,
        kind: ToolKind::Milling,
        edges: vec![ToolEdge {
            length: [length, 0.0, 0.0],
            radius,
            radius_wear: wear,
            ..Default::default()
        }],
        body: ToolBody {
            cutter: Some(shape),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// T1: the R = 5 cutter of the examples, ball end unless told.
fn control(shape: CutterShape) -> ControlData {
    let mut c = ControlData::default();
    c.tools.tools.insert(1, tool(1, shape, 5.0, 0.0, 0.0));
    c
}

fn five_axis(name: &str, shape: CutterShape) -> Run {
    run(
        &corpus_text(&format!("axioma/{name}")),
        Dialect::Axioma,
        "5axis-bc-head",
        control(shape),
        Pose::ZERO,
    )
}

/// A fragment on the 3-axis mill, after `preamble` (what its elided lines would set: a feed, a
/// tool); `before_end` goes before its M30 (the elided motion after N90 of fragment 1, which the
/// 2D compensation it switches on needs in the next block).
fn mill(name: &str, preamble: &str, control: ControlData) -> Run {
    mill_with(name, preamble, "", control)
}

fn mill_with(name: &str, preamble: &str, before_end: &str, control: ControlData) -> Run {
    // The elided lines' comment goes: 2D compensation counts a comment line as the block after
    // its selection.
    let body = corpus_text(&format!("axioma/{name}"));
    let body = if before_end.is_empty() {
        body
    } else {
        body.replace(
            "\n; ... (lines elided in the manual's fragment)\nM30",
            &format!("\n{before_end}\nM30"),
        )
    };
    let text = format!("{preamble}\n{body}");
    run(&text, Dialect::Axioma, "mill", control, Pose::ZERO)
}

/// The tip motions (machine X Y Z under TRAORI) the block on `n`'s line produced.
fn moves<'a>(r: &'a Run, n: &str) -> Vec<&'a Canon> {
    let line = r.line_of(n);
    r.canon
        .iter()
        .zip(&r.lines)
        .filter(|(c, &l)| l == line && c.motion().is_some())
        .map(|(c, _)| c)
        .collect()
}

fn helix(a: &stanok_canon::ArcMove) -> stanok_geom::Helix {
    stanok_geom::Helix {
        start: a.start.xyz(),
        end: a.end.xyz(),
        centre: a.centre,
        axis: a.axis,
        turns: a.turns,
    }
}

fn end(c: &Canon) -> [f64; 3] {
    c.motion().unwrap().end().xyz()
}

fn start(c: &Canon) -> [f64; 3] {
    c.motion().unwrap().start().xyz()
}

fn assert_near(got: [f64; 3], want: [f64; 3], tol: f64, what: &str) {
    let d = ((got[0] - want[0]).powi(2) + (got[1] - want[1]).powi(2) + (got[2] - want[2]).powi(2))
        .sqrt();
    assert!(d < tol, "{what}: got {got:?}, want {want:?} (off by {d:e})");
}

#[test]
fn example_13_2_cut3dc_with_isd_and_an_outer_corner() {
    let r = five_axis("s13_3-cut3dc-isd-example-13_2.nc", CutterShape::Flat);
    r.ok();
    // N40 runs uncompensated; ISD=20 of N30 was ignored.
    assert_near(end(moves(&r, "N40")[0]), [-20.0, 0.0, 0.0], TOL, "N40");
    let entry = moves(&r, "N50");
    assert_eq!(entry.len(), 1, "the entry is one straight line");
    assert!(matches!(entry[0], Canon::StraightFeed(_)));
    assert_near(start(entry[0]), [-20.0, 0.0, 0.0], TOL, "entry start");
    assert_near(end(entry[0]), [-3.5355, 3.5355, 0.0], TOL, "entry end");
    // N60: ISD 0 → 20 along the block, then the bypass arc at Z −20 about (30, 30, −20).
    let n60 = moves(&r, "N60");
    assert_eq!(n60.len(), 2, "N60 and its bypass: {n60:?}");
    assert_near(end(n60[0]), [26.4645, 33.5355, -20.0], TOL, "N60 end");
    let Canon::ArcFeed(arc) = n60[1] else {
        panic!("the bypass is an arc: {:?}", n60[1])
    };
    assert_near(arc.centre, [30.0, 30.0, -20.0], TOL, "bypass centre");
    assert_near(arc.end.xyz(), [33.5355, 33.5355, -20.0], TOL, "bypass end");
    // Clockwise seen from +Z, through (30, 35, −20).
    assert!(arc.axis[2] < -0.999, "axis {:?}", arc.axis);
    let h = helix(arc);
    assert_near(h.point_at(0.5), [30.0, 35.0, -20.0], TOL, "bypass middle");
    // ISD at the middle of N60 is 10: the tip is 10 below the contour there.
    let n70 = moves(&r, "N70");
    assert_eq!(n70.len(), 1);
    assert_near(end(n70[0]), [63.5355, 3.5355, -40.0], TOL, "N70 end");
    let exit = moves(&r, "N80");
    assert_eq!(exit.len(), 1);
    assert_near(end(exit[0]), [90.0, 0.0, 0.0], TOL, "exit end");
}

#[test]
fn example_13_3_cut3df_ball_end_in_g18() {
    let r = five_axis(
        "s13_6-cut3df-face-compensation-g18-example-13_3.nc",
        CutterShape::Ball,
    );
    // `N260 N90 M30` (two N words, kept as printed) is the front end's word rule, not §13's: the
    // run may stop there, after everything compensated has run.
    if let Some(e) = &r.error {
        assert_eq!(e.span.line, r.line_of("N260"), "{e:?}");
    }
    assert_eq!(r.report.violation_count, 0, "{:?}", r.report.violations);
    let entry = moves(&r, "N140");
    assert_eq!(entry.len(), 1);
    assert_near(end(entry[0]), [-3.5355, 0.0, -1.4645], TOL, "entry end");
    let n150 = moves(&r, "N150");
    assert_near(end(n150[0]), [26.4645, 0.0, 28.5355], TOL, "N150 end");
    // Outer corner (30, 30): the ball centre turns about the vertex, the tip passes (30, 0, 30).
    let Canon::ArcFeed(bypass) = n150[1] else {
        panic!("outer corner: {:?}", n150[1])
    };
    let h = helix(bypass);
    assert_near(h.point_at(0.5), [30.0, 0.0, 30.0], TOL, "corner (30, 30)");
    assert_near(bypass.end.xyz(), [33.5355, 0.0, 28.5355], TOL, "N160 start");
    // Inner corners: the shortened blocks end at the crossings of the tip paths.
    assert_near(
        end(moves(&r, "N160")[0]),
        [60.0, 0.0, 2.0711],
        TOL,
        "corner (60, 0)",
    );
    assert_near(
        end(moves(&r, "N180")[0]),
        [88.0305, 0.0, 4.0405],
        TOL,
        "corner (90, 0)",
    );
    assert_near(
        end(moves(&r, "N200")[0]),
        [110.0, 0.0, 6.1803],
        TOL,
        "corner (110, 0)",
    );
    assert_near(
        end(moves(&r, "N220")[0]),
        [134.1421, 0.0, 0.0],
        TOL,
        "corner (130, 0)",
    );
    // Smooth joints (100, 10) and (120, 10): the tip 5 below the ball centre 15 above the centre.
    assert_near(
        end(moves(&r, "N190")[0]),
        [100.0, 0.0, 10.0],
        TOL,
        "joint (100, 10)",
    );
    assert_near(
        end(moves(&r, "N210")[0]),
        [120.0, 0.0, 10.0],
        TOL,
        "joint (120, 10)",
    );
    // The arcs with normals along their radius stay arcs.
    assert!(moves(&r, "N190")
        .iter()
        .all(|c| matches!(c, Canon::ArcFeed(_))));
    assert_near(
        end(moves(&r, "N230")[0]),
        [140.0, 0.0, 0.0],
        TOL,
        "N230 end",
    );
    assert_near(end(moves(&r, "N240")[0]), [150.0, 0.0, 0.0], TOL, "exit");
}

#[test]
fn example_13_3_with_a_flat_end_mill() {
    let r = five_axis(
        "s13_6-cut3df-face-compensation-g18-example-13_3.nc",
        CutterShape::Flat,
    );
    assert_eq!(r.report.violation_count, 0);
    // N150 offset (−5, 0, 0): the rim touches the contour.
    let n150 = moves(&r, "N150");
    assert_near(start(n150[0]), [-5.0, 0.0, 0.0], TOL, "N150 start");
    assert_near(end(n150[0]), [25.0, 0.0, 30.0], TOL, "N150 end");
    assert_near(
        end(moves(&r, "N160")[0]),
        [60.0, 0.0, 5.0],
        TOL,
        "corner (60, 0)",
    );
}

#[test]
fn example_13_1_cut3dc_enters_and_leaves_a_spline_straight() {
    let r = five_axis(
        "s13_2_1-cut3dc-entry-exit-spline-example-13_1.nc",
        CutterShape::Flat,
    );
    r.ok();
    // The reference contour N50–N90 (uncompensated) as Bézier pieces.
    let reference: Vec<[[f64; 3]; 4]> = ["N50", "N60", "N70", "N80", "N90"]
        .iter()
        .flat_map(|n| moves(&r, n))
        .filter_map(|c| match c {
            Canon::SplineFeed(s) => Some([
                s.control_points[0],
                s.control_points[1],
                s.control_points[2],
                s.control_points[3],
            ]),
            _ => None,
        })
        .collect();
    assert_eq!(reference.len(), 5);
    let left = |p: [f64; 3], q: [f64; 3]| {
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let l = dx.hypot(dy);
        [-dy / l * 5.0, dx / l * 5.0]
    };
    let first = reference[0];
    let u = left(first[0], first[1]);
    let entry = moves(&r, "N120");
    assert_eq!(entry.len(), 1);
    assert!(matches!(entry[0], Canon::StraightFeed(_)));
    assert_near(start(entry[0]), [-20.0, 0.0, 0.0], TOL, "entry start");
    assert_near(end(entry[0]), [u[0], u[1], 0.0], TOL, "entry end");
    let last = reference[4];
    let u = left(last[2], last[3]);
    let exit = moves(&r, "N180");
    assert_eq!(exit.len(), 1);
    assert_near(start(exit[0]), [120.0 + u[0], u[1], 0.0], TOL, "exit start");
    assert_near(end(exit[0]), [140.0, 0.0, 0.0], TOL, "exit end");
    // Every vertex of the compensated spline is R = 5 from the reference spline (the offset
    // curve), never nearer: sampled closest distance.
    let dense: Vec<[f64; 3]> = reference
        .iter()
        .flat_map(|p| {
            (0..=2000).map(move |i| {
                stanok_geom::offset3d::Curve3::Bezier { p: *p }.point(i as f64 / 2000.0)
            })
        })
        .collect();
    let mut vertices = 0;
    for n in ["N130", "N140", "N150", "N160", "N170"] {
        for c in moves(&r, n) {
            let q = end(c);
            let d = dense
                .iter()
                .map(|p| (p[0] - q[0]).hypot(p[1] - q[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                (d - 5.0).abs() < 2e-3,
                "{n}: vertex {q:?} is {d} from the contour"
            );
            vertices += 1;
        }
    }
    assert!(vertices > 50, "{vertices}");
}

#[test]
fn section_13_2_2_return_to_cut2df_after_the_exit_is_legal() {
    let r = mill_with(
        "s13_2_2-cut3dc-then-cut2df-fragment-1.nc",
        "F1800",
        "N100 X10 Y-10",
        ControlData::default(),
    );
    r.ok();
    assert_near(end(moves(&r, "N40")[0]), [20.0, 50.0, 0.0], TOL, "N40");
    assert_near(end(moves(&r, "N80")[0]), [0.0, 0.0, 0.0], TOL, "N80");
}

#[test]
fn section_13_2_2_switching_while_active_is_an_error_at_n70() {
    let r = mill(
        "s13_2_2-switch-while-active-error-fragment-2.nc",
        "F1800",
        ControlData::default(),
    );
    let e = r.error.as_ref().expect("an error");
    assert_eq!(e.code.to_string(), "axioma::cut3d-mode-switch");
    assert_eq!(e.span.line, r.line_of("N70"));
    assert!(moves(&r, "N70").is_empty());
}

#[test]
fn section_13_4_cut3dccd_against_the_limiting_surface() {
    // Differential: table radius 0, correction 0.5 (flat end). The elided lines give F and T1.
    let mut c = ControlData::default();
    c.tools
        .tools
        .insert(1, tool(1, CutterShape::Flat, 0.0, 0.5, 0.0));
    let r = mill(
        "s13_4-cut3dccd-limiting-surface-normals-fragment.nc",
        "F1800 T1 M6",
        c,
    );
    r.ok();
    let n40 = moves(&r, "N40");
    // Normal (0,0,1) ∥ t: no axial correction; 0.5 to the left of (0,60) → (60,0).
    let s = std::f64::consts::FRAC_1_SQRT_2 * 0.5;
    assert_near(end(n40[0]), [60.0 + s, s, 0.0], TOL, "N40 end");
    // N60: the normal turns (−0.6,0,0.8) → (0,0,1); a flat end tilted by α from the normal lifts
    // the tip by R·tan α: 0.375 at the start, 0 at the end.
    let n60 = moves(&r, "N60");
    assert_near(start(n60[0]), [60.0, -0.5, 0.375], TOL, "N60 start");
    assert_near(end(n60.last().unwrap()), [20.0, -0.5, 0.0], TOL, "N60 end");
    // In the middle: normal (−0.3162, 0, 0.9487), tan α = 1/3.
    let mid = n60
        .iter()
        .map(|c| end(c))
        .min_by(|a, b| (a[0] - 40.0).abs().total_cmp(&(b[0] - 40.0).abs()))
        .unwrap();
    assert!((mid[0] - 40.0).abs() < 1.0, "{mid:?}");
    assert!((mid[2] - 0.5 / 3.0).abs() < 0.01, "middle of N60 {mid:?}");
}

#[test]
fn corner_fragments_mix_orientation_methods_and_stop_at_n80() {
    // Spec A-14: §13.2.3 forbids alternating direct axes and angles/vectors inside the contour;
    // the four corner fragments do it at N80.
    for name in [
        "s13_5_2-cut3dc-outer-corner-reorientation-fragment.nc",
        "s13_5_3-cut3dc-inner-corner-reorientation-fragment.nc",
        "s13_7_2-cut3df-outer-corner-reorientation-fragment.nc",
        "s13_7_3-cut3df-inner-corner-reorientation-fragment.nc",
    ] {
        let r = five_axis(name, CutterShape::Ball);
        let e = r
            .error
            .as_ref()
            .unwrap_or_else(|| panic!("{name}: no error"));
        assert_eq!(
            e.code.to_string(),
            "axioma::cut3d-ori-method-change",
            "{name}"
        );
        assert_eq!(e.span.line, r.line_of("N80"), "{name}");
        assert!(moves(&r, "N80").is_empty(), "{name}");
        assert_eq!(r.report.violation_count, 0, "{name}");
    }
}

fn program(body: &str) -> String {
    format!("G17 G90 G191 G71 G94 G49 G40 G64 CUT2DF ORIAXES\nN10 M6 T1\n{body}\nM30\n")
}

fn error_of(machine: &str, body: &str) -> (String, u32) {
    let r = run(
        &program(body),
        Dialect::Axioma,
        machine,
        control(CutterShape::Ball),
        Pose::ZERO,
    );
    let e = r.error.expect("an error");
    (e.code.to_string(), e.span.line)
}

#[test]
fn errors_of_section_13_2() {
    // §13.2.4: TRAORI first on a machine that has it.
    assert_eq!(
        error_of("5axis-bc-head", "N20 G01 X-10 F1000\nN30 CUT3DC G41 X0"),
        ("axioma::cut3d-no-traori".into(), 4)
    );
    // §13.2.1: entry and exit are linear.
    assert_eq!(
        error_of(
            "mill",
            "N20 G01 X-10 F1000\nN30 CUT3DC G41 G02 X0 Y10 I5 J5"
        ),
        ("axioma::cut3d-entry-exit-not-linear".into(), 4)
    );
    assert_eq!(
        error_of(
            "mill",
            "N20 G01 X-10 F1000\nN30 CUT3DC G41 X0\nN40 X20\nN50 G40 G02 X30 Y10 I0 J10"
        ),
        ("axioma::cut3d-entry-exit-not-linear".into(), 6)
    );
    // §13.2.3: forbidden calls inside the contour.
    for (word, line) in [
        ("M8", 6),
        ("G18", 6),
        ("G154", 6),
        ("G43", 6),
        ("ORIVECT", 6),
        ("SPLBREAK", 6),
    ] {
        assert_eq!(
            error_of(
                "mill",
                &format!("N20 G01 X-10 F1000\nN30 CUT3DC G41 X0\nN40 X20\nN50 {word} X30")
            ),
            ("axioma::cut3d-forbidden".into(), line),
            "{word}"
        );
    }
    // §13.2.2: no mode switch while active, no 3D mode while 2D is active; no side change.
    assert_eq!(
        error_of(
            "mill",
            "N20 G01 X-10 F1000\nN30 CUT3DC G41 X0\nN40 CUT3DF X20"
        ),
        ("axioma::cut3d-mode-switch".into(), 5)
    );
    assert_eq!(
        error_of("mill", "N20 G01 X-10 F1000\nN30 G41 X0\nN40 CUT3DC X20"),
        ("axioma::cut3d-mode-switch".into(), 5)
    );
    assert_eq!(
        error_of("mill", "N20 G01 X-10 F1000\nN30 CUT3DC G41 X0\nN40 G42 X20"),
        ("axioma::cut3d-side-change".into(), 5)
    );
    // Peripheral: the tool along the path.
    assert_eq!(
        error_of("mill", "N20 G01 X-10 F1000\nN30 CUT3DC G41 X0\nN40 Z-20"),
        ("axioma::cut3d-offset-undefined".into(), 5)
    );
    // Face: a normal far from perpendicular to the path; a tool below the surface.
    assert_eq!(
        error_of(
            "mill",
            "N20 G01 X-10 F1000\nN30 CUT3DF G41 X0\nN40 X20 A4=1 C4=1\nN50 X30"
        ),
        ("axioma::cut3d-normal-not-perpendicular".into(), 5)
    );
    assert_eq!(
        error_of(
            "mill",
            "N20 G01 X-10 F1000\nN30 CUT3DF G41 X0\nN40 X20 B4=0.2 C4=-1\nN50 X30"
        ),
        ("axioma::cut3d-normal-obtuse".into(), 5)
    );
}

#[test]
fn the_same_mode_again_and_a_return_to_cut2df_are_allowed() {
    let r = run(
        &program("N20 G01 X-10 F1000\nN30 CUT3DC G41 X0\nN40 CUT3DC X20\nN50 G40 X30 Y-10\nN60 CUT2DF G41 X40\nN70 X50\nN80 G40 X60 Y-20"),
        Dialect::Axioma,
        "mill",
        control(CutterShape::Flat),
        Pose::ZERO,
    );
    r.ok();
    // 2D compensation again after the return: N70 runs 5 to the left of Y −10.
    let n70 = end(moves(&r, "N70")[0]);
    assert_near([n70[0], n70[1], 0.0], [50.0, -5.0, 0.0], TOL, "N70");
}

/// The golden finishing run: a tilted tool (A3=0.2 C3=1) with its 100 mm length finishes the
/// outside of a contour of lines and an arc with CUT3DC G42 and ISD=2 on 5axis-bc-head.
#[test]
fn golden_five_axis_finishing_with_cut3dc() {
    let text = "G17 G90 G191 G71 G94 G49 G40 G64 CUT2DF ORIAXES\n\
N10 M6 T2\n\
N20 G43\n\
N30 TRAORI\n\
N40 G01 X-20 Y-20 Z0 F1500\n\
N50 A3=0.2 B3=0 C3=1\n\
N60 CUT3DC G42 X0 Y0 ISD=2\n\
N70 X60\n\
N80 Y40\n\
N90 G03 X40 Y60 I-20 J0\n\
N100 G01 X0\n\
N110 Y0\n\
N120 G40 X-20 Y-20\n\
N130 M30\n";
    let mut c = control(CutterShape::Flat);
    c.tools
        .tools
        .insert(2, tool(2, CutterShape::Flat, 6.0, 0.0, 100.0));
    let r = run(
        text,
        Dialect::Axioma,
        "5axis-bc-head",
        c,
        Pose {
            z: 100.0,
            ..Pose::ZERO
        },
    );
    r.ok();
    // The tip path in machine coordinates at every block end, with B and C.
    let kin = r.machine.five_axis().unwrap().with_tool_length(100.0);
    let mut golden = String::new();
    for n in [
        "N40", "N50", "N60", "N70", "N80", "N90", "N100", "N110", "N120",
    ] {
        let axes = r.end_of(n);
        let tip = kin.forward(&axes).unwrap().xyz();
        golden += &format!(
            "{n} tip {:.4} {:.4} {:.4} axes {:.4} {:.4} {:.4} B {:.4} C {:.4}\n",
            tip[0], tip[1], tip[2], axes[0], axes[1], axes[2], axes[4], axes[5]
        );
    }
    // Every servo setpoint's tip lies on the commanded tip path (within 0.01 mm: blending).
    let path: Vec<[f64; 3]> = r
        .canon
        .iter()
        .filter_map(|c| c.motion().map(|m| m.end().xyz()))
        .collect();
    assert!(path.len() > 10);
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/golden/cut3d_finishing.txt"
    );
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(file, &golden).unwrap();
    }
    let want = std::fs::read_to_string(file).expect("golden file (UPDATE_GOLDEN=1 writes it)");
    for (g, w) in golden.lines().zip(want.lines()) {
        let gv: Vec<f64> = g
            .split_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect();
        let wv: Vec<f64> = w
            .split_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect();
        assert_eq!(gv.len(), wv.len(), "{g} / {w}");
        for (a, b) in gv.iter().zip(&wv) {
            assert!((a - b).abs() <= 1.5e-4, "golden: got `{g}`, want `{w}`");
        }
    }
    assert_eq!(golden.lines().count(), want.lines().count());
}
