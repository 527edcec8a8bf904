//! The machine thread: one action at a time — a program, an MDI block, a jog, a reference return,
//! a touch-off — on the simulated machine (planner, interpolator, servo setpoints), paced against
//! the wall clock.
//!
//! ## Design
//! ```text
//!  HTTP handlers ──Event (start, cycle start, acknowledge, manual)──▶ machine thread
//!        │          atomics (hold, stop, single block, M01, overrides, jog)   │ run.rs: Interpreter
//!        │                                                                    │  → BlockSearch → tag
//!        ▼                                                                    │  → SimMachine
//!  Mutex<Status> ◀── setpoint sink (paced.rs): pace, snapshot of the executing ┘  (manual.rs: jog,
//!        │            block (executing.rs), publish (every servo period)            home, MDI)
//!        └─▶ WebSocket tasks copy the latest snapshot ~30 times a second
//! ```
//! * **The machine persists between actions** ([`MachineContext`]): where it stands, the stored
//!   control data (offsets, tool table — changed by touch-off and by what programs write, as
//!   LinuxCNC keeps its `.var` file), which axes are referenced. Every program and MDI block
//!   starts where the machine stands (`InterpOptions::initial_position`) with that data; checks
//!   and previews read the same context, so they see what the run will see.
//! * **The state shown is the executing block's** (`executing.rs`): commands are tagged with a
//!   snapshot of the state they leave, the interpolator hands the tag back with each setpoint.
//! * **Pacing, back-pressure, feed hold, stop, program stops, single block** as described in
//!   `paced.rs` and `run.rs`. The thread never waits for a client.
//! * **Overrides** are the motion stage's [`OverrideSwitch`], read by the interpolator at every
//!   servo instant: a change acts on the motion being executed and on everything planned.
//!
//! Invariant: a program with an error never starts (the HTTP layer checks it first); an error
//! found while running (a travel limit) stops the run at that block, nothing after it moves; a
//! panic inside an action is caught, reported as an alarm, and the thread goes on.

use crate::executing::Snapshot;
use crate::jobs::Cancel;
use crate::state::{ActiveCode, MachineState, SpindleState};
use serde::Serialize;
use stanok_canon::setup::ControlData;
use stanok_canon::{Diagnostic, Pose};
use stanok_interp::InterpOptions;
use stanok_machine::MachineData;
use stanok_machine::OverrideSwitch;
use stanok_motion::hold::HoldSwitch;
use stanok_syntax::Dialect;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Planner look-ahead of the panel's runs and previews, pieces (the motion stage's default:
/// overrides act on everything planned, so the window need not be short for them).
pub const SERVE_LOOKAHEAD: usize = stanok_motion::limits::DEFAULT_LOOKAHEAD;

/// Every dialect the panel runs, in the selector's order.
pub const DIALECTS: [Dialect; 8] = [
    Dialect::Axioma,
    Dialect::Rs274ngc,
    Dialect::Balt,
    Dialect::Mazatrol,
    Dialect::Nc31,
    Dialect::P2p32,
    Dialect::Mc2101,
    Dialect::Gost20999,
];

/// The dialect with this id (`Dialect::id`).
pub fn dialect_by_id(id: &str) -> Option<Dialect> {
    DIALECTS.iter().copied().find(|d| d.id() == id)
}

/// Where the run is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunState {
    /// Nothing running.
    Idle,
    /// Cycle start accepted, the thread is setting up.
    Starting,
    /// Executing.
    Running,
    /// Waiting for cycle start after a block (single block).
    BlockEnd,
    /// Waiting for acknowledge of M00/M01.
    Prompt,
    /// The program ended.
    Finished,
    /// Stopped by the operator.
    Stopped,
    /// Stopped by an error.
    Alarm,
    /// A jog is moving.
    Jogging,
    /// A reference return is moving.
    Homing,
    /// An MDI block is executing.
    Mdi,
}

