//! RS274/NGC splines: G5 cubic, G5.1 quadratic, G5.2/G5.3 NURBS (spec rs274ngc §4.5–§4.7).
//!
//! All three become one `Canon::SplineFeed` each: a rational B-spline with its exact control
//! points (machine coordinates), weights and clamped knot vector — a Bézier of degree 3 or 2 for
//! G5/G5.1 (knots [0,0,0,0,1,1,1,1] / [0,0,0,1,1,1]), the programmed NURBS for G5.2. LinuxCNC's
//! `rs274` prints them as `NURBS_FEED(n, ...)` with n control points.
//!
//! * G5: P0 = S, P1 = S + (I, J), P2 = E + (P, Q), P3 = E. P and Q are required; I and J are
//!   required on the first G5 of a series (the previous motion was not a G5; the spec's decision,
//!   stricter than LinuxCNC 2.9) and otherwise default to −(previous P, Q), which keeps the tangent.
//! * G5.1: P0 = S, P1 = S + (I, J), P2 = E; a missing I or J is 0 (spec decision), but not both.
//! * G5.2 P- L- opens a block whose first control point is the current point (weight P, default 1;
//!   order L, default 3); every following line adds `X- Y- <P->`; G5.3 closes it and emits the
//!   curve over the clamped uniform knots t_i = 0 (i < k), i − k + 1 (k ≤ i ≤ n), n − k + 2 (i > n).
//!   The points wait in `Parameters::nurbs_mut` (rolled back with a failing block).
//!
//! All three need G17, X/Y only, and a feed (a NURBS on its G5.2 blocks only, as LinuxCNC checks
//! it: a feed set to 0 before G5.3 cuts it at 0). The curve is built in program coordinates and
//! mapped to the machine through the work frame point by point (the frame is affine, and a
//! rational B-spline maps exactly under affine maps by mapping its control points).

use crate::codes::*;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::params::Parameters;
use crate::state::DistanceMode;
use stanok_canon::{Canon, Diagnostic, FeedMode, Plane, Pose, SplineMove};
use stanok_syntax::ColSpan;

/// Most control points of one G5.2 block.
pub const MAX_NURBS_POINTS: usize = 100_000;

fn check_plane_and_axes(cx: &mut Ctx<'_>, name: &str, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.st.plane != Plane::XY {
        return Err(cx.err(
            "rs274::spline-plane",
            format!("{name} only allowed in the XY plane"),
            span,
        ));
    }
    for &letter in AXIS_WORDS.iter().skip(2) {
        if let Some(v) = cx.words.take(letter) {
            return Err(cx.err(
                "rs274::spline-axis",
                format!("{name} accepts only X and Y, not {}", letter as char),
                v.span,
            ));
        }
    }
    Ok(())
}

/// The feed of a G5 or G5.1 block, with LinuxCNC's checks: they are arcs to it (an F under G93,
/// a feed under G94). A NURBS is checked on its G5.2 blocks instead (`nurbs_point`).
fn feed(cx: &mut Ctx<'_>, f_in_block: bool, span: ColSpan) -> Result<f64, Diagnostic> {
    match cx.st.feed_mode {
        FeedMode::InverseTime if !f_in_block => Err(cx.err(
            "rs274::spline-inverse-time-f",
            "F word missing with inverse time arc move",
            span,
        )),
        FeedMode::UnitsPerMinute if cx.st.feed <= 0.0 => Err(cx.err(
            "rs274::zero-feed",
            "Cannot make arc with zero feed rate",
            span,
        )),
        _ => Ok(cx.path_feed(0.0)),
    }
}

fn emit(cx: &mut Ctx<'_>, points: &[[f64; 2]], weights: Vec<f64>, knots: Vec<f64>, feed: f64) {
    emit_with(cx, points, weights, knots, feed, true)
}

