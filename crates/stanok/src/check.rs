//! `stanok check FILE…`: interprets each program without moving anything and reports **every**
//! diagnostic (a bad block is skipped and checking goes on with the state it left unchanged).
//!
//! Per program: a line naming the dialect and why (stderr), the diagnostics in line order (rendered
//! on stderr, or one JSON object per line on stdout with `--json`), and a summary line on stderr.
//! When the dialect was guessed and many errors follow, the other dialects are tried quietly and a
//! hint names one that reads the program with far fewer errors. Exit status: 2 if a program could
//! not be read, else 1 if one has an error, else 0.
//!
//! Unless `--no-travel-check`, every move up to the first error is also checked against the
//! machine's travel as a control does before the start (`stanok_machine::TravelCheck`, the same
//! check the run and the panel's preview make): machine positions with the offsets and tool
//! lengths in force, joints under tool-centre-point control; each violation is an error
//! (`machine::travel-limit`) at its block.

use crate::cli_args::{MachineArgs, ProgramArgs};
use crate::dialect::{self, Choice};
use crate::source::Program;
use crate::{diagnostics, hints, program, write_stdout};
use stanok_canon::Diagnostic;
use stanok_machine::MachineData;
use stanok_syntax::Dialect;
use std::collections::HashSet;
use std::path::PathBuf;
use std::process::ExitCode;

/// Blocks one trial reading in another dialect may execute (the hint is about the text, so a
/// bounded look is enough).
const TRIAL_BLOCKS: u64 = 200_000;

/// Blocks whose travel violations `check` lists; past them it stops checking travel.
const MAX_TRAVEL_ERRORS: usize = 100;

/// Every diagnostic of one program, warnings and errors in line order, and how many are errors;
/// with `travel`, also the moves beyond the machine's travel before the first error.
fn diagnose(
    program: &Program,
    dialect: Dialect,
    machine: &MachineData,
    args: &ProgramArgs,
    max_blocks: Option<u64>,
    travel: bool,
) -> Result<(Vec<Diagnostic>, usize), ExitCode> {
    let mut opts = program::options(dialect, machine, true, args);
    if let Some(n) = max_blocks {
        opts.max_blocks = n;
    }
    let mut interp = program::interpreter(program, opts)?;
    let mut errors = Vec::new();
    // A bad block inside a loop fails on every pass (AxiOMA `for`, RS274/NGC `o… while`): each
    // error is listed once.
    let mut seen = HashSet::new();
    // `check` runs no machine, but a feed or dwell that makes one block run for more than an
    // hour is worth a word (`stanok_machine::time_bound`).
    let mut long_blocks = Vec::new();
    let mut limits = travel.then(|| stanok_machine::TravelCheck::new(machine));
    let mut travel_blocks = HashSet::new();
    let mut failed = false;
    for item in interp.by_ref() {
        let d = match item {
            // The moves a run would make: those before the first error.
            Ok(cmd) if !failed => {
                if long_blocks.len() < 100 {
                    long_blocks.extend(stanok_machine::time_bound::long_block(
                        machine, &cmd.value, cmd.span,
                    ));
                }
                match limits.as_mut().map(|t| t.check(&cmd)) {
                    // One violation per block: in a loop each pass may go a step further, and
                    // a message per position made a million errors (33 s; mutation campaign,
                    // session 3). Past `MAX_TRAVEL_ERRORS` blocks the check stops.
                    Some(Err(d)) => {
                        if travel_blocks.len() >= MAX_TRAVEL_ERRORS {
                            limits = None;
                        }
                        if !travel_blocks.insert((d.span.start, d.span.end)) {
                            continue;
                        }
                        d
                    }
                    _ => continue,
                }
            }
            Ok(_) => continue,
            Err(d) => {
                failed = true;
                d
            }
        };
        if seen.insert((
            d.code.to_string(),
            d.span.start,
            d.span.end,
            d.message.clone(),
        )) {
            errors.push(d);
        }
    }
    let count = errors.len();
    let mut all: Vec<Diagnostic> = interp.take_warnings();
    all.extend(long_blocks);
    all.extend(errors);
    all.sort_by_key(|d| (d.file.is_some(), d.span.line, d.span.column));
    Ok((all, count))
}

