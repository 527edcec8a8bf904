//! The stock in the panel: the stock-removal simulation beside a program run, and its live view.
//!
//! * **Which stock.** The load request's `stock` (the `--stock` syntax of `stanok run`), else the
//!   machine data's `[stock]` shape; neither: no simulation. It is parsed at load, so a bad one
//!   is refused there (400) and never reaches the machine.
//! * **Where it runs.** On the machine thread, inside the simulated machine
//!   (`SimMachine::set_stock`): it sees every accepted command and every setpoint, exactly as
//!   `stanok run --stock` does, so the panel cuts what the report cuts. No request thread ever
//!   does stock work; a page only receives finished messages.
//! * **Budget.** Memory: the model is bounded by the stock over the resolution, and the panel
//!   never takes a resolution that would make more than `MAX_LINES` lines (it falls back to the
//!   automatic one, which coarsens to stay within it): ≤ 64 MB. Time: one sweep per chain of
//!   setpoints, on the machine thread, paced with the run (the pacer re-bases when a sweep makes
//!   it late, `paced.rs`); a stop ends the run and the simulation with it.
//! * **The live view.** After every setpoint the observer looks at the clock; at most
//!   [`UPDATES_PER_SECOND`] times a second it cuts the open chain (a long straight move is one
//!   sweep, made at its end; cut in two it removes the same volume) and samples the model into a
//!   `StockField` of at most
//!   [`FIELD_SIDE`]² cells (`stanok_stock::field`) and serialises one message into the shared
//!   [`StockSlot`]: `{"stock": {…field, "heights": base64 of u16 LE, "collisions": […], "done"}}`.
//!   Each page's WebSocket sends the latest message when its number changed, one frame in flight
//!   (a slow client skips messages, it never queues them). So a client gets at most
//!   `UPDATES_PER_SECOND × (FIELD_SIDE² × 2 × 4/3 + MAX_MARKS × ~120)` bytes a second
//!   (≈ 270 KB/s), whatever the stock, the program or the number of clients.
//! * **Collisions.** The stock sees the panel's commands with their tags in place of their lines
//!   (`executing.rs`), so a collision's line is looked up in the snapshot ring (which keeps the
//!   line changes of the last 2¹⁸ commands, executed or not). The records go with each message (the first [`MAX_MARKS`]:
//!   kind, line, position) for the view to mark in red, and into the alarm list as warnings
//!   `stock::<kind>` at their lines (the first [`MAX_ALARMS`]); the run goes on, as `stanok run`
//!   reports them without stopping.

use crate::executing::SnapshotRing;
use crate::machine::{Alarm, Shared};
use base64::Engine as _;
use serde_json::json;
use stanok_canon::setup::ToolTable;
use stanok_machine::{MachineData, StockObserver};
use stanok_stock::sim::{StockConfig, StockSim, MAX_LINES};
use stanok_stock::spec::{StockFrame, StockShape};
use std::cell::RefCell;
use std::rc::Rc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Live messages per second at most (module doc).
pub const UPDATES_PER_SECOND: u32 = 4;
/// Cells a side of the height field sent.
pub const FIELD_SIDE: usize = 128;
/// Collisions sent with a message, at most.
pub const MAX_MARKS: usize = 200;
/// Collisions put into the alarm list, at most.
pub const MAX_ALARMS: usize = 50;

/// The latest stock message and its number (module doc).
#[derive(Debug, Default)]
pub struct StockSlot {
    inner: Mutex<(u64, Option<Arc<str>>)>,
}

