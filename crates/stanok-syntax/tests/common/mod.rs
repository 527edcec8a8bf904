//! Helpers shared by the integration tests.
#![allow(dead_code)]

use stanok_canon::{Diagnostic, Severity};
use stanok_syntax::{Address, Block, BlockParser, Dialect, Value};

/// Parses one line as line 1 at offset 0.
pub fn one(text: &str, dialect: Dialect) -> (Block, Vec<Diagnostic>) {
    let mut parser = BlockParser::new(dialect);
    let mut block = Block::default();
    let mut diags = Vec::new();
    parser.parse_line(text, 1, 0, &mut block, &mut diags);
    (block, diags)
}

/// Parses one line that must give no diagnostic at all.
pub fn clean(text: &str, dialect: Dialect) -> Block {
    let (block, diags) = one(text, dialect);
    assert!(
        diags.is_empty(),
        "{text:?}: unexpected diagnostics {diags:#?}"
    );
    block
}

/// The words of a block as (address, value, written text).
pub fn words(b: &Block) -> Vec<(Address, Value, &str)> {
    b.words
        .iter()
        .map(|w| (w.address, w.value, b.slice(w.span)))
        .collect()
}

/// A letter address.
pub fn l(c: char) -> Address {
    Address::Letter(c as u8)
}

/// A numeric value.
pub fn n(v: f64) -> Value {
    Value::Number(v)
}

/// Asserts exactly one diagnostic, with this code, severity and 1-based column; returns it.
pub fn single<'a>(
    diags: &'a [Diagnostic],
    code: &str,
    severity: Severity,
    column: u32,
) -> &'a Diagnostic {
    assert_eq!(diags.len(), 1, "expected one diagnostic, got {diags:#?}");
    let d = &diags[0];
    assert_eq!(d.code.to_string(), code, "{d:#?}");
    assert_eq!(d.severity, severity, "{d:#?}");
    assert_eq!(d.span.column, column, "{d:#?}");
    d
}

/// Asserts exactly one error with this code at this column, covering `covered` of `text`.
pub fn single_error(text: &str, dialect: Dialect, code: &str, column: u32, covered: &str) -> Block {
    let (block, diags) = one(text, dialect);
    let d = single(&diags, code, Severity::Error, column);
    let got = &text[d.span.start as usize..d.span.end as usize];
    assert_eq!(got, covered, "span of {d:#?}");
    block
}
