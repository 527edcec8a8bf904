//! The planner's input: one programmed motion block with everything the planner must know about it.
//!
//! The [`adapter`](crate::adapter) builds these from the Canon stream, so that every segment carries
//! the path mode (G60/G61/G64 with its tolerance) and the profile (BRISK/SOFT) that were in force when
//! it was programmed, and its speed already converted to the planner's path parameter.
//!
//! ## Path parameter
//! The planner moves along the path in the **nine-dimensional** axis space X Y Z A B C U V W (mm and
//! degrees mixed, Euclidean length). The programmed feed applies to the *feed length* of spec
//! axioma-2 §3.2 (XYZ if XYZ moves, else UVW, else ABC); `path_speed` is that feed scaled by
//! (9-D length / feed length), so that the feed length advances at exactly the programmed feed while
//! the other axes follow synchronously.

use stanok_canon::{AccelerationProfile, PathMode, SurfaceSpeedLaw};
use stanok_geom::Helix;

/// A point of all nine axes, `Pose::to_array` order (mm / deg).
pub type Point9 = [f64; 9];

/// The shape of a programmed segment.
#[derive(Debug, Clone, PartialEq)]
pub enum SegmentGeometry {
    /// A straight move from `start` to `end`.
    Line,
    /// A circle, helix or spiral in XYZ (the other axes move linearly with the swept angle).
    Arc(Helix),
    /// A curve given as points (a spline tessellated within [`SPLINE_CHORD_TOLERANCE`]), `start`
    /// first and `end` last; the other axes move linearly with the XYZ length.
    Polyline(Vec<Point9>),
}

/// The speed the main spindle turns at while a segment runs: constant, or the G96 law evaluated at
/// every point of the path (see [`crate::css`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpindleSpeed {
    /// Rev/min as last programmed (G97, or no spindle speed yet: 0).
    Constant(f64),
    /// Constant surface speed: the speed follows the transverse position.
    Surface(SurfaceSpeedLaw),
}

impl Default for SpindleSpeed {
    fn default() -> Self {
        SpindleSpeed::Constant(0.0)
    }
}

impl SpindleSpeed {
    /// Rev/min with the tool at `p`.
    #[inline]
    pub fn rpm_at(&self, p: &Point9) -> f64 {
        match self {
            SpindleSpeed::Constant(rpm) => *rpm,
            SpindleSpeed::Surface(law) => law.rpm_at(p),
        }
    }
}

/// The speeds of the four spindles (0 = main) while a segment runs, and how each turns: +1 M3
/// (clockwise), −1 M4, 0 stopped (M5, and at power-on).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Spindles(pub [SpindleSpeed; 4], pub [f64; 4]);

impl Spindles {
    /// Commanded rev/min of every spindle with the tool at `p` (whether it turns or not).
    #[inline]
    pub fn rpm_at(&self, p: &Point9) -> [f64; 4] {
        std::array::from_fn(|i| self.0[i].rpm_at(p))
    }

    /// How every spindle turns: +1 M3, −1 M4, 0 stopped.
    #[inline]
    pub fn directions(&self) -> [i8; 4] {
        self.1.map(|d| match d.partial_cmp(&0.0) {
            Some(std::cmp::Ordering::Greater) => 1,
            Some(std::cmp::Ordering::Less) => -1,
            _ => 0,
        })
    }
}

/// Which override scales a programmed speed (see [`crate::piece::Overrides`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpeedClass {
    /// A feed move: the feed override.
    #[default]
    Feed,
    /// A rapid: the rapid override.
    Rapid,
    /// A spindle-synchronised move (G33, rigid tap): the spindle override, as the spindle's own
    /// speed changes and the axes follow it.
    Spindle,
    /// No override (the program disabled it, M48/M50 and the like).
    Fixed,
}

/// Chord tolerance of spline tessellation, mm: half of the 1 µm a spline's setpoints keep from its
/// curve (the other half goes to the blends at the chords' vertices, see [`crate::path`]).
pub const SPLINE_CHORD_TOLERANCE: f64 = 0.5e-3;

/// One programmed motion block, ready for planning.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSegment {
    /// Where it starts.
    pub start: Point9,
    /// Where it ends.
    pub end: Point9,
    /// Its shape.
    pub geometry: SegmentGeometry,
    /// Programmed speed along the 9-D path, unit/s (see the module doc), after clamping to the
    /// machine's maximum feed (or the rapid rate), before any override; always > 0.
    pub path_speed: f64,
    /// Highest path acceleration along it, unit/s² (`f64::INFINITY` = only the axis limits): set
    /// under tool-centre-point control, where the machine axes move faster than the path
    /// ([`crate::tcp`]).
    pub acceleration_cap: f64,
    /// Highest path speed the kinematics allow whatever the feed and override (set under
    /// tool-centre-point control, [`crate::tcp`]; ∞ otherwise), unit/s.
    pub velocity_cap: f64,
    /// G0 (true) or a feed move.
    pub rapid: bool,
    /// Which override scales `path_speed` (a rapid is always [`SpeedClass::Rapid`]).
    pub speed_class: SpeedClass,
    /// How its end joins the next segment.
    pub path_mode: PathMode,
    /// BRISK or SOFT.
    pub profile: AccelerationProfile,
    /// Source line (1-based) for reports.
    pub line: u32,
    /// The spindles' speeds while it runs.
    pub spindles: Spindles,
}

/// What the planner receives.
#[allow(clippy::large_enum_variant)] // one at a time, streamed: boxing would only add an allocation
#[derive(Debug, Clone, PartialEq)]
pub enum PlannerInput {
    /// A motion block.
    Segment(PathSegment),
    /// All axes must stop here (M0/M1, tool change, probe, program end, feed-mode change, spindle
    /// synchronisation…) and then stand still for `dwell_s` seconds (G4; 0 for a plain stop).
    Stop {
        /// Standstill after the stop, s.
        dwell_s: f64,
        /// Source line.
        line: u32,
    },
}
