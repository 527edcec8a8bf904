//! AxiOMA polar coordinates G15/G16 and polar arcs (spec axioma-1 §17).
//!
//! State: the pole (program coordinates of the plane's abscissa and ordinate), the modal radius ρ
//! and angle θ, and whether polar programming is on. A motion block in polar mode reads `R` (ρ) and
//! `Q` (θ) — absolute under G90, increments under G91 — and the target in the plane is
//! `pole + ρ·(cos θ, sin θ)`; the other axes are programmed normally.
//!
//! Decisions the spec proposes, taken here: |Q| > 360 is reduced to `sign·(|Q| mod 360)` with ±360
//! kept (A18); G16's coordinates are absolute under G90 and relative to the tool under G91 (A19);
//! ρ and θ start from the current position relative to the new pole (θ = 0 at the pole); a plane
//! change puts the pole at the workpiece zero; polar arcs run about the pole (or an I/J/K centre,
//! G190/G191 decide, G90/G91 do not — A21) in the commanded direction, up to 360° (A17); an arc to
//! the point it starts from is a full circle only for a G91 Q±360 (otherwise nothing moves).

use crate::arc::{ArcError, PlanarArc};
use crate::arc_rules;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::modes::Polar;
use crate::state::DistanceMode;
use crate::words::Val;
use stanok_canon::Diagnostic;
use stanok_syntax::ColSpan;

/// A programmed angle word: |Q| > 360 is reduced, ±360 is kept.
fn reduce(q: f64) -> f64 {
    if q.abs() > 360.0 {
        q.signum() * (q.abs() % 360.0)
    } else {
        q
    }
}

fn plane_coords(cx: &Ctx<'_>) -> (usize, usize, [f64; 2]) {
    let (a, b, _) = cx.st.plane.axes();
    let p = cx.st.program_position().to_array();
    (a, b, [p[a], p[b]])
}

/// ρ and θ of the current position about the pole.
fn from_position(cx: &mut Ctx<'_>) {
    let (_, _, cur) = plane_coords(cx);
    let pole = cx.fe.modes.polar.pole;
    let (dx, dy) = (cur[0] - pole[0], cur[1] - pole[1]);
    cx.fe.modes.polar.rho = dx.hypot(dy);
    cx.fe.modes.polar.theta = if cx.fe.modes.polar.rho < 1e-9 {
        0.0
    } else {
        dy.atan2(dx).to_degrees()
    };
}

/// A plane change moves the pole to the workpiece zero (spec §17.2).
pub(super) fn on_plane_change(cx: &mut Ctx<'_>) {
    cx.fe.modes.polar.pole = [0.0; 2];
    cx.fe.modes.polar.plane = cx.st.plane;
    if cx.fe.modes.polar.on {
        from_position(cx);
    }
}

/// G16 [abscissa ordinate]: sets the pole and turns polar programming on. A block of its own.
pub(super) fn g16(cx: &mut Ctx<'_>) -> Result<(), Diagnostic> {
    let (a, b, cur) = plane_coords(cx);
    let mut pole = cur;
    for (k, axis) in [a, b].into_iter().enumerate() {
        if let Some(v) = cx.words.take(AXIS_WORDS[axis]) {
            let mm = cx.mm(v.v);
            pole[k] = match cx.st.distance {
                DistanceMode::Absolute => mm,
                DistanceMode::Incremental => cur[k] + mm,
            };
        }
    }
    cx.fe.modes.polar = Polar {
        on: true,
        pole,
        plane: cx.st.plane,
        ..cx.fe.modes.polar
    };
    from_position(cx);
    for (i, &l) in AXIS_WORDS.iter().enumerate() {
        if cx.words.has(l) && !cx.words.is_used(l) && i != a && i != b {
            let span = cx.words.take(l).map(|v| v.span).unwrap_or_default();
            return Err(cx.err(
                "axioma::g16-block",
                "G16 is programmed in a block of its own: only the pole coordinates of the plane may follow",
                span,
            ));
        }
    }
    Ok(())
}

