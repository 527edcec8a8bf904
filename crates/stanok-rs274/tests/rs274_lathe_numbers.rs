//! The RS274/NGC lathe cycles G70/G71 by their numbers: cut depths (levels), cut end points,
//! retracts, entry points, pocket levels and finishing-pass distances of small profiles, each
//! worked out by hand from LinuxCNC's rules (docs/rs274ngc.md, `lathe_cycles/path.rs`) and checked to
//! agree with LinuxCNC 2.9's `rs274` on the same program (the same programs' traces were compared
//! with the shared trace comparison (`stanok_canon::linuxcnc_trace`); the goldens of `tests/rs274/stanok-g7x-*.ngc` hold more).
//!
//! Tolerance: `TOL` = 1e-9 mm. Every expected value is a closed formula of the program's words
//! (no iteration), so only floating-point rounding separates it from the interpreter's result.
//! End points are plane coordinates (z, x) in program mm (G21, G90, no offsets).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::Canon;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

/// One move of the trace: rapid or feed (arcs count as feeds), its end (z, x).
#[derive(Debug, Clone, Copy)]
struct M {
    rapid: bool,
    end: [f64; 2],
}

fn moves(text: &str) -> Vec<M> {
    let (cmds, err) = run(text, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::StraightTraverse(m) => Some(M {
                rapid: true,
                end: [m.end.z, m.end.x],
            }),
            Canon::StraightFeed(m) => Some(M {
                rapid: false,
                end: [m.end.z, m.end.x],
            }),
            Canon::ArcFeed(a) => Some(M {
                rapid: false,
                end: [a.end.z, a.end.x],
            }),
            _ => None,
        })
        .collect()
}

#[track_caller]
fn at(m: &M, rapid: bool, z: f64, x: f64) {
    assert_eq!(m.rapid, rapid, "{m:?}: rapid {rapid} expected");
    assert!(
        (m.end[0] - z).abs() < TOL && (m.end[1] - x).abs() < TOL,
        "{m:?}: expected ({z}, {x})"
    );
}

/// A step: X10 from Z0 to Z-10, up to X14, on to Z-20.
const STEP: &str = "O100 SUB\nG0 X10 Z0\nG1 Z-10\nG1 X14\nG1 Z-20\nO100 ENDSUB\n";

/// G71 Q100 X20 Z3 D0.5 I2 R0.5 over the step. The profile offset by D = 0.5 is
/// X10.5 (Z0 … Z−9.5), the wall Z−9.5 (X10.5 … X14, the concave corner's intersection), an arc
/// about (Z−10, X14) to X14.5 (convex corner) and X14.5 to Z−20. Entry I = S (S is before P0
/// along the cut). Levels X = 20 − 2k while above P0' (X10.5): 20, 18, 16, 14, 12. Each starts on
/// the line S → P0' at Z = 3 − 3·(20 − X)/9.5 and cuts to the offset profile (X ≥ 14.5: its end
/// Z−20; X14, X12: the wall Z−9.5); retract min(R, cut/2) = 0.5 at 45°.
#[test]
fn g71_levels_cut_ends_retracts_and_final_pass() {
    let m = moves(&format!(
        "G18 G21 G90 F100\nG0 X30 Z30\n{STEP}G71 Q100 X20 Z3 D0.5 I2 R0.5\nM2\n"
    ));
    at(&m[1], true, 3.0, 20.0); // the rapid to S
    let mut k = 2; // m[2]: the rapid to the entry point (= S)
    at(&m[k], true, 3.0, 20.0);
    k += 1;
    for (level, end_z) in [
        (20.0, -20.0),
        (18.0, -20.0),
        (16.0, -20.0),
        (14.0, -9.5),
        (12.0, -9.5),
    ] {
        let start_z = 3.0 - 3.0 * (20.0 - level) / 9.5;
        at(&m[k], true, start_z, level); // onto the closing line
        at(&m[k + 1], false, end_z, level); // the cut
        at(&m[k + 2], true, end_z + 0.5, level + 0.5); // retract at 45°
        at(&m[k + 3], true, start_z - 0.5, level + 0.5); // back over the cut
        at(&m[k + 4], true, start_z, level); // down to the level's start
        k += 5;
    }
    // The final pass: rapid to P0', along the offset profile, then up to S's X at its end.
    at(&m[k], true, 0.0, 10.5);
    at(&m[k + 1], false, -9.5, 10.5);
    at(&m[k + 2], false, -9.5, 14.0);
    at(&m[k + 3], false, -10.0, 14.5); // the arc round the convex corner
    at(&m[k + 4], false, -20.0, 14.5);
    at(&m[k + 5], false, -20.0, 20.0);
    assert_eq!(m.len(), k + 6, "nothing after the final pass");
}

