//! AxiOMA frame and offset functions (spec axioma-1 §9–§12, §14): table zero offsets G53/G54…G59
//! with pages, table workpiece systems G153/G154…G159 with pages, mirror G72/G73, scale G172/G173,
//! rotation G272/G273 with their poles, programmed shift G193/G194/G195, and G10 radius/diameter
//! programming.
//!
//! Each function updates `ModalState::axioma` and then recomposes the work frame. The current
//! position stays where the machine is; the program position is recomputed through the inverse of
//! the new chain (spec §8.2 — automatic, because the state keeps the machine position).
//!
//! Poles are resolved in the block that programs the function, with the program position *before*
//! the change (§8.2): G190 → the letter's value, G191 → current position + value; an omitted letter
//! → the current position. G90/G91 do not make a pole relative (examples 4.5/4.6).

use crate::codes::{G193, G194};
use crate::ctx::Ctx;
use crate::state::DistanceMode;
use crate::words::Val;
use stanok_canon::Diagnostic;
use stanok_syntax::ColSpan;

const XYZ: [u8; 3] = [b'X', b'Y', b'Z'];
const IJK: [u8; 3] = [b'I', b'J', b'K'];

/// Rejects words other than `allowed` (plus F, S, T, M-related ones handled elsewhere) in a block
/// that programs a frame: its X/Y/Z are factors or shift values, not a motion.
fn only(cx: &mut Ctx<'_>, allowed: &[u8], what: &str) -> Result<(), Diagnostic> {
    for l in [
        b'X', b'Y', b'Z', b'A', b'B', b'C', b'U', b'V', b'W', b'I', b'J', b'K', b'P', b'Q', b'R',
    ] {
        if cx.words.has(l) && !allowed.contains(&l) && !cx.words.is_used(l) {
            let v = cx.words.take(l).map(|v| v.span).unwrap_or_default();
            return Err(cx.err(
                "axioma::frame-block-word",
                format!("{} has no meaning in a {what} block", l as char),
                v,
            ));
        }
    }
    Ok(())
}

/// The pole of a frame function: per axis X, Y, Z.
fn pole(cx: &mut Ctx<'_>) -> [f64; 3] {
    let cur = cx.st.program_position().xyz();
    let mut p = cur;
    for k in 0..3 {
        if let Some(v) = cx.words.take(IJK[k]) {
            let mm = cx.mm(v.v);
            p[k] = match cx.st.arc_distance {
                DistanceMode::Absolute => mm,
                DistanceMode::Incremental => cur[k] + mm,
            };
        }
    }
    p
}

/// G72 / G73: per-axis inversion (±1) about the pole (spec §11.2). Per-axis state: an axis not
/// named keeps its inversion (ambiguity A1, the text's reading).
pub(super) fn mirror(cx: &mut Ctx<'_>, on: bool) -> Result<(), Diagnostic> {
    if !on {
        cx.fe.chain.mirror = [1.0; 3];
        return Ok(());
    }
    let pole = pole(cx);
    for (k, &l) in XYZ.iter().enumerate() {
        if let Some(v) = cx.words.take(l) {
            if v.v != 1.0 && v.v != -1.0 {
                return Err(cx.err(
                    "axioma::mirror-factor",
                    format!(
                        "G73 {}: a mirror factor is +1 or -1, not {}",
                        l as char, v.v
                    ),
                    v.span,
                ));
            }
            cx.fe.chain.mirror[k] = v.v;
            cx.fe.chain.mirror_pole[k] = pole[k];
        }
    }
    only(cx, &[], "G73")
}

/// G172 / G173: per-axis factors > 0, or `P` for all three, about the pole (spec §11.3).
pub(super) fn scale(cx: &mut Ctx<'_>, on: bool) -> Result<(), Diagnostic> {
    if !on {
        cx.fe.chain.scale = [1.0; 3];
        return Ok(());
    }
    let pole = pole(cx);
    let uniform = cx.words.take(b'P');
    let factors: [Option<Val>; 3] = [
        cx.words.take(b'X'),
        cx.words.take(b'Y'),
        cx.words.take(b'Z'),
    ];
    if let (Some(p), true) = (uniform, factors.iter().any(Option::is_some)) {
        return Err(cx.err(
            "axioma::scale-p-and-axes",
            "G173 with P and axis factors: write either P or X/Y/Z",
            p.span,
        ));
    }
    let check = |cx: &Ctx<'_>, v: Val| -> Result<f64, Diagnostic> {
        if v.v > 0.0 && v.v.is_finite() {
            Ok(v.v)
        } else {
            Err(cx.err(
                "axioma::scale-factor",
                format!("a scale factor must be positive, not {}", v.v),
                v.span,
            ))
        }
    };
    if let Some(p) = uniform {
        let k = check(cx, p)?;
        cx.fe.chain.scale = [k; 3];
        cx.fe.chain.scale_pole = pole;
    } else {
        for k in 0..3 {
            if let Some(v) = factors[k] {
                cx.fe.chain.scale[k] = check(cx, v)?;
                cx.fe.chain.scale_pole[k] = pole[k];
            }
        }
    }
    only(cx, &[], "G173")
}

