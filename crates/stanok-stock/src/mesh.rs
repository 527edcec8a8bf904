//! The stock's surface as triangles: surface nets over the dexel grid, STL in and out.
//!
//! ## Surface nets on dexels ([`Mesh::from_grid`])
//! Sample the solid on a lattice: X and Y at the line centres, Z every `h` (the cell size). A
//! sample is inside when its z lies in one of its line's intervals; the grid is padded with one
//! empty sample all round, so the surface is closed. Every lattice edge whose two samples differ
//! is crossed by the surface once; the four lattice cells around such an edge each get one vertex
//! (the mean of the crossing points of that cell's edges) and the edge emits the quad joining
//! them, wound so that its normal points from inside to outside. Crossings on Z edges are the
//! exact interval ends (so floors, ceilings and sloped surfaces are exact in Z); on X and Y edges
//! the midpoint of the two line centres (walls within half a cell).
//! The edges are found without visiting empty space: along Z at each interval's ends, across
//! lines where the two lines' sample runs differ (symmetric difference of runs). The result is
//! closed and consistently oriented; its volume is the dexels' within about half a cell of
//! surface area (`tests`). Flat runs of quads are merged into big polygons (`mesh_merge.rs`).
//!
//! STL: binary out ([`Mesh::write_stl`], `stl_io`); in ([`grid_from_stl`]) each vertical line is
//! cast through the mesh and the sorted crossings paired into intervals (a closed mesh; the lines
//! sit a hair off the cell centres so that no line passes exactly through an edge).

use crate::dexel::{Dexel, DexelGrid, Span};
use crate::mesh_merge::{triangulate, Quad};
use std::collections::HashMap;
use std::path::Path;

/// A triangle mesh, stock frame, mm.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertices.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// A run of inside samples `ka..=kb` of one column, with the interval ends it comes from.
#[derive(Debug, Clone, Copy)]
struct Run {
    ka: i32,
    kb: i32,
    lo: f64,
    hi: f64,
}

/// The lattice of a grid: Z of sample 0 and the step.
struct Lattice {
    z0: f64,
    h: f64,
    n: [usize; 2],
    runs: Vec<Vec<Run>>,
}

impl Lattice {
    fn new(grid: &DexelGrid) -> Lattice {
        let h = grid.cell[0].min(grid.cell[1]);
        let zmin = grid
            .lines
            .iter()
            .filter_map(|d| d.spans().first().map(|s| s.lo))
            .fold(f32::INFINITY, f32::min) as f64;
        let z0 = if zmin.is_finite() { zmin - h } else { 0.0 };
        let runs = grid
            .lines
            .iter()
            .map(|d| {
                d.spans()
                    .iter()
                    .filter_map(|s| {
                        let (lo, hi) = (s.lo as f64, s.hi as f64);
                        let ka = ((lo - z0) / h).ceil() as i32;
                        let kb = ((hi - z0) / h).floor() as i32;
                        (ka <= kb).then_some(Run { ka, kb, lo, hi })
                    })
                    .collect()
            })
            .collect();
        Lattice {
            z0,
            h,
            n: grid.n,
            runs,
        }
    }

    /// The runs of column (i, j); padding columns are empty.
    fn column(&self, i: i64, j: i64) -> &[Run] {
        if i < 0 || j < 0 || i >= self.n[0] as i64 || j >= self.n[1] as i64 {
            return &[];
        }
        &self.runs[j as usize * self.n[0] + i as usize]
    }
}

/// Calls `f(k, a_inside)` for every k where exactly one of two run lists is inside.
fn differences(a: &[Run], b: &[Run], mut f: impl FnMut(i32, bool)) {
    let mut events: Vec<(i32, u8, i8)> = Vec::with_capacity(2 * (a.len() + b.len()));
    for r in a {
        events.push((r.ka, 0, 1));
        events.push((r.kb + 1, 0, -1));
    }
    for r in b {
        events.push((r.ka, 1, 1));
        events.push((r.kb + 1, 1, -1));
    }
    events.sort_unstable();
    let mut inside = [0i32; 2];
    let mut e = 0;
    while e < events.len() {
        let k = events[e].0;
        while e < events.len() && events[e].0 == k {
            inside[events[e].1 as usize] += events[e].2 as i32;
            e += 1;
        }
        let Some(next) = events.get(e).map(|x| x.0) else {
            break;
        };
        let (ia, ib) = (inside[0] > 0, inside[1] > 0);
        if ia != ib {
            for kk in k..next {
                f(kk, ia);
            }
        }
    }
}

/// One crossed lattice edge: its four cells in winding order (for an outward normal along the
/// positive axis), the crossing point, and whether the inside is on the negative side.
type EdgeVisit<'a> = dyn FnMut([[i64; 3]; 4], [f64; 3], bool) + 'a;

