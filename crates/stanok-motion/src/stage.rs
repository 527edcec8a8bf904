//! The motion stage: Canon in, setpoints out, streaming.
//!
//! ```text
//!  Canon ─▶ CanonAdapter ─▶ PathBuilder ─▶ Planner (window) ─▶ Interpolator ─▶ sink(&Setpoint)
//!           modal state      chords, blends   reverse/forward     servo grid
//! ```
//! Each stage pushes into the next through a closure, so nothing is collected: memory is the
//! planner window plus the chords of one segment, whatever the program's length. Setpoints are
//! produced as soon as the planner releases pieces (when its window is full, at a stop, at the end).
//!
//! Tool-centre-point control: while it is on, the path is planned in tool poses and every setpoint
//! goes through [`TcpMap::joints`] (the kin stage, [`crate::tcp`]) before the sink sees it. The
//! switch drains the path (the adapter has stopped it) and re-expresses where the machine stands:
//! joints → pose by the forward kinematics when it goes on, pose → joints when it goes off.

use crate::adapter::CanonAdapter;
use crate::interpolator::{Interpolator, Setpoint};
use crate::limits::MotionConfig;
use crate::path::PathBuilder;
use crate::planner::Planner;
use crate::segment::{PlannerInput, Point9};
use crate::tcp::TcpMap;
use stanok_canon::Canon;
use stanok_kin::Kinematics;

/// Statistics of the pieces planned so far.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageStats {
    /// Pieces released by the planner (lines, blends, dwells).
    pub pieces: u64,
    /// Largest analytic deviation bound of any piece from the programmed path, unit.
    pub max_deviation: f64,
    /// Pieces whose deviation bound exceeded the tolerance in force (must stay 0).
    pub tolerance_violations: u64,
}

/// Canon → setpoints (module doc).
#[derive(Debug, Clone)]
pub struct MotionStage {
    adapter: CanonAdapter,
    builder: PathBuilder,
    planner: Planner,
    interpolator: Interpolator,
    stats: StageStats,
    finished: Option<f64>,
    /// The kin stage while tool-centre-point control is on.
    tcp: Option<TcpMap>,
    /// Canon commands fed so far (`apply`); the serial number of the last one.
    commands: u64,
    /// The planner inputs of one Canon command (reused: no allocation per command). A command
    /// makes at most a handful, except a G95 feed under G96, which `css::split` may cut into up to
    /// `css::MAX_PIECES`.
    inputs: Vec<PlannerInput>,
    /// The override factors last set through the stage's setters.
    wanted: Option<crate::piece::Overrides>,
}

/// The sink as the machine sees it: setpoints through the kin stage when one is active.
fn mapped<'a>(
    tcp: &'a Option<TcpMap>,
    out: &'a mut impl FnMut(&Setpoint),
) -> impl FnMut(&Setpoint) + 'a {
    move |sp: &Setpoint| match tcp {
        Some(map) => out(&map.joints(sp)),
        None => out(sp),
    }
}

/// Runs every piece the planner releases (module doc of [`crate::planner`], step 3): each is
/// sampled with the planner at hand, so that an override change while it runs re-plans the pieces
/// still in the window.
fn run_ready(
    planner: &mut Planner,
    interpolator: &mut Interpolator,
    stats: &mut StageStats,
    out: &mut impl FnMut(&Setpoint),
) {
    while let Some(pp) = planner.pop_ready() {
        stats.pieces += 1;
        stats.max_deviation = stats.max_deviation.max(pp.piece.deviation);
        if pp.piece.deviation
            > pp.piece
                .tolerance
                .max(2.0 * crate::path::INTERNAL_TOLERANCE)
                * (1.0 + 1e-9)
        {
            stats.tolerance_violations += 1;
        }
        interpolator.push(pp, planner, out);
    }
}

impl MotionStage {
    /// A stage standing at the origin.
    pub fn new(config: &MotionConfig) -> Self {
        let config = config.clone().sanitised();
        MotionStage {
            adapter: CanonAdapter::new(&config),
            builder: PathBuilder::new(&config),
            planner: Planner::with_config(&config),
            inputs: Vec::new(),
            interpolator: Interpolator::new(config.servo_period, [0.0; 9]),
            stats: StageStats::default(),
            finished: None,
            tcp: None,
            commands: 0,
            wanted: None,
        }
    }

    /// How many Canon commands [`MotionStage::apply`] has received: the serial number of the
    /// last one. Every setpoint carries the serial of the command its piece comes from
    /// ([`Setpoint::command`]), so an observer that records state changes by serial (a tool
    /// change, a spindle stop) can apply each to exactly the setpoints after it, although the
    /// look-ahead releases setpoints later than the commands arrive.
    pub fn commands(&self) -> u64 {
        self.commands
    }

    /// Feed override (fraction 0…2) from the next servo instant on, on the motion being executed
    /// and everything planned (see [`crate::overrides`]).
    pub fn set_feed_override(&mut self, fraction: f64) {
        let mut o = self.wanted_overrides();
        o.feed = fraction;
        self.wanted = Some(o.clamped());
        self.interpolator.set_overrides(o);
    }

    /// Rapid override (fraction 0…1) from the next servo instant on.
    pub fn set_rapid_override(&mut self, fraction: f64) {
        let mut o = self.wanted_overrides();
        o.rapid = fraction;
        self.wanted = Some(o.clamped());
        self.interpolator.set_overrides(o);
    }

