//! Which dialect a program is read in, and why, through the command line: each rule of
//! `dialect.rs` with the line `check` and `run` print, the wrong-dialect hint, and the hints at
//! diagnostics (missing subroutine at its call, unconfigured axes, labels).

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("dialects", name, text)
}

/// The `dialect:` line of a check of `file`.
fn said(args: &[&str]) -> String {
    let (_, _, err) = stanok(args);
    err.lines()
        .find(|l| l.starts_with("dialect: "))
        .unwrap_or_else(|| panic!("no dialect line: {err}"))
        .to_string()
}

#[test]
fn each_rule_says_its_dialect_and_why() {
    let cases = [
        ("p.ngc", "G0 X1\nM2\n", "dialect: rs274ngc (extension .ngc)"),
        (
            "nc31-part.nc",
            "N1 X100\n",
            "dialect: nc31 (file name prefix nc31-)",
        ),
        ("main.mpf", "G0 X1\nM30\n", "dialect: axioma (extension .mpf)"),
        (
            "five.nc",
            "N1 X0 Y0 Z0 A0 C0\n(a comment)\nCVU=1\nG1 A30\n",
            "dialect: balt (text: `CVU=` on line 3; .nc is used by several controls)",
        ),
        (
            "tip.gcode",
            "G90 G54\nG43.4 H1\n",
            "dialect: mazatrol (text: `G43.4` on line 2; .gcode is used by several controls)",
        ),
        (
            "sub.tap",
            "G21\no100 sub\nG1 X1\no100 endsub\n",
            "dialect: rs274ngc (text: O-word `o100 sub` on line 2; .tap is used by several controls)",
        ),
        (
            "named.nc",
            "#<depth> = 2\nG1 Z-#<depth>\n",
            "dialect: rs274ngc (text: named parameter `#<…>` on line 1; .nc is used by several controls)",
        ),
        (
            "keyword.cnc",
            "G64 BRISK\nG1 X1\n",
            "dialect: axioma (text: `BRISK` on line 1; .cnc is used by several controls)",
        ),
        (
            "plain.nc",
            "G0 X1\nM30\n",
            "dialect: axioma (the default: nothing in the text belongs to one dialect only; .nc is used by several controls)",
        ),
        (
            "noext",
            "G0 X1\nM30\n",
            "dialect: axioma (the default: nothing in the text belongs to one dialect only)",
        ),
    ];
    for (name, text, expected) in cases {
        let f = temp(name, text);
        assert_eq!(said(&["check", &f]), expected, "{name}");
        assert_eq!(said(&["run", &f]), expected, "{name} (run)");
    }
    let f = temp("given.nc", "G0 X1\nM30\n");
    assert_eq!(
        said(&["check", "--dialect", "rs274ngc", &f]),
        "dialect: rs274ngc (--dialect)"
    );
    // The guess decides how the program is read: the O-word program checks clean as RS274/NGC.
    let sub = temp(
        "clean.tap",
        "G21\no100 sub\nG1 X1 F100\no100 endsub\no100 call\nM2\n",
    );
    assert_eq!(stanok(&["check", &sub]).0, 0);
}

/// A Balt-System program without `CVU=` (example 5 of the corpus without its CVU lines): as the
/// default AxiOMA it is a cascade of errors.
fn balt_without_cvu() -> String {
    let text = std::fs::read_to_string(corpus("cvu/example-5-circle-yz-a-c.nc")).unwrap();
    text.lines()
        .filter(|l| !l.starts_with(';') && !l.contains("CVU") && !l.contains("MOVST"))
        .map(|l| format!("{l}\n"))
        .collect()
}

