//! The operator panel end to end, in headless Chromium, driving the real `stanok serve` binary as
//! an operator would (mouse clicks on the page, the DRO read off the page):
//!
//! 1. open a corpus program from the program directory, cycle start, feed hold (the DRO stands
//!    still for 0.4 s while held), resume, finish; the DRO's final machine position equals
//!    `stanok run`'s `final_position` (to the DRO's three decimals); a screenshot of the finished
//!    run is written to `$CARGO_TARGET_TMPDIR/panel/finished-run.png`;
//! 2. an M00 program: the prompt appears with the machine at X10, stays 0.5 s with nothing moving,
//!    and only the acknowledge lets it finish at X20 Y5;
//! 3. a program with an error in line 3, typed into the editor: the check as you type lists and
//!    marks it at line 3, and cycle start gives an alarm with the machine where it was.
//!
//! Runs at `--time-scale 4` with a token (so every request of the page carries it). Skips loudly
//! without Chromium unless `STANOK_REQUIRE_BROWSER=1` (see `cdp`).

mod cdp;
mod common;
use cdp::{chromium, Browser};
use common::*;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const TOKEN: &str = "panel-test-token-0123456789";
const CORPUS_PROGRAM: &str = "axioma/s4_3_4-combined-transforms-pole-example-4_8.nc";

/// `stanok serve` on a free loopback port.
struct Panel {
    child: Child,
    url: String,
}

impl Panel {
    fn start(programs: &Path) -> Panel {
        let mut child = Command::new(env!("CARGO_BIN_EXE_stanok"))
            .args([
                "serve",
                "--bind",
                "127.0.0.1:0",
                "--token",
                TOKEN,
                "--time-scale",
                "4",
            ])
            .arg("--programs")
            .arg(programs)
            .stderr(Stdio::piped())
            .spawn()
            .expect("start stanok serve");
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        let first = lines.next().expect("serve printed nothing").unwrap();
        let url = first
            .split("operator panel on ")
            .nth(1)
            .unwrap_or_else(|| panic!("unexpected: {first}"))
            .trim()
            .to_string();
        std::thread::spawn(move || for _ in lines {});
        Panel { child, url }
    }
}

