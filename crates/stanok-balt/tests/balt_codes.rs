//! The Balt-System code tables (`stanok_balt::codes`) and the front end agree: every G code the
//! front end accepts is a row, every row is recognised, the prohibited rows (spec §3.3.1) are
//! refused under CVU=1 as prohibited and outside it as unsupported, and `g_code` finds exactly
//! the rows; every M code the front end accepts is a row of the M table, every row is accepted,
//! runs in its phase (before or after the block's motion) and does what its handler says.

use stanok_balt::codes::{g_code, m_code, Handler, MHandler, Phase, G_CODES, M_CODES};
use stanok_canon::{Canon, Diagnostic};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

fn options() -> InterpOptions {
    let mut o = InterpOptions::new(Dialect::Balt);
    o.five_axis = Some(stanok_kin::from_fat("C,0,0,0,A,0,0,0").expect("characterization"));
    o
}

/// The commands and the first error of `text`.
fn run(text: &str) -> (Vec<Canon>, Option<Diagnostic>) {
    let mut cmds = Vec::new();
    for item in Interpreter::from_text(text, options()) {
        match item {
            Ok(c) => cmds.push(c.value),
            Err(d) => return (cmds, Some(d)),
        }
    }
    (cmds, None)
}

/// The written form of a code × 10 (`G27`, `G1.5`).
fn written(code: u32) -> String {
    if code.is_multiple_of(10) {
        format!("G{}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// Every integer code 0…99 and the decimals x.1…x.9 of 0…9: ×10 values.
fn sweep() -> impl Iterator<Item = u32> {
    (0..100)
        .map(|g| g * 10)
        .chain((0..100).filter(|v: &u32| !v.is_multiple_of(10)))
}

#[test]
fn g_code_finds_exactly_the_rows() {
    for c in G_CODES {
        assert_eq!(g_code(c.code), Some(*c), "{}", c.name);
    }
    for v in sweep() {
        let row = G_CODES.iter().find(|c| c.code == v).copied();
        assert_eq!(g_code(v), row, "{}", written(v));
    }
}

#[test]
fn outside_cvu_the_front_end_accepts_exactly_the_rows_it_builds() {
    for v in sweep() {
        let (_, err) = run(&format!("{}\nM30\n", written(v)));
        let unsupported = err
            .as_ref()
            .is_some_and(|d| d.code.to_string() == "interp::unsupported");
        let built = g_code(v).is_some_and(|c| c.handler != Handler::ProhibitedInCvu);
        assert_eq!(!unsupported, built, "{}: {err:?}", written(v));
        if built {
            assert!(err.is_none(), "{}: {err:?}", written(v));
        }
    }
}

#[test]
fn under_cvu_the_prohibited_rows_and_only_they_are_prohibited() {
    for v in sweep() {
        let (_, err) = run(&format!("CVU=1\nF100\n{}\nM30\n", written(v)));
        let code = err.as_ref().map(|d| d.code.to_string());
        let row = g_code(v);
        match row.map(|c| c.handler) {
            Some(Handler::ProhibitedInCvu) => {
                assert_eq!(
                    code.as_deref(),
                    Some("balt::prohibited-in-cvu"),
                    "{}",
                    written(v)
                );
            }
            Some(_) => assert_eq!(code, None, "{}", written(v)),
            None => assert_eq!(
                code.as_deref(),
                Some("interp::unsupported"),
                "{}",
                written(v)
            ),
        }
    }
}

#[test]
fn each_handler_does_what_its_row_says() {
    // G00/G01: the next block's move is a traverse / a feed move; G91 makes X incremental.
    let (cmds, err) = run("F100\nG91\nG01 X10\nX5\nG00 X1\nG90 X0\nM30\n");
    assert!(err.is_none(), "{err:?}");
    let moves: Vec<(bool, f64)> = cmds
        .iter()
        .filter_map(|c| match c {
            Canon::StraightFeed(m) => Some((false, m.end.x)),
            Canon::StraightTraverse(m) => Some((true, m.end.x)),
            _ => None,
        })
        .collect();
    assert_eq!(
        moves,
        [(false, 10.0), (false, 15.0), (true, 16.0), (true, 0.0)]
    );
    // G06 outside a (BSP …) definition: a spline node, which needs the definition.
    let (_, err) = run("F100\nG06 X10 Y5\nM30\n");
    assert!(err.is_some(), "a G06 node without (BSP …) is refused");
}

#[test]
fn m_code_finds_exactly_the_rows_and_the_front_end_accepts_exactly_them() {
    for m in 0..200u32 {
        let row = M_CODES.iter().find(|c| c.code == m).copied();
        assert_eq!(m_code(m), row, "M{m}");
        // `T` beside every code: M6 needs it, the others leave it used (it is read first).
        let (_, err) = run(&format!("T1.1 M{m}\nM30\n"));
        let unsupported = err
            .as_ref()
            .is_some_and(|d| d.code.to_string() == "interp::unsupported");
        assert_eq!(!unsupported, row.is_some(), "M{m}: {err:?}");
        if row.is_some() {
            assert!(err.is_none(), "M{m}: {err:?}");
        }
    }
}

#[test]
fn each_m_row_runs_in_its_phase_and_does_what_it_says() {
    for row in M_CODES {
        let (cmds, err) = run(&format!("F100\nT1.1 G01 X10 {}\nX20\nM30\n", row.name));
        assert!(err.is_none(), "{}: {err:?}", row.name);
        let first_move = cmds
            .iter()
            .position(|c| matches!(c, Canon::StraightFeed(_)))
            .expect("the block's move");
        let effect = cmds.iter().position(|c| match (row.handler, c) {
            (MHandler::StartSpindle(d), Canon::StartSpindle { direction, .. }) => *direction == d,
            (MHandler::StopSpindle, Canon::StopSpindle { .. }) => true,
            (MHandler::ToolChange, Canon::ChangeTool { tool, .. }) => *tool == 1,
            (MHandler::Stop { optional }, Canon::ProgramStop { optional: o }) => *o == optional,
            (MHandler::End, Canon::ProgramEnd) => true,
            _ => false,
        });
        let effect = effect.unwrap_or_else(|| panic!("{}: no effect in {cmds:?}", row.name));
        match row.handler.phase() {
            Phase::BeforeMotion => assert!(effect < first_move, "{}", row.name),
            Phase::AfterMotion => assert!(effect > first_move, "{}", row.name),
        }
        // M2/M30 end the run at their block: the next block's move never runs.
        let moves = cmds
            .iter()
            .filter(|c| matches!(c, Canon::StraightFeed(_)))
            .count();
        assert_eq!(
            moves,
            if row.handler == MHandler::End { 1 } else { 2 },
            "{}",
            row.name
        );
    }
    // M6 without T is refused, as before the table.
    let (_, err) = run("M6\nM30\n");
    assert_eq!(
        err.map(|d| d.code.to_string()).as_deref(),
        Some("balt::m6-without-t")
    );
}
