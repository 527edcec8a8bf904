//! Metamorphic law of the Balt-System CVU (issue 22): on a TT head (FAT=C,0,0,0,A,0,0,0, C outer
//! about Z), a CVU=1 program and its copy rotated by φ about Z — X Y turned by φ, C + φ — give the
//! same motion turned by φ: every end point's tip rotated, A unchanged, C + φ, to 1e-9 mm/deg.
//! Generated programs of 5-axis lines (integer X Y Z, A in ±60°, C in ±170°). 500 programs by
//! default; `STANOK_METAMORPHIC_CASES` raises it.

use proptest::prelude::*;
use stanok_canon::setup::{Tool, ToolEdge};
use stanok_canon::Canon;
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

const TOL: f64 = 1e-9;

fn cases() -> u32 {
    std::env::var("STANOK_METAMORPHIC_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(500)
}

fn options() -> InterpOptions {
    let mut o = InterpOptions::new(Dialect::Balt);
    o.five_axis = Some(stanok_kin::from_fat("C,0,0,0,A,0,0,0").unwrap());
    o.control.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                length: [100.0, 0.0, 0.0],
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    o
}

/// The program: moves (x, y, z, a, c) under CVU=1, rotated by `phi` degrees about Z.
fn program(moves: &[(i32, i32, i32, i32, i32)], phi: f64) -> String {
    let (s, c) = phi.to_radians().sin_cos();
    let mut t = String::from("T1.1 M6\nCVU=1\nG1 F1000\n");
    for &(x, y, z, a, cc) in moves {
        let (x, y) = (x as f64, y as f64);
        t.push_str(&format!(
            "G1 X{:.17} Y{:.17} Z{z} A{a} C{:.17}\n",
            c * x - s * y,
            s * x + c * y,
            cc as f64 + phi
        ));
    }
    t.push_str("G1 A0\nCVU=0\nM30\n");
    t
}

/// The end poses (X Y Z A C) of the motions under CVU=1.
fn ends(text: &str) -> Result<Vec<[f64; 5]>, TestCaseError> {
    let mut out = Vec::new();
    let mut tcp = false;
    for item in Interpreter::from_text(text, options()) {
        let c = item.map_err(|d| TestCaseError::fail(format!("{d}\nin:\n{text}")))?;
        match c.value {
            Canon::SetToolCentrePoint { active, .. } => tcp = active,
            Canon::StraightFeed(m) | Canon::StraightTraverse(m) if tcp => {
                let p = m.end.to_array();
                out.push([p[0], p[1], p[2], p[3], p[5]]);
            }
            _ => {}
        }
    }
    Ok(out)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    #[test]
    fn cvu_program_rotated_about_z_rotates_its_motion(
        moves in proptest::collection::vec(
            (-200i32..200, -200i32..200, -50i32..50, -60i32..60, -170i32..170), 1..8),
        phi in -90i32..90,
    ) {
        let phi = phi as f64;
        let want = ends(&program(&moves, 0.0))?;
        let got = ends(&program(&moves, phi))?;
        prop_assert_eq!(want.len(), moves.len() + 1, "one motion per block");
        prop_assert_eq!(want.len(), got.len());
        let (s, c) = phi.to_radians().sin_cos();
        for (i, (w, g)) in want.iter().zip(&got).enumerate() {
            let turned = [c * w[0] - s * w[1], s * w[0] + c * w[1], w[2], w[3], w[4] + phi];
            for k in 0..5 {
                prop_assert!((turned[k] - g[k]).abs() <= TOL,
                    "motion {}: got {:?}, want {:?}", i, g, turned);
            }
        }
    }
}
