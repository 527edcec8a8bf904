//! The access rules of the panel: bind and token, the upload limit, the program directory.

mod common;
use common::*;
use serde_json::{json, Value};
use stanok_serve::{check_bind, App};
use std::io::{BufRead, BufReader, Write};
use std::net::{SocketAddr, TcpStream};

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
