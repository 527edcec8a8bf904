//! One run of the interpreter on the machine: a program from cycle start to its end, or one MDI
//! block (`manual.rs`). The same loop for both:
//!
//! ```text
//!  interp.next() ─▶ BlockSearch::filter ─▶ single block / mark ─▶ execute: snapshot → ring → tag
//!                                                                  → SimMachine::apply → M00/M01
//! ```
//! * **Stop.** The loop looks at the stop switch before each command; the interpreter's source
//!   (`jobs::CancelReader`) looks at it on every line it reads, so a long computation without
//!   motion (a loop of parameter arithmetic) ends on stop too. Then the planned motion runs out
//!   under feed hold and ends at rest on the path (`paced.rs`).
//! * **Program stops** (M00, M01 with the optional-stop switch on) and **single block** drain the
//!   planner so that the machine is at rest at the block end, show the latest snapshot (everything
//!   has executed), then wait for cycle start / acknowledge.
//! * **Failures.** An interpreter error or a refused command (a travel limit) ends the run at that
//!   block: the motion planned before it runs out, nothing of it or after it moves. A panic inside
//!   the interpreter or the machine is caught (`guarded`) and reported as an alarm.

use crate::executing::Snapshot;
use crate::jobs::{panic_text, CancelReader, Cancelled};
use crate::machine::{
    finite9, interp_options, wait_for_operator, Alarm, Event, Job, MachineConfig, MachineContext,
    RunState, Shared, Woken,
};
use crate::paced::{paced_machine, Mode, Tracker};
use crate::search::BlockSearch;
use crate::state::{g_vector_of, m_vector, MachineState};
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::Interpreter;
use stanok_machine::{RunReport, SimMachine};
use stanok_syntax::Dialect;
use std::io::{BufRead, Seek};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::rc::Rc;
use std::sync::atomic::Ordering;
use std::sync::mpsc::Receiver;
use std::sync::Arc;

/// Why a guarded call did not return.
pub(crate) enum Unwound {
    /// Cancelled on purpose (stop at rest, stop while the interpreter computed).
    Cancelled,
    /// A panic: its message.
    Panic(String),
}

/// Runs `f`, catching the unwinding of a stop and any panic.
pub(crate) fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, Unwound> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|p| {
        if p.is::<Cancelled>() {
            Unwound::Cancelled
        } else {
            Unwound::Panic(panic_text(&*p))
        }
    })
}

/// An internal error as a diagnostic of the block where it happened.
fn internal(message: String, line: u32) -> Diagnostic {
    let mut d = Diagnostic::error(
        "serve::internal",
        format!("internal error, the run was stopped: {message}"),
        stanok_canon::Span::default(),
    );
    d.span.line = line;
    d
}

/// How a run ended.
pub(crate) struct Outcome {
    /// The error that stopped it.
    pub failure: Option<Diagnostic>,
    /// Stopped by the operator.
    pub stopped: bool,
    /// The report of a run that went to its end.
    pub report: Option<RunReport>,
    /// With a block search: whether its line came.
    pub search_reached: Option<bool>,
    /// The machine state after the last command accepted.
    pub state: MachineState,
}

/// What a run needs besides the interpreter.
pub(crate) struct RunSetup {
    /// Block search.
    pub search: Option<BlockSearch>,
    /// Record the state when this line first reaches the machine.
    pub mark_line: Option<u32>,
    /// The machine state before the first command (a program: power-on; an MDI block: what the
    /// previous block left). Its position is replaced by where the machine stands.
    pub state: MachineState,
    /// The stock simulation to run beside (`stock.rs`).
    pub stock: Option<stanok_stock::sim::StockSim>,
}

/// The machine's side of one run: the simulated machine, the state read off the accepted
/// commands, the snapshots (module doc).
struct Machine<'a> {
    shared: &'a Arc<Shared>,
    sim: SimMachine,
    tracker: Rc<Tracker>,
    state: MachineState,
    dialect: Dialect,
    messages: u64,
    last_message: Option<(u64, String)>,
}

