//! Structure tests of the SVG sheet: the string is taken apart, not compared byte for byte.

use super::*;
use crate::svg::num;
use stanok_canon::{ArcMove, LengthUnits, LineMove, Plane, Pose, Span};

mod sheets;

fn at(value: Canon) -> Spanned<Canon> {
    Spanned::new(Span::new(0, 0, 1, 1), value)
}

fn p(x: f64, y: f64, z: f64) -> Pose {
    Pose::ZERO.with_xyz([x, y, z])
}

fn init(x: f64, y: f64, z: f64) -> Spanned<Canon> {
    at(Canon::Init {
        position: p(x, y, z),
        units: LengthUnits::Millimetres,
        g5x_index: 1,
        g5x_offset: Pose::ZERO,
        g92_offset: Pose::ZERO,
        xy_rotation: 0.0,
    })
}

fn rapid(a: Pose, b: Pose) -> Spanned<Canon> {
    at(Canon::StraightTraverse(LineMove {
        start: a,
        end: b,
        feed: 0.0,
        law: stanok_canon::FeedLaw::PerMinute,
    }))
}

fn feed(a: Pose, b: Pose) -> Spanned<Canon> {
    at(Canon::StraightFeed(LineMove {
        start: a,
        end: b,
        feed: 500.0,
        law: stanok_canon::FeedLaw::PerMinute,
    }))
}

fn arc(a: Pose, b: Pose, centre: [f64; 3], axis: [f64; 3], turns: u32) -> Spanned<Canon> {
    at(Canon::ArcFeed(ArcMove {
        start: a,
        end: b,
        centre,
        axis,
        turns,
        plane: Plane::XY,
        feed: 500.0,
        law: stanok_canon::FeedLaw::PerMinute,
    }))
}

/// A pocket-like program: rapid in, plunge, a line, a CCW half circle r = 20 in XY, a CW quarter,
/// rapid out.
pub(crate) fn sample_program() -> Vec<Spanned<Canon>> {
    vec![
        init(0.0, 0.0, 0.0),
        rapid(p(0.0, 0.0, 0.0), p(0.0, 0.0, 5.0)),
        rapid(p(0.0, 0.0, 5.0), p(20.0, 0.0, 5.0)),
        feed(p(20.0, 0.0, 5.0), p(20.0, 0.0, -2.0)),
        feed(p(20.0, 0.0, -2.0), p(60.0, 0.0, -2.0)),
        arc(
            p(60.0, 0.0, -2.0),
            p(20.0, 0.0, -2.0),
            [40.0, 0.0, -2.0],
            [0.0, 0.0, 1.0],
            1,
        ),
        arc(
            p(20.0, 0.0, -2.0),
            p(0.0, 20.0, -2.0),
            [0.0, 0.0, -2.0],
            [0.0, 0.0, 1.0],
            1,
        ),
        rapid(p(0.0, 20.0, -2.0), p(0.0, 20.0, 5.0)),
    ]
}

/// A helix: 3 turns of r = 15 about (50, 50) down 12 mm.
pub(crate) fn helix_program() -> Vec<Spanned<Canon>> {
    vec![
        init(0.0, 0.0, 10.0),
        rapid(p(0.0, 0.0, 10.0), p(65.0, 50.0, 0.0)),
        arc(
            p(65.0, 50.0, 0.0),
            p(65.0, 50.0, -12.0),
            [50.0, 50.0, 0.0],
            [0.0, 0.0, -1.0],
            3,
        ),
        feed(p(65.0, 50.0, -12.0), p(50.0, 50.0, -12.0)),
        rapid(p(50.0, 50.0, -12.0), p(50.0, 50.0, 10.0)),
    ]
}

/// Checks that every tag is closed in order (a minimal XML well-formedness test).
fn assert_well_formed(svg: &str) {
    let mut stack: Vec<&str> = Vec::new();
    let mut rest = svg;
    while let Some(open) = rest.find('<') {
        let close = rest[open..].find('>').expect("unclosed tag") + open;
        let tag = &rest[open + 1..close];
        assert!(!tag.contains('<'), "'<' inside a tag: {tag}");
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop(), Some(name), "mismatched </{name}>");
        } else if !tag.ends_with('/') {
            stack.push(tag.split_whitespace().next().unwrap_or(""));
        }
        rest = &rest[close + 1..];
    }
    assert!(stack.is_empty(), "unclosed elements: {stack:?}");
    assert!(
        !svg.contains("NaN") && !svg.contains("inf"),
        "non-finite number"
    );
}

