//! Issue 22 (conformance audit) through the command line: the machine data reaches the AxiOMA
//! channel parameters (items 6 and 8).

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("issue22", name, text)
}

/// Example 11.7 with pitch 1.5 and the spindle block `{S}`.
const THREAD: &str = "G18 G90 G97 G40 G00 G80 G98\nN10 {S} X50 Z80\nN20 G276 Q5=5 Q6=30 Q7=1.5\nN30 Q8=-0.866 Q9=0.5\nN40 Q10=0.15 Q11=0.05\nN50 X30 Z60\nM30\n";

#[test]
fn issue22_g276_above_the_lathes_maximum_feed_is_refused() {
    // S20000 · 1.5 = 30 000 mm/min above the built-in lathe's max_feed 3 000 mm/min.
    let fast = temp("fast.nc", &THREAD.replace("{S}", "M3 S20000"));
    let (code, out, err) = stanok(&["run", &fast, "--dialect", "axioma", "--machine", "lathe"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        err.contains("axioma::thread-feed") && err.contains("fast.nc:6:"),
        "{err}"
    );
    assert!(out.contains("stopped at line 6"), "{out}");
    // S1000 · 1.5 = 1 500 mm/min runs.
    let slow = temp("slow.nc", &THREAD.replace("{S}", "M3 S1000"));
    let (code, out, err) = stanok(&["run", &slow, "--dialect", "axioma", "--machine", "lathe"]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn issue22_machine_without_spindle_encoder_gives_error_2301() {
    let lathe = std::fs::read_to_string(repo("machines/lathe.toml")).unwrap();
    let machine = temp(
        "no-encoder.toml",
        &format!("{lathe}\n[channel]\nspindle_encoder = false\n"),
    );
    let prog = temp("thread.nc", &THREAD.replace("{S}", "M3 S1000"));
    let (code, _, err) = stanok(&["check", &prog, "--dialect", "axioma", "--machine", &machine]);
    assert_eq!(code, 1);
    assert!(
        err.contains("E2301") && err.contains("thread.nc:6:"),
        "{err}"
    );
    // The same program on the built-in lathe (encoder by default) is clean.
    let (code, _, err) = stanok(&["check", &prog, "--dialect", "axioma", "--machine", "lathe"]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn issue22_machine_data_sets_the_number_of_plc_outputs() {
    let mill = std::fs::read_to_string(repo("machines/mill.toml")).unwrap();
    let machine = temp(
        "small-plc.toml",
        &format!("{mill}\n[channel]\nplc_outputs = 4\n"),
    );
    let prog = temp("q.nc", "G110 Q1=4\nM30\n");
    let (code, _, err) = stanok(&["check", &prog, "--dialect", "axioma", "--machine", &machine]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("q.nc:1:"), "{err}");
    let (code, _, err) = stanok(&["check", &prog, "--dialect", "axioma"]);
    assert_eq!(code, 0, "{err}");
}
