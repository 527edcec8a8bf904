//! The stored-data files beside the machine file: tools (`--tools`), offsets (`--offsets`) and
//! AxiOMA's permanent parameters (`--perm`), each a fragment of the machine-data TOML that may hold
//! only its own sections.

use super::{bad_data, data_note, Fragment, RawFile};
use serde::Serialize;
use stanok_canon::setup::{OffsetTables, ToolTable};
use stanok_canon::Diagnostic;
use std::collections::BTreeMap;

/// Reads a tool file in machine-data TOML: only `[[tool]]` sections. `file_name` is only used in
/// the diagnostic's note.
pub fn tools_from_toml_str(text: &str, file_name: &str) -> Result<ToolTable, Diagnostic> {
    let raw = RawFile::parse(text, file_name)?;
    raw.check_fragment(Fragment::Tools)
        .and_then(|()| raw.control().validate())
        .map(|c| c.tools)
        .map_err(|(message, range)| bad_data(text, &data_note(file_name), &message, Some(range)))
}

/// Offset tables and the other numbered parameters: what `--offsets` replaces.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct StoredOffsets {
    /// Zero offsets, workpiece frames, home and stored positions.
    pub offsets: OffsetTables,
    /// Other numbered parameters to preset (see `ControlData::parameters`).
    pub parameters: BTreeMap<u32, f64>,
}

/// Reads an offset file in machine-data TOML: only `active_system`, `[[zero_offset]]`,
/// `[[workpiece]]`, `[[home]]`, `[g28]`, `[g30]`, `[g92]` and `[parameters]`.
pub fn offsets_from_toml_str(text: &str, file_name: &str) -> Result<StoredOffsets, Diagnostic> {
    let raw = RawFile::parse(text, file_name)?;
    raw.check_fragment(Fragment::Offsets)
        .and_then(|()| raw.control().validate())
        .map(|c| StoredOffsets {
            offsets: c.offsets,
            parameters: c.parameters,
        })
        .map_err(|(message, range)| bad_data(text, &data_note(file_name), &message, Some(range)))
}

/// AxiOMA's permanent parameters `$iPerm[n]` / `$dPerm[n]`, as kept between runs.
pub type PermParameters = (BTreeMap<u32, i64>, BTreeMap<u32, f64>);

/// Reads a permanent-parameter file in machine-data TOML: only `[iperm]` and `[dperm]`.
pub fn perm_from_toml_str(text: &str, file_name: &str) -> Result<PermParameters, Diagnostic> {
    let raw = RawFile::parse(text, file_name)?;
    raw.check_fragment(Fragment::Perm)
        .and_then(|()| raw.control().validate())
        .map(|c| (c.perm_int, c.perm_double))
        .map_err(|(message, range)| bad_data(text, &data_note(file_name), &message, Some(range)))
}
