//! Spindle, coolant and the auxiliary functions (`docs/dialects/mazatrol-eia.md` §9, §13):
//! S with G96/G97 and the G50 S clamp, M03/M04/M05 (the turning spindle), M203/M204/M205 (the
//! T-series milling spindle), M19, machine M codes, program end, and the one-system codes G109,
//! G110/G111, G112.

use crate::block::{turning_of, Codes};
use crate::ctx::Ctx;
use crate::modes::Turning;
use stanok_canon::{AuxTiming, Canon, Diagnostic, SpindleDirection, SurfaceSpeedLaw};
use stanok_syntax::ColSpan;

/// Spindle 1: the T-series milling spindle.
const MILL: u8 = 1;

/// Which spindle the block's S and spindle codes are for: the milling spindle when the block has
/// M203/M204/M205 (T), else the main one [D].
fn spindle_of_block(cx: &Ctx<'_>) -> u8 {
    let mill = cx.fe.m.t() && cx.words.m.iter().any(|(m, _)| matches!(m, 203..=205));
    if mill {
        MILL
    } else {
        0
    }
}

/// S, G96/G97 and G50 S (`docs` §7.4, §9).
pub(crate) fn speed(cx: &mut Ctx<'_>, codes: &Codes) -> Result<(), Diagnostic> {
    let g50 = cx.fe.m.t() && codes.one_shot.iter().any(|(c, _)| *c == 500);
    let css_on = codes.modal.iter().any(|(c, _, _)| *c == 960);
    let css_off = codes.modal.iter().any(|(c, _, _)| *c == 970);
    let s = cx.words.take(b'S');
    if let Some(s) = s {
        if s.v < 0.0 {
            return Err(cx.err("mazatrol::value-range", "S must not be negative", s.span));
        }
    }
    if g50 {
        // G50 S: the clamp; the S word is consumed here.
        if let Some(s) = s {
            cx.fe.m.rpm_clamp = Some(s.v);
            if cx.fe.m.css.is_some() {
                publish_css(cx);
            }
        }
        if !css_on && !css_off {
            return Ok(());
        }
    }
    let spindle = spindle_of_block(cx);
    if css_on {
        let v = match (s, cx.fe.m.css) {
            (Some(s), _) if !g50 => s.v,
            (_, Some(v)) => v,
            _ => {
                return Err(cx.err(
                    "mazatrol::spindle",
                    "G96 needs a surface speed S",
                    codes
                        .modal
                        .iter()
                        .find(|(c, _, _)| *c == 960)
                        .map_or(cx.whole(), |x| x.2),
                ))
            }
        };
        cx.fe.m.css = Some(v);
        cx.out.push(Canon::SetSpindleMode {
            spindle: 0,
            constant_surface_speed: true,
            max_rpm: cx.fe.m.rpm_clamp.unwrap_or(0.0),
        });
        publish_css(cx);
        return Ok(());
    }
    if css_off {
        cx.fe.m.css = None;
        cx.out.push(Canon::SetSpindleMode {
            spindle: 0,
            constant_surface_speed: false,
            max_rpm: 0.0,
        });
        cx.out.push(Canon::SetSurfaceSpeedLaw {
            spindle: 0,
            law: None,
        });
    }
    let Some(s) = s.filter(|_| !g50) else {
        return Ok(());
    };
    if cx.fe.m.css.is_some() && spindle == 0 {
        cx.fe.m.css = Some(s.v);
        publish_css(cx);
        return Ok(());
    }
    let rpm = s.v;
    cx.st.spindle_speed[spindle as usize] = rpm;
    cx.out.push(Canon::SetSpindleSpeed { spindle, rpm });
    Ok(())
}

