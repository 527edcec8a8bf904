//! The access rules of the panel: bind and token, Host and Origin, the upload limit (also a
//! declared one), the program directory.

mod common;
use common::*;
use serde_json::{json, Value};
use stanok_serve::{check_bind, App};
use std::io::{BufRead, BufReader, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

const TOKEN: &str = "0123456789abcdef-token";

#[test]
fn loopback_needs_no_token_any_other_address_needs_one_of_16_characters() {
    let lo: SocketAddr = "127.0.0.1:8080".parse().unwrap();
    let lo6: SocketAddr = "[::1]:8080".parse().unwrap();
    let any: SocketAddr = "0.0.0.0:8080".parse().unwrap();
    let lan: SocketAddr = "192.168.1.20:8080".parse().unwrap();
    assert!(check_bind(&lo, None).is_ok());
    assert!(check_bind(&lo6, None).is_ok());
    assert!(check_bind(&any, None).unwrap_err().contains("--token"));
    assert!(check_bind(&lan, None).is_err());
    assert!(check_bind(&lan, Some("short")).unwrap_err().contains("16"));
    assert!(check_bind(&lan, Some(TOKEN)).is_ok());
    // The server itself refuses to start that way.
    let mut o = options(temp_programs("bind"));
    o.bind = "0.0.0.0:0".parse().unwrap();
    assert!(App::start(o).is_err());
}

/// The status line of a WebSocket handshake for `path` (the connection stays open on 101, so
/// only the first line is read).
fn ws_handshake_status(server: &Server, path: &str) -> u16 {
    let mut s = TcpStream::connect(server.addr).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n",
        server.addr
    )
    .unwrap();
    let mut line = String::new();
    BufReader::new(s).read_line(&mut line).unwrap();
    line.split(' ').nth(1).unwrap().parse().unwrap()
}

#[test]
fn with_a_token_every_http_and_websocket_request_must_carry_it() {
    let mut o = options(temp_programs("token"));
    o.token = Some(TOKEN.into());
    let server = Server::start(o);
    for path in ["/", "/api/state", "/api/programs", "/api/loaded"] {
        assert_eq!(server.raw("GET", path, b"", None).0, 401, "{path}");
        assert_eq!(
            server
                .raw("GET", path, b"", Some("wrong-token-wrong-token"))
                .0,
            401
        );
        assert_eq!(server.raw("GET", path, b"", Some(TOKEN)).0, 200, "{path}");
        let with_query = format!("{path}?token={TOKEN}");
        assert_eq!(server.raw("GET", &with_query, b"", None).0, 200, "{path}");
    }
    for path in [
        "/api/cycle-start",
        "/api/stop",
        "/api/feed-hold",
        "/api/acknowledge",
    ] {
        assert_eq!(server.raw("POST", path, b"", None).0, 401, "{path}");
    }
    // Nothing was started or held by the refused requests.
    let s = server.state();
    assert_eq!(s["run_state"], "idle");
    assert_eq!(s["held"], false);
    assert_eq!(ws_handshake_status(&server, "/ws"), 401);
    assert_eq!(ws_handshake_status(&server, "/ws?token=nope"), 401);
    assert_eq!(
        ws_handshake_status(&server, &format!("/ws?token={TOKEN}")),
        101
    );
}

#[test]
fn bodies_above_the_upload_limit_are_refused_with_413() {
    let mut o = options(temp_programs("limit"));
    o.upload_limit = 1024;
    let server = Server::start(o);
    let small = "G0 X1\n".repeat(100); // 600 bytes
    let big = "G0 X1\n".repeat(400); // 2400 bytes
    assert_eq!(
        server
            .raw("PUT", "/api/programs/small.nc", small.as_bytes(), None)
            .0,
        200
    );
    assert_eq!(
        server
            .raw("PUT", "/api/programs/big.nc", big.as_bytes(), None)
            .0,
        413
    );
    assert!(!server.programs.join("big.nc").exists());
    let load = json!({"name": "big.nc", "text": big}).to_string();
    assert_eq!(
        server.raw("POST", "/api/load", load.as_bytes(), None).0,
        413
    );
    assert_eq!(
        std::fs::read_to_string(server.programs.join("small.nc")).unwrap(),
        small
    );
}

#[test]
fn the_program_directory_is_the_only_place_read_or_written() {
    let programs = temp_programs("files");
    let outside = programs
        .parent()
        .unwrap()
        .join(format!("stanok-outside-{}.nc", std::process::id()));
    std::fs::write(&outside, "secret\n").unwrap();
    std::fs::write(programs.join("ok.ngc"), "G0 X1\nM2\n").unwrap();
    std::fs::write(programs.join("notes.sh"), "echo hi\n").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&outside, programs.join("link.nc")).unwrap();
    let server = Server::start(options(programs.clone()));

    let (code, body) = server.call("GET", "/api/programs/ok.ngc", Value::Null);
    assert_eq!((code, body["text"].as_str()), (200, Some("G0 X1\nM2\n")));
    let outside_name = outside.file_name().unwrap().to_string_lossy().to_string();
    for name in [
        format!("..%2F{outside_name}"),
        "..%2F..%2F..%2Fetc%2Fpasswd".to_string(),
        "%2Fetc%2Fpasswd".to_string(),
        "..".to_string(),
        ".hidden.nc".to_string(),
        "notes.sh".to_string(),
        "a%00b.nc".to_string(),
        "sub%5C..%5Cx.nc".to_string(),
        "link.nc".to_string(),
    ] {
        let path = format!("/api/programs/{name}");
        let (code, _) = server.raw("GET", &path, b"", None);
        assert!(code == 400 || code == 404, "GET {name}: {code}");
        assert_ne!(code, 200, "GET {name}");
        let (code, _) = server.raw("PUT", &path, b"overwritten\n", None);
        assert!(
            code == 400 || code == 404 || code == 405,
            "PUT {name}: {code}"
        );
    }
    // A name that would reach the outside file through `..` or the link changed nothing there.
    assert_eq!(std::fs::read_to_string(&outside).unwrap(), "secret\n");
    assert_eq!(
        std::fs::read_to_string(programs.join("notes.sh")).unwrap(),
        "echo hi\n"
    );
    // The listing shows plain program files only (no links, no other files).
    let (_, list) = server.call("GET", "/api/programs", Value::Null);
    assert_eq!(list["programs"], json!(["ok.ngc"]));
    let _ = std::fs::remove_file(&outside);
}

