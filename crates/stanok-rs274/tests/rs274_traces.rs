//! `stanok canon` against LinuxCNC: every RS274/NGC fixture of the pipeline-foundation scope, and
//! Stanok's own programs under tests/rs274 (goldens made by scripts/regen-linuxcnc-goldens.sh),
//! compared line by line with numbers within 1e-4.
//!
//! Error runs: LinuxCNC prints the calls of the failing block it produced before it hit the error;
//! Stanok commits a block all or nothing (ARCHITECTURE.md invariant 4), so its trace stops at the
//! block before. The test checks that Stanok's trace is exactly LinuxCNC's up to that block, that
//! what LinuxCNC printed beyond it moves nothing, that the error is reported on the same block, and
//! that the message is LinuxCNC's.

#[path = "../../stanok-interp/tests/common/mod.rs"]
mod common;
use common::*;
use stanok_interp::InterpOptions;
use stanok_syntax::Dialect;

const TOL: f64 = 1e-4;

/// A corpus fixture as the corpus README's harness runs it: setup lines, body, M2 if needed.
fn fixture_program(name: &str) -> String {
    let text = std::fs::read_to_string(corpus("rs274ngc").join(format!("{name}.ngc")))
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut setup = Vec::new();
    let mut append_m2 = false;
    let mut body = Vec::new();
    let mut in_header = true;
    for line in text.lines() {
        if in_header && line.starts_with(';') {
            if let Some(s) = line.strip_prefix("; setup:") {
                let s = s.trim();
                if s != "(none)" {
                    setup.push(s.to_string());
                }
            }
            if line.starts_with("; harness:") {
                append_m2 = true;
            }
            continue;
        }
        in_header = false;
        body.push(line.to_string());
    }
    let mut program = setup.join("\n");
    program.push('\n');
    program.push_str(&body.join("\n"));
    program.push('\n');
    if append_m2 {
        program.push_str("M2\n");
    }
    program
}

#[derive(Debug, PartialEq)]
enum Expect {
    /// Stanok must agree with LinuxCNC.
    LinuxCnc,
    /// The document's rule rejects what LinuxCNC 2.9 accepts (corpus README, "Known differences").
    DocumentRejects(&'static str),
    /// The spec deliberately differs from LinuxCNC 2.9's trace: Stanok must agree with the trace
    /// edited to the spec's result.
    Spec(SpecEdit),
}

/// How the spec's result differs from a LinuxCNC trace, and why.
#[derive(Debug, PartialEq)]
struct SpecEdit {
    /// The reason, for the failure message (and the reader).
    why: &'static str,
    /// Trace lines (1-based, as numbered in the file) replaced by a text, or deleted (None).
    replace: &'static [(usize, Option<&'static str>)],
    /// Cut the trace from this line on (dropping its error too) and append these lines.
    cut: Option<(usize, &'static [&'static str])>,
}

fn edit_trace(mut trace: Trace, e: &SpecEdit) -> Trace {
    let mut lines: Vec<Option<String>> = trace.lines.into_iter().map(Some).collect();
    for &(n, text) in e.replace {
        lines[n - 1] = text.map(str::to_string);
    }
    if let Some((from, tail)) = e.cut {
        lines.truncate(from - 1);
        lines.extend(tail.iter().map(|l| Some(l.to_string())));
        trace.error = None;
    }
    trace.lines = lines.into_iter().flatten().collect();
    trace
}

fn check(name: &str, program: &str, trace_text: &str, expect: Expect) {
    check_with(
        name,
        program,
        trace_text,
        expect,
        options(Dialect::Rs274ngc),
    );
}

