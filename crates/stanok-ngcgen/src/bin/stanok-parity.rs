//! `stanok-parity`: the differential runner. Generates RS274/NGC programs (`stanok_ngcgen`), runs
//! each through LinuxCNC's standalone interpreter (`rs274 -t tool.tbl -g`) and through
//! `stanok canon --machine linuxcnc --tools tool.tbl`, compares the two traces by the golden
//! tests' rules (`stanok_canon::linuxcnc_trace`), shrinks every mismatch to a minimal program and
//! prints it, and ends with `parity: M/N`. Exit status 1 if any program differs other than by a
//! known difference (docs/linuxcnc.md).
//!
//!   stanok-parity [--seed S] [--count N] [--start I] [--jobs J] [--stanok PATH] [--rs274 PATH]
//!                 [--keep DIR] [--no-shrink] [--coverage] [--emit DIR] [--tools TBL]
//!                 [--program FILE…] [--mutate DIR…]
//!
//! `--coverage` only generates and prints the feature table; `--emit DIR` writes the programs;
//! `--program FILE…` compares given files instead of generated ones (another generator's, or
//! LinuxCNC's samples: `scripts/linuxcnc-parity.sh`); `--tools TBL` replaces the generator's tool
//! table for both sides. `--mutate DIR…` compares the second style of program instead: mutants of
//! the `.ngc` files under the directories (LinuxCNC's samples; `stanok_ngcgen::mutate`), mutant
//! i of run S drawn from (S, i), not redrawn when rs274 refuses it.
//!
//! ## Algorithm
//! Workers (threads) take program indices from a shared counter. For index i, draws
//! `attempt = 0, 1, 2, 3` until rs274's verdict is the intended one (a valid program runs to its
//! end, an invalid variant stops): the program is reproducible from (seed, i, attempt). Then
//! Stanok runs it and the traces are compared. A mismatch is shrunk by deleting runs of lines
//! (halves, quarters, … single lines), then single words, keeping each deletion after which the
//! two still differ with the same [`Difference::signature`]; at most `SHRINK_RUNS` runs.

use stanok_canon::linuxcnc_trace::{compare, parse, Difference};
use stanok_ngcgen::known::known_difference;
use stanok_ngcgen::mutate::mutate;
use stanok_ngcgen::{generate, Program, TOOL_TABLE};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

const SHRINK_RUNS: usize = 300;
/// An endless loop: rs274 runs until the runner's timeout, Stanok stops it at its bound
/// (`flow::too-many-iterations`, the lines read again or in all, a lathe cycle's moves or work).
/// Not a difference in meaning: neither ends the program.
const ENDLESS_LOOP: &str = "an endless loop: rs274 never ends it, Stanok stops it at its bound";
/// The end of each of Stanok's endless-loop bounds' messages: a loop's passes, the lines read
/// again (an empty loop body reaches this one first), the lines read in all.
const ENDLESS_LOOP_MESSAGE: &str = ": stopping (endless loop?)";
const TIMEOUT: Duration = Duration::from_secs(30);

struct Config {
    seed: u64,
    count: u64,
    start: u64,
    jobs: usize,
    stanok: PathBuf,
    rs274: PathBuf,
    keep: Option<PathBuf>,
    shrink: bool,
    coverage: bool,
    emit: Option<PathBuf>,
    tools: Option<PathBuf>,
    programs: Vec<PathBuf>,
    mutate: Vec<PathBuf>,
}

fn usage() -> ExitCode {
    eprintln!("usage: stanok-parity [--seed S] [--count N] [--start I] [--jobs J] [--stanok PATH] [--rs274 PATH] [--keep DIR] [--no-shrink] [--coverage] [--emit DIR] [--tools TBL] [--program FILE...] [--mutate DIR...]");
    ExitCode::from(2)
}

