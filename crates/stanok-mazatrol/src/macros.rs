//! Custom macro blocks (`docs/dialects/mazatrol-eia.md` §14, §15): assignments to user and system
//! variables (#3000 alarms, #3006 messages, offsets), G65 / G66 / G66.1 / G67 calls, M98 / M99.
//! The calls themselves happen in `commit` (front.rs), after the block.

use crate::ctx::Ctx;
use crate::eval::writable;
use crate::flow::{CallKind, MAX_SUBPROGRAM_DEPTH};
use crate::front::Request;
use crate::macro_b::{variable_number, MVal};
use crate::modes::ModalCall;
use crate::rules::{sys_var, SysVar};
use crate::vars::MAX_MACRO_LEVELS;
use stanok_canon::{Canon, Diagnostic};
use stanok_syntax::{Address, ColSpan, CommentKind, ParamRef, Value};

/// The local variable of an argument letter (specification I), None for G L N O P.
pub fn argument_index(letter: u8) -> Option<usize> {
    Some(match letter {
        b'A' => 1,
        b'B' => 2,
        b'C' => 3,
        b'I' => 4,
        b'J' => 5,
        b'K' => 6,
        b'D' => 7,
        b'E' => 8,
        b'F' => 9,
        b'H' => 11,
        b'M' => 13,
        b'Q' => 17,
        b'R' => 18,
        b'S' => 19,
        b'T' => 20,
        b'U' => 21,
        b'V' => 22,
        b'W' => 23,
        b'X' => 24,
        b'Y' => 25,
        b'Z' => 26,
        _ => return None,
    })
}

/// The block's assignments, left to right (`docs` §15.4).
pub(crate) fn assignments(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    for i in 0..cx.block.assignments.len() {
        let a = cx.block.assignments[i];
        let ParamRef::Numbered(index) = a.target else {
            return Err(cx.err(
                "mazatrol::variable-range",
                "named parameters are not part of this language",
                a.span,
            ));
        };
        let (n, v) = {
            let env = cx.fe.env(cx.st);
            let n = env.value(cx.block, index)?;
            let at = cx.block.expr_span(index);
            let n = variable_number(n, at).map_err(|e| crate::eval::diag(cx.block, e))?;
            (n, env.value(cx.block, a.value)?)
        };
        write(cx, n, v, a.span)?;
    }
    Ok(())
}

/// The text of the comment right after `span` (the alarm or message of #3000 / #3006).
fn comment_after(cx: &Ctx<'_>, span: ColSpan) -> String {
    cx.block
        .comments
        .iter()
        .filter(|c| c.kind == CommentKind::Paren && c.text.start >= span.end)
        .map(|c| cx.block.slice(c.text).trim().to_string())
        .next()
        .unwrap_or_default()
}

/// mm of a program-unit value.
fn mm(cx: &Ctx<'_>, v: f64) -> f64 {
    cx.mm(v)
}

