//! The canonical machining commands.
//!
//! Frames and units, for every field below unless its doc says otherwise:
//! * positions are **machine Cartesian** coordinates: all offsets, frames, units and tool data have
//!   already been applied by the interpreter;
//! * linear quantities in **millimetres**, angles (A, B, C) in **degrees**, time in **seconds**, feed in
//!   **mm/min** (or deg/min for a rotary-only move), spindle speed in **rev/min**.
//!
//! The few state items (`UseLengthUnits`, `SetG5xOffset`, …) do not change the meaning of any position
//! in the stream; they exist so that printers can re-express machine positions the way a control's
//! operator screen or LinuxCNC's `rs274` would (work frame, program units).

use serde::Serialize;

pub use crate::quantities::*;

/// A straight move.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LineMove {
    /// Where the move starts (the previous motion's end or the initial position).
    pub start: Pose,
    /// Where it ends.
    pub end: Pose,
    /// Path feed in mm/min for feed moves; 0 for rapids (the machine's rapid rate applies).
    pub feed: f64,
    /// How the feed follows the machine (the law in force for rapids).
    #[serde(skip_serializing_if = "FeedLaw::is_per_minute")]
    pub law: FeedLaw,
}

impl LineMove {
    /// The move as executed when it stops early at `stop` (a probe's contact point), or as
    /// programmed without one.
    pub fn stopped_at(&self, stop: Option<Pose>) -> LineMove {
        LineMove {
            end: stop.unwrap_or(self.end),
            ..self.clone()
        }
    }
}

/// A circular or helical move.
///
/// Geometry: the tool turns about the line through `centre` along the unit vector `axis`, in the
/// right-handed (counter-clockwise) sense about `axis`; a clockwise arc simply has `axis` pointing the
/// other way. The planar sweep is the angle from `start` to `end` projected on the plane normal to
/// `axis` (in (0°, 360°]; 360° when the projections coincide), plus `turns − 1` full turns. The
/// component of the motion along `axis`, and every axis other than X Y Z, moves linearly with the swept
/// angle (helix). When the start and end radii differ (within the tolerance the interpreter accepted)
/// the radius changes linearly with the angle, so that `end` is reached exactly (LinuxCNC's spiral).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArcMove {
    /// Start pose.
    pub start: Pose,
    /// End pose.
    pub end: Pose,
    /// A point on the rotation axis, machine X Y Z, mm (the one in the plane of `start`).
    pub centre: [f64; 3],
    /// Unit vector of the rotation axis; motion is counter-clockwise about it.
    pub axis: [f64; 3],
    /// Number of turns as LinuxCNC counts them: 1 = the programmed arc only, n = arc + (n−1) full turns.
    pub turns: u32,
    /// The programming plane the arc was written in (for printers; `axis` is ± its normal unless a
    /// frame rotated it).
    pub plane: Plane,
    /// Path feed, mm/min.
    pub feed: f64,
    /// How the feed follows the machine.
    #[serde(skip_serializing_if = "FeedLaw::is_per_minute")]
    pub law: FeedLaw,
}

/// A rational B-spline (NURBS) curve in machine X Y Z: the one exact form every spline of both
/// controls is handed over in (LinuxCNC G5 cubic and G5.1 quadratic Béziers, G5.2 NURBS; AxiOMA
/// ASPLINE/CSPLINE pieces as Béziers and BSPLINE as NURBS).
///
/// Curve: C(u) = Σ N_{i,p}(u)·w_i·P_i / Σ N_{i,p}(u)·w_i for u in [knots[p], knots[n]] where n =
/// `control_points.len()`, p = `degree` and `knots.len() == n + p + 1` (clamped: the first and last
/// p + 1 knots are equal, so C starts at the first control point and ends at the last). The axes
/// other than X Y Z move linearly from `start` to `end` with the curve's arc length.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SplineMove {
    /// Start pose (= first control point in X Y Z).
    pub start: Pose,
    /// End pose (= last control point in X Y Z).
    pub end: Pose,
    /// Degree p ≥ 1 (order p + 1).
    pub degree: u8,
    /// Control points, machine X Y Z, mm.
    pub control_points: Vec<[f64; 3]>,
    /// One positive weight per control point.
    pub weights: Vec<f64>,
    /// Non-decreasing knot vector, `control_points.len() + degree + 1` values.
    pub knots: Vec<f64>,
    /// The programming plane it was written in (printers).
    pub plane: Plane,
    /// Path feed, mm/min.
    pub feed: f64,
    /// How the feed follows the machine.
    #[serde(skip_serializing_if = "FeedLaw::is_per_minute")]
    pub law: FeedLaw,
}

