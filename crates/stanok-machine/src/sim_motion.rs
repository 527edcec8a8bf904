//! The simulated machine's motion: Canon → planner → servo setpoints, checked and measured.
//!
//! `SimMachine::apply` hands every accepted command to a [`MotionStage`]; the setpoints it streams
//! out are executed here, one servo period at a time:
//! 1. **Soft limits.** Every setpoint must lie within each axis' travel (1e-9 slack); the planner
//!    guarantees it (blends and chords stay within the convex hull of the programmed path, which
//!    `SimMachine::apply` checked), this verifies it.
//! 2. **Dynamics.** [`TraceMonitor`] measures analytic and finite-difference velocity,
//!    acceleration and jerk per axis against the machine's limits.
//! 3. **Observer.** An optional sink (the CLI's `--trace` writer, its progress bar) sees every
//!    setpoint; nothing is stored here, so memory does not grow with the run.
//!
//! [`MotionRun::fill`] puts the cycle time (the trace duration), peaks and violations into the
//! [`RunReport`](crate::RunReport).

use crate::data::MachineData;
use crate::sim::LoggedEvent;
use serde::Serialize;
use stanok_canon::{Canon, AXIS_LETTERS};
use stanok_motion::monitor::TraceMonitor;
use stanok_motion::{AxisLimit, MotionConfig, MotionStage, Setpoint};
use stanok_stock::sim::StockSim;

/// Receives every setpoint (e.g. a trace writer).
pub type SetpointSink = Box<dyn FnMut(&Setpoint)>;

/// Sees the stock simulation after every setpoint it took (the panel's live stock view); it may
/// cut what is pending (`StockSim::cut_pending`) before it looks.
pub type StockObserver = Box<dyn FnMut(&mut StockSim)>;

/// How the simulated machine runs the motion.
#[derive(Debug, Clone, PartialEq)]
pub struct SimOptions {
    /// Servo period, s (default 1 ms).
    pub servo_period_s: f64,
    /// Feed override, fraction (1 = 100 %, at most 2).
    pub feed_override: f64,
    /// Rapid override, fraction (at most 1).
    pub rapid_override: f64,
    /// Planner look-ahead, pieces.
    pub lookahead: usize,
    /// A feed hold: (machine time at which the operator presses it, s; seconds the machine then
    /// stands before cycle start resumes it).
    pub feed_hold: Option<(f64, f64)>,
    /// Every move with this acceleration profile, whatever the program selects (None = as
    /// programmed); see `MotionConfig::forced_profile`.
    pub profile: Option<stanok_canon::AccelerationProfile>,
    /// Override changes at machine times (`stanok run --override-at`), acting on the motion being
    /// executed and everything planned ([`stanok_motion::overrides`]).
    pub override_changes: Vec<stanok_motion::overrides::OverrideChange>,
    /// Bound on simulated machine time, s (default 100 h; see `time_bound.rs`).
    pub max_machine_time_s: f64,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            servo_period_s: stanok_motion::limits::DEFAULT_SERVO_PERIOD,
            feed_override: 1.0,
            rapid_override: 1.0,
            lookahead: stanok_motion::limits::DEFAULT_LOOKAHEAD,
            feed_hold: None,
            profile: None,
            override_changes: Vec::new(),
            max_machine_time_s: crate::time_bound::DEFAULT_MAX_MACHINE_TIME_S,
        }
    }
}

/// Peaks of one machine axis against its limits. Units: the axis' unit (mm or deg) per s, s², s³.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AxisMotion {
    /// Axis letter.
    pub axis: char,
    /// Velocity limit.
    pub max_velocity: f64,
    /// Acceleration limit.
    pub max_acceleration: f64,
    /// Jerk limit (SOFT).
    pub max_jerk: f64,
    /// Highest analytic velocity.
    pub peak_velocity: f64,
    /// Highest analytic acceleration.
    pub peak_acceleration: f64,
    /// Highest analytic jerk in SOFT pieces.
    pub peak_jerk: f64,
    /// Highest velocity by finite differences of the setpoints.
    pub trace_peak_velocity: f64,
    /// Highest acceleration by finite differences.
    pub trace_peak_acceleration: f64,
    /// Highest jerk by finite differences (not a limit in BRISK; see `stanok_motion::monitor`).
    pub trace_peak_jerk: f64,
}

/// The range of speeds a spindle was commanded to turn at over the setpoints where it turned,
/// rev/min (under G96 the law evaluated at every position).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpindleRange {
    /// Spindle number (0 = main).
    pub spindle: u8,
    /// Lowest speed.
    pub min_rpm: f64,
    /// Highest speed.
    pub max_rpm: f64,
}

