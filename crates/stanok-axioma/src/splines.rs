//! AxiOMA splines: ASPLINE (Akima), CSPLINE (C² cubic), BSPLINE (NURBS) and SPLBREAK
//! (spec axioma-2 §2.4). Geometry in `stanok_geom::{akima, cubic_spline, Nurbs}`.
//!
//! ```text
//!  spline keyword ─▶ mode (Interpolate group; G00–G03/G75 or another spline type end it)
//!  point block    ─▶ point buffered with its *slot* (index in the held stream, extension.rs)
//!                    ─▶ every segment whose shape is final goes to `ready` at its end point's slot
//!  break          ─▶ the rest is final: ASPLINE/CSPLINE end with natural (zero-curvature) ends;
//!                    BSPLINE is validated (knot rules) and emitted whole
//! ```
//!
//! Breaks (§2.4.1, A16): SPLBREAK (the mode stays), any M function, G53–G59/G153–G159/G193–G195
//! and frame functions, another interpolation code or spline type, G04, G28/G29, and the end of
//! the program. Points are kept in machine X Y Z (after the frame); a whole spline is never
//! buffered for ASPLINE (T_i needs P_{i+2}: window ≤ 6 points) nor CSPLINE (window ≤ W + 2
//! points, W = `cspline_window`); BSPLINE must be buffered to its end (its errors show only
//! there), bounded by `MAX_BSPLINE_POINTS`.
//!
//! Output: ASPLINE/CSPLINE segments as cubic Béziers (`SplineMove`, degree 3, `bezier_knots`),
//! BSPLINE as the rational Bézier pieces (`stanok_geom::bezier_pieces`) of the NURBS with the knot
//! vector of the manual, one per point that owns a knot interval:
//!
//! ```text
//!   t_0 = … = t_p = 0;  t_{i+2} = t_{i+1} + PL_i (i = p−1 … n−1);  t_{n+2} = … = t_{n+p+1} = t_{n+1}
//! ```
//!
//! Axes other than X Y Z move linearly along each emitted piece: for BSPLINE over the interval of
//! the point that programs them (A15); a point with PL=0 moves them alone. Two consecutive points with the same X Y Z (ASPLINE/CSPLINE)
//! split the spline: the extra axes move alone in a straight feed, or the point is dropped.

use crate::ctx::Ctx;
use crate::words::Val;
use stanok_canon::{Canon, Diagnostic, LineMove, Plane, Pose, Span, Spanned, SplineMove};
use stanok_geom::{akima, bezier_knots, bezier_pieces, cubic_spline, hermite_bezier, Nurbs, Vec3};
use stanok_syntax::ColSpan;
use std::collections::VecDeque;

/// Control points of one BSPLINE at most (error beyond).
pub const MAX_BSPLINE_POINTS: usize = 10_000;

/// The three spline types.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SplineKind {
    /// ASPLINE.
    Akima,
    /// CSPLINE.
    Cubic,
    /// BSPLINE.
    Nurbs,
}

#[derive(Debug, Clone, Copy)]
struct Tag {
    span: Span,
    number: Option<u32>,
    label_digits: u8,
}

#[derive(Debug, Clone, Copy)]
enum FeedRule {
    /// mm/min.
    PerMinute(f64),
    /// G93: F × the piece's length.
    InverseTime(f64),
}

#[derive(Debug, Clone, Copy)]
struct Point {
    pose: Pose,
    weight: f64,
    increment: Option<f64>,
    extra_axes: bool,
    slot: u64,
    tag: Tag,
    feed: FeedRule,
}

/// The spline mode and the points not yet emitted.
#[derive(Debug, Clone)]
pub struct SplineState {
    /// The active spline type (None = G00–G03/G75 mode).
    pub kind: Option<SplineKind>,
    /// BSPLINE degree SD (2 or 3, default 3) and whether points fixed it.
    degree: u8,
    points: VecDeque<Point>,
    /// `points[0]` is the spline's first point.
    starts: bool,
    /// Segments emitted out of the window: the next starts at `points[emitted]`.
    emitted: usize,
    /// CSPLINE: tangent at `points[emitted]`.
    tangent: Option<Vec3>,
    plane: Plane,
    ready: Vec<(u64, Spanned<Canon>)>,
}

impl Default for SplineState {
    fn default() -> Self {
        SplineState {
            kind: None,
            degree: 3,
            points: VecDeque::new(),
            starts: true,
            emitted: 0,
            tangent: None,
            plane: Plane::XY,
            ready: Vec::new(),
        }
    }
}