fn config() -> Result<Config, ExitCode> {
    let here = std::env::current_exe().ok();
    let stanok = here
        .as_ref()
        .and_then(|p| p.parent())
        .map(|d| d.join("stanok"))
        .unwrap_or_else(|| PathBuf::from("stanok"));
    let mut c = Config {
        seed: 1,
        count: 100,
        start: 0,
        jobs: 4,
        stanok,
        rs274: PathBuf::from("rs274"),
        keep: None,
        shrink: true,
        coverage: false,
        emit: None,
        tools: None,
        programs: Vec::new(),
        mutate: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().ok_or_else(usage);
        let num = |s: String| s.parse::<u64>().map_err(|_| usage());
        match a.as_str() {
            "--seed" => c.seed = num(value()?)?,
            "--count" => c.count = num(value()?)?,
            "--start" => c.start = num(value()?)?,
            "--jobs" => c.jobs = num(value()?)?.max(1) as usize,
            "--stanok" => c.stanok = value()?.into(),
            "--rs274" => c.rs274 = value()?.into(),
            "--keep" => c.keep = Some(value()?.into()),
            "--emit" => c.emit = Some(value()?.into()),
            "--tools" => c.tools = Some(value()?.into()),
            "--no-shrink" => c.shrink = false,
            "--coverage" => c.coverage = true,
            "--program" => {
                c.programs.push(value()?.into());
                for rest in args.by_ref() {
                    c.programs.push(rest.into());
                }
                break;
            }
            "--mutate" => {
                c.mutate.push(value()?.into());
                for rest in args.by_ref() {
                    c.mutate.push(rest.into());
                }
                break;
            }
            _ => return Err(usage()),
        }
    }
    Ok(c)
}

/// Runs a command with a time limit; returns (stdout, stderr), or None on a time-out.
fn run(cmd: &mut Command) -> Option<(String, String)> {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .ok()?;
    let (mut out, mut err) = (child.stdout.take()?, child.stderr.take()?);
    let reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = std::io::Read::read_to_end(&mut out, &mut s);
        s
    });
    let ereader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = std::io::Read::read_to_end(&mut err, &mut s);
        s
    });
    let deadline = Instant::now() + TIMEOUT;
    loop {
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(2)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return None;
            }
        }
    }
    let out = String::from_utf8_lossy(&reader.join().ok()?).into_owned();
    let err = String::from_utf8_lossy(&ereader.join().ok()?).into_owned();
    Some((out, err))
}

/// A worker's scratch directory with the tool table.
struct Scratch {
    dir: PathBuf,
}

