//! The lab controls' code tables (`stanok_labs::codes`) and their front ends agree: every G code
//! a front end accepts is a row of its table, every row is recognised (whatever else the block
//! then lacks), and `g_code` finds exactly the rows. NC-31: a G frame on its own and a G frame
//! starting a `*` group; GOST-20999, 2P32 and MC2101: one G word in a block.

mod labs_support;

use labs_support::*;
use stanok_labs::codes::{iso, lookup, nc31};
use stanok_syntax::Dialect;

/// The codes swept: every number 0…199 and a few beyond.
fn sweep() -> impl Iterator<Item = i64> {
    (0..200).chain([250, 500, 940, 999, 1000])
}

fn first_error(r: &Run) -> Option<String> {
    r.error_codes().into_iter().next()
}

#[test]
fn g_code_finds_exactly_the_rows() {
    for g in sweep() {
        let v = g as u32 * 10;
        assert_eq!(
            nc31::g_code(v),
            nc31::G_CODES.iter().find(|c| c.code == v).copied(),
            "NC-31 G{g}"
        );
        assert_eq!(
            iso::g_code(v),
            iso::G_CODES.iter().find(|c| c.code == v).copied(),
            "ISO G{g}"
        );
        assert_eq!(lookup(g, iso::g_code), iso::g_code(v));
    }
}

#[test]
fn word_address_controls_accept_exactly_the_rows() {
    for dialect in [Dialect::Gost20999, Dialect::P2p32, Dialect::Mc2101] {
        for g in sweep() {
            let r = run_text(&format!("N1 G{g}\nN2 M2\n"), dialect, |_| {});
            let unknown = first_error(&r).as_deref() == Some("lab::unknown-g");
            let row = lookup(g, iso::g_code);
            assert_eq!(!unknown, row.is_some(), "{dialect:?} G{g}: {:?}", r.errors);
        }
    }
    // The 2P32's bare G is the G0 row (§3.4); elsewhere G needs its number.
    let r = run_text("N1 G X1000\nN2 M2\n", Dialect::P2p32, |_| {});
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert!(matches!(
        r.motions_of(1).first(),
        Some(stanok_canon::Canon::StraightTraverse(_))
    ));
}

#[test]
fn the_groups_of_the_rows_are_the_groups_the_front_end_enforces() {
    // Two codes of one modal group are refused; of different groups (or LengthComp, which binds
    // axis by axis, and the this-block codes) they combine.
    for a in iso::G_CODES {
        for b in iso::G_CODES {
            if a.code >= b.code {
                continue;
            }
            let r = run_text(
                &format!("N1 {} {}\nN2 M2\n", a.name, b.name),
                Dialect::Gost20999,
                |_| {},
            );
            let clash = first_error(&r).as_deref() == Some("lab::g-group")
                || first_error(&r).as_deref() == Some("lab::one-shot");
            let same = a.group == b.group
                && !matches!(a.group, iso::Group::LengthComp | iso::Group::ThisBlock);
            assert_eq!(clash, same, "{} {}: {:?}", a.name, b.name, r.errors);
        }
    }
}

#[test]
fn nc31_accepts_exactly_the_rows_alone_and_as_group_starts() {
    for g in sweep() {
        let row = lookup(g, nc31::g_code);
        let alone = run_text(&format!("N1 G{g}\nN2 M2\n"), Dialect::Nc31, |_| {});
        let unknown = first_error(&alone).as_deref() == Some("nc31::unknown-g");
        assert_eq!(!unknown, row.is_some(), "G{g} alone: {:?}", alone.errors);
        let group = run_text(
            &format!("N1 G{g}*\nN2 X100*\nN3 Z100\nN4 M2\n"),
            Dialect::Nc31,
            |_| {},
        );
        // A group start the front end refuses says so; a start it takes may still fail on what
        // follows (the frames here are no arc's).
        let refused = group.errors.first().is_some_and(|d| {
            d.code.to_string() == "nc31::bad-group" && d.message.contains("does not start a group")
        });
        let starter = row.is_some_and(|c| !matches!(c.handler, nc31::Handler::SetFeedUnit(_)));
        assert_eq!(!refused, starter, "G{g}* group: {:?}", group.errors);
    }
}

#[test]
fn word_address_m_codes_run_their_row_in_its_phase_or_are_machine_functions() {
    use stanok_canon::Canon;
    for m in 0..100u32 {
        let r = run_text(
            &format!("N1 G1 G90 X10. F100 M{m}\nN2 X20.\nN3 M2\n"),
            Dialect::Gost20999,
            |_| {},
        );
        let row = iso::m_code(m);
        if m == 17 {
            // M17 ends a subprogram only.
            assert_eq!(first_error(&r).as_deref(), Some("lab::m17-in-main"));
            continue;
        }
        assert!(r.errors.is_empty(), "M{m}: {:?}", r.errors);
        let cmds = r.commands_of(1);
        let at_move = cmds
            .iter()
            .position(|c| matches!(c, Canon::StraightFeed(_)))
            .expect("the block's move");
        let effect = cmds.iter().position(|c| match (row.map(|c| c.handler), c) {
            (Some(iso::MHandler::StartSpindle(d)), Canon::StartSpindle { direction, .. }) => {
                *direction == d
            }
            (Some(iso::MHandler::StopSpindle), Canon::StopSpindle { .. }) => true,
            (Some(iso::MHandler::Mist), Canon::Mist { on }) => *on,
            (Some(iso::MHandler::Flood), Canon::Flood { on }) => *on,
            (Some(iso::MHandler::CoolantOff), Canon::Flood { on }) => !*on,
            (Some(iso::MHandler::Stop(o)), Canon::ProgramStop { optional }) => *optional == o,
            (Some(iso::MHandler::End), Canon::ProgramEnd) => true,
            (
                Some(iso::MHandler::ServoSpindle(_)) | None,
                Canon::AuxiliaryFunction { number, .. },
            ) => *number == m,
            _ => false,
        });
        let effect = effect.unwrap_or_else(|| panic!("M{m}: no effect in {cmds:?}"));
        let after = row.is_some_and(|c| c.handler.after_motion());
        assert_eq!(effect > at_move, after, "M{m}: {cmds:?}");
    }
}

#[test]
fn nc31_m_codes_run_their_row_or_are_machine_functions() {
    use stanok_canon::Canon;
    for m in 0..100u32 {
        if m == 17 {
            continue; // a return needs a call
        }
        let r = run_text(&format!("N1 M{m}\nN2 M2\n"), Dialect::Nc31, |_| {});
        assert!(r.errors.is_empty(), "M{m}: {:?}", r.errors);
        let cmds = r.commands_of(1);
        let ok = cmds
            .iter()
            .any(|c| match (nc31::m_code(m).map(|c| c.handler), c) {
                (Some(nc31::MHandler::StartSpindle(d)), Canon::StartSpindle { direction, .. }) => {
                    *direction == d
                }
                (Some(nc31::MHandler::StopSpindle), Canon::StopSpindle { .. }) => true,
                (Some(nc31::MHandler::Stop), Canon::ProgramStop { optional }) => !*optional,
                (Some(nc31::MHandler::End), Canon::ProgramEnd) => true,
                (
                    Some(nc31::MHandler::GearRange) | None,
                    Canon::AuxiliaryFunction { number, .. },
                ) => *number == m,
                _ => false,
            });
        assert!(ok, "M{m}: {cmds:?}");
        let gear = r.state.gear_range;
        assert_eq!(gear, (38..=41).contains(&m).then_some(m), "M{m}");
    }
}