/// The words of a block that belong to splines.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct SplineWords {
    pub keyword: Option<(SplineKind, ColSpan)>,
    pub splbreak: bool,
    pub weight: Option<Val>,
    pub increment: Option<Val>,
    pub degree: Option<Val>,
}

impl SplineState {
    /// Slot of the first buffered point whose segment is not emitted yet.
    pub fn first_unresolved_slot(&self) -> Option<u64> {
        self.points.get(self.emitted + 1).map(|p| p.slot)
    }

    /// Segments ready for release, in slot order.
    pub fn take_ready(&mut self) -> Vec<(u64, Spanned<Canon>)> {
        std::mem::take(&mut self.ready)
    }

    fn xyz(&self) -> Vec<Vec3> {
        self.points.iter().map(|p| p.pose.xyz()).collect()
    }

    fn push(&mut self, end: &Point, value: Canon) {
        self.ready.push((
            end.slot,
            Spanned {
                span: end.tag.span,
                block_number: end.tag.number,
                label_digits: end.tag.label_digits,
                value,
            },
        ));
    }

    /// The piece's path feed; the length (a fine tessellation) is computed only for G93.
    fn feed(rule: FeedRule, length: impl FnOnce() -> f64) -> f64 {
        match rule {
            FeedRule::PerMinute(f) => f,
            FeedRule::InverseTime(f) => f * length(),
        }
    }

    fn emit_bezier(&mut self, k: usize, bez: [Vec3; 4]) {
        let (a, b) = (self.points[k], self.points[k + 1]);
        let weights = [1.0; 4];
        let knots = bezier_knots(3);
        let feed = Self::feed(b.feed, || Nurbs::new(3, &bez, &weights, &knots).length());
        let mv = SplineMove {
            start: a.pose,
            end: b.pose,
            degree: 3,
            control_points: bez.to_vec(),
            weights: weights.to_vec(),
            knots,
            plane: self.plane,
            feed,
            law: stanok_canon::FeedLaw::PerMinute,
        };
        self.push(&b, Canon::SplineFeed(Box::new(mv)));
    }

    /// Emits every ASPLINE/CSPLINE segment whose shape is final (all of them if `ended`) and
    /// drops the points no later segment needs.
    fn emit_ready(&mut self, ended: bool, cspline_window: usize) {
        let Some(kind) = self.kind else { return };
        if kind == SplineKind::Nurbs {
            return;
        }
        let pts = self.xyz();
        let n = pts.len().saturating_sub(1);
        let w = cspline_window.max(1);
        // Bounded: each pass emits one segment of the window (≤ n passes).
        while self.emitted < n {
            let k = self.emitted;
            let bez = match kind {
                SplineKind::Akima => {
                    if !(ended || k + 3 <= n) {
                        break;
                    }
                    let win = akima::Window {
                        points: &pts,
                        starts: self.starts,
                        ends: ended,
                    };
                    hermite_bezier(pts[k], win.tangent(k), pts[k + 1], win.tangent(k + 1))
                }
                _ => {
                    if !(ended || k + w <= n) {
                        break;
                    }
                    let tk = match self.tangent {
                        Some(t) => t,
                        None => cubic_spline::solve_tangents(&pts[k..=(k + w).min(n)], None)[0],
                    };
                    let sol = cubic_spline::solve_tangents(&pts[k..=(k + w).min(n)], Some(tk));
                    let tk1 = sol.get(1).copied().unwrap_or(tk);
                    self.tangent = Some(tk1);
                    hermite_bezier(pts[k], tk, pts[k + 1], tk1)
                }
            };
            self.emit_bezier(k, bez);
            self.emitted += 1;
        }
        let keep_before = if kind == SplineKind::Akima { 2 } else { 0 };
        while self.emitted > keep_before {
            self.points.pop_front();
            self.emitted -= 1;
            self.starts = false;
        }
    }

    /// Ends the current spline: everything buffered is emitted (BSPLINE validated first). The
    /// mode stays. `at`: where an error is reported (the breaking block).
    pub fn flush(&mut self, cspline_window: usize, at: Span) -> Result<(), Diagnostic> {
        if self.kind == Some(SplineKind::Nurbs) {
            self.emit_nurbs(at)?;
        } else {
            self.emit_ready(true, cspline_window);
        }
        self.drop_points();
        Ok(())
    }

