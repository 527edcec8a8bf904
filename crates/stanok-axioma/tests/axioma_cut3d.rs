//! The corner fragments of §13.5.2–§13.7.3 as the manual describes them, with orientation methods
//! allowed to alternate inside the contour (`AxiomaMachineParams::cut3d_mixed_orientation`, spec
//! A-14), on a C/B fork head (C about +Z carrying B about +Y, pivot at the tip: TRAORI with zero
//! tool length) and a flat end mill R 5: reorientation blocks at the corner, then the bypass;
//! shortened sides with the rotary axes' full motion; the obtuse angles of A-21.

use stanok_canon::setup::{Tool, ToolEdge};
use stanok_canon::{Canon, Pose, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

type V3 = [f64; 3];

fn corpus(name: &str) -> String {
    let p = format!(
        "{}/../../../shared/corpus/axioma/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{p}: {e}"))
}

fn run(text: &str) -> (Vec<Spanned<Canon>>, Option<stanok_canon::Diagnostic>) {
    let mut o = InterpOptions::new(Dialect::Axioma);
    o.five_axis = Some(stanok_kin::from_fat("C,0,0,0,B,0,0,0").unwrap());
    o.axioma.cut3d_mixed_orientation = true;
    o.control.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: 5.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    let mut out = Vec::new();
    for item in Interpreter::from_text(text, o) {
        match item {
            Ok(c) => out.push(c),
            Err(d) => return (out, Some(d)),
        }
    }
    (out, None)
}

/// The fragment after what its elided lines would set: tool T1 and a feed.
fn fragment(
    name: &str,
) -> (
    String,
    Vec<Spanned<Canon>>,
    Option<stanok_canon::Diagnostic>,
) {
    let text = format!("N1 T1 M6 F1800\n{}", corpus(name));
    let (out, err) = run(&text);
    (text, out, err)
}

fn line_of(text: &str, n: &str) -> u32 {
    text.lines()
        .position(|l| l.starts_with(&format!("{n} ")))
        .unwrap_or_else(|| panic!("no {n}")) as u32
        + 1
}

fn moves<'a>(text: &str, out: &'a [Spanned<Canon>], n: &str) -> Vec<&'a Canon> {
    let line = line_of(text, n);
    out.iter()
        .filter(|c| c.span.line == line && c.value.motion().is_some())
        .map(|c| &c.value)
        .collect()
}

fn end(c: &Canon) -> Pose {
    c.motion().unwrap().end()
}

fn near(a: V3, b: V3, tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < tol)
}

