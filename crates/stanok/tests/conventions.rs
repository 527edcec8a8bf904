//! The command line's conventions, end to end: colour (`--color`, `NO_COLOR`, `CLICOLOR_FORCE`),
//! standard input, `check FILE…` and its JSON, exit codes across verbs, options only on the verbs
//! they belong to, completions and the man page, `machine list`, `convert --to linuxcnc`, and
//! that no user text talks about issues.

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("conventions", name, text)
}

const ESC: char = '\u{1b}';

/// A program with one error (an A word on the 3-axis mill).
const BAD: &str = "G0 X1\nG1 X2 A10 F100\nM30\n";

#[test]
fn colour_follows_the_option_and_the_environment() {
    let bad = temp("colour.nc", BAD);
    let run = |args: &[&str], env: &[(&str, &str)]| {
        let mut all = args.to_vec();
        all.push(&bad);
        stanok_with(&all, env, None, None).2
    };
    // stderr is a pipe here: no colour by default.
    assert!(!run(&["check"], &[]).contains(ESC));
    assert!(run(&["check", "--color", "always"], &[]).contains(ESC));
    assert!(run(&["--color", "always", "check"], &[]).contains(ESC));
    assert!(run(&["check"], &[("CLICOLOR_FORCE", "1")]).contains(ESC));
    assert!(!run(&["check"], &[("CLICOLOR_FORCE", "0")]).contains(ESC));
    // NO_COLOR wins over CLICOLOR_FORCE; --color wins over both.
    assert!(!run(&["check"], &[("NO_COLOR", "1"), ("CLICOLOR_FORCE", "1")]).contains(ESC));
    assert!(run(&["check", "--color", "always"], &[("NO_COLOR", "1")]).contains(ESC));
    assert!(!run(&["check", "--color=never"], &[("CLICOLOR_FORCE", "1")]).contains(ESC));
    // The same for run.
    assert!(run(&["run", "--color", "always"], &[]).contains(ESC));
    assert!(!run(&["run"], &[("NO_COLOR", "yes")]).contains(ESC));
}

#[test]
fn programs_are_read_from_standard_input() {
    let (code, _, err) = stanok_with(&["check", "-"], &[], Some(BAD), None);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("<stdin>:2:"), "{err}");
    assert!(
        err.contains("G1 X2 A10 F100"),
        "the snippet comes from stdin: {err}"
    );
    let ok = "o100 sub\nG1 X1 F100\no100 endsub\no100 call\nM2\n";
    let (code, out, err) = stanok_with(&["run", "-", "--json"], &[], Some(ok), None);
    assert_eq!(code, 0, "{err}");
    assert_eq!(json(&out)["dialect"], "rs274ngc");
    assert_eq!(json(&out)["file"], "<stdin>");
    let (code, out, _) = stanok_with(
        &["canon", "-", "--dialect", "rs274ngc"],
        &[],
        Some(ok),
        None,
    );
    assert_eq!(code, 0);
    assert!(out.contains("STRAIGHT_FEED(1.0000"), "{out}");
    let (code, out, _) = stanok_with(&["plot", "-", "-o", "-"], &[], Some(ok), None);
    assert_eq!(code, 0);
    assert!(out.starts_with("<svg"), "{out}");
    // Twice `-` cannot work.
    let (code, _, err) = stanok_with(&["check", "-", "-"], &[], Some(ok), None);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn check_takes_several_files_and_reports_each() {
    let good = temp("good.ngc", "G0 X1\nM2\n");
    let bad = temp("bad.nc", BAD);
    let (code, _, err) = stanok(&["check", &good, &bad]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("good.ngc: ok (0 warning(s))"), "{err}");
    assert!(err.contains("bad.nc: 1 error(s), 0 warning(s)"), "{err}");
    assert!(
        err.contains("good.ngc: dialect rs274ngc (extension .ngc)"),
        "{err}"
    );
    // A file that cannot be read makes it 2, whatever the others.
    let (code, _, err) = stanok(&["check", &good, "/nonexistent/x.nc", &bad]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("bad.nc: 1 error(s)"),
        "the others are still checked: {err}"
    );
}

