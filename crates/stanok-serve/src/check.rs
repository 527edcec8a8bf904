//! Checking a program for the editor and previewing it for the view, as the control would before
//! the start — without the machine thread, in one pass of the interpreter (check mode: every error
//! is listed) from where the machine stands, with its stored data:
//!
//! * **Diagnostics**: every error and warning (as `stanok check`), each once.
//! * **Travel** (`stanok_machine::TravelCheck`, as the run and `stanok check` apply it): every move
//!   up to the first error is checked against the axes' limits with the offsets and tool lengths in
//!   force (Canon positions are machine positions), joints on 5-axis machines under
//!   tool-centre-point control. Each violation is an error at its block (so the program does not
//!   start) and a marker at its end point in the view.
//! * **Path** (preview only): the moves up to the first error — a program with an error previews
//!   up to it — simplified to the page's point budget (`lod.rs`); on a lathe also the programmed
//!   contour (the program run with every tool radius 0) when compensation changes the path; on a
//!   5-axis machine ticks along the tool axis under tool-centre-point control.
//! * **Time** (preview only): the planned cycle time from a simulated machine with the travel
//!   limits lifted (so that it plans past a violation), unpaced, 4 ms servo period. Planning is the
//!   costly part: when it passes its budget ([`PreviewLimits::planning`]) the simulated machine is
//!   dropped and the rest is extrapolated from the nominal time (length / feed) at the ratio of
//!   planned to nominal time so far (`time_estimate = "extrapolated"`).
//!
//! Everything runs inside a job (`jobs.rs`): the interpreter reads through a `CancelReader`, the
//! simulated machine's sink looks at the same flag, so a cancelled check ends at once.

use crate::executing::Snapshot;
use crate::jobs::{Cancel, CancelReader, MAX_WARNINGS};
use crate::lod::{LodPath, PathLod, DEFAULT_BUDGET};
use crate::machine::{interp_options, Alarm, MachineContext};
use crate::state::{g_vector_of, m_vector, MachineState};
use serde::Serialize;
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_geom::{Helix, Nurbs};
use stanok_interp::Interpreter;
use stanok_kin::Kinematics;
use stanok_machine::{MachineData, SimMachine, SimOptions, TravelCheck};
use stanok_motion::nominal::{self, AxisLimits};
use stanok_syntax::Dialect;
use std::cell::Cell;
use std::collections::HashSet;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The longest line the panel hands to the interpreter, bytes. The parser and the expression
/// evaluator recurse per term of a chain (`1+1+…`): a debug build takes about 5 KB of stack per
/// term, so this bounds the depth well within a job's stack (`jobs::JOB_STACK_BYTES`) whatever the
/// build. LinuxCNC's own limit is 256 characters; no real program comes near.
pub const MAX_LINE_BYTES: usize = 32 * 1024;

/// The first line longer than [`MAX_LINE_BYTES`], as an error (the text is then not interpreted).
pub fn long_line(text: &str) -> Option<Alarm> {
    for (n, line) in text.split('\n').enumerate() {
        if line.len() > MAX_LINE_BYTES {
            return Some(Alarm {
                line: n as u32 + 1,
                column: 1,
                severity: "error".into(),
                code: "serve::line-too-long".into(),
                message: format!(
                    "line {} has {} bytes; the panel reads lines of at most {MAX_LINE_BYTES} bytes",
                    n + 1,
                    line.len()
                ),
            });
        }
    }
    None
}

/// At most this many travel violations are listed (each is also an error diagnostic).
pub const MAX_VIOLATIONS: usize = 1000;

/// At most this many tool-axis ticks are drawn.
pub const MAX_TICKS: usize = 4000;

/// Length of a tool-axis tick, mm.
pub const TICK_MM: f64 = 10.0;

/// Limits of one preview.
#[derive(Debug, Clone, Copy)]
pub struct PreviewLimits {
    /// Points sent to the page.
    pub points: usize,
    /// Wall time spent planning before the rest is extrapolated.
    pub planning: Duration,
}

impl Default for PreviewLimits {
    fn default() -> Self {
        PreviewLimits {
            points: DEFAULT_BUDGET,
            planning: Duration::from_secs(15),
        }
    }
}

