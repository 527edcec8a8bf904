//! The panel shows the stock and the cut live, in headless Chromium (issue 25): a program loaded
//! with a stock (the page's stock field, the `--stock` syntax) runs; while it runs the view gets
//! the stock a few times a second with material already removed; at the end the removed volume
//! is the slot's and the rapid's (analytic, within 1 %), the height field shows the slot's floor,
//! and the rapid through the material is an alarm at its line and a red mark labelled with it.
//! Screenshot: `target/tmp/panel/stock.png`.

mod cdp;
mod common;
mod panel;
use panel::*;
use std::time::Duration;

/// A Ø6 flat end mill slots 2 deep along Y20 across the whole 60 mm stock (its rounded ends
/// outside), then a rapid plunges 1 deep at X30 Y10 and runs 10 mm in the material.
const PROGRAM: &str = "G21 G90 G17
T1 M6
S10000 M3
G0 X0 Y20 Z5
G1 Z-2 F600
G1 X60
G0 Z5
G0 X30 Y10
G0 Z-1
G0 X40
G0 Z5
M5
M2
";
/// The lines of the rapid plunge and of the rapid run in the material.
const RAPID_LINE: u64 = 9;
const RAPID_RUN_LINE: u64 = 10;
const STOCK: &str = "box:X0,Y0,Z-10:X60,Y40,Z0";

#[test]
fn the_panel_cuts_the_stock_live_and_marks_a_rapid_in_the_material() {
    let tools = std::env::temp_dir().join(format!("stanok-panel-stock-{}.tbl", std::process::id()));
    std::fs::write(&tools, "T1 P1 Z0 D6 ;flat end mill\n").unwrap();
    let tools_arg = tools.display().to_string();
    let panel = Panel::start("stock", &["--time-scale", "2", "--tools", &tools_arg]);
    let Some(mut b) = open(&panel, "stock") else {
        return;
    };
    set_value(&mut b, "stock", STOCK);
    load_program(&mut b, "slot.ngc", PROGRAM);
    assert_eq!(b.eval("window.panel.loaded.stock"), true);
    // Count the live messages that already show a cut.
    b.eval(
        "(() => { window.liveCuts = 0; const v = window.panel.view, set = v.setStock.bind(v); \
           v.setStock = st => { if (st && !st.done && st.removed_mm3 > 0) window.liveCuts++; set(st); }; })()",
    );
    b.click("#cycle-start");
    wait_state(&mut b, "finished", 120);
    b.wait_until(
        "window.panel.view.stats().stock && window.panel.view.stats().stock.done",
        Duration::from_secs(30),
    );
    let stats = view_stats(&mut b);
    let stock = &stats["stock"];
    assert_eq!(stock["kind"], "mill", "{stats}");
    // 60 × 6 × 2 (the slot) + π·3²·1 + 10 × 6 × 1 (the plunge and the rapid's run).
    let want = 720.0 + std::f64::consts::PI * 9.0 + 60.0;
    let removed = stock["removed_mm3"].as_f64().unwrap();
    assert!(
        (removed - want).abs() / want < 0.01,
        "removed {removed} mm³, want {want}"
    );
    assert!((stock["initial_mm3"].as_f64().unwrap() - 24_000.0).abs() < 1e-6);
    let n = stock["n"].as_array().unwrap();
    let cells = n[0].as_u64().unwrap() * n[1].as_u64().unwrap();
    assert!(cells <= 128 * 128 && cells > 1000, "{stock}");
    assert!(stock["vertices"].as_u64().unwrap() >= 2 * cells);
    // The height field: the slot's floor, the rapid's groove, the untouched top (within the
    // 16-bit quantisation of 10 mm).
    for (x, y, z) in [(30.0, 20.0, -2.0), (35.0, 10.0, -1.0), (30.0, 32.0, 0.0)] {
        let got = b
            .eval(&format!("window.panel.view.stockZ({x}, {y})"))
            .as_f64()
            .unwrap();
        assert!((got - z).abs() < 1e-3, "z at ({x}, {y}) = {got}, want {z}");
    }
    let live = b.eval("window.liveCuts").as_u64().unwrap();
    assert!(live >= 1, "no live message showed a cut before the end");
    // The rapid in the material: an alarm at its line, a red mark labelled with it.
    let alarms = b.eval("document.getElementById('alarms').textContent");
    let alarms = alarms.as_str().unwrap();
    for line in [RAPID_LINE, RAPID_RUN_LINE] {
        assert!(
            alarms.contains(&format!("{line}:1 [stock::rapid_in_material]")),
            "{alarms}"
        );
    }
    assert_eq!(stock["collisions"].as_u64().unwrap(), 2, "{stock}");
    let labels = stats["labels"].as_array().unwrap();
    assert!(
        labels
            .iter()
            .any(|l| l == &serde_json::json!(format!("line {RAPID_LINE} rapid in material"))),
        "{labels:?}"
    );
    // The cut slot did not stop the run, the alarm is a warning.
    assert_eq!(run_state(&mut b), "finished");
    b.click("#view-iso");
    std::thread::sleep(Duration::from_millis(300));
    shot(&mut b, "stock");
    no_page_errors(&mut b);
    let _ = std::fs::remove_file(&tools);
}
