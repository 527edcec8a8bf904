//! Command-line syntax (clap derive): the verbs and their options. Argument groups shared by
//! several verbs are in `cli_args.rs`, `stanok cutting turn`'s in `cli_cutting.rs`.
//!
//! Conventions, the same for every verb: exit status 0 = done, no error in the program;
//! 1 = the program (or a machine-data file) has an error; 2 = the command line or a file could not
//! be used (clap's usage errors, a missing file, a directory, an unwritable output).
//! `--color` and the `NO_COLOR` / `CLICOLOR_FORCE` variables decide colour on stderr.

use crate::cli_args::{MachineArgs, MotionArgs, ProgramArgs, VarArgs};
use crate::cli_cutting::CuttingCommand;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Exit status and environment, shown after the help of `stanok` itself.
const AFTER_HELP: &str = "\
Exit status: 0 = no error in the program (warnings allowed); 1 = the program or a machine-data file \
has an error; 2 = the command line or a file could not be used (usage, a missing file, a directory).

Environment: NO_COLOR (set, not empty) turns colour off; CLICOLOR_FORCE (not 0) turns it on when \
stderr is not a terminal; --color overrides both.

A program argument `-` reads the program from standard input.";

/// Stanok: an open CNC control kernel. Checks, runs, plots and converts part programs of AxiOMA
/// Control, LinuxCNC (RS274/NGC), Balt-System, Mazatrol and four teaching controls on a simulated
/// machine.
#[derive(Debug, Parser)]
#[command(name = "stanok", version, after_help = AFTER_HELP)]
pub struct Cli {
    #[command(flatten)]
    pub colour: ColourArgs,
    #[command(subcommand)]
    pub command: Command,
}

/// When to colour diagnostics on stderr.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ColorWhen {
    /// When stderr is a terminal, unless NO_COLOR is set (CLICOLOR_FORCE forces it on).
    Auto,
    /// Always.
    Always,
    /// Never.
    Never,
}

/// `--color WHEN`.
#[derive(Debug, Clone, Copy, Args)]
pub struct ColourArgs {
    /// Colour diagnostics: auto (a terminal, unless NO_COLOR is set; CLICOLOR_FORCE forces it),
    /// always, never.
    #[arg(
        long = "color",
        visible_alias = "colour",
        value_enum,
        value_name = "WHEN"
    )]
    pub when: Option<ColorWhen>,
}

/// The program's language. Without `--dialect` the file name decides (`.ngc`, a lab prefix), and
/// where it cannot (`.nc`, `.gcode`, `.tap`, stdin …) the text does; `check` and `run` print
/// which one and why.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DialectArg {
    /// AxiOMA Control: ISO with Sinumerik-style keywords (TRAORI, BRISK, MSG, CR=, $iPerm …).
    Axioma,
    /// LinuxCNC RS274/NGC (.ngc): O-words, #<named> parameters, G7x lathe cycles.
    #[value(alias = "linuxcnc", alias = "ngc")]
    Rs274ngc,
    /// Mazatrol EIA/ISO (Mazak): tool tip point control G43.4/G43.5 on a 5-axis machine.
    Mazatrol,
    /// Balt-System NC: 5-axis CVU=1/CVU=3 programs.
    Balt,
    /// Elektronika NC-31 (16K20F3 lathe): one address per frame, `*` groups.
    Nc31,
    /// 2P32 turning-milling centre: integers in 0.001 mm, X on the radius.
    #[value(name = "2p32")]
    P2p32,
    /// Elektronika MC2101 notation: 6-digit increments in 0.01 mm.
    Mc2101,
    /// The GOST 20999-83 control of the lab collection: no decimal point = 0.001 mm.
    Gost20999,
}

impl From<DialectArg> for stanok_syntax::Dialect {
    fn from(d: DialectArg) -> Self {
        match d {
            DialectArg::Axioma => stanok_syntax::Dialect::Axioma,
            DialectArg::Rs274ngc => stanok_syntax::Dialect::Rs274ngc,
            DialectArg::Nc31 => stanok_syntax::Dialect::Nc31,
            DialectArg::P2p32 => stanok_syntax::Dialect::P2p32,
            DialectArg::Mc2101 => stanok_syntax::Dialect::Mc2101,
            DialectArg::Gost20999 => stanok_syntax::Dialect::Gost20999,
            DialectArg::Mazatrol => stanok_syntax::Dialect::Mazatrol,
            DialectArg::Balt => stanok_syntax::Dialect::Balt,
        }
    }
}

/// What `plot --color` colours the path by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PlotColor {
    /// Each source line's mean path speed (length / planned time), in six bands.
    Speed,
    /// The limit that set each line's speed (programmed feed, axis velocity, …).
    Limit,
}