/// A travel violation, for the view.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Violation {
    /// 1-based line.
    pub line: u32,
    /// 1-based column.
    pub column: u32,
    /// What is exceeded.
    pub message: String,
    /// End point of the offending move, machine X Y Z.
    pub at: [f64; 3],
}

/// The preview of the module doc.
#[derive(Debug, Clone, Serialize)]
pub struct Preview {
    /// The tool-centre path, simplified.
    pub path: LodPath,
    /// Lathe: the programmed contour (tool radii 0), when it differs from `path`.
    pub programmed: Option<LodPath>,
    /// Show it in the lathe view (Z right, X up).
    pub lathe: bool,
    /// Travel violations.
    pub violations: Vec<Violation>,
    /// Tool-axis ticks (5-axis, under tool-centre-point control): tip, tip + 10 mm · axis.
    pub tool_axis: Vec<[[f32; 3]; 2]>,
    /// Cycle time, s (up to the first error).
    pub cycle_time_s: f64,
    /// `planned` or `extrapolated` (module doc).
    pub time_estimate: &'static str,
    /// Where a run ends (up to the first error), machine coordinates.
    pub final_position: [f64; 9],
    /// The first error, where the preview ends.
    pub ends_at_error: Option<Alarm>,
    /// The program's state at its start (the DRO after a load).
    pub start: Option<Snapshot>,
    /// Blocks executed up to the end of the preview.
    pub blocks: u64,
}

/// Diagnostics, and the preview if asked for.
#[derive(Debug, Clone, Default)]
pub struct Examined {
    /// Errors and warnings in line order.
    pub diagnostics: Vec<Alarm>,
    /// The preview.
    pub preview: Option<Preview>,
}

/// What to examine.
pub struct Subject<'a> {
    /// Program text.
    pub text: Arc<str>,
    /// Its dialect.
    pub dialect: Dialect,
    /// The machine.
    pub machine: &'a MachineData,
    /// Subroutine directories.
    pub subroutine_path: &'a [PathBuf],
    /// Where the machine stands and what it stores.
    pub at: &'a MachineContext,
}

/// Diagnostics only (the editor's check as you type).
pub fn check(subject: &Subject, cancel: &Cancel) -> Vec<Alarm> {
    examine(subject, cancel, None).diagnostics
}

/// True if the program is shown in the lathe view: a machine without Y, or a lathe dialect.
pub fn lathe_view(machine: &MachineData, dialect: Dialect) -> bool {
    !machine.axes.iter().any(|a| a.name == 'Y') || matches!(dialect, Dialect::Nc31 | Dialect::P2p32)
}

/// The machine with its travel lifted (the planner of the preview plans past a violation).
fn without_travel(machine: &MachineData) -> MachineData {
    let mut m = machine.clone();
    for a in &mut m.axes {
        a.min = f64::NEG_INFINITY;
        a.max = f64::INFINITY;
    }
    m
}

/// The unwinding payload of a planning budget that ran out.
struct PlanningOver;

/// The simulated machine of the preview, with the sink that watches the budget.
struct Planner {
    sim: SimMachine,
    last_t: Rc<Cell<f64>>,
}

