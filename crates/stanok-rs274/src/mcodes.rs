//! RS274/NGC M codes: LinuxCNC's steps 5a–7 of a block (`before_dwell`: I/O, M6/M61, spindle,
//! M70–M73, coolant, M19, overrides, user codes), with M19 spindle orientation, M48–M53 override
//! and feed-hold switches, M61 (declare the loaded tool), M62–M65 digital outputs and M66 wait on
//! an input (spec rs274ngc §5; LinuxCNC 2.9's `rs274` for what it prints). The stops (step 21)
//! stay in `execute`.
//!
//! Where they run in a line (LinuxCNC's order of execution): M62–M66 after T and before M6/M61,
//! M19 with the spindle codes, M48–M53 after coolant and before the user M codes. [`classify_m`]
//! sorts a block's M words into LinuxCNC's modal groups for `execute`.

use super::{unsupported, NO_CODE};
use crate::ctx::Ctx;
use crate::params::Parameters;
use stanok_canon::{Canon, Diagnostic, SpindleDirection};
use stanok_syntax::ColSpan;

/// Most I/O index a program may address (LinuxCNC's default `num_dio`/`num_aio` is 4; machines
/// raise it up to 64).
const MAX_IO: f64 = 63.0;

fn index_word(cx: &mut Ctx<'_>, letter: u8, code: u32, span: ColSpan) -> Result<u32, Diagnostic> {
    match cx.words.take(letter) {
        Some(v) if v.v >= 0.0 && v.v <= MAX_IO && v.v.fract() == 0.0 => Ok(v.v as u32),
        Some(v) => Err(cx.err(
            "rs274::io-index",
            format!("Invalid {} value with M{code}", letter as char),
            v.span,
        )),
        None => Err(cx.err(
            "rs274::io-index-missing",
            format!("No valid {} word with M{code}", letter as char),
            span,
        )),
    }
}

/// M62/M63 (with the next motion) and M64/M65 (now): set or clear a digital output; M66: wait for
/// an input (P digital, E analogue; L mode 0 immediate … 4 low; Q timeout).
pub(super) fn io(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    match code {
        62..=65 => {
            let index = index_word(cx, b'P', code, span)?;
            cx.out.push(Canon::DigitalOutput {
                index,
                on: code == 62 || code == 64,
                synchronised: code <= 63,
            });
        }
        _ => {
            let analog = cx.words.has(b'E');
            if analog && cx.words.has(b'P') {
                return Err(cx.err(
                    "rs274::m66-p-and-e",
                    "Both digital and analog inputs selected",
                    span,
                ));
            }
            let index = index_word(cx, if analog { b'E' } else { b'P' }, code, span)?;
            let mode = match cx.words.take(b'L') {
                Some(l) if (0.0..=4.0).contains(&l.v) && l.v.fract() == 0.0 => l.v as u8,
                Some(l) => {
                    return Err(cx.err("rs274::m66-l", "Unknown wait type in M66", l.span));
                }
                None => 0,
            };
            if analog && mode != 0 {
                return Err(cx.err(
                    "rs274::m66-analog-wait",
                    "Can't select analog input with wait type != immediate return",
                    span,
                ));
            }
            let timeout = cx.words.take(b'Q').map_or(0.0, |q| q.v);
            if timeout < 0.0 {
                return Err(cx.err("rs274::m66-q", "Negative Q value with M66", span));
            }
            cx.out.push(Canon::WaitInput {
                index,
                analog,
                mode,
                timeout,
            });
        }
    }
    Ok(())
}

/// M19 R (angle) Q (timeout) P (direction 0/1/2). LinuxCNC orients when R or P is given (to
/// angle 0 without R), waits when Q is (Q must be positive), and in any case takes the spindle
/// for stopped (G33, G76, the cycles that need it turning refuse to run until M3/M4) without a
/// stop command.
pub(super) fn orient(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let r = cx.words.take(b'R');
    let q = cx.words.take(b'Q');
    let p = cx.words.take(b'P');
    let direction = match p {
        Some(p) if [0.0, 1.0, 2.0].contains(&p.v) => p.v as u8,
        Some(p) => return Err(cx.err("rs274::m19-p", "M19 P must be 0, 1 or 2", p.span)),
        None => 0,
    };
    let _ = span;
    cx.fe.modes.spindle_direction = None;
    if let Some(q) = q.filter(|q| q.v <= 0.0) {
        return Err(cx.err(
            "rs274::m19-q",
            "Q word with M19 requires a value > 0",
            q.span,
        ));
    }
    // With R or P LinuxCNC orients (and waits Q); Q alone waits for an orientation it does not
    // command; M19 alone does nothing but stop the spindle's sense.
    if r.is_some() || p.is_some() {
        cx.out.push(Canon::OrientSpindle {
            spindle: 0,
            degrees: r.map_or(0.0, |r| r.v),
            direction,
            timeout: q.map(|q| q.v),
        });
    } else if let Some(q) = q {
        cx.out.push(Canon::WaitSpindleOrient {
            spindle: 0,
            timeout: q.v,
        });
    }
    Ok(())
}