/// The program-log operations of LinuxCNC's comment commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum LogAction {
    /// `(LOGOPEN,file)`: start a new log file.
    Open,
    /// `(LOGAPPEND,file)`: continue an existing one.
    Append,
    /// `(LOGCLOSE)`.
    Close,
    /// `(LOG,text)`: write a line.
    Write,
}

/// What a probe move does on contact (LinuxCNC G38.2–G38.5, AxiOMA G75).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ProbeKind {
    /// G38.2: stop on contact; error if the target is reached without contact.
    TowardErrorIfNone,
    /// G38.3: stop on contact; no error without one.
    Toward,
    /// G38.4: stop on loss of contact; error if none.
    AwayErrorIfNone,
    /// G38.5: stop on loss of contact; no error without one.
    Away,
}

/// How consecutive moves are joined (LinuxCNC G61/G61.1/G64, AxiOMA G60/G64). LinuxCNC's own
/// naming: G61 is CANON_EXACT_PATH, G61.1 CANON_EXACT_STOP (its `rs274` trace says so).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum PathMode {
    /// LinuxCNC G61.1 / AxiOMA G60: stop exactly at every block end.
    ExactStop,
    /// LinuxCNC G61: follow the path exactly (no blending) but without stopping where the path is
    /// smooth.
    ExactPath,
    /// G64: blend corners, staying within `tolerance` mm of the path (0 = as fast as possible, no
    /// tolerance given).
    Continuous {
        /// Path tolerance P, mm; 0 = none given.
        tolerance: f64,
    },
}

/// The shape of the speed profile (AxiOMA BRISK/SOFT).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum AccelerationProfile {
    /// BRISK: acceleration-limited, trapezoidal velocity.
    Brisk,
    /// SOFT: jerk-limited, S-curve velocity.
    Soft,
}

/// How the tool orientation moves between the start and the end of a block under tool-centre-point
/// control (AxiOMA ORIAXES / ORIVECT, spec axioma-4 §6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum OrientationInterpolation {
    /// The rotary axes move linearly with the path parameter (ORIAXES, direct axis programming,
    /// Balt-System CVU=1 and Mazatrol tool-tip control).
    Axes,
    /// The tool vector turns on the great circle from its start to its end direction (ORIVECT).
    Vector,
}

/// The largest a [`Canon`] may be, bytes. Every command of every program is moved through the
/// interpreter's queue and the later stages by value, so its size is paid per block: the common
/// variants (lines, arcs, `Init`) set it, and rare large payloads (a spline's vectors, the probe's
/// contact, the G96 law in a feed law) are boxed to stay within it (docs/decisions.md, issue 26;
/// docs/performance.md measures the cost per block).
pub const CANON_MAX_BYTES: usize = 240;

const _: () = assert!(std::mem::size_of::<Canon>() <= CANON_MAX_BYTES);

