//! The HTTP side: the page, the JSON API, the WebSocket, and the access rules.
//!
//! Every control of the page is one small JSON call, so the tests drive the panel exactly as the
//! page does (docs/panel.md lists them). Handlers never run the machine: they set a
//! switch or send an event to the machine thread and return at once; checking and previewing
//! (which run the interpreter) go to tokio's blocking pool.
//!
//! Access rules (enforced by the layers of [`router`]):
//! * with a token, every request — page, API, WebSocket — must carry it, as
//!   `Authorization: Bearer <token>` or `?token=<token>` (a browser's WebSocket cannot set
//!   headers); otherwise 401;
//! * request bodies are limited to `upload_limit` bytes (413 beyond);
//! * programs are read and written only through [`ProgramDir`](crate::files::ProgramDir).

use crate::check::{check, preview, Preview};
use crate::files::FileError;
use crate::machine::{Alarm, Event, Job, RunState, Shared};
use crate::App;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{DefaultBodyLimit, Path, Request, State};
use axum::http::{header, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{Html, IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde::Deserialize;
use serde_json::{json, Value};
use stanok_syntax::Dialect;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Duration;

type Shared_ = Arc<App>;

/// The page: one HTML document with its style and scripts inlined (so a token in the page's URL
/// is all the page needs; nothing is fetched from elsewhere).
fn page() -> String {
    include_str!("../assets/index.html")
        .replace("/*STYLE*/", include_str!("../assets/style.css"))
        .replace(
            "/*SCRIPT*/",
            &[
                include_str!("../assets/view3d.js"),
                include_str!("../assets/editor.js"),
                include_str!("../assets/app.js"),
            ]
            .join("\n"),
        )
}

/// The router with all routes and access rules (module doc).
pub fn router(app: Arc<App>) -> Router {
    let limit = app.options.upload_limit;
    Router::new()
        .route("/", get(|| async { Html(page()) }))
        .route("/api/state", get(state))
        .route("/api/programs", get(list_programs))
        .route("/api/programs/{name}", get(read_program).put(write_program))
        .route("/api/check", post(check_program))
        .route("/api/load", post(load_program))
        .route("/api/loaded", get(loaded_program))
        .route("/api/cycle-start", post(cycle_start))
        .route("/api/feed-hold", post(feed_hold))
        .route("/api/stop", post(stop))
        .route("/api/override", post(set_override))
        .route("/api/switches", post(set_switches))
        .route("/api/acknowledge", post(acknowledge))
        .route("/ws", get(websocket))
        .layer(DefaultBodyLimit::max(limit))
        .layer(middleware::from_fn_with_state(app.clone(), require_token))
        .with_state(app)
}

/// Compares without an early exit on the first differing byte.
fn same_secret(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

async fn require_token(State(app): State<Shared_>, req: Request, next: Next) -> Response {
    let Some(token) = &app.options.token else {
        return next.run(req).await;
    };
    let from_header = req
        .headers()
        .get(header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.strip_prefix("Bearer "))
        .map(str::to_string);
    let from_query = req.uri().query().and_then(|q| {
        q.split('&')
            .filter_map(|kv| kv.split_once('='))
            .find(|(k, _)| *k == "token")
            .map(|(_, v)| v.to_string())
    });
    let ok = [from_header, from_query]
        .iter()
        .flatten()
        .any(|t| same_secret(t, token));
    if ok {
        next.run(req).await
    } else {
        (StatusCode::UNAUTHORIZED, "a valid token is required\n").into_response()
    }
}

fn error(status: StatusCode, message: impl Into<String>) -> Response {
    (status, Json(json!({ "error": message.into() }))).into_response()
}

fn file_error(e: FileError) -> Response {
    let status = match e {
        FileError::BadName(_) => StatusCode::BAD_REQUEST,
        FileError::NotFound(_) => StatusCode::NOT_FOUND,
        FileError::Io(_) => StatusCode::INTERNAL_SERVER_ERROR,
    };
    error(status, e.to_string())
}

async fn state(State(app): State<Shared_>) -> Response {
    let json = serde_json::to_value(&*app.machine.status()).unwrap_or(Value::Null);
    Json(json).into_response()
}

async fn list_programs(State(app): State<Shared_>) -> Response {
    Json(json!({ "programs": app.programs.list() })).into_response()
}

async fn read_program(State(app): State<Shared_>, Path(name): Path<String>) -> Response {
    match app.programs.read(&name) {
        Ok(text) => Json(json!({ "name": name, "text": text })).into_response(),
        Err(e) => file_error(e),
    }
}

async fn write_program(
    State(app): State<Shared_>,
    Path(name): Path<String>,
    body: String,
) -> Response {
    match app.programs.write(&name, &body) {
        Ok(()) => Json(json!({ "saved": name, "bytes": body.len() })).into_response(),
        Err(e) => file_error(e),
    }
}

/// A program sent by the page: its text, and a name or dialect to tell the language.
#[derive(Debug, Deserialize)]
struct ProgramText {
    #[serde(default)]
    name: String,
    text: String,
    #[serde(default)]
    dialect: Option<String>,
}

fn dialect_of(p: &ProgramText) -> Result<Dialect, Box<Response>> {
    match p.dialect.as_deref() {
        Some("axioma") => Ok(Dialect::Axioma),
        Some("rs274ngc") => Ok(Dialect::Rs274ngc),
        None | Some("") => Ok(Dialect::from_path(std::path::Path::new(&p.name))),
        Some(other) => Err(Box::new(error(
            StatusCode::BAD_REQUEST,
            format!("unknown dialect {other:?} (axioma, rs274ngc)"),
        ))),
    }
}

async fn check_program(State(app): State<Shared_>, Json(p): Json<ProgramText>) -> Response {
    let dialect = match dialect_of(&p) {
        Ok(d) => d,
        Err(r) => return *r,
    };
    let app2 = app.clone();
    let alarms = tokio::task::spawn_blocking(move || {
        check(
            &p.text,
            dialect,
            &app2.options.machine,
            &app2.subroutine_path(),
        )
    })
    .await
    .unwrap_or_default();
    Json(json!({ "diagnostics": alarms })).into_response()
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
}

/// The loaded program, for a page opened while it runs.
async fn loaded_program(State(app): State<Shared_>) -> Response {
    let loaded = app.loaded.lock().unwrap_or_else(|e| e.into_inner()).clone();
    match loaded {
        Some(l) => Json(json!({
            "name": l.name,
            "text": &*l.text,
            "diagnostics": l.alarms,
            "preview": l.preview.as_deref(),
        }))
        .into_response(),
        None => Json(json!({ "name": null })).into_response(),
    }
}

async fn load_program(State(app): State<Shared_>, Json(p): Json<ProgramText>) -> Response {
    let dialect = match dialect_of(&p) {
        Ok(d) => d,
        Err(r) => return *r,
    };
    if matches!(
        app.machine.status().run_state,
        RunState::Starting | RunState::Running | RunState::BlockEnd | RunState::Prompt
    ) {
        return error(StatusCode::CONFLICT, "a program is running: stop it first");
    }
    let app2 = app.clone();
    let text: Arc<str> = p.text.into();
    let text2 = text.clone();
    let result = tokio::task::spawn_blocking(move || {
        let path = app2.subroutine_path();
        let alarms = check(&text2, dialect, &app2.options.machine, &path);
        let has_error = alarms.iter().any(|a| a.severity == "error");
        let pv = (!has_error).then(|| preview(&text2, dialect, &app2.options.machine, &path));
        (alarms, pv)
    })
    .await;
    let Ok((alarms, pv)) = result else {
        return error(StatusCode::INTERNAL_SERVER_ERROR, "check failed");
    };
    let pv: Option<Arc<Preview>> = pv.map(Arc::new);
    let loaded = Loaded {
        name: p.name.clone(),
        text,
        dialect,
        alarms: alarms.clone(),
        estimated_s: pv.as_ref().map(|v| v.cycle_time_s).unwrap_or(0.0),
        preview: pv.clone(),
    };
    *app.loaded.lock().unwrap_or_else(|e| e.into_inner()) = Some(loaded);
    {
        let mut s = app.machine.status();
        s.program = p.name.clone();
        s.alarms = alarms
            .iter()
            .filter(|a| a.severity == "error")
            .cloned()
            .collect();
        s.estimated_s = pv.as_ref().map(|v| v.cycle_time_s).unwrap_or(0.0);
        if !matches!(s.run_state, RunState::Idle) {
            s.run_state = RunState::Idle;
        }
        s.seq += 1;
    }
    Json(json!({ "name": p.name, "diagnostics": alarms, "preview": pv.as_deref() })).into_response()
}

/// Cycle start: a block search line and a line whose machine state to record are optional.
#[derive(Debug, Default, Deserialize)]
struct CycleStart {
    #[serde(default)]
    search_line: Option<u32>,
    #[serde(default)]
    mark_line: Option<u32>,
}

async fn cycle_start(State(app): State<Shared_>, body: axum::body::Bytes) -> Response {
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
        let mut s = shared.status();
        s.alarms = errors.clone();
        s.run_state = RunState::Alarm;
        s.seq += 1;
        return (
            StatusCode::CONFLICT,
            Json(json!({ "error": "the program has errors", "diagnostics": errors })),
        )
            .into_response();
    }
    let lines = loaded.text.lines().count() as u32;
    if let Some(n) = req.search_line {
        if n == 0 || n > lines {
            return error(
                StatusCode::BAD_REQUEST,
                format!("search line {n} is not a line of the program (1…{lines})"),
            );
        }
    }
    shared.controls.hold.set(false);
    shared.controls.stop.store(false, Ordering::Relaxed);
    {
        let mut s = shared.status();
        s.run_state = RunState::Starting;
        s.seq += 1;
    }
    shared.send(Event::Start(Box::new(Job {
        name: loaded.name,
        text: loaded.text,
        dialect: loaded.dialect,
        search_line: req.search_line,
        mark_line: req.mark_line,
        estimated_s: loaded.estimated_s,
    })));
    Json(json!({ "action": "start" })).into_response()
}

async fn feed_hold(State(app): State<Shared_>) -> Response {
    app.machine.controls.hold.set(true);
    Json(json!({ "held": true })).into_response()
}

async fn stop(State(app): State<Shared_>) -> Response {
    let shared = &app.machine;
    let running = matches!(
        shared.status().run_state,
        RunState::Starting | RunState::Running | RunState::BlockEnd | RunState::Prompt
    );
    if running {
        shared.controls.stop.store(true, Ordering::Relaxed);
    } else {
        // Reset: clear alarms and messages of a finished run.
        let mut s = shared.status();
        s.alarms.clear();
        s.message.clear();
        s.run_state = RunState::Idle;
        s.seq += 1;
    }
    Json(json!({ "stopping": running })).into_response()
}

#[derive(Debug, Deserialize)]
struct Override {
    #[serde(default)]
    feed: Option<f64>,
    #[serde(default)]
    rapid: Option<f64>,
}

async fn set_override(State(app): State<Shared_>, Json(o): Json<Override>) -> Response {
    let c = &app.machine.controls;
    if let Some(f) = o.feed {
        if !(0.0..=200.0).contains(&f) {
            return error(StatusCode::BAD_REQUEST, "feed override is 0…200 %");
        }
        c.feed_override.store(f.round() as u32, Ordering::Relaxed);
    }
    if let Some(r) = o.rapid {
        if !(1.0..=100.0).contains(&r) {
            return error(StatusCode::BAD_REQUEST, "rapid override is 1…100 %");
        }
        c.rapid_override.store(r.round() as u32, Ordering::Relaxed);
    }
    let (f, r) = (
        c.feed_override.load(Ordering::Relaxed),
        c.rapid_override.load(Ordering::Relaxed),
    );
    let mut s = app.machine.status();
    s.feed_override = f;
    s.rapid_override = r;
    s.seq += 1;
    Json(json!({ "feed": f, "rapid": r })).into_response()
}

#[derive(Debug, Deserialize)]
struct Switches {
    #[serde(default)]
    single_block: Option<bool>,
    #[serde(default)]
    optional_stop: Option<bool>,
}

async fn set_switches(State(app): State<Shared_>, Json(sw): Json<Switches>) -> Response {
    let c = &app.machine.controls;
    if let Some(v) = sw.single_block {
        c.single_block.store(v, Ordering::Relaxed);
    }
    if let Some(v) = sw.optional_stop {
        c.optional_stop.store(v, Ordering::Relaxed);
    }
    let (sb, os) = (
        c.single_block.load(Ordering::Relaxed),
        c.optional_stop.load(Ordering::Relaxed),
    );
    let mut s = app.machine.status();
    s.single_block = sb;
    s.optional_stop = os;
    s.seq += 1;
    Json(json!({ "single_block": sb, "optional_stop": os })).into_response()
}

async fn acknowledge(State(app): State<Shared_>) -> Response {
    let shared = &app.machine;
    let prompt = shared.status().run_state == RunState::Prompt;
    {
        let mut s = shared.status();
        s.message.clear();
        s.seq += 1;
    }
    shared.send(Event::Acknowledge);
    Json(json!({ "acknowledged": if prompt { "prompt" } else { "message" } })).into_response()
}

/// Updates per second sent to each page.
const UPDATES_PER_SECOND: u64 = 30;

async fn websocket(State(app): State<Shared_>, ws: WebSocketUpgrade) -> Response {
    ws.on_upgrade(move |socket| stream_status(app, socket))
}

/// Sends the latest status ~30 times a second while it changes. One frame in flight per client:
/// a slow client skips snapshots, it never queues them (module doc of `machine.rs`).
async fn stream_status(app: Shared_, mut socket: WebSocket) {
    let mut tick = tokio::time::interval(Duration::from_millis(1000 / UPDATES_PER_SECOND));
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut last_seq = u64::MAX;
    loop {
        tick.tick().await;
        let text = {
            let s = app.machine.status();
            if s.seq == last_seq {
                continue;
            }
            last_seq = s.seq;
            serde_json::to_string(&*s).unwrap_or_default()
        };
        if socket.send(Message::Text(text.into())).await.is_err() {
            break;
        }
    }
}
