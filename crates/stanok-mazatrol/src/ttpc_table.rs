//! Tables 12.1 and 12.2 applied to a block (`docs/dialects/mazatrol-eia.md` §16): column [1]
//! while tool tip point control is on, column [2] when a block selects it, and the format rules
//! R-08 (G49 alone) and R-09 (G43.4/G43.5 beside G90/G91 only, AMB-1).
//!
//! Every refusal names the code, the table, the column or note and the series:
//! "G28 is not allowed during tool tip point control on the T-series (table 12.1, column [1])".

use crate::block::Codes;
use crate::codes::{g_name, select_blocked_by, ttpc_row, Code, Mark, Series};
use crate::ctx::Ctx;
use crate::modes::CompMode;
use crate::TtpcMode;
use stanok_canon::{Diagnostic, FeedMode};
use stanok_interp_core::{MotionMode, PathMode};
use stanok_syntax::ColSpan;

fn series_of(cx: &Ctx<'_>) -> Series {
    cx.fe.m.series
}

/// Column [1] for one G code given in TTPC (`helical`: an arc with a third axis word).
pub(crate) fn column_one(
    cx: &Ctx<'_>,
    code: u32,
    helical: bool,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let s = series_of(cx);
    let Some(row) = ttpc_row(s, Code::G(code), helical) else {
        return Ok(());
    };
    match row.in_ttpc {
        Mark::No if helical && matches!(code, 20 | 30) => Err(cx.err(
            "mazatrol::code-not-allowed-in-ttpc",
            format!(
                "a helical {} is not allowed during tool tip point control on the {} (table {}, helical interpolation)",
                g_name(code),
                s.name(),
                s.table()
            ),
            span,
        )),
        Mark::No => Err(cx.err(
            "mazatrol::code-not-allowed-in-ttpc",
            format!(
                "{} is not allowed during tool tip point control on the {} (table {}, column [1])",
                g_name(code),
                s.name(),
                s.table()
            ),
            span,
        )),
        _ => Ok(()),
    }
}

/// M-series note 3 for an arc in TTPC: G43.4 with the workpiece frame, no B or C word.
pub(crate) fn note_three(cx: &Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.fe.modes.mode != TtpcMode::Type1 || !cx.fe.ttpc_workpiece_frame {
        return Err(cx.err(
            "mazatrol::code-not-allowed-in-ttpc",
            format!(
                "{} is not allowed during tool tip point control on the M-series unless G43.4 and the workpiece programming frame are in force (table 12.2, note 3)",
                g_name(code)
            ),
            span,
        ));
    }
    for l in [b'B', b'C'] {
        if let Some(w) = cx.words.peek(l) {
            return Err(cx.err(
                "mazatrol::rotary-word-in-arc",
                format!(
                    "{} with a {} word is not allowed during tool tip point control on the M-series (table 12.2, note 3)",
                    g_name(code),
                    l as char
                ),
                w.span,
            ));
        }
    }
    Ok(())
}

/// True if the block's arc (code `code`, G02/G03) would be helical: it has an axis word off the
/// plane (the plane's normal axis).
fn helical(cx: &Ctx<'_>) -> bool {
    let (_, _, n) = cx.st.plane.axes();
    cx.words.has(b"XYZ"[n])
}

