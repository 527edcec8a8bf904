//! The machine thread: one program at a time through interpreter → simulated machine (planner,
//! interpolator, servo setpoints), paced against the wall clock.
//!
//! ## Design
//! ```text
//!  HTTP handlers ──Event (start, cycle start, acknowledge)──▶ machine thread
//!        │          atomics (hold, stop, single block, M01, overrides)   │ Interpreter::next
//!        │                                                               │ BlockSearch::filter
//!        ▼                                                               │ SimMachine::apply
//!  Mutex<Status> ◀── setpoint sink: pace, publish (every servo period) ──┘   └─ MotionStage
//!        │
//!        └─▶ WebSocket tasks copy the latest snapshot ~30 times a second
//! ```
//! * **Pacing.** The setpoint sink sleeps until wall time `origin + (t − t₀) / time_scale` of
//!   each setpoint. When it finds itself more than 50 ms late (after a program stop or a single
//!   block wait, where machine time stood still, or on a busy host) it re-bases instead of
//!   rushing. `time_scale` 1 = real time; 10 = ten times faster (the tests); 0 = unpaced.
//! * **Back-pressure only downstream.** The thread never waits for a client: it writes the latest
//!   state into one `Mutex<Status>` (held for a copy's time) and every WebSocket task reads it at
//!   its own rate, so a slow client loses frames, never the machine.
//! * **Feed hold** is the motion stage's own ([`HoldSwitch`]): the interpolator brakes on the
//!   path, stands while held, resumes on release. **Stop** presses hold, and at rest abandons the
//!   run: the rest of the planner's window is computed unobserved and unpaced, the machine stays
//!   where it stopped. **Program stops** (M00, M01 with the optional-stop switch on) and **single
//!   block** drain the planner so that the machine is at rest at the block end, then wait for
//!   cycle start / acknowledge.
//! * **Overrides** are read before every command and apply to the commands planned from then on
//!   (the planner's window is `SERVE_LOOKAHEAD` pieces, so a change shows within that many).
//!
//! Invariant: a program with an error never starts (the HTTP layer checks it first); an error
//! found while running (a travel limit) stops the run at that block, nothing after it moves.

use crate::search::BlockSearch;
use crate::state::{g_vector, m_vector, ActiveCode, MachineState, SpindleState};
use serde::Serialize;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter, LengthComp};
use stanok_machine::{MachineData, SimMachine, SimOptions};
use stanok_motion::hold::HoldSwitch;
use stanok_motion::Setpoint;
use stanok_syntax::Dialect;
use std::cell::Cell;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Planner look-ahead of the panel's runs, pieces (see module doc, overrides).
pub const SERVE_LOOKAHEAD: usize = 64;

/// Where the run is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunState {
    /// No program running.
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
}

