//! Constant surface speed evaluated continuously (issue: G96 in the planner and the simulated
//! machine), through the real command line: `stanok run --trace` writes the spindle speed of every
//! setpoint (column S), and the test checks it against the law the program states.
//!
//! The program faces a part on the built-in lathe from r = 50 mm to r = 5 mm at 200 m/min, limit
//! 3000 rev/min, feed 0.2 mm/rev:
//! * at every setpoint S = clamp(200 000 / (2π·X), …, 3000) to the trace's rounding (1e-3 rev/min
//!   plus what the 1e-6 mm rounding of X makes of it);
//! * the feed per revolution v / (S/60), with v from finite differences of the trace, never exceeds
//!   0.2 mm (+0.5 % for the finite differences) and, in the middle of the cut, is at least 0.2 mm
//!   less the 2 % step of `stanok_motion::css` (−0.5 % again);
//! * the same cut under G94 keeps its mm/min feed while S still follows X.
//!
//! AxiOMA and RS274/NGC state the law in their own words (LMAXS/REFAX, D) and give the same trace.

mod common;
use common::*;

const CUT_SPEED_MM_MIN: f64 = 200_000.0;
const MAX_RPM: f64 = 3000.0;
const FEED_PER_REV: f64 = 0.2;
const SERVO_S: f64 = 0.002;

fn law(x: f64) -> f64 {
    (CUT_SPEED_MM_MIN / (std::f64::consts::TAU * x.abs())).min(MAX_RPM)
}

