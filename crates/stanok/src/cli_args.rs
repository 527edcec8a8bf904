//! Argument groups shared by several verbs (clap derive), each only on the verbs where it means
//! something: the machine (`MachineArgs`: every verb that loads one), how a program runs
//! (`ProgramArgs`: the verbs that interpret a program), stored parameters (`VarArgs`: `run`,
//! `canon`) and motion (`MotionArgs`: `run`).

use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Length unit of LinuxCNC tool tables and parameter files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum UnitsArg {
    /// Millimetres.
    Mm,
    /// Inches (a LinuxCNC machine with LINEAR_UNITS = inch; lengths are converted to mm).
    Inch,
}

impl From<UnitsArg> for stanok_canon::LengthUnits {
    fn from(u: UnitsArg) -> Self {
        match u {
            UnitsArg::Mm => stanok_canon::LengthUnits::Millimetres,
            UnitsArg::Inch => stanok_canon::LengthUnits::Inches,
        }
    }
}

/// The machine, and the stored data that replaces its own.
#[derive(Debug, Clone, Args)]
pub struct MachineArgs {
    /// Built-in machine (`stanok machine list` shows them) or a machine-data TOML file.
    #[arg(long, default_value = "mill", value_name = "NAME|FILE")]
    pub machine: String,
    /// Tool table to use instead of the machine's: a LinuxCNC tool table (.tbl) or Stanok machine
    /// data (.toml) holding only [[tool]] sections.
    #[arg(long, value_name = "FILE")]
    pub tools: Option<PathBuf>,
    /// Offsets to use instead of the machine's: a LinuxCNC parameter file (.var) or Stanok machine
    /// data (.toml) holding only offset sections ([[zero_offset]], [[workpiece]], [[home]], [g28],
    /// [g30], [g92], [parameters], active_system).
    #[arg(long, value_name = "FILE")]
    pub offsets: Option<PathBuf>,
    /// LinuxCNC machine units: the unit of .tbl/.var files and of RS274/NGC length parameters
    /// (default: the machine's `linuxcnc_units`). `inch` reproduces LinuxCNC's standalone `rs274`.
    #[arg(long, visible_alias = "machine-units", value_enum, value_name = "UNIT")]
    pub linuxcnc_units: Option<UnitsArg>,
}

/// How a program is read and run: only for the verbs that interpret one.
#[derive(Debug, Clone, Args)]
pub struct ProgramArgs {
    /// RS274/NGC: a directory searched for `name.ngc` when `o<name> call` names a subroutine the
    /// program does not define (LinuxCNC's SUBROUTINE_PATH); GOST-20999: where subprograms
    /// (`L0100` …) are found. Repeat for several, searched in order.
    #[arg(long, value_name = "DIR")]
    pub subroutine_path: Vec<PathBuf>,
    /// The operator's optional-stop switch off: M01 does not stop (AxiOMA; RS274/NGC's M1 is
    /// always passed on as OPTIONAL_PROGRAM_STOP, as LinuxCNC's interpreter does).
    #[arg(long)]
    pub skip_optional_stops: bool,
    /// Passes one loop may make before the run stops with a loop-limit error (AxiOMA `for`/`while`/
    /// `do`, RS274/NGC `o… while`/`repeat`), so that an endless loop ends with a diagnostic instead of
    /// running forever. Default 1,000,000.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_loop_iterations: Option<u64>,
    /// The simulated probe's world: where a probe move (G38.n, G75) makes contact, as a half-space
    /// of machine coordinates, e.g. `z<=-3.2` (a surface at Z −3.2 mm, contact below it) or
    /// `x>=50`; `z=-3.2` means `z<=-3.2`. Repeat for several surfaces. Without one the probe never
    /// trips.
    #[arg(long, value_name = "AXIS<=VALUE", value_parser = parse_probe_surface)]
    pub probe_surface: Vec<stanok_canon::setup::ProbeSurface>,
    /// Lab dialects: blank out the lab corpus's fixture annotations before reading (lines starting
    /// with `;`, and `//` to the end of a line), so that its files run as printed.
    #[arg(long)]
    pub strip_fixture_comments: bool,
    /// Lab dialects (2P32, GOST-20999): the value of corrector N in mm, e.g. `16=42` (repeat for
    /// several). Correctors not given hold 0.
    #[arg(long, value_name = "N=MM", value_parser = parse_corrector)]
    pub corrector: Vec<(u32, f64)>,
}

/// `16=42`: a lab corrector number and its value in mm.
pub fn parse_corrector(s: &str) -> Result<(u32, f64), String> {
    let (n, v) = s.split_once('=').ok_or("expected N=MM")?;
    let n: u32 = n
        .trim()
        .parse()
        .map_err(|_| format!("`{}` is not a corrector number", n.trim()))?;
    let v: f64 = v
        .trim()
        .parse()
        .map_err(|_| format!("`{}` is not a number", v.trim()))?;
    if !v.is_finite() {
        return Err("the value must be finite".into());
    }
    Ok((n, v))
}

