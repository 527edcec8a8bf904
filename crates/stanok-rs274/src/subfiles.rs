//! Where lines come from besides the program: subroutine files found on the subroutine path
//! (`o<name> call` of `name.ngc`, LinuxCNC's SUBROUTINE_PATH), and LinuxCNC's comment commands
//! that write the program log.
//!
//! A subroutine file is read by a reader of its own, stacked on the program's
//! (`stanok_interp_core::Source`): `flow.rs` decides when (its `CallFile` / `ReturnFromFile`
//! actions), the front end opens and closes, and while a file is open every line, position and
//! seek refer to it. `Flow::set_source` keeps labels of different files apart.

use crate::params::{normalise_name, Evaluator};
use crate::{flow, params, Rs274};
use stanok_canon::{Canon, Diagnostic, LogAction};
use stanok_interp_core::{Core, OpenFile};
use stanok_syntax::{Block, OKind};
use std::io::{BufRead, Seek};
use std::path::Path;

/// LinuxCNC's comment commands `(LOGOPEN,f)`, `(LOGAPPEND,f)`, `(LOGCLOSE)`, `(LOG,text)` and
/// `(PRINT,text)`: Some(command) for the log ones, Some(None) for PRINT (console output, no
/// command), None for an ordinary comment. Keywords are case-insensitive, as in LinuxCNC.
pub(crate) fn log_command(text: &str, eval: &params::Evaluator<'_>) -> Option<Option<Canon>> {
    let (head, rest) = match text.split_once(',') {
        Some((h, r)) => (h, r),
        None => (text, ""),
    };
    let action = match head.trim().to_ascii_uppercase().as_str() {
        "LOGOPEN" => LogAction::Open,
        "LOGAPPEND" => LogAction::Append,
        "LOGCLOSE" => LogAction::Close,
        "LOG" => LogAction::Write,
        "PRINT" => return Some(None),
        _ => return None,
    };
    let text = match action {
        LogAction::Write => substitute_parameters(rest, eval),
        LogAction::Close => String::new(),
        _ => rest.to_string(),
    };
    Some(Some(Canon::Log { action, text }))
}

impl Rs274 {
    /// `o<name> call` of a subroutine file: open it, find its `o<name> sub` line and continue
    /// reading after it (LinuxCNC: "EOF in file … seeking o-word" if the file does not define it).
    pub(crate) fn open_subroutine_file<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        path: &Path,
        label: &str,
    ) -> Result<(), Diagnostic> {
        let at = core.block.span();
        if core.source.depth() >= core.opts.max_call_depth {
            return Err(Diagnostic::error(
                "flow::call-depth",
                format!(
                    "subroutine files nested deeper than {}",
                    core.opts.max_call_depth
                ),
                at,
            )
            .fatal());
        }
        let mut reader = core.source.open(path, at)?;
        let mut block = Block::default();
        let mut diags = Vec::new();
        loop {
            let more = reader.next_block(&mut block, &mut diags).map_err(|e| {
                Diagnostic::error(
                    "io::read",
                    format!("cannot read {}: {e}", path.display()),
                    at,
                )
                .fatal()
            })?;
            if more {
                // Every call scans the file again up to its `sub` line: work done again.
                core.count_scanned_line()?;
            } else {
                return Err(Diagnostic::error(
                    "flow::sub-not-found",
                    format!("EOF in file:{} seeking o-word: o{label}", path.display()),
                    at,
                )
                .fatal());
            }
            if let Some(o) = &block.oword {
                if matches!(o.kind, OKind::Sub) && flow::label_text(&block, &o.label) == label {
                    break;
                }
            }
        }
        core.source.push(OpenFile {
            reader,
            path: path.to_path_buf(),
        });
        self.flow.set_source(core.source.depth());
        Ok(())
    }

    /// A subroutine file ended before its endsub.
    #[cold]
    pub(crate) fn file_without_endsub<R: BufRead + Seek>(&self, core: &Core<R>) -> Diagnostic {
        let path = core
            .source
            .current_file()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        Diagnostic::error(
            "flow::sub-no-endsub",
            format!("subroutine file {path} ended without its endsub"),
            core.block.span(),
        )
        .fatal()
    }
}

/// A parameter's value as LinuxCNC writes it into a comment (`convert_param_comment`): `%lf`, a
/// value within 10⁻⁶ of 0 as 0 (no "-0.000000"), C's `nan`/`inf`, and `######` for a text of 30
/// characters or more (its buffer).
fn param_text(v: f64) -> String {
    let v = if v.abs() < 1e-6 { 0.0 } else { v };
    let s = if v.is_nan() {
        if v.is_sign_negative() { "-nan" } else { "nan" }.to_string()
    } else if v.is_infinite() {
        if v < 0.0 { "-inf" } else { "inf" }.to_string()
    } else {
        format!("{v:.6}")
    };
    if s.len() >= 30 {
        "######".to_string()
    } else {
        s
    }
}

/// LinuxCNC `(DEBUG, …)`: `#n` and `#<name>` replaced by their values with six decimals.
pub fn substitute_parameters(text: &str, eval: &Evaluator<'_>) -> String {
    let mut out = String::with_capacity(text.len());
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'#' {
            if bytes.get(i + 1) == Some(&b'<') {
                if let Some(end) = text[i + 2..].find('>') {
                    let raw = &text[i + 2..i + 2 + end];
                    let name = normalise_name(raw);
                    let global = name.starts_with('_');
                    let v = eval.params_named(&name, global);
                    match v {
                        Some(v) => out.push_str(&param_text(v)),
                        None => out.push_str("######"),
                    }
                    i += end + 3;
                    continue;
                }
            } else {
                let digits = bytes[i + 1..]
                    .iter()
                    .take_while(|b| b.is_ascii_digit())
                    .count();
                if digits > 0 {
                    let n: usize = text[i + 1..i + 1 + digits].parse().unwrap_or(0);
                    out.push_str(&param_text(eval.numbered(n)));
                    i += 1 + digits;
                    continue;
                }
            }
        }
        let ch = text[i..].chars().next().unwrap_or(' ');
        out.push(ch);
        i += ch.len_utf8();
    }
    out
}
