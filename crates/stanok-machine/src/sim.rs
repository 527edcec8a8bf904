//! The simulated machine: checks and executes a Canon stream and builds the run report.
//!
//! Every accepted command also goes to the motion stage (`sim_motion.rs`): the look-ahead planner
//! and the servo-rate interpolator of `stanok-motion`, whose setpoints are executed and measured
//! there. The report has both times: `nominal_time_s` (length / feed, the lower bound kept from
//! before the planner) and `cycle_time_s` (the planned, executed trace).
//!
//! ## One command, check first, then commit (grbl's STEP 3 / STEP 4)
//!
//! `SimMachine::apply` first checks everything that can refuse the command and only then changes
//! state, so a refused command leaves no trace in the report:
//! 1. **Axes** and 2. **travel limits** ([`TravelCheck`](crate::TravelCheck), `travel.rs`: the
//!    moved axes exist; end points, arc bulges, spline tessellations and, under tool-centre-point
//!    control, the joints along the move are within the travel).
//! 3. **Commit.** Counters, distances, nominal time (`stanok_motion::nominal`), bounding box, the
//!    M-function and message logs, the position.
//!
//! ## Length and time of a move (spec axioma-2 §3.2, LinuxCNC canon)
//!
//! The length a rate applies to is the XYZ length if XYZ moves; otherwise the UVW length; otherwise
//! the ABC length in degrees (a rotary-only feed is in deg/min). Only millimetre lengths add to the
//! report's distances. An arc's length is the helix length of its XYZ part ([`Helix::length`]).
//! Feeds above the machine's `max_feed` are clamped to it, as a control does; a feed of zero (which
//! the interpreter never emits) takes no time. Rapids run at `rapid_rate`, slowed so that no axis
//! exceeds its `max_velocity`.
//!
//! Invariant: the report only grows by commands that were accepted; no input makes `apply` panic or
//! put a NaN or ∞ into the times (degenerate geometry is the interpreter's to refuse).

use crate::data::{AxisData, MachineData};
use crate::sim_motion::{AxisMotion, MotionRun, SetpointSink, SimOptions};
use crate::time_bound;
use crate::travel::TravelCheck;
use serde::Serialize;
use stanok_canon::{
    ArcMove, AuxTiming, Canon, Diagnostic, LineMove, Pose, Spanned, SpindleDirection, SplineMove,
};
use stanok_geom::{Helix, Nurbs};
use stanok_motion::nominal::{self, AxisLimits};
use std::collections::BTreeMap;

/// An axis-aligned box in machine X Y Z, mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoundingBox {
    /// Smallest X, Y, Z.
    pub min: [f64; 3],
    /// Largest X, Y, Z.
    pub max: [f64; 3],
}

impl BoundingBox {
    fn include(bbox: &mut Option<BoundingBox>, lo: [f64; 3], hi: [f64; 3]) {
        let b = bbox.get_or_insert(BoundingBox { min: lo, max: hi });
        for i in 0..3 {
            b.min[i] = b.min[i].min(lo[i]);
            b.max[i] = b.max[i].max(hi[i]);
        }
    }
}

/// Something that happened at a source line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoggedEvent {
    /// 1-based source line of the block.
    pub line: u32,
    /// What happened, e.g. `M3 spindle clockwise, 1200 rpm`.
    pub text: String,
}

