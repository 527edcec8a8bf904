//! Bounds on a run's warnings, so that their number — and the text a caller prints for them —
//! grows at most linearly with the program, whatever the front end (issue 17: one line of 1,000
//! repeated words gave 1,000 warnings, each reprinting the line).
//!
//! After each step the driver hands the warnings the step added to [`Core::admit_warnings`]:
//! * a warning already given (same code, span and file: a loop passing the line again) is
//!   dropped;
//! * at most `CoreOptions::max_diagnostics_per_line` per line; the last one kept gets a note
//!   counting the rest (`and K more … on this line`);
//! * at most [`MAX_WARNINGS`] in all; past them nothing more is remembered (memory stays
//!   bounded too), the last one kept notes how many more there were.

use crate::driver::Core;
use stanok_canon::Diagnostic;
use std::collections::{HashMap, HashSet};
use std::io::{BufRead, Seek};

/// Most warnings one run keeps.
pub const MAX_WARNINGS: usize = 1000;

/// What the bounds remember of the warnings given.
#[derive(Debug, Default)]
pub(crate) struct Admitted {
    /// Code, span and file of every warning kept.
    keys: HashSet<(String, u64, u64, Option<String>)>,
    /// Warnings given per line (file, line).
    per_line: HashMap<(Option<String>, u32), usize>,
    /// Warnings dropped past [`MAX_WARNINGS`].
    dropped: usize,
}

/// Sets the note `and K more warning(s) …` on `d` (replacing an earlier one of its kind).
fn note_more(d: &mut Diagnostic, k: usize, where_: &str) {
    let note = format!("and {k} more warning(s) {where_}");
    match d
        .notes
        .iter_mut()
        .find(|n| n.starts_with("and ") && n.ends_with(where_))
    {
        Some(n) => *n = note,
        None => d.notes.push(note),
    }
}

impl<R: BufRead + Seek> Core<R> {
    /// Bounds the warnings a step added (`warnings[from..]`), as the module comment says.
    #[cold]
    #[inline(never)]
    pub(crate) fn admit_warnings(&mut self, from: usize) {
        let added: Vec<Diagnostic> = self.warnings.drain(from..).collect();
        let per_line = self.opts.max_diagnostics_per_line.max(1);
        let seen = &mut self.admitted;
        for w in added {
            if self.warnings.len() >= MAX_WARNINGS {
                seen.dropped += 1;
                if let Some(last) = self.warnings.last_mut() {
                    note_more(
                        last,
                        seen.dropped,
                        "in the run (at most 1000 warnings are kept)",
                    );
                }
                continue;
            }
            let key = (w.code.to_string(), w.span.start, w.span.end, w.file.clone());
            if !seen.keys.insert(key) {
                continue;
            }
            let count = seen
                .per_line
                .entry((w.file.clone(), w.span.line))
                .or_insert(0);
            *count += 1;
            if *count > per_line {
                let more = *count - per_line;
                if let Some(last) = self
                    .warnings
                    .iter_mut()
                    .rev()
                    .find(|k| k.span.line == w.span.line && k.file == w.file)
                {
                    note_more(last, more, "on this line (--max-diagnostics-per-line)");
                }
                continue;
            }
            self.warnings.push(w);
        }
    }
}