impl StockSlot {
    /// The latest message and its number (0: none yet).
    pub fn latest(&self) -> (u64, Option<Arc<str>>) {
        self.inner.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    pub(crate) fn put(&self, text: String) {
        let mut g = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        g.0 += 1;
        g.1 = Some(text.into());
    }

    /// No stock to show (a new program is loaded or starts without one).
    pub fn clear(&self) {
        self.put(json!({ "stock": null }).to_string());
    }
}

/// The stock a load asks for: the request's, else the machine data's (module doc).
pub(crate) fn resolve(
    machine: &MachineData,
    request: Option<&str>,
) -> Result<Option<StockShape>, String> {
    match request.map(str::trim).filter(|s| !s.is_empty()) {
        Some(text) => StockShape::parse(text)
            .map(Some)
            .map_err(|e| format!("stock: {e}")),
        None => Ok(machine.stock.as_ref().and_then(|s| s.shape.clone())),
    }
}

/// The simulation of `shape` on this machine with the panel's tool table (module doc).
pub(crate) fn build(
    machine: &MachineData,
    shape: StockShape,
    lathe: bool,
    tools: &ToolTable,
) -> Result<StockSim, String> {
    let section = machine.stock.as_ref();
    // A resolution that would make more lines than the automatic one allows is not taken.
    let resolution = section.and_then(|s| s.resolution).filter(|r| {
        let area = match &shape {
            StockShape::Box { min, max } => (max[0] - min[0]) * (max[1] - min[1]),
            StockShape::Cylinder { diameter, .. } => diameter * diameter,
            StockShape::Mesh { .. } => 0.0,
        };
        area / (r * r) <= MAX_LINES
    });
    StockSim::new(StockConfig {
        shape,
        frame: section.map_or(StockFrame::Work, |s| s.frame),
        resolution,
        tools: tools.clone(),
        kinematics: machine.five_axis(),
        lathe,
        fixture_z: section.and_then(|s| s.fixture_z),
    })
}

/// The source line of a command's tag (the panel's commands carry tags through the machine,
/// `executing.rs`); 0 when it is no longer known.
fn line_of(ring: &RefCell<SnapshotRing>, tag: u32) -> u32 {
    ring.borrow().line_of(tag).unwrap_or(0)
}

/// The message of the stock now (module doc); None before the first motion.
pub(crate) fn message(sim: &StockSim, done: bool, ring: &RefCell<SnapshotRing>) -> Option<String> {
    let f = sim.field(FIELD_SIDE)?;
    let mut bytes = Vec::with_capacity(f.heights.len() * 2);
    for h in &f.heights {
        bytes.extend_from_slice(&h.to_le_bytes());
    }
    let collisions: Vec<_> = sim
        .collisions()
        .iter()
        .take(MAX_MARKS)
        .map(|c| {
            json!({
                "kind": c.kind.name(),
                "line": line_of(ring, c.line),
                "position": c.position,
                "depth_mm": c.depth_mm,
            })
        })
        .collect();
    let mut v = serde_json::to_value(&f).ok()?;
    v["heights"] = json!(base64::engine::general_purpose::STANDARD.encode(&bytes));
    v["collisions"] = json!(collisions);
    v["done"] = json!(done);
    Some(json!({ "stock": v }).to_string())
}

/// Puts the collisions not yet listed into the alarm list (module doc); returns how many are.
pub(crate) fn publish_alarms(
    shared: &Shared,
    sim: &StockSim,
    listed: usize,
    ring: &RefCell<SnapshotRing>,
) -> usize {
    let all = sim.collisions();
    let upto = all.len().min(MAX_ALARMS);
    if upto <= listed {
        return listed;
    }
    let new: Vec<Alarm> = all[listed..upto]
        .iter()
        .map(|c| Alarm {
            line: line_of(ring, c.line),
            column: 1,
            severity: "warning".into(),
            code: format!("stock::{}", c.kind.name()),
            message: format!(
                "{} at X{:.3} Y{:.3} Z{:.3}, {:.3} mm deep (tool {})",
                c.kind.name().replace('_', " "),
                c.position[0],
                c.position[1],
                c.position[2],
                c.depth_mm,
                c.tool
            ),
        })
        .collect();
    shared.publish(|s| s.alarms.extend(new));
    upto
}

/// The observer the simulated machine calls after every setpoint (module doc): a message and
/// the new alarms at most [`UPDATES_PER_SECOND`] times a second.
pub(crate) fn observer(shared: Arc<Shared>, ring: Rc<RefCell<SnapshotRing>>) -> StockObserver {
    let period = Duration::from_secs(1) / UPDATES_PER_SECOND;
    let mut last: Option<Instant> = None;
    let mut listed = 0usize;
    Box::new(move |sim: &mut StockSim| {
        if last.is_some_and(|t| t.elapsed() < period) {
            return;
        }
        // A long straight move is one chain, cut at its end: cut what is pending to show it.
        sim.cut_pending();
        if let Some(text) = message(sim, false, &ring) {
            last = Some(Instant::now());
            shared.stock.put(text);
            listed = publish_alarms(&shared, sim, listed, &ring);
        }
    })
}
