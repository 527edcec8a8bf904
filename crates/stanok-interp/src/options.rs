//! The settings of one interpreter run: the options every front end shares
//! (`stanok_interp_core::CoreOptions`) and each front end's own, in one struct for the callers.
//! `Interpreter::new` hands each front end its part.

use stanok_axioma::AxiomaMachineParams;
use stanok_canon::setup::ControlData;
use stanok_canon::{LengthUnits, Pose};
use stanok_interp_core::CoreOptions;
use stanok_labs::{LabMachineParams, LabOptions};
use stanok_mazatrol::MazatrolParams;
use stanok_rs274::Rs274Options;
use stanok_syntax::Dialect;

/// Settings of one interpreter run.
#[derive(Debug, Clone)]
pub struct InterpOptions {
    /// Program language.
    pub dialect: Dialect,
    /// Which of X Y Z A B C U V W the machine has.
    pub axes: [bool; 9],
    /// Where the tool is at program start, machine coordinates, mm.
    pub initial_position: Pose,
    /// Units at power-on (RS274/NGC: the machine's units; AxiOMA: G71).
    pub initial_units: LengthUnits,
    /// AxiOMA arc tolerance for errors 621/622/623 and the centre correction, mm (machine data);
    /// the arc tolerance of the other controls but RS274/NGC.
    pub arc_tolerance_mm: f64,
    /// RS274/NGC arc tolerance T in mm; `None` = the document's 0.0005 in / 0.005 mm by units.
    pub rs274_arc_tolerance_mm: Option<f64>,
    /// RS274/NGC without `rs274_arc_tolerance_mm`: LinuxCNC 2.9's default T (0.002828 in /
    /// 0.02828 mm) instead of the document's.
    pub rs274_linuxcnc_arc_tolerance: bool,
    /// Deepest subroutine nesting (RS274/NGC).
    pub max_call_depth: usize,
    /// Most iterations of one loop (RS274/NGC while/do/repeat, AxiOMA for/while/do).
    pub max_loop_iterations: u64,
    /// Most loop iterations of one run, all loops together (nested loops multiply: three nested
    /// `repeat [1000]` are 10⁹ passes, each under the per-loop bound).
    pub max_total_loop_iterations: u64,
    /// Most lines one run reads: executed blocks, control-flow lines and lines skipped by a false
    /// condition alike, each pass of a loop counting its lines again (the work of a run, whatever
    /// its lines do).
    pub max_blocks: u64,
    /// Most lines one run reads *again*: loop passes, subroutine calls, jumps back (every line
    /// below the furthest point read, and every line of a subroutine file).
    pub max_repeated_lines: u64,
    /// Deepest nesting of control structures (RS274/NGC O-word if/while/do/repeat, AxiOMA HLL
    /// `{ }` blocks and constructs).
    pub max_nesting: usize,
    /// Longest line kept, bytes; the rest of a longer line is an error.
    pub max_line_bytes: usize,
    /// Most bytes of a program read (main program and each subroutine file).
    pub max_program_bytes: u64,
    /// Most diagnostics kept for one line (warnings and, in `check`, errors); the rest are
    /// counted in a note on the last one.
    pub max_diagnostics_per_line: usize,
    /// Skip erroneous blocks and go on (for `stanok check`).
    pub continue_after_error: bool,
    /// RS274/NGC user M codes M100–M199: passed to the machine as auxiliary functions when true.
    /// False (default) rejects them as "Unknown m code", as LinuxCNC does without an executable
    /// of that name on its user M-code path (its standalone interpreter has none).
    pub user_m_codes: bool,
    /// RS274/NGC: directories searched, in order, for `name.ngc` when `o<name> call` names a
    /// subroutine the program does not define (LinuxCNC's SUBROUTINE_PATH).
    pub subroutine_path: Vec<std::path::PathBuf>,
    /// RS274/NGC block delete switch: when on, lines starting with `/` are skipped. Off by
    /// default, as in LinuxCNC (the operator turns it on).
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
    /// RS274/NGC: the machine's length unit (LinuxCNC `[TRAJ]LINEAR_UNITS`), in which numbered
    /// parameters hold lengths (`#5161…`, `#5211…`, `#5221…`, `#5401…`). LinuxCNC's standalone
    /// `rs274` works in inches.
    pub rs274_machine_units: LengthUnits,
    /// RS274/NGC: G92 offsets survive M2/M30 and the run (LinuxCNC's default); false is
    /// LinuxCNC's `DISABLE_G92_PERSISTENCE`: program end cancels them as G92.1 does.
    pub g92_persistence: bool,
    /// AxiOMA machine parameters of compensation, cycles and PLC outputs (spec axioma-3).
    pub axioma: AxiomaMachineParams,
    /// The operator's optional-stop switch: AxiOMA M01 stops only when it is on. Default on.
    pub optional_stop: bool,
    /// Machine data of the lab controls (NC-31, 2P32, MC2101, GOST-20999): correctors, turret
    /// codes, work offsets, gearbox table.
    pub labs: LabMachineParams,
    /// Lab dialects: blank out the lab corpus's fixture annotations (`;` lines, `//` to the end of
    /// a line) before reading; they are not program text of these controls. Off by default.
    pub strip_fixture_comments: bool,
    /// The machine's 5-axis kinematics (without a tool) when it allows tool-centre-point control
    /// (AxiOMA TRAORI, Balt-System CVU, Mazatrol G43.4/G43.5); None = not allowed (AxiOMA 654).
    pub five_axis: Option<stanok_kin::FiveAxis>,
    /// Mazatrol TTPC programs X Y Z in the workpiece frame (parameter 1, spec mazatrol §4.2)
    /// instead of the table frame (0, the default). It wins over `mazatrol.ttpc_workpiece_frame`.
    pub ttpc_workpiece_frame: bool,
    /// The Mazatrol control's parameters (machine data `[mazatrol]`): the series, the decimal
    /// point type, cycle clearances (`docs/dialects/mazatrol-eia.md` §1).
    pub mazatrol: MazatrolParams,
}