    fn drop_points(&mut self) {
        self.points.clear();
        self.starts = true;
        self.emitted = 0;
        self.tangent = None;
    }

    /// [`flush`](Self::flush), reporting a spline's error once (issue 22 item 10). A run that
    /// continues after an error (`stanok check`) rolls the failed block back, buffer included, so
    /// the next breaking block — and the end of input — would find the same bad spline again.
    /// `reported` (kept outside the rolled-back state) names the spline whose error was reported,
    /// by the span of its first point; meeting it again drops the spline silently.
    pub fn flush_once(
        &mut self,
        cspline_window: usize,
        at: Span,
        reported: &mut Option<Span>,
    ) -> Result<(), Diagnostic> {
        let first = self.points.front().map(|p| p.tag.span);
        match self.flush(cspline_window, at) {
            Err(_) if first.is_some() && *reported == first => {
                self.drop_points();
                Ok(())
            }
            Err(e) => {
                *reported = first;
                Err(e)
            }
            Ok(()) => Ok(()),
        }
    }

    /// End of the program text.
    pub fn finish(
        &mut self,
        cspline_window: usize,
        reported: &mut Option<Span>,
    ) -> Result<(), Diagnostic> {
        let at = self.points.back().map(|p| p.tag.span).unwrap_or_default();
        self.flush_once(cspline_window, at, reported)
    }

    fn emit_nurbs(&mut self, at: Span) -> Result<(), Diagnostic> {
        let n = self.points.len().saturating_sub(1);
        if n == 0 {
            return Ok(());
        }
        let p = self.degree as usize;
        let err = |msg: String| Diagnostic::error("axioma::bspline", msg, at);
        if n < p {
            return Err(err(format!(
                "a degree-{p} BSPLINE needs at least {p} control-point blocks after its start point; this one has {n}"
            ))
            .with_note("the number of control points (start point included) must be at least the order SD + 1"));
        }
        let last = self.points[n];
        if last.extra_axes {
            return Err(Diagnostic::error(
                "axioma::bspline",
                "additional axes on the last BSPLINE point: it owns no knot interval",
                last.tag.span,
            ));
        }
        // Knot increments PL_{p−1} … PL_{n−1}; first and last must not be 0; a run of p zeros
        // makes an inner knot of multiplicity > p.
        let inc: Vec<f64> = (p - 1..n)
            .map(|i| self.points[i].increment.unwrap_or(1.0))
            .collect();
        let span_of = |i: usize| self.points[i].tag.span;
        if inc[0] == 0.0 {
            return Err(Diagnostic::error(
                "axioma::bspline",
                "the first knot increment that counts (PL of the first interval) must not be 0",
                span_of(p - 1),
            ));
        }
        if inc[inc.len() - 1] == 0.0 {
            return Err(Diagnostic::error(
                "axioma::bspline",
                "the last knot increment that counts (PL of the last interval) must not be 0",
                span_of(n - 1),
            ));
        }
        let mut run = 0;
        for (j, &d) in inc.iter().enumerate() {
            run = if d == 0.0 { run + 1 } else { 0 };
            if run >= p {
                return Err(Diagnostic::error(
                    "axioma::bspline",
                    format!(
                        "{} consecutive PL=0: a knot may repeat at most SD = {p} times",
                        run
                    ),
                    span_of(p - 1 + j),
                ));
            }
        }
        let mut knots = vec![0.0; p + 1];
        for d in &inc {
            let last = knots[knots.len() - 1];
            knots.push(last + d);
        }
        let end = knots[knots.len() - 1];
        knots.extend(std::iter::repeat_n(end, p));
        let control_points = self.xyz();
        let weights: Vec<f64> = self.points.iter().map(|q| q.weight).collect();
        let curve = Nurbs::new(p as u8, &control_points, &weights, &knots);
        if curve.validate().is_err() {
            return Err(err(
                "the BSPLINE cannot be evaluated (weights or knots)".into()
            ));
        }
        // One rational Bézier piece per non-empty knot interval, each at the slot of the point
        // that owns it (P_i owns [t_{i+1}, t_{i+2}], i = p−1 … n−1): the extra axes of P_i move
        // over that piece; a PL=0 point (an empty interval) moves its extra axes alone (§2.4.4).
        let pieces = bezier_pieces(p as u8, &control_points, &weights, &knots);
        let mut pieces = pieces.into_iter();
        let bk = bezier_knots(p);
        let mut prev = self.points[0].pose;
        for i in p - 1..n {
            let owner = self.points[i];
            let mut end = owner.pose;
            if i == n - 1 {
                end = self.points[n].pose;
            }
            if inc[i + 1 - p] > 0.0 {
                let Some(piece) = pieces.next() else {
                    return Err(err("the BSPLINE cannot be split into pieces".into()));
                };
                if i != n - 1 {
                    end = end.with_xyz(piece.points[p]);
                }
                let feed = Self::feed(owner.feed, || {
                    Nurbs::new(p as u8, &piece.points, &piece.weights, &bk).length()
                });
                let mv = SplineMove {
                    start: prev,
                    end,
                    degree: p as u8,
                    control_points: piece.points,
                    weights: piece.weights,
                    knots: bk.clone(),
                    plane: self.plane,
                    feed,
                    law: stanok_canon::FeedLaw::PerMinute,
                };
                self.push(&owner, Canon::SplineFeed(Box::new(mv)));
            } else {
                end = end.with_xyz(prev.xyz());
                let (a, b) = (prev.to_array(), end.to_array());
                if (0..9).any(|k| (a[k] - b[k]).abs() > 1e-12) {
                    let feed = Self::feed(owner.feed, || super::technology::feed_length(&a, &b));
                    self.push(
                        &owner,
                        Canon::StraightFeed(LineMove {
                            start: prev,
                            end,
                            feed,
                            law: stanok_canon::FeedLaw::PerMinute,
                        }),
                    );
                }
            }
            prev = end;
        }
        Ok(())
    }
}

