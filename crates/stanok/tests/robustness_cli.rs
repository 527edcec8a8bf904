//! Issue 17, end to end: inputs that made a verb panic, hang or print without end, each run
//! through the real binary (docs/robustness.md).

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("robust", name, text)
}

const DIALECTS: [&str; 8] = [
    "axioma",
    "rs274ngc",
    "nc31",
    "2p32",
    "mc2101",
    "gost20999",
    "mazatrol",
    "balt",
];

/// The verbs that read a program, with the arguments each needs after the file.
fn verbs(out: &str) -> Vec<Vec<String>> {
    vec![
        vec!["check".into()],
        vec!["run".into()],
        vec!["canon".into()],
        vec!["plot".into(), "-o".into(), out.into()],
        vec![
            "convert".into(),
            "--to".into(),
            "rs274ngc".into(),
            "-o".into(),
            out.into(),
        ],
    ]
}

fn stanok_on(verb: &[String], file: &str, dialect: &str) -> (i32, String, String) {
    let mut args: Vec<&str> = vec![verb[0].as_str(), file, "--dialect", dialect];
    args.extend(verb[1..].iter().map(String::as_str));
    stanok(&args)
}

/// Item 2: a diagnostic past column 65,535 made miette's formatter panic (exit 101) in every
/// verb and dialect, warnings too. Now the header gives the real column and the echo is a window.
#[test]
fn diagnostics_past_column_65535_render_in_every_verb_and_dialect() {
    let pad = " ".repeat(70_000);
    let error = temp("column.nc", &format!("G1 X1 F100{pad}G999\nM30\n"));
    // An AxiOMA warning far out on the line: a word repeated.
    let warning = temp("column-warn.nc", &format!("G1 F100 X1{pad}G1 X1\nM30\n"));
    let out = temp("column-out.svg", "");
    for dialect in DIALECTS {
        for verb in verbs(&out) {
            let (code, _, err) = stanok_on(&verb, &error, dialect);
            assert!(
                code == 0 || code == 1,
                "{dialect} {verb:?}: exit {code}\n{err}"
            );
            assert!(!err.contains("panicked"), "{dialect} {verb:?}: {err}");
            assert!(err.len() < 8_000, "{dialect} {verb:?}: {} bytes", err.len());
        }
    }
    let (code, _, err) = stanok(&["check", &error, "--dialect", "rs274ngc"]);
    assert_eq!(code, 1);
    assert!(err.contains("column.nc:1:70011"), "{err}");
    assert!(err.contains("G999"), "{err}");
    for verb in verbs(&out) {
        let (code, _, err) = stanok_on(&verb, &warning, "axioma");
        assert!(code == 0 || code == 1, "{verb:?}: exit {code}\n{err}");
        assert!(!err.contains("panicked"), "{verb:?}: {err}");
    }
}

/// Item 5: one AxiOMA line of 1,000 (and 4,000) repeated `G1 X1` words printed one warning per
/// word, each echoing the whole line (24 MB, 386 MB). Now at most ten per line, each echoing a
/// window.
#[test]
fn many_diagnostics_on_one_line_print_a_bounded_text() {
    for n in [1_000, 4_000] {
        let file = temp(
            &format!("words-{n}.nc"),
            &format!("G1 F100 {}\nM30\n", "G1 X1 ".repeat(n)),
        );
        let (code, _, err) = stanok(&["check", &file, "--dialect", "axioma"]);
        assert!(code == 0 || code == 1, "{err}");
        assert!(
            err.len() < 16_000,
            "{n} words: {} bytes of stderr",
            err.len()
        );
    }
    // The bound is an option.
    let file = temp(
        "words-opt.nc",
        &format!("G1 F100 {}\nM30\n", "G1 X1 ".repeat(50)),
    );
    let (_, _, one) = stanok(&[
        "check",
        &file,
        "--dialect",
        "axioma",
        "--max-diagnostics-per-line",
        "1",
        "--max-echo-bytes",
        "40",
    ]);
    assert!(one.matches("warning[").count() <= 1, "{one}");
}