/// One canonical machining command. Exhaustive on purpose: a new variant makes every consumer decide.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Canon {
    /// The control's state when the program starts (always the first command of a stream).
    Init {
        /// Where the tool is.
        position: Pose,
        /// Program units in force.
        units: LengthUnits,
        /// Active work offset number (1 = G54 … 9 = G59.3); 0 = none (AxiOMA G53).
        g5x_index: u8,
        /// That offset, mm.
        g5x_offset: Pose,
        /// G92/G52 (LinuxCNC) or programmed shift (AxiOMA), mm.
        g92_offset: Pose,
        /// Rotation of the work frame about Z, degrees.
        xy_rotation: f64,
    },
    /// G0: straight move at the rapid rate.
    StraightTraverse(LineMove),
    /// G1: straight move at the feed.
    StraightFeed(LineMove),
    /// G2/G3: arc or helix at the feed.
    ArcFeed(ArcMove),
    /// G5/G5.1/G5.2 (LinuxCNC), ASPLINE/CSPLINE/BSPLINE (AxiOMA): a spline at the feed (boxed:
    /// rare and large, see [`CANON_MAX_BYTES`]).
    SplineFeed(Box<SplineMove>),
    /// A probe move (G38.n, G75): straight towards `end` until the probe trips (or stops tripping).
    /// The machine answers with the trip point; the interpreter's later blocks read it.
    StraightProbe {
        /// The move as programmed (to the target).
        motion: LineMove,
        /// Stop condition and error rule.
        probe: ProbeKind,
        /// Where the probe changes state according to the probe surfaces the run was configured
        /// with (the same data the machine is given); None = it runs to the end without doing so.
        /// Boxed: rare, and it would make every command 80 bytes larger ([`CANON_MAX_BYTES`]).
        contact: Option<Box<Pose>>,
    },
    /// G33.1 (and G84/G74 in rigid mode): spindle-synchronised feed to `end`, spindle reversal,
    /// synchronised return to `start`. The pitch is the one of the `StartSpindleSync` before it,
    /// stated in `law`.
    RigidTap {
        /// Where the tap starts and returns to.
        start: Pose,
        /// The bottom of the hole.
        end: Pose,
        /// LinuxCNC's scale factor of the return (1 = same pitch).
        scale: f64,
        /// How the feed follows the spindle (`FeedLaw::SpindleSync` with the pitch).
        #[serde(skip_serializing_if = "FeedLaw::is_per_minute")]
        law: FeedLaw,
    },
    /// G33/G76/G33.1 and AxiOMA G276: the following feed moves advance `pitch` per spindle revolution.
    StartSpindleSync {
        /// mm per revolution along the path.
        pitch: f64,
        /// LinuxCNC's `wait_for_index` = false form (G33 velocity mode); false = wait for the index.
        velocity_mode: bool,
    },
    /// End of spindle-synchronised motion.
    StopSpindleSync,
    /// G61/G61.1/G64 (LinuxCNC), G60/G64 (AxiOMA).
    SetPathMode {
        /// The new mode.
        mode: PathMode,
        /// LinuxCNC's naive-CAM detector tolerance Q, mm (None = not programmed).
        naive_cam_tolerance: Option<f64>,
    },
    /// AxiOMA BRISK/SOFT.
    SetAccelerationProfile {
        /// The new profile.
        profile: AccelerationProfile,
    },
    /// Feed override enabled or disabled (LinuxCNC M48/M49/M50, G76 threads, tapping cycles).
    SetFeedOverrideEnabled {
        /// True = the operator's override applies.
        enabled: bool,
    },
    /// M19: orient the spindle.
    OrientSpindle {
        /// Spindle number.
        spindle: u8,
        /// Angle, degrees.
        degrees: f64,
        /// LinuxCNC's P direction: 0 = shortest, 1 = CW, 2 = CCW.
        direction: u8,
        /// Seconds to wait for the orientation to complete (LinuxCNC M19 Q); None = no wait.
        timeout: Option<f64>,
    },
    /// LinuxCNC `M19 Q` without R or P: wait up to `timeout` seconds for an orientation to
    /// complete, commanding none.
    WaitSpindleOrient {
        /// Spindle number.
        spindle: u8,
        /// Seconds.
        timeout: f64,
    },
    /// Spindle speed override enabled or disabled (LinuxCNC M48/M49/M51, tapping cycles).
    SetSpindleOverrideEnabled {
        /// Spindle number.
        spindle: u8,
        /// True = the operator's override applies.
        enabled: bool,
    },
    /// LinuxCNC M52: adaptive feed (an external input scales the feed) on or off.
    SetAdaptiveFeed {
        /// On.
        enabled: bool,
    },
    /// LinuxCNC M53: the feed-stop input is honoured or not.
    SetFeedHoldEnabled {
        /// On.
        enabled: bool,
    },
    /// LinuxCNC M61: the tool in the spindle is declared without a tool change.
    SetCurrentTool {
        /// Tool number (0 = none).
        tool: u32,
        /// LinuxCNC's tool-table slot of that tool (rs274 prints it).
        slot: u32,
    },
    /// A digital output (LinuxCNC M62–M65, AxiOMA G110/G111 PLC outputs).
    DigitalOutput {
        /// Output number.
        index: u32,
        /// New state.
        on: bool,
        /// True = changes with the start of the next motion (M62/M63, G110/G111 without a stop);
        /// false = now (M64/M65).
        synchronised: bool,
    },
    /// M66: wait for an input (a timeout of 0 with mode 0 just reads it).
    WaitInput {
        /// Input number.
        index: u32,
        /// True for an analogue input (E word), false for digital (P word).
        analog: bool,
        /// 0 immediate, 1 rise, 2 fall, 3 high, 4 low.
        mode: u8,
        /// Seconds.
        timeout: f64,
    },
    /// G4: all axes stand still.
    Dwell {
        /// Seconds.
        seconds: f64,
    },
    /// An F word was programmed. For printers and displays: every motion states its own speed
    /// (`feed` and `law`).
    SetFeedRate {
        /// mm/min (in G95: mm/rev; in G93: 1/min).
        feed: f64,
    },
    /// G93/G94/G95. For printers and displays: every motion states its own law.
    SetFeedMode {
        /// The new mode.
        mode: FeedMode,
    },
    /// G17/G18/G19 was programmed.
    SelectPlane {
        /// The new plane.
        plane: Plane,
    },
    /// G20/G21 (G70/G71) was programmed. Printers only: positions stay in mm.
    UseLengthUnits {
        /// The new program units.
        units: LengthUnits,
    },
    /// The active work offset changed (G54…, G10 L2, program end).
    SetG5xOffset {
        /// 1 = G54 … 9 = G59.3; 0 = none.
        index: u8,
        /// mm.
        offset: Pose,
    },
    /// The G92/G52 offset changed.
    SetG92Offset {
        /// mm.
        offset: Pose,
    },
    /// The rotation of the work frame about Z changed.
    SetXyRotation {
        /// Degrees, counter-clockwise.
        degrees: f64,
    },
    /// An S word: commanded spindle speed.
    SetSpindleSpeed {
        /// Spindle number (0 = main; AxiOMA `S2=` is 1, …).
        spindle: u8,
        /// rev/min.
        rpm: f64,
    },
    /// M3/M4 (AxiOMA also M13/M14 with coolant, M203… for other spindles).
    StartSpindle {
        /// Spindle number (0 = main).
        spindle: u8,
        /// Rotation sense.
        direction: SpindleDirection,
    },
    /// M5 (and the stop implied by M0/M2/M6 where the control does it).
    StopSpindle {
        /// Spindle number (0 = main).
        spindle: u8,
    },
    /// G96/G97 (LinuxCNC's SET_SPINDLE_MODE).
    SetSpindleMode {
        /// Spindle number.
        spindle: u8,
        /// True = G96: S is a surface speed (m/min; the printer shows program units per minute)
        /// and the speed follows the transverse position; false = G97, S in rev/min.
        constant_surface_speed: bool,
        /// G96's speed limit D, rev/min (0 = none given).
        max_rpm: f64,
    },
    /// The constant-surface-speed law of a spindle changed (G96 and its speed, limits or the work
    /// zero of its transverse axis), or G97 ended it (`None`). Emitted beside `SetSpindleMode` /
    /// `SetSpindleSpeed`, which keep the values a control's screen shows; printers may ignore it.
    SetSurfaceSpeedLaw {
        /// Spindle number (0 = main).
        spindle: u8,
        /// The law, or `None` under G97 (the last `SetSpindleSpeed` holds).
        law: Option<SurfaceSpeedLaw>,
    },
    /// M7 (mist, AxiOMA coolant mode 1) on or off.
    Mist {
        /// On.
        on: bool,
    },
    /// M8 (flood, AxiOMA coolant mode 2) on or off.
    Flood {
        /// On.
        on: bool,
    },
    /// Tool-centre-point control switched on or off (AxiOMA TRAORI/TRAFOOF, Balt-System CVU=1/CVU=0,
    /// Mazatrol G43.4/G43.5/G49). While it is on, the positions of motion commands are **the tool
    /// tip** in the workpiece-fixed machine frame (the machine frame with every table axis at 0),
    /// mm, and the **rotary axis values**, degrees: the tool orientation is carried by those values
    /// (the machine's kinematics turns them into a tool vector). The `kin` stage turns every servo
    /// setpoint into machine axis positions with the inverse kinematics. While it is off, positions
    /// are machine axis positions (the tool length already applied along the spindle), as on a
    /// 3-axis machine. The switch itself moves nothing; the next motion starts where the machine is,
    /// expressed in the new meaning.
    SetToolCentrePoint {
        /// On (true) or off.
        active: bool,
        /// Tool tip → tool mount point at zero rotary positions, mm (length L along the base
        /// orientation: L·b); zero without an active tool length.
        tool_offset: [f64; 3],
    },
    /// ORIAXES / ORIVECT (spec axioma-4 §6): how the orientation moves in the blocks from now on.
    SetOrientationInterpolation {
        /// The new mode.
        mode: OrientationInterpolation,
    },
    /// The tool length offset in force changed (G43/G49 …). Printers only: positions already include it.
    UseToolLengthOffset {
        /// X Y Z A B C U V W offset, mm/deg.
        offset: Pose,
    },
    /// A tool-table entry was written (LinuxCNC `G10 L1/L10/L11`, its SET_TOOL_TABLE_ENTRY). Data
    /// only: the offset in force changes with the next G43.
    SetToolTableEntry {
        /// LinuxCNC's tool-table slot: n ≥ 1 = the n-th tool of the table (by number), 0 = the
        /// spindle's copy of the loaded tool (written too when the loaded tool changes).
        slot: u32,
        /// Tool number.
        tool: u32,
        /// Tool offset X Y Z A B C U V W, mm/deg (the table's values: machine frame, not program units).
        offset: Pose,
        /// Cutter diameter, mm.
        diameter: f64,
        /// Lathe front angle, degrees.
        front_angle: f64,
        /// Lathe back angle, degrees.
        back_angle: f64,
        /// Lathe cutting-edge orientation 0…9 (0 = none).
        orientation: u8,
    },
    /// The tool table is read again from where it is kept (LinuxCNC `G10 L0`, RELOAD_TOOLDATA).
    ReloadToolTable,
    /// A tool change begins (LinuxCNC's START_CHANGE: move to the change position, orient…).
    StartToolChange,
    /// A T word: the tool is prepared (not yet in the spindle).
    SelectTool {
        /// Tool number.
        tool: u32,
    },
    /// M6: the selected tool goes into the spindle.
    ChangeTool {
        /// Tool number.
        tool: u32,
        /// LinuxCNC's tool-table slot of that tool, which rs274 prints (n ≥ 1 = the n-th tool
        /// of the table, 0 = no tool); other dialects give the tool number.
        slot: u32,
    },
    /// A tool change in another spindle than the main one (AxiOMA `T2=… M06`).
    ChangeSpindleTool {
        /// Spindle number, 1 = the second spindle.
        spindle: u8,
        /// Tool number (0 = the tool goes back to the magazine).
        tool: u32,
    },
    /// An M function with no canonical meaning of its own (machine-specific, PLC).
    AuxiliaryFunction {
        /// The M number.
        number: u32,
        /// Before or after the block's motion.
        timing: AuxTiming,
    },
    /// An operator message (AxiOMA `MSG("…")`, LinuxCNC `(MSG,…)`); empty text clears it.
    Message {
        /// The text.
        text: String,
    },
    /// LinuxCNC's program log: `(LOGOPEN,file)`, `(LOGAPPEND,file)`, `(LOGCLOSE)`, `(LOG,text)`
    /// (the text with its parameters substituted).
    Log {
        /// What to do.
        action: LogAction,
        /// The file name (open, append) or the line to write; empty for close.
        text: String,
    },
    /// A passive comment that a printer may show (LinuxCNC prints every `( … )` as COMMENT).
    Comment {
        /// The text.
        text: String,
    },
    /// M0 (unconditional) or M1 (optional) stop.
    ProgramStop {
        /// True for M1.
        optional: bool,
    },
    /// LinuxCNC M30 (and M60): exchange the pallets.
    PalletShuttle,
    /// M2/M30 (AxiOMA also M99): the program is over.
    ProgramEnd,
    /// The program text ended with its closing `%` without M2/M30 (LinuxCNC's FINISH): nothing
    /// is reset, the run is over.
    Finish,
}