impl RunState {
    /// A program is in progress (started and not ended): nothing else may run or be loaded.
    pub fn program_active(self) -> bool {
        matches!(
            self,
            RunState::Starting | RunState::Running | RunState::BlockEnd | RunState::Prompt
        )
    }

    /// The machine is busy with anything (a program or a manual action).
    pub fn busy(self) -> bool {
        self.program_active()
            || matches!(self, RunState::Jogging | RunState::Homing | RunState::Mdi)
    }
}

/// A diagnostic as the page shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Alarm {
    /// 1-based line.
    pub line: u32,
    /// 1-based column.
    pub column: u32,
    /// `error` or `warning`.
    pub severity: String,
    /// Manual number or Stanok code.
    pub code: String,
    /// What is wrong.
    pub message: String,
}

impl Alarm {
    /// From a diagnostic.
    pub fn of(d: &Diagnostic) -> Self {
        Alarm {
            line: d.span.line,
            column: d.span.column,
            severity: format!("{:?}", d.severity).to_lowercase(),
            code: d.code.to_string(),
            message: d.message.clone(),
        }
    }

    /// An error of the panel itself (no program location: line 0 unless given).
    pub fn panel(code: &str, line: u32, message: impl Into<String>) -> Self {
        Alarm {
            line,
            column: 1,
            severity: "error".into(),
            code: code.into(),
            message: message.into(),
        }
    }
}

/// Everything the page shows, sent as JSON over the WebSocket and by `GET /api/state`.
#[derive(Debug, Clone, Serialize)]
pub struct Status {
    /// Increases with every published change.
    pub seq: u64,
    /// Run state.
    pub run_state: RunState,
    /// Name of the running (or loaded) program.
    pub program: String,
    /// Its dialect (`Dialect::id`).
    pub dialect: String,
    /// Source line of the block the machine executes (the current setpoint's); 0 = none.
    pub line: u32,
    /// The machine's axis letters, in `Pose` order.
    pub axes: Vec<char>,
    /// Actual position, machine coordinates X…W.
    pub machine_position: [f64; 9],
    /// Actual position in work coordinates (offsets in force).
    pub work_position: [f64; 9],
    /// Programmed feed of the executing block, mm/min.
    pub feed_programmed: f64,
    /// Actual path speed in X Y Z, mm/min.
    pub feed_actual: f64,
    /// Tool axis, a unit vector in machine coordinates (from the rotary axes on a 5-axis machine;
    /// +Z otherwise).
    pub tool_axis: [f64; 3],
    /// Spindles as the executing block commands them.
    pub spindles: [SpindleState; 4],
    /// Speed each spindle turns at now (the commanded one, under G96 at this position, times the
    /// spindle override), rev/min.
    pub spindle_actual_rpm: [f64; 4],
    /// Tool in the spindle.
    pub tool: u32,
    /// Active tool edge (D).
    pub edge: u8,
    /// Active G codes by group (the executing block's).
    pub g_codes: Vec<ActiveCode>,
    /// Active M functions by group (the executing block's).
    pub m_codes: Vec<ActiveCode>,
    /// Machine time since cycle start (holds and stops included), s.
    pub elapsed_s: f64,
    /// Planned cycle time of the whole program, s.
    pub estimated_s: f64,
    /// Operator message (MSG) of the executed blocks, empty when none or acknowledged.
    pub message: String,
    /// M00/M01 prompt waiting for acknowledge.
    pub prompt: Option<String>,
    /// A refusal the operator must read (e.g. a load while a program is paused); stays until
    /// acknowledged.
    pub notice: Option<String>,
    /// Errors that stopped or refused the run.
    pub alarms: Vec<Alarm>,
    /// Feed override in force, % (0…200).
    pub feed_override: u32,
    /// Rapid override in force, % (0…100).
    pub rapid_override: u32,
    /// Spindle override in force, % (50…120).
    pub spindle_override: u32,
    /// Machine time since which the overrides shown act on the motion (the first setpoint that
    /// ran with them), s.
    pub overrides_since_s: f64,
    /// Single block switch.
    pub single_block: bool,
    /// Optional stop (M01) switch.
    pub optional_stop: bool,
    /// Feed hold pressed.
    pub held: bool,
    /// Per axis of `axes`: referenced (homed) since the panel started.
    pub homed: Vec<bool>,
    /// Line of the running block search, if any.
    pub search_line: Option<u32>,
    /// Machine state of the executing block (see [`MachineState`]).
    pub state: MachineState,
    /// The machine state when the run's marked line (the search line, or `mark_line`) first
    /// reached the machine.
    pub marked_state: Option<MachineState>,
    /// Machine position at the program end (after the last setpoint), when finished.
    pub final_position: Option<[f64; 9]>,
    /// Planned cycle time of the finished run, s.
    pub cycle_time_s: Option<f64>,
}

