//! Each collision check fires on a small program (kind, line, depth asserted) and stays silent on
//! its corrected version; the text report and `plot --stock` show them.

mod common;
use common::*;

const TOOLS: &str = r#"
# Flat Ø10, flutes 20, tip → holder 30 (default holder Ø30 × 40 above).
[[tool]]
number = 1
flute_length = 20.0
reach = 30.0
[[tool.edge]]
radius = 5.0

# Flat Ø10 that cannot cut at its centre, ramps at most 3°.
[[tool]]
number = 4
centre_cutting = false
ramp_angle = 3.0
flute_length = 20.0
[[tool.edge]]
radius = 5.0

# Flat Ø6 on a Ø10 shank, flutes 10.
[[tool]]
number = 5
flute_length = 10.0
shank_diameter = 10.0
reach = 40.0
[[tool.edge]]
radius = 3.0
"#;

const STOCK: &str = "box:X0,Y20,Z-30:X80,Y60,Z0";

/// Runs a program (lines joined with newlines) on the mill, or on `machine`; the collisions.
fn collisions(tag: &str, lines: &[&str], machine: Option<&str>) -> Vec<serde_json::Value> {
    let prog = temp_in(tag, "p.ngc", &(lines.join("\n") + "\n"));
    let tools = temp_in(tag, "tools.toml", TOOLS);
    let mut args = vec!["run", &prog, "--json", "--tools", &tools, "--stock", STOCK];
    if let Some(m) = machine {
        args.extend_from_slice(&["--machine", m]);
    }
    let (code, out, err) = stanok(&args);
    assert_eq!(code, 0, "{err}\n{out}");
    json(&out)["stock"]["collisions"]
        .as_array()
        .unwrap()
        .clone()
}