/// [`emit`]; `print_inverse_feed`: under G93 announce the curve's rate (G5, G5.1 do in
/// LinuxCNC; a G5.2 NURBS does not: it keeps whatever rate was last set).
fn emit_with(
    cx: &mut Ctx<'_>,
    points: &[[f64; 2]],
    weights: Vec<f64>,
    knots: Vec<f64>,
    feed: f64,
    print_inverse_feed: bool,
) {
    cx.apply_pending_tlo();
    let start = cx.st.position;
    let here = cx.st.program_position();
    let control_points: Vec<[f64; 3]> = points
        .iter()
        .map(|p| {
            cx.st
                .frame
                .to_machine(&Pose {
                    x: p[0],
                    y: p[1],
                    ..here
                })
                .xyz()
        })
        .collect();
    let last = points[points.len() - 1];
    let end = cx.st.frame.to_machine(&Pose {
        x: last[0],
        y: last[1],
        ..here
    });
    let degree = (knots.len() - points.len() - 1) as u8;
    // In G93 the path feed is for the whole curve: F × its length.
    let feed = if cx.st.feed_mode == FeedMode::InverseTime {
        let length = stanok_geom::Nurbs::new(degree, &control_points, &weights, &knots).length();
        let f = cx.path_feed(length);
        if print_inverse_feed {
            cx.out.push(Canon::SetFeedRate { feed: f });
        }
        f
    } else {
        feed
    };
    cx.out.push(Canon::SplineFeed(Box::new(SplineMove {
        start,
        end,
        degree,
        control_points,
        weights,
        knots,
        plane: Plane::XY,
        feed,
        law: stanok_canon::FeedLaw::PerMinute,
    })));
    cx.st.position = end;
}

/// Reads X and Y as an end point (G90/G91).
fn end_xy(cx: &mut Ctx<'_>) -> Result<([f64; 2], bool), Diagnostic> {
    let given = cx.words.has(b'X') || cx.words.has(b'Y');
    let (end, _) = cx.end_point()?;
    Ok(([end.x, end.y], given))
}

/// An offset word pair (I, J) or (P, Q) in mm; which of them were given.
fn pair(cx: &mut Ctx<'_>, a: u8, b: u8) -> (Option<f64>, Option<f64>) {
    let x = cx.words.take(a).map(|v| cx.mm(v.v));
    let y = cx.words.take(b).map(|v| cx.mm(v.v));
    (x, y)
}

/// G5.
pub(super) fn cubic(cx: &mut Ctx<'_>, span: ColSpan, f_in_block: bool) -> Result<(), Diagnostic> {
    check_plane_and_axes(cx, "G5", span)?;
    let (i, j) = pair(cx, b'I', b'J');
    let (p, q) = pair(cx, b'P', b'Q');
    // LinuxCNC 2.9's convert_spline: without I and J the first control point continues the
    // previous G5 (its -P, -Q, kept however long ago it was; 0 before any G5).
    let (i, j) = match (i, j) {
        (Some(i), Some(j)) => (i, j),
        (None, None) => (-cx.fe.modes.g5_pq[0], -cx.fe.modes.g5_pq[1]),
        _ => {
            return Err(cx.err(
                "rs274::g5-ij",
                "Must specify both I and J, or neither",
                span,
            ))
        }
    };
    let (Some(p), Some(q)) = (p, q) else {
        return Err(cx.err("rs274::g5-pq", "Must specify both P and Q with G5", span));
    };
    let f = feed(cx, f_in_block, span)?;
    let s = cx.st.program_position();
    let (e, _) = end_xy(cx)?;
    let pts = [[s.x, s.y], [s.x + i, s.y + j], [e[0] + p, e[1] + q], e];
    emit(cx, &pts, vec![1.0; 4], stanok_geom::bezier_knots(3), f);
    cx.fe.modes.g5_pq = [p, q];
    // LinuxCNC leaves the motion mode as it was: axis words alone after a G5 block repeat the
    // mode before it, and #<_motion_mode> reads that mode.
    Ok(())
}

/// G5.1.
pub(super) fn quadratic(
    cx: &mut Ctx<'_>,
    span: ColSpan,
    f_in_block: bool,
) -> Result<(), Diagnostic> {
    check_plane_and_axes(cx, "G5.1", span)?;
    let (Some(i), Some(j)) = pair(cx, b'I', b'J') else {
        return Err(cx.err(
            "rs274::g5-1-ij",
            "Must specify both I and J with G5.1",
            span,
        ));
    };
    let f = feed(cx, f_in_block, span)?;
    let s = cx.st.program_position();
    let (e, _) = end_xy(cx)?;
    let pts = [[s.x, s.y], [s.x + i, s.y + j], e];
    emit(cx, &pts, vec![1.0; 3], stanok_geom::bezier_knots(2), f);
    Ok(())
}

