//! # stanok-plot: the tool path as a drawing
//!
//! [`render_svg`] draws the motion of a Canon stream on one SVG sheet with four views in a 2×2 grid:
//! XY (top), isometric, XZ (front) and YZ (side) (see `view.rs` for the arrangement). Rapids are
//! dashed, feed moves solid in another colour; a dot marks the start point.
//!
//! ## Algorithm
//! 1. **Collect** the motion commands as segments (line, arc or spline, rapid or feed; a probe
//!    move up to its contact point), in machine X Y Z.
//!    Commands with a non-finite coordinate are skipped, so one bad number cannot blank the sheet.
//! 2. **Bound** the path: end points plus the exact arc extrema (`Helix::bounding_box`).
//! 3. **Fit**: one scale for the three orthographic views, the largest at which the box fits all of
//!    them; the isometric view fits on its own.
//! 4. **Draw** each view: consecutive segments of one kind become one `<path>` (class `rapid` or
//!    `feed`), with `M` only where the pen must jump. Arcs are drawn true:
//!    * in an orthographic view whose plane is parallel to a flat, constant-radius arc, as SVG
//!      elliptical-arc commands `A r r 0 0 sweep x y`, split into pieces of at most 180° (so the
//!      large-arc flag is always 0). The arc turns counter-clockwise about its axis; seen with y up
//!      that is counter-clockwise on screen when the axis points at the viewer, which in SVG's
//!      y-down coordinates is sweep flag 0;
//!    * otherwise (helices, spirals, oblique views, the isometric view) as a polyline from
//!      `Helix::tessellate` with a chord tolerance of min(`chord_tolerance`, 0.25 px).
//!
//!    Splines (NURBS, the form of every spline in the stream) are polylines from
//!    `Nurbs::tessellate` with the same tolerance; their box comes from `Nurbs::bounding_box`.
//! 5. **Annotate** each view: title, direction arrows for its axes, a scale bar of a round length
//!    (1, 2 or 5 × 10ⁿ mm) and the start marker.
//!
//! **Colour by block** ([`PlotOptions::colouring`], `plot --color speed|limit`): each motion is
//! drawn in the colour of its source line's class (rapids still dashed, runs of one class in one
//! `<path>` of class `class-K`), and the header's key lists the classes instead of rapid/feed.
//!
//! Invariants: the output is a well-formed SVG document for any input (an empty stream gives a
//! sheet that says "no motion"); all text is escaped; all numbers are finite; the same input gives
//! byte-identical output.
#![deny(missing_docs)]

mod svg;
mod view;

use stanok_canon::{Canon, Spanned, SplineMove};
use stanok_geom::{dot, normalize, Helix, Nurbs, Vec3};
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::fmt::Write;
use svg::{escape, num, PathData};
use view::{Mapping, Projection, View};

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
    /// 0.25 px either, whichever is smaller.
    pub chord_tolerance: f64,
    /// A second stream whose feed moves are drawn under the path in their own colour: the
    /// programmed contour when the path is the compensated tool centre (empty = none).
    pub reference: Vec<Spanned<Canon>>,
    /// A lathe program (X = radius, Z along the spindle): the front view becomes the lathe's ZX
    /// view, Z to the right and X (radius) up, as a turning drawing is read.
    pub lathe: bool,
    /// Tool-axis ticks of a 5-axis program: each from the tool tip along the tool vector, machine
    /// X Y Z mm (empty = none). The caller computes them with the machine's kinematics.
    pub tool_axis: Vec<[[f64; 3]; 2]>,
    /// Colour by block (module doc): `None` draws rapids and feeds in their two styles.
    pub colouring: Option<Colouring>,
}

/// A class per source line and the key of the classes (`plot --color`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Colouring {
    /// Heading of the key, e.g. "limit" or "mean speed mm/min".
    pub title: String,
    /// The classes in key order: label and colour (`#rrggbb`).
    pub classes: Vec<(String, String)>,
    /// Class (index into `classes`) of each source line; a motion whose line is not listed keeps
    /// its rapid or feed style.
    pub line_class: BTreeMap<u32, usize>,
}

impl Default for PlotOptions {
    /// Untitled, 1200 × 900 px, 0.01 mm.
    fn default() -> Self {
        PlotOptions {
            title: String::new(),
            width: 1200,
            height: 900,
            chord_tolerance: 0.01,
            reference: Vec::new(),
            lathe: false,
            tool_axis: Vec::new(),
            colouring: None,
        }
    }
}