fn for_each_edge(grid: &DexelGrid, lat: &Lattice, f: &mut EdgeVisit<'_>) {
    let (n0, n1) = (grid.n[0] as i64, grid.n[1] as i64);
    let x = |i: i64| grid.origin[0] + (i as f64 + 0.5) * grid.cell[0];
    let y = |j: i64| grid.origin[1] + (j as f64 + 0.5) * grid.cell[1];
    let z = |k: i32| lat.z0 + k as f64 * lat.h;
    for j in -1..=n1 {
        for i in -1..=n0 {
            let here = lat.column(i, j);
            // Z edges: below each run (inside above: outward −Z) and above it (outward +Z).
            for r in here {
                let cells = |k: i64| [[i - 1, j - 1, k], [i, j - 1, k], [i, j, k], [i - 1, j, k]];
                f(cells(r.ka as i64 - 1), [x(i), y(j), r.lo], false);
                f(cells(r.kb as i64), [x(i), y(j), r.hi], true);
            }
            // X edges to (i + 1, j).
            if i < n0 {
                let xm = 0.5 * (x(i) + x(i + 1));
                differences(here, lat.column(i + 1, j), |k, inside_here| {
                    let k = k as i64;
                    let cells = [[i, j - 1, k - 1], [i, j, k - 1], [i, j, k], [i, j - 1, k]];
                    f(cells, [xm, y(j), z(k as i32)], inside_here);
                });
            }
            // Y edges to (i, j + 1).
            if j < n1 {
                let ym = 0.5 * (y(j) + y(j + 1));
                differences(here, lat.column(i, j + 1), |k, inside_here| {
                    let k = k as i64;
                    let cells = [[i - 1, j, k - 1], [i - 1, j, k], [i, j, k], [i, j, k - 1]];
                    f(cells, [x(i), ym, z(k as i32)], inside_here);
                });
            }
        }
    }
}

#[inline]
fn key(c: [i64; 3]) -> u64 {
    ((c[0] + 1) as u64) | (((c[1] + 1) as u64) << 21) | (((c[2] + 1) as u64) << 42)
}

impl Mesh {
    /// The surface of a dexel grid (module doc).
    pub fn from_grid(grid: &DexelGrid) -> Mesh {
        let lat = Lattice::new(grid);
        // Pass 1: each cell's vertex = mean of its crossings.
        let mut cells: HashMap<u64, ([f64; 3], u32)> = HashMap::new();
        for_each_edge(grid, &lat, &mut |quad, p, _| {
            for c in quad {
                let e = cells.entry(key(c)).or_insert(([0.0; 3], 0));
                for (s, v) in e.0.iter_mut().zip(p) {
                    *s += v;
                }
                e.1 += 1;
            }
        });
        let mut index: HashMap<u64, u32> = HashMap::with_capacity(cells.len());
        let mut vertices = Vec::with_capacity(cells.len());
        for (k, (sum, n)) in cells {
            index.insert(k, vertices.len() as u32);
            let n = n as f64;
            vertices.push([
                (sum[0] / n) as f32,
                (sum[1] / n) as f32,
                (sum[2] / n) as f32,
            ]);
        }
        // Pass 2: the quads, wound outwards; flat runs merged (`mesh_merge.rs`).
        let mut quads = Vec::new();
        for_each_edge(grid, &lat, &mut |cells, _, flip| {
            let cells = if flip {
                cells
            } else {
                [cells[0], cells[3], cells[2], cells[1]]
            };
            quads.push(Quad {
                cells,
                v: cells.map(|c| index[&key(c)]),
            });
        });
        let triangles = triangulate(&quads, &mut vertices, &|c| index.get(&key(c)).copied());
        Mesh {
            vertices,
            triangles,
        }
    }

    /// Enclosed volume (divergence theorem), mm³; positive when wound outwards.
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize].map(f64::from));
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }

    /// Smallest and largest vertex coordinates.
    pub fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        let first = *self.vertices.first()?;
        let mut lo = first;
        let mut hi = first;
        for v in &self.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        Some((lo, hi))
    }

    /// Writes a binary STL.
    pub fn write_stl(&self, path: &Path) -> Result<(), String> {
        let f = std::fs::File::create(path)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        let mut w = std::io::BufWriter::new(f);
        let tris = self.triangles.iter().map(|t| {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-30);
            stl_io::Triangle {
                normal: stl_io::Normal::new([n[0] / l, n[1] / l, n[2] / l]),
                vertices: [a, b, c].map(stl_io::Vertex::new),
            }
        });
        stl_io::write_stl(&mut w, tris).map_err(|e| format!("cannot write {}: {e}", path.display()))
    }
}

/// Largest STL file read as a stock, bytes.
pub const MAX_STL_BYTES: u64 = 512 * 1024 * 1024;

