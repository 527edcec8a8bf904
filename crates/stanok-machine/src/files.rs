//! Tool and offset files given on the command line (`--tools FILE`, `--offsets FILE`), read by
//! their extension:
//!
//! | extension | `--tools` | `--offsets` |
//! |---|---|---|
//! | `.tbl` | LinuxCNC tool table ([`crate::linuxcnc::parse_tool_table`]) | — |
//! | `.var` | — | LinuxCNC parameter file ([`crate::linuxcnc::parse_var_file`]) |
//! | `.toml` | `[[tool]]` sections only ([`crate::tools_from_toml_str`]) | offset sections only ([`crate::offsets_from_toml_str`]) |
//!
//! `units` is the length unit of the LinuxCNC files (the machine's `linuxcnc_units`); TOML is mm.

use crate::data::read_text;
use crate::BAD_DATA;
use crate::{linuxcnc, offsets_from_toml_str, tools_from_toml_str, StoredOffsets};
use stanok_canon::setup::ToolTable;
use stanok_canon::{Diagnostic, LengthUnits, Span};
use std::path::Path;

/// The kinds of data file, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataFileKind {
    /// `.tbl`: LinuxCNC tool table.
    LinuxCncToolTable,
    /// `.var`: LinuxCNC parameter file.
    LinuxCncParameters,
    /// `.toml`: Stanok machine data (a fragment).
    Toml,
}

impl DataFileKind {
    /// The kind of `path` by its extension (case-insensitive), if known.
    pub fn of(path: &Path) -> Option<DataFileKind> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "tbl" => Some(DataFileKind::LinuxCncToolTable),
            "var" => Some(DataFileKind::LinuxCncParameters),
            "toml" => Some(DataFileKind::Toml),
            _ => None,
        }
    }

    /// A name for people.
    pub fn describe(self) -> &'static str {
        match self {
            DataFileKind::LinuxCncToolTable => "LinuxCNC tool table",
            DataFileKind::LinuxCncParameters => "LinuxCNC parameter file",
            DataFileKind::Toml => "Stanok machine data",
        }
    }
}

fn refuse(path: &Path, message: String) -> Diagnostic {
    Diagnostic::error(BAD_DATA, message, Span::default())
        .with_note(format!("in {}", path.display()))
}

/// Reads a tool file (`.tbl` or `.toml`).
pub fn load_tool_file(path: &Path, units: LengthUnits) -> Result<ToolTable, Diagnostic> {
    let name = path.display().to_string();
    match DataFileKind::of(path) {
        Some(DataFileKind::LinuxCncToolTable) => {
            let text = read_text(path, "tool table")?;
            linuxcnc::parse_tool_table(&text, &name, units)
        }
        Some(DataFileKind::Toml) => tools_from_toml_str(&read_text(path, "tool file")?, &name),
        Some(DataFileKind::LinuxCncParameters) => Err(refuse(
            path,
            "a .var file holds offsets, not tools: give it to --offsets".into(),
        )),
        None => Err(refuse(
            path,
            "a tool file is a LinuxCNC tool table (.tbl) or Stanok machine data (.toml)".into(),
        )),
    }
}

/// Reads an offset file (`.var` or `.toml`).
pub fn load_offset_file(path: &Path, units: LengthUnits) -> Result<StoredOffsets, Diagnostic> {
    let name = path.display().to_string();
    match DataFileKind::of(path) {
        Some(DataFileKind::LinuxCncParameters) => {
            let text = read_text(path, "parameter file")?;
            linuxcnc::parse_var_file(&text, &name, units)
        }
        Some(DataFileKind::Toml) => offsets_from_toml_str(&read_text(path, "offset file")?, &name),
        Some(DataFileKind::LinuxCncToolTable) => Err(refuse(
            path,
            "a .tbl file holds tools, not offsets: give it to --tools".into(),
        )),
        None => Err(refuse(
            path,
            "an offset file is a LinuxCNC parameter file (.var) or Stanok machine data (.toml)"
                .into(),
        )),
    }
}
