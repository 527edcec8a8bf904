//! # stanok-plot: the tool path as a drawing
//!
//! A program is drawn in two streaming passes over its Canon stream, so that a program of any
//! length plots in memory bounded by the picture:
//!
//! 1. **[`Extent`]** reads every command once and keeps only the box around the path (end points
//!    plus the exact extrema of arcs, `Helix::bounding_box`, and splines, `Nurbs::bounding_box`)
//!    and the start point.
//! 2. **[`Sheet`]** is laid out from that box — one view or four (`view.rs`), the scale fitted so
//!    that the box fills them, one scale for all orthographic views so that a point lines up across
//!    them — and then reads every command again, drawing it into each view at once. Each view has
//!    one path per *layer* and colour ([`Style`]): rapids dashed, feed moves solid, the programmed
//!    contour under a compensated path, tool-axis ticks. `decimate.rs` simplifies each path while it
//!    streams and, once the sheet holds many vertices, leaves out segments that would only ink
//!    pixels already inked; a hard byte cap bounds the rest.
//!
//! [`Sheet::finish`] writes the SVG document: a header with the title and the legend, then per view
//! its frame and title, a grid with coordinates and the path's extents dimensioned (orthographic
//! views), the layers, the start marker, direction arrows and a scale bar. [`png::render_png`] turns
//! the SVG into a PNG with resvg.
//!
//! Arcs are drawn true: in an orthographic view whose plane is parallel to a flat, constant-radius
//! arc, as SVG elliptical-arc commands `A r r 0 0 sweep x y`, split into pieces of at most 180° (so
//! the large-arc flag is always 0). The arc turns counter-clockwise about its axis; seen with y up
//! that is counter-clockwise on screen when the axis points at the viewer, which in SVG's y-down
//! coordinates is sweep flag 0. Otherwise (helices, spirals, oblique views, the isometric view, a
//! dense sheet) an arc is a polyline from `Helix::tessellate`, a spline one from
//! `Nurbs::tessellate`, both within min(`chord_tolerance`, 0.15 px) of the curve; the path's
//! simplification adds at most 0.1 px while the sheet is not dense.
//!
//! Invariants: the output is a well-formed SVG document for any input (an empty stream gives a
//! sheet that says "no motion"); all text is escaped; all numbers are finite (a command with a
//! non-finite coordinate is skipped, so one bad number cannot blank the sheet); the same input
//! gives byte-identical output; the path data of the whole sheet never exceeds
//! [`PlotOptions::max_path_bytes`].
#![deny(missing_docs)]

mod decimate;
mod decor;
pub mod png;
mod sheet;
mod svg;
mod view;

pub use sheet::Sheet;
pub use view::ViewChoice;

use stanok_canon::{Canon, Motion, Spanned, SplineMove};
use stanok_geom::{Helix, Nurbs, Vec3};

/// How to draw the sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotOptions {
    /// Sheet title (e.g. the program's file name).
    pub title: String,
    /// Sheet width, px (at least 320 is used).
    pub width: u32,
    /// Sheet height, px (at least 240 is used).
    pub height: u32,
    /// Largest deviation of a drawn arc from the true arc, mm. The renderer never uses more than
    /// 0.15 px either, whichever is smaller.
    pub chord_tolerance: f64,
    /// Which views.
    pub view: ViewChoice,
    /// A lathe program (X = radius, Z along the spindle): in [`ViewChoice::All`] the front view
    /// becomes the lathe's ZX view, Z to the right and X (radius) up, as a turning drawing is read.
    pub lathe: bool,
    /// Vertices on the sheet after which it is drawn at the picture's resolution (`decimate.rs`).
    pub dense_after: usize,
    /// Most bytes of path data on the whole sheet; beyond it nothing more is drawn.
    pub max_path_bytes: usize,
    /// Extra legend entries (label, colour), e.g. for paths drawn with [`Sheet::draw_styled`].
    pub legend: Vec<(String, Colour)>,
}