/// Rows of the trace: (t, X, Z, S).
fn trace(file: &str) -> Vec<[f64; 4]> {
    let out = temp_in("css", &format!("{}.csv", file.replace('/', "_")), "");
    let (code, stdout, stderr) = stanok(&[
        "run",
        file,
        "--machine",
        "lathe",
        "--servo-period",
        &(SERVO_S * 1e3).to_string(),
        "--trace",
        &out,
    ]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,X,Z,S,line"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

/// The facing cut: the rows from the first at Z = 0 (the corner at X50 Z0 is blended under G64,
/// so no row need stand exactly on it) to the turning point near X5 (the retract that follows is
/// a reversal, so the machine stops there between two servo instants).
fn facing_rows(rows: &[[f64; 4]]) -> Vec<[f64; 4]> {
    let start = rows
        .iter()
        .position(|r| r[2].abs() < 1e-9 && r[1] > 40.0)
        .expect("the cut starts near X50 Z0");
    let turn = rows[start..]
        .windows(2)
        .position(|w| w[1][1] > w[0][1])
        .unwrap_or(rows.len() - 1 - start);
    let last = rows[start + turn];
    assert!(last[1] < 5.01 && last[1] >= 5.0 - 1e-9, "turns at {last:?}");
    // The turning row itself may already run the next block's (G97) speed.
    rows[start..start + turn].to_vec()
}

fn check_g95_facing(file: &str) {
    let rows = trace(file);
    let cut = facing_rows(&rows);
    assert!(cut.len() > 100, "{} rows on the cut", cut.len());
    // S follows the law at every setpoint of the cut.
    for r in &cut {
        assert!(
            (r[3] - law(r[1])).abs() < 2e-3,
            "t {} X {}: S {} law {}",
            r[0],
            r[1],
            r[3],
            law(r[1])
        );
    }
    // Feed per revolution from finite differences.
    let mut lowest_mid = f64::INFINITY;
    for w in cut.windows(2) {
        let v = (w[1][1] - w[0][1]).abs() / (w[1][0] - w[0][0]);
        let rev_per_s = 0.5 * (w[0][3] + w[1][3]) / 60.0;
        let per_rev = v / rev_per_s;
        assert!(
            per_rev <= FEED_PER_REV * 1.005,
            "X {}: {per_rev} mm/rev",
            w[0][1]
        );
        if (15.0..40.0).contains(&w[0][1]) {
            lowest_mid = lowest_mid.min(per_rev);
        }
    }
    assert!(
        lowest_mid >= FEED_PER_REV / 1.02 * 0.995,
        "lowest feed per revolution mid-cut {lowest_mid}"
    );
    // At the end of the program the spindle speed is constant again (G97 S500).
    assert!((rows.last().unwrap()[3] - 500.0).abs() < 1e-9);
}

#[test]
fn axioma_g96_g95_facing_follows_the_law_at_every_setpoint() {
    let f = temp_in(
        "css",
        "facing.nc",
        "N10 G18 G90 G00 X50 Z2\n\
         N20 M3 S500\n\
         N30 G95 G96 S200 LMAXS 3000 REFAX 1\n\
         N40 G01 Z0 F0.2\n\
         N50 X5\n\
         N60 G97 S500\n\
         N70 G00 X60\n\
         N80 M30\n",
    );
    check_g95_facing(&f);
}

#[test]
fn rs274_g96_g95_facing_follows_the_law_at_every_setpoint() {
    let f = temp_in(
        "css",
        "facing.ngc",
        "G18 G21 G90\n\
         G0 X50 Z2\n\
         M3 S500\n\
         G95 G96 S200 D3000\n\
         G1 Z0 F0.2\n\
         X5\n\
         G97 S500\n\
         G0 X60\n\
         M30\n",
    );
    check_g95_facing(&f);
}

#[test]
fn g94_feed_stays_while_the_speed_follows_the_position() {
    let f = temp_in(
        "css",
        "facing94.nc",
        "N10 G18 G90 G94 G00 X50 Z2\n\
         N20 M3 S500\n\
         N30 G96 S200 LMAXS 3000 REFAX 1\n\
         N40 G01 Z0 F600\n\
         N50 X5\n\
         N60 M30\n",
    );
    let rows = trace(&f);
    let cut = facing_rows(&rows);
    for r in &cut {
        assert!((r[3] - law(r[1])).abs() < 2e-3, "X {} S {}", r[1], r[3]);
    }
    // 600 mm/min = 10 mm/s in the middle of the cut, whatever S does.
    let mid: Vec<_> = cut
        .windows(2)
        .filter(|w| (15.0..40.0).contains(&w[0][1]))
        .collect();
    assert!(!mid.is_empty());
    for w in mid {
        let v = (w[1][1] - w[0][1]).abs() / (w[1][0] - w[0][0]);
        assert!((v - 10.0).abs() < 1e-3, "v {v}");
    }
}

#[test]
fn the_report_gives_the_spindle_speed_range() {
    let f = temp_in(
        "css",
        "range.nc",
        "N10 G18 G90 G94 G00 X50 Z2\n\
         N20 M3 S500\n\
         N30 G96 S200 LMAXS 3000 REFAX 1\n\
         N40 G01 Z0 F600\n\
         N50 X20\n\
         N60 M30\n",
    );
    let (code, out, err) = stanok(&["run", &f, "--machine", "lathe", "--json"]);
    assert_eq!(code, 0, "{out}{err}");
    let r = json(&out);
    assert_eq!(
        r["spindles"].as_array().unwrap().len(),
        1,
        "{}",
        r["spindles"]
    );
    let s0 = &r["spindles"][0];
    assert_eq!(s0["spindle"], 0);
    let range = [&s0["min_rpm"], &s0["max_rpm"]];
    // Nothing moves at 500 rev/min (the spindle is still at 0 during the first G00): from
    // law(50) = 636.62 where the cut starts to law(20) = 1591.55 where it ends.
    assert!(
        (range[0].as_f64().unwrap() - law(50.0)).abs() < 1e-6,
        "{range:?}"
    );
    assert!(
        (range[1].as_f64().unwrap() - law(20.0)).abs() < 1e-6,
        "{range:?}"
    );
}

#[test]
fn every_spindle_follows_its_own_law() {
    // Spindle 1 (S2=) at 100 m/min, LMAXS2=2000; spindle 0 at 200 m/min, LMAXS 3000. A cut from
    // X40 to X20 ends at law₀(20) = 1591.55 and law₁(20) = 795.77 rev/min.
    let f = temp_in(
        "css",
        "two-spindles.nc",
        "N10 G18 G90 G94 G00 X40 Z2\n\
         N20 M3 S500\n\
         N30 G96 S200 LMAXS 3000 S2=100 LMAXS2=2000\n\
         N40 G01 Z0 F600\n\
         N50 X20\n\
         N60 M30\n",
    );
    let (code, out, err) = stanok(&["run", &f, "--machine", "lathe", "--json"]);
    assert_eq!(code, 0, "{out}{err}");
    let r = json(&out);
    let spindles = r["spindles"].as_array().unwrap();
    assert_eq!(spindles.len(), 2, "{spindles:?}");
    let law1 = |x: f64| 100_000.0 / (std::f64::consts::TAU * x);
    for (s, lo, hi) in [(0, law(40.0), law(20.0)), (1, law1(40.0), law1(20.0))] {
        assert_eq!(spindles[s]["spindle"], s as u64);
        assert!(
            (spindles[s]["min_rpm"].as_f64().unwrap() - lo).abs() < 1e-6,
            "{spindles:?}"
        );
        assert!(
            (spindles[s]["max_rpm"].as_f64().unwrap() - hi).abs() < 1e-6,
            "{spindles:?}"
        );
    }
}