/// The triangles of an STL file, as read.
pub fn read_stl(path: &Path) -> Result<Vec<[[f64; 3]; 3]>, String> {
    let what = |e: &dyn std::fmt::Display| format!("cannot read {}: {e}", path.display());
    let meta = std::fs::metadata(path).map_err(|e| what(&e))?;
    if meta.len() > MAX_STL_BYTES {
        return Err(format!(
            "{} is larger than {} MiB",
            path.display(),
            MAX_STL_BYTES >> 20
        ));
    }
    let mut f = std::io::BufReader::new(std::fs::File::open(path).map_err(|e| what(&e))?);
    let mesh = stl_io::read_stl(&mut f).map_err(|e| what(&e))?;
    let mut out = Vec::with_capacity(mesh.faces.len());
    for t in &mesh.faces {
        let tri = t.vertices.map(|i| mesh.vertices[i].0.map(f64::from));
        if tri.iter().flatten().all(|v| v.is_finite()) {
            out.push(tri);
        }
    }
    if out.is_empty() {
        return Err(format!("{}: no triangles", path.display()));
    }
    Ok(out)
}

/// The dexel grid of a closed triangle mesh (module doc), and its Z range.
pub fn grid_from_triangles(tris: &[[[f64; 3]; 3]], resolution: f64) -> DexelGrid {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for t in tris {
        for v in t {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
    }
    let mut grid = DexelGrid::new([lo[0], lo[1]], [hi[0], hi[1]], resolution);
    // A hair off the centres: no line through a vertex or an edge of an axis-aligned mesh.
    let nudge = [grid.cell[0] * 1.234_567e-4, grid.cell[1] * 2.345_678e-4];
    let mut hits: Vec<Vec<f32>> = vec![Vec::new(); grid.lines.len()];
    for t in tris {
        let [a, b, c] = *t;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area.abs() < 1e-18 {
            continue;
        }
        let ir = grid.index_range(
            0,
            a[0].min(b[0]).min(c[0]) - nudge[0],
            a[0].max(b[0]).max(c[0]),
        );
        let jr = grid.index_range(
            1,
            a[1].min(b[1]).min(c[1]) - nudge[1],
            a[1].max(b[1]).max(c[1]),
        );
        for j in jr {
            for i in ir.clone() {
                let p = grid.centre(i, j);
                let (px, py) = (p[0] + nudge[0], p[1] + nudge[1]);
                let w0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
                let w1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                    hits[j * grid.n[0] + i].push((w0 * a[2] + w1 * b[2] + w2 * c[2]) as f32);
                }
            }
        }
    }
    for (line, mut z) in grid.lines.iter_mut().zip(hits) {
        z.sort_by(f32::total_cmp);
        let spans = z
            .chunks_exact(2)
            .map(|p| Span { lo: p[0], hi: p[1] })
            .collect();
        *line = Dexel::union_of(spans);
    }
    grid
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mill::MillModel;

    #[test]
    fn a_box_meshes_closed_with_its_volume() {
        let m = MillModel::new_box([0.0, 0.0, -3.0], [10.0, 8.0, 0.0], 0.5);
        let mesh = Mesh::from_grid(&m.grid);
        // Faces exact (walls midway between the last centre and the padding, top and bottom at
        // the interval ends); the box's edges are bevelled by up to half a cell.
        let v = mesh.volume();
        assert!(v < 240.0 && (v - 240.0).abs() / 240.0 < 0.03, "{v}");
        let (lo, hi) = mesh.bounds().unwrap();
        assert_eq!((lo, hi), ([0.0, 0.0, -3.0], [10.0, 8.0, 0.0]));
        // Flat faces merged: the quads of a face's interior become one fan (2 per surface cell
        // would be 2 144 here; what is left is mostly the ring of cells along each edge).
        assert!(mesh.triangles.len() < 1000, "{}", mesh.triangles.len());
        let fine =
            Mesh::from_grid(&MillModel::new_box([0.0, 0.0, -3.0], [10.0, 8.0, 0.0], 0.1).grid);
        assert!(fine.triangles.len() < 5000, "{}", fine.triangles.len());
        assert!((fine.volume() - 240.0).abs() / 240.0 < 0.01);
        // Closed: every edge is shared by exactly two triangles, in opposite directions.
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1);
            assert_eq!(edges.get(&(b, a)), Some(&1));
        }
    }

    #[test]
    fn a_stl_round_trip_keeps_the_solid() {
        let m = MillModel::new_cylinder([0.0, 0.0], [0.0, 20.0], 30.0, 10.0, 0.25);
        let mesh = Mesh::from_grid(&m.grid);
        let dir = std::env::temp_dir().join(format!("stanok-stock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("ring.stl");
        mesh.write_stl(&path).unwrap();
        let tris = read_stl(&path).unwrap();
        let back = grid_from_triangles(&tris, 0.25);
        let (v0, v1) = (m.volume(), back.volume());
        // π·(15² − 5²)·20 = 12566; the mesh's walls are within half a cell.
        assert!((v0 - 12566.4).abs() / 12566.4 < 0.01, "{v0}");
        assert!((v1 - v0).abs() / v0 < 0.03, "{v1} vs {v0}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
