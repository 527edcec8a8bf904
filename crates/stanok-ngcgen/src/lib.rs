//! A seeded generator of RS274/NGC programs over the whole language that Stanok's RS274/NGC front
//! end implements, for differential testing against LinuxCNC's standalone interpreter `rs274`
//! (the runner is `src/bin/stanok-parity.rs`; docs/linuxcnc.md says how to run it).
//!
//! ## How a program is made
//! [`generate`]`(seed, index, attempt)` seeds a ChaCha8 stream from the three numbers (`rng.rs`),
//! so a program is reproducible from them alone. It then
//! 1. draws the program's surface forms (lower case, compact text, spaces inside words, N words,
//!    `/` block-delete marks, `%` fences) and its subroutines (`flow.rs`);
//! 2. writes a prelude (units, distance mode, plane, feed, spindle) and 3–9 *sections*, each a
//!    short passage exercising one area of the language (`sections.rs`, `cycles.rs`): moves and
//!    arcs in every plane and form, parameters and expressions, control flow, offsets and
//!    coordinate systems, tools, canned cycles, cutter compensation, splines, threading, lathe
//!    cycles, feed and spindle modes, unit switches, path modes, M codes, probes, homes;
//! 3. ends the program (M2 or M30, or `%`), and applies the surface forms line by line.
//!
//! Every section starts from the tracked state [`State`] (units, distance mode, plane, position
//! when known, feed mode, spindle, tool, parameters) and leaves it valid for the next, so that
//! most programs run on LinuxCNC to the end; the runner draws again (`attempt + 1`) where rs274
//! still rejects one. A few programs per hundred are *invalid variants* ([`Program::invalid`]):
//! one block made wrong in a way whose first error LinuxCNC names (`invalid.rs`).
//!
//! [`Program::features`] lists what the program uses, for the coverage table of docs/linuxcnc.md.

mod cycles;
pub mod expr;
mod flow;
mod invalid;
pub mod known;
pub mod mutate;
pub mod rng;
mod sections;
mod state_sections;
mod surface;

use rng::Rng;
use std::collections::BTreeSet;

/// The tool table every generated program is run with (inch, as rs274's simulated machine): the
/// table of Stanok's RS274/NGC goldens, so that a shrunk program becomes a golden as it is.
pub const TOOL_TABLE: &str =
    "T1 P1 Z-1.5 D0.25 ;tool 1\nT2 P2 Z0 D0.1 ;tool 2\nT10 P10 Z0.1 D0.5 ;tool 10\n";

/// The tools of [`TOOL_TABLE`]: number, length offset (inch), diameter (inch).
pub const TOOLS: [(u32, f64, f64); 3] = [(1, -1.5, 0.25), (2, 0.0, 0.1), (10, 0.1, 0.5)];

/// A generated program.
#[derive(Debug, Clone)]
pub struct Program {
    /// The main program's text.
    pub text: String,
    /// Subroutine files (`name.ngc`, text) for the subroutine path, if it calls any.
    pub subfiles: Vec<(String, String)>,
    /// What it uses (coverage features).
    pub features: BTreeSet<&'static str>,
    /// For an invalid variant, what was made wrong.
    pub invalid: Option<&'static str>,
}

/// What the generator knows of the interpreter's state between blocks.
#[derive(Debug, Clone)]
pub struct State {
    /// G21 (true) or G20.
    pub metric: bool,
    /// G90 (true) or G91.
    pub absolute: bool,
    /// 17, 18 or 19.
    pub plane: u8,
    /// The position in program coordinates (current units, system, offsets), if known.
    pub pos: Option<[f64; 3]>,
    /// 93, 94 or 95.
    pub feed_mode: u8,
    /// The spindle turns (S > 0 and M3/M4 given).
    pub spindle: bool,
    /// The tool in the spindle (0: none).
    pub tool: u32,
    /// G96 constant surface speed is on.
    pub css: bool,
    /// Numbered parameters 1…30 set so far, with values.
    pub numbered: Vec<(u32, f64)>,
    /// Readable parameters with known values (numbered, named, predefined).
    pub params: Vec<(String, f64)>,
    /// Named global parameters set so far.
    pub names: Vec<String>,
    /// The next free O number.
    pub next_label: u32,
    /// Current coordinate system, 1…9 (#5220).
    pub system: u32,
    /// G7 lathe diameter mode.
    pub diameter: bool,
    /// Cutter compensation or a canned cycle is active: no section may start.
    pub busy: bool,
}

impl Default for State {
    fn default() -> State {
        State {
            metric: true,
            absolute: true,
            plane: 17,
            pos: None,
            feed_mode: 94,
            spindle: false,
            tool: 0,
            css: false,
            numbered: Vec::new(),
            params: Vec::new(),
            names: Vec::new(),
            next_label: 100,
            system: 1,
            diameter: false,
            busy: false,
        }
    }
}

/// The writer of one program: random source, state, lines, features.
pub struct Gen {
    /// The random source.
    pub rng: Rng,
    /// The tracked state.
    pub st: State,
    /// The main program's lines (before surface forms).
    pub lines: Vec<String>,
    /// Subroutines defined in the program, written before the main body.
    pub subs: Vec<String>,
    /// Subroutine files.
    pub subfiles: Vec<(String, String)>,
    /// Features used.
    pub features: BTreeSet<&'static str>,
}

impl Gen {
    /// Appends a line.
    pub fn line(&mut self, text: impl Into<String>) {
        self.lines.push(text.into());
    }

    /// Notes a feature.
    pub fn feat(&mut self, f: &'static str) {
        self.features.insert(f);
    }