/// `--dialect`, on every verb that reads a program.
#[derive(Debug, Clone, Copy, Args)]
pub struct DialectOption {
    /// The program's language (default: from the file name, else from its text).
    #[arg(long, value_enum, value_name = "DIALECT")]
    pub dialect: Option<DialectArg>,
}

/// Target dialect of `stanok convert`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TargetArg {
    /// LinuxCNC RS274/NGC.
    #[value(alias = "linuxcnc", alias = "ngc")]
    Rs274ngc,
    /// AxiOMA Control.
    Axioma,
}

impl From<TargetArg> for stanok_convert::Target {
    fn from(t: TargetArg) -> Self {
        match t {
            TargetArg::Rs274ngc => stanok_convert::Target::Rs274ngc,
            TargetArg::Axioma => stanok_convert::Target::Axioma,
        }
    }
}

/// Output format of `stanok canon`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CanonFormat {
    /// LinuxCNC `rs274 -g` canonical calls (default for rs274ngc).
    Linuxcnc,
    /// One JSON object per command (default for the other dialects).
    Jsonl,
}

/// `stanok plot --view`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ViewArg {
    /// XY from above.
    Xy,
    /// XZ from the front.
    Xz,
    /// YZ from the right.
    Yz,
    /// Isometric, from front right above.
    Iso,
    /// A lathe's ZX: Z to the right, X (radius) up (the default for lathes).
    Lathe,
    /// XY, isometric, XZ and YZ on one sheet (the default for other machines).
    All,
}

impl From<ViewArg> for stanok_plot::ViewChoice {
    fn from(v: ViewArg) -> Self {
        match v {
            ViewArg::Xy => stanok_plot::ViewChoice::Xy,
            ViewArg::Xz => stanok_plot::ViewChoice::Xz,
            ViewArg::Yz => stanok_plot::ViewChoice::Yz,
            ViewArg::Iso => stanok_plot::ViewChoice::Iso,
            ViewArg::Lathe => stanok_plot::ViewChoice::Lathe,
            ViewArg::All => stanok_plot::ViewChoice::All,
        }
    }
}

