//! The sheet's choices: single views, the grid and dimensioned extents, and drawing a path of any
//! length within the picture's budget.

use super::*;

#[test]
fn a_single_view_fills_the_sheet() {
    for (choice, id) in [
        (ViewChoice::Xy, "xy"),
        (ViewChoice::Xz, "xz"),
        (ViewChoice::Yz, "yz"),
        (ViewChoice::Iso, "iso"),
        (ViewChoice::Lathe, "zx"),
    ] {
        let options = PlotOptions {
            view: choice,
            ..Default::default()
        };
        let svg = render_svg(&sample_program(), &options);
        assert_well_formed(&svg);
        assert_eq!(svg.matches(r#"class="view""#).count(), 1, "{id}");
        let part = view(&svg, id);
        assert_eq!(paths(part, "feed").len(), 1, "{id}");
        // The cell is the sheet below the header: 1200 wide.
        assert!(part.contains(r#"width="1199""#), "{id}");
    }
    // One view gets a larger scale than the same view in the 2 × 2 grid.
    let one = render_svg(
        &sample_program(),
        &PlotOptions {
            view: ViewChoice::Xy,
            ..Default::default()
        },
    );
    let four = render_svg(&sample_program(), &PlotOptions::default());
    assert!(scale_of(view(&one, "xy")) > 1.8 * scale_of(view(&four, "xy")));
}

/// `data-mm` of the dimension lines of a view (horizontal first).
fn dimensions(part: &str) -> Vec<f64> {
    part.split(r#"class="dimension" data-mm=""#)
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].parse().unwrap())
        .collect()
}

#[test]
fn orthographic_views_dimension_the_extents_on_a_labelled_grid() {
    // The sample's box: X 0…60, Y 0…20, Z −2…5.
    let svg = render_svg(&sample_program(), &PlotOptions::default());
    for (id, expected) in [
        ("xy", [60.0, 20.0]),
        ("xz", [60.0, 7.0]),
        ("yz", [20.0, 7.0]),
    ] {
        let part = view(&svg, id);
        let dims = dimensions(part);
        assert_eq!(dims.len(), 2, "{id}");
        for (got, want) in dims.iter().zip(expected) {
            assert!((got - want).abs() < 1e-9, "{id}: {got} vs {want}");
        }
        assert!(
            part.contains(&format!(">{} mm</text>", expected[0])),
            "{id}"
        );
        // A grid with a 1-2-5 step and its coordinates; 0 is on it.
        let step: f64 = {
            let s = part.split(r#"data-step=""#).nth(1).expect("grid");
            s[..s.find('"').unwrap()].parse().unwrap()
        };
        let mantissa = step / 10f64.powf(step.log10().floor());
        assert!([1.0, 2.0, 5.0].iter().any(|k| (mantissa - k).abs() < 1e-9));
        assert!(step * scale_of(part) >= 56.0 - 1e-9);
        assert!(part.contains(">0</text>"), "{id}");
    }
    // The isometric view has neither.
    let iso = view(&svg, "iso");
    assert!(dimensions(iso).is_empty() && !iso.contains("data-step"));
}

#[test]
fn the_lathe_view_has_a_centre_line_on_the_spindle_axis() {
    let cmds = vec![
        feed(p(10.0, 0.0, 0.0), p(10.0, 0.0, -40.0)),
        feed(p(10.0, 0.0, -40.0), p(0.0, 0.0, -40.0)),
    ];
    let svg = render_svg(
        &cmds,
        &PlotOptions {
            view: ViewChoice::Lathe,
            ..Default::default()
        },
    );
    let part = view(&svg, "zx");
    assert!(part.contains(r#"class="centre-line""#));
    // Z across (40 mm), X up (10 mm).
    assert_eq!(dimensions(part), vec![40.0, 10.0]);
}

/// A zig-zag of `n` lines over a 100 × 100 mm field (a raster finishing pass, 1e-3 mm apart).
fn raster(n: usize) -> impl Iterator<Item = Canon> {
    (0..n).map(move |i| {
        let y = (i as f64) * 100.0 / n as f64;
        let (x0, x1) = if i % 2 == 0 {
            (0.0, 100.0)
        } else {
            (100.0, 0.0)
        };
        Canon::StraightFeed(LineMove {
            start: p(x0, y, 0.0),
            end: p(x1, y + 100.0 / n as f64, 0.0),
            feed: 1000.0,
        })
    })
}

#[test]
fn a_huge_path_is_drawn_at_the_pictures_resolution() {
    let n = 60_000;
    let options = PlotOptions {
        dense_after: 20_000,
        max_path_bytes: 2_000_000,
        ..Default::default()
    };
    let mut extent = Extent::new();
    raster(n).for_each(|c| extent.add(&c));
    let mut sheet = Sheet::new(&options, &extent);
    raster(n).for_each(|c| sheet.draw(&c));
    assert!(sheet.is_dense());
    let svg = sheet.finish();
    assert_well_formed(&svg);
    // 60 000 lines of 100 mm each would be 4 views × 60 000 × ~13 bytes: far more than this, and
    // the cells were enough (nothing was cut short).
    assert!(svg.len() < 1_500_000, "{} bytes", svg.len());
    assert!(!svg.contains("cut short"));
    assert!(svg.contains(r#"class="resolution-note""#));
    // Still the picture of the field: the XY view's feed path spans it.
    let xy = view(&svg, "xy");
    assert!(paths(xy, "feed")[0].len() > 10_000);
    assert_eq!(dimensions(xy), vec![100.0, 100.0]);
}

#[test]
fn the_byte_cap_holds_for_any_picture_size() {
    let options = PlotOptions {
        width: 4000,
        height: 4000,
        max_path_bytes: 300_000,
        dense_after: 10_000,
        ..Default::default()
    };
    let mut extent = Extent::new();
    raster(20_000).for_each(|c| extent.add(&c));
    let mut sheet = Sheet::new(&options, &extent);
    raster(20_000).for_each(|c| sheet.draw(&c));
    let svg = sheet.finish();
    assert_well_formed(&svg);
    assert!(svg.len() < 400_000, "{}", svg.len());
    assert!(svg.contains("cut short"));
}

#[test]
fn colours_passed_with_a_move_give_their_own_paths_and_legend_entries() {
    let red = Colour([0xe0, 0x31, 0x31]);
    let options = PlotOptions {
        legend: vec![("fast".into(), red)],
        ..Default::default()
    };
    let cmds = sample_program();
    let mut extent = Extent::new();
    cmds.iter().for_each(|c| extent.add(&c.value));
    let mut sheet = Sheet::new(&options, &extent);
    for (i, c) in cmds.iter().enumerate() {
        sheet.draw_styled(&c.value, (i % 2 == 0).then_some(red));
    }
    let svg = sheet.finish();
    assert_well_formed(&svg);
    let xy = view(&svg, "xy");
    assert_eq!(paths(xy, "feed").len(), 2);
    assert!(xy.contains(r##"stroke="#e03131""##));
    assert!(svg.contains(">fast</text>"));
}
