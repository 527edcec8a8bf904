//! The control's stored data that the interpreter reads: tool table, zero-offset tables, workpiece
//! coordinate systems, home positions.
//!
//! These types cross a boundary too, in the other direction from `Canon`: `stanok-machine` loads
//! them (machine-data TOML, LinuxCNC `.tbl` and `.var` files) and the interpreter receives them in
//! its options, so neither crate depends on the other. All lengths are mm, angles degrees, in the
//! machine's frame; none is affected by a program's G20/G70 or diameter programming.

use crate::canon::Pose;
use serde::Serialize;
use std::collections::BTreeMap;

/// Number of zero-offset systems: G54…G59 (AxiOMA and LinuxCNC) and G59.1…G59.3 (LinuxCNC).
pub const ZERO_OFFSET_SYSTEMS: usize = 9;
/// Pages per zero-offset and workpiece table (AxiOMA `P1`…`P32`; LinuxCNC uses page 1).
pub const PAGES: usize = 32;
/// Workpiece coordinate-system tables: AxiOMA G154…G159.
pub const WORKPIECE_SYSTEMS: usize = 6;
/// Home positions: AxiOMA H1…H8.
pub const HOME_POSITIONS: usize = 8;

/// AxiOMA tool groups (manual tables 9.1 and 9.2): they decide which axis each length L1…L3 acts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ToolKind {
    /// Milling cutter (table 9.1).
    #[default]
    Milling,
    /// Drill (table 9.1).
    Drilling,
    /// Special tool (table 9.1).
    Special,
    /// Turning tool (table 9.2).
    Turning,
    /// Grinding tool (table 9.2).
    Grinding,
}

/// One cutting edge (AxiOMA D1…D4; a LinuxCNC tool has exactly one).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ToolEdge {
    /// AxiOMA lengths L1, L2, L3, mm (assigned to axes by plane and tool kind).
    pub length: [f64; 3],
    /// Wear of L1…L3, mm (effective length = L + wear).
    pub length_wear: [f64; 3],
    /// Cutter radius r1, mm.
    pub radius: f64,
    /// Wear of r1, mm.
    pub radius_wear: f64,
    /// LinuxCNC per-axis tool offset X Y Z A B C U V W (mm/deg): what `G43` applies.
    pub offset: Pose,
    /// Lathe cutting-edge position code 0…9 (AxiOMA "edge position", LinuxCNC `Q`); 0 = none.
    pub orientation: u8,
    /// Front angle, degrees (LinuxCNC `I`).
    pub front_angle: f64,
    /// Back angle, degrees (LinuxCNC `J`).
    pub back_angle: f64,
}

/// One tool of the tool table.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Tool {
    /// T number.
    pub number: u32,
    /// Magazine pocket (LinuxCNC `P`).
    pub pocket: u32,
    /// AxiOMA tool group.
    pub kind: ToolKind,
    /// Edges D1…D4 (at least one).
    pub edges: Vec<ToolEdge>,
    /// Free text.
    pub comment: String,
    /// The tool's shape beyond its edges' radius: what the stock-removal simulation and its
    /// collision checks need (machine-data keys of `[[tool]]`, `machines/README.md`).
    #[serde(skip_serializing_if = "ToolBody::is_unspecified")]
    pub body: ToolBody,
}

/// The shape of a cutter's end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CutterShape {
    /// Flat end mill: a cylinder.
    Flat,
    /// Ball end mill: a hemisphere of the cutter radius on a cylinder.
    Ball,
    /// Bull-nose (torus) end mill: a corner radius (`ToolBody::corner_radius`).
    Bull,
    /// Drill: a cone of `ToolBody::point_angle` on a cylinder.
    Drill,
    /// Turning insert: a nose radius (the edge radius) and two cutting edges (the edge's
    /// orientation, front and back angles).
    Insert,
}

/// One section of a tool holder: a cylinder or a cone frustum, stacked upwards from where the tool
/// leaves the holder (`ToolBody::reach` above the tip).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HolderSection {
    /// Length along the tool axis, mm (> 0).
    pub length: f64,
    /// Diameter at the lower end (towards the tip), mm.
    pub bottom_diameter: f64,
    /// Diameter at the upper end, mm (= bottom for a cylinder).
    pub top_diameter: f64,
}

