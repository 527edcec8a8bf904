//! Mazatrol EIA/ISO through the real command line (issue 18): the two example jobs on the built-in
//! machines `mazak-m` and `mazak-t` — `check` clean, `run` with the numbers their headers give,
//! `plot`, `convert` to RS274/NGC and AxiOMA round-tripping to the same motion within 2·10⁻⁶ mm —,
//! `--subroutine-path` by O-number, `--perm` keeping #500–#999 between runs, and bad input stopping
//! at its block with file:line:column and nothing of the block executed.
//!
//! Hand-computed numbers (`examples/mazak-m-job.eia` header): G54 = X100 Y50 Z-200, T01 length
//! 150, T02 length 120, TTPC machine = tip + 270·v(B) − (0, 0, 150).
//! * Feed distance: 18 holes × 13 mm = 234 mm; the G43.4 selection move N31 from machine Z0 (after
//!   G28) to the tip at work Z30 (machine −170) = 170 mm; the tip path N32–N36 = 250 mm (header):
//!   654 mm.
//! * Final position (N37 G49): X180 Y50 Z−50 B0. Bounding box: X up to 100 + 112.990381 (the
//!   bolt circle's last hole), Y up to 50 + 50 (the third row), Z from −195 (the tip at work Z5) to
//!   70 (N36: tip −50 + 270 − 150).

mod common;
use common::*;
use serde_json::Value;

const TOL_MM: f64 = 2e-6;

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn run_json(args: &[&str]) -> Value {
    let mut all = vec![
        "run",
        "--json",
        "--servo-period",
        "4",
        "--dialect",
        "mazatrol",
    ];
    all.extend_from_slice(args);
    let (code, out, err) = stanok(&all);
    assert_eq!(code, 0, "{args:?}: {err}\n{out}");
    json(&out)
}

/// `stanok canon --format jsonl`: one JSON object per command.
fn canon(file: &str, dialect: &str, machine: &str) -> Vec<Value> {
    let (code, out, err) = stanok(&[
        "canon",
        "--format",
        "jsonl",
        "--dialect",
        dialect,
        "--machine",
        machine,
        file,
    ]);
    assert_eq!(code, 0, "{file}: {err}");
    out.lines().map(json).collect()
}

fn is_motion(c: &Value) -> bool {
    matches!(
        c["kind"].as_str(),
        Some("straight_traverse" | "straight_feed" | "arc_feed")
    )
}

/// Every number of `a` and `b` (objects and arrays compared key by key) within `tol`. Not
/// compared: the source line and N label, and the start (the previous motion's end, compared
/// already — except where tool-centre-point control is switched on or off, where the source
/// restates the same machine position as the tip and a target without TCP does not).
fn same_numbers(a: &Value, b: &Value, tol: f64, path: &str) -> Result<(), String> {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, va) in x {
                if matches!(k.as_str(), "line" | "n" | "start") {
                    continue;
                }
                let vb = y.get(k).ok_or(format!("{path}.{k} missing"))?;
                same_numbers(va, vb, tol, &format!("{path}.{k}"))?;
            }
            Ok(())
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (va, vb)) in x.iter().zip(y).enumerate() {
                same_numbers(va, vb, tol, &format!("{path}[{i}]"))?;
            }
            Ok(())
        }
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if close(x, y, tol * x.abs().max(1.0)) {
                Ok(())
            } else {
                Err(format!("{path}: {x} vs {y}"))
            }
        }
        _ if a == b => Ok(()),
        _ => Err(format!("{path}: {a} vs {b}")),
    }
}

#[test]
fn the_example_jobs_check_clean_on_the_built_in_machines() {
    for (file, machine) in [
        ("examples/mazak-m-job.eia", "mazak-m"),
        ("examples/mazak-t-job.eia", "mazak-t"),
    ] {
        let path = repo(file);
        let (code, out, err) = stanok(&[
            "check",
            "--dialect",
            "mazatrol",
            "--machine",
            machine,
            &path,
        ]);
        assert_eq!(code, 0, "{file}: {out}{err}");
        assert!(
            format!("{out}{err}").contains("ok (0 warning(s))"),
            "{out}{err}"
        );
    }
}