/// Everything the page shows, sent as JSON over the WebSocket and by `GET /api/state`.
#[derive(Debug, Clone, Serialize)]
pub struct Status {
    /// Increases with every published change.
    pub seq: u64,
    /// Run state.
    pub run_state: RunState,
    /// Name of the running (or last) program.
    pub program: String,
    /// Source line of the block the machine executes (the current setpoint's).
    pub line: u32,
    /// The machine's axis letters, in `Pose` order.
    pub axes: Vec<char>,
    /// Actual position, machine coordinates X…W.
    pub machine_position: [f64; 9],
    /// Actual position in work coordinates (offsets in force).
    pub work_position: [f64; 9],
    /// Programmed feed, mm/min.
    pub feed_programmed: f64,
    /// Actual path speed in X Y Z, mm/min.
    pub feed_actual: f64,
    /// Tool axis, a unit vector in machine coordinates (the page draws it at the tool). Always
    /// +Z today: no built-in machine has rotary axes that tilt the tool yet; a 5-axis machine's
    /// kinematics fills it in.
    pub tool_axis: [f64; 3],
    /// Spindles.
    pub spindles: [SpindleState; 4],
    /// Tool in the spindle.
    pub tool: u32,
    /// Active tool edge (D).
    pub edge: u8,
    /// Active G codes by group.
    pub g_codes: Vec<ActiveCode>,
    /// Active M functions by group.
    pub m_codes: Vec<ActiveCode>,
    /// Machine time since cycle start (holds and stops included), s.
    pub elapsed_s: f64,
    /// Planned cycle time of the whole program, s.
    pub estimated_s: f64,
    /// Operator message (MSG), empty when none.
    pub message: String,
    /// M00/M01 prompt waiting for acknowledge.
    pub prompt: Option<String>,
    /// Errors that stopped or refused the run.
    pub alarms: Vec<Alarm>,
    /// Feed override, %.
    pub feed_override: u32,
    /// Rapid override, %.
    pub rapid_override: u32,
    /// Single block switch.
    pub single_block: bool,
    /// Optional stop (M01) switch.
    pub optional_stop: bool,
    /// Feed hold pressed.
    pub held: bool,
    /// Line of the running block search, if any.
    pub search_line: Option<u32>,
    /// Machine state of the accepted commands (see [`MachineState`]).
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
        Status {
            seq: 0,
            run_state: RunState::Idle,
            program: String::new(),
            line: 0,
            axes,
            machine_position: [0.0; 9],
            work_position: [0.0; 9],
            feed_programmed: 0.0,
            feed_actual: 0.0,
            tool_axis: [0.0, 0.0, 1.0],
            spindles: MachineState::default().spindles,
            tool: 0,
            edge: 0,
            g_codes: Vec::new(),
            m_codes: Vec::new(),
            elapsed_s: 0.0,
            estimated_s: 0.0,
            message: String::new(),
            prompt: None,
            alarms: Vec::new(),
            feed_override: 100,
            rapid_override: 100,
            single_block: false,
            optional_stop: true,
            held: false,
            search_line: None,
            state: MachineState::default(),
            marked_state: None,
            final_position: None,
            cycle_time_s: None,
        }
    }
}

/// The operator's switches, read by the machine thread without locking.
#[derive(Debug)]
pub struct Controls {
    /// Feed hold (read by the interpolator at every servo instant).
    pub hold: Arc<HoldSwitch>,
    /// Stop / reset requested.
    pub stop: AtomicBool,
    /// Single block.
    pub single_block: AtomicBool,
    /// M01 stops.
    pub optional_stop: AtomicBool,
    /// Feed override, % (0…200).
    pub feed_override: AtomicU32,
    /// Rapid override, % (1…100).
    pub rapid_override: AtomicU32,
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
}

/// State shared between the HTTP side and the machine thread.
#[derive(Debug)]
pub struct Shared {
    /// Switches.
    pub controls: Controls,
    status: Mutex<Status>,
    events: Mutex<Sender<Event>>,
}

impl Shared {
    /// The status, locked (a poisoned lock is taken over: the status is plain data).
    pub fn status(&self) -> MutexGuard<'_, Status> {
        self.status.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Wakes the machine thread.
    pub fn send(&self, event: Event) {
        let tx = self.events.lock().unwrap_or_else(|e| e.into_inner());
        let _ = tx.send(event);
    }