impl Machine<'_> {
    /// Applies one command: its snapshot into the ring first (the command's own setpoints may come
    /// out during `apply`), then the command, tagged, to the simulated machine.
    fn execute<R: BufRead + Seek>(
        &mut self,
        cmd: &mut Spanned<Canon>,
        interp: &Interpreter<R>,
    ) -> Result<(), Result<Diagnostic, Unwound>> {
        let mut next = self.state.clone();
        next.apply(&cmd.value);
        if let Canon::Message { text } = &cmd.value {
            self.messages += 1;
            self.last_message = Some((self.messages, text.clone()));
        }
        let snapshot = Snapshot {
            line: cmd.span.line,
            state: next.clone(),
            g_codes: g_vector_of(interp, self.dialect),
            m_codes: m_vector(interp, &next, self.dialect),
            edge: interp.axioma_modes().map_or(0, |m| m.edge),
            message: self.last_message.clone(),
        };
        let tag = self.tracker.ring.borrow_mut().push(snapshot);
        let line = std::mem::replace(&mut cmd.span.line, tag);
        let applied = guarded(|| self.sim.apply(cmd));
        cmd.span.line = line;
        match applied {
            Ok(Ok(())) => {
                self.state = next;
                Ok(())
            }
            Ok(Err(mut d)) => {
                d.span.line = line;
                Err(Ok(d))
            }
            Err(u) => Err(Err(u)),
        }
    }

    /// Runs the planned motion to its end and shows the machine at rest there with the latest
    /// snapshot: the interpolator reaches a stop point exactly at the next servo instant, which
    /// belongs to the next piece, so the last setpoint sampled is one period short of it.
    fn settle(&mut self) -> Result<(), Unwound> {
        guarded(|| self.sim.drain_motion())?;
        if self.shared.controls.stop.is_raised() {
            return Ok(());
        }
        let at = self.state.position;
        self.tracker.at.set(at);
        let latest = self.tracker.ring.borrow().latest();
        let tracker = self.tracker.clone();
        self.shared.publish(|s| {
            s.machine_position = at;
            if let Some(snap) = &latest {
                tracker.show(s, snap);
            }
            s.work_position = s.state.work_of(&at);
            s.feed_actual = 0.0;
        });
        Ok(())
    }
}

/// Runs `interp` on the machine from `here` (module doc); `here.position` is where it ends.
pub(crate) fn drive<R: BufRead + Seek>(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    rx: &Receiver<Event>,
    here: &mut MachineContext,
    interp: &mut Interpreter<R>,
    dialect: Dialect,
    mut setup: RunSetup,
) -> Outcome {
    let controls = &shared.controls;
    let (mut sim, tracker) = paced_machine(config, shared, here.position, Mode::Program);
    if let Some(stock) = setup.stock.take() {
        sim.set_stock(stock);
        sim.set_stock_observer(crate::stock::observer(shared.clone(), tracker.ring.clone()));
    }
    let mut state = std::mem::take(&mut setup.state);
    state.position = here.position;
    let mut m = Machine {
        shared,
        sim,
        tracker,
        state,
        dialect,
        messages: 0,
        last_message: None,
    };
    let mark_line = setup
        .search
        .as_ref()
        .map(BlockSearch::line)
        .or(setup.mark_line);
    let mut block_line = 0u32;
    let mut block_moved = false;
    let mut failure: Option<Diagnostic> = None;
    let mut stopped = false;
    let fail = |u: Unwound, line: u32, failure: &mut Option<Diagnostic>| match u {
        Unwound::Cancelled => true,
        Unwound::Panic(msg) => {
            *failure = Some(internal(msg, line));
            false
        }
    };
    'run: loop {
        if controls.stop.is_raised() {
            stopped = true;
            break;
        }
        let item = match guarded(|| interp.next()) {
            Ok(Some(item)) => item,
            Ok(None) => break,
            Err(u) => {
                stopped = fail(u, block_line, &mut failure);
                break;
            }
        };
        let cmd = match item {
            Ok(cmd) => cmd,
            Err(d) => {
                failure = Some(d);
                break;
            }
        };
        let (approach, cmds) = match &mut setup.search {
            Some(s) => s.filter(cmd),
            None => (None, vec![cmd]),
        };
        if let Some(mut approach) = approach {
            match m.execute(&mut approach, interp) {
                Ok(()) => {}
                Err(Ok(d)) => {
                    failure = Some(d);
                    break 'run;
                }
                Err(Err(u)) => {
                    stopped = fail(u, approach.span.line, &mut failure);
                    break 'run;
                }
            }
        }
        for mut cmd in cmds {
            // Single block: the machine stops at the end of every block that moved.
            if cmd.span.line != block_line {
                if block_moved && controls.single_block.load(Ordering::Relaxed) {
                    if let Err(u) = m.settle() {
                        stopped = fail(u, block_line, &mut failure);
                        break 'run;
                    }
                    shared.publish(|s| s.run_state = RunState::BlockEnd);
                    if let Woken::Stop = wait_for_operator(shared, rx) {
                        stopped = true;
                        break 'run;
                    }
                    shared.publish(|s| s.run_state = RunState::Running);
                }
                block_line = cmd.span.line;
                block_moved = false;
                if Some(cmd.span.line) == mark_line {
                    let at = m.state.clone();
                    shared.publish(|s| {
                        if s.marked_state.is_none() {
                            s.marked_state = Some(at);
                        }
                    });
                }
            }
            match m.execute(&mut cmd, interp) {
                Ok(()) => {}
                Err(Ok(d)) => {
                    failure = Some(d);
                    break 'run;
                }
                Err(Err(u)) => {
                    stopped = fail(u, cmd.span.line, &mut failure);
                    break 'run;
                }
            }
            block_moved |= cmd.value.motion().is_some();
            if let Canon::ProgramStop { optional } = cmd.value {
                if !optional || controls.optional_stop.load(Ordering::Relaxed) {
                    if let Err(u) = m.settle() {
                        stopped = fail(u, cmd.span.line, &mut failure);
                        break 'run;
                    }
                    let text = if optional {
                        "M01 optional stop: acknowledge to continue"
                    } else {
                        "M00 program stop: acknowledge to continue"
                    };
                    let line = cmd.span.line;
                    shared.publish(|s| {
                        s.run_state = RunState::Prompt;
                        s.line = line;
                        s.prompt = Some(format!("line {line}: {text}"));
                    });
                    let woken = wait_for_operator(shared, rx);
                    shared.publish(|s| {
                        s.prompt = None;
                        s.run_state = RunState::Running;
                    });
                    if let Woken::Stop = woken {
                        stopped = true;
                        break 'run;
                    }
                }
            }
        }
    }
    // The rest of the motion runs here (paced): a stop may still come, and a stop already pressed
    // brakes what is planned and ends at rest (the sink unwinds there).
    stopped |= controls.stop.is_raised();
    let report = match guarded(|| m.sim.finish()) {
        Ok(r) if !stopped => Some(r),
        Ok(_) => None,
        Err(Unwound::Cancelled) => {
            stopped = true;
            None
        }
        Err(Unwound::Panic(msg)) => {
            failure.get_or_insert(internal(msg, block_line));
            None
        }
    };
    // The stock as the run left it (finished: everything cut; stopped: up to the stop).
    if let Some(stock) = m.sim.stock() {
        let ring = &m.tracker.ring;
        if let Some(text) = crate::stock::message(stock, true, ring) {
            shared.stock.put(text);
        }
        let listed = shared
            .status()
            .alarms
            .iter()
            .filter(|a| a.code.starts_with("stock::"))
            .count();
        crate::stock::publish_alarms(shared, stock, listed, ring);
    }
    controls.hold.set(false);
    here.position = match &report {
        Some(r) if finite9(&r.final_position.to_array()) => r.final_position.to_array(),
        _ => m.tracker.at.get(),
    };
    // A run that went to its end shows the state after its last command.
    if report.is_some() && failure.is_none() {
        let latest = m.tracker.ring.borrow().latest();
        let tracker = m.tracker.clone();
        shared.publish(|s| {
            if let Some(snap) = &latest {
                tracker.show(s, snap);
            }
            s.machine_position = here.position;
            s.work_position = s.state.work_of(&here.position);
        });
    }
    Outcome {
        failure,
        stopped,
        report,
        search_reached: setup.search.as_ref().map(BlockSearch::reached),
        state: m.state,
    }
}

