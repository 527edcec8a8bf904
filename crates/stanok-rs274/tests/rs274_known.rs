//! RS274/NGC against LinuxCNC where a trace alone does not say it: the known differences from
//! the standalone `rs274` (Stanok follows LinuxCNC's task, milltask; docs/linuxcnc.md "Known
//! differences", each with the machine position milltask ends at), the arc tolerance of the
//! `linuxcnc` machine, and the order and wording of reading errors. The traces themselves are
//! compared in rs274_traces.rs.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_syntax::Dialect;

/// The machine position (mm) where the last straight move ends.
fn last_straight_end(cmds: &[stanok_canon::Spanned<stanok_canon::Canon>]) -> [f64; 3] {
    cmds.iter()
        .rev()
        .find_map(|c| match &c.value {
            stanok_canon::Canon::StraightTraverse(m) | stanok_canon::Canon::StraightFeed(m) => {
                Some(m.end.xyz())
            }
            _ => None,
        })
        .expect("a straight move")
}

fn assert_at(cmds: &[stanok_canon::Spanned<stanok_canon::Canon>], want: [f64; 3], why: &str) {
    let end = last_straight_end(cmds);
    for k in 0..3 {
        assert!(
            (end[k] - want[k]).abs() < 1e-9,
            "{why}: ends at {end:?}, not {want:?}"
        );
    }
}

// Known differences from the standalone rs274 (docs/linuxcnc.md): Stanok does what LinuxCNC's
// task (`milltask`, run headless by ../shared/tools/lcnc-sim) does. Each program below ran there;
// the final machine position of its trace is the number asserted.

/// `T1 M6 G43` in one block, then `G10 L10 P1 Z45` and `G43`: milltask's spindle stays at machine
/// Z 50 (the new offset is 50 − 45 = 5); rs274 resynchronises after M6 without the offset, takes
/// 15 and would end at Z 60.
#[test]
fn known_difference_t_m6_g43_in_one_block_as_milltask() {
    let program = "G21 G90 G94 F3000\nG10 L1 P1 Z10\nG0 X0 Y0 Z50\nT1 M6 G43\nG10 L10 P1 Z45\nG43\nG0 X1\nG0 Z45\nG0 X2\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    assert_at(&cmds, [2.0, 0.0, 50.0], "milltask ends at X2 Z50");
}

/// Before any M6 the spindle is empty: `#<_current_tool>` is 0 and `G43` applies no offset even
/// after `G10 L1 P1 Z7`; milltask ends at machine Y 1, Z 20. rs274 starts with table slot 1 in the
/// spindle (G43 takes 7: Z 27).
#[test]
fn known_difference_the_spindle_is_empty_at_start_as_milltask() {
    let program =
        "G21 G90 G94 F3000\nG0 Y[#<_current_tool> + 1]\nG10 L1 P1 Z7\nG43\nG0 Z20\nG0 X5\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    assert_at(&cmds, [5.0, 1.0, 20.0], "milltask ends at X5 Y1 Z20");
}

/// With the spindle empty milltask reads `#<_current_pocket>` as −1 (rs274: 1, its slot 1); after
/// `T2 M6` it is tool 2's pocket.
#[test]
fn known_difference_the_empty_spindle_has_pocket_minus_one_as_milltask() {
    let program =
        "G21 G90 G94 F3000\nG0 X[#<_current_pocket>]\nT2 M6\nG0 Y[#<_current_pocket>]\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    assert_at(
        &cmds,
        [-1.0, 2.0, 0.0],
        "pocket -1 empty, then tool 2's pocket 2",
    );
}

/// `M61 Q1` declares tool 1 loaded: `#<_current_tool>` = 1, #5400 = 1 and G43 takes its offset 7;
/// milltask ends at machine X 5, Y 2, Z 27. rs274 leaves its tool data as they were.
#[test]
fn known_difference_m61_loads_the_tool_data_as_milltask() {
    let program = "G21 G90 G94 F3000\nG10 L1 P1 Z7\nM61 Q1\nG43\nG0 X[#<_current_tool> + 1] Y[#5400 + 1] Z20\nG0 X5\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    assert_at(&cmds, [5.0, 2.0, 27.0], "milltask ends at X5 Y2 Z27");
}

/// `G43` and then `M61 Q2` (or `T2 M6`) with no move between: the standalone rs274 resynchronises
/// its position from its stub, which has not seen the offset, and the next `G1 X5` goes to program
/// Z 0 (machine Z 10); milltask keeps the program position, Z −10, and ends at machine Z 0.
#[test]
fn known_difference_m6_or_m61_after_an_offset_without_a_move_as_milltask() {
    for change in ["M61 Q2", "T2 M6"] {
        let program = format!("G21 G90 G94 F3000\nG10 L1 P1 Z10\nG10 L1 P2 Z0\nT1 M6\nG43\n{change}\nG1 X5\nG1 Y3\nM2\n");
        let (cmds, err) = run(&program, Dialect::Rs274ngc);
        assert!(err.is_none(), "{err:?}");
        assert_at(&cmds, [5.0, 3.0, 0.0], "milltask ends at X5 Y3 Z0");
    }
}

