//! [`StockSim`]: the stock-removal simulation as an observer of a machine run.
//!
//! It sees two streams: the Canon commands the machine accepts ([`StockSim::command`], with the
//! motion stage's serial number of each) and the servo setpoints ([`StockSim::setpoint`], each
//! naming the serial of its command). The look-ahead releases setpoints later than the commands
//! arrive, so a state change (tool, tool length offset, tool-centre-point control, spindle on/off,
//! rapid/feed) is queued with its serial and applied to exactly the setpoints after it: a change
//! at command n to setpoints of commands > n, a motion command's own kind to its setpoints.
//!
//! ## From setpoints to sweeps
//! 1. **Tool pose.** The setpoint's axis positions are joints. The tip and axis come from the
//!    machine's forward kinematics with the tool length in force (the TCP length under tool-centre-
//!    point control, else the G43 offset): the tip is where the program's offsets put it, as
//!    LinuxCNC's preview draws it; on a Cartesian machine, position − offset along +Z. Then into
//!    the stock frame (the work frame in force at the first motion, or the machine frame).
//! 2. **Chains.** Consecutive poses of one state are merged into one straight sweep while the path
//!    stays within [`StockSim::tolerance`] (a tenth of the resolution) of the chord —
//!    `dev ← dev + |end − start|·sin(turn of the chord)` bounds every skipped point's distance —
//!    and the axis turns less than the angle at which the flute end moves half a resolution; a
//!    single step that turns more is cut into sub-steps. A chain of one block grows as long as it
//!    stays straight; a chain may take in further blocks only while it is at most
//!    [`MULTI_BLOCK_RUN`] cells long (the 0.1 mm blocks of a CAM finishing path would otherwise
//!    cost one sweep each, mostly overhead): its removal is shared among its blocks by their time,
//!    a collision goes to its first block (at most a millimetre from the block that caused it at
//!    the default resolution). A long rapid stays one exact sweep (the
//!    swept volume of `sweep.rs`), however far it goes in one servo period.
//! 3. **Sweep.** The model cuts the swept cutter, checks the bodies above it, and the result is
//!    booked: volume and time in material per tool and per block, collisions per kind and block
//!    (merged: the first sweep's time and position, the deepest depth).
//! 4. **Discontinuities.** A tool change, a new length offset or a TCP switch moves the computed tip
//!    without the machine moving: the chain restarts there, nothing is swept across the jump.
//!
//! Memory: the model (bounded by the stock and resolution), the event queue (the commands in the
//! look-ahead window), per-block totals (one entry per source line that cut) and at most
//! [`MAX_COLLISIONS`] collision records.

use crate::lathe::LatheModel;
use crate::mesh::{grid_from_triangles, read_stl, Mesh};
use crate::mill::{prim_lowest, MillModel};
use crate::report::{
    BlockRemoval, Collision, CollisionKind, RemovedVolume, StockReport, ToolRemoval,
};
use crate::spec::{StockFrame, StockShape};
use crate::sweep::Sweep;
use crate::tool::{resolve, ToolShape};
use crate::vec3::{add, dot, norm, sub, unit, V3};
use stanok_canon::setup::ToolTable;
use stanok_canon::Canon;
use stanok_kin::{FiveAxis, Kinematics};
use stanok_motion::Setpoint;
use std::collections::{BTreeMap, HashMap, VecDeque};

/// Collision records kept (all are counted).
pub const MAX_COLLISIONS: usize = 1000;
/// Default cell size, mm.
pub const DEFAULT_RESOLUTION: f64 = 0.1;
/// A straight run may merge several blocks while it is at most this many cells long (the short
/// blocks of a CAM surface path); its removal is shared among them by time, its collisions go to
/// its first block.
pub const MULTI_BLOCK_RUN: f64 = 10.0;
/// Most lines of a milling model: the default resolution is coarsened to stay within it.
pub const MAX_LINES: f64 = 4.0e6;