fn check_with(name: &str, program: &str, trace_text: &str, expect: Expect, opts: InterpOptions) {
    let mut trace = read_trace(trace_text);
    if let Expect::Spec(e) = &expect {
        println!("{name}: the spec differs from LinuxCNC 2.9 here: {}", e.why);
        trace = edit_trace(trace, e);
    }
    let (cmds, err) = run_with(program, opts);
    let ours = linuxcnc_lines(&cmds);
    match expect {
        Expect::DocumentRejects(message) => {
            let err = err.unwrap_or_else(|| panic!("{name}: the document's rule must reject it"));
            assert!(err.message.starts_with(message), "{name}: {}", err.message);
            assert!(ours.len() <= trace.lines.len());
            for (i, (a, b)) in ours.iter().zip(&trace.lines).enumerate() {
                assert!(
                    same_line(a, b, TOL),
                    "{name} line {}: ours {a:?}, LinuxCNC {b:?}",
                    i + 7
                );
            }
            return;
        }
        Expect::LinuxCnc | Expect::Spec(_) => {}
    }
    match (&trace.error, &err) {
        (None, None) => {
            for (i, (a, b)) in ours.iter().zip(&trace.lines).enumerate() {
                assert!(
                    same_line(a, b, TOL),
                    "{name} line {}: ours {a:?}, LinuxCNC {b:?}",
                    i + 1
                );
            }
            assert_eq!(
                ours.len(),
                trace.lines.len(),
                "{name}: ours {ours:#?}\nLinuxCNC {:#?}",
                trace.lines
            );
        }
        (Some((msg, block)), Some(d)) => {
            assert!(ours.len() <= trace.lines.len(), "{name}: ours {ours:#?}");
            for (i, (a, b)) in ours.iter().zip(&trace.lines).enumerate() {
                assert!(
                    same_line(a, b, TOL),
                    "{name} line {}: ours {a:?}, LinuxCNC {b:?}",
                    i + 1
                );
            }
            for extra in &trace.lines[ours.len()..] {
                assert!(
                    !extra.contains("STRAIGHT_") && !extra.contains("ARC_FEED"),
                    "{name}: LinuxCNC moved before the error but Stanok did not: {extra}"
                );
            }
            let head = msg.split(':').next().unwrap();
            assert!(
                d.message.starts_with(head),
                "{name}: message {:?}, LinuxCNC {msg:?}",
                d.message
            );
            let our_block = program.lines().nth(d.span.line as usize - 1).unwrap_or("");
            assert_eq!(
                our_block.trim(),
                block.trim(),
                "{name}: error on another block"
            );
        }
        (None, Some(d)) => panic!("{name}: LinuxCNC ran it, Stanok stopped: {d}\n{ours:#?}"),
        (Some((msg, _)), None) => panic!("{name}: LinuxCNC stopped ({msg}), Stanok ran it"),
    }
}

fn corpus_case(name: &str, expect: Expect) {
    let program = fixture_program(name);
    let trace =
        std::fs::read_to_string(corpus("rs274ngc").join(format!("expected/{name}.canon.txt")))
            .unwrap();
    check(name, &program, &trace, expect);
}

macro_rules! corpus_tests {
    ($($test:ident: $name:literal $(=> $reject:literal)? $(=~ $edit:expr)?;)*) => {$(
        #[test]
        fn $test() {
            #[allow(unused_mut, unused_assignments)]
            let mut expect = Expect::LinuxCnc;
            $(expect = Expect::DocumentRejects($reject);)?
            $(expect = Expect::Spec($edit);)?
            corpus_case($name, expect);
        }
    )*};
}

/// The end-of-program lines of a G20 fixture (M2 with G54 offset 0 and no rotation).
const M2_TAIL: [&str; 7] = [
    "N..... SET_G5X_OFFSET(1, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)",
    "N..... SET_XY_ROTATION(0.0000)",
    "N..... SET_FEED_MODE(0, 0)",
    "N..... SET_FEED_RATE(0.0000)",
    "N..... STOP_SPINDLE_TURNING(0)",
    "N..... SET_SPINDLE_MODE(0 0.0000)",
    "N..... PROGRAM_END()",
];

/// `G10 L1 P1` before any M6: rs274's simulated tool changer starts with slot 1 marked as the
/// spindle's tool although #5400 = 0 and G43 applies no offset, so it also rewrites the spindle
/// copy (slot 0). Stanok starts with the spindle empty: tool 1 is not loaded, there is no copy to
/// rewrite (after `T1 M6` both write it: g10-l10-example-1, tests/rs274).
const G10_L1_EMPTY_SPINDLE: SpecEdit = SpecEdit {
    why: "the spindle is empty at start, so G10 L1 P1 has no spindle copy to rewrite",
    replace: &[(10, None)],
    cut: None,
};

