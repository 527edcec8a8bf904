//! The panel runs every dialect (chosen in the selector, or told by the file name) and shows each
//! machine in its view, in headless Chromium:
//! * every dialect: a program typed, the dialect chosen, loaded, run, the DRO at its end;
//! * a lathe (`--machine lathe`): the lathe view (Z right, X up, the spindle centre line) with
//!   the programmed contour beside the tool-centre path of a tool-nose-compensated program;
//! * a 5-axis machine (`--machine 5axis-bc-head`): the tool-axis ticks along a TRAORI program and
//!   the tool drawn along the tool axis at the end;
//! * the view's grid with coordinates, the program's extents with dimensions, the travel box.
//!
//! Screenshots: `target/tmp/panel/{dialect-*,lathe,five-axis,readme}.png` (`readme.png` is the
//! picture in docs/panel.png: examples/demo-plate.nc held in its helical bore).

mod cdp;
mod common;
mod panel;
use common::repo;
use panel::*;
use std::time::Duration;

#[test]
fn every_dialect_runs_from_the_selector() {
    let panel = Panel::start("dialects", &["--time-scale", "0"]);
    let Some(mut b) = open(&panel, "dialects") else {
        return;
    };
    let cases: [(&str, &str, [f64; 3]); 8] = [
        ("axioma", "G0 X10 Y5\nG1 Z-2 F300\nM30\n", [10.0, 5.0, -2.0]),
        (
            "rs274ngc",
            "G21 G90\nG0 X10 Y5\nG1 Z-2 F300\nM2\n",
            [10.0, 5.0, -2.0],
        ),
        (
            "balt",
            "N1 G1 X10 Y5 F300\nN2 G0 Z20\nM30\n",
            [10.0, 5.0, 20.0],
        ),
        (
            "mazatrol",
            "G90 G0 X10 Y5\nG1 Z-2 F300\nM30\n",
            [10.0, 5.0, -2.0],
        ),
        (
            "nc31",
            "N1 G94\nN2 F500\nN3 X15000\nN4 Z15000\n",
            [75.0, 0.0, 150.0],
        ),
        (
            "2p32",
            "N1 G91\nN2 G1 Z-22000 X5000 F300\nN3 M2\n",
            [5.0, 0.0, -22.0],
        ),
        (
            "mc2101",
            "N 015 G01 X + 008000 Y - 006000 F500 LF\nN 016 X - 011000 Y - 002000 LF\n",
            [-30.0, -80.0, 0.0],
        ),
        (
            "gost20999",
            "N1 G1 G90 X12.146 Y90.7 F500\nN2 M2\n",
            [12.146, 90.7, 0.0],
        ),
    ];
    let options = b.eval("[...document.getElementById('dialect').options].map(o => o.value)");
    for (dialect, _, _) in &cases {
        assert!(
            options.as_array().unwrap().iter().any(|o| o == dialect),
            "{dialect} in {options}"
        );
    }
    for (dialect, text, want) in cases {
        b.click("#home-all");
        b.wait_until(
            "document.getElementById('run-state').classList.contains('idle') && \
             document.querySelector('tr[data-axis=\"X\"] .machine').textContent === '0.000'",
            Duration::from_secs(30),
        );
        set_value(&mut b, "dialect", dialect);
        load_program(&mut b, &format!("{dialect}.nc"), text);
        assert_eq!(
            b.eval("document.getElementById('diagnostics').children.length"),
            0,
            "{dialect}"
        );
        b.click("#cycle-start");
        wait_state(&mut b, "finished", 90);
        assert_eq!(
            b.eval("document.getElementById('dialect-used').textContent"),
            dialect
        );
        let got = dro(&mut b);
        for i in 0..3 {
            assert!(
                (got[i] - want[i]).abs() < 0.0005,
                "{dialect}: {got:?} vs {want:?}"
            );
        }
        let lathe = view_stats(&mut b)["lathe"].as_bool().unwrap();
        assert_eq!(lathe, matches!(dialect, "nc31" | "2p32"), "{dialect}");
        if dialect == "nc31" || dialect == "gost20999" {
            shot(&mut b, &format!("dialect-{dialect}"));
        }
    }
    // The file name tells the dialect when the selector says "from the name".
    set_value(&mut b, "dialect", "");
    load_program(&mut b, "part.ngc", "G21 G90\nG0 X1\nM2\n");
    assert_eq!(b.eval("window.panel.loaded.dialect"), "rs274ngc");
    no_page_errors(&mut b);
}