fn tool(b: f64, c: f64) -> V3 {
    let (b, c) = (b.to_radians(), c.to_radians());
    [b.sin() * c.cos(), b.sin() * c.sin(), b.cos()]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: V3) -> V3 {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

#[test]
fn outer_corner_13_5_2_reorients_about_the_vertex_then_bypasses() {
    let (text, out, err) = fragment("s13_5_2-cut3dc-outer-corner-reorientation-fragment.nc");
    assert!(err.is_none(), "{err:?}");
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let (p1, p2) = ([s, s, 0.0], [s, -s, 0.0]);
    let pc = [30.0, 30.0, 0.0];
    // N60 ends R to the left with the vertical tool.
    let n60 = moves(&text, &out, "N60");
    assert!(near(end(n60[0]).xyz(), [26.4645, 33.5355, 0.0], 1e-4));
    // N70, N80: the tool turns, the tip keeps the contact at the vertex: Q = P_c + R·unit(t × p1).
    for n in ["N70", "N80"] {
        for c in moves(&text, &out, n) {
            let e = end(c);
            let t = tool(e.b, e.c);
            let want = {
                let u = unit(cross(t, p1));
                [pc[0] + 5.0 * u[0], pc[1] + 5.0 * u[1], pc[2] + 5.0 * u[2]]
            };
            assert!(
                near(e.xyz(), want, 1e-9),
                "{n}: {:?} want {want:?}",
                e.xyz()
            );
        }
    }
    let e80 = end(moves(&text, &out, "N80").last().unwrap());
    assert!(
        (e80.b - 60.0).abs() < 1e-9 && (e80.c - 45.0).abs() < 1e-9,
        "{e80:?}"
    );
    // The bypass (emitted with N80's corner, on N60's line) then N90: an arc ⟂ t_c about P_c.
    let t_c = tool(60.0, 45.0);
    let u2 = unit(cross(t_c, p2));
    let bypass_end = [
        pc[0] + 5.0 * u2[0],
        pc[1] + 5.0 * u2[1],
        pc[2] + 5.0 * u2[2],
    ];
    assert!(near(bypass_end, [31.7678, 31.7678, -4.3301], 1e-4));
    let arc = out
        .iter()
        .find_map(|c| match &c.value {
            Canon::ArcFeed(a) => Some(a.clone()),
            _ => None,
        })
        .expect("the bypass arc");
    assert!(near(arc.centre, pc, 1e-9), "{:?}", arc.centre);
    assert!(near(arc.end.xyz(), bypass_end, 1e-9));
    let dot = arc.axis[0] * t_c[0] + arc.axis[1] * t_c[1] + arc.axis[2] * t_c[2];
    assert!(
        (dot.abs() - 1.0).abs() < 1e-9,
        "the arc lies in the plane ⟂ t: {:?}",
        arc.axis
    );
    let n90 = moves(&text, &out, "N90");
    assert!(near(
        end(n90.last().unwrap()).xyz(),
        [60.0 + 5.0 * u2[0], 5.0 * u2[1], 5.0 * u2[2]],
        1e-9
    ));
}

#[test]
fn inner_corner_13_5_3_shortens_both_sides_with_full_rotary_motion() {
    let (text, out, err) = fragment("s13_5_3-cut3dc-inner-corner-reorientation-fragment.nc");
    assert!(err.is_none(), "{err:?}");
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let (p1, p2) = ([s, -s, 0.0], [s, s, 0.0]);
    // Distance ⟂ t from the axis through q to the line through a along p.
    let dist = |q: V3, t: V3, a: V3, p: V3| {
        let m = cross(t, p);
        let w = [q[0] - a[0], q[1] - a[1], q[2] - a[2]];
        let mm = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        (w[0] * m[0] + w[1] * m[1] + w[2] * m[2]).abs() / mm
    };
    let pc = [30.0, -30.0, 0.0];
    // N60 stops short of the vertex with B45 C15 reached: the tool touches both sides there.
    let e60 = end(moves(&text, &out, "N60").last().unwrap());
    assert!(
        (e60.b - 45.0).abs() < 1e-9 && (e60.c - 15.0).abs() < 1e-9,
        "{e60:?}"
    );
    let t = tool(45.0, 15.0);
    assert!((dist(e60.xyz(), t, [0.0; 3], p1) - 5.0).abs() < 1e-6);
    assert!((dist(e60.xyz(), t, pc, p2) - 5.0).abs() < 1e-6);
    // N70 turns the tool touching both sides at every vertex of its path.
    for c in moves(&text, &out, "N70") {
        let e = end(c);
        let t = tool(e.b, e.c);
        assert!((dist(e.xyz(), t, [0.0; 3], p1) - 5.0).abs() < 1e-6, "{e:?}");
        assert!((dist(e.xyz(), t, pc, p2) - 5.0).abs() < 1e-6, "{e:?}");
    }
    // N80 ends at B30 C0 (C2=0 ignored on a 5-axis machine), R to the left of (60, 0).
    let e80 = end(moves(&text, &out, "N80").last().unwrap());
    assert!((e80.b - 30.0).abs() < 1e-9 && e80.c.abs() < 1e-9, "{e80:?}");
    let t = tool(30.0, 0.0);
    let u = unit(cross(t, p2));
    assert!(near(
        e80.xyz(),
        [60.0 + 5.0 * u[0], 5.0 * u[1], 5.0 * u[2]],
        1e-9
    ));
}

#[test]
fn face_corner_fragments_reach_obtuse_angles_a_21() {
    // §13.7.2: N80's tool makes an obtuse angle with the first side's normal (t·n1 = −0.0795).
    let (text, _, err) = fragment("s13_7_2-cut3df-outer-corner-reorientation-fragment.nc");
    let e = err.expect("an error");
    assert_eq!(e.code.to_string(), "axioma::cut3d-normal-obtuse");
    assert_eq!(e.span.line, line_of(&text, "N80"));
    // §13.7.3: the second side starts with B60 C45: t·n2 = −0.0795.
    let (text, _, err) = fragment("s13_7_3-cut3df-inner-corner-reorientation-fragment.nc");
    let e = err.expect("an error");
    assert_eq!(e.code.to_string(), "axioma::cut3d-normal-obtuse");
    assert_eq!(e.span.line, line_of(&text, "N80"));
}

/// A 3-axis run (the tool along +Z) with T1 R 5 and the given workpiece frame G154.
fn run_3axis(text: &str, frame: stanok_canon::setup::WorkpieceFrame) -> Vec<Spanned<Canon>> {
    let mut o = InterpOptions::new(Dialect::Axioma);
    o.control.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: 5.0,
                ..Default::default()
            }],
            body: stanok_canon::setup::ToolBody {
                cutter: Some(stanok_canon::setup::CutterShape::Ball),
                ..Default::default()
            },
            ..Default::default()
        },
    );
    o.control.offsets.workpiece[0][0] = frame;
    Interpreter::from_text(text, o)
        .map(|c| c.unwrap_or_else(|d| panic!("{d:?}\n{text}")))
        .collect()
}

fn tips(out: &[Spanned<Canon>]) -> Vec<V3> {
    out.iter()
        .filter_map(|c| c.value.motion().map(|m| m.end().xyz()))
        .collect()
}

