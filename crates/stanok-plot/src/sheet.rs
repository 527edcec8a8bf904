//! Pass 2: the sheet, drawn one command at a time (see the crate doc).
//!
//! A [`Sheet`] is laid out once from the [`Extent`] of pass 1; after that every command is projected
//! into every view at once and handed to the view's [`LayerPath`] of its style. Curves are
//! tessellated once per command (at the finest view's tolerance) and the points reused by all views.

use crate::decimate::{Budget, LayerPath};
use crate::svg::{escape, num};
use crate::view::{self, Mapping, Projection, View};
use crate::{decor, shapes, Colour, Extent, Layer, PlotOptions, Shape, Style};
use stanok_canon::Canon;
use stanok_geom::{dot, normalize, Helix, Nurbs, Vec3};
use std::f64::consts::PI;
use std::fmt::Write;

/// Height of the sheet's header band, px.
pub(crate) const HEADER: f64 = 40.0;
/// Most distinct styles per view; further colours fall back to their layer's own.
const MAX_STYLES: usize = 64;
/// Tessellation tolerance, px (the simplification adds at most 0.1 px: 0.25 px in all).
const TESSELLATION_PX: f64 = 0.15;

/// One view and what has been drawn in it.
struct ViewState {
    view: View,
    map: Mapping,
    layers: Vec<LayerPath>,
}

impl ViewState {
    fn layer(&mut self, style: Style) -> &mut LayerPath {
        let style =
            if self.layers.len() >= MAX_STYLES && !self.layers.iter().any(|l| l.style == style) {
                Style::plain(style.layer)
            } else {
                style
            };
        let i = match self.layers.iter().position(|l| l.style == style) {
            Some(i) => i,
            None => {
                let c = self.view.cell;
                self.layers
                    .push(LayerPath::new(style, [c.x, c.y, c.w, c.h]));
                self.layers.len() - 1
            }
        };
        &mut self.layers[i]
    }

    fn screen(&self, p: Vec3) -> [f64; 2] {
        self.map.to_screen(self.view.projection.project(p))
    }
}

/// A sheet being drawn (pass 2; see the crate doc).
pub struct Sheet {
    options: PlotOptions,
    width: f64,
    height: f64,
    views: Vec<ViewState>,
    start: Option<Vec3>,
    bounds: Option<(Vec3, Vec3)>,
    budget: Budget,
    /// Chord tolerance of tessellated curves, mm.
    tolerance: f64,
    /// Scratch for tessellated points.
    points: Vec<Vec3>,
    /// The layers drawn at least once, for the legend.
    drawn: [bool; 4],
}

impl Sheet {
    /// Lays out the sheet for what `extent` holds.
    pub fn new(options: &PlotOptions, extent: &Extent) -> Sheet {
        let width = f64::from(options.width.max(320));
        let height = f64::from(options.height.max(240));
        let bounds = extent.bounds();
        let views: Vec<ViewState> = match bounds {
            Some((lo, hi)) => {
                let views = view::layout(width, height, HEADER, options.view, options.lathe);
                let maps = view::fit(&views, lo, hi);
                views
                    .into_iter()
                    .zip(maps)
                    .map(|(view, map)| ViewState {
                        view,
                        map,
                        layers: Vec::new(),
                    })
                    .collect()
            }
            None => Vec::new(),
        };
        let finest = views.iter().map(|v| v.map.scale).fold(0.0, f64::max);
        let px = if finest > 0.0 {
            TESSELLATION_PX / finest
        } else {
            1e-3
        };
        let tolerance = if options.chord_tolerance > 0.0 {
            options.chord_tolerance.min(px)
        } else {
            px
        };
        Sheet {
            options: options.clone(),
            width,
            height,
            views,
            start: extent.start(),
            bounds,
            budget: Budget::new(options.dense_after, options.max_path_bytes),
            tolerance,
            points: Vec::new(),
            drawn: [false; 4],
        }
    }

    /// Draws a command in its layer's own look.
    pub fn draw(&mut self, cmd: &Canon) {
        self.draw_styled(cmd, None);
    }

    /// Draws a command in `colour` (None = its layer's own), e.g. coloured by speed.
    pub fn draw_styled(&mut self, cmd: &Canon, colour: Option<Colour>) {
        for (layer, shape) in shapes(cmd) {
            self.draw_shape(Style { layer, colour }, &shape);
        }
    }

    /// Draws the feed moves of a reference stream (the programmed contour) under the path.
    pub fn draw_reference(&mut self, cmd: &Canon) {
        for (layer, shape) in shapes(cmd) {
            if layer == Layer::Feed {
                self.draw_shape(Style::plain(Layer::Programmed), &shape);
            }
        }
    }

    /// Draws a tool-axis tick from `a` to `b` (machine X Y Z, mm).
    pub fn draw_tick(&mut self, a: Vec3, b: Vec3) {
        let shape = Shape::Line(a, b);
        if shape.is_drawable() {
            self.draw_shape(Style::plain(Layer::ToolAxis), &shape);
        }
    }

    /// True once the sheet is drawn at the picture's resolution (`decimate.rs`).
    pub fn is_dense(&self) -> bool {
        self.budget.dense
    }

