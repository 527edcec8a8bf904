//! The run controls over the JSON API: real-time pacing (with clients that never read their
//! WebSocket), feed hold and resume, stop, single block, M00/M01 with the optional-stop switch,
//! operator messages, feed override (before a run, and on the block being executed: 10 % within
//! 50 ms of machine time, 0 % standing on the path, 100 % resuming).

mod common;
use common::*;
use serde_json::{json, Value};
use std::io::Write;
use std::net::TcpStream;
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

fn paced(scale: f64) -> Server {
    let mut o = options(temp_programs(&format!("paced-{scale}")));
    o.time_scale = scale;
    Server::start(o)
}

#[test]
fn runs_in_real_time_and_at_the_time_scale_whatever_the_clients_do() {
    let server = paced(1.0);
    // Three clients that open the WebSocket and never read it.
    let _silent: Vec<TcpStream> = (0..3)
        .map(|_| {
            let mut s = TcpStream::connect(server.addr).unwrap();
            write!(
                s,
                "GET /ws HTTP/1.1\r\nHost: {}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
                 Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n",
                server.addr
            )
            .unwrap();
            s
        })
        .collect();
    load(&server, "line.ngc", "G21 G90\nG1 X60 F3000\nM2\n");
    let t0 = Instant::now();
    start(&server);
    let s = server.wait_for(&["finished"], LONG);
    let wall = t0.elapsed().as_secs_f64();
    let cycle = s["cycle_time_s"].as_f64().unwrap();
    // 60 mm at 50 mm/s plus acceleration: a little over 1.2 s of machine time.
    assert!(cycle > 1.2 && cycle < 1.4, "{cycle}");
    assert!(
        wall >= 0.97 * cycle && wall < cycle + 0.5,
        "wall {wall} s for {cycle} s"
    );
    assert_eq!(xyz(&s), [60.0, 0.0, 0.0]);

    let fast = paced(4.0);
    load(&fast, "line.ngc", "G21 G90\nG1 X60 F3000\nM2\n");
    let t0 = Instant::now();
    start(&fast);
    fast.wait_for(&["finished"], LONG);
    let wall = t0.elapsed().as_secs_f64();
    assert!(
        wall >= 0.97 * cycle / 4.0 && wall < cycle / 4.0 + 0.5,
        "wall {wall} s at ×4"
    );
}

#[test]
fn feed_hold_stands_still_and_cycle_start_resumes_to_the_end() {
    let server = paced(2.0);
    load(&server, "line.ngc", "G21 G90\nG1 X100 F3000\nM2\n");
    start(&server);
    let t0 = Instant::now();
    while server.state()["machine_position"][0].as_f64().unwrap() < 20.0 {
        assert!(t0.elapsed() < LONG);
        std::thread::sleep(Duration::from_millis(5));
    }
    server.call("POST", "/api/feed-hold", Value::Null);
    // Braking from 50 mm/s at 1000 mm/s² takes 0.05 s of machine time.
    std::thread::sleep(Duration::from_millis(200));
    let a = server.state();
    assert_eq!(a["held"], true);
    std::thread::sleep(Duration::from_millis(300));
    let b = server.state();
    assert_eq!(xyz(&a), xyz(&b), "moved while held");
    assert!(xyz(&b)[0] > 20.0 && xyz(&b)[0] < 100.0);
    assert_eq!(b["feed_actual"], 0.0);
    assert_eq!(b["run_state"], "running");
    let (_, r) = server.call("POST", "/api/cycle-start", Value::Null);
    assert_eq!(r["action"], "resume");
    let s = server.wait_for(&["finished"], LONG);
    assert_eq!(xyz(&s), [100.0, 0.0, 0.0]);
    // The standstill is part of the machine time: longer than the 2.1 s the move needs.
    assert!(s["cycle_time_s"].as_f64().unwrap() > 2.5, "{s}");
}

