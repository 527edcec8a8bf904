//! # stanok-labs: the lab-collection front ends
//!
//! The lab-collection controls: Elektronika NC-31, 2P32, MC2101 and the GOST-20999 control
//! (spec `lab-collection-nc31-2p32-cutting.md`), as front ends that produce the same [`Canon`] as
//! the AxiOMA and RS274/NGC paths.
//!
//! These languages share little with ISO: an NC-31 "frame" is one address, and a *group* of frames
//! joined by `*` is the unit of execution; the 2P32 searches its turret for a tool *code*; the
//! GOST-20999 control binds length corrections to the next axis word. So each has its own reader
//! (`stanok_syntax::labs`) and executor here, with its own small state ([`LabState`]), instead of
//! going through `Words`/`Ctx`:
//!
//! ```text
//!  program text ──(fixture comments stripped on request)──▶ programs: main + subprograms
//!      │                                                     (same file, or files on the
//!      ▼                                                      subroutine path with a header)
//!  LabRun::step: one execution unit (NC-31 group, or one block) on a scratch copy of LabState
//!      │ Ok: commit the state, queue the unit's commands      Err: nothing of the unit is queued
//!      ▼
//!  the driver's queue of Spanned<Canon> (same iterator, same check/run/canon/plot)
//! ```
//!
//! [`Labs`] is the front end the driver calls (`stanok_interp_core::FrontEnd`): its unit is
//! `LabRun::step`'s, read from the program in memory instead of a line of the streamed source.
//!
//! Invariants (the same as the other dialects'):
//! * a unit commits all of its state changes and commands or none (`LabRun::step` runs on a clone);
//! * every command carries its unit's span and frame number;
//! * jumps and calls are bounded ([`MAX_JUMPS`], call depth 5), so no program hangs;
//! * positions are machine Cartesian mm: **lathe X is the radius** (the NC-31's diameter values are
//!   halved here), Z along the spindle; the 2P32's spindle angle (Y word after M89) is the C axis.
//!
//! The whole program is held in memory (lab programs are short; the NC-31's `P` jumps and the
//! GOST-20999's subprograms need random access by frame number): the one exception to the
//! streaming invariant, bounded by [`MAX_PROGRAM_BYTES`].

pub mod codes;
mod iso;
mod iso_arcs;
mod iso_comp;
mod iso_motion;
mod iso_words;
mod nc31;
mod nc31_moves;

use stanok_canon::{Canon, Diagnostic, FeedMode, Plane, Pose, Span, Spanned, SpindleDirection};
use stanok_interp_core::state::MotionMode;
use stanok_interp_core::{Core, CoreOptions, FrontEnd, Outcome, Parts, Unit};
use stanok_syntax::labs::LineAt;
use stanok_syntax::Dialect;
use std::collections::{BTreeMap, VecDeque};
use std::io::{BufRead, Seek};

/// The lab controls' options: the common ones, their machine data, and the fixture convention.
#[derive(Debug, Clone)]
pub struct LabOptions {
    /// Options common to all front ends.
    pub core: CoreOptions,
    /// Machine data of the lab controls.
    pub labs: LabMachineParams,
    /// Blank out the lab corpus's fixture annotations (`;` lines, `//` to the end of a line)
    /// before reading; they are not program text of these controls. Off by default.
    pub strip_fixture_comments: bool,
}

impl std::ops::Deref for LabOptions {
    type Target = CoreOptions;
    fn deref(&self) -> &CoreOptions {
        &self.core
    }
}

/// The lab controls' front end: one `LabRun` unit per driver unit.
pub struct Labs {
    run: LabRun,
    opts: LabOptions,
    /// Units the last step executed (counted when it commits).
    units: u64,
    /// The span of the last command produced (where the work bound is reported).
    last_span: stanok_canon::Span,
}

/// Its state: the lab control's modes (the read position in the program, which moves past a
/// failing unit so that a check goes on, is not shown).
impl std::fmt::Debug for Labs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Labs")
            .field("state", self.run.state())
            .finish()
    }
}

