//! Machine data on the command line: `stanok machine show`, and `--tools` / `--offsets` on every
//! program command, with LinuxCNC files and TOML fragments; bad files give file:line:column and
//! exit status 1.

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("machine-data", name, text)
}

#[test]
fn show_prints_the_corpus_tool_table_in_mm() {
    let tbl = corpus("rs274ngc/tool.tbl");
    let (code, out, err) = stanok(&[
        "machine",
        "show",
        "--tools",
        &tbl,
        "--linuxcnc-units",
        "inch",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Tools       3 from"), "{out}");
    assert!(out.contains("(LinuxCNC tool table, inch)"), "{out}");
    // T1 Z-1.5 D0.25 in inches: Z offset −38.1 mm, diameter 6.35 mm = radius 3.175 mm.
    let t1 = out.lines().position(|l| l.contains("T1 ")).expect("T1");
    let d1 = out.lines().nth(t1 + 1).unwrap();
    assert!(out.lines().nth(t1).unwrap().contains("\"tool 1\""), "{out}");
    assert!(
        d1.contains("D1") && d1.contains("radius 3.175 mm") && d1.contains("offset Z-38.1"),
        "{d1}"
    );
    assert!(out.contains("Machine     mill"), "{out}");
    assert!(out.contains("Axes"), "{out}");
    assert!(
        out.contains("rapid 10000 mm/min, max feed 5000 mm/min"),
        "{out}"
    );
    assert!(out.contains("tolerance 0.01 mm"), "{out}");
}

#[test]
fn show_json_has_the_numbers() {
    let tbl = corpus("rs274ngc/tool.tbl");
    let (code, out, err) = stanok(&[
        "machine",
        "show",
        "--json",
        "--tools",
        &tbl,
        "--linuxcnc-units",
        "inch",
    ]);
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    let tools = v["tools"].as_array().unwrap();
    assert_eq!(tools.len(), 3);
    assert_eq!(tools[0]["number"], 1);
    assert_eq!(tools[0]["pocket"], 1);
    assert_eq!(tools[0]["comment"], "tool 1");
    assert_eq!(tools[0]["kind"], "milling");
    let e = &tools[0]["edges"][0];
    assert_eq!(e["offset"]["z"].as_f64(), Some(-38.1));
    assert_eq!(e["radius"].as_f64(), Some(3.175));
    assert_eq!(tools[2]["number"], 10);
    assert_eq!(tools[2]["edges"][0]["offset"]["z"].as_f64(), Some(2.54));
    assert_eq!(v["sources"]["tools"]["units"], "inch");
    assert_eq!(v["sources"]["offsets"]["from"], "machine mill");
    assert_eq!(v["machine"]["name"], "mill");
    assert_eq!(v["machine"]["axes"][2]["max"].as_f64(), Some(300.0));
    assert_eq!(v["machine"]["arc_tolerance"].as_f64(), Some(0.01));
    assert_eq!(v["active_system"], "G54");
    assert_eq!(v["zero_offsets"].as_array().unwrap().len(), 0);
}

#[test]
fn the_machine_says_which_units_its_linuxcnc_files_use() {
    let text = std::fs::read_to_string(repo("machines/mill.toml"))
        .unwrap()
        .replace("linuxcnc_units = \"mm\"", "linuxcnc_units = \"inch\"");
    let machine = temp("inch-mill.toml", &text);
    let tbl = corpus("rs274ngc/tool.tbl");
    let show = |extra: &[&str]| {
        let mut args = vec![
            "machine",
            "show",
            "--json",
            "--machine",
            &machine,
            "--tools",
            &tbl,
        ];
        args.extend_from_slice(extra);
        let (code, out, err) = stanok(&args);
        assert_eq!(code, 0, "{err}");
        json(&out)["tools"][0]["edges"][0]["offset"]["z"].as_f64()
    };
    assert_eq!(show(&[]), Some(-38.1));
    // The command line overrides it.
    assert_eq!(show(&["--linuxcnc-units", "mm"]), Some(-1.5));
}

#[test]
fn show_prints_every_section_of_the_example() {
    let example = repo("machines/example-offsets-tools.toml");
    let (code, out, err) = stanok(&["machine", "show", "--machine", &example]);
    assert_eq!(code, 0, "{err}");
    for want in [
        "Machine     example",
        "G54 P1      X100 Y50",
        "G56 P12     X-200 Y120.5 Z-15",
        "G59.3 P1    X10  rotation 90°",
        "G154 P1     origin 100 0 0  euler 90 0 0",
        "G157 P6     origin 0 0 50  euler 0 30 0",
        "H2          X450 Y450 Z250",
        "G28 Z250   G30 X450 Y450 Z250",
        "G92 0 (not applied)",
        "#31 = 2.5, #100 = 12",
        "T10    pocket 10   turning",
        "D2  L1 L2 L3 250 42.5 0 mm, radius 0.8 mm, edge position 4, angles front 95° back 155°",
    ] {
        assert!(out.contains(want), "{want}\n{out}");
    }
    let (_, out, _) = stanok(&["machine", "show", "--machine", &example, "--json"]);
    let v = json(&out);
    let z = &v["zero_offsets"][1];
    assert_eq!(
        (z["code"].as_str(), z["page"].as_u64()),
        (Some("G56"), Some(12))
    );
    assert_eq!(z["offset"]["y"].as_f64(), Some(120.5));
    assert_eq!(v["workpiece_frames"][0]["euler"][0].as_f64(), Some(90.0));
    assert_eq!(v["home"][1]["number"], 2);
    assert_eq!(v["parameters"]["31"].as_f64(), Some(2.5));
    assert_eq!(v["tools"][1]["edges"][0]["radius_wear"].as_f64(), Some(0.3));
}

#[test]
fn show_toml_reads_back_as_the_same_machine() {
    let tbl = corpus("rs274ngc/tool.tbl");
    let var = temp(
        "params.var",
        "31\t2.500000\n5220\t2.000000\n5241\t1.000000\n5250\t30.000000\n",
    );
    let base = [
        "--tools",
        tbl.as_str(),
        "--offsets",
        var.as_str(),
        "--linuxcnc-units",
        "inch",
    ];
    let mut args = vec!["machine", "show", "--toml"];
    args.extend_from_slice(&base);
    let (code, toml, err) = stanok(&args);
    assert_eq!(code, 0, "{err}");
    assert!(toml.contains("offset = { z = -38.1 }"), "{toml}");
    let saved = temp("saved.toml", &toml);
    let mut args = vec!["machine", "show", "--json"];
    args.extend_from_slice(&base);
    let (_, from_files, _) = stanok(&args);
    let (code, from_saved, err) = stanok(&["machine", "show", "--json", "--machine", &saved]);
    assert_eq!(code, 0, "{err}");
    let (mut a, mut b) = (json(&from_files), json(&from_saved));
    a["sources"] = serde_json::Value::Null;
    b["sources"] = serde_json::Value::Null;
    assert_eq!(a, b);
    assert_eq!(b["active_system"], "G55");
    assert_eq!(b["zero_offsets"][0]["offset"]["x"].as_f64(), Some(25.4));
    assert_eq!(b["zero_offsets"][0]["rotation"].as_f64(), Some(30.0));
}

#[test]
fn a_bad_tool_table_gives_file_line_column_and_exit_1() {
    let bad = temp("bad.tbl", "T1 P1 Z-1.5 D0.25 ;tool 1\nT2 P2 K5 ;tool 2\n");
    let (code, out, err) = stanok(&["machine", "show", "--tools", &bad]);
    assert_eq!(code, 1);
    assert!(out.is_empty(), "{out}");
    assert!(err.contains("bad.tbl:2:7"), "{err}");
    assert!(err.contains("machine::bad-data"), "{err}");
    assert!(err.contains("unknown word \"K5\""), "{err}");
    // The same for the program commands, before anything runs.
    let prog = corpus("axioma/s5_1-rapid-positioning-milling-example-5_1.nc");
    for cmd in ["run", "canon", "check"] {
        let (code, out, err) = stanok(&[cmd, &prog, "--tools", &bad]);
        assert_eq!(code, 1, "{cmd}");
        assert!(out.is_empty(), "{cmd}: {out}");
        assert!(err.contains("bad.tbl:2:7"), "{cmd}: {err}");
    }
    let svg = temp("never.svg", "");
    let (code, _, err) = stanok(&["plot", &prog, "-o", &svg, "--tools", &bad]);
    assert_eq!(code, 1);
    assert!(err.contains("bad.tbl:2:7"), "{err}");
}

#[test]
fn a_toml_zero_offset_on_page_33_gives_a_located_error() {
    let off = temp(
        "offsets.toml",
        "[[zero_offset]]\ncode = \"G56\"\npage = 33\nx = 1.0\n",
    );
    let prog = corpus("axioma/s5_1-rapid-positioning-milling-example-5_1.nc");
    let (code, _, err) = stanok(&["run", &prog, "--offsets", &off]);
    assert_eq!(code, 1);
    assert!(err.contains("offsets.toml:3:8"), "{err}");
    assert!(err.contains("G56: page 33 is outside 1…32"), "{err}");
    let (code, _, err) = stanok(&["machine", "show", "--offsets", &off, "--json"]);
    assert_eq!(code, 1);
    assert!(err.contains("offsets.toml:3:8"), "{err}");
}

#[test]
fn a_bad_var_file_and_a_bad_machine_file_are_located_too() {
    let var = temp("bad.var", "5161\t0.000000\n5221\t1.000000\n5222\tx\n");
    let (code, _, err) = stanok(&["machine", "show", "--offsets", &var]);
    assert_eq!(code, 1);
    assert!(err.contains("bad.var:3:6"), "{err}");
    let machine = temp(
        "tools-in-machine.toml",
        &(std::fs::read_to_string(repo("machines/mill.toml")).unwrap()
            + "\n[[tool]]\nnumber = 1\n[[tool.edge]]\norientation = 12\n"),
    );
    let (code, _, err) = stanok(&["machine", "show", "--machine", &machine]);
    assert_eq!(code, 1);
    assert!(
        err.contains("orientation (cutting-edge position) must be 0…9"),
        "{err}"
    );
    assert!(err.contains("tools-in-machine.toml:"), "{err}");
}

#[test]
fn good_files_are_accepted_by_every_program_command() {
    let tbl = corpus("rs274ngc/tool.tbl");
    let off = temp(
        "good-offsets.toml",
        "active_system = \"G55\"\n[[zero_offset]]\ncode = \"G55\"\nx = 10.0\n[[home]]\nnumber = 1\nz = 100.0\n",
    );
    let tools = temp(
        "good-tools.toml",
        "[[tool]]\nnumber = 3\n[[tool.edge]]\nradius = 5.0\n",
    );
    let prog = corpus("axioma/s5_1-rapid-positioning-milling-example-5_1.nc");
    let svg = temp("ok.svg", "");
    for args in [
        vec!["run", &prog, "--tools", &tbl, "--offsets", &off],
        vec!["canon", &prog, "--tools", &tools, "--offsets", &off],
        vec!["check", &prog, "--tools", &tools],
        vec!["plot", &prog, "-o", &svg, "--offsets", &off],
    ] {
        let (code, _, err) = stanok(&args);
        assert_eq!(code, 0, "{args:?}: {err}");
    }
    let (code, out, _) = stanok(&["machine", "show", "--tools", &tools, "--offsets", &off]);
    assert_eq!(code, 0);
    assert!(out.contains("active system G55"), "{out}");
    assert!(out.contains("G55 P1      X10"), "{out}");
    assert!(out.contains("H1          Z100"), "{out}");
    assert!(out.contains("radius 5 mm"), "{out}");
}

#[test]
fn files_of_the_wrong_kind_are_refused() {
    let var = temp("p.var", "5220\t1.000000\n");
    let (code, _, err) = stanok(&["machine", "show", "--tools", &var]);
    assert_eq!(code, 1);
    assert!(err.contains("p.var: error[machine::bad-data]"), "{err}");
    assert!(err.contains("give it to --offsets"), "{err}");
    let tbl = corpus("rs274ngc/tool.tbl");
    let (code, _, err) = stanok(&["machine", "show", "--offsets", &tbl]);
    assert_eq!(code, 1);
    assert!(err.contains("give it to --tools"), "{err}");
    let txt = temp("tools.txt", "T1\n");
    let (code, _, err) = stanok(&["machine", "show", "--tools", &txt]);
    assert_eq!(code, 1);
    assert!(err.contains(".tbl") && err.contains(".toml"), "{err}");
    // A TOML tool file holds tools only, an offset file offsets only.
    let mixed = temp(
        "mixed.toml",
        "[[tool]]\nnumber = 1\n[[tool.edge]]\n[g28]\nz = 1.0\n",
    );
    let (code, _, err) = stanok(&["machine", "show", "--tools", &mixed]);
    assert_eq!(code, 1);
    assert!(err.contains("mixed.toml:4:1"), "{err}");
    assert!(err.contains("only [[tool]] sections, not `g28`"), "{err}");
    // A file that is not there is a usage error (2), like a missing program.
    let (code, _, err) = stanok(&["machine", "show", "--tools", "/nonexistent/t.tbl"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--tools /nonexistent/t.tbl: no such file"),
        "{err}"
    );
}

#[test]
fn show_writes_linuxcnc_files_that_read_back() {
    let tbl = corpus("rs274ngc/tool.tbl");
    let inch = ["--linuxcnc-units", "inch"];
    let mut args = vec!["machine", "show", "--tbl", "--tools", &tbl];
    args.extend_from_slice(&inch);
    let (code, out, err) = stanok(&args);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "T1   P1   D+0.250000 Z-1.500000 ;tool 1\n\
         T2   P2   D+0.100000 ;tool 2\n\
         T10  P10  D+0.500000 Z+0.100000 ;tool 10\n"
    );
    let again = temp("again.tbl", &out);
    let tools_json = |file: &str| {
        let mut args = vec!["machine", "show", "--json", "--tools", file];
        args.extend_from_slice(&inch);
        json(&stanok(&args).1)["tools"].clone()
    };
    assert_eq!(tools_json(&tbl), tools_json(&again));

    let example = repo("machines/example-offsets-tools.toml");
    let (code, var, err) = stanok(&["machine", "show", "--var", "--machine", &example]);
    assert_eq!(code, 0, "{err}");
    assert!(
        var.starts_with("31\t2.500000\n100\t12.000000\n5161\t0.000000\n"),
        "{var}"
    );
    assert!(
        var.contains("\n5221\t100.000000\n5222\t50.000000\n"),
        "{var}"
    );
    assert!(
        var.contains("\n5381\t10.000000\n") && var.contains("\n5390\t90.000000\n"),
        "{var}"
    );
    let saved = temp("example.var", &var);
    let (code, out, err) = stanok(&["machine", "show", "--json", "--offsets", &saved]);
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    // Page 1 of G54…G59.3 and the stored positions survive; G56 page 12, the workpiece frames and
    // the home positions have no LinuxCNC parameters.
    let codes: Vec<&str> = v["zero_offsets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|z| z["code"].as_str().unwrap())
        .collect();
    assert_eq!(codes, ["G54", "G59.3"]);
    assert_eq!(v["g30"]["x"].as_f64(), Some(450.0));
    assert_eq!(v["parameters"]["100"].as_f64(), Some(12.0));
    assert_eq!(v["workpiece_frames"].as_array().unwrap().len(), 0);
}

#[test]
fn machine_show_names_the_m_function_profile() {
    let (code, out, err) = stanok(&["machine", "show", "--machine", "beavermill"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("M functions beavermill profile"), "{out}");
    let (code, json, err) = stanok(&["machine", "show", "--machine", "mill", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["machine"]["m_functions"], "generic");
}
