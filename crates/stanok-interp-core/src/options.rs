//! The settings of one interpreter run that every front end shares: the program's syntax, the
//! machine's axes, tolerances, stored control data, search paths, limits. Each front end has its
//! own options beside these (machine parameters of its control); the registry (`stanok-interp`'s
//! `InterpOptions`) holds them all and hands each front end its part.

use stanok_canon::setup::ControlData;
use stanok_canon::{LengthUnits, Pose};
use stanok_syntax::Dialect;

/// Default of [`CoreOptions::max_blocks`]: 50 million lines, five times a 10-million-block
/// CAM program; a runaway program reaches it in seconds (see `docs/robustness.md`).
pub const DEFAULT_MAX_BLOCKS: u64 = 50_000_000;
/// Default of [`CoreOptions::max_repeated_lines`]: a million lines read again (a runaway loop
/// stops after one to two seconds of CPU in a release build, whatever the size of its body).
pub const DEFAULT_MAX_REPEATED_LINES: u64 = 1_000_000;
/// Default of [`CoreOptions::max_total_loop_iterations`]: a million passes per run, as many as
/// one loop may make (three nested `repeat [1000]` stop after about a second of CPU in a release
/// build; a runaway loop that moves, after a few seconds of `stanok run`).
pub const DEFAULT_MAX_TOTAL_LOOP_ITERATIONS: u64 = 1_000_000;
/// Default of [`CoreOptions::max_nesting`].
pub const DEFAULT_MAX_NESTING: usize = 1000;
/// Default of [`CoreOptions::max_diagnostics_per_line`].
pub const DEFAULT_MAX_DIAGNOSTICS_PER_LINE: usize = 10;

/// Settings of one interpreter run common to all front ends.
#[derive(Debug, Clone)]
pub struct CoreOptions {
    /// Program language: selects the line parser (`stanok_syntax::BlockReader`). The core never
    /// looks at it otherwise; the registry chose the front end by it.
    pub dialect: Dialect,
    /// Which of X Y Z A B C U V W the machine has.
    pub axes: [bool; 9],
    /// Where the tool is at program start, machine coordinates, mm.
    pub initial_position: Pose,
    /// Units at power-on, for the front ends that take them from the machine (RS274/NGC: the
    /// machine's units; the others start in mm).
    pub initial_units: LengthUnits,
    /// The machine's arc tolerance, mm (machine data): AxiOMA errors 621/622/623 and the centre
    /// correction, and the other controls' arc checks.
    pub arc_tolerance_mm: f64,
    /// Deepest subroutine nesting.
    pub max_call_depth: usize,
    /// Most iterations of one loop of the program's control flow.
    pub max_loop_iterations: u64,
    /// Most loop iterations of one run, all loops together (nested loops multiply: three nested
    /// `repeat [1000]` are 10⁹ passes, each under the per-loop bound). Front ends with loops
    /// count their passes against it.
    pub max_total_loop_iterations: u64,
    /// Most lines one run reads: executed blocks, control-flow lines and lines skipped by a false
    /// condition alike, each pass of a loop counting its lines again (the work of a run, whatever
    /// its lines do). Counted by [`crate::Core::read_line`].
    pub max_blocks: u64,
    /// Most lines one run reads *again*: loop passes, subroutine calls, jumps back (every line
    /// below the furthest point read, and every line of a file a call opened).
    pub max_repeated_lines: u64,
    /// Deepest nesting of the program's control structures (front ends with nested constructs
    /// bound them by it).
    pub max_nesting: usize,
    /// Longest line kept, bytes; the rest of a longer line is an error ([`crate::Source`]).
    pub max_line_bytes: usize,
    /// Most bytes of a program read (the program and each file a call opens).
    pub max_program_bytes: u64,
    /// Most diagnostics kept for one line (warnings and, in `check`, errors); the rest are
    /// counted in a note on the last one.
    pub max_diagnostics_per_line: usize,
    /// Skip erroneous blocks and go on (for `stanok check`).
    pub continue_after_error: bool,
    /// Directories searched, in order, for subroutine files (RS274/NGC `name.ngc` when `o<name>
    /// call` names a subroutine the program does not define, LinuxCNC's SUBROUTINE_PATH; the lab
    /// controls' subprogram library).
    pub subroutine_path: Vec<std::path::PathBuf>,
    /// Block delete switch: when on, lines starting with `/` are skipped. Off by default, as in
    /// LinuxCNC (the operator turns it on).
    pub block_delete: bool,
    /// With `continue_after_error`: stop after this many errors.
    pub max_errors: usize,
    /// Stored control data: tool table, offset tables, home positions, preset parameters.
    pub control: ControlData,
    /// Axes that may be programmed as diameters (AxiOMA G10; the transverse axis of a lathe).
    pub diameter_axes: [bool; 9],
    /// Two sets of coordinates that a kinematic transformation makes interdependent (the AxiOMA
    /// manual's "biped": X/Y produced by V/W): a block may program one set or the other, never
    /// both (AxiOMA error 653, spec axioma-1 §7.1). None on the built-in machines.
    pub coupled_coordinates: Option<([bool; 9], [bool; 9])>,
    /// The operator's optional-stop switch: AxiOMA M01 stops only when it is on. Default on.
    pub optional_stop: bool,
    /// The machine's 5-axis kinematics (without a tool) when it allows tool-centre-point control
    /// (AxiOMA TRAORI, Balt-System CVU, Mazatrol G43.4/G43.5); None = not allowed (AxiOMA 654).
    pub five_axis: Option<stanok_kin::FiveAxis>,
}

impl CoreOptions {
    /// Defaults for a dialect: all nine axes, start at the origin, mm.
    pub fn new(dialect: Dialect) -> Self {
        CoreOptions {
            dialect,
            axes: [true; 9],
            initial_position: Pose::ZERO,
            initial_units: LengthUnits::Millimetres,
            arc_tolerance_mm: 0.01,
            max_call_depth: 64,
            max_loop_iterations: 1_000_000,
            max_total_loop_iterations: DEFAULT_MAX_TOTAL_LOOP_ITERATIONS,
            max_blocks: DEFAULT_MAX_BLOCKS,
            max_repeated_lines: DEFAULT_MAX_REPEATED_LINES,
            max_nesting: DEFAULT_MAX_NESTING,
            max_line_bytes: stanok_syntax::MAX_LINE_BYTES,
            max_program_bytes: stanok_syntax::MAX_PROGRAM_BYTES,
            max_diagnostics_per_line: DEFAULT_MAX_DIAGNOSTICS_PER_LINE,
            continue_after_error: false,
            block_delete: false,
            subroutine_path: Vec::new(),
            max_errors: 100,
            control: ControlData::default(),
            diameter_axes: [true, false, false, false, false, false, false, false, false],
            coupled_coordinates: None,
            optional_stop: true,
            five_axis: None,
        }
    }
}
