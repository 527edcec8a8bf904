//! Issue 19 over the JSON API, through the real server: the DRO is the executing block's, a load
//! during a pause asks first and a load resets the DRO, the manual modes (jog, reference return,
//! touch-off, MDI), every dialect. The browser tests (`stanok/tests/panel_browser.rs`) drive the
//! same through the page.

mod common;
use common::*;
use serde_json::{json, Value};
use std::time::{Duration, Instant};

const LONG: Duration = Duration::from_secs(60);

fn load(server: &Server, name: &str, text: &str) -> Value {
    let (code, body) = server.call("POST", "/api/load", json!({"name": name, "text": text}));
    assert_eq!(code, 200, "{body}");
    body
}

fn start(server: &Server) {
    let (code, body) = server.call("POST", "/api/cycle-start", Value::Null);
    assert_eq!(code, 200, "{body}");
}

fn xyz(s: &Value) -> [f64; 3] {
    [0, 1, 2].map(|i| s["machine_position"][i].as_f64().unwrap())
}

fn work(s: &Value, i: usize) -> f64 {
    s["work_position"][i].as_f64().unwrap()
}

fn paced(tag: &str, scale: f64) -> Server {
    let mut o = options(temp_programs(tag));
    o.time_scale = scale;
    Server::start(o)
}

/// What block `line` of [`CHANGING`] leaves: spindle speed and sense, distance mode, feed,
/// message.
fn expected(line: u64) -> (f64, u64, &'static str, f64, String) {
    let k = line - 2;
    let m = if k % 2 == 1 { 3 } else { 4 };
    let g = if k % 2 == 1 { "G90" } else { "G91" };
    let f = if k % 2 == 1 { 1200.0 } else { 2400.0 };
    (1000.0 * k as f64, m, g, f, format!("block {line}"))
}

/// Spindle, distance mode, feed and message change in every block (lines 3…10).
const CHANGING: &str = "G21 G90 G17 G94\n\
    G0 X0 Y0 Z0\n\
    S1000 M3 G90 G1 X20 F1200 (MSG, block 3)\n\
    S2000 M4 G91 G1 X20 F2400 (MSG, block 4)\n\
    S3000 M3 G90 G1 X60 F1200 (MSG, block 5)\n\
    S4000 M4 G91 G1 X20 F2400 (MSG, block 6)\n\
    S5000 M3 G90 G1 X100 F1200 (MSG, block 7)\n\
    S6000 M4 G91 G1 X20 F2400 (MSG, block 8)\n\
    S7000 M3 G90 G1 X140 F1200 (MSG, block 9)\n\
    S8000 M4 G91 G1 X20 F2400 (MSG, block 10)\n\
    M5\nM2\n";

/// The status never shows the interpreter's read-ahead: every sample taken while a block moves
/// has that block's spindle, G codes, feed and message (with the old panel, line 3 showed the
/// state of the blocks the planner had already read).
#[test]
fn the_dro_shows_the_state_of_the_block_being_executed() {
    let server = paced("executing", 4.0);
    load(&server, "changing.ngc", CHANGING);
    start(&server);
    let mut seen = std::collections::BTreeSet::new();
    let t0 = Instant::now();
    loop {
        let s = server.state();
        let line = s["line"].as_u64().unwrap();
        if s["run_state"] == "running" && (3..=10).contains(&line) && s["feed_actual"] != 0.0 {
            let (rpm, m, g, feed, msg) = expected(line);
            assert_eq!(s["spindles"][0]["rpm"], rpm, "line {line}: {s}");
            assert_eq!(s["spindles"][0]["m"], m, "line {line}");
            let codes: Vec<&str> = s["g_codes"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| c["code"].as_str().unwrap())
                .collect();
            assert!(codes.contains(&g), "line {line}: {codes:?}");
            assert_eq!(s["feed_programmed"], feed, "line {line}");
            assert_eq!(s["message"], msg.as_str(), "line {line}");
            let spindle_m: Vec<&str> = s["m_codes"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| c["code"].as_str().unwrap())
                .collect();
            assert!(
                spindle_m.contains(&format!("M{m}").as_str()),
                "{spindle_m:?}"
            );
            seen.insert(line);
        }
        if s["run_state"] == "finished" {
            break;
        }
        assert!(t0.elapsed() < LONG, "{s}");
        std::thread::sleep(Duration::from_millis(3));
    }
    assert_eq!(seen.len(), 8, "samples of every block: {seen:?}");
    // At the end: the last blocks' state (M5 of line 11).
    let s = server.state();
    assert_eq!(s["spindles"][0]["m"], 5);
    assert_eq!(s["message"], "block 10");
}

