//! The stock beside a panel run (`stock.rs`), through the real server: a stock given at load is
//! cut by the run, and a rapid through it is a warning at its line in the alarm list (the line,
//! not the tag the panel's commands carry through the machine), the run
//! finishing; the corrected program has none; a stock that does not parse is refused at load.
//! (The live view of the cut is tested in headless Chromium: `stanok/tests/panel_stock_browser.rs`.)

mod common;
use common::*;
use serde_json::{json, Value};
use stanok_canon::setup::{Tool, ToolEdge};
use std::time::Duration;

const STOCK: &str = "box:X0,Y0,Z-10:X60,Y40,Z0";

fn program(rapid_z: f64) -> String {
    format!(
        "G21 G90 G17\nT1 M6\nS10000 M3\nG0 X0 Y20 Z5\nG1 Z-2 F600\nG1 X60\nG0 Z5\n\
         G0 X30 Y10\nG0 Z{rapid_z}\nG0 X40\nG0 Z5\nM5\nM2\n"
    )
}

fn server(tag: &str) -> Server {
    let mut o = options(temp_programs(tag));
    o.machine.control.tools.tools.insert(
        1,
        Tool {
            number: 1,
            edges: vec![ToolEdge {
                radius: 3.0,
                ..Default::default()
            }],
            ..Default::default()
        },
    );
    Server::start(o)
}

fn stock_alarms(s: &Value) -> Vec<Value> {
    s["alarms"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|a| a["code"].as_str().unwrap().starts_with("stock::"))
        .cloned()
        .collect()
}

fn run(srv: &Server, text: &str, stock: Option<&str>) -> Value {
    let mut body = json!({ "name": "slot.ngc", "text": text });
    if let Some(s) = stock {
        body["stock"] = json!(s);
    }
    let (code, loaded) = srv.call("POST", "/api/load", body);
    assert_eq!(code, 200, "{loaded}");
    assert_eq!(loaded["stock"], stock.is_some(), "{loaded}");
    let (code, out) = srv.call("POST", "/api/cycle-start", Value::Null);
    assert_eq!(code, 200, "{out}");
    srv.wait_for(&["finished", "alarm", "stopped"], Duration::from_secs(120))
}

#[test]
fn a_rapid_through_the_stock_is_a_warning_at_its_line_and_the_run_finishes() {
    let srv = server("stock-rapid");
    let s = run(&srv, &program(-1.0), Some(STOCK));
    assert_eq!(s["run_state"], "finished", "{s}");
    let alarms = stock_alarms(&s);
    // The plunge (line 9) and the run (line 10) both go through the material.
    assert_eq!(alarms.len(), 2, "{alarms:?}");
    for (a, line) in alarms.iter().zip([9, 10]) {
        assert_eq!(a["code"], "stock::rapid_in_material", "{a}");
        assert_eq!(a["line"], line, "{a}");
        assert_eq!(a["severity"], "warning", "{a}");
    }
    // The corrected program (the rapid above the stock) cuts the slot without an alarm.
    srv.home();
    let s = run(&srv, &program(1.0), Some(STOCK));
    assert_eq!(s["run_state"], "finished", "{s}");
    assert!(stock_alarms(&s).is_empty(), "{s}");
    // Without a stock nothing is checked.
    srv.home();
    let s = run(&srv, &program(-1.0), None);
    assert!(stock_alarms(&s).is_empty(), "{s}");
}

#[test]
fn a_stock_that_does_not_parse_is_refused_at_load() {
    let srv = server("stock-bad");
    let (code, out) = srv.call(
        "POST",
        "/api/load",
        json!({ "name": "a.ngc", "text": "G0 X1\nM2\n", "stock": "box:X0,Y0" }),
    );
    assert_eq!(code, 400, "{out}");
    assert!(
        out["error"].as_str().unwrap().starts_with("stock:"),
        "{out}"
    );
}