/// `T1 M6 G43` on one line, then `G10 L10 P1 Z1.5` (corpus README, "Known differences"): after an
/// M6 the standalone rs274 resynchronises its position without the offset G43 applied on the same
/// line, so it computes 2 − 1.5 − 1.5 = −1.0. The spec (§4.12, example 5.16): the current Z
/// without tool length offset is 2, so the new offset is 2 − 1.5 = 0.5 and after G43 Z reads 1.5.
const G10_L10_SAME_LINE_M6: SpecEdit = SpecEdit {
    why: "T1 M6 G43 on one line: the new tool-1 Z offset is 2 - 1.5 = 0.5 (rs274 resyncs without the TLO and gets -1.0)",
    replace: &[
        (16, Some("N..... SET_TOOL_TABLE_ENTRY(1, 1, 0.0000 0.0000 0.5000 0.0000 0.0000 0.0000 0.0000 0.0000 0.0000, 0.0000, 0.0000, 0)")),
        (17, Some("N..... SET_TOOL_TABLE_ENTRY(0, 1, 0.0000 0.0000 0.5000 0.0000 0.0000 0.0000 0.0000 0.0000 0.0000, 0.0000, 0.0000, 0)")),
        (19, Some("N..... USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 0.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)")),
    ],
    cut: None,
};

/// `G43.2 X0.01 Z0.02` (corpus README, "Known differences"): LinuxCNC 2.9.0~pre1 rejects the axes
/// form ("Requested tool -1 not found"); the document (spec §4.25) adds the values to the offset
/// in force: X 0 + 0.01, Z −1.5 + 0.02 = −1.48; then M2.
const G43_2_AXES: SpecEdit = SpecEdit {
    why: "G43.2 with axis words adds them to the offset in force (LinuxCNC 2.9 rejects the form)",
    replace: &[],
    cut: Some((
        17,
        &[
            "N..... USE_TOOL_LENGTH_OFFSET(0.0100 0.0000 -1.4800, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)",
            "N..... COMMENT(\"завершити програму\")",
            M2_TAIL[0], M2_TAIL[1], M2_TAIL[2], M2_TAIL[3], M2_TAIL[4], M2_TAIL[5], M2_TAIL[6],
        ],
    )),
};