#[test]
fn the_m_series_job_runs_with_its_headers_numbers() {
    let r = run_json(&["--machine", "mazak-m", &repo("examples/mazak-m-job.eia")]);
    assert_eq!(r["status"], "ok");
    assert_eq!(r["program_ended"], true);
    assert_eq!(r["violation_count"], 0);
    assert_eq!(r["tools_used"], serde_json::json!([1, 2]));
    assert_eq!(r["tool_changes"], 2);
    // 18 holes, 6 TTPC feed blocks (N31–N36) and G49's N37 with motion: 25 feed moves.
    assert_eq!(r["feed_segments"], 25);
    assert_eq!(r["arc_segments"], 0);
    let feed = num(&r["feed_distance_mm"]);
    assert!(close(feed, 18.0 * 13.0 + 170.0 + 250.0, 1e-6), "{feed}");
    let f = &r["final_position"];
    for (axis, want) in [("x", 180.0), ("y", 50.0), ("z", -50.0), ("b", 0.0)] {
        assert!(close(num(&f[axis]), want, 1e-6), "final {axis}: {f}");
    }
    let bb = &r["bounding_box"];
    assert!(close(num(&bb["max"][0]), 212.990381, 1e-6), "{bb}");
    assert!(close(num(&bb["max"][1]), 100.0, 1e-6), "{bb}");
    assert!(close(num(&bb["min"][2]), -195.0, 1e-6), "{bb}");
    assert!(close(num(&bb["max"][2]), 70.0, 1e-6), "{bb}");
    let log: Vec<String> = r["m_functions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| format!("{} {}", m["line"], m["text"].as_str().unwrap()))
        .collect();
    for want in [
        "25 M6 tool change to T1",
        "26 M3 spindle clockwise, 2000 rpm",
        "27 M8 flood on",
        "38 M6 tool change to T2",
        "39 M3 spindle clockwise, 6000 rpm",
        "50 M2/M30 program end",
    ] {
        assert!(log.iter().any(|l| l == want), "{want} not in {log:?}");
    }
    // The hole bottoms in machine coordinates: Z −60 (work Z−10), at the rows' and the bolt
    // circle's X Y (header).
    let c = canon(&repo("examples/mazak-m-job.eia"), "mazatrol", "mazak-m");
    let bottoms: Vec<(f64, f64)> = c
        .iter()
        .filter(|c| c["kind"] == "straight_feed" && close(num(&c["end"]["z"]), -60.0, 1e-9))
        .map(|c| (num(&c["end"]["x"]), num(&c["end"]["y"])))
        .collect();
    let mut want = Vec::new();
    for y in [70.0, 85.0, 100.0] {
        for x in [120.0, 135.0, 150.0, 165.0] {
            want.push((x, y));
        }
    }
    for (x, y) in [
        (100.0, 50.0),
        (87.009619, 42.5),
        (87.009619, 27.5),
        (100.0, 20.0),
        (112.990381, 27.5),
        (112.990381, 42.5),
    ] {
        want.push((x + 100.0, y + 50.0));
    }
    assert_eq!(bottoms.len(), 18, "{bottoms:?}");
    for ((x, y), (wx, wy)) in bottoms.iter().zip(&want) {
        assert!(close(*x, *wx, 1e-6) && close(*y, *wy, 1e-6), "{bottoms:?}");
    }
}

#[test]
fn the_t_series_job_runs_with_its_headers_numbers() {
    let r = run_json(&["--machine", "mazak-t", &repo("examples/mazak-t-job.eia")]);
    assert_eq!(r["status"], "ok");
    assert_eq!(r["program_ended"], true);
    assert_eq!(r["violation_count"], 0);
    assert_eq!(r["tools_used"], serde_json::json!([1, 2]));
    // N67 G49: X141.421356 Y60 Z191.421356, B45 C90 (header).
    let f = &r["final_position"];
    for (axis, want) in [
        ("x", 141.421356),
        ("y", 60.0),
        ("z", 191.421356),
        ("b", 45.0),
        ("c", 90.0),
    ] {
        assert!(close(num(&f[axis]), want, 1e-6), "final {axis}: {f}");
    }
    // The milling spindle (M203) at 3000 rpm for G12.1 and TTPC.
    let spindles = r["spindles"].as_array().unwrap();
    assert!(
        spindles
            .iter()
            .any(|s| s["spindle"] == 1 && num(&s["max_rpm"]) == 3000.0),
        "{spindles:?}"
    );
    // N70 program end; the G70 finishing pass ends at machine X49 Z220 (radius 29 + offset 20,
    // Z−60 + 200 + 80), then returns to A.
    let c = canon(&repo("examples/mazak-t-job.eia"), "mazatrol", "mazak-t");
    let ends: Vec<&Value> = c
        .iter()
        .filter(|c| is_motion(c) && c["line"] == 35)
        .map(|c| &c["end"])
        .collect();
    assert!(
        ends.iter()
            .any(|e| close(num(&e["x"]), 49.0, 1e-6) && close(num(&e["z"]), 220.0, 1e-6)),
        "{ends:?}"
    );
}

#[test]
fn the_example_jobs_plot() {
    for (file, machine) in [
        ("examples/mazak-m-job.eia", "mazak-m"),
        ("examples/mazak-t-job.eia", "mazak-t"),
    ] {
        let out = temp_in("mazatrol-plot", &format!("{machine}.svg"), "");
        let (code, _, err) = stanok(&[
            "plot",
            "--dialect",
            "mazatrol",
            "--machine",
            machine,
            &repo(file),
            "-o",
            &out,
        ]);
        assert_eq!(code, 0, "{err}");
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(svg.contains("<svg") && svg.len() > 5_000, "{file}");
    }
}

/// `stanok convert --to rs274ngc|axioma`: the converted program, interpreted on the same machine,
/// gives the same motion commands — kind, end (all nine axes), centre, feed — within
/// 2·10⁻⁶ mm (6 printed decimals), as the other dialects' round-trip tests.
#[test]
fn the_example_jobs_convert_and_round_trip() {
    for (file, machine) in [
        ("examples/mazak-m-job.eia", "mazak-m"),
        ("examples/mazak-t-job.eia", "mazak-t"),
    ] {
        let source = canon(&repo(file), "mazatrol", machine);
        let source: Vec<&Value> = source.iter().filter(|c| is_motion(c)).collect();
        assert!(source.len() > 80, "{file}");
        for (to, ext) in [("rs274ngc", "ngc"), ("axioma", "nc")] {
            let out = temp_in("mazatrol-convert", &format!("{machine}.{ext}"), "");
            let (code, _, err) = stanok(&[
                "convert",
                "--dialect",
                "mazatrol",
                "--machine",
                machine,
                "--to",
                to,
                &repo(file),
                "-o",
                &out,
            ]);
            assert_eq!(code, 0, "{err}");
            let again = canon(&out, to, machine);
            let again: Vec<&Value> = again.iter().filter(|c| is_motion(c)).collect();
            assert_eq!(source.len(), again.len(), "{file} → {to}");
            for (i, (a, b)) in source.iter().zip(&again).enumerate() {
                if let Err(e) = same_numbers(a, b, TOL_MM, "") {
                    panic!("{file} → {to}, motion {i} (line {}): {e}", a["line"]);
                }
            }
        }
    }
}

#[test]
fn subprogram_files_by_o_number_and_macro_functions() {
    // M98 P3100 L3 from a file O3100.eia on --subroutine-path, G65 P9100 from a file named O9100,
    // then the macro functions: SQRT[16] + FIX[2.7] + FUP[2.1] + ROUND[2.5] + ABS[-1] + ATAN[1]/[1]
    // + LN[EXP[1]] = 4 + 2 + 3 + 3 + 1 + 45 + 1 = 59.
    let main = temp_in(
        "mazatrol-subs",
        "main.eia",
        "O2\nG90 G00 X0 Y0 Z50.\nM98 P3100 L3\nG65 P9100 A2. B3.\n#100 = SQRT[16] + FIX[2.7] + FUP[2.1] + ROUND[2.5] + ABS[-1] + ATAN[1]/[1] + LN[EXP[1]]\nIF [#100 NE 59] GOTO 20\nG00 Z#100\nN20 M30\n",
    );
    temp_in(
        "mazatrol-subs",
        "O3100.eia",
        "O3100\nG91 G01 X10. F500.\nG90\nM99\n",
    );
    temp_in("mazatrol-subs", "O9100", "O9100\nG00 Y[#1 * #2]\nM99\n");
    let dir = std::path::Path::new(&main)
        .parent()
        .unwrap()
        .display()
        .to_string();
    let r = run_json(&["--machine", "mazak-m", "--subroutine-path", &dir, &main]);
    assert_eq!(r["status"], "ok", "{r}");
    let f = &r["final_position"];
    // G54 X100 Y50 Z-200: X 3 × 10, Y 2 × 3, Z 59.
    assert_eq!(
        (num(&f["x"]), num(&f["y"]), num(&f["z"])),
        (130.0, 56.0, -141.0)
    );
}

#[test]
fn perm_keeps_the_common_variables_500_to_999_between_runs() {
    let prog = temp_in(
        "mazatrol-perm",
        "count.eia",
        "O1\n#500 = [#500 + 1]\n#501 = #500 * 2.5\n#3006 = 1 (COUNTED)\nG00 X#500\nM30\n",
    );
    let perm = temp_in("mazatrol-perm", "perm.toml", "");
    std::fs::remove_file(&perm).unwrap();
    for run in 1..=2 {
        let r = run_json(&["--machine", "mazak-m", "--perm", &perm, &prog]);
        assert_eq!(num(&r["final_position"]["x"]), 100.0 + f64::from(run));
        // #3006 stops with its message.
        let messages = r["messages"].to_string();
        assert!(messages.contains("COUNTED"), "{messages}");
        let stored = std::fs::read_to_string(&perm).unwrap();
        let (_, double) = stanok_machine::perm_from_toml_str(&stored, "perm.toml").unwrap();
        let want = f64::from(run);
        assert_eq!(double.get(&500), Some(&want), "{stored}");
        assert_eq!(double.get(&501), Some(&(want * 2.5)), "{stored}");
    }
    // --perm is refused for a dialect without permanent variables.
    let ngc = temp_in("mazatrol-perm", "p.ngc", "G0 X1\nM2\n");
    let (code, _, err) = stanok(&["run", "--perm", &perm, &ngc]);
    assert_eq!(code, 2, "{err}");
}

/// The bad input: each stops at its block with the code, the message and
/// file:line:column, and a run keeps nothing of the block.
#[test]
fn bad_input_stops_at_the_block() {
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "unknown.eia",
            "G00 X1.\nG123.4 X2.\nM30\n",
            "mazatrol::unknown-code",
            ":2:1",
        ),
        (
            "expr.eia",
            "G00 X1.\n#1 = [1 + ]\nM30\n",
            "syntax::",
            ":2:11",
        ),
        (
            "goto.eia",
            "G00 X1.\nGOTO 99\nM30\n",
            "mazatrol::goto-target",
            ":2:6",
        ),
        (
            "m99.eia",
            "G00 X1.\nM99\n",
            "mazatrol::m99-without-caller",
            ":2:1",
        ),
        (
            "alarm.eia",
            "G00 X1.\n#3000 = 12 (TOOL BROKEN)\nM30\n",
            "MACRO ALARM 3012: TOOL BROKEN",
            ":2:1",
        ),
        (
            "ttpc.eia",
            "G90 G01 F1000.\nG43.4 X0 Y0 Z50. B0 H2\nG02 X10. Y0 R5. B10.\nM30\n",
            "(table 12.2, note 3)",
            ":3:1",
        ),
    ];
    for (name, text, want, at) in cases {
        let path = temp_in("mazatrol-bad", name, text);
        let (code, out, err) = stanok(&[
            "check",
            "--dialect",
            "mazatrol",
            "--machine",
            "mazak-m",
            &path,
        ]);
        let all = format!("{out}{err}");
        assert_eq!(code, 1, "{name}: {all}");
        assert!(all.contains(want), "{name}: {all}");
        assert!(all.contains(&format!("{name}{at}")), "{name}: {all}");
    }
    // WHILE nesting deeper than the control's 27 levels (#1 is vacant: 0 < 1 enters each).
    let mut deep = String::new();
    for n in 1..=28 {
        deep.push_str(&format!("WHILE [#1 LT 1] DO {n}\n"));
    }
    for n in (1..=28).rev() {
        deep.push_str(&format!("END {n}\n"));
    }
    deep.push_str("M30\n");
    let path = temp_in("mazatrol-bad", "deep.eia", &deep);
    let (code, out, err) = stanok(&[
        "check",
        "--dialect",
        "mazatrol",
        "--machine",
        "mazak-m",
        &path,
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        format!("{out}{err}").contains("mazatrol::loop-nesting"),
        "{out}{err}"
    );
    // A run keeps nothing of the failing block: X stays at the first block's 100 + 1.
    let path = temp_in(
        "mazatrol-bad",
        "partial.eia",
        "G00 X1.\nG01 X20. F100. G123.4\nM30\n",
    );
    let (code, out, _) = stanok(&[
        "run",
        "--json",
        "--dialect",
        "mazatrol",
        "--machine",
        "mazak-m",
        &path,
    ]);
    assert_eq!(code, 1);
    let r = json(&out);
    assert_eq!(r["status"], "error");
    assert_eq!(r["error"]["span"]["line"], 2);
    assert_eq!(num(&r["final_position"]["x"]), 101.0);
    assert_eq!(r["motion_segments"], 1);
}
