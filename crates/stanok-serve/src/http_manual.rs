//! Overrides, switches and the manual modes over HTTP. A manual action goes to the machine thread
//! as an event (`manual.rs` does it there) and the handler waits a little for its answer: a
//! refusal (outside travel, a program in progress, an MDI error) comes at once; a motion that is
//! still going is answered `{"moving": true}` and the page follows it in the status.

use crate::http::{dialect_of, error, AppState};
use crate::machine::{Event, Manual, ManualReply};
use axum::extract::State;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::json;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// How long a continuous jog goes on without the page's "still held", ms.
pub const JOG_ALIVE_MS: u64 = 500;

#[derive(Debug, Deserialize)]
pub(crate) struct Override {
    #[serde(default)]
    feed: Option<f64>,
    #[serde(default)]
    rapid: Option<f64>,
    #[serde(default)]
    spindle: Option<f64>,
}

pub(crate) async fn set_override(State(app): State<AppState>, Json(o): Json<Override>) -> Response {
    let knobs = &app.machine.controls.overrides;
    let checks = [
        (o.feed, 0.0, 200.0, "feed override is 0…200 %"),
        (o.rapid, 0.0, 100.0, "rapid override is 0…100 %"),
        (o.spindle, 50.0, 120.0, "spindle override is 50…120 %"),
    ];
    for (value, lo, hi, why) in checks {
        if let Some(v) = value {
            if !(lo..=hi).contains(&v) {
                return error(StatusCode::BAD_REQUEST, why);
            }
        }
    }
    // Whole percent, as the knobs show them.
    let fraction = |v: f64| v.round() / 100.0;
    if let Some(v) = o.feed {
        knobs.set_feed(fraction(v));
    }
    if let Some(v) = o.rapid {
        knobs.set_rapid(fraction(v));
    }
    if let Some(v) = o.spindle {
        knobs.set_spindle(fraction(v));
    }
    let (f, r, s) = crate::machine::switches(&app.machine.controls);
    // At rest the status shows the knobs at once; while moving the setpoints publish them as
    // they take effect (paced.rs).
    if !app.machine.status().run_state.busy() {
        app.machine.publish(|st| {
            st.feed_override = f;
            st.rapid_override = r;
            st.spindle_override = s;
        });
    }
    Json(json!({ "feed": f, "rapid": r, "spindle": s })).into_response()
}

#[derive(Debug, Deserialize)]
pub(crate) struct Switches {
    #[serde(default)]
    single_block: Option<bool>,
    #[serde(default)]
    optional_stop: Option<bool>,
}

pub(crate) async fn set_switches(
    State(app): State<AppState>,
    Json(sw): Json<Switches>,
) -> Response {
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
    app.machine.publish(|s| {
        s.single_block = sb;
        s.optional_stop = os;
    });
    Json(json!({ "single_block": sb, "optional_stop": os })).into_response()
}

/// The `Pose` index of an axis letter the machine has.
fn axis_index(app: &AppState, name: &str) -> Result<usize, Box<Response>> {
    let letter = name.trim().to_ascii_uppercase();
    app.options
        .machine
        .axes
        .iter()
        .find(|a| a.name.to_string() == letter)
        .map(|a| a.pose_index())
        .ok_or_else(|| {
            Box::new(error(
                StatusCode::BAD_REQUEST,
                format!("machine {} has no axis {name:?}", app.options.machine.name),
            ))
        })
}

/// Sends a manual action and waits up to `wait` for its answer.
async fn manual(app: &AppState, action: Manual, wait: Duration) -> Response {
    if app.machine.status().run_state.program_active() {
        return error(
            StatusCode::CONFLICT,
            "a program is in progress: stop it first",
        );
    }
    let (tx, rx) = tokio::sync::oneshot::channel();
    app.machine.send(Event::Manual(action, Instant::now(), tx));
    match tokio::time::timeout(wait, rx).await {
        Ok(Ok(ManualReply::Done { note, diagnostics })) => {
            Json(json!({ "done": note, "diagnostics": diagnostics })).into_response()
        }
        Ok(Ok(ManualReply::Refused { error, diagnostics })) => (
            StatusCode::CONFLICT,
            Json(json!({ "error": error, "diagnostics": diagnostics })),
        )
            .into_response(),
        Ok(Err(_)) => error(
            StatusCode::INTERNAL_SERVER_ERROR,
            "the machine thread is gone",
        ),
        Err(_) => Json(json!({ "moving": true })).into_response(),
    }
}