corpus_tests! {
    g00_rapid: "g00-rapid-example-1";
    g01_linear: "g01-linear-example-1";
    g02_centre: "g02-arc-center-example-1";
    g02_g03_centre: "g02-g03-arc-center-example-2";
    g02_helix_invalid: "g02-helix-example-3";
    g02_p_word: "g02-p-word-example-4";
    g02_radius: "g02-arc-radius-example-1";
    g04_dwell: "g04-dwell-example-1";
    g90_absolute: "g90-example-1";
    g91_incremental: "g91-example-1";
    full_circle: "derived-g02-full-circle";
    radius_negative: "derived-g02-radius-negative";
    radius_end_equals_start: "derived-g02-radius-endpoint-equals-start-error";
    tolerance_ok_abs: "derived-arc-tolerance-inch-ok-abs";
    tolerance_ok_rel: "derived-arc-tolerance-inch-ok-rel";
    // The corpus README: LinuxCNC 2.9 accepts these (wider default tolerance); the document's
    // rule, which the spec chooses, rejects them.
    tolerance_error_rel: "derived-arc-tolerance-inch-error" => "Radius to end of arc differs from radius to start";
    tolerance_error_abs: "derived-arc-tolerance-inch-error-abs" => "Radius to end of arc differs from radius to start";
    inverse_time_missing_f: "derived-g93-inverse-time-missing-f-error";
    g80_axis_words: "derived-g80-axis-words-error";
    // Coordinate systems, offsets, tool data.
    g10_l1_tool_table: "g10-l1-tool-table-example-1" =~ G10_L1_EMPTY_SPINDLE;
    g10_l10: "g10-l10-example-1" =~ G10_L10_SAME_LINE_M6;
    g10_l2_1: "g10-l2-example-1";
    g10_l2_2: "g10-l2-example-2";
    g10_l20: "g10-l20-example-1";
    g10_l2_rotation: "derived-g10-l2-rotation";
    g28: "g28-example-1";
    g30: "g30-example-1";
    g43: "g43-example-1";
    g43_1: "g43.1-example-1";
    g43_2_h: "g43.2-h-example-1";
    g43_2_axes: "g43.2-axes-example-2" =~ G43_2_AXES;
    g53: "g53-example-1";
    g92: "g92-example-1";
    g92_family: "derived-g92-family";
    g07_diameter_mode: "derived-g07-diameter-mode";
    // Cycles, spindle synchronisation, probing, splines, path control (issue 4).
    derived_canned_missing_r_error: "derived-canned-missing-r-error";
    derived_canned_r_below_z_error: "derived-canned-r-below-z-error";
    derived_canned_series_lowered_r: "derived-canned-series-lowered-r";
    derived_g38_2_target_equals_start_error: "derived-g38.2-target-equals-start-error";
    derived_g73_chip_break: "derived-g73-chip-break";
    derived_g74_tap_left_hand: "derived-g74-tap-left-hand";
    derived_g83_peck: "derived-g83-peck";
    derived_g84_tap_right_hand: "derived-g84-tap-right-hand";
    derived_g85_bore_feed_out: "derived-g85-bore-feed-out";
    derived_g86_bore_spindle_stop: "derived-g86-bore-spindle-stop";
    derived_g89_bore_dwell_feed_out: "derived-g89-bore-dwell-feed-out";
    derived_g99_retract_r_plane: "derived-g99-retract-r-plane";
    g05_cubic_spline_example_1: "g05-cubic-spline-example-1";
    g05_cubic_spline_example_2: "g05-cubic-spline-example-2";
    g05_1_quadratic_spline_example_1: "g05.1-quadratic-spline-example-1";
    g05_2_nurbs_example_1: "g05.2-nurbs-example-1";
    g33_inline_example_2: "g33-inline-example-2";
    g33_inline_example_3: "g33-inline-example-3";
    g33_spindle_sync_example_1: "g33-spindle-sync-example-1";
    g33_1_rigid_tap_example_1: "g33.1-rigid-tap-example-1";
    g38_2_probe_tool_length_example_1: "g38.2-probe-tool-length-example-1";
    g40_example_1: "g40-example-1";
    g64_example_1: "g64-example-1";
    g64_example_2: "g64-example-2";
    g64_example_3: "g64-example-3";
    g64_example_4: "g64-example-4";
    g76_threading_example_1: "g76-threading-example-1";
    g80_example_1: "g80-example-1";
    g80_example_2: "g80-example-2";
    g80_example_3_eight_holes: "g80-example-3-eight-holes";
    g81_eight_holes_example: "g81-eight-holes-example";
    g81_example_1_absolute: "g81-example-1-absolute";
    g81_example_2_incremental_repeat: "g81-example-2-incremental-repeat";
    g81_example_3_start_below_r: "g81-example-3-start-below-r";
    g81_example_4_incremental_from_origin: "g81-example-4-incremental-from-origin";
    g81_example_5_absolute_from_origin: "g81-example-5-absolute-from-origin";
    g81_twelve_holes_example: "g81-twelve-holes-example";
    g82_example_1: "g82-example-1";
    g96_example_1: "g96-example-1";
    g98_retract_example_1: "g98-retract-example-1";
}

/// One of Stanok's own programs under tests/rs274 against its LinuxCNC golden.
fn own_case(name: &str) {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/rs274"));
    let program = std::fs::read_to_string(dir.join(format!("{name}.ngc"))).unwrap();
    let trace = std::fs::read_to_string(dir.join(format!("expected/{name}.canon.txt")))
        .unwrap_or_else(|_| panic!("{name}: no golden; run scripts/regen-linuxcnc-goldens.sh"));
    check(name, &program, &trace, Expect::LinuxCnc);
}

macro_rules! own_tests {
    ($($test:ident: $name:literal;)*) => {$(
        #[test]
        fn $test() {
            own_case($name);
        }
    )*};
}

