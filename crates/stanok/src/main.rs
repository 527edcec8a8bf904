//! `stanok`: the command line of the Stanok CNC control kernel.
//!
//! Glue only (ripgrep's core/main.rs in spirit): it opens files, builds an interpreter and a
//! simulated machine, wires the Canon stream between them and prints what comes out. Every
//! decision about G-code lives in `stanok-interp`, every decision about the machine in
//! `stanok-machine`.
//!
//! Machine data: `--machine` names the machine, `--tools` / `--offsets` replace its tool table /
//! offsets (LinuxCNC `.tbl` / `.var`, or Stanok `.toml`), `program::load_machine` reads and checks
//! them before anything runs, and `stanok machine show` prints the result (`machine_show.rs`).
//! Programs: `program::open` reads a file or standard input (`source.rs`) and decides the dialect
//! (`dialect.rs`). Exit status: 0 ok, 1 an error in the program or a data file, 2 the command
//! line or a file could not be used (`cli.rs`).

mod canon_convert;
mod check;
mod cli;
mod cli_args;
mod cli_cutting;
mod cutting;
mod diagnostics;
mod dialect;
mod hints;
mod limits;
mod machine_list;
mod machine_show;
mod perm;
mod plot;
mod plot_colour;
mod program;
mod progress;
mod report;
mod source;
mod stock;
mod tool_axis;
mod trace;

use canon_convert::{canon, convert, plot_stock};
use clap::{CommandFactory, Parser};
use cli::{CanonFormat, Cli, ColourArgs, Command, MachineCommand};
use cli_args::{MachineArgs, MotionArgs, ProgramArgs, VarArgs};
use cli_cutting::CuttingCommand;
use dialect::Choice;
use source::Program;
use stanok_canon::linuxcnc::LinuxCncPrinter;
use stanok_canon::Diagnostic;
use stanok_interp::Interpreter;
use stanok_machine::{linuxcnc, MachineData, SimMachine, SimOptions, StoredOffsets};
use stanok_machine::{OverrideChange, OverrideKind};
use stanok_syntax::Dialect;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    diagnostics::set_colour(verb_colour(&cli.command).when.or(cli.colour.when));
    match run(cli) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// The verb's own `--color`, if it has one.
fn verb_colour(command: &Command) -> ColourArgs {
    match command {
        Command::Check { colour, .. }
        | Command::Run { colour, .. }
        | Command::Canon { colour, .. }
        | Command::Convert { colour, .. }
        | Command::Serve { colour, .. }
        | Command::Machine {
            command: MachineCommand::Show { colour, .. },
        } => *colour,
        _ => ColourArgs { when: None },
    }
}