/// G272 / G273: rotation by Q in the active plane about the pole; G91 adds to the angle (spec §11.4).
pub(super) fn rotate(cx: &mut Ctx<'_>, on: bool) -> Result<(), Diagnostic> {
    if !on {
        cx.fe.chain.rotation_deg = 0.0;
        return Ok(());
    }
    let pole = pole(cx);
    if let Some(q) = cx.words.take(b'Q') {
        cx.fe.chain.rotation_deg = match cx.st.distance {
            DistanceMode::Absolute => q.v,
            DistanceMode::Incremental => cx.fe.chain.rotation_deg + q.v,
        };
    }
    cx.fe.chain.rotation_pole = pole;
    cx.fe.chain.rotation_plane = cx.st.plane;
    only(cx, &[], "G273")
}

/// G193 / G194 / G195: programmed zero shift (spec §12). Omitted G195 axes keep their value.
pub(super) fn shift(cx: &mut Ctx<'_>, code: u32) -> Result<(), Diagnostic> {
    match code {
        G193 => cx.fe.chain.prog_shift = [0.0; 3],
        _ => {
            for (k, &l) in XYZ.iter().enumerate() {
                if let Some(v) = cx.words.take(l) {
                    let mm = cx.mm(v.v);
                    if code == G194 {
                        cx.fe.chain.prog_shift[k] += mm;
                    } else {
                        cx.fe.chain.prog_shift[k] = mm;
                    }
                }
            }
            only(cx, &[], if code == G194 { "G194" } else { "G195" })?;
        }
    }
    Ok(())
}

/// The block-level rules of the frame functions (issue 22 items 1 and 4): G10 and G16 alone in
/// their block, one `P` user per block.
pub(super) fn block_rules(
    cx: &Ctx<'_>,
    actions: &[(crate::GAction, u32, ColSpan)],
) -> Result<(), Diagnostic> {
    use crate::state::MotionMode;
    use crate::GAction;
    for &(a, code, _) in actions {
        match a {
            GAction::Diameter => alone(cx, code, &crate::ctx::AXIS_WORDS)?,
            GAction::Polar(true) => {
                let (h, v, _) = cx.st.plane.axes();
                let pole = [crate::ctx::AXIS_WORDS[h], crate::ctx::AXIS_WORDS[v]];
                alone(cx, code, &pole)?
            }
            _ => {}
        }
    }
    // [D] (spec §12 for G194/G195, §11 "separate block" for the others): the axis words of a
    // mirror, scale, rotation or shift block are its factors, angle or vector, and the block
    // moves nothing — a motion code in it would silently not move, so it is refused.
    let frame = actions.iter().find(|(a, _, _)| {
        matches!(
            a,
            GAction::Mirror(true)
                | GAction::Scale(true)
                | GAction::Rotate(true)
                | GAction::Shift(crate::codes::G194 | crate::codes::G195)
        )
    });
    let motion = actions
        .iter()
        .find(|(a, _, _)| matches!(a, GAction::Motion(_)));
    if let (Some(&(_, frame, _)), Some(&(_, motion, at))) = (frame, motion) {
        return Err(cx
            .err(
                "axioma::frame-with-motion",
                format!(
                    "{} moves nothing: its axis words are not a move, so {} cannot be in its block",
                    crate::g_name(frame),
                    crate::g_name(motion)
                ),
                at,
            )
            .with_note("program the frame function in a block of its own, the move after it"));
    }
    one_p_user(
        cx,
        actions.iter().filter_map(|&(a, code, _)| match a {
            GAction::ZeroOffset(Some(_))
            | GAction::Workpiece(Some(_))
            | GAction::Scale(true)
            | GAction::Motion(MotionMode::ArcCw | MotionMode::ArcCcw) => Some(code),
            _ => None,
        }),
    )?;
    Ok(())
}

/// Spec axioma-1 §9 [D] and A15: `P` is the page of G54…G59/G154…G159, the uniform factor of
/// G173 and the extra turns of an arc, one user per block. The words layer keeps the last of two
/// `P` words (with a warning), which would hand G54's page to G173 as a factor: so two `P` words
/// are refused here, and so is one `P` that two of its users in the block would both read.
pub(super) fn one_p_user(cx: &Ctx<'_>, users: impl Iterator<Item = u32>) -> Result<(), Diagnostic> {
    let mut p_words = cx
        .block
        .words
        .iter()
        .filter(|w| w.address == stanok_syntax::Address::Letter(b'P'));
    let Some(first) = p_words.next() else {
        return Ok(());
    };
    if let Some(second) = p_words.next() {
        return Err(cx
            .err(
                "axioma::p-twice",
                format!(
                    "two P words in one block (`{}` and `{}`): P may have one user per block",
                    cx.block.slice(first.span),
                    cx.block.slice(second.span)
                ),
                second.span,
            )
            .with_note(
                "P is the page of G54…G59/G154…G159 and the factor of G173: program them in separate blocks",
            ));
    }
    let users: Vec<u32> = users.collect();
    if users.len() > 1 {
        return Err(cx
            .err(
                "axioma::p-ambiguous",
                format!(
                    "`{}` could belong to {} or {}: P may have one user per block",
                    cx.block.slice(first.span),
                    crate::g_name(users[0]),
                    crate::g_name(users[1])
                ),
                first.span,
            )
            .with_note("program the functions that read P in separate blocks"));
    }
    Ok(())
}