/// Rapid or feed: which class, colour and dash a segment gets.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Rapid,
    Feed,
    /// A feed move of the reference stream (the programmed contour).
    Programmed,
    /// A short tick along the tool axis from the tip (5-axis programs).
    ToolAxis,
    /// A motion of a [`Colouring`] class (index into its classes); rapid or not.
    Class(usize, bool),
}

impl Kind {
    /// Class and presentation attributes of a path of this kind.
    fn attributes(self) -> &'static str {
        match self {
            Kind::Rapid => {
                r##"class="rapid" fill="none" stroke="#e8590c" stroke-width="1" stroke-dasharray="6 4""##
            }
            Kind::Feed => r##"class="feed" fill="none" stroke="#1864ab" stroke-width="1.5""##,
            Kind::Programmed => {
                r##"class="programmed" fill="none" stroke="#ae3ec9" stroke-width="1" stroke-dasharray="2 2""##
            }
            Kind::ToolAxis => {
                r##"class="tool-axis" fill="none" stroke="#2f9e44" stroke-width="1""##
            }
            Kind::Class(..) => "",
        }
    }

    /// [`Kind::attributes`], with a class's colour from `classes`.
    fn attributes_in(self, classes: &[(String, String)]) -> String {
        match self {
            Kind::Class(k, rapid) => {
                let colour = classes.get(k).map_or("#495057", |c| c.1.as_str());
                format!(
                    r#"class="class-{k}" fill="none" stroke="{}" stroke-width="{}"{}"#,
                    escape(colour),
                    if rapid { "1" } else { "1.8" },
                    if rapid {
                        r#" stroke-dasharray="6 4""#
                    } else {
                        ""
                    }
                )
            }
            _ => self.attributes().to_string(),
        }
    }
}

/// One motion in machine X Y Z.
#[derive(Debug, Clone)]
enum Shape {
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
}

/// Step 1: the segments of the stream and the start point.
fn collect(commands: &[Spanned<Canon>]) -> (Vec<(Kind, Shape)>, Option<Vec3>) {
    let (segments, start, _) = collect_with_lines(commands);
    (segments, start)
}

/// [`collect`], with the source line of each segment.
fn collect_with_lines(commands: &[Spanned<Canon>]) -> (Vec<(Kind, Shape)>, Option<Vec3>, Vec<u32>) {
    let mut lines = Vec::new();
    let finite = |p: &[Vec3]| p.iter().flatten().all(|c| c.is_finite());
    let mut segments = Vec::new();
    let mut start = None;
    for cmd in commands {
        let seg = match &cmd.value {
            Canon::Init { position, .. } => {
                if start.is_none() && finite(&[position.xyz()]) {
                    start = Some(position.xyz());
                }
                continue;
            }
            Canon::StraightTraverse(m) => (Kind::Rapid, Shape::Line(m.start.xyz(), m.end.xyz())),
            Canon::StraightFeed(m) => (Kind::Feed, Shape::Line(m.start.xyz(), m.end.xyz())),
            Canon::ArcFeed(a) => (
                Kind::Feed,
                Shape::Arc(Helix {
                    start: a.start.xyz(),
                    end: a.end.xyz(),
                    centre: a.centre,
                    axis: a.axis,
                    turns: a.turns,
                }),
            ),
            Canon::SplineFeed(s) => (Kind::Feed, Shape::Spline(Box::new(s.clone()))),
            // A probe move ends where the probe trips.
            Canon::StraightProbe {
                motion, contact, ..
            } => (
                Kind::Feed,
                Shape::Line(motion.start.xyz(), contact.unwrap_or(motion.end).xyz()),
            ),
            _ => continue,
        };
        let ok = match &seg.1 {
            Shape::Line(a, b) => finite(&[*a, *b]),
            Shape::Arc(h) => finite(&[h.start, h.end, h.centre, h.axis]),
            Shape::Spline(s) => {
                finite(&s.control_points)
                    && Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots)
                        .validate()
                        .is_ok()
            }
        };
        if ok {
            start.get_or_insert(seg.1.start());
            segments.push(seg);
            lines.push(cmd.span.line);
        }
    }
    (segments, start, lines)
}