/// The largest distance of a setpoint from the programmed path in one class of setpoints, measured
/// on the trace (`stanok_motion::contour`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ContourError {
    /// Distance, mm (X Y Z; the tool tip under tool-centre-point control).
    pub max_mm: f64,
    /// Machine time of that setpoint, s.
    pub t_s: f64,
    /// Source line of its block.
    pub line: u32,
}

/// The measured contour error, split into the junction blends between programmed segments and
/// everything else (lines, arcs, splines; at most 1 µm on splines, rounding on lines and arcs).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ContourErrors {
    /// On junction blends (within the path tolerance in force).
    pub junctions: ContourError,
    /// Everywhere else.
    pub elsewhere: ContourError,
}

/// One block's planned and nominal time and the limit that set its speed
/// (`stanok_motion::timing`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BlockTime {
    /// Source line.
    pub line: u32,
    /// Planned (executed) time, s.
    pub planned_s: f64,
    /// Length / programmed feed (rapid rate) at 100 %, dwells at their time, s.
    pub nominal_s: f64,
    /// Path length, mm (0 for a dwell): length / planned time is the block's mean speed.
    pub length_mm: f64,
    /// What set its speed for most of its time: "programmed feed", "axis velocity", "axis
    /// acceleration", "jerk", "curvature", "blend tolerance", "exact stop", "look-ahead window",
    /// "override" or "dwell".
    pub limit: &'static str,
}

impl From<&stanok_motion::timing::BlockTime> for BlockTime {
    fn from(b: &stanok_motion::timing::BlockTime) -> Self {
        BlockTime {
            line: b.line,
            planned_s: b.planned_s,
            nominal_s: b.nominal_s,
            length_mm: b.length_mm,
            limit: b.limit.name(),
        }
    }
}

/// The operator's feed hold in a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FeedHoldReport {
    /// Machine time the hold was pressed at, s.
    pub at_s: f64,
    /// How long the machine stood, s.
    pub standstill_s: f64,
    /// False when the program ended before `at_s`: the hold never happened.
    pub happened: bool,
}

/// The motion part of a simulated run (module doc).
pub(crate) struct MotionRun {
    stage: MotionStage,
    checks: SetpointChecks,
    limits: [AxisLimit; 9],
    feed_override: f64,
    feed_hold: Option<(f64, f64)>,
    cycle_time: Option<f64>,
}

/// What the machine does with every setpoint, wherever the stage releases it (a command, a drain,
/// the end): one place, so no path of release can skip a check or the caller's observer.
struct SetpointChecks {
    monitor: TraceMonitor,
    observer: Option<SetpointSink>,
    travel: [Option<(char, f64, f64)>; 9],
    travel_violations: Vec<LoggedEvent>,
    travel_violation_count: u64,
    spindle_rpm_range: [Option<(f64, f64)>; 4],
    /// The stock-removal simulation, when the run has a stock.
    stock: Option<StockSim>,
    stock_observer: Option<StockObserver>,
}

impl SetpointChecks {
    /// Measures the setpoint, checks the travel, widens the spindle ranges, hands it on.
    fn observe(&mut self, sp: &Setpoint) {
        execute(
            sp,
            &mut self.monitor,
            &self.travel,
            &mut self.travel_violations,
            &mut self.travel_violation_count,
        );
        track_spindles(&mut self.spindle_rpm_range, &sp.spindle_rpm);
        if let Some(s) = self.stock.as_mut() {
            s.setpoint(sp);
            if let Some(o) = self.stock_observer.as_mut() {
                o(s);
            }
        }
        if let Some(o) = self.observer.as_mut() {
            o(sp);
        }
    }
}

impl std::fmt::Debug for MotionRun {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MotionRun")
            .field("setpoints", &self.checks.monitor.count())
            .finish_non_exhaustive()
    }
}

