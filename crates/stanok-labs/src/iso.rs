//! The word-address lab controls: the GOST-20999 control (spec §4), the 2P32 (§3, which takes the
//! GOST-20999 rules where its own text is silent, [decide] §3.1) and the MC2101 notation (§3.10).
//!
//! A block executes in this order (the document gives none; this is the one its examples need):
//!
//! 1. checks: a letter twice (only G, M, D may repeat, §4.2), two G codes of one group, two of the
//!    one-shot G4/G28/G92 ([decide] §4.4: G9 and G53 combine with motion and do not count);
//! 2. variable assignments (`R1#39.`, 2P32 `R27 - 4910`), in written order;
//! 3. modal G codes: motion G0–G3, plane G17–G19, G90/G91, G54/G55, G40/G41/G42;
//! 4. F, S, T (2P32: the turret search of §3.6), M functions that act before motion (M3, M4, M7,
//!    M8, M83, M85, M89, M90 …);
//! 5. one of: G4 dwell (its time in the X word), G92 (set position), G28 (home), or the block's
//!    motion — axis words with the per-axis G43/G44/D binding (§4.8), G53 for this block;
//! 6. M functions that act after motion (M5, M9, M0, M1, M2, M30, M17), then the L call.
//!
//! Positions: program coordinates = machine − work origin − applied correction, per axis; a
//! correction binding takes effect on its axis's next move. 2P32: X is the radius, the Y word after
//! M89 is the spindle angle (C axis, 0.001° per count); a bare `G` is G0 (§3.4); G4's time is the
//! X word at 1 s per mm-unit ([decide]: X+4000 = 4 s, the document gives no unit). MC2101: 0.01
//! mm per count and incremental values (the lab's rule, G90 switches it).

use super::iso_comp::{BlockComp, Comp};
use super::iso_words::{code, dimension, err, number, Pending};
use super::{Emit, LabState, Program, MAX_JUMPS};
use crate::codes::{self, iso as iso_codes, iso::Handler, iso::MHandler};
use crate::LabOptions;
use stanok_canon::{AuxTiming, Canon, Diagnostic, PathMode, Plane, Span, Spanned};
use stanok_interp_core::state::MotionMode;
use stanok_syntax::labs::words::{parse_line, Item, LabBlock, Profile, Word};
use stanok_syntax::Dialect;

/// Deepest subprogram nesting (§4.10).
const MAX_NESTING: usize = 5;

/// A program running: which, the next line, and how many more runs are due.
#[derive(Debug, Clone, Copy)]
struct CallFrame {
    prog: usize,
    line: usize,
    repeats_left: u32,
}

pub(crate) struct IsoRun {
    dialect: Dialect,
    profile: Profile,
    programs: Vec<Program>,
    stack: Vec<CallFrame>,
    jumps: u32,
    /// Cutter radius compensation: the held move and what came after it.
    comp: Comp,
    pub state: LabState,
}

type StepResult = Result<(bool, Option<Emit>, u64), Diagnostic>;

/// A row of the G code table (codes.rs).
type IsoCode = stanok_interp_core::codes::Code<iso_codes::Group, Handler>;

/// What follows a block.
pub(super) enum Control {
    Next,
    End,
    Call(u32, u32, Span),
    Return(Span),
}

impl IsoRun {
    pub fn new(dialect: Dialect, programs: Vec<Program>, state: LabState) -> Self {
        let profile = match dialect {
            Dialect::P2p32 => Profile::P2p32,
            Dialect::Mc2101 => Profile::Mc2101,
            _ => Profile::Gost20999,
        };
        IsoRun {
            dialect,
            profile,
            programs,
            stack: vec![CallFrame {
                prog: 0,
                line: 0,
                repeats_left: 1,
            }],
            jumps: 0,
            comp: Comp::default(),
            state,
        }
    }

