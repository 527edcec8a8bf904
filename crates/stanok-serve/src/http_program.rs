//! Programs: the directory, check, load, the loaded program, and the run controls (cycle start,
//! feed hold, stop/reset, acknowledge).
//!
//! **Load and reset.** A load replaces the program the panel runs and returns the DRO to the new
//! program's start: no line, the program's power-on modes and no message, where the machine stands
//! (`machine::reset_to_start`), and the view gets the new preview. While a program is in progress
//! (running, held, at a block end or an M00/M01 prompt) a load is refused with 409 and a notice
//! that stays on the page until acknowledged — unless the request says `"stop": true` (the page's
//! "Stop and load" after asking the operator): then the run is stopped first (on the path, as the
//! stop button does) and the load follows. The program that was running is never resumed by a
//! later cycle start.
//!
//! **Large programs.** A program is loaded from its text or, without text, from the program
//! directory by name (up to `jobs::MAX_PROGRAM_BYTES`): a 10-million-block file never crosses the
//! browser. The page gets the text only up to [`INLINE_TEXT_BYTES`]; beyond that it shows a
//! read-only view that asks for the lines it displays (`/api/loaded/lines`).

use crate::check::{examine, Examined, Preview, PreviewLimits, Subject};
use crate::files::FileError;
use crate::http::{dialect_of, error, AppState};
use crate::jobs::{JobError, MAX_PROGRAM_BYTES};
use crate::machine::{reset_to_start, Alarm, Event, Job, RunState, Shared};
use axum::extract::{Path, Query, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::{json, Value};
use stanok_syntax::Dialect;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Programs up to this size are sent to the page as text (module doc).
pub const INLINE_TEXT_BYTES: usize = 2 * 1024 * 1024;

/// Lines one `/api/loaded/lines` request returns at most.
pub const MAX_LINES_PER_REQUEST: usize = 2000;

fn file_error(e: FileError) -> Response {
    let status = match e {
        FileError::BadName(_) => StatusCode::BAD_REQUEST,
        FileError::NotFound(_) => StatusCode::NOT_FOUND,
        FileError::Io(_) => StatusCode::INTERNAL_SERVER_ERROR,
    };
    error(status, e.to_string())
}

pub(crate) async fn list_programs(State(app): State<AppState>) -> Response {
    Json(json!({ "programs": app.programs.list() })).into_response()
}

pub(crate) async fn read_program(
    State(app): State<AppState>,
    Path(name): Path<String>,
) -> Response {
    match app.programs.read(&name) {
        Ok(text) => Json(json!({
            "name": name,
            "text": text,
            "dialect": Dialect::from_path(std::path::Path::new(&name)).id(),
        }))
        .into_response(),
        Err(e) => file_error(e),
    }
}

pub(crate) async fn write_program(
    State(app): State<AppState>,
    Path(name): Path<String>,
    body: String,
) -> Response {
    match app.programs.write(&name, &body) {
        Ok(()) => Json(json!({ "saved": name, "bytes": body.len() })).into_response(),
        Err(e) => file_error(e),
    }
}

/// A program sent by the page: its text (or, for a load, none: the file `name`), and a name or
/// dialect to tell the language.
#[derive(Debug, Deserialize)]
pub(crate) struct ProgramText {
    #[serde(default)]
    name: String,
    #[serde(default)]
    text: Option<String>,
    #[serde(default)]
    dialect: Option<String>,
    /// Load: stop a program in progress first.
    #[serde(default)]
    stop: bool,
    /// Load: the stock to cut (`stock.rs`; the `--stock` syntax), else the machine data's.
    #[serde(default)]
    stock: Option<String>,
}

/// The diagnostic of a job that gave no result.
fn job_alarm(e: &JobError) -> Alarm {
    Alarm::panel("serve::budget", 1, e.to_string())
}

pub(crate) async fn check_program(
    State(app): State<AppState>,
    Json(p): Json<ProgramText>,
) -> Response {
    let dialect = match dialect_of(&p.name, p.dialect.as_deref()) {
        Ok(d) => d,
        Err(r) => return *r,
    };
    let text: Arc<str> = p.text.unwrap_or_default().into();
    let at = app.machine.context();
    let app2 = app.clone();
    let result = app
        .jobs
        .run(move |cancel| {
            let path = app2.subroutine_path();
            let subject = Subject {
                text,
                dialect,
                machine: &app2.options.machine,
                subroutine_path: &path,
                at: &at,
            };
            crate::check::check(&subject, cancel)
        })
        .await;
    let diagnostics = result.unwrap_or_else(|e| vec![job_alarm(&e)]);
    Json(json!({ "diagnostics": diagnostics, "dialect": dialect.id() })).into_response()
}

/// The program the panel runs on cycle start.
#[derive(Debug, Clone)]
pub struct Loaded {
    name: String,
    text: Arc<str>,
    dialect: Dialect,
    alarms: Vec<Alarm>,
    estimated_s: f64,
    preview: Option<Arc<Preview>>,
    lines: usize,
    stock: Option<stanok_stock::spec::StockShape>,
}

/// The loaded program as the page gets it (text only when small, module doc).
fn loaded_json(l: &Loaded) -> Value {
    let inline = l.text.len() <= INLINE_TEXT_BYTES;
    json!({
        "name": l.name,
        "dialect": l.dialect.id(),
        "text": if inline { Some(&*l.text) } else { None },
        "lines": l.lines,
        "bytes": l.text.len(),
        "diagnostics": l.alarms,
        "preview": l.preview.as_deref(),
        "stock": l.stock.is_some(),
    })
}

/// The loaded program, for a page opened while it runs.
pub(crate) async fn loaded_program(State(app): State<AppState>) -> Response {
    let loaded = app.loaded.lock().unwrap_or_else(|e| e.into_inner()).clone();
    match loaded {
        Some(l) => Json(loaded_json(&l)).into_response(),
        None => Json(json!({ "name": null })).into_response(),
    }
}

#[derive(Debug, Deserialize)]
pub(crate) struct LineRange {
    from: usize,
    count: usize,
}

/// Lines `from` (1-based) … of the loaded program (the page's view of a large program).
pub(crate) async fn loaded_lines(
    State(app): State<AppState>,
    Query(r): Query<LineRange>,
) -> Response {
    let loaded = app.loaded.lock().unwrap_or_else(|e| e.into_inner()).clone();
    let Some(l) = loaded else {
        return error(StatusCode::NOT_FOUND, "no program loaded");
    };
    let count = r.count.min(MAX_LINES_PER_REQUEST);
    let from = r.from.max(1);
    // A scan from the start: a few hundred ms for 100 MB, only for large programs and on scrolls.
    let lines: Vec<&str> = l.text.lines().skip(from - 1).take(count).collect();
    Json(json!({ "from": from, "lines": lines, "total": l.lines })).into_response()
}

/// Waits until no program is in progress (after a stop), at most `limit`.
async fn wait_until_stopped(shared: &Shared, limit: Duration) -> bool {
    let t0 = Instant::now();
    loop {
        if !shared.status().run_state.program_active() {
            return true;
        }
        if t0.elapsed() > limit {
            return false;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

pub(crate) async fn load_program(
    State(app): State<AppState>,
    Json(p): Json<ProgramText>,
) -> Response {
    let dialect = match dialect_of(&p.name, p.dialect.as_deref()) {
        Ok(d) => d,
        Err(r) => return *r,
    };
    let shared = &app.machine;
    let run_state = shared.status().run_state;
    if run_state.program_active() {
        let running = shared.status().program.clone();
        if !p.stop {
            let notice = format!(
                "{} was not loaded: {running} is in progress ({}). Stop it first, or confirm \
                 \"Stop and load\".",
                if p.name.is_empty() {
                    "the program"
                } else {
                    &p.name
                },
                format!("{run_state:?}").to_lowercase()
            );
            shared.publish(|s| s.notice = Some(notice.clone()));
            return (
                StatusCode::CONFLICT,
                Json(json!({ "error": notice, "confirm": "stop", "running": running })),
            )
                .into_response();
        }
        shared.controls.stop.raise();
        if !wait_until_stopped(shared, Duration::from_secs(30)).await {
            return error(StatusCode::CONFLICT, "the running program did not stop");
        }
    } else if run_state.busy() {
        return error(
            StatusCode::CONFLICT,
            "the machine is moving (jog, reference return or MDI): wait for it",
        );
    }
    let stock = match crate::stock::resolve(&app.options.machine, p.stock.as_deref()) {
        Ok(s) => s,
        Err(e) => return error(StatusCode::BAD_REQUEST, e),
    };
    let text: Arc<str> = match p.text {
        Some(t) => t.into(),
        None => match read_large(&app, &p.name) {
            Ok(t) => t,
            Err(r) => return *r,
        },
    };
    let at = shared.context();
    let app2 = app.clone();
    let text2 = text.clone();
    let limits = PreviewLimits {
        points: app.options.preview_points,
        // A third of the budget, at most 4 s: past that the time is extrapolated (check.rs).
        planning: (app.options.job_budget / 3).min(Duration::from_secs(4)),
    };
    let result = app
        .jobs
        .run(move |cancel| {
            let path = app2.subroutine_path();
            let subject = Subject {
                text: text2,
                dialect,
                machine: &app2.options.machine,
                subroutine_path: &path,
                at: &at,
            };
            examine(&subject, cancel, Some(limits))
        })
        .await;
    let examined = result.unwrap_or_else(|e| Examined {
        diagnostics: vec![job_alarm(&e)],
        preview: None,
    });
    let preview: Option<Arc<Preview>> = examined.preview.map(Arc::new);
    let lines = bytecount_lines(&text);
    let loaded = Loaded {
        name: p.name.clone(),
        text,
        dialect,
        alarms: examined.diagnostics.clone(),
        estimated_s: preview.as_ref().map_or(0.0, |v| v.cycle_time_s),
        preview: preview.clone(),
        lines,
        stock,
    };
    let body = loaded_json(&loaded);
    *app.loaded.lock().unwrap_or_else(|e| e.into_inner()) = Some(loaded);
    let errors: Vec<Alarm> = examined
        .diagnostics
        .iter()
        .filter(|a| a.severity == "error")
        .cloned()
        .collect();
    let start = preview.as_ref().and_then(|v| v.start.clone());
    shared.stock.clear();
    shared.publish(|s| {
        reset_to_start(s, start.as_ref());
        s.program = p.name.clone();
        s.dialect = dialect.id().into();
        s.alarms = errors;
        s.notice = None;
        s.estimated_s = preview.as_ref().map_or(0.0, |v| v.cycle_time_s);
        if !s.run_state.busy() {
            s.run_state = RunState::Idle;
        }
    });
    Json(body).into_response()
}

/// Lines of a text (a last line without a newline counts).
fn bytecount_lines(text: &str) -> usize {
    let n = text.bytes().filter(|b| *b == b'\n').count();
    n + usize::from(!text.is_empty() && !text.ends_with('\n'))
}

/// A program file read by name for a load (module doc).
fn read_large(app: &AppState, name: &str) -> Result<Arc<str>, Box<Response>> {
    let path = app
        .programs
        .resolve(name)
        .map_err(|e| Box::new(file_error(e)))?;
    let meta = std::fs::metadata(&path)
        .map_err(|_| Box::new(file_error(FileError::NotFound(name.into()))))?;
    if meta.len() > MAX_PROGRAM_BYTES {
        return Err(Box::new(error(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "{name} has {} bytes; the panel loads programs up to {MAX_PROGRAM_BYTES} bytes",
                meta.len()
            ),
        )));
    }
    app.programs
        .read(name)
        .map(Arc::from)
        .map_err(|e| Box::new(file_error(e)))
}

/// Cycle start: a block search line and a line whose machine state to record are optional.
#[derive(Debug, Default, Deserialize)]
struct CycleStart {
    #[serde(default)]
    search_line: Option<u32>,
    #[serde(default)]
    mark_line: Option<u32>,
}

pub(crate) async fn cycle_start(State(app): State<AppState>, body: axum::body::Bytes) -> Response {
    // No body (or an empty one) is a plain cycle start.
    let req: CycleStart = if body.iter().all(u8::is_ascii_whitespace) {
        CycleStart::default()
    } else {
        match serde_json::from_slice(&body) {
            Ok(r) => r,
            Err(e) => return error(StatusCode::BAD_REQUEST, format!("cycle start: {e}")),
        }
    };
    let shared: &Shared = &app.machine;
    let run_state = shared.status().run_state;
    match run_state {
        RunState::BlockEnd | RunState::Prompt => {
            shared.send(Event::CycleStart);
            return Json(json!({ "action": "continue" })).into_response();
        }
        RunState::Starting | RunState::Running => {
            if shared.controls.hold.is_held() {
                shared.controls.hold.set(false);
                return Json(json!({ "action": "resume" })).into_response();
            }
            return error(StatusCode::CONFLICT, "the program is running");
        }
        RunState::Jogging | RunState::Homing | RunState::Mdi => {
            return error(StatusCode::CONFLICT, "the machine is moving: wait for it");
        }
        _ => {}
    }
    let Some(loaded) = app.loaded.lock().unwrap_or_else(|e| e.into_inner()).clone() else {
        return error(StatusCode::CONFLICT, "no program loaded");
    };
    let errors: Vec<Alarm> = loaded
        .alarms
        .iter()
        .filter(|a| a.severity == "error")
        .cloned()
        .collect();
    if !errors.is_empty() {
        shared.publish(|s| {
            s.alarms = errors.clone();
            s.run_state = RunState::Alarm;
        });
        return (
            StatusCode::CONFLICT,
            Json(json!({ "error": "the program has errors", "diagnostics": errors })),
        )
            .into_response();
    }
    let lines = loaded.lines as u32;
    if let Some(n) = req.search_line {
        if n == 0 || n > lines {
            return error(
                StatusCode::BAD_REQUEST,
                format!("search line {n} is not a line of the program (1…{lines})"),
            );
        }
    }
    shared.controls.hold.set(false);
    shared.controls.stop.lower();
    shared.publish(|s| s.run_state = RunState::Starting);
    shared.send(Event::Start(Box::new(Job {
        name: loaded.name,
        text: loaded.text,
        dialect: loaded.dialect,
        search_line: req.search_line,
        mark_line: req.mark_line,
        estimated_s: loaded.estimated_s,
        stock: loaded.stock,
    })));
    Json(json!({ "action": "start" })).into_response()
}

pub(crate) async fn feed_hold(State(app): State<AppState>) -> Response {
    app.machine.controls.hold.set(true);
    Json(json!({ "held": true })).into_response()
}

pub(crate) async fn stop(State(app): State<AppState>) -> Response {
    let shared = &app.machine;
    let busy = shared.status().run_state.busy();
    if busy {
        shared.controls.stop.raise();
        shared
            .controls
            .jog_until_ms
            .store(0, std::sync::atomic::Ordering::Relaxed);
    } else {
        // Reset: clear alarms and messages of a finished run.
        shared.publish(|s| {
            s.alarms.clear();
            s.message.clear();
            s.notice = None;
            s.run_state = RunState::Idle;
        });
    }
    Json(json!({ "stopping": busy })).into_response()
}

/// Acknowledge: the M00/M01 prompt and the message; `{"what": "notice"}` only the notice (it must
/// not let a waiting program go on).
pub(crate) async fn acknowledge(State(app): State<AppState>, body: axum::body::Bytes) -> Response {
    let shared = &app.machine;
    let only_notice = serde_json::from_slice::<Value>(&body).is_ok_and(|v| v["what"] == "notice");
    if only_notice {
        shared.publish(|s| s.notice = None);
        return Json(json!({ "acknowledged": "notice" })).into_response();
    }
    let prompt = shared.status().run_state == RunState::Prompt;
    shared.publish(|s| {
        s.message.clear();
        s.notice = None;
    });
    shared.send(Event::Acknowledge);
    Json(json!({ "acknowledged": if prompt { "prompt" } else { "message" } })).into_response()
}
