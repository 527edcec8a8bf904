//! Text and JSON forms of the run report, and the JSON-lines form of the Canon stream.

use crate::source::Program;
use serde::Serialize;
use stanok_canon::{Canon, Diagnostic, Span, Spanned, AXIS_LETTERS};
use stanok_machine::RunReport;
use stanok_syntax::Dialect;
use std::fmt::Write;

fn dialect_name(d: Dialect) -> &'static str {
    d.id()
}

/// A duration for people: seconds, and from a minute on also h:mm:ss.s (`3725.100 s (1:02:05.1)`).
pub fn duration(seconds: f64) -> String {
    if !(seconds.is_finite() && seconds >= 60.0) {
        return format!("{seconds:.3} s");
    }
    let tenths = (seconds * 10.0).round() as u64;
    let (h, rest) = (tenths / 36_000, tenths % 36_000);
    let (m, rest) = (rest / 600, rest % 600);
    format!("{seconds:.3} s ({h}:{m:02}:{:02}.{})", rest / 10, rest % 10)
}

/// How the report names a spindle: the main one plainly when it is the only one, else counted
/// from 1.
fn spindle_label(spindle: u8, only_main: bool) -> String {
    if only_main {
        "Spindle".into()
    } else {
        format!("Spindle {}", u32::from(spindle) + 1)
    }
}