impl Status {
    fn new(axes: Vec<char>) -> Self {
        let homed = vec![false; axes.len()];
        Status {
            seq: 0,
            run_state: RunState::Idle,
            program: String::new(),
            dialect: Dialect::Rs274ngc.id().into(),
            line: 0,
            axes,
            machine_position: [0.0; 9],
            work_position: [0.0; 9],
            feed_programmed: 0.0,
            feed_actual: 0.0,
            tool_axis: [0.0, 0.0, 1.0],
            spindles: MachineState::default().spindles,
            spindle_actual_rpm: [0.0; 4],
            tool: 0,
            edge: 0,
            g_codes: Vec::new(),
            m_codes: Vec::new(),
            elapsed_s: 0.0,
            estimated_s: 0.0,
            message: String::new(),
            prompt: None,
            notice: None,
            alarms: Vec::new(),
            feed_override: 100,
            rapid_override: 100,
            spindle_override: 100,
            overrides_since_s: 0.0,
            single_block: false,
            optional_stop: true,
            held: false,
            homed,
            search_line: None,
            state: MachineState::default(),
            marked_state: None,
            final_position: None,
            cycle_time_s: None,
        }
    }

    /// Shows a block's state: line, DRO, codes (not the message: see `paced.rs`).
    pub fn show_block(&mut self, snap: &Snapshot) {
        self.line = snap.line;
        self.state = snap.state.clone();
        self.work_position = self.state.work_of(&self.machine_position);
        self.feed_programmed = snap.state.feed;
        self.spindles = snap.state.spindles;
        self.tool = snap.state.tool;
        self.edge = snap.edge;
        self.g_codes = snap.g_codes.clone();
        self.m_codes = snap.m_codes.clone();
    }
}

/// The operator's switches, read by the machine thread without locking.
#[derive(Debug)]
pub struct Controls {
    /// Feed hold (read by the interpolator at every servo instant).
    pub hold: Arc<HoldSwitch>,
    /// Stop / reset requested (also read by the interpreter's source: `jobs::CancelReader`).
    pub stop: Cancel,
    /// Single block.
    pub single_block: AtomicBool,
    /// M01 stops.
    pub optional_stop: AtomicBool,
    /// Feed, rapid and spindle override: the motion stage's knobs, read by the interpolator at
    /// every servo instant of a program or MDI block (jogs and reference returns ignore them).
    pub overrides: Arc<OverrideSwitch>,
    /// A continuous jog moves until this instant (ms since the thread started; extended by the
    /// page while the key is held, so a lost page stops the jog).
    pub jog_until_ms: AtomicU64,
    /// When the thread started (the origin of `jog_until_ms`).
    pub epoch: Instant,
}

impl Controls {
    /// Milliseconds since `epoch`.
    pub fn now_ms(&self) -> u64 {
        self.epoch.elapsed().as_millis() as u64
    }
}

