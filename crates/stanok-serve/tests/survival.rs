//! Issue 17, items 1 and 3, through the real server: one request must not kill the panel or keep
//! a core busy.
//!
//! * A check of a 5,000-term expression line — which overflowed a worker's stack and aborted the
//!   process — is answered (on a job thread with a known stack), and the server goes on serving;
//!   a 50,000-term line is refused by the panel's line bound with a diagnostic.
//! * A load of a runaway feed (`G1 X100 F0.0000001`: endless simulated time) is answered within
//!   the job budget, its planned time extrapolated.
//! * A load whose interpreter work outlasts the budget (three nested 1000-fold loops) is answered
//!   at the budget with a diagnostic naming it, and its thread ends; a client that leaves before
//!   the answer ends its job's thread within a second ("the CPU released").
//!
//! One test in this file on purpose: it watches the process's job threads (`/proc/self/task`),
//! which other tests in the same process would disturb.

mod common;
use common::*;
use serde_json::{json, Value};
use std::io::Write;
use std::net::TcpStream;
use std::time::{Duration, Instant};

/// Job threads alive now (by name, `jobs.rs`).
fn job_threads() -> usize {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0;
    };
    tasks
        .flatten()
        .filter(|t| {
            std::fs::read_to_string(t.path().join("comm")).is_ok_and(|c| c.trim() == "stanok-job")
        })
        .count()
}

/// Waits until no job thread is alive; the time it took.
fn jobs_end_within(limit: Duration) -> Duration {
    let t0 = Instant::now();
    while job_threads() > 0 {
        assert!(
            t0.elapsed() < limit,
            "a job thread still runs after {limit:?}"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    t0.elapsed()
}

const NESTED_LOOPS: &str = "#1 = 0\n\
    o1 repeat [1000]\n\
    o2 repeat [1000]\n\
    o3 repeat [1000]\n\
    #1 = [#1 + 1]\n\
    o3 endrepeat\n\
    o2 endrepeat\n\
    o1 endrepeat\n\
    G0 X1\nM2\n";

#[test]
fn no_request_kills_the_panel_or_keeps_a_core_busy() {
    let mut o = options(temp_programs("survival"));
    o.job_budget = Duration::from_secs(3);
    let server = Server::start(o);

    // 1. Long expression chains, AxiOMA HLL and the ISO word form.
    for terms in [5_000, 50_000] {
        let chain = vec!["1"; terms].join("+");
        for text in [
            format!("double aa = {chain};\nM30\n"),
            format!("G0 X={chain}\nM30\n"),
        ] {
            let (code, body) = server.call(
                "POST",
                "/api/check",
                json!({"name": "long.nc", "text": text}),
            );
            assert_eq!(code, 200, "{terms} terms: {body}");
            let codes: Vec<&str> = body["diagnostics"]
                .as_array()
                .unwrap()
                .iter()
                .map(|d| d["code"].as_str().unwrap())
                .collect();
            // 5,000 terms (10 KB) are read; 50,000 (100 KB) pass the panel's line bound.
            assert_eq!(
                codes.contains(&"serve::line-too-long"),
                terms > 16_000,
                "{terms} terms: {codes:?}"
            );
        }
        assert_eq!(server.state()["run_state"], "idle", "the server is alive");
    }

    // 2. A runaway feed: answered within the budget, the time extrapolated.
    let t0 = Instant::now();
    let (code, body) = server.call(
        "POST",
        "/api/load",
        json!({"name": "runaway.ngc", "text": "G21 G90\nG1 X100 F0.0000001\nM2\n"}),
    );
    let took = t0.elapsed();
    assert_eq!(code, 200, "{body}");
    assert!(took < Duration::from_secs(4), "answered after {took:?}");
    assert_eq!(body["preview"]["time_estimate"], "extrapolated", "{body}");
    // 100 mm at 1e-7 mm/min = 6e10 s.
    let t = body["preview"]["cycle_time_s"].as_f64().unwrap();
    assert!(t > 5.9e10, "{t}");
    jobs_end_within(Duration::from_secs(2));

    // 3. Interpreter work beyond the budget: a diagnostic naming the budget, the thread ends.
    let t0 = Instant::now();
    let (code, body) = server.call(
        "POST",
        "/api/load",
        json!({"name": "loops.ngc", "text": NESTED_LOOPS}),
    );
    let took = t0.elapsed();
    assert_eq!(code, 200, "{body}");
    assert!(
        took >= Duration::from_secs(3) && took < Duration::from_secs(5),
        "answered after {took:?}"
    );
    assert_eq!(body["diagnostics"][0]["code"], "serve::budget", "{body}");
    assert!(
        body["diagnostics"][0]["message"]
            .as_str()
            .unwrap()
            .contains("--job-budget"),
        "{body}"
    );
    jobs_end_within(Duration::from_secs(2));
    // The program with the budget diagnostic does not start.
    let (code, _) = server.call("POST", "/api/cycle-start", Value::Null);
    assert_eq!(code, 409);

    // 4. A client that leaves: its job ends at once, long before the budget.
    let request = json!({"name": "loops.ngc", "text": NESTED_LOOPS}).to_string();
    let mut s = TcpStream::connect(server.addr).unwrap();
    write!(
        s,
        "POST /api/load HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\n\r\n{request}",
        server.addr,
        request.len()
    )
    .unwrap();
    let t0 = Instant::now();
    while job_threads() == 0 {
        assert!(
            t0.elapsed() < Duration::from_secs(2),
            "the job never started"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(300));
    drop(s);
    let ended = jobs_end_within(Duration::from_secs(1));
    eprintln!("job ended {ended:?} after its client left");
    // Still serving (the state is the refused start's alarm of step 3).
    assert_eq!(server.state()["run_state"], "alarm");
}
