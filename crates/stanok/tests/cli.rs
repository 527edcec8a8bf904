//! The command line, end to end: exit codes, the run report's numbers, the canon formats, the plot
//! sheet and diagnostics with file:line:column.

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("cli", name, text)
}

#[test]
fn run_json_reports_the_helix_example() {
    let file = corpus("axioma/s5_3_6-helix-extra-turns-p-example-5_14.nc");
    let (code, out, err) = stanok(&["run", &file, "--json"]);
    assert_eq!(code, 0, "{err}");
    let r = json(&out);
    assert_eq!(r["status"], "ok");
    assert_eq!(r["arc_segments"], 2);
    // 633.391 + 318.113 mm of helix (spec axioma-2 W §5.3).
    let feed = r["feed_distance_mm"].as_f64().unwrap();
    assert!((feed - 951.504).abs() < 1e-3, "{feed}");
    // 21.113 s + 10.604 s of helices plus the two rapids (80 mm Z and √(60²+100²) at 10 m/min).
    let rapid = r["rapid_distance_mm"].as_f64().unwrap();
    assert!((rapid - (80.0 + (60f64.powi(2) + 100f64.powi(2)).sqrt())).abs() < 1e-9);
    let t = r["nominal_time_s"].as_f64().unwrap();
    assert!(
        (t - (21.113 + 10.604 + rapid / 10000.0 * 60.0)).abs() < 2e-3,
        "{t}"
    );
    let fp = &r["final_position"];
    assert_eq!(
        (fp["x"].as_f64(), fp["y"].as_f64(), fp["z"].as_f64()),
        (Some(100.0), Some(0.0), Some(50.0))
    );
    assert_eq!(r["program_ended"], true);
    let bb = &r["bounding_box"];
    assert_eq!(bb["min"][1].as_f64(), Some(-20.0));
    assert_eq!(bb["max"][1].as_f64(), Some(20.0));
}

#[test]
fn run_text_report_and_error_exit() {
    let file = corpus("axioma/s2_3-msg-example-2_1.nc");
    let (code, out, _) = stanok(&["run", &file]);
    assert_eq!(code, 0);
    assert!(out.contains("line    16  Tool T3 is active"), "{out}");
    assert!(out.contains("T3 (1 change(s))"), "{out}");
    let bad = temp(
        "bad.nc",
        "G17 G90 F100\nG01 X10\nG02 X20 Y0 R4\nG01 X0\nM30\n",
    );
    let (code, out, err) = stanok(&["run", &bad]);
    assert_eq!(code, 1);
    assert!(out.contains("stopped at line 3"), "{out}");
    assert!(out.contains("Final       X10.000 Y0.000"), "{out}");
    assert!(err.contains("E623") && err.contains("bad.nc:3:"), "{err}");
}

#[test]
fn check_lists_every_error_with_file_line_column() {
    let bad = temp(
        "check.ngc",
        "G21 F100\nG1 X1 X2\nG1 Y#<nope>\nG2 X1 Y1\nM2\n",
    );
    let (code, _, err) = stanok(&["check", &bad]);
    assert_eq!(code, 1);
    for (line, code) in [
        (2, "rs274::multiple-words"),
        (3, "rs274::named-parameter-undefined"),
        (4, "rs274::arc-r-ijk-missing"),
    ] {
        assert!(
            err.contains(&format!("check.ngc:{line}:")),
            "line {line}: {err}"
        );
        assert!(err.contains(code), "{code}: {err}");
    }
    assert!(err.contains("3 error(s)"), "{err}");
    let good = corpus("axioma/s5_3_2-arc-radius-example-5_7.nc");
    assert_eq!(stanok(&["check", &good]).0, 0);
}

#[test]
fn canon_linuxcnc_matches_rs274_for_a_program_with_m2() {
    // g01-linear-example-1 ends with M2 and needs only `G20` as setup.
    let text = std::fs::read_to_string(corpus("rs274ngc/g01-linear-example-1.ngc")).unwrap();
    let prog = temp("g01.ngc", &format!("G20\n{text}"));
    let (code, out, err) = stanok(&["canon", &prog]);
    assert_eq!(code, 0, "{err}");
    let expected =
        std::fs::read_to_string(corpus("rs274ngc/expected/g01-linear-example-1.canon.txt"))
            .unwrap();
    let expected: Vec<&str> = expected.lines().take_while(|l| *l != "executing").collect();
    let ours: Vec<&str> = out.lines().collect();
    assert_eq!(ours, expected);
}

#[test]
fn canon_jsonl_has_kind_end_centre_and_line() {
    let file = corpus("axioma/s5_3_3-arc-cr-signed-radius-example-5_9.nc");
    let (code, out, _) = stanok(&["canon", &file]);
    assert_eq!(code, 0);
    let arcs: Vec<serde_json::Value> = out
        .lines()
        .map(json)
        .filter(|v| v["kind"] == "arc_feed")
        .collect();
    assert_eq!(arcs.len(), 2);
    assert_eq!(arcs[0]["line"], 15);
    assert_eq!(arcs[0]["n"], 20);
    assert!((arcs[0]["centre"][0].as_f64().unwrap() - 49.8568).abs() < 1e-3);
    assert!((arcs[1]["centre"][1].as_f64().unwrap() - 68.1560).abs() < 1e-3);
    assert_eq!(arcs[1]["end"]["x"].as_f64(), Some(17.203));
    assert_eq!(arcs[0]["axis"][2].as_f64(), Some(1.0));
}

