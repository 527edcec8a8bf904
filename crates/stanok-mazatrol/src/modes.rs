//! The Mazatrol modal state beyond the core's: everything a block may change that a failing block
//! must give back. `Copy`, held in a `Journalled` cell (one copy on the first write of a block).

use crate::codes::Series;
use crate::macro_b::MVal;

/// A canned cycle in force (group 01 cycle code and its data, `docs` §10, §11.8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleModes {
    /// The cycle's G code × 10.
    pub code: u32,
    /// The initial level (drilling-axis program coordinate when the cycle mode began).
    pub initial: f64,
    /// R: the R level (absolute, program coordinates of the drilling axis).
    pub r: Option<f64>,
    /// Z: the bottom (absolute).
    pub z: Option<f64>,
    /// Q in mm (peck or shift).
    pub q: f64,
    /// P dwell, seconds.
    pub dwell: f64,
    /// Whether R and Z were given in G91 (increments: R from the initial level, Z from R).
    pub incremental: bool,
    /// R as written in G91 (from the initial level).
    pub r_inc: f64,
    /// Z as written in G91 (from R).
    pub z_inc: f64,
}

/// The first blocks of the T-series multiple cycles, kept until their second block.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TurnData {
    /// G71: depth of cut Δd, retract e (radius, mm).
    pub g71: (f64, f64),
    /// G72: depth of cut Δd, retract e.
    pub g72: (f64, f64),
    /// G73: relief Δi (X, radius), Δk (Z), passes d.
    pub g73: (f64, f64, u32),
    /// G74: retract e.
    pub g74: f64,
    /// G75: retract e.
    pub g75: f64,
    /// G76: finishing passes m, chamfer tenths r, angle a, least infeed Δdmin, allowance d.
    pub g76: (u32, u32, f64, f64, f64),
}

/// Cutter / nose radius compensation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CompMode {
    /// G40.
    #[default]
    Off,
    /// G41.
    Left,
    /// G42.
    Right,
    /// G46 (T): the side is chosen at start-up.
    Auto,
}

/// G51 scaling: centre (program X Y Z) and factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scaling {
    /// Centre, program coordinates, mm.
    pub centre: [f64; 3],
    /// Factors per axis (negative mirrors).
    pub k: [f64; 3],
}

/// Which work system is selected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorkSystem {
    /// G54 … G59 (1 … 6).
    Standard(u8),
    /// G54.1 P1 … P48.
    Extra(u8),
}

/// A G66 / G66.1 modal call in force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalCall {
    /// G66 (false) or G66.1 (true).
    pub every_block: bool,
    /// The called program.
    pub program: u32,
    /// Repeats L.
    pub repeats: u32,
    /// The arguments (#1 … #33).
    pub args: [MVal; 33],
    /// The macro level it was programmed at: it applies to the blocks of that level only (the
    /// called macro's own blocks are not called again).
    pub level: usize,
}

/// Spindle direction (for the cycles' reversal and restore).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Turning {
    /// M05.
    #[default]
    Stopped,
    /// M03.
    Cw,
    /// M04.
    Ccw,
}