/// What a tool looks like beyond its edges' radius. Every field is optional ("as written"): what
/// is absent takes the defaults the stock simulation derives from the tool's kind and diameter
/// (`stanok-stock`, docs/stock.md). Lengths mm, angles degrees.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ToolBody {
    /// The cutter's end shape.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cutter: Option<CutterShape>,
    /// Bull-nose corner radius, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corner_radius: Option<f64>,
    /// Drill point angle (included), degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub point_angle: Option<f64>,
    /// Length of the cutting part from the tip, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flute_length: Option<f64>,
    /// Diameter of the shank (the part between the flutes and the holder), mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shank_diameter: Option<f64>,
    /// Length from the tip to the holder (the tool's stick-out), mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reach: Option<f64>,
    /// The cutter can plunge (cuts at its centre).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centre_cutting: Option<bool>,
    /// Steepest descent towards the tip a non-centre-cutting tool may take in material, degrees
    /// from the plane normal to its axis.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ramp_angle: Option<f64>,
    /// Turning insert: length of its cutting edges from the nose, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub insert_length: Option<f64>,
    /// The holder, from the tool upwards.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub holder: Vec<HolderSection>,
}

impl ToolBody {
    /// Nothing was written.
    pub fn is_unspecified(&self) -> bool {
        *self == ToolBody::default()
    }
}

/// The tool table, by T number.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ToolTable {
    /// Tools by number.
    pub tools: BTreeMap<u32, Tool>,
}

impl ToolTable {
    /// A tool by number.
    pub fn get(&self, number: u32) -> Option<&Tool> {
        self.tools.get(&number)
    }

    /// An edge: `edge` is 1-based (D1 = 1); None if the tool or edge does not exist.
    pub fn edge(&self, number: u32, edge: u32) -> Option<&ToolEdge> {
        let i = (edge as usize).checked_sub(1)?;
        self.get(number)?.edges.get(i)
    }
}

/// One zero offset: a translation, plus LinuxCNC's rotation about Z (`G10 L2 R`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ZeroOffset {
    /// X Y Z A B C U V W, mm/deg.
    pub offset: Pose,
    /// Rotation of the system about Z, degrees counter-clockwise.
    pub rotation_xy: f64,
}

/// An AxiOMA table workpiece coordinate system (G154…G159): `p_MCS = origin + R(φ,θ,ψ)·p_WCS`,
/// R = Rz(φ)·Ry(θ)·Rz(ψ) (Euler ZY'Z'', spec axioma-1 §10, A16).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct WorkpieceFrame {
    /// Origin of the system in machine coordinates, mm.
    pub origin: [f64; 3],
    /// Euler angles φ, θ, ψ (ZY'Z''), degrees.
    pub euler: [f64; 3],
}

/// All stored offsets.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OffsetTables {
    /// `zero[s][p]`: system s (0 = G54 … 5 = G59, 6…8 = G59.1…G59.3), page p (0 = P1).
    pub zero: Vec<Vec<ZeroOffset>>,
    /// `workpiece[s][p]`: G154 + s, page p + 1.
    pub workpiece: Vec<Vec<WorkpieceFrame>>,
    /// AxiOMA home positions H1…H8 in machine coordinates; None = not used (G28 to it is an error).
    pub home: Vec<Option<Pose>>,
    /// LinuxCNC G28 position (parameters 5161…5169), machine coordinates.
    pub g28: Pose,
    /// LinuxCNC G30 position (parameters 5181…5189), machine coordinates.
    pub g30: Pose,
    /// LinuxCNC G92 offset (5211…5219) and whether it is applied (5210).
    pub g92: Pose,
    /// See `g92`.
    pub g92_applied: bool,
    /// LinuxCNC active system at start (5220): 1 = G54 … 9 = G59.3.
    pub active_system: u8,
}

impl Default for OffsetTables {
    fn default() -> Self {
        OffsetTables {
            zero: vec![vec![ZeroOffset::default(); PAGES]; ZERO_OFFSET_SYSTEMS],
            workpiece: vec![vec![WorkpieceFrame::default(); PAGES]; WORKPIECE_SYSTEMS],
            home: vec![None; HOME_POSITIONS],
            g28: Pose::ZERO,
            g30: Pose::ZERO,
            g92: Pose::ZERO,
            g92_applied: false,
            active_system: 1,
        }
    }
}