/// What a run did: counts, distances, nominal and planned time, axis peaks, logs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunReport {
    /// Machine data name.
    pub machine: String,
    /// Blocks executed: filled in by the caller (the machine sees commands, not blocks); 0 here.
    pub blocks: u64,
    /// All motion commands: rapid + feed + arc.
    pub motion_segments: u64,
    /// G0 moves.
    pub rapid_segments: u64,
    /// Straight feed moves (G1).
    pub feed_segments: u64,
    /// Arcs and helices (G2/G3).
    pub arc_segments: u64,
    /// Path length of the rapids, mm.
    pub rapid_distance_mm: f64,
    /// Path length of the feed moves (lines and arcs), mm.
    pub feed_distance_mm: f64,
    /// Rapids + feeds + dwells, seconds, no acceleration.
    pub nominal_time_s: f64,
    /// Dwells alone, seconds.
    pub dwell_time_s: f64,
    /// Box around the whole tool path incl. arc extrema, machine X Y Z, mm; `None` without motion.
    pub bounding_box: Option<BoundingBox>,
    /// Tools put in the spindle, in order of their first change.
    pub tools_used: Vec<u32>,
    /// Number of tool changes (M6).
    pub tool_changes: u64,
    /// Operator messages, in order.
    pub messages: Vec<LoggedEvent>,
    /// Spindle, coolant, tool change, auxiliary M functions, stops and program end, in order.
    pub m_functions: Vec<LoggedEvent>,
    /// Where the machine stands after the last accepted command.
    pub final_position: Pose,
    /// True once a program end (M2/M30) was executed.
    pub program_ended: bool,
    /// Planned cycle time: the duration of the servo-rate setpoint trace (acceleration, jerk,
    /// look-ahead and dwells included), s. Filled by [`SimMachine::finish`].
    pub cycle_time_s: f64,
    /// Servo period of the trace, s.
    pub servo_period_s: f64,
    /// Setpoints executed (one per servo period, plus the final one).
    pub setpoints: u64,
    /// Feed override the run used, %.
    pub feed_override_percent: f64,
    /// Peaks of every machine axis against its limits.
    pub axes: Vec<AxisMotion>,
    /// Largest bound of the distance from the programmed path of any planned piece, mm.
    pub max_path_deviation_mm: f64,
    /// The contour error measured on the trace: the largest distance of a setpoint from the
    /// programmed path, at junctions and elsewhere, with where it occurred.
    pub contour_error: crate::sim_motion::ContourErrors,
    /// Per executed block (the first 100 000): planned and nominal time and the limit that set
    /// its speed.
    pub block_times: Vec<crate::sim_motion::BlockTime>,
    /// More blocks ran than `block_times` lists.
    pub block_times_truncated: bool,
    /// The ten blocks that lose the most time against nominal, most first.
    pub slowest_blocks: Vec<crate::sim_motion::BlockTime>,
    /// Limit, travel and tolerance violations of the setpoints (the first 100 or so); must be empty.
    pub violations: Vec<LoggedEvent>,
    /// How many violations in all.
    pub violation_count: u64,
    /// Per spindle that turned: the range of its commanded speed over the setpoints (under G96 the
    /// speed the law gives at each position).
    pub spindles: Vec<crate::sim_motion::SpindleRange>,
    /// The stock-removal simulation's results, when the run had a stock.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stock: Option<stanok_stock::report::StockReport>,
    /// A constant-surface-speed law (G96) was in force at some point of the run.
    pub surface_speed: bool,
    /// The operator's feed hold of the run (`SimOptions::feed_hold`): at machine time `at_s` for
    /// `standstill_s` seconds; None without one.
    pub feed_hold: Option<crate::sim_motion::FeedHoldReport>,
}

/// Executes Canon commands on a simulated machine (see the module doc).
#[derive(Debug)]
pub struct SimMachine {
    machine: MachineData,
    /// The machine's axis for each index of `Pose::to_array`, if it has one.
    axes: [Option<AxisData>; 9],
    /// Last commanded speed of each spindle, rev/min.
    spindle_rpm: BTreeMap<u8, f64>,
    report: RunReport,
    motion: MotionRun,
    /// Rules 1 and 2 of the module doc (it also follows tool-centre-point control).
    travel: TravelCheck,
    /// Bound on simulated machine time, s (`time_bound.rs`).
    max_machine_time_s: f64,
    /// `machine::long-block` warnings (at most [`MAX_WARNINGS`]).
    warnings: Vec<Diagnostic>,
}

/// Most warnings a run keeps.
const MAX_WARNINGS: usize = 100;

/// How the log names a spindle: the main one (Canon's 0) plainly, the others by their number
/// counted from 1 (AxiOMA's S2…S4, LinuxCNC's `$1`… are spindles 2…).
fn spindle_name(spindle: u8) -> String {
    match spindle {
        0 => "spindle".into(),
        n => format!("spindle {}", u32::from(n) + 1),
    }
}

/// The M-function log's entry for M9.
const COOLANT_OFF: &str = "M9 coolant off";

/// Which counter a straight move goes to.
#[derive(Clone, Copy)]
enum LineKind {
    Rapid,
    Feed,
}

/// Length a rate applies to, and whether it is in mm (module doc).
fn line_length(start: &Pose, end: &Pose) -> (f64, bool) {
    let (s, e) = (start.to_array(), end.to_array());
    let len = |r: std::ops::Range<usize>| r.map(|i| (e[i] - s[i]).powi(2)).sum::<f64>().sqrt();
    let (xyz, abc, uvw) = (len(0..3), len(3..6), len(6..9));
    if xyz > 0.0 {
        (xyz, true)
    } else if uvw > 0.0 {
        (uvw, true)
    } else {
        (abc, false)
    }
}

