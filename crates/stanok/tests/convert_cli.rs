//! `stanok convert` through the real command line: a program converted to each target and run on
//! the simulated machine gives the run the source gives — same motion counts, rapid and feed
//! distances (within 1e-5 mm), bounding box and final position (within 1e-6 mm) — and a program
//! with an error is not converted.

mod common;
use common::*;

fn run_json(file: &str) -> serde_json::Value {
    let (code, out, err) = stanok(&["run", file, "--json", "--servo-period", "4"]);
    assert_eq!(code, 0, "{file}: {err}");
    json(&out)
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

#[test]
fn converted_programs_run_the_same_path_on_the_machine() {
    for (source, dialect) in [
        (repo("examples/demo-plate.nc"), "axioma"),
        (repo("examples/demo-bolt-circle.ngc"), "rs274ngc"),
    ] {
        let original = run_json(&source);
        for (to, ext) in [("rs274ngc", "ngc"), ("axioma", "nc")] {
            let out = temp_in("convert", &format!("{dialect}-to-{to}.{ext}"), "");
            let (code, _, err) = stanok(&["convert", &source, "--to", to, "-o", &out]);
            assert_eq!(code, 0, "{err}");
            assert!(err.contains("wrote"), "{err}");
            let again = run_json(&out);
            let what = format!("{source} → {to}");
            for key in [
                "motion_segments",
                "rapid_segments",
                "feed_segments",
                "arc_segments",
            ] {
                assert_eq!(original[key], again[key], "{what}: {key}");
            }
            for key in ["rapid_distance_mm", "feed_distance_mm"] {
                let (a, b) = (num(&original[key]), num(&again[key]));
                assert!((a - b).abs() < 1e-5, "{what}: {key} {a} vs {b}");
            }
            for corner in ["min", "max"] {
                for i in 0..3 {
                    let a = num(&original["bounding_box"][corner][i]);
                    let b = num(&again["bounding_box"][corner][i]);
                    assert!((a - b).abs() < 1e-6, "{what}: bounding box {corner}");
                }
            }
            for axis in ["x", "y", "z"] {
                let a = num(&original["final_position"][axis]);
                let b = num(&again["final_position"][axis]);
                assert!((a - b).abs() < 1e-6, "{what}: final {axis}");
            }
        }
    }
}

#[test]
fn a_program_with_an_error_is_not_converted() {
    let bad = temp_in("convert", "bad.ngc", "G0 X0 Y0\nG2 X10 Y0 I1 J0 F100\nM2\n");
    let (code, out, err) = stanok(&["convert", &bad, "--to", "axioma"]);
    assert_eq!(code, 1);
    assert!(out.is_empty(), "{out}");
    assert!(err.contains("not converted"), "{err}");
}

/// A lab program (2P32 stepped shaft, with its correctors) converted for the lathe: X Z only (the
/// lathe has no Y, so no Y word is written), the lab's machine M functions as comments, and the
/// converted program runs on the lathe exactly as the source does — same segment counts, the
/// 8 s of dwell, distances within 1e-6 mm, the same bounding box and end.
#[test]
fn a_lab_program_converted_for_the_lathe_runs_the_same() {
    let source = corpus("labs/2p32-stepped-shaft-program1.nc");
    let lab = [
        "--dialect",
        "2p32",
        "--machine",
        "lathe",
        "--strip-fixture-comments",
        "--corrector",
        "16=42",
        "--corrector",
        "17=28",
    ];
    let mut args = vec!["run", source.as_str()];
    args.extend(lab);
    args.push("--json");
    let (code, out, err) = stanok(&args);
    assert_eq!(code, 0, "{err}");
    let original = json(&out);
    for (to, ext) in [("rs274ngc", "ngc"), ("axioma", "nc")] {
        let out_file = temp_in("convert", &format!("shaft-to-{to}.{ext}"), "");
        let mut args = vec!["convert", source.as_str(), "--to", to, "-o", &out_file];
        args.extend(lab);
        let (code, _, err) = stanok(&args);
        assert_eq!(code, 0, "{err}");
        assert!(err.contains("M86"), "the lab's M86 is reported: {err}");
        let text = std::fs::read_to_string(&out_file).unwrap();
        assert!(
            !text
                .lines()
                .any(|l| !l.starts_with(['(', ';']) && l.contains(" Y")),
            "no Y word for the lathe:\n{text}"
        );
        let (code, out, err) = stanok(&["run", &out_file, "--machine", "lathe", "--json"]);
        assert_eq!(code, 0, "{to}: {err}");
        let again = json(&out);
        assert_eq!(again["status"], "ok", "{to}");
        for key in ["motion_segments", "rapid_segments", "feed_segments"] {
            assert_eq!(original[key], again[key], "{to}: {key}");
        }
        for key in ["rapid_distance_mm", "feed_distance_mm", "dwell_time_s"] {
            let (a, b) = (num(&original[key]), num(&again[key]));
            assert!((a - b).abs() < 1e-6, "{to}: {key} {a} vs {b}");
        }
        assert!((num(&again["dwell_time_s"]) - 8.0).abs() < 1e-9);
        assert_eq!(original["bounding_box"], again["bounding_box"], "{to}");
        assert_eq!(original["final_position"], again["final_position"], "{to}");
    }
}
