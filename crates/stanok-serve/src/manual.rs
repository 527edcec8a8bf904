//! The manual modes: jog, reference return, touch-off and MDI, run on the machine thread between
//! programs (never during one: `wait_for_operator` refuses them while a program waits).
//!
//! * **Jog** moves one axis at the jog speed, by an increment or — continuous — towards its travel
//!   limit while the page keeps the jog alive (`Controls::jog_until_ms`, extended every 200 ms
//!   while the key or button is held: a page that goes away stops the jog within half a second).
//!   The end brakes on the path like a stop (`paced.rs`). An increment that would leave the travel
//!   is refused.
//! * **Reference return** (homing) rapids the retract axis first — Z on a mill, X on a lathe
//!   (a machine without Y) — then every other axis together, to the reference point: machine zero,
//!   or the nearest travel limit if zero is outside it. The axes are then referenced.
//! * **Touch-off** sets the active work offset (G54 when none is active) so that the axis reads
//!   the typed value where the machine stands: `offset = machine − tool length offset − G92 −
//!   value`. It is stored in the panel's control data, which every later program, MDI block, check
//!   and preview starts from. Refused under an XY rotation for X and Y.
//! * **MDI** runs one block in the chosen dialect through the same loop as a program (`run.rs`):
//!   the block is a small program of its own, which continues in the modes the previous MDI block
//!   left ([`MdiSession`]: the interpreter's modal state and parameters, via
//!   `Interpreter::resume_modal_state`) and starts where the machine stands. What the block writes
//!   to the stored data (G10, G92) persists. The session restarts from the stored data after a
//!   program, a touch-off, a program end in MDI, or a change of dialect.

use crate::jobs::CancelReader;
use crate::machine::{
    interp_options, Alarm, Event, MachineConfig, MachineContext, Manual, ManualReply, RunState,
    Shared,
};
use crate::paced::{paced_machine, Mode};
use crate::run::{drive, guarded, RunSetup, Unwound};
use crate::state::MachineState;
use stanok_canon::{Canon, LengthUnits, LineMove, Pose, Span, Spanned};
use stanok_interp::{Interpreter, ModalState, Parameters};
use stanok_machine::AxisData;
use stanok_syntax::Dialect;
use std::sync::mpsc::Receiver;
use std::sync::Arc;

/// The modes an MDI block leaves for the next (module doc): the interpreter's modal state and
/// parameters, and the machine state the DRO shows.
#[derive(Debug, Default)]
pub struct MdiSession {
    modes: Option<(Dialect, ModalState, Option<Box<Parameters>>, MachineState)>,
}

fn done(note: impl Into<String>) -> ManualReply {
    ManualReply::Done {
        note: note.into(),
        diagnostics: Vec::new(),
    }
}

fn refused(error: impl Into<String>) -> ManualReply {
    ManualReply::Refused {
        error: error.into(),
        diagnostics: Vec::new(),
    }
}

/// Runs one manual action (module doc).
pub(crate) fn execute(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    rx: &Receiver<Event>,
    here: &mut MachineContext,
    mdi: &mut MdiSession,
    action: Manual,
) -> ManualReply {
    if shared.status().run_state.program_active() {
        return refused("a program is in progress: stop it first");
    }
    shared.controls.stop.lower();
    match action {
        Manual::Jog {
            axis,
            direction,
            increment,
            speed,
        } => jog(config, shared, here, axis, direction, increment, speed),
        Manual::Home { axis } => home(config, shared, here, axis),
        Manual::TouchOff { axis, value } => {
            let r = touch_off(config, shared, here, axis, value);
            if matches!(r, ManualReply::Done { .. }) {
                *mdi = MdiSession::default();
            }
            r
        }
        Manual::Mdi { text, dialect } => run_mdi(config, shared, rx, here, mdi, &text, dialect),
    }
}

fn axis_of(config: &MachineConfig, axis: usize) -> Option<&AxisData> {
    config.machine.axes.iter().find(|a| a.pose_index() == axis)
}