impl SimMachine {
    /// A machine standing at the origin with an empty report, default options (1 ms servo period,
    /// no override).
    pub fn new(machine: MachineData) -> Self {
        Self::with_options(machine, SimOptions::default())
    }

    /// A machine standing at the origin with an empty report, running with `options`.
    pub fn with_options(machine: MachineData, options: SimOptions) -> Self {
        let mut axes: [Option<AxisData>; 9] = Default::default();
        for a in &machine.axes {
            axes[a.pose_index()] = Some(a.clone());
        }
        let report = RunReport {
            machine: machine.name.clone(),
            blocks: 0,
            motion_segments: 0,
            rapid_segments: 0,
            feed_segments: 0,
            arc_segments: 0,
            rapid_distance_mm: 0.0,
            feed_distance_mm: 0.0,
            nominal_time_s: 0.0,
            dwell_time_s: 0.0,
            bounding_box: None,
            tools_used: Vec::new(),
            tool_changes: 0,
            messages: Vec::new(),
            m_functions: Vec::new(),
            final_position: Pose::ZERO,
            program_ended: false,
            cycle_time_s: 0.0,
            servo_period_s: options.servo_period_s,
            setpoints: 0,
            feed_override_percent: options.feed_override * 100.0,
            axes: Vec::new(),
            max_path_deviation_mm: 0.0,
            contour_error: Default::default(),
            block_times: Vec::new(),
            block_times_truncated: false,
            slowest_blocks: Vec::new(),
            violations: Vec::new(),
            violation_count: 0,
            spindles: Vec::new(),
            stock: None,
            surface_speed: false,
            feed_hold: None,
        };
        let motion = MotionRun::new(&machine, &options);
        let travel = TravelCheck::new(&machine);
        SimMachine {
            machine,
            axes,
            spindle_rpm: BTreeMap::new(),
            report,
            motion,
            travel,
            max_machine_time_s: options.max_machine_time_s,
            warnings: Vec::new(),
        }
    }

    /// Every setpoint also goes to `sink` (a trace writer, the panel's machine): every servo
    /// period is then stepped.
    pub fn set_setpoint_sink(&mut self, sink: SetpointSink) {
        self.motion.set_observer(sink);
    }

    /// A progress display: sees the setpoints, but not necessarily every one (steady stretches
    /// — dwells, straight cruises — are skipped, so a long dwell costs no work).
    pub fn set_progress_sink(&mut self, sink: SetpointSink) {
        self.motion.set_sparse_observer(sink);
    }

    /// Simulates the stock the program cuts (`stanok-stock`): from now on every accepted command
    /// and every setpoint also go to it, and the report gets its results.
    pub fn set_stock(&mut self, stock: stanok_stock::sim::StockSim) {
        self.motion.set_stock(stock);
    }

    /// Hands the stock simulation to `o` after every setpoint it took (a live view samples it
    /// there, at its own rate: the call is on the servo path, so it must be cheap when it does
    /// not sample).
    pub fn set_stock_observer(&mut self, o: crate::sim_motion::StockObserver) {
        self.motion.set_stock_observer(o);
    }

    /// The stock simulation, if there is one (its mesh, its collisions so far).
    pub fn stock(&self) -> Option<&stanok_stock::sim::StockSim> {
        self.motion.stock()
    }

    /// Runs everything the planner holds to its end, so that the machine stands at the last
    /// accepted position (the path stops there: an operator's single block or program stop).
    pub fn drain_motion(&mut self) {
        self.motion.drain();
    }

    /// Connects the operator's feed-hold button, read at every servo instant
    /// ([`stanok_motion::hold::HoldSwitch`]).
    pub fn set_hold_switch(&mut self, switch: std::sync::Arc<stanok_motion::hold::HoldSwitch>) {
        self.motion.set_hold_switch(switch);
    }

    /// Feed override (fraction, 0…2) from the next servo instant on: on the motion being executed
    /// and on everything planned ([`stanok_motion::overrides`]).
    pub fn set_feed_override(&mut self, fraction: f64) {
        self.motion.set_feed_override(fraction);
    }

    /// Rapid override (fraction, 0…1) from the next servo instant on.
    pub fn set_rapid_override(&mut self, fraction: f64) {
        self.motion.set_rapid_override(fraction);
    }

    /// Spindle override (fraction, 0.5…1.2) from the next servo instant on.
    pub fn set_spindle_override(&mut self, fraction: f64) {
        self.motion.set_spindle_override(fraction);
    }

