//! Renders diagnostics like rustc, with miette: `file:line:column`, the code, the message, the
//! offending text underlined with a label that says what is wrong, and the notes; or as one JSON
//! object per line (`check --json`).
//!
//! Colour: `--color always|never` decides; `auto` (the default) colours when stderr is a terminal,
//! unless `NO_COLOR` is set to anything but the empty string, and also when it is not a terminal if
//! `CLICOLOR_FORCE` is set to anything but `0` (the conventions of no-color.org and bixense.com).
//!
//! The source text is read again only to render (and only up to 64 MiB; beyond that the line and
//! column are printed without a snippet), so interpretation itself stays streaming; a file's text
//! is kept once read, so a thousand diagnostics do not read it a thousand times.

use crate::cli::ColorWhen;
use crate::source::{read_limited, Program};
use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan, MietteDiagnostic, NamedSource};
use serde::Serialize;
use stanok_canon::{Diagnostic, Severity};
use std::cell::RefCell;
use std::collections::HashMap;
use std::io::IsTerminal;
use std::path::Path;
use std::rc::Rc;
use std::sync::OnceLock;

const MAX_SNIPPET_FILE: u64 = 64 * 1024 * 1024;

static COLOUR: OnceLock<bool> = OnceLock::new();

/// Whether to colour, from the option and the environment (see the module doc).
pub fn colour_wanted(
    when: Option<ColorWhen>,
    no_color: Option<&str>,
    clicolor_force: Option<&str>,
    terminal: bool,
) -> bool {
    match when.unwrap_or(ColorWhen::Auto) {
        ColorWhen::Always => true,
        ColorWhen::Never => false,
        ColorWhen::Auto => {
            if no_color.is_some_and(|v| !v.is_empty()) {
                false
            } else if clicolor_force.is_some_and(|v| v != "0") {
                true
            } else {
                terminal
            }
        }
    }
}

/// Decides colour for this process (first call wins).
pub fn set_colour(when: Option<ColorWhen>) {
    let no_color = std::env::var("NO_COLOR").ok();
    let force = std::env::var("CLICOLOR_FORCE").ok();
    let _ = COLOUR.set(colour_wanted(
        when,
        no_color.as_deref(),
        force.as_deref(),
        std::io::stderr().is_terminal(),
    ));
}

/// True when stderr output is coloured.
pub fn colour() -> bool {
    *COLOUR.get().unwrap_or(&false)
}

thread_local! {
    /// Source texts read for snippets, by file name.
    static TEXTS: RefCell<HashMap<String, Option<Rc<str>>>> = RefCell::new(HashMap::new());
}

/// A file's text for snippets (cached).
fn text_of(name: &str, read: impl FnOnce() -> Option<String>) -> Option<Rc<str>> {
    TEXTS.with(|t| {
        t.borrow_mut()
            .entry(name.to_string())
            .or_insert_with(|| read().map(Rc::from))
            .clone()
    })
}

/// Where a diagnostic is: its file's name for people and the file's text (for the snippet).
fn source_of(program: &Program, d: &Diagnostic) -> (String, Option<Rc<str>>) {
    match &d.file {
        Some(f) => (
            f.clone(),
            text_of(f, || read_limited(Path::new(f), MAX_SNIPPET_FILE)),
        ),
        None => {
            let name = program.display();
            let text = text_of(&name, || program.snippet_text(MAX_SNIPPET_FILE));
            (name, text)
        }
    }
}

/// Prints one diagnostic about the program to stderr.
pub fn render(program: &Program, d: &Diagnostic) {
    let (name, text) = source_of(program, d);
    eprint!("{}", to_string(&name, text.as_deref(), d, colour()));
}

/// Prints one diagnostic about a data file (machine data, a tool table …) to stderr.
pub fn render_path(path: &Path, d: &Diagnostic) {
    let name = path.display().to_string();
    let text = text_of(&name, || read_limited(path, MAX_SNIPPET_FILE));
    eprint!("{}", to_string(&name, text.as_deref(), d, colour()));
}

/// What the underline says: the message when it is short, else its first clause.
pub fn label(message: &str) -> String {
    const MAX: usize = 64;
    if message.chars().count() <= MAX {
        return message.to_string();
    }
    let cut = [": ", "; ", " (", " — "]
        .iter()
        .filter_map(|s| message.find(s))
        .filter(|&i| i >= 12)
        .min();
    match cut {
        Some(i) if message[..i].chars().count() <= MAX => message[..i].to_string(),
        _ => message.chars().take(MAX - 1).collect::<String>() + "…",
    }
}

