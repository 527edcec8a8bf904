//! Test support of the AxiOMA metamorphic laws (issue 22): a seeded generator of tool paths whose
//! numbers are exact in every notation, a printer that writes one path in the notations the laws
//! compare, and the motion stream a program produces.
//!
//! ## Why the numbers are exact
//! A path lives on a grid of u = 1/8 inch = 3.175 mm: every coordinate is a whole number of u, so
//! it prints exactly in mm (three decimals) and in inches (u/8, three decimals), absolute or
//! incremental, radius or diameter. Arcs are Pythagorean: centre on the grid, start and end at
//! k·(±3, ±4), k·(±4, ±3), k·(±5, 0), k·(0, ±5) from it (radius 5k u), so the IJK form is exact and
//! the R/CR= forms differ from it only by the rounding of a square root (~1e-13 mm). Polar lines
//! print ρ and θ with 17 significant digits. So a law that holds must hold to 1e-9 mm, and one
//! that fails does so by far more.
#![allow(dead_code)]

use proptest::prelude::*;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

/// mm per grid unit.
pub const U: f64 = 3.175;
/// The laws' tolerance, mm.
pub const TOL: f64 = 1e-9;

/// Generated programs per law: 500 by default (CI), `STANOK_METAMORPHIC_CASES` raises it (≥ 10 000
/// locally).
pub fn cases() -> u32 {
    std::env::var("STANOK_METAMORPHIC_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(500)
}

/// One element of a path, in grid units (absolute).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Seg {
    /// G00 / G01 to (x, y, z).
    Line { rapid: bool, to: [i64; 3] },
    /// G02 (cw) / G03 to `to` about `centre` (in the XY plane, Z unchanged).
    Arc {
        cw: bool,
        to: [i64; 2],
        centre: [i64; 2],
    },
}

/// The 12 Pythagorean directions of radius 5.
const PYTH: [[i64; 2]; 12] = [
    [3, 4],
    [4, 3],
    [5, 0],
    [4, -3],
    [3, -4],
    [0, -5],
    [-3, -4],
    [-4, -3],
    [-5, 0],
    [-4, 3],
    [-3, 4],
    [0, 5],
];

/// A path: segments from the origin (the program starts with `G00 X0 Y0 Z0`).
pub fn path() -> impl Strategy<Value = Vec<Seg>> {
    // Each step: kind, a target, arc choices; resolved against the running position below.
    let step = (
        0u8..10,
        (-20i64..=20, -20i64..=20, -4i64..=4),
        (0usize..12, 1usize..11, 1i64..=3, any::<bool>()),
    );
    proptest::collection::vec(step, 1..12).prop_map(|steps| {
        let mut at = [0i64; 3];
        let mut segs = Vec::new();
        for (kind, (x, y, z), (from, turn, k, cw)) in steps {
            match kind {
                0..=4 => {
                    let to = [x, y, if kind == 0 { z } else { at[2] }];
                    if to == at {
                        continue;
                    }
                    segs.push(Seg::Line {
                        rapid: kind == 1,
                        to,
                    });
                    at = to;
                }
                _ => {
                    // Start at centre + k·PYTH[from]; end k·PYTH[from + turn] (never 0° or 180°:
                    // turn 6 is the opposite direction, skipped).
                    let turn = if turn == 6 { 5 } else { turn };
                    let v0 = PYTH[from];
                    let v1 = PYTH[(from + turn) % 12];
                    let centre = [at[0] - k * v0[0], at[1] - k * v0[1]];
                    let to = [centre[0] + k * v1[0], centre[1] + k * v1[1]];
                    segs.push(Seg::Arc { cw, to, centre });
                    at = [to[0], to[1], at[2]];
                }
            }
        }
        segs
    })
}

/// How a path is written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Form {
    /// G91 instead of G90.
    pub incremental: bool,
    /// 0 = I J, 1 = R, 2 = CR=.
    pub arc: u8,
    /// G70 (inches) instead of G71.
    pub inches: bool,
    /// G10 X1: X words are diameters.
    pub diameter: bool,
    /// Lines as polar moves about the origin (G16 … G15 around each arc; needs absolute).
    pub polar: bool,
}

