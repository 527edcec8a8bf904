//! Machine limits and planner settings, in the planner's units (mm or deg, seconds).
//!
//! Machine data gives velocities per minute; everything here is per **second**, because the
//! profiles and the servo period are in seconds. An axis the machine lacks has no limits (it never
//! moves: the simulated machine refuses such moves before they reach the planner).

/// One axis' dynamic limits, unit = mm (linear) or deg (rotary).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisLimit {
    /// Maximum velocity, unit/s.
    pub velocity: f64,
    /// Maximum acceleration, unit/s².
    pub acceleration: f64,
    /// Maximum jerk, unit/s³ (SOFT only).
    pub jerk: f64,
}

impl AxisLimit {
    /// No limit at all (an axis the machine does not have).
    pub const UNLIMITED: AxisLimit = AxisLimit {
        velocity: f64::INFINITY,
        acceleration: f64::INFINITY,
        jerk: f64::INFINITY,
    };

    /// Limits from machine-data units: velocity per minute, acceleration per s², jerk per s³. A
    /// non-positive or non-finite value becomes "no limit" for that quantity (machine data
    /// validation refuses such values, so this only guards the planner against a caller's bug).
    pub fn from_machine(velocity_per_min: f64, acceleration: f64, jerk: f64) -> Self {
        let sane = |x: f64| {
            if x.is_finite() && x > 0.0 {
                x
            } else {
                f64::INFINITY
            }
        };
        AxisLimit {
            velocity: sane(velocity_per_min / 60.0),
            acceleration: sane(acceleration),
            jerk: sane(jerk),
        }
    }
}

/// What the planner needs to know about the machine and the run.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionConfig {
    /// Limits per axis in `Pose::to_array` order (X Y Z A B C U V W).
    pub axes: [AxisLimit; 9],
    /// Rapid (G0) path rate, mm/s.
    pub rapid_rate: f64,
    /// Highest path feed, mm/s; higher programmed feeds are clamped to it.
    pub max_feed: f64,
    /// Servo (interpolation) period, s.
    pub servo_period: f64,
    /// Look-ahead window: the most path pieces held for planning (≥ 2). Memory is bounded by it.
    pub lookahead: usize,
    /// The path tolerance of G64 without P ("as fast as possible"), mm.
    pub default_tolerance: f64,
    /// Feed override at the start, as a fraction, 0…2 (1 = 100 %); 0 holds feed moves. It can
    /// change at any servo instant ([`crate::overrides`]).
    pub feed_override: f64,
    /// Rapid override as a fraction, 0…1.
    pub rapid_override: f64,
    /// Spindle override as a fraction, 0.5…1.2.
    pub spindle_override: f64,
    /// The machine's 5-axis kinematics (without a tool), for tool-centre-point control; None on
    /// a Cartesian machine.
    pub kinematics: Option<stanok_kin::FiveAxis>,
    /// Run every move with this acceleration profile, whatever the program selects (BRISK/SOFT
    /// commands are then ignored); None = as programmed (power-on BRISK). For checking a program
    /// under SOFT (`stanok run --profile soft`) and for tests.
    pub forced_profile: Option<stanok_canon::AccelerationProfile>,
}

impl MotionConfig {
    /// The override factors at the start of a run.
    pub fn overrides(&self) -> crate::piece::Overrides {
        crate::piece::Overrides {
            feed: self.feed_override,
            rapid: self.rapid_override,
            spindle: self.spindle_override,
        }
        .clamped()
    }

    /// Servo period 1 ms, look-ahead 1024 pieces, G64 default tolerance 0.05 mm, overrides 100 %.
    pub fn new(axes: [AxisLimit; 9], rapid_rate_per_min: f64, max_feed_per_min: f64) -> Self {
        let sane = |x: f64| {
            if x.is_finite() && x > 0.0 {
                x / 60.0
            } else {
                1.0
            }
        };
        MotionConfig {
            axes,
            rapid_rate: sane(rapid_rate_per_min),
            max_feed: sane(max_feed_per_min),
            servo_period: DEFAULT_SERVO_PERIOD,
            lookahead: DEFAULT_LOOKAHEAD,
            default_tolerance: DEFAULT_TOLERANCE,
            feed_override: 1.0,
            rapid_override: 1.0,
            spindle_override: 1.0,
            kinematics: None,
            forced_profile: None,
        }
    }

    /// The same settings with every out-of-range value brought into range: servo period in
    /// [10 µs, 1 s], look-ahead in [2, 1 000 000], tolerance in (0, 10] mm, overrides clamped.
    pub fn sanitised(mut self) -> Self {
        let clamp = |x: f64, lo: f64, hi: f64, default: f64| {
            if x.is_nan() {
                default
            } else {
                x.clamp(lo, hi)
            }
        };
        self.servo_period = clamp(self.servo_period, 1e-5, 1.0, DEFAULT_SERVO_PERIOD);
        self.lookahead = self.lookahead.clamp(2, 1_000_000);
        self.default_tolerance = clamp(self.default_tolerance, 1e-6, 10.0, DEFAULT_TOLERANCE);
        self.feed_override = clamp(self.feed_override, 0.0, 2.0, 1.0);
        self.rapid_override = clamp(self.rapid_override, 0.0, 1.0, 1.0);
        self.spindle_override = clamp(self.spindle_override, 0.5, 1.2, 1.0);
        self
    }
}

/// Default servo period, s.
pub const DEFAULT_SERVO_PERIOD: f64 = 1e-3;
/// Default look-ahead window, pieces.
pub const DEFAULT_LOOKAHEAD: usize = 1024;
/// Default G64 tolerance when none is programmed, mm.
pub const DEFAULT_TOLERANCE: f64 = 0.05;