fn planner(machine: &MachineData, cancel: &Cancel, deadline: Instant) -> Planner {
    let options = SimOptions {
        lookahead: crate::machine::SERVE_LOOKAHEAD,
        servo_period_s: 0.004,
        // The preview has its own wall-time budget and extrapolates past it (module doc): the
        // simulated-time bound of a run would only cut the estimate short.
        max_machine_time_s: f64::INFINITY,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(without_travel(machine), options);
    let last_t = Rc::new(Cell::new(0.0));
    let (cancel, t) = (cancel.clone(), last_t.clone());
    let mut count = 0u32;
    sim.set_setpoint_sink(Box::new(move |sp| {
        t.set(sp.t);
        count = count.wrapping_add(1);
        if count.is_multiple_of(1024) {
            cancel.check();
            if Instant::now() > deadline {
                resume_unwind(Box::new(PlanningOver));
            }
        }
    }));
    Planner { sim, last_t }
}

/// Nominal time of a command (length / feed, rapids at the rapid rate), s.
fn nominal_time(cmd: &Canon, machine: &MachineData, limits: &[AxisLimits]) -> f64 {
    let length = |s: &Pose, e: &Pose| {
        let (s, e) = (s.to_array(), e.to_array());
        let len = |r: std::ops::Range<usize>| r.map(|i| (e[i] - s[i]).powi(2)).sum::<f64>().sqrt();
        let (xyz, uvw, abc) = (len(0..3), len(6..9), len(3..6));
        if xyz > 0.0 {
            xyz
        } else if uvw > 0.0 {
            uvw
        } else {
            abc
        }
    };
    let feed = |f: f64| f.min(machine.max_feed);
    match cmd {
        Canon::StraightTraverse(m) => {
            let (s, e) = (m.start.to_array(), m.end.to_array());
            let deltas: Vec<f64> = s.iter().zip(&e).map(|(a, b)| b - a).collect();
            nominal::rapid_time(
                length(&m.start, &m.end),
                &deltas,
                machine.rapid_rate,
                limits,
            )
        }
        Canon::StraightFeed(m) => nominal::feed_time(length(&m.start, &m.end), feed(m.feed)),
        Canon::ArcFeed(a) => {
            let h = Helix {
                start: a.start.xyz(),
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
                turns: a.turns,
            };
            nominal::feed_time(h.length(), feed(a.feed))
        }
        Canon::SplineFeed(s) => nominal::feed_time(
            Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots).length(),
            feed(s.feed),
        ),
        Canon::Dwell { seconds } => nominal::dwell_time(*seconds),
        _ => 0.0,
    }
}

/// The points of a motion command for the view: (rapid, start, points after the start).
fn motion_points(cmd: &Canon, out: &mut Vec<[f64; 3]>) -> Option<(bool, [f64; 3])> {
    out.clear();
    match cmd {
        Canon::StraightTraverse(m) => {
            out.push(m.end.xyz());
            Some((true, m.start.xyz()))
        }
        Canon::StraightFeed(m) => {
            out.push(m.end.xyz());
            Some((false, m.start.xyz()))
        }
        Canon::StraightProbe {
            motion, contact, ..
        } => {
            out.push(motion.stopped_at(contact.as_deref().copied()).end.xyz());
            Some((false, motion.start.xyz()))
        }
        Canon::ArcFeed(a) => {
            let h = Helix {
                start: a.start.xyz(),
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
                turns: a.turns,
            };
            h.tessellate(0.01, out);
            Some((false, a.start.xyz()))
        }
        Canon::SplineFeed(s) => {
            Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots).tessellate(0.01, out);
            Some((false, s.start.xyz()))
        }
        other => other.motion().map(|m| {
            out.push(m.end().xyz());
            (false, m.start().xyz())
        }),
    }
}

/// Diagnostics in line order, each once; warnings capped.
struct Diagnostics {
    errors: Vec<Alarm>,
    seen: HashSet<(String, u64, u64, String)>,
}

impl Diagnostics {
    fn add(&mut self, d: &Diagnostic) {
        let key = (
            d.code.to_string(),
            d.span.start,
            d.span.end,
            d.message.clone(),
        );
        if self.seen.insert(key) {
            self.errors.push(Alarm::of(d));
        }
    }
}