#[test]
fn check_json_is_one_object_per_diagnostic_and_line() {
    let text = "G21 F100\nG1 X1 X2\nT1 M6\nG1 A1\nM2\n";
    let file = temp("json.ngc", text);
    let (code, out, _) = stanok(&["check", "--json", &file]);
    assert_eq!(code, 1);
    let lines: Vec<serde_json::Value> = out.lines().map(json).collect();
    assert_eq!(lines.len(), 2, "{out}");
    let first = &lines[0];
    assert_eq!(first["file"], file.as_str());
    assert_eq!(first["line"], 2);
    assert_eq!(first["column"], 7);
    assert_eq!(first["severity"], "error");
    assert_eq!(first["code"], "rs274::multiple-words");
    // start/end are byte offsets of the underlined text in the file.
    let (start, end) = (
        first["start"].as_u64().unwrap(),
        first["end"].as_u64().unwrap(),
    );
    assert_eq!(&text[start as usize..end as usize], "X2");
    assert!(first["message"].as_str().unwrap().len() > 5);
    assert!(first["label"].as_str().is_some());
    assert!(first["notes"].is_array());
    let second = &lines[1];
    assert_eq!(second["line"], 4);
    assert_eq!(second["code"], "interp::axis-not-configured");
    assert!(second["notes"][0]
        .as_str()
        .unwrap()
        .contains("5axis-ab-head"));
    // Every field is there on every line, warnings included.
    let warn = temp("warn.nc", "T7 M6\nM30\n");
    let (code, out, _) = stanok(&["check", "--json", &warn]);
    assert_eq!(code, 0);
    let w = json(out.lines().next().unwrap());
    assert_eq!(w["severity"], "warning");
    for key in [
        "file", "line", "column", "start", "end", "severity", "code", "message", "label", "notes",
    ] {
        assert!(w.get(key).is_some(), "{key}");
    }
}

#[test]
fn exit_codes_are_the_same_across_verbs() {
    let dir = std::env::temp_dir();
    let dir = dir.to_str().unwrap();
    let bad = temp("exit.nc", BAD);
    let good = temp("exit-good.nc", "G0 X1\nM30\n");
    let out = temp("exit.svg", "");
    let verbs: [&[&str]; 5] = [
        &["check"],
        &["run"],
        &["canon"],
        &["plot", "-o", &out],
        &["convert", "--to", "rs274ngc"],
    ];
    for verb in verbs {
        let with = |file: &str| {
            let mut a = verb.to_vec();
            a.push(file);
            stanok(&a)
        };
        let name = verb[0];
        assert_eq!(with(&good).0, 0, "{name} ok");
        assert_eq!(with(&bad).0, 1, "{name} program error");
        let (code, _, err) = with("/nonexistent/prog.nc");
        assert_eq!(code, 2, "{name} missing file");
        assert!(
            err.contains("cannot open /nonexistent/prog.nc"),
            "{name}: {err}"
        );
        let (code, _, err) = with(dir);
        assert_eq!(code, 2, "{name} directory");
        assert!(err.contains("is a directory"), "{name}: {err}");
        let mut unknown = verb.to_vec();
        unknown.extend(["--no-such-option", &good]);
        assert_eq!(stanok(&unknown).0, 2, "{name} usage");
        let mut machine = verb.to_vec();
        machine.extend(["--machine", "nosuch", &good]);
        let (code, _, err) = stanok(&machine);
        assert_eq!(code, 2, "{name} unknown machine");
        assert!(err.contains("built-in machines: mill, lathe"), "{err}");
    }
}

#[test]
fn options_are_accepted_only_by_the_verbs_they_belong_to() {
    let good = temp("verbs.nc", "G0 X1\nM30\n");
    for args in [
        vec!["machine", "show", "--probe-surface", "z<=0"],
        vec!["machine", "show", "--subroutine-path", "."],
        vec!["machine", "list", "--machine", "mill"],
        vec!["check", "--trace", "t.csv", &good],
        vec!["check", "--feed-override", "50", &good],
        vec!["canon", "--trace", "t.csv", &good],
        vec!["plot", "--json", &good],
        vec!["serve", "--corrector", "1=2"],
        vec!["serve", "--strip-fixture-comments"],
        vec!["convert", "--to", "axioma", "--perm", "p.toml", &good],
    ] {
        let (code, _, err) = stanok(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(err.contains("unexpected argument"), "{args:?}: {err}");
    }
    // … and by them.
    assert_eq!(stanok(&["run", "--probe-surface", "z<=-1", &good]).0, 0);
    assert_eq!(stanok(&["check", "--subroutine-path", ".", &good]).0, 0);
}

#[test]
fn completions_and_the_man_page_come_from_the_command_line_definition() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let (code, out, err) = stanok(&["completions", shell]);
        assert_eq!(code, 0, "{shell}: {err}");
        assert!(out.contains("stanok"), "{shell}");
        assert!(out.contains("dialect"), "{shell}");
    }
    let (code, out, _) = stanok(&["man"]);
    assert_eq!(code, 0);
    assert!(out.contains(".TH stanok 1"), "{out}");
    assert!(out.contains("check") && out.contains("plot"), "{out}");
    assert_eq!(stanok(&["completions", "tcsh"]).0, 2);
}

