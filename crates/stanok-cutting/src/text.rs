//! The calculation as text: every step with the cells it read, its working and its defaults.

use crate::{Calculation, PassKind, Step};
use std::fmt::Write;

/// The whole calculation as a report a student can check by hand.
pub fn text(c: &Calculation) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Cutting conditions for turning (method of Lab 2)");
    let _ = writeln!(out, "data: {}", c.source);
    let _ = writeln!(
        out,
        "work: {}, D = {} mm; tool {}",
        c.input.material.describe(),
        c.input.diameter_mm,
        c.input.tool
    );
    out.push('\n');
    step(&mut out, "0", &c.tool);
    for p in &c.passes {
        let kind = match p.kind {
            PassKind::Rough => "rough",
            PassKind::Finish => "finish",
        };
        let _ = writeln!(
            out,
            "\n== pass {} ({kind}): t = {:.3} mm, D = {:.3} mm ==",
            p.number, p.depth_mm, p.diameter_mm
        );
        for (i, s) in p.steps.iter().enumerate() {
            step(&mut out, &format!("{}.{}", p.number, i + 1), s);
        }
        let _ = write!(
            out,
            "result: S = {} mm/rev, v = {:.2} m/min, n = {:.1} rpm",
            p.feed_mm_rev, p.v_m_min, p.n_rpm
        );
        if let (Some(n), Some(v)) = (p.n_act_rpm, p.v_act_m_min) {
            let _ = write!(out, ", n_act = {n} rpm, v_act = {v:.2} m/min");
        }
        out.push('\n');
    }
    let _ = writeln!(out, "\nnot in the document (not computed):");
    for n in &c.not_in_document {
        let _ = writeln!(out, "  - {n}");
    }
    out
}

fn step(out: &mut String, number: &str, s: &Step) {
    let _ = writeln!(out, "{number}. {}", s.title);
    for c in &s.cells {
        let _ = write!(
            out,
            "   [table {}] {} | {} = {}",
            c.table, c.row, c.column, c.value
        );
        if let Some(n) = &c.note {
            let _ = write!(out, "   (the printed table is unclear here: {n})");
        }
        out.push('\n');
    }
    for l in &s.lines {
        let _ = writeln!(out, "   {l}");
    }
    for d in &s.defaults {
        let _ = writeln!(out, "   default: {d}");
    }
}