/// The Mazatrol modes (`docs` §3.1 besides what the core's `ModalState` holds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Modes {
    /// The series (machine data; constant).
    pub series: Series,
    /// T: G16, the Z–C plane.
    pub plane_zc: bool,
    /// T: G122.1, X on the radius (false: G123.1, diameter).
    pub x_radius: bool,
    /// T: G122, polar coordinate input.
    pub polar_input: bool,
    /// T: G12.1 polar interpolation.
    pub polar: bool,
    /// T: G07.1 cylindrical interpolation radius (None: off).
    pub cylinder: Option<f64>,
    /// T: G96 surface speed, m/min (None: G97).
    pub css: Option<f64>,
    /// T: G50 S, the maximum rpm.
    pub rpm_clamp: Option<f64>,
    /// The canned cycle in force.
    pub cycle: Option<CycleModes>,
    /// G98 (true) or G99.
    pub return_initial: bool,
    /// Compensation mode and its radius (mm).
    pub comp: CompMode,
    /// The D number of G41/G42 (M).
    pub comp_d: u32,
    /// G51.
    pub scaling: Option<Scaling>,
    /// G51.1 mirror per axis X Y Z: the mirror's centre.
    pub mirror: [Option<f64>; 3],
    /// G68 (M): plane centre (a, b) and angle, degrees.
    pub rotation: Option<([f64; 2], f64)>,
    /// G68.5: pole and axis-angle (unit axis, degrees), composed when several are given.
    pub rotation3d: Option<([f64; 3], [[f64; 3]; 3])>,
    /// G92.5 (M): rotation about (x, y) of the work system, degrees.
    pub work_rotation: Option<([f64; 2], f64)>,
    /// G68 (T): the facing turret's X mirror.
    pub turret_mirror: bool,
    /// The selected work system.
    pub work: WorkSystem,
    /// G53.5 (T): the MAZATROL coordinate system in force.
    pub mazatrol_wpc: bool,
    /// G52 local shift, mm (X Y Z A B C).
    pub local: [f64; 6],
    /// G92 / G50 shift, mm.
    pub g92: [f64; 6],
    /// G22 area (machine X Y Z min and max) and whether it is on.
    pub stroke: Option<([f64; 3], [f64; 3])>,
    /// G22 in force.
    pub stroke_on: bool,
    /// G61 / G61.1 / G62 / G63 / G64 × 10.
    pub path: u32,
    /// G66 / G66.1.
    pub modal_call: Option<ModalCall>,
    /// G109 L (T).
    pub sequence: u8,
    /// G110 in force (T).
    pub cross: bool,
    /// The last G28/G30 intermediate point (machine), for G29.
    pub intermediate: Option<[f64; 9]>,
    /// G31's stop, work coordinates (program units).
    pub skip: [f64; 6],
    /// The turning spindle's direction (M03/M04/M05).
    pub spindle: Turning,
    /// The milling spindle's (T: M203/M204/M205).
    pub mill_spindle: Turning,
    /// M29 given: the next tapping cycle is rigid.
    pub rigid: bool,
    /// T-series: the tool offset number in force (T tt oo), 0 = none.
    pub t_offset: u32,
    /// G62 warned once.
    pub warned_g62: bool,
    /// Addresses of the block before for #4102…#4120: B D F H M N O S T.
    pub last_address: [MVal; 9],
    /// The program number of the program being run (O).
    pub program: MVal,
    /// The group-01 code in force × 10 (G00 … G03, G02.1/G03.1, G32–G34, G77–G79; a canned
    /// cycle is `cycle`).
    pub motion: u32,
    /// The thread lead of G32/G33/G34/G78, mm per revolution.
    pub lead: f64,
    /// G34's lead change per revolution, mm.
    pub lead_change: f64,
    /// The T-series multiple cycles' first blocks.
    pub turn: TurnData,
}

impl Modes {
    /// Power-on modes of a series.
    pub fn power_on(series: Series) -> Self {
        Modes {
            series,
            plane_zc: false,
            x_radius: false,
            polar_input: false,
            polar: false,
            cylinder: None,
            css: None,
            rpm_clamp: None,
            cycle: None,
            return_initial: true,
            comp: CompMode::Off,
            comp_d: 0,
            scaling: None,
            mirror: [None; 3],
            rotation: None,
            rotation3d: None,
            work_rotation: None,
            turret_mirror: false,
            work: WorkSystem::Standard(1),
            mazatrol_wpc: false,
            local: [0.0; 6],
            g92: [0.0; 6],
            stroke: None,
            stroke_on: false,
            path: 640,
            modal_call: None,
            sequence: 1,
            cross: false,
            intermediate: None,
            skip: [0.0; 6],
            spindle: Turning::Stopped,
            mill_spindle: Turning::Stopped,
            rigid: false,
            t_offset: 0,
            warned_g62: false,
            last_address: [None; 9],
            program: None,
            motion: 0,
            lead: 0.0,
            lead_change: 0.0,
            turn: TurnData {
                g71: (1.0, 0.5),
                g72: (1.0, 0.5),
                g73: (0.0, 0.0, 1),
                g74: 0.0,
                g75: 0.0,
                g76: (1, 0, 60.0, 0.0, 0.0),
            },
        }
    }

    /// True on the T-series.
    pub fn t(&self) -> bool {
        self.series == Series::T
    }
}

impl Default for Modes {
    fn default() -> Self {
        Modes::power_on(Series::M)
    }
}
