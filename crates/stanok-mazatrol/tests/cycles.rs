//! Canned cycles as runs (`docs/dialects/mazatrol-eia.md` §10–§12); their geometry is tested
//! in `drilling.rs` and `turning.rs`. Hand-computed levels on the plain mill (machine =
//! program) and on `mazak-t`.

mod common;
use common::*;
use stanok_canon::Canon;

/// (kind, z) of the motions: 'r' rapid, 'f' feed.
fn z_moves(r: &Run) -> Vec<(char, f64)> {
    r.canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightTraverse(m) => Some(('r', m.end.z)),
            Canon::StraightFeed(m) => Some(('f', m.end.z)),
            _ => None,
        })
        .collect()
}

#[test]
fn g81_with_g98_and_g99() {
    // From Z20: G99 returns to R2 between holes, G98 to the initial level Z20.
    let r = run(
        "G00 X0 Y0 Z20.\nS500 M03\nG99 G81 X10. Y0 Z-5. R2. F100.\nX20.\nG98 X30.\nG80\n",
        &mill(),
    );
    r.ok();
    let z = z_moves(&r);
    assert_eq!(
        &z[1..],
        &[
            ('r', 20.0),
            ('r', 2.0),
            ('f', -5.0),
            ('r', 2.0),
            ('r', 2.0),
            ('r', 2.0),
            ('f', -5.0),
            ('r', 2.0),
            ('r', 2.0),
            ('r', 2.0),
            ('f', -5.0),
            ('r', 20.0),
        ]
    );
}

#[test]
fn k_repeats_and_k0() {
    // G91: X15 repeated 3 times; K0 stores the cycle without drilling.
    let r = run(
        "G00 X0 Y0 Z10.\nS500 M03\nG91 G81 X15. Z-12. R-8. K3 F100.\nG90 G80\n",
        &mill(),
    );
    r.ok();
    let bottoms: Vec<(f64, f64)> = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some((m.end.x, m.end.z)),
            _ => None,
        })
        .collect();
    assert_eq!(bottoms, vec![(15.0, -10.0), (30.0, -10.0), (45.0, -10.0)]);
    let r = run("G00 Z10.\nG81 X1. Y1. Z-5. R2. K0 F100.\nG80\n", &mill());
    r.ok();
    assert!(!r
        .canon
        .iter()
        .any(|c| matches!(c.value, Canon::StraightFeed(_))));
}

#[test]
fn pecks_taps_and_bores() {
    // G83 Q4 from R2 to Z-10 with d = 1: 2 → -2, out, back to -1, → -6, out, -5 → -10.
    let r = run(
        "G00 X0 Y0 Z10.\nS500 M03\nG99 G83 Z-10. R2. Q4. F100.\nG80\n",
        &mill(),
    );
    r.ok();
    let feeds: Vec<f64> = z_moves(&r)
        .iter()
        .filter(|m| m.0 == 'f')
        .map(|m| m.1)
        .collect();
    assert_eq!(feeds, vec![-2.0, -6.0, -10.0]);
    // G84: the spindle reverses at the bottom and comes back at R.
    let r = run(
        "S500 M03\nG00 Z10.\nG84 X0 Y0 Z-10. R2. F100.\nG80\n",
        &mill(),
    );
    r.ok();
    let dirs: Vec<bool> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::StartSpindle { direction, .. } => {
                Some(direction == stanok_canon::SpindleDirection::Clockwise)
            }
            _ => None,
        })
        .collect();
    assert_eq!(dirs, vec![true, false, true]);
    // M29: a rigid tap at the pitch F/S = 100/500 = 0.2.
    let r = run(
        "S500 M03\nG00 Z10.\nM29\nG84 X0 Y0 Z-10. R2. F100.\nG80\n",
        &mill(),
    );
    r.ok();
    assert!(r.canon.iter().any(|c| c.value
        == Canon::StartSpindleSync {
            pitch: 0.2,
            velocity_mode: false
        }));
    assert!(r
        .canon
        .iter()
        .any(|c| matches!(c.value, Canon::RigidTap { .. })));
    // G76: orient and shift by Q along −X at the bottom.
    let r = run(
        "S500 M03\nG00 Z10.\nG76 X0 Y0 Z-10. R2. Q0.3 F100.\nG80\n",
        &mill(),
    );
    r.ok();
    assert!(r
        .ends()
        .iter()
        .any(|p| (p.x + 0.3).abs() < 1e-12 && p.z == -10.0));
    // G88: the program stops at the bottom.
    let r = run(
        "S500 M03\nG00 Z10.\nG88 X0 Y0 Z-10. R2. F100.\nG80\n",
        &mill(),
    );
    r.ok();
    assert!(r
        .canon
        .iter()
        .any(|c| c.value == Canon::ProgramStop { optional: false }));
    // Missing Z.
    let e = run("G81 X0 Y0 R2. F100.\n", &mill()).error.unwrap();
    assert_eq!(e.message, "G81 needs the bottom Z");
}