/// G70 Q100 X20 Z3 D0.6 E0.1 P2 over the step: pass k at (k − 1)(D − E)/P + E from the profile,
/// k = 2, 1: 0.35 then 0.1. Each: rapid to S, rapid to the pass start (Z0, X10 + d), feed along
/// (X10 + d to Z −10 + d, the wall, the arc to X14 + d, on to Z−20); the tool stays at the end.
#[test]
fn g70_passes_at_their_distances() {
    let m = moves(&format!(
        "G18 G21 G90 F100\nG0 X30 Z30\n{STEP}G70 Q100 X20 Z3 D0.6 E0.1 P2\nM2\n"
    ));
    let mut k = 2;
    for d in [0.35, 0.1] {
        at(&m[k], true, 3.0, 20.0);
        at(&m[k + 1], true, 0.0, 10.0 + d);
        at(&m[k + 2], false, -10.0 + d, 10.0 + d);
        at(&m[k + 3], false, -10.0 + d, 14.0);
        at(&m[k + 4], false, -10.0, 14.0 + d);
        at(&m[k + 5], false, -20.0, 14.0 + d);
        k += 6;
    }
    assert_eq!(m.len(), k);
}

/// A pocket: X10 to Z−5, down to X6 at Z−10, Z−15, up to X12 at Z−18, on to Z−25;
/// G71 Q100 X16 Z2 D0 I1 R0.3. Main levels X16 … X11 (while above P0's X10): X ≥ 13 cut to the
/// end Z−25, X12 to the corner Z−18, X11 to the rising wall at Z = −15 − 3·(X − 6)/6. The final
/// pass cuts the pocket on the same grid: at its top A (Z−5, X10) to B, the first crossing of
/// X10 after A (Z−17); then X9, X8, X7 (above the floor X6) from the falling wall
/// Z = −5 − 5·(10 − X)/4 to the rising one, each retracted by 0.3 at 45°, back, fed onto the
/// wall and down it.
#[test]
fn g71_pocket_levels_on_the_cycle_grid() {
    let m = moves(
        "G18 G21 G90 F100\nG0 X30 Z30\nO100 SUB\nG0 X10 Z0\nG1 Z-5\nG1 X6 Z-10\nG1 Z-15\n\
         G1 X12 Z-18\nG1 Z-25\nO100 ENDSUB\nG71 Q100 X16 Z2 D0 I1 R0.3\nM2\n",
    );
    let rising = |x: f64| -15.0 - 3.0 * (x - 6.0) / 6.0;
    let falling = |x: f64| -5.0 - 5.0 * (10.0 - x) / 4.0;
    let mut k = 3;
    for level in [16.0, 15.0, 14.0, 13.0, 12.0, 11.0] {
        let start_z = 2.0 - 2.0 * (16.0 - level) / 6.0;
        let end_z = if level >= 13.0 { -25.0 } else { rising(level) };
        at(&m[k], true, start_z, level);
        at(&m[k + 1], false, end_z, level);
        at(&m[k + 2], true, end_z + 0.3, level + 0.3);
        k += 5;
    }
    at(&m[k], true, 0.0, 10.0); // P0
    at(&m[k + 1], false, -5.0, 10.0); // A
    at(&m[k + 2], false, -5.0, 10.0); // the pocket's first level starts where the tool is
    k += 3;
    for level in [10.0, 9.0, 8.0, 7.0] {
        if level < 10.0 {
            at(&m[k], false, falling(level), level); // down the wall
            k += 1;
        }
        at(&m[k], false, rising(level), level); // the pocket cut
        at(&m[k + 1], true, rising(level) + 0.3, level + 0.3);
        at(&m[k + 2], true, falling(level) - 0.3, level + 0.3);
        at(&m[k + 3], false, falling(level), level); // fed back onto the wall
        k += 4;
    }
    at(&m[k], false, -10.0, 6.0); // the rest of the wall, the floor, the far wall
    at(&m[k + 1], false, -15.0, 6.0);
    at(&m[k + 2], false, -18.0, 12.0);
    at(&m[k + 3], false, -25.0, 12.0);
    at(&m[k + 4], false, -25.0, 16.0);
    assert_eq!(m.len(), k + 5);
}

/// S in a profile is ignored (LinuxCNC 2.9): under G96 the law the profile's S would set never
/// leaves the interpreter, and the next law sent (G92 moves the spindle centre line in work
/// coordinates) still carries the cutting speed from before the cycle.
#[test]
fn a_profile_s_word_leaves_the_g96_law_alone() {
    let (cmds, err) = run(
        "G18 G21 G90 F100\nG96 S100 D2000 M3\nG0 X30 Z30\nO100 SUB\nG0 X10 Z0 S250\nG1 Z-10\n\
         O100 ENDSUB\nG71 Q100 X20 Z3 D0.5 I2\nG92 X5\nM2\n",
        Dialect::Rs274ngc,
    );
    assert!(err.is_none(), "{err:?}");
    let laws: Vec<f64> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::SetSurfaceSpeedLaw { law: Some(l), .. } => Some(l.mm_per_min),
            _ => None,
        })
        .collect();
    assert_eq!(laws, vec![100_000.0, 100_000.0]);
}

