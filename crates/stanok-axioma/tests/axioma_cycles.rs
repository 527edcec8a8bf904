//! AxiOMA canned cycles (spec axioma-3 §6–§9, manual 11): activation / call / cancel, G98/G99,
//! error 603, drilling G81/G83, turning G276/G281/G282/G288/G289, milling G387/G388/G389. Move
//! lists are those of spec W.6–W.9 (fixtures s11_*); positions to 1e-9 mm.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge};
use stanok_canon::{Canon, DiagCode, Spanned};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn fixture(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap()
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    /// Rapid to X Y Z.
    R([f64; 3]),
    /// Feed move to X Y Z at F.
    F([f64; 3], f64),
    /// Dwell, s.
    D(f64),
    /// Arc to X Y Z about centre (ccw).
    A([f64; 3], [f64; 3], bool),
    /// Spindle synchronisation on (pitch) / off.
    Sync(f64),
    Unsync,
}

fn steps(cmds: &[Spanned<Canon>], n: u32) -> Vec<Step> {
    cmds.iter()
        .filter(|c| c.block_number == Some(n))
        .filter_map(|c| match &c.value {
            Canon::StraightTraverse(m) => Some(Step::R(m.end.xyz())),
            Canon::StraightFeed(m) => Some(Step::F(m.end.xyz(), m.feed)),
            Canon::Dwell { seconds } => Some(Step::D(*seconds)),
            Canon::ArcFeed(a) => Some(Step::A(
                a.end.xyz(),
                a.centre,
                a.axis[2] > 0.0 || a.axis[1] > 0.0,
            )),
            Canon::StartSpindleSync { pitch, .. } => Some(Step::Sync(*pitch)),
            Canon::StopSpindleSync => Some(Step::Unsync),
            _ => None,
        })
        .collect()
}

fn close3(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < TOL)
}

fn same(a: &Step, b: &Step) -> bool {
    match (a, b) {
        (Step::R(p), Step::R(q)) => close3(*p, *q),
        (Step::F(p, f), Step::F(q, g)) => close3(*p, *q) && (f - g).abs() < TOL,
        (Step::D(s), Step::D(t)) => (s - t).abs() < TOL,
        (Step::A(p, c, d), Step::A(q, e, f)) => close3(*p, *q) && close3(*c, *e) && d == f,
        (Step::Sync(p), Step::Sync(q)) => (p - q).abs() < TOL,
        (Step::Unsync, Step::Unsync) => true,
        _ => false,
    }
}

#[track_caller]
fn assert_steps(got: &[Step], want: &[Step]) {
    assert_eq!(got.len(), want.len(), "\n got {got:?}\nwant {want:?}");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(same(g, w), "step {i}: got {g:?}, want {w:?}\n got {got:?}");
    }
}

fn run_ok(text: &str) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run(text, Dialect::Axioma);
    assert!(err.is_none(), "{err:?}");
    cmds
}

use Step::*;

/// G81 at (x, 0), surface Z0, depth `d`, dwell 0.5, from Z20 (spec W.6/W.7).
fn g81(x: f64, d: f64) -> Vec<Step> {
    vec![
        R([x, 0.0, 20.0]),
        R([x, 0.0, 5.0]),
        F([x, 0.0, d], 500.0),
        D(0.5),
        R([x, 0.0, 5.0]),
        R([x, 0.0, 20.0]),
    ]
}

/// G83 of Example 11.6 at (x, 0).
fn g83(x: f64) -> Vec<Step> {
    let mut v = vec![
        R([x, 0.0, 20.0]),
        R([x, 0.0, 5.0]),
        F([x, 0.0, -5.0], 500.0),
    ];
    for k in 2..=6 {
        let k = k as f64;
        v.push(R([x, 0.0, 5.0]));
        v.push(R([x, 0.0, -5.0 * (k - 1.0) + 5.0]));
        v.push(F([x, 0.0, -5.0 * k], 500.0));
    }
    v.push(R([x, 0.0, 5.0]));
    v.push(R([x, 0.0, 20.0]));
    v
}

#[test]
fn example_11_5_g81_drilling() {
    let cmds = run_ok(&fixture("s11_6_1-g81-drilling-example-11_5.nc"));
    assert_steps(&steps(&cmds, 20), &g81(30.0, -30.0));
}

