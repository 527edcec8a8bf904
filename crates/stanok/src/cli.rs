//! Command-line syntax (clap derive).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Stanok: an open CNC control kernel.
#[derive(Debug, Parser)]
#[command(name = "stanok", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// Program language, when the file name does not say it (`.ngc` → rs274ngc; a name starting
/// `nc31-`, `2p32-`, `mc2101-` or `gost20999-` → that lab dialect; else axioma).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DialectArg {
    /// AxiOMA Control (ISO with Sinumerik-style keywords).
    Axioma,
    /// LinuxCNC RS274/NGC.
    Rs274ngc,
    /// Elektronika NC-31 (16K20F3 lathe): one address per frame, `*` groups.
    Nc31,
    /// 2P32 turning-milling centre (integers in 0.001 mm, X on the radius).
    #[value(name = "2p32")]
    P2p32,
    /// Elektronika MC2101 notation (6-digit increments in 0.01 mm).
    Mc2101,
    /// The GOST 20999-83 control of the lab collection (section 6.3).
    Gost20999,
    /// Mazatrol EIA/ISO, tool tip point control G43.4/G43.5.
    Mazatrol,
    /// Balt-System NC, 5-axis CVU programs.
    Balt,
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

/// Target dialect of `stanok convert`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TargetArg {
    /// LinuxCNC RS274/NGC.
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
    /// Built-in machine name (`mill`) or a machine-data TOML file.
    #[arg(long, default_value = "mill")]
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
    /// RS274/NGC: a directory searched for `name.ngc` when `o<name> call` names a subroutine the
    /// program does not define (LinuxCNC's SUBROUTINE_PATH); repeat for several, searched in order.
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
    /// with `;`, and `//` to the end of a line), so that `corpus/labs` files run as printed.
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
    /// Write the servo-rate setpoints to a CSV file: `t,X,Y,Z[,A,B,C…]` (the machine's axes;
    /// seconds, mm, degrees), one line per servo period.
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
        #[command(flatten)]
        machine: MachineArgs,
    },
    /// Run a program on the simulated machine and print the run report.
    Run {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
        #[command(flatten)]
        machine: MachineArgs,
        /// Print the report as one JSON object.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        var: VarArgs,
        #[command(flatten)]
        motion: MotionArgs,
        #[command(flatten)]
        stock: crate::stock::StockArgs,
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
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        var: VarArgs,
    },
    /// Draw the tool path: XY, XZ, YZ and isometric views on one SVG sheet.
    Plot {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
        /// Output SVG file (with --stock: a PNG of the stock after the run).
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        #[command(flatten)]
        machine: MachineArgs,
        #[command(flatten)]
        stock: crate::stock::StockArgs,
    },
    /// Convert a program to another dialect: written from its canonical commands (cycles,
    /// subprograms and compensation expanded; positions absolute in the start frame).
    Convert {
        /// The part program.
        file: PathBuf,
        #[arg(long, value_enum)]
        dialect: Option<DialectArg>,
        /// The dialect to write.
        #[arg(long, value_enum)]
        to: TargetArg,
        /// Output file (default: standard output).
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
        /// Largest deviation of the chords written for curves the target cannot express, mm.
        #[arg(long, value_name = "MM", default_value_t = 0.001)]
        chord_tolerance: f64,
        #[command(flatten)]
        machine: MachineArgs,
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
        #[command(flatten)]
        machine: MachineArgs,
    },
    /// Machine data: show what a machine is and what its control stores.
    Machine {
        #[command(subcommand)]
        command: MachineCommand,
    },
    /// Cutting data: the lab collection's method, step by step, with every table cell it uses.
    Cutting {
        #[command(subcommand)]
        command: CuttingCommand,
    },
}

#[derive(Debug, Subcommand)]
pub enum CuttingCommand {
    /// Turning (Lab 2): feed, Cv/x/y/m, Kv, cutting speed v, spindle speed n and the machine's n.
    Turn(TurnArgs),
}

/// Work material of `stanok cutting turn` (tables 2.7/2.8 rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MaterialArg {
    /// Carbon steel, C < 0.6 % (needs --sigma-b).
    CarbonSteel,
    /// Carbon steel, C > 0.6 % (needs --sigma-b).
    HighCarbonSteel,
    /// Free-machining or chromium steel (needs --sigma-b).
    FreeMachiningSteel,
    /// Chromium-nickel or Cr-Mo-V steel (needs --sigma-b).
    CrNiSteel,
    /// Grey cast iron (needs --hb).
    GreyIron,
    /// Malleable cast iron (needs --hb; the document has no Cv for it).
    MalleableIron,
}