/// Handles the spline words of a block before its motion: mode changes and breaks.
/// `other_motion`: the block programs G00–G03, G75 or G28/G29; `breaks`: it has an M function,
/// a frame or offset function, or G04.
pub(super) fn before_motion(
    cx: &mut Ctx<'_>,
    w: &SplineWords,
    other_motion: bool,
    breaks: bool,
) -> Result<(), Diagnostic> {
    let window = cx.fe.params.cspline_window;
    let at = cx.block.span();
    let st = &mut cx.fe.ext.spline;
    let new_kind = w.keyword.map(|k| k.0).filter(|k| st.kind != Some(*k));
    if st.kind.is_some() && (other_motion || breaks || w.splbreak || new_kind.is_some()) {
        st.flush_once(window, at, &mut cx.fe.reported_spline)?;
    }
    if other_motion {
        cx.fe.ext.spline.kind = None;
    }
    if let Some((kind, span)) = w.keyword {
        if cx.fe.ext.comp.is_active() {
            return Err(cx
                .err(
                    "axioma::spline-under-compensation",
                    "splines are not allowed while radius compensation (G41/G42) is active",
                    span,
                )
                .with_note("switch compensation off with G40 first (spec axioma-2 §2.4.1)"));
        }
        if new_kind.is_some() {
            let st = &mut cx.fe.ext.spline;
            st.kind = Some(kind);
            st.degree = 3;
            st.plane = cx.st.plane;
        }
    }
    let nurbs = cx.fe.ext.spline.kind == Some(SplineKind::Nurbs);
    for (v, what) in [(w.weight, "PW="), (w.increment, "PL="), (w.degree, "SD=")] {
        if let (Some(v), false) = (v, nurbs) {
            return Err(cx.err(
                "axioma::nurbs-word-outside-bspline",
                format!("{what} has a meaning only in BSPLINE mode"),
                v.span,
            ));
        }
    }
    if let Some(sd) = w.degree {
        if sd.v != 2.0 && sd.v != 3.0 {
            return Err(cx.err(
                "axioma::bspline-degree",
                format!("SD={}: the BSPLINE degree is 2 or 3", sd.v),
                sd.span,
            ));
        }
        if cx.fe.ext.spline.points.is_empty() {
            cx.fe.ext.spline.degree = sd.v as u8;
        } else {
            cx.warnings.push(Diagnostic::warning(
                "axioma::bspline-degree-ignored",
                "SD= after the first control point is ignored",
                cx.block.span_of(sd.span),
            ));
        }
    }
    if let Some(pw) = w.weight {
        if !(0.0..=3.0).contains(&pw.v) {
            return Err(cx.err(
                "axioma::bspline-weight",
                format!("PW={}: the weight is 0 … 3", pw.v),
                pw.span,
            ));
        }
        if pw.v == 0.0 {
            return Err(cx
                .err(
                    "axioma::bspline-weight-zero",
                    "PW=0 is not supported: spline weights must be positive",
                    pw.span,
                )
                .with_note("Stanok hands splines on as NURBS with positive weights; use a small weight such as PW=0.001"));
        }
    }
    if let Some(pl) = w.increment {
        if pl.v < 0.0 {
            return Err(cx.err(
                "axioma::bspline-increment",
                format!("PL={}: the knot increment cannot be negative", pl.v),
                pl.span,
            ));
        }
    }
    Ok(())
}