#[test]
fn example_11_6_g83_peck_drilling() {
    let cmds = run_ok(&fixture("s11_6_2-g83-peck-drilling-example-11_6.nc"));
    assert_steps(&steps(&cmds, 20), &g83(30.0));
}

#[test]
fn example_11_1_activation_only_does_not_move() {
    let cmds = run_ok(&fixture("s11_2-cycle-activation-only-example-11_1.nc"));
    assert!(steps(&cmds, 20).is_empty());
}

#[test]
fn example_11_2_activation_parameters_and_calls() {
    let cmds = run_ok(&fixture("s11_2-cycle-activation-and-call-example-11_2.nc"));
    assert!(steps(&cmds, 20).is_empty() && steps(&cmds, 30).is_empty());
    assert_steps(&steps(&cmds, 40), &g83(30.0));
    assert_steps(&steps(&cmds, 50), &g81(50.0, -30.0));
    assert_steps(&steps(&cmds, 60), &g81(70.0, -35.0));
}

#[test]
fn example_11_3_g01_cancels_and_f_is_kept() {
    let cmds = run_ok(&fixture("s11_3-cycle-cancel-by-g01-example-11_3.nc"));
    assert_steps(&steps(&cmds, 20), &g81(10.0, -30.0));
    assert_steps(&steps(&cmds, 30), &g81(30.0, -30.0));
    assert!(steps(&cmds, 40).is_empty());
    // A22: the position after a cycle is its real end (Z20); F is the modal 1800, not Q3.
    assert_steps(&steps(&cmds, 50), &[F([-20.0, 0.0, 20.0], 1800.0)]);
}

#[test]
fn example_11_4_g80_restores_g02() {
    let cmds = run_ok(&fixture("s11_3-cycle-cancel-by-g80-example-11_4.nc"));
    assert_steps(
        &steps(&cmds, 20),
        &[A([0.0, 0.0, 20.0], [20.0, 0.0, 20.0], false)],
    );
    assert_steps(&steps(&cmds, 30), &g81(10.0, -30.0));
    assert_steps(&steps(&cmds, 40), &g81(30.0, -30.0));
    assert!(steps(&cmds, 50).is_empty());
    assert_steps(
        &steps(&cmds, 60),
        &[A([30.0, 0.0, 20.0], [10.0, 0.0, 20.0], false)],
    );
}

#[test]
fn g99_returns_to_safety_distance_2_and_positive_depth_drills_upwards() {
    let cmds = run_ok("G99\nN10 Z20\nN20 G81 X0 Y0 Z0 Q2=3 Q3=100 Q5=-10\nM30\n");
    assert_steps(
        &steps(&cmds, 20),
        &[
            R([0.0, 0.0, 5.0]),
            F([0.0, 0.0, -10.0], 100.0),
            R([0.0, 0.0, 5.0]),
            R([0.0, 0.0, 3.0]),
        ],
    );
    // Q5 > 0: from below, the safety distance is measured downwards (surface Z0 → Z−5).
    let cmds = run_ok("N10 Z-20\nN20 G81 X0 Y0 Z0 Q3=100 Q5=10 Q4=300\nM30\n");
    assert_steps(
        &steps(&cmds, 20),
        &[
            R([0.0, 0.0, -5.0]),
            F([0.0, 0.0, 10.0], 100.0),
            F([0.0, 0.0, -5.0], 300.0),
            R([0.0, 0.0, -20.0]),
        ],
    );
}

