//! Tools as the simulation sees them: a cutter that removes material and the bodies above it that
//! must not touch it, resolved from the tool table's edge and body keys with the defaults below.
//!
//! ## Milling and drilling tools ([`MillTool`])
//! Heights from the tip along the axis; `D` = 2 × (edge D1 radius + radius wear).
//! * **Cutter** (removes material), up to the flute length: flat = a cylinder; ball = a sphere of
//!   radius R on a cylinder; bull nose = frustums inscribed in the corner torus (sagitta ≤ the
//!   tolerance the model asks for) on a cylinder; drill = a cone of the point angle on a cylinder.
//! * **Above the flutes** up to `reach` (tip → holder): the part within the cutter radius
//!   (`flute_ext`, "engaged deeper than the flute length"); where the shank is wider than the
//!   cutter, the shank itself (`shank`).
//! * **Holder**: its sections stacked from `reach` upwards.
//!
//! Defaults (what a LinuxCNC `.tbl` tool gets: it has only D): flute length 3·D, shank diameter D,
//! reach 4·D (at least the flute length), holder one cylinder of diameter max(3·D, 20 mm) and
//! length 40 mm, centre cutting, ramp angle 0, point angle 118°, corner radius R/4. A tool that is
//! not in the table or has no diameter is simulated as [`DEFAULT_DIAMETER`] with a note in the
//! report.
//!
//! ## Turning inserts ([`Insert`])
//! In the ZX plane: a nose circle of radius r (the edge radius; 0.4 mm if 0) whose centre S lies
//! from the controlled point P as LinuxCNC's orientation says (`P − S` = r along −X and/or ±Z,
//! Stanok's `nose_shift`: 1 = −X+Z, 2 = −X−Z, 3 = +X−Z, 4 = +X+Z, 5 = +Z, 6 = −X, 7 = −Z, 8 = +X,
//! 0/9 = the centre), and two straight cutting edges tangent to it, leaving the nose at the
//! directions `front_angle` and `back_angle` (degrees from +Z towards +X), `insert_length` long
//! (default 10 mm). Without angles the insert points away from its tip: both edges 40° either side
//! of the direction S − P (+X for 0/9), an 80° rhombic insert. An unknown tool is orientation 2.

use crate::sweep::Prim;
use stanok_canon::setup::{CutterShape, ToolKind, ToolTable};

/// Diameter of the tool simulated when the table has none, mm.
pub const DEFAULT_DIAMETER: f64 = 6.0;
/// Nose radius of a turning insert without one, mm.
pub const DEFAULT_NOSE_RADIUS: f64 = 0.4;
/// Cutting-edge length of an insert without one, mm.
pub const DEFAULT_INSERT_LENGTH: f64 = 10.0;

/// A milling or drilling tool (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct MillTool {
    /// T number.
    pub number: u32,
    /// Cutter radius, mm.
    pub radius: f64,
    /// The cutting part, from the tip.
    pub cutter: Vec<Prim>,
    /// Cutting length from the tip, mm.
    pub flute_length: f64,
    /// Tip → holder, mm.
    pub reach: f64,
    /// Above the flutes within the cutter radius (flute-length check).
    pub flute_ext: Option<Prim>,
    /// The shank where it is wider than the cutter.
    pub shank: Option<Prim>,
    /// Holder sections.
    pub holder: Vec<Prim>,
    /// May plunge.
    pub centre_cutting: bool,
    /// Steepest descent towards the tip a non-centre-cutting tool may take in material, rad.
    pub ramp_angle: f64,
    /// Highest point of the whole tool above the tip, mm.
    pub top: f64,
    /// Widest radius of any of its parts, mm.
    pub widest: f64,
}

/// A turning insert (module doc); lengths mm, angles radians.
#[derive(Debug, Clone, PartialEq)]
pub struct Insert {
    /// T number.
    pub number: u32,
    /// Nose radius, mm.
    pub nose_radius: f64,
    /// Nose centre − controlled point, (z, x), mm.
    pub centre_offset: [f64; 2],
    /// Directions of the two edges from the nose, radians from +Z towards +X.
    pub edges: [f64; 2],
    /// Edge length, mm.
    pub length: f64,
}

impl Insert {
    /// The insert's outline less the nose radius (the triangle whose Minkowski sum with the nose
    /// circle is the insert), relative to the controlled point, (z, x).
    pub fn core(&self) -> [[f64; 2]; 3] {
        let s = self.centre_offset;
        let l = (self.length - self.nose_radius).max(0.0);
        let at = |a: f64| [s[0] + l * a.cos(), s[1] + l * a.sin()];
        [s, at(self.edges[0]), at(self.edges[1])]
    }
}

/// A tool of either kind.
#[derive(Debug, Clone, PartialEq)]
pub enum ToolShape {
    /// Milling, drilling (the mill model).
    Mill(MillTool),
    /// Turning (the revolved model).
    Insert(Insert),
}