#[test]
fn a_lathe_shows_z_right_x_up_with_the_programmed_contour_beside_the_tool_centre_path() {
    let tools = std::env::temp_dir().join(format!("stanok-panel-lathe-{}.tbl", std::process::id()));
    std::fs::write(&tools, "T1 P1 X0 Z0 D0.8 Q3 ;finishing, nose radius 0.4\n").unwrap();
    let tools_arg = tools.display().to_string();
    let panel = Panel::start(
        "lathe",
        &[
            "--time-scale",
            "4",
            "--machine",
            "lathe",
            "--tools",
            &tools_arg,
        ],
    );
    let Some(mut b) = open(&panel, "lathe") else {
        return;
    };
    load_program(
        &mut b,
        "shaft.ngc",
        "G18 G21 G90\nT1 M6\nG0 X20 Z5\nG42 G1 X10 Z0 F300\nG1 Z-20\nX15 Z-25\nZ-35\nG40 G0 X30\nM2\n",
    );
    let stats = view_stats(&mut b);
    assert_eq!(stats["lathe"], true, "{stats}");
    assert!(stats["programmedVertices"].as_u64().unwrap() > 2, "{stats}");
    assert!(stats["pathVertices"].as_u64().unwrap() > 2, "{stats}");
    // Z right, X up: Z at the screen's right is larger, X at the top is larger.
    let dirs = b.eval(
        "(() => { const v = window.panel.view; v.draw(); const c = v.camera; \
           const right = new v.T.Vector3().setFromMatrixColumn(c.matrix, 0).toArray(); \
           const up = new v.T.Vector3().setFromMatrixColumn(c.matrix, 1).toArray(); \
           return [right, up]; })()",
    );
    let (right, up) = (&dirs[0], &dirs[1]);
    assert!((right[2].as_f64().unwrap() - 1.0).abs() < 1e-9, "{dirs}");
    assert!((up[0].as_f64().unwrap() - 1.0).abs() < 1e-9, "{dirs}");
    assert_eq!(
        b.eval("!!window.panel.view.layers.grid.getObjectByName('centre-line')"),
        true
    );
    b.click("#cycle-start");
    wait_state(&mut b, "finished", 90);
    shot(&mut b, "lathe");
    no_page_errors(&mut b);
    let _ = std::fs::remove_file(&tools);
}

#[test]
fn a_five_axis_program_shows_its_tool_axis() {
    let panel = Panel::start("five", &["--time-scale", "4", "--machine", "5axis-bc-head"]);
    let Some(mut b) = open(&panel, "five") else {
        return;
    };
    set_value(&mut b, "dialect", "axioma");
    load_program(
        &mut b,
        "orient.nc",
        "G0 X0 Y0 Z100 B0 C0\nTRAORI\nG1 X10 Y0 Z50 A3=0 B3=0.6 C3=0.8 F1000\nG1 X40 Y20 Z50\nTRAFOOF\nM30\n",
    );
    let stats = view_stats(&mut b);
    assert!(stats["ticks"].as_u64().unwrap() >= 6, "{stats}");
    b.click("#cycle-start");
    wait_state(&mut b, "finished", 90);
    // The tool is drawn along the tool axis (0, 0.6, 0.8) at the end.
    let axis = view_stats(&mut b)["toolAxis"].clone();
    let a: Vec<f64> = axis
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    for (got, want) in a.iter().zip([0.0, 0.6, 0.8]) {
        assert!((got - want).abs() < 1e-6, "{a:?}");
    }
    let stats = view_stats(&mut b);
    assert_eq!(stats["travelBox"], true);
    assert!(stats["gridStep"].as_f64().unwrap() > 0.0);
    let labels: Vec<String> = stats["labels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap().to_string())
        .collect();
    // The extents, from the start at the origin: X 0…40, Y 0…20, Z 0…100.
    for dim in ["X 40", "Y 20", "Z 100"] {
        assert!(labels.iter().any(|l| l == dim), "{dim} in {labels:?}");
    }
    assert!(
        labels
            .iter()
            .any(|l| l.starts_with('X') && l[1..].parse::<f64>().is_ok()),
        "grid: {labels:?}"
    );
    shot(&mut b, "five-axis");
    no_page_errors(&mut b);
}

#[test]
fn the_readme_picture_shows_demo_plate_in_its_helical_bore() {
    let tools =
        std::env::temp_dir().join(format!("stanok-panel-readme-{}.tbl", std::process::id()));
    std::fs::write(&tools, "T1 P1 Z50 D10 ;10 mm end mill\n").unwrap();
    let tools_arg = tools.display().to_string();
    let panel = Panel::start("readme", &["--time-scale", "4", "--tools", &tools_arg]);
    // The demo selects no tool (the built-in mill keeps no tool table): for the picture the
    // 10 mm end mill of its comment is loaded from the table given to the panel.
    let demo = std::fs::read_to_string(repo("examples/demo-plate.nc")).unwrap();
    let demo = demo.replacen(
        "; a 10 mm end mill is in the spindle (the built-in mill keeps no tool table)",
        "T1 D1 M6 ; the 10 mm end mill",
        1,
    );
    assert!(demo.contains("T1 D1 M6"), "the demo's tool comment moved");
    std::fs::write(panel.programs.join("demo-plate.nc"), demo).unwrap();
    let Some(mut b) = open(&panel, "readme") else {
        return;
    };
    b.wait_until(
        "[...document.getElementById('program-select').options].some(o => o.value === 'demo-plate.nc')",
        Duration::from_secs(30),
    );
    set_value(&mut b, "program-select", "demo-plate.nc");
    b.click("#open");
    b.wait_until(
        "window.panel.loaded && window.panel.loaded.name === 'demo-plate.nc'",
        Duration::from_secs(60),
    );
    b.click("#cycle-start");
    // In the helical bore (line 21, or just past it on a slow host): hold there for the picture.
    b.wait_until(
        "(() => { const s = window.panel.status; \
           return s && (s.line >= 21 || s.run_state === 'finished'); })()",
        Duration::from_secs(120),
    );
    b.click("#feed-hold");
    std::thread::sleep(Duration::from_millis(500));
    // The tool is drawn at its size from the tool table.
    let tool = view_stats(&mut b)["tool"].clone();
    assert_eq!(tool["diameter"], 10.0, "{tool}");
    assert_eq!(tool["length"], 50.0, "{tool}");
    shot(&mut b, "readme");
    no_page_errors(&mut b);
    let _ = std::fs::remove_file(&tools);
}