#[test]
fn many_errors_after_a_guess_name_the_likely_dialect() {
    let f = temp("balt.nc", &balt_without_cvu());
    let (code, _, err) = stanok(&["check", "--machine", "5axis-cvu-tt", &f]);
    assert_eq!(code, 1);
    assert!(err.contains("dialect: axioma (the default"), "{err}");
    let hint = err
        .lines()
        .find(|l| l.starts_with("hint: "))
        .unwrap_or_else(|| panic!("{err}"));
    assert!(
        hint.contains("read as balt (Balt-System) the program has 0 error(s)")
            && hint.ends_with("try --dialect balt"),
        "{hint}"
    );
    // run stops at the first error and gives the same hint.
    let (code, _, err) = stanok(&["run", "--machine", "5axis-cvu-tt", &f]);
    assert_eq!(code, 1);
    assert!(err.contains("hint: read as balt (Balt-System)"), "{err}");
    // Given the dialect, it is clean; given a wrong one on purpose, no hint second-guesses it.
    assert_eq!(
        stanok(&[
            "check",
            "--machine",
            "5axis-cvu-tt",
            "--dialect",
            "balt",
            &f
        ])
        .0,
        0
    );
    let (_, _, err) = stanok(&[
        "check",
        "--machine",
        "5axis-cvu-tt",
        "--dialect",
        "axioma",
        &f,
    ]);
    assert!(!err.contains("hint:"), "{err}");
    // One or two errors in a guessed program are its own mistakes: no hint.
    let one = temp("one.nc", "G0 X1\nG1 X2 A5 F100\nM30\n");
    assert!(!stanok(&["check", &one]).2.contains("hint:"));
}

#[test]
fn a_missing_subroutine_is_reported_at_its_call_with_the_path_tried() {
    let dir = std::env::temp_dir().join(format!("stanok-dialects-sub-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prog =
        "G21 G90\nG0 X0 Y0 Z5\nF100\nG1 X10\nG1 Y10\nG1 X0\nG1 Y0\no<nosuch> call\nG0 Z10\nM2\n";
    let f = temp("missing.ngc", prog);
    let (code, _, err) = stanok(&["check", &f]);
    assert_eq!(code, 1);
    assert!(
        err.contains("missing.ngc:8:1"),
        "at the call, not at M2: {err}"
    );
    assert!(
        err.contains("EOF in file seeking o-word: o<nosuch> from line: 8"),
        "{err}"
    );
    assert!(err.contains("--subroutine-path DIR"), "{err}");
    let dir_text = dir.display().to_string();
    let (_, out, _) = stanok(&["check", "--json", "--subroutine-path", &dir_text, &f]);
    let d = json(out.lines().next().unwrap());
    assert_eq!(d["line"], 8);
    let tried = d["notes"][0].as_str().unwrap();
    assert!(
        tried.ends_with(&format!("and in {}", dir.join("nosuch.ngc").display())),
        "the file tried: {tried}"
    );
    // run stops there too, with nothing after the call executed.
    let (code, out, _) = stanok(&["run", &f]);
    assert_eq!(code, 1);
    assert!(out.contains("stopped at line 8"), "{out}");
    assert!(out.contains("Final       X0.000 Y0.000 Z5.000"), "{out}");
}

#[test]
fn an_unconfigured_axis_names_the_machines_that_have_it_and_labels_say_what_is_wrong() {
    let f = temp("axis.nc", "G0 X1\nG1 B30 F100\nM30\n");
    let (code, _, err) = stanok(&["check", &f]);
    assert_eq!(code, 1);
    assert!(
        err.contains("machine `mill` has the axes XYZ; built-in machines with B:"),
        "{err}"
    );
    assert!(
        err.contains("5axis-bc-head") && err.contains("millturn-bc"),
        "{err}"
    );
    // The underline's label is the problem, not "here".
    assert!(
        err.contains("╰── B axis is not configured on this machine"),
        "{err}"
    );
    assert!(!err.contains("── here"), "{err}");
    // On a machine with B the program runs.
    assert_eq!(stanok(&["run", "--machine", "5axis-bc-head", &f]).0, 0);
}
