//! Where lines come from: the program's reader, and a stack of files a call opened on top of it
//! (RS274/NGC `o<name> call` of `name.ngc` on the subroutine path). While a file is open every line,
//! position and seek refer to it; closing it goes back to the reader below. Which file to open and
//! when is the front end's decision (its control flow); the stack only reads.
//!
//! Every reader here is bounded the same way (`CoreOptions::max_line_bytes`,
//! `max_program_bytes`): a longer line is cut with `syntax::line-too-long`, a larger program
//! stops with `syntax::program-too-large`, so `/dev/zero` ends instead of being read forever.

use crate::options::CoreOptions;
use stanok_canon::{Diagnostic, Span};
use stanok_syntax::{Block, BlockReader, Dialect, SeekBufReader, SourcePos};
use std::io::{BufRead, Seek};
use std::path::{Path, PathBuf};

/// A file opened by a call, read by a reader of its own.
pub struct OpenFile {
    /// Its reader.
    pub reader: BlockReader<SeekBufReader<std::fs::File>>,
    /// Its path (diagnostics inside it are located there).
    pub path: PathBuf,
}

/// What [`Source::read`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Read {
    /// A line, which started at this position.
    Line(SourcePos),
    /// The end of the program.
    EndOfInput,
    /// The end of a file a call opened (it is still open: the front end decides what that means).
    EndOfFile,
}

/// The program's reader and the files opened above it, innermost last.
pub struct Source<R: BufRead + Seek> {
    reader: BlockReader<R>,
    files: Vec<OpenFile>,
    dialect: Dialect,
    /// Longest line kept and most bytes read, of the program and of each file.
    max_line_bytes: usize,
    max_program_bytes: u64,
}

impl<R: BufRead + Seek> Source<R> {
    /// The program `source`, read with the line parser of `opts.dialect`, within the size
    /// bounds of `opts`.
    pub fn new(source: R, opts: &CoreOptions) -> Self {
        let mut reader = BlockReader::new(source, opts.dialect);
        reader.set_limits(opts.max_line_bytes, opts.max_program_bytes);
        Source {
            reader,
            files: Vec::new(),
            dialect: opts.dialect,
            max_line_bytes: opts.max_line_bytes,
            max_program_bytes: opts.max_program_bytes,
        }
    }

    /// Where the next line will be read (in the innermost open file, if any).
    #[inline(always)]
    pub fn position(&self) -> SourcePos {
        match self.files.last() {
            Some(f) => f.reader.position(),
            None => self.reader.position(),
        }
    }

    /// Continues reading at `pos` of the current file.
    pub fn seek(&mut self, pos: SourcePos, at: Span) -> Result<(), Diagnostic> {
        let r = match self.files.last_mut() {
            Some(f) => f.reader.seek(pos),
            None => self.reader.seek(pos),
        };
        r.map_err(|e| {
            Diagnostic::error("io::seek", format!("cannot seek in the program: {e}"), at).fatal()
        })
    }

    /// Reads the next line into `block` (its syntax diagnostics into `syntax`).
    #[inline(always)]
    pub fn read(
        &mut self,
        block: &mut Block,
        syntax: &mut Vec<Diagnostic>,
    ) -> Result<Read, Diagnostic> {
        if !self.files.is_empty() {
            return self.read_file(block, syntax);
        }
        let here = self.reader.position();
        let more = self.reader.next_block(block, syntax).map_err(|e| {
            Diagnostic::error(
                "io::read",
                format!("cannot read the program: {e}"),
                Span::default(),
            )
            .fatal()
        })?;
        Ok(if more {
            Read::Line(here)
        } else {
            Read::EndOfInput
        })
    }

    #[cold]
    fn read_file(
        &mut self,
        block: &mut Block,
        syntax: &mut Vec<Diagnostic>,
    ) -> Result<Read, Diagnostic> {
        let Some(f) = self.files.last_mut() else {
            return Ok(Read::EndOfInput);
        };
        let here = f.reader.position();
        let more = f.reader.next_block(block, syntax).map_err(|e| {
            Diagnostic::error(
                "io::read",
                format!("cannot read {}: {e}", f.path.display()),
                Span::default(),
            )
            .fatal()
        })?;
        Ok(if more {
            Read::Line(here)
        } else {
            Read::EndOfFile
        })
    }

    /// Opens `path` with the program's line parser; the caller positions it (reads it to where
    /// the call enters) and then pushes it with [`Source::push`]. `at`: the calling block.
    pub fn open(
        &self,
        path: &Path,
        at: Span,
    ) -> Result<BlockReader<SeekBufReader<std::fs::File>>, Diagnostic> {
        let file = std::fs::File::open(path).map_err(|e| {
            Diagnostic::error(
                "io::read",
                format!("cannot open subroutine file {}: {e}", path.display()),
                at,
            )
            .fatal()
        })?;
        // Seeks inside the buffer are free: a loop in a called file jumps back every pass.
        let mut reader = BlockReader::new(SeekBufReader::new(file), self.dialect);
        reader.set_limits(self.max_line_bytes, self.max_program_bytes);
        Ok(reader)
    }

    /// Makes `file` the current one: lines come from it until [`Source::pop`].
    pub fn push(&mut self, file: OpenFile) {
        self.files.push(file);
    }

    /// Closes the current file: lines come from the one below again.
    pub fn pop(&mut self) -> Option<OpenFile> {
        self.files.pop()
    }

    /// How many files are open above the program.
    pub fn depth(&self) -> usize {
        self.files.len()
    }

    /// The current file's path, None while reading the program itself.
    pub fn current_file(&self) -> Option<&Path> {
        self.files.last().map(|f| f.path.as_path())
    }
}
