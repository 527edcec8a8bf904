//! `stanok`: the command line of the Stanok CNC control kernel.
//!
//! Glue only (ripgrep's core/main.rs in spirit): it opens files, builds an interpreter and a
//! simulated machine, wires the Canon stream between them and prints what comes out. Every
//! decision about G-code lives in `stanok-interp`, every decision about the machine in
//! `stanok-machine`.
//!
//! Machine data: `--machine` names the machine, `--tools` / `--offsets` replace its tool table /
//! offsets (LinuxCNC `.tbl` / `.var`, or Stanok `.toml`), `load_machine` reads and checks them
//! before anything runs, `control_data` is what the interpreter receives, and `stanok machine show`
//! prints the result (`machine_show.rs`).

mod cli;
mod cutting;
mod diagnostics;
mod machine_show;
mod perm;
mod progress;
mod report;
mod stock;
mod tool_axis;
mod trace;

use clap::Parser;
use cli::{
    CanonFormat, Cli, Command, CuttingCommand, MachineArgs, MachineCommand, MotionArgs, VarArgs,
};
use machine_show::{DataSource, Sources};
use stanok_canon::setup::ControlData;
use stanok_canon::{linuxcnc::LinuxCncPrinter, Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_machine::files::{load_offset_file, load_tool_file, DataFileKind};
use stanok_machine::{linuxcnc, MachineData, SimMachine, SimOptions, StoredOffsets};
use stanok_machine::{OverrideChange, OverrideKind};
use stanok_syntax::Dialect;
use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode, String> {
    match cli.command {
        Command::Check {
            file,
            dialect,
            machine,
        } => check(&file, dialect.map(Into::into), &machine),
        Command::Run {
            file,
            dialect,
            machine,
            json,
            var,
            motion,
            stock,
        } => run_program(
            &file,
            dialect.map(Into::into),
            &machine,
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
            var,
        } => canon(&file, dialect.map(Into::into), format, &machine, &var),
        Command::Plot {
            file,
            dialect,
            output,
            machine,
            stock,
        } => match stock.stock.is_some() || stock.stock_out.is_some() {
            true => plot_stock(&file, dialect.map(Into::into), &output, &machine, &stock),
            false => plot(&file, dialect.map(Into::into), &output, &machine),
        },
        Command::Serve {
            bind,
            token,
            programs,
            upload_limit,
            time_scale,
            machine,
        } => {
            let machine = match load_machine(&machine) {
                Ok((m, _)) => m,
                Err(code) => return Ok(code),
            };
            let mut options = stanok_serve::ServeOptions::new(machine, programs);
            options.bind = bind;
            options.token = token;
            options.upload_limit =
                usize::try_from(upload_limit.saturating_mul(1024 * 1024)).unwrap_or(usize::MAX);
            options.time_scale = time_scale;
            stanok_serve::run(options)?;
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
        } => convert(
            &file,
            dialect.map(Into::into),
            to.into(),
            output.as_deref(),
            chord_tolerance,
            &machine,
        ),
        Command::Cutting {
            command: CuttingCommand::Turn(args),
        } => cutting::turn(&args),
    }
}

/// Writes to stdout; a closed pipe (`stanok … | head`) ends the program quietly instead of panicking.
fn write_stdout(text: &str) -> Result<(), String> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
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

/// The stored data the interpreter reads (tool table, offset tables, preset parameters): the
/// machine's own, or what `--tools` / `--offsets` replaced it with.
fn control_data(machine: &MachineData) -> ControlData {
    machine.control.clone()
}

/// Opens a program and builds its interpreter.
fn interpreter(
    file: &Path,
    dialect: Option<Dialect>,
    machine: &MachineData,
    check_mode: bool,
    args: &MachineArgs,
) -> Result<(Interpreter<BufReader<File>>, Dialect), String> {
    let dialect = dialect.unwrap_or_else(|| Dialect::from_path(file));
    let f = File::open(file).map_err(|e| format!("cannot open {}: {e}", file.display()))?;
    let mut opts = InterpOptions::new(dialect);
    opts.axes = machine.axis_mask();
    opts.arc_tolerance_mm = machine.arc_tolerance;
    opts.continue_after_error = check_mode;
    opts.control = control_data(machine);
    opts.diameter_axes = machine.diameter_axes();
    opts.rs274_machine_units = machine.linuxcnc_units;
    if let Some(table) = stanok_interp::MTable::profile(&machine.m_functions) {
        opts.axioma.m_table = table;
    }
    opts.axioma
        .set_table_entries(&machine.feed_table, &machine.speed_table);
    opts.subroutine_path = args.subroutine_path.clone();
    opts.optional_stop = !args.skip_optional_stops;
    if let Some(n) = args.max_loop_iterations {
        opts.max_loop_iterations = n;
    }
    opts.strip_fixture_comments = args.strip_fixture_comments;
    opts.labs.correctors.extend(args.corrector.iter().copied());
    // Tool-centre-point control needs the machine's kinematics, and the machine's permission.
    opts.five_axis = machine.tcp_kinematics();
    opts.ttpc_workpiece_frame = machine.ttpc_workpiece_frame();
    Ok((Interpreter::new(BufReader::new(f), opts), dialect))
}

/// The machine named by `--machine`, with its tools and offsets replaced by `--tools` and
/// `--offsets`, and where each part came from. A bad file is reported (file:line:column) and gives
/// exit status 1.
fn load_machine(args: &MachineArgs) -> Result<(MachineData, Sources), ExitCode> {
    let fail = |path: &Path, d: &Diagnostic| {
        diagnostics::render(path, d);
        ExitCode::from(1)
    };
    let mut machine = match MachineData::builtin(&args.machine) {
        Some(m) => m,
        None => {
            let path = PathBuf::from(&args.machine);
            MachineData::load(&path).map_err(|d| fail(&path, &d))?
        }
    };
    if let Some(u) = args.linuxcnc_units {
        machine.linuxcnc_units = u.into();
    }
    if !args.probe_surface.is_empty() {
        machine.control.probe_surfaces = args.probe_surface.clone();
    }
    let units = machine.linuxcnc_units;
    let mut sources = Sources::machine(&machine.name);
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

/// What `stanok machine show` prints.
enum ShowFormat {
    Text,
    Json,
    Toml,
    Tbl,
    Var,
}

fn machine_show(args: &MachineArgs, format: ShowFormat) -> Result<ExitCode, String> {
    let (machine, sources) = match load_machine(args) {
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

fn check(file: &Path, dialect: Option<Dialect>, args: &MachineArgs) -> Result<ExitCode, String> {
    let machine = match load_machine(args) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    let (mut interp, _) = interpreter(file, dialect, &machine, true, args)?;
    let mut errors = Vec::new();
    // A bad block inside a loop fails on every pass (AxiOMA `for`, RS274/NGC `o… while`): each
    // error is listed once.
    let mut seen = std::collections::HashSet::new();
    for item in interp.by_ref() {
        if let Err(d) = item {
            if seen.insert((
                d.code.to_string(),
                d.span.start,
                d.span.end,
                d.message.clone(),
            )) {
                errors.push(d);
            }
        }
    }
    let mut all: Vec<Diagnostic> = interp.take_warnings();
    all.extend(errors.iter().cloned());
    all.sort_by_key(|d| (d.span.line, d.span.column));
    for d in &all {
        diagnostics::render(file, d);
    }
    let warnings = all.len() - errors.len();
    if errors.is_empty() {
        eprintln!("{}: ok ({warnings} warning(s))", file.display());
        Ok(ExitCode::SUCCESS)
    } else {
        eprintln!(
            "{}: {} error(s), {warnings} warning(s)",
            file.display(),
            errors.len()
        );
        Ok(ExitCode::from(1))
    }
}

/// `--var FILE`: the machine with its offsets replaced by the parameter file's, if the file exists
/// (a missing file is created after the run, from the machine's offsets). Only for RS274/NGC.
/// `--perm FILE` (AxiOMA) is read here too (`perm.rs`).
fn load_var(
    file: &Path,
    dialect: Option<Dialect>,
    var: &VarArgs,
    machine: &mut MachineData,
) -> Result<(), ExitCode> {
    perm::load(file, dialect, var, machine)?;
    let Some(path) = &var.var else {
        return Ok(());
    };
    let refuse = |why: &str| {
        eprintln!("error: --var {}: {why}", path.display());
        ExitCode::from(2)
    };
    if dialect.unwrap_or_else(|| Dialect::from_path(file)) != Dialect::Rs274ngc {
        return Err(refuse(
            "a LinuxCNC parameter file is for RS274/NGC programs",
        ));
    }
    if DataFileKind::of(path) != Some(DataFileKind::LinuxCncParameters) {
        return Err(refuse("the file must be a LinuxCNC parameter file (.var)"));
    }
    if path.exists() {
        let stored = load_offset_file(path, machine.linuxcnc_units).map_err(|d| {
            diagnostics::render(path, &d);
            ExitCode::from(1)
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

fn run_program(
    file: &Path,
    dialect: Option<Dialect>,
    args: &MachineArgs,
    json: bool,
    var: &VarArgs,
    motion: &MotionArgs,
    stock_args: &stock::StockArgs,
) -> Result<ExitCode, String> {
    let options = match sim_options(motion) {
        Ok(o) => o,
        Err(why) => {
            eprintln!("error: {why}");
            return Ok(ExitCode::from(2));
        }
    };
    let mut machine = match load_machine(args) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    if let Err(code) = load_var(file, dialect, var, &mut machine) {
        return Ok(code);
    }
    let units = machine.linuxcnc_units;
    let (mut interp, dialect) = interpreter(file, dialect, &machine, false, args)?;
    let trace = match &motion.trace {
        Some(path) => Some(trace::TraceWriter::create(path, &machine)?),
        None => None,
    };
    let stock_sim = match stock::build(stock_args, &machine, dialect) {
        Ok(s) => s,
        Err(why) => {
            eprintln!("error: {why}");
            return Ok(ExitCode::from(2));
        }
    };
    let mut sim = SimMachine::with_options(machine, options);
    if let Some(s) = stock_sim {
        sim.set_stock(s);
    }
    let progress = progress::Progress::new(file);
    sim.set_setpoint_sink(trace::sink(trace.clone(), progress.clone()));
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
    let warnings = interp.take_warnings();
    let mut rep = sim.finish();
    progress.done();
    if let Some(t) = &trace {
        t.close()?;
    }
    rep.blocks = interp.stats().blocks_executed;
    stock::write_outputs(stock_args, &sim)?;
    if json {
        let mut out = report::json(file, dialect, &rep, failure.as_ref(), &warnings);
        out.push('\n');
        write_stdout(&out)?;
    } else {
        for w in &warnings {
            diagnostics::render(file, w);
        }
        if let Some(d) = &failure {
            diagnostics::render(file, d);
        }
        write_stdout(&report::text(file, dialect, &rep, failure.as_ref()))?;
    }
    Ok(if failure.is_some() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// `stanok run`'s motion options, checked.
fn sim_options(m: &MotionArgs) -> Result<SimOptions, String> {
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
            cli::ProfileArg::Soft => stanok_canon::AccelerationProfile::Soft,
            cli::ProfileArg::Brisk => stanok_canon::AccelerationProfile::Brisk,
        }),
        override_changes,
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

fn canon(
    file: &Path,
    dialect: Option<Dialect>,
    format: Option<CanonFormat>,
    args: &MachineArgs,
    var: &VarArgs,
) -> Result<ExitCode, String> {
    let mut machine = match load_machine(args) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    if let Err(code) = load_var(file, dialect, var, &mut machine) {
        return Ok(code);
    }
    let (mut interp, dialect) = interpreter(file, dialect, &machine, false, args)?;
    // LinuxCNC's rs274 knows all nine axes whatever the machine: keep its traces comparable.
    let format = format.unwrap_or(match dialect {
        Dialect::Rs274ngc => CanonFormat::Linuxcnc,
        _ => CanonFormat::Jsonl,
    });
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let mut printer = LinuxCncPrinter::new();
    let mut failure = None;
    for item in interp.by_ref() {
        match item {
            Ok(cmd) => {
                let text = match format {
                    CanonFormat::Linuxcnc => printer.print(&cmd).to_string(),
                    CanonFormat::Jsonl => report::canon_json_line(&cmd),
                };
                if let Err(e) = out.write_all(text.as_bytes()) {
                    return quiet_on_broken_pipe(e);
                }
            }
            Err(d) => {
                failure = Some(d);
                break;
            }
        }
    }
    if format == CanonFormat::Linuxcnc {
        if let Err(e) = out.write_all(printer.finish().as_bytes()) {
            return quiet_on_broken_pipe(e);
        }
    }
    if let Err(e) = out.flush() {
        return quiet_on_broken_pipe(e);
    }
    drop(out);
    save_var(var, &interp, machine.linuxcnc_units)?;
    for w in interp.take_warnings() {
        diagnostics::render(file, &w);
    }
    if let Some(d) = failure {
        diagnostics::render(file, &d);
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// The programmed contour of a program that uses cutter radius compensation: the same program run
/// with every tool radius 0 (compensation then offsets by nothing). Empty when it moves exactly as
/// the compensated run does (no compensation) or cannot be run.
fn programmed_contour(
    file: &Path,
    dialect: Option<Dialect>,
    machine: &MachineData,
    args: &MachineArgs,
    compensated: &[Spanned<Canon>],
) -> Vec<Spanned<Canon>> {
    let mut zero = machine.clone();
    for tool in zero.control.tools.tools.values_mut() {
        for edge in &mut tool.edges {
            edge.radius = 0.0;
            edge.radius_wear = 0.0;
        }
    }
    let Ok((interp, _)) = interpreter(file, dialect, &zero, false, args) else {
        return Vec::new();
    };
    let reference: Vec<Spanned<Canon>> = interp.map_while(Result::ok).collect();
    let moves = |cmds: &[Spanned<Canon>]| -> Vec<Canon> {
        cmds.iter()
            .filter(|c| c.value.motion().is_some())
            .map(|c| c.value.clone())
            .collect()
    };
    if moves(&reference) == moves(compensated) {
        return Vec::new();
    }
    reference
}

/// `plot --stock`: runs the program on the simulated machine with the stock and draws what is
/// left (PNG), collisions marked.
fn plot_stock(
    file: &Path,
    dialect: Option<Dialect>,
    output: &Path,
    args: &MachineArgs,
    stock_args: &stock::StockArgs,
) -> Result<ExitCode, String> {
    let machine = match load_machine(args) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    let (mut interp, dialect) = interpreter(file, dialect, &machine, false, args)?;
    let Some(stock_sim) = stock::build(stock_args, &machine, dialect)? else {
        return Err("plot --stock-out needs --stock".into());
    };
    let mut sim = SimMachine::with_options(machine, SimOptions::default());
    sim.set_stock(stock_sim);
    let mut failure = None;
    for item in interp.by_ref() {
        if let Err(d) = item.and_then(|cmd| sim.apply(&cmd)) {
            failure = Some(d);
            break;
        }
    }
    sim.finish();
    if let Some(e) = sim.stock().and_then(|s| s.error()) {
        return Err(e.to_string());
    }
    stock::write_png(&sim, output)?;
    stock::write_outputs(stock_args, &sim)?;
    if let Some(d) = failure {
        diagnostics::render(file, &d);
        eprintln!("drew the stock up to the error: {}", output.display());
        return Ok(ExitCode::from(1));
    }
    eprintln!("wrote {}", output.display());
    Ok(ExitCode::SUCCESS)
}

fn plot(
    file: &Path,
    dialect: Option<Dialect>,
    output: &Path,
    args: &MachineArgs,
) -> Result<ExitCode, String> {
    let machine = match load_machine(args) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    let (mut interp, used) = interpreter(file, dialect, &machine, false, args)?;
    let mut commands: Vec<Spanned<Canon>> = Vec::new();
    let mut failure = None;
    for item in interp.by_ref() {
        match item {
            Ok(c) => commands.push(c),
            Err(d) => {
                failure = Some(d);
                break;
            }
        }
    }
    let title = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let options = stanok_plot::PlotOptions {
        title,
        reference: programmed_contour(file, dialect, &machine, args, &commands),
        // The lab lathes (X = radius): the turning drawing's ZX view.
        lathe: matches!(used, Dialect::Nc31 | Dialect::P2p32),
        tool_axis: tool_axis::ticks(&commands, machine.five_axis().as_ref()),
        ..Default::default()
    };
    let svg = stanok_plot::render_svg(&commands, &options);
    std::fs::write(output, svg).map_err(|e| format!("cannot write {}: {e}", output.display()))?;
    if let Some(d) = failure {
        diagnostics::render(file, &d);
        eprintln!("plotted up to the error: {}", output.display());
        return Ok(ExitCode::from(1));
    }
    eprintln!("wrote {}", output.display());
    Ok(ExitCode::SUCCESS)
}

/// `stanok convert`: the program's Canon stream written in the target dialect. Nothing is written
/// when the source has an error (a partial program is not a program); warnings name every command
/// the target cannot express exactly.
fn convert(
    file: &Path,
    dialect: Option<Dialect>,
    target: stanok_convert::Target,
    output: Option<&Path>,
    chord_tolerance: f64,
    args: &MachineArgs,
) -> Result<ExitCode, String> {
    if !(chord_tolerance.is_finite() && chord_tolerance >= 1e-6) {
        eprintln!("error: --chord-tolerance must be at least 1e-6 mm, not {chord_tolerance}");
        return Ok(ExitCode::from(2));
    }
    let machine = match load_machine(args) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    let (mut interp, dialect) = interpreter(file, dialect, &machine, false, args)?;
    let name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut options = stanok_convert::ConvertOptions::new(target, &name, dialect.id());
    options.chord_tolerance_mm = chord_tolerance;
    options.max_feed_mm_per_min = machine.max_feed;
    options.axes = machine.axis_mask();
    let mut converter = stanok_convert::Converter::new(options);
    let mut text = String::new();
    let mut failure = None;
    for item in interp.by_ref() {
        match item {
            Ok(cmd) => {
                converter.push(&cmd);
                text.push_str(&converter.take_text());
            }
            Err(d) => {
                failure = Some(d);
                break;
            }
        }
    }
    for w in interp.take_warnings() {
        diagnostics::render(file, &w);
    }
    if let Some(d) = failure {
        diagnostics::render(file, &d);
        eprintln!(
            "{}: not converted (the program has an error)",
            file.display()
        );
        return Ok(ExitCode::from(1));
    }
    converter.finish();
    text.push_str(&converter.take_text());
    for w in converter.warnings() {
        eprintln!("warning: {}:{}: {}", file.display(), w.line, w.message);
    }
    match output {
        Some(path) => {
            std::fs::write(path, &text)
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            eprintln!(
                "wrote {} ({} warning(s))",
                path.display(),
                converter.warnings().len()
            );
        }
        None => write_stdout(&text)?,
    }
    Ok(ExitCode::SUCCESS)
}