/// A block in spline mode: its end point is the next spline point (no axis words: mode only).
pub(super) fn point(cx: &mut Ctx<'_>, span: ColSpan, w: &SplineWords) -> Result<(), Diagnostic> {
    if !cx.has_axis_words() {
        return Ok(());
    }
    if cx.fe.ext.comp.is_active() {
        return Err(cx.err(
            "axioma::spline-under-compensation",
            "splines are not allowed while radius compensation (G41/G42) is active",
            span,
        ));
    }
    let (end, given) = cx.end_point()?;
    let rule = match cx.st.feed_mode {
        stanok_canon::FeedMode::InverseTime => {
            if cx.st.feed <= 0.0 {
                return Err(cx.err("axioma::feed-missing", "feed move with feed F = 0", span));
            }
            FeedRule::InverseTime(cx.st.feed)
        }
        _ => FeedRule::PerMinute(super::motion::feed_check(cx, span, 1.0)?),
    };
    cx.apply_pending_tlo();
    let end_m = cx.st.frame.to_machine(&end);
    let start = cx.st.position;
    let extra_axes = given[3..].iter().any(|&g| g);
    let window = cx.fe.params.cspline_window;
    let tag = Tag {
        span: cx.out.span,
        number: cx.out.number,
        label_digits: cx.out.label_digits,
    };
    let slot = cx.fe.ext.held_base + cx.out.queue.len() as u64;
    let st = &mut cx.fe.ext.spline;
    let kind = st.kind.unwrap_or(SplineKind::Akima);
    let same_xyz = {
        let (a, b) = (start.xyz(), end_m.xyz());
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    };
    if same_xyz && kind != SplineKind::Nurbs {
        // A zero-length chord: the spline is split here (spec §2.4.1 PROPOSAL).
        st.flush_once(window, cx.block.span(), &mut cx.fe.reported_spline)?;
        let moves = (0..9).any(|k| (start.to_array()[k] - end_m.to_array()[k]).abs() > 1e-12);
        if moves {
            let feed = match rule {
                FeedRule::PerMinute(f) => f,
                FeedRule::InverseTime(f) => {
                    f * super::technology::feed_length(&start.to_array(), &end_m.to_array())
                }
            };
            let p = Point {
                pose: end_m,
                weight: 1.0,
                increment: None,
                extra_axes,
                slot,
                tag,
                feed: rule,
            };
            st.push(
                &p,
                Canon::StraightFeed(LineMove {
                    start,
                    end: end_m,
                    feed,
                    law: stanok_canon::FeedLaw::PerMinute,
                }),
            );
        } else {
            cx.warnings.push(Diagnostic::warning(
                "axioma::spline-duplicate-point",
                "the spline point repeats the previous one: dropped",
                cx.block.span_of(span),
            ));
        }
        cx.st.position = end_m;
        return Ok(());
    }
    if st.points.is_empty() {
        st.points.push_back(Point {
            pose: start,
            weight: 1.0,
            increment: None,
            extra_axes: false,
            slot,
            tag,
            feed: rule,
        });
        st.starts = true;
        st.emitted = 0;
        st.tangent = None;
    }
    if kind == SplineKind::Nurbs {
        if st.points.len() > MAX_BSPLINE_POINTS {
            return Err(cx.err(
                "axioma::bspline-too-long",
                format!("a BSPLINE may have at most {MAX_BSPLINE_POINTS} control points"),
                span,
            ));
        }
        // P_1 of a cubic owns no knot interval: extra axes are an error there (§2.4.4).
        if st.degree == 3 && st.points.len() == 1 && extra_axes {
            return Err(cx.err(
                "axioma::bspline",
                "additional axes on the first BSPLINE point of degree 3: it owns no knot interval",
                span,
            ));
        }
    }
    st.points.push_back(Point {
        pose: end_m,
        weight: w.weight.map(|v| v.v).unwrap_or(1.0),
        increment: w.increment.map(|v| v.v),
        extra_axes,
        slot,
        tag,
        feed: rule,
    });
    st.emit_ready(false, window);
    cx.st.position = end_m;
    Ok(())
}
