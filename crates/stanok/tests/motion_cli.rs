//! `stanok run` motion options: --trace, --feed-override, --servo-period, and the JSON fields.

mod common;
use common::*;

fn program(tag: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("stanok-motion-cli-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("p.ngc");
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

#[test]
fn trace_file_has_one_line_per_period_and_ends_at_the_final_position() {
    let prog = program("trace", "G21 G90 G61\nG1 X100 F3000\nM2\n");
    let trace = std::path::Path::new(&prog).with_file_name("t.csv");
    let (code, out, err) = stanok(&[
        "run",
        &prog,
        "--json",
        "--trace",
        &trace.display().to_string(),
        "--servo-period",
        "2",
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    // 100 mm at F3000 (50 mm/s), a = 1000: 100/50 + 50/1000 = 2.05 s; at 2 ms: 1026 setpoints.
    assert!(
        (r["cycle_time_s"].as_f64().unwrap() - 2.05).abs() < 1e-9,
        "{}",
        r["cycle_time_s"]
    );
    assert_eq!(r["setpoints"], 1026);
    assert_eq!(r["violation_count"], 0);
    assert_eq!(r["servo_period_s"].as_f64(), Some(0.002));
    let text = std::fs::read_to_string(&trace).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "t,X,Y,Z,S,line");
    assert_eq!(lines.len(), 1027);
    assert_eq!(lines[1], "0.000000,0.000000,0.000000,0.000000,0.000,2");
    assert_eq!(
        *lines.last().unwrap(),
        "2.050000,100.000000,0.000000,0.000000,0.000,2"
    );
}

#[test]
fn feed_override_and_text_report() {
    let prog = program("override", "G21 G90\nG1 X100 F3000\nM2\n");
    let (code, out, _) = stanok(&["run", &prog, "--feed-override", "200"]);
    assert_eq!(code, 0);
    assert!(out.contains("Cycle time  1.100 s planned"), "{out}");
    assert!(out.contains("feed override 200%"), "{out}");
    assert!(out.contains("Limits      ok"), "{out}");
    let (code, _, err) = stanok(&["run", &prog, "--feed-override", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--feed-override"), "{err}");
}

#[test]
fn feed_hold_adds_the_standstill_and_the_extra_ramps() {
    // 100 mm at F3000 (50 mm/s): 2.05 s. Hold at 1 s (cruising, s = 1.25 + 50·0.95 = 48.75 mm):
    // 0.05 s braking to s = 50 mm at 1.05 s, 2 s standing, then 50 mm from rest: 1 + 0.05 s.
    // Total 4.1 s.
    let prog = program("hold", "G21 G90\nG1 X100 F3000\nM2\n");
    let (code, out, err) = stanok(&["run", &prog, "--json", "--feed-hold", "1:2"]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    let t = r["cycle_time_s"].as_f64().unwrap();
    assert!((t - 4.1).abs() < 1e-9, "{t}");
    assert_eq!(r["violation_count"], 0);
    assert_eq!(stanok(&["run", &prog, "--feed-hold", "x"]).0, 2);
}

/// The trace's (t, X) pairs.
fn trace_x(path: &std::path::Path) -> Vec<(f64, f64)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let mut f = l.split(',').map(|x| x.parse::<f64>().unwrap());
            (f.next().unwrap(), f.next().unwrap())
        })
        .collect()
}

/// Issue 19 from the command line: a long G1 X400 at 1200 mm/min (20 mm/s), `--override-at 2:10`:
/// from t = 2.05 s the trace moves 2 mm/s (0.002 mm per 1 ms period, to the trace's 1e-6 mm);
/// the cycle time grows by the slower feed; no limit is exceeded.
#[test]
fn override_at_slows_the_running_block_within_50_ms() {
    let prog = program("override-at", "G21 G90 G64\nG1 X400 F1200\nM2\n");
    let trace = std::path::Path::new(&prog).with_file_name("t.csv");
    let trace_arg = trace.display().to_string();
    let (code, out, err) = stanok(&["run", &prog, "--json"]);
    assert_eq!(code, 0, "{err}");
    let base: serde_json::Value = serde_json::from_str(&out).unwrap();
    let t0 = base["cycle_time_s"].as_f64().unwrap();
    let (code, out, err) = stanok(&[
        "run",
        &prog,
        "--json",
        "--override-at",
        "2:10",
        "--trace",
        &trace_arg,
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["violation_count"], 0);
    let x = trace_x(&trace);
    let k = x.iter().position(|(t, _)| *t >= 2.05).unwrap();
    for w in x[k..k + 2000].windows(2) {
        assert!(((w[1].1 - w[0].1) - 0.002).abs() < 2.1e-6, "{w:?}");
    }
    // 360 mm at 2 mm/s instead of 20 mm/s: 162 s more (to the braking, ~0.01 s).
    let t = r["cycle_time_s"].as_f64().unwrap();
    assert!((t - t0 - 162.0).abs() < 0.02, "{t} vs {t0}");
}

/// `--override-at 2:0 --override-at 3:100`: at rest on the path within 21 ms, standing until 3 s,
/// then on at 20 mm/s; one second more; a schedule that leaves the feed at 0 is refused.
#[test]
fn override_at_zero_stops_on_the_path_and_a_raise_resumes() {
    let prog = program("override-zero", "G21 G90 G64\nG1 X400 F1200\nM2\n");
    let trace = std::path::Path::new(&prog).with_file_name("t.csv");
    let trace_arg = trace.display().to_string();
    let (_, out, _) = stanok(&["run", &prog, "--json"]);
    let t0 = serde_json::from_str::<serde_json::Value>(&out).unwrap()["cycle_time_s"]
        .as_f64()
        .unwrap();
    let (code, out, err) = stanok(&[
        "run",
        &prog,
        "--json",
        "--override-at",
        "2:0",
        "--override-at",
        "3:100",
        "--trace",
        &trace_arg,
    ]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["violation_count"], 0);
    let x = trace_x(&trace);
    let rest = x.iter().position(|(t, _)| *t >= 2.021).unwrap();
    let resume = x.iter().position(|(t, _)| *t >= 3.0).unwrap();
    assert!(x[rest..resume].iter().all(|p| p.1 == x[rest].1));
    assert!(x[resume + 30].1 - x[resume + 29].1 > 0.0199);
    let t = r["cycle_time_s"].as_f64().unwrap();
    assert!((t - t0 - 1.0).abs() < 0.002, "{t} vs {t0}");
    let (code, _, err) = stanok(&["run", &prog, "--override-at", "2:0"]);
    assert_eq!(code, 2);
    assert!(err.contains("stand for ever"), "{err}");
    let (code, _, err) = stanok(&["run", &prog, "--override-at", "2:rapid=150"]);
    assert_eq!(code, 2);
    assert!(err.contains("0 … 100"), "{err}");
}

fn json_run(prog: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["run", prog, "--json"];
    args.extend_from_slice(extra);
    let (code, out, err) = stanok(&args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

/// The contour error is measured on the trace: a square under G64 P0.05 has its largest distance
/// from the path at a corner blend (a circular blend 0.05 from the corner lies 0.0354 from the two
/// sides at its middle; the setpoints, 0.011 mm apart there, come within 3 % of that), the sides
/// themselves are exact; a full circle under G64 is on its circle to 1 µm
/// outside the junctions (it was 0.025 mm inside when arcs were chords).
#[test]
fn contour_error_is_measured_at_junctions_and_elsewhere() {
    let prog = program(
        "contour-square",
        "G21 G90 G64 P0.05\nG1 X50 F3000\nY50\nX0\nY0\nM2\n",
    );
    let r = json_run(&prog, &[]);
    let c = &r["contour_error"];
    let j = c["junctions"]["max_mm"].as_f64().unwrap();
    let e = c["elsewhere"]["max_mm"].as_f64().unwrap();
    let r45 = 0.05 / (std::f64::consts::PI / 8.0).tan();
    let middle = r45 * (1.0 - 0.5f64.sqrt());
    assert!(j <= middle + 1e-9 && j > 0.97 * middle, "{j}");
    assert!(e < 1e-9, "{e}");
    let line = c["junctions"]["line"].as_u64().unwrap();
    assert!((3..=5).contains(&line), "{line}");
    let (code, text, _) = stanok(&["run", &prog]);
    assert_eq!(code, 0);
    assert!(text.contains("Contour     0.034"), "{text}");
    let prog = program(
        "contour-circle",
        "G21 G90 G64\nG1 X10 F3000\nG2 X10 Y0 I10 J0\nG1 X30\nM2\n",
    );
    for profile in ["brisk", "soft"] {
        let r = json_run(&prog, &["--profile", profile]);
        let c = &r["contour_error"];
        assert!(c["elsewhere"]["max_mm"].as_f64().unwrap() < 1e-6, "{c}");
        assert!(
            c["junctions"]["max_mm"].as_f64().unwrap() <= 0.05 + 1e-9,
            "{c}"
        );
        assert_eq!(r["violation_count"], 0);
    }
}

/// The machine data's `path_tolerance` is G64's tolerance without P: 0.01 instead of 0.05.
#[test]
fn path_tolerance_is_machine_data() {
    let prog = program("path-tol", "G21 G90 G64\nG1 X50 F3000\nY50\nM2\n");
    let mill = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../machines/mill.toml"
    ))
    .unwrap();
    let machine = std::path::Path::new(&prog).with_file_name("tight.toml");
    std::fs::write(
        &machine,
        mill.replace("path_tolerance = 0.05", "path_tolerance = 0.01"),
    )
    .unwrap();
    let wide = json_run(&prog, &[]);
    let tight = json_run(&prog, &["--machine", &machine.display().to_string()]);
    let j = |r: &serde_json::Value| r["contour_error"]["junctions"]["max_mm"].as_f64().unwrap();
    let k = 1.0 - 0.5f64.sqrt();
    let r45 = |e: f64| e / (std::f64::consts::PI / 8.0).tan();
    for (r, e) in [(&wide, 0.05), (&tight, 0.01)] {
        let middle = r45(e) * k;
        assert!(
            j(r) <= middle + 1e-9 && j(r) > 0.95 * middle,
            "{} {e}",
            j(r)
        );
    }
}

/// The trace's S follows M3/M4/M5 (signed by the direction, 0 when stopped) and its `line` column
/// names the block being executed.
#[test]
fn trace_s_follows_the_spindle_and_line_names_the_block() {
    let prog = program(
        "spindle",
        "G21 G90 G61\nS1000 M3\nG1 X10 F600\nM5\nG1 X20\nM4\nG1 X30\nM2\n",
    );
    let trace = std::path::Path::new(&prog).with_file_name("t.csv");
    let (code, _, err) = stanok(&["run", &prog, "--trace", &trace.display().to_string()]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&trace).unwrap();
    let rows: Vec<(f64, f64, u32)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[1].parse().unwrap(),
                f[4].parse().unwrap(),
                f[5].parse().unwrap(),
            )
        })
        .collect();
    for (x, s, line) in &rows {
        let want = match line {
            3 => (1000.0, *x <= 10.0),
            5 => (0.0, *x >= 10.0 && *x <= 20.0),
            7 => (-1000.0, *x >= 20.0),
            _ => panic!("line {line}"),
        };
        assert_eq!(*s, want.0, "x {x} line {line}");
        assert!(want.1, "x {x} line {line}");
    }
    assert!(rows.iter().any(|r| r.2 == 5));
}

/// Per block, the limit that set its speed (`block_times` in `--json`, the slowest blocks in the
/// text report): on a mill whose Z runs at most 1000 mm/min, a long G1 X100 at F3000 runs at its
/// programmed feed, a G1 Z−50 at F3000 at Z's velocity limit (3 s instead of 1 s), and a 1 mm
/// move that must stop at the program end never reaches its feed: the axis acceleration.
#[test]
fn block_limits_name_what_set_the_speed() {
    let prog = program(
        "limits",
        "G21 G90 G64\nG1 X100 F3000\nG1 Z-50 F3000\nG1 X101 F3000\nM2\n",
    );
    let mill = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../machines/mill.toml"
    ))
    .unwrap();
    let z = mill.find("name = \"Z\"").unwrap();
    let v = z + mill[z..].find("max_velocity = 10000.0").unwrap();
    let slow_z = format!(
        "{}max_velocity = 1000.0{}",
        &mill[..v],
        &mill[v + "max_velocity = 10000.0".len()..]
    );
    let machine = std::path::Path::new(&prog).with_file_name("slow-z.toml");
    std::fs::write(&machine, slow_z).unwrap();
    let machine = machine.display().to_string();
    let r = json_run(&prog, &["--machine", &machine]);
    let blocks = r["block_times"].as_array().unwrap();
    let got: Vec<(u64, &str)> = blocks
        .iter()
        .map(|b| (b["line"].as_u64().unwrap(), b["limit"].as_str().unwrap()))
        .collect();
    assert_eq!(
        got,
        [
            (2, "programmed feed"),
            (3, "axis velocity"),
            (4, "axis acceleration")
        ]
    );
    let z_block = &blocks[1];
    assert!((z_block["nominal_s"].as_f64().unwrap() - 1.0).abs() < 0.01);
    assert!((z_block["planned_s"].as_f64().unwrap() - 3.0).abs() < 0.02);
    assert_eq!(r["block_times_truncated"], false);
    assert_eq!(r["slowest_blocks"][0]["line"], 3);
    let (code, text, _) = stanok(&["run", &prog, "--machine", &machine]);
    assert_eq!(code, 0);
    assert!(text.contains("line     3  3.005 s planned"), "{text}");
    assert!(text.contains("axis velocity"), "{text}");
    // Its length: 50 mm, less what the G64 blends at its ends cut off.
    assert!((z_block["length_mm"].as_f64().unwrap() - 50.0).abs() < 0.1);

    // The plot coloured by limit: each move in its limit's colour, the legend lists the three.
    let svg = std::path::Path::new(&prog).with_file_name("limits.svg");
    let svg_arg = svg.display().to_string();
    let (code, _, err) = stanok(&[
        "plot",
        &prog,
        "--machine",
        &machine,
        "--color",
        "limit",
        "-o",
        &svg_arg,
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&svg).unwrap();
    let legend: Vec<(&str, &str)> = text
        .split(r#"class="legend-colour" fill="none" stroke=""#)
        .skip(1)
        .map(|t| {
            let colour = &t[..7];
            let label = &t[t.find("<text").unwrap()..];
            let label = &label[label.find('>').unwrap() + 1..label.find("</text>").unwrap()];
            (colour, label)
        })
        .collect();
    assert_eq!(
        legend,
        [
            ("#2f9e44", "programmed feed"),
            ("#1c7ed6", "axis velocity"),
            ("#f59f00", "axis acceleration")
        ]
    );
    // X100 in the feed's green, the Z move in the velocity's blue, X101 in the acceleration's
    // orange.
    for colour in ["#2f9e44", "#1c7ed6", "#f59f00"] {
        let attrs = format!(r#"<path class="feed" fill="none" stroke="{colour}""#);
        assert!(text.contains(&attrs), "{attrs}");
    }
    // Coloured by speed: X100 at ~3000 mm/min and X101 at ~1000 mm/min or less fall in different
    // bands of 500 mm/min (the fastest line, ~2980 mm/min, over six bands).
    let (code, _, err) = stanok(&[
        "plot",
        &prog,
        "--machine",
        &machine,
        "--color",
        "speed",
        "-o",
        &svg_arg,
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains(">2500–3000 mm/min</text>"), "{text}");
    assert!(text.contains(r##"<path class="feed" fill="none" stroke="#313695""##));
    assert!(text.contains(r##"<path class="feed" fill="none" stroke="#f46d43""##));
}
