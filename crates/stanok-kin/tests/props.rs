//! Kinematics properties over every machine type, and the worked examples of the specs as oracles
//! (numbers from the fixture headers of corpus/axioma/s12_*, corpus/mazatrol/*oracle*).
#![allow(clippy::approx_constant)] // the headers print 1/√2 to four places

use proptest::prelude::*;
use stanok_canon::Pose;
use stanok_kin::{
    head_head, head_table, millturn_bc, table_table, FiveAxis, Kinematics, RotaryPair,
};

const PAIRS: [RotaryPair; 3] = [RotaryPair::AB, RotaryPair::AC, RotaryPair::BC];

/// Every machine type for every pair, with off-origin pivots and a tool.
fn machines() -> Vec<(String, FiveAxis)> {
    let mut out = Vec::new();
    for pair in PAIRS {
        out.push((
            format!("head-head {pair:?}"),
            head_head(pair, 37.5).unwrap().with_tool_length(112.0),
        ));
        out.push((
            format!("table-table {pair:?}"),
            table_table(pair, [10.0, 250.0, -500.0], [500.0, 250.0, -20.0])
                .unwrap()
                .with_tool_length(90.0),
        ));
        out.push((
            format!("head-table {pair:?}"),
            head_table(pair, [300.0, -20.0, 0.0], 150.5)
                .unwrap()
                .with_tool_offset([3.0, -2.0, 80.0]),
        ));
    }
    out.push((
        "mill-turn BC".into(),
        millturn_bc(150.5)
            .unwrap()
            .with_linear_offset([250.0, 0.0, 0.0])
            .with_tool_length(100.0),
    ));
    out
}

fn pose(xyz: [f64; 3], a: f64, b: f64, c: f64) -> Pose {
    Pose {
        x: xyz[0],
        y: xyz[1],
        z: xyz[2],
        a,
        b,
        c,
        ..Pose::ZERO
    }
}