#[derive(Debug, Deserialize)]
pub(crate) struct Jog {
    axis: String,
    direction: f64,
    /// Step, mm (deg); absent = continuous.
    #[serde(default)]
    increment: Option<f64>,
    /// mm/min (deg/min); absent = the panel's default.
    #[serde(default)]
    speed: Option<f64>,
}

pub(crate) async fn jog(State(app): State<AppState>, Json(j): Json<Jog>) -> Response {
    let axis = match axis_index(&app, &j.axis) {
        Ok(a) => a,
        Err(r) => return *r,
    };
    if !(j.direction == 1.0 || j.direction == -1.0) {
        return error(StatusCode::BAD_REQUEST, "direction is 1 or -1");
    }
    if let Some(inc) = j.increment {
        if !(inc > 0.0 && inc <= 1000.0) {
            return error(
                StatusCode::BAD_REQUEST,
                "the increment is more than 0 and at most 1000",
            );
        }
    }
    let speed = j.speed.unwrap_or(1000.0);
    if !(speed > 0.0 && speed.is_finite()) {
        return error(StatusCode::BAD_REQUEST, "the jog speed must be more than 0");
    }
    let c = &app.machine.controls;
    c.jog_until_ms
        .store(c.now_ms() + JOG_ALIVE_MS, Ordering::Relaxed);
    let action = Manual::Jog {
        axis,
        direction: j.direction,
        increment: j.increment,
        speed,
    };
    manual(&app, action, Duration::from_millis(300)).await
}

/// A continuous jog goes on for another `JOG_ALIVE_MS`.
pub(crate) async fn jog_alive(State(app): State<AppState>) -> Response {
    let c = &app.machine.controls;
    c.jog_until_ms
        .store(c.now_ms() + JOG_ALIVE_MS, Ordering::Relaxed);
    Json(json!({ "alive": true })).into_response()
}

/// Ends a continuous jog (it brakes on the path).
pub(crate) async fn jog_stop(State(app): State<AppState>) -> Response {
    app.machine
        .controls
        .jog_until_ms
        .store(0, Ordering::Relaxed);
    Json(json!({ "stopping": true })).into_response()
}

#[derive(Debug, Deserialize)]
pub(crate) struct Home {
    #[serde(default)]
    axis: Option<String>,
}

pub(crate) async fn home(State(app): State<AppState>, body: axum::body::Bytes) -> Response {
    let h: Home = if body.iter().all(u8::is_ascii_whitespace) {
        Home { axis: None }
    } else {
        match serde_json::from_slice(&body) {
            Ok(h) => h,
            Err(e) => return error(StatusCode::BAD_REQUEST, format!("home: {e}")),
        }
    };
    let axis = match h.axis.as_deref() {
        None | Some("") => None,
        Some(name) => match axis_index(&app, name) {
            Ok(a) => Some(a),
            Err(r) => return *r,
        },
    };
    manual(&app, Manual::Home { axis }, Duration::from_millis(300)).await
}

#[derive(Debug, Deserialize)]
pub(crate) struct TouchOff {
    axis: String,
    value: f64,
}

pub(crate) async fn touch_off(State(app): State<AppState>, Json(t): Json<TouchOff>) -> Response {
    let axis = match axis_index(&app, &t.axis) {
        Ok(a) => a,
        Err(r) => return *r,
    };
    if app.machine.status().run_state.busy() {
        return error(StatusCode::CONFLICT, "the machine is moving: wait for it");
    }
    let action = Manual::TouchOff {
        axis,
        value: t.value,
    };
    manual(&app, action, Duration::from_secs(10)).await
}

#[derive(Debug, Deserialize)]
pub(crate) struct Mdi {
    text: String,
    #[serde(default)]
    dialect: Option<String>,
}

pub(crate) async fn mdi(State(app): State<AppState>, Json(m): Json<Mdi>) -> Response {
    // The dialect named, else the loaded program's (the status shows it), else RS274/NGC.
    let fallback = app.machine.status().dialect.clone();
    let dialect = match dialect_of("", Some(m.dialect.as_deref().unwrap_or(&fallback))) {
        Ok(d) => d,
        Err(r) => return *r,
    };
    if app.machine.status().run_state.busy() {
        return error(StatusCode::CONFLICT, "the machine is moving: wait for it");
    }
    let action = Manual::Mdi {
        text: m.text,
        dialect,
    };
    manual(&app, action, Duration::from_secs(2)).await
}
