//! `stanok serve` refuses to start in the configurations the panel's access rules forbid.

mod common;
use common::*;

#[test]
fn serve_refuses_a_non_loopback_bind_without_a_token_and_a_missing_program_directory() {
    let (code, _, err) = stanok(&["serve", "--bind", "0.0.0.0:0", "--programs", "."]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("requires --token"), "{err}");
    let (code, _, err) = stanok(&[
        "serve",
        "--bind",
        "0.0.0.0:0",
        "--token",
        "short",
        "--programs",
        ".",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("at least 16"), "{err}");
    let (code, _, err) = stanok(&[
        "serve",
        "--bind",
        "127.0.0.1:0",
        "--programs",
        "/nonexistent/stanok-programs",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("program directory"), "{err}");
}
