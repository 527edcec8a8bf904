//! Metamorphic laws of AxiOMA (issue 22): with no reference implementation to diff against, one
//! path written in different notations must give the same motion, and a frame function wrapped
//! around a program must move its whole motion by exactly that transform. Generated programs
//! (`metamorphic/mod.rs`: lines, rapid moves, arcs in the three forms, polar lines, G70/G71, G10)
//! on a grid where every form is exact, compared motion by motion (ends, arc centres, arc sense)
//! to 1e-9 mm. 500 programs per law by default; `STANOK_METAMORPHIC_CASES=10000` for a local run.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
mod metamorphic;

use metamorphic::*;
use proptest::prelude::*;

fn base(segs: &[Seg]) -> Result<Vec<Mv>, TestCaseError> {
    let want = motions(&program(segs, Form::BASE, ""), options())
        .map_err(|d| TestCaseError::fail(format!("base program refused: {d}")))?;
    // The stream compared is the path itself, not an empty one.
    prop_assert_eq!(want.len(), segs.len(), "one motion per segment");
    Ok(want)
}

fn run(segs: &[Seg], form: Form, header: &str) -> Result<Vec<Mv>, TestCaseError> {
    let text = program(segs, form, header);
    motions(&text, options()).map_err(|d| TestCaseError::fail(format!("{d}\nin:\n{text}")))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    /// G90 and G91 write the same path.
    #[test]
    fn absolute_and_incremental_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        let got = run(&segs, Form { incremental: true, ..Form::BASE }, "")?;
        same(&want, &got)?;
    }

    /// I J, R and CR= write the same arcs.
    #[test]
    fn ijk_r_and_cr_arcs_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        for arc in [1, 2] {
            same(&want, &run(&segs, Form { arc, ..Form::BASE }, "")?)?;
            same(&want, &run(&segs, Form { arc, incremental: true, ..Form::BASE }, "")?)?;
        }
    }

    /// G70 (inches) and G71 (mm) write the same path.
    #[test]
    fn inches_and_millimetres_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        for form in [
            Form { inches: true, ..Form::BASE },
            Form { inches: true, incremental: true, arc: 2, ..Form::BASE },
        ] {
            same(&want, &run(&segs, form, "")?)?;
        }
    }

    /// G10 X1 diameter programming equals its radius rewrite.
    #[test]
    fn diameter_programs_equal_their_radius_rewrite(segs in path()) {
        let want = base(&segs)?;
        for form in [
            Form { diameter: true, ..Form::BASE },
            Form { diameter: true, incremental: true, ..Form::BASE },
            Form { diameter: true, arc: 1, ..Form::BASE },
        ] {
            same(&want, &run(&segs, form, "")?)?;
        }
    }

    /// Lines in polar coordinates (pole at the origin) equal their Cartesian form.
    #[test]
    fn polar_and_cartesian_lines_give_the_same_motion(segs in path()) {
        let want = base(&segs)?;
        same(&want, &run(&segs, Form { polar: true, ..Form::BASE }, "")?)?;
        same(&want, &run(&segs, Form { polar: true, arc: 2, inches: true, ..Form::BASE }, "")?)?;
    }

    /// A G54 page shifts the whole path by its offset.
    #[test]
    fn a_zero_offset_shifts_the_path(segs in path(), page in 1u8..=32,
                                     ox in -200i32..200, oy in -200i32..200, oz in -50i32..50) {
        let want = base(&segs)?;
        let mut opts = options();
        let off = [ox as f64 * 0.5, oy as f64 * 0.25, oz as f64];
        let e = &mut opts.control.offsets.zero[0][page as usize - 1].offset;
        (e.x, e.y, e.z) = (off[0], off[1], off[2]);
        let text = program(&segs, Form::BASE, &format!("G54 P{page}\n"));
        let got = motions(&text, opts).map_err(|d| TestCaseError::fail(format!("{d}\n{text}")))?;
        assert_transformed(&want, &got, &Transform {
            point: &|p| [p[0] + off[0], p[1] + off[1], p[2] + off[2]],
            flips: false,
        })?;
    }

    /// G273 rotates the whole path about the pole (the origin).
    #[test]
    fn a_rotation_rotates_the_path(segs in path(), tenths in -3600i32..3600) {
        let want = base(&segs)?;
        let q = tenths as f64 / 10.0;
        let got = run(&segs, Form::BASE, &format!("G273 Q{q} I0 J0\n"))?;
        let (s, c) = q.to_radians().sin_cos();
        assert_transformed(&want, &got, &Transform {
            point: &|p| [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]],
            flips: false,
        })?;
    }

    /// G173 P scales the whole path about the pole (the origin), Z included.
    #[test]
    fn a_scale_scales_the_path(segs in path(), k in 1u32..40) {
        let want = base(&segs)?;
        let f = k as f64 * 0.125;
        let got = run(&segs, Form::BASE, &format!("G173 P{f} I0 J0 K0\n"))?;
        assert_transformed(&want, &got, &Transform {
            point: &|p| [f * p[0], f * p[1], f * p[2]],
            flips: false,
        })?;
    }

    /// G73 mirrors the path about the pole and reverses the arcs' sense.
    #[test]
    fn a_mirror_mirrors_the_path_and_reverses_arcs(segs in path(), in_x in any::<bool>()) {
        let want = base(&segs)?;
        let (word, sx, sy) = if in_x { ("X-1", -1.0, 1.0) } else { ("Y-1", 1.0, -1.0) };
        let got = run(&segs, Form::BASE, &format!("G73 {word} I0 J0\n"))?;
        assert_transformed(&want, &got, &Transform {
            point: &|p| [sx * p[0], sy * p[1], p[2]],
            flips: true,
        })?;
    }
}