/// The check and, with `limits`, the preview of the module doc.
pub fn examine(subject: &Subject, cancel: &Cancel, limits: Option<PreviewLimits>) -> Examined {
    if let Some(alarm) = long_line(&subject.text) {
        return Examined {
            diagnostics: vec![alarm],
            preview: None,
        };
    }
    let machine = subject.machine;
    let mut opts = interp_options(
        machine,
        subject.dialect,
        subject.subroutine_path,
        subject.at,
    );
    opts.continue_after_error = true;
    let mut interp = Interpreter::new(
        CancelReader::new(subject.text.clone(), cancel.clone()),
        opts,
    );
    let mut diagnostics = Diagnostics {
        errors: Vec::new(),
        seen: HashSet::new(),
    };
    let mut travel = TravelCheck::new(machine);
    let want = limits.is_some();
    let limits = limits.unwrap_or_default();
    let deadline = Instant::now() + limits.planning;
    let mut plan = want.then(|| planner(machine, cancel, deadline));
    let axis_limits: Vec<AxisLimits> = (0..9)
        .map(|i| AxisLimits {
            max_velocity_per_min: machine
                .axes
                .iter()
                .find(|a| a.pose_index() == i)
                .map_or(0.0, |a| a.max_velocity),
        })
        .collect();
    let (mut nominal_total, mut nominal_planned) = (0.0, 0.0);
    // Once planning stopped: (planned time, planned / nominal ratio, nominal time before).
    let mut extrapolation: Option<(f64, f64, f64)> = None;
    let mut lod = PathLod::new(limits.points);
    let mut violations = Vec::new();
    let mut ticks: Vec<[[f32; 3]; 2]> = Vec::new();
    let mut tick_stride = 1u64;
    let mut tick_count = 0u64;
    let kinematics = machine.five_axis();
    let mut first_error: Option<Diagnostic> = None;
    let mut start: Option<Snapshot> = None;
    let mut final_position = subject.at.position;
    let mut pts = Vec::new();
    // Not `for … in interp.by_ref()`: the loop body reads the interpreter's state.
    #[allow(clippy::while_let_on_iterator)]
    while let Some(item) = interp.next() {
        let cmd = match item {
            Ok(cmd) => cmd,
            Err(d) => {
                diagnostics.add(&d);
                if first_error.is_none() {
                    first_error = Some(d);
                }
                continue;
            }
        };
        if first_error.is_some() {
            continue;
        }
        if let Err(v) = travel.check(&cmd) {
            diagnostics.add(&v);
            if violations.len() < MAX_VIOLATIONS {
                let at = cmd
                    .value
                    .motion()
                    .map_or(final_position, |m| m.end().to_array());
                violations.push(Violation {
                    line: v.span.line,
                    column: v.span.column,
                    message: v.message.clone(),
                    at: [at[0], at[1], at[2]],
                });
            }
        }
        if !want {
            continue;
        }
        if start.is_none() {
            let mut state = MachineState::default();
            state.apply(&cmd.value);
            start = Some(Snapshot {
                line: 0,
                g_codes: g_vector_of(&interp, subject.dialect),
                m_codes: m_vector(&interp, &state, subject.dialect),
                edge: interp.axioma_modes().map_or(0, |m| m.edge),
                message: None,
                state,
            });
        }
        if let Some(m) = cmd.value.motion() {
            final_position = m.end().to_array();
        }
        if let Some((rapid, from)) = motion_points(&cmd.value, &mut pts) {
            lod.push(rapid, cmd.span.line, from, &pts);
            if let (Some(kin), Some(_)) = (&kinematics, travel.tcp()) {
                add_ticks(
                    &cmd.value,
                    kin,
                    &mut ticks,
                    &mut tick_stride,
                    &mut tick_count,
                );
            }
        }
        let t = nominal_time(&cmd.value, machine, &axis_limits);
        nominal_total += t;
        if let Some(p) = plan.as_mut() {
            match catch_unwind(AssertUnwindSafe(|| p.sim.apply(&cmd))) {
                Ok(_) => nominal_planned += t,
                Err(payload) if payload.is::<PlanningOver>() => {
                    // Keep the planned time so far; the rest at the ratio seen (module doc).
                    let done = p.last_t.get();
                    extrapolation = Some((done, ratio(done, nominal_planned), nominal_total - t));
                    plan = None;
                }
                Err(payload) => resume_unwind(payload),
            }
        }
    }
    let blocks = interp.stats().blocks_executed;
    for w in interp.take_warnings().iter().take(MAX_WARNINGS) {
        diagnostics.add(w);
    }
    let mut all = diagnostics.errors;
    all.sort_by_key(|a| (a.line, a.column));
    if !want {
        return Examined {
            diagnostics: all,
            preview: None,
        };
    }
    let cycle_time_s = match plan.as_mut() {
        Some(p) => match catch_unwind(AssertUnwindSafe(|| p.sim.finish())) {
            Ok(report) => report.cycle_time_s,
            Err(payload) if payload.is::<PlanningOver>() => {
                let done = p.last_t.get();
                extrapolation = Some((done, ratio(done, nominal_planned), nominal_total));
                done.max(nominal_total * ratio(done, nominal_planned))
            }
            Err(payload) => resume_unwind(payload),
        },
        None => match extrapolation {
            Some((done, ratio, before)) => done + (nominal_total - before).max(0.0) * ratio,
            None => 0.0,
        },
    };
    let lathe = lathe_view(machine, subject.dialect);
    let path = lod.finish();
    let programmed = if lathe {
        programmed_contour(subject, cancel, limits.points, &path)
    } else {
        None
    };
    Examined {
        diagnostics: all,
        preview: Some(Preview {
            path,
            programmed,
            lathe,
            violations,
            tool_axis: ticks,
            cycle_time_s,
            time_estimate: if extrapolation.is_some() {
                "extrapolated"
            } else {
                "planned"
            },
            final_position,
            ends_at_error: first_error.as_ref().map(Alarm::of),
            start,
            blocks,
        }),
    }
}