impl Form {
    pub const BASE: Form = Form {
        incremental: false,
        arc: 0,
        inches: false,
        diameter: false,
        polar: false,
    };
}

/// A grid value in the form's unit, exactly.
fn num(u: i64, inches: bool) -> String {
    if inches {
        // u/8 inch: at most three decimals.
        format!("{}", u as f64 / 8.0)
    } else {
        // 3.175·u mm, written from the integer 3175·u thousandths (no float rounding).
        let t = 3175 * u;
        let sign = if t < 0 { "-" } else { "" };
        format!("{sign}{}.{:03}", t.abs() / 1000, t.abs() % 1000)
    }
}

/// Writes `segs` in `form`, after `header` (frame functions …), ending with M30.
pub fn program(segs: &[Seg], form: Form, header: &str) -> String {
    let mut s = String::new();
    s.push_str(if form.inches { "G70\n" } else { "G71\n" });
    s.push_str("G17 G90 G191 G94 F500\n");
    s.push_str(header);
    // The start: every axis programmed once after the frame (an axis never programmed keeps its
    // machine position, not its program one). Its line is START_LINE + the header's lines.
    s.push_str("G00 X0 Y0 Z0\n");
    if form.diameter {
        s.push_str("G10 X1\n");
    }
    s.push_str(if form.incremental { "G91\n" } else { "G90\n" });
    let n = |u: i64| num(u, form.inches);
    let xk = if form.diameter { 2 } else { 1 };
    let mut at = [0i64; 3];
    let mut polar_on = false;
    for seg in segs {
        match *seg {
            Seg::Line { rapid, to } => {
                let g = if rapid { "G00" } else { "G01" };
                if form.polar {
                    if !polar_on {
                        s.push_str("G16 X0 Y0\n");
                        polar_on = true;
                    }
                    let scale = if form.inches { 1.0 / 8.0 } else { U };
                    let (x, y) = (to[0] as f64 * scale, to[1] as f64 * scale);
                    let rho = x.hypot(y);
                    let theta = y.atan2(x).to_degrees();
                    s.push_str(&format!("{g} R{rho:.17} Q{theta:.17} Z{}\n", n(to[2])));
                } else if form.incremental {
                    s.push_str(&format!(
                        "{g} X{} Y{} Z{}\n",
                        n(xk * (to[0] - at[0])),
                        n(to[1] - at[1]),
                        n(to[2] - at[2])
                    ));
                } else {
                    s.push_str(&format!(
                        "{g} X{} Y{} Z{}\n",
                        n(xk * to[0]),
                        n(to[1]),
                        n(to[2])
                    ));
                }
                at = to;
            }
            Seg::Arc { cw, to, centre } => {
                if polar_on {
                    s.push_str("G15\n");
                    polar_on = false;
                }
                let g = if cw { "G02" } else { "G03" };
                let (x, y) = if form.incremental {
                    (xk * (to[0] - at[0]), to[1] - at[1])
                } else {
                    (xk * to[0], to[1])
                };
                let end = format!("{g} X{} Y{}", n(x), n(y));
                let r = {
                    let v = [at[0] - centre[0], at[1] - centre[1]];
                    let radius = ((v[0] * v[0] + v[1] * v[1]) as f64).sqrt();
                    // The sweep in the arc's sense: > 180° takes a negative radius.
                    let cross = (at[0] - centre[0]) * (to[1] - centre[1])
                        - (at[1] - centre[1]) * (to[0] - centre[0]);
                    let ccw_short = cross > 0;
                    let major = ccw_short == cw;
                    let mm = if form.inches {
                        radius / 8.0
                    } else {
                        radius * U
                    };
                    if major {
                        -mm
                    } else {
                        mm
                    }
                };
                match form.arc {
                    0 => s.push_str(&format!(
                        "{end} I{} J{}\n",
                        n(centre[0] - at[0]),
                        n(centre[1] - at[1])
                    )),
                    // AxiOMA's R is unsigned (E623): an arc over 180° exists only as CR=<0 — a
                    // limit of the notation, not of the law.
                    1 if r > 0.0 => s.push_str(&format!("{end} R{r:.17}\n")),
                    _ => s.push_str(&format!("{end} CR={r:.17}\n")),
                }
                at = [to[0], to[1], at[2]];
            }
        }
    }
    if polar_on {
        s.push_str("G15\n");
    }
    s.push_str("M30\n");
    s
}

