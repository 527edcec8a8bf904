//! Pictures of the stock: a shaded PNG with an isometric view and the three planes.
//!
//! The mesh is rasterised with a depth buffer (per triangle: its screen box, barycentric
//! coverage at pixel centres, depth interpolated; the nearest wins), shaded by the angle between
//! the face normal and a light over the viewer's left shoulder (ambient 0.25, diffuse 0.75), into a
//! `tiny_skia::Pixmap`, which also draws the panel frames and collision markers and writes the
//! PNG. Views (world → screen, y down):
//! * isometric: from (+1, −1, +1) (X right-down, Y right-up, Z up), as `stanok plot` draws it;
//! * XY: from +Z (top); XZ: from −Y (front); YZ: from +X (side).
//!
//! Each view is scaled to fit its quarter of the sheet with a margin, every view at the same
//! scale so sizes compare. Collision positions (stock frame) are red discs drawn over the part.

use crate::mesh::Mesh;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// Sheet size, pixels (2 × 2 views).
pub const SHEET: u32 = 1200;

/// A view: world point → (screen x, screen y, depth; larger = nearer).
type Project = fn([f64; 3]) -> [f64; 3];

const S2: f64 = std::f64::consts::FRAC_1_SQRT_2;
const S6: f64 = 0.408_248_290_463_863; // 1/√6

fn iso(p: [f64; 3]) -> [f64; 3] {
    // Camera looks along −(1, −1, 1)/√3; right = (1, 1, 0)/√2, up = (−1, 1, 2)/√6.
    let right = (p[0] + p[1]) * S2;
    let up = (-p[0] + p[1] + 2.0 * p[2]) * S6;
    let depth = (p[0] - p[1] + p[2]) / 3f64.sqrt();
    [right, -up, depth]
}
fn top(p: [f64; 3]) -> [f64; 3] {
    [p[0], -p[1], p[2]]
}
fn front(p: [f64; 3]) -> [f64; 3] {
    [p[0], -p[2], -p[1]]
}
fn side(p: [f64; 3]) -> [f64; 3] {
    [p[1], -p[2], p[0]]
}

/// The four views and their titles.
const VIEWS: [(Project, &str); 4] = [
    (iso, "isometric"),
    (top, "XY (top)"),
    (front, "XZ (front)"),
    (side, "YZ (side)"),
];