/// A manual action (`manual.rs`).
#[derive(Debug, Clone)]
pub enum Manual {
    /// Jog one axis (index in `Pose` order) by `increment` (None = continuous, to the travel
    /// limit, while `Controls::jog_until_ms` is ahead) at `speed` unit/min.
    Jog {
        /// Axis, `Pose` index.
        axis: usize,
        /// +1 or −1.
        direction: f64,
        /// Step, unit; None = continuous.
        increment: Option<f64>,
        /// unit/min.
        speed: f64,
    },
    /// Reference return of one axis or (None) all: the tool axis first, then the others.
    Home {
        /// Axis, `Pose` index; None = all.
        axis: Option<usize>,
    },
    /// Set the active work offset so that the axis reads `value` here.
    TouchOff {
        /// Axis, `Pose` index.
        axis: usize,
        /// Work coordinate wanted, unit.
        value: f64,
    },
    /// Execute one MDI block.
    Mdi {
        /// The block.
        text: String,
        /// In this dialect.
        dialect: Dialect,
    },
}

/// What a manual action answers.
#[derive(Debug, Clone, PartialEq)]
pub enum ManualReply {
    /// Accepted (and, for MDI, executed): the diagnostics (warnings) and a note.
    Done {
        /// What happened.
        note: String,
        /// Warnings (MDI).
        diagnostics: Vec<Alarm>,
    },
    /// Refused: why, and the diagnostics of an MDI block.
    Refused {
        /// Why.
        error: String,
        /// Errors (MDI).
        diagnostics: Vec<Alarm>,
    },
}

/// What wakes the machine thread.
#[derive(Debug)]
pub enum Event {
    /// Run a program.
    Start(Box<Job>),
    /// Cycle start while waiting at a block end or a prompt.
    CycleStart,
    /// Acknowledge a prompt or a message.
    Acknowledge,
    /// A manual action, sent at the instant given; the answer goes to the sender.
    Manual(Manual, Instant, tokio::sync::oneshot::Sender<ManualReply>),
}

/// A program to run.
#[derive(Debug, Clone)]
pub struct Job {
    /// Name shown.
    pub name: String,
    /// Program text.
    pub text: Arc<str>,
    /// Its dialect.
    pub dialect: Dialect,
    /// Block search: start at this 1-based line.
    pub search_line: Option<u32>,
    /// Record the machine state when this line first reaches the machine (tests; the search line
    /// is always recorded).
    pub mark_line: Option<u32>,
    /// Planned cycle time (from the check), s.
    pub estimated_s: f64,
    /// The stock to cut (`stock.rs`), if any.
    pub stock: Option<stanok_stock::spec::StockShape>,
}

/// The machine between actions (module doc).
#[derive(Debug, Clone)]
pub struct MachineContext {
    /// Where the machine stands, machine coordinates.
    pub position: [f64; 9],
    /// Stored control data: offsets, tools, parameters.
    pub control: ControlData,
    /// Referenced axes, `Pose` order.
    pub homed: [bool; 9],
}

/// State shared between the HTTP side and the machine thread.
#[derive(Debug)]
pub struct Shared {
    /// Switches.
    pub controls: Controls,
    status: Mutex<Status>,
    events: Mutex<Sender<Event>>,
    context: Mutex<MachineContext>,
    /// The latest live message of the stock (`stock.rs`).
    pub stock: crate::stock::StockSlot,
}

impl Shared {
    /// The status, locked (a poisoned lock is taken over: the status is plain data).
    pub fn status(&self) -> MutexGuard<'_, Status> {
        self.status.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The machine between actions (position, stored data).
    pub fn context(&self) -> MachineContext {
        self.context
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }

    pub(crate) fn set_context(&self, ctx: &MachineContext) {
        *self.context.lock().unwrap_or_else(|e| e.into_inner()) = ctx.clone();
    }

    /// Wakes the machine thread.
    pub fn send(&self, event: Event) {
        let tx = self.events.lock().unwrap_or_else(|e| e.into_inner());
        let _ = tx.send(event);
    }

    /// Changes the status and counts the change.
    pub fn publish(&self, f: impl FnOnce(&mut Status)) {
        let mut s = self.status();
        f(&mut s);
        s.seq += 1;
    }
}

