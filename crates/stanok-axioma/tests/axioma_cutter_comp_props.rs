//! Property tests of AxiOMA radius compensation G41/G42 (spec axioma-3 §4.5): for random star
//! polygons (convex and concave corners) whose edges are lines or arcs bulging out or in, the
//! compensated tool-centre path keeps exactly the tool radius from the programmed contour (never
//! less, to 1e-6 mm) and lies on the correct side (outside for G42 on a counter-clockwise
//! contour and for G41 on a clockwise one).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use proptest::prelude::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge};
use stanok_canon::Canon;
use stanok_geom::offset2d::{turn_angle, Seg2, P2};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-6;

/// One edge: to `end`, straight (bulge 0) or an arc whose sagitta is `bulge`·chord (> 0 to the
/// right of the direction of travel).
struct Edge {
    end: P2,
    bulge: f64,
}

/// A contour program: entry from outside onto the middle of edge 0, all edges, exit back out.
/// Returns the program and the programmed contour segments.
fn program(vertices: &[P2], bulges: &[f64], r: f64, left: bool) -> (String, Vec<Seg2>) {
    let n = vertices.len();
    let (p0, p1) = (vertices[0], vertices[1]);
    let m = [(p0[0] + p1[0]) / 2.0, (p0[1] + p1[1]) / 2.0];
    let t = {
        let d = [p1[0] - p0[0], p1[1] - p0[1]];
        let l = d[0].hypot(d[1]);
        [d[0] / l, d[1] / l]
    };
    // Outward normal: right of travel for a CCW contour (G42), left for a CW one (G41).
    let out = if left { [-t[1], t[0]] } else { [t[1], -t[0]] };
    let s = [
        m[0] + (3.0 * r + 5.0) * out[0],
        m[1] + (3.0 * r + 5.0) * out[1],
    ];
    let mut edges: Vec<Edge> = vec![Edge {
        end: p1,
        bulge: 0.0,
    }];
    for i in 1..n {
        edges.push(Edge {
            end: vertices[(i + 1) % n],
            bulge: bulges[i],
        });
    }
    edges.push(Edge { end: m, bulge: 0.0 });
    let mut text = format!(
        "T1 M06\nN1 G00 X{:.9} Y{:.9}\nN2 {} G01 X{:.9} Y{:.9} F500\n",
        s[0],
        s[1],
        if left { "G41" } else { "G42" },
        m[0],
        m[1]
    );
    let mut segs = Vec::new();
    let mut at = m;
    for (k, e) in edges.iter().enumerate() {
        let nblock = 10 + k;
        if e.bulge == 0.0 {
            text += &format!("N{nblock} G01 X{:.9} Y{:.9}\n", e.end[0], e.end[1]);
            segs.push(Seg2::Line { a: at, b: e.end });
        } else {
            // Centre on the chord's perpendicular bisector: sagitta h = bulge·c, R = (h² + (c/2)²)/2h.
            let d = [e.end[0] - at[0], e.end[1] - at[1]];
            let c = d[0].hypot(d[1]);
            let h = e.bulge.abs() * c;
            let radius = (h * h + c * c / 4.0) / (2.0 * h);
            let right = [d[1] / c, -d[0] / c];
            let side = if e.bulge > 0.0 { 1.0 } else { -1.0 };
            // The arc bulges to `side`·right; its centre lies on the other side at R − h.
            let mid = [(at[0] + e.end[0]) / 2.0, (at[1] + e.end[1]) / 2.0];
            let centre = [
                mid[0] - side * right[0] * (radius - h),
                mid[1] - side * right[1] * (radius - h),
            ];
            // The centre is on the left of travel when the arc bulges to the right: counter-clockwise.
            let ccw = e.bulge > 0.0;
            text += &format!(
                "N{nblock} G0{} X{:.9} Y{:.9} I{:.9} J{:.9}\n",
                if ccw { 3 } else { 2 },
                e.end[0],
                e.end[1],
                centre[0] - at[0],
                centre[1] - at[1]
            );
            segs.push(Seg2::arc_through(centre, at, e.end, ccw, false));
        }
        at = e.end;
    }
    text += &format!("N99 G40 G01 X{:.9} Y{:.9}\nM30\n", s[0], s[1]);
    (text, segs)
}