impl MotionRun {
    pub(crate) fn new(machine: &MachineData, options: &SimOptions) -> Self {
        let mut limits = [AxisLimit::UNLIMITED; 9];
        let mut travel = [None; 9];
        for a in &machine.axes {
            let i = a.pose_index();
            limits[i] = AxisLimit::from_machine(a.max_velocity, a.max_acceleration, a.max_jerk);
            travel[i] = Some((a.name, a.min, a.max));
        }
        let mut config = MotionConfig::new(limits, machine.rapid_rate, machine.max_feed);
        config.servo_period = options.servo_period_s;
        config.feed_override = options.feed_override;
        config.rapid_override = options.rapid_override;
        config.lookahead = options.lookahead;
        config.kinematics = machine.five_axis();
        config.default_tolerance = machine.path_tolerance;
        config.forced_profile = options.profile;
        let config = config.sanitised();
        let mut stage = MotionStage::new(&config);
        stage.set_time_limit(options.max_machine_time_s);
        // Nobody needs every setpoint until an observer that does is set (`set_observer`).
        stage.set_skip_steady(true);
        if let Some((at, standstill)) = options.feed_hold {
            stage.feed_hold(at, standstill);
        }
        stage.schedule_overrides(&options.override_changes);
        MotionRun {
            stage,
            checks: SetpointChecks {
                monitor: TraceMonitor::new(limits, config.servo_period),
                observer: None,
                travel,
                travel_violations: Vec::new(),
                travel_violation_count: 0,
                spindle_rpm_range: [None; 4],
                stock: None,
                stock_observer: None,
            },
            limits,
            feed_override: config.feed_override,
            feed_hold: options.feed_hold,
            cycle_time: None,
        }
    }

    /// An observer of every setpoint (a trace writer, the panel's machine).
    pub(crate) fn set_observer(&mut self, sink: SetpointSink) {
        self.checks.observer = Some(sink);
        self.stage.set_skip_steady(false);
    }

    /// An observer that does not need every setpoint (a progress display): steady stretches
    /// may be skipped (see `stanok_motion::interpolator`).
    pub(crate) fn set_sparse_observer(&mut self, sink: SetpointSink) {
        self.checks.observer = Some(sink);
        self.stage.set_skip_steady(true);
    }

    /// The time at which the bound on machine time stopped the motion.
    pub(crate) fn stopped_at(&self) -> Option<f64> {
        self.stage.stopped_at()
    }

    pub(crate) fn set_stock(&mut self, stock: StockSim) {
        self.checks.stock = Some(stock);
    }

    pub(crate) fn set_stock_observer(&mut self, o: StockObserver) {
        self.checks.stock_observer = Some(o);
    }

    pub(crate) fn stock(&self) -> Option<&StockSim> {
        self.checks.stock.as_ref()
    }

    /// Runs one accepted command. The stock simulation hears of it first, with the serial number
    /// the stage is about to give it, so that it applies the command's state changes to exactly
    /// the setpoints after it.
    pub(crate) fn apply(&mut self, cmd: &Canon, line: u32) {
        let Self { stage, checks, .. } = self;
        if let Some(s) = checks.stock.as_mut() {
            s.command(stage.commands() + 1, cmd);
        }
        let mut sink = |sp: &Setpoint| checks.observe(sp);
        stage.apply(cmd, line, &mut sink);
    }

    /// Runs everything pending; the path stops at its current end.
    pub(crate) fn drain(&mut self) {
        let Self { stage, checks, .. } = self;
        let mut sink = |sp: &Setpoint| checks.observe(sp);
        stage.drain(&mut sink);
    }

    pub(crate) fn set_hold_switch(
        &mut self,
        switch: std::sync::Arc<stanok_motion::hold::HoldSwitch>,
    ) {
        self.stage.set_hold_switch(switch);
    }

    pub(crate) fn set_feed_override(&mut self, fraction: f64) {
        self.stage.set_feed_override(fraction);
        self.feed_override = fraction;
    }

    pub(crate) fn set_rapid_override(&mut self, fraction: f64) {
        self.stage.set_rapid_override(fraction);
    }

    pub(crate) fn set_spindle_override(&mut self, fraction: f64) {
        self.stage.set_spindle_override(fraction);
    }

    pub(crate) fn set_override_switch(
        &mut self,
        switch: std::sync::Arc<stanok_motion::overrides::OverrideSwitch>,
    ) {
        self.stage.set_override_switch(switch);
    }

    /// Runs what is left; idempotent.
    pub(crate) fn finish(&mut self) {
        if self.cycle_time.is_some() {
            return;
        }
        let Self { stage, checks, .. } = self;
        let mut sink = |sp: &Setpoint| checks.observe(sp);
        self.cycle_time = Some(stage.finish(&mut sink));
        if let Some(s) = checks.stock.as_mut() {
            s.finish();
        }
    }