/// `stanok check`.
pub fn check(
    files: &[PathBuf],
    given: Option<Dialect>,
    json: bool,
    travel: bool,
    machine_args: &MachineArgs,
    args: &ProgramArgs,
) -> Result<ExitCode, String> {
    let machine = match program::load_machine(machine_args, &args.probe_surface) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    if files.iter().filter(|f| f.as_os_str() == "-").count() > 1 {
        return Ok(program::refuse(
            "standard input (`-`) can be read once only",
        ));
    }
    let mut worst = 0u8;
    for file in files {
        let status = match program::open(file, given) {
            Ok((program, choice)) => {
                if files.len() > 1 {
                    eprintln!(
                        "{}: dialect {} ({})",
                        program.display(),
                        choice.dialect.id(),
                        choice.reason
                    );
                } else {
                    program::say_dialect(&choice);
                }
                check_one(&program, &choice, json, travel, &machine, args)?
            }
            Err(_) => 2,
        };
        worst = worst.max(status);
    }
    Ok(ExitCode::from(worst))
}

/// One program: its diagnostics, summary and hint; 0, 1 or 2.
fn check_one(
    program: &Program,
    choice: &Choice,
    json: bool,
    travel: bool,
    machine: &MachineData,
    args: &ProgramArgs,
) -> Result<u8, String> {
    let Ok((mut all, errors)) = diagnose(program, choice.dialect, machine, args, None, travel)
    else {
        return Ok(2);
    };
    for d in &mut all {
        hints::enrich(d, machine);
        if json {
            write_stdout(&diagnostics::json_line(program, d))?;
        } else {
            diagnostics::render(program, d);
        }
    }
    let warnings = all.len() - errors;
    let name = program.display();
    if errors == 0 {
        eprintln!("{name}: ok ({warnings} warning(s))");
        return Ok(0);
    }
    eprintln!("{name}: {errors} error(s), {warnings} warning(s)");
    if choice.guessed {
        say_hint(program, choice.dialect, errors, machine, args);
    }
    Ok(1)
}

/// After `errors` errors from a guessed `dialect`: reads the program in the other dialects and,
/// if one fits far better, says so on stderr.
pub fn say_hint(
    program: &Program,
    dialect: Dialect,
    errors: usize,
    machine: &MachineData,
    args: &ProgramArgs,
) {
    let hint = dialect::hint_for(dialect, errors, |d| {
        diagnose(program, d, machine, args, Some(TRIAL_BLOCKS), false)
            .map(|(_, n)| n)
            .unwrap_or(usize::MAX)
    });
    if let Some((better, n)) = hint {
        eprintln!(
            "hint: read as {} ({}) the program has {n} error(s) instead of {errors}: try --dialect {}",
            better.id(),
            control_name(better),
            better.id()
        );
    }
}

/// A run stopped at an error of a guessed dialect: counts the program's errors as `check` would
/// and, if they are many, hints at a dialect that fits better.
pub fn hint_after_run(
    program: &Program,
    dialect: Dialect,
    machine: &MachineData,
    args: &ProgramArgs,
) {
    if let Ok((_, errors)) = diagnose(program, dialect, machine, args, Some(TRIAL_BLOCKS), false) {
        say_hint(program, dialect, errors, machine, args);
    }
}

/// The control a dialect belongs to, for hints.
pub fn control_name(d: Dialect) -> &'static str {
    match d {
        Dialect::Axioma => "AxiOMA Control",
        Dialect::Rs274ngc => "LinuxCNC",
        Dialect::Balt => "Balt-System",
        Dialect::Mazatrol => "Mazatrol EIA/ISO",
        Dialect::Nc31 => "Elektronika NC-31",
        Dialect::P2p32 => "2P32",
        Dialect::Mc2101 => "Elektronika MC2101",
        Dialect::Gost20999 => "the GOST 20999 control",
    }
}
