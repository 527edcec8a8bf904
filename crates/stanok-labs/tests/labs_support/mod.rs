//! Shared harness of the lab-dialect tests: reads a `corpus/labs` fixture in place, strips the
//! fixture conventions (`;` header lines, `//` annotations — not program text of these controls),
//! and runs it.
#![allow(dead_code)]

use stanok_canon::{Canon, Diagnostic, Pose, Spanned};
use stanok_interp::{InterpOptions, Interpreter, LabState};
use stanok_syntax::Dialect;

pub const LABS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/corpus/labs");

/// The fixture's text with its annotations blanked (the harness's job, not the parser's).
pub fn fixture(name: &str) -> String {
    let text = std::fs::read_to_string(format!("{LABS}/{name}"))
        .unwrap_or_else(|e| panic!("cannot read fixture {name}: {e}"));
    stanok_syntax::labs::strip_fixture_comments(&text)
}

/// What a run produced.
pub struct Run {
    pub commands: Vec<Spanned<Canon>>,
    pub errors: Vec<Diagnostic>,
    pub warnings: Vec<Diagnostic>,
    pub state: LabState,
}

impl Run {
    /// End pose of every motion command with its block number, in order.
    pub fn moves(&self) -> Vec<(Option<u32>, Pose)> {
        self.commands
            .iter()
            .filter_map(|c| c.value.motion().map(|m| (c.block_number, m.end())))
            .collect()
    }

    /// End pose of the last motion of block `n`.
    pub fn end_of(&self, n: u32) -> Pose {
        self.moves()
            .into_iter()
            .rev()
            .find(|(b, _)| *b == Some(n))
            .unwrap_or_else(|| panic!("block N{n} has no motion"))
            .1
    }

    /// The motion commands of block `n`.
    pub fn motions_of(&self, n: u32) -> Vec<&Canon> {
        self.commands
            .iter()
            .filter(|c| c.block_number == Some(n) && c.value.motion().is_some())
            .map(|c| &c.value)
            .collect()
    }

    /// All commands of block `n`.
    pub fn commands_of(&self, n: u32) -> Vec<&Canon> {
        self.commands
            .iter()
            .filter(|c| c.block_number == Some(n))
            .map(|c| &c.value)
            .collect()
    }

    /// Error codes in order.
    pub fn error_codes(&self) -> Vec<String> {
        self.errors.iter().map(|d| d.code.to_string()).collect()
    }
}

/// Runs `text` in `dialect` with options adjusted by `tune`.
pub fn run_text(text: &str, dialect: Dialect, tune: impl FnOnce(&mut InterpOptions)) -> Run {
    let mut opts = InterpOptions::new(dialect);
    tune(&mut opts);
    let mut interp = Interpreter::from_text(text, opts);
    let mut commands = Vec::new();
    let mut errors = Vec::new();
    for item in interp.by_ref() {
        match item {
            Ok(c) => commands.push(c),
            Err(d) => errors.push(d),
        }
    }
    let state = interp.lab_state().expect("a lab dialect").clone();
    Run {
        commands,
        errors,
        warnings: interp.take_warnings(),
        state,
    }
}

/// Runs a fixture.
pub fn run(name: &str, dialect: Dialect, tune: impl FnOnce(&mut InterpOptions)) -> Run {
    run_text(&fixture(name), dialect, tune)
}

/// Asserts two numbers agree within `tol`.
#[track_caller]
pub fn near(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tol,
        "{what}: got {actual}, expected {expected} ± {tol}"
    );
}

/// Asserts a pose's X and Z (lathe: radius, Z).
#[track_caller]
pub fn xz(p: Pose, x: f64, z: f64, tol: f64, what: &str) {
    near(p.x, x, tol, &format!("{what} X"));
    near(p.z, z, tol, &format!("{what} Z"));
}

/// Asserts a pose's X and Y.
#[track_caller]
pub fn xy(p: Pose, x: f64, y: f64, tol: f64, what: &str) {
    near(p.x, x, tol, &format!("{what} X"));
    near(p.y, y, tol, &format!("{what} Y"));
}

/// Pose with X, Y, Z.
pub fn at(x: f64, y: f64, z: f64) -> Pose {
    Pose {
        x,
        y,
        z,
        ..Pose::ZERO
    }
}
