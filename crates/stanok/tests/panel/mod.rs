//! What the panel's browser tests share: `stanok serve` on a free port, the page in headless
//! Chromium, reading the DRO and the run state off the page, screenshots to
//! `target/tmp/panel/`.
#![allow(dead_code)]

use crate::cdp::{chromium, Browser};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

pub const TOKEN: &str = "panel-test-token-0123456789";

/// `stanok serve` on a free loopback port.
pub struct Panel {
    child: Child,
    pub url: String,
    pub programs: PathBuf,
}

impl Panel {
    /// Serves `programs` (a fresh directory per test) with these extra arguments.
    pub fn start(tag: &str, extra: &[&str]) -> Panel {
        let programs =
            std::env::temp_dir().join(format!("stanok-panel-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&programs);
        std::fs::create_dir_all(&programs).unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_stanok"))
            .args(["serve", "--bind", "127.0.0.1:0", "--token", TOKEN])
            .args(extra)
            .arg("--programs")
            .arg(&programs)
            .stderr(Stdio::piped())
            .spawn()
            .expect("start stanok serve");
        let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
        let first = loop {
            let line = lines.next().expect("serve printed nothing").unwrap();
            if line.contains("operator panel on ") {
                break line;
            }
        };
        let url = first
            .split("operator panel on ")
            .nth(1)
            .unwrap()
            .trim()
            .to_string();
        std::thread::spawn(move || for _ in lines {});
        Panel {
            child,
            url,
            programs,
        }
    }
}

impl Panel {
    /// The server's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }
}

impl Drop for Panel {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.programs);
    }
}

/// Chromium on the panel's page, online (None: no Chromium, the test is skipped loudly).
pub fn open(panel: &Panel, tag: &str) -> Option<Browser> {
    let exe = chromium()?;
    let mut b = Browser::launch(&exe, tag);
    b.navigate(&panel.url);
    b.wait_until(
        "document.getElementById('connection').textContent === 'online'",
        Duration::from_secs(30),
    );
    Some(b)
}

/// Machine (or work) positions of X Y Z on the DRO.
pub fn dro_of(b: &mut Browser, column: &str) -> [f64; 3] {
    let v = b.eval(&format!(
        "['X','Y','Z'].map(a => {{ const r = document.querySelector(`tr[data-axis=\"${{a}}\"] .{column}`); \
           return r ? r.textContent : '0'; }})"
    ));
    let mut p = [0.0; 3];
    for (i, slot) in p.iter_mut().enumerate() {
        *slot = v[i].as_str().unwrap().parse().unwrap();
    }
    p
}

/// Machine positions of X Y Z on the DRO.
pub fn dro(b: &mut Browser) -> [f64; 3] {
    dro_of(b, "machine")
}

pub fn run_state(b: &mut Browser) -> String {
    b.eval("document.getElementById('run-state').className")
        .as_str()
        .unwrap()
        .trim_start_matches("badge ")
        .to_string()
}

pub fn wait_state(b: &mut Browser, state: &str, secs: u64) {
    b.wait_until(
        &format!("document.getElementById('run-state').classList.contains('{state}')"),
        Duration::from_secs(secs),
    );
}

/// Puts `text` into the editor as typing would and names it.
pub fn type_program(b: &mut Browser, name: &str, text: &str) {
    b.eval(&format!(
        "(() => {{ const e = document.getElementById('editor'); e.value = {t}; \
           e.dispatchEvent(new Event('input')); \
           document.getElementById('program-name').value = {n}; }})()",
        t = serde_json::json!(text),
        n = serde_json::json!(name)
    ));
}

/// Types `text` and presses Load; waits until the load is shown (the program name in the status).
pub fn load_program(b: &mut Browser, name: &str, text: &str) {
    type_program(b, name, text);
    b.click("#load");
    b.wait_until(
        &format!(
            "window.panel.loaded && window.panel.loaded.name === {} && !window.panel.dirty",
            serde_json::json!(name)
        ),
        Duration::from_secs(60),
    );
}

/// Sets a form field's value and fires its change event.
pub fn set_value(b: &mut Browser, id: &str, value: &str) {
    b.eval(&format!(
        "(() => {{ const e = document.getElementById({id}); e.value = {v}; \
           e.dispatchEvent(new Event('change')); e.dispatchEvent(new Event('input')); }})()",
        id = serde_json::json!(id),
        v = serde_json::json!(value)
    ));
}

/// A screenshot of the page to `target/tmp/panel/<name>.png`.
pub fn shot(b: &mut Browser, name: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("panel/{name}.png"));
    b.screenshot(&path);
    assert!(
        std::fs::metadata(&path).unwrap().len() > 10_000,
        "{}",
        path.display()
    );
    eprintln!("screenshot: {}", path.display());
    path
}

/// No uncaught error on the page.
pub fn no_page_errors(b: &mut Browser) {
    let errors = b.errors();
    assert!(errors.is_empty(), "page errors: {errors:?}");
}

/// The view's own account of what it draws (`View3D::stats`).
pub fn view_stats(b: &mut Browser) -> serde_json::Value {
    b.eval("window.panel.view.stats()")
}

pub fn write_program(panel: &Panel, name: &str, text: &str) -> PathBuf {
    let p = panel.programs.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

pub fn exists(p: &Path) -> bool {
    p.exists()
}