/// The rendered text of a diagnostic in file `name` whose text is `text` (no colour unless
/// `colour`).
pub fn to_string(name: &str, text: Option<&str>, d: &Diagnostic, colour: bool) -> String {
    let severity = match d.severity {
        Severity::Error => miette::Severity::Error,
        Severity::Warning => miette::Severity::Warning,
    };
    let sev = if d.is_error() { "error" } else { "warning" };
    let Some(text) = text.filter(|t| d.span.line > 0 && (d.span.end as usize) <= t.len()) else {
        // Line 0: about the file as a whole (cannot read it, wrong kind), no position to give.
        let at = if d.span.line == 0 {
            name.to_string()
        } else {
            format!("{name}:{}:{}", d.span.line, d.span.column)
        };
        let mut s = format!("{at}: {sev}[{}]: {}\n", d.code, d.message);
        for n in &d.notes {
            s.push_str(&format!("  = note: {n}\n"));
        }
        return s;
    };
    let mut md = MietteDiagnostic::new(d.message.clone())
        .with_code(format!("{sev}[{}]", d.code))
        .with_severity(severity);
    if !d.notes.is_empty() {
        md = md.with_help(d.notes.join("\n"));
    }
    let len = (d.span.end - d.span.start) as usize;
    md = md.with_label(LabeledSpan::at(
        d.span.start as usize..d.span.start as usize + len,
        label(&d.message),
    ));
    let report = miette::Report::new(md).with_source_code(NamedSource::new(name, text.to_string()));
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

/// One diagnostic as a JSON object (`check --json`): the stable fields documented in docs/cli.md.
#[derive(Serialize)]
struct JsonDiagnostic<'a> {
    file: String,
    line: u32,
    column: u32,
    start: u64,
    end: u64,
    severity: &'static str,
    code: String,
    message: &'a str,
    label: String,
    notes: &'a [String],
}

/// A diagnostic about `program` as one line of JSON (with its newline).
pub fn json_line(program: &Program, d: &Diagnostic) -> String {
    let j = JsonDiagnostic {
        file: d.file.clone().unwrap_or_else(|| program.display()),
        line: d.span.line,
        column: d.span.column,
        start: d.span.start,
        end: d.span.end,
        severity: if d.is_error() { "error" } else { "warning" },
        code: d.code.to_string(),
        message: &d.message,
        label: label(&d.message),
        notes: &d.notes,
    };
    let mut s = serde_json::to_string(&j).unwrap_or_default();
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::Span;

    #[test]
    fn colour_follows_the_option_then_no_color_then_clicolor_force_then_the_terminal() {
        use ColorWhen::*;
        assert!(colour_wanted(Some(Always), Some("1"), None, false));
        assert!(!colour_wanted(Some(Never), None, Some("1"), true));
        assert!(!colour_wanted(None, Some("1"), None, true));
        assert!(
            colour_wanted(None, Some(""), None, true),
            "an empty NO_COLOR does not count"
        );
        assert!(colour_wanted(Some(Auto), None, Some("1"), false));
        assert!(!colour_wanted(Some(Auto), None, Some("0"), false));
        assert!(
            !colour_wanted(None, Some("1"), Some("1"), true),
            "NO_COLOR wins"
        );
        assert!(colour_wanted(None, None, None, true));
        assert!(!colour_wanted(None, None, None, false));
    }

    #[test]
    fn labels_say_what_is_wrong() {
        assert_eq!(
            label("A axis is not configured on this machine"),
            "A axis is not configured on this machine"
        );
        let long = "radius at the start 28.7220 mm differs from the radius at the end 83.7655 mm: \
                    the end point is not on the circle";
        assert_eq!(
            label(long),
            "radius at the start 28.7220 mm differs from the radius at the end 83.7655 mm"
                .chars()
                .take(63)
                .collect::<String>()
                + "…"
        );
        assert_eq!(
            label("a subroutine of this program is not defined anywhere: o<x> (searched here)"),
            "a subroutine of this program is not defined anywhere"
        );
    }

    #[test]
    fn the_underline_carries_the_label_not_here() {
        let d = Diagnostic::error(
            "x::y",
            "A axis is not configured on this machine",
            Span::new(6, 9, 1, 7),
        );
        let s = to_string("p.nc", Some("G0 X1 A10\n"), &d, false);
        assert!(s.contains("╰── A axis is not configured"), "{s}");
        assert!(!s.contains("here"), "{s}");
        assert!(s.contains("p.nc:1:7"), "{s}");
    }
}