/// Options with tool 1 of radius 0.5 mm (a fifth of the grid, so most generated contours are
/// wide enough to compensate).
fn comp_options() -> stanok_interp::InterpOptions {
    use stanok_canon::setup::{Tool, ToolEdge, ToolKind};
    let mut o = options();
    o.control.tools.tools.insert(
        1,
        Tool {
            number: 1,
            kind: ToolKind::Milling,
            edges: vec![ToolEdge {
                radius: 0.5,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    o
}

/// The base program with radius compensation `g` (41/42) from its first feed line (the entry)
/// to its last segment, a feed line made the G40 exit; None when the path has no such lines.
fn compensated(segs: &[Seg], header: &str, g: u32) -> Option<String> {
    let text = program(segs, Form::BASE, &format!("T1 M06\n{header}"));
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let body = lines.iter().position(|l| l == "G90")? + 1;
    let first = (body..lines.len()).find(|&i| lines[i].starts_with("G01"))?;
    let last = lines.len() - 2;
    if last <= first || !lines[last].starts_with("G01") {
        return None;
    }
    lines[first] = lines[first].replacen("G01", &format!("G01 G{g}"), 1);
    lines[last] = lines[last].replacen("G01", "G01 G40", 1);
    Some(lines.join("\n") + "\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    /// Radius compensation commutes with a zero offset and a rotation: the compensated path of
    /// the moved program is the moved compensated path. Programs whose contour the control
    /// refuses (too narrow for the tool, a reversal) are refused the same way moved — the law
    /// then compares the errors' codes.
    #[test]
    fn compensation_commutes_with_shift_and_rotation(segs in path(), left in any::<bool>(),
                                                     tenths in -3600i32..3600) {
        let g = if left { 41 } else { 42 };
        let Some(base_text) = compensated(&segs, "", g) else { return Ok(()) };
        let q = tenths as f64 / 10.0;
        let Some(rot_text) = compensated(&segs, &format!("G273 Q{q} I0 J0\n"), g) else {
            return Ok(());
        };
        let want = motions(&base_text, comp_options());
        let got = motions(&rot_text, comp_options());
        match (want, got) {
            (Ok(want), Ok(got)) => {
                let (s, c) = q.to_radians().sin_cos();
                assert_transformed(&want, &got, &Transform {
                    point: &|p| [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]],
                    flips: false,
                })?;
            }
            (Err(a), Err(b)) => prop_assert_eq!(a.code, b.code, "{}\n{}", a, b),
            (a, b) => prop_assert!(false, "one refused: {:?} / {:?}\n{}\n{}", a.err(), b.err(), base_text, rot_text),
        }
    }
}

/// A law's map of points (program → moved program), boxed per case.
type PointMap = Box<dyn Fn([f64; 3]) -> [f64; 3]>;

/// The spline pieces of a program after its start line: (control points, weights, knots).
type Piece = (Vec<[f64; 3]>, Vec<f64>, Vec<f64>);

fn spline_pieces(text: &str) -> Result<Vec<Piece>, TestCaseError> {
    let start = text.lines().position(|l| l == "G00 X0 Y0 Z0").unwrap_or(0) as u32 + 1;
    let mut out = Vec::new();
    for item in stanok_interp::Interpreter::from_text(text, options()) {
        let c = item.map_err(|d| TestCaseError::fail(format!("{d}\nin:\n{text}")))?;
        if let (stanok_canon::Canon::SplineFeed(s), true) = (&c.value, c.span.line > start) {
            out.push((s.control_points.clone(), s.weights.clone(), s.knots.clone()));
        }
    }
    Ok(out)
}

fn spline_program(kind: &str, points: &[(i32, i32, i32)], header: &str) -> String {
    let mut s = format!("G71\nG17 G90 G191 G94 F500\n{header}G00 X0 Y0 Z0\n");
    for (i, &(x, y, z)) in points.iter().enumerate() {
        let word = if i == 0 {
            format!("{kind} ")
        } else {
            String::new()
        };
        s.push_str(&format!("{word}X{x} Y{y} Z{z}\n"));
    }
    s.push_str("G01 X0 Y0 Z0\nM30\n");
    s
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    /// Splines are built where the program is written: a programmed shift, a rotation, a uniform
    /// scale and a mirror move every piece's control points by the map, with the same weights and
    /// knots, for ASPLINE, CSPLINE and BSPLINE.
    #[test]
    fn splines_move_with_the_frame(
        points in proptest::collection::vec((-40i32..40, -40i32..40, -5i32..5), 4..9),
        kind in 0usize..3, which in 0usize..4, tenths in -3600i32..3600,
    ) {
        // Consecutive points distinct (a repeated point splits ASPLINE/CSPLINE).
        let mut pts = vec![];
        let mut at = (0, 0, 0);
        for p in points { if p != at { pts.push(p); at = p; } }
        prop_assume!(pts.len() >= 4);
        let kind = ["ASPLINE", "CSPLINE", "BSPLINE"][kind];
        let q = tenths as f64 / 10.0;
        let (s, c) = q.to_radians().sin_cos();
        let (header, map): (String, PointMap) = match which {
            0 => ("G193\nG194 X12.5 Y-7.25 Z3\n".into(), Box::new(|p| [p[0] + 12.5, p[1] - 7.25, p[2] + 3.0])),
            1 => (format!("G273 Q{q} I0 J0\n"), Box::new(move |p| [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]])),
            2 => ("G173 P2.5 I0 J0 K0\n".into(), Box::new(|p| [2.5 * p[0], 2.5 * p[1], 2.5 * p[2]])),
            _ => ("G73 X-1 I0 J0\n".into(), Box::new(|p| [-p[0], p[1], p[2]])),
        };
        let want = spline_pieces(&spline_program(kind, &pts, ""))?;
        let got = spline_pieces(&spline_program(kind, &pts, &header))?;
        prop_assert!(!want.is_empty(), "no spline pieces");
        prop_assert_eq!(want.len(), got.len());
        for (i, (w, g)) in want.iter().zip(&got).enumerate() {
            prop_assert_eq!(w.0.len(), g.0.len());
            for (a, b) in w.0.iter().zip(&g.0) {
                let a = map(*a);
                prop_assert!((0..3).all(|k| (a[k] - b[k]).abs() <= 1e-9),
                    "{} piece {}: control point {:?}, want {:?}", kind, i, b, a);
            }
            prop_assert!(w.1.iter().zip(&g.1).all(|(a, b)| (a - b).abs() <= 1e-12), "weights");
            prop_assert!(w.2.iter().zip(&g.2).all(|(a, b)| (a - b).abs() <= 1e-9), "knots");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    /// A drilling cycle (G81, G83) called at generated holes moves with a zero offset, a rotation
    /// and a mirror: every feed and rapid of every call, by the map. (A scale is not claimed: which
    /// parameters a scale transforms is spec axioma-3 §6's table, a law of its own.)
    #[test]
    fn drilling_cycles_move_with_the_frame(
        holes in proptest::collection::vec((-60i32..60, -60i32..60), 1..6),
        peck in any::<bool>(), which in 0usize..3, tenths in -3600i32..3600,
    ) {
        let q = tenths as f64 / 10.0;
        let (s, c) = q.to_radians().sin_cos();
        let (header, map): (String, PointMap) = match which {
            0 => ("G193\nG194 X12.5 Y-7.25\n".into(), Box::new(|p| [p[0] + 12.5, p[1] - 7.25, p[2]])),
            1 => (format!("G273 Q{q} I0 J0\n"), Box::new(move |p| [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]])),
            _ => ("G73 Y-1 I0 J0\n".into(), Box::new(|p| [p[0], -p[1], p[2]])),
        };
        let program = |header: &str| {
            let mut t = format!("G71\nG17 G90 G191 G94 F500 G98\n{header}G00 X0 Y0 Z0\nG00 Z20\n");
            let cycle = if peck { "G83 Q3=500 Q5=-12 Q6=0.5 Q7=4" } else { "G81 Q3=500 Q5=-8 Q6=0.5" };
            for (i, (x, y)) in holes.iter().enumerate() {
                let g = if i == 0 { format!("{cycle} ") } else { String::new() };
                t.push_str(&format!("{g}X{x} Y{y} Z0\n"));
            }
            t.push_str("G80\nM30\n");
            t
        };
        let (a, b) = (program(""), program(&header));
        let want = motions(&a, options()).map_err(|d| TestCaseError::fail(format!("{d}\n{a}")))?;
        let got = motions(&b, options()).map_err(|d| TestCaseError::fail(format!("{d}\n{b}")))?;
        prop_assert!(want.len() > holes.len(), "the cycles moved");
        assert_transformed(&want, &got, &Transform { point: &*map, flips: false })?;
    }
}
