//! Renders diagnostics like rustc, with miette: `file:line:column`, the code, the message, the
//! offending text underlined, and the notes.
//!
//! ## Bounded echo
//! The source shown is a window of the offending line around the span, read from the file by
//! seeking to it: at most [`max_echo_bytes`] bytes (a quarter before the span, up to half of the
//! span itself, the rest after it), cut at the line's ends, with `…` where the line goes on. So
//! one diagnostic costs the same whatever the size of the program or the length of its line (a
//! 1 MB comment is not echoed whole, a warning on each of 4,000 words of one line does not print
//! the line 4,000 times), and the columns miette lays out stay small (a column above 65,535
//! made its formatter panic). Messages and notes are clipped to the same budget times four.
//! The header's `line:column` are the span's own, whatever part of the line is shown.

use miette::{
    GraphicalReportHandler, GraphicalTheme, LabeledSpan, MietteDiagnostic, MietteError,
    MietteSpanContents, SourceCode, SourceSpan, SpanContents,
};
use stanok_canon::{Diagnostic, Severity};
use std::io::{IsTerminal, Read, Seek, SeekFrom};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Default of [`max_echo_bytes`].
pub const DEFAULT_MAX_ECHO_BYTES: usize = 240;

static MAX_ECHO: AtomicUsize = AtomicUsize::new(DEFAULT_MAX_ECHO_BYTES);

/// Most bytes of program text one diagnostic shows (`--max-echo-bytes`).
pub fn max_echo_bytes() -> usize {
    MAX_ECHO.load(Ordering::Relaxed)
}

/// Sets [`max_echo_bytes`] (at least 16).
pub fn set_max_echo_bytes(n: usize) {
    MAX_ECHO.store(n.max(16), Ordering::Relaxed);
}

/// Prints one diagnostic to stderr.
pub fn render(file: &Path, d: &Diagnostic) {
    eprint!("{}", to_string(file, d, std::io::stderr().is_terminal()));
}

/// `text` cut to at most `max` bytes (at a character boundary) with `…` when cut.
fn clip(text: &str, max: usize) -> std::borrow::Cow<'_, str> {
    if text.len() <= max {
        return text.into();
    }
    let mut end = max;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}… ({} bytes in all)", &text[..end], text.len()).into()
}