/// Moves the machine from `here` through `targets` (one straight move each, rapid or at `feed`),
/// paced and stoppable; `here.position` is where it ends.
fn manual_motion(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    here: &mut MachineContext,
    targets: &[[f64; 9]],
    feed: Option<f64>,
    mode: Mode,
    run_state: RunState,
) -> Result<(), String> {
    shared.publish(|s| {
        s.run_state = run_state;
        s.line = 0;
    });
    let (mut sim, tracker) = paced_machine(config, shared, here.position, mode);
    let span = Span::default();
    let mut from = Pose::from_array(here.position);
    let result = guarded(|| -> Result<(), String> {
        let init = Canon::Init {
            position: from,
            units: LengthUnits::Millimetres,
            g5x_index: 0,
            g5x_offset: Pose::ZERO,
            g92_offset: Pose::ZERO,
            xy_rotation: 0.0,
        };
        sim.apply(&Spanned::new(span, init))
            .map_err(|d| d.message)?;
        for target in targets {
            let to = Pose::from_array(*target);
            let m = LineMove {
                start: from,
                end: to,
                feed: feed.unwrap_or(0.0),
                // Jogs feed per minute: the machine thread's moves carry their own law.
                law: stanok_canon::FeedLaw::PerMinute,
            };
            let cmd = match feed {
                Some(_) => Canon::StraightFeed(m),
                None => Canon::StraightTraverse(m),
            };
            sim.apply(&Spanned::new(span, cmd)).map_err(|d| d.message)?;
            from = to;
        }
        sim.finish();
        Ok(())
    });
    shared.controls.hold.set(false);
    let outcome = match result {
        Ok(Ok(())) => {
            here.position = from.to_array();
            Ok(())
        }
        Ok(Err(e)) => {
            here.position = tracker.at.get();
            Err(e)
        }
        Err(Unwound::Cancelled) => {
            here.position = tracker.at.get();
            Ok(())
        }
        Err(Unwound::Panic(m)) => {
            here.position = tracker.at.get();
            Err(format!("internal error: {m}"))
        }
    };
    let at = here.position;
    shared.publish(|s| {
        s.run_state = RunState::Idle;
        s.machine_position = at;
        s.work_position = s.state.work_of(&at);
        s.feed_actual = 0.0;
        s.held = false;
    });
    outcome
}

/// Jog (module doc).
fn jog(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    here: &mut MachineContext,
    axis: usize,
    direction: f64,
    increment: Option<f64>,
    speed: f64,
) -> ManualReply {
    let Some(data) = axis_of(config, axis) else {
        return refused("the machine has no such axis");
    };
    let (name, min, max) = (data.name, data.min, data.max);
    let speed = speed.min(data.max_velocity).max(1e-3);
    let mut target = here.position;
    let dir = direction.signum();
    match increment {
        Some(step) => {
            target[axis] += dir * step;
            if target[axis] < min - 1e-9 || target[axis] > max + 1e-9 {
                return refused(format!(
                    "a jog of {}{step} would take {name} to {:.4}, outside its travel [{min}, {max}]",
                    if dir > 0.0 { "+" } else { "−" },
                    target[axis]
                ));
            }
        }
        // Continuous: towards the limit (an endless rotary axis: ten turns, the page stops it).
        None => {
            let limit = if dir > 0.0 { max } else { min };
            target[axis] = if limit.is_finite() {
                limit
            } else {
                here.position[axis] + dir * 3600.0
            };
        }
    }
    if (target[axis] - here.position[axis]).abs() < 1e-9 {
        return done(format!("{name} is at its travel limit"));
    }
    let mode = if increment.is_some() {
        Mode::Manual
    } else {
        Mode::Jog
    };
    match manual_motion(
        config,
        shared,
        here,
        &[target],
        Some(speed),
        mode,
        RunState::Jogging,
    ) {
        Ok(()) => done(format!("{name} at {:.4}", here.position[axis])),
        Err(e) => refused(e),
    }
}

/// Reference return (module doc).
fn home(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    here: &mut MachineContext,
    axis: Option<usize>,
) -> ManualReply {
    let axes: Vec<&AxisData> = config
        .machine
        .axes
        .iter()
        .filter(|a| axis.is_none_or(|i| a.pose_index() == i))
        .collect();
    if axes.is_empty() {
        return refused("the machine has no such axis");
    }
    let has_y = config.machine.axes.iter().any(|a| a.name == 'Y');
    let retract = if has_y { 2 } else { 0 };
    let reference = |a: &AxisData| 0.0f64.clamp(a.min, a.max);
    let mut first = here.position;
    let mut then = here.position;
    for a in &axes {
        let i = a.pose_index();
        if i == retract {
            first[i] = reference(a);
        }
        then[i] = reference(a);
    }
    then[retract] = first[retract];
    let targets: Vec<[f64; 9]> = [first, then]
        .into_iter()
        .filter(|t| t != &here.position)
        .collect();
    let mut targets_dedup: Vec<[f64; 9]> = Vec::new();
    for t in targets {
        if targets_dedup.last() != Some(&t) {
            targets_dedup.push(t);
        }
    }
    let result = manual_motion(
        config,
        shared,
        here,
        &targets_dedup,
        None,
        Mode::Manual,
        RunState::Homing,
    );
    let stopped = shared.controls.stop.is_raised();
    match result {
        Ok(()) if !stopped => {
            for a in &axes {
                here.homed[a.pose_index()] = true;
            }
            let homed: Vec<bool> = config
                .machine
                .axes
                .iter()
                .map(|a| here.homed[a.pose_index()])
                .collect();
            shared.publish(|s| s.homed = homed);
            done("referenced")
        }
        Ok(()) => refused("the reference return was stopped"),
        Err(e) => refused(e),
    }
}

