//! Checking a program for the editor and previewing it for the 3D view, without the machine
//! thread: the interpreter in check mode gives every diagnostic (as `stanok check`); a second,
//! unpaced pass through a fresh simulated machine gives the programmed path (polylines, rapids
//! apart) and the planned cycle time (as `stanok run`).

use crate::machine::{interp_options, Alarm, SERVE_LOOKAHEAD};
use serde::Serialize;
use stanok_canon::Canon;
use stanok_geom::{Helix, Nurbs};
use stanok_interp::Interpreter;
use stanok_machine::{MachineData, SimMachine, SimOptions};
use stanok_syntax::Dialect;
use std::path::PathBuf;

/// At most this many preview points (a huge program is previewed in part, `truncated`).
const MAX_PREVIEW_POINTS: usize = 400_000;

/// Every diagnostic of a program, in line order (errors and warnings).
pub fn check(
    text: &str,
    dialect: Dialect,
    machine: &MachineData,
    subroutine_path: &[PathBuf],
) -> Vec<Alarm> {
    let mut opts = interp_options(machine, dialect, subroutine_path);
    opts.continue_after_error = true;
    let mut interp = Interpreter::from_text(text, opts);
    let mut all: Vec<Alarm> = Vec::new();
    // A bad block inside a loop fails on every pass: each error is listed once (as `stanok check`).
    let mut seen = std::collections::HashSet::new();
    for item in interp.by_ref() {
        if let Err(d) = item {
            if seen.insert((
                d.code.to_string(),
                d.span.start,
                d.span.end,
                d.message.clone(),
            )) {
                all.push(Alarm::of(&d));
            }
        }
    }
    all.extend(interp.take_warnings().iter().map(Alarm::of));
    all.sort_by_key(|a| (a.line, a.column));
    all
}

/// One polyline of the programmed path.
#[derive(Debug, Clone, Serialize)]
pub struct PathPiece {
    /// Rapid (drawn dashed) or feed.
    pub rapid: bool,
    /// X Y Z points, machine coordinates, mm.
    pub points: Vec<[f32; 3]>,
}

/// The programmed path and the planned time.
#[derive(Debug, Clone, Serialize)]
pub struct Preview {
    /// Polylines in program order.
    pub path: Vec<PathPiece>,
    /// True if the path was cut at `MAX_PREVIEW_POINTS`.
    pub truncated: bool,
    /// Planned cycle time, s (up to the first error).
    pub cycle_time_s: f64,
    /// Final position of a full run, machine coordinates.
    pub final_position: [f64; 9],
}

fn push(path: &mut Vec<PathPiece>, rapid: bool, start: [f64; 3], points: &[[f64; 3]]) {
    let f = |p: &[f64; 3]| [p[0] as f32, p[1] as f32, p[2] as f32];
    match path.last_mut() {
        Some(last) if last.rapid == rapid && last.points.last() == Some(&f(&start)) => {}
        _ => path.push(PathPiece {
            rapid,
            points: vec![f(&start)],
        }),
    }
    let last = path.last_mut().expect("pushed above");
    last.points.extend(points.iter().map(f));
}

/// The preview of the module doc.
pub fn preview(
    text: &str,
    dialect: Dialect,
    machine: &MachineData,
    subroutine_path: &[PathBuf],
) -> Preview {
    let opts = interp_options(machine, dialect, subroutine_path);
    let mut interp = Interpreter::from_text(text, opts);
    let options = SimOptions {
        lookahead: SERVE_LOOKAHEAD,
        servo_period_s: 0.004,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(machine.clone(), options);
    let mut path: Vec<PathPiece> = Vec::new();
    let mut points = 0usize;
    let mut truncated = false;
    for item in interp.by_ref() {
        let Ok(cmd) = item else { break };
        if sim.apply(&cmd).is_err() {
            break;
        }
        if points > MAX_PREVIEW_POINTS {
            truncated = true;
            continue;
        }
        let mut pts: Vec<[f64; 3]> = Vec::new();
        let (rapid, start) = match &cmd.value {
            Canon::StraightTraverse(m) => {
                pts.push(m.end.xyz());
                (true, m.start.xyz())
            }
            Canon::StraightFeed(m) => {
                pts.push(m.end.xyz());
                (false, m.start.xyz())
            }
            Canon::StraightProbe {
                motion, contact, ..
            } => {
                pts.push(motion.stopped_at(*contact).end.xyz());
                (false, motion.start.xyz())
            }
            Canon::ArcFeed(a) => {
                let h = Helix {
                    start: a.start.xyz(),
                    end: a.end.xyz(),
                    centre: a.centre,
                    axis: a.axis,
                    turns: a.turns,
                };
                h.tessellate(0.01, &mut pts);
                (false, a.start.xyz())
            }
            Canon::SplineFeed(s) => {
                Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots)
                    .tessellate(0.01, &mut pts);
                (false, s.start.xyz())
            }
            other => match other.motion() {
                Some(m) => {
                    pts.push(m.end().xyz());
                    (false, m.start().xyz())
                }
                None => continue,
            },
        };
        points += pts.len() + 1;
        push(&mut path, rapid, start, &pts);
    }
    let report = sim.finish();
    Preview {
        path,
        truncated,
        cycle_time_s: report.cycle_time_s,
        final_position: report.final_position.to_array(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_block_in_a_loop_is_listed_once() {
        let text = "for (int i = 0; i < 3; i++) {\nG01 X=i*zz F100\n}\nM30\n";
        let alarms = check(text, Dialect::Axioma, &MachineData::default_mill(), &[]);
        let found: Vec<(u32, u32, &str)> = alarms
            .iter()
            .map(|a| (a.line, a.column, a.code.as_str()))
            .collect();
        assert_eq!(found, [(2, 9, "hll::undeclared")]);
    }
}
