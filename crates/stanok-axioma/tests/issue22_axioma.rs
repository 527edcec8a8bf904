//! Issue 22 (conformance audit), AxiOMA items 1–10: each defect the audit found, as the program
//! that showed it, with the numbers or the error code the spec gives (axioma-1…3).

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind};
use stanok_canon::{AuxTiming, Canon, DiagCode, Diagnostic, Spanned, SpindleDirection};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

fn opts() -> InterpOptions {
    InterpOptions::new(Dialect::Axioma)
}

fn ok_with(text: &str, opts: InterpOptions) -> Vec<Spanned<Canon>> {
    let (cmds, err) = run_with(text, opts);
    assert!(err.is_none(), "{text}: {}", err.unwrap());
    cmds
}

#[track_caller]
fn refused_with(text: &str, opts: InterpOptions, code: &'static str) -> Diagnostic {
    let (_, err) = run_with(text, opts);
    let err = err.unwrap_or_else(|| panic!("{text}: accepted, want {code}"));
    assert_eq!(err.code, DiagCode::Stanok(code), "{text}: {err}");
    err
}

/// Every diagnostic of a `stanok check` style run (continue after an error), errors and warnings.
fn check_all(text: &str, mut opts: InterpOptions) -> (Vec<Diagnostic>, Vec<Diagnostic>) {
    opts.continue_after_error = true;
    let mut it = Interpreter::from_text(text, opts);
    let mut errors = Vec::new();
    for item in it.by_ref() {
        if let Err(d) = item {
            errors.push(d);
        }
    }
    (errors, it.take_warnings())
}

/// Warnings of a run that must succeed, and its commands.
fn warnings_of(text: &str, opts: InterpOptions) -> (Vec<Spanned<Canon>>, Vec<Diagnostic>) {
    let mut it = Interpreter::from_text(text, opts);
    let mut cmds = Vec::new();
    for item in it.by_ref() {
        cmds.push(item.unwrap_or_else(|d| panic!("{text}: {d}")));
    }
    (cmds, it.take_warnings())
}

fn ends(cmds: &[Spanned<Canon>]) -> Vec<[f64; 3]> {
    cmds.iter()
        .filter_map(|c| match &c.value {
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Some(m.end.xyz()),
            Canon::ArcFeed(a) => Some(a.end.xyz()),
            _ => None,
        })
        .collect()
}

// ---- item 1: one P user per block (spec axioma-1 §9 [D], A15) ----

fn page_32() -> InterpOptions {
    let mut o = opts();
    o.control.offsets.zero[0][31].offset.x = 1.0;
    o.control.offsets.zero[0][31].offset.y = 2.0;
    o
}

#[test]
fn issue22_two_p_words_in_one_block_is_an_error() {
    for block in ["G173 P2 G54 P32", "G54 P32 G173 P2"] {
        let text = format!("N10 G00 X0 Y0\nN20 {block}\nN30 X1 Y1\nM30\n");
        let err = refused_with(&text, page_32(), "axioma::p-twice");
        assert_eq!(err.span.line, 2, "{block}");
    }
    // One P read by two functions is as ambiguous.
    refused_with(
        "N10 G00 X0 Y0\nN20 G173 G54 P2\nN30 X1 Y1\nM30\n",
        page_32(),
        "axioma::p-ambiguous",
    );
    // The page alone: G54 page 32 = (1, 2), so X1 Y1 is machine (2, 3).
    let cmds = ok_with(
        "N10 G00 X0 Y0\nN20 G54 P32\nN25 G00 X0 Y0\nN30 X1 Y1\nM30\n",
        page_32(),
    );
    assert_eq!(ends(&cmds).last().unwrap(), &[2.0, 3.0, 0.0]);
}

// ---- item 2: G96 S M3 in one block (axioma-2 §3.8) ----

#[test]
fn issue22_g96_with_s_and_m3_in_one_block_starts_css() {
    // At X50 (REFAX 1 = X), 100 m/min → 100 000 / (2π·50) = 318.3099 rev/min.
    let want = 100_000.0 / (2.0 * std::f64::consts::PI * 50.0);
    for block in [
        "G96 S100 M3",
        "M3 G96 S100",
        "G96 S100 M3 LMAXS 5000",
        "G96 S100 M3 LMAXS 5000 LMINS 10 REFAX 1",
    ] {
        let text = format!("G18 G90 G00 X50 Z0\n{block}\nG01 Z-10 F100\nM30\n");
        let cmds = ok_with(&text, opts());
        let rpm = cmds
            .iter()
            .find_map(|c| match c.value {
                Canon::SetSpindleSpeed { spindle: 0, rpm } => Some(rpm),
                _ => None,
            })
            .unwrap_or_else(|| panic!("{block}: no speed"));
        assert!((rpm - want).abs() < 1e-6, "{block}: {rpm}");
        assert!(
            cmds.iter().any(|c| c.value
                == Canon::StartSpindle {
                    spindle: 0,
                    direction: SpindleDirection::Clockwise
                }),
            "{block}: spindle not started"
        );
    }
    // G96 without any S ever: still refused.
    refused_with("G96 M3\nM30\n", opts(), "axioma::css-without-speed");
}