/// Touch-off (module doc).
fn touch_off(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    here: &mut MachineContext,
    axis: usize,
    value: f64,
) -> ManualReply {
    let Some(data) = axis_of(config, axis) else {
        return refused("the machine has no such axis");
    };
    if !value.is_finite() {
        return refused("the value must be a number");
    }
    let state = shared.status().state.clone();
    if state.xy_rotation_deg != 0.0 && axis < 2 {
        return refused("the work frame is rotated: touch off X and Y with G10 L20 in MDI");
    }
    let system = if state.g5x_index == 0 {
        1
    } else {
        state.g5x_index
    };
    let offset = here.position[axis] - state.tool_offset[axis] - state.g92_offset[axis] - value;
    let Some(entry) = here
        .control
        .offsets
        .zero
        .get_mut(system as usize - 1)
        .and_then(|pages| pages.first_mut())
    else {
        return refused("no such work offset in the control data");
    };
    let mut o = entry.offset.to_array();
    o[axis] = offset;
    entry.offset = Pose::from_array(o);
    let at = here.position;
    shared.publish(|s| {
        s.state.g5x_index = system;
        s.state.g5x_offset[axis] = offset;
        s.work_position = s.state.work_of(&at);
    });
    const NAMES: [&str; 9] = [
        "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
    ];
    done(format!(
        "{} {} = {offset:.4}: {} reads {value}",
        NAMES[system as usize - 1],
        data.name,
        data.name
    ))
}

/// One MDI block (module doc).
fn run_mdi(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    rx: &Receiver<Event>,
    here: &mut MachineContext,
    session: &mut MdiSession,
    text: &str,
    dialect: Dialect,
) -> ManualReply {
    let block = text.trim_end_matches(['\r', '\n']);
    if block.contains('\n') {
        return refused("MDI runs one block at a time");
    }
    if block.trim().is_empty() {
        return refused("the MDI block is empty");
    }
    if let Some(a) = crate::check::long_line(block) {
        return refused(a.message);
    }
    let mut opts = interp_options(&config.machine, dialect, &config.subroutine_path, here);
    opts.max_blocks = 1_000_000;
    let source = CancelReader::new(
        Arc::from(format!("{block}\n")),
        shared.controls.stop.clone(),
    );
    let mut interp = Interpreter::new(source, opts);
    let mut machine_state = MachineState::default();
    let previous = session.modes.take();
    if let Some((d, state, params, shown)) = &previous {
        if *d == dialect {
            let mut state = *state;
            state.position = Pose::from_array(here.position);
            interp.resume_modal_state(state);
            if let (Some(slot), Some(p)) = (interp.parameters_mut(), params) {
                *slot = (**p).clone();
            }
            machine_state = shown.clone();
        }
    }
    shared.publish(|s| {
        s.run_state = RunState::Mdi;
        s.alarms.clear();
        s.prompt = None;
    });
    let setup = RunSetup {
        search: None,
        mark_line: None,
        state: machine_state.clone(),
        stock: None,
    };
    let out = drive(config, shared, rx, here, &mut interp, dialect, setup);
    let mut warnings: Vec<Alarm> = interp.take_warnings().iter().map(Alarm::of).collect();
    // A block is not a file: RS274/NGC's "no program end" at the end of the text is no error here.
    let failure = out
        .failure
        .filter(|d| d.code.to_string() != "rs274::no-program-end");
    let ended = out.report.as_ref().is_some_and(|r| r.program_ended);
    if failure.is_none() && !ended {
        session.modes = Some((
            dialect,
            *interp.state(),
            interp.parameters().map(|p| Box::new(p.clone())),
            out.state.clone(),
        ));
        here.control = interp.control_data();
    } else if failure.is_some() {
        // A failing block changes nothing: the session goes on as it was.
        if let Some(prev) = previous {
            session.modes = Some(prev);
        }
    }
    let alarm = failure.as_ref().map(Alarm::of);
    shared.publish(|s| {
        s.run_state = RunState::Idle;
        s.feed_actual = 0.0;
        s.spindle_actual_rpm = [0.0; 4];
        s.held = false;
        if let Some(a) = &alarm {
            s.alarms = vec![a.clone()];
        }
    });
    match alarm {
        Some(a) => {
            warnings.insert(0, a.clone());
            ManualReply::Refused {
                error: format!("{}: {}", a.code, a.message),
                diagnostics: warnings,
            }
        }
        None if out.stopped => refused("the MDI block was stopped"),
        None => ManualReply::Done {
            note: if ended {
                "program end: the MDI session starts afresh".into()
            } else {
                "executed".into()
            },
            diagnostics: warnings,
        },
    }
}