impl Default for PlotOptions {
    /// Untitled, 1200 × 900 px, 0.01 mm, all views, dense after 200 000 vertices, at most 4.5 MB
    /// of path data.
    fn default() -> Self {
        PlotOptions {
            title: String::new(),
            width: 1200,
            height: 900,
            chord_tolerance: 0.01,
            view: ViewChoice::All,
            lathe: false,
            dense_after: 200_000,
            max_path_bytes: 4_500_000,
            legend: Vec::new(),
        }
    }
}

/// What a path element is, which decides its default colour, dash and drawing order (first below).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Layer {
    /// A feed move of the programmed contour (drawn under a cutter-compensated path).
    Programmed,
    /// A rapid move.
    Rapid,
    /// A feed move (lines, arcs, splines, probe moves, taps).
    Feed,
    /// A short tick along the tool axis from the tip (5-axis programs).
    ToolAxis,
}

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Colour(pub [u8; 3]);

impl Colour {
    /// `#rrggbb`.
    pub fn hex(self) -> String {
        let [r, g, b] = self.0;
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

/// How one path element is drawn: its layer, and a colour in place of the layer's own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Style {
    /// Layer (class, dash, order).
    pub layer: Layer,
    /// Stroke colour; `None` = the layer's.
    pub colour: Option<Colour>,
}

impl Style {
    /// The layer's own look.
    pub fn plain(layer: Layer) -> Self {
        Style {
            layer,
            colour: None,
        }
    }

    /// Class and presentation attributes of a path of this style.
    fn attributes(self) -> String {
        let (class, colour, rest) = match self.layer {
            Layer::Rapid => (
                "rapid",
                "#e8590c",
                r#"stroke-width="1" stroke-dasharray="6 4""#,
            ),
            Layer::Feed => ("feed", "#1864ab", r#"stroke-width="1.5""#),
            Layer::Programmed => (
                "programmed",
                "#ae3ec9",
                r#"stroke-width="1" stroke-dasharray="2 2""#,
            ),
            Layer::ToolAxis => ("tool-axis", "#2f9e44", r#"stroke-width="1""#),
        };
        let colour = self.colour.map_or_else(|| colour.to_string(), Colour::hex);
        format!(r#"class="{class}" fill="none" stroke="{colour}" {rest}"#)
    }
}

/// One motion in machine X Y Z, as it is drawn.
#[derive(Debug, Clone)]
pub(crate) enum Shape {
    Line(Vec3, Vec3),
    Arc(Helix),
    /// A spline (NURBS), drawn as a polyline within the chord tolerance of the exact curve.
    Spline(Box<SplineMove>),
}

impl Shape {
    fn start(&self) -> Vec3 {
        match self {
            Shape::Line(a, _) => *a,
            Shape::Arc(h) => h.start,
            Shape::Spline(s) => s.start.xyz(),
        }
    }

    /// False when a coordinate is not finite or a spline is malformed: such a move is skipped.
    fn is_drawable(&self) -> bool {
        let finite = |p: &[Vec3]| p.iter().flatten().all(|c| c.is_finite());
        match self {
            Shape::Line(a, b) => finite(&[*a, *b]),
            Shape::Arc(h) => finite(&[h.start, h.end, h.centre, h.axis]),
            Shape::Spline(s) => {
                finite(&s.control_points)
                    && Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots)
                        .validate()
                        .is_ok()
            }
        }
    }

    /// The box around the shape.
    fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Shape::Line(a, b) => (
                std::array::from_fn(|i| a[i].min(b[i])),
                std::array::from_fn(|i| a[i].max(b[i])),
            ),
            Shape::Arc(h) => h.bounding_box(),
            Shape::Spline(s) => {
                Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots).bounding_box()
            }
        }
    }
}