// The shrunk reproductions of the differential runner `stanok-parity` (issue 21; docs/linuxcnc.md),
// each a named regression test with rs274's trace (also part of `own_programs_match_linuxcnc`).
own_tests! {
    err_parity_sub_after_percent: "stanok-err-parity-sub-after-percent";
    err_parity_if_to_percent: "stanok-err-parity-if-to-percent";
    err_parity_break_in_repeat: "stanok-err-parity-break-in-repeat";
    err_parity_g76_p_missing: "stanok-err-parity-g76-p-missing";
    err_parity_comp_zero_radius_error: "stanok-err-parity-comp-zero-radius-error";
    err_parity_abort_comment: "stanok-err-parity-abort-comment";
    err_parity_stray_endsub_after_call: "stanok-err-parity-stray-endsub-after-call";
    err_parity_comp_arc_gouge: "stanok-err-parity-comp-arc-gouge";
    err_parity_motion_axes_missing: "stanok-err-parity-motion-axes-missing";
    err_parity_negative_tool: "stanok-err-parity-negative-tool";
    err_parity_endsub_outside: "stanok-err-parity-endsub-outside";
    err_parity_comp_exit_arc: "stanok-err-parity-comp-exit-arc";
    err_parity_comp_arc_sweep: "stanok-err-parity-comp-arc-sweep";
    err_parity_comp_g40_flush: "stanok-err-parity-comp-g40-flush";
    err_parity_comp_arc_line_gouge: "stanok-err-parity-comp-arc-line-gouge";
    err_parity_comp_arc_arc_gouge: "stanok-err-parity-comp-arc-arc-gouge";
    err_parity_comp_entry_direction: "stanok-err-parity-comp-entry-direction";
    err_parity_comp_plane: "stanok-err-parity-comp-plane";
    err_parity_coolant_group: "stanok-err-parity-coolant-group";
    err_parity_g74_l: "stanok-err-parity-g74-l";
    err_parity_g7x_arc_centre: "stanok-err-parity-g7x-arc-centre";
    err_parity_g7x_parallel: "stanok-err-parity-g7x-parallel";
    err_parity_g76_spindle: "stanok-err-parity-g76-spindle";
    err_parity_g4: "stanok-err-parity-g4";
    err_parity_g5_1_inverse_time: "stanok-err-parity-g5-1-inverse-time";
    err_parity_g5_zero_feed: "stanok-err-parity-g5-zero-feed";
    err_parity_g5_2_zero_feed: "stanok-err-parity-g5-2-zero-feed";
    err_parity_g_group_before_repeat: "stanok-err-parity-g-group-before-repeat";
    err_parity_m19_g33: "stanok-err-parity-m19-g33";
    err_parity_m61_negative: "stanok-err-parity-m61-negative";
    err_parity_n_not_first: "stanok-err-parity-n-not-first";
    err_parity_r0: "stanok-err-parity-r0";
    err_parity_reading_order: "stanok-err-parity-reading-order";
    err_parity_spindle_number: "stanok-err-parity-spindle-number";
    err_parity_unknown_operation: "stanok-err-parity-unknown-operation";
    err_parity_g5_1: "stanok-err-parity-g5-1";
    err_parity_mod_zero: "stanok-err-parity-mod-zero";
    err_parity_negative_f: "stanok-err-parity-negative-f";
    err_parity_nested_comment: "stanok-err-parity-nested-comment";
    err_parity_pow: "stanok-err-parity-pow";
    err_parity_unclosed_comment: "stanok-err-parity-unclosed-comment";
    parity_change_tool_slot: "stanok-parity-change-tool-slot";
    parity_comp_after_g40: "stanok-parity-comp-after-g40";
    parity_comp_labels: "stanok-parity-comp-labels";
    parity_comp_after_stop_unchecked: "stanok-parity-comp-after-stop-unchecked";
    parity_comp_convex_before_arc: "stanok-parity-comp-convex-before-arc";
    parity_comp_stop_flush: "stanok-parity-comp-stop-flush";
    parity_comp_arc_join: "stanok-parity-comp-arc-join";
    parity_comp_near_reversal: "stanok-parity-comp-near-reversal";
    parity_comp_reversal: "stanok-parity-comp-reversal";
    parity_comp_rapid_corner: "stanok-parity-comp-rapid-corner";
    parity_css_inch: "stanok-parity-css-inch";
    parity_flow_break_continue: "stanok-parity-flow-break-continue";
    parity_flow_continue_repeat: "stanok-parity-flow-continue-repeat";
    parity_cycle_after_g61_1: "stanok-parity-cycle-after-g61-1";
    parity_cycle_at_r_offset: "stanok-parity-cycle-at-r-offset";
    parity_cycles_g91_l: "stanok-parity-cycles-g91-l";
    parity_g5_feed_units: "stanok-parity-g5-feed-units";
    parity_g5_2_inverse_time: "stanok-parity-g5-2-inverse-time";
    parity_g5_3_zero_feed: "stanok-parity-g5-3-zero-feed";
    parity_g53_tlo: "stanok-parity-g53-tlo";
    parity_g73_peck_rounding: "stanok-parity-g73-peck-rounding";
    parity_g7x_arc_corner: "stanok-parity-g7x-arc-corner";
    parity_g7x_arc_top: "stanok-parity-g7x-arc-top";
    parity_g7x_empty_levels: "stanok-parity-g7x-empty-levels";
    parity_g93_rotary: "stanok-parity-g93-rotary";
    parity_g7x_inch_defaults: "stanok-parity-g7x-inch-defaults";
    parity_g7x_labels: "stanok-parity-g7x-labels";
    parity_g7x_level_element: "stanok-parity-g7x-level-element";
    parity_g7x_rounding_7327: "stanok-parity-g7x-rounding-20261211-7327";
    parity_g7x_rounding_4124: "stanok-parity-g7x-rounding-20261213-4124";
    parity_g7x_rounding_1583: "stanok-parity-g7x-rounding-20261209-1583";
    parity_g7x_profile_mcodes: "stanok-parity-g7x-profile-mcodes";
    parity_g7x_sharp_corner: "stanok-parity-g7x-sharp-corner";
    parity_g7x_inch_corner_tie: "stanok-parity-g7x-inch-corner-tie";
    parity_g7x_short_profile: "stanok-parity-g7x-short-profile";
    parity_g7x_start_level: "stanok-parity-g7x-start-level";
    parity_g87_repeat: "stanok-parity-g87-repeat";
    parity_m19: "stanok-parity-m19";
    parity_tap_overrides: "stanok-parity-tap-overrides";
    parity_g64_units_cycle: "stanok-parity-g64-units-cycle";
    parity_g64_units_cycle_q: "stanok-parity-g64-units-cycle-q";
    parity_g64_units_m72: "stanok-parity-g64-units-m72";
    parity_g83_incremental_pecks: "stanok-parity-g83-incremental-pecks";
    parity_m19_q_alone: "stanok-parity-m19-q-alone";
    parity_g76_any_plane: "stanok-parity-g76-any-plane";
    parity_g5_keeps_unset_motion: "stanok-parity-g5-keeps-unset-motion";
    parity_comp_zero_radius: "stanok-parity-comp-zero-radius";
    parity_debug_value_text: "stanok-parity-debug-value-text";
    parity_g76_inch_passes: "stanok-parity-g76-inch-passes";
    parity_trig_long_double: "stanok-parity-trig-long-double";
    parity_g10_rotation_under_shift: "stanok-parity-g10-rotation-under-shift";
    parity_g93_minimum_rate: "stanok-parity-g93-minimum-rate";
    parity_named_created_by_assignment: "stanok-parity-named-created-by-assignment";
    parity_tap_plane_m6: "stanok-parity-tap-plane-m6";
    parity_tap_plane_m61: "stanok-parity-tap-plane-m61";
    parity_tap_plane_probe: "stanok-parity-tap-plane-probe";
    parity_m60: "stanok-parity-m60";
    parity_m72_coolant: "stanok-parity-m72-coolant";
    parity_m72_g92: "stanok-parity-m72-g92";
    parity_modal_centre_words: "stanok-parity-modal-centre-words";
    parity_negative_words: "stanok-parity-negative-words";
    parity_predefined: "stanok-parity-predefined";
    parity_spindle_select: "stanok-parity-spindle-select";
    parity_probe_backoff: "stanok-parity-probe-backoff";
    parity_tapping_offsets: "stanok-parity-tapping-offsets";
    parity_tapping_planes: "stanok-parity-tapping-planes";
}