/// How the machine thread runs programs.
#[derive(Debug, Clone)]
pub struct MachineConfig {
    /// Machine data.
    pub machine: MachineData,
    /// Where `o<name> call` finds subroutine files (the program directory).
    pub subroutine_path: Vec<PathBuf>,
    /// 1 = real time, >1 faster, 0 = unpaced.
    pub time_scale: f64,
    /// Servo period, s.
    pub servo_period_s: f64,
}

/// Interpreter options for `machine` (as `stanok run` builds them), starting at `at` with its
/// stored data.
pub fn interp_options(
    machine: &MachineData,
    dialect: Dialect,
    subroutine_path: &[PathBuf],
    at: &MachineContext,
) -> InterpOptions {
    let mut opts = InterpOptions::new(dialect);
    opts.axes = machine.axis_mask();
    opts.arc_tolerance_mm = machine.arc_tolerance;
    opts.control = at.control.clone();
    opts.initial_position = Pose::from_array(at.position);
    opts.diameter_axes = machine.diameter_axes();
    opts.rs274_machine_units = machine.linuxcnc_units;
    if let Some(table) = stanok_interp::MTable::profile(&machine.m_functions) {
        opts.axioma.m_table = table;
    }
    opts.axioma
        .set_table_entries(&machine.feed_table, &machine.speed_table);
    let ch = &machine.channel;
    opts.axioma.set_channel(
        Some(machine.max_feed),
        ch.spindle_encoder,
        ch.plc_outputs,
        ch.compensation_depth,
        &ch.edge_positions,
    );
    opts.subroutine_path = subroutine_path.to_vec();
    // Tool-centre-point control (TRAORI, CVU, G43.4/G43.5) as on the command line.
    opts.five_axis = machine.tcp_kinematics();
    opts.ttpc_workpiece_frame = machine.ttpc_workpiece_frame();
    opts.mazatrol = mazatrol_params(machine);
    // M01 reaches the machine thread, which decides with the operator's switch.
    opts.optional_stop = true;
    opts
}

/// The Mazatrol front end's parameters from the machine's `[mazatrol]` section (defaults where it
/// has none; the series from the kinematics type when the section does not name it).
pub fn mazatrol_params(machine: &MachineData) -> stanok_interp::MazatrolParams {
    let data = machine.mazatrol.clone().unwrap_or_default();
    stanok_interp::MazatrolParams {
        series: match machine.mazatrol_series() {
            stanok_machine::MazatrolSeries::M => stanok_interp::MazatrolSeries::M,
            stanok_machine::MazatrolSeries::T => stanok_interp::MazatrolSeries::T,
        },
        decimal_point_type: data.decimal_point_type,
        peck_clearance: data.peck_clearance,
        thread_chamfer_angle: data.thread_chamfer_angle,
        g60_overshoot: data.g60_overshoot,
        tool_data_length: data.tool_data_length,
        g49_moves: data.g49_moves,
        mazatrol_wpc: data.mazatrol_wpc,
        ttpc_workpiece_frame: machine.ttpc_workpiece_frame(),
        power_on_feed_per_revolution: data
            .power_on_feed
            .map(|f| f == stanok_machine::MazatrolFeedMode::G95),
    }
}

/// Starts the machine thread, standing at the machine's origin (not referenced).
pub fn spawn(config: MachineConfig) -> Arc<Shared> {
    let (tx, rx) = std::sync::mpsc::channel();
    let axes = config.machine.axes.iter().map(|a| a.name).collect();
    let context = MachineContext {
        position: [0.0; 9],
        control: config.machine.control.clone(),
        homed: [false; 9],
    };
    let shared = Arc::new(Shared {
        controls: Controls {
            hold: Arc::new(HoldSwitch::default()),
            stop: Cancel::new(),
            single_block: AtomicBool::new(false),
            optional_stop: AtomicBool::new(true),
            overrides: Arc::new(OverrideSwitch::default()),
            jog_until_ms: AtomicU64::new(0),
            epoch: Instant::now(),
        },
        status: Mutex::new(Status::new(axes)),
        events: Mutex::new(tx),
        context: Mutex::new(context.clone()),
        stock: Default::default(),
    });
    let thread_shared = shared.clone();
    std::thread::Builder::new()
        .name("stanok-machine".into())
        .spawn(move || machine_loop(&config, &thread_shared, &rx, context))
        .expect("spawn the machine thread");
    shared
}