#[test]
fn t_series_grooving_threading_and_single_cycles() {
    let m = mazak_t();
    // G74 on the axis (peck drilling): A Z2, Q4 mm pecks, e 1.
    let r = run("T0100\nG00 X0 Z2.\nG74 R1.\nG74 Z-10. Q4000 F0.1\n", &m);
    r.ok();
    let feeds: Vec<f64> = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => Some(m.end.z - 200.0),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, vec![-2.0, -6.0, -10.0]);
    // G76 with k 1.3, Δd 0.4, Δdmin 0.1, d 0.1, m 2: the ten passes of turning.rs's test.
    let r = run(
        "T0100\nG97 S500 M03\nG00 X24. Z5.\nG76 P020060 Q100 R0.1\nG76 X17.4 Z-30. P1300 Q400 F2.\n",
        &m,
    );
    r.ok();
    let threads = r
        .canon
        .iter()
        .filter(|c| matches!(c.value, Canon::StartSpindleSync { pitch, .. } if pitch == 2.0))
        .count();
    assert_eq!(threads, 10);
    // G77: X20 (radius 10) to Z-10 from A (D30, Z2): the cut at radius 10, back at A's radius.
    let r = run("T0100\nG00 X30. Z2.\nG77 X20. Z-10. F0.1\n", &m);
    r.ok();
    let e = r.ends();
    assert_eq!((e[2].x, e[2].z), (10.0, 190.0));
    assert_eq!((e.last().unwrap().x, e.last().unwrap().z), (15.0, 202.0));
}

#[test]
fn polar_and_cylindrical_interpolation() {
    let m = mazak_t();
    // G12.1: from (D20, C0) = virtual (10, 0) to X20 C10 (virtual (10, 10)): C ends at 45°.
    let r = run(
        "T0100\nG94\nG00 X20. C0 Z0\nG12.1\nG01 X20. C10. F100.\nG13.1\n",
        &m,
    );
    r.ok();
    let last = *r.ends().last().unwrap();
    assert!((last.c - 45.0).abs() < 1e-9 && (last.x - 200f64.sqrt()).abs() < 1e-9);
    // The chords take the virtual length at F: 10 mm at 100 mm/min = 6 s in all.
    let secs: f64 = r
        .canon
        .iter()
        .filter_map(|c| match &c.value {
            Canon::StraightFeed(m) => {
                let d = ((m.end.x - m.start.x).powi(2) + (m.end.z - m.start.z).powi(2)).sqrt();
                let len = if d > 0.0 {
                    d
                } else {
                    (m.end.c - m.start.c).abs()
                };
                Some(len / m.feed * 60.0)
            }
            _ => None,
        })
        .sum();
    assert!((secs - 6.0).abs() < 1e-9, "{secs}");
    // Through the centre: refused.
    let e = run("T0100\nG94\nG00 X20. C0 Z0\nG12.1\nG01 X-20. F100.\n", &m)
        .error
        .unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::polar");
    // G07.1 on R20: Z-20 with C90 (developed 31.415927): one move, 37.24 mm at F100.
    let r = run(
        "T0100\nG94\nG00 X40. C0 Z0\nG07.1 C20.\nG01 Z-20. C90. F100.\nG07.1 C0\n",
        &m,
    );
    r.ok();
    let last = *r.ends().last().unwrap();
    assert_eq!((last.z, last.c), (180.0, 90.0));
}

#[test]
fn one_system_codes() {
    let m = mazak_t();
    let r = run("G109 L2\nG110\nG111\nG112 M03 S1000\nG113\n", &m);
    r.ok();
    assert!(r.canon.iter().any(|c| c.value
        == Canon::Comment {
            text: "to system 2: M3 S1000".into()
        }));
    assert!(!r
        .canon
        .iter()
        .any(|c| matches!(c.value, Canon::StartSpindle { .. })));
    assert_eq!(
        r.warnings
            .iter()
            .filter(|w| w.code.to_string() == "mazatrol::single-system")
            .count(),
        1
    );
}