impl Labs {
    /// The front end for `text`, the whole program (lab programs are held in memory).
    pub fn new(text: &str, opts: LabOptions) -> Self {
        Labs {
            run: LabRun::new(text, &opts),
            opts,
            units: 0,
            last_span: stanok_canon::Span::new(0, 0, 1, 1),
        }
    }

    /// The modal state after the units run so far.
    pub fn state(&self) -> &LabState {
        self.run.state()
    }
}

impl FrontEnd for Labs {
    type Undo = ();

    fn next_unit<R: BufRead + Seek>(&mut self, _core: &mut Core<R>) -> Result<Unit, Diagnostic> {
        // The unit is read from the program in memory by `execute` (`LabRun::step`).
        Ok(Unit::Execute)
    }

    fn begin<R: BufRead + Seek>(&mut self, _core: &Core<R>) {}

    fn execute(&mut self, parts: Parts<'_>) -> Result<Outcome, Diagnostic> {
        // `LabRun::step` is all or nothing itself: it runs the unit on a copy of its state.
        let (done, units) = self.run.step(parts.out.queue, parts.warnings, &self.opts)?;
        self.units = units;
        Ok(if done {
            Outcome::End
        } else {
            Outcome::Continue
        })
    }

    fn rollback<R: BufRead + Seek>(&mut self, _undo: (), _core: &mut Core<R>) {}

    fn commit<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        _outcome: Outcome,
    ) -> Result<(), Diagnostic> {
        // Where the last command the units produced was (line 1 before any): the lab front
        // end keeps no block of its own in the core.
        if let Some(c) = core.queue.back() {
            self.last_span = c.span;
        }
        core.count_units(std::mem::take(&mut self.units), self.last_span)
    }

    fn finish<R: BufRead + Seek>(&mut self, _core: &mut Core<R>) -> Result<(), Diagnostic> {
        Ok(())
    }
}

/// Most backward jumps or subprogram repeats of one run before it is stopped as endless.
pub const MAX_JUMPS: u32 = 1_000;
/// Largest lab program (with its subprograms) read into memory.
pub const MAX_PROGRAM_BYTES: usize = 16 << 20;

/// Machine data of the lab controls: what the operator enters on the panel before a run.
#[derive(Debug, Clone, PartialEq)]
pub struct LabMachineParams {
    /// Correctors (D words; 2P32/GOST-20999), mm: tool radii and length/position corrections.
    /// A corrector that is not set holds 0.
    pub correctors: BTreeMap<u32, f64>,
    /// 2P32: tool code mounted in turret position p (correctors 381–392, spec §3.6), p = 1…12.
    /// Default: position p holds code p.
    pub turret_codes: [u32; 12],
    /// 2P32: turret position at program start (default 1).
    pub turret_position: u32,
    /// GOST-20999 work systems G54 and G55: origin in machine coordinates, mm, axes X Y Z and the
    /// 4th (parameters 155–158 and 159–162, spec §4.7). Default 0.
    pub work_offsets: [[f64; 4]; 2],
    /// GOST-20999 home (the values the axes take after G28, parameters 163–166), machine mm.
    pub home: [f64; 4],
    /// NC-31 automatic gearbox (АКС): rpm of each 2-digit S code, index = code. The default is a
    /// placeholder with code 7 = 560 rpm (the document's one data point) and a φ = 1.26 series
    /// around it: enter the machine's own table.
    pub nc31_gearbox_rpm: Vec<f64>,
}

impl Default for LabMachineParams {
    fn default() -> Self {
        let mut codes = [0; 12];
        for (i, c) in codes.iter_mut().enumerate() {
            *c = i as u32 + 1;
        }
        LabMachineParams {
            correctors: BTreeMap::new(),
            turret_codes: codes,
            turret_position: 1,
            work_offsets: [[0.0; 4]; 2],
            home: [0.0; 4],
            nc31_gearbox_rpm: (0..100)
                .map(|k| (560.0 * 1.26f64.powi(k - 7)).round())
                .collect(),
        }
    }
}