/// M48 (all overrides on), M49 (off), M50 P (feed), M51 P (spindle), M52 P (adaptive feed),
/// M53 P (feed hold input): P0 disables, any other P or no P enables (LinuxCNC 2.9: `M52 P10`
/// and `M51 P-1` enable).
pub(super) fn overrides(cx: &mut Ctx<'_>, code: u32) -> Result<(), Diagnostic> {
    let enabled = match code {
        48 => true,
        49 => false,
        _ => cx.words.take(b'P').is_none_or(|p| p.v != 0.0),
    };
    if matches!(code, 48..=50) {
        cx.fe.modes.feed_override_disabled = !enabled;
        cx.out.push(Canon::SetFeedOverrideEnabled { enabled });
    }
    if matches!(code, 48 | 49 | 51) {
        cx.fe.modes.speed_override_disabled = !enabled;
        cx.out.push(Canon::SetSpindleOverrideEnabled {
            spindle: 0,
            enabled,
        });
    }
    match code {
        52 => cx.out.push(Canon::SetAdaptiveFeed { enabled }),
        53 => cx.out.push(Canon::SetFeedHoldEnabled { enabled }),
        _ => {}
    }
    Ok(())
}

/// M61 Q: the spindle holds tool Q from now on, without a tool change.
pub(super) fn set_tool_number(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let Some(q) = cx.words.take(b'Q') else {
        return Err(cx.err("rs274::m61-q-missing", "Q word missing with M61", span));
    };
    // LinuxCNC rounds Q to the nearest tool number (`M61 Q1.5` is tool 2).
    let rounded = q.v.round();
    if rounded < 0.0 || rounded > u32::MAX as f64 {
        return Err(cx.err(
            "rs274::m61-q",
            "Need non-negative Q-word to specify tool number with M61",
            q.span,
        ));
    }
    let tool = rounded as u32;
    let slot = if tool == 0 {
        0
    } else {
        match params.tool_slot(tool) {
            Some(s) => s,
            None => {
                return Err(cx.err(
                    "rs274::tool-not-found",
                    format!("Requested tool {tool} not found in the tool table"),
                    q.span,
                ))
            }
        }
    };
    cx.st.current_tool = tool;
    cx.st.selected_tool = Some(tool);
    super::tools::load_tool_parameters(params, tool);
    cx.out.push(Canon::SetCurrentTool { tool, slot });
    Ok(())
}

/// Steps 5a–7 of LinuxCNC's order of execution: M62–M66, M6, M61, the spindle, M70–M73, coolant,
/// M19, M48–M53 and the user M codes.
#[inline(never)]
pub(super) fn before_dwell(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    m: &MCodes,
) -> Result<(), Diagnostic> {
    // 5a. HAL I/O: M62–M66.
    for &(code, span) in &m.io[..m.n_io] {
        io(cx, code, span)?;
    }
    // 6. M6, M61.
    if m.tool_change {
        super::tools::change_tool(cx, params);
        cx.fe.modes.spindle_direction = None;
        // LinuxCNC resynchronises its position after a tool change: a programmed point left
        // over from cutter compensation is forgotten.
        if !cx.fe.modes.comp.on() {
            cx.fe.modes.comp.program = None;
        }
    }
    if let Some(span) = m.set_tool {
        set_tool_number(cx, params, span)?;
    }
    // Both reread the position from the machine before the next block (`TapApart`).
    if m.tool_change || m.set_tool.is_some() {
        if let Some(apart) = &mut cx.fe.modes.tap_apart {
            apart.reread = true;
        }
    }
    // 7. Spindle, coolant, user M codes.
    if m.spindle != NO_CODE {
        let code = m.spindle;
        match code {
            3 | 4 => {
                let direction = if code == 3 {
                    SpindleDirection::Clockwise
                } else {
                    SpindleDirection::CounterClockwise
                };
                cx.st.spindle_on[0] = true;
                cx.fe.modes.spindle_direction = Some(direction);
                cx.out.push(Canon::StartSpindle {
                    spindle: 0,
                    direction,
                });
            }
            _ => {
                cx.st.spindle_on[0] = false;
                cx.fe.modes.spindle_direction = None;
                cx.out.push(Canon::StopSpindle { spindle: 0 });
            }
        }
    }
    // 7a. M70–M73: save, forget, restore the modal state.
    if let Some((code, span)) = m.context {
        super::modal_context::m70_73(cx, params, code, span)?;
    }
    for &code in &m.coolant[..m.n_coolant] {
        cx.coolant(code);
    }
    if let Some(span) = m.orient {
        orient(cx, span)?;
    }
    for &code in &m.overrides[..m.n_overrides] {
        overrides(cx, code)?;
    }
    for &code in &m.user[..m.n_user] {
        cx.out.push(Canon::AuxiliaryFunction {
            number: code,
            timing: stanok_canon::AuxTiming::Prefix,
        });
    }
    Ok(())
}

