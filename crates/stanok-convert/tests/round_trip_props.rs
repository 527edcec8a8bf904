//! Property: random RS274/NGC programs of lines, arcs and helices in all three planes (with extra
//! turns), cubic splines, dwells and technology words round-trip through both targets to the same
//! motions (the comparison and tolerances of `round_trip.rs`).

mod common;
use common::*;
use proptest::prelude::*;
use stanok_convert::{convert, ConvertOptions, Target};
use stanok_syntax::Dialect;

/// One program step, with the numbers it needs (all in a ±50 mm box, feeds 10…5000 mm/min).
#[derive(Debug, Clone)]
enum Step {
    Line([f64; 3], f64),
    Rapid([f64; 3]),
    /// Plane 0/1/2, centre offset in the plane, swept angle (deg, sign = direction), axial travel,
    /// extra turns, feed.
    Arc(usize, [f64; 2], f64, f64, u32, f64),
    /// G5 with control offsets I J P Q and end X Y.
    Cubic([f64; 4], [f64; 2], f64),
    Dwell(f64),
    Tech(usize),
}

fn coord() -> impl Strategy<Value = f64> {
    (-50_000i32..50_000).prop_map(|v| v as f64 / 1000.0)
}

fn step() -> impl Strategy<Value = Step> {
    let feed = (10u32..5000).prop_map(f64::from);
    prop_oneof![
        ([coord(), coord(), coord()], feed.clone()).prop_map(|(p, f)| Step::Line(p, f)),
        [coord(), coord(), coord()].prop_map(Step::Rapid),
        (
            0usize..3,
            [coord(), coord()],
            -359i32..359,
            coord(),
            0u32..3,
            feed.clone()
        )
            .prop_filter("a real arc", |(_, c, a, ..)| *a != 0
                && c[0].hypot(c[1]) > 0.5)
            .prop_map(|(pl, c, a, h, t, f)| Step::Arc(pl, c, f64::from(a), h, t, f)),
        (
            [coord(), coord(), coord(), coord()],
            [coord(), coord()],
            feed
        )
            .prop_map(|(c, e, f)| Step::Cubic(c, e, f)),
        (1u32..3000).prop_map(|ms| Step::Dwell(f64::from(ms) / 1000.0)),
        (0usize..6).prop_map(Step::Tech),
    ]
}

/// The program text; the current position is tracked to compute arc end points on the circle.
fn program(steps: &[Step]) -> String {
    let mut s = String::from("G21 G90 G94 G17\nG0 X0 Y0 Z0\n");
    let mut pos = [0.0f64; 3];
    let f4 = |v: f64| format!("{v:.4}");
    for st in steps {
        match st {
            Step::Line(p, f) => {
                s += &format!("G1 X{} Y{} Z{} F{f}\n", f4(p[0]), f4(p[1]), f4(p[2]));
                pos = *p;
            }
            Step::Rapid(p) => {
                s += &format!("G0 X{} Y{} Z{}\n", f4(p[0]), f4(p[1]), f4(p[2]));
                pos = *p;
            }
            Step::Arc(plane, c, angle, h, turns, f) => {
                let (g, a, b, n, la, lb) = match plane {
                    0 => ("G17", 0, 1, 2, 'I', 'J'),
                    1 => ("G18", 2, 0, 1, 'K', 'I'),
                    _ => ("G19", 1, 2, 0, 'J', 'K'),
                };
                let centre = [pos[a] + c[0], pos[b] + c[1]];
                let th = angle.to_radians();
                let (u, v) = (pos[a] - centre[0], pos[b] - centre[1]);
                let mut end = pos;
                end[a] = centre[0] + u * th.cos() - v * th.sin();
                end[b] = centre[1] + u * th.sin() + v * th.cos();
                end[n] = pos[n] + h;
                let dir = if *angle > 0.0 { "G3" } else { "G2" };
                let p = if *turns > 0 {
                    format!(" P{}", turns + 1)
                } else {
                    String::new()
                };
                s += &format!(
                    "{g} {dir} X{} Y{} Z{} {la}{} {lb}{}{p} F{f}\n",
                    f4(end[0]),
                    f4(end[1]),
                    f4(end[2]),
                    f4(c[0]),
                    f4(c[1])
                );
                // The written end (4 decimals) is where the next move starts.
                pos = end.map(|v| (v * 1e4).round() / 1e4);
            }
            Step::Cubic(c, e, f) => {
                s += &format!(
                    "G17 G5 I{} J{} P{} Q{} X{} Y{} F{f}\n",
                    f4(c[0]),
                    f4(c[1]),
                    f4(c[2]),
                    f4(c[3]),
                    f4(e[0]),
                    f4(e[1])
                );
                pos[0] = e[0];
                pos[1] = e[1];
            }
            Step::Dwell(t) => s += &format!("G4 P{t}\n"),
            Step::Tech(k) => {
                s += [
                    "S1500 M3\n",
                    "M5\n",
                    "M8\n",
                    "M9\n",
                    "T3 M6\n",
                    "G64 P0.01\n",
                ][*k]
            }
        }
    }
    s + "M2\n"
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    #[test]
    fn random_programs_round_trip_in_both_targets(steps in prop::collection::vec(step(), 1..25)) {
        let text = program(&steps);
        let dir = std::env::temp_dir();
        // A random program may be refused (e.g. a G5 whose first control offsets the interpreter
        // rejects); what runs must convert exactly.
        let source = interpret_prefix(&text, Dialect::Rs274ngc, &dir);
        for target in [Target::Rs274ngc, Target::Axioma] {
            let (converted, _) = convert(&source, ConvertOptions::new(target, "prop", "rs274ngc"));
            let again = interpret(&converted, target_dialect(target), &dir)
                .map_err(|e| TestCaseError::fail(format!("{e}\n{text}\n{converted}")))?;
            let mut tally = Tally::default();
            compare(&source, &again, &mut tally)
                .map_err(|e| TestCaseError::fail(format!("{} {e}\n{text}\n{converted}", target.id())))?;
        }
    }
}