/// Metamorphic law: a workpiece frame turned about Z and shifted moves the compensated path of a
/// vertical tool rigidly (the compensation is made in machine coordinates, after the frame).
#[test]
fn a_turned_workpiece_frame_turns_the_compensated_path() {
    let body = "N10 M6 T1 F1000\nN20 G01 X-20 Y0 Z0\nN30 CUT3DC G41 X0 Y0\nN40 X30 Y30 ISD=2\nN50 G02 X60 Y0 I15 J-15\nN60 G01 X70 Y-20\nN70 G40 X90\nN80 M30\n";
    let head = "G17 G90 G191 G71 G94 G49 G40 G64 CUT2DF\n";
    let plain = tips(&run_3axis(
        &format!("{head}G153\n{body}"),
        Default::default(),
    ));
    let phi: f64 = 30.0;
    let origin = [100.0, 50.0, -10.0];
    let framed = tips(&run_3axis(
        &format!("{head}G154\n{body}"),
        stanok_canon::setup::WorkpieceFrame {
            origin,
            euler: [phi, 0.0, 0.0],
        },
    ));
    assert_eq!(plain.len(), framed.len());
    assert!(plain.len() >= 6);
    let (s, c) = phi.to_radians().sin_cos();
    for (p, f) in plain.iter().zip(&framed) {
        let want = [
            origin[0] + c * p[0] - s * p[1],
            origin[1] + s * p[0] + c * p[1],
            origin[2] + p[2],
        ];
        assert!(near(*f, want, 1e-9), "{f:?} want {want:?}");
    }
}

/// Face modes in the three planes: CUT3DFS takes the plane's axis as the tool (G17 Z, G18 Y,
/// G19 X), so the same contour written in each plane with its normal gives the same path with
/// the axes permuted (ball end: v = R·(n − t)).
#[test]
fn cut3dfs_in_the_three_planes() {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    // (plane, the contour's two axes (a, b) and the tool axis n)
    let cases: [(&str, [usize; 3]); 3] =
        [("G17", [0, 1, 2]), ("G18", [2, 0, 1]), ("G19", [1, 2, 0])];
    let letters = ['X', 'Y', 'Z'];
    let normal_words = ["A4", "B4", "C4"];
    let mut results: Vec<Vec<V3>> = Vec::new();
    for (plane, [a, b, n]) in cases {
        // A ridge over the plane: up the slope, then down; normals (−1, 0, 1) and (1, 0, 1) in
        // (a, n) coordinates.
        let w = |va: f64, vn: f64| format!("{}{va} {}0 {}{vn}", letters[a], letters[b], letters[n]);
        let nw = |ka: f64, kn: f64| format!("{}={ka} {}={kn}", normal_words[a], normal_words[n]);
        let text = format!(
            "G90 G191 G71 G94 G49 G40 G64 CUT2DF {plane}\nN10 M6 T1 F1000\nN20 G01 {}\nN30 CUT3DFS G41 {} {}\nN40 {}\nN50 {} {}\nN60 G40 {}\nN70 M30\n",
            w(-10.0, 0.0),
            w(0.0, 0.0),
            nw(-1.0, 1.0),
            w(30.0, 30.0),
            w(60.0, 0.0),
            nw(1.0, 1.0),
            w(70.0, 0.0),
        );
        let out = run_3axis(&text, Default::default());
        // Back to (a, b, n) coordinates.
        results.push(tips(&out).iter().map(|q| [q[a], q[b], q[n]]).collect());
    }
    assert!(results[0].len() >= 5);
    for r in &results[1..] {
        assert_eq!(r.len(), results[0].len());
        for (p, q) in r.iter().zip(&results[0]) {
            assert!(near(*p, *q, 1e-9), "{p:?} vs {q:?}");
        }
    }
    // The entry ends at v = 5·(n − t) of the first normal.
    let entry = results[0][1];
    assert!(
        near(entry, [5.0 * -s, 0.0, 5.0 * (s - 1.0)], 1e-9),
        "{entry:?}"
    );
}

/// Fuzz finding (CI, 2026-11-27): a fragment that ends without M30 under CUT3DC warned with no
/// line (the end of the text has no block). The warning names the last compensated block.
#[test]
fn cut3d_active_at_the_end_of_the_text_names_the_last_compensated_block() {
    let text = "N1 T1 M6 F1800\nN2 TRAORI\nN30 CUT3DC G41\nN40 G01 X20 Y50\nN50 X60\n";
    let mut o = InterpOptions::new(Dialect::Axioma);
    o.five_axis = Some(stanok_kin::from_fat("C,0,0,0,B,0,0,0").unwrap());
    o.control.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: 5.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    let mut interp = Interpreter::from_text(text, o);
    for item in interp.by_ref() {
        if let Err(d) = item {
            panic!("{d:?}");
        }
    }
    let warnings = interp.take_warnings();
    let w = warnings
        .iter()
        .find(|w| w.code.to_string().contains("cut3d-active-at-end"))
        .expect("the end-of-text warning");
    assert_eq!(w.span.line, 5, "{w:?}");
    assert!(w.span.column >= 1, "{w:?}");
}
