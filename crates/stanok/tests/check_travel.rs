//! `stanok check` reports the moves beyond the machine's travel, as the run and the panel's
//! preview check them: machine positions (offsets and tool lengths in force), every violation up
//! to the first error, each at its block; `--no-travel-check` skips them.

mod common;
use common::*;

#[test]
fn check_lists_travel_violations_at_their_blocks_unless_told_not_to() {
    // The built-in mill's X travel is ±500 mm. G10 L2 P1 X300 moves G54 by 300: X250 in G54 is
    // machine X550.
    let program = temp_in(
        "check-travel",
        "over.ngc",
        "G21 G90\nG0 X600 Y10\nG10 L2 P1 X300\nG54 G0 X100\nG0 X250\nG0 X0 Y-600\nM2\n",
    );
    let (code, _, err) = stanok(&["check", &program]);
    assert_eq!(code, 1, "{err}");
    let located: Vec<&str> = err
        .lines()
        .filter(|l| l.contains("over.ngc:") && l.contains("╭"))
        .collect();
    assert_eq!(located.len(), 3, "{err}");
    assert!(located[0].contains("over.ngc:2:"), "{err}");
    assert!(located[1].contains("over.ngc:5:"), "{err}");
    assert!(located[2].contains("over.ngc:6:"), "{err}");
    assert!(
        err.contains("X would reach 600.0000 mm, beyond its maximum 500.0000 mm"),
        "{err}"
    );
    assert!(err.contains("X would reach 550.0000 mm"), "{err}");
    assert!(
        err.contains("Y would reach -600.0000 mm, beyond its minimum -500.0000 mm"),
        "{err}"
    );
    assert!(err.contains("3 error(s)"), "{err}");
    let (code, _, err) = stanok(&["check", "--no-travel-check", &program]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn travel_is_checked_only_up_to_the_first_error() {
    let program = temp_in(
        "check-travel",
        "after-error.ngc",
        "G21 G90\nG0 X10\nG1 X20 Q\nG0 X900\nM2\n",
    );
    let (code, _, err) = stanok(&["check", &program]);
    assert_eq!(code, 1);
    assert!(
        !err.contains("travel-limit"),
        "a move after the error is not a move of the run: {err}"
    );
    assert!(err.contains("1 error(s)"), "{err}");
}

/// Mutation campaign (session 3): a loop whose every pass moves one step further beyond travel
/// made a new error per pass (the message names the position) — a million of them, 33 s. Each
/// block is listed once, at its first violation.
#[test]
fn a_loop_beyond_travel_lists_its_block_once() {
    let program = temp_in(
        "check-travel",
        "loop.mpf",
        "G90 G0 X0\nG91\nint i;\nfor (i = 0; i < 2000; i++) {\nG1 X1 F100\n}\nM30\n",
    );
    let (code, _, err) = stanok(&["check", "--dialect", "axioma", &program]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("X would reach 501.0000 mm"), "{err}");
    assert_eq!(err.matches("× X would reach").count(), 1, "{err}");
}
