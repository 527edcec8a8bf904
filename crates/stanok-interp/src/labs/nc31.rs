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
//!   G31*, G25*, ~S …*, L, R     recognised, refused as unsupported (the document gives no cycle)
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

use super::{Emit, LabState, Program, MAX_JUMPS};
use crate::InterpOptions;
use stanok_canon::{
    ArcMove, Canon, Diagnostic, FeedMode, LineMove, Plane, Pose, Span, SpindleDirection,
};
use stanok_syntax::labs::nc31::{parse_line, Body, Chamfer, Line};

/// Radius mm per unit of an X (diameter) value.
const X_MM: f64 = 0.005;
/// mm per unit of Z and of the arc's P words.
const Z_MM: f64 = 0.01;

pub(crate) struct Nc31Run {
    programs: Vec<Program>,
    /// (program, next line) of the program running and of each caller.
    stack: Vec<(usize, usize)>,
    jumps: u32,
    pub state: LabState,
}

/// One frame of a group, with its span.
struct Frame {
    number: u32,
    span: Span,
    body: Body,
}

type StepResult = Result<(bool, Option<Emit>, u64), Diagnostic>;

impl Nc31Run {
    pub fn new(programs: Vec<Program>, state: LabState) -> Self {
        Nc31Run {
            programs,
            stack: vec![(0, 0)],
            jumps: 0,
            state,
        }
    }

