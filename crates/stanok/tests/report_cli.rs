//! The run report's wording (`stanok run`), the convert and cutting texts: what they say is what
//! happened, in the user's terms.

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("report", name, text)
}

/// The report lines starting with `key`.
fn lines<'a>(out: &'a str, key: &str) -> Vec<&'a str> {
    out.lines().filter(|l| l.starts_with(key)).collect()
}

#[test]
fn the_demo_runs_without_a_warning_and_its_report_says_what_happened() {
    let (code, out, err) = stanok(&["run", &repo("examples/demo-plate.nc")]);
    assert_eq!(code, 0, "{err}");
    // Only the dialect line on stderr: no warning.
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("dialect: axioma"), "{err}");
    // The main spindle by name, no G96 words without G96.
    assert_eq!(
        lines(&out, "Spindle"),
        vec!["Spindle     6000 rev/min while moving"]
    );
    assert!(!out.contains("G96") && !out.contains("Spindle 0"), "{out}");
    // M9 once; the main spindle without a number.
    assert_eq!(out.matches("M9").count(), 1, "{out}");
    assert!(out.contains("M9 coolant off") && out.contains("M3 spindle clockwise, 6000 rpm"));
    // BRISK: no jerk column and no jerk in the limits line.
    assert!(!out.contains("mm/s³") && !out.contains("(SOFT)"), "{out}");
    assert!(out.contains("no velocity, acceleration, travel or path-tolerance violation"));
    // The mill's own axes only.
    assert_eq!(
        lines(&out, "Final"),
        vec!["Final       X0.000 Y0.000 Z50.000"]
    );
}

#[test]
fn soft_runs_show_jerk_and_g96_runs_say_so() {
    let (code, out, _) = stanok(&["run", &repo("examples/demo-plate.nc"), "--profile", "soft"]);
    assert_eq!(code, 0);
    assert!(out.contains("  j ") && out.contains("mm/s³"), "{out}");
    assert!(
        out.contains("no velocity, acceleration, jerk, travel"),
        "{out}"
    );
    let css = corpus("axioma/s6_7-css-g96-turning-example-6_4.nc");
    let (code, out, err) = stanok(&["run", &css, "--machine", "lathe"]);
    assert_eq!(code, 0, "{err}");
    let spindle = lines(&out, "Spindle");
    assert_eq!(spindle.len(), 1, "{out}");
    assert!(
        spindle[0].contains("(G96: the speed the surface-speed law gives"),
        "{out}"
    );
}

#[test]
fn long_times_are_also_given_as_hours_minutes_seconds() {
    let f = temp("dwell.ngc", "G21\nG4 P3725.1\nM2\n");
    // A coarse servo period: an hour of dwell at 1 ms would be 3.7 million setpoints.
    let (code, out, _) = stanok(&["run", &f, "--servo-period", "100"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("of which dwell 3725.100 s (1:02:05.1)"),
        "{out}"
    );
    assert!(
        lines(&out, "Cycle time")[0].contains(" s (1:02:05."),
        "{out}"
    );
    let short = temp("short.ngc", "G21\nG4 P2\nM2\n");
    let (_, out, _) = stanok(&["run", &short]);
    assert!(!lines(&out, "Cycle time")[0].contains(':'), "{out}");
}

#[test]
fn a_feed_hold_is_reported() {
    let f = temp("hold.ngc", "G21 G90\nG1 X100 F600\nM2\n");
    let (code, out, _) = stanok(&["run", &f, "--feed-hold", "2:1.5"]);
    assert_eq!(code, 0);
    assert_eq!(
        lines(&out, "Feed hold"),
        vec!["Feed hold   at 2.000 s of machine time the machine braked on the path, stood 1.500 s and resumed"]
    );
    let (_, out, _) = stanok(&["run", &f, "--feed-hold", "500:1"]);
    assert!(
        out.contains("Feed hold   at 500.000 s (0:08:20.0): not reached"),
        "{out}"
    );
    let (_, out, _) = stanok(&["run", &f]);
    assert!(!out.contains("Feed hold"), "{out}");
    let (_, out, _) = stanok(&["run", &f, "--feed-hold", "2:1.5", "--json"]);
    let hold = &json(&out)["feed_hold"];
    assert_eq!(hold["at_s"], 2.0);
    assert_eq!(hold["standstill_s"], 1.5);
    assert_eq!(hold["happened"], true);
}

#[test]
fn a_stop_inside_a_subroutine_file_names_that_file() {
    let dir = std::env::temp_dir().join(format!("stanok-report-sub-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let sub = dir.join("bad.ngc");
    std::fs::write(&sub, "o<bad> sub\nG1 X5 F100\nG1 A5\no<bad> endsub\n").unwrap();
    let main = temp("caller.ngc", "G21\no<bad> call\nM2\n");
    let (code, out, err) = stanok(&["run", &main, "--subroutine-path", dir.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    let status = lines(&out, "Status");
    assert_eq!(status.len(), 1);
    assert!(
        status[0].starts_with(&format!(
            "Status      stopped at line 3 of {}:",
            sub.display()
        )),
        "{out}"
    );
    assert!(err.contains(&format!("{}:3:", sub.display())), "{err}");
}

#[test]
fn convert_says_each_warning_once_in_one_form() {
    let f = corpus("labs/gost20999-linear-g1-absolute.nc");
    let (code, _, err) = stanok(&[
        "convert",
        &f,
        "--strip-fixture-comments",
        "--to",
        "rs274ngc",
    ]);
    assert_eq!(code, 0, "{err}");
    // The interpreter's lab::no-feed and the converter's "written at the maximum feed" were the
    // same warning twice: now only the converter's, rendered like every other diagnostic.
    assert!(!err.contains("lab::no-feed"), "{err}");
    assert_eq!(
        err.matches("⚠ feed move without a feed").count(),
        1,
        "{err}"
    );
    assert!(err.contains("warning[convert::not-expressible]"), "{err}");
    assert!(!err.lines().any(|l| l.starts_with("warning: ")), "{err}");
    // A target limitation is located at its line with the source shown.
    let demo = repo("examples/demo-plate.nc");
    let (_, _, err) = stanok(&["convert", &demo, "--to", "rs274ngc"]);
    assert!(
        err.contains("BRISK (acceleration profile) has no RS274/NGC form"),
        "{err}"
    );
    assert!(err.contains("demo-plate.nc:3:1"), "{err}");
}

#[test]
fn cutting_speaks_to_students() {
    let (code, out, _) = stanok(&[
        "cutting",
        "turn",
        "--material",
        "grey-iron",
        "--hb",
        "210",
        "--surface",
        "casting",
        "--tool-material",
        "VK6",
        "--diameter",
        "120",
        "--depth",
        "2",
    ]);
    assert_eq!(code, 0);
    for word in [
        "003_", ".txt", "[decide]", "spec §", "spec [", "doubt", "OCR",
    ] {
        assert!(!out.contains(word), "{word}: {out}");
    }
    assert!(out.contains("data: Lab 2 of the lab collection"), "{out}");
    assert!(
        out.contains("n_v, carbide = 1.26   (the printed table is unclear here:"),
        "{out}"
    );
    assert!(out.contains("(--feed chooses another)"), "{out}");
}
