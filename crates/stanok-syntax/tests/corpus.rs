//! Golden tests over the shared corpus (read in place from `../../../shared/corpus`, never copied).

mod common;

use common::*;
use stanok_canon::Severity;
use stanok_syntax::{parse, Address, CommentKind, Dialect, Program};

const CORPUS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/corpus");

fn read(rel: &str) -> String {
    let path = format!("{CORPUS}/{rel}");
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    String::from_utf8(bytes).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn files(dir: &str, ext: &str) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(format!("{CORPUS}/{dir}"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(ext))
        .collect();
    names.sort();
    names
}

#[test]
fn syntax_forms_fixture_parses_with_the_values_its_header_states() {
    let text = read("axioma/s2_s4-syntax-forms-parse-only.nc");
    let (program, diags) = parse(&text, Dialect::Axioma);
    assert!(diags.is_empty(), "{diags:#?}");
    let blocks: Vec<_> = program
        .blocks
        .iter()
        .filter(|b| !b.words.is_empty())
        .collect();
    let idx = |letter: char, index: u8| Address::Indexed {
        letter: letter as u8,
        index,
    };
    let expected = vec![
        // 1  S2=1000: address S, index 2, '=', value 1000
        vec![(idx('S', 2), n(1000.0), "S2=1000")],
        // 2  G73 X-1 Y-1 I5 J5
        vec![
            (l('G'), n(73.0), "G73"),
            (l('X'), n(-1.0), "X-1"),
            (l('Y'), n(-1.0), "Y-1"),
            (l('I'), n(5.0), "I5"),
            (l('J'), n(5.0), "J5"),
        ],
        // 3  G173 X2 Y3 I5 J5
        vec![
            (l('G'), n(173.0), "G173"),
            (l('X'), n(2.0), "X2"),
            (l('Y'), n(3.0), "Y3"),
            (l('I'), n(5.0), "I5"),
            (l('J'), n(5.0), "J5"),
        ],
        // 4  G273 Q45 I5 J5
        vec![
            (l('G'), n(273.0), "G273"),
            (l('Q'), n(45.0), "Q45"),
            (l('I'), n(5.0), "I5"),
            (l('J'), n(5.0), "J5"),
        ],
        // 5  G10 X1
        vec![(l('G'), n(10.0), "G10"), (l('X'), n(1.0), "X1")],
        // 6  G16 X50 Y40
        vec![
            (l('G'), n(16.0), "G16"),
            (l('X'), n(50.0), "X50"),
            (l('Y'), n(40.0), "Y40"),
        ],
        // 7  G02 R60 Q0 I30 J0
        vec![
            (l('G'), n(2.0), "G02"),
            (l('R'), n(60.0), "R60"),
            (l('Q'), n(0.0), "Q0"),
            (l('I'), n(30.0), "I30"),
            (l('J'), n(0.0), "J0"),
        ],
    ];
    let got: Vec<_> = blocks.iter().map(|b| words(b)).collect();
    assert_eq!(got, expected);
    // One block per line: the seven blocks are the last seven lines, and the header is comments.
    let total = program.blocks.len();
    assert_eq!(blocks[0].line as usize, total - 6);
    for b in &program.blocks[..total - 7] {
        assert!(b.is_empty());
        assert_eq!(b.comments[0].kind, CommentKind::Line);
    }
}

/// Errors the AxiOMA corpus is expected to produce, each with its reason:
/// (file, line, code, reason). Since the high-level language is parsed (`int ii=0;`, `for(…)`,
/// `{`/`}`, `sprintf(…)`, `MSG(str)`, `F=$iPerm[1]`), the whole corpus parses clean.
const EXPECTED_AXIOMA_ERRORS: &[(&str, u32, &str, &str)] = &[];

#[test]
fn every_axioma_file_parses_and_only_listed_constructs_fail() {
    let names = files("axioma", ".nc");
    assert!(names.len() > 100, "corpus not found at {CORPUS}");
    let mut seen = Vec::new();
    let mut clean_files = 0;
    for name in &names {
        let text = read(&format!("axioma/{name}"));
        let (_, diags) = parse(&text, Dialect::Axioma);
        if diags.is_empty() {
            clean_files += 1;
        }
        for d in &diags {
            let code = d.code.to_string();
            let listed = EXPECTED_AXIOMA_ERRORS
                .iter()
                .any(|&(f, line, c, _)| f == name && line == d.span.line && c == code);
            assert!(
                listed && d.severity == Severity::Error,
                "{name}:{d} is not an expected diagnostic"
            );
            seen.push((name.clone(), d.span.line));
        }
    }
    for &(f, line, _, why) in EXPECTED_AXIOMA_ERRORS {
        assert!(
            seen.iter().any(|(n, l)| n == f && *l == line),
            "{f}:{line} ({why}) no longer fails: update the list"
        );
    }
    assert_eq!(clean_files, names.len());
}

#[test]
fn every_rs274ngc_file_parses_clean() {
    let names = files("rs274ngc", ".ngc");
    assert!(names.len() > 50);
    for name in &names {
        let text = read(&format!("rs274ngc/{name}"));
        let (program, diags) = parse(&text, Dialect::Rs274ngc);
        assert!(diags.is_empty(), "{name}: {diags:#?}");
        assert!(program.blocks.iter().any(|b| !b.words.is_empty()), "{name}");
    }
}

#[test]
fn rs274ngc_expression_fixture() {
    let text = read("rs274ngc/g38.2-probe-tool-length-example-1.ngc");
    let (program, diags) = parse(&text, Dialect::Rs274ngc);
    assert!(diags.is_empty());
    let b = program
        .blocks
        .iter()
        .find(|b| !b.assignments.is_empty())
        .expect("the assignment line");
    assert_eq!(
        b.slice(b.assignments[0].span),
        "#<zworkoffset> = [#[5203 + #5220 * 20] + #5213 * #5210]"
    );
}

#[test]
fn other_corpora_never_panic() {
    // Other dialects are not implemented yet; parsing them as AxiOMA must still not panic.
    for dir in ["cvu", "labs", "mazatrol"] {
        for name in files(dir, "") {
            let bytes = std::fs::read(format!("{CORPUS}/{dir}/{name}")).unwrap();
            let text = String::from_utf8_lossy(&bytes);
            let _: (Program, _) = parse(&text, Dialect::Axioma);
            let _: (Program, _) = parse(&text, Dialect::Rs274ngc);
        }
    }
}
