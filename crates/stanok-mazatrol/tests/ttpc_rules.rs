//! Tool tip point control inside the language (`docs/dialects/mazatrol-eia.md` §16): column [2],
//! the notes, R-08/R-09, reset at program end, and the regressions of issue 22 item 11.

mod common;
use common::*;
use stanok_canon::Canon;

const M_START: &str = "G90 G01 F1000.\nG43.4 X0 Y0 Z50. B0 H2\n";

fn err_m(text: &str) -> stanok_canon::Diagnostic {
    run(text, &mazak_m()).error.expect("an error")
}

#[test]
fn issue_22_item_11_codes_the_tables_allow_run_in_ttpc() {
    // G04, G09, G22, G61, G64, M98 and (M-series) G93 were refused in TTPC; they run.
    let text = format!(
        "{M_START}G04 P100\nG09 G01 X5.\nG22 X-900. Y-900. Z-900. I-800. J-800. K-800.\nG61\nG64\nM98 P9000\nG93 G01 X10. F2.\nG94\nG49\nM30\nO9000\nM99\n"
    );
    run(&text, &mazak_m()).ok();
}

#[test]
fn issue_22_item_11_codes_the_tables_forbid_are_refused() {
    // A helical arc (a Z word in a G17 arc) on the M-series, under G43.4 with the workpiece frame.
    let mut m = mazak_m();
    m.params.ttpc_workpiece_frame = true;
    let e = run(&format!("{M_START}G02 X10. Y0 Z45. R5.\n"), &m)
        .error
        .unwrap();
    assert_eq!(e.code.to_string(), "mazatrol::code-not-allowed-in-ttpc");
    assert_eq!(
        e.message,
        "a helical G02 is not allowed during tool tip point control on the M-series (table 12.2, helical interpolation)"
    );
    // The same arc without Z runs (note 3).
    run(&format!("{M_START}G02 X10. Y0 R5.\nG49\n"), &m).ok();
    // G17–G19 on the T-series.
    let e = run(
        "G90 G94 G01 F1000.\nG43.4 X100. Y0 Z50. B0 H2\nG18\n",
        &mazak_t(),
    )
    .error
    .unwrap();
    assert_eq!(
        e.message,
        "G18 is not allowed during tool tip point control on the T-series (table 12.1, column [1])"
    );
}

#[test]
fn note_three_names_itself() {
    // Table frame: an arc is refused by note 3; with a B word too.
    let e = err_m(&format!("{M_START}G02 X10. Y0 R5.\n"));
    assert_eq!(
        e.message,
        "G02 is not allowed during tool tip point control on the M-series unless G43.4 and the workpiece programming frame are in force (table 12.2, note 3)"
    );
    let mut m = mazak_m();
    m.params.ttpc_workpiece_frame = true;
    let e = run(&format!("{M_START}G02 X10. Y0 R5. B10.\n"), &m)
        .error
        .unwrap();
    assert_eq!(
        e.message,
        "G02 with a B word is not allowed during tool tip point control on the M-series (table 12.2, note 3)"
    );
}

#[test]
fn column_two_refuses_selection_under_on_modes() {
    // M-series: G41 in force (column [1] forbids compensation in TTPC).
    let e = err_m("G41 D3\nG43.4 X0 Y0 Z50. B0 H2\n");
    assert_eq!(e.code.to_string(), "mazatrol::ttpc-not-selectable");
    assert_eq!(
        e.message,
        "G43.4 cannot be selected while G41 is in force on the M-series (table 12.2, column [1])"
    );
    // A canned cycle in force.
    let e = err_m("S500 M03\nG81 X1. Y1. Z-1. R1. F100.\nG43.4 X0 Y0 Z50. B0 H2\n");
    assert_eq!(
        e.message,
        "G43.4 cannot be selected while G81 is in force on the M-series (table 12.2, column [2])"
    );
    // G68, G51, G51.1, G95, G66.
    for (mode, code) in [
        ("G68 X0 Y0 R10.", "G68"),
        ("G51 X0 Y0 P2.", "G51"),
        ("G51.1 X0", "G51.1"),
        ("G95", "G95"),
        ("G66 P9000", "G66"),
    ] {
        let e = err_m(&format!(
            "{mode}\nG43.4 X0 Y0 Z50. B0 H2\nM30\nO9000\nM99\n"
        ));
        assert!(
            e.message.contains(&format!("while {code} is in force")),
            "{mode}: {}",
            e.message
        );
    }
    // The OFF codes do not block: G40, G80, G50, G69, G67, G94 are the normal state.
    run(
        "G40 G80 G50 G69 G67 G94\nG43.4 X0 Y0 Z50. B0 H2\nG49\n",
        &mazak_m(),
    )
    .ok();
    // T-series: G95 (the power-on feed) blocks; G54–G59 do not (D24).
    let e = run("G43.4 X100. Y0 Z50. B0 H2\n", &mazak_t())
        .error
        .unwrap();
    assert_eq!(
        e.message,
        "G43.4 cannot be selected while G95 is in force on the T-series (table 12.1, column [2])"
    );
    run(
        "G94 G55\nG01 F1000.\nG43.4 X100. Y0 Z50. B0 H2\nG49\n",
        &mazak_t(),
    )
    .ok();
    // G96 (T).
    let e = run("G94 G96 S100\nG43.4 X100. Y0 Z50. B0 H2\n", &mazak_t())
        .error
        .unwrap();
    assert!(e.message.contains("while G96 is in force"), "{}", e.message);
}