/// G10 (spec §14) and G16 (§17.4) are programmed "in a separate block without any other codes":
/// [D] besides the function, N and comments, only the letters in `allowed` (G10: axis words, the
/// mode selectors; G16: the two pole coordinates of the plane) — anything else is refused, so that
/// `G10 X1 F100 G01` cannot set a feed or a motion mode as a side effect (issue 22 item 4).
pub(super) fn alone(cx: &Ctx<'_>, code: u32, allowed: &[u8]) -> Result<(), Diagnostic> {
    use stanok_syntax::{Address, Value};
    let name = crate::g_name(code);
    for w in &cx.block.words {
        let ok = match w.address {
            Address::Letter(b'G') => {
                matches!(w.value, Value::Number(v) if (v * 10.0).round() as u32 == code)
            }
            Address::Letter(l) => allowed.contains(&l),
            _ => false,
        };
        if !ok {
            return Err(cx
                .err(
                    "axioma::not-alone",
                    format!(
                        "{name} is programmed in a block of its own: `{}` cannot be in it",
                        cx.block.slice(w.span)
                    ),
                    w.span,
                )
                .with_note(format!(
                    "move `{}` to the block before or after",
                    cx.block.slice(w.span)
                )));
        }
    }
    if cx.block.message.is_some() {
        return Err(cx.err(
            "axioma::not-alone",
            format!("{name} is programmed in a block of its own: MSG cannot be in it"),
            cx.whole(),
        ));
    }
    Ok(())
}

/// The page of a G54…G59 / G154…G159 block: `P1`…`P32`, default 1.
fn page(cx: &mut Ctx<'_>) -> Result<u8, Diagnostic> {
    match cx.words.take(b'P') {
        None => Ok(1),
        Some(p) if p.v.fract() == 0.0 && (1.0..=32.0).contains(&p.v) => Ok(p.v as u8),
        Some(p) => Err(cx.err(
            "axioma::page-range",
            format!("page P{} out of range: the tables have pages 1 to 32", p.v),
            p.span,
        )),
    }
}

/// G53 (None) / G54…G59 (1…6) with page.
pub(super) fn zero_offset(cx: &mut Ctx<'_>, system: Option<u8>) -> Result<(), Diagnostic> {
    cx.fe.chain.zero = match system {
        None => None,
        Some(s) => Some((s, page(cx)?)),
    };
    Ok(())
}

/// G153 (None) / G154…G159 (1…6) with page.
pub(super) fn workpiece(cx: &mut Ctx<'_>, system: Option<u8>) -> Result<(), Diagnostic> {
    cx.fe.chain.wcs = match system {
        None => None,
        Some(s) => Some((s, page(cx)?)),
    };
    Ok(())
}

/// Recomposes the work frame after any change above.
pub(super) fn apply(cx: &mut Ctx<'_>) {
    let chain = cx.fe.chain;
    chain.apply_to(&mut cx.st.frame, &cx.opts.control);
}

/// G10 `<axis><0|1>`: radius (0) or diameter (1) programming per axis, in a block of its own
/// (spec §14). Only axes the machine marks transverse may be diameters.
pub(super) fn diameter_mode(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let mut any = false;
    for (i, &l) in crate::ctx::AXIS_WORDS.iter().enumerate() {
        let Some(v) = cx.words.take(l) else { continue };
        any = true;
        let on = match v.v {
            0.0 => false,
            1.0 => true,
            _ => {
                return Err(cx.err(
                    "axioma::g10-value",
                    format!(
                        "G10 {}{}: the mode is 0 (radius) or 1 (diameter)",
                        l as char, v.v
                    ),
                    v.span,
                ))
            }
        };
        if on && !cx.opts.diameter_axes[i] {
            return Err(cx
                .err(
                    "axioma::g10-axis",
                    format!(
                        "{} is not a transverse axis: it cannot be programmed as a diameter",
                        l as char
                    ),
                    v.span,
                )
                .with_note(
                    "machine data marks the axes that may be diameters (`transverse = true`)",
                ));
        }
        cx.fe.modes.axioma_diameter[i] = on;
    }
    if !any {
        return Err(cx.err(
            "axioma::g10-empty",
            "G10 needs an axis and a mode, e.g. `G10 X1` (diameter) or `G10 X0` (radius)",
            span,
        ));
    }
    only(cx, &[], "G10")
}