/// How to simulate (the CLI and machine data fill it).
#[derive(Debug, Clone)]
pub struct StockConfig {
    /// The raw stock.
    pub shape: StockShape,
    /// Its coordinates.
    pub frame: StockFrame,
    /// Cell size, mm (None = [`DEFAULT_RESOLUTION`], coarsened to [`MAX_LINES`]).
    pub resolution: Option<f64>,
    /// The tool table (edges and bodies).
    pub tools: ToolTable,
    /// The machine's kinematics (None = Cartesian).
    pub kinematics: Option<FiveAxis>,
    /// A lathe: the revolved model and turning inserts.
    pub lathe: bool,
    /// Top of the fixture/table, machine Z (workpiece-fixed frame): nothing may go below it.
    pub fixture_z: Option<f64>,
}

/// Machine (workpiece-fixed) → stock frame: `R(−θ)·(p − origin) − shift`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Placement {
    origin: V3,
    rotation: f64,
    shift: V3,
}

impl Placement {
    fn rot(v: V3, deg: f64) -> V3 {
        let (s, c) = deg.to_radians().sin_cos();
        [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
    }
    fn to_stock(self, p: V3) -> V3 {
        sub(Self::rot(sub(p, self.origin), -self.rotation), self.shift)
    }
    fn dir_to_stock(&self, v: V3) -> V3 {
        Self::rot(v, -self.rotation)
    }
    fn to_machine(self, q: V3) -> V3 {
        add(Self::rot(add(q, self.shift), self.rotation), self.origin)
    }
}

/// The material model of either machine.
#[derive(Debug, Clone)]
pub enum Model {
    /// Mills: vertical dexels.
    Mill(MillModel),
    /// Lathes: revolved rows.
    Lathe(LatheModel),
}

impl Model {
    /// Material volume, mm³.
    pub fn volume(&self) -> f64 {
        match self {
            Model::Mill(m) => m.volume(),
            Model::Lathe(l) => l.volume(),
        }
    }
}

/// A state change, queued until the setpoints it applies to arrive (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    Tool(u32),
    Offset(V3),
    Tcp(Option<V3>),
    Spindle(bool),
    Rapid(bool),
    Restart,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct State {
    tool: u32,
    offset: V3,
    tcp: Option<V3>,
    spindle: bool,
    rapid: bool,
}

/// A tool pose in the stock frame.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ToolPose {
    tip: V3,
    axis: V3,
}

/// The sweep being built (module doc, step 2).
#[derive(Debug, Clone, Copy)]
struct Chain {
    start: ToolPose,
    end: ToolPose,
    t0: f64,
    t1: f64,
    line: u32,
    dev: f64,
}

#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    volume: f64,
    time: f64,
}

/// The stock-removal simulation (module doc).
#[derive(Debug)]
pub struct StockSim {
    config: StockConfig,
    resolution: f64,
    model: Option<Model>,
    placement: Placement,
    frame_now: Placement,
    events: VecDeque<(u64, Event)>,
    last_rapid_queued: Option<bool>,
    state: State,
    tools: HashMap<u32, ToolShape>,
    tool_now: Option<ToolShape>,
    /// The kinematics with the tool offset in force, and that offset.
    kin: Option<(V3, FiveAxis)>,
    chain: Option<Chain>,
    last: Option<(ToolPose, f64)>,
    per_tool: BTreeMap<u32, Tally>,
    per_line: BTreeMap<u32, Tally>,
    collisions: Vec<Collision>,
    collision_count: u64,
    /// The blocks of the open chain: (line, time it starts), in order.
    chain_lines: Vec<(u32, f64)>,
    /// Per kind: the line, index and last sweep of the record still open.
    open: HashMap<CollisionKind, (u32, usize, u64)>,
    notes: Vec<String>,
    initial_volume: f64,
    sweeps: u64,
    error: Option<String>,
}