#[test]
fn format_rules() {
    // G49 alone in TTPC; outside TTPC a safety block with G49 is fine.
    let e = err_m(&format!("{M_START}G49 Z100.\n"));
    assert_eq!(e.code.to_string(), "mazatrol::g49-not-alone");
    run("G21 G17 G40 G49 G80 G90 G94\n", &mazak_m()).ok();
    // G43.4 beside G90/G91 only.
    let e = err_m("G01 G43.4 X0 Y0 Z50. B0 H2\n");
    assert_eq!(e.code.to_string(), "mazatrol::ttpc-with-other-g-code");
    run("G01 F1000.\nG91 G43.4 X0 Y0 Z0 B0 H2\n", &mazak_m()).ok();
}

#[test]
fn program_end_resets_ttpc() {
    let r = run(&format!("{M_START}M30\n"), &mazak_m());
    r.ok();
    let tcp: Vec<bool> = r
        .canon
        .iter()
        .filter_map(|c| match c.value {
            Canon::SetToolCentrePoint { active, .. } => Some(active),
            _ => None,
        })
        .collect();
    assert_eq!(tcp, vec![true, false]);
}

#[test]
fn g49_without_motion_by_machine_data() {
    let mut m = mazak_m();
    m.params.g49_moves = false;
    let r = run(&format!("{M_START}G49\n"), &m);
    r.ok();
    let last_line = r.canon.iter().map(|c| c.span.line).max().unwrap();
    assert!(
        !r.canon
            .iter()
            .any(|c| c.span.line == last_line && c.value.motion().is_some()),
        "G49 moves nothing"
    );
}

#[test]
fn issue_22_item_12_r_in_ttpc() {
    // The corpus's m-g02-arc-type1-wcs N30 (I10 J0) and the same arc with R10: one arc.
    let mut m = mazak_m();
    m.params.ttpc_workpiece_frame = true;
    let arc_of = |block: &str| {
        let r = run(
            &format!("G90 G17 G01 F500\nG43.4 X0 Y0 Z10. B0 H2\n{block}\n"),
            &m,
        );
        r.ok();
        r.canon
            .iter()
            .find_map(|c| match &c.value {
                Canon::ArcFeed(a) => Some(a.clone()),
                _ => None,
            })
            .unwrap()
    };
    let ijk = arc_of("G02 X20. Y0 I10. J0");
    let r = arc_of("G02 X20. Y0 R10.");
    assert_eq!(ijk, r);
    // And G02 X10 Y0 R5 of the issue: the centre is 5 mm along X from the start.
    let a = arc_of("G02 X10 Y0 R5");
    assert!((a.centre[0] - a.start.x - 5.0).abs() < 1e-9, "{a:?}");
}

#[test]
fn power_on_feed_mode_is_machine_data() {
    // The T-series powers on in G95 (#4005 = 95), which forbids selecting TTPC (table 12.1,
    // column [2]); a machine whose data says `power_on_feed = "G94"` (millturn-bc) selects it at
    // once, and the M-series powers on in G94.
    let ttpc = "G90 G01 F1000.\nG43.4 X100. Y0 Z50. B0 H2\n";
    let t = mazak_t();
    let e = run(ttpc, &t).error.expect("G95 in force");
    assert_eq!(e.code.to_string(), "mazatrol::ttpc-not-selectable");
    assert_eq!(
        e.message,
        "G43.4 cannot be selected while G95 is in force on the T-series (table 12.1, column [2])"
    );
    let mut t94 = mazak_t();
    t94.params.power_on_feed_per_revolution = Some(false);
    run(ttpc, &t94).ok();
    // #4005, the group 05 code, at power-on: 95 / 94 / 94 — read back through a G00 Z move.
    for (m, want) in [(mazak_t(), 95.0), (t94, 94.0), (mazak_m(), 94.0)] {
        let r = run("#1 = #4005\nG00 Z#1\n", &m);
        r.ok();
        let z = r.ends()[0].z;
        let g54 = m.opts.control.offsets.zero.first().and_then(|p| p.first());
        let z0 = g54.map_or(0.0, |o| o.offset.z);
        assert_eq!(z - z0, want, "{:?}", m.params.series);
    }
}
