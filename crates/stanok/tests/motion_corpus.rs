//! The planner's guarantees over every corpus program that moves, through the real command line
//! (`stanok run --json --trace`): programs the interpreter rejects are skipped.
//!
//! Per program: no velocity, acceleration, jerk, travel or path-tolerance violation in the report
//! (analytic and finite differences, see `stanok_motion::monitor`); the trace's last line is at the
//! report's final position (to the trace's six decimals) and at t = the report's cycle time; the
//! cycle time is not below 99 % of the nominal time (blends shorten the path a little). The servo period is 4 ms to keep the debug-build test
//! short (the guarantees do not depend on the period; the motion crate's tests run at 1 ms).

mod common;
use common::*;
use std::path::PathBuf;

fn corpus_programs() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for (dir, ext) in [("axioma", "nc"), ("rs274ngc", "ngc")] {
        let Ok(entries) = std::fs::read_dir(corpus(dir)) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.extension().and_then(|x| x.to_str()) == Some(ext) {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn every_corpus_program_that_moves_keeps_the_guarantees() {
    let programs = corpus_programs();
    assert!(programs.len() > 100, "corpus not found: {}", programs.len());
    let dir = std::env::temp_dir().join(format!("stanok-motion-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (mut checked, mut skipped) = (0, 0);
    for program in &programs {
        let trace = dir.join("trace.csv");
        let file = program.display().to_string();
        let (_, out, _) = stanok(&[
            "run",
            &file,
            "--json",
            "--servo-period",
            "4",
            "--trace",
            &trace.display().to_string(),
        ]);
        let Ok(r) = serde_json::from_str::<serde_json::Value>(&out) else {
            skipped += 1;
            continue;
        };
        if r["status"] != "ok" || r["motion_segments"].as_u64().unwrap_or(0) == 0 {
            skipped += 1;
            continue;
        }
        checked += 1;
        assert_eq!(r["violation_count"], 0, "{file}: {}", r["violations"]);
        let cycle = r["cycle_time_s"].as_f64().unwrap();
        let nominal = r["nominal_time_s"].as_f64().unwrap();
        // Blends and chords shorten the path a little under G64, so the planned time can dip
        // below the nominal one, but only by a hair.
        assert!(
            cycle >= 0.99 * nominal,
            "{file}: planned {cycle} ≪ nominal {nominal}"
        );
        let text = std::fs::read_to_string(&trace).unwrap();
        let last = text.lines().last().unwrap();
        let cols: Vec<f64> = last.split(',').map(|c| c.parse().unwrap()).collect();
        assert!(
            (cols[0] - cycle).abs() < 1e-6,
            "{file}: trace ends at {} s, cycle {cycle} s",
            cols[0]
        );
        let fin = &r["final_position"];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let want = fin[axis].as_f64().unwrap();
            assert!(
                (cols[k + 1] - want).abs() <= 1e-6,
                "{file}: trace ends at {axis} = {}, program at {want}",
                cols[k + 1]
            );
        }
        assert_eq!(
            text.lines().count() as u64,
            r["setpoints"].as_u64().unwrap() + 1,
            "{file}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
    eprintln!("checked {checked} programs, skipped {skipped}");
    assert!(checked >= 50, "only {checked} corpus programs ran");
}
