//! `stanok plot` through the command line: the format from the extension, `-o -`, the default
//! name, `--view`, `--size`, the lathe view for lathes and lathe dialects.

mod common;
use common::*;

fn temp(name: &str, text: &str) -> String {
    temp_in("plot", name, text)
}

/// Width and height of a PNG (from its IHDR chunk), after checking its signature.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR");
    (
        u32::from_be_bytes(bytes[16..20].try_into().unwrap()),
        u32::from_be_bytes(bytes[20..24].try_into().unwrap()),
    )
}

#[test]
fn the_extension_decides_the_format() {
    let demo = repo("examples/demo-plate.nc");
    let png = temp("demo.png", "");
    let (code, _, err) = stanok(&["plot", &demo, "-o", &png, "--size", "800x600"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("wrote") && err.contains("800 × 600 px"),
        "{err}"
    );
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (800, 600));
    let upper = temp("demo.PNG", "");
    assert_eq!(stanok(&["plot", &demo, "-o", &upper]).0, 0);
    assert_eq!(png_size(&std::fs::read(&upper).unwrap()), (1200, 900));
    let svg = temp("demo.svg", "");
    assert_eq!(stanok(&["plot", &demo, "-o", &svg]).0, 0);
    assert!(std::fs::read_to_string(&svg)
        .unwrap()
        .starts_with("<svg xmlns"));
    // Anything else is refused before any work, and nothing is written.
    let jpg = temp("demo.jpg", "");
    std::fs::remove_file(&jpg).unwrap();
    let (code, _, err) = stanok(&["plot", &demo, "-o", &jpg]);
    assert_eq!(code, 2);
    assert!(err.contains(".svg or .png"), "{err}");
    assert!(!std::path::Path::new(&jpg).exists());
    for bad in ["10x10", "wide", "99999x600"] {
        assert_eq!(stanok(&["plot", &demo, "--size", bad]).0, 2, "{bad}");
    }
}

#[test]
fn dash_writes_svg_to_standard_output_and_no_o_writes_next_to_the_caller() {
    let demo = repo("examples/demo-plate.nc");
    let (code, out, err) = stanok(&["plot", &demo, "-o", "-"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("<svg xmlns") && out.trim_end().ends_with("</svg>"));
    assert!(!std::path::Path::new("-").exists(), "no file named -");
    let dir = std::env::temp_dir().join(format!("stanok-plot-cwd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (code, _, err) = stanok_with(&["plot", &demo], &[], None, Some(&dir));
    assert_eq!(code, 0, "{err}");
    let written = dir.join("demo-plate.svg");
    assert!(written.exists(), "{err}");
    assert!(err.contains("wrote demo-plate.svg"), "{err}");
}

/// The `data-view` ids of a sheet.
fn views(svg: &str) -> Vec<String> {
    svg.split(r#"class="view" data-view=""#)
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect()
}

#[test]
fn views_are_chosen_and_lathes_get_the_lathe_view() {
    let demo = repo("examples/demo-plate.nc");
    let sheet = |args: &[&str]| {
        let mut all = vec!["plot", "-o", "-"];
        all.extend_from_slice(args);
        let (code, out, err) = stanok(&all);
        assert_eq!(code, 0, "{args:?}: {err}");
        out
    };
    assert_eq!(views(&sheet(&[&demo])), ["xy", "iso", "xz", "yz"]);
    for (view, id) in [
        ("xy", "xy"),
        ("xz", "xz"),
        ("yz", "yz"),
        ("iso", "iso"),
        ("lathe", "zx"),
    ] {
        assert_eq!(views(&sheet(&[&demo, "--view", view])), [id], "{view}");
    }
    assert_eq!(views(&sheet(&[&demo, "--view", "all"])).len(), 4);
    // A lathe (the built-in `lathe`) and a lathe dialect: the ZX view alone by default.
    let turning = corpus("axioma/s4_7_1-absolute-turning-example-4_14.nc");
    assert_eq!(views(&sheet(&[&turning, "--machine", "lathe"])), ["zx"]);
    let nc31 = corpus("labs/nc31-absolute-xz-moves.nc");
    let svg = sheet(&[&nc31, "--strip-fixture-comments", "--machine", "lathe"]);
    assert_eq!(views(&svg), ["zx"]);
    assert!(svg.contains(r#"class="centre-line""#));
    // Asked for, a lathe gets the four views with ZX in place of XZ.
    assert_eq!(
        views(&sheet(&[&turning, "--machine", "lathe", "--view", "all"])),
        ["xy", "iso", "zx", "yz"]
    );
}

#[test]
fn the_sheet_has_a_grid_and_the_extents_dimensioned() {
    let demo = repo("examples/demo-plate.nc");
    let (_, svg, _) = stanok(&["plot", &demo, "-o", "-", "--view", "xy"]);
    // The plate: X −5 … 60 (65 mm, the lead-in from X−5), Y 0 … 40.
    assert!(
        svg.contains(r#"class="dimension" data-mm="65""#),
        "X extent"
    );
    assert!(
        svg.contains(r#"class="dimension" data-mm="40""#),
        "Y extent"
    );
    assert!(svg.contains(">65 mm</text>") && svg.contains(">40 mm</text>"));
    assert!(svg.contains(r#"class="grid""#));
    for label in [">0</text>", ">20</text>", ">40</text>"] {
        assert!(svg.contains(label), "{label}");
    }
}
