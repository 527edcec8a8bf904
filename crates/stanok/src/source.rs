//! Where a program comes from: a file, or standard input (`-`).
//!
//! A file is read as a stream (the interpreter seeks in it for loops and calls); standard input
//! cannot seek, so it is read into memory first, at most [`MAX_STDIN`] bytes. Opening checks what
//! the path is, so that a missing file, a directory or an unreadable file are all the same kind of
//! failure (exit status 2), before any program text is read.

use std::fs::File;
use std::io::{BufRead, BufReader, Cursor, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Most bytes read from standard input.
pub const MAX_STDIN: u64 = 256 * 1024 * 1024;

/// A program to read.
#[derive(Debug, Clone)]
pub struct Program {
    /// The file, or None for standard input.
    pub path: Option<PathBuf>,
    /// The text of standard input.
    memory: Option<Arc<Vec<u8>>>,
}

impl Program {
    /// Opens the program named on the command line (`-` = standard input). The error is for the
    /// user, e.g. `cannot open x.nc: No such file or directory`.
    pub fn open(arg: &Path) -> Result<Program, String> {
        if arg.as_os_str() == "-" {
            let mut data = Vec::new();
            std::io::stdin()
                .lock()
                .take(MAX_STDIN + 1)
                .read_to_end(&mut data)
                .map_err(|e| format!("cannot read standard input: {e}"))?;
            if data.len() as u64 > MAX_STDIN {
                return Err(format!(
                    "standard input holds more than {} MiB: give the program as a file",
                    MAX_STDIN >> 20
                ));
            }
            return Ok(Program {
                path: None,
                memory: Some(Arc::new(data)),
            });
        }
        let meta = std::fs::metadata(arg)
            .map_err(|e| format!("cannot open {}: {}", arg.display(), plain(&e)))?;
        if meta.is_dir() {
            return Err(format!(
                "{} is a directory, not a program file",
                arg.display()
            ));
        }
        File::open(arg).map_err(|e| format!("cannot open {}: {}", arg.display(), plain(&e)))?;
        Ok(Program {
            path: Some(arg.to_path_buf()),
            memory: None,
        })
    }

    /// The program as text, e.g. for tests (`name` is what messages call it).
    #[cfg(test)]
    pub fn from_text(text: &str) -> Program {
        Program {
            path: None,
            memory: Some(Arc::new(text.as_bytes().to_vec())),
        }
    }

    /// How messages name it: the path as given, or `<stdin>`.
    pub fn display(&self) -> String {
        match &self.path {
            Some(p) => p.display().to_string(),
            None => "<stdin>".into(),
        }
    }

    /// The file name alone (`demo.nc`), for titles and default output names.
    pub fn file_name(&self) -> Option<String> {
        self.path
            .as_ref()
            .and_then(|p| p.file_name())
            .map(|n| n.to_string_lossy().into_owned())
    }

    /// A fresh reader from the start.
    pub fn reader(&self) -> Result<ProgramReader, String> {
        match (&self.memory, &self.path) {
            (Some(m), _) => Ok(ProgramReader::Memory(Cursor::new(SharedBytes(m.clone())))),
            (None, Some(p)) => File::open(p)
                .map(|f| ProgramReader::File(BufReader::new(f)))
                .map_err(|e| format!("cannot open {}: {}", p.display(), plain(&e))),
            (None, None) => Err("no program".into()),
        }
    }

    /// The first `limit` bytes (for recognising the dialect).
    pub fn head(&self, limit: usize) -> Vec<u8> {
        match (&self.memory, &self.path) {
            (Some(m), _) => m[..m.len().min(limit)].to_vec(),
            (None, Some(p)) => {
                let mut buf = Vec::new();
                if let Ok(f) = File::open(p) {
                    let _ = f.take(limit as u64).read_to_end(&mut buf);
                }
                buf
            }
            (None, None) => Vec::new(),
        }
    }

    /// The whole text for showing source lines in diagnostics, if it is not too large.
    pub fn snippet_text(&self, limit: u64) -> Option<String> {
        match (&self.memory, &self.path) {
            (Some(m), _) => {
                (m.len() as u64 <= limit).then(|| String::from_utf8_lossy(m).into_owned())
            }
            (None, Some(p)) => read_limited(p, limit),
            (None, None) => None,
        }
    }

    /// Size in bytes, if known.
    pub fn len(&self) -> u64 {
        match (&self.memory, &self.path) {
            (Some(m), _) => m.len() as u64,
            (None, Some(p)) => std::fs::metadata(p).map(|m| m.len()).unwrap_or(0),
            (None, None) => 0,
        }
    }
}

/// A file's text when it is at most `limit` bytes.
pub fn read_limited(path: &Path, limit: u64) -> Option<String> {
    std::fs::metadata(path)
        .ok()
        .filter(|m| m.is_file() && m.len() <= limit)
        .and_then(|_| std::fs::read(path).ok())
        .map(|b| String::from_utf8_lossy(&b).into_owned())
}

/// An I/O error without Rust's ` (os error 2)` tail.
pub fn plain(e: &std::io::Error) -> String {
    let s = e.to_string();
    match s.find(" (os error") {
        Some(i) => s[..i].to_string(),
        None => s,
    }
}

/// The bytes of standard input, shared by the readers of one run (a plot reads twice).
#[derive(Debug, Clone)]
pub struct SharedBytes(Arc<Vec<u8>>);

impl AsRef<[u8]> for SharedBytes {
    fn as_ref(&self) -> &[u8] {
        &self.0
    }
}

/// A program being read: a buffered file or bytes in memory.
#[derive(Debug)]
pub enum ProgramReader {
    /// A file.
    File(BufReader<File>),
    /// Standard input, read before.
    Memory(Cursor<SharedBytes>),
}

impl Read for ProgramReader {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        match self {
            ProgramReader::File(r) => r.read(buf),
            ProgramReader::Memory(r) => r.read(buf),
        }
    }
}

impl BufRead for ProgramReader {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        match self {
            ProgramReader::File(r) => r.fill_buf(),
            ProgramReader::Memory(r) => r.fill_buf(),
        }
    }

    fn consume(&mut self, amt: usize) {
        match self {
            ProgramReader::File(r) => r.consume(amt),
            ProgramReader::Memory(r) => r.consume(amt),
        }
    }
}

impl Seek for ProgramReader {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        match self {
            ProgramReader::File(r) => r.seek(pos),
            ProgramReader::Memory(r) => r.seek(pos),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_directory_and_a_missing_file_are_refused_alike() {
        let dir = std::env::temp_dir();
        let e = Program::open(&dir).unwrap_err();
        assert!(e.contains("is a directory"), "{e}");
        let e = Program::open(Path::new("/nonexistent/x.nc")).unwrap_err();
        assert_eq!(
            e,
            "cannot open /nonexistent/x.nc: No such file or directory"
        );
    }

    #[test]
    fn memory_reads_and_seeks() {
        let p = Program::from_text("G0 X1\nM2\n");
        let mut r = p.reader().unwrap();
        let mut line = String::new();
        r.read_line(&mut line).unwrap();
        assert_eq!(line, "G0 X1\n");
        r.seek(SeekFrom::Start(0)).unwrap();
        line.clear();
        r.read_line(&mut line).unwrap();
        assert_eq!(line, "G0 X1\n");
        assert_eq!(p.head(3), b"G0 ");
        assert_eq!(p.display(), "<stdin>");
    }
}