/// The modal state of a lab control after the units run so far (tests and reports read it).
#[derive(Debug, Clone, PartialEq)]
pub struct LabState {
    /// Tool position, machine mm (X = radius on the lathes), C = spindle angle (deg).
    pub position: Pose,
    /// Feed mode: NC-31 starts in G95 (mm/rev), the others in mm/min.
    pub feed_mode: FeedMode,
    /// Modal feed in the mode's unit (mm/min or mm/rev); 0 = none programmed.
    pub feed: f64,
    /// Commanded spindle speed, rpm.
    pub spindle_rpm: f64,
    /// Spindle running, and which way.
    pub spindle: Option<SpindleDirection>,
    /// NC-31: the spindle sub-range M38–M41 selected.
    pub gear_range: Option<u32>,
    /// Active tool (number; 2P32: the tool code).
    pub tool: Option<u32>,
    /// 2P32: turret position (1…12).
    pub turret_position: u32,
    /// Variables R<n> as written (GOST-20999 `R1#39.`, 2P32 `R27 - 4910`): value and whether it
    /// was written with a decimal point.
    pub variables: BTreeMap<u32, (f64, bool)>,
    /// ISO dialects: the motion mode (G0…G3).
    pub motion: MotionMode,
    /// ISO dialects: plane.
    pub plane: Plane,
    /// ISO dialects: G91.
    pub incremental: bool,
    /// GOST-20999: active work system, 1 = G54, 2 = G55.
    pub work_system: u8,
    /// GOST-20999: the G92 shift added to both work systems, mm (X Y Z 4th).
    pub g92_shift: [f64; 4],
    /// Per axis (X Y Z A B C U V W): length/position correction mode (+1 G43, −1 G44, 0 off) and
    /// corrector number (spec §4.8).
    pub axis_correction: [(i8, Option<u32>); 9],
    /// Correction applied to each axis's end point now, mm (sign included).
    pub applied_correction: [f64; 9],
    /// Cutter radius compensation: 0 = G40, 1 = G41, −1 = G42; and its corrector.
    pub radius_comp: (i8, Option<u32>),
    /// 2P32: servo ("tracking") spindle mode M89: the Y word is the spindle angle.
    pub servo_spindle: bool,
    /// A warning about a feed move without a usable feed was given (once per run).
    pub warned_feed: bool,
    /// A G43/G44/D still waiting for its axis word (it binds to the next one, §4.8).
    pub(crate) pending: iso_words::Pending,
}

impl LabState {
    fn new(dialect: Dialect, opts: &LabOptions) -> Self {
        LabState {
            position: opts.initial_position,
            feed_mode: if dialect == Dialect::Nc31 {
                FeedMode::UnitsPerRevolution
            } else {
                FeedMode::UnitsPerMinute
            },
            feed: 0.0,
            spindle_rpm: 0.0,
            spindle: None,
            gear_range: None,
            tool: None,
            turret_position: opts.labs.turret_position,
            variables: BTreeMap::new(),
            motion: MotionMode::Rapid,
            plane: Plane::XY,
            incremental: dialect == Dialect::Mc2101,
            work_system: 1,
            g92_shift: [0.0; 4],
            axis_correction: [(0, None); 9],
            applied_correction: [0.0; 9],
            radius_comp: (0, None),
            servo_spindle: false,
            warned_feed: false,
            pending: iso_words::Pending::default(),
        }
    }