    fn draw_shape(&mut self, style: Style, shape: &Shape) {
        self.drawn[style.layer as usize] = true;
        let Sheet {
            views,
            budget,
            points,
            tolerance,
            ..
        } = self;
        match shape {
            Shape::Line(a, b) => {
                for v in views.iter_mut() {
                    let (sa, sb) = (v.screen(*a), v.screen(*b));
                    let l = v.layer(style);
                    l.move_to(sa, budget);
                    l.line_to(sb, budget);
                }
            }
            Shape::Arc(h) => {
                let mut tessellated = false;
                for v in views.iter_mut() {
                    let flag = if budget.dense {
                        None
                    } else {
                        flat_arc_sweep_flag(h, v.view.projection)
                    };
                    let start = v.screen(h.start);
                    match flag {
                        Some(flag) => {
                            let r = h.start_radius() * v.map.scale;
                            let pieces = ((h.sweep() / PI) - 1e-9).ceil().max(1.0);
                            let ends: Vec<[f64; 2]> = (1..=pieces as u32)
                                .map(|k| v.screen(h.point_at(f64::from(k) / pieces)))
                                .collect();
                            let l = v.layer(style);
                            l.move_to(start, budget);
                            for e in ends {
                                l.arc_to(r, flag, e, budget);
                            }
                        }
                        None => {
                            if !tessellated {
                                points.clear();
                                h.tessellate(*tolerance, points);
                                tessellated = true;
                            }
                            polyline(v, style, start, points, budget);
                        }
                    }
                }
            }
            Shape::Spline(s) => {
                points.clear();
                Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots)
                    .tessellate(*tolerance, points);
                for v in views.iter_mut() {
                    let start = v.screen(s.start.xyz());
                    polyline(v, style, start, points, budget);
                }
            }
        }
    }

    /// The finished SVG document.
    pub fn finish(mut self) -> String {
        for v in &mut self.views {
            for l in &mut v.layers {
                l.flush(&mut self.budget);
            }
        }
        let (width, height) = (self.width, self.height);
        let mut out = String::with_capacity(64 * 1024 + self.budget.bytes);
        let _ = write!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">"#,
            w = num(width),
            h = num(height)
        );
        out.push_str(concat!(
            r##"<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto-start-reverse">"##,
            r##"<path d="M0 0L10 5L0 10z" fill="#343a40"/></marker></defs>"##
        ));
        let _ = write!(
            out,
            r##"<rect x="0" y="0" width="{}" height="{}" fill="#ffffff"/>"##,
            num(width),
            num(height)
        );
        let _ = write!(
            out,
            r##"<text class="sheet-title" x="12" y="26" font-size="18" fill="#212529">{}</text>"##,
            escape(&self.options.title)
        );
        let (Some(start), Some((lo, hi))) = (self.start, self.bounds) else {
            let _ = write!(
                out,
                r##"<text class="no-motion" x="{}" y="{}" text-anchor="middle" font-size="20" fill="#868e96">no motion</text>"##,
                num(width / 2.0),
                num(height / 2.0)
            );
            out.push_str("</svg>\n");
            return out;
        };
        decor::legend(&mut out, width, &self.drawn, &self.options.legend);
        decor::resolution_note(&mut out, &self.budget, height);
        for v in &mut self.views {
            decor::frame(&mut out, &v.view, v.map.scale);
            if v.view.is_orthographic() {
                decor::grid(&mut out, &v.view, &v.map);
            }
            let _ = write!(
                out,
                r#"<clipPath id="clip-{id}"><rect x="{x}" y="{y}" width="{w}" height="{h}"/></clipPath><g clip-path="url(#clip-{id})">"#,
                id = v.view.id,
                x = num(v.view.cell.x + 1.0),
                y = num(v.view.cell.y + 1.0),
                w = num(v.view.cell.w - 2.0),
                h = num(v.view.cell.h - 2.0),
            );
            // Lower layers first; within a layer, colours in the order they first appeared.
            v.layers.sort_by_key(|l| l.style.layer);
            for l in &v.layers {
                if !l.d.is_empty() {
                    let _ = write!(out, r#"<path {} d="{}"/>"#, l.style.attributes(), l.d);
                }
            }
            let p = v.screen(start);
            let _ = write!(
                out,
                r##"<circle class="start" cx="{}" cy="{}" r="4" fill="#2f9e44"/></g>"##,
                num(p[0]),
                num(p[1])
            );
            if v.view.is_orthographic() {
                decor::dimensions(&mut out, &v.view, &v.map, lo, hi);
            }
            decor::arrows(&mut out, &v.view);
            decor::scale_bar(&mut out, &v.view, v.map.scale);
            out.push_str("</g>");
        }
        out.push_str("</svg>\n");
        out
    }
}

/// A tessellated curve (points after `start`) into one view.
fn polyline(
    v: &mut ViewState,
    style: Style,
    start: [f64; 2],
    points: &[Vec3],
    budget: &mut Budget,
) {
    let (map, projection) = (v.map, v.view.projection);
    let l = v.layer(style);
    l.move_to(start, budget);
    for p in points {
        l.line_to(map.to_screen(projection.project(*p)), budget);
    }
}

/// The SVG sweep flag when `h` can be drawn with `A` commands in this view: a flat, constant-radius
/// arc whose plane is parallel to the view plane; `None` otherwise.
fn flat_arc_sweep_flag(h: &Helix, projection: Projection) -> Option<u8> {
    let normal = projection.normal()?;
    let axis = normalize(h.axis).unwrap_or([0.0, 0.0, 1.0]);
    let facing = dot(axis, normal);
    let r = h.start_radius();
    let flat = h.axial_travel().abs() <= 1e-9 * r.max(1.0);
    let round = (h.end_radius() - r).abs() <= 1e-9 * r.max(1.0);
    if facing.abs() >= 1.0 - 1e-12 && flat && round {
        Some(if facing > 0.0 { 0 } else { 1 })
    } else {
        None
    }
}
