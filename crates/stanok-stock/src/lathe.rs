//! The turning model: the stock as a revolved profile, one dexel along the radius per Z row.
//!
//! The workpiece turns about a Z-parallel axis through `axis` (stock frame), so material is a
//! region of the (z, ρ) half plane: row k at `z0 + (k + ½)·dz` holds the radii of material as
//! intervals. The insert lies in the plane of the axis and the tool's X: a point of it at
//! `(z, x)` meets every material point at radius `|x − axis_x|` as the part turns. So one sweep is
//! 2-D: the insert's core triangle at both ends of the motion, their convex hull `H`, grown by the
//! nose radius (`H ⊕ disk(r)`, the exact swept insert), cut by each row's line into an x interval
//! (the union of the chords of `r`-capsules around H's edges), folded to radii. Volume is exact
//! in ρ: `Σ π·(ρ₂² − ρ₁²)·dz`.

use crate::dexel::{Dexel, DexelGrid, Span};
use crate::tool::Insert;

/// The stock of a lathe (module doc).
#[derive(Debug, Clone)]
pub struct LatheModel {
    /// X, Y of the spindle axis, stock frame, mm.
    pub axis: [f64; 2],
    /// Z of the lower edge of row 0, mm.
    pub z0: f64,
    /// Row height, mm.
    pub dz: f64,
    /// Radii of material per row.
    pub rows: Vec<Dexel>,
    /// Outer radius at the start, mm.
    pub initial_radius: f64,
}

/// What one sweep of an insert did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TurnHits {
    /// Volume removed, mm³.
    pub removed: f64,
    /// Longest radial length removed on one row, mm.
    pub depth: f64,
    /// Lowest z of the swept insert, mm.
    pub z_min: f64,
}

/// 2-D points as (z, x).
type P2 = [f64; 2];