/// The shapes a command draws, with their default layer (a rigid tap draws its way down and back).
pub(crate) fn shapes(cmd: &Canon) -> Vec<(Layer, Shape)> {
    let line = |a: &stanok_canon::Pose, b: &stanok_canon::Pose| Shape::Line(a.xyz(), b.xyz());
    let shapes = match cmd.motion() {
        None => return Vec::new(),
        Some(Motion::Rapid(m)) => vec![(Layer::Rapid, line(&m.start, &m.end))],
        Some(Motion::Line(m)) => vec![(Layer::Feed, line(&m.start, &m.end))],
        Some(Motion::Arc(a)) => vec![(
            Layer::Feed,
            Shape::Arc(Helix {
                start: a.start.xyz(),
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
                turns: a.turns,
            }),
        )],
        Some(Motion::Spline(s)) => vec![(Layer::Feed, Shape::Spline(Box::new(s.clone())))],
        // A probe move ends where the probe trips.
        Some(Motion::Probe { motion, contact }) => vec![(
            Layer::Feed,
            line(&motion.start, &contact.unwrap_or(motion.end)),
        )],
        Some(Motion::RigidTap { start, bottom }) => vec![
            (Layer::Feed, line(&start, &bottom)),
            (Layer::Feed, line(&bottom, &start)),
        ],
    };
    shapes
        .into_iter()
        .filter(|(_, s)| s.is_drawable())
        .collect()
}

/// Pass 1: the box around everything a sheet will draw, and the start point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Extent {
    lo: Vec3,
    hi: Vec3,
    /// Where the path starts: the `Init` position, else the first move's start.
    start: Option<Vec3>,
    /// Something will be drawn.
    any: bool,
}

impl Extent {
    /// An empty extent.
    pub fn new() -> Self {
        Self::default()
    }

    /// Includes what `cmd` draws (and takes the start point from the first `Init` or move).
    pub fn add(&mut self, cmd: &Canon) {
        if let Canon::Init { position, .. } = cmd {
            let p = position.xyz();
            if self.start.is_none() && p.iter().all(|c| c.is_finite()) {
                self.start = Some(p);
            }
            return;
        }
        for (_, shape) in shapes(cmd) {
            if self.start.is_none() {
                self.start = Some(shape.start());
            }
            let (a, b) = shape.bounds();
            self.include(a, b);
        }
    }

    /// Includes the feed moves of a reference stream (the programmed contour).
    pub fn add_reference(&mut self, cmd: &Canon) {
        for (layer, shape) in shapes(cmd) {
            if layer == Layer::Feed {
                let (a, b) = shape.bounds();
                self.include(a, b);
            }
        }
    }

    /// Includes a tool-axis tick from `a` to `b` (machine X Y Z, mm).
    pub fn add_tick(&mut self, a: Vec3, b: Vec3) {
        if a.iter().chain(&b).all(|c| c.is_finite()) {
            self.include(a, a);
            self.include(b, b);
        }
    }

    /// Includes everything `other` holds (its start point only if this one has none).
    pub fn union(&mut self, other: &Extent) {
        if other.any {
            self.include(other.lo, other.hi);
        }
        if self.start.is_none() {
            self.start = other.start;
        }
    }

    fn include(&mut self, a: Vec3, b: Vec3) {
        if !self.any {
            (self.lo, self.hi) = (a, b);
            self.any = true;
        }
        for i in 0..3 {
            self.lo[i] = self.lo[i].min(a[i]);
            self.hi[i] = self.hi[i].max(b[i]);
        }
    }

    /// True when nothing will be drawn.
    pub fn is_empty(&self) -> bool {
        !self.any
    }

    /// The box (with the start point), or None when empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let (mut lo, mut hi) = (self.lo, self.hi);
        if let Some(s) = self.start {
            for i in 0..3 {
                lo[i] = lo[i].min(s[i]);
                hi[i] = hi[i].max(s[i]);
            }
        }
        self.any.then_some((lo, hi))
    }

    /// The start point.
    pub fn start(&self) -> Option<Vec3> {
        self.start.or(self.any.then_some(self.lo))
    }
}

/// Renders the tool path of a whole stream as an SVG sheet (both passes over the slice).
pub fn render_svg(commands: &[Spanned<Canon>], options: &PlotOptions) -> String {
    let mut extent = Extent::new();
    for c in commands {
        extent.add(&c.value);
    }
    let mut sheet = Sheet::new(options, &extent);
    for c in commands {
        sheet.draw(&c.value);
    }
    sheet.finish()
}

#[cfg(test)]
mod tests;
