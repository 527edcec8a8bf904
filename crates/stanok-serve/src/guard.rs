//! The access rules every request passes before a handler sees it, in this order:
//!
//! 1. **Host** ([`host_allowed`]). A request is served only if its `Host` names the panel: the
//!    bound address itself (`127.0.0.1:8080`), `localhost` when bound to loopback, any IP literal
//!    when bound to all interfaces (`0.0.0.0`, `::`), or a name given with `--allowed-host`; the
//!    port must be the bound one. Why: DNS rebinding. A web page on `evil.example` can make the
//!    browser resolve `evil.example` to 127.0.0.1 and then call the panel *as its own origin*; the
//!    browser still sends `Host: evil.example`, which is refused here (403). An IP literal cannot
//!    be rebound, so the rule needs no list for addresses.
//! 2. **Declared size** ([`content_length_allowed`]). A `Content-Length` above the upload limit is
//!    answered 413 at once, before a byte of the body is read (a lying `Content-Length:
//!    99999999999` would otherwise hold a connection open waiting for the body). Bodies without a
//!    length are cut at the limit while they are read (`DefaultBodyLimit`).
//! 3. **Token** (when one is set): `Authorization: Bearer <token>` or `?token=<token>`, else 401.
//!    `/assets/…` (public library code, e.g. three.js) is served without it: a module's relative
//!    imports cannot carry a query token, and the code is no secret.
//! 4. **Origin** ([`origin_allowed`]). WebSocket handshakes and state-changing requests (anything
//!    but GET/HEAD/OPTIONS) that carry an `Origin` must come from the panel's own page
//!    (`http://<Host>` or `https://<Host>`); a browser always sends `Origin` on these, so another
//!    site's page cannot start the machine or read its state through the user's browser. A request
//!    without `Origin` is not from a web page (curl, the tests) and passes.