/// `z<=-3.2`, `x>=50`, `z=-3.2` (= `<=`): a probe surface (machine coordinates, mm/deg).
pub fn parse_probe_surface(s: &str) -> Result<stanok_canon::setup::ProbeSurface, String> {
    let s = s.trim();
    let (axis_text, rest) = s.split_at(
        s.find(['<', '>', '='])
            .ok_or("expected AXIS<=VALUE, AXIS>=VALUE or AXIS=VALUE")?,
    );
    let axis = match axis_text.trim().to_ascii_uppercase().as_str() {
        "X" => 0,
        "Y" => 1,
        "Z" => 2,
        "A" => 3,
        "B" => 4,
        "C" => 5,
        "U" => 6,
        "V" => 7,
        "W" => 8,
        other => return Err(format!("unknown axis `{other}`")),
    };
    let (at_or_below, value) = if let Some(v) = rest.strip_prefix("<=") {
        (true, v)
    } else if let Some(v) = rest.strip_prefix(">=") {
        (false, v)
    } else if let Some(v) = rest.strip_prefix('=') {
        (true, v)
    } else {
        return Err("expected <=, >= or = after the axis".into());
    };
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("`{}` is not a number", value.trim()))?;
    if !value.is_finite() {
        return Err("the value must be finite".into());
    }
    Ok(stanok_canon::setup::ProbeSurface {
        axis,
        at_or_below,
        value,
    })
}

/// Stored parameters kept from run to run (a LinuxCNC parameter file, AxiOMA's $iPerm/$dPerm).
#[derive(Debug, Clone, Args)]
pub struct VarArgs {
    /// RS274/NGC: a LinuxCNC parameter file (.var) kept between runs, as LinuxCNC keeps its
    /// PARAMETER_FILE: read before the run in place of the machine's offsets (if it exists), written
    /// back after it with the offsets, G28/G30 positions, G92 and active system the program left
    /// (in --linuxcnc-units).
    #[arg(long, value_name = "FILE", conflicts_with = "offsets")]
    pub var: Option<PathBuf>,
    /// AxiOMA: the permanent parameters $iPerm[n] / $dPerm[n] kept between runs, as the control
    /// keeps them: a TOML file with [iperm] and [dperm] (`1 = 1500`), read before the run in place
    /// of the machine's (if it exists), written back after it with what the program left.
    #[arg(long, value_name = "FILE")]
    pub perm: Option<PathBuf>,
}

/// How `stanok run` moves the simulated machine.
#[derive(Debug, Clone, Args)]
pub struct MotionArgs {
    /// Servo (interpolation) period in milliseconds (0.01 … 1000).
    #[arg(long, value_name = "MS", default_value_t = 1.0)]
    pub servo_period: f64,
    /// Write the servo-rate setpoints to a CSV file, one line per servo period, columns
    /// `t,X,Y,Z[,A,B,C…],S,line`: time (s), the machine's axes (mm, degrees), the main spindle's
    /// commanded speed (rev/min; M3 positive, M4 negative, 0 when stopped) and the source line of
    /// the block being executed.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Feed override in percent (more than 0, at most 200).
    #[arg(long, value_name = "PERCENT", default_value_t = 100.0)]
    pub feed_override: f64,
    /// Rapid override in percent (more than 0, at most 100).
    #[arg(long, value_name = "PERCENT", default_value_t = 100.0)]
    pub rapid_override: f64,
    /// Feed hold: at machine time AT seconds the operator holds the feed; the machine brakes on
    /// the path, stands SECONDS, then resumes (`--feed-hold 2.5:1`).
    #[arg(long, value_name = "AT:SECONDS")]
    pub feed_hold: Option<String>,
    /// Override change at machine time T seconds, acting within the servo period on the motion
    /// being executed and on everything planned: `T:PERCENT` (feed, 0…200), `T:rapid=PERCENT`
    /// (0…100), `T:spindle=PERCENT` (50…120). Repeatable; the last feed and rapid values must not
    /// be 0 (the machine would stand for ever).
    #[arg(long, value_name = "T:PERCENT")]
    pub override_at: Vec<String>,
    /// Planner look-ahead window, path pieces (at least 2).
    #[arg(long, value_name = "PIECES", default_value_t = 1024)]
    pub lookahead: usize,
    /// Acceleration profile of every move, whatever the program selects: `soft` (jerk-limited,
    /// curvature-continuous corners) or `brisk`. Without it, as programmed (power-on BRISK).
    #[arg(long, value_enum, value_name = "PROFILE")]
    pub profile: Option<ProfileArg>,
}

/// `stanok run --profile`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ProfileArg {
    /// Jerk-limited S-curves (SOFT).
    Soft,
    /// Acceleration-limited trapezoids (BRISK).
    Brisk,
}