impl InterpOptions {
    /// Defaults for a dialect: all nine axes, start at the origin, mm.
    pub fn new(dialect: Dialect) -> Self {
        let core = CoreOptions::new(dialect);
        let rs274 = Rs274Options::default();
        InterpOptions {
            dialect,
            axes: core.axes,
            initial_position: core.initial_position,
            initial_units: core.initial_units,
            arc_tolerance_mm: core.arc_tolerance_mm,
            rs274_arc_tolerance_mm: rs274.arc_tolerance_mm,
            rs274_linuxcnc_arc_tolerance: rs274.linuxcnc_arc_tolerance,
            max_call_depth: core.max_call_depth,
            max_loop_iterations: core.max_loop_iterations,
            max_total_loop_iterations: core.max_total_loop_iterations,
            max_blocks: core.max_blocks,
            max_repeated_lines: core.max_repeated_lines,
            max_nesting: core.max_nesting,
            max_line_bytes: core.max_line_bytes,
            max_program_bytes: core.max_program_bytes,
            max_diagnostics_per_line: core.max_diagnostics_per_line,
            continue_after_error: core.continue_after_error,
            block_delete: core.block_delete,
            subroutine_path: core.subroutine_path,
            user_m_codes: rs274.user_m_codes,
            max_errors: core.max_errors,
            control: core.control,
            diameter_axes: core.diameter_axes,
            coupled_coordinates: core.coupled_coordinates,
            rs274_machine_units: rs274.machine_units,
            g92_persistence: rs274.g92_persistence,
            axioma: AxiomaMachineParams::default(),
            optional_stop: core.optional_stop,
            labs: LabMachineParams::default(),
            strip_fixture_comments: false,
            five_axis: core.five_axis,
            ttpc_workpiece_frame: false,
            mazatrol: MazatrolParams::default(),
        }
    }

    /// The options every front end shares.
    pub fn core(&self) -> CoreOptions {
        CoreOptions {
            dialect: self.dialect,
            axes: self.axes,
            initial_position: self.initial_position,
            initial_units: self.initial_units,
            arc_tolerance_mm: self.arc_tolerance_mm,
            max_call_depth: self.max_call_depth,
            max_loop_iterations: self.max_loop_iterations,
            max_total_loop_iterations: self.max_total_loop_iterations,
            max_blocks: self.max_blocks,
            max_repeated_lines: self.max_repeated_lines,
            max_nesting: self.max_nesting,
            max_line_bytes: self.max_line_bytes,
            max_program_bytes: self.max_program_bytes,
            max_diagnostics_per_line: self.max_diagnostics_per_line,
            continue_after_error: self.continue_after_error,
            subroutine_path: self.subroutine_path.clone(),
            block_delete: self.block_delete,
            max_errors: self.max_errors,
            control: self.control.clone(),
            diameter_axes: self.diameter_axes,
            coupled_coordinates: self.coupled_coordinates,
            optional_stop: self.optional_stop,
            five_axis: self.five_axis.clone(),
        }
    }

    /// RS274/NGC's own options.
    pub fn rs274(&self) -> Rs274Options {
        Rs274Options {
            arc_tolerance_mm: self.rs274_arc_tolerance_mm,
            linuxcnc_arc_tolerance: self.rs274_linuxcnc_arc_tolerance,
            user_m_codes: self.user_m_codes,
            machine_units: self.rs274_machine_units,
            g92_persistence: self.g92_persistence,
        }
    }

    /// The Mazatrol front end's parameters.
    pub fn mazatrol(&self) -> MazatrolParams {
        MazatrolParams {
            ttpc_workpiece_frame: self.ttpc_workpiece_frame,
            ..self.mazatrol.clone()
        }
    }

    /// The lab controls' options.
    pub fn lab(&self) -> LabOptions {
        LabOptions {
            core: self.core(),
            labs: self.labs.clone(),
            strip_fixture_comments: self.strip_fixture_comments,
        }
    }
}
