//! Embeds three.js (the view's WebGL library) into the panel, if it can be had.
//!
//! The version is pinned in `package.json` / `package-lock.json` beside this file; nothing of it is
//! committed. Where it comes from, first found wins:
//! 1. `node_modules/three/build/` beside this file (`npm ci` in this directory; `.ci/run` does it);
//! 2. `npm ci` run here into `OUT_DIR` (when `npm` is on the PATH and `STANOK_NO_NPM` is unset; npm
//!    answers from its cache when offline);
//! 3. nothing: empty files are embedded, and the page draws the path with its own 2D canvas
//!    renderer under a notice that says how to get the 3D view (README, "Operator panel").
//!
//! The files go to `OUT_DIR/three/` for `include_str!` in `http.rs`; `STANOK_THREE` in the
//! environment of the build says which case it was.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const FILES: [&str; 2] = ["three.module.js", "three.core.js"];

fn has_three(dir: &Path) -> bool {
    FILES.iter().all(|f| dir.join(f).is_file())
}

fn npm_ci(manifest: &Path, out: &Path) -> Option<PathBuf> {
    if std::env::var_os("STANOK_NO_NPM").is_some() {
        return None;
    }
    let work = out.join("npm");
    std::fs::create_dir_all(&work).ok()?;
    for f in ["package.json", "package-lock.json"] {
        std::fs::copy(manifest.join(f), work.join(f)).ok()?;
    }
    let ok = Command::new("npm")
        .args([
            "ci",
            "--no-audit",
            "--no-fund",
            "--ignore-scripts",
            "--loglevel=error",
        ])
        .current_dir(&work)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    let dir = work.join("node_modules/three/build");
    (ok && has_three(&dir)).then_some(dir)
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets it"));
    println!("cargo:rerun-if-changed=package.json");
    println!("cargo:rerun-if-changed=package-lock.json");
    println!("cargo:rerun-if-changed=node_modules/three/package.json");
    println!("cargo:rerun-if-env-changed=STANOK_NO_NPM");
    let local = manifest.join("node_modules/three/build");
    let (source, how) = if has_three(&local) {
        (Some(local), "node_modules")
    } else {
        match npm_ci(&manifest, &out) {
            Some(dir) => (Some(dir), "npm ci"),
            None => (None, "none"),
        }
    };
    let target = out.join("three");
    std::fs::create_dir_all(&target).expect("OUT_DIR is writable");
    for f in FILES {
        let text = source
            .as_ref()
            .and_then(|d| std::fs::read_to_string(d.join(f)).ok())
            .unwrap_or_default();
        std::fs::write(target.join(f), text).expect("OUT_DIR is writable");
    }
    if source.is_none() {
        println!(
            "cargo:warning=three.js not found (npm ci in crates/stanok-serve): the panel's view falls back to 2D"
        );
    }
    println!("cargo:rustc-env=STANOK_THREE={how}");
}
