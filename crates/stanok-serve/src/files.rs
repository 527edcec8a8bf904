//! The program directory: the only part of the file system the panel reads or writes.
//!
//! A program is named by a plain file name: letters, digits, `.`, `_`, `-`, not starting with a
//! dot, at most 128 bytes, with a program extension ([`PROGRAM_EXTENSIONS`]). Anything else —
//! separators, `..`, absolute paths, NUL, drive letters, hidden files — is refused before the file
//! system is touched, and a name that resolves (through a symbolic link) outside the directory is
//! refused after. So no request can read or write a file outside `--programs`, nor a non-program
//! file inside it.

use std::path::{Path, PathBuf};

/// File extensions the panel reads and writes (case-insensitive).
pub const PROGRAM_EXTENSIONS: [&str; 9] = [
    "nc", "ngc", "txt", "mpf", "spf", "cnc", "tap", "iso", "gcode",
];

/// Why a name or a file was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FileError {
    /// The name breaks the rules of the module doc.
    BadName(String),
    /// No such program.
    NotFound(String),
    /// The file system refused.
    Io(String),
}

impl std::fmt::Display for FileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FileError::BadName(n) => write!(
                f,
                "{n:?} is not a program name (a plain file name with a program extension)"
            ),
            FileError::NotFound(n) => write!(f, "no program {n:?}"),
            FileError::Io(e) => write!(f, "{e}"),
        }
    }
}

/// The program directory (module doc).
#[derive(Debug, Clone)]
pub struct ProgramDir {
    root: PathBuf,
}

/// True if `name` follows the rules of the module doc.
pub fn valid_name(name: &str) -> bool {
    let ext_ok = name
        .rsplit_once('.')
        .map(|(_, e)| PROGRAM_EXTENSIONS.iter().any(|x| x.eq_ignore_ascii_case(e)))
        .unwrap_or(false);
    !name.is_empty()
        && name.len() <= 128
        && !name.starts_with('.')
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'.' | b'_' | b'-'))
        && ext_ok
}

impl ProgramDir {
    /// The directory `root`, which must exist.
    pub fn new(root: &Path) -> Result<Self, String> {
        let root = root
            .canonicalize()
            .map_err(|e| format!("program directory {}: {e}", root.display()))?;
        if !root.is_dir() {
            return Err(format!("{} is not a directory", root.display()));
        }
        Ok(ProgramDir { root })
    }

    /// The directory.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The path of program `name`, refused unless it is inside the directory (module doc).
    pub fn resolve(&self, name: &str) -> Result<PathBuf, FileError> {
        if !valid_name(name) {
            return Err(FileError::BadName(name.into()));
        }
        let path = self.root.join(name);
        // symlink_metadata: a dangling link exists too (writing through it would leave the directory).
        if path.symlink_metadata().is_ok() {
            let real = path
                .canonicalize()
                .map_err(|_| FileError::BadName(name.into()))?;
            if !real.starts_with(&self.root) {
                return Err(FileError::BadName(name.into()));
            }
        }
        Ok(path)
    }

    /// Program names in the directory, sorted.
    pub fn list(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.root)
            .map(|rd| {
                rd.flatten()
                    .filter(|e| e.file_type().map(|t| t.is_file()).unwrap_or(false))
                    .filter_map(|e| e.file_name().into_string().ok())
                    .filter(|n| valid_name(n))
                    .collect()
            })
            .unwrap_or_default();
        names.sort();
        names
    }

    /// The text of program `name`.
    pub fn read(&self, name: &str) -> Result<String, FileError> {
        let path = self.resolve(name)?;
        if !path.is_file() {
            return Err(FileError::NotFound(name.into()));
        }
        let bytes = std::fs::read(&path).map_err(|e| FileError::Io(e.to_string()))?;
        Ok(String::from_utf8_lossy(&bytes).into_owned())
    }

    /// Writes program `name`.
    pub fn write(&self, name: &str, text: &str) -> Result<(), FileError> {
        let path = self.resolve(name)?;
        std::fs::write(&path, text).map_err(|e| FileError::Io(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::valid_name;

    #[test]
    fn only_plain_program_file_names_are_valid() {
        for ok in ["part.nc", "A-1_b.NGC", "x.gcode", "plate.v2.nc"] {
            assert!(valid_name(ok), "{ok}");
        }
        for bad in [
            "",
            ".nc",
            ".hidden.nc",
            "../x.nc",
            "a/b.nc",
            "a\\b.nc",
            "/etc/passwd",
            "C:x.nc",
            "x.sh",
            "noext",
            "a b.nc",
            "x.nc\0",
            "..",
        ] {
            assert!(!valid_name(bad), "{bad:?}");
        }
        assert!(!valid_name(&format!("{}.nc", "a".repeat(130))));
    }
}
