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
            Canon::ArcFeed(a) => Some(*a),
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