/// The end point of a polar motion block (program coordinates); `None` if the block has no
/// motion words. Updates ρ and θ.
pub(super) fn end_point(
    cx: &mut Ctx<'_>,
) -> Result<Option<(stanok_canon::Pose, bool)>, Diagnostic> {
    let (a, b, _) = cx.st.plane.axes();
    for axis in [a, b] {
        if let Some(v) = cx.words.take(AXIS_WORDS[axis]) {
            return Err(cx.err(
                "axioma::polar-plane-word",
                format!(
                    "{} is a plane axis: in polar mode (G16) the point is given by R and Q; G15 ends polar mode",
                    AXIS_WORDS[axis] as char
                ),
                v.span,
            ));
        }
    }
    let r = cx.words.take(b'R');
    let q = cx.words.take(b'Q');
    let other_axes = AXIS_WORDS
        .iter()
        .any(|&l| cx.words.has(l) && !cx.words.is_used(l));
    if r.is_none() && q.is_none() && !other_axes {
        return Ok(None);
    }
    let incremental = cx.st.distance == DistanceMode::Incremental;
    let mut full_turn = false;
    if let Some(r) = r {
        let mm = cx.mm(r.v);
        let rho = if incremental {
            cx.fe.modes.polar.rho + mm
        } else {
            mm
        };
        if rho < 0.0 {
            return Err(cx.err(
                "axioma::polar-negative-radius",
                format!("polar radius {rho:.4} mm is negative"),
                r.span,
            ));
        }
        cx.fe.modes.polar.rho = rho;
    }
    if let Some(q) = q {
        let v = reduce(q.v);
        full_turn = incremental && v.abs() == 360.0;
        cx.fe.modes.polar.theta = if incremental {
            cx.fe.modes.polar.theta + v
        } else {
            v
        };
    }
    // The other axes: as in a Cartesian block (the plane axes are not there).
    let (mut end, _) = cx.end_point()?;
    let (rho, theta) = (cx.fe.modes.polar.rho, cx.fe.modes.polar.theta.to_radians());
    let pole = cx.fe.modes.polar.pole;
    let mut v = end.to_array();
    v[a] = pole[0] + rho * theta.cos();
    v[b] = pole[1] + rho * theta.sin();
    end = stanok_canon::Pose::from_array(v);
    Ok(Some((end, full_turn)))
}

/// A polar arc (G02/G03 with R/Q): about the pole, or the I/J/K centre.
pub(super) fn arc_geometry(
    cx: &mut Ctx<'_>,
    start: [f64; 2],
    end: [f64; 2],
    span: ColSpan,
) -> Result<PlanarArc, Diagnostic> {
    let (a, b, _) = cx.st.plane.axes();
    let letters = [b'I', b'J', b'K'];
    let ia: Option<Val> = cx.words.take(letters[a]);
    let ib: Option<Val> = cx.words.take(letters[b]);
    let centre = if ia.is_none() && ib.is_none() {
        cx.fe.modes.polar.pole
    } else {
        let relative = cx.st.arc_distance == DistanceMode::Incremental;
        let c = |w: Option<Val>, s: f64, cx: &Ctx<'_>| match w {
            Some(v) if relative => s + cx.mm(v.v),
            Some(v) => cx.mm(v.v),
            None if relative => s,
            None => 0.0,
        };
        [c(ia, start[0], cx), c(ib, start[1], cx)]
    };
    arc_rules::centre_format(start, end, centre, 0, cx.opts.arc_tolerance_mm).map_err(|e| match e {
        ArcError::ZeroRadius => cx.manual(621, "invalid coordinates of the circle centre: the centre is the start point", span),
        ArcError::RadiusMismatch { r1, r2 } => cx
            .manual(622, "invalid coordinates of the circle end point: it is not on the circle about the centre", span)
            .with_note(format!("start radius {r1:.4} mm, end radius {r2:.4} mm")),
        _ => cx.manual(623, "invalid value of the circle radius", span),
    })
}