/// A load while a program waits at M00 is refused with a notice that stays until acknowledged;
/// the old program goes on with cycle start. "Stop and load" stops it and loads; the DRO then
/// shows the new program's start.
#[test]
fn a_load_during_a_pause_asks_first_and_a_load_resets_the_dro() {
    let server = Server::start(options(temp_programs("pause-load")));
    load(
        &server,
        "first.ngc",
        "G21 G90\nS1200 M3 G1 X10 F3000 (MSG, first)\nM0\nG1 X20\nM2\n",
    );
    start(&server);
    server.wait_for(&["prompt"], LONG);
    let (code, body) = server.call(
        "POST",
        "/api/load",
        json!({"name": "second.ngc", "text": "G21 G91\nG0 Y5\nM2\n"}),
    );
    assert_eq!(code, 409, "{body}");
    assert_eq!(body["confirm"], "stop");
    std::thread::sleep(Duration::from_millis(300));
    let s = server.state();
    assert_eq!(s["run_state"], "prompt");
    assert_eq!(s["program"], "first.ngc");
    assert!(
        s["notice"]
            .as_str()
            .unwrap()
            .contains("second.ngc was not loaded"),
        "{s}"
    );
    // The refused program is not the loaded one.
    assert_eq!(
        server.call("GET", "/api/loaded", Value::Null).1["name"],
        "first.ngc"
    );
    // Stop and load.
    let (code, body) = server.call(
        "POST",
        "/api/load",
        json!({"name": "second.ngc", "text": "G21 G91\nG0 Y5\nM2\n", "stop": true}),
    );
    assert_eq!(code, 200, "{body}");
    let s = server.state();
    assert_eq!(s["run_state"], "idle");
    assert_eq!(s["program"], "second.ngc");
    assert_eq!(s["line"], 0);
    assert_eq!(s["message"], "");
    assert_eq!(s["notice"], Value::Null);
    assert_eq!(
        s["spindles"][0]["m"], 5,
        "the new program's start: spindle off"
    );
    assert_eq!(s["feed_programmed"], 0.0);
    assert_eq!(
        xyz(&s),
        [10.0, 0.0, 0.0],
        "the machine stays where it stopped"
    );
    let codes: Vec<&str> = s["g_codes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["code"].as_str().unwrap())
        .collect();
    assert!(
        codes.contains(&"G90"),
        "power-on modes, not the old run's: {codes:?}"
    );
    // Cycle start runs the new program from where the machine stands.
    start(&server);
    let s = server.wait_for(&["finished"], LONG);
    assert_eq!(xyz(&s), [10.0, 5.0, 0.0]);
    // A notice stays until acknowledged.
    load(&server, "third.ngc", "G21 G90\nG1 X0 F3000\nM0\nM2\n");
    start(&server);
    server.wait_for(&["prompt"], LONG);
    server.call(
        "POST",
        "/api/load",
        json!({"name": "x.ngc", "text": "M2\n"}),
    );
    assert!(server.state()["notice"].is_string());
    server.call("POST", "/api/acknowledge", Value::Null);
    let s = server.wait_for(&["finished"], LONG);
    assert_eq!(s["notice"], Value::Null);
}

#[test]
fn jog_by_increments_and_continuously_within_the_travel() {
    let server = paced("jog", 1.0);
    for (inc, want) in [(1.0, 1.0), (0.1, 1.1), (0.01, 1.11), (0.001, 1.111)] {
        let (code, body) = server.call(
            "POST",
            "/api/jog",
            json!({"axis": "X", "direction": 1, "increment": inc, "speed": 3000}),
        );
        assert_eq!(code, 200, "{body}");
        let s = server.wait_for(&["idle"], LONG);
        assert!((xyz(&s)[0] - want).abs() < 1e-9, "{s}");
    }
    let (code, body) = server.call(
        "POST",
        "/api/jog",
        json!({"axis": "Z", "direction": -1, "increment": 1000, "speed": 3000}),
    );
    assert_eq!(code, 409, "Z travel is ±300: {body}");
    assert!(body["error"]
        .as_str()
        .unwrap()
        .contains("outside its travel"));
    // Continuous: moves while kept alive, brakes on the path when released.
    let (code, _) = server.call(
        "POST",
        "/api/jog",
        json!({"axis": "Y", "direction": -1, "speed": 1200}),
    );
    assert_eq!(code, 200);
    for _ in 0..4 {
        std::thread::sleep(Duration::from_millis(150));
        server.call("POST", "/api/jog/alive", Value::Null);
    }
    assert_eq!(server.state()["run_state"], "jogging");
    server.call("POST", "/api/jog/stop", Value::Null);
    let s = server.wait_for(&["idle"], LONG);
    let y = xyz(&s)[1];
    // 0.6 s at 20 mm/s, give or take the acceleration and the request timing.
    assert!(y < -8.0 && y > -20.0, "{y}");
    std::thread::sleep(Duration::from_millis(200));
    assert_eq!(xyz(&server.state())[1], y, "stands after the jog");
    // A page that stops sending "alive" stops the jog by itself.
    server.call(
        "POST",
        "/api/jog",
        json!({"axis": "Y", "direction": 1, "speed": 1200}),
    );
    let s = server.wait_for(&["idle"], Duration::from_secs(3));
    assert!(xyz(&s)[1] < y + 15.0, "{s}");
}

#[test]
fn reference_return_brings_the_axes_to_their_reference_tool_axis_first() {
    let server = Server::start(options(temp_programs("home")));
    load(&server, "away.ngc", "G21 G90\nG0 X40 Y-30 Z-20\nM2\n");
    start(&server);
    server.wait_for(&["finished"], LONG);
    assert_eq!(server.state()["homed"], json!([false, false, false]));
    let (code, body) = server.call("POST", "/api/home", json!({"axis": "Z"}));
    assert_eq!(code, 200, "{body}");
    let s = server.wait_for(&["idle"], LONG);
    assert_eq!(xyz(&s), [40.0, -30.0, 0.0]);
    assert_eq!(s["homed"], json!([false, false, true]));
    server.home();
    assert_eq!(server.state()["homed"], json!([true, true, true]));
}

#[test]
fn touch_off_sets_the_active_work_offset_and_programs_use_it() {
    let server = Server::start(options(temp_programs("touch")));
    server.call(
        "POST",
        "/api/jog",
        json!({"axis": "X", "direction": 1, "increment": 25, "speed": 5000}),
    );
    server.wait_for(&["idle"], LONG);
    let (code, body) = server.call("POST", "/api/touch-off", json!({"axis": "X", "value": 5}));
    assert_eq!(code, 200, "{body}");
    assert!(
        body["done"].as_str().unwrap().starts_with("G54 X = 20"),
        "{body}"
    );
    let s = server.state();
    assert_eq!(work(&s, 0), 5.0);
    assert_eq!(xyz(&s)[0], 25.0);
    // A program now works in the new G54: X0 is machine X20.
    let body = load(&server, "use.ngc", "G21 G90 G54\nG0 X0 Y0\nM2\n");
    assert_eq!(body["preview"]["final_position"][0], 20.0);
    start(&server);
    let s = server.wait_for(&["finished"], LONG);
    assert_eq!(xyz(&s), [20.0, 0.0, 0.0]);
    assert_eq!(work(&s, 0), 0.0);
}

#[test]
fn mdi_runs_one_block_at_a_time_in_the_machines_current_state() {
    let server = Server::start(options(temp_programs("mdi")));
    let mdi = |text: &str| {
        server.call(
            "POST",
            "/api/mdi",
            json!({"text": text, "dialect": "rs274ngc"}),
        )
    };
    let (code, body) = mdi("G21 G90 G0 X10 Y5");
    assert_eq!(code, 200, "{body}");
    assert_eq!(xyz(&server.wait_for(&["idle"], LONG)), [10.0, 5.0, 0.0]);
    // Modal state carries over: G91 stays, G1 and F too.
    assert_eq!(mdi("G91").0, 200);
    assert_eq!(mdi("G1 X1 F600").0, 200);
    assert_eq!(xyz(&server.wait_for(&["idle"], LONG)), [11.0, 5.0, 0.0]);
    assert_eq!(mdi("Y-2").0, 200);
    assert_eq!(xyz(&server.wait_for(&["idle"], LONG)), [11.0, 3.0, 0.0]);
    // After a jog the next block starts where the machine stands, still incremental.
    server.call(
        "POST",
        "/api/jog",
        json!({"axis": "Z", "direction": 1, "increment": 2, "speed": 3000}),
    );
    server.wait_for(&["idle"], LONG);
    assert_eq!(mdi("X1").0, 200);
    assert_eq!(xyz(&server.wait_for(&["idle"], LONG)), [12.0, 3.0, 2.0]);
    // An error: refused with its diagnostic, nothing moves; two blocks at once are refused.
    let (code, body) = mdi("G1 X5 Q");
    assert_eq!(code, 409, "{body}");
    assert_eq!(body["diagnostics"][0]["column"], 7, "{body}");
    assert_eq!(mdi("G0 X1\nG0 X2").0, 409);
    assert_eq!(xyz(&server.state()), [12.0, 3.0, 2.0]);
    // The state shown is the block's: G91 and the feed.
    let s = server.state();
    assert_eq!(s["feed_programmed"], 600.0);
    // An MDI G10 persists into the stored data that programs use.
    assert_eq!(mdi("G10 L2 P1 X100").0, 200);
    let body = load(&server, "p.ngc", "G21 G90 G54\nG0 X0\nM2\n");
    assert_eq!(body["preview"]["final_position"][0], 100.0);
}

/// Every dialect runs in the panel, told by the request or by the file name.
#[test]
fn every_dialect_runs() {
    let server = Server::start(options(temp_programs("dialects")));
    let cases: [(&str, &str, &str, [f64; 3]); 8] = [
        (
            "axioma",
            "p.nc",
            "G0 X10 Y5\nG1 Z-2 F300\nM30\n",
            [10.0, 5.0, -2.0],
        ),
        (
            "rs274ngc",
            "p.ngc",
            "G21 G90\nG0 X10 Y5\nG1 Z-2 F300\nM2\n",
            [10.0, 5.0, -2.0],
        ),
        (
            "balt",
            "p.nc",
            "N1 G1 X10 Y5 F300\nN2 G0 Z20\nM30\n",
            [10.0, 5.0, 20.0],
        ),
        (
            "mazatrol",
            "p.nc",
            "G90 G0 X10 Y5\nG1 Z-2 F300\nM30\n",
            [10.0, 5.0, -2.0],
        ),
        (
            "nc31",
            "p.nc",
            "N1 G94\nN2 F500\nN3 X15000\nN4 Z15000\n",
            [75.0, 0.0, 150.0],
        ),
        (
            "2p32",
            "p.nc",
            "N1 G91\nN2 G1 Z-22000 X5000 F300\nN3 M2\n",
            [5.0, 0.0, -22.0],
        ),
        (
            "mc2101",
            "p.nc",
            "N 015 G01 X + 008000 Y - 006000 F500 LF\nN 016 X - 011000 Y - 002000 LF\n",
            [-30.0, -80.0, 0.0],
        ),
        (
            "gost20999",
            "p.nc",
            "N1 G1 G90 X12.146 Y90.7 F500\nN2 M2\n",
            [12.146, 90.7, 0.0],
        ),
    ];
    for (dialect, name, text, want) in cases {
        server.home();
        let (code, body) = server.call(
            "POST",
            "/api/load",
            json!({"name": name, "text": text, "dialect": dialect}),
        );
        assert_eq!(code, 200, "{dialect}: {body}");
        assert_eq!(body["dialect"], dialect);
        assert_eq!(body["diagnostics"], json!([]), "{dialect}");
        start(&server);
        let s = server.wait_for(&["finished", "alarm"], LONG);
        assert_eq!(s["run_state"], "finished", "{dialect}: {s}");
        assert_eq!(s["dialect"], dialect);
        let at = xyz(&s);
        for i in 0..3 {
            assert!(
                (at[i] - want[i]).abs() < 1e-9,
                "{dialect}: {at:?} vs {want:?}"
            );
        }
        assert!(!s["g_codes"].as_array().unwrap().is_empty(), "{dialect}");
    }
    // The file name tells the dialect when the request does not.
    let (_, body) = server.call(
        "POST",
        "/api/load",
        json!({"name": "nc31-part.nc", "text": "N1 G94\nN2 F500\nN3 X100\n"}),
    );
    assert_eq!(body["dialect"], "nc31");
    assert_eq!(
        body["preview"]["lathe"], true,
        "NC-31 is a lathe: the lathe view"
    );
    let (code, _) = server.call(
        "POST",
        "/api/load",
        json!({"name": "p.nc", "text": "M30\n", "dialect": "fanuc"}),
    );
    assert_eq!(code, 400);
}
