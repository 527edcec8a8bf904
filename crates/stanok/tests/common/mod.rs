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

/// Runs `stanok` with `args`, extra environment variables (`NO_COLOR` and `CLICOLOR_FORCE` are
/// removed first unless given), standard input `stdin` and working directory `cwd`.
pub fn stanok_with(
    args: &[&str],
    env: &[(&str, &str)],
    stdin: Option<&str>,
    cwd: Option<&std::path::Path>,
) -> (i32, String, String) {
    use std::io::Write;
    use std::process::Stdio;
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stanok"));
    cmd.args(args)
        .env_remove("NO_COLOR")
        .env_remove("CLICOLOR_FORCE")
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    for (k, v) in env {
        cmd.env(k, v);
    }
    if let Some(dir) = cwd {
        cmd.current_dir(dir);
    }
    let mut child = cmd.spawn().expect("run stanok");
    if let Some(text) = stdin {
        let mut pipe = child.stdin.take().unwrap();
        pipe.write_all(text.as_bytes()).unwrap();
    }
    let out = child.wait_with_output().expect("wait for stanok");
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