/// One motion of the stream: rapid/feed/arc, end, and for arcs centre and axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mv {
    /// Source line.
    pub line: u32,
    pub kind: u8,
    pub end: [f64; 3],
    pub centre: [f64; 3],
    pub axis: [f64; 3],
}

/// The motion stream of a program (machine coordinates) after its start line `G00 X0 Y0 Z0`
/// (whose move depends on where the machine stood), or the error that stopped it.
pub fn motions(text: &str, opts: InterpOptions) -> Result<Vec<Mv>, Diagnostic> {
    let start = text
        .lines()
        .position(|l| l == "G00 X0 Y0 Z0")
        .map_or(0, |i| i as u32 + 1);
    let mut out = Vec::new();
    for item in Interpreter::from_text(text, opts) {
        let c: Spanned<Canon> = item?;
        match &c.value {
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => out.push(Mv {
                line: c.span.line,
                kind: matches!(c.value, Canon::StraightFeed(_)) as u8,
                end: m.end.xyz(),
                centre: [0.0; 3],
                axis: [0.0; 3],
            }),
            Canon::ArcFeed(a) => out.push(Mv {
                line: c.span.line,
                kind: 2,
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
            }),
            _ => {}
        }
    }
    out.retain(|m| m.line > start);
    Ok(out)
}

/// AxiOMA options; X may be a diameter (the laws' G10 form needs a transverse X).
pub fn options() -> InterpOptions {
    let mut o = InterpOptions::new(Dialect::Axioma);
    o.diameter_axes[0] = true;
    o
}

/// A point transform of a law: `point` maps positions and centres, `flips` says whether the
/// transform reverses the sense of rotation (a mirror).
pub struct Transform<'a> {
    pub point: &'a dyn Fn([f64; 3]) -> [f64; 3],
    pub flips: bool,
}

/// `got` is `want` moved by `t`, motion by motion, to [`TOL`].
pub fn assert_transformed(want: &[Mv], got: &[Mv], t: &Transform<'_>) -> Result<(), TestCaseError> {
    prop_assert_eq!(want.len(), got.len(), "number of motions");
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() <= TOL);
    for (i, (w, g)) in want.iter().zip(got).enumerate() {
        prop_assert_eq!(w.kind, g.kind, "motion {}: kind", i);
        let end = (t.point)(w.end);
        prop_assert!(
            close(end, g.end),
            "motion {}: end {:?}, want {:?}",
            i,
            g.end,
            end
        );
        if w.kind == 2 {
            let c = (t.point)(w.centre);
            // Centres are points on the axis: compare in the arc's plane (XY here).
            prop_assert!(
                (c[0] - g.centre[0]).abs() <= TOL && (c[1] - g.centre[1]).abs() <= TOL,
                "motion {}: centre {:?}, want {:?}",
                i,
                g.centre,
                c
            );
            let sense = if t.flips { -w.axis[2] } else { w.axis[2] };
            prop_assert!(
                (sense - g.axis[2]).abs() <= TOL,
                "motion {}: axis {:?}, want z {}",
                i,
                g.axis,
                sense
            );
        }
    }
    Ok(())
}

/// The identity law: the same motion.
pub fn same(want: &[Mv], got: &[Mv]) -> Result<(), TestCaseError> {
    assert_transformed(
        want,
        got,
        &Transform {
            point: &|p| p,
            flips: false,
        },
    )
}
