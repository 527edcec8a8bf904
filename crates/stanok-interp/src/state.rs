//! The interpreter's persistent state (grbl's `parser_state_t`): modal groups, units, the work frame,
//! the current position, technology values. A block reads it, computes everything it will do, and
//! only then commits (see `block.rs`), so an erroneous block leaves this untouched.

use stanok_canon::{FeedMode, LengthUnits, Plane, Pose};

/// Group 1 / Interpolate: the motion mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionMode {
    /// G0.
    Rapid,
    /// G1.
    Linear,
    /// G2.
    ArcCw,
    /// G3.
    ArcCcw,
    /// RS274/NGC G80 (its power-on motion mode): axis words alone are an error.
    None,
}

/// G90/G91 (and G90.1/G91.1, G190/G191 for arc centres).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DistanceMode {
    /// Positions.
    Absolute,
    /// Increments.
    Incremental,
}

/// AxiOMA G60/G64 and RS274/NGC G61/G61.1/G64: kept for the planner (a later stage).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PathMode {
    /// G60 / G61.1: stop at every block end.
    ExactStop,
    /// RS274/NGC G61: exact path.
    ExactPath,
    /// G64 with optional blend tolerance P and naive-CAM tolerance Q (program units).
    Continuous {
        /// P, mm (0 = as fast as possible).
        blend_tolerance: f64,
    },
}

/// The work frame of the RS274/NGC chain (LinuxCNC, spec rs274ngc §3.1), in mm and degrees:
///
/// ```text
/// machine = Rot_R(p + g92) + g5x + tlo          p = Rot_−R(machine − g5x − tlo) − g92
/// ```
///
/// AxiOMA programs use the same structure with all terms zero until the coordinate-chain issue adds
/// its table offsets and frames.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkFrame {
    /// Active G54…G59.3 origin.
    pub g5x: Pose,
    /// G92/G52 offset (applied before the rotation).
    pub g92: Pose,
    /// Rotation about Z of the active coordinate system, degrees CCW.
    pub rotation_deg: f64,
    /// Tool length offset.
    pub tlo: Pose,
}

impl Default for WorkFrame {
    fn default() -> Self {
        WorkFrame {
            g5x: Pose::ZERO,
            g92: Pose::ZERO,
            rotation_deg: 0.0,
            tlo: Pose::ZERO,
        }
    }
}

impl WorkFrame {
    /// Program (work) coordinates → machine coordinates, mm.
    ///
    /// Written field by field (no `[f64; 9]` round trips: this runs two or three times per move),
    /// with the same operations in the same order as the formula, so results are bit-identical
    /// (`-0.0 + 0.0` is `+0.0` here too, which the LinuxCNC traces show).
    #[inline]
    pub fn to_machine(&self, p: &Pose) -> Pose {
        let mut v = add(p, &self.g92);
        if self.rotation_deg != 0.0 {
            let (s, c) = self.rotation_deg.to_radians().sin_cos();
            let (x, y) = (v.x, v.y);
            v.x = x * c - y * s;
            v.y = x * s + y * c;
        }
        add(&v, &add(&self.g5x, &self.tlo))
    }

    /// Machine coordinates → program (work) coordinates, mm.
    #[inline]
    pub fn to_program(&self, m: &Pose) -> Pose {
        let mut v = sub(m, &add(&self.g5x, &self.tlo));
        if self.rotation_deg != 0.0 {
            let (s, c) = (-self.rotation_deg).to_radians().sin_cos();
            let (x, y) = (v.x, v.y);
            v.x = x * c - y * s;
            v.y = x * s + y * c;
        }
        sub(&v, &self.g92)
    }

    /// Rotates a direction (no translation) from the program frame to the machine frame.
    pub fn rotate_to_machine(&self, d: [f64; 3]) -> [f64; 3] {
        if self.rotation_deg == 0.0 {
            return d;
        }
        let (s, c) = self.rotation_deg.to_radians().sin_cos();
        [d[0] * c - d[1] * s, d[0] * s + d[1] * c, d[2]]
    }
}

/// `a + b`, axis by axis.
#[inline(always)]
fn add(a: &Pose, b: &Pose) -> Pose {
    Pose {
        x: a.x + b.x,
        y: a.y + b.y,
        z: a.z + b.z,
        a: a.a + b.a,
        b: a.b + b.b,
        c: a.c + b.c,
        u: a.u + b.u,
        v: a.v + b.v,
        w: a.w + b.w,
    }
}

/// `a - b`, axis by axis.
#[inline(always)]
fn sub(a: &Pose, b: &Pose) -> Pose {
    Pose {
        x: a.x - b.x,
        y: a.y - b.y,
        z: a.z - b.z,
        a: a.a - b.a,
        b: a.b - b.b,
        c: a.c - b.c,
        u: a.u - b.u,
        v: a.v - b.v,
        w: a.w - b.w,
    }
}

/// Everything that persists from block to block. `Copy`: a block works on a copy (no heap data).
#[derive(Debug, Clone, Copy)]
pub struct ModalState {
    /// Interpolate group.
    pub motion: MotionMode,
    /// G17/G18/G19.
    pub plane: Plane,
    /// G90/G91.
    pub distance: DistanceMode,
    /// Arc centres: G90.1/G91.1 (RS274/NGC), G190/G191 (AxiOMA).
    pub arc_distance: DistanceMode,
    /// G20/G21 (G70/G71).
    pub units: LengthUnits,
    /// G93/G94/G95.
    pub feed_mode: FeedMode,
    /// F as programmed, converted to mm/min (G94), mm/rev (G95) or 1/min (G93).
    pub feed: f64,
    /// Commanded spindle speeds, rev/min, per spindle (0 = main).
    pub spindle_speed: [f64; 4],
    /// Spindle on/off per spindle.
    pub spindle_on: [bool; 4],
    /// Tool prepared by the last T word.
    pub selected_tool: Option<u32>,
    /// Tool in the spindle.
    pub current_tool: u32,
    /// G60/G64 family.
    pub path_mode: PathMode,
    /// AxiOMA BRISK (false) / SOFT (true).
    pub soft_acceleration: bool,
    /// RS274/NGC G98 (true) / G99; AxiOMA G98/G99.
    pub retract_to_initial: bool,
    /// RS274/NGC G7 (true) / G8.
    pub diameter_mode: bool,
    /// Mist (M7) and flood (M8).
    pub mist: bool,
    /// See `mist`.
    pub flood: bool,
    /// Active work offset number (1 = G54 … 9 = G59.3), 0 = none (AxiOMA G53).
    pub g5x_index: u8,
    /// The work frame.
    pub frame: WorkFrame,
    /// Where the tool is, machine coordinates, mm.
    pub position: Pose,
}

impl ModalState {
    /// Current position in program coordinates (mm).
    #[inline]
    pub fn program_position(&self) -> Pose {
        self.frame.to_program(&self.position)
    }
}
