//! The corner after a *stale* tool position: LinuxCNC 2.9 reads a G70 profile (under cutter
//! compensation, which G70 allows) by moving its idea of the current point along the profile, so
//! the first finishing pass starts with the interpreter believing the tool stands at the
//! profile's end `c` (nose centre) while the programmed point `p` is still the cycle start.
//! Its compensation then joins the next move from those two points, not from the path:
//!
//! ```text
//!   θ = angle(c − p)   (normally the previous element's offset normal at p)
//!   α = angle(e − p)   (the new line's direction)
//!   G41: θ += 2π if θ < α;  β = θ − α − π/2;  γ = +π/2
//!   G42: α += 2π if α < θ;  β = α − θ − π/2;  γ = −π/2
//!   concave  (β < −t or β > π + t, t = 0.05): the held moves end at c + ρ·u(θ + γ),
//!            ρ = r / tan((β + π)/2)  (a step back "along the previous path" from c)
//!   convex   (β > t): the held moves end at c, then an arc about p to p + r·u(α + γ) (for a
//!            rapid a traverse there: `corner_move`)
//!   straight (otherwise): the held moves stay
//! ```
//!
//! Either way the held straight move must still run its programmed way (`reachable`): after the
//! stale corner the next corner finds the pass's first rapid running backwards on a facing
//! profile, LinuxCNC's gouging error.
//!
//! With a true tool position (c = p + r·n) this is the same corner as `corner` computes from the
//! elements; with the stale one it reproduces `rs274`'s first pass (tests/rs274/
//! `stanok-g70-comp*.ngc`). A move with no motion in the plane keeps the tool at c meanwhile.

use super::{
    add, corner_move, move_held_end, reachable, sub, CornerOf, Element, CONCAVE_TOLERANCE,
};
use crate::ctx::Ctx;
use stanok_canon::Diagnostic;
use stanok_syntax::ColSpan;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The corner between the held moves and a line from the programmed point `p` to `e`, with
/// LinuxCNC's stale tool position `c` (module comment).
pub(super) fn corner(
    cx: &mut Ctx<'_>,
    p: [f64; 2],
    c: [f64; 2],
    e: [f64; 2],
    of: CornerOf,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let comp = cx.fe.modes.comp;
    let r = comp.radius;
    let v = sub(c, p);
    let w = sub(e, p);
    let mut theta = v[1].atan2(v[0]);
    let mut alpha = w[1].atan2(w[0]);
    let (beta, gamma) = if comp.side == 1 {
        if theta < alpha {
            theta += TAU;
        }
        (theta - alpha - FRAC_PI_2, FRAC_PI_2)
    } else {
        if alpha < theta {
            alpha += TAU;
        }
        (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
    };
    let t = CONCAVE_TOLERANCE;
    if beta < -t || beta > PI + t {
        if matches!(comp.last, Some(Element::Arc { .. })) {
            // After an arc LinuxCNC intersects with the arc's circle: the ordinary corner.
            let d = super::unit(w);
            let n = super::scale(super::left(d), r * comp.sign());
            let new = Element::Line { from: p, to: e };
            return super::corner(cx, p, d, add(p, n), new, of, span);
        }
        let half = (beta + PI) / 2.0;
        if half == 0.0 {
            return Err(cx.err(
                "rs274::comp-zero-corner",
                "Zero degree inside corner is invalid for cutter compensation",
                span,
            ));
        }
        let back = r / half.tan();
        let mid = add(
            c,
            [back * (theta + gamma).cos(), back * (theta + gamma).sin()],
        );
        reachable(cx, mid, span)?;
        move_held_end(cx, mid);
    } else if beta > t {
        reachable(cx, c, span)?;
        move_held_end(cx, c);
        let mid = add(p, [r * (alpha + gamma).cos(), r * (alpha + gamma).sin()]);
        corner_move(cx, of, p, mid);
    }
    cx.fe.modes.comp.unchecked = false;
    Ok(())
}