/// Kind of turning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum OperationArg {
    /// External longitudinal turning.
    Longitudinal,
    /// Facing (cross turning).
    Facing,
    /// Boring.
    Boring,
    /// Parting-off.
    PartingOff,
    /// Grooving.
    Grooving,
    /// Form turning.
    FormTurning,
    /// Thread cutting (the document gives no formula).
    Threading,
}

/// Roughing or finishing, for a single --depth pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PassArg {
    /// Feed from table 2.4.
    Rough,
    /// Feed from table 2.5.
    Finish,
}

/// `stanok cutting turn`.
#[derive(Debug, Clone, Args)]
pub struct TurnArgs {
    /// Work material.
    #[arg(long, value_enum)]
    pub material: MaterialArg,
    /// Ultimate strength of a steel, MPa.
    #[arg(long, value_name = "MPA")]
    pub sigma_b: Option<f64>,
    /// Brinell hardness of a cast iron.
    #[arg(long, value_name = "HB")]
    pub hb: Option<f64>,
    /// Blank surface (K_nv): none, rolled, forging, cu-al, casting, casting-dirty.
    #[arg(long, default_value = "none")]
    pub surface: String,
    /// K_nv inside the surface's range (casting 0.8-0.85, casting-dirty 0.5-0.6); default the
    /// lower bound.
    #[arg(long, value_name = "K")]
    pub surface_factor: Option<f64>,
    /// Tool material grade: T5K10, T14K8, T15K6, T30K4, VK3, VK3M, VK4, VK6, VK6M, VK8, P6M5, P18, KhVG.
    #[arg(long, value_name = "GRADE")]
    pub tool_material: String,
    /// Kind of turning.
    #[arg(long, value_enum, default_value = "longitudinal")]
    pub operation: OperationArg,
    /// Work diameter before the first pass, mm.
    #[arg(long, value_name = "MM")]
    pub diameter: f64,
    /// Depth of cut of one pass, mm.
    #[arg(
        long,
        value_name = "MM",
        required_unless_present = "allowance",
        conflicts_with = "allowance"
    )]
    pub depth: Option<f64>,
    /// Roughing or finishing (with --depth).
    #[arg(long, value_enum, default_value = "rough")]
    pub pass: PassArg,
    /// Allowance per side, mm: split into a rough pass and finish passes (see --split).
    #[arg(long, value_name = "MM")]
    pub allowance: Option<f64>,
    /// Shares of the allowance per pass (0.7,0.3 or 0.7,0.2,0.1).
    #[arg(long, value_delimiter = ',', default_value = "0.7,0.3")]
    pub split: Vec<f64>,
    /// Feed of the (first) pass, mm/rev; default from table 2.4 (the range's lower bound).
    #[arg(long, value_name = "MM_PER_REV")]
    pub feed: Option<f64>,
    /// Feed of the finish passes, mm/rev; default from table 2.5.
    #[arg(long, value_name = "MM_PER_REV")]
    pub finish_feed: Option<f64>,
    /// Required roughness for table 2.5: Ra2.5, Rz20, Rz40, Rz80.
    #[arg(long)]
    pub roughness: Option<String>,
    /// Tool nose radius for table 2.5, mm (0.4, 0.8, 1.2, 1.6, 2.0, 2.4).
    #[arg(long, value_name = "MM")]
    pub nose_radius: Option<f64>,
    /// Tool life T, min (default 60; 120 for form cutters).
    #[arg(long, value_name = "MIN")]
    pub life: Option<f64>,
    /// Lathe centre height for the holder section, mm (16K20: 200).
    #[arg(long, value_name = "MM")]
    pub centre_height: Option<f64>,
    /// The machine's feeds, mm/rev, comma-separated: the feed is corrected down to one of them.
    #[arg(long, value_delimiter = ',', value_name = "LIST")]
    pub machine_feeds: Vec<f64>,
    /// The machine's spindle speeds, rpm, comma-separated: n_act is the largest ≤ n.
    #[arg(long, value_delimiter = ',', value_name = "LIST")]
    pub machine_speeds: Vec<f64>,
    /// Print the calculation as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Subcommand)]
pub enum MachineCommand {
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
    },
}