/// Planned time per nominal time (at least 1: acceleration only adds time).
fn ratio(planned: f64, nominal: f64) -> f64 {
    if nominal > 0.0 {
        (planned / nominal).max(1.0)
    } else {
        1.0
    }
}

/// Tool-axis ticks of a straight move under tool-centre-point control: at its start, middle and
/// end, every `stride`-th move; the stride doubles when the ticks reach [`MAX_TICKS`].
fn add_ticks(
    cmd: &Canon,
    kin: &stanok_kin::FiveAxis,
    ticks: &mut Vec<[[f32; 3]; 2]>,
    stride: &mut u64,
    count: &mut u64,
) {
    let (Canon::StraightFeed(m) | Canon::StraightTraverse(m)) = cmd else {
        return;
    };
    *count += 1;
    if !(*count).is_multiple_of(*stride) {
        return;
    }
    let (s, e) = (m.start.to_array(), m.end.to_array());
    for f in [0.0, 0.5, 1.0] {
        let p = Pose::from_array(std::array::from_fn(|i| s[i] + (e[i] - s[i]) * f));
        let t = kin.tool_vector(&p);
        let tip = p.xyz();
        let top: [f64; 3] = std::array::from_fn(|i| tip[i] + TICK_MM * t[i]);
        ticks.push([tip.map(|v| v as f32), top.map(|v| v as f32)]);
    }
    if ticks.len() >= MAX_TICKS {
        let kept: Vec<_> = ticks.chunks(3).step_by(2).flatten().copied().collect();
        *ticks = kept;
        *stride *= 2;
    }
}