    /// Reads and runs the next block that holds something.
    pub fn step(&mut self, warnings: &mut Vec<Diagnostic>, opts: &LabOptions) -> StepResult {
        loop {
            let top = *self.stack.last().expect("main program frame");
            let file = self.programs[top.prog].file.clone();
            let at_file = |d: Diagnostic| match &file {
                Some(f) => d.in_file(f.clone()),
                None => d,
            };
            let Some(src) = self.programs[top.prog].lines.get(top.line) else {
                if self.stack.len() > 1 {
                    // Reported at the subprogram's last line; the run goes back to the caller
                    // (so that `stanok check` goes on instead of reading past the end again).
                    let span = self.programs[top.prog].last_line_span();
                    self.stack.pop();
                    return Err(at_file(Diagnostic::error(
                        "lab::no-return",
                        "the subprogram ends without M17",
                        span,
                    )));
                }
                // A program (or fragment) without M2/M30 ends with its text; a move held for
                // compensation ends at its own S1.
                let mut out = Emit::new(Span::default(), None);
                self.comp.finish(self.state.plane, &mut out.cmds);
                return Ok((true, Some(out), 0));
            };
            self.stack.last_mut().expect("frame").line += 1;
            let (block, diags) = parse_line(&src.text, src.at, self.profile);
            let text = src.text.clone();
            let line_offset = src.at.offset;
            if let Some(d) = diags.into_iter().find(|d| d.is_error()) {
                return Err(at_file(d));
            }
            if block.items.is_empty() {
                continue;
            }
            if block.skip && opts.block_delete {
                continue;
            }
            let mut st = self.state.clone();
            let mut out = Emit::new(block.span, block.number);
            let mut ctl = Control::Next;
            let in_sub = self.stack.len() > 1;
            let mut ex = Exec {
                dialect: self.dialect,
                block: &block,
                text: &text,
                line_offset,
                st: &mut st,
                out: &mut out,
                ctl: &mut ctl,
                warnings,
                opts,
                in_sub,
            };
            ex.run().map_err(at_file)?;
            // Cutter compensation moves the programmed contour's corners (§4.9).
            let mut comp = self.comp.clone();
            let before = self.state.radius_comp.0;
            let after = st.radius_comp.0;
            if !(comp.idle() && before == 0 && after == 0) {
                let d = st.radius_comp.1.unwrap_or(0);
                let bc = BlockComp {
                    after,
                    radius: opts.labs.correctors.get(&d).copied().unwrap_or(0.0),
                    plane: st.plane,
                };
                comp.block(&mut out, &bc, block.span).map_err(at_file)?;
            }
            match ctl {
                Control::Next => {}
                Control::End => {
                    self.state = st;
                    self.comp = comp;
                    return Ok((true, Some(out), 1));
                }
                Control::Call(number, times, at) => {
                    let idx = self
                        .programs
                        .iter()
                        .position(|p| p.number == Some(number))
                        .ok_or_else(|| {
                            at_file(err(
                                "lab::no-subprogram",
                                format!("subprogram {number:02} is not loaded"),
                                at,
                            ))
                            .with_note("subprograms come after the main program (header L nn 00) or in files on the subroutine path")
                        })?;
                    if self.stack.len() > MAX_NESTING {
                        return Err(at_file(err(
                            "lab::nesting",
                            format!("subprograms nested deeper than {MAX_NESTING}"),
                            at,
                        )));
                    }
                    self.count_jump(at).map_err(at_file)?;
                    self.stack.push(CallFrame {
                        prog: idx,
                        line: 0,
                        repeats_left: times,
                    });
                }
                Control::Return(at) => {
                    let top = self.stack.last_mut().expect("frame");
                    top.repeats_left -= 1;
                    if top.repeats_left > 0 {
                        top.line = 0;
                        self.count_jump(at).map_err(at_file)?;
                    } else {
                        self.stack.pop();
                    }
                }
            }
            // The caller's modal state is not restored on return (§4.10).
            self.state = st;
            self.comp = comp;
            return Ok((false, Some(out), 1));
        }
    }

