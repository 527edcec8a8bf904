//! Where lines come from besides the program: subroutine files found on the subroutine path
//! (`o<name> call` of `name.ngc`, LinuxCNC's SUBROUTINE_PATH), and LinuxCNC's comment commands
//! that write the program log.
//!
//! A subroutine file is read by a reader of its own, stacked on the program's: `flow.rs` decides
//! when (its `CallFile` / `ReturnFromFile` actions), the driver opens and closes, and while a file
//! is open every line, position and seek refer to it. `Flow::set_source` keeps labels of different
//! files apart.

use crate::{flow, params, Interpreter};
use stanok_canon::{Canon, Diagnostic, LogAction};
use stanok_syntax::SeekBufReader;
use stanok_syntax::{Block, BlockReader, OKind};
use std::io::{BufRead, Seek};
use std::path::Path;

/// A subroutine file being executed.
pub(crate) struct SubroutineFile {
    pub(crate) reader: BlockReader<SeekBufReader<std::fs::File>>,
    pub(crate) path: std::path::PathBuf,
}

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
        LogAction::Write => flow::substitute_parameters(rest, eval),
        LogAction::Close => String::new(),
        _ => rest.to_string(),
    };
    Some(Some(Canon::Log { action, text }))
}

impl<R: BufRead + Seek> Interpreter<R> {
    /// `o<name> call` of a subroutine file: open it, find its `o<name> sub` line and continue
    /// reading after it (LinuxCNC: "EOF in file … seeking o-word" if the file does not define it).
    pub(crate) fn open_subroutine_file(
        &mut self,
        path: &Path,
        label: &str,
    ) -> Result<(), Diagnostic> {
        if self.files.len() >= self.opts.max_call_depth {
            return Err(Diagnostic::error(
                "flow::call-depth",
                format!(
                    "subroutine files nested deeper than {}",
                    self.opts.max_call_depth
                ),
                self.block.span(),
            ));
        }
        let file = std::fs::File::open(path).map_err(|e| {
            Diagnostic::error(
                "io::read",
                format!("cannot open subroutine file {}: {e}", path.display()),
                self.block.span(),
            )
        })?;
        let mut reader = BlockReader::new(SeekBufReader::new(file), self.opts.dialect);
        reader.set_limits(self.opts.max_line_bytes, self.opts.max_program_bytes);
        let mut block = Block::default();
        let mut diags = Vec::new();
        loop {
            let more = reader.next_block(&mut block, &mut diags).map_err(|e| {
                Diagnostic::error(
                    "io::read",
                    format!("cannot read {}: {e}", path.display()),
                    self.block.span(),
                )
            })?;
            if !more {
                return Err(Diagnostic::error(
                    "flow::sub-not-found",
                    format!("EOF in file:{} seeking o-word: o{label}", path.display()),
                    self.block.span(),
                ));
            }
            if let Some(o) = &block.oword {
                if matches!(o.kind, OKind::Sub) && flow::label_text(&block, &o.label) == label {
                    break;
                }
            }
        }
        self.files.push(SubroutineFile {
            reader,
            path: path.to_path_buf(),
        });
        self.flow.set_source(self.files.len());
        Ok(())
    }

    /// `read` while a subroutine file is open: its end before the endsub is an error.
    #[cold]
    pub(crate) fn read_subroutine_file(&mut self) -> Result<bool, Diagnostic> {
        let Some(f) = self.files.last_mut() else {
            return Ok(false);
        };
        let more = f
            .reader
            .next_block(&mut self.block, &mut self.syntax)
            .map_err(|e| {
                Diagnostic::error(
                    "io::read",
                    format!("cannot read {}: {e}", f.path.display()),
                    stanok_canon::Span::default(),
                )
            })?;
        if !more {
            return Err(Diagnostic::error(
                "flow::sub-no-endsub",
                format!(
                    "subroutine file {} ended without its endsub",
                    f.path.display()
                ),
                self.block.span(),
            ));
        }
        self.count_line()?;
        Ok(true)
    }
}