/// G70 under G42.1 (r = 0.2) over a step profile ending at (z −12, x 9), from S = (2, 10) after
/// a compensated entry from (−30, 20). LinuxCNC reads the profile by moving its current point
/// to the profile's end c, so the first pass's rapid to S (no motion in the plane) goes to c,
/// and the corner before the rapid to the pass start P = (1, 2) is worked out from p = S and c
/// (`cutter_comp/stale.rs`): θ = angle(c − p), α = angle(P − p), β = α − θ − π/2 (G42, α
/// wrapped above θ) < 0: concave, so the held entry and the zero move end at
/// c + r/tan((β + π)/2) · u(θ − π/2) — (−12.0014, 9.0196) in rs274's trace.
#[test]
fn g70_under_compensation_starts_from_the_profile_end() {
    let prog = "G18 G21 G40 F400\no100 sub\nG0 X2 Z1\nG1 Z-5\nG1 X6 Z-8\nG1 Z-12\nG0 X9\n\
                o100 endsub\nG0 X20 Z-30\nG42.1 D0.4\nG70 Q100 X10 Z2 D0 E0 P1\nG40\nG0 X20\nM2\n";
    let m = moves(prog);
    let (p, c, e) = ([2.0f64, 10.0f64], [-12.0f64, 9.0f64], [1.0f64, 2.0f64]);
    let theta = (c[1] - p[1]).atan2(c[0] - p[0]);
    let mut alpha = (e[1] - p[1]).atan2(e[0] - p[0]);
    if alpha < theta {
        alpha += std::f64::consts::TAU;
    }
    let beta = alpha - theta - std::f64::consts::FRAC_PI_2;
    assert!(beta < -0.05, "concave: {beta}");
    let back = 0.2 / ((beta + std::f64::consts::PI) / 2.0).tan();
    let g = theta - std::f64::consts::FRAC_PI_2;
    let (z, x) = (c[0] + back * g.cos(), c[1] + back * g.sin());
    assert!(
        (z + 12.0014).abs() < 1e-4 && (x - 9.0196).abs() < 1e-4,
        "({z}, {x})"
    );
    // m[0]: G0 X20 Z-30; m[1]: the entry; m[2]: the first pass's rapid to S.
    at(&m[1], true, z, x);
    at(&m[2], true, z, x);
}

/// Bounds (issue 17): a level step of 10⁻⁷ mm over a 100 mm profile would print 10⁹ levels
/// (LinuxCNC prints them); Stanok stops the cycle at a million moves with a G7X error on the
/// profile's endsub, having emitted nothing of it, in well under a second.
#[test]
fn a_cycle_of_a_billion_levels_is_refused_not_run() {
    let prog = "G18 G21 F100\nO100 SUB\nG0 X0 Z0\nG1 Z-5\nG1 X100 Z-8\nO100 ENDSUB\n\
                G71 Q100 X110 Z1 D0 I0.0000001\nM2\n";
    let (cmds, err) = run(prog, Dialect::Rs274ngc);
    let err = err.expect("refused");
    assert!(
        err.message
            .starts_with("G7X error: the cycle makes more than 1000000 moves"),
        "{}",
        err.message
    );
    assert_eq!(err.span.line, 6, "the profile's endsub");
    // The rapid to S, nothing of the cycle.
    assert_eq!(
        cmds.iter().filter(|c| c.value.motion().is_some()).count(),
        1
    );
}

/// Mutant 191 of seed 17 (LinuxCNC's sample `lathe_g7x_quadrants` with one arc's end moved off its
/// radius): LinuxCNC's pocket loop never ends — `rs274` prints the same rapid without end
/// (565 MB in 10 s) — and Stanok stops it at its bound with the endless-loop wording the runner
/// counts apart.
#[test]
fn a_pocket_loop_linuxcnc_never_ends_stops_at_the_bound() {
    let prog = "G18 G21 F400\nO102 SUB\nG0 Z44 X14\nG1 Z42 X14\nG1 X10 Z42\n\
                G2 K-5 I0 X0 Z37\nG1 X5 Z32\nX-1\nZ30\nO102 ENDSUB\n\
                G71 Q102 X-5 Z46 D0.5 I1 R0.3\nM2\n";
    let (_, err) = run(prog, Dialect::Rs274ngc);
    let err = err.expect("stopped");
    assert!(
        err.message
            .starts_with("G7X error: the cycle makes more than 1000000 moves")
            && err.message.ends_with(": stopping (endless loop?)"),
        "{}",
        err.message
    );
}