#[test]
fn plot_writes_four_views() {
    let file = corpus("axioma/s4_8_1-absolute-centre-turning-example-4_18.nc");
    let out = temp("plot.svg", "");
    let (code, _, err) = stanok(&["plot", &file, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    for view in ["xy", "xz", "yz", "iso"] {
        assert!(svg.contains(&format!("data-view=\"{view}\"")), "{view}");
    }
    // The G18 arc is an SVG elliptical-arc command (radius 30 mm at the sheet scale) in the XZ view.
    let xz = &svg[svg.find("data-view=\"xz\"").unwrap()..];
    let scale: f64 = {
        let s = &xz[xz.find("data-scale=\"").unwrap() + 12..];
        s[..s.find('"').unwrap()].parse().unwrap()
    };
    let r = format!("{:.2}", 30.0 * scale);
    let r = r.trim_end_matches('0').trim_end_matches('.');
    assert!(
        xz.contains(&format!("A{r} {r} 0 0 1")),
        "the G18 arc must be drawn as a true arc of {r} px"
    );
}

#[test]
fn plot_of_a_compensated_contour_draws_the_programmed_one_too() {
    // Example 9.6: a 100 mm square under G41 with T1 (radius 3 mm in the example machine data).
    let file = corpus("axioma/s9_2_1-g41-square-contour-example-9_6.nc");
    let machine = repo("machines/example-offsets-tools.toml");
    let out = temp("comp.svg", "");
    let (code, _, err) = stanok(&["plot", &file, "--machine", &machine, "-o", &out]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains(r#"class="programmed""#),
        "programmed contour missing"
    );
    assert!(svg.contains(">programmed</text>"), "legend entry missing");
    // Without compensation there is nothing extra to draw.
    let plain = corpus("axioma/s4_8_1-absolute-centre-turning-example-4_18.nc");
    let out2 = temp("plain.svg", "");
    let (code, _, err) = stanok(&["plot", &plain, "-o", &out2]);
    assert_eq!(code, 0, "{err}");
    assert!(!std::fs::read_to_string(&out2)
        .unwrap()
        .contains("programmed"));
}

#[test]
fn bad_machine_file_gives_a_located_diagnostic() {
    let m = temp("m.toml", "name = \"x\"\nrapid_rate = \"fast\"\n");
    let prog = corpus("axioma/s5_1-rapid-positioning-milling-example-5_1.nc");
    let (code, _, err) = stanok(&["run", &prog, "--machine", &m]);
    assert_eq!(code, 1);
    assert!(err.contains("m.toml:2:"), "{err}");
}

#[test]
fn probe_moves_stop_at_the_configured_surface() {
    // G38.2 towards Z-10 trips at the surface Z -3.2: #5063 reads it, #5070 = 1, the next move
    // starts there; G38.4 back up loses contact as soon as it leaves the surface.
    let prog = temp(
        "probe.ngc",
        "G21 G90 F100\nG0 X1 Y2 Z5\nG38.2 Z-10\n(debug, z=#5063 ok=#5070)\nG38.4 Z0\n(debug, z=#5063 ok=#5070)\nM2\n",
    );
    let (code, out, err) = stanok(&["canon", &prog, "--probe-surface", "z<=-3.2"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("STRAIGHT_PROBE(1.0000, 2.0000, -10.0000"),
        "{out}"
    );
    assert!(
        out.contains("MESSAGE(\" z=-3.200000 ok=1.000000\")"),
        "{out}"
    );
    // Away from the surface the contact ends at once (Z -3.2 again), and it is a success.
    assert!(out.contains("MESSAGE(\" z=-3.200000 ok=1.000000\")"));
    // The run's final position is the trip point of the last probe.
    let (code, json, err) = stanok(&["run", &prog, "--json", "--probe-surface", "z=-3.2"]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!(
        (r["final_position"]["z"].as_f64().unwrap() + 3.2).abs() < 1e-9,
        "{json}"
    );
    // G38.2 that never reaches the surface is an error at its block.
    let miss = temp("miss.ngc", "G21 G90 F100\nG0 Z5\nG38.2 Z-1\nM2\n");
    let (code, _, err) = stanok(&["canon", &miss, "--probe-surface", "z<=-3.2"]);
    assert_eq!(code, 1);
    assert!(
        err.contains("without the probe changing state") && err.contains("miss.ngc:3"),
        "{err}"
    );
    // A malformed surface is refused by the command line.
    let (code, _, err) = stanok(&["canon", &miss, "--probe-surface", "q<=1"]);
    assert_ne!(code, 0);
    assert!(err.contains("unknown axis"), "{err}");
}

#[test]
fn the_optional_stop_switch_decides_whether_m01_stops() {
    let prog = temp("m01.nc", "G71 G90\nG0 X0 Y0 Z5\nM01\nG0 X10\nM30\n");
    let (code, on, err) = stanok(&["canon", "--format", "jsonl", &prog]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(on.matches("\"program_stop\"").count(), 1, "{on}");
    let (code, off, err) = stanok(&["canon", "--format", "jsonl", "--skip-optional-stops", &prog]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(off.matches("\"program_stop\"").count(), 0, "{off}");
}

#[test]
fn axioma_hll_programs_run_and_their_errors_are_located() {
    // The manual's sprintf fragment: the message "value: 50" at N10 (line 19).
    let file = corpus("axioma/s2_3-sprintf-msg-fragment.nc");
    let (code, out, _) = stanok(&["run", &file]);
    assert_eq!(code, 0);
    assert!(out.contains("line    19  value: 50"), "{out}");
    // An undeclared variable in a word value: file:line:column of the name.
    let bad = temp("hll-bad.nc", "int ab = 2;\nG01 X=ab+cd F100\nM30\n");
    let (code, _, err) = stanok(&["check", &bad]);
    assert_eq!(code, 1);
    assert!(
        err.contains("hll-bad.nc:2:10") && err.contains("hll::undeclared"),
        "{err}"
    );
    // In check mode a bad block in a loop is listed once, not once per pass.
    let looped = temp(
        "hll-looped.nc",
        "for (int i = 0; i < 3; i++) {\nG01 X=i*zz F100\n}\nM30\n",
    );
    let (code, _, err) = stanok(&["check", &looped]);
    assert_eq!(code, 1);
    assert_eq!(err.matches("hll::undeclared").count(), 1, "{err}");
    assert!(
        err.contains("hll-looped.nc:2:9") && err.contains("1 error(s)"),
        "{err}"
    );
    // An endless loop stops at the configured limit with a diagnostic, after exactly that many
    // passes of its ISO block.
    let endless = temp(
        "hll-endless.nc",
        "int k = 0;\nwhile (k >= 0) {\nk++;\nG01 X=k F1000\n}\nM30\n",
    );
    let (code, out, err) = stanok(&["run", &endless, "--max-loop-iterations", "50"]);
    assert_eq!(code, 1, "{out}");
    assert!(err.contains("hll::loop-limit"), "{err}");
    assert!(out.contains("X50.000"), "{out}");
}

#[test]
fn perm_file_keeps_iperm_and_dperm_between_runs() {
    let program = temp(
        "perm-count.nc",
        "$iPerm[1] = $iPerm[1] + 1;\n$dPerm[2] = $dPerm[2] + 0.5;\n\
         G01 X=$iPerm[1]*10 Y=$dPerm[2] F100\nM30\n",
    );
    let perm = temp("perm.toml", "");
    std::fs::remove_file(&perm).unwrap();
    // No file yet: the machine's (none: 0) are used, and the file is written after the run.
    let (code, out, err) = stanok(&["run", &program, "--perm", &perm]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("Final       X10.000 Y0.500"), "{out}");
    assert_eq!(
        std::fs::read_to_string(&perm).unwrap(),
        "[iperm]\n1 = 1\n\n[dperm]\n2 = 0.5\n\n"
    );
    // The second run starts from what the first left.
    let (code, out, _) = stanok(&["run", &program, "--perm", &perm]);
    assert_eq!(code, 0);
    assert!(out.contains("Final       X20.000 Y1.000"), "{out}");
    // A file with anything else is refused at its line; RS274/NGC programs have no $iPerm.
    let bad = temp(
        "perm-bad.toml",
        "[iperm]\n1 = 5\n[parameters]\n5221 = 1.0\n",
    );
    let (code, _, err) = stanok(&["run", &program, "--perm", &bad]);
    assert_eq!(code, 1);
    assert!(err.contains("perm-bad.toml:3:"), "{err}");
    let ngc = temp("perm.ngc", "G0 X1\nM2\n");
    assert_eq!(stanok(&["run", &ngc, "--perm", &perm]).0, 2);
}

#[test]
fn ftable_and_stable_read_the_machine_data_tables() {
    // The mill with FTABLE entry 20 and STABLE entry 2 configured; the others keep the manual's.
    let mill = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../machines/mill.toml"
    ))
    .unwrap();
    let machine = temp(
        "tables.toml",
        &format!("{mill}\n[feed_table]\n20 = 4321.0\n\n[speed_table]\n2 = 777.0\n"),
    );
    let file = corpus("axioma/s6_1-feed-table-ftable-fragment-3.nc");
    let (code, out, err) = stanok(&["canon", &file, "--machine", &machine]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("\"kind\":\"straight_feed\"") && out.contains("\"feed\":4321.0}"),
        "{out}"
    );
    let program = temp("tables.nc", "S=STABLE(2) M3\nS=STABLE(3) M3\nM30\n");
    let (code, out, _) = stanok(&["canon", &program, "--machine", &machine]);
    assert_eq!(code, 0);
    assert!(
        out.contains("\"rpm\":777.0") && out.contains("\"rpm\":1500.0"),
        "{out}"
    );
}
