//! The progress bar of `stanok run` (indicatif), on stderr, for runs that take more than a second.
//!
//! Position = byte offset of the block being executed in the program file (loops and subroutine
//! calls move it back, which the bar shows honestly); message = simulated machine time. The bar
//! stays hidden for the first second of wall-clock time, so short runs print nothing, and
//! indicatif hides it anyway when stderr is not a terminal. Cheap: the clock is read every 256
//! commands and the message updated every 4096 setpoints.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::cell::Cell;
use std::rc::Rc;
use std::time::{Duration, Instant};

struct Inner {
    bar: ProgressBar,
    started: Instant,
    shown: Cell<bool>,
    commands: Cell<u64>,
    setpoints: Cell<u64>,
}

/// A shared handle on the run's progress bar.
#[derive(Clone)]
pub struct Progress(Rc<Inner>);

impl Progress {
    /// A hidden bar over a program of `total` bytes.
    pub fn new(total: u64) -> Self {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {wide_bar} {bytes}/{total_bytes} of the program, {msg}",
        ) {
            bar.set_style(style);
        }
        Progress(Rc::new(Inner {
            bar,
            started: Instant::now(),
            shown: Cell::new(false),
            commands: Cell::new(0),
            setpoints: Cell::new(0),
        }))
    }

    /// A command from byte `offset` of the program is being executed.
    pub fn command(&self, offset: u64) {
        let n = self.0.commands.get().wrapping_add(1);
        self.0.commands.set(n);
        if n & 255 != 0 {
            return;
        }
        if !self.0.shown.get() && self.0.started.elapsed() > Duration::from_secs(1) {
            self.0.shown.set(true);
            self.0.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        if self.0.shown.get() {
            self.0.bar.set_position(offset);
        }
    }

    /// A setpoint at simulated time `t` (s) was executed.
    pub fn setpoint(&self, t: f64) {
        let n = self.0.setpoints.get().wrapping_add(1);
        self.0.setpoints.set(n);
        if n & 4095 == 0 && self.0.shown.get() {
            self.0.bar.set_message(format!("{t:.1} s of machine time"));
        }
    }

    /// The run is over: removes the bar.
    pub fn done(&self) {
        self.0.bar.finish_and_clear();
    }
}