/// The part of the sheet that belongs to view `id`.
fn view<'a>(svg: &'a str, id: &str) -> &'a str {
    let start = svg
        .find(&format!(r#"data-view="{id}""#))
        .expect("view present");
    let end = svg[start + 1..]
        .find(r#"data-view=""#)
        .map_or(svg.len(), |i| start + 1 + i);
    &svg[start..end]
}

/// px per mm of a view, from its `data-scale`.
fn scale_of(view: &str) -> f64 {
    let s = view.split(r#"data-scale=""#).nth(1).unwrap();
    s[..s.find('"').unwrap()].parse().unwrap()
}

/// The `d` attributes of the paths of one class in `part`.
fn paths<'a>(part: &'a str, class: &str) -> Vec<&'a str> {
    part.split(&format!(r#"<path class="{class}""#))
        .skip(1)
        .map(|s| {
            let d = &s[s.find(r#" d=""#).unwrap() + 4..];
            &d[..d.find('"').unwrap()]
        })
        .collect()
}

#[test]
fn sheet_has_four_views_with_paths_by_class() {
    let svg = render_svg(&sample_program(), &PlotOptions::default());
    assert_well_formed(&svg);
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    for (id, title) in [
        ("xy", "XY (top)"),
        ("xz", "XZ (front)"),
        ("yz", "YZ (side)"),
        ("iso", "isometric"),
    ] {
        let part = view(&svg, id);
        assert!(part.contains(&format!(">{title}</text>")), "{id} title");
        // One path per layer and view; the rapids jump (M) between their two runs.
        assert_eq!(paths(part, "rapid").len(), 1, "{id}");
        if id != "xy" {
            // Seen from above, the first and last rapids are points: only the second one shows.
            assert_eq!(paths(part, "rapid")[0].matches('M').count(), 2, "{id}");
        }
        assert_eq!(paths(part, "feed").len(), 1, "{id}");
        assert_eq!(part.matches(r#"class="start""#).count(), 1);
        assert_eq!(part.matches(r#"class="scale-bar""#).count(), 1);
        assert!(part.contains("marker-end=\"url(#arrow)\""));
    }
    // Rapids are dashed, feeds are not.
    let elements = |class: &str| -> Vec<String> {
        svg.split(&format!(r#"<path class="{class}""#))
            .skip(1)
            .map(|s| s[..s.find("/>").unwrap()].to_string())
            .collect()
    };
    assert!(elements("rapid")
        .iter()
        .all(|e| e.contains("stroke-dasharray")));
    assert!(elements("feed")
        .iter()
        .all(|e| !e.contains("stroke-dasharray")));
    // One path per view (the legend's samples put `d` first).
    assert_eq!(elements("rapid").len(), 4);
    assert_eq!(elements("feed").len(), 4);
}

#[test]
fn planar_arcs_are_true_arcs_in_their_plane_only() {
    let svg = render_svg(&sample_program(), &PlotOptions::default());
    let xy = view(&svg, "xy");
    let feed = paths(xy, "feed")[0];
    let scale = scale_of(xy);
    // Half circle r = 20 (one piece) and quarter r = 20 (one piece), both CCW about +Z, which is
    // counter-clockwise on screen: sweep flag 0.
    let r = num(20.0 * scale);
    let arcs: Vec<&str> = feed.split('A').skip(1).collect();
    assert_eq!(arcs.len(), 2, "{feed}");
    for a in arcs {
        assert!(a.starts_with(&format!("{r} {r} 0 0 0 ")), "{a}");
    }
    // In the front and side views the XY arcs are edge-on: polylines, no A.
    for id in ["xz", "yz", "iso"] {
        let part = view(&svg, id);
        assert!(!paths(part, "feed")[0].contains('A'), "{id}");
    }
}

#[test]
fn the_orthographic_views_share_one_scale() {
    let svg = render_svg(&sample_program(), &PlotOptions::default());
    let s = scale_of(view(&svg, "xy"));
    assert_eq!(s, scale_of(view(&svg, "xz")));
    assert_eq!(s, scale_of(view(&svg, "yz")));
    assert!(s > 0.0);
    // Scale bars show a 1-2-5 length and it is labelled in mm.
    let label = view(&svg, "xy")
        .split(r#"class="scale-bar" data-mm=""#)
        .nth(1)
        .unwrap();
    let mm: f64 = label[..label.find('"').unwrap()].parse().unwrap();
    let mantissa = mm / 10f64.powf(mm.log10().floor());
    assert!(
        [1.0, 2.0, 5.0].iter().any(|k| (mantissa - k).abs() < 1e-9),
        "{mm}"
    );
}

#[test]
fn clockwise_arcs_get_sweep_flag_1_and_long_arcs_are_split() {
    // A clockwise full circle r = 10 about (10, 0): 360° → two 180° pieces, flag 1.
    let cmds = vec![
        init(0.0, 0.0, 0.0),
        arc(
            p(0.0, 0.0, 0.0),
            p(0.0, 0.0, 0.0),
            [10.0, 0.0, 0.0],
            [0.0, 0.0, -1.0],
            1,
        ),
    ];
    let svg = render_svg(&cmds, &PlotOptions::default());
    assert_well_formed(&svg);
    let feed = paths(view(&svg, "xy"), "feed")[0];
    let pieces: Vec<&str> = feed.split('A').skip(1).collect();
    assert_eq!(pieces.len(), 2, "{feed}");
    assert!(pieces.iter().all(|a| a.contains(" 0 0 1 ")), "{feed}");
    // A ZX arc seen in the XZ view: axis +Y points away from the front viewer (normal −Y), so a
    // counter-clockwise arc about +Y looks clockwise: flag 1.
    let zx = vec![arc(
        p(10.0, 0.0, 0.0),
        p(0.0, 0.0, 10.0),
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        1,
    )];
    let svg = render_svg(&zx, &PlotOptions::default());
    let feed = paths(view(&svg, "xz"), "feed")[0];
    assert!(feed.contains(" 0 0 1 "), "{feed}");
    assert!(!paths(view(&svg, "xy"), "feed")[0].contains('A'));
}

#[test]
fn helices_are_tessellated_within_a_quarter_pixel() {
    let svg = render_svg(&helix_program(), &PlotOptions::default());
    assert_well_formed(&svg);
    let xy = view(&svg, "xy");
    let feed = paths(xy, "feed")[0];
    assert!(!feed.contains('A'), "a helix is no planar arc");
    // Every polyline vertex of the helix lies on the circle r = 15 about (50, 50) in XY: check the
    // radius of each vertex in px against 15 mm × scale (to 0.25 px + rounding).
    let scale = scale_of(xy);
    let pts: Vec<[f64; 2]> = feed
        .split(['M', 'L'])
        .filter(|s| !s.is_empty())
        .map(|s| {
            let mut it = s.split(' ').map(|n| n.parse::<f64>().unwrap());
            [it.next().unwrap(), it.next().unwrap()]
        })
        .collect();
    // The helix's first vertex is its start (65, 50): the centre is 15 mm to its left on screen.
    let centre = [pts[0][0] - 15.0 * scale, pts[0][1]];
    let helix_pts = &pts[..pts.len() - 1]; // the last vertex is the final line's end
    assert!(helix_pts.len() > 100, "{}", helix_pts.len());
    for q in helix_pts {
        let r = (q[0] - centre[0]).hypot(q[1] - centre[1]);
        assert!(
            (r - 15.0 * scale).abs() < 0.02,
            "vertex off the circle by {}",
            r - 15.0 * scale
        );
    }
    // Chord error: neighbouring vertices are close enough that the sagitta is ≤ 0.25 px.
    let rs = 15.0 * scale;
    for w in helix_pts.windows(2) {
        let chord = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        let sagitta = rs - (rs * rs - chord * chord / 4.0).max(0.0).sqrt();
        assert!(sagitta <= 0.25 + 0.02, "sagitta {sagitta} px");
    }
}

#[test]
fn empty_program_says_no_motion() {
    for cmds in [vec![], vec![init(1.0, 2.0, 3.0)]] {
        let svg = render_svg(&cmds, &PlotOptions::default());
        assert_well_formed(&svg);
        assert!(svg.contains(">no motion</text>"));
        assert!(!svg.contains("data-view"));
    }
}

#[test]
fn text_is_escaped_and_bad_numbers_are_dropped() {
    let options = PlotOptions {
        title: "<a&b> \"q\"".into(),
        width: 10, // raised to the minimum
        height: 10,
        chord_tolerance: f64::NAN,
        ..Default::default()
    };
    let mut cmds = sample_program();
    cmds.push(feed(p(0.0, 20.0, 5.0), p(f64::NAN, 0.0, 0.0)));
    cmds.push(arc(
        p(0.0, 20.0, 5.0),
        p(0.0, 20.0, 5.0),
        [f64::INFINITY, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        1,
    ));
    let mut extent = Extent::new();
    cmds.iter().for_each(|c| extent.add(&c.value));
    // A tick with a NaN end is dropped like a bad move.
    extent.add_tick([0.0; 3], [f64::NAN, 0.0, 0.0]);
    let mut sheet = Sheet::new(&options, &extent);
    cmds.iter().for_each(|c| sheet.draw(&c.value));
    sheet.draw_tick([0.0; 3], [f64::NAN, 0.0, 0.0]);
    let svg = sheet.finish();
    assert_well_formed(&svg);
    assert!(!svg.contains("tool-axis"));
    assert!(svg.contains("&lt;a&amp;b&gt; &quot;q&quot;"));
    assert!(svg.contains(r#"width="320" height="240""#));
}

#[test]
fn a_single_point_motion_still_draws() {
    // A zero-length feed: the box has no size; the default scale applies.
    let cmds = vec![feed(p(5.0, 5.0, 5.0), p(5.0, 5.0, 5.0))];
    let svg = render_svg(&cmds, &PlotOptions::default());
    assert_well_formed(&svg);
    assert_eq!(scale_of(view(&svg, "xy")), 10.0);
}

#[test]
fn round_lengths_and_labels() {
    use crate::decor::{length_label, round_length};
    assert_eq!(round_length(7.3), 5.0);
    assert_eq!(round_length(0.031), 0.02);
    assert_eq!(round_length(100.0), 100.0);
    assert_eq!(round_length(199.0), 100.0);
    assert_eq!(length_label(0.5), "0.5 mm");
    assert_eq!(length_label(0.02), "0.02 mm");
    assert_eq!(length_label(200.0), "200 mm");
}

/// The rational quadratic NURBS circle of radius 20 about (50, 50) (AxiOMA example 5.16's form).
fn nurbs_circle_program() -> Vec<Spanned<Canon>> {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let c = |x: f64, y: f64| [50.0 + 20.0 * x, 50.0 + 20.0 * y, 0.0];
    vec![
        init(70.0, 50.0, 0.0),
        at(Canon::SplineFeed(Box::new(stanok_canon::SplineMove {
            start: p(70.0, 50.0, 0.0),
            end: p(70.0, 50.0, 0.0),
            degree: 2,
            control_points: vec![
                c(1.0, 0.0),
                c(1.0, 1.0),
                c(0.0, 1.0),
                c(-1.0, 1.0),
                c(-1.0, 0.0),
                c(-1.0, -1.0),
                c(0.0, -1.0),
                c(1.0, -1.0),
                c(1.0, 0.0),
            ],
            weights: vec![1.0, w, 1.0, w, 1.0, w, 1.0, w, 1.0],
            knots: vec![
                0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
            ],
            plane: Plane::XY,
            feed: 1000.0,
            law: stanok_canon::FeedLaw::PerMinute,
        }))),
    ]
}

#[test]
fn splines_are_drawn_as_curves_within_a_quarter_pixel() {
    let svg = render_svg(&nurbs_circle_program(), &PlotOptions::default());
    assert_well_formed(&svg);
    let xy = view(&svg, "xy");
    let feed = paths(xy, "feed")[0];
    let scale = scale_of(xy);
    let pts: Vec<[f64; 2]> = feed
        .split(['M', 'L'])
        .filter(|s| !s.is_empty())
        .map(|s| {
            let mut it = s.split(' ').map(|n| n.parse::<f64>().unwrap());
            [it.next().unwrap(), it.next().unwrap()]
        })
        .collect();
    assert!(
        pts.len() > 50,
        "a circle, not its control polygon: {}",
        pts.len()
    );
    // Every vertex on the circle r = 20 (the first vertex is (70, 50): the centre is 20 mm left).
    let centre = [pts[0][0] - 20.0 * scale, pts[0][1]];
    let rs = 20.0 * scale;
    for q in &pts {
        let r = (q[0] - centre[0]).hypot(q[1] - centre[1]);
        assert!(
            (r - rs).abs() < 0.02,
            "vertex off the circle by {} px",
            r - rs
        );
    }
    for w in pts.windows(2) {
        let chord = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        let sagitta = rs - (rs * rs - chord * chord / 4.0).max(0.0).sqrt();
        assert!(sagitta <= 0.25 + 0.02, "sagitta {sagitta} px");
    }
    // The box is the circle's, not the control polygon's (whose corners are 20·√2 out).
    let mut extent = Extent::new();
    nurbs_circle_program()
        .iter()
        .for_each(|c| extent.add(&c.value));
    let (lo, hi) = extent.bounds().unwrap();
    assert!(
        (lo[0] - 30.0).abs() < 1e-3 && (hi[1] - 70.0).abs() < 1e-3,
        "{lo:?} {hi:?}"
    );
}

#[test]
fn a_reference_is_drawn_under_the_path_in_its_own_class() {
    let cmds = sample_program();
    let plain = render_svg(&cmds, &PlotOptions::default());
    assert!(!plain.contains("programmed"));
    // The reference: the same square 1 mm inside.
    let reference = [
        init(1.0, 1.0, 0.0),
        feed(p(1.0, 1.0, 0.0), p(9.0, 1.0, 0.0)),
        rapid(p(9.0, 1.0, 0.0), p(9.0, 9.0, 0.0)),
    ];
    let mut extent = Extent::new();
    cmds.iter().for_each(|c| extent.add(&c.value));
    reference
        .iter()
        .for_each(|c| extent.add_reference(&c.value));
    let mut sheet = Sheet::new(&PlotOptions::default(), &extent);
    // The path first, the reference after: the sheet still draws the reference underneath.
    cmds.iter().for_each(|c| sheet.draw(&c.value));
    reference
        .iter()
        .for_each(|c| sheet.draw_reference(&c.value));
    let svg = sheet.finish();
    assert_well_formed(&svg);
    // Only the reference's feed move: once per view where it is not edge-on (YZ), and before
    // the path's own feed moves.
    assert_eq!(
        svg.matches(r#"class="programmed""#).count(),
        3 + 1,
        "XY, XZ, iso + legend"
    );
    let xy = view(&svg, "xy");
    assert!(xy.find(r#"class="programmed""#).unwrap() < xy.find(r#"class="feed""#).unwrap());
}

#[test]
fn lathe_sheet_shows_z_right_and_x_up() {
    // A turning move: Z from 0 to −40 at radius 10, then a face out to radius 30.
    let cmds = vec![
        feed(p(10.0, 0.0, 0.0), p(10.0, 0.0, -40.0)),
        feed(p(10.0, 0.0, -40.0), p(30.0, 0.0, -40.0)),
    ];
    let lathe = PlotOptions {
        lathe: true,
        ..Default::default()
    };
    let svg = render_svg(&cmds, &lathe);
    assert!(svg.contains(r#"data-view="zx""#) && !svg.contains(r#"data-view="xz""#));
    assert!(svg.contains("ZX (lathe: Z right, X radius up)"));
    let mill = render_svg(&cmds, &PlotOptions::default());
    assert!(mill.contains(r#"data-view="xz""#) && !mill.contains(r#"data-view="zx""#));
}