/// The programmed contour of a lathe program under tool nose radius compensation: the program run
/// with every tool radius 0 (as `stanok plot` draws it). None when it is the same path.
fn programmed_contour(
    subject: &Subject,
    cancel: &Cancel,
    budget: usize,
    compensated: &LodPath,
) -> Option<LodPath> {
    let mut zero = subject.at.clone();
    for tool in zero.control.tools.tools.values_mut() {
        for edge in &mut tool.edges {
            edge.radius = 0.0;
            edge.radius_wear = 0.0;
        }
    }
    let opts = interp_options(
        subject.machine,
        subject.dialect,
        subject.subroutine_path,
        &zero,
    );
    let interp = Interpreter::new(
        CancelReader::new(subject.text.clone(), cancel.clone()),
        opts,
    );
    let mut lod = PathLod::new(budget);
    let mut pts = Vec::new();
    for item in interp {
        let Ok(cmd) = item else { break };
        if let Some((rapid, from)) = motion_points(&cmd.value, &mut pts) {
            lod.push(rapid, cmd.span.line, from, &pts);
        }
    }
    let path = lod.finish();
    (path.pieces != compensated.pieces).then_some(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn subject<'a>(
        text: &str,
        dialect: Dialect,
        machine: &'a MachineData,
        at: &'a MachineContext,
    ) -> Subject<'a> {
        Subject {
            text: text.into(),
            dialect,
            machine,
            subroutine_path: &[],
            at,
        }
    }

    fn origin(machine: &MachineData) -> MachineContext {
        MachineContext {
            position: [0.0; 9],
            control: machine.control.clone(),
            homed: [false; 9],
        }
    }

    #[test]
    fn a_bad_block_in_a_loop_is_listed_once() {
        let m = MachineData::default_mill();
        let at = origin(&m);
        let text = "for (int i = 0; i < 3; i++) {\nG01 X=i*zz F100\n}\nM30\n";
        let alarms = check(&subject(text, Dialect::Axioma, &m, &at), &Cancel::new());
        let found: Vec<(u32, u32, &str)> = alarms
            .iter()
            .map(|a| (a.line, a.column, a.code.as_str()))
            .collect();
        assert_eq!(found, [(2, 9, "hll::undeclared")]);
    }

    #[test]
    fn travel_violations_are_errors_at_their_blocks_with_the_offsets_in_force() {
        let m = MachineData::default_mill();
        let at = origin(&m);
        // X travel ±500: G0 X600 is beyond; with G10 L2 P1 X-200, X450 reaches machine 250.
        let text = "G21 G90\nG0 X600\nG10 L2 P1 X-200\nG54 G0 X450\nG0 X710\nM2\n";
        let e = examine(
            &subject(text, Dialect::Rs274ngc, &m, &at),
            &Cancel::new(),
            Some(PreviewLimits::default()),
        );
        let lines: Vec<(u32, &str)> = e
            .diagnostics
            .iter()
            .map(|a| (a.line, a.code.as_str()))
            .collect();
        assert_eq!(
            lines,
            [(2, "machine::travel-limit"), (5, "machine::travel-limit")]
        );
        let p = e.preview.unwrap();
        assert_eq!(p.violations.len(), 2);
        assert_eq!(p.violations[0].at, [600.0, 0.0, 0.0]);
        assert_eq!(p.violations[1].at, [510.0, 0.0, 0.0]);
        assert!(p.violations[1].message.contains("maximum 500"));
        // The path goes on past the violations (it is a preview, not a run).
        assert_eq!(p.final_position[0], 510.0);
        assert!(p.ends_at_error.is_none());
    }

    #[test]
    fn a_program_with_an_error_previews_up_to_it() {
        let m = MachineData::default_mill();
        let at = origin(&m);
        let text = "G21 G90\nG0 X10\nG1 X20 F100\nG1 X30 Q\nG0 X40\nM2\n";
        let e = examine(
            &subject(text, Dialect::Rs274ngc, &m, &at),
            &Cancel::new(),
            Some(PreviewLimits::default()),
        );
        assert_eq!(e.diagnostics[0].line, 4);
        let p = e.preview.unwrap();
        assert_eq!(p.ends_at_error.unwrap().line, 4);
        assert_eq!(p.final_position[0], 20.0);
        let last = p.path.pieces.last().unwrap();
        assert_eq!(last.points[last.points.len() - 3], 20.0);
        // 10 mm at 100 mm/min = 6 s plus the rapid.
        assert!(
            p.cycle_time_s > 6.0 && p.cycle_time_s < 7.0,
            "{}",
            p.cycle_time_s
        );
    }

    #[test]
    fn a_runaway_feed_is_extrapolated_when_planning_passes_its_budget() {
        let m = MachineData::default_mill();
        let at = origin(&m);
        let text = "G21 G90\nG1 X100 F0.0000001\nM2\n";
        let t0 = Instant::now();
        let e = examine(
            &subject(text, Dialect::Rs274ngc, &m, &at),
            &Cancel::new(),
            Some(PreviewLimits {
                points: 1000,
                planning: Duration::from_millis(300),
            }),
        );
        assert!(t0.elapsed() < Duration::from_secs(5));
        let p = e.preview.unwrap();
        assert_eq!(p.time_estimate, "extrapolated");
        // 100 mm at 1e-7 mm/min: 6e10 s.
        assert!(
            p.cycle_time_s > 5.9e10 && p.cycle_time_s < 6.1e10,
            "{}",
            p.cycle_time_s
        );
    }

    #[test]
    fn the_start_snapshot_is_the_programs_power_on_state_where_the_machine_stands() {
        let m = MachineData::default_mill();
        let mut at = origin(&m);
        at.position[0] = 12.0;
        let e = examine(
            &subject("G21 G91\nG0 X5\nM2\n", Dialect::Rs274ngc, &m, &at),
            &Cancel::new(),
            Some(PreviewLimits::default()),
        );
        let p = e.preview.unwrap();
        let start = p.start.unwrap();
        assert_eq!(start.state.position[0], 12.0);
        assert!(
            start.g_codes.iter().any(|c| c.code == "G90"),
            "{:?}",
            start.g_codes
        );
        assert_eq!(p.final_position[0], 17.0);
    }
}
