//! Balt-System splines in CVU=1: `(BSP,abscissa,ordinate,…,n)`, a start block (G00/G01), `G06`
//! nodes, a closing G00/G01 block, `(ESP)` (cvu-five-axis.md §6.5).
//!
//! The curve is defined in the programmer's manual, not in the CVU document; only the nodes are
//! oracles. Stanok's curve (decision): the parametric C² cubic spline with chord-length parameter
//! through the point where the first node block starts and every node (`stanok_geom::
//! cubic_spline`, the AxiOMA CSPLINE algorithm), as one cubic Bézier per node block, so the tip
//! passes exactly through every node and each block keeps its own source line. End conditions n:
//! 0 natural/natural, 1 tangent/natural, 2 natural/tangent, 3 tangent/tangent; "tangent" at the
//! first point is the direction of the start block, at the last point that of the closing block
//! (natural where there is none). With both ends tangent the tangents come from the start-clamped
//! solve and the last one is then set to the closing direction (C¹ at the last node, C² elsewhere).
//! Rotary axes move linearly with arc length within each node block (Canon `SplineMove`).
//! The axis letters of `(BSP …)` name the programmed axes (the manual's example lists five,
//! AMB-13); the curve is always in X Y Z.
//!
//! Errors: `G06` outside `(BSP …)…(ESP)` and two nodes at the same X Y Z are `balt::spline`;
//! G02/G03 inside the definition is the manual's message 477 ("Incongruent profile").
//!
//! The nodes wait in [`SplineBuffer`] (restored with the block backup on failure) until the
//! closing block or `(ESP)` emits them, each tagged with its own block's span.

use crate::ctx::Ctx;
use stanok_canon::{Canon, Diagnostic, Pose, Span, Spanned, SplineMove};
use stanok_geom::cubic_spline::solve_tangents;
use stanok_syntax::ColSpan;

/// One node block.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    pub pose: Pose,
    pub feed: f64,
    pub span: Span,
    pub number: Option<u32>,
    pub label_digits: u8,
}

/// An open `(BSP …)` definition.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SplineBuffer {
    /// Inside `(BSP …)` … `(ESP)`.
    pub open: bool,
    /// End conditions 0–3.
    pub n: u8,
    /// Where the first node block starts.
    pub start: Option<Pose>,
    /// Direction of the start block (unit), for n = 1, 3.
    pub start_tangent: Option<[f64; 3]>,
    /// The node blocks so far.
    pub nodes: Vec<Node>,
}

/// `(BSP,…,n)`.
pub(crate) fn begin(cx: &mut Ctx<'_>, text: &str, at: ColSpan) -> Result<(), Diagnostic> {
    if cx.fe.modes.cvu3 {
        return Err(cx.err(
            "interp::unsupported",
            "(BSP …) in CVU=3 is not supported",
            at,
        ));
    }
    let last = text.rsplit(',').next().unwrap_or("").trim();
    let n = match last {
        "0" => 0,
        "1" => 1,
        "2" => 2,
        "3" => 3,
        _ => {
            return Err(cx.err(
                "balt::spline",
                format!("(BSP …): the end condition n must be 0, 1, 2 or 3, not {last:?}"),
                at,
            ))
        }
    };
    cx.fe.spline = SplineBuffer {
        open: true,
        n,
        ..SplineBuffer::default()
    };
    Ok(())
}