/// The checks of a block (`docs` §16).
pub(crate) fn check(cx: &Ctx<'_>, codes: &Codes) -> Result<(), Diagnostic> {
    let on = cx.fe.modes.mode != TtpcMode::Off;
    let s = series_of(cx);
    let select = codes
        .span(434)
        .map(|sp| (434, sp))
        .or(codes.span(435).map(|sp| (435, sp)));
    // R-09 (AMB-1 compatibility: G90/G91 beside it).
    if let Some((code, span)) = select {
        if let Some((other, _)) = codes
            .all()
            .find(|(c, _)| !matches!(*c, 900 | 910) && *c != code)
        {
            return Err(cx.err(
                "mazatrol::ttpc-with-other-g-code",
                format!(
                    "{} must not be commanded together with {}",
                    g_name(code),
                    g_name(other)
                ),
                span,
            ));
        }
    }
    // G49 alone when it cancels TTPC.
    if let Some(span) = codes.span(490) {
        let others = codes.all().count() > 1
            || cx.has_axis_words()
            || !cx.words.m.is_empty()
            || cx.words.first_unused().is_some();
        if on && others {
            return Err(cx.err(
                "mazatrol::g49-not-alone",
                "G49 must be commanded alone in its block",
                span,
            ));
        }
    }
    if on {
        for (code, span) in codes.all() {
            if matches!(code, 434 | 435 | 490) {
                continue;
            }
            // Note 1 (M): G43/G44 replace TTPC; T-series: tlo.rs refuses (AMB-13).
            if matches!(code, 430 | 440) {
                continue;
            }
            if matches!(code, 20 | 30) {
                let h = helical(cx);
                if h || s == Series::T {
                    column_one(cx, code, h, span)?;
                }
                note_three(cx, code, span)?;
                continue;
            }
            column_one(cx, code, false, span)?;
        }
        // A modal arc in TTPC (no G02/G03 in the block, axis words).
        if codes.motion.is_none()
            && matches!(cx.st.motion, MotionMode::ArcCw | MotionMode::ArcCcw)
            && cx.has_axis_words()
        {
            let code = if cx.st.motion == MotionMode::ArcCw {
                20
            } else {
                30
            };
            let span = cx.whole();
            let h = helical(cx);
            if h || s == Series::T {
                column_one(cx, code, h, span)?;
            }
            note_three(cx, code, span)?;
        }
        return Ok(());
    }
    let Some((code, span)) = select else {
        return Ok(());
    };
    // Column [2]: the modes in force when TTPC is selected (the ON code of a combined row).
    let blocked = |c: u32| select_blocked_by(s, c);
    let m = &cx.fe.m;
    let mut in_force: Vec<u32> = Vec::new();
    match cx.st.motion {
        MotionMode::ArcCw => in_force.push(20),
        MotionMode::ArcCcw => in_force.push(30),
        _ => {}
    }
    if let Some(c) = m.cycle {
        in_force.push(c.code);
    }
    match m.comp {
        CompMode::Left => in_force.push(410),
        CompMode::Right => in_force.push(420),
        CompMode::Auto => in_force.push(460),
        CompMode::Off => {}
    }
    if cx.st.feed_mode == FeedMode::UnitsPerRevolution {
        in_force.push(950);
    }
    if m.css.is_some() {
        in_force.push(960);
    }
    if m.scaling.is_some() {
        in_force.push(510);
    }
    if m.mirror.iter().any(Option::is_some) {
        in_force.push(511);
    }
    if m.rotation.is_some() || m.turret_mirror {
        in_force.push(680);
    }
    if m.rotation3d.is_some() {
        in_force.push(685);
    }
    if let Some(c) = m.modal_call {
        in_force.push(if c.every_block { 661 } else { 660 });
    }
    if matches!(m.path, 611 | 620 | 630) {
        in_force.push(m.path);
    }
    if m.cylinder.is_some() {
        in_force.push(71);
    }
    if m.polar {
        in_force.push(121);
    }
    if m.cross {
        in_force.push(1100);
    }
    if m.polar_input {
        in_force.push(1220);
    }
    let _ = PathMode::ExactStop;
    for c in in_force {
        // M-series radius compensation: column [2] is "—", but column [1] forbids it in TTPC.
        let comp_m = s == Series::M && matches!(c, 410 | 420);
        if blocked(c) || comp_m {
            let table_ref = if comp_m { "column [1]" } else { "column [2]" };
            return Err(cx.err(
                "mazatrol::ttpc-not-selectable",
                format!(
                    "{} cannot be selected while {} is in force on the {} (table {}, {table_ref})",
                    g_name(code),
                    g_name(c),
                    s.name(),
                    s.table()
                ),
                span,
            ));
        }
    }
    Ok(())
}