#[test]
fn invalid_parameters_give_603_at_the_call_and_nothing_moves() {
    let cases = [
        "G81 Q3=500 X1",                                   // Q5 missing
        "G81 Q3=500 Q5=-3 Q1=0 X1",                        // Q1 < 0.1
        "G83 Q3=500 Q5=-3 X1",                             // Q7 missing
        "G83 Q3=500 Q5=-3 Q7=4 X1",                        // Q7 > |Q5|
        "G81 Q5=-3 X1",                                    // no Q3 and no F
        "G288 Q3=5 Q5=-3 Q6=10 Q7=4 Q9=4 X1",              // overlap ≥ width
        "G387 Q3=5 Q5=-3 Q6=1 Q7=20 Q8=20 Q10=5 Q13=1 X1", // no tool selected
    ];
    for text in cases {
        let (cmds, err) = run(&format!("N1 Z20\nN2 {text}\nM30\n"), Dialect::Axioma);
        let err = err.unwrap_or_else(|| panic!("{text}: no error"));
        assert_eq!(err.code, DiagCode::Manual(603), "{text}: {err}");
        assert!(steps(&cmds, 2).is_empty(), "{text}");
    }
    // A20 and Q words without a cycle.
    let (_, err) = run("G01 G81 Q5=-3 X1 F100\n", Dialect::Axioma);
    assert_eq!(
        err.unwrap().code,
        DiagCode::Stanok("axioma::cycle-and-interpolation")
    );
    let (_, err) = run("Q5=-3\n", Dialect::Axioma);
    assert_eq!(
        err.unwrap().code,
        DiagCode::Stanok("axioma::q-without-cycle")
    );
    // Huge pass counts are bounded.
    let (_, err) = run("Z20\nG83 X0 Q3=100 Q5=-100000 Q7=0.001\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code, DiagCode::Manual(603));
}

#[test]
fn example_11_7_g276_threading_passes_and_2301() {
    let text = fixture("s11_7_1-g276-threading-example-11_7.nc");
    let cmds = run_ok(&text);
    let mut want = vec![R([30.0, 0.0, 80.0]), R([30.0, 0.0, 65.0])];
    for x in [29.5, 29.35, 29.2, 29.134] {
        want.extend([
            R([x, 0.0, 65.0]),
            Sync(1.0),
            F([x, 0.0, 25.0], 1000.0),
            Unsync,
            R([x + 2.0, 0.0, 25.0]),
            R([x + 2.0, 0.0, 65.0]),
            R([30.0, 0.0, 65.0]),
        ]);
    }
    want.push(R([30.0, 0.0, 80.0]));
    assert_steps(&steps(&cmds, 50), &want);
    // Without a spindle position encoder: error 2301 at the call, nothing of N50.
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.axioma.spindle_encoder = false;
    let (cmds, err) = run_with(&text, opts);
    assert_eq!(err.unwrap().code, DiagCode::Manual(2301));
    assert!(steps(&cmds, 50).is_empty());
    // S1000 is below the recommended 60·0.05/(1·0.001) = 3000 rpm: no warning; S4000 warns.
    let mut it = stanok_interp::Interpreter::from_text(&text, InterpOptions::new(Dialect::Axioma));
    for c in it.by_ref() {
        c.unwrap();
    }
    assert!(!it
        .warnings()
        .iter()
        .any(|w| w.code == DiagCode::Stanok("axioma::thread-speed")));
    let fast = text.replace("S1000", "S4000");
    let mut it = stanok_interp::Interpreter::from_text(&fast, InterpOptions::new(Dialect::Axioma));
    for c in it.by_ref() {
        c.unwrap();
    }
    assert!(it
        .warnings()
        .iter()
        .any(|w| w.code == DiagCode::Stanok("axioma::thread-speed")));
    // A thread feed above the channel maximum stops the program.
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.axioma.max_feed = Some(900.0);
    let (_, err) = run_with(&text, opts);
    assert_eq!(err.unwrap().code, DiagCode::Stanok("axioma::thread-feed"));
}

#[test]
fn example_11_8_g281_longitudinal_recess() {
    let cmds = run_ok(&fixture("s11_7_2-g281-longitudinal-recess-example-11_8.nc"));
    let mut want = vec![R([50.0, 0.0, 80.0]), R([35.0, 0.0, 80.0])];
    for k in 1..=5 {
        let k = k as f64;
        want.push(F([30.0 - 2.0 * k, 0.0, 80.0 - 2.0 * k], 500.0));
        want.push(F([30.0 - 2.0 * k, 0.0, 20.0 + k], 500.0));
        if k < 5.0 {
            want.push(R([35.0 - 2.0 * k, 0.0, 20.0 + k]));
            want.push(R([35.0 - 2.0 * k, 0.0, 80.0 - 2.0 * k]));
        }
    }
    want.extend([R([35.0, 0.0, 25.0]), R([50.0, 0.0, 25.0])]);
    // N10 X50 leaves Z at 0: step 1 is the rapid to Z80 (at X50).
    assert_steps(&steps(&cmds, 20), &want);
}

#[test]
fn example_11_9_g282_face_recess() {
    let cmds = run_ok(&fixture("s11_7_3-g282-face-recess-example-11_9.nc"));
    let mut want = vec![R([10.0, 0.0, 50.0]), R([10.0, 0.0, 35.0])];
    for k in 1..=5 {
        let k = k as f64;
        want.push(F([10.0 + 2.0 * k, 0.0, 30.0 - 2.0 * k], 500.0));
        want.push(F([70.0 - k, 0.0, 30.0 - 2.0 * k], 500.0));
        if k < 5.0 {
            want.push(R([70.0 - k, 0.0, 35.0 - 2.0 * k]));
            want.push(R([10.0 + 2.0 * k, 0.0, 35.0 - 2.0 * k]));
        }
    }
    want.extend([R([65.0, 0.0, 35.0]), R([65.0, 0.0, 50.0])]);
    assert_steps(&steps(&cmds, 20), &want);
}

fn groove(
    cmds: &[Spanned<Canon>],
    depth_axis: usize,
    positions: &[f64],
    start: [f64; 3],
    ret: f64,
) {
    let along = 2 - depth_axis;
    let at = |d: f64, l: f64| {
        let mut p = [0.0; 3];
        p[depth_axis] = d;
        p[along] = l;
        p
    };
    // Surface 30, depth 10 towards −, Q1 = 5: plunges to 20 from 35 (both grooves).
    let (bottom, safe) = (20.0, 35.0);
    let mut want = vec![R(start), R(at(safe, positions[0]))];
    for (j, &l) in positions.iter().enumerate() {
        if j > 0 {
            want.push(R(at(safe, l)));
        }
        want.extend([F(at(bottom, l), 500.0), D(0.5), R(at(safe, l))]);
    }
    want.push(R(at(ret, *positions.last().unwrap())));
    assert_steps(&steps(cmds, 20), &want);
}

#[test]
fn example_11_10_g288_and_11_11_g289_grooves() {
    let cmds = run_ok(&fixture(
        "s11_7_4-g288-longitudinal-groove-example-11_10.nc",
    ));
    groove(
        &cmds,
        0,
        &[80.0, 71.0, 62.0, 53.0, 44.0, 35.0, 30.0],
        [50.0, 0.0, 80.0],
        50.0,
    );
    let cmds = run_ok(&fixture("s11_7_5-g289-face-groove-example-11_11.nc"));
    groove(
        &cmds,
        2,
        &[10.0, 19.0, 28.0, 37.0, 46.0, 55.0, 60.0],
        [10.0, 0.0, 50.0],
        50.0,
    );
}

/// Tool T1 with radius `r` selected before the fixture's program.
fn with_tool(text: &str, r: f64) -> Vec<Spanned<Canon>> {
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
    let text = if text.contains("T1") {
        text.to_string()
    } else {
        format!("T1 M6\n{text}")
    };
    let (cmds, err) = run_with(&text, opts);
    assert!(err.is_none(), "{err:?}");
    cmds
}

/// Z levels of the plunges (feed moves along Z only) and the largest distance of any feed point
/// in the plane from `centre` — and checks every layer ends with the Q4 retract and the centre.
fn layers(cmds: &[Spanned<Canon>], n: u32) -> Vec<f64> {
    steps(cmds, n)
        .windows(2)
        .filter_map(|w| match (w[0], w[1]) {
            (R(p), F(q, _)) | (F(p, _), F(q, _)) | (A(p, _, _), F(q, _))
                if (p[0] - q[0]).abs() < TOL && (p[1] - q[1]).abs() < TOL && q[2] < p[2] - TOL =>
            {
                Some(q[2])
            }
            _ => None,
        })
        .collect()
}

/// Plane points of the feed path of block n at depth z, arcs sampled every 5°.
fn path_points(cmds: &[Spanned<Canon>], n: u32) -> Vec<[f64; 2]> {
    let mut pts = Vec::new();
    for c in cmds.iter().filter(|c| c.block_number == Some(n)) {
        match &c.value {
            Canon::StraightFeed(m) => {
                for i in 0..=20 {
                    let t = i as f64 / 20.0;
                    pts.push([
                        m.start.x + t * (m.end.x - m.start.x),
                        m.start.y + t * (m.end.y - m.start.y),
                    ]);
                }
            }
            Canon::ArcFeed(a) => {
                let r = (a.start.x - a.centre[0]).hypot(a.start.y - a.centre[1]);
                let a0 = (a.start.y - a.centre[1]).atan2(a.start.x - a.centre[0]);
                let a1 = (a.end.y - a.centre[1]).atan2(a.end.x - a.centre[0]);
                let ccw = a.axis[2] > 0.0;
                let mut sweep = if ccw {
                    (a1 - a0).rem_euclid(std::f64::consts::TAU)
                } else {
                    -(a0 - a1).rem_euclid(std::f64::consts::TAU)
                };
                if sweep.abs() < 1e-12 {
                    sweep = if ccw {
                        std::f64::consts::TAU
                    } else {
                        -std::f64::consts::TAU
                    };
                }
                for i in 0..=72 {
                    let phi = a0 + sweep * i as f64 / 72.0;
                    pts.push([a.centre[0] + r * phi.cos(), a.centre[1] + r * phi.sin()]);
                }
            }
            _ => {}
        }
    }
    pts
}

#[test]
fn example_11_12_g387_pocket_layers_contour_and_stepover() {
    let cmds = with_tool(
        &fixture("s11_8_1-g387-rectangular-pocket-example-11_12.nc"),
        3.0,
    );
    let s = steps(&cmds, 40);
    assert!(
        same(&s[0], &R([30.0, 0.0, 60.0])) && same(&s[1], &R([30.0, 0.0, 5.0])),
        "{s:?}"
    );
    assert!(same(s.last().unwrap(), &R([30.0, 0.0, 60.0])));
    assert_eq!(layers(&cmds, 40), vec![-2.0, -4.0, -6.0, -8.0, -10.0]);
    // Final tool-centre contour: 32 × 22 about (30,0), corner radius 6, rotated 30° → every point
    // lies inside it, and points on its boundary exist.
    let (c30, s30) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let local = |p: [f64; 2]| {
        let (dx, dy) = (p[0] - 30.0, p[1]);
        [dx * c30 + dy * s30, -dx * s30 + dy * c30]
    };
    let inside = |q: [f64; 2]| {
        let (u, v) = (q[0].abs(), q[1].abs());
        let (a, b, rho) = (16.0, 11.0, 6.0);
        if u > a - rho && v > b - rho {
            (u - (a - rho)).hypot(v - (b - rho)) - rho
        } else {
            (u - a).max(v - b)
        }
    };
    let pts = path_points(&cmds, 40);
    let worst = pts
        .iter()
        .map(|p| inside(local(*p)))
        .fold(f64::MIN, f64::max);
    assert!(
        worst.abs() < 1e-6,
        "the outermost path must be the final contour: {worst}"
    );
    // Stepover: every point of the pocket's tool-centre area is within e/2 = 3.5 of the path
    // (neighbouring paths ≤ e = 7 apart, corners included).
    let mut gap: f64 = 0.0;
    for i in -32..=32 {
        for j in -22..=22 {
            let q = [i as f64 * 0.5, j as f64 * 0.5];
            if inside(q) > 0.0 {
                continue;
            }
            let d = pts
                .iter()
                .map(|p| {
                    let l = local(*p);
                    (l[0] - q[0]).hypot(l[1] - q[1])
                })
                .fold(f64::MAX, f64::min);
            gap = gap.max(d);
        }
    }
    assert!(gap <= 3.5 + 0.1, "largest distance to the path {gap} > e/2");
}

#[test]
fn example_11_13_g388_slot() {
    let text = fixture("s11_8_2-g388-slot-example-11_13.nc");
    // No tool selected in the program: 603 (a tool must be selected).
    let (_, err) = run(&text, Dialect::Axioma);
    assert_eq!(err.unwrap().code, DiagCode::Manual(603));
    let cmds = with_tool(&text, 4.0);
    let s = steps(&cmds, 30);
    let p2 = [30.0 + 35.0 * 0.5f64.sqrt(), 35.0 * 0.5f64.sqrt()];
    let mut want = vec![R([30.0, 0.0, 60.0]), R([30.0, 0.0, 5.0])];
    for k in 1..=5 {
        let at = if k % 2 == 1 { [30.0, 0.0] } else { p2 };
        let to = if k % 2 == 1 { p2 } else { [30.0, 0.0] };
        want.push(F([at[0], at[1], -2.0 * k as f64], 500.0));
        want.push(F([to[0], to[1], -2.0 * k as f64], 500.0));
    }
    assert_steps(&s[..12], &want);
    // Four racetracks of half-width 1, 2, 3, 3.5: the outermost touches 3.5 from the centre line.
    let pts = path_points(&cmds, 30);
    let u = [0.5f64.sqrt(), 0.5f64.sqrt()];
    let dist = |p: [f64; 2]| {
        let t = ((p[0] - 30.0) * u[0] + p[1] * u[1]).clamp(0.0, 35.0);
        (p[0] - 30.0 - t * u[0]).hypot(p[1] - t * u[1])
    };
    let max = pts.iter().map(|p| dist(*p)).fold(0.0, f64::max);
    assert!((max - 3.5).abs() < 1e-6, "{max}");
    assert_eq!(s.iter().filter(|x| matches!(x, A(..))).count(), 4 * 3);
    // The last racetrack ends at its cap apex behind P2 (3.5 beyond it along the slot axis);
    // there the tool retracts (Q4 = rapid) and returns to the initial Z60.
    let apex = [p2[0] + 3.5 * u[0], p2[1] + 3.5 * u[1]];
    assert!(
        same(&s[s.len() - 2], &R([apex[0], apex[1], 5.0])),
        "{:?}",
        &s[s.len() - 2..]
    );
    assert!(same(s.last().unwrap(), &R([apex[0], apex[1], 60.0])));
}

#[test]
fn example_11_14_g389_circular_pocket() {
    let cmds = with_tool(
        &fixture("s11_8_3-g389-circular-pocket-example-11_14.nc"),
        4.0,
    );
    assert_eq!(layers(&cmds, 30), vec![-2.0, -4.0, -6.0, -8.0, -10.0]);
    // Circles of radius 16/3, 32/3, 16 about (30,0), counter-clockwise, in every layer.
    let s = steps(&cmds, 30);
    let radii: Vec<f64> = s
        .iter()
        .filter_map(|x| match x {
            A(p, c, true) => Some((p[0] - c[0]).hypot(p[1] - c[1])),
            _ => None,
        })
        .collect();
    assert_eq!(radii.len(), 15);
    for (i, r) in radii.iter().enumerate() {
        let want = 16.0 / 3.0 * ((i % 3) as f64 + 1.0);
        assert!((r - want).abs() < 1e-9, "{i}: {r}");
    }
}

#[test]
fn mirror_reverses_the_pocket_direction() {
    // G73 X-1 mirrors X: the CCW circles come out clockwise in machine coordinates.
    let cmds = with_tool(
        "Z60\nG73 X-1\nN30 G389 Q3=500 Q5=-2 Q6=2 Q7=40 Q12=4 Q13=1 X30 Y0 Z0\nM30\n",
        4.0,
    );
    let arcs: Vec<bool> = steps(&cmds, 30)
        .iter()
        .filter_map(|x| match x {
            A(_, c, ccw) => Some({
                assert!((c[0] + 30.0).abs() < 1e-9);
                *ccw
            }),
            _ => None,
        })
        .collect();
    assert!(!arcs.is_empty() && arcs.iter().all(|c| !c));
}

#[test]
fn incremental_calls_are_relative_to_the_real_end_of_the_previous_cycle() {
    // A22: after a cycle the tool is at the call point in the plane and at the return level
    // (Z20) on the tool axis; under G91 the next call point is relative to that.
    let cmds = run_ok("N1 Z20\nN2 G91 G81 X10 Z-20 Q3=100 Q5=-5\nN3 X10 Z-20\nM30\n");
    let hole = |x: f64| {
        vec![
            R([x, 0.0, 20.0]),
            R([x, 0.0, 5.0]),
            F([x, 0.0, -5.0], 100.0),
            R([x, 0.0, 5.0]),
            R([x, 0.0, 20.0]),
        ]
    };
    assert_steps(&steps(&cmds, 2), &hole(10.0));
    assert_steps(&steps(&cmds, 3), &hole(20.0));
}