/// Renders the mesh (and red markers at `marks`) as a PNG sheet of four views.
pub fn render_png(mesh: &Mesh, marks: &[[f64; 3]]) -> Result<Vec<u8>, String> {
    let mut pix = Pixmap::new(SHEET, SHEET).ok_or("cannot allocate the picture")?;
    pix.fill(Color::WHITE);
    let half = SHEET / 2;
    let verts: Vec<[f64; 3]> = mesh
        .vertices
        .iter()
        .map(|v| [v[0] as f64, v[1] as f64, v[2] as f64])
        .collect();
    // One scale for every view: the largest extent of any.
    let mut boxes = Vec::new();
    let mut scale = f64::INFINITY;
    for (proj, _) in VIEWS {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for v in &verts {
            let s = proj(*v);
            for k in 0..2 {
                lo[k] = lo[k].min(s[k]);
                hi[k] = hi[k].max(s[k]);
            }
        }
        let w = (hi[0] - lo[0]).max(1e-9);
        let h = (hi[1] - lo[1]).max(1e-9);
        scale = scale.min(0.86 * half as f64 / w.max(h));
        boxes.push((lo, hi));
    }
    if !scale.is_finite() {
        scale = 1.0;
    }
    let mut rgba = vec![[255u8; 4]; (SHEET * SHEET) as usize];
    let mut depth = vec![f64::NEG_INFINITY; (SHEET * SHEET) as usize];
    for (v, ((proj, _), (lo, hi))) in VIEWS.iter().zip(&boxes).enumerate() {
        let ox = (v as u32 % 2 * half) as f64 + half as f64 / 2.0 - scale * (lo[0] + hi[0]) / 2.0;
        let oy = (v as u32 / 2 * half) as f64 + half as f64 / 2.0 - scale * (lo[1] + hi[1]) / 2.0;
        let screen: Vec<[f64; 3]> = verts
            .iter()
            .map(|p| {
                let s = proj(*p);
                [ox + scale * s[0], oy + scale * s[1], s[2]]
            })
            .collect();
        let x0 = (v as u32 % 2 * half) as i64;
        let y0 = (v as u32 / 2 * half) as i64;
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| screen[i as usize]);
            // Screen-space area: > 0 faces the viewer (y down flips the winding).
            let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            if area >= 0.0 {
                continue;
            }
            // Shade by the world normal against a light from the viewer's upper left.
            let [pa, pb, pc] = t.map(|i| proj(verts[i as usize]));
            let u = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
            let w = [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]];
            let n = [
                u[1] * w[2] - u[2] * w[1],
                u[2] * w[0] - u[0] * w[2],
                u[0] * w[1] - u[1] * w[0],
            ];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-30);
            let light = [-0.35, -0.45, 0.82];
            let lambert = ((n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) / len)
                .abs()
                .min(1.0);
            let k = 0.25 + 0.75 * lambert;
            let colour = [
                (95.0 + 120.0 * k) as u8,
                (110.0 + 120.0 * k) as u8,
                (130.0 + 115.0 * k) as u8,
                255,
            ];
            let xmin = a[0].min(b[0]).min(c[0]).floor().max(x0 as f64) as i64;
            let xmax = a[0]
                .max(b[0])
                .max(c[0])
                .ceil()
                .min((x0 + half as i64 - 1) as f64) as i64;
            let ymin = a[1].min(b[1]).min(c[1]).floor().max(y0 as f64) as i64;
            let ymax = a[1]
                .max(b[1])
                .max(c[1])
                .ceil()
                .min((y0 + half as i64 - 1) as f64) as i64;
            for py in ymin..=ymax {
                for px in xmin..=xmax {
                    let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
                    let w0 = ((b[0] - x) * (c[1] - y) - (b[1] - y) * (c[0] - x)) / area;
                    let w1 = ((c[0] - x) * (a[1] - y) - (c[1] - y) * (a[0] - x)) / area;
                    let w2 = 1.0 - w0 - w1;
                    if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                        continue;
                    }
                    let z = w0 * a[2] + w1 * b[2] + w2 * c[2];
                    let idx = (py as u32 * SHEET + px as u32) as usize;
                    if z > depth[idx] {
                        depth[idx] = z;
                        rgba[idx] = colour;
                    }
                }
            }
        }
    }
    for (dst, src) in pix.pixels_mut().iter_mut().zip(&rgba) {
        *dst = tiny_skia::ColorU8::from_rgba(src[0], src[1], src[2], src[3]).premultiply();
    }
    // Frames and markers.
    let mut frame = Paint::default();
    frame.set_color_rgba8(160, 160, 160, 255);
    let mut red = Paint::default();
    red.set_color_rgba8(220, 30, 30, 230);
    red.anti_alias = true;
    for (v, ((proj, _), (lo, hi))) in VIEWS.iter().zip(&boxes).enumerate() {
        let (vx, vy) = ((v as u32 % 2 * half) as f32, (v as u32 / 2 * half) as f32);
        if let Some(rect) =
            tiny_skia::Rect::from_xywh(vx + 1.0, vy + 1.0, half as f32 - 2.0, half as f32 - 2.0)
        {
            let path = PathBuilder::from_rect(rect);
            pix.stroke_path(
                &path,
                &frame,
                &Stroke::default(),
                Transform::identity(),
                None,
            );
        }
        let ox = vx as f64 + half as f64 / 2.0 - scale * (lo[0] + hi[0]) / 2.0;
        let oy = vy as f64 + half as f64 / 2.0 - scale * (lo[1] + hi[1]) / 2.0;
        for m in marks {
            let s = proj(*m);
            if let Some(circle) = PathBuilder::from_circle(
                (ox + scale * s[0]) as f32,
                (oy + scale * s[1]) as f32,
                5.0,
            ) {
                pix.fill_path(
                    &circle,
                    &red,
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
    }
    pix.encode_png()
        .map_err(|e| format!("cannot encode the picture: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mill::MillModel;

    #[test]
    fn a_box_fills_its_views() {
        let m = MillModel::new_box([0.0, 0.0, -10.0], [40.0, 20.0, 0.0], 1.0);
        let png = render_png(&Mesh::from_grid(&m.grid), &[[20.0, 10.0, 0.0]]).unwrap();
        let pix = Pixmap::decode_png(&png).unwrap();
        // The top view's centre is the part (shaded, not white); its corner is background.
        let at = |x: u32, y: u32| pix.pixel(x, y).unwrap();
        let centre = at(SHEET * 3 / 4 + 40, SHEET / 4);
        assert!(centre.red() < 250 && centre.alpha() == 255, "{centre:?}");
        assert_eq!(at(SHEET / 2 + 5, 5).red(), 255);
        // The marker is red at the centre of the top view.
        let mark = at(SHEET * 3 / 4, SHEET / 4);
        assert!(mark.red() > 150 && mark.green() < 100, "{mark:?}");
    }
}