/// Writes variable `n`.
fn write(cx: &mut Ctx<'_>, n: u32, v: MVal, span: ColSpan) -> Result<(), Diagnostic> {
    if let Some(k) = writable(cx.block, n, span)? {
        cx.fe.vars.set(k, v);
        return Ok(());
    }
    let t = cx.fe.m.t();
    let Some(sv) = sys_var(n, t) else {
        return Err(cx.err(
            "mazatrol::variable-range",
            format!("#{n} is not a variable of this control"),
            span,
        ));
    };
    let x = v.unwrap_or(0.0);
    match sv {
        SysVar::Alarm => {
            let number = v.unwrap_or(0.0);
            if number.fract() != 0.0 || !(0.0..=999.0).contains(&number) {
                return Err(cx.err(
                    "mazatrol::value-range",
                    format!("#3000 = {number}: the alarm number is 0 … 999"),
                    span,
                ));
            }
            let text = comment_after(cx, span);
            Err(cx.err(
                "mazatrol::macro-alarm",
                format!("MACRO ALARM {}: {text}", 3000 + number as u32),
                span,
            ))
        }
        SysVar::Message => {
            let text = comment_after(cx, span);
            cx.out.push(Canon::Message { text });
            cx.out.push(Canon::ProgramStop { optional: false });
            Ok(())
        }
        SysVar::SingleBlock => Ok(()),
        SysVar::FeedControl => {
            let bits = x as u32;
            cx.out.push(Canon::SetFeedHoldEnabled {
                enabled: bits & 1 == 0,
            });
            cx.out.push(Canon::SetFeedOverrideEnabled {
                enabled: bits & 2 == 0,
            });
            Ok(())
        }
        SysVar::LengthWear(tool)
        | SysVar::LengthGeometry(tool)
        | SysVar::RadiusWear(tool)
        | SysVar::RadiusGeometry(tool) => {
            let v = mm(cx, x);
            cx.fe.tables.touch();
            let e = cx.fe.tables.edge_mut(tool);
            match sv {
                SysVar::LengthWear(_) => e.length_wear[0] = v,
                SysVar::LengthGeometry(_) => e.length[0] = v,
                SysVar::RadiusWear(_) => e.radius_wear = v,
                _ => e.radius = v,
            }
            Ok(())
        }
        SysVar::TurnWear(o, a) | SysVar::TurnGeometry(o, a) => {
            let wear = matches!(sv, SysVar::TurnWear(..));
            cx.fe.tables.touch();
            let turning = cx.fe.tables.is_turning(o) || cx.fe.tables.edge(o).is_none();
            let v = mm(cx, x);
            let e = cx.fe.tables.edge_mut(o);
            let (lx, lz) = if turning { (0, 1) } else { (usize::MAX, 0) };
            match a {
                0 if lx != usize::MAX => {
                    // X offsets are written on the diameter.
                    let slot = if wear {
                        &mut e.length_wear[lx]
                    } else {
                        &mut e.length[lx]
                    };
                    *slot = v / 2.0;
                }
                1 => {
                    let slot = if wear {
                        &mut e.length_wear[lz]
                    } else {
                        &mut e.length[lz]
                    };
                    *slot = v;
                }
                2 => {
                    if wear {
                        e.radius_wear = v;
                    } else {
                        e.radius = v;
                    }
                }
                3 => e.orientation = x.clamp(0.0, 9.0) as u8,
                _ => {}
            }
            if cx.fe.m.t_offset == o {
                crate::tools::set_turn_offset(cx, o);
            }
            Ok(())
        }
        SysVar::WorkOffset(_, i) | SysVar::ExtraOffset(_, i) if i < 6 => {
            let v = if i < 3 { mm(cx, x) } else { x };
            cx.fe.tables.touch();
            match sv {
                SysVar::WorkOffset(s2, _) => cx.fe.tables.set_work_offset(s2, i, v),
                SysVar::ExtraOffset(p, _) => cx.fe.tables.set_extra_offset(p as u8, i, v),
                _ => {}
            }
            crate::coords::apply_frame(cx)
        }
        _ => Err(cx.err(
            "mazatrol::read-only-variable",
            format!("#{n} can be read, not written"),
            span,
        )),
    }
}

/// The arguments of a call block, from its words as written (`docs` §15.7).
fn arguments(cx: &Ctx<'_>) -> Result<[MVal; 33], Diagnostic> {
    let mut args = [None; 33];
    let env = cx.fe.env(cx.st);
    for w in &cx.block.words {
        let Address::Letter(l) = w.address else {
            continue;
        };
        if matches!(l, b'G' | b'L' | b'N' | b'O' | b'P') {
            continue;
        }
        let Some(i) = argument_index(l) else {
            return Err(cx.err(
                "mazatrol::macro-call",
                format!("{} is not an argument address", l as char),
                w.span,
            ));
        };
        let v = match w.value {
            Value::Number(v) => Some(v),
            Value::Expr(e) => env.value(cx.block, e)?,
            _ => None,
        };
        args[i - 1] = v;
    }
    Ok(args)
}

/// Marks every word of a call block used (they are arguments).
fn consume_all(cx: &mut Ctx<'_>) {
    for l in b'A'..=b'Z' {
        cx.words.take(l);
    }
    cx.words.m.clear();
    cx.words.second = None;
}

fn repeats(cx: &mut Ctx<'_>) -> Result<u32, Diagnostic> {
    match cx.words.take(b'L') {
        Some(l) => {
            let n = cx.non_negative_integer(l, "L (repeats)")?;
            if n > 9999 {
                return Err(cx.err("mazatrol::value-range", "L is 0 … 9999", l.span));
            }
            Ok(n)
        }
        None => Ok(1),
    }
}

/// Only G65/G66 and their words in a call block.
fn only_call_code(cx: &Ctx<'_>, code: u32) -> Result<(), Diagnostic> {
    if let Some(&(other, span)) = cx.words.g.iter().find(|(c, _)| *c != code) {
        return Err(cx.err(
            "mazatrol::macro-call",
            format!(
                "{} takes only P, L and argument words; {} must be in another block",
                crate::codes::g_name(code),
                crate::codes::g_name(other)
            ),
            span,
        ));
    }
    Ok(())
}

