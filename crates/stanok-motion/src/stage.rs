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
use crate::contour::{ContourMonitor, Reference, SPLINE_REFERENCE_TOLERANCE};
use crate::interpolator::{Interpolator, Setpoint};
use crate::limits::MotionConfig;
use crate::path::PathBuilder;
use crate::planner::Planner;
use crate::segment::{PlannerInput, Point9, SegmentGeometry};
use crate::tcp::TcpMap;
use crate::timing::{BlockTimer, PieceInfo};
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
    /// The planner inputs of one Canon command (reused: no allocation per command). A command
    /// makes at most a handful, except a G95 feed under G96, which `css::split` may cut into up to
    /// `css::MAX_PIECES`.
    inputs: Vec<PlannerInput>,
    /// The override factors last set through the stage's setters.
    wanted: Option<crate::piece::Overrides>,
    /// The contour measurement (see [`crate::contour`]).
    contour: ContourMonitor,
    /// The blocks' times and limits (see [`crate::timing`]).
    timer: BlockTimer,
    /// The reference points of the spline command being adapted (a fine tessellation of its
    /// curve), for the contour measurement of its segments.
    spline_reference: Option<std::sync::Arc<Vec<[f64; 3]>>>,
}

/// The sink as the machine sees it: setpoints through the kin stage when one is active.
/// Every setpoint is measured against the programmed path first (in pose space under TCP).
fn mapped<'a>(
    tcp: &'a Option<TcpMap>,
    contour: &'a mut ContourMonitor,
    out: &'a mut impl FnMut(&Setpoint),
) -> impl FnMut(&Setpoint) + 'a {
    move |sp: &Setpoint| {
        contour.observe(&sp.position, sp.seq, sp.junction, sp.t, sp.line);
        match tcp {
            Some(map) => out(&map.joints(sp)),
            None => out(sp),
        }
    }
}

/// Runs every piece the planner releases (module doc of [`crate::planner`], step 3): each is
/// sampled with the planner at hand, so that an override change while it runs re-plans the pieces
/// still in the window.
fn run_ready(
    planner: &mut Planner,
    interpolator: &mut Interpolator,
    stats: &mut StageStats,
    timer: &mut BlockTimer,
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
        let info = PieceInfo::of(&pp, &planner.overrides());
        let run = interpolator.push(pp, planner, out);
        timer.piece(&info, &run);
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
            wanted: None,
            contour: ContourMonitor::default(),
            timer: BlockTimer::default(),
            spline_reference: None,
        }
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

    /// The blocks' planned and nominal times and limits so far (see [`crate::timing`]); the block
    /// being run is added by [`MotionStage::finish`].
    pub fn block_times(&self) -> &BlockTimer {
        &self.timer
    }

    /// The contour error measured so far (see [`crate::contour`]).
    pub fn contour(&self) -> &ContourMonitor {
        &self.contour
    }

    /// Feeds a planner input directly (tests and benchmarks: no Canon needed).
    pub fn push_input(&mut self, input: PlannerInput, out: &mut impl FnMut(&Setpoint)) {
        // A segment that does not move (a compensation corner of radius 0) makes no piece: it is
        // not a side of any junction either.
        let moves = |seg: &crate::segment::PathSegment| match &seg.geometry {
            SegmentGeometry::Arc(h) => {
                h.length() > 0.0 || (3..9).any(|i| seg.start[i] != seg.end[i])
            }
            _ => seg.start != seg.end,
        };
        if let Some(seg) = match &input {
            PlannerInput::Segment(seg) if moves(seg) => Some(seg),
            _ => None,
        } {
            let reference = match &seg.geometry {
                SegmentGeometry::Line => crate::contour::line_reference(&seg.start, &seg.end),
                SegmentGeometry::Arc(h) => Reference::Arc(h.frame()),
                SegmentGeometry::Polyline(p) => Reference::Polyline(match &self.spline_reference {
                    Some(r) => r.clone(),
                    None => std::sync::Arc::new(p.iter().map(|q| [q[0], q[1], q[2]]).collect()),
                }),
            };
            self.contour.register(self.builder.next_seq(), reference);
        }
        let Self {
            builder,
            planner,
            interpolator,
            stats,
            tcp,
            contour,
            timer,
            ..
        } = self;
        let out = &mut mapped(tcp, contour, out);
        builder.push(input, &mut |piece| {
            planner.push_piece(piece);
            run_ready(planner, interpolator, stats, timer, out);
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
            contour,
            timer,
            ..
        } = self;
        let out = &mut mapped(tcp, contour, out);
        builder.set_position(at, &mut |piece| {
            planner.push_piece(piece);
            run_ready(planner, interpolator, stats, timer, out);
        });
        interpolator.set_position(at);
    }

    /// Feeds one Canon command of source line `line`.
    pub fn apply(&mut self, cmd: &Canon, line: u32, out: &mut impl FnMut(&Setpoint)) {
        if let Canon::Init { position, .. } = cmd {
            self.set_position(position.to_array(), out);
            return;
        }
        let mut inputs = std::mem::take(&mut self.inputs);
        self.adapter
            .adapt(cmd, line, &mut |input| inputs.push(input));
        if let Canon::SplineFeed(sp) = cmd {
            self.spline_reference = Some(std::sync::Arc::new(spline_points(sp)));
        }
        for input in inputs.drain(..) {
            self.push_input(input, out);
        }
        self.spline_reference = None;
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
            contour,
            timer,
            ..
        } = self;
        let out = &mut mapped(tcp, contour, out);
        builder.flush(&mut |piece| {
            planner.push_piece(piece);
            run_ready(planner, interpolator, stats, timer, out);
        });
        planner.finish_window();
        run_ready(planner, interpolator, stats, timer, out);
    }

    /// The program is over: runs everything and emits the final setpoint. Returns the trace
    /// duration (the cycle time), s. Calling it again returns the same time and emits nothing.
    pub fn finish(&mut self, out: &mut impl FnMut(&Setpoint)) -> f64 {
        if let Some(t) = self.finished {
            return t;
        }
        self.drain(out);
        self.timer.close();
        let t = self
            .interpolator
            .finish(&mut mapped(&self.tcp, &mut self.contour, out));
        self.finished = Some(t);
        t
    }
}

/// A spline's curve as points within [`SPLINE_REFERENCE_TOLERANCE`], from its start to its end.
fn spline_points(sp: &stanok_canon::SplineMove) -> Vec<[f64; 3]> {
    let curve = stanok_geom::Nurbs::new(sp.degree, &sp.control_points, &sp.weights, &sp.knots);
    let mut points = vec![sp.start.xyz()];
    if curve.validate().is_ok() {
        curve.tessellate(SPLINE_REFERENCE_TOLERANCE, &mut points);
    }
    points.push(sp.end.xyz());
    points
}
