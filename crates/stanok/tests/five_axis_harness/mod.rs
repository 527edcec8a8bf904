//! Runs a 5-axis fixture through the whole pipeline (interpreter → simulated machine with the
//! kin stage → servo setpoints) and keeps what the assertions need: the machine axes of every
//! setpoint by source line, the Canon stream, the run report and the error that stopped the run.
#![allow(dead_code)]

use stanok_canon::setup::ControlData;
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_machine::{MachineData, RunReport, SimMachine, SimOptions};
use stanok_syntax::Dialect;
use std::cell::RefCell;
use std::rc::Rc;

/// One setpoint: source line, time, machine axes.
#[derive(Debug, Clone, Copy)]
pub struct Sp {
    pub line: u32,
    pub t: f64,
    pub joints: [f64; 9],
}

pub struct Run {
    pub text: String,
    pub canon: Vec<Canon>,
    /// Source line of each command of `canon`.
    pub lines: Vec<u32>,
    pub setpoints: Vec<Sp>,
    pub report: RunReport,
    pub error: Option<Diagnostic>,
    pub machine: MachineData,
}

/// A corpus file's text.
pub fn corpus_text(path: &str) -> String {
    let p = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/corpus/").to_string() + path;
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{p}: {e}"))
}

/// Runs `text` in `dialect` on built-in machine `machine` with the given stored data, starting
/// with the machine axes at `start`.
pub fn run(text: &str, dialect: Dialect, machine: &str, control: ControlData, start: Pose) -> Run {
    let mut machine = MachineData::builtin(machine).expect("built-in machine");
    machine.control = control;
    run_on(text, dialect, machine, start)
}

/// Runs `text` on the given machine data.
pub fn run_on(text: &str, dialect: Dialect, machine: MachineData, start: Pose) -> Run {
    let mut opts = InterpOptions::new(dialect);
    opts.axes = machine.axis_mask();
    opts.control = machine.control.clone();
    opts.five_axis = machine.five_axis();
    opts.ttpc_workpiece_frame = machine
        .kinematics
        .as_ref()
        .is_some_and(|k| k.ttpc_frame == stanok_kin::TtpcFrame::Workpiece);
    opts.mazatrol = stanok_serve::machine::mazatrol_params(&machine);
    opts.initial_position = start;
    let options = SimOptions {
        servo_period_s: 2e-3,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(machine.clone(), options);
    let trace: Rc<RefCell<Vec<Sp>>> = Rc::default();
    let sink = trace.clone();
    sim.set_setpoint_sink(Box::new(move |sp| {
        sink.borrow_mut().push(Sp {
            line: sp.line,
            t: sp.t,
            joints: sp.position,
        })
    }));
    let mut canon = Vec::new();
    let mut lines = Vec::new();
    let mut error = None;
    for item in Interpreter::from_text(text, opts) {
        match item {
            Ok(c) => {
                if let Err(d) = sim.apply(&c) {
                    error = Some(d);
                    break;
                }
                lines.push(c.span.line);
                canon.push(c.value);
            }
            Err(d) => {
                error = Some(d);
                break;
            }
        }
    }
    let report = sim.finish();
    let setpoints = trace.borrow().clone();
    Run {
        text: text.to_string(),
        canon,
        lines,
        setpoints,
        report,
        error,
        machine,
    }
}

impl Run {
    /// The source line (1-based) of the block starting with `n` ("N40"); the first one.
    pub fn line_of(&self, n: &str) -> u32 {
        self.text
            .lines()
            .position(|l| {
                l.trim_start()
                    .strip_prefix(n)
                    .is_some_and(|rest| !rest.starts_with(|c: char| c.is_ascii_digit()))
            })
            .unwrap_or_else(|| panic!("no block {n}")) as u32
            + 1
    }

    /// The setpoints of block `n`.
    pub fn block(&self, n: &str) -> Vec<Sp> {
        let line = self.line_of(n);
        self.setpoints
            .iter()
            .filter(|s| s.line == line)
            .copied()
            .collect()
    }

    /// Machine axes at the end of block `n`: the kin stage's inverse kinematics of the end pose
    /// of its last motion command (exact; the servo grid rarely falls on a block end). Under TCP
    /// (exact stop) the last setpoint of the block must be within 0.01 mm/deg of it.
    pub fn end_of(&self, n: &str) -> [f64; 9] {
        self.end_at_line(self.line_of(n), n)
    }

    /// [`Run::end_of`] for the block on source line `line` (`what` names it in messages).
    pub fn end_at_line(&self, line: u32, what: &str) -> [f64; 9] {
        let n = what;
        let base = self.machine.five_axis();
        let mut kin = None;
        let mut end = None;
        let mut under_tcp = false;
        for (c, &l) in self.canon.iter().zip(&self.lines) {
            if let Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } = c
            {
                kin = match (active, &base) {
                    (true, Some(k)) => Some(k.clone().with_tool_offset(*tool_offset)),
                    _ => None,
                };
            }
            if let (Some(m), true) = (c.motion(), l == line) {
                let p = m.end();
                under_tcp = kin.is_some();
                end = Some(match &kin {
                    Some(k) => stanok_kin::Kinematics::inverse(k, &p).unwrap(),
                    None => p.to_array(),
                });
            }
        }
        let end = end.unwrap_or_else(|| panic!("block {n} has no motion"));
        if !under_tcp {
            // Without TCP a G64 block blends into the next one: no stop at its end.
            return end;
        }
        let Some(last) = self
            .setpoints
            .iter()
            .rev()
            .find(|s| s.line == line)
            .map(|s| s.joints)
        else {
            // A block that moves nothing (it is already there) has no setpoint of its own.
            return end;
        };
        for i in 0..9 {
            assert!(
                (last[i] - end[i]).abs() < 0.01,
                "{n}: the trace stops at {last:?}, the block ends at {end:?}"
            );
        }
        end
    }

    /// How long block `n` moved, s.
    pub fn duration_of(&self, n: &str) -> f64 {
        let b = self.block(n);
        b.last().map_or(0.0, |l| l.t) - b.first().map_or(0.0, |f| f.t)
    }

    /// The run ended without error, or panics with it.
    pub fn ok(&self) -> &Self {
        if let Some(d) = &self.error {
            panic!("run stopped: {d:?}");
        }
        assert_eq!(
            self.report.violation_count, 0,
            "{:?}",
            self.report.violations
        );
        self
    }
}

/// Asserts machine X Y Z (and the given rotary values, slot → value) within `tol`.
pub fn assert_axes(got: [f64; 9], xyz: [f64; 3], rotary: &[(usize, f64)], tol: f64, what: &str) {
    for i in 0..3 {
        assert!(
            (got[i] - xyz[i]).abs() < tol,
            "{what}: axes {got:?}, want XYZ {xyz:?}"
        );
    }
    for &(i, v) in rotary {
        assert!(
            (got[i] - v).abs() < tol,
            "{what}: axis {i} is {}, want {v}",
            got[i]
        );
    }
}
