//! # stanok-serve: the operator panel (`stanok serve`)
//!
//! A web HMI that runs programs on the simulated machine in real time:
//!
//! ```text
//!  browser ──HTTP JSON──▶ guard.rs (Host, size, token, Origin) ─▶ http*.rs (axum) ──events──▶ machine thread
//!     ▲                      │ jobs.rs: check.rs (check, preview, travel) on       │ run.rs, manual.rs:
//!     │                      │   budgeted, cancellable threads                     │ Interpreter → tag →
//!     │                      │ files.rs (the program directory)                    │ SimMachine (paced.rs)
//!     └──WebSocket ~30/s─────┴──────────── Mutex<Status> ◀─────────────────────────┘
//! ```
//!
//! * [`machine`]: the machine thread's types and loop; [`run`]: a program (or MDI block) through
//!   interpreter → block search → simulated machine; [`paced`]: pacing, publishing, stop on the
//!   path; [`executing`]: the state of the block being executed travels with its motion;
//!   [`manual`]: jog, reference return, touch-off, MDI.
//! * [`search`]: block search (start at line N with a full run's state there).
//! * [`state`]: the machine state read off the executed Canon stream; G and M vectors.
//! * [`check`]: diagnostics, travel checks and the preview (path at a level of detail, [`lod`];
//!   planned time), run as [`jobs`] under a time budget on threads with a known stack.
//! * [`files`]: the program directory and its name rules.
//! * [`guard`]: the access rules; [`http`], [`http_program`], [`http_manual`]: the routes.
//! * `assets/`: the page (HTML, CSS, JS), embedded at build time; three.js (pinned in
//!   `package.json`, installed by `npm ci`, embedded by `build.rs`) draws the view when present.
//!
//! Architecture invariants: this is the only crate that knows HTTP, tokio or the browser; it uses
//! the pipeline crates exactly as `stanok run` does (interpreter → machine, one way), plus the
//! motion stage's [`HoldSwitch`](stanok_motion::hold::HoldSwitch). The machine thread never waits
//! for a client. Bound to a non-loopback address the server refuses to start without a token
//! ([`check_bind`]). No request can stop the server: its work runs in jobs that catch panics and
//! have their own stacks, budgets and cancellation.
#![deny(missing_docs)]

pub mod check;
pub mod executing;
pub mod files;
pub mod guard;
pub mod http;
pub mod http_manual;
pub mod http_program;
pub mod jobs;
pub mod lod;
pub mod machine;
pub mod manual;
pub mod paced;
pub mod run;
pub mod search;
pub mod state;
pub mod stock;

use files::ProgramDir;
use jobs::{JobLimits, Jobs};
use machine::{MachineConfig, Shared};
use stanok_machine::MachineData;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

/// Default request body limit (uploads), bytes: 64 MB.
pub const DEFAULT_UPLOAD_LIMIT: usize = 64 * 1024 * 1024;

/// Shortest token accepted, characters.
pub const MIN_TOKEN_LEN: usize = 16;

/// How `stanok serve` runs.
#[derive(Debug, Clone)]
pub struct ServeOptions {
    /// Address to listen on (default 127.0.0.1:8080).
    pub bind: SocketAddr,
    /// Access token; required off loopback.
    pub token: Option<String>,
    /// Host names accepted besides the bound address (`--allowed-host`; see `guard.rs`).
    pub allowed_hosts: Vec<String>,
    /// The program directory.
    pub programs: PathBuf,
    /// Machine data.
    pub machine: MachineData,
    /// Request body limit, bytes.
    pub upload_limit: usize,
    /// 1 = real time, 10 = ten times faster, 0 = as fast as the host can (tests).
    pub time_scale: f64,
    /// Servo period, s.
    pub servo_period_s: f64,
    /// Wall-time budget of one check, load or preview (`--job-budget`).
    pub job_budget: Duration,
    /// Points a preview sends to the page at most.
    pub preview_points: usize,
}