#[test]
fn machine_list_names_every_builtin_machine() {
    let (code, out, _) = stanok(&["machine", "list"]);
    assert_eq!(code, 0);
    let line = |name: &str| {
        out.lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name}: {out}"))
            .to_string()
    };
    assert!(line("mill").contains(" XYZ ") && line("mill").contains("cartesian"));
    assert!(line("lathe").contains(" XZ ") && line("lathe").contains("lathe"));
    assert!(line("5axis-bc-head").contains("XYZBC") && line("5axis-bc-head").contains("head-head"));
    assert!(line("millturn-bc").contains("mill-turn"));
    let (_, out, _) = stanok(&["machine", "list", "--json"]);
    let list = json(&out);
    let names: Vec<&str> = list
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["name"].as_str().unwrap())
        .collect();
    for name in [
        "mill",
        "lathe",
        "beavermill",
        "5axis-ac-table",
        "5axis-cvu-tt",
    ] {
        assert!(names.contains(&name), "{name}");
        // Every listed name works as --machine.
        let (code, _, err) = stanok(&["machine", "show", "--machine", name]);
        assert_eq!(code, 0, "{name}: {err}");
    }
    assert!(list[0]["axes"].is_string() && list[0]["kinematics"].is_string());
    assert!(list[0]["description"].is_string());
}

#[test]
fn convert_to_linuxcnc_is_rs274ngc() {
    let file = repo("examples/demo-plate.nc");
    let (code, a, _) = stanok(&["convert", &file, "--to", "linuxcnc"]);
    assert_eq!(code, 0);
    let (_, b, _) = stanok(&["convert", &file, "--to", "rs274ngc"]);
    assert_eq!(a, b);
    assert!(a.contains("to rs274ngc)"));
}

#[test]
fn no_help_text_or_message_talks_about_issues() {
    let mut texts = Vec::new();
    for verb in [
        vec![],
        vec!["check"],
        vec!["run"],
        vec!["canon"],
        vec!["plot"],
        vec!["convert"],
        vec!["serve"],
        vec!["machine"],
        vec!["machine", "list"],
        vec!["machine", "show"],
        vec!["cutting", "turn"],
        vec!["completions"],
        vec!["man"],
    ] {
        let mut args = verb.clone();
        args.push("--help");
        let (code, out, _) = stanok(&args);
        assert_eq!(code, 0, "{verb:?}");
        texts.push(out);
    }
    texts.push(stanok(&["man"]).1);
    // An unsupported code's note (the UVW plane G17.1 in RS274/NGC).
    let uvw = temp("uvw-plane.ngc", "G17.1\nM2\n");
    texts.push(stanok(&["check", &uvw]).2);
    for t in &texts {
        let lower = t.to_lowercase();
        assert!(!lower.contains("issue"), "{t}");
        assert!(!lower.contains("../shared"), "{t}");
    }
    assert!(texts
        .last()
        .unwrap()
        .contains("not implemented in this version"));
    // --dialect's help names every dialect with its control.
    let help = &texts[1];
    for (value, control) in [
        ("axioma", "AxiOMA"),
        ("rs274ngc", "LinuxCNC"),
        ("mazatrol", "Mazatrol"),
        ("balt", "Balt-System"),
        ("nc31", "NC-31"),
        ("2p32", "2P32"),
        ("mc2101", "MC2101"),
        ("gost20999", "GOST 20999"),
    ] {
        let line = help
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("- {value}:")))
            .unwrap_or_else(|| panic!("{value}: {help}"));
        assert!(line.contains(control), "{line}");
    }
}