    fn count_jump(&mut self, at: Span) -> Result<(), Diagnostic> {
        self.jumps += 1;
        if self.jumps > MAX_JUMPS {
            return Err(err(
                "lab::too-many-calls",
                format!("more than {MAX_JUMPS} subprogram runs: stopping"),
                at,
            ));
        }
        Ok(())
    }
}

/// One block's execution.
pub(super) struct Exec<'a> {
    pub(super) dialect: Dialect,
    pub(super) block: &'a LabBlock,
    pub(super) text: &'a str,
    pub(super) line_offset: u64,
    pub(super) st: &'a mut LabState,
    pub(super) out: &'a mut Emit,
    pub(super) ctl: &'a mut Control,
    pub(super) warnings: &'a mut Vec<Diagnostic>,
    pub(super) opts: &'a LabOptions,
    pub(super) in_sub: bool,
}

/// The G codes of a block, by group.
#[derive(Default)]
pub(super) struct Gs {
    pub(super) motion: Option<MotionMode>,
    pub(super) plane: Option<Plane>,
    pub(super) incremental: Option<bool>,
    pub(super) work: Option<u8>,
    pub(super) comp: Option<i8>,
    /// G4, G28 or G92 (their table row) and where it was written.
    pub(super) one_shot: Option<(IsoCode, Span)>,
    pub(super) g53: bool,
    pub(super) g9: bool,
    pub(super) lengths: bool,
}

