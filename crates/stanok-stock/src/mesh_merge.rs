//! Flat faces of a surface-net mesh merged into big polygons, keeping the mesh closed.
//!
//! A machined part is mostly planes (tops, floors, walls): surface nets give them two triangles
//! per lattice cell, 1.6 M for a 100 × 80 mm top at 0.1 mm. Here the quads of one lattice plane
//! (same crossing axis, same plane index, same orientation) whose four vertices are *flat* — each
//! used by exactly four quads, all of that plane, and lying in it — are grown greedily into
//! rectangles (along u, then whole rows along w). A rectangle becomes a fan around its centre
//! through **every** vertex of its boundary, so the neighbours' edges still meet vertex to vertex:
//! no T-junctions, the mesh stays closed and its volume is unchanged. The fan is wound like the
//! quads it replaces.

use std::collections::HashMap;

/// One quad of surface nets: its four cells (lattice coordinates, winding order of the quad)
/// and its vertex indices in the emitted order (outward winding).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Quad {
    pub cells: [[i64; 3]; 4],
    pub v: [u32; 4],
}

impl Quad {
    /// The crossing axis (0 X, 1 Y, 2 Z): the cell coordinate all four share.
    fn axis(&self) -> usize {
        (0..3)
            .rev()
            .find(|&a| self.cells.iter().all(|c| c[a] == self.cells[0][a]))
            .unwrap_or(2)
    }
}

/// (u, w): the two in-plane coordinate indices for a crossing axis.
fn plane_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

fn normal(p: &[[f32; 3]], a: u32, b: u32, c: u32) -> [f64; 3] {
    let (a, b, c) = (p[a as usize], p[b as usize], p[c as usize]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]].map(f64::from);
    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]].map(f64::from);
    [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ]
}

/// The triangles of the quads, flat runs merged (module doc). New centre vertices are appended
/// to `vertices`; `cell_vertex` maps a lattice cell to its vertex.
pub(crate) fn triangulate(
    quads: &[Quad],
    vertices: &mut Vec<[f32; 3]>,
    cell_vertex: &dyn Fn([i64; 3]) -> Option<u32>,
) -> Vec<[u32; 3]> {
    // Each vertex: how many quads use it, and whether all are of one plane (axis, index, sign).
    #[derive(Clone, Copy, PartialEq)]
    enum Use {
        None,
        Plane(usize, i64, bool, u32),
        Mixed,
    }
    let sign = |q: &Quad| {
        let n = normal(vertices, q.v[0], q.v[1], q.v[2]);
        n[q.axis()] > 0.0
    };
    let mut uses = vec![Use::None; vertices.len()];
    for q in quads {
        let a = q.axis();
        let key = (a, q.cells[0][a], sign(q));
        for &v in &q.v {
            uses[v as usize] = match uses[v as usize] {
                Use::None => Use::Plane(key.0, key.1, key.2, 1),
                Use::Plane(x, y, z, n) if (x, y, z) == key => Use::Plane(x, y, z, n + 1),
                _ => Use::Mixed,
            };
        }
    }
    let flat = |q: &Quad| {
        let a = q.axis();
        let key = (a, q.cells[0][a], sign(q));
        let level = vertices[q.v[0] as usize][a];
        q.v.iter().all(|&v| {
            uses[v as usize] == Use::Plane(key.0, key.1, key.2, 4)
                && vertices[v as usize][a] == level
        })
    };
    // Mergeable quads by plane, then by their (u, w) corner cell.
    // (axis, level, facing) → (u, w) corner cell → quad.
    type Plane = HashMap<(i64, i64), usize>;
    let mut planes: HashMap<(usize, i64, bool), Plane> = HashMap::new();
    let mut triangles = Vec::with_capacity(quads.len());
    for (n, q) in quads.iter().enumerate() {
        if flat(q) {
            let a = q.axis();
            let (u, w) = plane_axes(a);
            planes
                .entry((a, q.cells[0][a], sign(q)))
                .or_default()
                .insert((q.cells[2][u], q.cells[2][w]), n);
        } else {
            triangles.push([q.v[0], q.v[1], q.v[2]]);
            triangles.push([q.v[0], q.v[2], q.v[3]]);
        }
    }
    let mut planes: Vec<_> = planes.into_iter().collect();
    planes.sort_by_key(|(k, _)| *k);
    for ((axis, index, _), grid) in planes {
        let (ua, wa) = plane_axes(axis);
        let mut keys: Vec<(i64, i64)> = grid.keys().copied().collect();
        keys.sort_by_key(|&(u, w)| (w, u));
        let mut done: HashMap<(i64, i64), bool> = HashMap::new();
        for &(u0, w0) in &keys {
            if done.contains_key(&(u0, w0)) {
                continue;
            }
            let free = |u: i64, w: i64, done: &HashMap<(i64, i64), bool>| {
                grid.contains_key(&(u, w)) && !done.contains_key(&(u, w))
            };
            let mut u1 = u0;
            while free(u1 + 1, w0, &done) {
                u1 += 1;
            }
            let mut w1 = w0;
            while (u0..=u1).all(|u| free(u, w1 + 1, &done)) {
                w1 += 1;
            }
            for w in w0..=w1 {
                for u in u0..=u1 {
                    done.insert((u, w), true);
                }
            }
            let first = quads[grid[&(u0, w0)]];
            if u1 == u0 && w1 == w0 {
                triangles.push([first.v[0], first.v[1], first.v[2]]);
                triangles.push([first.v[0], first.v[2], first.v[3]]);
                continue;
            }
            // The boundary loop of cells, (u, w) counter-clockwise.
            let cell = |cu: i64, cw: i64| {
                let mut c = [0i64; 3];
                c[axis] = index;
                c[ua] = cu;
                c[wa] = cw;
                c
            };
            let mut ring: Vec<[i64; 3]> = Vec::new();
            for cu in u0 - 1..=u1 {
                ring.push(cell(cu, w0 - 1));
            }
            for cw in w0..=w1 {
                ring.push(cell(u1, cw));
            }
            for cu in (u0 - 1..u1).rev() {
                ring.push(cell(cu, w1));
            }
            for cw in (w0..w1).rev() {
                ring.push(cell(u0 - 1, cw));
            }
            let Some(mut loop_v) = ring
                .iter()
                .map(|&c| cell_vertex(c))
                .collect::<Option<Vec<u32>>>()
            else {
                // Cannot happen for a closed net; keep the quads as they are.
                for w in w0..=w1 {
                    for u in u0..=u1 {
                        let q = quads[grid[&(u, w)]];
                        triangles.push([q.v[0], q.v[1], q.v[2]]);
                        triangles.push([q.v[0], q.v[2], q.v[3]]);
                    }
                }
                continue;
            };
            let corners = [
                loop_v[0],
                loop_v[(u1 - u0 + 1) as usize],
                loop_v[(u1 - u0 + 1 + w1 - w0 + 1) as usize],
                loop_v[(2 * (u1 - u0 + 1) + w1 - w0 + 1) as usize],
            ];
            let mut centre = [0.0f32; 3];
            for c in corners {
                for k in 0..3 {
                    centre[k] += vertices[c as usize][k] / 4.0;
                }
            }
            let want = normal(vertices, first.v[0], first.v[1], first.v[2]);
            let have = normal(vertices, corners[0], corners[1], corners[2]);
            if want.iter().zip(&have).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
                loop_v.reverse();
            }
            let c = vertices.len() as u32;
            vertices.push(centre);
            for k in 0..loop_v.len() {
                triangles.push([c, loop_v[k], loop_v[(k + 1) % loop_v.len()]]);
            }
        }
    }
    triangles
}