    /// Connects the operator's override knobs ([`stanok_motion::overrides::OverrideSwitch`]),
    /// read at every servo instant: a thread-safe handle the panel sets at any time.
    pub fn set_override_switch(
        &mut self,
        switch: std::sync::Arc<stanok_motion::overrides::OverrideSwitch>,
    ) {
        self.motion.set_override_switch(switch);
    }

    /// The program is over (or stopped at an error): runs the motion still in the planner's
    /// window to its end and returns the full report.
    pub fn finish(&mut self) -> RunReport {
        self.motion.finish();
        self.report()
    }

    /// The machine data this machine runs with.
    pub fn machine(&self) -> &MachineData {
        &self.machine
    }

    /// Applies one command. Returns `Err(Diagnostic)` if it cannot run (an axis the machine lacks, a
    /// travel-limit violation); the state is then unchanged and the run stops there.
    pub fn apply(&mut self, cmd: &Spanned<Canon>) -> Result<(), Diagnostic> {
        if let Some(at) = self.motion.stopped_at() {
            return Err(time_bound::time_limit(
                self.max_machine_time_s,
                at,
                cmd.span,
            ));
        }
        // Guard 1 of `time_bound.rs`: the nominal time, before anything of the command runs.
        let seconds = time_bound::nominal_seconds(&self.machine, &cmd.value);
        if seconds > 0.0 {
            let at = self.report.nominal_time_s + seconds;
            if at.is_nan() || at > self.max_machine_time_s {
                return Err(time_bound::time_limit(
                    self.max_machine_time_s,
                    at,
                    cmd.span,
                ));
            }
            if let Some(w) = time_bound::long_block(&self.machine, &cmd.value, cmd.span) {
                if self.warnings.len() < MAX_WARNINGS {
                    self.warnings.push(w);
                }
            }
        }
        self.check_and_log(cmd)?;
        self.motion.apply(&cmd.value, cmd.span.line);
        // Guard 2: the interpolator stopped at the bound while this command's motion ran.
        if let Some(at) = self.motion.stopped_at() {
            return Err(time_bound::time_limit(
                self.max_machine_time_s,
                at,
                cmd.span,
            ));
        }
        Ok(())
    }