/// Item 5: a 1 MB Balt comment was echoed upper-cased into one error (6.5 MB).
#[test]
fn a_huge_comment_is_not_echoed_whole() {
    let file = temp(
        "comment.nc",
        &format!("G1 X1 F100\n({})\nM30\n", "a".repeat(1_000_000)),
    );
    for dialect in DIALECTS {
        let (code, _, err) = stanok(&["check", &file, "--dialect", dialect]);
        assert!(code == 0 || code == 1, "{dialect}: {err}");
        assert!(err.len() < 8_000, "{dialect}: {} bytes", err.len());
    }
}

/// Item 6: `stanok check /dev/zero` never ended. The size bound stops it (lowered here to keep
/// the debug test quick; the default 1 GiB takes about a second in a release build).
#[test]
fn an_endless_input_stops_at_the_size_bound() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    for dialect in ["rs274ngc", "axioma", "gost20999"] {
        let (code, _, err) = stanok(&[
            "check",
            "/dev/zero",
            "--dialect",
            dialect,
            "--max-program-size",
            "4000000",
        ]);
        assert_eq!(code, 1, "{dialect}: {err}");
        assert!(
            err.contains("program-too-large") || err.contains("lab::too-large"),
            "{dialect}: {err}"
        );
        assert!(err.len() < 8_000);
    }
}

/// Item 3: `G1 X100 F0.0000001`, `G4 P1000000000`, a GOST `G4 X999…9`: `run` never ended. Now the
/// run stops at the block with `machine::time-limit` (exit 1), and `check` warns of the block.
#[test]
fn a_run_past_the_machine_time_bound_stops_at_the_block() {
    let cases = [
        ("feed.ngc", "G1 X100 F0.0000001\nM2\n", "rs274ngc"),
        ("dwell.ngc", "G4 P1000000000\nM2\n", "rs274ngc"),
        (
            "gost.nc",
            &*format!("N1 G4 X{}\nN2 M2\n", "9".repeat(30)),
            "gost20999",
        ),
    ];
    for (name, text, dialect) in cases {
        let file = temp(name, text);
        let (code, out, err) = stanok(&["run", &file, "--dialect", dialect]);
        assert_eq!(code, 1, "{name}: {out}{err}");
        assert!(err.contains("machine::time-limit"), "{name}: {err}");
        assert!(err.contains(":1:1]"), "{name}: {err}");
        let (code, _, err) = stanok(&["check", &file, "--dialect", dialect]);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(err.contains("machine::long-block"), "{name}: {err}");
    }
    // The bound is an option (hours): a 10 s dwell passes 0.001 h.
    let file = temp("short.ngc", "G4 P10\nM2\n");
    let (code, _, err) = stanok(&["run", &file, "--max-machine-time", "0.001"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("3.6 s"), "{err}");
    let (code, _, err) = stanok(&["run", &file]);
    assert_eq!(code, 0, "{err}");
}

/// Item 1 through the binary: the CLI aborted (exit 134) from about 20,000 terms.
#[test]
fn a_20000_term_chain_is_a_diagnostic() {
    let chain = vec!["1"; 20_000].join("+");
    let hll = temp("chain.nc", &format!("double aa = {chain};\nM30\n"));
    let iso = temp("chain-iso.nc", &format!("G0 X={chain}\nM30\n"));
    let ngc = temp("chain.ngc", &format!("G0 X[{chain}]\nM2\n"));
    let out = temp("chain-out.svg", "");
    for (file, dialect) in [(&hll, "axioma"), (&iso, "axioma"), (&ngc, "rs274ngc")] {
        for verb in verbs(&out) {
            let (code, _, err) = stanok_on(&verb, file, dialect);
            assert_eq!(code, 1, "{file} {verb:?}: {err}");
            assert!(err.contains("too-long"), "{file} {verb:?}: {err}");
        }
    }
}

/// Item 4 through the binary: the nested repeats end with a diagnostic naming the option.
#[test]
fn nested_repeats_end_with_a_diagnostic() {
    let file = temp(
        "repeat.ngc",
        "#1=0\no1 repeat [1000]\no2 repeat [1000]\no3 repeat [1000]\n#1=[#1+1]\no3 endrepeat\no2 endrepeat\no1 endrepeat\nM2\n",
    );
    let (code, _, err) = stanok(&["check", &file, "--max-total-loop-iterations", "5000"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("flow::too-many-iterations"), "{err}");
    assert!(err.contains("--max-total-loop-iterations"), "{err}");
    let (code, _, err) = stanok(&["run", &file, "--max-blocks", "3000"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("interp::too-many-blocks"), "{err}");
}
