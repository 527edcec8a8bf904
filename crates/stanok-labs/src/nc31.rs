//! The Elektronika NC-31 (16K20F3 lathe) executor (spec lab-collection §2).
//!
//! Unit of execution = a *group*: frames are read until one without `*`; the group is dispatched
//! on its first frame (spec §2.11):
//!
//! ```text
//!   X | Z                      single-axis move (flags: rapid, incremental, chamfer ±45)
//!   X* Z [F] | Z* X [F]        simultaneous two-axis line, F local to the group
//!   X* F | Z* F                single-axis move with a group-local feed
//!   G2*/G3* X* Z* P* P [F]     arc of less than 90° (§2.6.1)
//!   G12*/G13* X* Z* [F]        quarter-circle rounding (§2.6.2)
//!   G94 | G95 | F | S | M | T  modal frames;   P nnn  jump to frame nnn (§2.10)
//!   G25* P aaabbb* [R k]       repeat frames aaa…bbb k more times (§2.10 best reading)
//!   G31*, ~S …*, R             recognised, refused as unsupported (the document gives no rule)
//! ```
//!
//! Units: X is the diameter in 0.01 mm (radius = value × 0.005 mm), Z and the arc's P words 0.01
//! mm (P's X part on the radius, [derived] §2.6.1). Canon X is the radius. Arc sense [derived,
//! decided as proposed]: G2/G12 turn counter-clockwise in a Z-right/X-up view (the tool-post view
//! with +X pointing down makes them clockwise), i.e. about +Y; G3/G13 about −Y.
//!
//! F [doc §2.7 + decided]: a stand-alone F frame is 1 mm/min (G94) or 0.01 mm/rev (G95) per unit
//! and is modal; an F inside a group is 0.01 mm/min (G94) or 0.01 mm/rev (G95, [decide]: the
//! document gives no unit) per unit and holds for that group only. RAPID frames keep the modal F.

use super::nc31_moves::{
    arc_group, axis_target, feed_line, get, line_group, rounding_group, set, traverse,
};
use super::{Emit, LabState, Program, MAX_JUMPS};
use crate::codes::{self, nc31 as nc31_codes, nc31::Handler, nc31::MHandler};
use crate::LabOptions;
use stanok_canon::{Canon, Diagnostic, FeedMode, Span};
use stanok_syntax::labs::nc31::{parse_line, Body, Chamfer, Line};

/// Radius mm per unit of an X (diameter) value.
pub(super) const X_MM: f64 = 0.005;
/// mm per unit of Z and of the arc's P words.
pub(super) const Z_MM: f64 = 0.01;

pub(crate) struct Nc31Run {
    programs: Vec<Program>,
    /// (program, next line) of the program running and of each caller.
    stack: Vec<(usize, usize)>,
    /// Active `G25` repeats, innermost last.
    repeats: Vec<Repeat>,
    jumps: u32,
    pub state: LabState,
}

/// A `G25* P aaabbb* R k` repeat ([decide] §2.10, the spec's best reading): frames aaa…bbb run k
/// more times, then the program goes on after the G25 group.
#[derive(Debug, Clone, Copy)]
struct Repeat {
    depth: usize,
    start: usize,
    last: usize,
    left: u32,
    back: usize,
}

/// One frame of a group, with its span.
pub(super) struct Frame {
    pub(super) number: u32,
    pub(super) span: Span,
    pub(super) body: Body,
}

type StepResult = Result<(bool, Option<Emit>, u64), Diagnostic>;

impl Nc31Run {
    pub fn new(programs: Vec<Program>, state: LabState) -> Self {
        Nc31Run {
            programs,
            stack: vec![(0, 0)],
            repeats: Vec::new(),
            jumps: 0,
            state,
        }
    }