    /// Spindle override (fraction 0.5…1.2) from the next servo instant on.
    pub fn set_spindle_override(&mut self, fraction: f64) {
        let mut o = self.wanted_overrides();
        o.spindle = fraction;
        self.wanted = Some(o.clamped());
        self.interpolator.set_overrides(o);
    }

    fn wanted_overrides(&self) -> crate::piece::Overrides {
        self.wanted.unwrap_or(self.planner.overrides())
    }

    /// Connects the operator's override knobs, read at every servo instant (see
    /// [`crate::overrides::OverrideSwitch`]); from now on their values are the ones wanted.
    pub fn set_override_switch(
        &mut self,
        switch: std::sync::Arc<crate::overrides::OverrideSwitch>,
    ) {
        self.interpolator.set_override_switch(switch);
    }

    /// Timed override changes at machine times (`stanok run --override-at`).
    pub fn schedule_overrides(&mut self, changes: &[crate::overrides::OverrideChange]) {
        self.interpolator.schedule_overrides(changes);
    }

    /// The override factors in force now.
    pub fn overrides(&self) -> crate::piece::Overrides {
        self.planner.overrides()
    }

    /// True if a zero override stopped the machine for good (no change could come): the rest of
    /// the run did not execute.
    pub fn stalled_for_good(&self) -> bool {
        self.interpolator.stalled_for_good()
    }

    /// Feed hold at simulated time `at` (s): brake on the path, stand `standstill` s, resume.
    pub fn feed_hold(&mut self, at: f64, standstill: f64) {
        self.interpolator.request_hold(at, standstill);
    }

    /// Connects the operator's feed-hold button (see [`crate::hold::HoldSwitch`]).
    pub fn set_hold_switch(&mut self, switch: std::sync::Arc<crate::hold::HoldSwitch>) {
        self.interpolator.set_hold_switch(switch);
    }

    /// Pieces released so far, deviation statistics.
    pub fn stats(&self) -> StageStats {
        self.stats
    }

    /// Planned time so far (pieces released to the interpolator), s.
    pub fn planned_time(&self) -> f64 {
        self.interpolator.planned_time()
    }

    /// The servo period, s.
    pub fn servo_period(&self) -> f64 {
        self.interpolator.period()
    }

    /// Feeds a planner input directly (tests and benchmarks: no Canon needed).
    pub fn push_input(&mut self, input: PlannerInput, out: &mut impl FnMut(&Setpoint)) {
        let Self {
            builder,
            planner,
            interpolator,
            stats,
            tcp,
            ..
        } = self;
        let out = &mut mapped(tcp, out);
        builder.push(input, &mut |piece| {
            planner.push_piece(piece);
            run_ready(planner, interpolator, stats, out);
        });
    }

    /// The machine stands at `at` (Canon `Init`); anything pending is run first.
    pub fn set_position(&mut self, at: Point9, out: &mut impl FnMut(&Setpoint)) {
        self.drain(out);
        let Self {
            builder,
            planner,
            interpolator,
            stats,
            tcp,
            ..
        } = self;
        let out = &mut mapped(tcp, out);
        builder.set_position(at, &mut |piece| {
            planner.push_piece(piece);
            run_ready(planner, interpolator, stats, out);
        });
        interpolator.set_position(at);
    }

    /// Feeds one Canon command of source line `line`.
    pub fn apply(&mut self, cmd: &Canon, line: u32, out: &mut impl FnMut(&Setpoint)) {
        self.commands += 1;
        self.adapter.set_command(self.commands);
        if let Canon::Init { position, .. } = cmd {
            self.set_position(position.to_array(), out);
            return;
        }
        let mut inputs = std::mem::take(&mut self.inputs);
        self.adapter
            .adapt(cmd, line, &mut |input| inputs.push(input));
        for input in inputs.drain(..) {
            self.push_input(input, out);
        }
        self.inputs = inputs;
        if let Canon::SetToolCentrePoint { .. } = cmd {
            self.switch_tcp(out);
        }
    }

    /// Tool-centre-point control changed (module doc): run the path out, then re-express the
    /// position in the new meaning.
    fn switch_tcp(&mut self, out: &mut impl FnMut(&Setpoint)) {
        self.drain(out);
        let here = self.interpolator.end();
        let joints = match &self.tcp {
            Some(map) => map
                .kinematics()
                .inverse(&stanok_canon::Pose::from_array(here))
                .unwrap_or(here),
            None => here,
        };
        let next = self.adapter.tcp().cloned().map(TcpMap::new);
        let pose = match &next {
            Some(map) => map
                .kinematics()
                .forward(&joints)
                .map(|p| p.to_array())
                .unwrap_or(joints),
            None => joints,
        };
        self.tcp = next;
        self.set_position(pose, out);
    }

    /// Runs everything pending (the path stops at its current end).
    pub fn drain(&mut self, out: &mut impl FnMut(&Setpoint)) {
        let Self {
            builder,
            planner,
            interpolator,
            stats,
            tcp,
            ..
        } = self;
        let out = &mut mapped(tcp, out);
        builder.flush(&mut |piece| {
            planner.push_piece(piece);
            run_ready(planner, interpolator, stats, out);
        });
        planner.finish_window();
        run_ready(planner, interpolator, stats, out);
    }

    /// The program is over: runs everything and emits the final setpoint. Returns the trace
    /// duration (the cycle time), s. Calling it again returns the same time and emits nothing.
    pub fn finish(&mut self, out: &mut impl FnMut(&Setpoint)) -> f64 {
        if let Some(t) = self.finished {
            return t;
        }
        self.drain(out);
        let t = self.interpolator.finish(&mut mapped(&self.tcp, out));
        self.finished = Some(t);
        t
    }
}
