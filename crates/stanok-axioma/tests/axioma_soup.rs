//! Random AxiOMA programs built from the vocabulary of the compensation, cycle, spline,
//! technology and M-function issues — G41/G42/G143/G144 with G40, CUT3D* with normals and ISD, canned cycles, ASPLINE/CSPLINE/
//! BSPLINE, G75, G110/G111, G96/G97, frames, polar moves — with random (often wrong) values:
//! * the interpreter never panics and always stops (an error is fine; a panic or hang is not);
//! * every motion it emits starts where the previous one ended and every coordinate is finite.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use proptest::prelude::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge};
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

fn block(kind: usize, v: &[f64; 4]) -> String {
    let [a, b, c, d] = *v;
    match kind {
        0 => format!("G00 X{a:.2} Y{b:.2}"),
        1 => format!("G01 X{a:.2} Y{b:.2} F{:.0}", c.abs() * 50.0 + 10.0),
        2 => format!("G02 X{a:.2} Y{b:.2} CR={:.2}", c.abs() + 60.0),
        3 => format!("G03 X{a:.2} Y{b:.2} CR={:.2}", d.abs() + 60.0),
        4 => format!("G41 G01 X{a:.2} Y{b:.2}"),
        5 => format!("G42 G01 X{a:.2} Y{b:.2}"),
        6 => format!("G40 G01 X{a:.2} Y{b:.2}"),
        7 => format!("G143 G01 X{a:.2}"),
        8 => format!("G144 G01 Y{b:.2}"),
        9 => format!("G81 X{a:.2} Y{b:.2} Z0 Q3=500 Q5={:.2} Q6=0.5", -c.abs() - 1.0),
        10 => format!("G83 X{a:.2} Y{b:.2} Z0 Q3=400 Q5={:.2} Q7=2 Q8=1", -c.abs() - 1.0),
        11 => "G80".to_string(),
        12 => format!(
            "G387 Q3=500 Q5=-5 Q6=2 Q7={:.1} Q8={:.1} Q10=1 Q11=0 Q12=2 Q13=0.5\nX{a:.2} Y{b:.2} Z0\nG80",
            c.abs() + 10.0,
            d.abs() + 8.0
        ),
        13 => format!("G389 Q3=500 Q5=-4 Q6=2 Q7={:.1} Q12=2 Q13=1\nX{a:.2} Y{b:.2} Z0\nG80", c.abs() + 10.0),
        14 => format!(
            "ASPLINE X{a:.2} Y{b:.2} F800\nX{:.2} Y{:.2}\nX{c:.2} Y{d:.2}\nX{:.2}\nG01 X0 Y0",
            a + 5.0,
            b - 3.0,
            c + 7.0
        ),
        15 => format!(
            "CSPLINE X{a:.2} Y{b:.2} F800\nX{:.2}\nX{c:.2} Y{d:.2}\nX{:.2} Y{:.2}\nSPLBREAK\nG01 X0",
            a + 4.0,
            c + 3.0,
            d - 2.0
        ),
        16 => format!(
            "G01 X30 Y0 F900\nBSPLINE X30 Y30 PW=0.707 SD=2 PL=0.25\nX{a:.2} Y{b:.2} PW=1 PL=0.1\nX0 Y0 PW=1 PL=0.2\nG01 X10"
        ),
        17 => format!("G75 X{a:.2} F100"),
        18 => "G110 Q1=0 Q3=7\nG111 Q2=1".to_string(),
        19 => format!("G96 S{:.0} LMAXS=3000", c.abs() * 10.0 + 20.0),
        20 => "G97 S800 M03".to_string(),
        21 => format!("G72 X{a:.2} Y{b:.2}"),
        22 => "G73".to_string(),
        23 => format!("G72 X{:.2} Y{:.2}\nG01 X{a:.2}\nG73", c.abs() + 1.0, 1.0),
        24 => "G273".to_string(),
        25 => format!("G16\nG01 R{:.2} Q{:.2}", c.abs() + 1.0, d * 20.0),
        26 => "G15".to_string(),
        27 => "G60".to_string(),
        28 => "SOFT".to_string(),
        29 => "BRISK G64".to_string(),
        30 => "M905 N1=4".to_string(),
        31 => format!("G91 G01 X{a:.2} Y{b:.2}\nG90"),
        // 3D compensation (issue 23): modes, normals, ISD, arcs and splines inside the contour.
        33 => format!("CUT3DC G41 G01 X{a:.2} Y{b:.2} ISD={c:.2}"),
        34 => format!("CUT3DF G42 X{a:.2} Y{b:.2} A4={:.2} C4=1 A5={:.2} B5={c:.2} C5=0.5", d / 40.0, c / 40.0),
        35 => format!("CUT3DCC G41 X{a:.2} Z{:.2} B4={:.2} C4=1", c / 4.0, d / 50.0),
        36 => format!("CUT2DF\nCUT3DFS\nX{a:.2} Y{b:.2} ISD={d:.2}"),
        37 => format!("CUT3DCCD G42 X{a:.2} Y{b:.2}\nG03 X{c:.2} Y{d:.2} CR={:.2}\nG01 X{:.2}", c.abs() + 50.0, a + 1.0),
        _ => format!("G04 X{:.2}", c.abs() / 10.0),
    }
}

fn program() -> impl Strategy<Value = String> {
    prop::collection::vec((0usize..38, prop::array::uniform4(-40.0f64..40.0)), 1..30).prop_map(
        |blocks| {
            let mut text = String::from("G17 G90 G71 G40 G94 F1000\nT1 M06 D1\nM03 S1000\n");
            for (kind, v) in blocks {
                text.push_str(&block(kind, &v));
                text.push('\n');
            }
            text.push_str("G40 G01 X-50 Y-50\nM30\n");
            text
        },
    )
}

fn options() -> InterpOptions {
    let mut c = ControlData::default();
    c.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: 2.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.control = c;
    opts
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]

    #[test]
    fn random_programs_never_panic_and_move_continuously(text in program()) {
        let (cmds, _err) = run_with(&text, options());
        let mut prev: Option<[f64; 9]> = None;
        for c in &cmds {
            let Some(m) = c.value.motion() else { continue };
            let (s, e) = (m.start().to_array(), m.end().to_array());
            prop_assert!(s.iter().chain(e.iter()).all(|x| x.is_finite()), "{text}");
            if let Some(p) = prev {
                let jump = (0..9).map(|k| (p[k] - s[k]).abs()).fold(0.0, f64::max);
                prop_assert!(jump < 1e-6, "jump {jump} before {:?}\n{text}", c.value);
            }
            prev = Some(e);
        }
    }
}
