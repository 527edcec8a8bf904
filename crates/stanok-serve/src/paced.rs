//! The simulated machine as the machine thread drives it: paced to the wall clock, publishing
//! every setpoint, showing the executing block, and stoppable on the path.
//!
//! * **Pacing.** The setpoint sink sleeps until wall time `origin + (t − t₀) / time_scale` of
//!   each setpoint. When it finds itself more than 50 ms late (after a program stop or a single
//!   block wait, where machine time stood still, or on a busy host) it re-bases instead of
//!   rushing. `time_scale` 1 = real time; 10 = ten times faster (the tests); 0 = unpaced.
//! * **Publishing.** Every setpoint goes into the one `Mutex<Status>` (held for a copy's time):
//!   position, speed, spindle speed, and — when the tag of the setpoint names another snapshot
//!   (`executing.rs`) — the executing block's line, DRO state, codes and message together.
//!   A message is shown once when its block executes; acknowledging clears it.
//! * **Stop on the path.** Stop (and the end of a continuous jog) presses the motion stage's feed
//!   hold: the interpolator brakes along the path at the pieces' limits. At the first setpoint at
//!   rest the action is over: the sink records where the machine stands and unwinds with
//!   `jobs::Cancelled` out of the simulated machine, which the caller catches and drops (the
//!   rest of the plan is never computed: a runaway feed cannot keep a core busy).

use crate::executing::{Snapshot, SnapshotRing};
use crate::jobs::Cancelled;
use crate::machine::{MachineConfig, Shared, Status, SERVE_LOOKAHEAD};
use stanok_machine::{SimMachine, SimOptions};
use stanok_motion::Setpoint;
use std::cell::{Cell, RefCell};
use std::panic::resume_unwind;
use std::rc::Rc;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};

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

/// What an action is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// A program or an MDI block: elapsed time and the executing block are shown.
    Program,
    /// A jog: ends also when `Controls::jog_until_ms` passes.
    Jog,
    /// Another manual motion (reference return).
    Manual,
}

/// What the sink shares with the action driving it.
#[derive(Debug)]
pub(crate) struct Tracker {
    /// Position of the last setpoint.
    pub at: Cell<[f64; 9]>,
    /// The machine stood still at a stop (or jog end) and the action ended there.
    pub abandoned: Cell<bool>,
    /// The snapshot shown.
    current: RefCell<Option<Arc<Snapshot>>>,
    /// Sequence number of the last message shown.
    shown_message: Cell<u64>,
    /// The ring of snapshots of a program or MDI block.
    pub ring: Rc<RefCell<SnapshotRing>>,
}

impl Tracker {
    /// Shows `snap` in `s` unless it is the one shown (and its message, if it is new).
    pub fn show(&self, s: &mut Status, snap: &Arc<Snapshot>) {
        let same = self
            .current
            .borrow()
            .as_ref()
            .is_some_and(|c| Arc::ptr_eq(c, snap));
        if same {
            return;
        }
        s.show_block(snap);
        if let Some((seq, text)) = &snap.message {
            if *seq > self.shown_message.get() {
                s.message = text.trim().to_string();
                self.shown_message.set(*seq);
            }
        }
        *self.current.borrow_mut() = Some(snap.clone());
    }
}

/// A simulated machine standing at `at`, whose setpoints are paced and published (module doc).
pub(crate) fn paced_machine(
    config: &MachineConfig,
    shared: &Arc<Shared>,
    at: [f64; 9],
    mode: Mode,
) -> (SimMachine, Rc<Tracker>) {
    let options = SimOptions {
        servo_period_s: config.servo_period_s,
        lookahead: SERVE_LOOKAHEAD,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(config.machine.clone(), options);
    sim.set_hold_switch(shared.controls.hold.clone());
    if mode == Mode::Program {
        sim.set_override_switch(shared.controls.overrides.clone());
    }
    let tracker = Rc::new(Tracker {
        at: Cell::new(at),
        abandoned: Cell::new(false),
        current: RefCell::new(None),
        shown_message: Cell::new(0),
        ring: Rc::new(RefCell::new(SnapshotRing::new())),
    });
    sim.set_setpoint_sink(sink(
        shared.clone(),
        config.time_scale,
        tracker.clone(),
        config.machine.five_axis(),
        mode,
    ));
    (sim, tracker)
}

/// The setpoint sink of the module doc.
fn sink(
    shared: Arc<Shared>,
    time_scale: f64,
    tracker: Rc<Tracker>,
    kinematics: Option<stanok_kin::FiveAxis>,
    mode: Mode,
) -> Box<dyn FnMut(&Setpoint)> {
    let mut pacer = Pacer {
        scale: time_scale,
        origin: Instant::now(),
        origin_t: 0.0,
    };
    // The overrides the last setpoint ran with, and since when (module doc of machine.rs).
    let mut in_force = (None, 0.0);
    Box::new(move |sp: &Setpoint| {
        if tracker.abandoned.get() {
            resume_unwind(Box::new(Cancelled));
        }
        let controls = &shared.controls;
        let v = &sp.velocity;
        let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let at_rest = v.iter().all(|x| *x == 0.0);
        let jog_over =
            mode == Mode::Jog && controls.now_ms() > controls.jog_until_ms.load(Ordering::Relaxed);
        let ending = controls.stop.is_raised() || jog_over;
        if ending {
            controls.hold.set(true);
        }
        // The tool axis from the rotary axes' positions (a 3-axis machine: +Z).
        let tool_axis = kinematics.as_ref().map_or([0.0, 0.0, 1.0], |k| {
            k.tool_vector_at(&stanok_canon::Pose::from_array(sp.position))
        });
        let snapshot = match mode {
            Mode::Program => tracker.ring.borrow_mut().executing(sp.line),
            _ => None,
        };
        let overrides = (mode == Mode::Program).then(|| crate::machine::switches(controls));
        if overrides.is_some() && overrides != in_force.0 {
            in_force = (overrides, sp.t);
        }
        tracker.at.set(sp.position);
        shared.publish(|s| {
            s.machine_position = sp.position;
            s.tool_axis = tool_axis;
            if let Some(snap) = &snapshot {
                tracker.show(s, snap);
            }
            s.work_position = s.state.work_of(&sp.position);
            if mode == Mode::Program {
                s.elapsed_s = sp.t;
            }
            s.feed_actual = speed * 60.0;
            // The commanded speed with the spindle override (the motion stage applies it).
            s.spindle_actual_rpm = sp.spindle_rpm;
            if let Some((f, r, sp_o)) = in_force.0 {
                (s.feed_override, s.rapid_override, s.spindle_override) = (f, r, sp_o);
                s.overrides_since_s = in_force.1;
            }
            s.held = controls.hold.is_held() && !ending;
        });
        if ending && at_rest {
            // Stopped on the path: the action ends here (module doc).
            tracker.abandoned.set(true);
            controls.hold.set(false);
            resume_unwind(Box::new(Cancelled));
        }
        pacer.pace(sp.t);
    })
}