fn run(cli: Cli) -> Result<ExitCode, String> {
    match cli.command {
        Command::Check {
            files,
            dialect,
            json,
            no_travel_check,
            machine,
            program,
            ..
        } => check::check(
            &files,
            dialect.dialect.map(Into::into),
            json,
            !no_travel_check,
            &machine,
            &program,
        ),
        Command::Run {
            file,
            dialect,
            json,
            machine,
            program,
            var,
            motion,
            stock,
            ..
        } => run_program(
            &file,
            dialect.dialect.map(Into::into),
            &machine,
            &program,
            json,
            &var,
            &motion,
            &stock,
        ),
        Command::Canon {
            file,
            dialect,
            format,
            machine,
            program,
            var,
            ..
        } => canon(
            &file,
            dialect.dialect.map(Into::into),
            format,
            &machine,
            &program,
            &var,
        ),
        Command::Plot {
            file,
            dialect,
            output,
            view,
            size,
            color,
            machine,
            program,
            stock,
        } => match stock.stock.is_some() || stock.stock_out.is_some() {
            true => plot_stock(
                &file,
                dialect.dialect.map(Into::into),
                output.as_deref(),
                &machine,
                &program,
                &stock,
            ),
            false => plot::plot(
                &file,
                dialect.dialect.map(Into::into),
                output.as_deref(),
                view,
                size,
                color,
                &machine,
                &program,
            ),
        },
        Command::Serve {
            bind,
            token,
            programs,
            upload_limit,
            time_scale,
            allowed_host,
            job_budget,
            probe_surface,
            machine,
            ..
        } => {
            if !(job_budget > 0.0 && job_budget <= 86_400.0) {
                eprintln!("error: --job-budget must be more than 0 and at most 86400 s");
                return Ok(ExitCode::from(2));
            }
            let machine = match program::load_machine(&machine, &probe_surface) {
                Ok((m, _)) => m,
                Err(code) => return Ok(code),
            };
            let mut options = stanok_serve::ServeOptions::new(machine, programs);
            options.bind = bind;
            options.token = token;
            options.upload_limit =
                usize::try_from(upload_limit.saturating_mul(1024 * 1024)).unwrap_or(usize::MAX);
            options.time_scale = time_scale;
            options.allowed_hosts = allowed_host;
            options.job_budget = std::time::Duration::from_secs_f64(job_budget);
            stanok_serve::run(options)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Machine {
            command: MachineCommand::List { json },
        } => {
            write_stdout(&if json {
                machine_list::json()
            } else {
                machine_list::text()
            })?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Machine {
            command:
                MachineCommand::Show {
                    machine,
                    json,
                    toml,
                    tbl,
                    var,
                    ..
                },
        } => {
            let format = match (json, toml, tbl, var) {
                (true, ..) => ShowFormat::Json,
                (_, true, ..) => ShowFormat::Toml,
                (_, _, true, _) => ShowFormat::Tbl,
                (.., true) => ShowFormat::Var,
                _ => ShowFormat::Text,
            };
            machine_show(&machine, format)
        }
        Command::Convert {
            file,
            dialect,
            to,
            output,
            chord_tolerance,
            machine,
            program,
            ..
        } => convert(
            &file,
            dialect.dialect.map(Into::into),
            to.into(),
            output.as_deref(),
            chord_tolerance,
            &machine,
            &program,
        ),
        Command::Cutting {
            command: CuttingCommand::Turn(args),
        } => cutting::turn(&args),
        Command::Completions { shell } => {
            let mut out = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "stanok", &mut out);
            write_stdout_bytes(&out)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Man => {
            let mut out = Vec::new();
            clap_mangen::Man::new(Cli::command())
                .render(&mut out)
                .map_err(|e| e.to_string())?;
            write_stdout_bytes(&out)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Writes to stdout; a closed pipe (`stanok … | head`) ends the program quietly instead of panicking.
fn write_stdout(text: &str) -> Result<(), String> {
    write_stdout_bytes(text.as_bytes())
}

/// [`write_stdout`] for bytes (a PNG, a man page).
fn write_stdout_bytes(bytes: &[u8]) -> Result<(), String> {
    let mut out = std::io::stdout().lock();
    match out.write_all(bytes).and_then(|_| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(e) => Err(e.to_string()),
    }
}

fn quiet_on_broken_pipe(e: std::io::Error) -> Result<ExitCode, String> {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(e.to_string())
    }
}

/// What `stanok machine show` prints.
enum ShowFormat {
    Text,
    Json,
    Toml,
    Tbl,
    Var,
}

fn machine_show(args: &MachineArgs, format: ShowFormat) -> Result<ExitCode, String> {
    let (machine, sources) = match program::load_machine(args, &[]) {
        Ok(m) => m,
        Err(code) => return Ok(code),
    };
    let units = machine.linuxcnc_units;
    let text = match format {
        ShowFormat::Text => machine_show::text(&machine, &sources),
        ShowFormat::Json => machine_show::json(&machine, &sources) + "\n",
        ShowFormat::Toml => machine.to_toml(),
        ShowFormat::Tbl => linuxcnc::write_tool_table(&machine.control.tools, units),
        ShowFormat::Var => {
            let stored = StoredOffsets {
                offsets: machine.control.offsets,
                parameters: machine.control.parameters,
            };
            linuxcnc::write_var_file(&stored, units)
        }
    };
    write_stdout(&text)?;
    Ok(ExitCode::SUCCESS)
}

/// `--var FILE`: the machine with its offsets replaced by the parameter file's, if the file exists
/// (a missing file is created after the run, from the machine's offsets). Only for RS274/NGC.
/// `--perm FILE` (AxiOMA) is read here too (`perm.rs`).
fn load_var(dialect: Dialect, var: &VarArgs, machine: &mut MachineData) -> Result<(), ExitCode> {
    perm::load(dialect, var, machine)?;
    let Some(path) = &var.var else {
        return Ok(());
    };
    if dialect != Dialect::Rs274ngc {
        return Err(program::refuse(format_args!(
            "--var {}: a LinuxCNC parameter file is for RS274/NGC programs",
            path.display()
        )));
    }
    if stanok_machine::files::DataFileKind::of(path)
        != Some(stanok_machine::files::DataFileKind::LinuxCncParameters)
    {
        return Err(program::refuse(format_args!(
            "--var {}: the file must be a LinuxCNC parameter file (.var)",
            path.display()
        )));
    }
    if path.exists() {
        let stored = stanok_machine::files::load_offset_file(path, machine.linuxcnc_units)
            .map_err(|d| {
                diagnostics::render_path(path, &d);
                program::program_error()
            })?;
        machine.control.offsets = stored.offsets;
        machine.control.parameters = stored.parameters;
    }
    Ok(())
}

/// `--var FILE` after the run: writes back what the program left, as LinuxCNC does on exit; the
/// same for `--perm FILE`.
fn save_var<R: std::io::BufRead + std::io::Seek>(
    var: &VarArgs,
    interp: &Interpreter<R>,
    units: stanok_canon::LengthUnits,
) -> Result<(), String> {
    let c = interp.control_data();
    perm::save(var, &c)?;
    let Some(path) = &var.var else {
        return Ok(());
    };
    let stored = StoredOffsets {
        offsets: c.offsets,
        parameters: c.parameters,
    };
    std::fs::write(path, linuxcnc::write_var_file(&stored, units))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// The machine, the program and its dialect for the verbs that run one; `Err` is the exit status.
fn prepare(
    file: &Path,
    dialect: Option<Dialect>,
    args: &MachineArgs,
    program_args: &ProgramArgs,
) -> Result<(MachineData, Program, Choice), ExitCode> {
    let (machine, _) = program::load_machine(args, &program_args.probe_surface)?;
    let (program, choice) = program::open(file, dialect)?;
    Ok((machine, program, choice))
}

// One argument per option group of the verb (clap's flattened structs), as the CLI declares them.
#[allow(clippy::too_many_arguments)]
fn run_program(
    file: &Path,
    dialect: Option<Dialect>,
    args: &MachineArgs,
    program_args: &ProgramArgs,
    json: bool,
    var: &VarArgs,
    motion: &MotionArgs,
    stock_args: &stock::StockArgs,
) -> Result<ExitCode, String> {
    let options = match sim_options(motion, &program_args.limits) {
        Ok(o) => o,
        Err(why) => return Ok(program::refuse(why)),
    };
    let (mut machine, program, choice) = match prepare(file, dialect, args, program_args) {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    program::say_dialect(&choice);
    let dialect = choice.dialect;
    if let Err(code) = load_var(dialect, var, &mut machine) {
        return Ok(code);
    }
    let units = machine.linuxcnc_units;
    let opts = program::options(dialect, &machine, false, program_args);
    let mut interp = match program::interpreter(&program, opts) {
        Ok(i) => i,
        Err(code) => return Ok(code),
    };
    let trace = match &motion.trace {
        Some(path) => match trace::TraceWriter::create(path, &machine) {
            Ok(t) => Some(t),
            Err(why) => return Ok(program::refuse(why)),
        },
        None => None,
    };
    let stock_sim = match stock::build(stock_args, &machine, dialect) {
        Ok(s) => s,
        Err(why) => return Ok(program::refuse(why)),
    };
    let machine_for_hints = machine.clone();
    let mut sim = SimMachine::with_options(machine, options);
    if let Some(s) = stock_sim {
        sim.set_stock(s);
    }
    let progress = progress::Progress::new(program.len());
    // A trace wants every servo period; the progress display alone does not, and then the
    // machine skips steady stretches (a long dwell, a slow straight feed) in constant time.
    if trace.is_some() {
        sim.set_setpoint_sink(trace::sink(trace.clone(), progress.clone()));
    } else {
        sim.set_progress_sink(trace::sink(None, progress.clone()));
    }
    let mut failure: Option<Diagnostic> = None;
    for item in interp.by_ref() {
        let applied = item.and_then(|cmd| {
            progress.command(cmd.span.start);
            sim.apply(&cmd)
        });
        if let Err(d) = applied {
            failure = Some(d);
            break;
        }
    }
    save_var(var, &interp, units)?;
    let mut warnings = interp.take_warnings();
    let mut rep = sim.finish();
    warnings.extend(sim.take_warnings());
    warnings.sort_by_key(|d| (d.span.line, d.span.column));
    progress.done();
    if let Some(t) = &trace {
        t.close()?;
    }
    rep.blocks = interp.stats().blocks_executed;
    stock::write_outputs(stock_args, &sim)?;
    for d in warnings.iter_mut().chain(failure.as_mut()) {
        hints::enrich(d, &machine_for_hints);
    }
    let name = program.display();
    if json {
        let mut out = report::json(&name, dialect, &rep, failure.as_ref(), &warnings);
        out.push('\n');
        write_stdout(&out)?;
    } else {
        for w in &warnings {
            diagnostics::render(&program, w);
        }
        if let Some(d) = &failure {
            diagnostics::render(&program, d);
        }
        write_stdout(&report::text(&name, dialect, &rep, failure.as_ref()))?;
        if failure.is_some() && choice.guessed {
            check::hint_after_run(&program, dialect, &machine_for_hints, program_args);
        }
    }
    Ok(if failure.is_some() {
        program::program_error()
    } else {
        ExitCode::SUCCESS
    })
}

/// `stanok run`'s motion options, checked.
fn sim_options(m: &MotionArgs, limits: &limits::LimitsArgs) -> Result<SimOptions, String> {
    if !(m.servo_period >= 0.01 && m.servo_period <= 1000.0) {
        return Err(format!(
            "--servo-period must be 0.01 … 1000 ms, not {}",
            m.servo_period
        ));
    }
    if !(m.feed_override > 0.0 && m.feed_override <= 200.0) {
        return Err(format!(
            "--feed-override must be more than 0 and at most 200 %, not {}",
            m.feed_override
        ));
    }
    if !(m.rapid_override > 0.0 && m.rapid_override <= 100.0) {
        return Err(format!(
            "--rapid-override must be more than 0 and at most 100 %, not {}",
            m.rapid_override
        ));
    }
    if m.lookahead < 2 {
        return Err("--lookahead must be at least 2 pieces".into());
    }
    let feed_hold = match &m.feed_hold {
        None => None,
        Some(text) => {
            let parsed = text.split_once(':').and_then(|(a, b)| {
                Some((a.trim().parse::<f64>().ok()?, b.trim().parse::<f64>().ok()?))
            });
            match parsed {
                Some((at, s)) if at.is_finite() && at >= 0.0 && s.is_finite() && s >= 0.0 => {
                    Some((at, s))
                }
                _ => {
                    return Err(format!(
                        "--feed-hold wants AT:SECONDS (two numbers ≥ 0), not {text}"
                    ))
                }
            }
        }
    };
    let override_changes = m
        .override_at
        .iter()
        .map(|text| parse_override_at(text))
        .collect::<Result<Vec<_>, _>>()?;
    for kind in [OverrideKind::Feed, OverrideKind::Rapid] {
        let last = override_changes
            .iter()
            .filter(|c| c.kind == kind)
            .max_by(|a, b| a.at.total_cmp(&b.at));
        if let Some(c) = last.filter(|c| c.fraction == 0.0) {
            return Err(format!(
                "--override-at: the {} override stays at 0 % from t = {} s, so the machine would \
                 stand for ever; add a later change that raises it",
                if kind == OverrideKind::Feed {
                    "feed"
                } else {
                    "rapid"
                },
                c.at
            ));
        }
    }
    Ok(SimOptions {
        servo_period_s: m.servo_period * 1e-3,
        feed_override: m.feed_override / 100.0,
        rapid_override: m.rapid_override / 100.0,
        lookahead: m.lookahead,
        feed_hold,
        profile: m.profile.map(|p| match p {
            cli_args::ProfileArg::Soft => stanok_canon::AccelerationProfile::Soft,
            cli_args::ProfileArg::Brisk => stanok_canon::AccelerationProfile::Brisk,
        }),
        override_changes,
        max_machine_time_s: limits.machine_time_s(),
    })
}

/// One `--override-at` value: `T:PERCENT` (feed), `T:rapid=PERCENT`, `T:spindle=PERCENT`.
fn parse_override_at(text: &str) -> Result<OverrideChange, String> {
    let bad = || {
        format!(
            "--override-at wants T:PERCENT, T:rapid=PERCENT or T:spindle=PERCENT (T seconds ≥ 0), \
             not {text}"
        )
    };
    let (at, rest) = text.split_once(':').ok_or_else(bad)?;
    let at: f64 = at.trim().parse().map_err(|_| bad())?;
    let (kind, value) = match rest.split_once('=') {
        None => (OverrideKind::Feed, rest),
        Some((name, value)) => match name.trim() {
            "feed" => (OverrideKind::Feed, value),
            "rapid" => (OverrideKind::Rapid, value),
            "spindle" => (OverrideKind::Spindle, value),
            _ => return Err(bad()),
        },
    };
    let percent: f64 = value
        .trim()
        .trim_end_matches('%')
        .trim()
        .parse()
        .map_err(|_| bad())?;
    let (lo, hi) = match kind {
        OverrideKind::Feed => (0.0, 200.0),
        OverrideKind::Rapid => (0.0, 100.0),
        OverrideKind::Spindle => (50.0, 120.0),
    };
    if !(at.is_finite() && at >= 0.0) {
        return Err(bad());
    }
    if !(percent >= lo && percent <= hi) {
        return Err(format!(
            "--override-at {text}: the percentage must be {lo} … {hi} for this override"
        ));
    }
    Ok(OverrideChange {
        at,
        kind,
        fraction: percent / 100.0,
    })
}