/// The rendered text (no colour unless `colour`).
pub fn to_string(file: &Path, d: &Diagnostic, colour: bool) -> String {
    // A diagnostic about a subroutine file names it; its line and column are in that file.
    let file = d.file.as_deref().map(Path::new).unwrap_or(file);
    let name = file.display().to_string();
    let echo = max_echo_bytes();
    let message = clip(&d.message, 4 * echo);
    let notes: Vec<_> = d.notes.iter().map(|n| clip(n, 4 * echo)).collect();
    let severity = match d.severity {
        Severity::Error => miette::Severity::Error,
        Severity::Warning => miette::Severity::Warning,
    };
    let sev = if d.is_error() { "error" } else { "warning" };
    let window = (d.span.line > 0)
        .then(|| Window::read(file, d, echo, name.clone()))
        .flatten();
    let Some(window) = window else {
        // Line 0: about the file as a whole (cannot read it, wrong kind), no position to give.
        let at = if d.span.line == 0 {
            name
        } else {
            format!("{name}:{}:{}", d.span.line, d.span.column)
        };
        let mut s = format!("{at}: {sev}[{}]: {message}\n", d.code);
        for n in &notes {
            s.push_str(&format!("  = note: {n}\n"));
        }
        return s;
    };
    let mut md = MietteDiagnostic::new(message.into_owned())
        .with_code(format!("{sev}[{}]", d.code))
        .with_severity(severity);
    if !notes.is_empty() {
        md = md.with_help(notes.join("\n"));
    }
    md = md.with_label(LabeledSpan::at(window.label.clone(), "here"));
    let report = miette::Report::new(md).with_source_code(window);
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

/// The part of the span's line that a diagnostic shows (module doc), as miette's source: its
/// line and column numbers are the file's.
#[derive(Debug)]
struct Window {
    name: String,
    text: String,
    /// The span, in `text`.
    label: std::ops::Range<usize>,
    /// 0-based line of the file.
    line0: usize,
    /// 0-based column (characters) of the file's line where `text` starts.
    col0: usize,
}

impl Window {
    /// Reads the window of `d.span` from `file`; None when the file cannot be read there.
    fn read(file: &Path, d: &Diagnostic, echo: usize, name: String) -> Option<Window> {
        let span = d.span;
        let before_max = (echo / 4) as u64;
        let shown_max = (echo / 2) as u64;
        let lo = span.start.saturating_sub(before_max);
        let shown_len = span.len().min(shown_max);
        let hi = span.start + shown_len + (echo as u64 - shown_len.min(echo as u64)) + 4;
        let mut f = std::fs::File::open(file).ok()?;
        f.seek(SeekFrom::Start(lo)).ok()?;
        let mut bytes = Vec::new();
        f.take(hi - lo).read_to_end(&mut bytes).ok()?;
        let at = usize::try_from(span.start - lo).ok()?;
        if at > bytes.len() {
            return None;
        }
        // Before: from the line start (the last LF before the span), else `…`.
        let line_start = bytes[..at].iter().rposition(|&b| b == b'\n').map(|i| i + 1);
        let mut b0 = line_start.unwrap_or(0);
        while b0 < at && is_continuation(bytes[b0]) {
            b0 += 1;
        }
        let elided_before = line_start.is_none() && lo > 0;
        // The span's part: up to `shown_max` bytes, not past the line's end.
        let line_end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .map_or(bytes.len(), |i| at + i);
        let mut s1 = (at + shown_len as usize).min(line_end);
        while s1 > at && s1 < bytes.len() && is_continuation(bytes[s1]) {
            s1 -= 1;
        }
        // After: the rest of the budget, not past the line's end.
        let budget = echo.saturating_sub(s1 - b0);
        let mut a1 = (s1 + budget).min(line_end);
        while a1 > s1 && a1 < bytes.len() && is_continuation(bytes[a1]) {
            a1 -= 1;
        }
        let elided_after =
            a1 < line_end || (line_end == bytes.len() && hi - lo == bytes.len() as u64);
        let before = String::from_utf8_lossy(&bytes[b0..at]);
        let shown = String::from_utf8_lossy(&bytes[at..s1]);
        let after = String::from_utf8_lossy(&bytes[s1..a1]);
        let mut text = String::new();
        if elided_before {
            text.push('…');
        }
        text.push_str(&before);
        let label_start = text.len();
        text.push_str(&shown);
        let label = label_start..text.len();
        text.push_str(&after);
        if elided_after {
            text.push('…');
        }
        let chars_before = text[..label_start].chars().count();
        Some(Window {
            name,
            text,
            label,
            line0: span.line.saturating_sub(1) as usize,
            col0: (span.column as usize).saturating_sub(1 + chars_before),
        })
    }
}

fn is_continuation(b: u8) -> bool {
    (0x80..0xc0).contains(&b)
}

impl SourceCode for Window {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'a> + 'a>, MietteError> {
        let inner = self
            .text
            .read_span(span, context_lines_before, context_lines_after)?;
        // Columns in characters, as the span's (miette counts bytes): the window is one line.
        let column = if inner.line() == 0 {
            let at = inner.span().offset().min(self.text.len());
            let before = self.text.get(..at).map_or(at, |t| t.chars().count());
            self.col0 + before
        } else {
            inner.column()
        };
        Ok(Box::new(MietteSpanContents::new_named(
            self.name.clone(),
            inner.data(),
            *inner.span(),
            self.line0 + inner.line(),
            column,
            inner.line_count(),
        )))
    }
}
