//! The settings of one interpreter run that every front end shares: the program's syntax, the
//! machine's axes, tolerances, stored control data, search paths, limits. Each front end has its
//! own options beside these (machine parameters of its control); the registry (`stanok-interp`'s
//! `InterpOptions`) holds them all and hands each front end its part.

use stanok_canon::setup::ControlData;
use stanok_canon::{LengthUnits, Pose};
use stanok_syntax::Dialect;

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
    /// Most blocks executed in one run (loops included).
    pub max_blocks: u64,
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
            max_blocks: 200_000_000,
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