impl Scratch {
    fn new(worker: usize, tools: Option<&Path>) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("stanok-parity-{}-{worker}", std::process::id()));
        let _ = std::fs::create_dir_all(dir.join("subs"));
        let table = tools
            .and_then(|t| std::fs::read_to_string(t).ok())
            .unwrap_or_else(|| TOOL_TABLE.to_string());
        let _ = std::fs::write(dir.join("tool.tbl"), table);
        Scratch { dir }
    }

    /// Writes the program and its subroutine files; returns the program's path.
    fn write(&self, text: &str, subfiles: &[(String, String)]) -> PathBuf {
        let subs = self.dir.join("subs");
        let _ = std::fs::remove_dir_all(&subs);
        let _ = std::fs::create_dir_all(&subs);
        for (name, body) in subfiles {
            let _ = std::fs::write(subs.join(name), body);
        }
        let p = self.dir.join("prog.ngc");
        let _ = std::fs::write(&p, text);
        p
    }

    /// LinuxCNC's trace of the program (output file then standard error), None on a time-out.
    fn rs274(&self, c: &Config, prog: &Path, subs: bool) -> Option<String> {
        let out = self.dir.join("out.txt");
        let _ = std::fs::remove_file(&out);
        let mut cmd = Command::new(&c.rs274);
        // rs274 keeps its tool table in a file mapped from $HOME/.tool.mmap: runs in parallel
        // (and other users' runs) would share it, so each worker has a home of its own.
        cmd.current_dir(&self.dir).env("HOME", &self.dir);
        if subs {
            let ini = self.dir.join("sub.ini");
            let _ = std::fs::write(
                &ini,
                format!(
                    "[RS274NGC]\nSUBROUTINE_PATH = {}\n",
                    self.dir.join("subs").display()
                ),
            );
            cmd.arg("-i").arg(&ini);
        }
        cmd.arg("-t")
            .arg(self.dir.join("tool.tbl"))
            .arg("-g")
            .arg(prog)
            .arg(&out);
        let (_, err) = run(&mut cmd)?;
        let trace = std::fs::read_to_string(&out).unwrap_or_default();
        Some(format!("{trace}{err}"))
    }

    /// Stanok's trace (standard output then standard error), None on a time-out.
    fn stanok(&self, c: &Config, prog: &Path, subs: bool) -> Option<String> {
        let mut cmd = Command::new(&c.stanok);
        cmd.env("NO_COLOR", "1").env("COLUMNS", "400");
        cmd.args(["canon", "--machine", "linuxcnc", "--tools"]);
        cmd.arg(self.dir.join("tool.tbl"));
        if subs {
            cmd.arg("--subroutine-path").arg(self.dir.join("subs"));
        }
        cmd.arg(prog);
        let (out, err) = run(&mut cmd)?;
        Some(format!("{out}{err}"))
    }

    /// Compares the two on a program text: Ok, or the difference (None if a run timed out).
    fn verdict(
        &self,
        c: &Config,
        text: &str,
        subfiles: &[(String, String)],
    ) -> (Option<bool>, Result<(), Difference>) {
        let prog = self.write(text, subfiles);
        let subs = !subfiles.is_empty();
        let Some(theirs) = self.rs274(c, &prog, subs) else {
            // rs274 never ends an endless loop; Stanok stops it at its iteration bound.
            let stopped_loop = self.stanok(c, &prog, subs).is_some_and(|ours| {
                parse(&ours)
                    .error
                    .is_some_and(|e| e.contains(ENDLESS_LOOP_MESSAGE))
            });
            let why = if stopped_loop {
                ENDLESS_LOOP
            } else {
                "rs274 timed out"
            };
            return (None, Err(Difference::OnlyLinuxCncStopped(why.into())));
        };
        let theirs = parse(&theirs);
        let linuxcnc_stopped = Some(theirs.error.is_some());
        let Some(ours) = self.stanok(c, &prog, subs) else {
            return (
                linuxcnc_stopped,
                Err(Difference::OnlyStanokStopped("stanok timed out".into())),
            );
        };
        (
            linuxcnc_stopped,
            compare(&parse(&ours), &theirs, Some(text)),
        )
    }
}

/// A difference found by the runner and not fixed yet (docs/linuxcnc.md, "Open differences"):
/// Stanok's own shortcoming, listed so that the run stays a regression guard for everything else.
/// None are open now; a new one gets a rule here (on the program's text) and a line in the docs.
pub fn open_difference(_text: &str) -> Option<&'static str> {
    None
}

/// Deletes lines, then words, while the difference keeps its signature.
fn shrink(
    scratch: &Scratch,
    c: &Config,
    text: &str,
    subfiles: &[(String, String)],
    signature: &str,
) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut runs = 0;
    let still = |lines: &[String], runs: &mut usize| -> bool {
        *runs += 1;
        let t = lines.join("\n") + "\n";
        matches!(scratch.verdict(c, &t, subfiles).1, Err(d) if d.signature() == signature)
    };
    // Runs of lines, largest first.
    let mut size = lines.len().div_ceil(2).max(1);
    loop {
        let mut at = 0;
        while at < lines.len() && runs < SHRINK_RUNS {
            let end = (at + size).min(lines.len());
            let mut trial = lines.clone();
            trial.drain(at..end);
            if !trial.is_empty() && still(&trial, &mut runs) {
                lines = trial;
            } else {
                at += size;
            }
        }
        if size == 1 || runs >= SHRINK_RUNS {
            break;
        }
        size = size.div_ceil(2);
    }
    // Words within lines.
    for i in 0..lines.len() {
        let mut words: Vec<String> = lines[i].split_whitespace().map(str::to_string).collect();
        let mut w = 0;
        while w < words.len() && words.len() > 1 && runs < SHRINK_RUNS {
            let mut trial_words = words.clone();
            trial_words.remove(w);
            let mut trial = lines.clone();
            trial[i] = trial_words.join(" ");
            if still(&trial, &mut runs) {
                words = trial_words;
                lines = trial;
            } else {
                w += 1;
            }
        }
    }
    lines.join("\n") + "\n"
}