/// Step 2: the box around the path and the start point.
fn bounds(segments: &[(Kind, Shape)], start: Vec3) -> (Vec3, Vec3) {
    let (mut lo, mut hi) = (start, start);
    let mut include = |a: Vec3, b: Vec3| {
        for i in 0..3 {
            lo[i] = lo[i].min(a[i]);
            hi[i] = hi[i].max(b[i]);
        }
    };
    for (_, shape) in segments {
        match shape {
            Shape::Line(a, b) => {
                include(*a, *a);
                include(*b, *b);
            }
            Shape::Arc(h) => {
                let (a, b) = h.bounding_box();
                include(a, b);
            }
            Shape::Spline(s) => {
                let (a, b) =
                    Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots).bounding_box();
                include(a, b);
            }
        }
    }
    (lo, hi)
}

/// Renders the tool path of `commands` as an SVG sheet (see the crate doc).
pub fn render_svg(commands: &[Spanned<Canon>], options: &PlotOptions) -> String {
    let width = f64::from(options.width.max(320));
    let height = f64::from(options.height.max(240));
    let mut out = String::new();
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
        escape(&options.title)
    );
    let (mut segments, start, lines) = collect_with_lines(commands);
    if let Some(c) = &options.colouring {
        colour(&mut segments, &lines, c);
    }
    // The reference's feed moves go first, so the path is drawn over them.
    let (reference, _) = collect(&options.reference);
    let with_reference = reference.iter().any(|(k, _)| *k == Kind::Feed);
    if with_reference {
        let mut all: Vec<(Kind, Shape)> = reference
            .into_iter()
            .filter(|(k, _)| *k == Kind::Feed)
            .map(|(_, s)| (Kind::Programmed, s))
            .collect();
        all.append(&mut segments);
        segments = all;
    }
    segments.extend(
        options
            .tool_axis
            .iter()
            .filter(|t| t.iter().flatten().all(|c| c.is_finite()))
            .map(|t| (Kind::ToolAxis, Shape::Line(t[0], t[1]))),
    );
    match start {
        Some(start) if !segments.is_empty() => {
            match &options.colouring {
                Some(c) => colour_key(&mut out, width, c),
                None => legend(&mut out, width, with_reference),
            }
            let views = view::layout(width, height, HEADER, options.lathe);
            let (lo, hi) = bounds(&segments, start);
            let mappings = view::fit(&views, lo, hi);
            let tolerance = options.chord_tolerance;
            let classes = options
                .colouring
                .as_ref()
                .map_or(&[][..], |c| &c.classes[..]);
            for (v, m) in views.iter().zip(&mappings) {
                draw_view(&mut out, v, m, &segments, start, tolerance, classes);
            }
        }
        _ => {
            let _ = write!(
                out,
                r##"<text class="no-motion" x="{}" y="{}" text-anchor="middle" font-size="20" fill="#868e96">no motion</text>"##,
                num(width / 2.0),
                num(height / 2.0)
            );
        }
    }
    out.push_str("</svg>\n");
    out
}

/// Gives each motion of `segments` whose source line (`lines`, parallel) has a class that class.
fn colour(segments: &mut [(Kind, Shape)], lines: &[u32], c: &Colouring) {
    for ((kind, _), line) in segments.iter_mut().zip(lines) {
        if let Some(&k) = c.line_class.get(line) {
            *kind = Kind::Class(k, *kind == Kind::Rapid);
        }
    }
}

/// The key of a colouring in the header: its title, then a swatch and label per class.
fn colour_key(out: &mut String, width: f64, c: &Colouring) {
    // About 6.5 px per character at 12 px, a 20 px swatch and a gap.
    let entry = |label: &str| 34.0 + 6.5 * label.chars().count() as f64;
    let total: f64 = 6.5 * c.title.chars().count() as f64
        + 12.0
        + c.classes.iter().map(|(l, _)| entry(l)).sum::<f64>();
    let mut x = (width - 12.0 - total).max(260.0);
    let _ = write!(
        out,
        r##"<g class="legend colour-key" font-size="12" fill="#212529"><text x="{}" y="25" font-weight="bold">{}</text>"##,
        num(x),
        escape(&c.title)
    );
    x += 6.5 * c.title.chars().count() as f64 + 12.0;
    for (label, colour) in &c.classes {
        let _ = write!(
            out,
            r#"<path d="M{} 21H{}" stroke="{}" stroke-width="4"/><text x="{}" y="25">{}</text>"#,
            num(x),
            num(x + 20.0),
            escape(colour),
            num(x + 25.0),
            escape(label)
        );
        x += entry(label);
    }
    out.push_str("</g>");
}