/// The human-readable report.
pub fn text(name: &str, dialect: Dialect, r: &RunReport, failure: Option<&Diagnostic>) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Program     {name} ({})", dialect_name(dialect));
    let _ = writeln!(s, "Machine     {}", r.machine);
    let status = match failure {
        None if r.program_ended => "completed (program end)".to_string(),
        None => "completed (end of file)".to_string(),
        Some(d) => match &d.file {
            Some(f) => format!("stopped at line {} of {f}: {}", d.span.line, d.message),
            None => format!("stopped at line {}: {}", d.span.line, d.message),
        },
    };
    let _ = writeln!(s, "Status      {status}");
    let _ = writeln!(s, "Blocks      {}", r.blocks);
    let _ = writeln!(
        s,
        "Motion      {} segments ({} rapid, {} linear feed, {} arc)",
        r.motion_segments, r.rapid_segments, r.feed_segments, r.arc_segments
    );
    let _ = writeln!(
        s,
        "Distance    rapid {:.3} mm, feed {:.3} mm",
        r.rapid_distance_mm, r.feed_distance_mm
    );
    // SOFT pieces are the only ones with jerk: without any, the run was BRISK throughout.
    let soft = r.axes.iter().any(|a| a.peak_jerk > 0.0);
    let _ = writeln!(
        s,
        "Cycle time  {} planned (look-ahead, acceleration{}, servo period {} ms, {} setpoints, feed override {}%)",
        duration(r.cycle_time_s),
        if soft { ", jerk" } else { "" },
        r.servo_period_s * 1e3,
        r.setpoints,
        r.feed_override_percent
    );
    let _ = writeln!(
        s,
        "Time        {} nominal (length / feed, no acceleration), of which dwell {}",
        duration(r.nominal_time_s),
        duration(r.dwell_time_s)
    );
    if let Some(h) = &r.feed_hold {
        if h.happened {
            let _ = writeln!(
                s,
                "Feed hold   at {} of machine time the machine braked on the path, stood {} and resumed",
                duration(h.at_s),
                duration(h.standstill_s)
            );
        } else {
            let _ = writeln!(
                s,
                "Feed hold   at {}: not reached (the program ended before)",
                duration(h.at_s)
            );
        }
    }
    if !r.axes.is_empty() {
        let _ = writeln!(
            s,
            "Axis peaks  (planned / limit; trace = finite differences of the setpoints)"
        );
        for a in &r.axes {
            let u = if matches!(a.axis, 'A' | 'B' | 'C') {
                "deg"
            } else {
                "mm"
            };
            let mut line = format!(
                "  {}  v {:.1}/{:.1} {u}/s (trace {:.1})  a {:.1}/{:.1} {u}/s² (trace {:.1})",
                a.axis,
                a.peak_velocity,
                a.max_velocity,
                a.trace_peak_velocity,
                a.peak_acceleration,
                a.max_acceleration,
                a.trace_peak_acceleration,
            );
            if soft {
                let _ = write!(line, "  j {:.0}/{:.0} {u}/s³", a.peak_jerk, a.max_jerk);
            }
            let _ = writeln!(s, "{line}");
        }
    }
    let only_main = r.spindles.iter().all(|sp| sp.spindle == 0);
    for sp in &r.spindles {
        let speed = if (sp.max_rpm - sp.min_rpm).abs() < 0.5 {
            format!("{:.0} rev/min", sp.max_rpm)
        } else {
            format!("{:.0}…{:.0} rev/min", sp.min_rpm, sp.max_rpm)
        };
        let _ = writeln!(
            s,
            "{:<12}{speed} while moving{}",
            spindle_label(sp.spindle, only_main),
            if r.surface_speed {
                " (G96: the speed the surface-speed law gives at every setpoint)"
            } else {
                ""
            }
        );
    }
    let c = &r.contour_error;
    let _ = writeln!(
        s,
        "Contour     {:.6} mm at junctions (line {}, t = {:.3} s), {:.6} mm elsewhere (line {}, t = {:.3} s): the largest distance of a setpoint from the programmed path",
        c.junctions.max_mm,
        c.junctions.line,
        c.junctions.t_s,
        c.elsewhere.max_mm,
        c.elsewhere.line,
        c.elsewhere.t_s
    );
    if r.slowest_blocks
        .iter()
        .any(|b| b.planned_s - b.nominal_s > 5e-4)
    {
        let _ = writeln!(
            s,
            "Slowest     blocks that lose the most time against nominal (planned − nominal, the limit that set their speed)"
        );
        for b in r
            .slowest_blocks
            .iter()
            .filter(|b| b.planned_s - b.nominal_s > 5e-4)
        {
            let _ = writeln!(
                s,
                "  line {:>5}  {:.3} s planned, {:.3} s nominal, +{:.3} s  {}",
                b.line,
                b.planned_s,
                b.nominal_s,
                b.planned_s - b.nominal_s,
                b.limit
            );
        }
    }
    if r.violation_count == 0 {
        let _ = writeln!(
            s,
            "Limits      ok: no velocity, acceleration, {}travel or path-tolerance violation",
            if soft { "jerk, " } else { "" },
        );
    } else {
        let _ = writeln!(s, "Limits      {} VIOLATION(S)", r.violation_count);
        for v in &r.violations {
            let _ = writeln!(s, "  line {:>5}  {}", v.line, v.text);
        }
    }
    match &r.bounding_box {
        Some(b) => {
            let _ = writeln!(
                s,
                "Bounds      X [{:.3}, {:.3}]  Y [{:.3}, {:.3}]  Z [{:.3}, {:.3}] mm",
                b.min[0], b.max[0], b.min[1], b.max[1], b.min[2], b.max[2]
            );
        }
        None => {
            let _ = writeln!(s, "Bounds      (no motion)");
        }
    }
    let tools: Vec<String> = r.tools_used.iter().map(|t| format!("T{t}")).collect();
    let _ = writeln!(
        s,
        "Tools       {} ({} change(s))",
        if tools.is_empty() {
            "none".into()
        } else {
            tools.join(", ")
        },
        r.tool_changes
    );
    if !r.messages.is_empty() {
        let _ = writeln!(s, "Messages");
        for m in &r.messages {
            let _ = writeln!(s, "  line {:>5}  {}", m.line, m.text);
        }
    }
    if !r.m_functions.is_empty() {
        let _ = writeln!(s, "M functions");
        for m in &r.m_functions {
            let _ = writeln!(s, "  line {:>5}  {}", m.line, m.text);
        }
    }
    // The machine's own axes only (a 3-axis mill has no A B C to report).
    let p = r.final_position.to_array();
    let letters: Vec<char> = if r.axes.is_empty() {
        vec!['X', 'Y', 'Z']
    } else {
        r.axes.iter().map(|a| a.axis).collect()
    };
    let position: Vec<String> = letters
        .iter()
        .filter_map(|l| AXIS_LETTERS.iter().position(|a| a == l))
        .map(|i| format!("{}{:.3}", AXIS_LETTERS[i], p[i]))
        .collect();
    let _ = writeln!(s, "Final       {}", position.join(" "));
    s
}