/// One program run from cycle start (module doc).
pub(crate) fn run_program(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    rx: &Receiver<Event>,
    here: &mut MachineContext,
    job: &Job,
) {
    shared.publish(|s| {
        s.run_state = RunState::Running;
        s.program = job.name.clone();
        s.dialect = job.dialect.id().into();
        s.alarms.clear();
        s.message.clear();
        s.prompt = None;
        s.search_line = job.search_line;
        s.marked_state = None;
        s.final_position = None;
        s.cycle_time_s = None;
        s.elapsed_s = 0.0;
        s.estimated_s = job.estimated_s;
    });
    let opts = interp_options(&config.machine, job.dialect, &config.subroutine_path, here);
    let source = CancelReader::new(job.text.clone(), shared.controls.stop.clone());
    let mut interp = Interpreter::new(source, opts);
    shared.stock.clear();
    let stock = job.stock.clone().and_then(|shape| {
        let lathe = crate::check::lathe_view(&config.machine, job.dialect);
        match crate::stock::build(&config.machine, shape, lathe, &here.control.tools) {
            Ok(s) => Some(s),
            Err(e) => {
                shared.publish(|s| s.alarms.push(Alarm::panel("serve::stock", 0, e)));
                None
            }
        }
    });
    let setup = RunSetup {
        search: job.search_line.map(BlockSearch::new),
        mark_line: job.mark_line,
        state: MachineState::default(),
        stock,
    };
    let out = drive(config, shared, rx, here, &mut interp, job.dialect, setup);
    let not_reached_line = job
        .search_line
        .filter(|_| out.search_reached == Some(false));
    shared.publish(|s| {
        s.held = false;
        s.feed_actual = 0.0;
        s.spindle_actual_rpm = [0.0; 4];
        if let Some(d) = &out.failure {
            s.alarms.push(Alarm::of(d));
        }
        if let Some(line) = not_reached_line {
            s.alarms.push(Alarm::panel(
                "serve::search-not-reached",
                line,
                "block search: the program never reaches this line",
            ));
        }
        s.run_state = if out.failure.is_some() || not_reached_line.is_some() {
            RunState::Alarm
        } else if out.stopped {
            RunState::Stopped
        } else {
            if let Some(r) = &out.report {
                s.final_position = Some(r.final_position.to_array());
                s.cycle_time_s = Some(r.cycle_time_s);
            }
            RunState::Finished
        };
    });
}
