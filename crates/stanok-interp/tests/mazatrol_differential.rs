//! Mazatrol EIA/ISO against RS274/NGC on their common ground, on seeded generated programs: G00,
//! G01 and G02/G03 with R in G17 (both languages are Fanuc's there), absolute positions written
//! with a decimal point. Two laws:
//! * differential: the same text run by the Mazatrol front end and by the RS274/NGC front end gives
//!   the same motion commands (kind, end, arc centre and turn, feed);
//! * metamorphic: the Mazatrol program rewritten in G91 with every increment passed through a
//!   macro variable (`#101 = 12.345` then `X#101`) gives the same motion as the absolute one.
//!
//! Coordinates are whole micrometres (±60 mm), so the increments print exactly; arcs have a chord
//! of at least 1 mm and |R| at least 0.5 mm more than half of it (no full circles, no R at the
//! tangency limit, where the two controls may legitimately round differently). Tolerance: 1e-9 mm
//! on ends, 1e-7 mm on centres (computed from R by each front end's own arithmetic).

use proptest::prelude::*;
use stanok_canon::{Canon, Pose};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

#[derive(Debug, Clone)]
enum Move {
    Rapid([i64; 3]),
    Line([i64; 3], u32),
    /// Clockwise?, end XY, R in µm (negative: the arc over 180°), feed.
    Arc(bool, [i64; 2], i64, u32),
}

fn mm(um: i64) -> String {
    let sign = if um < 0 { "-" } else { "" };
    let a = um.unsigned_abs();
    format!("{sign}{}.{:03}", a / 1000, a % 1000)
}

fn moves() -> impl Strategy<Value = Vec<Move>> {
    let c = -60_000i64..60_000;
    let feed = prop::sample::select(vec![100u32, 250, 1000, 2500]);
    let one = prop_oneof![
        1 => (c.clone(), c.clone(), c.clone()).prop_map(|(x, y, z)| Move::Rapid([x, y, z])),
        2 => (c.clone(), c.clone(), c.clone(), feed.clone()).prop_map(|(x, y, z, f)| Move::Line([x, y, z], f)),
        2 => (any::<bool>(), c.clone(), c.clone(), 500i64..40_000, any::<bool>(), feed)
            .prop_map(|(cw, x, y, extra, big, f)| Move::Arc(cw, [x, y], if big { -extra } else { extra }, f)),
    ];
    prop::collection::vec(one, 1..20)
}

/// The three texts: RS274/NGC, Mazatrol absolute, Mazatrol incremental through variables. Arcs
/// whose chord is under 1 mm are dropped (from all three); R gets half the chord added.
fn texts(moves: &[Move]) -> (String, String, String) {
    let mut ngc = String::from("G21 G17 G90 G94 G40 G49 G80\n");
    let mut eia = String::from("G21 G17 G90 G94 G40 G49 G80\n");
    let mut inc = String::from("G21 G17 G91 G94 G40 G49 G80\n");
    let mut at = [0i64; 3];
    for m in moves {
        let (word, end, r, feed) = match *m {
            Move::Rapid(p) => ("G00", p, None, None),
            Move::Line(p, f) => ("G01", p, None, Some(f)),
            Move::Arc(cw, [x, y], r, f) => {
                let chord = (((x - at[0]) as f64).powi(2) + ((y - at[1]) as f64).powi(2)).sqrt();
                if chord < 1000.0 {
                    continue;
                }
                let half = (chord / 2.0).ceil() as i64;
                let r = if r < 0 { r - half } else { r + half };
                (
                    if cw { "G02" } else { "G03" },
                    [x, y, at[2]],
                    Some(r),
                    Some(f),
                )
            }
        };
        let abs_words = format!("X{} Y{} Z{}", mm(end[0]), mm(end[1]), mm(end[2]));
        let extra = match (r, feed) {
            (Some(r), Some(f)) => format!(" R{} F{f}.", mm(r)),
            (None, Some(f)) => format!(" F{f}."),
            _ => String::new(),
        };
        ngc.push_str(&format!("{word} {abs_words}{extra}\n"));
        eia.push_str(&format!("{word} {abs_words}{extra}\n"));
        inc.push_str(&format!(
            "#101 = {}\n#102 = {}\n#103 = {}\n{word} X#101 Y#102 Z#103{extra}\n",
            mm(end[0] - at[0]),
            mm(end[1] - at[1]),
            mm(end[2] - at[2])
        ));
        at = end;
    }
    ngc.push_str("M2\n");
    eia.push_str("M30\n");
    inc.push_str("M30\n");
    (ngc, eia, inc)
}