impl StockSim {
    /// A simulation; the model is built at the first motion (the work frame is known then).
    /// A resolution outside 0.001 … 100 mm, or a lathe with a box, is an error.
    pub fn new(config: StockConfig) -> Result<StockSim, String> {
        let resolution = match config.resolution {
            Some(r) if !(0.001..=100.0).contains(&r) => {
                return Err(format!(
                    "the stock resolution must be 0.001 … 100 mm, not {r}"
                ))
            }
            Some(r) => r,
            None => {
                let area = match &config.shape {
                    StockShape::Box { min, max } => (max[0] - min[0]) * (max[1] - min[1]),
                    StockShape::Cylinder { diameter, .. } => diameter * diameter,
                    StockShape::Mesh { .. } => 0.0,
                };
                DEFAULT_RESOLUTION.max((area / MAX_LINES).sqrt())
            }
        };
        if config.lathe && !matches!(config.shape, StockShape::Cylinder { .. }) {
            return Err("a lathe's stock is a cylinder: --stock cylinder:Z-80:D50,Z0".into());
        }
        Ok(StockSim {
            resolution,
            model: None,
            placement: Placement::default(),
            frame_now: Placement::default(),
            events: VecDeque::new(),
            last_rapid_queued: None,
            state: State {
                tool: 0,
                offset: [0.0; 3],
                tcp: None,
                spindle: false,
                rapid: true,
            },
            tools: HashMap::new(),
            tool_now: None,
            kin: None,
            chain: None,
            chain_lines: Vec::new(),
            last: None,
            per_tool: BTreeMap::new(),
            per_line: BTreeMap::new(),
            collisions: Vec::new(),
            collision_count: 0,
            open: HashMap::new(),
            notes: Vec::new(),
            initial_volume: 0.0,
            sweeps: 0,
            error: None,
            config,
        })
    }

    /// Cell size in use, mm.
    pub fn resolution(&self) -> f64 {
        self.resolution
    }

    /// Chains stay within this distance of their chord, mm.
    pub fn tolerance(&self) -> f64 {
        self.resolution / 10.0
    }

    /// The model (None before the first motion).
    pub fn model(&self) -> Option<&Model> {
        self.model.as_ref()
    }

    /// An error that stopped the simulation (an STL that could not be read).
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Collisions so far.
    pub fn collisions(&self) -> &[Collision] {
        &self.collisions
    }

    fn build_model(&mut self) {
        self.placement = match self.config.frame {
            StockFrame::Work => self.frame_now,
            StockFrame::Machine => Placement::default(),
        };
        let r = self.resolution;
        let model = match &self.config.shape {
            StockShape::Cylinder {
                centre,
                z,
                diameter,
                bore,
            } if self.config.lathe => {
                Model::Lathe(LatheModel::new_cylinder(*centre, *z, *diameter, *bore, r))
            }
            StockShape::Cylinder {
                centre,
                z,
                diameter,
                bore,
            } => Model::Mill(MillModel::new_cylinder(*centre, *z, *diameter, *bore, r)),
            StockShape::Box { min, max } => Model::Mill(MillModel::new_box(*min, *max, r)),
            StockShape::Mesh { path } => match read_stl(path) {
                Ok(tris) => Model::Mill(MillModel::from_grid(grid_from_triangles(&tris, r))),
                Err(e) => {
                    self.error = Some(e);
                    return;
                }
            },
        };
        self.initial_volume = model.volume();
        self.model = Some(model);
    }