    /// Reads the next group and executes it on a copy of the state.
    pub fn step(&mut self, warnings: &mut Vec<Diagnostic>, opts: &LabOptions) -> StepResult {
        let (prog, first_line) = *self.stack.last().expect("main program frame");
        let file = self.programs[prog].file.clone();
        let at_file = |d: Diagnostic| match &file {
            Some(f) => d.in_file(f.clone()),
            None => d,
        };
        // Read frames up to the first one without `*`.
        let mut frames: Vec<Frame> = Vec::new();
        let mut line = first_line;
        let mut error = None;
        let lines = &self.programs[prog].lines;
        loop {
            let Some(src) = lines.get(line) else {
                if let Some(f) = frames.last() {
                    error.get_or_insert(Diagnostic::error(
                        "nc31::unterminated-group",
                        "the program ends inside a `*` group",
                        f.span,
                    ));
                    break;
                }
                self.stack.last_mut().expect("frame").1 = line;
                if self.stack.len() > 1 {
                    // Reported at the subprogram's last line; the run goes back to the caller
                    // (so that `stanok check` goes on instead of reading past the end again).
                    let span = self.programs[prog].last_line_span();
                    self.stack.pop();
                    return Err(at_file(Diagnostic::error(
                        "nc31::no-return",
                        "the subprogram ends without M17",
                        span,
                    )));
                }
                return Ok((true, None, 0));
            };
            line += 1;
            let (parsed, diags) = parse_line(&src.text, src.at);
            if let Some(d) = diags.into_iter().next() {
                error.get_or_insert(d);
            }
            match parsed {
                Line::Empty | Line::Header { .. } => {
                    if frames.is_empty() && error.is_some() {
                        break;
                    }
                    continue;
                }
                Line::Frame {
                    body: None, span, ..
                } => {
                    if frames.is_empty() {
                        // An empty frame (N195): no operation.
                        self.stack.last_mut().expect("frame").1 = line;
                        if error.is_some() {
                            break;
                        }
                        return Ok((false, Some(Emit::new(span, None)), 1));
                    }
                    error.get_or_insert(Diagnostic::error(
                        "nc31::empty-frame-in-group",
                        "an empty frame inside a `*` group",
                        span,
                    ));
                    break;
                }
                Line::Frame {
                    number,
                    span,
                    body: Some(body),
                } => {
                    let more = body.group;
                    frames.push(Frame { number, span, body });
                    if !more {
                        break;
                    }
                }
            }
        }
        self.stack.last_mut().expect("frame").1 = line;
        if let Some(d) = error {
            let _ = self.section_end(first_line, line, d.span);
            return Err(at_file(d));
        }
        let span = group_span(&frames);
        let mut emit = Emit::new(span, Some(frames[0].number));
        let mut st = self.state.clone();
        let mut ctl = Control::Next;
        let done = execute(&frames, &mut st, &mut emit, &mut ctl, warnings, opts);
        // A failing unit ends a repeated section too (`stanok check` goes on after it).
        let repeated = self.section_end(first_line, line, span);
        done.map_err(at_file)?;
        repeated.map_err(at_file)?;
        let units = frames.len() as u64;
        match ctl {
            Control::Next => {}
            Control::Repeat(from, to, times, at) => {
                let start = self.find_frame(prog, from);
                let last = self.find_frame(prog, to);
                let (Some(start), Some(last)) = (start, last) else {
                    return Err(at_file(Diagnostic::error(
                        "nc31::no-such-frame",
                        format!(
                            "G25 repeats frames N{from}…N{to}, which the program does not have"
                        ),
                        at,
                    )));
                };
                if start > last || (start..=last).contains(&first_line) {
                    return Err(at_file(Diagnostic::error(
                        "nc31::bad-repeat",
                        format!(
                            "G25: N{from}…N{to} is not a section before or after the G25 group"
                        ),
                        at,
                    )));
                }
                if times > 0 {
                    self.count_jump(at).map_err(at_file)?;
                    if self.repeats.len() >= 5 {
                        return Err(at_file(Diagnostic::error(
                            "nc31::nesting",
                            "G25 repeats nested deeper than 5",
                            at,
                        )));
                    }
                    self.repeats.push(Repeat {
                        depth: self.stack.len(),
                        start,
                        last,
                        left: times,
                        back: line,
                    });
                    self.stack.last_mut().expect("frame").1 = start;
                }
            }
            Control::End => {
                self.state = st;
                return Ok((true, Some(emit), units));
            }
            Control::Jump(target, at) => {
                let idx = self.find_frame(prog, target).ok_or_else(|| {
                    at_file(Diagnostic::error(
                        "nc31::no-such-frame",
                        format!("jump to frame N{target}, which the program does not have"),
                        at,
                    ))
                })?;
                if idx < line {
                    self.count_jump(at).map_err(at_file)?;
                }
                self.stack.last_mut().expect("frame").1 = idx;
            }
            Control::Call(number, at) => {
                let idx = self
                    .programs
                    .iter()
                    .position(|p| p.number == Some(number))
                    .ok_or_else(|| {
                        at_file(Diagnostic::error(
                            "nc31::no-subprogram",
                            format!("subprogram {number:02} is not loaded"),
                            at,
                        ))
                    })?;
                if self.stack.len() > 5 {
                    return Err(at_file(Diagnostic::error(
                        "nc31::nesting",
                        "subprograms nested deeper than 5",
                        at,
                    )));
                }
                self.count_jump(at).map_err(at_file)?;
                self.stack.push((idx, 0));
            }
            Control::Return(at) => {
                if self.stack.len() == 1 {
                    return Err(at_file(Diagnostic::error(
                        "nc31::return-in-main",
                        "M17 (return from subprogram) in the main program",
                        at,
                    )));
                }
                self.stack.pop();
            }
        }
        self.state = st;
        Ok((false, Some(emit), units))
    }

