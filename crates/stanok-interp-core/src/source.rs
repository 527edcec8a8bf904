//! Where lines come from: the program's reader, and a stack of files a call opened on top of it
//! (RS274/NGC `o<name> call` of `name.ngc` on the subroutine path). While a file is open every line,
//! position and seek refer to it; closing it goes back to the reader below. Which file to open and
//! when is the front end's decision (its control flow); the stack only reads.

use stanok_canon::{Diagnostic, Span};
use stanok_syntax::{Block, BlockReader, Dialect, SourcePos};
use std::io::{BufRead, BufReader, Seek};
use std::path::{Path, PathBuf};

/// A file opened by a call, read by a reader of its own.
pub struct OpenFile {
    /// Its reader.
    pub reader: BlockReader<BufReader<std::fs::File>>,
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
}

impl<R: BufRead + Seek> Source<R> {
    /// The program `source`, read with the line parser of `dialect`.
    pub fn new(source: R, dialect: Dialect) -> Self {
        Source {
            reader: BlockReader::new(source, dialect),
            files: Vec::new(),
            dialect,
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
        r.map_err(|e| Diagnostic::error("io::seek", format!("cannot seek in the program: {e}"), at))
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
    ) -> Result<BlockReader<BufReader<std::fs::File>>, Diagnostic> {
        let file = std::fs::File::open(path).map_err(|e| {
            Diagnostic::error(
                "io::read",
                format!("cannot open subroutine file {}: {e}", path.display()),
                at,
            )
        })?;
        Ok(BlockReader::new(BufReader::new(file), self.dialect))
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
