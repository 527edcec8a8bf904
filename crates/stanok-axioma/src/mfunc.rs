//! Executing AxiOMA M functions (spec axioma-2 §4, §5): the table (`mtable.rs`, machine data)
//! says what a number is; this file does it to the Canon stream and the M vector.
//!
//! Words that belong to an M function run with it (§4.1, DERIVED): S (S<i>=) with the spindle
//! functions of spindle i — a speed for M<x>03/04/13/14, an angle for M<x>19 — T/D with M06/M66,
//! H1=/N1= with M902/M903/M905. An S with no spindle function of its spindle is set before the
//! prefix functions (it is stored for later ones, §3.7).
//!
//! After each function its group shows it in the M vector, except the rotary-table group, which
//! shows the function that names the resulting clamp state (§5.3). Program end returns the
//! groups marked `reset_at_end` to their defaults (spindles stop, coolant off).

use super::mtable::{MEntry, MKind, MTable, PROGRAM_CONTROL_ORDER};
use crate::ctx::Ctx;
use crate::words::Val;
use stanok_canon::{AuxTiming, Canon, Diagnostic, Pose};
use stanok_syntax::ColSpan;

/// One M function of a block, with its place in the block's execution order.
#[derive(Debug, Clone)]
pub(super) struct MFunction {
    pub number: u32,
    /// (group order, group index): the sort key within prefix and within postfix.
    pub order: (u32, usize),
    pub group: usize,
    pub timing: AuxTiming,
    pub kind: MKind,
}

impl MFunction {
    /// Program control (M00/M01/M02/M30/M99).
    pub fn is_program_control(&self) -> bool {
        self.order.0 >= PROGRAM_CONTROL_ORDER
    }

    /// The spindle whose S word goes with this function.
    pub fn spindle(&self) -> Option<u8> {
        match self.kind {
            MKind::SpindleOn { spindle, .. }
            | MKind::SpindleStop { spindle }
            | MKind::SpindleOrient { spindle } => Some(spindle),
            _ => None,
        }
    }
}

pub(super) fn m_function(table: &MTable, number: u32) -> Option<MFunction> {
    let MEntry {
        group,
        timing,
        kind,
        ..
    } = *table.lookup(number)?;
    Some(MFunction {
        number,
        order: (table.groups.get(group)?.order, group),
        group,
        timing,
        kind,
    })
}

/// The words an M function may take with it, and which were consumed.
#[derive(Debug, Default)]
pub(super) struct MWords {
    /// S (index 0) and S2= … S4= (index 1 … 3).
    pub speed: [Option<Val>; 4],
    pub speed_done: [bool; 4],
    pub tool: Option<u32>,
    pub tool_done: bool,
    pub edge: Option<Val>,
    /// `H1=` (M902) / `N1=` (M903, M905).
    pub spindle_param: Option<Val>,
}

pub(super) fn set_speed(cx: &mut Ctx<'_>, spindle: u8, v: Val) -> Result<(), Diagnostic> {
    super::technology::speed_word(cx, spindle, v)
}

fn show(cx: &mut Ctx<'_>, group: usize, number: u32) {
    let table = &cx.fe.params.m_table;
    if let Some(slot) = cx.fe.ext.m.vector_mut(table).get_mut(group) {
        *slot = Some(number);
    }
}

fn aux(cx: &mut Ctx<'_>, f: &MFunction) {
    cx.out.push(Canon::AuxiliaryFunction {
        number: f.number,
        timing: f.timing,
    });
}

/// `H1=`/`N1=` as a spindle number 1…4.
fn spindle_param(cx: &Ctx<'_>, f: &MFunction, w: &MWords, at: ColSpan) -> Result<u8, Diagnostic> {
    let letter = if f.kind == MKind::AxisModeOf {
        "H1="
    } else {
        "N1="
    };
    let Some(v) = w.spindle_param else {
        return Err(cx.err(
            "axioma::spindle-number-missing",
            format!("M{} needs the spindle number as {letter}<1…4>", f.number),
            at,
        ));
    };
    if v.v.fract() != 0.0 || !(1.0..=4.0).contains(&v.v) {
        return Err(cx.err(
            "axioma::spindle-number",
            format!("{letter}{}: the spindle number is 1 … 4", v.v),
            v.span,
        ));
    }
    Ok(v.v as u8 - 1)
}

