//! AxiOMA home positions: G28 (go to home position H1…H8, optionally via an intermediate point) and
//! G29 (return, via the same intermediate point) — spec axioma-2 §3.8.
//!
//! Home positions are machine coordinates from the stored control data. The intermediate point is
//! programmed like any target (G90/G91, unprogrammed axes keep the current position); it is kept
//! until G29 uses and clears it. Decisions the spec proposes: all configured axes go to the home
//! position; an undefined H is an error; G29 without G28 is an error; axes G29 does not program go
//! to the intermediate point's value (or stay at home when there was none); `N<k>` after the first
//! word of a G28 block is read as `H<k>` with a warning (the manual's slip, A35).

use crate::ctx::{Ctx, AXIS_WORDS};
use crate::modes::HomeReturn;
use stanok_canon::{Diagnostic, Pose};
use stanok_syntax::ColSpan;

/// G28.
pub(super) fn g28(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let h = match (cx.words.take(b'H'), cx.words.take(b'N')) {
        (Some(h), _) => h,
        (None, Some(n)) => {
            cx.warnings.push(Diagnostic::warning(
                "axioma::g28-n-as-h",
                format!(
                    "N{} inside a G28 block is read as the home-position number H{}",
                    n.v, n.v
                ),
                cx.block.span_of(n.span),
            ));
            n
        }
        (None, None) => crate::words::Val { v: 1.0, span },
    };
    let number = h.v;
    if number.fract() != 0.0 || !(1.0..=8.0).contains(&number) {
        return Err(cx.err(
            "axioma::home-range",
            format!("home position H{number}: H1 to H8"),
            h.span,
        ));
    }
    let Some(home) = cx.opts.control.offsets.home[number as usize - 1] else {
        return Err(cx
            .err(
                "axioma::home-undefined",
                format!("home position H{number} is not defined"),
                h.span,
            )
            .with_note("home positions H1…H8 are machine data (`[[home]]` in the machine file)"));
    };
    let via = if cx.has_axis_words() {
        let (p, _) = cx.end_point()?;
        cx.straight(true, p, 0.0);
        Some(cx.st.position)
    } else {
        None
    };
    // The home position in machine coordinates: only the machine's axes move.
    let mut target = cx.st.position.to_array();
    for (k, v) in home.to_array().into_iter().enumerate() {
        if cx.opts.axes[k] {
            target[k] = v;
        }
    }
    let p = cx.st.frame.to_program(&Pose::from_array(target));
    cx.straight(true, p, 0.0);
    cx.fe.modes.home_return = HomeReturn::From { via };
    Ok(())
}

/// G29.
pub(super) fn g29(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let HomeReturn::From { via } = cx.fe.modes.home_return else {
        return Err(cx.err(
            "axioma::g29-without-g28",
            "G29 returns from a home position: program G28 first",
            span,
        ));
    };
    let base = match via {
        Some(q) => {
            let p = cx.st.frame.to_program(&q);
            cx.straight(true, p, 0.0);
            p
        }
        None => cx.st.program_position(),
    };
    // Programmed axes go to their values; the others stay at `base`.
    let (end, given) = cx.end_point()?;
    let (mut v, e) = (base.to_array(), end.to_array());
    for k in 0..AXIS_WORDS.len() {
        if given[k] {
            v[k] = e[k];
        }
    }
    cx.straight(true, Pose::from_array(v), 0.0);
    cx.fe.modes.home_return = HomeReturn::None;
    Ok(())
}
