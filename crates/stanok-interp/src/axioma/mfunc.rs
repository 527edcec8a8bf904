//! AxiOMA M functions (manual tables 2.2/2.3): group order, prefix/postfix timing, and what each
//! does to the Canon stream; S travels with the spindle functions and T with the tool change.

use crate::ctx::Ctx;
use crate::words::Val;
use stanok_canon::{AuxTiming, Canon, Diagnostic, SpindleDirection};

/// One M function: its table 2.2 group order, prefix/postfix timing and what it does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum MAction {
    Stop {
        optional: bool,
    },
    End,
    EndToWaitingPosition,
    Spindle {
        spindle: u8,
        on: Option<SpindleDirection>,
        coolant: bool,
    },
    Coolant(u32),
    ToolChange,
    Aux,
}

pub(super) struct MFunction {
    pub number: u32,
    /// Execution order within prefix/postfix (spec axioma-2 §4.1: spindle 1, coolant 2, tool 3).
    pub order: u32,
    pub timing: AuxTiming,
    pub action: MAction,
}

pub(super) fn m_function(number: u32) -> Option<MFunction> {
    use AuxTiming::{Postfix, Prefix};
    let (order, timing, action) = match number {
        0 => (99, Postfix, MAction::Stop { optional: false }),
        1 => (99, Postfix, MAction::Stop { optional: true }),
        2 | 30 => (99, Postfix, MAction::End),
        99 => (99, Postfix, MAction::EndToWaitingPosition),
        999 => (99, Postfix, MAction::Aux),
        n if matches!(n % 100, 3 | 4 | 5 | 13 | 14 | 19 | 70) && n < 500 && n / 100 != 1 => {
            let spindle = (n / 100).saturating_sub(1) as u8;
            let order = 10 + spindle as u32;
            match n % 100 {
                3 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::Clockwise),
                        coolant: false,
                    },
                ),
                4 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::CounterClockwise),
                        coolant: false,
                    },
                ),
                5 => (
                    order,
                    Postfix,
                    MAction::Spindle {
                        spindle,
                        on: None,
                        coolant: false,
                    },
                ),
                13 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::Clockwise),
                        coolant: true,
                    },
                ),
                14 => (
                    order,
                    Prefix,
                    MAction::Spindle {
                        spindle,
                        on: Some(SpindleDirection::CounterClockwise),
                        coolant: true,
                    },
                ),
                _ => (order, Prefix, MAction::Aux),
            }
        }
        7 | 8 => (20, Prefix, MAction::Coolant(number)),
        9 => (20, Postfix, MAction::Coolant(9)),
        6 | 66 => (30, Prefix, MAction::ToolChange),
        902 | 903 => (40, Prefix, MAction::Aux),
        905 => (40, Postfix, MAction::Aux),
        16 | 22 | 51 | 55 | 109 | 110 | 112 | 911 => (50, Postfix, MAction::Aux),
        17 | 21 | 50 | 54 | 108 | 111 | 910 => (50, Prefix, MAction::Aux),
        _ => return None,
    };
    Some(MFunction {
        number,
        order,
        timing,
        action,
    })
}

pub(super) fn set_speed(cx: &mut Ctx<'_>, spindle: u8, rpm: f64) -> Result<(), Diagnostic> {
    if rpm < 0.0 {
        return Err(cx.err(
            "axioma::negative-speed",
            "negative spindle speed S",
            cx.whole(),
        ));
    }
    cx.st.spindle_speed[spindle as usize] = rpm;
    cx.out.push(Canon::SetSpindleSpeed { spindle, rpm });
    Ok(())
}

pub(super) fn run_m(
    cx: &mut Ctx<'_>,
    f: &MFunction,
    s_done: &mut bool,
    s_word: Option<Val>,
    t_done: &mut bool,
    tool: Option<u32>,
    d: Option<Val>,
) -> Result<(), Diagnostic> {
    match f.action {
        MAction::Spindle {
            spindle,
            on,
            coolant,
        } => {
            if spindle == 0 && !*s_done {
                if let Some(s) = s_word {
                    set_speed(cx, 0, s.v)?;
                }
                *s_done = true;
            }
            if coolant {
                cx.st.flood = true;
                cx.out.push(Canon::Flood { on: true });
            }
            match on {
                Some(direction) => {
                    cx.st.spindle_on[spindle as usize] = true;
                    cx.out.push(Canon::StartSpindle { spindle, direction });
                }
                None => {
                    cx.st.spindle_on[spindle as usize] = false;
                    cx.out.push(Canon::StopSpindle { spindle });
                }
            }
        }
        MAction::Coolant(n) => cx.coolant(n),
        MAction::ToolChange => {
            if !*t_done {
                if let Some(t) = tool {
                    cx.st.selected_tool = Some(t);
                    cx.out.push(Canon::SelectTool { tool: t });
                }
                *t_done = true;
            }
            // Rules of spec axioma-2 §3.10: D alone (or T = the tool already in the spindle)
            // changes only the edge, without a tool-change cycle.
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
                cx.out.push(Canon::ChangeTool { tool: t });
                super::tools::tool_change(cx, Some(t), d)?;
            } else if !other_spindles_only {
                super::tools::tool_change(cx, tool, d)?;
            }
        }
        MAction::Aux => cx.out.push(Canon::AuxiliaryFunction {
            number: f.number,
            timing: f.timing,
        }),
        MAction::Stop { optional } => cx.out.push(Canon::ProgramStop { optional }),
        MAction::End | MAction::EndToWaitingPosition => cx.out.push(Canon::ProgramEnd),
    }
    Ok(())
}