    /// Millimetres in the current units (a length drawn for mm, scaled for G20).
    pub fn len(&self, mm: f64) -> f64 {
        if self.st.metric {
            mm
        } else {
            ((mm / 25.4) * 10000.0).round() / 10000.0
        }
    }

    /// A length in `lo..hi` mm, in current units.
    pub fn rlen(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.rng.value(lo, hi);
        self.len(v)
    }

    /// A signed length of magnitude `lo..hi` mm, in current units.
    pub fn slen(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.rng.signed(lo, hi);
        self.len(v)
    }

    /// `X1.5`: a word with a number.
    pub fn w(&mut self, letter: char, v: f64) -> String {
        let t = self.rng.number_text(v);
        format!("{letter}{t}")
    }

    /// A word whose value is sometimes written as an expression of the same value (within 1e-6).
    pub fn wx(&mut self, letter: char, v: f64) -> String {
        if self.rng.chance(0.12) {
            if let Some(e) = self.expr_for(v) {
                self.feat("expr: in a word");
                return format!("{letter}{e}");
            }
        }
        self.w(letter, v)
    }

    /// An expression text whose value is `v` within 1e-6: `[e + c]` with a random `e`.
    pub fn expr_for(&mut self, v: f64) -> Option<String> {
        let mut used = Vec::new();
        for _ in 0..8 {
            let params = self.st.params.clone();
            let numbered = self.st.numbered.clone();
            let names = self.st.names.clone();
            let scope = expr::Scope {
                params: &params,
                numbered: &numbered,
                names: &names,
            };
            let depth = 1 + self.rng.below(3) as u32;
            let e = expr::random_expr(&mut self.rng, depth, &scope, &mut used);
            if let Some(ev) = e.value() {
                let c = ((v - ev) * 1e6).round() / 1e6;
                if c.abs() > 1e5 {
                    continue;
                }
                for f in used {
                    self.feat(f);
                }
                let inner = e.inner(&mut self.rng);
                return Some(format!("[[{inner}] + {c:.6}]"));
            }
            used.clear();
        }
        None
    }

    /// A fresh O number.
    pub fn label(&mut self) -> u32 {
        let l = self.st.next_label;
        self.st.next_label += 1 + self.rng.below(3) as u32;
        l
    }

    /// The axis letters of the current plane: (first, second, normal).
    pub fn plane_axes(&self) -> (char, char, char) {
        match self.st.plane {
            18 => ('Z', 'X', 'Y'),
            19 => ('Y', 'Z', 'X'),
            _ => ('X', 'Y', 'Z'),
        }
    }

    /// The index (0 X, 1 Y, 2 Z) of an axis letter.
    pub fn axis_index(c: char) -> usize {
        match c {
            'X' => 0,
            'Y' => 1,
            _ => 2,
        }
    }

    /// Makes the position known: a rapid to an absolute point (G90 for the block if needed).
    pub fn known_position(&mut self) -> [f64; 3] {
        if let Some(p) = self.st.pos {
            return p;
        }
        let p = [
            self.slen(0.0, 40.0),
            self.slen(0.0, 40.0),
            self.rlen(5.0, 40.0),
        ];
        let g90 = if self.st.absolute { "" } else { "G90 " };
        let (x, y, z) = (self.w('X', p[0]), self.w('Y', p[1]), self.w('Z', p[2]));
        self.line(format!("{g90}G0 {x} {y} {z}"));
        if !self.st.absolute {
            self.line("G91");
        }
        self.st.pos = Some(p);
        p
    }

    /// Sets a numbered or named parameter's known value (replacing an older one).
    pub fn set_param(&mut self, name: String, v: f64) {
        self.st.params.retain(|(n, _)| *n != name);
        if let Some(n) = name.strip_prefix('#').and_then(|n| n.parse::<u32>().ok()) {
            self.st.numbered.retain(|(k, _)| *k != n);
            if (1..=30).contains(&n) {
                self.st.numbered.push((n, v));
            }
        }
        if name.starts_with("#<_") && !self.st.names.contains(&name) {
            self.st.names.push(name.clone());
        }
        self.st.params.push((name, v));
    }

    /// Forgets a parameter's value (a value the generator cannot be sure of).
    pub fn forget_param(&mut self, name: &str) {
        self.st.params.retain(|(n, _)| n != name);
        if let Some(n) = name.strip_prefix('#').and_then(|n| n.parse::<u32>().ok()) {
            self.st.numbered.retain(|(k, _)| *k != n);
        }
    }

    /// Forgets the values that depend on the position (predefined `#<_x>` …).
    pub fn forget_position(&mut self) {
        self.st.pos = None;
        self.st.params.retain(|(n, _)| {
            !n.starts_with("#<_x") && !n.starts_with("#<_y") && !n.starts_with("#<_z")
        });
    }
}

/// Generates program `index` of run `seed` (draw `attempt`).
pub fn generate(seed: u64, index: u64, attempt: u32) -> Program {
    let mut g = Gen {
        rng: Rng::new(seed, index, attempt),
        st: State::default(),
        lines: Vec::new(),
        subs: Vec::new(),
        subfiles: Vec::new(),
        features: BTreeSet::new(),
    };
    let forms = surface::Forms::draw(&mut g);
    sections::prelude(&mut g);
    let n = 3 + g.rng.below(7);
    for _ in 0..n {
        sections::section(&mut g);
    }
    let invalid = if g.rng.chance(0.06) {
        invalid::corrupt(&mut g)
    } else {
        None
    };
    sections::ending(&mut g);
    let text = forms.apply(&mut g);
    Program {
        text,
        subfiles: std::mem::take(&mut g.subfiles),
        features: std::mem::take(&mut g.features),
        invalid,
    }
}