impl Exec<'_> {
    pub(super) fn words(&self) -> impl Iterator<Item = &Word> {
        self.block.items.iter().filter_map(|i| match i {
            Item::Word(w) => Some(w),
            Item::Assign(_) => None,
        })
    }

    pub(super) fn word(&self, letter: char) -> Option<&Word> {
        self.words().find(|w| w.letter == letter)
    }

    fn run(&mut self) -> Result<(), Diagnostic> {
        // 1. Repeated letters.
        let mut seen: Vec<char> = Vec::new();
        for w in self.words() {
            if !matches!(w.letter, 'G' | 'M' | 'D') && seen.contains(&w.letter) {
                return Err(err(
                    "lab::repeated-word",
                    format!(
                        "{} twice in one block (only G, M and D may repeat)",
                        w.letter
                    ),
                    w.span,
                ));
            }
            seen.push(w.letter);
        }
        for w in self.words() {
            if !"GMDFSTLXYZABCUVWIJKREω".contains(w.letter) {
                return Err(err(
                    "lab::unknown-word",
                    format!("{} is not an address of this control", w.letter),
                    w.span,
                ));
            }
            if matches!(w.letter, 'E' | 'ω') {
                return Err(err(
                    "lab::unsupported",
                    format!("{} words (jumps and their conditions) are not supported: the document does not define them", w.letter),
                    w.span,
                )
                .with_note("spec lab-collection §3.3, §4.10: the arithmetic and jumps of the missing section 10"));
            }
        }
        // 2. Assignments.
        for item in &self.block.items {
            if let Item::Assign(a) = item {
                self.st
                    .variables
                    .insert(a.number, (a.value.value, a.value.point));
            }
        }
        // 3. G codes.
        let gs = self.g_codes()?;
        if let Some(p) = gs.plane {
            self.st.plane = p;
            self.out.push(Canon::SelectPlane { plane: p });
        }
        if let Some(i) = gs.incremental {
            self.st.incremental = i;
        }
        if let Some(w) = gs.work {
            self.st.work_system = w;
        }
        if let Some(m) = gs.motion {
            self.st.motion = m;
        }
        let comp_before = self.st.radius_comp.0;
        if let Some(c) = gs.comp {
            self.st.radius_comp.0 = c;
            if c == 0 && self.dialect == Dialect::P2p32 {
                // 2P32 G40: "cancel all correctors" (§3.4).
                self.st.axis_correction = [(0, None); 9];
                self.st.pending = Pending::default();
            }
        }
        // 4. F, S, T, M before motion.
        self.technology()?;
        for w in self
            .words()
            .filter(|w| w.letter == 'M')
            .copied()
            .collect::<Vec<_>>()
        {
            self.m_function(&w, true)?;
        }
        // 5. The block's action.
        match gs.one_shot.map(|(c, at)| (c.handler, at)) {
            Some((Handler::Dwell, at)) => self.dwell(at)?,
            Some((Handler::SetPosition, at)) => self.set_position(at)?,
            Some((Handler::Home, _)) => self.home()?,
            _ => {
                // G9 (§4.6): exact stop at the end of this block only.
                let mark = self.out.cmds.len();
                self.motion(&gs, comp_before)?;
                let moved = self.out.cmds[mark..]
                    .iter()
                    .any(|c| c.value.motion().is_some());
                if gs.g9 && moved {
                    self.out.cmds.insert(
                        mark,
                        Spanned {
                            value: Canon::SetPathMode {
                                mode: PathMode::ExactStop,
                                naive_cam_tolerance: None,
                            },
                            ..self.out.cmds[mark].clone()
                        },
                    );
                    self.out.push(Canon::SetPathMode {
                        mode: PathMode::Continuous { tolerance: 0.0 },
                        naive_cam_tolerance: None,
                    });
                }
            }
        }
        // 6. After motion.
        for w in self
            .words()
            .filter(|w| w.letter == 'M')
            .copied()
            .collect::<Vec<_>>()
        {
            self.m_function(&w, false)?;
        }
        self.call()
    }

    fn g_codes(&mut self) -> Result<Gs, Diagnostic> {
        let mut gs = Gs::default();
        fn set<T>(slot: &mut Option<T>, v: T, w: &Word, what: &str) -> Result<(), Diagnostic> {
            if slot.is_some() {
                return Err(err(
                    "lab::g-group",
                    format!("two {what} codes in one block"),
                    w.span,
                ));
            }
            *slot = Some(v);
            Ok(())
        }
        for w in self.words().copied().collect::<Vec<_>>() {
            if w.letter != 'G' {
                continue;
            }
            let g = match w.value {
                None if self.dialect == Dialect::P2p32 => 0,
                _ => code(&w, self.st)?,
            };
            let Some(c) = codes::lookup(g, iso_codes::g_code) else {
                return Err(err(
                    "lab::unknown-g",
                    format!("G{g} is not a function of this control"),
                    w.span,
                ));
            };
            let what = c.group.name();
            match c.handler {
                Handler::SetMotion(m) => set(&mut gs.motion, m, &w, what)?,
                Handler::SetPlane(p) => set(&mut gs.plane, p, &w, what)?,
                Handler::SetIncremental(i) => set(&mut gs.incremental, i, &w, what)?,
                Handler::SetWork(n) => set(&mut gs.work, n, &w, what)?,
                Handler::SetRadiusComp(r) => set(&mut gs.comp, r, &w, what)?,
                Handler::LengthBinding(_) => gs.lengths = true,
                Handler::ExactStop => gs.g9 = true,
                Handler::MachineCoordinates => gs.g53 = true,
                Handler::Dwell | Handler::Home | Handler::SetPosition => {
                    if let Some((other, _)) = gs.one_shot {
                        return Err(err(
                            "lab::one-shot",
                            format!(
                                "G{g} and {} in one block: two one-shot functions",
                                other.name
                            ),
                            w.span,
                        ));
                    }
                    gs.one_shot = Some((c, w.span));
                }
                Handler::CylinderSystem => {
                    // The part radius of the XA system is corrector 175 (§4.4): 0 is error 17.
                    if self.opts.labs.correctors.get(&175).copied().unwrap_or(0.0) == 0.0 {
                        return Err(Diagnostic::manual(
                            17,
                            "G20: the part radius in corrector 175 is 0",
                            w.span,
                        ));
                    }
                    return Err(err(
                        "lab::unsupported",
                        "G20 (the XA coordinate system for compensation on a cylinder) is not supported",
                        w.span,
                    ));
                }
            }
        }
        Ok(gs)
    }

    fn technology(&mut self) -> Result<(), Diagnostic> {
        if let Some(w) = self.word('F').copied() {
            let n = number(&w, self.st)?;
            // F: direct coding in mm/min, 1 mm/min steps, 1…24000 (§4.6).
            if !(1.0..=24000.0).contains(&n.value) {
                return Err(err(
                    "lab::feed-range",
                    format!("F {} is outside 1…24000 mm/min", n.value),
                    w.span,
                ));
            }
            self.st.feed = n.value;
            self.out.push(Canon::SetFeedRate { feed: n.value });
        }
        if let Some(w) = self.word('S').copied() {
            let s = code(&w, self.st)?;
            if s < 0 {
                return Err(err("lab::bad-speed", "S must not be negative", w.span));
            }
            self.st.spindle_rpm = s as f64;
            self.out.push(Canon::SetSpindleSpeed {
                spindle: 0,
                rpm: s as f64,
            });
        }
        if let Some(w) = self.word('T').copied() {
            let t = code(&w, self.st)?;
            if t < 0 {
                return Err(err("lab::bad-tool", "T must not be negative", w.span));
            }
            if self.dialect == Dialect::P2p32 {
                self.turret_search(t as u32, w.span)?;
            }
            self.st.tool = Some(t as u32);
            self.out.push(Canon::SelectTool { tool: t as u32 });
            self.out.push(Canon::ChangeTool {
                tool: t as u32,
                slot: t as u32,
            });
        }
        Ok(())
    }

    /// 2P32 tool search (§3.6): the position whose corrector 380 + p holds the code; the turret
    /// turns the shorter way, forward (increasing position) = counter-clockwise; [decide] a tie at
    /// 6 steps turns forward; a code held by no position or by several is an error.
    fn turret_search(&mut self, tool_code: u32, at: Span) -> Result<(), Diagnostic> {
        let codes = &self.opts.labs.turret_codes;
        let holders: Vec<u32> = (1..=12u32)
            .filter(|&p| codes[p as usize - 1] == tool_code)
            .collect();
        let target = match holders.as_slice() {
            [p] => *p,
            [] => {
                return Err(err(
                    "lab::tool-code-not-found",
                    format!("no turret position holds tool code {tool_code} (correctors 381–392)"),
                    at,
                ))
            }
            many => {
                return Err(err(
                    "lab::tool-code-ambiguous",
                    format!("tool code {tool_code} is in several turret positions: {many:?}"),
                    at,
                ))
            }
        };
        let current = self.st.turret_position;
        let forward = (target + 12 - current) % 12;
        let backward = (current + 12 - target) % 12;
        let text = if forward == 0 {
            format!("turret: tool code {tool_code} already at position {target}")
        } else if forward <= backward {
            format!("turret: position {current} -> {target}, {forward} step(s) counter-clockwise")
        } else {
            format!("turret: position {current} -> {target}, {backward} step(s) clockwise")
        };
        self.out.push(Canon::Comment { text });
        self.st.turret_position = target;
        Ok(())
    }

    /// One M word, through the table (`codes::iso::M_CODES`): `before` runs the rows that act
    /// before the block's motion (and the machine functions without a row), else those after it.
    fn m_function(&mut self, w: &Word, before: bool) -> Result<(), Diagnostic> {
        let m = code(w, self.st)?;
        let row = u32::try_from(m).ok().and_then(iso_codes::m_code);
        let after_motion = row.is_some_and(|c| c.handler.after_motion());
        if before == after_motion {
            return Ok(());
        }
        let Some(row) = row else {
            if m < 0 {
                return Err(err("lab::bad-m", "M must not be negative", w.span));
            }
            self.out.push(Canon::AuxiliaryFunction {
                number: m as u32,
                timing: AuxTiming::Prefix,
            });
            return Ok(());
        };
        match row.handler {
            MHandler::StartSpindle(direction) => {
                self.st.spindle = Some(direction);
                self.out.push(Canon::StartSpindle {
                    spindle: 0,
                    direction,
                });
            }
            MHandler::StopSpindle => {
                self.st.spindle = None;
                self.out.push(Canon::StopSpindle { spindle: 0 });
            }
            MHandler::Mist => self.out.push(Canon::Mist { on: true }),
            MHandler::Flood => self.out.push(Canon::Flood { on: true }),
            MHandler::CoolantOff => {
                self.out.push(Canon::Mist { on: false });
                self.out.push(Canon::Flood { on: false });
            }
            MHandler::Stop(optional) => self.out.push(Canon::ProgramStop { optional }),
            MHandler::End => {
                self.st.spindle = None;
                self.out.push(Canon::ProgramEnd);
                *self.ctl = Control::End;
            }
            MHandler::SubprogramEnd => {
                if !self.in_sub {
                    return Err(err(
                        "lab::m17-in-main",
                        "M17 (end of subprogram) is not allowed in a main program",
                        w.span,
                    ));
                }
                // "The last block holds M17 and no geometric or technological information"
                // (§4.10): a move or a feed there would belong to no contour of the caller's.
                if let Some(o) = self
                    .words()
                    .find(|o| "XYZUVWPQIJKABCDEFST".contains(o.letter))
                {
                    return Err(err(
                        "lab::m17-block",
                        format!(
                            "the M17 block holds no geometric or technological words, not {}",
                            o.letter
                        ),
                        o.span,
                    )
                    .with_note("move the word to a block of its own before M17"));
                }
                *self.ctl = Control::Return(w.span);
            }
            MHandler::ServoSpindle(on) => {
                if self.dialect == Dialect::P2p32 {
                    self.st.servo_spindle = on;
                }
                self.out.push(Canon::AuxiliaryFunction {
                    number: m as u32,
                    timing: AuxTiming::Prefix,
                });
            }
        }
        Ok(())
    }

    /// G4: the time is the X word, 1 s per mm-unit (0.001 s per count).
    fn dwell(&mut self, at: Span) -> Result<(), Diagnostic> {
        let Some(w) = self.word('X').copied() else {
            return Err(err(
                "lab::dwell-time",
                "G4 needs its time in the X word",
                at,
            ));
        };
        let n = number(&w, self.st)?;
        let seconds = dimension(self.dialect, n);
        if seconds < 0.0 {
            return Err(err(
                "lab::dwell-time",
                "a dwell time must not be negative",
                w.span,
            ));
        }
        self.out.push(Canon::Dwell { seconds });
        Ok(())
    }

    /// The L call (§4.10): last word of its block, with only G codes and assignments beside it;
    /// `Lnnrr` = subprogram nn, rr times (1…99, `00` forbidden); `Lnn` = `Lnn01`.
    fn call(&mut self) -> Result<(), Diagnostic> {
        let Some(w) = self.word('L').copied() else {
            return Ok(());
        };
        if !matches!(self.block.items.last(), Some(Item::Word(l)) if l.span == w.span) {
            return Err(err(
                "lab::call-not-last",
                "the L call must be the last word of its block",
                w.span,
            ));
        }
        if let Some(o) = self.words().find(|o| !matches!(o.letter, 'G' | 'L')) {
            return Err(err(
                "lab::call-block",
                format!(
                    "a call block holds only G codes and assignments, not {}",
                    o.letter
                ),
                o.span,
            ));
        }
        let v = code(&w, self.st)?;
        let start = (w.span.start - self.line_offset) as usize;
        let end = (w.span.end - self.line_offset) as usize;
        let digits = self
            .text
            .get(start..end)
            .map_or(0, |t| t.bytes().filter(u8::is_ascii_digit).count());
        let (number, times) = match digits {
            1 | 2 => (v, 1),
            4 => (v / 100, v % 100),
            _ => {
                return Err(err(
                    "lab::call-format",
                    "a call is L + 2 digits (subprogram) or 4 digits (subprogram, repeats); keep the leading zero",
                    w.span,
                ))
            }
        };
        if times == 0 {
            return Err(err(
                "lab::call-format",
                "a call cannot repeat 00 times (L..00 is a subprogram header)",
                w.span,
            ));
        }
        *self.ctl = Control::Call(number as u32, times as u32, w.span);
        Ok(())
    }
}
