//! `stanok canon` and `stanok convert` (the interpreted stream printed, or written as another
//! dialect) and `stanok plot --stock` (the stock's picture after a run).

use super::*;

pub(super) fn canon(
    file: &Path,
    dialect: Option<Dialect>,
    format: Option<CanonFormat>,
    args: &MachineArgs,
    program_args: &ProgramArgs,
    var: &VarArgs,
) -> Result<ExitCode, String> {
    let (mut machine, program, choice) = match prepare(file, dialect, args, program_args) {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let dialect = choice.dialect;
    if let Err(code) = load_var(dialect, var, &mut machine) {
        return Ok(code);
    }
    let opts = program::options(dialect, &machine, false, program_args);
    let mut interp = match program::interpreter(&program, opts) {
        Ok(i) => i,
        Err(code) => return Ok(code),
    };
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
    for mut w in interp.take_warnings() {
        hints::enrich(&mut w, &machine);
        diagnostics::render(&program, &w);
    }
    if let Some(mut d) = failure {
        hints::enrich(&mut d, &machine);
        diagnostics::render(&program, &d);
        return Ok(program::program_error());
    }
    Ok(ExitCode::SUCCESS)
}

/// `plot --stock`: runs the program on the simulated machine with the stock and draws what is
/// left (PNG; default `NAME.png` beside the current directory), collisions marked.
pub(super) fn plot_stock(
    file: &Path,
    given: Option<Dialect>,
    output: Option<&Path>,
    machine_args: &MachineArgs,
    args: &ProgramArgs,
    stock_args: &stock::StockArgs,
) -> Result<ExitCode, String> {
    let machine = match program::load_machine(machine_args, &args.probe_surface) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    let (program, choice) = match program::open(file, given) {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let output = match output {
        Some(p) if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) => p.to_path_buf(),
        Some(p) => {
            return Ok(program::refuse(format!(
                "{}: plot --stock draws a PNG (give -o NAME.png)",
                p.display()
            )))
        }
        None => {
            let stem = program
                .path
                .as_ref()
                .and_then(|p| p.file_stem())
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "stock".into());
            PathBuf::from(format!("{stem}.png"))
        }
    };
    program::say_dialect(&choice);
    let dialect = choice.dialect;
    let stock_sim = match stock::build(stock_args, &machine, dialect) {
        Ok(Some(s)) => s,
        Ok(None) => return Ok(program::refuse("plot --stock-out needs --stock")),
        Err(why) => return Ok(program::refuse(why)),
    };
    let opts = program::options(dialect, &machine, false, args);
    let mut interp = match program::interpreter(&program, opts) {
        Ok(i) => i,
        Err(code) => return Ok(code),
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
        return Ok(program::refuse(e));
    }
    stock::write_png(&sim, &output)?;
    stock::write_outputs(stock_args, &sim)?;
    if let Some(d) = failure {
        diagnostics::render(&program, &d);
        eprintln!("drew the stock up to the error: {}", output.display());
        return Ok(program::program_error());
    }
    eprintln!("wrote {}", output.display());
    Ok(ExitCode::SUCCESS)
}

/// `stanok convert`: the program's Canon stream written in the target dialect. Nothing is written
/// when the source has an error (a partial program is not a program); warnings name every command
/// the target cannot express exactly, each once, in the same form as the interpreter's.
pub(super) fn convert(
    file: &Path,
    dialect: Option<Dialect>,
    target: stanok_convert::Target,
    output: Option<&Path>,
    chord_tolerance: f64,
    args: &MachineArgs,
    program_args: &ProgramArgs,
) -> Result<ExitCode, String> {
    if !(chord_tolerance.is_finite() && chord_tolerance >= 1e-6) {
        return Ok(program::refuse(format_args!(
            "--chord-tolerance must be at least 1e-6 mm, not {chord_tolerance}"
        )));
    }
    let (machine, program, choice) = match prepare(file, dialect, args, program_args) {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    program::say_dialect(&choice);
    let dialect = choice.dialect;
    let opts = program::options(dialect, &machine, false, program_args);
    let mut interp = match program::interpreter(&program, opts) {
        Ok(i) => i,
        Err(code) => return Ok(code),
    };
    let name = program.file_name().unwrap_or_else(|| "stdin".into());
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
    // The converter warns about every move written without a feed, with the feed it wrote: the
    // interpreter's one warning about the same moves would say it twice.
    let warnings: Vec<Diagnostic> = interp
        .take_warnings()
        .into_iter()
        .filter(|w| w.code.to_string() != "lab::no-feed")
        .collect();
    for w in &warnings {
        diagnostics::render(&program, w);
    }
    if let Some(mut d) = failure {
        hints::enrich(&mut d, &machine);
        diagnostics::render(&program, &d);
        eprintln!(
            "{}: not converted (the program has an error)",
            program.display()
        );
        return Ok(program::program_error());
    }
    converter.finish();
    text.push_str(&converter.take_text());
    for w in converter.warnings() {
        diagnostics::render(&program, &report::convert_warning(&program, w));
    }
    match output {
        Some(path) => {
            if let Err(e) = std::fs::write(path, &text) {
                return Ok(program::refuse(format_args!(
                    "cannot write {}: {}",
                    path.display(),
                    source::plain(&e)
                )));
            }
            eprintln!(
                "wrote {} ({} warning(s))",
                path.display(),
                converter.warnings().len() + warnings.len()
            );
        }
        None => write_stdout(&text)?,
    }
    Ok(ExitCode::SUCCESS)
}