/// Height of the sheet's header band, px.
const HEADER: f64 = 40.0;

/// The key in the header: what the line styles mean.
fn legend(out: &mut String, width: f64, with_reference: bool) {
    let x = width - 330.0;
    if with_reference {
        let _ = write!(
            out,
            r##"<g class="legend-programmed" font-size="13" fill="#212529"><path d="M{} 21H{}" {}/><text x="{}" y="25">programmed</text></g>"##,
            num(x - 150.0),
            num(x - 114.0),
            Kind::Programmed.attributes(),
            num(x - 108.0),
        );
    }
    let _ = write!(
        out,
        concat!(
            r##"<g class="legend" font-size="13" fill="#212529">"##,
            r##"<path d="M{x0} 21H{x1}" {rapid}/><text x="{t0}" y="25">rapid</text>"##,
            r##"<path d="M{x2} 21H{x3}" {feed}/><text x="{t1}" y="25">feed</text>"##,
            r##"<circle cx="{x4}" cy="21" r="4" fill="#2f9e44"/><text x="{t2}" y="25">start</text></g>"##
        ),
        x0 = num(x),
        x1 = num(x + 36.0),
        t0 = num(x + 42.0),
        x2 = num(x + 100.0),
        x3 = num(x + 136.0),
        t1 = num(x + 142.0),
        x4 = num(x + 206.0),
        t2 = num(x + 216.0),
        rapid = Kind::Rapid.attributes(),
        feed = Kind::Feed.attributes(),
    );
}

/// Step 4 and 5 for one view.
fn draw_view(
    out: &mut String,
    v: &View,
    m: &Mapping,
    segments: &[(Kind, Shape)],
    start: Vec3,
    chord_tolerance: f64,
    classes: &[(String, String)],
) {
    let c = v.cell;
    let _ = write!(
        out,
        r##"<g class="view" data-view="{id}" data-scale="{s}"><rect x="{x}" y="{y}" width="{w}" height="{h}" fill="none" stroke="#ced4da"/>"##,
        id = v.id,
        s = m.scale,
        x = num(c.x + 0.5),
        y = num(c.y + 0.5),
        w = num(c.w - 1.0),
        h = num(c.h - 1.0),
    );
    let _ = write!(
        out,
        r##"<text class="view-title" x="{}" y="{}" font-size="14" font-weight="bold" fill="#343a40">{}</text>"##,
        num(c.x + 12.0),
        num(c.y + 19.0),
        escape(v.title)
    );
    let _ = write!(
        out,
        r#"<clipPath id="clip-{id}"><rect x="{x}" y="{y}" width="{w}" height="{h}"/></clipPath><g clip-path="url(#clip-{id})">"#,
        id = v.id,
        x = num(c.x + 1.0),
        y = num(c.y + 1.0),
        w = num(c.w - 2.0),
        h = num(c.h - 2.0),
    );
    draw_path(out, v.projection, m, segments, chord_tolerance, classes);
    let p = m.to_screen(v.projection.project(start));
    let _ = write!(
        out,
        r##"<circle class="start" cx="{}" cy="{}" r="4" fill="#2f9e44"/></g>"##,
        num(p[0]),
        num(p[1])
    );
    arrows(out, v);
    scale_bar(out, v, m.scale);
    out.push_str("</g>");
}