#[test]
fn stop_brakes_on_the_path_and_leaves_the_machine_where_it_stopped() {
    let server = paced(2.0);
    load(&server, "line.ngc", "G21 G90\nG1 X100 F3000\nG1 Y100\nM2\n");
    start(&server);
    let t0 = Instant::now();
    while server.state()["machine_position"][0].as_f64().unwrap() < 30.0 {
        assert!(t0.elapsed() < LONG);
        std::thread::sleep(Duration::from_millis(5));
    }
    server.call("POST", "/api/stop", Value::Null);
    let s = server.wait_for(&["stopped"], LONG);
    let at = xyz(&s);
    assert!(at[0] > 30.0 && at[0] < 100.0 && at[1] == 0.0, "{at:?}");
    std::thread::sleep(Duration::from_millis(200));
    assert_eq!(xyz(&server.state()), at);
    assert_eq!(s["alarms"], json!([]));
    assert_eq!(s["final_position"], Value::Null);
}

#[test]
fn single_block_stops_after_every_block_that_moves() {
    let server = Server::start(options(temp_programs("single")));
    load(
        &server,
        "steps.ngc",
        "G21 G90\nG0 X10\nS1000 M3\nG1 Y10 F2000\nG1 X0\nM2\n",
    );
    server.call("POST", "/api/switches", json!({"single_block": true}));
    start(&server);
    let mut stops = Vec::new();
    loop {
        let s = server.wait_for(&["block_end", "finished"], LONG);
        if s["run_state"] == "finished" {
            assert_eq!(xyz(&s), [0.0, 10.0, 0.0]);
            break;
        }
        stops.push(xyz(&s));
        std::thread::sleep(Duration::from_millis(50));
        assert_eq!(
            server.state()["run_state"],
            "block_end",
            "went on by itself"
        );
        let (_, r) = server.call("POST", "/api/cycle-start", Value::Null);
        assert_eq!(r["action"], "continue");
        // Wait until it left this block end (unpaced, it may already stand at the next one).
        let here = *stops.last().unwrap();
        let t0 = Instant::now();
        loop {
            let s = server.state();
            if s["run_state"] != "block_end" || xyz(&s) != here {
                break;
            }
            assert!(t0.elapsed() < LONG, "cycle start did not continue");
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    assert_eq!(
        stops,
        vec![[10.0, 0.0, 0.0], [10.0, 10.0, 0.0], [0.0, 10.0, 0.0]],
        "a stop at the end of every block that moved (not after S1000 M3)"
    );
}

#[test]
fn m00_always_and_m01_only_with_the_switch_wait_for_acknowledge() {
    let server = Server::start(options(temp_programs("m01")));
    let text = "G21 G90\nG0 X5\nM1\nG0 X6\nM0\nG0 X7\nM2\n";
    load(&server, "stops.ngc", text);
    // Optional stop on (the default): M01 and M00 both prompt.
    start(&server);
    let s = server.wait_for(&["prompt"], LONG);
    assert!(
        s["prompt"].as_str().unwrap().starts_with("line 3: M01"),
        "{s}"
    );
    assert_eq!(xyz(&s), [5.0, 0.0, 0.0]);
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(server.state()["run_state"], "prompt");
    server.call("POST", "/api/acknowledge", Value::Null);
    let t0 = Instant::now();
    let s = loop {
        let s = server.state();
        if s["run_state"] == "prompt" && s["line"] == 5 {
            break s;
        }
        assert!(t0.elapsed() < LONG, "{s}");
        std::thread::sleep(Duration::from_millis(2));
    };
    assert!(s["prompt"].as_str().unwrap().starts_with("line 5: M00"));
    assert_eq!(xyz(&s), [6.0, 0.0, 0.0]);
    server.call("POST", "/api/acknowledge", Value::Null);
    assert_eq!(xyz(&server.wait_for(&["finished"], LONG)), [7.0, 0.0, 0.0]);
    // Optional stop off: only M00 prompts.
    server.call("POST", "/api/switches", json!({"optional_stop": false}));
    start(&server);
    let s = server.wait_for(&["prompt", "finished"], LONG);
    assert!(
        s["prompt"].as_str().unwrap().starts_with("line 5: M00"),
        "{s}"
    );
    server.call("POST", "/api/acknowledge", Value::Null);
    server.wait_for(&["finished"], LONG);
}

#[test]
fn operator_messages_show_until_acknowledged() {
    let server = Server::start(options(temp_programs("msg")));
    load(
        &server,
        "msg.ngc",
        "G21 G90\n(MSG, check the clamps)\nG0 X5\nM2\n",
    );
    start(&server);
    let s = server.wait_for(&["finished"], LONG);
    assert_eq!(s["message"], "check the clamps");
    let (_, r) = server.call("POST", "/api/acknowledge", Value::Null);
    assert_eq!(r["acknowledged"], "message");
    assert_eq!(server.state()["message"], "");
}

#[test]
fn feed_override_scales_the_feed_moves() {
    let server = Server::start(options(temp_programs("override")));
    load(&server, "slow.ngc", "G21 G90\nG1 X100 F600\nM2\n");
    start(&server);
    let full = server.wait_for(&["finished"], LONG)["cycle_time_s"]
        .as_f64()
        .unwrap();
    let (code, _) = server.call("POST", "/api/override", json!({"feed": 50}));
    assert_eq!(code, 200);
    server.home();
    start(&server);
    let s = server.wait_for(&["finished"], LONG);
    let half = s["cycle_time_s"].as_f64().unwrap();
    // 100 mm at 10 mm/s = 10 s; at 50 %, 20 s (acceleration is a few ms).
    assert!(
        (full - 10.0).abs() < 0.05 && (half - 20.0).abs() < 0.05,
        "{full} {half}"
    );
    assert_eq!(s["feed_override"], 50);
    assert_eq!(
        server.call("POST", "/api/override", json!({"feed": 250})).0,
        400
    );
    assert_eq!(
        server
            .call("POST", "/api/override", json!({"rapid": 101}))
            .0,
        400
    );
    assert_eq!(
        server
            .call("POST", "/api/override", json!({"spindle": 40}))
            .0,
        400
    );
}

/// On a 5-axis machine the panel runs tool-centre-point programs as the command line does
/// (TRAORI allowed by the machine data, not error 654) and shows the tool axis from the rotary
/// axes: after orienting to the vector (0, 0.6, 0.8) on `5axis-bc-head` it is that vector (1e-9),
/// with B = 36.87° and C = 90° (`stanok run` gives the same).
#[test]
fn a_five_axis_program_runs_and_the_tool_axis_follows_the_rotary_axes() {
    let mut o = options(temp_programs("five-axis"));
    o.machine = stanok_machine::MachineData::builtin("5axis-bc-head").unwrap();
    let server = Server::start(o);
    let idle = server.state();
    assert_eq!(
        [0, 1, 2].map(|i| idle["tool_axis"][i].as_f64().unwrap()),
        [0.0, 0.0, 1.0]
    );
    load(
        &server,
        "orient.nc",
        "G0 X0 Y0 Z100 B0 C0\nTRAORI\nG1 X10 Y0 Z50 A3=0 B3=0.6 C3=0.8 F1000\nTRAFOOF\nM30\n",
    );
    start(&server);
    let s = server.wait_for(&["finished", "alarm"], LONG);
    assert_eq!(s["run_state"], "finished", "{s}");
    let axis = [0, 1, 2].map(|i| s["tool_axis"][i].as_f64().unwrap());
    for (got, want) in axis.iter().zip([0.0, 0.6, 0.8]) {
        assert!((got - want).abs() < 1e-9, "tool axis {axis:?}");
    }
    let b = s["machine_position"][4].as_f64().unwrap();
    let c = s["machine_position"][5].as_f64().unwrap();
    assert!(
        (b - 0.8f64.acos().to_degrees()).abs() < 1e-6 && (c - 90.0).abs() < 1e-6,
        "{s}"
    );
}

/// Issue 19: the feed override acts at the interpolator. On a G1 of 60 mm at 1200 mm/min, 10 %
/// set while it moves gives 120 mm/min within 50 ms of machine time (from the setpoint that first
/// ran with it, `overrides_since_s`), 0 % brings the machine to rest on the path, 100 % resumes
/// it to the end; the cycle time grows by the slow and the standing time.
#[test]
fn feed_override_acts_on_the_block_being_executed_and_zero_stands_on_the_path() {
    let server = paced(2.0);
    load(&server, "long.ngc", "G21 G90\nG1 X60 F1200\nM2\n");
    start(&server);
    let sample = |s: &Value| {
        (
            s["elapsed_s"].as_f64().unwrap(),
            s["feed_actual"].as_f64().unwrap(),
            s["feed_override"].as_u64().unwrap(),
            s["overrides_since_s"].as_f64().unwrap(),
            xyz(s),
        )
    };
    let t0 = Instant::now();
    while server.state()["elapsed_s"].as_f64().unwrap() < 1.0 {
        assert!(t0.elapsed() < LONG);
        std::thread::sleep(Duration::from_millis(2));
    }
    assert_eq!(
        server.state()["line"],
        2,
        "the G1 is the block being executed"
    );
    // Samples from the change until `span` s of machine time after it took effect.
    let watch = |pct: u64, span: f64| {
        let mut samples = Vec::new();
        let t = Instant::now();
        loop {
            let s = sample(&server.state());
            let done = s.2 == pct && s.0 >= s.3 + span;
            samples.push(s);
            if done {
                break;
            }
            assert!(t.elapsed() < LONG, "{pct} %: {:?}", samples.last());
            std::thread::sleep(Duration::from_millis(2));
        }
        let since = samples.iter().find(|s| s.2 == pct).unwrap().3;
        (since, samples)
    };
    // 10 %.
    server.call("POST", "/api/override", json!({"feed": 10}));
    let (since, slow) = watch(10, 0.5);
    let late: Vec<_> = slow
        .iter()
        .filter(|s| s.2 == 10 && s.0 >= since + 0.050)
        .collect();
    assert!(late.len() >= 3, "{} samples", late.len());
    for s in &late {
        assert!(
            s.1 > 118.0 && s.1 < 121.0,
            "{:.4} s after the change: {} mm/min",
            s.0 - since,
            s.1
        );
    }
    // 0 %: at rest on the path (Y stays 0), standing.
    server.call("POST", "/api/override", json!({"feed": 0}));
    let (since, stood) = watch(0, 0.5);
    let at_rest: Vec<_> = stood
        .iter()
        .filter(|s| s.2 == 0 && s.0 >= since + 0.050)
        .collect();
    assert!(at_rest.len() >= 3, "{} samples", at_rest.len());
    let here = at_rest[0].4;
    for s in &at_rest {
        assert_eq!(s.1, 0.0, "moving at 0 %");
        assert_eq!(s.4, here, "moved at 0 %");
    }
    assert!(
        here[0] > 20.0 && here[0] < 60.0 && here[1] == 0.0,
        "{here:?}"
    );
    assert_eq!(server.state()["run_state"], "running");
    // 100 %: on to the end.
    server.call("POST", "/api/override", json!({"feed": 100}));
    let s = server.wait_for(&["finished"], LONG);
    assert_eq!(xyz(&s), [60.0, 0.0, 0.0]);
    // 3 s at 100 % plus the slow and the standing part.
    assert!(s["cycle_time_s"].as_f64().unwrap() > 3.5, "{s}");
}