/// Issue 17 item 9: DNS rebinding. A request whose Host is not the panel's address is refused
/// (pages, API, WebSocket), and nothing it asked for happens; names given with `--allowed-host`
/// are accepted.
#[test]
fn a_foreign_host_is_refused_and_an_allowed_name_accepted() {
    let mut o = options(temp_programs("host"));
    o.allowed_hosts = vec!["cnc.shop.lan".into()];
    let server = Server::start(o);
    let port = server.addr.port();
    let own = server.addr.to_string();
    for host in [
        "evil.example".to_string(),
        format!("evil.example:{port}"),
        format!("127.0.0.1:{}", port.wrapping_add(1)),
        String::new(),
    ] {
        for (method, path) in [
            ("GET", "/"),
            ("GET", "/api/state"),
            ("POST", "/api/cycle-start"),
        ] {
            let (code, body) = server.raw_with(method, path, b"", None, &host, "");
            assert_eq!(code, 403, "{method} {path} Host {host:?}: {body}");
        }
        assert_eq!(ws_status_with(&server, &host, ""), 403, "Host {host:?}");
    }
    let (code, body) = server.raw_with(
        "POST",
        "/api/load",
        json!({"name": "x.ngc", "text": "G0 X1\nM2\n"})
            .to_string()
            .as_bytes(),
        None,
        "evil.example",
        "",
    );
    assert_eq!(code, 403, "{body}");
    assert_eq!(
        server.call("GET", "/api/loaded", Value::Null).1["name"],
        Value::Null
    );
    for host in [
        own.clone(),
        format!("localhost:{port}"),
        format!("cnc.shop.lan:{port}"),
    ] {
        assert_eq!(
            server.raw_with("GET", "/api/state", b"", None, &host, "").0,
            200,
            "{host}"
        );
    }
}

/// A WebSocket handshake's status with this Host and extra headers.
fn ws_status_with(server: &Server, host: &str, extra: &str) -> u16 {
    let mut s = TcpStream::connect(server.addr).unwrap();
    write!(
        s,
        "GET /ws HTTP/1.1\r\nHost: {host}\r\n{extra}Upgrade: websocket\r\nConnection: Upgrade\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n"
    )
    .unwrap();
    let mut line = String::new();
    BufReader::new(s).read_line(&mut line).unwrap();
    line.split(' ').nth(1).unwrap_or("0").parse().unwrap_or(0)
}

/// Issue 17 item 9: another site's page may not drive the machine or read its state through the
/// operator's browser: WebSockets and state-changing requests with a foreign Origin are refused;
/// the panel's own Origin (and no Origin: not a browser) passes.
#[test]
fn state_changing_requests_and_websockets_need_the_panels_own_origin() {
    let server = Server::start(options(temp_programs("origin")));
    let own = server.addr.to_string();
    let evil = "Origin: http://evil.example\r\n";
    for path in [
        "/api/cycle-start",
        "/api/feed-hold",
        "/api/stop",
        "/api/acknowledge",
    ] {
        let (code, _) = server.raw_with("POST", path, b"", None, &own, evil);
        assert_eq!(code, 403, "{path}");
    }
    let (code, _) = server.raw_with("PUT", "/api/programs/x.nc", b"G0 X1\n", None, &own, evil);
    assert_eq!(code, 403);
    assert!(!server.programs.join("x.nc").exists());
    assert_eq!(
        server.state()["held"],
        false,
        "the refused feed hold did nothing"
    );
    assert_eq!(ws_status_with(&server, &own, evil), 403);
    assert_eq!(ws_status_with(&server, &own, "Origin: null\r\n"), 403);
    // A GET from another origin is no harm (the browser does not let it read the answer).
    assert_eq!(
        server
            .raw_with("GET", "/api/state", b"", None, &own, evil)
            .0,
        200
    );
    let mine = format!("Origin: http://{own}\r\n");
    assert_eq!(
        server
            .raw_with("POST", "/api/feed-hold", b"", None, &own, &mine)
            .0,
        200
    );
    assert_eq!(ws_status_with(&server, &own, &mine), 101);
    assert_eq!(ws_status_with(&server, &own, ""), 101);
}

/// Issue 17 item 9: a declared Content-Length over the limit is answered 413 at once, without
/// waiting for a body that never comes.
#[test]
fn a_lying_content_length_is_answered_413_at_once() {
    let server = Server::start(options(temp_programs("lying")));
    let mut s = TcpStream::connect(server.addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    let t0 = Instant::now();
    write!(
        s,
        "POST /api/load HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\n\
         Content-Length: 99999999999\r\n\r\n{{\"name\":",
        server.addr
    )
    .unwrap();
    let mut line = String::new();
    BufReader::new(&s).read_line(&mut line).unwrap();
    let took = t0.elapsed();
    assert!(line.starts_with("HTTP/1.1 413"), "{line}");
    assert!(took < Duration::from_millis(500), "answered after {took:?}");
    assert_eq!(server.state()["run_state"], "idle");
}