fn points(cmds: &[stanok_canon::Spanned<Canon>]) -> Vec<(u32, P2)> {
    let mut out = Vec::new();
    for c in cmds {
        let n = c.block_number.unwrap_or(0);
        match &c.value {
            Canon::StraightFeed(m) | Canon::StraightTraverse(m) => {
                for i in 0..=16 {
                    let t = i as f64 / 16.0;
                    out.push((
                        n,
                        [
                            m.start.x + t * (m.end.x - m.start.x),
                            m.start.y + t * (m.end.y - m.start.y),
                        ],
                    ));
                }
            }
            Canon::ArcFeed(a) => {
                let seg = Seg2::arc_through(
                    [a.centre[0], a.centre[1]],
                    [a.start.x, a.start.y],
                    [a.end.x, a.end.y],
                    a.axis[2] > 0.0,
                    true,
                );
                for i in 0..=32 {
                    out.push((n, seg.point(i as f64 / 32.0)));
                }
            }
            _ => {}
        }
    }
    out
}

/// Winding test against the contour sampled finely.
fn inside(p: P2, contour: &[Seg2]) -> bool {
    let poly: Vec<P2> = contour
        .iter()
        .flat_map(|s| (0..64).map(move |i| s.point(i as f64 / 64.0)))
        .collect();
    let mut c = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            c = !c;
        }
    }
    c
}

fn options(r: f64) -> InterpOptions {
    let mut opts = InterpOptions::new(Dialect::Axioma);
    let mut c = ControlData::default();
    c.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: r,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    opts.control = c;
    opts
}

fn star() -> impl Strategy<Value = (Vec<P2>, Vec<f64>)> {
    (3usize..9)
        .prop_flat_map(|n| {
            (
                proptest::collection::vec(0.0f64..1.0, n),
                proptest::collection::vec(50.0f64..100.0, n),
                proptest::collection::vec(-0.1f64..0.1, n),
                proptest::collection::vec(any::<bool>(), n),
            )
        })
        .prop_map(|(jitter, radii, bulge, straight)| {
            let n = jitter.len();
            // Angles 30° … 150° apart, counter-clockwise: the origin stays inside (a star polygon).
            let slot = 360.0 / n as f64;
            let spread = (slot - 30.0).min(150.0 - slot).max(0.0);
            let v: Vec<P2> = (0..n)
                .map(|i| {
                    let a = (i as f64 * slot + jitter[i] * spread).to_radians();
                    [radii[i] * a.cos(), radii[i] * a.sin()]
                })
                .collect();
            let b: Vec<f64> = (0..n)
                .map(|i| {
                    if straight[i] || bulge[i].abs() < 0.01 {
                        0.0
                    } else {
                        bulge[i]
                    }
                })
                .collect();
            (v, b)
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, .. ProptestConfig::default() })]

    #[test]
    fn equidistant_keeps_exactly_r_on_the_outside((vertices, bulges) in star(), r in 0.5f64..3.0, left in any::<bool>()) {
        // G41 runs the polygon clockwise (reversed vertex order), G42 counter-clockwise.
        let (vertices, bulges) = if left {
            let mut v = vertices.clone();
            v.reverse();
            let mut b: Vec<f64> = bulges.clone();
            b.reverse();
            (v, b)
        } else {
            (vertices, bulges)
        };
        let (text, contour) = program(&vertices, &bulges, r, left);
        // A simple contour: inward bulges at an acute vertex can fold it over itself (a turn
        // beyond ±180° there); such input is not a contour, so keep every turn within ±160°.
        let simple = (0..contour.len()).all(|i| {
            let (s1, s2) = (&contour[i], &contour[(i + 1) % contour.len()]);
            turn_angle(s1.tangent(1.0), s2.tangent(0.0)).abs() <= 160f64.to_radians()
                && (s1.start()[0] - s2.start()[0]).hypot(s1.start()[1] - s2.start()[1]) > 1.0
        });
        prop_assume!(simple);
        let (cmds, err) = run_with(&text, options(r));
        prop_assert!(err.is_none(), "{err:?}\n{text}");
        let pts = points(&cmds);
        let mut seen = 0;
        for (n, p) in pts {
            if n < 10 || n == 99 {
                continue; // entry and exit lines
            }
            seen += 1;
            let d = contour.iter().map(|s| s.distance_to(p)).fold(f64::MAX, f64::min);
            prop_assert!((d - r).abs() < TOL, "N{n} point {p:?}: distance {d} ≠ r {r}\n{text}");
            prop_assert!(!inside(p, &contour), "N{n} point {p:?} is inside\n{text}");
        }
        prop_assert!(seen > 0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 100, .. ProptestConfig::default() })]

    /// Inside a circle (G41 + G03 / G42 + G02 after a G143 approach) the path is the circle of
    /// radius R − r; outside (the other pairing) R + r.
    #[test]
    fn full_circles_inside_and_outside(radius in 10.0f64..80.0, r in 0.5f64..8.0, ccw in any::<bool>(), inner in any::<bool>()) {
        prop_assume!(radius > r + 0.5);
        let g = if ccw { "G03" } else { "G02" };
        // G41 + G03 and G42 + G02 are inside (§4.2).
        let side = match (ccw, inner) { (true, true) | (false, false) => "G41", _ => "G42" };
        let approach = if inner { "G143" } else { "G144" };
        let text = format!("T1 M06\nG01 X0 Y0 F500\nN1 G01 {approach} Y{radius}\nN2 {g} X0 Y{radius} I0 J{} {side}\nN3 G143\nN4 G40 G01 X0 Y0\nM30\n", -radius);
        let (cmds, err) = run_with(&text, options(r));
        prop_assert!(err.is_none(), "{err:?}\n{text}");
        let want = if inner { radius - r } else { radius + r };
        let pts = points(&cmds);
        let on: Vec<&(u32, P2)> = pts.iter().filter(|(n, _)| *n == 2).collect();
        prop_assert!(!on.is_empty());
        for (_, p) in on {
            prop_assert!((p[0].hypot(p[1]) - want).abs() < TOL, "{p:?} not at {want}");
        }
    }
}

