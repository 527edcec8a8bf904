//! Balt-System circles: G02/G03 with a signed radius R in the plane of `(DPI,abscissa,ordinate)`
//! (cvu-five-axis.md §6.4), in CVU=0 and in CVU=1.
//!
//! * The plane is the ordered pair of `(DPI,a,b)`: counter-clockwise (G03) turns from +a towards
//!   +b, seen from the positive side of a × b. The pair maps onto Canon's planes (XY, ZX, YZ);
//!   a reversed pair (Y,X), (X,Z), (Z,Y) is the same plane with the sense of rotation flipped.
//!   Default (no DPI): (X,Y).
//! * R > 0: the arc of at most 179.999°; R < 0: 180° to 359.999° (an arc of exactly 180° takes −).
//!   Centre: the standard construction (S+E)/2 ± h·n̂, h = √(r² − d²/4), on the side that gives the
//!   sweep R's sign asks for (`stanok_geom::centre_from_radius`). d > 2r (beyond 1 µm), R = 0, a
//!   missing R and E = S are errors (`balt::arc`).
//! * In CVU=1 the tip follows the arc in part coordinates and rotary words (or I J K, through the
//!   same orientation rule as G01) move linearly in the arc parameter; the kin stage maps every
//!   servo setpoint (decision as the spec proposes; "correction operands" are not built, AMB-15).
//! * Not in CVU=3 (the local frame would have to carry the plane): refused.
//!
//! Invariant: the arc emitted ends exactly at the programmed end; its start is the current point.

use crate::ctx::Ctx;
use crate::state::MotionMode;
use stanok_canon::{Diagnostic, Plane, Pose};
use stanok_interp_core::arc::PlanarArc;
use stanok_syntax::ColSpan;

/// Half-chord tolerance of the radius check, mm.
const RADIUS_TOLERANCE: f64 = 1e-3;

/// `(DPI,a,b)`: the plane and whether its sense is reversed against Canon's plane.
pub(crate) fn dpi(cx: &mut Ctx<'_>, text: &str, at: ColSpan) -> Result<(), Diagnostic> {
    let pair: String = text
        .split(',')
        .skip(1)
        .map(|f| f.trim().to_ascii_uppercase())
        .collect::<Vec<_>>()
        .join(",");
    let (plane, flip) = match pair.as_str() {
        "X,Y" => (Plane::XY, false),
        "Y,X" => (Plane::XY, true),
        "Z,X" => (Plane::ZX, false),
        "X,Z" => (Plane::ZX, true),
        "Y,Z" => (Plane::YZ, false),
        "Z,Y" => (Plane::YZ, true),
        _ => {
            return Err(cx.err(
                "interp::unsupported",
                format!("(DPI,{pair}): only planes of two of X, Y, Z are supported"),
                at,
            ))
        }
    };
    cx.st.plane = plane;
    cx.fe.modes.plane_reversed = flip;
    Ok(())
}

/// A G02/G03 block to `end` (part coordinates and rotary angles, already resolved).
pub(crate) fn arc(
    cx: &mut Ctx<'_>,
    end: [f64; 9],
    feed: f64,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    if cx.fe.modes.cvu3 {
        return Err(cx.err(
            "interp::unsupported",
            "G02/G03 in CVU=3 is not supported (linear blocks only)",
            at,
        ));
    }
    let Some(r) = cx.words.take(b'R') else {
        return Err(cx.err("balt::arc", "G02/G03 needs the radius R", at));
    };
    let radius = cx.mm(r.v);
    let plane = cx.st.plane;
    let (a, b, _) = plane.axes();
    let s = cx.st.program_position().to_array();
    let ccw = (cx.st.motion == MotionMode::ArcCcw) != cx.fe.modes.plane_reversed;
    // R+ is an arc of at most 179.999° (§6.5): a chord longer than 2r·sin(179.999°/2) — a half
    // circle, within the tolerance of the radius check — needs R− (issue 22 item 16).
    let half_chord = 0.5 * (end[a] - s[a]).hypot(end[b] - s[b]);
    // No circle of radius |R| joins points further apart than its diameter (§6.4: d > 2r is an
    // error), whatever the sign; the check tolerates what the centre construction tolerates.
    if half_chord > radius.abs() + RADIUS_TOLERANCE {
        return Err(cx
            .err(
                "balt::arc",
                format!(
                    "R{}: the end is {:.4} mm from the start, more than the diameter {:.4} mm",
                    r.v,
                    2.0 * half_chord,
                    2.0 * radius.abs()
                ),
                r.span,
            )
            .with_note(
                "no circle of this radius passes through both points: check R and the end point",
            ));
    }
    if radius > 0.0 && half_chord > radius * (179.999f64 / 2.0).to_radians().sin() {
        return Err(cx
            .err(
                "balt::arc",
                format!(
                    "R{}: the arc sweeps 180° or more, which R+ cannot program",
                    r.v
                ),
                r.span,
            )
            .with_note(
                "R+ programs arcs of up to 179.999°, R− those of 180° to 359.999°: write R-",
            ));
    }
    let centre = stanok_geom::centre_from_radius(
        [s[a], s[b]],
        [end[a], end[b]],
        radius.abs(),
        ccw,
        radius < 0.0,
        RADIUS_TOLERANCE,
    )
    .map_err(|e| {
        cx.err(
            "balt::arc",
            format!(
                "no circle of radius R{} through the start and the end{}",
                r.v,
                match e {
                    stanok_geom::RadiusError::EndEqualsStart => ": the start and the end coincide",
                    stanok_geom::RadiusError::NonPositiveRadius => ": R must not be 0",
                    stanok_geom::RadiusError::RadiusTooSmall { .. } => "",
                }
            ),
            r.span,
        )
    })?;
    cx.arc(
        plane,
        ccw,
        Pose::from_array(end),
        PlanarArc { centre, turns: 1 },
        feed,
    );
    Ok(())
}
