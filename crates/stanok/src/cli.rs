//! Command-line syntax (clap derive).

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Stanok: an open CNC control kernel.
#[derive(Debug, Parser)]
#[command(name = "stanok", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// Program language, when the file extension does not say it (`.ngc` → rs274ngc, else axioma).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DialectArg {
    /// AxiOMA Control (ISO with Sinumerik-style keywords).
    Axioma,
    /// LinuxCNC RS274/NGC.
    Rs274ngc,
}

impl From<DialectArg> for stanok_syntax::Dialect {
    fn from(d: DialectArg) -> Self {
        match d {
            DialectArg::Axioma => stanok_syntax::Dialect::Axioma,
            DialectArg::Rs274ngc => stanok_syntax::Dialect::Rs274ngc,
        }
    }
}

/// Output format of `stanok canon`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CanonFormat {
    /// LinuxCNC `rs274 -g` canonical calls (default for rs274ngc).
    Linuxcnc,
    /// One JSON object per command (default for axioma).
    Jsonl,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Check a program: every diagnostic, exit status 0 (clean) or 1.
    Check {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
    },
    /// Run a program on the simulated machine and print the run report.
    Run {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
        /// Built-in machine name (`mill`) or a machine-data TOML file.
        #[arg(long, default_value = "mill")]
        machine: String,
        /// Print the report as one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Print the canonical command stream.
    Canon {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
        /// Output format.
        #[arg(long, value_enum)]
        format: Option<CanonFormat>,
        /// Built-in machine name or machine-data TOML file (configured axes, arc tolerance).
        #[arg(long, default_value = "mill")]
        machine: String,
    },
    /// Draw the tool path: XY, XZ, YZ and isometric views on one SVG sheet.
    Plot {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
        /// Output SVG file.
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        /// Built-in machine name or machine-data TOML file.
        #[arg(long, default_value = "mill")]
        machine: String,
    },
}
