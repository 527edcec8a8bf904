//! One diagnostic type for every stage.
//!
//! Syntax, interpreter, machine data and motion all report problems as a [`Diagnostic`]: a code, a
//! short message (grbl-style: what is wrong, not a paragraph), the primary span and optional notes.
//! The code is the manual's error number where the manual gives one (`621`, `653`, …) and a stable
//! Stanok identifier otherwise, so that tests and users can match on it.

use crate::span::Span;
use serde::Serialize;
use std::fmt;

/// How bad it is. An error stops the run at its block; a warning is reported and the block runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// The block cannot be executed; nothing at or after it runs.
    Error,
    /// Reported; execution continues (e.g. the ignored `/` of AxiOMA).
    Warning,
}

/// The identifier of a diagnostic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum DiagCode {
    /// An error number printed in the control's manual (AxiOMA 621/622/623, 653, 615, 617 …).
    Manual(u32),
    /// A Stanok identifier such as `"syntax::unclosed-comment"` where the manual has no number.
    Stanok(&'static str),
}

impl fmt::Display for DiagCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DiagCode::Manual(n) => write!(f, "E{n}"),
            DiagCode::Stanok(s) => f.write_str(s),
        }
    }
}

/// A problem found in a program or in machine data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Manual number or Stanok identifier.
    pub code: DiagCode,
    /// One line saying what is wrong.
    pub message: String,
    /// The offending text (a word, or the whole block when no single word is to blame).
    pub span: Span,
    /// Extra lines: the arithmetic that failed, the rule of the manual, a hint.
    pub notes: Vec<String>,
    /// The file the span refers to when it is not the program being run (an RS274/NGC subroutine
    /// file called from it); None = the program.
    pub file: Option<String>,
    /// The run cannot go on past it, not even to list further errors (`stanok check`): the
    /// program cannot be read or followed (I/O, control flow, the block limit, no program end).
    #[serde(skip)]
    pub fatal: bool,
}

impl Diagnostic {
    /// An error with a Stanok code.
    pub fn error(code: &'static str, message: impl Into<String>, span: Span) -> Self {
        Diagnostic {
            severity: Severity::Error,
            code: DiagCode::Stanok(code),
            message: message.into(),
            span,
            notes: Vec::new(),
            file: None,
            fatal: false,
        }
    }

    /// An error carrying the manual's error number.
    pub fn manual(number: u32, message: impl Into<String>, span: Span) -> Self {
        Diagnostic {
            severity: Severity::Error,
            code: DiagCode::Manual(number),
            message: message.into(),
            span,
            notes: Vec::new(),
            file: None,
            fatal: false,
        }
    }

    /// A warning with a Stanok code.
    pub fn warning(code: &'static str, message: impl Into<String>, span: Span) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            code: DiagCode::Stanok(code),
            message: message.into(),
            span,
            notes: Vec::new(),
            file: None,
            fatal: false,
        }
    }

    /// Adds a note (builder style).
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    /// The same diagnostic, marked as ending the run (see [`Diagnostic::fatal`]).
    pub fn fatal(mut self) -> Self {
        self.fatal = true;
        self
    }

    /// True for [`Severity::Error`].
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl Diagnostic {
    /// The same diagnostic, located in `file` (see [`Diagnostic::file`]).
    pub fn in_file(mut self, file: impl Into<String>) -> Self {
        self.file = Some(file.into());
        self
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sev = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(
            f,
            "{}:{}: {sev}[{}]: {}",
            self.span.line, self.span.column, self.code, self.message
        )
    }
}

impl std::error::Error for Diagnostic {}