    /// Reads the next group and executes it on a copy of the state.
    pub fn step(&mut self, warnings: &mut Vec<Diagnostic>, opts: &InterpOptions) -> StepResult {
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
                    let span = self.programs[prog]
                        .lines
                        .iter()
                        .rev()
                        .find(|l| !l.text.trim().is_empty())
                        .map(|l| l.at.span(&l.text, 0, l.text.len()))
                        .unwrap_or_default();
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
            return Err(at_file(d));
        }
        let span = group_span(&frames);
        let mut emit = Emit::new(span, Some(frames[0].number));
        let mut st = self.state.clone();
        let mut ctl = Control::Next;
        execute(&frames, &mut st, &mut emit, &mut ctl, warnings, opts).map_err(at_file)?;
        let units = frames.len() as u64;
        match ctl {
            Control::Next => {}
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
    End,
    Jump(u32, Span),
    Call(u32, Span),
    Return(Span),
}

/// The span from the first frame's start to the last frame's end.
fn group_span(frames: &[Frame]) -> Span {
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

fn value_of(f: &Frame) -> Result<i64, Diagnostic> {
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
    opts: &InterpOptions,
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
        b'G' => match value_of(first)? {
            2 | 3 => arc_group(frames, st, out, warnings, opts),
            12 | 13 => rounding_group(frames, st, out, warnings, opts),
            31 | 32 | 33 | 77 | 78 => Err(unsupported(
                &format!("the canned cycle G{}", value_of(first)?),
                first.span,
            )),
            25 => Err(unsupported("the G25 repeat/call group", first.span)),
            g => Err(Diagnostic::error(
                "nc31::bad-group",
                format!("G{g} does not start a group"),
                first.span,
            )),
        },
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

/// A frame on its own.
fn single(
    f: &Frame,
    st: &mut LabState,
    out: &mut Emit,
    ctl: &mut Control,
    warnings: &mut Vec<Diagnostic>,
    opts: &InterpOptions,
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
        b'G' => match value_of(f)? {
            94 => {
                st.feed_mode = FeedMode::UnitsPerMinute;
                out.push(Canon::SetFeedMode {
                    mode: FeedMode::UnitsPerMinute,
                });
            }
            95 => {
                st.feed_mode = FeedMode::UnitsPerRevolution;
                out.push(Canon::SetFeedMode {
                    mode: FeedMode::UnitsPerRevolution,
                });
            }
            g @ (2 | 3 | 12 | 13) => {
                return Err(Diagnostic::error(
                    "nc31::group-expected",
                    format!("G{g} starts an arc group: G{g}*, X*, Z*, … (spec §2.6)"),
                    f.span,
                ))
            }
            g @ (25 | 31 | 32 | 33 | 77 | 78) => return Err(unsupported(&format!("G{g}"), f.span)),
            g => {
                return Err(Diagnostic::error(
                    "nc31::unknown-g",
                    format!("G{g} is not an NC-31 function of the lab document"),
                    f.span,
                ))
            }
        },
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
            let m = value_of(f)?;
            match m {
                3 | 4 => {
                    let direction = if m == 3 {
                        SpindleDirection::Clockwise
                    } else {
                        SpindleDirection::CounterClockwise
                    };
                    st.spindle = Some(direction);
                    out.push(Canon::StartSpindle {
                        spindle: 0,
                        direction,
                    });
                }
                5 => {
                    st.spindle = None;
                    out.push(Canon::StopSpindle { spindle: 0 });
                }
                0 => out.push(Canon::ProgramStop { optional: false }),
                17 => *ctl = Control::Return(f.span),
                30 | 2 => {
                    st.spindle = None;
                    out.push(Canon::ProgramEnd);
                    *ctl = Control::End;
                }
                m => {
                    if (38..=41).contains(&m) {
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
            out.push(Canon::ChangeTool { tool: t as u32 });
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

/// The target of an axis value: X in diameter units → radius, Z in 0.01 mm.
fn axis_target(axis: usize, v: i64, incremental: bool, current: f64) -> f64 {
    let mm = v as f64 * if axis == 0 { X_MM } else { Z_MM };
    if incremental {
        current + mm
    } else {
        mm
    }
}

/// `X* Z [F]`, `Z* X [F]`, `X* F`, `Z* F`.
fn line_group(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(), Diagnostic> {
    // A flag on the group's first frame covers the group (spec §2.5.3 recommendation).
    let group_incremental = frames[0].body.incremental;
    let mut end = st.position;
    let mut seen = [false; 3];
    let mut rapid = false;
    let mut feed = None;
    for (k, f) in frames.iter().enumerate() {
        let b = &f.body;
        match b.address {
            b'X' | b'Z' if feed.is_none() => {
                let axis = if b.address == b'X' { 0 } else { 2 };
                if seen[axis] {
                    return Err(Diagnostic::error(
                        "nc31::bad-group",
                        "an axis twice in one group",
                        f.span,
                    ));
                }
                seen[axis] = true;
                let v = value_of(f)?;
                rapid |= b.rapid;
                let t = axis_target(
                    axis,
                    v,
                    group_incremental || b.incremental,
                    get(&st.position, axis),
                );
                set(&mut end, axis, t);
            }
            b'F' if k == frames.len() - 1 && k > 0 => {
                let v = value_of(f)? as f64;
                if v <= 0.0 {
                    return Err(Diagnostic::error(
                        "nc31::bad-feed",
                        "F must be positive",
                        f.span,
                    ));
                }
                feed = Some(v * 0.01);
            }
            _ => {
                return Err(Diagnostic::error(
                    "nc31::bad-group",
                    "a line group is X* Z [F] (or Z* X [F], X* F, Z* F)",
                    f.span,
                ))
            }
        }
    }
    if rapid {
        traverse(st, out, end);
    } else {
        // The group's own F holds only inside the group (§2.7).
        let f = st.path_feed(feed.unwrap_or(st.feed), out.span, warnings);
        feed_line(st, out, end, f);
    }
    Ok(())
}

/// Checks the group's frame addresses against the expected order; returns the optional last F.
fn expect_frames(frames: &[Frame], order: &[u8], what: &str) -> Result<Option<f64>, Diagnostic> {
    let n = order.len();
    let ok_len = frames.len() == n || frames.len() == n + 1;
    let bad = |at: Span| {
        Diagnostic::error(
            "nc31::bad-group",
            format!("{what}: the frames must come in the order {}", {
                let mut s: Vec<String> = order.iter().map(|c| (*c as char).to_string()).collect();
                s.push("[F]".into());
                s.join(", ")
            }),
            at,
        )
    };
    if !ok_len {
        return Err(bad(group_span(frames)));
    }
    for (f, &a) in frames.iter().zip(order) {
        if f.body.address != a || f.body.chamfer.is_some() {
            return Err(bad(f.span));
        }
        value_of(f)?;
    }
    match frames.get(n) {
        Some(f) if f.body.address == b'F' => {
            let v = value_of(f)? as f64;
            if v <= 0.0 {
                return Err(Diagnostic::error(
                    "nc31::bad-feed",
                    "F must be positive",
                    f.span,
                ));
            }
            Ok(Some(v * 0.01))
        }
        Some(f) => Err(bad(f.span)),
        None => Ok(None),
    }
}

/// The end point of an arc or rounding group in (radius, Z) mm.
fn group_end(frames: &[Frame], st: &LabState) -> (f64, f64) {
    let inc = frames[0].body.incremental;
    let x = &frames[1].body;
    let z = &frames[2].body;
    let r = axis_target(0, x.value.unwrap_or(0), inc || x.incremental, st.position.x);
    let zz = axis_target(2, z.value.unwrap_or(0), inc || z.incremental, st.position.z);
    (r, zz)
}

/// `G2*/G3* X* Z* P* P [F]` (spec §2.6.1): centre = start − (P4 on the radius, P5).
fn arc_group(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    warnings: &mut Vec<Diagnostic>,
    opts: &InterpOptions,
) -> Result<(), Diagnostic> {
    let feed = expect_frames(frames, b"GXZPP", "an arc group")?;
    let g2 = frames[0].body.value == Some(2);
    let (er, ez) = group_end(frames, st);
    let (sr, sz) = (st.position.x, st.position.z);
    let pr = frames[3].body.value.unwrap_or(0) as f64 * Z_MM;
    let pz = frames[4].body.value.unwrap_or(0) as f64 * Z_MM;
    let (cr, cz) = (sr - pr, sz - pz);
    let r_start = pr.hypot(pz);
    let r_end = (er - cr).hypot(ez - cz);
    if (r_start - r_end).abs() > opts.arc_tolerance_mm || r_start <= 0.0 {
        return Err(Diagnostic::error(
            "nc31::arc-radius",
            "the arc's end point is not on its circle",
            out.span,
        )
        .with_note(format!(
            "radius at the start {r_start:.4} mm, at the end {r_end:.4} mm (tolerance {} mm)",
            opts.arc_tolerance_mm
        )));
    }
    let sweep = sweep_deg(g2, (cr, cz), (sr, sz), (er, ez));
    // The document restricts one group to arcs of less than 90° ([decide]: enforced, with the
    // rounding groups G12/G13 for quarters).
    if sweep > 90.0 + 1e-6 {
        return Err(Diagnostic::error(
            "nc31::arc-too-long",
            format!("an arc group turns less than 90°, this one {sweep:.3}°"),
            out.span,
        )
        .with_note("split the arc, or use G12/G13 for a quarter circle"));
    }
    let f = st.path_feed(feed.unwrap_or(st.feed), out.span, warnings);
    arc(st, out, g2, (er, ez), (cr, cz), f);
    Ok(())
}

/// `G12*/G13* X* Z* [F]` (spec §2.6.2): a quarter circle tangent to both axes; |Δr| = |ΔZ| = R,
/// centre (r_S, z_E) or (r_E, z_S), whichever turns 90° in the commanded sense.
fn rounding_group(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    warnings: &mut Vec<Diagnostic>,
    opts: &InterpOptions,
) -> Result<(), Diagnostic> {
    let feed = expect_frames(frames, b"GXZ", "a rounding group")?;
    let g12 = frames[0].body.value == Some(12);
    let (er, ez) = group_end(frames, st);
    let (sr, sz) = (st.position.x, st.position.z);
    let (dr, dz) = (er - sr, ez - sz);
    // [decide] |Δr| ≠ |ΔZ| is refused: the CNC computes the radius from a quarter circle.
    if (dr.abs() - dz.abs()).abs() > opts.arc_tolerance_mm || dr.abs() < 1e-9 {
        return Err(Diagnostic::error(
            "nc31::rounding-not-quarter",
            "a rounding needs equal radial and axial travel",
            out.span,
        )
        .with_note(format!("Δr = {dr:.3} mm, ΔZ = {dz:.3} mm")));
    }
    let centre = [(sr, ez), (er, sz)]
        .into_iter()
        .find(|&c| (sweep_deg(g12, c, (sr, sz), (er, ez)) - 90.0).abs() < 1e-3)
        .unwrap_or((sr, ez));
    let f = st.path_feed(feed.unwrap_or(st.feed), out.span, warnings);
    arc(st, out, g12, (er, ez), centre, f);
    Ok(())
}

/// Sweep in degrees from s to e about c, counter-clockwise in the Z-right/X-up view when `ccw`.
/// Points are (r, z).
fn sweep_deg(ccw: bool, c: (f64, f64), s: (f64, f64), e: (f64, f64)) -> f64 {
    // Plane coordinates (Z, X): CCW from +Z towards +X.
    let a = stanok_geom::ccw_sweep([c.1, c.0], [s.1, s.0], [e.1, e.0], 1e-9).to_degrees();
    if ccw {
        a
    } else {
        (360.0 - a) % 360.0
    }
}

fn get(p: &Pose, axis: usize) -> f64 {
    p.to_array()[axis]
}

fn set(p: &mut Pose, axis: usize, v: f64) {
    let mut a = p.to_array();
    a[axis] = v;
    *p = Pose::from_array(a);
}

fn traverse(st: &mut LabState, out: &mut Emit, end: Pose) {
    out.push(Canon::StraightTraverse(LineMove {
        start: st.position,
        end,
        feed: 0.0,
    }));
    st.position = end;
}

fn feed_line(st: &mut LabState, out: &mut Emit, end: Pose, feed: f64) {
    out.push(Canon::StraightFeed(LineMove {
        start: st.position,
        end,
        feed,
    }));
    st.position = end;
}

/// An arc in the ZX plane; `ccw` about +Y (Z towards X).
fn arc(st: &mut LabState, out: &mut Emit, ccw: bool, e: (f64, f64), c: (f64, f64), feed: f64) {
    let mut end = st.position;
    end.x = e.0;
    end.z = e.1;
    out.push(Canon::ArcFeed(ArcMove {
        start: st.position,
        end,
        centre: [c.0, st.position.y, c.1],
        axis: [0.0, if ccw { 1.0 } else { -1.0 }, 0.0],
        turns: 1,
        plane: Plane::ZX,
        feed,
    }));
    st.position = end;
}
