//! The lab dialects end to end: `check`, `run`, `canon` and `plot` with `--dialect`, the dialect
//! from the file-name prefix, `--strip-fixture-comments` and `--corrector`.

mod common;
use common::*;

fn lab(name: &str) -> String {
    corpus(&format!("labs/{name}"))
}

#[test]
fn run_program1_on_the_lathe_with_its_correctors() {
    let file = lab("2p32-stepped-shaft-program1.nc");
    let (code, out, err) = stanok(&[
        "run",
        &file,
        "--dialect",
        "2p32",
        "--machine",
        "lathe",
        "--strip-fixture-comments",
        "--corrector",
        "16=42",
        "--corrector",
        "17=28",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let r = json(&out);
    assert_eq!(r["status"], "ok");
    assert_eq!(r["program_ended"], true);
    // Deepest point: X −137.9 (r 4.1 of the end face), Z −208.6 (z −40.1).
    let bb = &r["bounding_box"];
    assert_eq!(bb["min"][0].as_f64(), Some(-137.9));
    assert!((bb["min"][2].as_f64().unwrap() + 208.6).abs() < 1e-9);
    // Two 4 s dwells (G4 X+4000).
    let dwell = r["dwell_time_s"].as_f64().unwrap();
    assert!((dwell - 8.0).abs() < 1e-9, "{dwell}");
}

#[test]
fn check_names_the_undocumented_words_with_file_line_column() {
    // Dialect from the file-name prefix; without --strip-fixture-comments the `;` header of an
    // NC-31 fixture is not program text: an error at line 1, column 1.
    let file = lab("nc31-rapid-flag.nc");
    let (code, _, err) = stanok(&["check", &file]);
    assert_eq!(code, 1);
    assert!(
        err.contains("nc31::syntax") && err.contains("nc31-rapid-flag.nc:1:1"),
        "{err}"
    );
    let (code, _, err) = stanok(&["check", &file, "--strip-fixture-comments"]);
    assert_eq!(code, 0, "{err}");
    // The 2P32 program's E/ω words (line 133).
    let file = lab("2p32-turn-mill-program3.nc");
    let (code, _, err) = stanok(&["check", &file]);
    assert_eq!(code, 1);
    assert!(
        err.contains("lab::unsupported") && err.contains("2p32-turn-mill-program3.nc:133:"),
        "{err}"
    );
}

#[test]
fn canon_of_an_nc31_arc_is_ordinary_json_canon() {
    let file = lab("nc31-arc-g2-group.nc");
    let (code, out, err) = stanok(&["canon", &file, "--strip-fixture-comments"]);
    assert_eq!(code, 0, "{err}");
    let arc = out
        .lines()
        .map(json)
        .find(|l| l["kind"] == "arc_feed")
        .expect("an arc");
    // From the origin: centre (0.20, 0, −0.10), end (0.10, 0, 0.10), about +Y.
    assert!((arc["centre"][0].as_f64().unwrap() - 0.2).abs() < 1e-12);
    assert!((arc["centre"][2].as_f64().unwrap() + 0.1).abs() < 1e-12);
    assert_eq!(arc["axis"][1].as_f64(), Some(1.0));
    assert_eq!(arc["n"], 22);
    assert_eq!(arc["line"], 13, "the group's first frame, N22");
}

#[test]
fn plot_of_a_lathe_program_has_the_zx_view() {
    let file = lab("nc31-two-axis-group-relative.nc");
    let out = std::env::temp_dir().join("stanok-labs-cli-plot.svg");
    let out = out.to_string_lossy().into_owned();
    let (code, _, err) = stanok(&["plot", &file, "--strip-fixture-comments", "-o", &out]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains(r#"data-view="zx""#), "lathe view");
    assert!(svg.contains("ZX (lathe"), "its title");
}

#[test]
fn gost_subprogram_from_the_subroutine_path() {
    let file = lab("gost20999-main-fig48-call-l0101.nc");
    let dir = corpus("labs");
    let (code, out, err) = stanok(&[
        "run",
        &file,
        "--strip-fixture-comments",
        "--subroutine-path",
        &dir,
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let r = json(&out);
    assert_eq!(r["arc_segments"], 4);
    let bb = &r["bounding_box"];
    let w = bb["max"][0].as_f64().unwrap() - bb["min"][0].as_f64().unwrap();
    let h = bb["max"][1].as_f64().unwrap() - bb["min"][1].as_f64().unwrap();
    assert!(
        (w - 20.0).abs() < 1e-9 && (h - 17.0).abs() < 1e-9,
        "{w} × {h}"
    );
}