/// A G00/G01 block inside the definition from `start` to `end` (X Y Z): before any node it is the
/// start block (its direction is the start tangent); after nodes it closes the spline.
pub(crate) fn straight_block(
    cx: &mut Ctx<'_>,
    start: [f64; 3],
    end: [f64; 3],
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let d = [end[0] - start[0], end[1] - start[1], end[2] - start[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let dir = (len > 1e-12).then(|| d.map(|v| v / len));
    if !cx.fe.spline.open {
        return Ok(());
    }
    if cx.fe.spline.nodes.is_empty() {
        cx.fe.spline.start_tangent = dir;
        Ok(())
    } else {
        flush(cx, dir, at)
    }
}

/// A `G06` node block ending at `end`.
pub(crate) fn node(cx: &mut Ctx<'_>, end: Pose, feed: f64, at: ColSpan) -> Result<(), Diagnostic> {
    if !cx.fe.spline.open {
        return Err(cx.err(
            "balt::spline",
            "G06 outside a (BSP …) … (ESP) definition",
            at,
        ));
    }
    let prev = cx.st.position;
    if (0..3).all(|i| (end.to_array()[i] - prev.to_array()[i]).abs() < 1e-9) {
        return Err(cx.err(
            "balt::spline",
            "a spline node at the same X Y Z as the point before it",
            at,
        ));
    }
    let b = &mut cx.fe.spline;
    if b.nodes.is_empty() {
        b.start = Some(prev);
    }
    b.nodes.push(Node {
        pose: end,
        feed,
        span: cx.out.span,
        number: cx.out.number,
        label_digits: cx.out.label_digits,
    });
    cx.st.position = end;
    Ok(())
}

/// `(ESP)`: emits what is pending (natural end) and closes the definition.
pub(crate) fn end(cx: &mut Ctx<'_>, at: ColSpan) -> Result<(), Diagnostic> {
    if !cx.fe.spline.nodes.is_empty() {
        flush(cx, None, at)?;
    }
    cx.fe.spline = SplineBuffer::default();
    Ok(())
}

/// Emits the buffered nodes as cubic Béziers (module doc); `end_tangent` = the closing block's
/// direction.
fn flush(cx: &mut Ctx<'_>, end_tangent: Option<[f64; 3]>, _at: ColSpan) -> Result<(), Diagnostic> {
    let b = std::mem::take(&mut cx.fe.spline);
    let Some(start) = b.start else {
        return Ok(());
    };
    let mut poses = vec![start];
    poses.extend(b.nodes.iter().map(|n| n.pose));
    let pts: Vec<[f64; 3]> = poses.iter().map(|p| p.xyz()).collect();
    let clamp_start = matches!(b.n, 1 | 3).then_some(b.start_tangent).flatten();
    let clamp_end = matches!(b.n, 2 | 3).then_some(end_tangent).flatten();
    let tangents = match (clamp_start, clamp_end) {
        (s, None) => solve_tangents(&pts, s),
        (None, Some(e)) => {
            // Natural start, clamped end: the reversed curve has a clamped start.
            let rev: Vec<[f64; 3]> = pts.iter().rev().copied().collect();
            let t = solve_tangents(&rev, Some(e.map(|v| -v)));
            t.iter().rev().map(|v| v.map(|x| -x)).collect()
        }
        (Some(s), Some(e)) => {
            let mut t = solve_tangents(&pts, Some(s));
            if let Some(last) = t.last_mut() {
                *last = e;
            }
            t
        }
    };
    for (i, node) in b.nodes.iter().enumerate() {
        let bez = stanok_geom::hermite_bezier(pts[i], tangents[i], pts[i + 1], tangents[i + 1]);
        cx.out.queue.push_back(Spanned {
            span: node.span,
            block_number: node.number,
            label_digits: node.label_digits,
            value: Canon::SplineFeed(Box::new(SplineMove {
                start: poses[i],
                end: poses[i + 1],
                degree: 3,
                control_points: bez.to_vec(),
                weights: vec![1.0; 4],
                knots: stanok_geom::bezier_knots(3),
                plane: cx.st.plane,
                feed: node.feed,
                law: stanok_canon::FeedLaw::PerMinute,
            })),
        });
    }
    // The definition stays open until (ESP); the nodes are out.
    cx.fe.spline = SplineBuffer {
        open: b.open,
        n: b.n,
        ..SplineBuffer::default()
    };
    Ok(())
}
