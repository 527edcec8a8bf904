//! Everything on the sheet that is not the path: the legend, each view's frame and title, the
//! coordinate grid, the dimensioned extents, direction arrows and the scale bar.
//!
//! The grid step is the smallest 1, 2 or 5 × 10ⁿ mm that puts grid lines at least
//! [`GRID_MIN_PX`] apart, so labels never collide; each line is labelled with its coordinate just
//! outside the plot area (below for the horizontal axis, left for the vertical one). The extents
//! are the box of the whole path projected into the view: a dimension line under the plot area
//! and one to its left, each with extension lines up to the box and its length in mm.

use crate::decimate::Budget;
use crate::svg::{escape, num};
use crate::view::{Mapping, Projection, View};
use crate::{Colour, Layer, Style};
use stanok_geom::Vec3;
use std::fmt::Write;

/// Least distance between grid lines, px.
pub(crate) const GRID_MIN_PX: f64 = 56.0;

/// The key in the header: what the line styles mean (only the layers drawn, plus `extra`).
pub(crate) fn legend(out: &mut String, width: f64, drawn: &[bool; 4], extra: &[(String, Colour)]) {
    let mut entries: Vec<(String, String)> = Vec::new();
    for (layer, name) in [
        (Layer::Programmed, "programmed"),
        (Layer::Rapid, "rapid"),
        (Layer::Feed, "feed"),
        (Layer::ToolAxis, "tool axis"),
    ] {
        if drawn[layer as usize] {
            entries.push((Style::plain(layer).attributes(), name.to_string()));
        }
    }
    for (label, colour) in extra {
        entries.push((
            format!(
                r#"class="legend-colour" fill="none" stroke="{}" stroke-width="3""#,
                colour.hex()
            ),
            label.clone(),
        ));
    }
    // Each entry: a 30 px line sample, 6 px gap, the label (about 7 px a character), 18 px space.
    let entry_width = |label: &str| 54.0 + 7.0 * label.chars().count() as f64;
    let total: f64 = entries.iter().map(|(_, l)| entry_width(l)).sum::<f64>() + 60.0;
    let mut x = (width - total - 12.0).max(12.0);
    out.push_str(r##"<g class="legend" font-size="13" fill="#212529">"##);
    for (attributes, label) in &entries {
        let _ = write!(
            out,
            r#"<path d="M{} 21H{}" {attributes}/><text x="{}" y="25">{}</text>"#,
            num(x),
            num(x + 30.0),
            num(x + 36.0),
            escape(label)
        );
        x += entry_width(label);
    }
    let _ = write!(
        out,
        r##"<circle cx="{}" cy="21" r="4" fill="#2f9e44"/><text x="{}" y="25">start</text></g>"##,
        num(x + 4.0),
        num(x + 14.0)
    );
}

/// A line at the foot of the sheet when the path was drawn at the picture's resolution.
pub(crate) fn resolution_note(out: &mut String, budget: &Budget, height: f64) {
    let text = if budget.truncated {
        "the drawing was cut short: the picture cannot hold more of this path".to_string()
    } else if budget.covered > 0 {
        format!(
            "drawn at the picture's resolution: {} moves that would not show were left out",
            budget.covered
        )
    } else {
        return;
    };
    let _ = write!(
        out,
        r##"<text class="resolution-note" x="12" y="{}" font-size="11" fill="#868e96">{}</text>"##,
        num(height - 4.0),
        escape(&text)
    );
}

/// Opens the view's group: frame and title.
pub(crate) fn frame(out: &mut String, v: &View, scale: f64) {
    let c = v.cell;
    let _ = write!(
        out,
        r##"<g class="view" data-view="{id}" data-scale="{s}"><rect x="{x}" y="{y}" width="{w}" height="{h}" fill="none" stroke="#ced4da"/>"##,
        id = v.id,
        s = scale,
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
}

/// The smallest 1, 2 or 5 × 10ⁿ mm that is at least `min_mm`.
pub(crate) fn nice_step(min_mm: f64) -> f64 {
    if !(min_mm.is_finite() && min_mm > 0.0) {
        return 1.0;
    }
    let decade = 10f64.powf(min_mm.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * decade)
        .find(|&s| s >= min_mm * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade)
}

/// A coordinate for a grid label, with the decimals the step needs.
fn coordinate(value: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).clamp(0.0, 9.0) as usize;
    let s = format!("{value:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
}

/// Grid lines over the plot area of an orthographic view, labelled with their coordinates.
pub(crate) fn grid(out: &mut String, v: &View, m: &Mapping) {
    let Projection::Ortho { .. } = v.projection else {
        return;
    };
    let step = nice_step(GRID_MIN_PX / m.scale);
    let p = v.plot;
    let (w0, w1) = (m.to_world([p.x, p.y + p.h]), m.to_world([p.x + p.w, p.y]));
    let mut lines = String::new();
    let mut labels = String::new();
    let range = |a: f64, b: f64| {
        let (first, last) = ((a / step).ceil(), (b / step).floor());
        // At most one line per GRID_MIN_PX of the plot area: bounded whatever the numbers.
        (first as i64..=last as i64)
            .take(200)
            .map(|i| i as f64 * step)
    };
    for x in range(w0[0], w1[0]) {
        let sx = m.to_screen([x, 0.0])[0];
        let _ = write!(lines, "M{} {}V{}", num(sx), num(p.y), num(p.y + p.h));
        let _ = write!(
            labels,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            num(sx),
            num(p.y + p.h + 11.0),
            coordinate(x, step)
        );
    }
    for y in range(w0[1], w1[1]) {
        let sy = m.to_screen([0.0, y])[1];
        let _ = write!(lines, "M{} {}H{}", num(p.x), num(sy), num(p.x + p.w));
        let _ = write!(
            labels,
            r#"<text x="{}" y="{}" text-anchor="end">{}</text>"#,
            num(p.x - 4.0),
            num(sy + 3.5),
            coordinate(y, step)
        );
    }
    let _ = write!(
        out,
        r##"<g class="grid" data-step="{step}"><path d="{lines}" fill="none" stroke="#e9ecef" stroke-width="1"/><g class="grid-label" font-size="10" fill="#868e96">{labels}</g></g>"##,
    );
    // The lathe's spindle axis (X = 0 in the ZX view) as a dash-dot centre line.
    if v.projection == (Projection::Ortho { h: 2, v: 0 }) && w0[1] <= 0.0 && 0.0 <= w1[1] {
        let sy = m.to_screen([0.0, 0.0])[1];
        let _ = write!(
            out,
            r##"<path class="centre-line" d="M{} {}H{}" stroke="#495057" stroke-width="0.8" stroke-dasharray="12 3 2 3"/>"##,
            num(p.x),
            num(sy),
            num(p.x + p.w)
        );
    }
}

/// A length for a dimension: up to three decimals, trailing zeros dropped.
pub(crate) fn extent_label(mm: f64) -> String {
    let s = format!("{mm:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    format!("{s} mm")
}

/// The path's extents in an orthographic view: a dimension line under the plot area (horizontal
/// axis) and one left of it (vertical axis), with extension lines to the box.
pub(crate) fn dimensions(out: &mut String, v: &View, m: &Mapping, lo: Vec3, hi: Vec3) {
    let Projection::Ortho { h, v: vert } = v.projection else {
        return;
    };
    let p = v.plot;
    let (a, b) = (
        m.to_screen([lo[h], lo[vert]]),
        m.to_screen([hi[h], hi[vert]]),
    );
    out.push_str(r##"<g class="dimensions" font-size="11" fill="#343a40" stroke-width="0.8">"##);
    let attrs = r##"stroke="#343a40" marker-start="url(#arrow)" marker-end="url(#arrow)""##;
    let extension = r##"fill="none" stroke="#adb5bd" stroke-dasharray="3 2""##;
    let across = hi[h] - lo[h];
    if across > 1e-9 {
        let y = p.y + p.h + 27.0;
        let _ = write!(
            out,
            r#"<path d="M{x1} {top}V{y2}M{x2} {top}V{y2}" {extension}/><path class="dimension" data-mm="{mm}" d="M{x1} {y}H{x2}" {attrs}/><text x="{tx}" y="{ty}" text-anchor="middle">{label}</text>"#,
            x1 = num(a[0]),
            x2 = num(b[0]),
            top = num(a[1].max(b[1])),
            y2 = num(y + 3.0),
            y = num(y),
            mm = across,
            tx = num((a[0] + b[0]) / 2.0),
            ty = num(y - 4.0),
            label = extent_label(across),
        );
    }
    let up = hi[vert] - lo[vert];
    if up > 1e-9 {
        let x = p.x - 40.0;
        let _ = write!(
            out,
            r#"<path d="M{left} {y1}H{x2}M{left} {y2}H{x2}" {extension}/><path class="dimension" data-mm="{mm}" d="M{x} {y1}V{y2}" {attrs}/><text x="{tx}" y="{ty}" text-anchor="middle" transform="rotate(-90 {tx} {ty})">{label}</text>"#,
            left = num(a[0].min(b[0])),
            x2 = num(x - 3.0),
            y1 = num(a[1]),
            y2 = num(b[1]),
            x = num(x),
            mm = up,
            tx = num(x - 4.0),
            ty = num((a[1] + b[1]) / 2.0),
            label = extent_label(up),
        );
    }
    out.push_str("</g>");
}

/// Direction arrows of the view's axes, bottom left of the cell.
pub(crate) fn arrows(out: &mut String, v: &View) {
    const LEN: f64 = 26.0;
    let arrows = v.projection.arrows();
    // Raise the origin so that an arrow pointing down (the isometric X) keeps its label in the cell.
    let drop = arrows
        .iter()
        .map(|(_, d)| -d[1] * (LEN + 14.0))
        .fold(0.0, f64::max);
    let origin = [v.cell.x + 22.0, v.cell.y + v.cell.h - 12.0 - drop];
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
pub(crate) fn round_length(max_mm: f64) -> f64 {
    let decade = 10f64.powf(max_mm.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|k| k * decade)
        .find(|&l| l <= max_mm)
        .unwrap_or(decade)
}

/// A length for a label: as many decimals as a 1-2-5 length needs.
pub(crate) fn length_label(mm: f64) -> String {
    let decimals = (-mm.log10().floor()).clamp(0.0, 12.0) as usize;
    format!("{mm:.decimals$} mm")
}

/// Scale bar of a round length, bottom right of the cell.
pub(crate) fn scale_bar(out: &mut String, v: &View, scale: f64) {
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
mod tests {
    use super::*;

    #[test]
    fn grid_steps_and_labels() {
        assert_eq!(nice_step(0.7), 1.0);
        assert_eq!(nice_step(1.2), 2.0);
        assert_eq!(nice_step(3.0), 5.0);
        assert_eq!(nice_step(6.0), 10.0);
        assert_eq!(nice_step(0.011), 0.02);
        assert_eq!(coordinate(-0.0, 10.0), "0");
        assert_eq!(coordinate(-20.0, 10.0), "-20");
        assert_eq!(coordinate(0.25, 0.05), "0.25");
        assert_eq!(extent_label(65.0), "65 mm");
        assert_eq!(extent_label(12.3456), "12.346 mm");
    }
}