/// M codes by LinuxCNC's modal groups: stopping (4), tool change (6), spindle (7), coolant (8),
/// user-defined (M100–M199). Plain fields with a sentinel: this runs for every block.
pub(super) struct MCodes {
    pub(super) stop: u32,
    pub(super) stop_span: ColSpan,
    pub(super) tool_change: bool,
    pub(super) spindle: u32,
    /// Coolant codes in written order (at most four M words per line).
    pub(super) coolant: [u32; 4],
    pub(super) n_coolant: usize,
    pub(super) user: [u32; 4],
    pub(super) n_user: usize,
    /// M62–M66 in written order.
    pub(super) io: [(u32, ColSpan); 4],
    pub(super) n_io: usize,
    /// M48–M53 in written order.
    pub(super) overrides: [u32; 4],
    pub(super) n_overrides: usize,
    /// M19.
    pub(super) orient: Option<ColSpan>,
    /// M70–M73.
    pub(super) context: Option<(u32, ColSpan)>,
    /// M61.
    pub(super) set_tool: Option<ColSpan>,
}

#[inline(always)]
pub(super) fn classify_m(cx: &Ctx<'_>) -> Result<MCodes, Diagnostic> {
    let mut m = MCodes {
        stop: NO_CODE,
        stop_span: ColSpan::default(),
        tool_change: false,
        spindle: NO_CODE,
        coolant: [0; 4],
        n_coolant: 0,
        user: [0; 4],
        n_user: 0,
        io: [(0, ColSpan::default()); 4],
        n_io: 0,
        overrides: [0; 4],
        n_overrides: 0,
        orient: None,
        context: None,
        set_tool: None,
    };
    if cx.words.m.len() > 4 {
        return Err(cx.err(
            "rs274::too-many-m-codes",
            "Too many m codes on line",
            cx.words.m[4].1,
        ));
    }
    // LinuxCNC's modal group 7 holds M3–M5, M19 and M70–M73: two of them on a line are refused.
    let mut group7 = false;
    for &(code, span) in &cx.words.m {
        let taken = match code {
            3..=5 | 19 | 70..=73 if std::mem::replace(&mut group7, true) => true,
            0 | 1 | 2 | 30 | 60 => {
                let t = m.stop != NO_CODE;
                m.stop = code;
                m.stop_span = span;
                t
            }
            6 => std::mem::replace(&mut m.tool_change, true) || m.set_tool.is_some(),
            3..=5 => std::mem::replace(&mut m.spindle, code) != NO_CODE || m.orient.is_some(),
            // M7, M8 and M9 are one group in LinuxCNC 2.9: `M7 M8` on one line is refused.
            7..=9 => {
                m.coolant[m.n_coolant] = code;
                m.n_coolant += 1;
                m.n_coolant > 1
            }
            100..=199 if cx.fe.opts.user_m_codes => {
                m.user[m.n_user] = code;
                m.n_user += 1;
                m.n_user > 1
            }
            19 => m.orient.replace(span).is_some() || m.spindle != NO_CODE,
            61 => m.set_tool.replace(span).is_some() || m.tool_change,
            62..=66 => {
                m.io[m.n_io] = (code, span);
                m.n_io += 1;
                m.n_io > 1
            }
            48..=53 => {
                m.overrides[m.n_overrides] = code;
                m.n_overrides += 1;
                m.n_overrides > 1
            }
            70..=73 => m.context.replace((code, span)).is_some(),
            67 | 68 => {
                return Err(unsupported(
                    cx,
                    &format!("M{code}"),
                    "RS274/NGC completeness",
                    span,
                ))
            }
            _ if code > 199 => {
                return Err(cx.err(
                    "rs274::unknown-m-code",
                    format!("M-code greater than 199: M{code}"),
                    span,
                ))
            }
            _ => {
                return Err(cx.err(
                    "rs274::unknown-m-code",
                    format!("Unknown m code used: M{code}"),
                    span,
                ))
            }
        };
        if taken {
            return Err(cx.err(
                "rs274::two-m-codes-same-group",
                "Two m codes used from same modal group",
                span,
            ));
        }
    }
    Ok(m)
}
