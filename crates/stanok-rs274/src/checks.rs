//! Checks LinuxCNC makes on a block before it runs any of it, kept apart from the order of
//! execution in `lib.rs`: a motion code without axis words, the `$` spindle-selection word and the
//! L word of G74/G33.1.

use crate::codes::*;
use crate::ctx::Ctx;
use crate::{GCodes, Group};
use stanok_canon::Diagnostic;
use stanok_interp_core::words::Val;

/// LinuxCNC's `enhance_block`, right after reading: a motion code written in the block needs an
/// axis (or polar) word, except G0–G3, G5.2 and the G7x lathe cycles — so `G33 K1`, `G5 …`,
/// `G38.2 F1`, `G76 …` or a canned cycle without one are refused before their own word checks.
/// The test inlined (G0/G1 pass at once), the check out of line.
#[inline(always)]
pub(super) fn motion_axes(cx: &Ctx<'_>, g: &GCodes) -> Result<(), Diagnostic> {
    match g.get(Group::Motion, cx) {
        None | Some((G0 | G1 | G2 | G3 | G80, _)) => Ok(()),
        Some((code, span)) => motion_axes_cold(cx, code, span),
    }
}

#[cold]
#[inline(never)]
fn motion_axes_cold(
    cx: &Ctx<'_>,
    code: u32,
    span: stanok_syntax::ColSpan,
) -> Result<(), Diagnostic> {
    let exempt = matches!(code, G5_2 | G70 | G71 | G71_1 | G71_2 | G72 | G72_1 | G72_2);
    if exempt || cx.has_axis_words() {
        return Ok(());
    }
    Err(cx.err(
        "rs274::motion-axes-missing",
        "All axes missing with motion code",
        span,
    ))
}

/// LinuxCNC checks a block's L word before it runs anything: G74 (left-hand tapping) and G33.1
/// take none, unlike the other canned cycles (`G74 … L2` is refused even with the spindle the
/// wrong way round, which the cycle itself would report).
/// The test inlined, the check out of line: most blocks have no L word.
#[inline(always)]
pub(super) fn l_word_check(cx: &Ctx<'_>, g: &GCodes) -> Result<(), Diagnostic> {
    match cx.words.peek(b'L') {
        None => Ok(()),
        Some(l) => l_word_check_cold(cx, g, l),
    }
}

#[cold]
#[inline(never)]
fn l_word_check_cold(cx: &Ctx<'_>, g: &GCodes, l: Val) -> Result<(), Diagnostic> {
    let motion = match g.get(Group::Motion, cx) {
        Some((code, _)) => Some(code),
        None if cx.has_axis_words() => cx.fe.modes.motion_code,
        None => None,
    };
    let other_user = g.get(Group::NonModal, cx).is_some_and(|(c, _)| c == G10)
        || g.get(Group::CutterComp, cx).is_some()
        || cx.words.m.iter().any(|&(c, _)| c == 66);
    if matches!(motion, Some(G74 | G33_1)) && !other_user {
        return Err(cx.err(
            "interp::unused-word",
            "L word with no G10, cutter compensation, canned cycle, digital/analog input, M98 or NURBS code",
            l.span,
        ));
    }
    Ok(())
}

/// LinuxCNC's `$` word selects the spindle of S, M3–M5, M19, M51, G33, G33.1, G76 and G95–G97.
/// The `linuxcnc` machine has one spindle: `$0` (or `$-1`, all of them) changes nothing, any other
/// number is refused with the message of the first word that would use it (S before the M codes,
/// as LinuxCNC checks them), and a `$` nothing uses is refused.
/// The test inlined, the check out of line: most blocks have no `$` word.
#[inline(always)]
pub(super) fn spindle_selection(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    match cx.words.take(b'$') {
        None => Ok(()),
        Some(sel) => spindle_selection_cold(cx, sel),
    }
}

#[cold]
#[inline(never)]
fn spindle_selection_cold(cx: &mut Ctx<'_>, sel: Val) -> Result<(), Diagnostic> {
    let m_user = cx
        .words
        .m
        .iter()
        .find(|(c, _)| matches!(c, 3 | 4 | 5 | 19 | 51))
        .map(|&(c, _)| c);
    let g_user = cx
        .words
        .g
        .iter()
        .any(|(c, _)| matches!(*c, G33 | G33_1 | G76 | G95 | G96 | G97));
    let s_user = cx.words.has(b'S');
    if m_user.is_none() && !g_user && !s_user {
        return Err(cx.err(
            "rs274::spindle-word-unused",
            "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G76, G95, G96 or G97 to use it",
            sel.span,
        ));
    }
    let n = sel.v.trunc();
    if n == 0.0 || n == -1.0 {
        return Ok(());
    }
    let msg = match m_user {
        _ if s_user => "Invalid spindle ($) number in Spindle speed command".to_string(),
        Some(c) => format!("Spindle ($) number out of range in M{c} Command"),
        None => "Spindle ($) number out of range".to_string(),
    };
    Err(cx.err("rs274::spindle-number", msg, sel.span))
}
