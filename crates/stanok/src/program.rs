//! Loading what a verb works on: the machine (`--machine`, `--tools`, `--offsets`), the program and
//! its dialect, and the interpreter built from them.
//!
//! Failures here are reported once, where they happen, and turned into the exit status: a
//! machine-data file with an error is 1 (its diagnostic has file:line:column), a name that is
//! neither a built-in machine nor a file, or a program that cannot be opened, is 2.

use crate::cli_args::{MachineArgs, ProgramArgs};
use crate::diagnostics;
use crate::dialect::{self, Choice};
use crate::machine_show::{DataSource, Sources};
use crate::source::{Program, ProgramReader};
use stanok_canon::setup::ProbeSurface;
use stanok_canon::Diagnostic;
use stanok_interp::{InterpOptions, Interpreter};
use stanok_machine::files::{load_offset_file, load_tool_file, DataFileKind};
use stanok_machine::{MachineData, BUILTIN_MACHINES};
use stanok_syntax::Dialect;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit status 1: the program or a data file has an error.
pub fn program_error() -> ExitCode {
    ExitCode::from(1)
}

/// Exit status 2: the command line or a file could not be used.
pub fn usage_error() -> ExitCode {
    ExitCode::from(2)
}

/// Prints `error: …` and gives exit status 2.
pub fn refuse(message: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {message}");
    usage_error()
}

/// The machine named by `--machine`, with its tools and offsets replaced by `--tools` and
/// `--offsets` and its probe surfaces by `probe`, and where each part came from.
pub fn load_machine(
    args: &MachineArgs,
    probe: &[ProbeSurface],
) -> Result<(MachineData, Sources), ExitCode> {
    let fail = |path: &Path, d: &Diagnostic| {
        diagnostics::render_path(path, d);
        program_error()
    };
    let mut machine = match MachineData::builtin(&args.machine) {
        Some(m) => m,
        None => {
            let path = PathBuf::from(&args.machine);
            if !path.exists() {
                return Err(refuse(format_args!(
                    "no built-in machine `{}` and no machine-data file of that name\n  \
                     built-in machines: {} (`stanok machine list` describes them)",
                    args.machine,
                    BUILTIN_MACHINES.join(", ")
                )));
            }
            if path.is_dir() {
                return Err(refuse(format_args!(
                    "--machine {}: a directory, not a machine-data file",
                    path.display()
                )));
            }
            MachineData::load(&path).map_err(|d| fail(&path, &d))?
        }
    };
    if let Some(u) = args.linuxcnc_units {
        machine.linuxcnc_units = u.into();
    }
    if !probe.is_empty() {
        machine.control.probe_surfaces = probe.to_vec();
    }
    let units = machine.linuxcnc_units;
    let mut sources = Sources::machine(&machine.name);
    for (path, what) in [(&args.tools, "--tools"), (&args.offsets, "--offsets")] {
        if let Some(p) = path {
            if !p.is_file() {
                return Err(refuse(format_args!("{what} {}: no such file", p.display())));
            }
        }
    }
    if let Some(path) = &args.tools {
        machine.control.tools = load_tool_file(path, units).map_err(|d| fail(path, &d))?;
        sources.tools = DataSource::file(path, DataFileKind::of(path), units);
    }
    if let Some(path) = &args.offsets {
        let stored = load_offset_file(path, units).map_err(|d| fail(path, &d))?;
        machine.control.offsets = stored.offsets;
        machine.control.parameters = stored.parameters;
        sources.offsets = DataSource::file(path, DataFileKind::of(path), units);
    }
    Ok((machine, sources))
}

/// The program named on the command line and its dialect.
pub fn open(file: &Path, given: Option<Dialect>) -> Result<(Program, Choice), ExitCode> {
    let program = Program::open(file).map_err(refuse)?;
    let choice = dialect::choose(given, &program);
    Ok((program, choice))
}

/// Prints which dialect a program is read in, and why (stderr, one line).
pub fn say_dialect(choice: &Choice) {
    eprintln!("dialect: {} ({})", choice.dialect.id(), choice.reason);
}

/// The interpreter's options for `machine` and the program options.
pub fn options(
    dialect: Dialect,
    machine: &MachineData,
    check_mode: bool,
    args: &ProgramArgs,
) -> InterpOptions {
    let mut opts = InterpOptions::new(dialect);
    opts.axes = machine.axis_mask();
    opts.arc_tolerance_mm = machine.arc_tolerance;
    opts.continue_after_error = check_mode;
    opts.control = machine.control.clone();
    opts.diameter_axes = machine.diameter_axes();
    opts.rs274_machine_units = machine.linuxcnc_units;
    opts.rs274_linuxcnc_arc_tolerance = machine.rs274_linuxcnc_arc_tolerance;
    if let Some(table) = stanok_interp::MTable::profile(&machine.m_functions) {
        opts.axioma.m_table = table;
    }
    opts.axioma
        .set_table_entries(&machine.feed_table, &machine.speed_table);
    let ch = &machine.channel;
    opts.axioma.set_channel(
        Some(machine.max_feed),
        ch.spindle_encoder,
        ch.plc_outputs,
        ch.compensation_depth,
        &ch.edge_positions,
    );
    opts.subroutine_path = args.subroutine_path.clone();
    opts.optional_stop = !args.skip_optional_stops;
    if let Some(n) = args.max_loop_iterations {
        opts.max_loop_iterations = n;
    }
    args.limits.apply(&mut opts);
    opts.strip_fixture_comments = args.strip_fixture_comments;
    opts.labs.correctors.extend(args.corrector.iter().copied());
    // Tool-centre-point control needs the machine's kinematics, and the machine's permission.
    opts.five_axis = machine.tcp_kinematics();
    opts.ttpc_workpiece_frame = machine.ttpc_workpiece_frame();
    // The Mazatrol control's parameters (series, decimal point type, …: `[mazatrol]`).
    opts.mazatrol = stanok_serve::machine::mazatrol_params(machine);
    opts
}

/// An interpreter over the program from its start.
pub fn interpreter(
    program: &Program,
    opts: InterpOptions,
) -> Result<Interpreter<ProgramReader>, ExitCode> {
    let reader = program.reader().map_err(refuse)?;
    Ok(Interpreter::new(reader, opts))
}