    fn publish(&self, f: impl FnOnce(&mut Status)) {
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

/// Interpreter options for `machine` (as `stanok run` builds them).
pub fn interp_options(
    machine: &MachineData,
    dialect: Dialect,
    subroutine_path: &[PathBuf],
) -> InterpOptions {
    let mut opts = InterpOptions::new(dialect);
    opts.axes = machine.axis_mask();
    opts.arc_tolerance_mm = machine.arc_tolerance;
    opts.control = machine.control.clone();
    opts.diameter_axes = machine.diameter_axes();
    opts.rs274_machine_units = machine.linuxcnc_units;
    if let Some(table) = stanok_interp::MTable::profile(&machine.m_functions) {
        opts.axioma.m_table = table;
    }
    opts.axioma
        .set_table_entries(&machine.feed_table, &machine.speed_table);
    opts.subroutine_path = subroutine_path.to_vec();
    // Tool-centre-point control (TRAORI, CVU, G43.4/G43.5) as on the command line.
    opts.five_axis = machine.tcp_kinematics();
    opts.ttpc_workpiece_frame = machine.ttpc_workpiece_frame();
    // M01 reaches the machine thread, which decides with the operator's switch.
    opts.optional_stop = true;
    opts
}

/// Starts the machine thread.
pub fn spawn(config: MachineConfig) -> Arc<Shared> {
    let (tx, rx) = std::sync::mpsc::channel();
    let axes = config.machine.axes.iter().map(|a| a.name).collect();
    let shared = Arc::new(Shared {
        controls: Controls {
            hold: Arc::new(HoldSwitch::default()),
            stop: AtomicBool::new(false),
            single_block: AtomicBool::new(false),
            optional_stop: AtomicBool::new(true),
            feed_override: AtomicU32::new(100),
            rapid_override: AtomicU32::new(100),
        },
        status: Mutex::new(Status::new(axes)),
        events: Mutex::new(tx),
    });
    let thread_shared = shared.clone();
    std::thread::Builder::new()
        .name("stanok-machine".into())
        .spawn(move || machine_loop(&config, &thread_shared, &rx))
        .expect("spawn the machine thread");
    shared
}

fn machine_loop(config: &MachineConfig, shared: &Arc<Shared>, rx: &Receiver<Event>) {
    while let Ok(event) = rx.recv() {
        match event {
            // The stop switch was cleared by the cycle start that sent this (`http::cycle_start`),
            // so a stop pressed before the thread picks the job up still counts.
            Event::Start(job) => run_job(config, shared, rx, &job),
            Event::Acknowledge => shared.publish(|s| s.message.clear()),
            Event::CycleStart => {}
        }
    }
}

/// Sleeps setpoint by setpoint to the wall clock (module doc).
struct Pacer {
    scale: f64,
    origin: Instant,
    origin_t: f64,
}

impl Pacer {
    fn pace(&mut self, t: f64) {
        if self.scale <= 0.0 || !t.is_finite() {
            return;
        }
        let due =
            self.origin + Duration::from_secs_f64(((t - self.origin_t) / self.scale).max(0.0));
        let now = Instant::now();
        if now > due + Duration::from_millis(50) {
            self.origin = now;
            self.origin_t = t;
        } else if due > now + Duration::from_micros(500) {
            std::thread::sleep(due - now);
        }
    }
}

/// Why a wait ended.
enum Woken {
    Go,
    Stop,
}

/// Waits for cycle start or acknowledge (or stop).
fn wait_for_operator(shared: &Shared, rx: &Receiver<Event>) -> Woken {
    loop {
        if shared.controls.stop.load(Ordering::Relaxed) {
            return Woken::Stop;
        }
        match rx.recv_timeout(Duration::from_millis(20)) {
            Ok(Event::CycleStart) | Ok(Event::Acknowledge) => return Woken::Go,
            Ok(Event::Start(_)) => {}
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => return Woken::Stop,
        }
    }
}

/// One run of one program (module doc).
fn run_job(config: &MachineConfig, shared: &Arc<Shared>, rx: &Receiver<Event>, job: &Job) {
    let controls = &shared.controls;
    let mut state = MachineState::default();
    shared.publish(|s| {
        s.run_state = RunState::Running;
        s.program = job.name.clone();
        s.alarms.clear();
        s.message.clear();
        s.prompt = None;
        s.search_line = job.search_line;
        s.marked_state = None;
        s.final_position = None;
        s.cycle_time_s = None;
        s.elapsed_s = 0.0;
        s.estimated_s = job.estimated_s;
        s.state = state.clone();
    });
    let opts = interp_options(&config.machine, job.dialect, &config.subroutine_path);
    let mut interp = Interpreter::from_text(&job.text, opts);
    let sim_options = SimOptions {
        servo_period_s: config.servo_period_s,
        lookahead: SERVE_LOOKAHEAD,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(config.machine.clone(), sim_options);
    sim.set_hold_switch(controls.hold.clone());
    let abandoned = Rc::new(Cell::new(false));
    sim.set_setpoint_sink(setpoint_sink(
        shared.clone(),
        config.time_scale,
        abandoned.clone(),
        config.machine.five_axis(),
    ));
    let mut search = job.search_line.map(BlockSearch::new);
    let mark_line = job.search_line.or(job.mark_line);
    let (mut feed_pct, mut rapid_pct) = (100, 100);
    let mut block_line = 0u32;
    let mut block_moved = false;
    let mut failure: Option<Diagnostic> = None;
    'run: while let Some(item) = interp.next() {
        if controls.stop.load(Ordering::Relaxed) || abandoned.get() {
            break;
        }
        let cmd = match item {
            Ok(cmd) => cmd,
            Err(d) => {
                failure = Some(d);
                break;
            }
        };
        let (f, r) = (
            controls.feed_override.load(Ordering::Relaxed),
            controls.rapid_override.load(Ordering::Relaxed),
        );
        if (f, r) != (feed_pct, rapid_pct) {
            (feed_pct, rapid_pct) = (f, r);
            sim.set_feed_override((f as f64 / 100.0).max(0.001));
            sim.set_rapid_override((r as f64 / 100.0).max(0.001));
        }
        let (approach, cmds) = match &mut search {
            Some(s) => s.filter(cmd),
            None => (None, vec![cmd]),
        };
        if let Some(approach) = approach {
            if let Err(d) = execute(
                &mut sim,
                &mut state,
                &approach,
                &interp,
                job.dialect,
                shared,
            ) {
                failure = Some(d);
                break 'run;
            }
        }
        for cmd in cmds {
            // Single block: the machine stops at the end of every block that moved.
            if cmd.span.line != block_line {
                if block_moved && controls.single_block.load(Ordering::Relaxed) {
                    settle(&mut sim, &state, shared);
                    shared.publish(|s| s.run_state = RunState::BlockEnd);
                    if let Woken::Stop = wait_for_operator(shared, rx) {
                        break 'run;
                    }
                    shared.publish(|s| s.run_state = RunState::Running);
                }
                block_line = cmd.span.line;
                block_moved = false;
                if Some(cmd.span.line) == mark_line {
                    let at = state.clone();
                    shared.publish(|s| {
                        if s.marked_state.is_none() {
                            s.marked_state = Some(at);
                        }
                    });
                }
            }
            if let Err(d) = execute(&mut sim, &mut state, &cmd, &interp, job.dialect, shared) {
                failure = Some(d);
                break 'run;
            }
            block_moved |= cmd.value.motion().is_some();
            if let Canon::ProgramStop { optional } = cmd.value {
                if !optional || controls.optional_stop.load(Ordering::Relaxed) {
                    settle(&mut sim, &state, shared);
                    let text = if optional {
                        "M01 optional stop: acknowledge to continue"
                    } else {
                        "M00 program stop: acknowledge to continue"
                    };
                    shared.publish(|s| {
                        s.run_state = RunState::Prompt;
                        s.line = cmd.span.line;
                        s.prompt = Some(format!("line {}: {text}", cmd.span.line));
                    });
                    let woken = wait_for_operator(shared, rx);
                    shared.publish(|s| {
                        s.prompt = None;
                        s.run_state = RunState::Running;
                    });
                    if let Woken::Stop = woken {
                        break 'run;
                    }
                }
            }
        }
    }
    finish(shared, &mut sim, &abandoned, failure, search.as_ref());
}

/// Runs the planned motion to its end and shows the machine at rest there: the interpolator
/// reaches a stop point exactly at the next servo instant, which belongs to the next piece, so the
/// last setpoint sampled is one period short of it.
fn settle(sim: &mut SimMachine, state: &MachineState, shared: &Shared) {
    sim.drain_motion();
    if shared.controls.stop.load(Ordering::Relaxed) {
        return;
    }
    let at = state.position;
    shared.publish(|s| {
        s.machine_position = at;
        s.work_position = s.state.work_of(&at);
        s.feed_actual = 0.0;
    });
}

/// Applies one command to the machine and to the published state.
fn execute<R: std::io::BufRead + std::io::Seek>(
    sim: &mut SimMachine,
    state: &mut MachineState,
    cmd: &Spanned<Canon>,
    interp: &Interpreter<R>,
    dialect: Dialect,
    shared: &Shared,
) -> Result<(), Diagnostic> {
    sim.apply(cmd)?;
    state.apply(&cmd.value);
    let modal = interp.state();
    let axioma = interp.axioma_modes();
    let length_comp = axioma.map_or(LengthComp::Off, |m| m.length_comp);
    let (g, m) = (
        g_vector(modal, length_comp, dialect),
        m_vector(interp, state, dialect),
    );
    let edge = axioma.map_or(0, |m| m.edge);
    shared.publish(|s| {
        if let Canon::Message { text } = &cmd.value {
            s.message = text.trim().to_string();
        }
        s.state = state.clone();
        s.feed_programmed = state.feed;
        s.spindles = state.spindles;
        s.tool = state.tool;
        s.edge = edge;
        s.g_codes = g;
        s.m_codes = m;
    });
    Ok(())
}

/// The end of a run: the rest of the motion, the final state, the run state.
fn finish(
    shared: &Shared,
    sim: &mut SimMachine,
    abandoned: &Rc<Cell<bool>>,
    failure: Option<Diagnostic>,
    search: Option<&BlockSearch>,
) {
    if shared.controls.stop.load(Ordering::Relaxed) && !abandoned.get() {
        // Stopped while waiting (prompt, block end): nothing is moving; drop the plan.
        abandoned.set(true);
    }
    shared.controls.hold.set(false);
    // The rest of the motion runs here (paced), so a stop may still come during it.
    let report = sim.finish();
    let stopped = shared.controls.stop.load(Ordering::Relaxed);
    let not_reached = search.filter(|s| !s.reached()).map(|_| ());
    shared.publish(|s| {
        s.held = false;
        s.feed_actual = 0.0;
        if let Some(d) = &failure {
            s.alarms.push(Alarm::of(d));
        }
        if not_reached.is_some() {
            s.alarms.push(Alarm {
                line: s.search_line.unwrap_or(0),
                column: 1,
                severity: "error".into(),
                code: "serve::search-not-reached".into(),
                message: "block search: the program never reaches this line".into(),
            });
        }
        s.run_state = if failure.is_some() || not_reached.is_some() {
            RunState::Alarm
        } else if stopped {
            RunState::Stopped
        } else {
            s.final_position = Some(report.final_position.to_array());
            s.cycle_time_s = Some(report.cycle_time_s);
            RunState::Finished
        };
    });
}

/// The setpoint sink: pace, publish, and carry out a stop (module doc).
fn setpoint_sink(
    shared: Arc<Shared>,
    time_scale: f64,
    abandoned: Rc<Cell<bool>>,
    kinematics: Option<stanok_kin::FiveAxis>,
) -> Box<dyn FnMut(&Setpoint)> {
    let mut pacer = Pacer {
        scale: time_scale,
        origin: Instant::now(),
        origin_t: 0.0,
    };
    Box::new(move |sp: &Setpoint| {
        if abandoned.get() {
            return;
        }
        let controls = &shared.controls;
        let v = &sp.velocity;
        let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let at_rest = v.iter().all(|x| *x == 0.0);
        if controls.stop.load(Ordering::Relaxed) {
            controls.hold.set(true);
            if at_rest {
                // Stopped on the path: from here on the plan runs unobserved and unpaced.
                abandoned.set(true);
                controls.hold.set(false);
            }
        }
        // The tool axis from the rotary axes' positions (a 3-axis machine: +Z, as at start).
        let tool_axis = kinematics.as_ref().map_or([0.0, 0.0, 1.0], |k| {
            k.tool_vector_at(&stanok_canon::Pose::from_array(sp.position))
        });
        shared.publish(|s| {
            s.machine_position = sp.position;
            s.tool_axis = tool_axis;
            s.work_position = s.state.work_of(&sp.position);
            s.line = sp.line;
            s.elapsed_s = sp.t;
            s.feed_actual = speed * 60.0;
            s.held = controls.hold.is_held();
        });
        if !abandoned.get() {
            pacer.pace(sp.t);
        }
    })
}