/// G65 P L arguments.
pub(crate) fn simple_call(cx: &mut Ctx<'_>, _span: ColSpan) -> Result<(), Diagnostic> {
    only_call_code(cx, 650)?;
    if cx.fe.vars.level() >= MAX_MACRO_LEVELS {
        return Err(cx.err(
            "mazatrol::call-nesting",
            format!("macro calls nested deeper than {MAX_MACRO_LEVELS}"),
            cx.whole(),
        ));
    }
    let args = arguments(cx)?;
    let n = repeats(cx)?;
    consume_all(cx);
    let Some(target) = cx.fe.prepared.call.clone() else {
        return Err(cx.err("mazatrol::missing-word", "G65 needs P", cx.whole()));
    };
    cx.fe.request = Some(Request::Call {
        target,
        repeats: n,
        kind: CallKind::Macro,
        args: Some(Box::new(args)),
    });
    Ok(())
}

/// G66 / G66.1 P L arguments, G67.
pub(crate) fn modal_call(cx: &mut Ctx<'_>, code: u32, _span: ColSpan) -> Result<(), Diagnostic> {
    if code == 670 {
        cx.fe.m.modal_call = None;
        return Ok(());
    }
    only_call_code(cx, code)?;
    if cx.fe.m.modal_call.is_some() {
        return Err(cx.err(
            "mazatrol::macro-call",
            "G66 is already in force: cancel it with G67 first",
            cx.whole(),
        ));
    }
    let args = arguments(cx)?;
    let n = repeats(cx)?;
    let program = cx.words.take(b'P').map_or(0, |p| p.v as u32);
    consume_all(cx);
    cx.fe.m.modal_call = Some(ModalCall {
        every_block: code == 661,
        program,
        repeats: n,
        args,
        level: cx.fe.vars.level(),
    });
    Ok(())
}

/// G66: the call after a block that moved.
pub(crate) fn after_move_call(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    let Some(c) = cx.fe.m.modal_call else {
        return Ok(());
    };
    if c.every_block || c.level != cx.fe.vars.level() {
        return Ok(());
    }
    let Some(target) = cx.fe.prepared.call.clone() else {
        return Ok(());
    };
    if cx.fe.vars.level() >= MAX_MACRO_LEVELS {
        return Err(cx.err(
            "mazatrol::call-nesting",
            format!("macro calls nested deeper than {MAX_MACRO_LEVELS}"),
            cx.whole(),
        ));
    }
    cx.fe.request = Some(Request::Call {
        target,
        repeats: c.repeats,
        kind: CallKind::Macro,
        args: Some(Box::new(c.args)),
    });
    Ok(())
}

/// G66.1: the block is not executed; its words are the arguments of the call.
pub(crate) fn every_block_call(
    cx: &mut Ctx<'_>,
) -> Result<stanok_interp_core::Outcome, Diagnostic> {
    if cx.words.g.iter().any(|(c, _)| *c == 670) {
        cx.fe.m.modal_call = None;
        cx.words.g.clear();
        return Ok(stanok_interp_core::Outcome::Continue);
    }
    let Some(c) = cx.fe.m.modal_call else {
        return Ok(stanok_interp_core::Outcome::Continue);
    };
    let args = arguments(cx)?;
    consume_all(cx);
    cx.words.g.clear();
    let Some(target) = cx.fe.prepared.call.clone() else {
        return Ok(stanok_interp_core::Outcome::Continue);
    };
    cx.fe.request = Some(Request::Call {
        target,
        repeats: c.repeats,
        kind: CallKind::Macro,
        args: Some(Box::new(args)),
    });
    Ok(stanok_interp_core::Outcome::Continue)
}

/// M98 P H L.
pub(crate) fn subprogram_call(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    cx.words.take(b'P');
    cx.words.take(b'H');
    let n = repeats(cx)?;
    if cx.fe.sub_depth >= MAX_SUBPROGRAM_DEPTH {
        return Err(cx.err(
            "mazatrol::call-nesting",
            format!("subprogram calls nested deeper than {MAX_SUBPROGRAM_DEPTH}"),
            span,
        ));
    }
    let Some(target) = cx.fe.prepared.call.clone() else {
        return Err(cx.err("mazatrol::missing-word", "M98 needs P", span));
    };
    cx.fe.request = Some(Request::Call {
        target,
        repeats: n,
        kind: CallKind::Subprogram,
        args: None,
    });
    Ok(())
}

/// M99 (P n).
pub(crate) fn subprogram_return(cx: &mut Ctx<'_>, _span: ColSpan) -> Result<(), Diagnostic> {
    cx.words.take(b'P');
    cx.fe.request = Some(Request::Return(cx.fe.prepared.ret));
    Ok(())
}
