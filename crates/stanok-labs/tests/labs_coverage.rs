//! Every `corpus/labs` fixture has a test that asserts its header's numbers, and every fixture
//! reads without a panic in its dialect (named by its file-name prefix).

mod labs_support;

use labs_support::*;
use stanok_syntax::Dialect;

const TESTS: [&str; 3] = [
    include_str!("labs_nc31.rs"),
    include_str!("labs_gost20999.rs"),
    include_str!("labs_2p32_mc2101.rs"),
];

fn fixtures() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(LABS)
        .expect("corpus/labs")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".nc"))
        .collect();
    names.sort();
    names
}

#[test]
fn every_labs_fixture_is_named_by_a_test() {
    let names = fixtures();
    assert_eq!(names.len(), 42, "the spec lists 42 fixtures");
    for name in &names {
        assert!(
            TESTS.iter().any(|t| t.contains(name.as_str())),
            "{name} has no test"
        );
    }
}

#[test]
fn every_labs_fixture_runs_in_its_dialect_without_panicking() {
    for name in fixtures() {
        let dialect = Dialect::from_path(std::path::Path::new(&name));
        assert!(dialect.is_lab(), "{name}: prefix names a lab dialect");
        let r = run(&name, dialect, |o| o.continue_after_error = true);
        // Every motion starts where the previous one ended.
        let mut last = None;
        for c in &r.commands {
            if let Some(m) = c.value.motion() {
                if let Some(p) = last {
                    assert_eq!(m.start(), p, "{name}: continuous motion");
                }
                last = Some(m.end());
            }
        }
        for d in &r.errors {
            assert!(d.span.line >= 1, "{name}: error without a location: {d:?}");
        }
    }
}