    /// The path feed in mm/min of a feed move at `feed` (the mode's unit), and a warning when there
    /// is none to use (no F, or mm/rev with the spindle speed unknown): the Canon then carries 0,
    /// which the machine runs at its maximum feed.
    fn path_feed(&mut self, feed: f64, span: Span, warnings: &mut Vec<Diagnostic>) -> f64 {
        let f = match self.feed_mode {
            FeedMode::UnitsPerRevolution => feed * self.spindle_rpm,
            _ => feed,
        };
        if f <= 0.0 && !self.warned_feed {
            self.warned_feed = true;
            let why = if feed <= 0.0 {
                "no feed has been programmed"
            } else {
                "feed per revolution with no spindle speed programmed"
            };
            warnings.push(
                Diagnostic::warning(
                    "lab::no-feed",
                    format!("feed move: {why}; the machine's maximum feed is used"),
                    span,
                )
                .with_note("reported once per run"),
            );
        }
        f.max(0.0)
    }
}

/// One line of a lab program.
#[derive(Debug, Clone)]
pub(crate) struct SrcLine {
    pub at: LineAt,
    pub text: String,
}

/// A main program or a subprogram.
#[derive(Debug, Clone)]
pub(crate) struct Program {
    /// Subprogram number; None for the main program.
    pub number: Option<u32>,
    /// The lines after the header.
    pub lines: Vec<SrcLine>,
    /// The file it came from when that is not the program being run.
    pub file: Option<String>,
}

impl Program {
    /// The span of its last non-blank line: where "the subprogram ends without M17" is reported.
    pub(crate) fn last_line_span(&self) -> Span {
        self.lines
            .iter()
            .rev()
            .find(|l| !l.text.trim().is_empty())
            .map(|l| l.at.span(&l.text, 0, l.text.len()))
            .unwrap_or_default()
    }
}

/// The commands of one execution unit, each stamped with the unit's span and frame number.
pub(crate) struct Emit {
    pub cmds: Vec<Spanned<Canon>>,
    pub span: Span,
    pub number: Option<u32>,
}

impl Emit {
    fn new(span: Span, number: Option<u32>) -> Self {
        Emit {
            cmds: Vec::new(),
            span,
            number,
        }
    }

    pub fn push(&mut self, value: Canon) {
        self.cmds.push(Spanned {
            span: self.span,
            block_number: self.number,
            label_digits: 0,
            value,
        });
    }
}

/// A lab program being run.
struct LabRun {
    front: Front,
    /// Spans of the errors reported so far: `stanok check` goes on after an error, and a jump back
    /// over a bad frame must not report it again.
    reported: Vec<Span>,
    /// The program is longer than [`MAX_PROGRAM_BYTES`] (reported by the first step).
    too_large: bool,
}

enum Front {
    Nc31(Box<nc31::Nc31Run>),
    Iso(Box<iso::IsoRun>),
}

impl LabRun {
    /// Splits the program text into its programs and loads the subprogram library.
    pub fn new(text: &str, opts: &LabOptions) -> LabRun {
        let dialect = opts.dialect;
        let mut programs = split_programs(&prepare(text, opts), dialect, None);
        programs.extend(library(opts));
        let state = LabState::new(dialect, opts);
        let front = match dialect {
            Dialect::Nc31 => Front::Nc31(Box::new(nc31::Nc31Run::new(programs, state))),
            _ => Front::Iso(Box::new(iso::IsoRun::new(dialect, programs, state))),
        };
        LabRun {
            front,
            reported: Vec::new(),
            too_large: text.len() as u64 > (MAX_PROGRAM_BYTES as u64).min(opts.max_program_bytes),
        }
    }

    /// The state after the units run so far.
    pub fn state(&self) -> &LabState {
        match &self.front {
            Front::Nc31(r) => &r.state,
            Front::Iso(r) => &r.state,
        }
    }