fn machine_loop(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    rx: &Receiver<Event>,
    mut here: MachineContext,
) {
    let mut mdi = crate::manual::MdiSession::default();
    while let Ok(event) = rx.recv() {
        match event {
            // The stop switch was cleared by the cycle start that sent this (`http::cycle_start`),
            // so a stop pressed before the thread picks the job up still counts.
            Event::Start(job) => {
                crate::run::run_program(config, shared, rx, &mut here, &job);
                // A program leaves its own modal state: MDI starts afresh from the stored data.
                mdi = Default::default();
            }
            Event::Acknowledge => shared.publish(|s| {
                s.message.clear();
                s.notice = None;
            }),
            Event::CycleStart => {}
            Event::Manual(action, sent, reply) => {
                let answer = if sent.elapsed() > Duration::from_secs(2) {
                    ManualReply::Refused {
                        error: "the machine was busy: the request came too late".into(),
                        diagnostics: Vec::new(),
                    }
                } else {
                    crate::manual::execute(config, shared, rx, &mut here, &mut mdi, action)
                };
                // The stored data first, then the answer: a load right after an MDI block's
                // answer must see what the block stored (it raced, and once saw the old data).
                shared.set_context(&here);
                let _ = reply.send(answer);
            }
        }
        shared.set_context(&here);
    }
}

/// Why a wait ended.
pub(crate) enum Woken {
    Go,
    Stop,
}

/// Waits for cycle start or acknowledge (or stop). Manual actions meanwhile are refused.
pub(crate) fn wait_for_operator(shared: &Shared, rx: &Receiver<Event>) -> Woken {
    loop {
        if shared.controls.stop.is_raised() {
            return Woken::Stop;
        }
        match rx.recv_timeout(Duration::from_millis(20)) {
            Ok(Event::CycleStart) | Ok(Event::Acknowledge) => return Woken::Go,
            Ok(Event::Start(_)) => {}
            Ok(Event::Manual(_, _, reply)) => {
                let _ = reply.send(ManualReply::Refused {
                    error: "a program is in progress: stop it first".into(),
                    diagnostics: Vec::new(),
                });
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => return Woken::Stop,
        }
    }
}

/// True if `x` has no NaN (the status goes out as JSON, where NaN is null).
pub(crate) fn finite9(x: &[f64; 9]) -> bool {
    x.iter().all(|v| v.is_finite())
}

/// Clears the Status fields a load or reset returns to the program's start.
pub(crate) fn reset_to_start(s: &mut Status, start: Option<&Snapshot>) {
    s.line = 0;
    s.message.clear();
    s.prompt = None;
    s.search_line = None;
    s.marked_state = None;
    s.final_position = None;
    s.cycle_time_s = None;
    s.elapsed_s = 0.0;
    s.feed_actual = 0.0;
    s.spindle_actual_rpm = [0.0; 4];
    s.held = false;
    match start {
        Some(snap) => s.show_block(snap),
        None => {
            s.state = MachineState {
                position: s.machine_position,
                ..MachineState::default()
            };
            s.feed_programmed = 0.0;
            s.spindles = MachineState::default().spindles;
            s.g_codes.clear();
            s.m_codes.clear();
        }
    }
    s.line = 0;
    s.work_position = s.state.work_of(&s.machine_position);
}

/// The override knobs in %, for the status.
pub(crate) fn switches(c: &Controls) -> (u32, u32, u32) {
    let o = c.overrides.get();
    let pct = |f: f64| (f * 100.0).round() as u32;
    (pct(o.feed), pct(o.rapid), pct(o.spindle))
}
