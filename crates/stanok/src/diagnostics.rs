//! Renders diagnostics like rustc, with miette: `file:line:column`, the code, the message, the
//! offending text underlined, and the notes.
//!
//! The source text is read again only to render (and only up to 64 MiB; beyond that the line and
//! column are printed without a snippet), so interpretation itself stays streaming.

use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan, MietteDiagnostic, NamedSource};
use stanok_canon::{Diagnostic, Severity};
use std::io::IsTerminal;
use std::path::Path;

const MAX_SNIPPET_FILE: u64 = 64 * 1024 * 1024;

/// Prints one diagnostic to stderr.
pub fn render(file: &Path, d: &Diagnostic) {
    eprint!("{}", to_string(file, d, std::io::stderr().is_terminal()));
}

/// The rendered text (no colour unless `colour`).
pub fn to_string(file: &Path, d: &Diagnostic, colour: bool) -> String {
    // A diagnostic about a subroutine file names it; its line and column are in that file.
    let file = d.file.as_deref().map(Path::new).unwrap_or(file);
    let name = file.display().to_string();
    let severity = match d.severity {
        Severity::Error => miette::Severity::Error,
        Severity::Warning => miette::Severity::Warning,
    };
    let sev = if d.is_error() { "error" } else { "warning" };
    let mut md = MietteDiagnostic::new(d.message.clone())
        .with_code(format!("{sev}[{}]", d.code))
        .with_severity(severity);
    if !d.notes.is_empty() {
        md = md.with_help(d.notes.join("\n"));
    }
    let source = std::fs::metadata(file)
        .ok()
        .filter(|m| m.len() <= MAX_SNIPPET_FILE)
        .and_then(|_| std::fs::read(file).ok())
        .map(|b| String::from_utf8_lossy(&b).into_owned());
    let Some(text) = source.filter(|t| d.span.line > 0 && (d.span.end as usize) <= t.len()) else {
        // Line 0: about the file as a whole (cannot read it, wrong kind), no position to give.
        let at = if d.span.line == 0 {
            name
        } else {
            format!("{name}:{}:{}", d.span.line, d.span.column)
        };
        let mut s = format!("{at}: {sev}[{}]: {}\n", d.code, d.message);
        for n in &d.notes {
            s.push_str(&format!("  = note: {n}\n"));
        }
        return s;
    };
    let len = (d.span.end - d.span.start) as usize;
    md = md.with_label(LabeledSpan::at(
        d.span.start as usize..d.span.start as usize + len,
        "here",
    ));
    let report = miette::Report::new(md).with_source_code(NamedSource::new(name, text));
    let theme = if colour {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let mut out = String::new();
    let _ = GraphicalReportHandler::new_themed(theme)
        .with_width(110)
        .render_report(&mut out, report.as_ref());
    out
}
