//! AxiOMA technology (spec axioma-2 §3) on the corpus fixtures s6_1, s6_4–s6_8: F as a constant
//! and from FTABLE, the kinematic length F refers to under G93, G60/G64 and BRISK/SOFT as Canon
//! modes, G96/G97 constant surface speed with its limits, S/S<i>=/STABLE. Feeds to 1e-9 mm/min,
//! speeds to 1e-6 rev/min unless stated.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::{AccelerationProfile, Canon, PathMode, Spanned};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

fn program(name: &str) -> String {
    std::fs::read_to_string(corpus("axioma").join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn run_opts(text: &str, o: InterpOptions) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run_with(text, o);
    assert!(err.is_none(), "unexpected error {err:?}");
    cmds
}

fn ok(text: &str) -> Vec<Spanned<Canon>> {
    run_opts(text, options(Dialect::Axioma))
}

/// (N, end X Y Z, feed) of every feed line.
fn feed_lines(cmds: &[Spanned<Canon>]) -> Vec<(Option<u32>, [f64; 3], f64)> {
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some((c.block_number, m.end.xyz(), m.feed)),
            _ => None,
        })
        .collect()
}

fn speeds(cmds: &[Spanned<Canon>]) -> Vec<(Option<u32>, u8, f64)> {
    cmds.iter()
        .filter_map(|c| match c.value {
            Canon::SetSpindleSpeed { spindle, rpm } => Some((c.block_number, spindle, rpm)),
            _ => None,
        })
        .collect()
}

#[test]
fn s6_1_feed_constant_applies_to_its_own_block() {
    let f = feed_lines(&ok(&program("s6_1-feed-constant-fragment-1.nc")));
    assert_eq!(f, [(Some(10), [50.0, 0.0, 0.0], 2000.0)]);
}