    /// After the unit on lines `first..line`: at the end of a repeated section, run it once more
    /// or go back after its G25 group.
    /// Every repetition counts against [`MAX_JUMPS`]; past it the repeat ends with an error.
    fn section_end(&mut self, first: usize, line: usize, at: Span) -> Result<(), Diagnostic> {
        let depth = self.stack.len();
        let Some(rep) = self.repeats.last_mut() else {
            return Ok(());
        };
        if rep.depth != depth || !(first..line).contains(&rep.last) {
            return Ok(());
        }
        rep.left -= 1;
        let (left, start, back) = (rep.left, rep.start, rep.back);
        if left == 0 {
            self.repeats.pop();
            self.stack.last_mut().expect("frame").1 = back;
            return Ok(());
        }
        self.stack.last_mut().expect("frame").1 = start;
        if let Err(e) = self.count_jump(at) {
            self.repeats.pop();
            self.stack.last_mut().expect("frame").1 = back;
            return Err(e);
        }
        Ok(())
    }

    fn count_jump(&mut self, at: Span) -> Result<(), Diagnostic> {
        self.jumps += 1;
        if self.jumps > MAX_JUMPS {
            return Err(Diagnostic::error(
                "nc31::too-many-jumps",
                format!("more than {MAX_JUMPS} backward jumps and calls: stopping (endless loop?)"),
                at,
            ));
        }
        Ok(())
    }

    /// The line index of frame `number` in program `prog` (its first occurrence).
    fn find_frame(&self, prog: usize, number: u32) -> Option<usize> {
        self.programs[prog].lines.iter().position(
            |l| matches!(parse_line(&l.text, l.at).0, Line::Frame { number: n, .. } if n == number),
        )
    }
}

/// What happens after a group.
enum Control {
    Next,
    /// G25: frames (from, to), times.
    Repeat(u32, u32, u32, Span),
    End,
    Jump(u32, Span),
    Call(u32, Span),
    Return(Span),
}

/// The span from the first frame's start to the last frame's end.
pub(super) fn group_span(frames: &[Frame]) -> Span {
    let (a, b) = (frames[0].span, frames[frames.len() - 1].span);
    Span::new(a.start, b.end, a.line, a.column)
}

fn unsupported(what: &str, at: Span) -> Diagnostic {
    Diagnostic::error(
        "nc31::unsupported",
        format!("{what} is not supported: the lab document gives no rule for it"),
        at,
    )
    .with_note("spec lab-collection §2.9–§2.10")
}

pub(super) fn value_of(f: &Frame) -> Result<i64, Diagnostic> {
    f.body.value.ok_or_else(|| {
        Diagnostic::error(
            "nc31::missing-value",
            format!("{} needs a value", f.body.address as char),
            f.body.address_span,
        )
    })
}

/// Executes one group on the scratch state `st`.
fn execute(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    ctl: &mut Control,
    warnings: &mut Vec<Diagnostic>,
    opts: &LabOptions,
) -> Result<(), Diagnostic> {
    let first = &frames[0];
    let b = &first.body;
    if b.chamfer.is_some() && frames.len() > 1 {
        return Err(unsupported("a chamfer flag in a group", b.address_span));
    }
    if frames.len() == 1 {
        return single(first, st, out, ctl, warnings, opts);
    }
    match b.address {
        b'X' | b'Z' => line_group(frames, st, out, warnings),
        b'G' => {
            let g = value_of(first)?;
            match codes::lookup(g, nc31_codes::g_code).map(|c| c.handler) {
                Some(Handler::ArcGroup) => arc_group(frames, st, out, warnings, opts),
                Some(Handler::RoundingGroup) => rounding_group(frames, st, out, warnings, opts),
                Some(Handler::Unsupported) => {
                    Err(unsupported(&format!("the canned cycle G{g}"), first.span))
                }
                Some(Handler::RepeatGroup) => repeat_group(frames, ctl),
                Some(Handler::SetFeedUnit(_)) | None => Err(Diagnostic::error(
                    "nc31::bad-group",
                    format!("G{g} does not start a group"),
                    first.span,
                )),
            }
        }
        b'S' if b.rapid => Err(unsupported("the `~S` group", first.span)),
        a => Err(Diagnostic::error(
            "nc31::bad-group",
            format!(
                "a group cannot start with {}: only moves, arcs and cycles form groups",
                a as char
            ),
            b.address_span,
        )),
    }
}

