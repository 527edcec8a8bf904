//! Helpers of the panel's tests: a server in this process on a free loopback port, a small
//! blocking HTTP client (one request per connection), waiting for run states, the corpus.
#![allow(dead_code)]

use serde_json::Value;
use stanok_machine::MachineData;
use stanok_serve::{App, ServeOptions};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// A running panel.
pub struct Server {
    pub addr: SocketAddr,
    pub token: Option<String>,
    pub programs: PathBuf,
}

/// A fresh, empty program directory for one test.
pub fn temp_programs(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stanok-serve-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Options for tests: the built-in mill, unpaced, 4 ms servo period, on a free port.
pub fn options(programs: PathBuf) -> ServeOptions {
    let mut o = ServeOptions::new(MachineData::builtin("mill").unwrap(), programs);
    o.bind = SocketAddr::from(([127, 0, 0, 1], 0));
    o.time_scale = 0.0;
    o.servo_period_s = 0.004;
    o
}

impl Server {
    /// Starts the panel with `options` on its own runtime thread.
    pub fn start(options: ServeOptions) -> Server {
        let token = options.token.clone();
        let programs = options.programs.clone();
        let app = App::start(options).expect("start the panel");
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let rt = tokio::runtime::Builder::new_multi_thread()
                .worker_threads(1)
                .enable_all()
                .build()
                .unwrap();
            rt.block_on(stanok_serve::serve(app, |addr| tx.send(addr).unwrap()))
                .unwrap();
        });
        let addr = rx.recv_timeout(Duration::from_secs(10)).expect("listening");
        Server {
            addr,
            token,
            programs,
        }
    }

    /// One request; `token` is sent as a bearer header when given. Returns (status, body).
    pub fn raw(&self, method: &str, path: &str, body: &[u8], token: Option<&str>) -> (u16, String) {
        let host = self.addr.to_string();
        self.raw_with(method, path, body, token, &host, "")
    }

    /// One request with this `Host` and extra header lines (each ending in `\r\n`).
    pub fn raw_with(
        &self,
        method: &str,
        path: &str,
        body: &[u8],
        token: Option<&str>,
        host: &str,
        extra: &str,
    ) -> (u16, String) {
        let mut s = TcpStream::connect(self.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
        let auth = token
            .map(|t| format!("Authorization: Bearer {t}\r\n"))
            .unwrap_or_default();
        let head = format!(
            "{method} {path} HTTP/1.1\r\nHost: {host}\r\n{auth}{extra}Content-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
            body.len()
        );
        s.write_all(head.as_bytes()).unwrap();
        // The server may answer (413) before reading a large body; a failed write is fine then.
        let _ = s.write_all(body);
        let mut out = Vec::new();
        let _ = s.read_to_end(&mut out);
        let text = String::from_utf8_lossy(&out).into_owned();
        let status = text
            .split(' ')
            .nth(1)
            .and_then(|c| c.parse().ok())
            .unwrap_or(0);
        let (headers, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
        let body = if headers
            .to_ascii_lowercase()
            .contains("transfer-encoding: chunked")
        {
            dechunk(body)
        } else {
            body.to_string()
        };
        (status, body)
    }

    /// A request with the server's own token; the body as JSON (Null if it is not JSON).
    pub fn call(&self, method: &str, path: &str, body: Value) -> (u16, Value) {
        let text = if body.is_null() {
            String::new()
        } else {
            body.to_string()
        };
        let (status, out) = self.raw(method, path, text.as_bytes(), self.token.as_deref());
        (status, serde_json::from_str(&out).unwrap_or(Value::Null))
    }

    pub fn state(&self) -> Value {
        self.call("GET", "/api/state", Value::Null).1
    }

    /// Reference return of every axis: the machine back at its origin (tests start runs there).
    pub fn home(&self) {
        let (code, body) = self.call("POST", "/api/home", Value::Null);
        assert_eq!(code, 200, "{body}");
        let s = self.wait_for(
            &["idle", "finished", "stopped", "alarm"],
            Duration::from_secs(60),
        );
        for i in 0..9 {
            assert_eq!(s["machine_position"][i].as_f64().unwrap(), 0.0, "{s}");
        }
    }

    /// Waits until the run state is one of `states`; returns the status.
    pub fn wait_for(&self, states: &[&str], timeout: Duration) -> Value {
        let t0 = Instant::now();
        loop {
            let s = self.state();
            if states.iter().any(|w| s["run_state"] == *w) {
                return s;
            }
            assert!(
                t0.elapsed() < timeout,
                "run state still {} after {timeout:?}, waiting for {states:?}: {s}",
                s["run_state"]
            );
            std::thread::sleep(Duration::from_millis(5));
        }
    }
}

fn dechunk(body: &str) -> String {
    let mut out = String::new();
    let mut rest = body;
    while let Some((size, tail)) = rest.split_once("\r\n") {
        let n = usize::from_str_radix(size.trim(), 16).unwrap_or(0);
        if n == 0 || tail.len() < n {
            break;
        }
        out.push_str(&tail[..n]);
        rest = tail[n..].trim_start_matches("\r\n");
    }
    out
}

/// A directory of `../shared/corpus`, read in place.
pub fn corpus(dir: &str) -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus"
    ))
    .join(dir)
}

/// Every AxiOMA and RS274/NGC program of the corpus, sorted.
pub fn corpus_programs() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for (dir, ext) in [("axioma", "nc"), ("rs274ngc", "ngc")] {
        let Ok(entries) = std::fs::read_dir(corpus(dir)) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.extension().and_then(|x| x.to_str()) == Some(ext) {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}