fn cross(o: P2, a: P2, b: P2) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, of a few points.
fn hull(mut pts: Vec<P2>) -> Vec<P2> {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut h: Vec<P2> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &P2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// The x interval of the line z = `zr` within `r` of the segment a–b (points as (z, x)).
pub(crate) fn capsule_chord(a: P2, b: P2, r: f64, zr: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for c in [a, b] {
        let dz = zr - c[0];
        if dz.abs() <= r {
            let w = (r * r - dz * dz).sqrt();
            lo = lo.min(c[1] - w);
            hi = hi.max(c[1] + w);
        }
    }
    // The band: 0 ≤ λ ≤ 1 and |v × (q − a)| ≤ r·|v|, both affine in x.
    let v = [b[0] - a[0], b[1] - a[1]];
    let vv = v[0] * v[0] + v[1] * v[1];
    if vv > 1e-24 {
        let (mut xa, mut xb) = (f64::NEG_INFINITY, f64::INFINITY);
        let mut clip = |k: f64, c: f64, lo_v: f64, hi_v: f64| -> bool {
            // lo_v ≤ k·x + c ≤ hi_v
            if k.abs() < 1e-15 {
                return c >= lo_v && c <= hi_v;
            }
            let (p, q) = ((lo_v - c) / k, (hi_v - c) / k);
            xa = xa.max(p.min(q));
            xb = xb.min(p.max(q));
            true
        };
        let dzr = zr - a[0];
        // λ·vv = v_z·(zr − a_z) + v_x·(x − a_x)
        let ok1 = clip(v[1], v[0] * dzr - v[1] * a[1], 0.0, vv);
        // v × (q − a) = v_z·(x − a_x) − v_x·(zr − a_z)
        let rv = r * vv.sqrt();
        let ok2 = clip(v[0], -v[0] * a[1] - v[1] * dzr, -rv, rv);
        if ok1 && ok2 && xa <= xb {
            lo = lo.min(xa);
            hi = hi.max(xb);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

impl LatheModel {
    /// A cylinder about the axis through `axis` from `z[0]` to `z[1]`, with an optional bore.
    pub fn new_cylinder(
        axis: [f64; 2],
        z: [f64; 2],
        diameter: f64,
        bore: f64,
        resolution: f64,
    ) -> LatheModel {
        let n = (((z[1] - z[0]) / resolution).ceil() as usize).max(1);
        let span = Span {
            lo: (bore / 2.0) as f32,
            hi: (diameter / 2.0) as f32,
        };
        LatheModel {
            axis,
            z0: z[0],
            dz: (z[1] - z[0]) / n as f64,
            rows: vec![Dexel::One(span); n],
            initial_radius: diameter / 2.0,
        }
    }

    fn row_volume(&self, d: &Dexel) -> f64 {
        d.spans()
            .iter()
            .map(|s| std::f64::consts::PI * ((s.hi as f64).powi(2) - (s.lo as f64).powi(2)))
            .sum::<f64>()
            * self.dz
    }

    /// Material volume, mm³.
    pub fn volume(&self) -> f64 {
        self.rows.iter().map(|d| self.row_volume(d)).sum()
    }

    /// The outer radius of material in the row at `z` (None: no material or outside).
    pub fn outer_radius_at(&self, z: f64) -> Option<f64> {
        let k = ((z - self.z0) / self.dz).floor();
        if k < 0.0 || k as usize >= self.rows.len() {
            return None;
        }
        self.rows[k as usize].top().map(f64::from)
    }

    /// Sweeps `insert` with its controlled point from `p0` to `p1` ((z, x), stock frame) and
    /// removes what it passes (module doc).
    pub fn apply(&mut self, insert: &Insert, p0: P2, p1: P2) -> TurnHits {
        let core = insert.core();
        let mut pts = Vec::with_capacity(6);
        for p in [p0, p1] {
            for c in core {
                pts.push([p[0] + c[0], p[1] + c[1] - self.axis[0]]);
            }
        }
        let h = hull(pts);
        let r = insert.nose_radius;
        let z_min = h.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min) - r;
        let z_max = h.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max) + r;
        let mut hits = TurnHits {
            z_min,
            ..Default::default()
        };
        let k0 = ((z_min - self.z0) / self.dz - 0.5).ceil().max(0.0);
        let k1 = (((z_max - self.z0) / self.dz - 0.5).floor() + 1.0).min(self.rows.len() as f64);
        if !(k0.is_finite() && k1.is_finite()) || k1 <= k0 {
            return hits;
        }
        for k in k0 as usize..k1 as usize {
            if self.rows[k].top().is_none() {
                continue;
            }
            let zr = self.z0 + (k as f64 + 0.5) * self.dz;
            let mut range: Option<(f64, f64)> = None;
            let n = h.len();
            for e in 0..n.max(1) {
                let (a, b) = (h[e % n], h[(e + 1) % n]);
                if let Some((x0, x1)) = capsule_chord(a, b, r, zr) {
                    range = Some(range.map_or((x0, x1), |(p, q)| (p.min(x0), q.max(x1))));
                }
            }
            let Some((xa, xb)) = range else { continue };
            let (ra, rb) = if xa >= 0.0 {
                (xa, xb)
            } else if xb <= 0.0 {
                (-xb, -xa)
            } else {
                (0.0, xb.max(-xa))
            };
            let before = self.row_volume(&self.rows[k]);
            let (len, _) = self.rows[k].cut(ra, rb);
            if len > 0.0 {
                hits.removed += before - self.row_volume(&self.rows[k]);
                hits.depth = hits.depth.max(len);
            }
        }
        hits
    }

    /// The part's surface, revolved: `segments` facets around. Runs of equal rows are one band;
    /// each band's radii become cylinders (outer faces out, bores in) and the changes between
    /// bands annular faces, all on the same `segments` angles, so the mesh is closed without
    /// T-junctions. Radii are exact; Z steps at the row height.
    pub fn mesh(&self, segments: usize) -> crate::mesh::Mesh {
        let n = segments.max(8);
        let mut mesh = crate::mesh::Mesh::default();
        // Bands: (z0, z1, intervals).
        type Band = (f64, f64, Vec<(f64, f64)>);
        let mut bands: Vec<Band> = Vec::new();
        for (k, row) in self.rows.iter().enumerate() {
            let iv: Vec<(f64, f64)> = row
                .spans()
                .iter()
                .map(|s| (s.lo as f64, s.hi as f64))
                .collect();
            let z0 = self.z0 + k as f64 * self.dz;
            let z1 = z0 + self.dz;
            match bands.last_mut() {
                Some(b) if b.2 == iv => b.1 = z1,
                _ => bands.push((z0, z1, iv)),
            }
        }
        let angle = |i: usize| std::f64::consts::TAU * (i % n) as f64 / n as f64;
        let mut ring = |mesh: &mut crate::mesh::Mesh, r: f64, z: f64| -> u32 {
            let first = mesh.vertices.len() as u32;
            for i in 0..n {
                let a = angle(i);
                mesh.vertices.push([
                    (self.axis[0] + r * a.cos()) as f32,
                    (self.axis[1] + r * a.sin()) as f32,
                    z as f32,
                ]);
            }
            first
        };
        // A band between two rings: outward when `out` (counter-clockwise seen from outside).
        let quad_strip = |mesh: &mut crate::mesh::Mesh, a: u32, b: u32, out: bool| {
            for i in 0..n as u32 {
                let j = (i + 1) % n as u32;
                let (p, q, r, s) = (a + i, a + j, b + j, b + i);
                if out {
                    mesh.triangles.push([p, q, r]);
                    mesh.triangles.push([p, r, s]);
                } else {
                    mesh.triangles.push([p, r, q]);
                    mesh.triangles.push([p, s, r]);
                }
            }
        };
        // Annulus at height z between radii r0 < r1 facing up (true) or down; a disc if r0 = 0.
        let annulus = |mesh: &mut crate::mesh::Mesh,
                       ring: &mut dyn FnMut(&mut crate::mesh::Mesh, f64, f64) -> u32,
                       r0: f64,
                       r1: f64,
                       z: f64,
                       up: bool| {
            let outer = ring(mesh, r1, z);
            if r0 <= 1e-9 {
                let c = mesh.vertices.len() as u32;
                mesh.vertices
                    .push([self.axis[0] as f32, self.axis[1] as f32, z as f32]);
                for i in 0..n as u32 {
                    let j = (i + 1) % n as u32;
                    if up {
                        mesh.triangles.push([c, outer + i, outer + j]);
                    } else {
                        mesh.triangles.push([c, outer + j, outer + i]);
                    }
                }
            } else {
                let inner = ring(mesh, r0, z);
                // Seen from +z the outer ring runs counter-clockwise.
                quad_strip(mesh, inner, outer, !up);
            }
        };
        let set_minus = |a: &[(f64, f64)], b: &[(f64, f64)]| -> Vec<(f64, f64)> {
            let mut out = Vec::new();
            for &(lo, hi) in a {
                let mut pieces = vec![(lo, hi)];
                for &(blo, bhi) in b {
                    pieces = pieces
                        .into_iter()
                        .flat_map(|(p, q)| {
                            let mut v = Vec::new();
                            if blo > p {
                                v.push((p, blo.min(q)));
                            }
                            if bhi < q {
                                v.push((bhi.max(p), q));
                            }
                            v.into_iter().filter(|(x, y)| y - x > 1e-6)
                        })
                        .collect();
                }
                out.extend(pieces);
            }
            out
        };
        for (k, (z0, z1, iv)) in bands.iter().enumerate() {
            for &(lo, hi) in iv {
                let (a, b) = (ring(&mut mesh, hi, *z0), ring(&mut mesh, hi, *z1));
                quad_strip(&mut mesh, a, b, true);
                if lo > 1e-9 {
                    let (a, b) = (ring(&mut mesh, lo, *z0), ring(&mut mesh, lo, *z1));
                    quad_strip(&mut mesh, a, b, false);
                }
            }
            let below: &[(f64, f64)] = if k == 0 { &[] } else { &bands[k - 1].2 };
            let above: &[(f64, f64)] = bands.get(k + 1).map_or(&[], |b| &b.2);
            for (lo, hi) in set_minus(iv, below) {
                annulus(&mut mesh, &mut ring, lo, hi, *z0, false);
            }
            for (lo, hi) in set_minus(iv, above) {
                annulus(&mut mesh, &mut ring, lo, hi, *z1, true);
            }
        }
        mesh
    }

    /// The part as vertical dexels (for meshing and pictures): each line at radius ρ from the
    /// axis holds the rows whose material contains ρ.
    pub fn to_grid(&self, resolution: f64) -> DexelGrid {
        let r = self.initial_radius;
        let mut grid = DexelGrid::new(
            [self.axis[0] - r, self.axis[1] - r],
            [self.axis[0] + r, self.axis[1] + r],
            resolution,
        );
        for j in 0..grid.n[1] {
            for i in 0..grid.n[0] {
                let c = grid.centre(i, j);
                let rho = ((c[0] - self.axis[0]).powi(2) + (c[1] - self.axis[1]).powi(2)).sqrt();
                if rho > r {
                    continue;
                }
                let mut spans: Vec<Span> = Vec::new();
                for (k, row) in self.rows.iter().enumerate() {
                    if row
                        .spans()
                        .iter()
                        .any(|s| (s.lo as f64) <= rho && rho <= s.hi as f64)
                    {
                        let lo = (self.z0 + k as f64 * self.dz) as f32;
                        let hi = (self.z0 + (k + 1) as f64 * self.dz) as f32;
                        match spans.last_mut() {
                            Some(last) if last.hi >= lo => last.hi = hi,
                            _ => spans.push(Span { lo, hi }),
                        }
                    }
                }
                grid.lines[j * grid.n[0] + i] = Dexel::union_of(spans);
            }
        }
        grid
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tool::{resolve, ToolShape};
    use stanok_canon::setup::ToolTable;

    fn insert() -> Insert {
        match resolve(1, &ToolTable::default(), true, 0.01).0 {
            ToolShape::Insert(i) => i,
            ToolShape::Mill(_) => unreachable!(),
        }
    }

    #[test]
    fn capsule_chords() {
        // Segment from (0, 0) to (0, 10) (along x), r = 1: the line z = 0.5 meets it from
        // x = −√0.75 to 10 + √0.75.
        let (a, b) = capsule_chord([0.0, 0.0], [0.0, 10.0], 1.0, 0.5).unwrap();
        assert!((a + 0.75f64.sqrt()).abs() < 1e-12 && (b - 10.0 - 0.75f64.sqrt()).abs() < 1e-12);
        // Along z: the band is |x| ≤ 1.
        assert_eq!(
            capsule_chord([0.0, 0.0], [10.0, 0.0], 1.0, 5.0),
            Some((-1.0, 1.0))
        );
        assert_eq!(capsule_chord([0.0, 0.0], [10.0, 0.0], 1.0, 11.5), None);
    }

    #[test]
    fn a_turned_step_removes_its_annulus() {
        // Ø50 bar, z −80…0; turn Ø40 from z 2 to z −30 (controlled point on the diameter).
        // A square insert (edges along +Z and +X), nose 0.4: the shoulder is a plane at z −30 with
        // a fillet of the nose radius in the corner.
        let mut m = LatheModel::new_cylinder([0.0, 0.0], [-80.0, 0.0], 50.0, 0.0, 0.1);
        let v0 = m.volume();
        let square = Insert {
            edges: [0.0, std::f64::consts::FRAC_PI_2],
            ..insert()
        };
        let hits = m.apply(&square, [2.0, 20.0], [-30.0, 20.0]);
        let pi = std::f64::consts::PI;
        let annulus = pi * (625.0 - 400.0) * 30.0;
        // The fillet's cross-section r²·(1 − π/4) revolved at its centroid, r ≈ 20 + 0.22·0.4.
        let want = annulus - 2.0 * pi * 20.09 * 0.16 * (1.0 - pi / 4.0);
        assert!(
            (hits.removed - annulus).abs() / annulus < 0.005,
            "{} vs {annulus}",
            hits.removed
        );
        assert!(
            (hits.removed - want).abs() / want < 0.001,
            "{} vs {want}",
            hits.removed
        );
        assert!((v0 - m.volume() - hits.removed).abs() < 1e-6 * v0);
        assert!((m.outer_radius_at(-15.0).unwrap() - 20.0).abs() < 1e-4);
        assert!((m.outer_radius_at(-40.0).unwrap() - 25.0).abs() < 1e-4);
        assert!((hits.depth - 5.0).abs() < 1e-4);
        // Its revolved mesh: closed, the model's volume within the 256-gon's deficit.
        let mesh = m.mesh(256);
        let ngon = 256.0 / 2.0 * (std::f64::consts::TAU / 256.0).sin() / pi;
        assert!(
            (mesh.volume() - m.volume() * ngon).abs() / m.volume() < 1e-4,
            "{}",
            mesh.volume()
        );
        let mut edges = std::collections::HashMap::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        // Rings are duplicated per face, so closedness is by position.
        let pos = |i: u32| mesh.vertices[i as usize].map(|c| (c * 1e4).round() as i64);
        let mut by_pos = std::collections::HashMap::new();
        for (&(a, b), &n) in &edges {
            *by_pos.entry((pos(a), pos(b))).or_insert(0) += n;
        }
        for (&(a, b), &n) in &by_pos {
            assert_eq!(Some(&n), by_pos.get(&(b, a)), "open edge {a:?}–{b:?}");
        }
    }
}