/// Step 4: the path elements of one view.
fn draw_path(
    out: &mut String,
    projection: Projection,
    m: &Mapping,
    segments: &[(Kind, Shape)],
    chord_tolerance: f64,
    classes: &[(String, String)],
) {
    let screen = |p: Vec3| m.to_screen(projection.project(p));
    // Finer than 0.25 px, and than the caller's tolerance when that is smaller.
    let px_tolerance = 0.25 / m.scale;
    let tolerance = if chord_tolerance > 0.0 {
        chord_tolerance.min(px_tolerance)
    } else {
        px_tolerance
    };
    let mut data = PathData::default();
    let mut points = Vec::new();
    for (i, (kind, shape)) in segments.iter().enumerate() {
        data.start_at(screen(shape.start()));
        match shape {
            Shape::Line(_, b) => data.line_to(screen(*b)),
            Shape::Arc(h) => match flat_arc_sweep_flag(h, projection) {
                Some(flag) => {
                    let r = h.start_radius() * m.scale;
                    let pieces = ((h.sweep() / PI) - 1e-9).ceil().max(1.0);
                    let n = pieces as u32;
                    for k in 1..=n {
                        data.arc_to(r, flag, screen(h.point_at(f64::from(k) / pieces)));
                    }
                }
                None => {
                    points.clear();
                    h.tessellate(tolerance, &mut points);
                    for p in &points {
                        data.line_to(screen(*p));
                    }
                }
            },
            Shape::Spline(s) => {
                points.clear();
                Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots)
                    .tessellate(tolerance, &mut points);
                for p in &points {
                    data.line_to(screen(*p));
                }
            }
        }
        let last_of_run = !matches!(segments.get(i + 1), Some((next, _)) if next == kind);
        if last_of_run && !data.is_empty() {
            let attributes = kind.attributes_in(classes);
            let _ = write!(out, r#"<path {attributes} d="{}"/>"#, data.take());
        }
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

/// Direction arrows of the view's axes, bottom left of the cell.
fn arrows(out: &mut String, v: &View) {
    const LEN: f64 = 26.0;
    let arrows = v.projection.arrows();
    // Raise the origin so that an arrow pointing down (the isometric X) keeps its label in the cell.
    let drop = arrows
        .iter()
        .map(|(_, d)| -d[1] * (LEN + 14.0))
        .fold(0.0, f64::max);
    let origin = [v.cell.x + 30.0, v.cell.y + v.cell.h - 12.0 - drop];
    out.push_str(r##"<g class="axes" font-size="12" fill="#343a40">"##);
    for (letter, d) in arrows {
        let tip = [origin[0] + d[0] * LEN, origin[1] - d[1] * LEN];
        let label = [
            origin[0] + d[0] * (LEN + 9.0),
            origin[1] - d[1] * (LEN + 9.0) + 4.0,
        ];
        let _ = write!(
            out,
            r##"<path d="M{} {}L{} {}" stroke="#343a40" stroke-width="1.2" marker-end="url(#arrow)"/><text x="{}" y="{}" text-anchor="middle">{letter}</text>"##,
            num(origin[0]),
            num(origin[1]),
            num(tip[0]),
            num(tip[1]),
            num(label[0]),
            num(label[1]),
        );
    }
    out.push_str("</g>");
}

/// The longest 1, 2 or 5 × 10ⁿ mm that is at most `max_mm`.
fn round_length(max_mm: f64) -> f64 {
    let decade = 10f64.powf(max_mm.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|k| k * decade)
        .find(|&l| l <= max_mm)
        .unwrap_or(decade)
}

/// A length for a label: as many decimals as a 1-2-5 length needs.
fn length_label(mm: f64) -> String {
    let decimals = (-mm.log10().floor()).clamp(0.0, 12.0) as usize;
    format!("{mm:.decimals$} mm")
}

/// Scale bar of a round length, bottom right of the cell.
fn scale_bar(out: &mut String, v: &View, scale: f64) {
    let max_px = (v.plot.w / 3.0).min(160.0);
    let mm = round_length(max_px / scale);
    let px = mm * scale;
    if !(px.is_finite() && px > 0.0) {
        return;
    }
    let right = v.cell.x + v.cell.w - 20.0;
    let y = v.cell.y + v.cell.h - 14.0;
    let left = right - px;
    let _ = write!(
        out,
        r##"<g class="scale-bar" data-mm="{mm}"><path d="M{l} {t}V{y}H{r}V{t}" fill="none" stroke="#343a40" stroke-width="1.2"/><text x="{cx}" y="{ty}" font-size="12" text-anchor="middle" fill="#343a40">{label}</text></g>"##,
        l = num(left),
        r = num(right),
        y = num(y),
        t = num(y - 5.0),
        cx = num((left + right) / 2.0),
        ty = num(y - 8.0),
        label = length_label(mm),
    );
}

#[cfg(test)]
mod tests;