/// The G96 law of the main spindle as Canon, and the speed at the current position.
pub(crate) fn publish_css(cx: &mut Ctx<'_>) {
    let Some(v) = cx.fe.m.css else {
        return;
    };
    let metres = match cx.st.units {
        stanok_canon::LengthUnits::Inches => v * 12.0 * 25.4,
        stanok_canon::LengthUnits::Millimetres => v * 1000.0,
    };
    // The radius is the control point's distance from the spindle axis: the machine X of
    // program X = 0.
    let zero = cx.st.frame.to_machine(&stanok_canon::Pose::ZERO);
    let law = SurfaceSpeedLaw {
        mm_per_min: metres,
        axis: 0,
        centre: zero.x,
        min_rpm: 0.0,
        max_rpm: cx.fe.m.rpm_clamp.unwrap_or(0.0),
    };
    let rpm = law.rpm_at(&cx.st.position.to_array());
    cx.out.push(Canon::SetSurfaceSpeedLaw {
        spindle: 0,
        law: Some(law),
    });
    cx.st.spindle_speed[0] = rpm;
    cx.out.push(Canon::SetSpindleSpeed { spindle: 0, rpm });
}

/// After a block that moved under G96: the speed at the new position (the value a screen shows;
/// the motion follows the law itself).
pub(crate) fn refresh_css(cx: &mut Ctx<'_>) {
    let Some(v) = cx.fe.m.css else {
        return;
    };
    let metres = match cx.st.units {
        stanok_canon::LengthUnits::Inches => v * 12.0 * 25.4,
        stanok_canon::LengthUnits::Millimetres => v * 1000.0,
    };
    let zero = cx.st.frame.to_machine(&stanok_canon::Pose::ZERO);
    let law = SurfaceSpeedLaw {
        mm_per_min: metres,
        axis: 0,
        centre: zero.x,
        min_rpm: 0.0,
        max_rpm: cx.fe.m.rpm_clamp.unwrap_or(0.0),
    };
    let rpm = law.rpm_at(&cx.st.position.to_array());
    if (rpm - cx.st.spindle_speed[0]).abs() > 1e-9 {
        cx.st.spindle_speed[0] = rpm;
        cx.out.push(Canon::SetSpindleSpeed { spindle: 0, rpm });
    }
}

/// M03 / M04 / M203 / M204.
pub(crate) fn start(cx: &mut Ctx<'_>, m: u32, _span: ColSpan) -> Result<(), Diagnostic> {
    let spindle = if matches!(m, 203 | 204) { MILL } else { 0 };
    if spindle == MILL && !cx.fe.m.t() {
        return Ok(());
    }
    let direction = if matches!(m, 3 | 203) {
        SpindleDirection::Clockwise
    } else {
        SpindleDirection::CounterClockwise
    };
    cx.st.spindle_on[spindle as usize] = true;
    if spindle == MILL {
        cx.fe.m.mill_spindle = turning_of(m);
    } else {
        cx.fe.m.spindle = turning_of(m);
    }
    cx.out.push(Canon::StartSpindle { spindle, direction });
    Ok(())
}

/// M05 / M205.
pub(crate) fn stop(cx: &mut Ctx<'_>, m: u32) {
    let spindle = if m == 205 { MILL } else { 0 };
    cx.st.spindle_on[spindle as usize] = false;
    if spindle == MILL {
        cx.fe.m.mill_spindle = Turning::Stopped;
    } else {
        cx.fe.m.spindle = Turning::Stopped;
    }
    cx.out.push(Canon::StopSpindle { spindle });
}

/// The spindle the cycles drive: the milling spindle on the T-series when it turns, else main.
pub(crate) fn cycle_spindle(cx: &Ctx<'_>) -> (u8, Turning) {
    if cx.fe.m.t() && cx.fe.m.mill_spindle != Turning::Stopped {
        (MILL, cx.fe.m.mill_spindle)
    } else {
        (0, cx.fe.m.spindle)
    }
}