impl Drop for Panel {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn dro(b: &mut Browser) -> [f64; 3] {
    let v = b.eval(
        "['X','Y','Z'].map(a => document.querySelector(`tr[data-axis=\"${a}\"] .machine`).textContent)",
    );
    let mut p = [0.0; 3];
    for (i, slot) in p.iter_mut().enumerate() {
        *slot = v[i].as_str().unwrap().parse().unwrap();
    }
    p
}

fn run_state(b: &mut Browser) -> String {
    b.eval("document.getElementById('run-state').className")
        .as_str()
        .unwrap()
        .trim_start_matches("badge ")
        .to_string()
}

fn wait_state(b: &mut Browser, state: &str, secs: u64) {
    b.wait_until(
        &format!("document.getElementById('run-state').classList.contains('{state}')"),
        Duration::from_secs(secs),
    );
}

/// Puts `text` into the editor as typing would, names it and presses Load.
fn type_program(b: &mut Browser, name: &str, text: &str) {
    b.eval(&format!(
        "(() => {{ const e = document.getElementById('editor'); e.value = {t}; \
           e.dispatchEvent(new Event('input')); \
           document.getElementById('program-name').value = {n}; }})()",
        t = serde_json::json!(text),
        n = serde_json::json!(name)
    ));
    b.click("#load");
}

#[test]
fn the_panel_runs_holds_resumes_prompts_and_refuses_a_bad_program_in_a_real_browser() {
    let Some(exe) = chromium() else { return };
    let t0 = Instant::now();
    let programs = std::env::temp_dir().join(format!("stanok-panel-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&programs);
    std::fs::create_dir_all(&programs).unwrap();
    let source = PathBuf::from(corpus(CORPUS_PROGRAM));
    let name = source.file_name().unwrap().to_string_lossy().to_string();
    std::fs::copy(&source, programs.join(&name)).unwrap();
    let (code, out, _) = stanok(&["run", &source.display().to_string(), "--json"]);
    assert_eq!(code, 0, "{out}");
    let report = json(&out);
    let want = ["x", "y", "z"].map(|a| report["final_position"][a].as_f64().unwrap());

    let panel = Panel::start(&programs);
    let mut b = Browser::launch(&exe, "panel");
    b.navigate(&panel.url);
    b.wait_until(
        "document.getElementById('connection').textContent === 'online'",
        Duration::from_secs(20),
    );

    // 1. Open, start, hold, resume, finish.
    b.wait_until(
        &format!(
            "[...document.getElementById('program-select').options].some(o => o.value === {})",
            serde_json::json!(name)
        ),
        Duration::from_secs(10),
    );
    b.eval(&format!(
        "document.getElementById('program-select').value = {}",
        serde_json::json!(name)
    ));
    b.click("#open");
    b.wait_until(
        "Number(document.getElementById('estimated').textContent) > 0",
        Duration::from_secs(20),
    );
    b.click("#cycle-start");
    b.wait_until(
        "Number(document.getElementById('elapsed').textContent) > 2",
        Duration::from_secs(30),
    );
    assert_eq!(run_state(&mut b), "running");
    b.click("#feed-hold");
    b.wait_until(
        "document.getElementById('feed-hold').textContent === 'Held' && \
         document.getElementById('feed-actual').textContent === '0'",
        Duration::from_secs(10),
    );
    std::thread::sleep(Duration::from_millis(100));
    let held_at = dro(&mut b);
    std::thread::sleep(Duration::from_millis(400));
    assert_eq!(dro(&mut b), held_at, "the machine moved while held");
    assert_eq!(run_state(&mut b), "running");
    b.click("#cycle-start");
    wait_state(&mut b, "finished", 60);
    let got = dro(&mut b);
    for i in 0..3 {
        assert!(
            (got[i] - want[i]).abs() <= 0.0005 + 1e-9,
            "DRO {got:?} vs stanok run {want:?}"
        );
    }
    let shot = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("panel/finished-run.png");
    b.screenshot(&shot);
    assert!(std::fs::metadata(&shot).unwrap().len() > 10_000);
    eprintln!("screenshot: {}", shot.display());

    // 2. M00 blocks until acknowledged.
    type_program(
        &mut b,
        "m00.ngc",
        "G21 G90 G17\nG0 X0 Y0 Z5\nG1 X10 F3000\nM0\nG1 X20 Y5\nM2\n",
    );
    b.wait_until(
        "document.getElementById('program-name').value === 'm00.ngc' && \
         document.getElementById('run-state').classList.contains('idle')",
        Duration::from_secs(10),
    );
    b.click("#cycle-start");
    b.wait_until(
        "!document.getElementById('prompt').hidden",
        Duration::from_secs(30),
    );
    assert_eq!(dro(&mut b), [10.0, 0.0, 5.0]);
    // The block of the stop is the highlighted one.
    assert_eq!(
        b.eval("document.querySelector('#highlight .current').dataset.line"),
        "4"
    );
    let prompt = b.eval("document.getElementById('prompt-text').textContent");
    assert!(prompt.as_str().unwrap().contains("M00"), "{prompt}");
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(run_state(&mut b), "prompt");
    assert_eq!(
        dro(&mut b),
        [10.0, 0.0, 5.0],
        "moved before the acknowledge"
    );
    b.click("#prompt-ack");
    wait_state(&mut b, "finished", 30);
    assert_eq!(dro(&mut b), [20.0, 5.0, 5.0]);

    // 3. A program with an error: checked as it is typed (no Load pressed), shown at its line,
    //    and cycle start (which loads the edited text) refuses it without moving.
    b.eval(&format!(
        "(() => {{ const e = document.getElementById('editor'); e.value = {t}; \
           e.dispatchEvent(new Event('input')); \
           document.getElementById('program-name').value = 'bad.ngc'; }})()",
        t = serde_json::json!("G21 G90\nG0 X1 Y1\nG1 X10\nM2\n")
    ));
    let line = b.wait_until(
        "(() => { const e = document.querySelector('#diagnostics li.error'); return e && e.dataset.line; })()",
        Duration::from_secs(10),
    );
    assert_eq!(line, "3");
    assert_eq!(
        b.eval("!!document.querySelector('#highlight .err[data-line=\"3\"]')"),
        true
    );
    let before = dro(&mut b);
    b.click("#cycle-start");
    wait_state(&mut b, "alarm", 10);
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(
        dro(&mut b),
        before,
        "a program with an error moved the machine"
    );
    let alarm = b.eval("document.getElementById('alarms').textContent");
    assert!(alarm.as_str().unwrap().starts_with("3:"), "{alarm}");

    drop(b);
    drop(panel);
    let _ = std::fs::remove_dir_all(&programs);
    eprintln!("browser test took {:.1} s", t0.elapsed().as_secs_f64());
}