    /// Feeds an accepted Canon command with the motion stage's serial number of it (module doc).
    pub fn command(&mut self, serial: u64, cmd: &Canon) {
        let after = 2 * serial + 1;
        let push = |s: &mut Self, key: u64, e: Event| s.events.push_back((key, e));
        match cmd {
            Canon::Init {
                g5x_offset,
                g92_offset,
                xy_rotation,
                ..
            } => {
                self.frame_now = Placement {
                    origin: [g5x_offset.x, g5x_offset.y, g5x_offset.z],
                    rotation: *xy_rotation,
                    shift: [g92_offset.x, g92_offset.y, g92_offset.z],
                };
                push(self, 2 * serial, Event::Restart);
            }
            Canon::SetG5xOffset { offset, .. } => {
                self.frame_now.origin = [offset.x, offset.y, offset.z]
            }
            Canon::SetG92Offset { offset } => self.frame_now.shift = [offset.x, offset.y, offset.z],
            Canon::SetXyRotation { degrees } => self.frame_now.rotation = *degrees,
            Canon::ChangeTool { tool, .. } | Canon::SetCurrentTool { tool, .. } => {
                push(self, after, Event::Tool(*tool))
            }
            Canon::UseToolLengthOffset { offset } => {
                push(self, after, Event::Offset([offset.x, offset.y, offset.z]))
            }
            Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } => push(self, after, Event::Tcp(active.then_some(*tool_offset))),
            Canon::StartSpindle { spindle: 0, .. } => push(self, after, Event::Spindle(true)),
            Canon::StopSpindle { spindle: 0 } => push(self, after, Event::Spindle(false)),
            Canon::StraightTraverse(_)
            | Canon::StraightFeed(_)
            | Canon::ArcFeed(_)
            | Canon::SplineFeed(_)
            | Canon::StraightProbe { .. }
            | Canon::RigidTap { .. } => {
                if self.model.is_none() && self.error.is_none() {
                    self.build_model();
                }
                let rapid = matches!(cmd, Canon::StraightTraverse(_));
                if self.last_rapid_queued != Some(rapid) {
                    self.last_rapid_queued = Some(rapid);
                    push(self, 2 * serial, Event::Rapid(rapid));
                }
            }
            _ => {}
        }
    }

    fn tool_shape(&mut self, number: u32) -> ToolShape {
        if let Some(t) = self.tools.get(&number) {
            return t.clone();
        }
        let (shape, note) = resolve(
            number,
            &self.config.tools,
            self.config.lathe,
            self.tolerance(),
        );
        if let Some(n) = note {
            self.notes.push(n);
        }
        self.tools.insert(number, shape.clone());
        shape
    }

    /// The tool pose of a setpoint in the stock frame (module doc, step 1).
    fn pose(&mut self, joints: &[f64; 9]) -> ToolPose {
        let offset = self.state.tcp.unwrap_or(self.state.offset);
        // The machine with this tool offset, made once per offset (not per setpoint: it owns
        // its axes' vectors).
        if let Some(k) = &self.config.kinematics {
            if self.kin.as_ref().is_none_or(|(o, _)| *o != offset) {
                self.kin = Some((offset, k.clone().with_tool_offset(offset)));
            }
        }
        let (tip, axis) = match &self.kin {
            Some((_, kin)) => match kin.forward(joints) {
                Ok(p) => ([p.x, p.y, p.z], kin.tool_vector(&p)),
                Err(_) => ([joints[0], joints[1], joints[2]], [0.0, 0.0, 1.0]),
            },
            None => (
                sub([joints[0], joints[1], joints[2]], offset),
                [0.0, 0.0, 1.0],
            ),
        };
        ToolPose {
            tip: self.placement.to_stock(tip),
            axis: unit(self.placement.dir_to_stock(axis)).unwrap_or([0.0, 0.0, 1.0]),
        }
    }

    /// Feeds one servo setpoint (module doc).
    pub fn setpoint(&mut self, sp: &Setpoint) {
        // 1. State changes up to this setpoint's command: the open chain is swept under the
        // state it was built in, then the new state holds.
        let mut restart = false;
        let mut next = self.state;
        while let Some(&(key, e)) = self.events.front() {
            if key > 2 * sp.command {
                break;
            }
            self.events.pop_front();
            match e {
                Event::Tool(t) => next.tool = t,
                Event::Offset(o) => next.offset = o,
                Event::Tcp(t) => next.tcp = t,
                Event::Spindle(on) => next.spindle = on,
                Event::Rapid(r) => next.rapid = r,
                Event::Restart => restart = true,
            }
        }
        if self.model.is_none() {
            self.state = next;
            return;
        }
        let s = self.state;
        restart |= next.tool != s.tool || next.offset != s.offset || next.tcp != s.tcp;
        if restart || next != s {
            self.flush();
        }
        self.state = next;
        if restart || self.tool_now.is_none() {
            let t = self.tool_shape(self.state.tool);
            self.tool_now = Some(t);
        }
        if restart {
            self.chain = None;
            self.last = None;
        }
        let pose = self.pose(&sp.position);
        let Some((prev, t_prev)) = self.last else {
            self.last = Some((pose, sp.t));
            return;
        };
        self.last = Some((pose, sp.t));
        // A step whose axis turns too far is cut into sub-steps (module doc, step 2).
        let turn = dot(prev.axis, pose.axis).clamp(-1.0, 1.0).acos();
        let max_turn = self.max_turn();
        let steps = if turn > max_turn {
            ((turn / max_turn).ceil() as usize).min(1000)
        } else {
            1
        };
        for k in 1..=steps {
            let f = k as f64 / steps as f64;
            let q = if steps == 1 {
                pose
            } else {
                ToolPose {
                    tip: crate::vec3::lerp(prev.tip, pose.tip, f),
                    axis: unit(crate::vec3::lerp(prev.axis, pose.axis, f)).unwrap_or(pose.axis),
                }
            };
            let t = t_prev + (sp.t - t_prev) * f;
            let from = if k == 1 {
                (prev, t_prev)
            } else {
                self.chain.map_or((prev, t_prev), |c| (c.end, c.t1))
            };
            self.extend(from, q, t, sp.line);
        }
    }

    /// Largest turn of the axis within one sweep, rad: the flute end moves half a resolution.
    fn max_turn(&self) -> f64 {
        let len = match &self.tool_now {
            Some(ToolShape::Mill(m)) => m.flute_length.max(m.radius),
            _ => 1.0,
        };
        (0.5 * self.resolution / len.max(1e-3)).min(0.1)
    }

    /// Adds the step `from` → `q` to the open chain, or sweeps the chain and opens a new one.
    fn extend(&mut self, from: (ToolPose, f64), q: ToolPose, t: f64, line: u32) {
        let tol = self.tolerance();
        let max_turn = self.max_turn();
        let multi = MULTI_BLOCK_RUN * self.resolution;
        if let Some(c) = &mut self.chain {
            // A run of one block grows as long as it is straight; a run of several blocks (the
            // short blocks of a CAM surface path) stays within MULTI_BLOCK_RUN cells.
            let joins = (self.chain_lines.len() == 1 && c.line == line)
                || norm(sub(q.tip, c.start.tip)) <= multi;
            let turned = dot(c.start.axis, q.axis).clamp(-1.0, 1.0).acos() <= max_turn;
            if joins && turned {
                let old = sub(c.end.tip, c.start.tip);
                let new = sub(q.tip, c.start.tip);
                let (lo, ln) = (norm(old), norm(new));
                let dev = if lo < 1e-12 || ln < 1e-12 {
                    c.dev + lo.min(ln)
                } else {
                    let cos = (dot(old, new) / (lo * ln)).clamp(-1.0, 1.0);
                    c.dev + lo * (1.0 - cos * cos).sqrt() + if cos < 0.0 { lo } else { 0.0 }
                };
                if dev <= tol {
                    c.end = q;
                    c.t1 = t;
                    c.dev = dev;
                    if self.chain_lines.last().is_some_and(|l| l.0 != line) {
                        self.chain_lines.push((line, from.1));
                    }
                    return;
                }
            }
        }
        let start = match self.chain.take() {
            Some(c) => {
                self.sweep(&c);
                (c.end, c.t1)
            }
            None => from,
        };
        self.chain_lines.clear();
        self.chain_lines.push((line, start.1));
        self.chain = Some(Chain {
            start: start.0,
            end: q,
            t0: start.1,
            t1: t,
            line,
            dev: 0.0,
        });
    }

    /// Sweeps the open chain, if any, and keeps its end as the start of the next.
    fn flush(&mut self) {
        if let Some(c) = self.chain.take() {
            self.sweep(&c);
        }
    }

    /// Books a collision of this sweep: it extends the record of the same kind if that one is
    /// still open (the same block, or the contact went on from the previous sweep without a
    /// break), else opens a new one.
    fn record(&mut self, kind: CollisionKind, c: &Chain, depth: f64, tool: u32) {
        if let Some(&(line, idx, last)) = self.open.get(&kind) {
            if line == c.line || last + 1 == self.sweeps {
                let rec = &mut self.collisions[idx];
                rec.depth_mm = rec.depth_mm.max(depth);
                self.open.insert(kind, (line, idx, self.sweeps));
                return;
            }
        }
        self.collision_count += 1;
        if self.collisions.len() < MAX_COLLISIONS {
            self.open
                .insert(kind, (c.line, self.collisions.len(), self.sweeps));
            self.collisions.push(Collision {
                kind,
                line: c.line,
                time_s: c.t0,
                position: self.placement.to_machine(c.start.tip),
                depth_mm: depth,
                tool,
            });
        } else {
            self.open.remove(&kind);
        }
    }

    fn sweep(&mut self, c: &Chain) {
        let Some(tool) = self.tool_now.clone() else {
            return;
        };
        let Some(model) = self.model.as_mut() else {
            return;
        };
        self.sweeps += 1;
        let d = sub(c.end.tip, c.start.tip);
        let fixture = self
            .config
            .fixture_z
            .map(|z| z - self.placement.origin[2] - self.placement.shift[2]);
        let mut found: Vec<(CollisionKind, f64)> = Vec::new();
        let removed = match (&tool, model) {
            (ToolShape::Mill(m), Model::Mill(model)) => {
                let axis = unit(add(c.start.axis, c.end.axis)).unwrap_or(c.end.axis);
                let sw = Sweep {
                    p0: c.start.tip,
                    d,
                    axis,
                };
                let hits = model.apply(m, &sw);
                for (kind, depth) in [
                    (CollisionKind::FluteLength, hits.flute),
                    (CollisionKind::Shank, hits.shank),
                    (CollisionKind::Holder, hits.holder),
                ] {
                    if depth > 1e-6 {
                        found.push((kind, depth));
                    }
                }
                if hits.removed > 0.0 && !m.centre_cutting {
                    let len = norm(d);
                    let descent = if len > 0.0 { -dot(d, axis) / len } else { 0.0 };
                    let tip_low = c.start.tip[2].min(c.end.tip[2]);
                    let at_tip = axis[2] < 1.0 - 1e-12
                        || hits.lowest_removed <= tip_low + 0.5 * self.resolution;
                    if descent > m.ramp_angle.sin() + 1e-9 && at_tip {
                        found.push((CollisionKind::Plunge, hits.depth));
                    }
                }
                if let Some(fz) = fixture {
                    let mut low = f64::INFINITY;
                    for p in m.cutter.iter().chain(&m.holder).chain(m.shank.iter()) {
                        for pose in [c.start, c.end] {
                            low = low.min(prim_lowest(p, pose.tip, axis));
                        }
                    }
                    if low < fz - 1e-9 {
                        found.push((CollisionKind::Fixture, fz - low));
                    }
                }
                (hits.removed, hits.depth)
            }
            (ToolShape::Insert(i), Model::Lathe(model)) => {
                let p = |q: V3| [q[2], q[0]];
                let hits = model.apply(i, p(c.start.tip), p(c.end.tip));
                if let Some(fz) = fixture {
                    if hits.z_min < fz - 1e-9 {
                        found.push((CollisionKind::Fixture, fz - hits.z_min));
                    }
                }
                (hits.removed, hits.depth)
            }
            _ => (0.0, 0.0),
        };
        let (volume, depth) = removed;
        let number = self.state.tool;
        if volume > 1e-9 {
            let dt = (c.t1 - c.t0).max(0.0);
            // The blocks of the run share its removal by time.
            let n = self.chain_lines.len();
            for k in 0..n {
                let (line, from) = self.chain_lines[k];
                let to = self.chain_lines.get(k + 1).map_or(c.t1, |l| l.1);
                let share = if n == 1 || dt <= 0.0 {
                    1.0
                } else {
                    ((to - from) / dt).clamp(0.0, 1.0)
                };
                let tally = self.per_line.entry(line).or_default();
                tally.volume += volume * share;
                tally.time += dt * share;
            }
            // A rapid or a stopped spindle matters when it removes more than a sliver: at least a
            // disk of the tool's radius one cell thick (a G64 blend into a retract grazes less).
            let sliver = match &tool {
                ToolShape::Mill(m) => std::f64::consts::PI * m.radius * m.radius,
                ToolShape::Insert(i) => 2.0 * std::f64::consts::PI * i.nose_radius * i.length,
            } * self.resolution;
            let tally = self.per_tool.entry(number).or_default();
            tally.volume += volume;
            tally.time += dt;
            if self.state.rapid && volume > sliver {
                found.push((CollisionKind::RapidInMaterial, depth));
            }
            if !self.state.spindle && volume > sliver {
                found.push((CollisionKind::SpindleStopped, depth));
            }
        }
        for (kind, depth) in found {
            self.record(kind, c, depth, number);
        }
    }

    /// Ends the run: sweeps what is open and reports.
    pub fn finish(&mut self) -> StockReport {
        self.flush();
        self.report()
    }

    /// The report so far (what is still in the open chain is not yet cut).
    pub fn report(&self) -> StockReport {
        let final_volume = self.model.as_ref().map_or(0.0, Model::volume);
        let mut blocks: Vec<BlockRemoval> = self
            .per_line
            .iter()
            .map(|(&line, t)| BlockRemoval {
                line,
                removed_mm3: t.volume,
                time_in_material_s: t.time,
                mrr_mm3_per_min: if t.time > 0.0 {
                    t.volume / t.time * 60.0
                } else {
                    0.0
                },
            })
            .collect();
        blocks.sort_by_key(|b| b.line);
        let peak = blocks.iter().map(|b| b.mrr_mm3_per_min).fold(0.0, f64::max);
        let mut notes = self.notes.clone();
        if let Some(e) = &self.error {
            notes.push(e.clone());
        }
        if self.model.is_none() && self.error.is_none() {
            notes.push("the program has no motion: nothing was simulated".into());
        }
        StockReport {
            model: match self.model {
                Some(Model::Lathe(_)) => "revolved",
                _ => "z-dexel",
            },
            resolution_mm: self.resolution,
            initial_volume_mm3: self.initial_volume,
            final_volume_mm3: final_volume,
            removed_volume_mm3: RemovedVolume {
                total: self.per_tool.values().map(|t| t.volume).sum(),
                per_tool: self
                    .per_tool
                    .iter()
                    .map(|(&tool, t)| ToolRemoval {
                        tool,
                        volume_mm3: t.volume,
                        time_in_material_s: t.time,
                    })
                    .collect(),
            },
            collisions: self.collisions.clone(),
            collision_count: self.collision_count,
            blocks,
            peak_mrr_mm3_per_min: peak,
            sweeps: self.sweeps,
            model_bytes: match &self.model {
                Some(Model::Mill(m)) => m.grid.memory_bytes(),
                Some(Model::Lathe(l)) => l.rows.len() * std::mem::size_of::<crate::dexel::Dexel>(),
                None => 0,
            },
            notes,
        }
    }

    /// The stock's surface now, in the stock frame (for STL, pictures and the panel). `stride`
    /// > 1 samples every stride-th line for a lighter mesh.
    pub fn mesh(&self, stride: usize) -> Option<Mesh> {
        match self.model.as_ref()? {
            Model::Mill(m) => Some(Mesh::from_grid(&m.grid.coarse(stride))),
            Model::Lathe(l) => Some(l.mesh((256 / stride.max(1)).max(16))),
        }
    }

    /// Cuts the open chain now (a live view that shows the stock mid-move): a straight chain cut
    /// in two sweeps removes the same volume as in one, the next setpoint starts a new chain.
    pub fn cut_pending(&mut self) {
        self.flush();
    }

    /// Material removed so far by the sweeps done, mm³.
    pub fn removed_mm3(&self) -> f64 {
        self.per_tool.values().map(|t| t.volume).sum()
    }

    /// Volume of the stock as it was made, mm³ (0 before the first motion).
    pub fn initial_volume_mm3(&self) -> f64 {
        self.initial_volume
    }

    /// Stock-frame coordinates of a machine point.
    pub fn to_stock(&self, p: [f64; 3]) -> [f64; 3] {
        self.placement.to_stock(p)
    }

    /// Machine coordinates of a stock-frame point.
    pub fn to_machine(&self, q: [f64; 3]) -> [f64; 3] {
        self.placement.to_machine(q)
    }
}
