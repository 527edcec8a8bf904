//! Text and JSON forms of the run report, and the JSON-lines form of the Canon stream.

use serde::Serialize;
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_machine::RunReport;
use stanok_syntax::Dialect;
use std::fmt::Write;
use std::path::Path;

fn dialect_name(d: Dialect) -> &'static str {
    d.id()
}

/// The human-readable report.
pub fn text(file: &Path, dialect: Dialect, r: &RunReport, failure: Option<&Diagnostic>) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Program     {} ({})",
        file.display(),
        dialect_name(dialect)
    );
    let _ = writeln!(s, "Machine     {}", r.machine);
    let status = match failure {
        None if r.program_ended => "completed (program end)".to_string(),
        None => "completed (end of file)".to_string(),
        Some(d) => format!("stopped at line {}: {}", d.span.line, d.message),
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
    let _ = writeln!(
        s,
        "Cycle time  {:.3} s planned (look-ahead, acceleration{}, servo period {} ms, {} setpoints, feed override {}%)",
        r.cycle_time_s,
        if r.axes.iter().any(|a| a.peak_jerk > 0.0) { ", jerk" } else { "" },
        r.servo_period_s * 1e3,
        r.setpoints,
        r.feed_override_percent
    );
    let _ = writeln!(
        s,
        "Time        {:.3} s nominal (length / feed, no acceleration), of which dwell {:.3} s",
        r.nominal_time_s, r.dwell_time_s
    );
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
            let _ = writeln!(
                s,
                "  {}  v {:.1}/{:.1} {u}/s (trace {:.1})  a {:.1}/{:.1} {u}/s² (trace {:.1})  j {:.0}/{:.0} {u}/s³ (SOFT)",
                a.axis,
                a.peak_velocity,
                a.max_velocity,
                a.trace_peak_velocity,
                a.peak_acceleration,
                a.max_acceleration,
                a.trace_peak_acceleration,
                a.peak_jerk,
                a.max_jerk
            );
        }
    }
    for sp in &r.spindles {
        let _ = writeln!(
            s,
            "Spindle {}   {:.0}…{:.0} rev/min commanded while moving (G96 evaluated at every setpoint)",
            sp.spindle, sp.min_rpm, sp.max_rpm
        );
    }
    if r.violation_count == 0 {
        let _ = writeln!(
            s,
            "Limits      ok: no velocity, acceleration, jerk, travel or path-tolerance violation (path deviation ≤ {:.4} mm)",
            r.max_path_deviation_mm
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
    let p = &r.final_position;
    let _ = writeln!(
        s,
        "Final       X{:.3} Y{:.3} Z{:.3} A{:.3} B{:.3} C{:.3}",
        p.x, p.y, p.z, p.a, p.b, p.c
    );
    if let Some(st) = &r.stock {
        s.push_str(&crate::stock::text(st));
    }
    s
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

/// The report as one JSON object (field names documented in the README).
pub fn json(
    file: &Path,
    dialect: Dialect,
    r: &RunReport,
    failure: Option<&Diagnostic>,
    warnings: &[Diagnostic],
) -> String {
    let j = JsonReport {
        file: file.display().to_string(),
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