/// A warning of the converter (a line, a message) as a diagnostic at that line of the program.
pub fn convert_warning(program: &Program, w: &stanok_convert::Warning) -> Diagnostic {
    let span = program
        .snippet_text(64 * 1024 * 1024)
        .and_then(|text| line_span(&text, w.line))
        .unwrap_or(Span::new(0, 0, w.line, 1));
    Diagnostic::warning("convert::not-expressible", w.message.clone(), span)
}

/// The span of line `line` (1-based) of `text`, without its line end.
fn line_span(text: &str, line: u32) -> Option<Span> {
    if line == 0 {
        return None;
    }
    let mut start = 0usize;
    for (i, l) in text.split_inclusive('\n').enumerate() {
        if i + 1 == line as usize {
            let body = l.trim_end_matches(['\n', '\r']);
            return Some(Span::new(
                start as u64,
                (start + body.len()) as u64,
                line,
                1,
            ));
        }
        start += l.len();
    }
    None
}

#[derive(Serialize)]
struct JsonReport<'a> {
    file: String,
    dialect: &'static str,
    status: &'static str,
    error: Option<&'a Diagnostic>,
    warnings: &'a [Diagnostic],
    #[serde(flatten)]
    report: &'a RunReport,
}

/// The report as one JSON object (field names documented in docs/report.md).
pub fn json(
    file: &str,
    dialect: Dialect,
    r: &RunReport,
    failure: Option<&Diagnostic>,
    warnings: &[Diagnostic],
) -> String {
    let j = JsonReport {
        file: file.to_string(),
        dialect: dialect_name(dialect),
        status: if failure.is_some() { "error" } else { "ok" },
        error: failure,
        warnings,
        report: r,
    };
    serde_json::to_string_pretty(&j).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

#[derive(Serialize)]
struct JsonCanon<'a> {
    line: u32,
    #[serde(skip_serializing_if = "Option::is_none")]
    n: Option<u32>,
    #[serde(flatten)]
    canon: &'a Canon,
}

/// One command as a JSON line.
pub fn canon_json_line(cmd: &Spanned<Canon>) -> String {
    let j = JsonCanon {
        line: cmd.span.line,
        n: cmd.block_number,
        canon: &cmd.value,
    };
    let mut s = serde_json::to_string(&j).unwrap_or_default();
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_durations_also_in_hours_minutes_seconds() {
        assert_eq!(duration(32.8491), "32.849 s");
        assert_eq!(duration(3725.1), "3725.100 s (1:02:05.1)");
        assert_eq!(duration(59.99), "59.990 s");
        assert_eq!(duration(60.0), "60.000 s (0:01:00.0)");
        assert_eq!(duration(86399.96), "86399.960 s (24:00:00.0)");
    }

    #[test]
    fn a_line_span_covers_the_line() {
        let text = "G0 X1\r\nG1 Y2 F100\nM2";
        assert_eq!(line_span(text, 2), Some(Span::new(7, 17, 2, 1)));
        assert_eq!(line_span(text, 3), Some(Span::new(18, 20, 3, 1)));
        assert_eq!(line_span(text, 9), None);
    }
}
