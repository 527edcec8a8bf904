//! Properties of CUT3DC over generated contours, through the interpreter on a C/B fork head
//! (C about +Z carrying B about +Y) under TRAORI (spec axioma-4 §7.3, §7.8, §7.10):
//!
//! * the tool axis keeps exactly the distance R from the programmed contour (measured in the
//!   plane ⟂ t, where the offset is made), never less (no gouge), along every compensated move
//!   (1e-9 mm; every move is sampled) — for contours that keep clear of themselves, since §13.8
//!   checks no collisions beyond the two blocks of a corner;
//! * the tip is ISD below the contact along the axis: (Q − P)·t = −ISD at the nearest contour
//!   point P (1e-9);
//! * the entry ends at P0 + R·side·unit(t × p0) − ISD·t, the exit at the programmed point (§13.2.1).
//!
//! Regime A: vertical tool, lines and arcs (radii above R), random ISD and side. Regime B: a
//! random tilt up to 30° (A3/B3/C3), lines only (a tilted tool turns an arc's offset into a
//! polyline within the output's chord tolerance; fixtures and the golden run cover those).

use proptest::prelude::*;
use stanok_canon::{Canon, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn unit(a: V3) -> V3 {
    scale(a, 1.0 / dot(a, a).sqrt())
}

/// A programmed element in XY (z = 0).
#[derive(Debug, Clone, Copy)]
enum Seg {
    Line {
        a: V3,
        b: V3,
    },
    Arc {
        c: V3,
        rho: f64,
        a0: f64,
        sweep: f64,
        a: V3,
        b: V3,
    },
}

impl Seg {
    fn point(&self, s: f64) -> V3 {
        match *self {
            Seg::Line { a, b } => add(a, scale(sub(b, a), s)),
            Seg::Arc {
                c, rho, a0, sweep, ..
            } => {
                let x = a0 + sweep * s;
                [c[0] + rho * x.cos(), c[1] + rho * x.sin(), 0.0]
            }
        }
    }
    /// The nearest point to the axis line through q along t: (distance ⟂ t, the point).
    fn nearest(&self, q: V3, t: V3) -> (f64, V3) {
        let perp = |v: V3| sub(v, scale(t, dot(v, t)));
        match *self {
            Seg::Line { a, b } => {
                let (d, w) = (perp(sub(b, a)), perp(sub(q, a)));
                let s = (dot(w, d) / dot(d, d)).clamp(0.0, 1.0);
                let p = add(a, scale(sub(b, a), s));
                let e = perp(sub(q, p));
                (dot(e, e).sqrt(), p)
            }
            Seg::Arc {
                c,
                rho,
                a0,
                sweep,
                a,
                b,
            } => {
                // Only with t = e_z (regime A): plane distance to the arc.
                let v = sub(q, c);
                let ang = v[1].atan2(v[0]);
                let rel = |x: f64| {
                    let tau = std::f64::consts::TAU;
                    if sweep > 0.0 {
                        (x - a0).rem_euclid(tau)
                    } else {
                        (a0 - x).rem_euclid(tau)
                    }
                };
                let mut best = {
                    let da = ((q[0] - a[0]).powi(2) + (q[1] - a[1]).powi(2)).sqrt();
                    let db = ((q[0] - b[0]).powi(2) + (q[1] - b[1]).powi(2)).sqrt();
                    if da < db {
                        (da, a)
                    } else {
                        (db, b)
                    }
                };
                if rel(ang) <= sweep.abs() {
                    let r = v[0].hypot(v[1]);
                    let p = [c[0] + rho * ang.cos(), c[1] + rho * ang.sin(), 0.0];
                    if (r - rho).abs() < best.0 {
                        best = ((r - rho).abs(), p);
                    }
                }
                best
            }
        }
    }
}

#[derive(Debug, Clone)]
struct Case {
    text: String,
    segs: Vec<Seg>,
    t: V3,
    radius: f64,
    isd: f64,
    side: f64,
    exit: V3,
}

fn opts(radius: f64) -> InterpOptions {
    let mut o = InterpOptions::new(Dialect::Axioma);
    o.five_axis = Some(stanok_kin::from_fat("C,0,0,0,B,0,0,0").unwrap());
    o.control.tools.tools.insert(
        1,
        stanok_canon::setup::Tool {
            number: 1,
            edges: vec![stanok_canon::setup::ToolEdge {
                radius,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    o
}

/// (kind 0 line / 1 ccw arc / 2 cw arc, turn, length or radius, sweep).
type Step = (u8, f64, f64, f64);

fn build(steps: &[Step], radius: f64, isd: f64, left: bool, tilt: Option<(f64, f64)>) -> Case {
    // The program states ISD to 6 places: the case uses that value.
    let isd = (isd * 1e6).round() / 1e6;
    let mut text = String::from(
        "G17 G90 G191 G71 G94 G49 G40 G64 CUT2DF ORIAXES\nN10 M6 T1\nN20 TRAORI\nN30 G01 X-30 Y-40 Z0 F1000\n",
    );
    let t = match tilt {
        Some((polar, azimuth)) => {
            let t = [
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            ];
            text += &format!("N35 A3={:.12} B3={:.12} C3={:.12}\n", t[0], t[1], t[2]);
            unit(t)
        }
        None => [0.0, 0.0, 1.0],
    };
    text += &format!(
        "N40 CUT3DC {} X0 Y0 ISD={isd:.6}\n",
        if left { "G41" } else { "G42" }
    );
    let mut cur = [0.0, 0.0, 0.0];
    let mut heading: f64 = 0.0;
    let mut segs = Vec::new();
    for (i, &(kind, turn, size, sweep)) in steps.iter().enumerate() {
        heading += turn;
        let n = 50 + 10 * i;
        if kind == 0 || tilt.is_some() {
            let b = [
                cur[0] + size * heading.cos(),
                cur[1] + size * heading.sin(),
                0.0,
            ];
            text += &format!("N{n} G01 X{:.12} Y{:.12}\n", b[0], b[1]);
            segs.push(Seg::Line { a: cur, b });
            cur = b;
        } else {
            let ccw = kind == 1;
            let rho = size;
            let normal = if ccw {
                heading + std::f64::consts::FRAC_PI_2
            } else {
                heading - std::f64::consts::FRAC_PI_2
            };
            let c = [
                cur[0] + rho * normal.cos(),
                cur[1] + rho * normal.sin(),
                0.0,
            ];
            let a0 = (cur[1] - c[1]).atan2(cur[0] - c[0]);
            let sw = if ccw { sweep } else { -sweep };
            let a1 = a0 + sw;
            let b = [c[0] + rho * a1.cos(), c[1] + rho * a1.sin(), 0.0];
            text += &format!(
                "N{n} {} X{:.12} Y{:.12} I{:.12} J{:.12}\n",
                if ccw { "G03" } else { "G02" },
                b[0],
                b[1],
                c[0] - cur[0],
                c[1] - cur[1]
            );
            segs.push(Seg::Arc {
                c,
                rho,
                a0,
                sweep: sw,
                a: cur,
                b,
            });
            heading += sw;
            cur = b;
        }
    }
    let exit = [
        cur[0] + 30.0 * (heading + 0.7).cos(),
        cur[1] + 30.0 * (heading + 0.7).sin(),
        0.0,
    ];
    text += &format!("N900 G01 G40 X{:.12} Y{:.12}\nN910 M30\n", exit[0], exit[1]);
    Case {
        text,
        segs,
        t,
        radius,
        isd,
        side: if left { 1.0 } else { -1.0 },
        exit,
    }
}

/// The commands of the run, or the error it stopped with.
fn run(case: &Case) -> Result<Vec<Spanned<Canon>>, stanok_canon::Diagnostic> {
    let mut out = Vec::new();
    for item in Interpreter::from_text(&case.text, opts(case.radius)) {
        out.push(item?);
    }
    Ok(out)
}

/// A programmed element's tool-axis path in the plane, vertical tool (regime A): a line shifted
/// by R to the compensation side, or an arc about the same centre with its radius ± R (None
/// when the arc shrinks to nothing).
fn offset(seg: &Seg, side: f64, r: f64) -> Option<Seg> {
    match *seg {
        Seg::Line { a, b } => {
            let d = unit(sub(b, a));
            let n = scale([-d[1], d[0], 0.0], side * r);
            Some(Seg::Line {
                a: add(a, n),
                b: add(b, n),
            })
        }
        Seg::Arc {
            c, rho, a0, sweep, ..
        } => {
            // Left of travel is towards the centre on a counterclockwise arc.
            let rho = rho - side * r * sweep.signum();
            let at = |x: f64| [c[0] + rho * x.cos(), c[1] + rho * x.sin(), 0.0];
            (rho > 1e-9).then(|| Seg::Arc {
                c,
                rho,
                a0,
                sweep,
                a: at(a0),
                b: at(a0 + sweep),
            })
        }
    }
}

impl Seg {
    /// Where `p` (on the element's carrier) lies along the element: 0 at its start, 1 at its end.
    fn param(&self, p: V3) -> f64 {
        match *self {
            Seg::Line { a, b } => dot(sub(p, a), sub(b, a)) / dot(sub(b, a), sub(b, a)),
            Seg::Arc { c, a0, sweep, .. } => {
                let ang = (p[1] - c[1]).atan2(p[0] - c[0]);
                let rel = if sweep > 0.0 { ang - a0 } else { a0 - ang };
                // Angles just before the start read as slightly negative, not as nearly 2π.
                let rel = (rel + 0.5).rem_euclid(std::f64::consts::TAU) - 0.5;
                rel / sweep.abs()
            }
        }
    }
    /// Line through (point, direction) or circle (centre, radius).
    fn carrier(&self) -> Result<(V3, V3), (V3, f64)> {
        match *self {
            Seg::Line { a, b } => Ok((a, sub(b, a))),
            Seg::Arc { c, rho, .. } => Err((c, rho)),
        }
    }
}

/// The points where two carriers (lines or circles in the plane) cross.
fn crossings(e1: &Seg, e2: &Seg) -> Vec<V3> {
    let cross2 = |u: V3, v: V3| u[0] * v[1] - u[1] * v[0];
    let line_circle = |p: V3, d: V3, c: V3, rho: f64| -> Vec<V3> {
        let w = sub(p, c);
        let (qa, qb, qc) = (dot(d, d), 2.0 * dot(w, d), dot(w, w) - rho * rho);
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 {
            return vec![];
        }
        let sq = disc.sqrt();
        [(-qb - sq) / (2.0 * qa), (-qb + sq) / (2.0 * qa)]
            .iter()
            .map(|&k| add(p, scale(d, k)))
            .collect()
    };
    match (e1.carrier(), e2.carrier()) {
        (Ok((p, d)), Ok((q, e))) => {
            let den = cross2(d, e);
            if den.abs() < 1e-12 {
                return vec![];
            }
            vec![add(p, scale(d, cross2(sub(q, p), e) / den))]
        }
        (Ok((p, d)), Err((c, rho))) | (Err((c, rho)), Ok((p, d))) => line_circle(p, d, c, rho),
        (Err((c1, r1)), Err((c2, r2))) => {
            let dc = sub(c2, c1);
            let dist = dot(dc, dc).sqrt();
            if dist < 1e-12 || dist > r1 + r2 || dist < (r1 - r2).abs() {
                return vec![];
            }
            let along = (r1 * r1 - r2 * r2 + dist * dist) / (2.0 * dist);
            let h = (r1 * r1 - along * along).max(0.0).sqrt();
            let m = add(c1, scale(dc, along / dist));
            let n = scale([-dc[1], dc[0], 0.0], h / dist);
            vec![add(m, n), sub(m, n)]
        }
    }
}

/// Whether the contour has an inner corner whose two offset elements do not cross within their
/// blocks, or a block whose two inner corners trim it from both ends past each other: the cases
/// where §13.4 says the control finds no intersection of the blocks (vertical tool only).
fn inner_corner_without_crossing(case: &Case) -> bool {
    let offs: Vec<Option<Seg>> = case
        .segs
        .iter()
        .map(|s| offset(s, case.side, case.radius))
        .collect();
    let tangent = |s: &Seg, at_end: bool| -> V3 {
        match *s {
            Seg::Line { a, b } => unit(sub(b, a)),
            Seg::Arc { c, a, b, sweep, .. } => {
                let r = sub(if at_end { b } else { a }, c);
                unit(scale([-r[1], r[0], 0.0], sweep.signum()))
            }
        }
    };
    // (trim from the start, trim to the end) of each block, as parameters.
    let mut trims = vec![(0.0f64, 1.0f64); case.segs.len()];
    for i in 0..case.segs.len().saturating_sub(1) {
        let turn = cross(
            tangent(&case.segs[i], true),
            tangent(&case.segs[i + 1], false),
        )[2];
        if case.side * turn <= 1e-9 {
            continue; // outer or tangent: the control inserts an arc or goes straight on
        }
        let (Some(e1), Some(e2)) = (offs[i], offs[i + 1]) else {
            return true;
        };
        let tol = 1e-9;
        let best = crossings(&e1, &e2)
            .into_iter()
            .map(|p| (e1.param(p), e2.param(p)))
            .filter(|&(s, g)| (-tol..=1.0 + tol).contains(&s) && (-tol..=1.0 + tol).contains(&g))
            .min_by(|a, b| ((1.0 - a.0) + a.1).total_cmp(&((1.0 - b.0) + b.1)));
        let Some((s, g)) = best else {
            return true;
        };
        trims[i].1 = s;
        trims[i + 1].0 = g;
    }
    trims.iter().any(|&(from, to)| from > to + 1e-9)
}

fn line_of(text: &str, n: &str) -> u32 {
    text.lines().position(|l| l.starts_with(n)).unwrap() as u32 + 1
}

fn check(case: &Case) -> Result<(), TestCaseError> {
    let out = match run(case) {
        Ok(out) => out,
        // A block too short for the tool at an inner corner is the control's error (§13.4): the
        // case is then no case, but only when the plane geometry confirms it.
        Err(d)
            if d.code.to_string() == "axioma::cut3d-inner-no-intersection"
                && case.t[2] > 1.0 - 1e-15
                && inner_corner_without_crossing(case) =>
        {
            return Err(TestCaseError::reject("an inner corner without a crossing"));
        }
        Err(d) => return Err(TestCaseError::fail(format!("{d:?}\n{}", case.text))),
    };
    let (entry_line, exit_line) = (line_of(&case.text, "N40"), line_of(&case.text, "N900"));
    let first_line = entry_line + 1;
    let t = case.t;
    // Entry (§13.2.1): straight to P0 + R·u − ISD·t.
    let p0 = match case.segs[0] {
        Seg::Line { a, b } => unit(sub(b, a)),
        Seg::Arc { c, a, sweep, .. } => {
            let r = sub(a, c);
            let tan = [-r[1], r[0], 0.0];
            unit(if sweep > 0.0 { tan } else { scale(tan, -1.0) })
        }
    };
    let u = scale(unit(cross(t, p0)), case.side);
    let want = sub(scale(u, case.radius), scale(t, case.isd));
    let entry: Vec<_> = out
        .iter()
        .filter(|c| c.span.line == entry_line && c.value.motion().is_some())
        .collect();
    prop_assert_eq!(entry.len(), 1);
    let e = entry[0].value.motion().unwrap().end().xyz();
    prop_assert!(
        sub(e, want).iter().all(|d| d.abs() < 1e-9),
        "entry {:?} want {:?}",
        e,
        want
    );
    let exit: Vec<_> = out
        .iter()
        .filter(|c| c.span.line == exit_line && c.value.motion().is_some())
        .collect();
    prop_assert_eq!(exit.len(), 1);
    let x = exit[0].value.motion().unwrap().end().xyz();
    prop_assert!(
        sub(x, case.exit).iter().all(|d| d.abs() < 1e-9),
        "exit {:?}",
        x
    );
    // The contour keeps clear of itself (more than 2R + 1 between blocks, adjacent blocks away
    // from their shared vertex): §13.8 checks no collisions, so only such contours are cases.
    let dense: Vec<Vec<V3>> = case
        .segs
        .iter()
        .map(|s| (0..=100).map(|k| s.point(k as f64 / 100.0)).collect())
        .collect();
    let far = |a: &V3, b: &V3, d: f64| dot(sub(*a, *b), sub(*a, *b)).sqrt() > d;
    let keep = 2.0 * case.radius + 1.0;
    let clear = (0..dense.len()).all(|i| {
        ((i + 1)..dense.len()).all(|j| {
            let v = dense[i][100];
            dense[i].iter().all(|a| {
                dense[j].iter().all(|b| {
                    (j == i + 1 && (!far(a, &v, keep + 1.0) || !far(b, &v, keep + 1.0)))
                        || far(a, b, keep)
                })
            })
        })
    });
    prop_assume!(clear);
    // Along every compensated move: the axis at R from the contour, the tip ISD below.
    let mut samples = 0;
    for c in out
        .iter()
        .filter(|c| c.span.line >= first_line && c.span.line < exit_line)
    {
        let pts: Vec<V3> = match &c.value {
            Canon::StraightFeed(m) => (0..=8)
                .map(|k| {
                    let (a, b) = (m.start.xyz(), m.end.xyz());
                    add(a, scale(sub(b, a), k as f64 / 8.0))
                })
                .collect(),
            Canon::ArcFeed(a) => {
                let h = stanok_geom::Helix {
                    start: a.start.xyz(),
                    end: a.end.xyz(),
                    centre: a.centre,
                    axis: a.axis,
                    turns: a.turns,
                };
                (0..=8).map(|k| h.point_at(k as f64 / 8.0)).collect()
            }
            other => {
                prop_assert!(other.motion().is_none(), "unexpected {:?}", other);
                continue;
            }
        };
        for q in pts {
            let (d, p) = case
                .segs
                .iter()
                .map(|s| s.nearest(q, t))
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .unwrap();
            prop_assert!(
                (d - case.radius).abs() < 1e-9,
                "line {}: axis at {} from the contour, R = {}\n{}",
                c.span.line,
                d,
                case.radius,
                case.text
            );
            if clear {
                let g = case
                    .segs
                    .iter()
                    .map(|s| s.nearest(q, t).0)
                    .fold(f64::INFINITY, f64::min);
                prop_assert!(
                    g > case.radius - 1e-9,
                    "gouge: {} < R {}\n{}",
                    g,
                    case.radius,
                    case.text
                );
            }
            // The depth: exact with a vertical tool; a tilted tool spreads an inner corner's
            // axial jump over the first block (§13.5.3), so only the distance is exact there.
            if t[2] > 1.0 - 1e-15 {
                let axial = dot(sub(q, p), t);
                prop_assert!(
                    (axial + case.isd).abs() < 1e-9,
                    "line {}: tip {} along t from the contact, ISD {}",
                    c.span.line,
                    axial,
                    case.isd
                );
            }
            samples += 1;
        }
    }
    prop_assert!(samples >= 9 * case.segs.len());
    Ok(())
}

fn step() -> impl Strategy<Value = Step> {
    (
        0u8..3,
        prop_oneof![-2.0f64..-0.1, 0.1f64..2.0],
        20.0f64..50.0,
        0.3f64..1.5,
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn vertical_tool_lines_and_arcs(
        steps in prop::collection::vec(step(), 1..5),
        radius in 0.5f64..5.0,
        isd in -3.0f64..10.0,
        left in any::<bool>(),
    ) {
        // Arc radii above the cutter radius (the concave side must fit: §13.8 does not check).
        let steps: Vec<Step> = steps.into_iter().map(|(k, turn, size, sw)| (k, turn, size.max(radius + 10.0), sw)).collect();
        check(&build(&steps, radius, isd, left, None))?;
    }

    #[test]
    fn tilted_tool_lines(
        steps in prop::collection::vec(step(), 1..5),
        radius in 0.5f64..5.0,
        isd in -3.0f64..10.0,
        left in any::<bool>(),
        polar in 0.05f64..0.52,
        azimuth in -3.1f64..3.1,
    ) {
        check(&build(&steps, radius, isd, left, Some((polar, azimuth))))?;
    }
}

/// The shrunk case of `vertical_tool_lines_and_arcs` (a 0.3 rad arc of radius 20, then a line
/// turning 105° into the compensation side with R 4.63): the inner corner's trim (≈ 6 mm) is
/// longer than the offset arc (≈ 4.6 mm), so the control refuses the corner — and the plane
/// geometry agrees. The same corner after a longer arc crosses and runs.
#[test]
fn a_short_arc_at_an_inner_corner_is_refused_as_the_geometry_says() {
    let r = 4.6271793287933605;
    let turn = -1.8357948282714138;
    let short = build(
        &[(2, -0.1, 20.0, 0.3), (0, turn, 20.0, 0.3)],
        r,
        0.0,
        false,
        None,
    );
    let err = run(&short).unwrap_err();
    assert_eq!(err.code.to_string(), "axioma::cut3d-inner-no-intersection");
    assert!(inner_corner_without_crossing(&short));
    let long = build(
        &[(2, -0.1, 20.0, 0.9), (0, turn, 20.0, 0.3)],
        r,
        0.0,
        false,
        None,
    );
    assert!(!inner_corner_without_crossing(&long));
    check(&long).unwrap();
}