/// Stanok's own programs with LinuxCNC goldens.
#[test]
fn own_programs_match_linuxcnc() {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/rs274"));
    let mut n = 0;
    let mut entries: Vec<_> = std::fs::read_dir(dir).unwrap().flatten().collect();
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let p = e.path();
        if p.extension().and_then(|x| x.to_str()) != Some("ngc") {
            continue;
        }
        let name = p.file_stem().unwrap().to_string_lossy().into_owned();
        let program = std::fs::read_to_string(&p).unwrap();
        let trace = std::fs::read_to_string(dir.join(format!("expected/{name}.canon.txt")))
            .unwrap_or_else(|_| panic!("{name}: no golden; run scripts/regen-linuxcnc-goldens.sh"));
        check(&name, &program, &trace, Expect::LinuxCnc);
        n += 1;
    }
    assert!(n >= 15, "only {n} programs found");
}

#[test]
fn numbers_compare_within_tolerance() {
    assert!(same_line(
        "N..... ARC_FEED(1.0000, -2.5000)",
        "N..... ARC_FEED(1.00004, -2.49996)",
        TOL
    ));
    assert!(!same_line(
        "N..... ARC_FEED(1.0000, -2.5000)",
        "N..... ARC_FEED(1.0002, -2.5000)",
        TOL
    ));
    assert!(!same_line(
        "N..... SELECT_PLANE(CANON_PLANE_XY)",
        "N..... SELECT_PLANE(CANON_PLANE_XZ)",
        TOL
    ));
    assert!(same_line(
        "N..... STRAIGHT_FEED(-0.0000)",
        "N..... STRAIGHT_FEED(0.0000)",
        TOL
    ));
}