/// Block soup over the words of this part (compensation, cycles, outputs, arcs, planes): the
/// interpreter never panics and never loops, whatever the order, and its moves form one
/// continuous path.
fn soup_block() -> impl Strategy<Value = String> {
    let word = prop_oneof![
        Just("G40".to_string()),
        Just("G41".to_string()),
        Just("G42".to_string()),
        Just("G143".to_string()),
        Just("G144".to_string()),
        Just("G00".to_string()),
        Just("G01".to_string()),
        Just("G02".to_string()),
        Just("G03".to_string()),
        Just("G17".to_string()),
        Just("G18".to_string()),
        Just("G80".to_string()),
        Just("G81".to_string()),
        Just("G83".to_string()),
        Just("G276".to_string()),
        Just("G281".to_string()),
        Just("G288".to_string()),
        Just("G387".to_string()),
        Just("G388".to_string()),
        Just("G389".to_string()),
        Just("G99".to_string()),
        Just("G110".to_string()),
        Just("G111".to_string()),
        Just("M905".to_string()),
        Just("M3 S500".to_string()),
        Just("T1 M6".to_string()),
        Just("T0 M6".to_string()),
        Just("F300".to_string()),
        (1u8..17, -20.0f64..20.0).prop_map(|(i, v)| format!("Q{i}={v:.2}")),
        (0usize..6, -60.0f64..60.0)
            .prop_map(|(a, v)| format!("{}{v:.2}", ["X", "Y", "Z", "I", "J", "R"][a])),
        (1u32..10).prop_map(|n| format!("N1={n}")),
    ];
    proptest::collection::vec(word, 1..5).prop_map(|w| w.join(" "))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn block_soup_never_panics(blocks in proptest::collection::vec(soup_block(), 1..25)) {
        let text = blocks.join("\n") + "\nM30\n";
        let mut opts = options(3.0);
        opts.continue_after_error = true;
        opts.max_errors = 1000;
        let mut n = 0usize;
        let mut at: Option<[f64; 9]> = None;
        for item in stanok_interp::Interpreter::from_text(&text, opts) {
            n += 1;
            prop_assert!(n < 2_000_000, "runaway output");
            if let Ok(c) = item {
                if let Some(m) = c.value.motion() {
                    let (s, e) = (m.start().to_array(), m.end().to_array());
                    prop_assert!(e.iter().all(|v| v.is_finite()), "{text}");
                    // The stream is continuous: every move starts where the previous one ended.
                    if let Some(p) = at {
                        prop_assert!((0..9).all(|k| (p[k] - s[k]).abs() < 1e-6), "jump {p:?} → {s:?} at line {}\n{text}", c.span.line);
                    }
                    at = Some(e);
                }
            }
        }
    }
}