/// The program fires exactly `want` (kind, line, depth ± 0.05) and its correction nothing.
fn check(tag: &str, bad: &[&str], good: &[&str], want: &[(&str, u64, f64)], machine: Option<&str>) {
    let got = collisions(&format!("{tag}-bad"), bad, machine);
    let kinds: Vec<(String, u64, f64)> = got
        .iter()
        .map(|c| {
            (
                c["kind"].as_str().unwrap().to_string(),
                c["line"].as_u64().unwrap(),
                c["depth_mm"].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(kinds.len(), want.len(), "{tag}: {kinds:?}");
    for ((k, l, d), (wk, wl, wd)) in kinds.iter().zip(want) {
        assert_eq!((k.as_str(), *l), (*wk, *wl), "{tag}: {kinds:?}");
        assert!((d - wd).abs() <= 0.05, "{tag}: depth {d}, want {wd}");
    }
    for c in &got {
        assert!(c["time_s"].as_f64().unwrap() > 0.0);
        assert_eq!(c["position"].as_array().unwrap().len(), 3);
    }
    let fine = collisions(&format!("{tag}-good"), good, machine);
    assert!(fine.is_empty(), "{tag} corrected: {fine:?}");
}

const HEAD: [&str; 3] = ["G21 G90 G17 G54 G61", "T1 M6", "S10000 M3"];

fn with_head(tool: &str, body: &[&'static str]) -> Vec<&'static str> {
    let t: &'static str = Box::leak(format!("T{tool} M6").into_boxed_str());
    let mut v = vec![HEAD[0], t, HEAD[2]];
    v.extend_from_slice(body);
    v
}

#[test]
fn a_rapid_into_the_stock() {
    check(
        "rapid",
        &with_head("1", &["G0 X50 Y40 Z5", "G0 Z-3", "G0 Z5", "M30"]),
        &with_head("1", &["G0 X50 Y40 Z5", "G1 Z-3 F300", "G0 Z5", "M30"]),
        &[("rapid_in_material", 5, 3.0)],
        None,
    );
}

#[test]
fn cutting_with_the_spindle_stopped() {
    check(
        "spindle",
        &[
            "G21 G90 G17 G54 G61",
            "T1 M6",
            "G0 X50 Y40 Z5",
            "G1 Z-3 F300",
            "G0 Z5",
            "M30",
        ],
        &[
            "G21 G90 G17 G54 G61",
            "T1 M6",
            "M3 S8000",
            "G0 X50 Y40 Z5",
            "G1 Z-3 F300",
            "G0 Z5",
            "M30",
        ],
        &[("spindle_stopped", 4, 3.0)],
        None,
    );
}

#[test]
fn deeper_than_the_flutes() {
    // Flutes end 20 above the tip: at a depth of 25 the wall above them is 5 high.
    check(
        "flutes",
        &with_head(
            "1",
            &["G0 X-10 Y40 Z5", "G0 Z-25", "G1 X50 F500", "G0 Z5", "M30"],
        ),
        &with_head(
            "1",
            &["G0 X-10 Y40 Z5", "G0 Z-15", "G1 X50 F500", "G0 Z5", "M30"],
        ),
        // … and the retract then cuts the wall left above the flutes at rapid.
        &[("flute_length", 6, 5.0), ("rapid_in_material", 7, 5.0)],
        None,
    );
}

#[test]
fn a_shank_wider_than_the_cutter() {
    // Ø6 cutter, Ø10 shank from 10 above the tip: a slot 15 deep leaves 5 mm of wall to either.
    check(
        "shank",
        &with_head(
            "5",
            &["G0 X-10 Y40 Z5", "G0 Z-15", "G1 X50 F500", "G0 Z5", "M30"],
        ),
        &with_head(
            "5",
            &["G0 X-10 Y40 Z5", "G0 Z-8", "G1 X50 F500", "G0 Z5", "M30"],
        ),
        &[
            ("flute_length", 6, 5.0),
            ("shank", 6, 5.0),
            ("rapid_in_material", 7, 5.0),
        ],
        None,
    );
}

#[test]
fn the_holder_into_the_top() {
    // The holder starts 30 above the tip: a hole 32 deep puts it 2 into the top.
    check(
        "holder",
        &with_head("1", &["G0 X50 Y40 Z5", "G1 Z-32 F300", "G0 Z5", "M30"]),
        &with_head("1", &["G0 X50 Y40 Z5", "G1 Z-25 F300", "G0 Z5", "M30"]),
        &[("holder", 5, 2.0)],
        None,
    );
}

#[test]
fn a_plunge_with_a_tool_that_cannot() {
    check(
        "plunge",
        &with_head("4", &["G0 X50 Y40 Z5", "G1 Z-3 F300", "G0 Z5", "M30"]),
        &with_head(
            "4",
            &["G0 X-10 Y40 Z5", "G0 Z-3", "G1 X50 F300", "G0 Z5", "M30"],
        ),
        &[("plunge", 5, 3.0)],
        None,
    );
}

#[test]
fn the_tool_into_the_fixture() {
    let text = std::fs::read_to_string(repo("machines/mill.toml")).unwrap()
        + "\n[stock]\nfixture_z = -30.0\n";
    let machine = temp_in("fixture", "mill.toml", &text);
    check(
        "fixture",
        &with_head("1", &["G0 X-20 Y40 Z5", "G1 Z-31 F300", "G0 Z5", "M30"]),
        &with_head("1", &["G0 X-20 Y40 Z5", "G1 Z-29 F300", "G0 Z5", "M30"]),
        &[("fixture", 5, 1.0)],
        Some(&machine),
    );
}

#[test]
fn the_text_report_and_the_picture_show_them() {
    let prog = temp_in(
        "report",
        "p.ngc",
        "G21 G90 G54\nT1 M6\nS9000 M3\nG0 X50 Y40 Z5\nG0 Z-3\nG0 Z5\nM30\n",
    );
    let tools = temp_in("report", "tools.toml", TOOLS);
    let (code, out, err) = stanok(&["run", &prog, "--tools", &tools, "--stock", STOCK]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Stock       z-dexel model at 0.1 mm"), "{out}");
    assert!(out.contains("rapid_in_material"), "{out}");
    assert!(out.contains("line     5"), "{out}");
    let png = temp_in("report", "stock.png", "");
    let (code, _, err) = stanok(&[
        "plot",
        &prog,
        "--tools",
        &tools,
        "--stock",
        STOCK,
        "--stock-resolution",
        "0.5",
        "-o",
        &png,
    ]);
    assert_eq!(code, 0, "{err}");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn bad_stock_options_say_why() {
    let prog = temp_in("bad", "p.ngc", "G0 X1\nM30\n");
    for (args, why) in [
        (vec!["--stock", "box:X0,Y0:X1,Y1,Z1"], "Z missing"),
        (
            vec![
                "--stock",
                "box:X0,Y0,Z0:X1,Y1,Z1",
                "--stock-resolution",
                "0",
            ],
            "resolution",
        ),
        (vec!["--stock-out", "x.stl"], "needs a stock"),
        (
            vec!["--stock", "box:X0,Y0,Z0:X1,Y1,Z1", "--machine", "lathe"],
            "cylinder",
        ),
    ] {
        let mut a = vec!["run", prog.as_str()];
        a.extend(args.iter().copied());
        let (code, _, err) = stanok(&a);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(why), "{args:?}: {err}");
    }
}