// ---- item 3: the rest of table 2.2 ----

#[test]
fn issue22_m16_m17_m108_to_m112_m999_are_in_the_generic_table() {
    let want = [
        (16, AuxTiming::Postfix),
        (17, AuxTiming::Prefix),
        (108, AuxTiming::Prefix),
        (109, AuxTiming::Postfix),
        (110, AuxTiming::Postfix),
        (111, AuxTiming::Prefix),
        (112, AuxTiming::Postfix),
        (999, AuxTiming::Postfix),
    ];
    let text: String = want
        .iter()
        .map(|(m, _)| format!("M{m}\n"))
        .chain(["M30\n".to_string()])
        .collect();
    let cmds = ok_with(&text, opts());
    let got: Vec<(u32, AuxTiming)> = cmds
        .iter()
        .filter_map(|c| match c.value {
            Canon::AuxiliaryFunction { number, timing } => Some((number, timing)),
            _ => None,
        })
        .collect();
    assert_eq!(got, want);
    // Prefix before the motion, postfix after it, in one block.
    let cmds = ok_with("G01 X10 F100 M17 M16\nM30\n", opts());
    let order: Vec<&str> = cmds
        .iter()
        .filter_map(|c| match c.value {
            Canon::AuxiliaryFunction { number: 17, .. } => Some("M17"),
            Canon::AuxiliaryFunction { number: 16, .. } => Some("M16"),
            Canon::StraightFeed(_) => Some("move"),
            _ => None,
        })
        .collect();
    assert_eq!(order, ["M17", "move", "M16"]);
}

// ---- item 4: G10 and G16 in a block of their own (spec §14, §17.4) ----

#[test]
fn issue22_g10_and_g16_must_be_alone_in_their_block() {
    let mut o = opts();
    o.diameter_axes[0] = true;
    for bad in [
        "G10 X1 F100 G01",
        "G10 X1 F100",
        "G10 X1 G01",
        "G10 X1 M3",
        "G16 X0 Y0 F100",
        "G16 X0 Y0 G01",
        "G16 X0 Y0 M3",
        "G16 Z5",
        "G16 X0 Y0 S100",
    ] {
        let text = format!("G00 X0 Y0\n{bad}\nM30\n");
        let err = refused_with(&text, o.clone(), "axioma::not-alone");
        assert_eq!(err.span.line, 2, "{bad}");
    }
    // G10 X1 Z-5: Z-5 is no mode (0/1) — refused as before.
    refused_with("G10 X1 Z-5\nM30\n", o.clone(), "axioma::g10-value");
    // The allowed forms: N, the mode selectors / pole coordinates, comments.
    ok_with(
        "N5 G00 X0 Y0\nN10 G10 X1 (diameter)\nN20 G10 X0\nN30 G16 X0 Y0 ; pole\nN40 G16\nM30\n",
        o,
    );
}

// ---- item 5: MSG limits (spec axioma-1 §4 [D], A28) ----