/// `G25* P aaabbb* [R k]`: repeat frames aaa…bbb k times (1 without R).
fn repeat_group(frames: &[Frame], ctl: &mut Control) -> Result<(), Diagnostic> {
    let bad = |at: Span| {
        Diagnostic::error(
            "nc31::bad-group",
            "a repeat group is G25*, P aaabbb* (first and last frame), R k (times)",
            at,
        )
    };
    let p = frames.get(1).ok_or_else(|| bad(frames[0].span))?;
    if p.body.address != b'P' || frames.len() > 3 {
        return Err(bad(p.span));
    }
    let v = value_of(p)?;
    if v < 0 {
        return Err(bad(p.span));
    }
    let times = match frames.get(2) {
        Some(r) if r.body.address == b'R' => value_of(r)?,
        Some(r) => return Err(bad(r.span)),
        None => 1,
    };
    if !(0..=999).contains(&times) {
        return Err(Diagnostic::error(
            "nc31::bad-repeat",
            "the repeat count R is 0…999",
            frames[2].span,
        ));
    }
    *ctl = Control::Repeat(
        (v / 1000) as u32,
        (v % 1000) as u32,
        times as u32,
        frames[0].span,
    );
    Ok(())
}

/// A frame on its own.
fn single(
    f: &Frame,
    st: &mut LabState,
    out: &mut Emit,
    ctl: &mut Control,
    warnings: &mut Vec<Diagnostic>,
    opts: &LabOptions,
) -> Result<(), Diagnostic> {
    let b = &f.body;
    if b.chamfer.is_some() && !matches!(b.address, b'X' | b'Z') {
        return Err(Diagnostic::error(
            "nc31::bad-chamfer",
            "the chamfer flag belongs to an X or Z frame",
            f.span,
        ));
    }
    if b.rapid && !matches!(b.address, b'X' | b'Z') {
        return Err(unsupported(
            &format!("the rapid flag on {}", b.address as char),
            f.span,
        ));
    }
    match b.address {
        b'X' | b'Z' => {
            let axis = if b.address == b'X' { 0 } else { 2 };
            let Some(v) = b.value else {
                if !b.rapid {
                    return Err(value_of(f).unwrap_err());
                }
                // `~X` / `~Z` without a value (flange listing): rapid return of that axis to the
                // fixed point, decided = where the program started (spec §2.10).
                let mut end = st.position;
                set(&mut end, axis, get(&opts.initial_position, axis));
                traverse(st, out, end);
                return Ok(());
            };
            let mut end = st.position;
            let start_v = get(&st.position, axis);
            let target = axis_target(axis, v, b.incremental, start_v);
            set(&mut end, axis, target);
            if let Some(ch) = b.chamfer {
                // ±45 (spec §2.5.6, [derived]): the other axis moves by the same distance (radius
                // distance for X) in the flag's direction.
                let sign = match ch {
                    Chamfer::Plus => 1.0,
                    Chamfer::Minus => -1.0,
                    Chamfer::Unknown => {
                        return Err(Diagnostic::error(
                            "nc31::unknown-chamfer",
                            "`~45°` has no documented meaning (probably -45°)",
                            f.span,
                        ))
                    }
                };
                let other = 2 - axis;
                let d = (target - start_v).abs();
                set(&mut end, other, get(&st.position, other) + sign * d);
            }
            if b.rapid {
                traverse(st, out, end);
            } else {
                let feed = st.path_feed(st.feed, f.span, warnings);
                feed_line(st, out, end, feed);
            }
        }
        b'G' => {
            let g = value_of(f)?;
            match codes::lookup(g, nc31_codes::g_code).map(|c| c.handler) {
                Some(Handler::SetFeedUnit(mode)) => {
                    st.feed_mode = mode;
                    out.push(Canon::SetFeedMode { mode });
                }
                Some(Handler::ArcGroup | Handler::RoundingGroup) => {
                    return Err(Diagnostic::error(
                        "nc31::group-expected",
                        format!("G{g} starts an arc group: G{g}*, X*, Z*, … (spec §2.6)"),
                        f.span,
                    ))
                }
                Some(Handler::RepeatGroup | Handler::Unsupported) => {
                    return Err(unsupported(&format!("G{g}"), f.span))
                }
                None => {
                    return Err(Diagnostic::error(
                        "nc31::unknown-g",
                        format!("G{g} is not an NC-31 function of the lab document"),
                        f.span,
                    ))
                }
            }
        }
        b'F' => {
            let v = value_of(f)? as f64;
            if v <= 0.0 {
                return Err(Diagnostic::error(
                    "nc31::bad-feed",
                    "F must be positive",
                    f.span,
                ));
            }
            st.feed = match st.feed_mode {
                FeedMode::UnitsPerRevolution => v * 0.01,
                _ => v,
            };
            out.push(Canon::SetFeedRate { feed: st.feed });
        }
        b'S' => {
            let v = value_of(f)?;
            // A 2-digit S after a sub-range M38–M41 is the automatic gearbox's code (§2.8).
            let rpm = if st.gear_range.is_some() && (0..=99).contains(&v) {
                opts.labs
                    .nc31_gearbox_rpm
                    .get(v as usize)
                    .copied()
                    .ok_or_else(|| {
                        Diagnostic::error(
                            "nc31::gearbox-code",
                            format!("no speed for gearbox code S{v} in the machine data"),
                            f.span,
                        )
                    })?
            } else if v < 0 {
                return Err(Diagnostic::error(
                    "nc31::bad-speed",
                    "S must not be negative",
                    f.span,
                ));
            } else {
                v as f64
            };
            st.spindle_rpm = rpm;
            out.push(Canon::SetSpindleSpeed { spindle: 0, rpm });
        }
        b'M' => {
            // Through the table (`codes::nc31::M_CODES`); a number without a row is a machine
            // function.
            let m = value_of(f)?;
            let row = u32::try_from(m).ok().and_then(nc31_codes::m_code);
            match row.map(|c| c.handler) {
                Some(MHandler::StartSpindle(direction)) => {
                    st.spindle = Some(direction);
                    out.push(Canon::StartSpindle {
                        spindle: 0,
                        direction,
                    });
                }
                Some(MHandler::StopSpindle) => {
                    st.spindle = None;
                    out.push(Canon::StopSpindle { spindle: 0 });
                }
                Some(MHandler::Stop) => out.push(Canon::ProgramStop { optional: false }),
                Some(MHandler::Return) => *ctl = Control::Return(f.span),
                Some(MHandler::End) => {
                    st.spindle = None;
                    out.push(Canon::ProgramEnd);
                    *ctl = Control::End;
                }
                Some(MHandler::GearRange) | None => {
                    if row.is_some() {
                        st.gear_range = Some(m as u32);
                    }
                    out.push(Canon::AuxiliaryFunction {
                        number: m.max(0) as u32,
                        timing: stanok_canon::AuxTiming::Prefix,
                    });
                }
            }
        }
        b'T' => {
            let t = value_of(f)?;
            if t < 0 {
                return Err(Diagnostic::error(
                    "nc31::bad-tool",
                    "T must not be negative",
                    f.span,
                ));
            }
            st.tool = Some(t as u32);
            out.push(Canon::SelectTool { tool: t as u32 });
            out.push(Canon::ChangeTool {
                tool: t as u32,
                slot: t as u32,
            });
        }
        b'P' => {
            // A stand-alone P: unconditional jump to frame nnn ([decide] §2.10).
            let target = value_of(f)?;
            *ctl = Control::Jump(target.max(0) as u32, f.span);
        }
        b'L' => {
            // `L0201`: subprogram 02, once (the GOST-20999 rule the flange listing follows).
            let v = value_of(f)?;
            let (number, times) = if v >= 100 { (v / 100, v % 100) } else { (v, 1) };
            if times != 1 {
                return Err(unsupported("a repeated subprogram call", f.span));
            }
            *ctl = Control::Call(number as u32, f.span);
        }
        b'R' => return Err(unsupported("an R frame outside a G25 group", f.span)),
        _ => unreachable!("the reader admits only G F X Z P M S T L R"),
    }
    Ok(())
}