/// LinuxCNC's lathe tool origin (the interpreter's `nose_shift`): controlled point − nose
/// centre in (z, x) for an orientation, as a unit pattern.
fn tip_direction(orientation: u8) -> [f64; 2] {
    let dx = match orientation {
        1 | 2 | 6 => -1.0,
        3 | 4 | 8 => 1.0,
        _ => 0.0,
    };
    let dz = match orientation {
        2 | 3 | 7 => -1.0,
        1 | 4 | 5 => 1.0,
        _ => 0.0,
    };
    [dz, dx]
}

/// The tool `number` as the simulation cuts with it, and a note when defaults stood in for a
/// missing entry. `lathe` picks inserts; `tolerance` bounds the bull-nose approximation, mm.
pub fn resolve(
    number: u32,
    table: &ToolTable,
    lathe: bool,
    tolerance: f64,
) -> (ToolShape, Option<String>) {
    let tool = table.get(number);
    let edge = tool.and_then(|t| t.edges.first());
    let radius = edge.map_or(0.0, |e| e.radius + e.radius_wear);
    let body = tool.map(|t| t.body.clone()).unwrap_or_default();
    let shape = body.cutter.unwrap_or(match tool.map(|t| t.kind) {
        Some(ToolKind::Drilling) => CutterShape::Drill,
        Some(ToolKind::Turning) => CutterShape::Insert,
        _ if lathe => CutterShape::Insert,
        _ => CutterShape::Flat,
    });
    if lathe || shape == CutterShape::Insert {
        let mut note = None;
        let nose = if radius > 0.0 {
            radius
        } else {
            note = Some(format!(
                "T{number}: no nose radius in the tool table: simulated with {DEFAULT_NOSE_RADIUS} mm"
            ));
            DEFAULT_NOSE_RADIUS
        };
        let orientation = match edge {
            Some(e) => e.orientation,
            None => 2,
        };
        let tip = tip_direction(orientation);
        let centre_offset = [-tip[0] * nose, -tip[1] * nose];
        let edges = match edge {
            Some(e) if e.front_angle != 0.0 || e.back_angle != 0.0 => {
                [e.front_angle.to_radians(), e.back_angle.to_radians()]
            }
            _ => {
                let away = if tip == [0.0, 0.0] {
                    std::f64::consts::FRAC_PI_2
                } else {
                    (-tip[1]).atan2(-tip[0])
                };
                let half = 40f64.to_radians();
                [away - half, away + half]
            }
        };
        return (
            ToolShape::Insert(Insert {
                number,
                nose_radius: nose,
                centre_offset,
                edges,
                length: body.insert_length.unwrap_or(DEFAULT_INSERT_LENGTH),
            }),
            note,
        );
    }
    let mut note = None;
    let r = if radius > 0.0 {
        radius
    } else {
        note = Some(format!(
            "T{number}: {} in the tool table: simulated as a flat end mill of {DEFAULT_DIAMETER} mm",
            if tool.is_some() { "no diameter" } else { "not" }
        ));
        DEFAULT_DIAMETER / 2.0
    };
    let d = 2.0 * r;
    let flute = body.flute_length.unwrap_or(3.0 * d);
    let reach = body.reach.unwrap_or(4.0 * d).max(flute);
    let shank_r = body.shank_diameter.map_or(r, |s| s / 2.0);
    let mut cutter = Vec::new();
    match shape {
        CutterShape::Ball => {
            let rb = r.min(flute);
            cutter.push(Prim::Sphere { hc: rb, r: rb });
            if flute > rb {
                cutter.push(Prim::cylinder(rb, flute, r));
            }
        }
        CutterShape::Bull => {
            let rc = body
                .corner_radius
                .unwrap_or(r / 4.0)
                .clamp(0.0, r)
                .min(flute);
            let tol = tolerance.max(1e-4);
            let n = if rc > tol {
                let step = 2.0 * (1.0 - tol / rc).clamp(-1.0, 1.0).acos();
                ((std::f64::consts::FRAC_PI_2 / step).ceil() as usize).clamp(2, 64)
            } else {
                0
            };
            let at = |k: usize| {
                let phi = std::f64::consts::FRAC_PI_2 * k as f64 / n.max(1) as f64;
                (rc - rc * phi.cos(), r - rc + rc * phi.sin())
            };
            for k in 0..n {
                let ((h0, r0), (h1, r1)) = (at(k), at(k + 1));
                cutter.push(Prim::Frustum { h0, h1, r0, r1 });
            }
            if flute > rc {
                cutter.push(Prim::cylinder(rc, flute, r));
            }
        }
        CutterShape::Drill => {
            let angle = body.point_angle.unwrap_or(118.0).to_radians();
            let hp = (r / (angle / 2.0).tan()).min(flute);
            cutter.push(Prim::Frustum {
                h0: 0.0,
                h1: hp,
                r0: 0.0,
                r1: r * hp / (r / (angle / 2.0).tan()),
            });
            if flute > hp {
                cutter.push(Prim::cylinder(hp, flute, r));
            }
        }
        CutterShape::Flat | CutterShape::Insert => cutter.push(Prim::cylinder(0.0, flute, r)),
    }
    let flute_ext = (reach > flute).then(|| Prim::cylinder(flute, reach, r.min(shank_r)));
    let shank = (reach > flute && shank_r > r).then(|| Prim::cylinder(flute, reach, shank_r));
    let mut holder = Vec::new();
    let mut h = reach;
    if body.holder.is_empty() {
        holder.push(Prim::cylinder(h, h + 40.0, (1.5 * d).max(10.0)));
        h += 40.0;
    } else {
        for s in &body.holder {
            holder.push(Prim::Frustum {
                h0: h,
                h1: h + s.length,
                r0: s.bottom_diameter / 2.0,
                r1: s.top_diameter / 2.0,
            });
            h += s.length;
        }
    }
    let widest = cutter
        .iter()
        .chain(&holder)
        .chain(shank.iter())
        .map(Prim::max_radius)
        .fold(0.0, f64::max);
    (
        ToolShape::Mill(MillTool {
            number,
            radius: r,
            cutter,
            flute_length: flute,
            reach,
            flute_ext,
            shank,
            holder,
            centre_cutting: body.centre_cutting.unwrap_or(true),
            ramp_angle: body.ramp_angle.unwrap_or(0.0).to_radians(),
            top: h,
            widest,
        }),
        note,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::setup::{Tool, ToolBody, ToolEdge};

    fn table(body: ToolBody, radius: f64, kind: ToolKind) -> ToolTable {
        let mut t = ToolTable::default();
        t.tools.insert(
            1,
            Tool {
                number: 1,
                kind,
                edges: vec![ToolEdge {
                    radius,
                    ..Default::default()
                }],
                body,
                ..Default::default()
            },
        );
        t
    }

    #[test]
    fn a_tbl_tool_gets_its_defaults_from_the_diameter() {
        let (shape, note) = resolve(
            1,
            &table(ToolBody::default(), 5.0, ToolKind::Milling),
            false,
            0.01,
        );
        assert!(note.is_none());
        let ToolShape::Mill(m) = shape else { panic!() };
        assert_eq!(m.cutter, vec![Prim::cylinder(0.0, 30.0, 5.0)]);
        assert_eq!((m.flute_length, m.reach), (30.0, 40.0));
        assert_eq!(m.flute_ext, Some(Prim::cylinder(30.0, 40.0, 5.0)));
        assert_eq!(m.shank, None);
        assert_eq!(m.holder, vec![Prim::cylinder(40.0, 80.0, 15.0)]);
        assert!(m.centre_cutting);
    }

    #[test]
    fn a_missing_tool_is_the_default_with_a_note() {
        let (shape, note) = resolve(7, &ToolTable::default(), false, 0.01);
        assert!(note.unwrap().contains("T7: not in the tool table"));
        let ToolShape::Mill(m) = shape else { panic!() };
        assert_eq!(m.radius, 3.0);
    }

    #[test]
    fn a_bull_nose_is_inscribed_within_the_tolerance() {
        let body = ToolBody {
            cutter: Some(CutterShape::Bull),
            corner_radius: Some(2.0),
            ..Default::default()
        };
        let (shape, _) = resolve(1, &table(body, 5.0, ToolKind::Milling), false, 0.01);
        let ToolShape::Mill(m) = shape else { panic!() };
        // Every frustum's mid-point lies within 0.01 of the torus (r − 3)² + (h − 2)² = 4.
        for p in &m.cutter[..m.cutter.len() - 1] {
            let Prim::Frustum { h0, h1, r0, r1 } = *p else {
                panic!()
            };
            let (h, r) = ((h0 + h1) / 2.0, (r0 + r1) / 2.0);
            let gap = 2.0 - ((r - 3.0).powi(2) + (h - 2.0).powi(2)).sqrt();
            assert!((0.0..=0.0100001).contains(&gap), "{gap}");
        }
        assert_eq!(*m.cutter.last().unwrap(), Prim::cylinder(2.0, 30.0, 5.0));
    }

    #[test]
    fn an_unknown_lathe_tool_is_an_orientation_2_insert() {
        let (shape, note) = resolve(3, &ToolTable::default(), true, 0.01);
        assert!(note.is_some());
        let ToolShape::Insert(i) = shape else {
            panic!()
        };
        assert_eq!(i.centre_offset, [0.4, 0.4]);
        assert!((i.edges[0].to_degrees() - 5.0).abs() < 1e-9);
        assert!((i.edges[1].to_degrees() - 85.0).abs() < 1e-9);
    }
}