/// A G5 cubic (rs274 prints it as `NURBS_FEED`) and then `T1 M6` with no move between: the
/// standalone rs274 resynchronises from its stub, which has not followed the spline, and the next
/// `G0 X-3.661` goes to Y 0; milltask (lcnc-sim, 2026-11-27) ends at X −3.661, Y −7.457, Z 0. The
/// shrunk program of seed 20261130, 557.
#[test]
fn known_difference_m6_after_a_g5_spline_without_a_move_as_milltask() {
    let program =
        "G21 G90 F1000\nG0 X0 Y0 Z0\nG5 I1.921 J3 P5.813 Q4.3 X6 Y-7.457\nT1 M6\nG0 X-3.661\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    assert_at(
        &cmds,
        [-3.661, -7.457, 0.0],
        "milltask ends at X-3.661 Y-7.457 Z0",
    );
}

/// G84 with the spindle counterclockwise: LinuxCNC's message, on the G84 block; rs274 has already
/// issued the cycle's first rapid when it finds the error, Stanok's block leaves nothing
/// (ARCHITECTURE.md invariant 4).
#[test]
fn known_difference_an_error_inside_a_cycle_leaves_nothing_of_its_block() {
    let program = "G21 F100\nM4 S100\nG84 X1 R2 Z-3\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    let err = err.expect("refused");
    assert_eq!(err.message, "Spindle turning counterclockwise in G84");
    assert_eq!(err.span.line, 3);
    assert!(!cmds.iter().any(|c| c.value.motion().is_some()));
}

/// A G7x profile arc whose end is off its radius, and a G7x cycle without a feed: LinuxCNC reads
/// the profile without checking either and refuses the cycle when it cuts the element, on the
/// profile's `O… ENDSUB` after the cycle's first moves (rs274 2.9: "Radius to end of arc differs
/// from radius to start: start=(Z-15.5450,X5.9060) …" and "Cannot do g1 with zero feed rate",
/// both on `O100 ENDSUB`); Stanok fails the same block with the same message and leaves nothing
/// of the cycle (ARCHITECTURE.md invariant 4). The shrunk programs of seed 20261129, 144.
#[test]
fn known_difference_a_g7x_profile_error_fails_the_endsub_with_nothing_of_the_cycle() {
    let arc = "G21 G18 G7 F100\nO100 SUB\nG0 X8.112 Z0\nG1 Z-7.545\nX11.812\nZ-15.545\n\
               G2 X14.282 Z-18.015 I2.47 K0\nG1 Z-21.015\nO100 ENDSUB\nG0 X19.321 Z3.3\n\
               G72 Q100 X19.321 Z3.3 I1.224\nM2\n";
    let no_feed = "G21 G18\nG0 X20 Z5\nO100 SUB\nG1 X11.812\nZ-21.015\nO100 ENDSUB\n\
                   G72 Q100 X20 Z5 D0.1 I1\nM2\n";
    for (program, message, moves_before) in [
        (arc, "Radius to end of arc differs from radius to start", 2),
        (no_feed, "Cannot do g1 with zero feed rate", 2),
    ] {
        let (cmds, err) = run(program, Dialect::Rs274ngc);
        let err = err.expect("refused");
        assert!(err.message.starts_with(message), "{}", err.message);
        let endsub = program.lines().position(|l| l == "O100 ENDSUB").unwrap() + 1;
        assert_eq!(err.span.line as usize, endsub);
        let moves = cmds.iter().filter(|c| c.value.motion().is_some()).count();
        assert_eq!(
            moves, moves_before,
            "the rapids before the cycle and to its start"
        );
    }
}