impl OffsetTables {
    /// A zero offset; `system` 1 = G54 … 9 = G59.3, `page` 1…32. None outside the tables.
    pub fn zero_offset(&self, system: u8, page: u8) -> Option<&ZeroOffset> {
        let s = (system as usize).checked_sub(1)?;
        let p = (page as usize).checked_sub(1)?;
        self.zero.get(s)?.get(p)
    }

    /// A workpiece frame; `system` 1 = G154 … 6 = G159, `page` 1…32.
    pub fn workpiece_frame(&self, system: u8, page: u8) -> Option<&WorkpieceFrame> {
        let s = (system as usize).checked_sub(1)?;
        let p = (page as usize).checked_sub(1)?;
        self.workpiece.get(s)?.get(p)
    }
}

/// Everything stored in the control that a program can read.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ControlData {
    /// Tool table.
    pub tools: ToolTable,
    /// Offset tables and stored positions.
    pub offsets: OffsetTables,
    /// Other numbered parameters to preset before a program runs, by number: what a LinuxCNC `.var`
    /// file holds besides the offsets above (e.g. user parameters 31…5000 that a machine keeps).
    /// Values exactly as stored: their meaning, and so their unit, is the program's.
    pub parameters: BTreeMap<u32, f64>,
    /// The simulated probe's world: where a probe move (G38.n, G75) makes contact. Empty = the
    /// probe never makes contact (LinuxCNC's standalone interpreter behaves so).
    pub probe_surfaces: Vec<ProbeSurface>,
    /// AxiOMA permanent integer parameters `$iPerm[n]` (n = 0…999), stored with the machine
    /// data; absent = 0.
    pub perm_int: BTreeMap<u32, i64>,
    /// AxiOMA permanent floating parameters `$dPerm[n]` (n = 0…999); absent = 0.
    pub perm_double: BTreeMap<u32, f64>,
}

/// A half-space of machine coordinates in which the probe is in contact, e.g. `z <= -3.2` (the top
/// of a workpiece or a tool setter at Z −3.2 mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProbeSurface {
    /// Axis index in `Pose` order (0 = X … 8 = W).
    pub axis: usize,
    /// Contact where the coordinate is ≤ `value` (true) or ≥ `value` (false).
    pub at_or_below: bool,
    /// mm (deg for A B C), machine coordinates.
    pub value: f64,
}

impl ProbeSurface {
    /// True if the probe at `p` touches this surface.
    pub fn contact(&self, p: &Pose) -> bool {
        let v = p.to_array()[self.axis.min(8)];
        if self.at_or_below {
            v <= self.value
        } else {
            v >= self.value
        }
    }

    /// Fraction t in [0, 1] along start → end where the contact state first changes from that at
    /// `start` (None if it never does).
    pub fn crossing(&self, start: &Pose, end: &Pose) -> Option<f64> {
        let a = start.to_array()[self.axis.min(8)];
        let b = end.to_array()[self.axis.min(8)];
        let (ca, cb) = (self.contact(start), self.contact(end));
        if ca == cb || a == b {
            return None;
        }
        Some(((self.value - a) / (b - a)).clamp(0.0, 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookups_are_one_based_and_bounded() {
        let mut t = OffsetTables::default();
        t.zero[5][11].offset.x = 7.0;
        assert_eq!(t.zero_offset(6, 12).map(|z| z.offset.x), Some(7.0));
        assert!(t.zero_offset(0, 1).is_none());
        assert!(t.zero_offset(1, 33).is_none());
        assert!(t.zero_offset(10, 1).is_none());
        let mut tools = ToolTable::default();
        tools.tools.insert(
            3,
            Tool {
                number: 3,
                edges: vec![
                    ToolEdge::default(),
                    ToolEdge {
                        radius: 4.0,
                        ..Default::default()
                    },
                ],
                ..Default::default()
            },
        );
        assert_eq!(tools.edge(3, 2).map(|e| e.radius), Some(4.0));
        assert!(tools.edge(3, 0).is_none());
        assert!(tools.edge(3, 3).is_none());
        assert!(tools.edge(4, 1).is_none());
    }
}