pub(super) fn run_m(
    cx: &mut Ctx<'_>,
    f: &MFunction,
    w: &mut MWords,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    match f.kind {
        MKind::SpindleOn {
            spindle,
            direction,
            coolant,
        } => {
            let s = spindle as usize;
            if let (Some(v), false) = (w.speed[s], w.speed_done[s]) {
                set_speed(cx, spindle, v)?;
            }
            w.speed_done[s] = true;
            if coolant {
                cx.st.flood = true;
                cx.out.push(Canon::Flood { on: true });
            }
            cx.fe.ext.m.axis_mode[s] = false;
            cx.st.spindle_on[s] = true;
            cx.out.push(Canon::StartSpindle { spindle, direction });
        }
        MKind::SpindleStop { spindle } => {
            let s = spindle as usize;
            if let (Some(v), false) = (w.speed[s], w.speed_done[s]) {
                set_speed(cx, spindle, v)?;
            }
            w.speed_done[s] = true;
            cx.fe.ext.m.axis_mode[s] = false;
            cx.st.spindle_on[s] = false;
            cx.out.push(Canon::StopSpindle { spindle });
        }
        MKind::SpindleOrient { spindle } => {
            let s = spindle as usize;
            // S is an angle here (§4.3); without S the spindle goes to its previous position.
            let degrees = match (w.speed[s], w.speed_done[s]) {
                (Some(v), false) => {
                    if !(0.0..=360.0).contains(&v.v) {
                        return Err(cx.err(
                            "axioma::orient-angle",
                            format!("M{} S{}: the spindle position is 0 … 360°", f.number, v.v),
                            v.span,
                        ));
                    }
                    v.v
                }
                _ => cx.fe.ext.m.orientation[s],
            };
            w.speed_done[s] = true;
            if !cx.fe.params.spindle_encoder {
                return Err(cx
                    .err(
                        "axioma::orient-without-encoder",
                        format!("M{}: oriented stop needs a spindle position encoder", f.number),
                        at,
                    )
                    .with_note("a SERCOS/EtherCAT spindle drive or a rotary encoder (machine data `spindle_encoder`)"));
            }
            cx.fe.ext.m.orientation[s] = degrees;
            cx.st.spindle_on[s] = false;
            cx.out.push(Canon::OrientSpindle {
                spindle,
                degrees,
                direction: 0,
                timeout: None,
            });
        }
        MKind::SpindleAxisMode { spindle } => {
            cx.fe.ext.m.axis_mode[spindle as usize] = true;
            aux(cx, f);
        }
        MKind::AxisModeOf | MKind::SpindleModeOf => {
            let s = spindle_param(cx, f, w, at)?;
            cx.fe.ext.m.axis_mode[s as usize] = f.kind == MKind::AxisModeOf;
            aux(cx, f);
            // M902/M903 are not shown in the GMT vector (§4.4).
            return Ok(());
        }
        MKind::CompensationDepth => aux(cx, f),
        MKind::CoolantMist => cx.coolant(7),
        MKind::CoolantFlood => cx.coolant(8),
        MKind::CoolantOff => cx.coolant(9),
        MKind::ToolChange => tool_change(cx, w)?,
        MKind::BatchProbe { on } => {
            cx.fe.ext.m.batch_probe = on;
            aux(cx, f);
        }
        MKind::TableClamp { a, c } => {
            let before = cx.fe.ext.m.clamped;
            let mut after = before;
            if let Some(a) = a {
                after[0] = a;
            }
            if let Some(c) = c {
                after[1] = c;
            }
            if after == before {
                cx.warnings.push(Diagnostic::warning(
                    "axioma::meaningless-clamp",
                    format!(
                        "M{} does not change the rotary-table clamps (active: M{})",
                        f.number,
                        cx.fe.ext.m.clamp_display()
                    ),
                    cx.block.span_of(at),
                ));
            }
            cx.fe.ext.m.clamped = after;
            aux(cx, f);
            let shown = cx.fe.ext.m.clamp_display();
            show(cx, f.group, shown);
            return Ok(());
        }
        MKind::Machine => aux(cx, f),
        MKind::ProgramStop { optional } => {
            if !optional || cx.opts.optional_stop {
                cx.out.push(Canon::ProgramStop { optional });
            }
        }
        MKind::ProgramEnd | MKind::ProgramEndToWaitingPosition => program_end(cx, f, at)?,
    }
    show(cx, f.group, f.number);
    Ok(())
}

