//! `stanok canon` against LinuxCNC's own traces of its sample programs (the goldens in
//! tests/linuxcnc-samples/expected, made by `scripts/linuxcnc-parity.sh --update-goldens` with
//! LinuxCNC 2.9's rs274, tool table tests/linuxcnc-samples/sim.tbl, machine sim.toml).
//!
//! The programs are LinuxCNC's, not ours: they are read from the linuxcnc-uspace package's files
//! under `$STANOK_LINUXCNC_ROOT` (default `/`). `.ci/run` extracts the package there without
//! installing LinuxCNC and sets `STANOK_REQUIRE_LINUXCNC_SAMPLES=1`, which turns missing programs
//! into a failure; elsewhere the test says it skipped.
//!
//! Comparison (as tests/rs274_traces.rs in stanok-interp and scripts/linuxcnc_compare.py): line
//! by line, numbers within 1.0001e-4 (both sides print 4 decimals); if LinuxCNC stopped with an
//! error, Stanok must stop too, with LinuxCNC's message, having printed LinuxCNC's lines up to
//! the failing block and LinuxCNC nothing that moves after them (Stanok's blocks are atomic).

mod common;
use common::*;
use std::path::PathBuf;

const TOL: f64 = 1.0001e-4;

/// The trace lines (`N….. CALL(…)`, counters and exit `ON_RESET`s dropped) and the first error text.
fn parse(text: &str) -> (Vec<String>, Option<String>) {
    let mut lines = Vec::new();
    let mut error = None;
    for raw in text.lines() {
        let t = raw.trim_start();
        let call = t
            .split_once(' ')
            .filter(|(n, _)| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            .map(|(_, rest)| rest);
        match call {
            Some(c) if c.len() > 7 && c.starts_with('N') => {
                let body = &c[7..];
                if let Some(rest) = body.strip_prefix("ON_RESET()") {
                    if error.is_none() && !rest.trim().is_empty() && rest.trim() != "executing" {
                        error = Some(rest.trim().to_string());
                    }
                } else {
                    lines.push(c.to_string());
                }
            }
            _ => {
                let t = t.trim();
                if error.is_none() && !t.is_empty() && t != "executing" && !t.starts_with("error[")
                {
                    error = Some(t.trim_start_matches('×').trim().to_string());
                }
            }
        }
    }
    (lines, error)
}

/// Splits a line into its text with numbers blanked and the numbers.
fn numbers(line: &str) -> (String, Vec<f64>) {
    let mut text = String::new();
    let mut nums = Vec::new();
    let b = line.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let start = i;
        let mut j = i;
        if b[j] == b'-' {
            j += 1;
        }
        let digits = j;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        if j > digits && j + 1 < b.len() && b[j] == b'.' && b[j + 1].is_ascii_digit() {
            j += 1;
            while j < b.len() && b[j].is_ascii_digit() {
                j += 1;
            }
            nums.push(line[start..j].parse().unwrap_or(f64::NAN));
            text.push('#');
            i = j;
        } else {
            text.push(b[i] as char);
            i += 1;
        }
    }
    (text, nums)
}

fn same(a: &str, b: &str) -> bool {
    let (ta, na) = numbers(a);
    let (tb, nb) = numbers(b);
    ta == tb && na.len() == nb.len() && na.iter().zip(&nb).all(|(x, y)| (x - y).abs() <= TOL)
}

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
        let (ours, our_error) = parse(&format!("{out}\n{err}"));
        let (theirs, their_error) = parse(&golden);
        let verdict = compare(&ours, &our_error, &theirs, &their_error);
        if let Err(why) = verdict {
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

fn compare(
    ours: &[String],
    our_error: &Option<String>,
    theirs: &[String],
    their_error: &Option<String>,
) -> Result<(), String> {
    for (i, (a, b)) in ours.iter().zip(theirs).enumerate() {
        if !same(a, b) {
            return Err(format!("line {}: ours {a:?}, LinuxCNC {b:?}", i + 1));
        }
    }
    match (our_error, their_error) {
        (None, None) if ours.len() == theirs.len() => Ok(()),
        (None, None) => Err(format!("{} lines, LinuxCNC {}", ours.len(), theirs.len())),
        (Some(e), None) => Err(format!("Stanok stopped: {e}")),
        (None, Some(e)) => Err(format!("LinuxCNC stopped ({e}), Stanok ran it")),
        (Some(ours_e), Some(theirs_e)) => {
            let head = theirs_e.split(':').next().unwrap_or("");
            if !ours_e.starts_with(head) {
                return Err(format!("error {ours_e:?}, LinuxCNC {theirs_e:?}"));
            }
            match theirs[ours.len().min(theirs.len())..]
                .iter()
                .find(|l| l.contains("STRAIGHT_") || l.contains("ARC_FEED") || l.contains("NURBS"))
            {
                Some(l) => Err(format!("LinuxCNC moved before its error: {l}")),
                None => Ok(()),
            }
        }
    }
}

#[test]
fn the_comparison_can_fail() {
    let a = vec!["N..... STRAIGHT_FEED(1.0000, 2.0000)".to_string()];
    let b = vec!["N..... STRAIGHT_FEED(1.0000, 2.0002)".to_string()];
    assert!(compare(&a, &None, &b, &None).is_err());
    let c = vec!["N..... STRAIGHT_FEED(1.0000, 2.0001)".to_string()];
    assert!(compare(&a, &None, &c, &None).is_ok());
    assert!(compare(&a, &Some("X".into()), &a, &None).is_err());
    let (lines, err) = parse("    1 N..... DWELL(1.0000)\n    2 N..... ON_RESET()\n    3 N..... ON_RESET()executing\nBad thing\nG1 X\n");
    assert_eq!(lines, vec!["N..... DWELL(1.0000)"]);
    assert_eq!(err.as_deref(), Some("Bad thing"));
}