    /// The motion fields of the report.
    pub(crate) fn fill(&self, r: &mut crate::RunReport) {
        let c = &self.checks;
        r.cycle_time_s = self.cycle_time.unwrap_or(c.monitor.last_t);
        r.servo_period_s = self.stage.servo_period();
        r.setpoints = c.monitor.count();
        r.feed_override_percent = self.feed_override * 100.0;
        r.feed_hold = self.feed_hold.map(|(at_s, standstill_s)| FeedHoldReport {
            at_s,
            standstill_s,
            happened: at_s < r.cycle_time_s,
        });
        r.spindles = (0..4u8)
            .filter_map(|i| {
                let (min_rpm, max_rpm) = c.spindle_rpm_range[i as usize]?;
                Some(SpindleRange {
                    spindle: i,
                    min_rpm,
                    max_rpm,
                })
            })
            .collect();
        let stats = self.stage.stats();
        r.max_path_deviation_mm = stats.max_deviation;
        let contour = self.stage.contour();
        let max = |m: &stanok_motion::contour::ContourMax| ContourError {
            max_mm: m.distance,
            t_s: m.t,
            line: m.line,
        };
        r.contour_error = ContourErrors {
            junctions: max(&contour.junctions),
            elsewhere: max(&contour.elsewhere),
        };
        let timer = self.stage.block_times();
        r.block_times = timer.blocks.iter().map(BlockTime::from).collect();
        r.block_times_truncated = timer.truncated;
        r.slowest_blocks = timer.slowest.iter().map(BlockTime::from).collect();
        r.axes = (0..9)
            .filter_map(|i| {
                let (axis, ..) = c.travel[i]?;
                let (l, p) = (self.limits[i], c.monitor.peaks[i]);
                Some(AxisMotion {
                    axis,
                    max_velocity: l.velocity,
                    max_acceleration: l.acceleration,
                    max_jerk: l.jerk,
                    peak_velocity: p.velocity,
                    peak_acceleration: p.acceleration,
                    peak_jerk: p.jerk,
                    trace_peak_velocity: p.fd_velocity,
                    trace_peak_acceleration: p.fd_acceleration,
                    trace_peak_jerk: p.fd_jerk,
                })
            })
            .collect();
        let mut v: Vec<LoggedEvent> = c.travel_violations.clone();
        for x in &c.monitor.violations {
            v.push(LoggedEvent {
                line: x.line,
                text: format!(
                    "t = {:.4} s: {} {} {:.6} exceeds its limit {:.6}",
                    x.t, AXIS_LETTERS[x.axis], x.what, x.value, x.limit
                ),
            });
        }
        if stats.tolerance_violations > 0 {
            v.push(LoggedEvent {
                line: 0,
                text: format!(
                    "{} path pieces beyond the path tolerance",
                    stats.tolerance_violations
                ),
            });
        }
        if let Some(t) = self.stage.stopped_at() {
            v.push(LoggedEvent {
                line: 0,
                text: format!(
                    "t = {t:.4} s: the bound on simulated machine time stopped the motion; the \
                     rest was not simulated (--max-machine-time)"
                ),
            });
        }
        r.violations = v;
        r.violation_count = c.travel_violation_count
            + c.monitor.violation_count
            + stats.tolerance_violations
            + u64::from(self.stage.stopped_at().is_some());
        r.stock = c.stock.as_ref().map(StockSim::report);
    }
}

/// Widens each spindle's range of commanded speeds by this setpoint's (zero speeds are not counted).
fn track_spindles(ranges: &mut [Option<(f64, f64)>; 4], rpm: &[f64; 4]) {
    for (range, &n) in ranges.iter_mut().zip(rpm) {
        if n > 0.0 {
            *range = Some(match *range {
                Some((lo, hi)) => (lo.min(n), hi.max(n)),
                None => (n, n),
            });
        }
    }
}

/// Executes one setpoint: measure, check travel.
fn execute(
    sp: &Setpoint,
    monitor: &mut TraceMonitor,
    travel: &[Option<(char, f64, f64)>; 9],
    violations: &mut Vec<LoggedEvent>,
    count: &mut u64,
) {
    monitor.observe(sp);
    for (i, t) in travel.iter().enumerate() {
        let Some((name, lo, hi)) = t else { continue };
        let x = sp.position[i];
        if !(x >= lo - 1e-9 && x <= hi + 1e-9) {
            *count += 1;
            if violations.len() < 100 {
                violations.push(LoggedEvent {
                    line: sp.line,
                    text: format!(
                        "t = {:.4} s: {name} setpoint {x:.6} outside its travel [{lo}, {hi}]",
                        sp.t
                    ),
                });
            }
        }
    }
}
