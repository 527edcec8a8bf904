//! Helpers shared by the command-line tests: run the binary, find corpus and repository files,
//! write temporary programs, parse JSON output.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;

/// Runs `stanok` with `args`: (exit code, stdout, stderr).
pub fn stanok(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_stanok"))
        .args(args)
        .output()
        .expect("run stanok");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A file of `../shared/corpus`, read in place.
pub fn corpus(path: &str) -> String {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus"
    ))
    .join(path)
    .display()
    .to_string()
}

/// A file of this repository.
pub fn repo(path: &str) -> String {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join(path)
        .display()
        .to_string()
}

/// Writes `text` to a file in a directory of this test process (`tag` keeps test binaries apart).
pub fn temp_in(tag: &str, name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("stanok-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// Parses JSON or fails with the text.
pub fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}