/// `o<name> call` of subroutines kept in files of their own on the subroutine path (nested: a
/// file calling another file, return values, `return` from inside an if). Golden made with
/// LinuxCNC's rs274 and an ini whose [RS274NGC]SUBROUTINE_PATH is tests/rs274-subfiles.
#[test]
fn subroutine_files_on_the_search_path_match_linuxcnc() {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/rs274-subfiles"));
    let program = std::fs::read_to_string(dir.join("main.ngc")).unwrap();
    let trace = std::fs::read_to_string(dir.join("expected.canon.txt")).unwrap();
    let mut opts = options(Dialect::Rs274ngc);
    opts.subroutine_path = vec![dir.to_path_buf()];
    check_with("subfiles", &program, &trace, Expect::LinuxCnc, opts);
    // Without the path the call is an error at the first call, as in LinuxCNC.
    let (cmds, err) = run(&program, Dialect::Rs274ngc);
    let err = err.expect("no path: the subroutine is unknown");
    assert!(err.message.starts_with("EOF in file"), "{}", err.message);
    assert!(!cmds.iter().any(|c| c.value.motion().is_some()));
}

#[test]
fn a_subroutine_file_without_its_sub_is_an_error() {
    let dir = std::env::temp_dir().join(format!("stanok-subfile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("other.ngc"),
        "o<different> sub\nG0 X1\no<different> endsub\nM2\n",
    )
    .unwrap();
    let mut opts = options(Dialect::Rs274ngc);
    opts.subroutine_path = vec![dir.clone()];
    let (_, err) = run_with("G21\no<other> call\nM2\n", opts);
    let err = err.unwrap();
    assert!(
        err.message.contains("seeking o-word: o<other>"),
        "{}",
        err.message
    );
    assert_eq!(err.span.line, 2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_error_inside_a_subroutine_file_is_located_in_that_file() {
    let dir = std::env::temp_dir().join(format!("stanok-subfile-err-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("bad.ngc"),
        "o<bad> sub\nG1 X1 F0\no<bad> endsub\nM2\n",
    )
    .unwrap();
    let mut opts = options(Dialect::Rs274ngc);
    opts.subroutine_path = vec![dir.clone()];
    let (_, err) = run_with("G21\no<bad> call\nM2\n", opts);
    let err = err.unwrap();
    assert!(
        err.message.starts_with("Cannot do g1 with zero feed rate"),
        "{}",
        err.message
    );
    assert_eq!(err.span.line, 2);
    assert!(
        err.file.as_deref().unwrap().ends_with("bad.ngc"),
        "{:?}",
        err.file
    );
    let _ = std::fs::remove_dir_all(&dir);
}