impl ServeOptions {
    /// Defaults: loopback port 8080, no token, 64 MB uploads, real time, 1 ms servo period, 60 s
    /// per job, 300,000 preview points.
    pub fn new(machine: MachineData, programs: PathBuf) -> Self {
        ServeOptions {
            bind: SocketAddr::from(([127, 0, 0, 1], 8080)),
            token: None,
            allowed_hosts: Vec::new(),
            programs,
            machine,
            upload_limit: DEFAULT_UPLOAD_LIMIT,
            time_scale: 1.0,
            servo_period_s: 0.001,
            job_budget: JobLimits::default().wall,
            preview_points: lod::DEFAULT_BUDGET,
        }
    }
}

/// The bind rule: loopback needs nothing; any other address needs a token of at least
/// [`MIN_TOKEN_LEN`] characters.
pub fn check_bind(bind: &SocketAddr, token: Option<&str>) -> Result<(), String> {
    match token {
        Some(t) if t.chars().count() < MIN_TOKEN_LEN => Err(format!(
            "--token must be at least {MIN_TOKEN_LEN} characters"
        )),
        Some(_) => Ok(()),
        None if bind.ip().is_loopback() => Ok(()),
        None => Err(format!(
            "binding {bind} (not loopback) requires --token: every request must then carry it"
        )),
    }
}

/// The running panel: options, program directory, machine thread, jobs, loaded program.
#[derive(Debug)]
pub struct App {
    /// How it runs.
    pub options: ServeOptions,
    /// The program directory.
    pub programs: ProgramDir,
    /// The machine thread's shared state.
    pub machine: Arc<Shared>,
    /// Checks, loads and previews.
    pub jobs: Jobs,
    bound: OnceLock<SocketAddr>,
    loaded: Mutex<Option<http_program::Loaded>>,
}

impl App {
    /// Checks the options and starts the machine thread.
    pub fn start(options: ServeOptions) -> Result<Arc<App>, String> {
        check_bind(&options.bind, options.token.as_deref())?;
        if !(options.time_scale >= 0.0 && options.time_scale.is_finite()) {
            return Err("--time-scale must be 0 (unpaced) or more".into());
        }
        if options.job_budget.is_zero() {
            return Err("--job-budget must be more than 0 s".into());
        }
        let programs = ProgramDir::new(&options.programs)?;
        let machine = machine::spawn(MachineConfig {
            machine: options.machine.clone(),
            subroutine_path: vec![programs.root().to_path_buf()],
            time_scale: options.time_scale,
            servo_period_s: options.servo_period_s,
        });
        let jobs = Jobs::new(JobLimits {
            wall: options.job_budget,
        });
        Ok(Arc::new(App {
            options,
            programs,
            machine,
            jobs,
            bound: OnceLock::new(),
            loaded: Mutex::new(None),
        }))
    }

    fn subroutine_path(&self) -> Vec<PathBuf> {
        vec![self.programs.root().to_path_buf()]
    }

    /// The address the server listens on (the configured one until it is bound).
    pub fn bound_addr(&self) -> SocketAddr {
        self.bound.get().copied().unwrap_or(self.options.bind)
    }
}

/// Serves until the process ends (`stanok serve`). `on_listening` gets the bound address.
pub async fn serve(app: Arc<App>, on_listening: impl FnOnce(SocketAddr)) -> Result<(), String> {
    let listener = tokio::net::TcpListener::bind(app.options.bind)
        .await
        .map_err(|e| format!("cannot listen on {}: {e}", app.options.bind))?;
    let addr = listener.local_addr().map_err(|e| e.to_string())?;
    let _ = app.bound.set(addr);
    on_listening(addr);
    axum::serve(listener, http::router(app))
        .await
        .map_err(|e| e.to_string())
}

/// `stanok serve`: starts the panel and blocks.
pub fn run(options: ServeOptions) -> Result<(), String> {
    let app = App::start(options)?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| e.to_string())?;
    let token = app.options.token.clone();
    runtime.block_on(serve(app, |addr| {
        let query = token.map(|t| format!("/?token={t}")).unwrap_or_default();
        eprintln!("stanok serve: operator panel on http://{addr}{query}");
    }))
}