#[test]
fn issue22_msg_over_256_characters_is_cut_with_a_warning() {
    let long: String = (0..300).map(|i| (b'a' + (i % 26) as u8) as char).collect();
    let (cmds, warnings) = warnings_of(&format!("MSG(\"{long}\")\nM30\n"), opts());
    let text = cmds
        .iter()
        .find_map(|c| match &c.value {
            Canon::Message { text } => Some(text.clone()),
            _ => None,
        })
        .unwrap();
    assert_eq!(text.chars().count(), 256);
    assert_eq!(text, long[..256]);
    assert!(warnings
        .iter()
        .any(|w| w.code == DiagCode::Stanok("axioma::msg-too-long")));
    // 256 exactly: whole, no warning.
    let (_, warnings) = warnings_of(&format!("MSG(\"{}\")\nM30\n", &long[..256]), opts());
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn issue22_msg_in_a_non_latin_alphabet_is_not_displayed_with_a_warning() {
    let (cmds, warnings) = warnings_of(
        "MSG(\"Включение лазера\")\nMSG(\"Öl prüfen: 5°\")\nM30\n",
        opts(),
    );
    let shown: Vec<String> = cmds
        .iter()
        .filter_map(|c| match &c.value {
            Canon::Message { text } => Some(text.clone()),
            _ => None,
        })
        .collect();
    assert_eq!(shown, ["Öl prüfen: 5°"]);
    assert_eq!(
        warnings
            .iter()
            .filter(|w| w.code == DiagCode::Stanok("axioma::msg-not-latin"))
            .count(),
        1
    );
}

// ---- item 6: G276 limits (spec axioma-3 §8.1, §9.4) ----

/// Example 11.7 (pitch Q7 = 1 mm … here 1.5) with the spindle block `{S}`.
const THREAD: &str = "G18 G90 G97 G40 G00 G80 G98\nN10 {S} X50 Z80\nN20 G276 Q5=5 Q6=30 Q7=1.5\nN30 Q8=-0.866 Q9=0.5\nN40 Q10=0.15 Q11=0.05\nN50 X30 Z60\nM30\n";

#[test]
fn issue22_g276_above_the_maximum_feed_is_refused() {
    // S20000 · 1.5 = 30 000 mm/min above the lathe's 3 000 mm/min.
    let mut o = opts();
    o.axioma
        .set_channel(Some(3000.0), None, None, None, std::iter::empty());
    let err = refused_with(
        &THREAD.replace("{S}", "M3 S20000"),
        o.clone(),
        "axioma::thread-feed",
    );
    assert!(err.message.contains("30000.0 mm/min"), "{err}");
    // S1000 · 1.5 = 1 500 mm/min: runs.
    ok_with(&THREAD.replace("{S}", "M3 S1000"), o);
}

#[test]
fn issue22_g276_under_g96_is_refused() {
    let text = THREAD.replace("{S}", "G96 S100 M3");
    refused_with(&text, opts(), "axioma::thread-under-css");
}

// ---- item 7: the exit block's distance (spec axioma-3 §4.3, A17) ----

fn tool_r5() -> InterpOptions {
    let mut o = opts();
    let mut c = ControlData::default();
    c.tools.tools.insert(
        1,
        Tool {
            number: 1,
            kind: ToolKind::Milling,
            edges: vec![ToolEdge {
                radius: 5.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    o.control = c;
    o
}

#[test]
fn issue22_g40_exit_block_closer_than_the_radius_is_an_error() {
    let head = "T1 M06\nG00 X-20 Y-20\nG01 G41 X0 Y0 F500\nX50\n";
    let err = refused_with(
        &format!("{head}G40 X52\nM30\n"),
        tool_r5(),
        "axioma::comp-exit-too-close",
    );
    assert_eq!(err.span.line, 5);
    refused_with(
        &format!("{head}G40 X54.9\nM30\n"),
        tool_r5(),
        "axioma::comp-exit-too-close",
    );
    // Exactly r away is allowed, as the manual's examples 9.3/9.4 exit (`G40 X15` from X10, r 5).
    let cmds = ok_with(&format!("{head}G40 X55\nM30\n"), tool_r5());
    assert_eq!(ends(&cmds).last().unwrap(), &[55.0, 0.0, 0.0]);
    ok_with(&format!("{head}G40 X60 Y-10\nM30\n"), tool_r5());
}

// ---- item 9: G73/G173/G273 under compensation (docs/decisions.md) ----

#[test]
fn issue22_mirror_scale_rotation_under_compensation_stay_refused() {
    for frame in ["G73 X-1", "G173 P2", "G273 R30"] {
        let text = format!("T1 M06\nG00 X-20 Y-20\nG01 G41 X0 Y0 F500\nX50\n{frame}\nM30\n");
        refused_with(&text, tool_r5(), "axioma::forbidden-under-compensation");
    }
}

// ---- item 10: one diagnostic for one bad BSPLINE ----

#[test]
fn issue22_bspline_with_too_few_points_is_reported_once() {
    // Broken by a G01 block, by M30, and by the end of input (the manual's fragment).
    for (text, line) in [
        ("N10 G01 X0 Y0 F1500\nN20 BSPLINE X10 Y10 SD=3\nN30 X20 Y0\nN40 G01 X0 Y0\nN50 X5\nM30\n", 4),
        ("N10 G01 X0 Y0 F1500\nN20 BSPLINE X10 Y10 SD=3\nN30 X20 Y0\nN40 G01 X0 Y0\n", 4),
        ("N10 G01 X0 Y0 F1500\nN20 BSPLINE X10 Y10 SD=3\nN30 X20 Y0\nM30\n", 4),
    ] {
        let (errors, _) = check_all(text, opts());
        let bspline: Vec<_> = errors
            .iter()
            .filter(|e| e.code == DiagCode::Stanok("axioma::bspline"))
            .collect();
        assert_eq!(bspline.len(), 1, "{text}: {errors:?}");
        assert_eq!(bspline[0].span.line, line, "{text}");
    }
}

/// Spec axioma-1 §12 [D] and the "separate block" of the frame functions: a motion code in a
/// G73/G173/G273/G194/G195 block is refused at the motion code (its axis words are the frame's,
/// so it would silently not move); after the frame, in its own block, the move runs.
#[test]
fn a_motion_code_in_a_frame_block_is_refused() {
    for (text, at) in [
        ("G194 X5 G1 Y3 F100\nM30\n", "G1"),
        ("G195 X5 G0\nM30\n", "G0"),
        ("G73 X-1 G01 F100\nM30\n", "G01"),
        ("G173 P2 G02\nM30\n", "G02"),
        ("G273 Q30 G1\nM30\n", "G1"),
    ] {
        let err = refused_with(text, opts(), "axioma::frame-with-motion");
        assert_eq!(err.span.line, 1, "{text}");
        assert_eq!(
            &text[err.span.start as usize..err.span.end as usize],
            at,
            "{text}"
        );
    }
    let cmds = ok_with("G194 X5\nG1 X1 F100\nM30\n", opts());
    assert_eq!(ends(&cmds).last().copied(), Some([6.0, 0.0, 0.0]));
}
