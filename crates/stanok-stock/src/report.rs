//! What a stock simulation reports (`run --json`'s `stock` object, the text report's section).

use serde::Serialize;

/// What went wrong, by kind (docs/stock.md defines each).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CollisionKind {
    /// A rapid (G0) removed material.
    RapidInMaterial,
    /// The tool above its flutes (within the cutter radius) touched material: engaged deeper
    /// than its flute length.
    FluteLength,
    /// The shank, where wider than the cutter, touched material.
    Shank,
    /// The holder touched material.
    Holder,
    /// A non-centre-cutting tool moved into material towards its tip, steeper than its ramp angle.
    Plunge,
    /// The tool or holder went below the fixture/table plane.
    Fixture,
    /// Material was removed while the spindle was stopped.
    SpindleStopped,
}

impl CollisionKind {
    /// The name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            CollisionKind::RapidInMaterial => "rapid_in_material",
            CollisionKind::FluteLength => "flute_length",
            CollisionKind::Shank => "shank",
            CollisionKind::Holder => "holder",
            CollisionKind::Plunge => "plunge",
            CollisionKind::Fixture => "fixture",
            CollisionKind::SpindleStopped => "spindle_stopped",
        }
    }
}

/// One collision: the first sweep of a block where it happened, and the deepest.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Collision {
    /// What.
    pub kind: CollisionKind,
    /// Source line of the block.
    pub line: u32,
    /// Machine time at its start, s.
    pub time_s: f64,
    /// Tool tip there, machine coordinates (workpiece-fixed frame), mm.
    pub position: [f64; 3],
    /// How far into the material (or below the fixture plane), mm: the longest length along a
    /// model line (radius on a lathe), over the block.
    pub depth_mm: f64,
    /// Tool number.
    pub tool: u32,
}

/// Material one tool removed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToolRemoval {
    /// Tool number (0 = none in the spindle).
    pub tool: u32,
    /// Volume removed, mm³.
    pub volume_mm3: f64,
    /// Time the tool spent removing material, s.
    pub time_in_material_s: f64,
}

/// Removed volume, total and per tool.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RemovedVolume {
    /// All tools, mm³.
    pub total: f64,
    /// Per tool, in order of number.
    pub per_tool: Vec<ToolRemoval>,
}

/// Material removal of one block (source line).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BlockRemoval {
    /// Source line.
    pub line: u32,
    /// Volume removed, mm³.
    pub removed_mm3: f64,
    /// Time in material, s.
    pub time_in_material_s: f64,
    /// Mean material removal rate while in material, mm³/min.
    pub mrr_mm3_per_min: f64,
}

/// The stock simulation's part of the run report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StockReport {
    /// `z-dexel` (mill) or `revolved` (lathe).
    pub model: &'static str,
    /// Cell size of the model, mm.
    pub resolution_mm: f64,
    /// Stock volume at the start, mm³.
    pub initial_volume_mm3: f64,
    /// Stock volume at the end, mm³.
    pub final_volume_mm3: f64,
    /// Removed volume, total and per tool.
    pub removed_volume_mm3: RemovedVolume,
    /// Collisions in time order (the first [`crate::sim::MAX_COLLISIONS`]); empty when none.
    pub collisions: Vec<Collision>,
    /// All collisions, including those beyond the list.
    pub collision_count: u64,
    /// Material removal per block that removed any, in line order.
    pub blocks: Vec<BlockRemoval>,
    /// Highest removal rate of a block, mm³/min.
    pub peak_mrr_mm3_per_min: f64,
    /// Sweeps the model applied.
    pub sweeps: u64,
    /// Memory of the model, bytes.
    pub model_bytes: usize,
    /// What the simulation assumed (tools from defaults, …).
    pub notes: Vec<String>,
}