    /// The machine's warnings so far (`machine::long-block`), emptied.
    pub fn take_warnings(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.warnings)
    }

    /// Checks a command and updates the counters and logs (module doc, steps 1–3).
    fn check_and_log(&mut self, cmd: &Spanned<Canon>) -> Result<(), Diagnostic> {
        self.travel.check(cmd)?;
        let line = cmd.span.line;
        match &cmd.value {
            Canon::Init { position, .. } => self.report.final_position = *position,
            Canon::StraightTraverse(m) => self.apply_line(m, LineKind::Rapid),
            Canon::StraightFeed(m) => self.apply_line(m, LineKind::Feed),
            Canon::ArcFeed(a) => self.apply_arc(a),
            Canon::SplineFeed(sp) => self.apply_spline(sp),
            // The probe stops where it makes (or loses) contact.
            Canon::StraightProbe {
                motion, contact, ..
            } => self.apply_line(
                &motion.stopped_at(contact.as_deref().copied()),
                LineKind::Feed,
            ),
            Canon::RigidTap { start, end, .. } => {
                let down = LineMove {
                    start: *start,
                    end: *end,
                    feed: 0.0,
                    law: stanok_canon::FeedLaw::PerMinute,
                };
                self.apply_line(&down, LineKind::Feed);
                let up = LineMove {
                    start: *end,
                    end: *start,
                    feed: 0.0,
                    law: stanok_canon::FeedLaw::PerMinute,
                };
                self.apply_line(&up, LineKind::Feed);
            }
            Canon::OrientSpindle {
                spindle, degrees, ..
            } => self.log(
                line,
                format!("M19 {} orient to {degrees} deg", spindle_name(*spindle)),
            ),
            Canon::WaitSpindleOrient { spindle, timeout } => self.log(
                line,
                format!(
                    "M19 {} wait up to {timeout} s for an orientation",
                    spindle_name(*spindle)
                ),
            ),
            Canon::DigitalOutput { index, on, .. } => self.log(
                line,
                format!("output {index} {}", if *on { "on" } else { "off" }),
            ),
            Canon::WaitInput { index, timeout, .. } => self.log(
                line,
                format!("M66 wait for input {index} (timeout {timeout} s)"),
            ),
            Canon::Dwell { seconds } => {
                let t = nominal::dwell_time(*seconds);
                self.report.dwell_time_s += t;
                self.report.nominal_time_s += t;
            }
            Canon::SetSpindleSpeed { spindle, rpm } => {
                self.spindle_rpm.insert(*spindle, *rpm);
            }
            Canon::StartSpindle { spindle, direction } => {
                let (code, sense) = match direction {
                    SpindleDirection::Clockwise => ("M3", "clockwise"),
                    SpindleDirection::CounterClockwise => ("M4", "counter-clockwise"),
                };
                let speed = match self.spindle_rpm.get(spindle) {
                    Some(rpm) => format!(", {rpm} rpm"),
                    None => String::new(),
                };
                self.log(
                    line,
                    format!("{code} {} {sense}{speed}", spindle_name(*spindle)),
                );
            }
            Canon::StopSpindle { spindle } => {
                self.log(line, format!("M5 {} stop", spindle_name(*spindle)))
            }
            Canon::Mist { on: true } => self.log(line, "M7 mist on"),
            Canon::Flood { on: true } => self.log(line, "M8 flood on"),
            // M9 switches mist and flood off together: one entry, not one per coolant.
            Canon::Mist { on: false } | Canon::Flood { on: false } => {
                let logged = self.report.m_functions.last();
                if !logged.is_some_and(|e| e.line == line && e.text == COOLANT_OFF) {
                    self.log(line, COOLANT_OFF);
                }
            }
            Canon::SetSurfaceSpeedLaw { law: Some(_), .. } => self.report.surface_speed = true,
            Canon::ChangeTool { tool, .. } => {
                if !self.report.tools_used.contains(tool) {
                    self.report.tools_used.push(*tool);
                }
                self.report.tool_changes += 1;
                self.log(line, format!("M6 tool change to T{tool}"));
            }
            Canon::SetCurrentTool { tool, .. } => {
                if *tool != 0 && !self.report.tools_used.contains(tool) {
                    self.report.tools_used.push(*tool);
                }
                self.log(line, format!("M61 tool T{tool} declared in the spindle"));
            }
            Canon::ChangeSpindleTool { spindle, tool } => {
                self.report.tool_changes += 1;
                self.log(
                    line,
                    format!("M6 spindle {} tool change to T{tool}", spindle + 1),
                );
            }
            Canon::AuxiliaryFunction { number, timing } => {
                let when = match timing {
                    AuxTiming::Prefix => "before",
                    AuxTiming::Postfix => "after",
                };
                self.log(
                    line,
                    format!("M{number} auxiliary function ({when} motion)"),
                );
            }
            Canon::ProgramStop { optional } => self.log(
                line,
                if *optional {
                    "M1 optional stop"
                } else {
                    "M0 program stop"
                },
            ),
            Canon::PalletShuttle => self.log(line, "pallet shuttle"),
            Canon::Log { action, text } => {
                self.log(line, format!("program log {action:?}: {text}"))
            }
            Canon::Finish => {
                self.report.program_ended = true;
                self.log(line, "% end of program text");
            }
            Canon::ProgramEnd => {
                self.report.program_ended = true;
                self.log(line, "M2/M30 program end");
            }
            Canon::Message { text } => {
                if !text.is_empty() {
                    self.report.messages.push(LoggedEvent {
                        line,
                        text: text.clone(),
                    });
                }
            }
            // State for printers and the interpreter; nothing happens on the machine.
            Canon::SetFeedRate { .. }
            | Canon::SetFeedMode { .. }
            | Canon::SelectPlane { .. }
            | Canon::UseLengthUnits { .. }
            | Canon::SetG5xOffset { .. }
            | Canon::SetG92Offset { .. }
            | Canon::SetXyRotation { .. }
            | Canon::SetSpindleMode { .. }
            | Canon::SetSurfaceSpeedLaw { .. }
            | Canon::StartSpindleSync { .. }
            | Canon::StopSpindleSync
            | Canon::SetPathMode { .. }
            | Canon::SetAccelerationProfile { .. }
            | Canon::SetFeedOverrideEnabled { .. }
            | Canon::SetSpindleOverrideEnabled { .. }
            | Canon::SetAdaptiveFeed { .. }
            | Canon::SetFeedHoldEnabled { .. }
            | Canon::SelectTool { .. }
            | Canon::UseToolLengthOffset { .. }
            | Canon::StartToolChange
            | Canon::SetToolTableEntry { .. }
            | Canon::ReloadToolTable
            | Canon::SetOrientationInterpolation { .. }
            | Canon::Comment { .. } => {}
            // Checked (and followed) by the travel check above.
            Canon::SetToolCentrePoint { .. } => {}
        }
        Ok(())
    }

    /// The report so far; the motion fields cover the setpoints executed so far (call
    /// [`SimMachine::finish`] after the last command for the whole run).
    pub fn report(&self) -> RunReport {
        let mut r = self.report.clone();
        self.motion.fill(&mut r);
        r
    }

    fn log(&mut self, line: u32, text: impl Into<String>) {
        self.report.m_functions.push(LoggedEvent {
            line,
            text: text.into(),
        });
    }

    fn apply_line(&mut self, m: &LineMove, kind: LineKind) {
        let (s, e) = (m.start.to_array(), m.end.to_array());
        let (length, in_mm) = line_length(&m.start, &m.end);
        let distance = if in_mm { length } else { 0.0 };
        let r = &mut self.report;
        let time = match kind {
            LineKind::Rapid => {
                let deltas: Vec<f64> = s.iter().zip(&e).map(|(a, b)| b - a).collect();
                let limits: Vec<AxisLimits> = self
                    .axes
                    .iter()
                    .map(|a| AxisLimits {
                        max_velocity_per_min: a.as_ref().map_or(0.0, |a| a.max_velocity),
                    })
                    .collect();
                r.rapid_segments += 1;
                r.rapid_distance_mm += distance;
                nominal::rapid_time(length, &deltas, self.machine.rapid_rate, &limits)
            }
            LineKind::Feed => {
                r.feed_segments += 1;
                r.feed_distance_mm += distance;
                nominal::feed_time(length, clamp_feed(m.feed, self.machine.max_feed))
            }
        };
        r.motion_segments += 1;
        r.nominal_time_s += time;
        let (ps, pe) = (m.start.xyz(), m.end.xyz());
        BoundingBox::include(&mut r.bounding_box, ps, ps);
        BoundingBox::include(&mut r.bounding_box, pe, pe);
        r.final_position = m.end;
    }

    fn apply_arc(&mut self, a: &ArcMove) {
        let helix = Helix {
            start: a.start.xyz(),
            end: a.end.xyz(),
            centre: a.centre,
            axis: a.axis,
            turns: a.turns,
        };
        let (box_lo, box_hi) = helix.bounding_box();
        let length = helix.length();
        let r = &mut self.report;
        r.arc_segments += 1;
        r.motion_segments += 1;
        r.feed_distance_mm += length;
        r.nominal_time_s += nominal::feed_time(length, clamp_feed(a.feed, self.machine.max_feed));
        BoundingBox::include(&mut r.bounding_box, box_lo, box_hi);
        r.final_position = a.end;
    }
}

