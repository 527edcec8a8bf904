//! The bounds every verb runs under (`docs/robustness.md`): options shared by `check`, `run`,
//! `canon`, `plot` and `convert`, so that no program — however long, deep or endless — makes a
//! verb hang, exhaust memory or print without end. Each bound reached is a diagnostic naming its
//! option.

use clap::Args;
use stanok_interp::InterpOptions;

/// The bounds of one run (defaults in `docs/robustness.md`).
#[derive(Debug, Clone, Args)]
pub struct LimitsArgs {
    /// Most lines one run reads: executed blocks, control-flow lines and skipped lines alike, each
    /// pass of a loop counting its lines again. Default 50,000,000 (five times a 10-million-block
    /// program; a runaway loop reaches it in seconds).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_blocks: Option<u64>,
    /// Most lines one run reads again: loop passes, subroutine calls, jumps back (a program read
    /// once is bounded by --max-blocks alone). Default 1,000,000.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_repeated_lines: Option<u64>,
    /// Most loop passes of one run, all loops together (nested loops multiply). Default
    /// 1,000,000.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_total_loop_iterations: Option<u64>,
    /// Most control structures open at once (RS274/NGC O-word if/loops, AxiOMA `{ }` blocks and
    /// loops). Default 1,000.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pub max_nesting: Option<u64>,
    /// Longest line kept, bytes; the rest of a longer line is an error. Default 1,048,576.
    #[arg(long, value_name = "BYTES", value_parser = clap::value_parser!(u64).range(16..=1_073_741_824))]
    pub max_line_length: Option<u64>,
    /// Most bytes of a program read; past it the run stops with an error. Default 1 GiB
    /// (1,073,741,824).
    #[arg(long, value_name = "BYTES", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_program_size: Option<u64>,
    /// Most diagnostics shown for one line; the last one counts the rest. Default 10.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pub max_diagnostics_per_line: Option<u64>,
    /// Most bytes of program text one diagnostic echoes (a window around the offending text).
    /// Default 240.
    #[arg(long, value_name = "BYTES", value_parser = clap::value_parser!(u64).range(16..=1_000_000))]
    pub max_echo_bytes: Option<u64>,
    /// `run`: bound on simulated machine time, hours; a block that would pass it stops the run
    /// with an error. Default 100.
    #[arg(long, value_name = "HOURS", value_parser = parse_hours)]
    pub max_machine_time: Option<f64>,
}

fn parse_hours(s: &str) -> Result<f64, String> {
    let h: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number of hours"))?;
    if h.is_finite() && h > 0.0 {
        Ok(h)
    } else {
        Err("the bound must be a positive number of hours".into())
    }
}

impl LimitsArgs {
    /// Sets the interpreter's bounds (and the renderer's echo bound).
    pub fn apply(&self, opts: &mut InterpOptions) {
        if let Some(n) = self.max_blocks {
            opts.max_blocks = n;
        }
        if let Some(n) = self.max_repeated_lines {
            opts.max_repeated_lines = n;
        }
        if let Some(n) = self.max_total_loop_iterations {
            opts.max_total_loop_iterations = n;
        }
        if let Some(n) = self.max_nesting {
            opts.max_nesting = n as usize;
        }
        if let Some(n) = self.max_line_length {
            opts.max_line_bytes = n as usize;
        }
        if let Some(n) = self.max_program_size {
            opts.max_program_bytes = n;
        }
        if let Some(n) = self.max_diagnostics_per_line {
            opts.max_diagnostics_per_line = n as usize;
        }
        if let Some(n) = self.max_echo_bytes {
            crate::diagnostics::set_max_echo_bytes(n as usize);
        }
    }

    /// The bound on simulated machine time, s.
    pub fn machine_time_s(&self) -> f64 {
        self.max_machine_time.map_or(
            stanok_machine::time_bound::DEFAULT_MAX_MACHINE_TIME_S,
            |h| h * 3600.0,
        )
    }
}