/// The outcome of one program.
enum Outcome {
    Same,
    Known(&'static str),
    Differs { text: String, why: String },
}

/// The outcome of one program, and whether rs274 stopped on it (None: it timed out).
fn check_one(scratch: &Scratch, c: &Config, name: &str, p: &Program) -> (Outcome, Option<bool>) {
    let (stopped, verdict) = scratch.verdict(c, &p.text, &p.subfiles);
    let outcome = match verdict {
        Ok(()) => Outcome::Same,
        Err(d) => {
            if let Some(k) = known_difference(&p.text) {
                return (Outcome::Known(k), stopped);
            }
            if let Some(k) = open_difference(&p.text) {
                return (Outcome::Known(k), stopped);
            }
            if matches!(&d, Difference::OnlyLinuxCncStopped(m) if m == ENDLESS_LOOP) {
                return (Outcome::Known(ENDLESS_LOOP), stopped);
            }
            if matches!(d, Difference::MovedBeforeError(_)) {
                // Same block, same message; rs274 issued calls of the failing block first.
                let k = "an error found after the block moved leaves nothing of it";
                return (Outcome::Known(k), stopped);
            }
            let shrunk = if c.shrink {
                shrink(scratch, c, &p.text, &p.subfiles, &d.signature())
            } else {
                p.text.clone()
            };
            let mut text = format!("== {name}: {d}\n-- shrunk program --\n{shrunk}");
            for (f, body) in &p.subfiles {
                text.push_str(&format!("-- subroutine file {f} --\n{body}"));
            }
            if let Some(dir) = &c.keep {
                let _ = std::fs::create_dir_all(dir);
                let name = name.split(' ').next().unwrap_or(name).replace('/', "_");
                let _ = std::fs::write(dir.join(format!("{name}.ngc")), &p.text);
                let _ = std::fs::write(dir.join(format!("{name}.min.ngc")), &shrunk);
                for (f, body) in &p.subfiles {
                    let _ = std::fs::write(dir.join(f), body);
                }
            }
            Outcome::Differs {
                text,
                why: d.signature(),
            }
        }
    };
    (outcome, stopped)
}

/// Program `index`: the first draw whose rs274 verdict is the intended one.
fn program(scratch: &Scratch, c: &Config, index: u64) -> Program {
    let mut p = generate(c.seed, index, 0);
    for attempt in 1..4 {
        let prog = scratch.write(&p.text, &p.subfiles);
        let stopped = scratch
            .rs274(c, &prog, !p.subfiles.is_empty())
            .map(|t| parse(&t).error.is_some());
        if stopped == Some(p.invalid.is_some()) {
            break;
        }
        p = generate(c.seed, index, attempt);
    }
    p
}

fn coverage(c: &Config) {
    let mut counts: BTreeMap<&str, u64> = BTreeMap::new();
    for i in c.start..c.start + c.count {
        let p = generate(c.seed, i, 0);
        for f in p.features {
            *counts.entry(f).or_default() += 1;
        }
        if let Some(dir) = &c.emit {
            let _ = std::fs::create_dir_all(dir);
            let _ = std::fs::write(dir.join(format!("p{i:05}.ngc")), &p.text);
            for (f, body) in &p.subfiles {
                let _ = std::fs::write(dir.join(f), body);
            }
        }
    }
    println!("| feature | programs of {} |", c.count);
    println!("|---|---:|");
    for (f, n) in counts {
        println!("| {f} | {n} |");
    }
}

/// The sources of `--mutate`: every `.ngc` file under the directories of at most 32 kB (the
/// longest samples would make a run slow without adding language), read, sorted by path, with
/// duplicate texts dropped (the sample configurations repeat programs). (file stem, text) pairs.
fn mutation_sources(dirs: &[PathBuf]) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let mut todo: Vec<PathBuf> = dirs.to_vec();
    while let Some(d) = todo.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                todo.push(p);
            } else if p.extension().is_some_and(|x| x == "ngc")
                && e.metadata().is_ok_and(|m| m.len() <= 32 * 1024)
            {
                files.push(p);
            }
        }
    }
    files.sort();
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for p in files {
        let Ok(text) = std::fs::read_to_string(&p) else {
            continue;
        };
        if seen.insert(text.clone()) {
            let stem = p
                .file_stem()
                .map_or(String::new(), |s| s.to_string_lossy().into_owned());
            out.push((stem, text));
        }
    }
    out
}

