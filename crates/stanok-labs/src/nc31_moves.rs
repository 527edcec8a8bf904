//! NC-31 moves: single-axis targets, line groups, arc groups (§2.6.1) and roundings (§2.6.2), and
//! the Canon they emit (ZX plane, X = radius). Part of [`super::nc31`].

use super::nc31::{group_span, value_of, Frame, X_MM, Z_MM};
use super::{Emit, LabState};
use crate::LabOptions;
use stanok_canon::{ArcMove, Canon, Diagnostic, LineMove, Plane, Pose, Span};

/// The target of an axis value: X in diameter units → radius, Z in 0.01 mm.
pub(super) fn axis_target(axis: usize, v: i64, incremental: bool, current: f64) -> f64 {
    let mm = v as f64 * if axis == 0 { X_MM } else { Z_MM };
    if incremental {
        current + mm
    } else {
        mm
    }
}

/// `X* Z [F]`, `Z* X [F]`, `X* F`, `Z* F`.
pub(super) fn line_group(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(), Diagnostic> {
    // A flag on the group's first frame covers the group (spec §2.5.3 recommendation).
    let group_incremental = frames[0].body.incremental;
    let mut end = st.position;
    let mut seen = [false; 3];
    let mut rapid = false;
    let mut feed = None;
    for (k, f) in frames.iter().enumerate() {
        let b = &f.body;
        match b.address {
            b'X' | b'Z' if feed.is_none() => {
                let axis = if b.address == b'X' { 0 } else { 2 };
                if seen[axis] {
                    return Err(Diagnostic::error(
                        "nc31::bad-group",
                        "an axis twice in one group",
                        f.span,
                    ));
                }
                seen[axis] = true;
                let v = value_of(f)?;
                rapid |= b.rapid;
                let t = axis_target(
                    axis,
                    v,
                    group_incremental || b.incremental,
                    get(&st.position, axis),
                );
                set(&mut end, axis, t);
            }
            b'F' if k == frames.len() - 1 && k > 0 => {
                let v = value_of(f)? as f64;
                if v <= 0.0 {
                    return Err(Diagnostic::error(
                        "nc31::bad-feed",
                        "F must be positive",
                        f.span,
                    ));
                }
                feed = Some(v * 0.01);
            }
            _ => {
                return Err(Diagnostic::error(
                    "nc31::bad-group",
                    "a line group is X* Z [F] (or Z* X [F], X* F, Z* F)",
                    f.span,
                ))
            }
        }
    }
    if rapid {
        traverse(st, out, end);
    } else {
        // The group's own F holds only inside the group (§2.7).
        let f = st.path_feed(feed.unwrap_or(st.feed), out.span, warnings);
        feed_line(st, out, end, f);
    }
    Ok(())
}

/// Checks the group's frame addresses against the expected order; returns the optional last F.
pub(super) fn expect_frames(
    frames: &[Frame],
    order: &[u8],
    what: &str,
) -> Result<Option<f64>, Diagnostic> {
    let n = order.len();
    let ok_len = frames.len() == n || frames.len() == n + 1;
    let bad = |at: Span| {
        Diagnostic::error(
            "nc31::bad-group",
            format!("{what}: the frames must come in the order {}", {
                let mut s: Vec<String> = order.iter().map(|c| (*c as char).to_string()).collect();
                s.push("[F]".into());
                s.join(", ")
            }),
            at,
        )
    };
    if !ok_len {
        return Err(bad(group_span(frames)));
    }
    for (f, &a) in frames.iter().zip(order) {
        if f.body.address != a || f.body.chamfer.is_some() {
            return Err(bad(f.span));
        }
        value_of(f)?;
    }
    match frames.get(n) {
        Some(f) if f.body.address == b'F' => {
            let v = value_of(f)? as f64;
            if v <= 0.0 {
                return Err(Diagnostic::error(
                    "nc31::bad-feed",
                    "F must be positive",
                    f.span,
                ));
            }
            Ok(Some(v * 0.01))
        }
        Some(f) => Err(bad(f.span)),
        None => Ok(None),
    }
}

/// The end point of an arc or rounding group in (radius, Z) mm.
pub(super) fn group_end(frames: &[Frame], st: &LabState) -> (f64, f64) {
    let inc = frames[0].body.incremental;
    let x = &frames[1].body;
    let z = &frames[2].body;
    let r = axis_target(0, x.value.unwrap_or(0), inc || x.incremental, st.position.x);
    let zz = axis_target(2, z.value.unwrap_or(0), inc || z.incremental, st.position.z);
    (r, zz)
}

/// `G2*/G3* X* Z* P* P [F]` (spec §2.6.1): centre = start − (P4 on the radius, P5).
pub(super) fn arc_group(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    warnings: &mut Vec<Diagnostic>,
    opts: &LabOptions,
) -> Result<(), Diagnostic> {
    let feed = expect_frames(frames, b"GXZPP", "an arc group")?;
    let g2 = frames[0].body.value == Some(2);
    let (er, ez) = group_end(frames, st);
    let (sr, sz) = (st.position.x, st.position.z);
    let pr = frames[3].body.value.unwrap_or(0) as f64 * Z_MM;
    let pz = frames[4].body.value.unwrap_or(0) as f64 * Z_MM;
    let (cr, cz) = (sr - pr, sz - pz);
    let r_start = pr.hypot(pz);
    let r_end = (er - cr).hypot(ez - cz);
    if (r_start - r_end).abs() > opts.arc_tolerance_mm || r_start <= 0.0 {
        return Err(Diagnostic::error(
            "nc31::arc-radius",
            "the arc's end point is not on its circle",
            out.span,
        )
        .with_note(format!(
            "radius at the start {r_start:.4} mm, at the end {r_end:.4} mm (tolerance {} mm)",
            opts.arc_tolerance_mm
        )));
    }
    let sweep = sweep_deg(g2, (cr, cz), (sr, sz), (er, ez));
    // The document restricts one group to arcs of less than 90° ([decide]: enforced, with the
    // rounding groups G12/G13 for quarters).
    if sweep > 90.0 + 1e-6 {
        return Err(Diagnostic::error(
            "nc31::arc-too-long",
            format!("an arc group turns less than 90°, this one {sweep:.3}°"),
            out.span,
        )
        .with_note("split the arc, or use G12/G13 for a quarter circle"));
    }
    let f = st.path_feed(feed.unwrap_or(st.feed), out.span, warnings);
    arc(st, out, g2, (er, ez), (cr, cz), f);
    Ok(())
}

/// `G12*/G13* X* Z* [F]` (spec §2.6.2): a quarter circle tangent to both axes; |Δr| = |ΔZ| = R,
/// centre (r_S, z_E) or (r_E, z_S), whichever turns 90° in the commanded sense.
pub(super) fn rounding_group(
    frames: &[Frame],
    st: &mut LabState,
    out: &mut Emit,
    warnings: &mut Vec<Diagnostic>,
    opts: &LabOptions,
) -> Result<(), Diagnostic> {
    let feed = expect_frames(frames, b"GXZ", "a rounding group")?;
    let g12 = frames[0].body.value == Some(12);
    let (er, ez) = group_end(frames, st);
    let (sr, sz) = (st.position.x, st.position.z);
    let (dr, dz) = (er - sr, ez - sz);
    // [decide] |Δr| ≠ |ΔZ| is refused: the CNC computes the radius from a quarter circle.
    if (dr.abs() - dz.abs()).abs() > opts.arc_tolerance_mm || dr.abs() < 1e-9 {
        return Err(Diagnostic::error(
            "nc31::rounding-not-quarter",
            "a rounding needs equal radial and axial travel",
            out.span,
        )
        .with_note(format!("Δr = {dr:.3} mm, ΔZ = {dz:.3} mm")));
    }
    let centre = [(sr, ez), (er, sz)]
        .into_iter()
        .find(|&c| (sweep_deg(g12, c, (sr, sz), (er, ez)) - 90.0).abs() < 1e-3)
        .unwrap_or((sr, ez));
    let f = st.path_feed(feed.unwrap_or(st.feed), out.span, warnings);
    arc(st, out, g12, (er, ez), centre, f);
    Ok(())
}

/// Sweep in degrees from s to e about c, counter-clockwise in the Z-right/X-up view when `ccw`.
/// Points are (r, z).
pub(super) fn sweep_deg(ccw: bool, c: (f64, f64), s: (f64, f64), e: (f64, f64)) -> f64 {
    // Plane coordinates (Z, X): CCW from +Z towards +X.
    let a = stanok_geom::ccw_sweep([c.1, c.0], [s.1, s.0], [e.1, e.0], 1e-9).to_degrees();
    if ccw {
        a
    } else {
        (360.0 - a) % 360.0
    }
}

pub(super) fn get(p: &Pose, axis: usize) -> f64 {
    p.to_array()[axis]
}

pub(super) fn set(p: &mut Pose, axis: usize, v: f64) {
    let mut a = p.to_array();
    a[axis] = v;
    *p = Pose::from_array(a);
}

pub(super) fn traverse(st: &mut LabState, out: &mut Emit, end: Pose) {
    out.push(Canon::StraightTraverse(LineMove {
        start: st.position,
        end,
        feed: 0.0,
    }));
    st.position = end;
}

pub(super) fn feed_line(st: &mut LabState, out: &mut Emit, end: Pose, feed: f64) {
    out.push(Canon::StraightFeed(LineMove {
        start: st.position,
        end,
        feed,
    }));
    st.position = end;
}

/// An arc in the ZX plane; `ccw` about +Y (Z towards X).
pub(super) fn arc(
    st: &mut LabState,
    out: &mut Emit,
    ccw: bool,
    e: (f64, f64),
    c: (f64, f64),
    feed: f64,
) {
    let mut end = st.position;
    end.x = e.0;
    end.z = e.1;
    out.push(Canon::ArcFeed(ArcMove {
        start: st.position,
        end,
        centre: [c.0, st.position.y, c.1],
        axis: [0.0, if ccw { 1.0 } else { -1.0 }, 0.0],
        turns: 1,
        plane: Plane::ZX,
        feed,
    }));
    st.position = end;
}
