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
    assert_eq!(lines[0], "t,X,Y,Z,S");
    assert_eq!(lines.len(), 1027);
    assert_eq!(lines[1], "0.000000,0.000000,0.000000,0.000000,0.000");
    assert_eq!(
        *lines.last().unwrap(),
        "2.050000,100.000000,0.000000,0.000000,0.000"
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