use crate::App;
use axum::extract::{Request, State};
use axum::http::{header, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;

/// Splits a `Host` value into its name and port (`[::1]:80` → `::1`, 80).
fn split_host(host: &str) -> (&str, Option<u16>) {
    if let Some(rest) = host.strip_prefix('[') {
        // An IPv6 literal: `[addr]` or `[addr]:port`.
        if let Some((addr, tail)) = rest.split_once(']') {
            let port = tail.strip_prefix(':').and_then(|p| p.parse().ok());
            return (addr, port);
        }
        return (host, None);
    }
    match host.rsplit_once(':') {
        Some((name, port)) if !name.contains(':') => match port.parse() {
            Ok(p) => (name, Some(p)),
            Err(_) => (host, None),
        },
        _ => (host, None),
    }
}

/// Rule 1 of the module doc.
pub fn host_allowed(host: &str, bound: SocketAddr, allowed: &[String]) -> bool {
    let host = host.trim();
    if host.is_empty() {
        return false;
    }
    // A name given with --allowed-host, with or without its port.
    let (name, port) = split_host(host);
    if allowed.iter().any(|a| {
        a.eq_ignore_ascii_case(host) || (a.eq_ignore_ascii_case(name) && port == Some(bound.port()))
    }) {
        return true;
    }
    if port != Some(bound.port()) && !(port.is_none() && bound.port() == 80) {
        return false;
    }
    match name.parse::<IpAddr>() {
        Ok(ip) if ip == bound.ip() => true,
        Ok(ip) if bound.ip().is_unspecified() => !ip.is_unspecified(),
        Ok(ip) => bound.ip().is_loopback() && ip.is_loopback(),
        Err(_) => bound.ip().is_loopback() && name.eq_ignore_ascii_case("localhost"),
    }
}

/// Rule 2 of the module doc: false if the declared length exceeds `limit` (or is not a number).
pub fn content_length_allowed(value: Option<&str>, limit: usize) -> bool {
    match value {
        None => true,
        Some(v) => v.trim().parse::<u64>().is_ok_and(|n| n <= limit as u64),
    }
}

/// Rule 4 of the module doc: `origin` (if any) is the page of `host`.
pub fn origin_allowed(origin: Option<&str>, host: &str) -> bool {
    match origin {
        None => true,
        Some(o) => {
            let o = o.trim().trim_end_matches('/');
            o.strip_prefix("http://")
                .or_else(|| o.strip_prefix("https://"))
                .is_some_and(|rest| rest.eq_ignore_ascii_case(host.trim()))
        }
    }
}

/// Compares without an early exit on the first differing byte.
fn same_secret(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

fn refuse(status: StatusCode, text: &str) -> Response {
    (status, format!("{text}\n")).into_response()
}

/// Rule 3: the request carries the token (or needs none).
fn token_ok(app: &App, req: &Request) -> bool {
    let Some(token) = &app.options.token else {
        return true;
    };
    if req.uri().path().starts_with("/assets/") {
        return true;
    }
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
    [from_header, from_query]
        .iter()
        .flatten()
        .any(|t| same_secret(t, token))
}

/// The middleware applying the rules of the module doc.
pub async fn access(State(app): State<Arc<App>>, req: Request, next: Next) -> Response {
    let headers = req.headers();
    let text = |name| headers.get(name).and_then(|v| v.to_str().ok());
    let host = text(header::HOST).unwrap_or("").to_string();
    let bound = app.bound_addr();
    if !host_allowed(&host, bound, &app.options.allowed_hosts) {
        return refuse(
            StatusCode::FORBIDDEN,
            "this Host is not the panel's address (serve --allowed-host NAME to allow a name)",
        );
    }
    if !content_length_allowed(text(header::CONTENT_LENGTH), app.options.upload_limit) {
        return refuse(
            StatusCode::PAYLOAD_TOO_LARGE,
            "the request is larger than the upload limit (serve --upload-limit)",
        );
    }
    if !token_ok(&app, &req) {
        return refuse(StatusCode::UNAUTHORIZED, "a valid token is required");
    }
    let upgrade = headers.contains_key(header::UPGRADE);
    let changes_state = !matches!(*req.method(), Method::GET | Method::HEAD | Method::OPTIONS);
    if (upgrade || changes_state) && !origin_allowed(text(header::ORIGIN), &host) {
        return refuse(
            StatusCode::FORBIDDEN,
            "requests that change the machine and WebSockets are accepted only from the panel's own page",
        );
    }
    next.run(req).await
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_host_must_name_the_bound_address() {
        let lo: SocketAddr = "127.0.0.1:8080".parse().unwrap();
        let none: &[String] = &[];
        for ok in [
            "127.0.0.1:8080",
            "localhost:8080",
            "LOCALHOST:8080",
            "127.0.0.2:8080",
        ] {
            assert!(host_allowed(ok, lo, none), "{ok}");
        }
        for bad in [
            "",
            "evil.example",
            "evil.example:8080",
            "127.0.0.1:8081",
            "127.0.0.1",
            "192.168.1.5:8080",
            "localhost.evil.example:8080",
        ] {
            assert!(!host_allowed(bad, lo, none), "{bad}");
        }
        let six: SocketAddr = "[::1]:9000".parse().unwrap();
        assert!(host_allowed("[::1]:9000", six, none));
        assert!(!host_allowed("[::1]:9001", six, none));
        let any: SocketAddr = "0.0.0.0:8080".parse().unwrap();
        assert!(host_allowed("192.168.1.5:8080", any, none));
        assert!(!host_allowed("cnc.shop:8080", any, none));
        let named = ["cnc.shop".to_string()];
        assert!(host_allowed("cnc.shop:8080", any, &named));
        assert!(host_allowed("CNC.shop:8080", any, &named));
        assert!(!host_allowed("cnc.shop:9999", any, &named));
        let with_port = ["proxy.shop:443".to_string()];
        assert!(host_allowed("proxy.shop:443", any, &with_port));
        let eighty: SocketAddr = "127.0.0.1:80".parse().unwrap();
        assert!(host_allowed("localhost", eighty, none));
    }

    #[test]
    fn a_declared_length_over_the_limit_is_refused() {
        assert!(content_length_allowed(None, 10));
        assert!(content_length_allowed(Some("10"), 10));
        assert!(!content_length_allowed(Some("11"), 10));
        assert!(!content_length_allowed(Some("99999999999999999999999"), 10));
        assert!(!content_length_allowed(Some("-1"), 10));
    }

    #[test]
    fn the_origin_must_be_the_panels_own_page() {
        assert!(origin_allowed(None, "127.0.0.1:8080"));
        assert!(origin_allowed(
            Some("http://127.0.0.1:8080"),
            "127.0.0.1:8080"
        ));
        assert!(origin_allowed(
            Some("https://127.0.0.1:8080/"),
            "127.0.0.1:8080"
        ));
        assert!(!origin_allowed(
            Some("http://evil.example"),
            "127.0.0.1:8080"
        ));
        assert!(!origin_allowed(Some("null"), "127.0.0.1:8080"));
        assert!(!origin_allowed(
            Some("http://127.0.0.1:8081"),
            "127.0.0.1:8080"
        ));
    }
}