    /// Runs one execution unit: its commands go to `queue`. Ok(true) when the program is over.
    /// On an error, nothing of the unit is queued and the next call goes on after it.
    pub fn step(
        &mut self,
        queue: &mut VecDeque<Spanned<Canon>>,
        warnings: &mut Vec<Diagnostic>,
        opts: &LabOptions,
    ) -> Result<(bool, u64), Diagnostic> {
        if std::mem::take(&mut self.too_large) {
            return Err(Diagnostic::error(
                "lab::too-large",
                format!("a lab program is read into memory: at most {MAX_PROGRAM_BYTES} bytes"),
                Span::new(0, 0, 1, 1),
            ));
        }
        let r = match &mut self.front {
            Front::Nc31(r) => r.step(warnings, opts),
            Front::Iso(r) => r.step(warnings, opts),
        };
        let (done, emit, units) = match r {
            Ok(x) => x,
            Err(d) if opts.continue_after_error && self.reported.contains(&d.span) => {
                return Ok((false, 1));
            }
            Err(d) => {
                self.reported.push(d.span);
                return Err(d);
            }
        };
        queue.extend(emit.map(|e| e.cmds).unwrap_or_default());
        Ok((done, units))
    }
}

/// The text as the reader will see it: the fixture conventions removed when asked for.
fn prepare(text: &str, opts: &LabOptions) -> String {
    let mut cut = text.len().min(MAX_PROGRAM_BYTES);
    while !text.is_char_boundary(cut) {
        cut -= 1;
    }
    let text = &text[..cut];
    if opts.strip_fixture_comments {
        stanok_syntax::labs::strip_fixture_comments(text)
    } else {
        text.to_string()
    }
}

/// Cuts a file into programs: the lines before the first subprogram header are the main program;
/// each header (`L01` on the NC-31, `Lnn00` on the others) starts a subprogram.
fn split_programs(text: &str, dialect: Dialect, file: Option<String>) -> Vec<Program> {
    let mut programs = vec![Program {
        number: None,
        lines: Vec::new(),
        file: file.clone(),
    }];
    let mut offset = 0u64;
    for (i, line) in text.split('\n').enumerate() {
        let at = LineAt {
            line: i as u32 + 1,
            offset,
        };
        offset += line.len() as u64 + 1;
        let line = line.trim_end_matches('\r');
        if let Some(number) = header_number(line, dialect) {
            programs.push(Program {
                number: Some(number),
                lines: Vec::new(),
                file: file.clone(),
            });
            continue;
        }
        if let Some(p) = programs.last_mut() {
            p.lines.push(SrcLine {
                at,
                text: line.to_string(),
            });
        }
    }
    programs
}

/// The subprogram number of a header line: `L01` (NC-31, 2 digits), `L0100` (others: number and
/// `00`).
fn header_number(line: &str, dialect: Dialect) -> Option<u32> {
    let t = line.trim();
    let digits = t.strip_prefix('L')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    match dialect {
        Dialect::Nc31 if digits.len() <= 2 => digits.parse().ok(),
        Dialect::Nc31 => None,
        _ if digits.len() == 4 && digits.ends_with("00") => digits[..2].parse().ok(),
        _ => None,
    }
}

/// Subprograms in files on the subroutine path: every file there whose first program line is a
/// subprogram header of this dialect (spec §4.10: "subprograms are loaded into memory like main
/// programs").
fn library(opts: &LabOptions) -> Vec<Program> {
    let mut out = Vec::new();
    for dir in &opts.subroutine_path {
        let Ok(entries) = std::fs::read_dir(dir) else {
            continue;
        };
        let mut paths: Vec<_> = entries.flatten().map(|e| e.path()).collect();
        paths.sort();
        for path in paths {
            let Ok(text) = std::fs::read_to_string(&path) else {
                continue;
            };
            let text = prepare(&text, opts);
            let file = Some(path.display().to_string());
            let programs = split_programs(&text, opts.dialect, file);
            // Only files that are subprograms: the main part holds no program text.
            if programs.len() > 1
                && programs[0]
                    .lines
                    .iter()
                    .all(|l| l.text.trim().is_empty() || l.text.trim() == "ПС")
            {
                out.extend(programs.into_iter().skip(1));
            }
        }
    }
    out
}