fn dist(p: [f64; 9], q: [f64; 9]) -> f64 {
    p.iter()
        .zip(q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// forward(inverse(p)) = p within 1e-9 for every machine type.
    #[test]
    fn forward_of_inverse_is_identity(
        xyz in prop::array::uniform3(-800.0f64..800.0),
        a in -359.0f64..359.0, b in -359.0f64..359.0, c in -359.0f64..359.0,
    ) {
        for (name, m) in machines() {
            let p = pose(xyz, a, b, c);
            let back = m.forward(&m.inverse(&p).unwrap()).unwrap();
            prop_assert!(dist(back.to_array(), p.to_array()) < 1e-9, "{name}: {p:?} -> {back:?}");
        }
    }

    /// orient(t) gives rotary values whose tool vector is t (1e-9), for any reachable t (one the
    /// machine makes at some rotary position), from any current position.
    #[test]
    fn orient_reaches_every_reachable_vector(
        a in -180.0f64..180.0, b in -180.0f64..180.0, c in -180.0f64..180.0,
        ca in -400.0f64..400.0, cb in -400.0f64..400.0, cc in -400.0f64..400.0,
    ) {
        for (name, m) in machines() {
            let t = m.tool_vector(&pose([0.0; 3], a, b, c));
            let current = pose([1.0, 2.0, 3.0], ca, cb, cc);
            let got = m.orient(t, &current).unwrap();
            let t2 = m.tool_vector(&got);
            for k in 0..3 {
                prop_assert!((t[k] - t2[k]).abs() < 1e-9, "{name}: {t:?} vs {t2:?}");
            }
            // Continuity: no axis moves by more than half a turn plus the branch flip.
            for k in 3..6 {
                prop_assert!((got.to_array()[k] - current.to_array()[k]).abs() <= 360.0 + 1e-9);
            }
            prop_assert_eq!(got.xyz(), current.xyz());
        }
    }
}

fn bc_head_l100() -> FiveAxis {
    head_head(RotaryPair::BC, 0.0)
        .unwrap()
        .with_tool_length(100.0)
}

fn assert_xyz(j: [f64; 9], want: [f64; 3], tol: f64) {
    for k in 0..3 {
        assert!((j[k] - want[k]).abs() < tol, "joints {j:?}, want {want:?}");
    }
}

#[test]
fn axioma_example_12_1_rotate_in_place() {
    // Tip (0,0,0), B −75: mount point (−96.5926, 0, 25.8819); at B −37.5: (−60.8761, 0, 79.3353).
    let m = bc_head_l100();
    assert_xyz(
        m.inverse(&pose([0.0; 3], 0.0, -75.0, 0.0)).unwrap(),
        [-96.5926, 0.0, 25.8819],
        1e-4,
    );
    assert_xyz(
        m.inverse(&pose([0.0; 3], 0.0, -37.5, 0.0)).unwrap(),
        [-60.8761, 0.0, 79.3353],
        1e-4,
    );
}

#[test]
fn axioma_example_12_5_direct_axes() {
    // Tip (100, 50, 0), B45 C30: t = (0.6124, 0.3536, 0.7071), machine (161.2372, 85.3553, 70.7107).
    let m = bc_head_l100();
    let p = pose([100.0, 50.0, 0.0], 0.0, 45.0, 30.0);
    let t = m.tool_vector(&p);
    assert!(
        (t[0] - 0.6124).abs() < 1e-4
            && (t[1] - 0.3536).abs() < 1e-4
            && (t[2] - 0.7071).abs() < 1e-4
    );
    assert_xyz(m.inverse(&p).unwrap(), [161.2372, 85.3553, 70.7107], 1e-4);
}

#[test]
fn axioma_example_12_6_euler_choices_and_the_pole() {
    let m = bc_head_l100();
    let start = Pose::ZERO;
    // N50 t = (0, .7071, .7071): C90 B45 (not C−90 B−45: equal time and travel, B ≥ 0 wins).
    let n50 = m
        .orient([0.0, 0.5f64.sqrt(), 0.5f64.sqrt()], &start)
        .unwrap();
    assert!(
        (n50.c - 90.0).abs() < 1e-9 && (n50.b - 45.0).abs() < 1e-9,
        "{n50:?}"
    );
    let n60 = m
        .orient(m.tool_vector(&pose([0.0; 3], 0.0, 45.0, 30.0)), &n50)
        .unwrap();
    assert!(
        (n60.c - 30.0).abs() < 1e-9 && (n60.b - 45.0).abs() < 1e-9,
        "{n60:?}"
    );
    // N70 t = (0,0,1): B0, C undetermined, stays at 30 (no jump at the singular pose).
    let n70 = m.orient([0.0, 0.0, 1.0], &n60).unwrap();
    assert!(
        (n70.c - 30.0).abs() < 1e-12 && n70.b.abs() < 1e-9,
        "{n70:?}"
    );
}

#[test]
fn axioma_example_12_7_rpy_angles() {
    // RPY (45, 15, 90) → C 14.5108, B 46.9205; then (45, 30, 45) → C −18.4349, B 52.2388.
    let m = bc_head_l100();
    let t1 = stanok_kin::orientation::tool_vector_of(&stanok_kin::orientation::rpy_zyx(
        45.0, 15.0, 90.0,
    ));
    let p1 = m.orient(t1.into(), &Pose::ZERO).unwrap();
    assert!(
        (p1.c - 14.5108).abs() < 1e-4 && (p1.b - 46.9205).abs() < 1e-4,
        "{p1:?}"
    );
    let t2 = stanok_kin::orientation::tool_vector_of(&stanok_kin::orientation::rpy_zyx(
        45.0, 30.0, 45.0,
    ));
    let p2 = m.orient(t2.into(), &p1).unwrap();
    assert!(
        (p2.c + 18.4349).abs() < 1e-4 && (p2.b - 52.2388).abs() < 1e-4,
        "{p2:?}"
    );
}

#[test]
fn orientation_choice_respects_travel_limits_and_unwraps() {
    // A C/B head whose B may not go negative, C at 350: t along −X... C180 B45 or C0 B−45; only
    // the first is allowed, and C unwraps to 180 (not −180, nearer 350).
    let axes = vec![
        stanok_kin::RotaryAxis::new('C', stanok_kin::Carrier::Head, [0.0, 0.0, 1.0], [0.0; 3]),
        stanok_kin::RotaryAxis::new('B', stanok_kin::Carrier::Head, [0.0, 1.0, 0.0], [0.0; 3])
            .with_limits(0.0, 120.0),
    ];
    let m = FiveAxis::new(axes, [0.0, 0.0, 1.0]).unwrap();
    let t = [-(0.5f64.sqrt()), 0.0, 0.5f64.sqrt()];
    let p = m.orient(t, &pose([0.0; 3], 0.0, 10.0, 350.0)).unwrap();
    assert!(
        (p.b - 45.0).abs() < 1e-9 && (p.c - 180.0).abs() < 1e-9,
        "{p:?}"
    );
    // Unreachable: a vector below the horizon needs B > 90 + … fine; B limited to [0, 30] cannot
    // give a 45° tilt.
    let axes = vec![
        stanok_kin::RotaryAxis::new('C', stanok_kin::Carrier::Head, [0.0, 0.0, 1.0], [0.0; 3]),
        stanok_kin::RotaryAxis::new('B', stanok_kin::Carrier::Head, [0.0, 1.0, 0.0], [0.0; 3])
            .with_limits(0.0, 30.0),
    ];
    let m = FiveAxis::new(axes, [0.0, 0.0, 1.0]).unwrap();
    assert_eq!(
        m.orient(t, &Pose::ZERO),
        Err(stanok_kin::KinError::OrientationUnreachable)
    );
}

#[test]
fn mazatrol_oracle_d_trunnion_ac() {
    // A parallel to X through y 250, z −500; C centre (500, 250); work offset (500, 250, −450);
    // H1 = 100. Positions are the spindle gauge point.
    let m = table_table(RotaryPair::AC, [0.0, 250.0, -500.0], [500.0, 250.0, 0.0])
        .unwrap()
        .with_tool_length(100.0);
    let w = [500.0, 250.0, -450.0];
    let tip =
        |l: [f64; 3], a: f64, c: f64| pose([l[0] + w[0], l[1] + w[1], l[2] + w[2]], a, 0.0, c);
    assert_xyz(
        m.inverse(&tip([0.0, 0.0, 50.0], 0.0, 0.0)).unwrap(),
        [500.0, 250.0, -300.0],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 10.0, 50.0], 30.0, 0.0)).unwrap(),
        [500.0, 208.6602540, -308.3974596],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 5.0, 50.0], 15.0, 0.0)).unwrap(),
        [500.0, 228.9477246, -302.1133221],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 20.0, 50.0], 30.0, 90.0)).unwrap(),
        [480.0, 200.0, -313.3974596],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 15.0, 50.0], 30.0, 45.0)).unwrap(),
        [489.3933983, 209.1855865, -308.0941588],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 20.0, 50.0], 15.0, 90.0)).unwrap(),
        [480.0, 224.1180955, -303.4074174],
        1e-6,
    );
    // Tool direction in the table frame at A30 C0: (0, 0.5, 0.8660254).
    let t = m.tool_vector(&tip([0.0; 3], 30.0, 0.0));
    assert!(
        t[0].abs() < 1e-9 && (t[1] - 0.5).abs() < 1e-9 && (t[2] - 0.8660254).abs() < 1e-7,
        "{t:?}"
    );
}

#[test]
fn mazatrol_oracle_a_millturn_bc() {
    // Lp = 150.5, r0 = 250 (X counts from the pivot's zero), X on diameter, workpiece origin on C
    // at z −400, H1 = 100.
    let m = millturn_bc(150.5)
        .unwrap()
        .with_linear_offset([250.0, 0.0, 0.0])
        .with_tool_length(100.0);
    let tip = |l: [f64; 3], b: f64, c: f64| pose([l[0], l[1], l[2] - 400.0], 0.0, b, c);
    assert_xyz(
        m.inverse(&tip([0.0, 20.0, 5.0], 45.0, 0.0)).unwrap(),
        [-145.7395026, 20.0, -368.3697513],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 20.0, 0.0], 45.0, 45.0)).unwrap(),
        [-174.0237739, 14.1421356, -373.3697513],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 20.0, -5.0], 45.0, 90.0)).unwrap(),
        [-185.7395026, 0.0, -378.3697513],
        1e-6,
    );
    assert_xyz(
        m.inverse(&tip([0.0, 20.0, -5.0], 90.0, 90.0)).unwrap(),
        [-39.0, 0.0, -555.5],
        1e-6,
    );
}
