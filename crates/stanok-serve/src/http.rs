//! The HTTP side: the page, the routes, the WebSocket. The handlers are in `http_program.rs`
//! (programs, check, load, run controls) and `http_manual.rs` (overrides, switches, jog, home,
//! touch-off, MDI); the access rules every request passes first are in `guard.rs`.
//!
//! Every control of the page is one small JSON call, so the tests drive the panel exactly as the
//! page does (docs/panel.md lists them). Handlers never run the machine: they set a switch or send
//! an event to the machine thread; checking and previewing (which run the interpreter) are jobs
//! (`jobs.rs`) on their own threads.

use crate::http_manual as manual;
use crate::http_program as program;
use crate::machine::{dialect_by_id, DIALECTS};
use crate::App;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{DefaultBodyLimit, State};
use axum::http::{header, StatusCode};
use axum::middleware;
use axum::response::{Html, IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde_json::{json, Value};
use stanok_syntax::Dialect;
use std::sync::Arc;
use std::time::Duration;

pub(crate) type AppState = Arc<App>;

/// three.js as `build.rs` found it (empty when it was not there).
const THREE_MODULE: &str = include_str!(concat!(env!("OUT_DIR"), "/three/three.module.js"));
const THREE_CORE: &str = include_str!(concat!(env!("OUT_DIR"), "/three/three.core.js"));

/// True if the binary carries three.js (the page then draws the view in WebGL).
pub fn has_three() -> bool {
    !THREE_MODULE.is_empty() && !THREE_CORE.is_empty()
}

/// The page: one HTML document with its style and scripts inlined (so a token in the page's URL
/// is all the page needs; only three.js comes as a module from `/assets/`).
fn page() -> String {
    include_str!("../assets/index.html")
        .replace("/*STYLE*/", include_str!("../assets/style.css"))
        .replace(
            "/*SCRIPT*/",
            &[
                format!("const STANOK_THREE = {};", has_three()),
                include_str!("../assets/view2d.js").to_string(),
                include_str!("../assets/view3d.js").to_string(),
                include_str!("../assets/editor.js").to_string(),
                include_str!("../assets/app.js").to_string(),
                include_str!("../assets/manual.js").to_string(),
            ]
            .join("\n"),
        )
}

fn javascript(text: &'static str) -> Response {
    if text.is_empty() {
        return (
            StatusCode::NOT_FOUND,
            "three.js is not built into this panel\n",
        )
            .into_response();
    }
    (
        [
            (header::CONTENT_TYPE, "text/javascript; charset=utf-8"),
            (header::CACHE_CONTROL, "max-age=86400"),
        ],
        text,
    )
        .into_response()
}

/// The router with all routes and access rules (module doc).
pub fn router(app: Arc<App>) -> Router {
    let limit = app.options.upload_limit;
    Router::new()
        .route("/", get(|| async { Html(page()) }))
        .route(
            "/assets/three.module.js",
            get(|| async { javascript(THREE_MODULE) }),
        )
        .route(
            "/assets/three.core.js",
            get(|| async { javascript(THREE_CORE) }),
        )
        .route("/api/state", get(state))
        .route("/api/machine", get(machine_info))
        .route("/api/programs", get(program::list_programs))
        .route(
            "/api/programs/{name}",
            get(program::read_program).put(program::write_program),
        )
        .route("/api/check", post(program::check_program))
        .route("/api/load", post(program::load_program))
        .route("/api/loaded", get(program::loaded_program))
        .route("/api/loaded/lines", get(program::loaded_lines))
        .route("/api/cycle-start", post(program::cycle_start))
        .route("/api/feed-hold", post(program::feed_hold))
        .route("/api/stop", post(program::stop))
        .route("/api/acknowledge", post(program::acknowledge))
        .route("/api/override", post(manual::set_override))
        .route("/api/switches", post(manual::set_switches))
        .route("/api/jog", post(manual::jog))
        .route("/api/jog/alive", post(manual::jog_alive))
        .route("/api/jog/stop", post(manual::jog_stop))
        .route("/api/home", post(manual::home))
        .route("/api/touch-off", post(manual::touch_off))
        .route("/api/mdi", post(manual::mdi))
        .route("/ws", get(websocket))
        .layer(DefaultBodyLimit::max(limit))
        .layer(middleware::from_fn_with_state(
            app.clone(),
            crate::guard::access,
        ))
        .with_state(app)
}

/// A JSON error answer.
pub(crate) fn error(status: StatusCode, message: impl Into<String>) -> Response {
    (status, Json(json!({ "error": message.into() }))).into_response()
}

/// The dialect a request names (`dialect`), or the one its file name implies.
pub(crate) fn dialect_of(name: &str, dialect: Option<&str>) -> Result<Dialect, Box<Response>> {
    match dialect {
        None | Some("") => Ok(Dialect::from_path(std::path::Path::new(name))),
        Some(id) => dialect_by_id(id).ok_or_else(|| {
            let ids: Vec<&str> = DIALECTS.iter().map(|d| d.id()).collect();
            Box::new(error(
                StatusCode::BAD_REQUEST,
                format!("unknown dialect {id:?} ({})", ids.join(", ")),
            ))
        }),
    }
}

async fn state(State(app): State<AppState>) -> Response {
    let json = serde_json::to_value(&*app.machine.status()).unwrap_or(Value::Null);
    Json(json).into_response()
}

/// What the page needs to know of the machine: axes and travel (the travel box), the lathe view,
/// the tools' shapes, the dialects, whether three.js is built in.
async fn machine_info(State(app): State<AppState>) -> Response {
    let m = &app.options.machine;
    let ctx = app.machine.context();
    let axes: Vec<Value> = m
        .axes
        .iter()
        .map(|a| {
            json!({
                "name": a.name.to_string(),
                "index": a.pose_index(),
                "min": finite_or_null(a.min),
                "max": finite_or_null(a.max),
                "rotary": matches!(a.kind, stanok_machine::AxisKind::Rotary),
                "max_velocity": a.max_velocity,
            })
        })
        .collect();
    let tools: Vec<Value> = ctx
        .control
        .tools
        .tools
        .iter()
        .map(|(number, t)| {
            let edge = t.edges.first();
            let radius = edge.map_or(0.0, |e| e.radius);
            let length = edge.map_or(0.0, |e| {
                let l = e.length.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                l.max(e.offset.z.abs())
            });
            json!({ "number": number, "diameter": 2.0 * radius, "length": length })
        })
        .collect();
    let dialects: Vec<Value> = DIALECTS
        .iter()
        .map(|d| json!({ "id": d.id(), "name": dialect_name(*d) }))
        .collect();
    Json(json!({
        "name": m.name,
        "description": m.description,
        "axes": axes,
        "lathe": crate::check::lathe_view(m, Dialect::Rs274ngc),
        "five_axis": m.five_axis().is_some(),
        "tools": tools,
        "dialects": dialects,
        "three": has_three(),
        "jog_speed": m.axes.iter().map(|a| a.max_velocity).fold(f64::INFINITY, f64::min).min(1000.0),
    }))
    .into_response()
}

fn finite_or_null(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

/// The selector's label of a dialect.
pub fn dialect_name(d: Dialect) -> &'static str {
    match d {
        Dialect::Axioma => "AxiOMA",
        Dialect::Rs274ngc => "LinuxCNC RS274/NGC",
        Dialect::Balt => "Balt-System CVU",
        Dialect::Mazatrol => "Mazatrol EIA/ISO",
        Dialect::Nc31 => "NC-31 (lab)",
        Dialect::P2p32 => "2P32 (lab)",
        Dialect::Mc2101 => "MC2101 (lab)",
        Dialect::Gost20999 => "GOST 20999 (lab)",
    }
}

/// Updates per second sent to each page.
const UPDATES_PER_SECOND: u64 = 30;

async fn websocket(State(app): State<AppState>, ws: WebSocketUpgrade) -> Response {
    ws.on_upgrade(move |socket| stream_status(app, socket))
}

/// Sends the latest status ~30 times a second while it changes, and the stock's latest live
/// message when there is a new one (`stock.rs`). One frame in flight per client:
/// a slow client skips snapshots, it never queues them (module doc of `machine.rs`).
async fn stream_status(app: AppState, mut socket: WebSocket) {
    let mut tick = tokio::time::interval(Duration::from_millis(1000 / UPDATES_PER_SECOND));
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut last_seq = u64::MAX;
    // The stock's live messages (`stock.rs`): the latest when it changed, already bounded in
    // size and rate by the machine thread that made it.
    let mut last_stock = 0u64;
    loop {
        tick.tick().await;
        let (stock_seq, stock) = app.machine.stock.latest();
        if stock_seq != last_stock {
            last_stock = stock_seq;
            if let Some(text) = stock {
                if socket.send(Message::Text((&*text).into())).await.is_err() {
                    break;
                }
            }
        }
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