fn main() -> ExitCode {
    let c = match config() {
        Ok(c) => c,
        Err(code) => return code,
    };
    if c.coverage || (c.emit.is_some() && c.programs.is_empty()) {
        coverage(&c);
        return ExitCode::SUCCESS;
    }
    let given: Vec<(String, String)> = c
        .programs
        .iter()
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(p).unwrap_or_default(),
            )
        })
        .collect();
    let sources = mutation_sources(&c.mutate);
    if !c.mutate.is_empty() && sources.is_empty() {
        eprintln!("stanok-parity: no .ngc files under the --mutate directories");
        return ExitCode::from(2);
    }
    let texts: Vec<String> = sources.iter().map(|s| s.1.clone()).collect();
    let total = if given.is_empty() {
        c.count
    } else {
        given.len() as u64
    };
    let next = AtomicU64::new(0);
    let stops = AtomicU64::new(0);
    let results: Mutex<Vec<(u64, Outcome)>> = Mutex::new(Vec::new());
    let started = Instant::now();
    std::thread::scope(|s| {
        for worker in 0..c.jobs {
            let (c, next, results, given, sources, texts, stops) =
                (&c, &next, &results, &given, &sources, &texts, &stops);
            s.spawn(move || {
                let scratch = Scratch::new(worker, c.tools.as_deref());
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= total {
                        break;
                    }
                    let plain = |text: String| Program {
                        text,
                        subfiles: Vec::new(),
                        features: Default::default(),
                        invalid: None,
                    };
                    let (name, p) = if !sources.is_empty() {
                        let i = c.start + k;
                        let m = mutate(texts, c.seed, i);
                        let from = &sources[m.source].0;
                        let name = format!("mutant{}-{i} ({from}: {})", c.seed, m.ops.join(", "));
                        (name, plain(m.text))
                    } else if given.is_empty() {
                        let i = c.start + k;
                        (format!("seed{}-{i}", c.seed), program(&scratch, c, i))
                    } else {
                        let (n, t) = &given[k as usize];
                        (n.clone(), plain(t.clone()))
                    };
                    let (outcome, stopped) = check_one(&scratch, c, &name, &p);
                    if stopped == Some(true) {
                        stops.fetch_add(1, Ordering::Relaxed);
                    }
                    if let Outcome::Differs { text, .. } = &outcome {
                        println!("{text}");
                    }
                    results.lock().unwrap().push((k, outcome));
                }
                let _ = std::fs::remove_dir_all(&scratch.dir);
            });
        }
    });
    let results = results.into_inner().unwrap();
    let same = results
        .iter()
        .filter(|(_, o)| matches!(o, Outcome::Same))
        .count();
    let mut known: BTreeMap<&str, usize> = BTreeMap::new();
    let mut kinds: BTreeMap<String, usize> = BTreeMap::new();
    for (_, o) in &results {
        match o {
            Outcome::Known(k) => *known.entry(k).or_default() += 1,
            Outcome::Differs { why, .. } => *kinds.entry(why.clone()).or_default() += 1,
            Outcome::Same => {}
        }
    }
    for (k, n) in &known {
        println!("known difference ({n}): {k}");
    }
    for (k, n) in &kinds {
        println!("differs ({n}): {k}");
    }
    let known_total: usize = known.values().sum();
    println!(
        "parity: {same}/{total} ({known_total} known differences, {:.1} s; rs274 stopped on {})",
        started.elapsed().as_secs_f64(),
        stops.into_inner()
    );
    if kinds.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