impl Canon {
    /// The motion part of a command, if it moves the machine.
    pub fn motion(&self) -> Option<Motion<'_>> {
        match self {
            Canon::StraightTraverse(m) => Some(Motion::Rapid(m)),
            Canon::StraightFeed(m) => Some(Motion::Line(m)),
            Canon::ArcFeed(a) => Some(Motion::Arc(a)),
            Canon::SplineFeed(s) => Some(Motion::Spline(s)),
            Canon::StraightProbe {
                motion, contact, ..
            } => Some(Motion::Probe {
                motion,
                contact: contact.as_deref().copied(),
            }),
            Canon::RigidTap { start, end, .. } => Some(Motion::RigidTap {
                start: *start,
                bottom: *end,
            }),
            _ => None,
        }
    }
}

/// A borrowed view of the motion commands.
#[derive(Debug, Clone, Copy)]
pub enum Motion<'a> {
    /// G0.
    Rapid(&'a LineMove),
    /// G1.
    Line(&'a LineMove),
    /// G2/G3.
    Arc(&'a ArcMove),
    /// A spline.
    Spline(&'a SplineMove),
    /// A probe move: programmed to `motion.end`, it stops at `contact` when there is one.
    Probe {
        /// The move as programmed.
        motion: &'a LineMove,
        /// Where the probe changes state (the move ends there).
        contact: Option<Pose>,
    },
    /// A rigid tap: down to `bottom` and back to `start`.
    RigidTap {
        /// Start and end of the cycle.
        start: Pose,
        /// The bottom of the hole.
        bottom: Pose,
    },
}

impl Motion<'_> {
    /// Start pose.
    pub fn start(&self) -> Pose {
        match self {
            Motion::Rapid(m) | Motion::Line(m) => m.start,
            Motion::Probe { motion, .. } => motion.start,
            Motion::Arc(a) => a.start,
            Motion::Spline(s) => s.start,
            Motion::RigidTap { start, .. } => *start,
        }
    }

    /// End pose.
    pub fn end(&self) -> Pose {
        match self {
            Motion::Rapid(m) | Motion::Line(m) => m.end,
            Motion::Probe { motion, contact } => contact.unwrap_or(motion.end),
            Motion::Arc(a) => a.end,
            Motion::Spline(s) => s.end,
            // The tap comes back to where it started.
            Motion::RigidTap { start, .. } => *start,
        }
    }
}