#[test]
fn s6_1_ftable_reads_the_configured_channel_table() {
    let mut o = options(Dialect::Axioma);
    o.axioma.feed_table[20] = 4321.0;
    let f = feed_lines(&run_opts(
        &program("s6_1-feed-table-ftable-fragment-3.nc"),
        o,
    ));
    assert_eq!(f, [(Some(10), [50.0, 0.0, 0.0], 4321.0)]);
    // The printed defaults (entries 0…3, 127) and an index outside 0…127.
    let f = feed_lines(&ok(
        "G01 X1 F=FTABLE(0)\nX2 F=FTABLE(3)\nX3 F=FTABLE(127)\n",
    ));
    let feeds: Vec<f64> = f.iter().map(|l| l.2).collect();
    assert_eq!(feeds, [2000.0, 3500.0, 15000.0]);
    let (_, err) = run("G01 X1 F=FTABLE(128)\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "axioma::table-index");
}

#[test]
fn s6_4_inverse_time_feed_uses_the_spatial_length() {
    // N10: L = 20 mm (C does not count while X moves) → 20·6 = 120 mm/min (10 s);
    // N20: L = 40 mm → 40·0.5 = 20 mm/min (2 min).
    let mut o = options(Dialect::Axioma);
    o.axes[5] = true;
    let cmds = run_opts(&program("s6_4-inverse-time-g93-fragment.nc"), o.clone());
    let f = feed_lines(&cmds);
    assert_eq!(f.len(), 2);
    assert!((f[0].2 - 120.0).abs() < 1e-9, "{f:?}");
    assert!((f[1].2 - 20.0).abs() < 1e-9, "{f:?}");
    // Block times: 20/120 min = 10 s, 40/20 min = 120 s.
    assert!((20.0 / f[0].2 * 60.0 - 10.0).abs() < 1e-9);
    assert!((40.0 / f[1].2 * 60.0 - 120.0).abs() < 1e-9);
    // Rotary-only: F is a rotary speed over the Euclidean norm of the rotary axes (§3.2 case 2).
    let f = feed_lines(&run_opts("G93 G01 C90 F2\n", o));
    assert!((f[0].2 - 180.0).abs() < 1e-9, "{f:?}");
}

#[test]
fn g93_in_a_canned_cycle_is_error_617_and_feed_type_change_resets_f() {
    let (_, err) = run(
        "G17 G90 G00 X0 Y0 Z10\nG81 Q1=2 Q2=-5\nG93 F1\nX10 Y10\n",
        Dialect::Axioma,
    );
    let err = err.unwrap();
    assert_eq!(err.code.to_string(), "E617", "{err}");
    let (_, err) = run("G01 X1 F100\nG93\nX2\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "axioma::feed-missing");
    let (_, err) = run("G95 F1\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "E615");
    // A23: a G95 feed move with the spindle stopped (S set, no M03) is 615 too.
    let (_, err) = run("S500\nG95 F0.1\nG01 X10\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "E615");
    let (cmds, err) = run("S500 M03\nG95 F0.1\nG01 X10\n", Dialect::Axioma);
    assert!(err.is_none());
    let f = feed_lines(&cmds);
    assert!((f[0].2 - 50.0).abs() < 1e-9, "0.1 mm/rev × 500 rpm: {f:?}");
}

fn path_modes(cmds: &[Spanned<Canon>]) -> Vec<(Option<u32>, PathMode)> {
    cmds.iter()
        .filter_map(|c| match c.value {
            Canon::SetPathMode { mode, .. } => Some((c.block_number, mode)),
            _ => None,
        })
        .collect()
}

#[test]
fn s6_5_g60_and_g64_reach_the_planner_as_path_modes() {
    let cmds = ok(&program("s6_5-exact-stop-vs-continuous-example-6_1.nc"));
    assert_eq!(
        path_modes(&cmds),
        [
            (None, PathMode::Continuous { tolerance: 0.0 }),
            (Some(20), PathMode::ExactStop),
            (Some(80), PathMode::Continuous { tolerance: 0.0 })
        ]
    );
    let f = feed_lines(&cmds);
    assert_eq!(f.len(), 10);
    assert!(f.iter().all(|l| l.2 == 1800.0));
    assert_eq!(f.last().unwrap().1, [90.0, 0.0, 0.0]);
    // The G60 mode precedes N30's motion, G64 precedes N80's.
    let idx = |pred: &dyn Fn(&Spanned<Canon>) -> bool| cmds.iter().position(pred).unwrap();
    let g60 = idx(&|c| {
        matches!(
            c.value,
            Canon::SetPathMode {
                mode: PathMode::ExactStop,
                ..
            }
        )
    });
    let n30 = idx(&|c| c.block_number == Some(30) && matches!(c.value, Canon::StraightFeed(_)));
    assert!(g60 < n30);
}

#[test]
fn s6_5_feed_change_keeps_each_blocks_feed() {
    let f = feed_lines(&ok(&program("s6_5-feed-change-at-junction-example-6_2.nc")));
    assert_eq!(
        f,
        [
            (Some(30), [30.0, 0.0, 0.0], 1600.0),
            (Some(40), [40.0, 0.0, 0.0], 800.0)
        ]
    );
}

#[test]
fn s6_6_brisk_and_soft_reach_the_planner_from_their_block() {
    let cmds = ok(&program("s6_6-brisk-soft-example-6_3.nc"));
    let profiles: Vec<(Option<u32>, AccelerationProfile)> = cmds
        .iter()
        .filter_map(|c| match c.value {
            Canon::SetAccelerationProfile { profile } => Some((c.block_number, profile)),
            _ => None,
        })
        .collect();
    assert_eq!(
        profiles,
        [
            (None, AccelerationProfile::Brisk),
            (Some(20), AccelerationProfile::Brisk),
            (Some(40), AccelerationProfile::Soft)
        ]
    );
    // SOFT of N40 comes before N40's motion (A25).
    let soft = cmds
        .iter()
        .position(|c| {
            matches!(
                c.value,
                Canon::SetAccelerationProfile {
                    profile: AccelerationProfile::Soft
                }
            )
        })
        .unwrap();
    let n40 = cmds
        .iter()
        .position(|c| c.block_number == Some(40) && matches!(c.value, Canon::StraightFeed(_)))
        .unwrap();
    assert!(soft < n40);
    let f = feed_lines(&cmds);
    assert_eq!(f.last().unwrap(), &(Some(50), [70.0, 0.0, 0.0], 800.0));
}

#[test]
fn s6_7_css_turning_is_clamped_to_lmaxs() {
    // n = 300 000 / (2π·10) = 4774.6 rev/min at X10, 2387.3 at X20: both above LMAXS 1200.
    let cmds = ok(&program("s6_7-css-g96-turning-example-6_4.nc"));
    let s = speeds(&cmds);
    assert_eq!(s, [(Some(20), 0, 1000.0), (Some(30), 0, 1200.0)]);
    let f = feed_lines(&cmds);
    assert_eq!(f.last().unwrap().1, [20.0, 0.0, -240.0]);
    // The law itself, unclamped and clamped.
    let law = stanok_interp::css_rpm;
    assert!((law(300_000.0, 10.0, None, None).unwrap() - 4774.648).abs() < 1e-3);
    assert!((law(300_000.0, 20.0, None, None).unwrap() - 2387.324).abs() < 1e-3);
    assert_eq!(
        law(300_000.0, 20.0, Some(150.0), Some(1200.0)),
        Some(1200.0)
    );
    assert_eq!(
        law(300_000.0, 1000.0, Some(150.0), Some(1200.0)),
        Some(150.0)
    );
    assert_eq!(law(300_000.0, 0.0, Some(150.0), Some(1200.0)), Some(1200.0));
}

#[test]
fn css_follows_the_reference_axis_between_the_limits() {
    // Unclamped: at X50 n = 300000/(2π·50) = 954.93, at X100 477.46.
    let cmds =
        ok("G18 G90 G01 X50 Z0 F100\nG96 S300 LMAXS 5000 LMINS 150 REFAX 1\nX100\nG97\nX50\n");
    let s: Vec<f64> = speeds(&cmds).iter().map(|s| s.2).collect();
    assert_eq!(s.len(), 2, "{s:?}");
    assert!(
        (s[0] - 954.9297).abs() < 1e-3 && (s[1] - 477.4648).abs() < 1e-3,
        "{s:?}"
    );
    // G97 keeps the last speed (PROPOSAL): nothing after it.
    let (_, err) = run("G96\n", Dialect::Axioma);
    assert_eq!(err.unwrap().code.to_string(), "axioma::css-without-speed");
}

#[test]
fn s6_7_css_syntax_with_three_spindles() {
    let cmds = ok(&program("s6_7-css-g96-syntax-fragment.nc"));
    // At X0 (radius 0) every spindle runs at its LMAXS.
    let s = speeds(&cmds);
    assert!(s.contains(&(None, 0, 5000.0)), "{s:?}");
    assert!(s.contains(&(None, 1, 4500.0)), "{s:?}");
    assert!(s.contains(&(None, 2, 5500.0)), "{s:?}");
}

#[test]
fn s6_8_spindle_speed_forms() {
    let cmds = ok(&program("s6_8-spindle-speed-direct-fragment-1.nc"));
    assert_eq!(speeds(&cmds), [(Some(10), 0, 10000.0)]);
    assert!(cmds
        .iter()
        .any(|c| matches!(c.value, Canon::StartSpindle { spindle: 0, .. })));
    let cmds = ok(&program("s6_8-spindle-speed-syntax-example.nc"));
    assert_eq!(speeds(&cmds), [(None, 1, 2000.0)]);
    assert!(!cmds
        .iter()
        .any(|c| matches!(c.value, Canon::StartSpindle { .. })));
    // STABLE(2) = 1200 by default; entry 20 from the configured table.
    let mut o = options(Dialect::Axioma);
    o.axioma.speed_table[20] = 777.0;
    let cmds = run_opts(&program("s6_8-spindle-speed-table-stable-fragment-3.nc"), o);
    assert_eq!(speeds(&cmds), [(Some(10), 0, 1200.0), (Some(10), 1, 777.0)]);
}

#[test]
fn start_up_modes_come_from_the_machine_parameters() {
    let mut o = options(Dialect::Axioma);
    o.axioma.start_exact_stop = true;
    o.axioma.start_soft = true;
    let cmds = run_opts("G01 X10 F100\nG64 BRISK X20\n", o);
    let modes: Vec<String> = cmds
        .iter()
        .filter_map(|c| match c.value {
            Canon::SetPathMode { mode, .. } => Some(format!("{:?} {mode:?}", c.block_number)),
            Canon::SetAccelerationProfile { profile } => {
                Some(format!("{:?} {profile:?}", c.block_number))
            }
            Canon::StraightFeed(_) => Some("move".into()),
            _ => None,
        })
        .collect();
    assert_eq!(
        modes,
        [
            "None ExactStop",
            "None Soft",
            "move",
            "None Brisk",
            "None Continuous { tolerance: 0.0 }",
            "move"
        ]
    );
    // Defaults (G64, BRISK): nothing is sent before the program says so.
    let cmds = ok("G01 X10 F100\n");
    assert!(!cmds.iter().any(|c| matches!(
        c.value,
        Canon::SetPathMode { .. } | Canon::SetAccelerationProfile { .. }
    )));
}
