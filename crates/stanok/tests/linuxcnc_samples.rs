//! `stanok canon` against LinuxCNC's own traces of its sample programs (the goldens in
//! tests/linuxcnc-samples/expected, made by `scripts/linuxcnc-parity.sh --update-goldens` with
//! LinuxCNC 2.9's rs274, tool table tests/linuxcnc-samples/sim.tbl, machine sim.toml).
//!
//! The programs are LinuxCNC's, not ours: they are read from the linuxcnc-uspace package's files
//! under `$STANOK_LINUXCNC_ROOT` (default `/`). `.ci/run` extracts the package there without
//! installing LinuxCNC and sets `STANOK_REQUIRE_LINUXCNC_SAMPLES=1`, which turns missing programs
//! into a failure; elsewhere the test says it skipped.
//!
//! Comparison: `stanok_canon::linuxcnc_trace` (the rules of every LinuxCNC parity check): line
//! by line, numbers within 1.0001e-4 (both sides print 4 decimals); if LinuxCNC stopped with an
//! error, Stanok must stop too, with LinuxCNC's message, having printed LinuxCNC's lines up to
//! the failing block and LinuxCNC nothing that moves after them (Stanok's blocks are atomic).

mod common;
use common::*;
use stanok_canon::linuxcnc_trace::{compare, parse};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(std::env::var("STANOK_LINUXCNC_ROOT").unwrap_or_else(|_| "/".into()))
}

#[test]
fn sample_programs_match_linuxcnc() {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/linuxcnc-samples"
    ));
    let list = std::fs::read_to_string(dir.join("list.txt")).unwrap();
    let entries: Vec<&str> = list
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .collect();
    assert!(entries.len() >= 320, "{} goldens listed", entries.len());
    let required = std::env::var_os("STANOK_REQUIRE_LINUXCNC_SAMPLES").is_some();
    let machine = dir.join("sim.toml").display().to_string();
    let tools = dir.join("sim.tbl").display().to_string();
    let mut checked = 0;
    let mut failures = Vec::new();
    for rel in &entries {
        let program = root().join(rel);
        if !program.exists() {
            assert!(
                !required,
                "{} is missing: extract linuxcnc-uspace into STANOK_LINUXCNC_ROOT",
                program.display()
            );
            continue;
        }
        let golden = dir.join("expected").join(format!(
            "{}.canon.txt",
            rel.replace('/', "_").trim_end_matches(".ngc")
        ));
        let golden = std::fs::read_to_string(&golden)
            .unwrap_or_else(|e| panic!("{}: {e}", golden.display()));
        let program = program.display().to_string();
        let (_, out, err) = stanok(&[
            "canon",
            "--dialect",
            "rs274ngc",
            "--machine",
            &machine,
            "--tools",
            &tools,
            "--linuxcnc-units",
            "inch",
            &program,
        ]);
        let ours = parse(&format!("{out}\n{err}"));
        let theirs = parse(&golden);
        if let Err(why) = compare(&ours, &theirs, None) {
            failures.push(format!("{rel}: {why}"));
        }
        checked += 1;
    }
    if checked == 0 {
        println!(
            "skipped: LinuxCNC's sample programs are not under {}",
            root().display()
        );
        return;
    }
    assert!(
        failures.is_empty(),
        "{} of {checked} differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