/// `WIDTHxHEIGHT` in px, each 320 … 16384 (width) and 240 … 16384 (height).
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X', '×'])
        .ok_or("expected WIDTHxHEIGHT, e.g. 1600x1200")?;
    let parse = |t: &str, min: u32| -> Result<u32, String> {
        let v: u32 = t
            .trim()
            .parse()
            .map_err(|_| format!("`{}` is not a whole number of pixels", t.trim()))?;
        if (min..=16384).contains(&v) {
            Ok(v)
        } else {
            Err(format!("{v} px is outside {min} … 16384"))
        }
    };
    Ok((parse(w, 320)?, parse(h, 240)?))
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Check programs without moving anything: every diagnostic with file:line:column.
    Check {
        /// The part programs (`-` = standard input).
        #[arg(required = true, value_name = "FILE")]
        files: Vec<PathBuf>,
        #[command(flatten)]
        dialect: DialectOption,
        /// One JSON object per diagnostic and line on stdout (fields in docs/cli.md).
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        program: ProgramArgs,
        #[command(flatten)]
        colour: ColourArgs,
    },
    /// Run a program on the simulated machine and print the run report.
    Run {
        /// The part program (`-` = standard input).
        file: PathBuf,
        #[command(flatten)]
        dialect: DialectOption,
        /// Print the report as one JSON object (fields in docs/report.md).
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        program: ProgramArgs,
        #[command(flatten)]
        var: VarArgs,
        #[command(flatten)]
        motion: MotionArgs,
        #[command(flatten)]
        colour: ColourArgs,
    },
    /// Print the canonical command stream (LinuxCNC's `rs274 -g` form, or JSON lines).
    Canon {
        /// The part program (`-` = standard input).
        file: PathBuf,
        #[command(flatten)]
        dialect: DialectOption,
        /// Output format.
        #[arg(long, value_enum)]
        format: Option<CanonFormat>,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        program: ProgramArgs,
        #[command(flatten)]
        var: VarArgs,
        #[command(flatten)]
        colour: ColourArgs,
    },
    /// Draw the tool path as a picture (SVG or PNG, from the output's extension).
    Plot {
        /// The part program (`-` = standard input).
        file: PathBuf,
        #[command(flatten)]
        dialect: DialectOption,
        /// The picture: `NAME.svg`, `NAME.png`, or `-` for SVG on standard output (default: the
        /// program's name with `.svg`, in the current directory).
        #[arg(short = 'o', long = "output", value_name = "FILE")]
        output: Option<PathBuf>,
        /// Which views (default: `lathe` on a lathe or for a lathe dialect, else `all`).
        #[arg(long, value_enum)]
        view: Option<ViewArg>,
        /// Picture size in px.
        #[arg(long, value_name = "WxH", default_value = "1200x900", value_parser = parse_size)]
        size: (u32, u32),
        /// Colour the path by block, with a key: `speed` (each line's mean path speed) or
        /// `limit` (what set its speed, as `run` reports it). Runs the motion on the machine.
        /// (Diagnostics' colours: `stanok --color WHEN plot …`.)
        #[arg(long, value_enum, value_name = "BY")]
        color: Option<PlotColor>,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        program: ProgramArgs,
    },
    /// Convert a program to another dialect: written from its canonical commands (cycles,
    /// subprograms and compensation expanded; positions absolute in the start frame).
    Convert {
        /// The part program (`-` = standard input).
        file: PathBuf,
        #[command(flatten)]
        dialect: DialectOption,
        /// The dialect to write.
        #[arg(long, value_enum)]
        to: TargetArg,
        /// Output file (default: standard output).
        #[arg(short = 'o', long = "output", value_name = "FILE")]
        output: Option<PathBuf>,
        /// Largest deviation of the chords written for curves the target cannot express, mm.
        #[arg(long, value_name = "MM", default_value_t = 0.001)]
        chord_tolerance: f64,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        program: ProgramArgs,
        #[command(flatten)]
        colour: ColourArgs,
    },
    /// Operator panel: a web HMI on 127.0.0.1:8080 that runs programs on the simulated machine in
    /// real time (program, 3D path, DRO, cycle start, feed hold, overrides, single block, block
    /// search, M00/M01 prompts).
    Serve {
        /// Address to listen on. Anything but loopback requires --token.
        #[arg(long, default_value = "127.0.0.1:8080")]
        bind: std::net::SocketAddr,
        /// Access token (at least 16 characters): every request must carry it, as
        /// `Authorization: Bearer TOKEN` or `?token=TOKEN`.
        #[arg(long)]
        token: Option<String>,
        /// The program directory: the only place the panel reads and writes programs.
        #[arg(long, value_name = "DIR", default_value = ".")]
        programs: PathBuf,
        /// Request size limit (program uploads), MB.
        #[arg(long, value_name = "MB", default_value_t = 64)]
        upload_limit: u64,
        /// Machine time per wall-clock time: 1 = real time, 10 = ten times faster, 0 = unpaced.
        #[arg(long, default_value_t = 1.0)]
        time_scale: f64,
        /// Where the simulated probe makes contact (as for `run`).
        #[arg(long, value_name = "AXIS<=VALUE", value_parser = crate::cli_args::parse_probe_surface)]
        probe_surface: Vec<stanok_canon::setup::ProbeSurface>,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        colour: ColourArgs,
    },
    /// Machine data: the built-in machines, and what a machine is and stores.
    Machine {
        #[command(subcommand)]
        command: MachineCommand,
    },
    /// Cutting data: the lab collection's method, step by step, with every table cell it uses.
    Cutting {
        #[command(subcommand)]
        command: CuttingCommand,
    },
    /// Print a shell completion script (e.g. `stanok completions bash > ~/.local/share/bash-completion/completions/stanok`).
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Print the manual page (roff; e.g. `stanok man | man -l -`).
    Man,
}

#[derive(Debug, Subcommand)]
pub enum MachineCommand {
    /// List the built-in machines: name, axes, kinematics, description.
    List {
        /// Print the list as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Print the effective machine data: axes, rates, offsets, home positions, tools.
    Show {
        #[command(flatten)]
        machine: MachineArgs,
        /// Print everything as one JSON object.
        #[arg(long, conflicts_with_all = ["toml", "tbl", "var"])]
        json: bool,
        /// Print everything as Stanok machine-data TOML (e.g. to turn LinuxCNC files into a
        /// machine file).
        #[arg(long, conflicts_with_all = ["tbl", "var"])]
        toml: bool,
        /// Print the tool table as a LinuxCNC tool table (in --linuxcnc-units).
        #[arg(long, conflicts_with = "var")]
        tbl: bool,
        /// Print the offsets and parameters as a LinuxCNC parameter file (in --linuxcnc-units).
        #[arg(long)]
        var: bool,
        #[command(flatten)]
        colour: ColourArgs,
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn sizes() {
        assert_eq!(parse_size("1600x1200"), Ok((1600, 1200)));
        assert_eq!(parse_size("800×600"), Ok((800, 600)));
        assert!(parse_size("10x10").is_err());
        assert!(parse_size("big").is_err());
        assert!(parse_size("99999x1000").is_err());
    }
}