/// Seed 20261205, program 4846: the G72.1 passes cut the G7 profile's arc offset by D, ending
/// 0.0273 mm off its radius. LinuxCNC 2.9's default tolerance (0.02828 mm, the `linuxcnc`
/// machine's) takes it, and Stanok then prints rs274's moves; the document's (0.005 mm, Stanok's
/// default) refuses it on the endsub, with LinuxCNC's message.
#[test]
fn an_offset_g7x_arc_within_linuxcnc_tolerance_is_cut_on_the_linuxcnc_machine() {
    let program = "G21 G18 G7 F100\nO100 SUB\nG0 X10 Z0\nX12.475\nZ-15.45\n\
                   G2 X14.775 Z-17.75 I2.3\nG1 Z-22.742\nO100 ENDSUB\nG0 X17.975 Z2.742\n\
                   G72.1 Q100 X17.975 Z2.742 D0.1310\nM2\n";
    let mut opts = options(Dialect::Rs274ngc);
    opts.rs274_linuxcnc_arc_tolerance = true;
    let (cmds, err) = run_with(program, opts);
    assert!(err.is_none(), "{err:?}");
    let arc = linuxcnc_lines(&cmds)
        .into_iter()
        .find(|l| l.contains("ARC_FEED(-17.3956"))
        .expect("the offset arc");
    assert!(
        arc.contains("ARC_FEED(-17.3956, 7.5185, -15.4500, 8.5375, -1"),
        "{arc}"
    );
    let (_, err) = run(program, Dialect::Rs274ngc);
    let err = err.expect("the document's tolerance refuses it");
    assert!(
        err.message.starts_with(
            "Radius to end of arc differs from radius to start: start=(Z-15.4500,X6.3685)"
        ),
        "{}",
        err.message
    );
}

/// Two reading errors in one block: LinuxCNC reads the words left to right and reports the first
/// it cannot take — a second G or M code of a modal group (M3–M5, M19 and M70–M73 are one), a
/// repeated letter, a value it cannot evaluate — before anything of the block runs. The messages
/// are rs274's (LinuxCNC 2.9) for each block.
#[test]
fn reading_errors_are_reported_in_text_order_as_linuxcnc() {
    const M_GROUP: &str = "Two m codes used from same modal group";
    const G_GROUP: &str = "Two g codes used from same modal group";
    for (block, message) in [
        ("M3 M4 X1 X2", M_GROUP),
        ("X1 X2 M3 M4", "Multiple x words on one line"),
        ("M3 X1 M4 X2", M_GROUP),
        ("X1 G0 X2 G1", "Multiple x words on one line"),
        ("M3 M4 G0 G1", M_GROUP),
        ("G0 G1 M3 M4", G_GROUP),
        ("M62 P1 M63 P2", M_GROUP),
        ("X2 X[1/0]", "Multiple x words on one line"),
        ("X[1/0] X2", "Attempt to divide by zero"),
        ("M3 M4 X[1/0]", M_GROUP),
        ("G0 G1 X[SQRT[-1]]", G_GROUP),
        ("M3 M4 T1 T2", M_GROUP),
        ("G80 X1 M3 M4", M_GROUP),
        ("M3 M4 #1=[1/0]", M_GROUP),
        ("#1=[1/0] M3 M4", "Attempt to divide by zero"),
        ("M3 M70", M_GROUP),
        ("M5 M73", M_GROUP),
        ("M19 R1 M5", M_GROUP),
        ("M48 M49", M_GROUP),
    ] {
        let program = format!("G21 F10\n{block}\nM2\n");
        let (_, err) = run(&program, Dialect::Rs274ngc);
        let err = err.unwrap_or_else(|| panic!("{block}: accepted"));
        assert_eq!(err.message, message, "{block}");
        assert_eq!(err.span.line, 2, "{block}");
    }
}

/// An axis the machine lacks stops LinuxCNC's reader at its letter, before any later error of the
/// block: on rs274's XYZABC machine `w100 f-2000` is "Bad character 'w' used", not the negative F
/// (mutant 78 of seed 11, the second style).
#[test]
fn an_axis_the_machine_lacks_is_the_first_error_of_its_block() {
    let mut opts = options(Dialect::Rs274ngc);
    opts.axes = [true, true, true, true, true, true, false, false, false];
    let (_, err) = run_with("G21\nG0 X1\nw100 f-2000\nM2\n", opts);
    let err = err.expect("refused");
    assert!(
        err.message.starts_with("Bad character 'w' used"),
        "{}",
        err.message
    );
    assert_eq!(err.span.line, 3);
}

/// The fuzz smoke's crash (`fuzz interp`, 2026-11-27): a comment starting with a multi-byte
/// character was sliced at byte 6 when tested for `ABORT,`. Any comment is a comment; only
/// `(ABORT, …)` stops the program.
#[test]
fn a_comment_starting_with_multibyte_text_is_no_abort() {
    let program = "G21\n(Ду газа годинниковою стрілкою в площині XY)\n(abörtion)\nG0 X1\nM2\n";
    let (cmds, err) = run(program, Dialect::Rs274ngc);
    assert!(err.is_none(), "{err:?}");
    assert!(cmds.iter().any(|c| c.value.motion().is_some()));
    let (_, err) = run("G21\n(ABORT, стоп)\nG0 X1\nM2\n", Dialect::Rs274ngc);
    assert_eq!(err.expect("aborted").message, "стоп");
}
