//! Metamorphic law of the GOST-20999 control (issue 22): a path written absolute (G90) and
//! incremental (G91) gives the same motion, to 1e-9 mm, on the generated paths of the AxiOMA laws
//! (lines, rapid moves, Pythagorean arcs with I J from the start point — the dialect's rule in both
//! modes). 500 programs by default; `STANOK_METAMORPHIC_CASES` raises it.

#[path = "../../stanok-axioma/tests/metamorphic/mod.rs"]
mod metamorphic;

use metamorphic::*;
use proptest::prelude::*;
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

/// 3.175·u mm with a point (GOST: at most 3 decimals).
fn mm(u: i64) -> String {
    let t = 3175 * u;
    let sign = if t < 0 { "-" } else { "" };
    format!("{sign}{}.{:03}", t.abs() / 1000, t.abs() % 1000)
}

fn gost(segs: &[Seg], incremental: bool) -> String {
    let mut s = String::from("G17 G90 F500\nG00 X0 Y0 Z0\n");
    s.push_str(if incremental { "G91\n" } else { "G90\n" });
    let mut at = [0i64; 3];
    for seg in segs {
        match *seg {
            Seg::Line { rapid, to } => {
                let p = if incremental {
                    [to[0] - at[0], to[1] - at[1], to[2] - at[2]]
                } else {
                    to
                };
                let g = if rapid { "G0" } else { "G1" };
                s.push_str(&format!("{g} X{} Y{} Z{}\n", mm(p[0]), mm(p[1]), mm(p[2])));
                at = to;
            }
            Seg::Arc { cw, to, centre } => {
                let p = if incremental {
                    [to[0] - at[0], to[1] - at[1]]
                } else {
                    to
                };
                s.push_str(&format!(
                    "{} X{} Y{} I{} J{}\n",
                    if cw { "G2" } else { "G3" },
                    mm(p[0]),
                    mm(p[1]),
                    mm(centre[0] - at[0]),
                    mm(centre[1] - at[1])
                ));
                at = [to[0], to[1], at[2]];
            }
        }
    }
    s.push_str("M2\n");
    s
}

fn run(text: &str) -> Result<Vec<Mv>, TestCaseError> {
    motions(text, InterpOptions::new(Dialect::Gost20999))
        .map_err(|d| TestCaseError::fail(format!("{d}\nin:\n{text}")))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), .. ProptestConfig::default() })]

    #[test]
    fn gost20999_absolute_and_incremental_give_the_same_motion(segs in path()) {
        let want = run(&gost(&segs, false))?;
        prop_assert_eq!(want.len(), segs.len(), "one motion per segment");
        let got = run(&gost(&segs, true))?;
        same(&want, &got)?;
    }
}