/// Emits a spindle state (the cycles' reverse and restore).
pub(crate) fn set(cx: &mut Ctx<'_>, spindle: u8, t: Turning) {
    match t {
        Turning::Stopped => cx.out.push(Canon::StopSpindle { spindle }),
        Turning::Cw | Turning::Ccw => cx.out.push(Canon::StartSpindle {
            spindle,
            direction: if t == Turning::Cw {
                SpindleDirection::Clockwise
            } else {
                SpindleDirection::CounterClockwise
            },
        }),
    }
}

/// M19: orient the spindle at S degrees (0 without S) [D].
pub(crate) fn orient(cx: &mut Ctx<'_>, _span: ColSpan) -> Result<(), Diagnostic> {
    let degrees = cx.words.take(b'S').map_or(0.0, |s| s.v);
    cx.out.push(Canon::OrientSpindle {
        spindle: 0,
        degrees,
        direction: 0,
        timeout: None,
    });
    Ok(())
}

/// M02 / M30: spindles and coolant stop, TTPC is reset (`docs` §3.4).
pub(crate) fn program_end(cx: &mut Ctx<'_>) {
    crate::ttpc::reset(cx);
    for s in 0..2u8 {
        if cx.st.spindle_on[s as usize] {
            cx.st.spindle_on[s as usize] = false;
            cx.out.push(Canon::StopSpindle { spindle: s });
        }
    }
    if cx.st.mist || cx.st.flood {
        cx.coolant(9);
    }
    let series = cx.fe.m.series;
    *cx.fe.m = crate::modes::Modes::power_on(series);
}

/// A machine M code: passed on, with a warning the first time [D].
pub(crate) fn machine_m(cx: &mut Ctx<'_>, m: u32, span: ColSpan) {
    cx.out.push(Canon::AuxiliaryFunction {
        number: m,
        timing: AuxTiming::Postfix,
    });
    let (i, bit) = ((m / 64) as usize, m % 64);
    let seen = cx
        .fe
        .once
        .m_codes
        .get(i)
        .is_some_and(|w| w & (1 << bit) != 0);
    if !seen {
        if let Some(w) = cx.fe.once.m_codes.get_mut(i) {
            *w |= 1 << bit;
        }
        cx.warnings.push(Diagnostic::warning(
            "mazatrol::machine-m-code",
            format!("M{m} is a machine function: passed on to the machine, no effect simulated"),
            cx.block.span_of(span),
        ));
    }
}

/// G110 / G111 / G109 / G112 warn once: Stanok simulates one system.
pub(crate) fn single_system(cx: &mut Ctx<'_>, span: ColSpan) {
    if !cx.fe.once.single_system {
        cx.fe.once.single_system = true;
        cx.warnings.push(Diagnostic::warning(
            "mazatrol::single-system",
            "Stanok simulates one system: two-system codes (G109, G110/G111, G112) act on it alone",
            cx.block.span_of(span),
        ));
    }
}

/// G109 L n: the process sequence (1 or 2), run one after the other [D].
pub(crate) fn sequence(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let l = cx.words.take(b'L');
    let n = match l {
        Some(v) if v.v == 1.0 || v.v == 2.0 => v.v as u8,
        Some(v) => {
            return Err(cx.err(
                "mazatrol::value-range",
                format!("G109 L{}: the process sequence is 1 or 2", v.v),
                v.span,
            ))
        }
        None => return Err(cx.err("mazatrol::missing-word", "G109 needs L (1 or 2)", span)),
    };
    cx.fe.m.sequence = n;
    single_system(cx, span);
    Ok(())
}

/// G112: the block's M, S, T are for the other system: a comment, no effect here [D].
pub(crate) fn opposite_system(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let mut parts = Vec::new();
    for (m, _) in cx.words.m.drain(..) {
        parts.push(format!("M{m}"));
    }
    for l in [b'S', b'T', b'B'] {
        if let Some(v) = cx.words.take(l) {
            parts.push(format!("{}{}", l as char, v.v));
        }
    }
    cx.out.push(Canon::Comment {
        text: format!("to system 2: {}", parts.join(" ")),
    });
    single_system(cx, span);
    Ok(())
}