/// M02/M30/M99: spindles and coolant stop (all spindles of the channel, A), the groups marked
/// `reset_at_end` return to their defaults (a machine builder's default, e.g. the BeaverMill's M9,
/// is sent to the PLC), M99 moves to its waiting position at rapid.
fn program_end(cx: &mut Ctx<'_>, f: &MFunction, at: ColSpan) -> Result<(), Diagnostic> {
    if f.kind == MKind::ProgramEndToWaitingPosition {
        let home = cx.fe.params.m_table.waiting_position.and_then(|h| {
            cx.opts
                .control
                .offsets
                .home
                .get(h.wrapping_sub(1) as usize)
                .copied()
                .flatten()
        });
        match home {
            Some(home) => {
                let mut target = cx.st.position.to_array();
                for (k, v) in home.to_array().into_iter().enumerate() {
                    if cx.opts.axes[k] {
                        target[k] = v;
                    }
                }
                let p = cx.st.frame.to_program(&Pose::from_array(target));
                cx.straight(true, p, 0.0);
            }
            None => cx.warnings.push(Diagnostic::warning(
                "axioma::m99-waiting-position",
                "M99: no waiting position is configured (M-function table `waiting_position` with a defined home position); the program ends where it is",
                cx.block.span_of(at),
            )),
        }
    }
    for spindle in 0..4u8 {
        if cx.st.spindle_on[spindle as usize] {
            cx.st.spindle_on[spindle as usize] = false;
            cx.out.push(Canon::StopSpindle { spindle });
        }
    }
    if cx.st.mist {
        cx.st.mist = false;
        cx.out.push(Canon::Mist { on: false });
    }
    if cx.st.flood {
        cx.st.flood = false;
        cx.out.push(Canon::Flood { on: false });
    }
    let table = &cx.fe.params.m_table;
    let mut implied = Vec::new();
    let vector = cx.fe.ext.m.vector_mut(table);
    for (i, g) in table.groups.iter().enumerate() {
        if g.reset_at_end && vector[i] != g.default {
            vector[i] = g.default;
            if let Some(e) = g.default.and_then(|d| table.lookup(d)) {
                if e.kind == MKind::Machine {
                    implied.push(e.number);
                }
            }
        }
    }
    for number in implied {
        cx.out.push(Canon::AuxiliaryFunction {
            number,
            timing: AuxTiming::Postfix,
        });
    }
    let end_span = cx.block.span();
    cx.fe.ext.comp.end_of_program(end_span, cx.warnings)?;
    let ext = &mut cx.fe.ext;
    ext.comp3d
        .flush_spline_and_end(&mut ext.spline, cx.warnings, end_span)?;
    cx.out.push(Canon::ProgramEnd);
    Ok(())
}

/// M06/M66 with T and D (spec axioma-2 §3.9, §3.10).
fn tool_change(cx: &mut Ctx<'_>, w: &mut MWords) -> Result<(), Diagnostic> {
    let (tool, d) = (w.tool, w.edge);
    if !w.tool_done {
        if let Some(t) = tool {
            cx.st.selected_tool = Some(t);
            cx.out.push(Canon::SelectTool { tool: t });
        }
        w.tool_done = true;
    }
    // Rules of §3.10: D alone (or T = the tool already in the spindle) changes only the edge,
    // without a tool-change cycle.
    let t = tool.unwrap_or(cx.st.current_tool);
    // M06 that only addresses other spindles (`T2=10 M06`) leaves the main spindle alone.
    let other_spindles_only = tool.is_none()
        && d.is_none()
        && cx
            .words
            .indexed
            .iter()
            .any(|&(l, i, _)| (l == b'T' || l == b'D') && i >= 2);
    let change = tool.is_some() && t != cx.st.current_tool
        || tool.is_none() && d.is_none() && !other_spindles_only;
    if change {
        let t = cx.st.selected_tool.unwrap_or(t);
        cx.out.push(Canon::ChangeTool { tool: t, slot: t });
        super::tools::tool_change(cx, Some(t), d)?;
    } else if !other_spindles_only {
        super::tools::tool_change(cx, tool, d)?;
    }
    Ok(())
}