/// A motion as compared: kind, end, centre, turns and sense of rotation (arcs), feed.
#[derive(Debug, Clone, PartialEq)]
struct Motion {
    kind: &'static str,
    end: Pose,
    centre: Option<[f64; 2]>,
    turn: (u32, i8),
    feed: f64,
}

fn motions(text: &str, dialect: Dialect) -> Result<Vec<Motion>, String> {
    let opts = InterpOptions::new(dialect);
    let mut out = Vec::new();
    for c in Interpreter::from_text(text, opts) {
        let c =
            c.map_err(|d| format!("{dialect:?} line {}: {} {}", d.span.line, d.code, d.message))?;
        out.push(match c.value {
            Canon::StraightTraverse(m) => Motion {
                kind: "rapid",
                end: m.end,
                centre: None,
                turn: (0, 0),
                feed: 0.0,
            },
            Canon::StraightFeed(m) => Motion {
                kind: "line",
                end: m.end,
                centre: None,
                turn: (0, 0),
                feed: m.feed,
            },
            Canon::ArcFeed(a) => Motion {
                kind: "arc",
                end: a.end,
                centre: Some([a.centre[0], a.centre[1]]),
                turn: (a.turns, a.axis[2].signum() as i8),
                feed: a.feed,
            },
            _ => continue,
        });
    }
    Ok(out)
}

fn same(a: &[Motion], b: &[Motion]) -> Result<(), String> {
    if a.len() != b.len() {
        return Err(format!("{} motions vs {}", a.len(), b.len()));
    }
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let ends = [(x.end.x, y.end.x), (x.end.y, y.end.y), (x.end.z, y.end.z)];
        let centre_ok = match (x.centre, y.centre) {
            (Some(p), Some(q)) => (p[0] - q[0]).abs() < 1e-7 && (p[1] - q[1]).abs() < 1e-7,
            (None, None) => true,
            _ => false,
        };
        if x.kind != y.kind
            || ends.iter().any(|(p, q)| (p - q).abs() > 1e-9)
            || !centre_ok
            || x.turn != y.turn
            || (x.feed - y.feed).abs() > 1e-9
        {
            return Err(format!("motion {i}: {x:?} vs {y:?}"));
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mazatrol_moves_as_rs274_and_g91_through_variables_moves_as_g90(ms in moves()) {
        let (ngc, eia, inc) = texts(&ms);
        let reference = motions(&ngc, Dialect::Rs274ngc).map_err(|e| TestCaseError::fail(format!("{e}\n{ngc}")))?;
        let absolute = motions(&eia, Dialect::Mazatrol).map_err(|e| TestCaseError::fail(format!("{e}\n{eia}")))?;
        let incremental = motions(&inc, Dialect::Mazatrol).map_err(|e| TestCaseError::fail(format!("{e}\n{inc}")))?;
        prop_assert!(same(&reference, &absolute).is_ok(), "{}\n{eia}", same(&reference, &absolute).unwrap_err());
        prop_assert!(same(&absolute, &incremental).is_ok(), "{}\n{inc}", same(&absolute, &incremental).unwrap_err());
    }
}

/// The law on one hand-checked program: a quarter arc of R10 from (10, 0) to (0, 10) about the
/// origin, counter-clockwise, then the 270° arc back with R−10.
#[test]
fn a_hand_checked_pair_of_arcs() {
    let text = "G90 G17 G00 X10. Y0 Z0\nG03 X0 Y10. R10. F100.\nG03 X10. Y0 R-10.\nM30\n";
    let m = motions(text, Dialect::Mazatrol).unwrap();
    assert_eq!(m.len(), 3);
    let c1 = m[1].centre.unwrap();
    let c2 = m[2].centre.unwrap();
    assert!(c1[0].abs() < 1e-12 && c1[1].abs() < 1e-12, "{c1:?}");
    assert!(c2[0].abs() < 1e-12 && c2[1].abs() < 1e-12, "{c2:?}");
    assert_eq!((m[2].end.x, m[2].end.y), (10.0, 0.0));
    let ngc = text.replace("M30", "M2");
    same(&motions(&ngc, Dialect::Rs274ngc).unwrap(), &m).unwrap();
}