impl SimMachine {
    /// A spline: checked and measured over its tessellation (chord tolerance 1 µm).
    fn apply_spline(&mut self, sp: &SplineMove) {
        let curve = Nurbs::new(sp.degree, &sp.control_points, &sp.weights, &sp.knots);
        let mut pts = Vec::new();
        curve.tessellate(1e-3, &mut pts);
        let (s, e) = (sp.start.to_array(), sp.end.to_array());
        let mut lo = [0.0; 9];
        let mut hi = [0.0; 9];
        for i in 0..9 {
            (lo[i], hi[i]) = (s[i].min(e[i]), s[i].max(e[i]));
        }
        for p in &pts {
            for i in 0..3 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        let length: f64 = pts
            .windows(2)
            .map(|w| stanok_geom::norm(stanok_geom::sub(w[1], w[0])))
            .sum();
        let r = &mut self.report;
        r.feed_segments += 1;
        r.motion_segments += 1;
        r.feed_distance_mm += length;
        r.nominal_time_s += nominal::feed_time(length, clamp_feed(sp.feed, self.machine.max_feed));
        BoundingBox::include(
            &mut r.bounding_box,
            [lo[0], lo[1], lo[2]],
            [hi[0], hi[1], hi[2]],
        );
        r.final_position = sp.end;
    }
}

/// The feed a control would run: the programmed one, at most `max_feed` (NaN stays NaN and so takes
/// no time in `nominal::feed_time`).
fn clamp_feed(feed: f64, max_feed: f64) -> f64 {
    if feed > max_feed {
        max_feed
    } else {
        feed
    }
}

#[cfg(test)]
#[path = "sim_tests.rs"]
mod tests;
