//! `--perm FILE`: AxiOMA's permanent parameters `$iPerm[n]` / `$dPerm[n]` kept from run to run, as
//! the control keeps them in its non-volatile memory. The file is machine-data TOML holding only
//! `[iperm]` and `[dperm]`: read before the run in place of the machine's (if it exists), written
//! back after it with what the program left (also after an error: the failing line's own writes
//! are already undone by the interpreter, so the file holds the state before that line).

use crate::cli_args::VarArgs;
use crate::{diagnostics, program};
use stanok_canon::setup::ControlData;
use stanok_machine::{perm_from_toml_str, perm_to_toml, MachineData};
use stanok_syntax::Dialect;
use std::process::ExitCode;

/// Before the run: the file's parameters replace the machine's. Only for AxiOMA programs.
pub fn load(dialect: Dialect, args: &VarArgs, machine: &mut MachineData) -> Result<(), ExitCode> {
    let Some(path) = &args.perm else {
        return Ok(());
    };
    if dialect != Dialect::Axioma {
        return Err(program::refuse(format_args!(
            "--perm {}: $iPerm/$dPerm are AxiOMA's permanent parameters",
            path.display()
        )));
    }
    if !path.exists() {
        return Ok(());
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| program::refuse(format_args!("cannot read {}: {e}", path.display())))?;
    let (int, double) = perm_from_toml_str(&text, &path.display().to_string()).map_err(|d| {
        diagnostics::render_path(path, &d);
        program::program_error()
    })?;
    machine.control.perm_int = int;
    machine.control.perm_double = double;
    Ok(())
}

/// After the run: writes the parameters the program left.
pub fn save(args: &VarArgs, control: &ControlData) -> Result<(), String> {
    let Some(path) = &args.perm else {
        return Ok(());
    };
    std::fs::write(path, perm_to_toml(control))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}