/// G5.2 and its continuation lines: collect control points.
pub(super) fn nurbs_point(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    explicit: bool,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    check_plane_and_axes(cx, "G5.2", span)?;
    let opening = explicit || cx.fe.modes.motion_code != Some(G5_2);
    // LinuxCNC's convert_nurbs: every point after the first (the current point) needs P > 0.
    let p_word = cx.words.take(b'P');
    let weight = match p_word {
        Some(p) if p.v > 0.0 => p.v,
        _ if opening => 1.0,
        Some(p) => {
            return Err(cx.err(
                "rs274::nurbs-weight",
                "Must specify positive weight P for every Control Point",
                p.span,
            ))
        }
        None => {
            return Err(cx.err(
                "rs274::nurbs-weight",
                "Must specify positive weight P for every Control Point",
                span,
            ))
        }
    };
    let order = cx.words.take(b'L').map(|l| l.v);
    let has_x = cx.words.has(b'X');
    let has_y = cx.words.has(b'Y');
    if has_x != has_y {
        return Err(cx.err(
            "rs274::nurbs-xy",
            "You must specify both X and Y coordinates for Control Point",
            span,
        ));
    }
    // LinuxCNC checks the feed on every G5.2 block (under G94 only), not on G5.3.
    if cx.st.feed_mode == FeedMode::UnitsPerMinute && cx.st.feed <= 0.0 {
        return Err(cx.err(
            "rs274::zero-feed",
            "Cannot make a NURBS with 0 feedrate",
            span,
        ));
    }
    let here = cx.st.program_position();
    if opening {
        // LinuxCNC takes L only above 3 (order 3 otherwise).
        let k = match order {
            Some(l) if l > 3.0 && l.fract() == 0.0 && l <= 16.0 => l as u32,
            Some(l) if l <= 3.0 => 3,
            Some(_) => {
                return Err(cx.err(
                    "rs274::nurbs-order",
                    "G5.2 order L must be an integer from 2 to 16",
                    span,
                ))
            }
            None => 3,
        };
        let buf = params.nurbs_mut();
        buf.order = k;
        buf.points.clear();
        // The current point is always the first control point; a first line without X/Y only
        // gives its weight.
        buf.points
            .push(([here.x, here.y, here.z], if has_x { 1.0 } else { weight }));
    } else if order.is_some() {
        return Err(cx.err(
            "rs274::nurbs-order-late",
            "L (order) only on the G5.2 line",
            span,
        ));
    }
    if has_x {
        let x = cx.words.take(b'X').map_or(0.0, |v| cx.mm(v.v));
        let y = cx.words.take(b'Y').map_or(0.0, |v| cx.mm(v.v));
        // Incremental points are relative to the current point, which stays where the G5.2
        // block began until G5.3 (LinuxCNC's find_ends on an unmoved current point).
        let (x, y) = match cx.st.distance {
            DistanceMode::Absolute => (x, y),
            DistanceMode::Incremental => (here.x + x, here.y + y),
        };
        let buf = params.nurbs_mut();
        if buf.points.len() >= MAX_NURBS_POINTS {
            return Err(cx.err(
                "rs274::nurbs-too-long",
                format!("More than {MAX_NURBS_POINTS} control points in one G5.2 block"),
                span,
            ));
        }
        buf.points.push(([x, y, here.z], weight));
    }
    cx.fe.modes.motion_code = Some(G5_2);
    Ok(())
}

/// G5.3: the NURBS block is complete; emit it.
pub(super) fn nurbs_end(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    if cx.fe.modes.motion_code != Some(G5_2) {
        return Err(cx.err(
            "rs274::g5-3-without-g5-2",
            "Cannot use G5.3 without G5.2 first",
            span,
        ));
    }
    let buf = params.nurbs().clone();
    let k = buf.order as usize;
    let n_points = buf.points.len();
    if n_points < k {
        return Err(cx.err(
            "rs274::nurbs-too-few",
            format!(
                "You must specify a number of control points at least equal to the order L = {k}"
            ),
            span,
        ));
    }
    // LinuxCNC checks no feed here: a feed set to 0 after the last G5.2 block (`F0` alone, or
    // on this line) cuts the NURBS at 0, as rs274 prints it.
    let f = cx.path_feed(0.0);
    // Clamped uniform knots over n + 1 points (n = n_points − 1).
    let n = n_points - 1;
    let knots: Vec<f64> = (0..=n + k)
        .map(|i| {
            if i < k {
                0.0
            } else if i <= n {
                (i - k + 1) as f64
            } else {
                (n + 2 - k) as f64
            }
        })
        .collect();
    let pts: Vec<[f64; 2]> = buf.points.iter().map(|(p, _)| [p[0], p[1]]).collect();
    let weights: Vec<f64> = buf.points.iter().map(|(_, w)| *w).collect();
    emit_with(cx, &pts, weights, knots, f, false);
    params.nurbs_mut().points.clear();
    cx.fe.modes.motion_code = None;
    cx.st.motion = crate::state::MotionMode::None;
    // LinuxCNC leaves no motion mode at all (-1, not G80's 80): #<_motion_mode> reads -1.
    cx.fe.modes.motion_unset = true;
    Ok(())
}
