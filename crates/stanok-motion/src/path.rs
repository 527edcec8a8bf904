//! The path builder: programmed segments → tangent-continuous pieces (lines and blends: circular
//! arcs in BRISK, clothoid pairs in SOFT).
//!
//! ## Algorithm
//! 1. **Elements.** A line is one element. An arc (circle, helix, spiral) is one element too: an
//!    exact [`HelixCurve`], interpolated on the programmed curve ([`crate::curve`]), never chords.
//!    A spline arrives as chords within [`SPLINE_CHORD_TOLERANCE`] (0.5 µm) of its curve; each
//!    chord is an element, and the vertices inside a spline are blended within another 0.5 µm, so
//!    a spline's setpoints are within 1 µm of its curve under every path mode.
//! 2. **Junctions.** Where two elements meet, the rule of the first one's end applies:
//!    * *stop* (G60/G61 exact stop at a block end, a forced stop, a reversal): the piece after it
//!      starts from rest;
//!    * *tangent only* (G61.1 exact path at a block end): pass at speed if the elements are
//!      tangent (turning angle ≤ 1e-9 rad), otherwise stop;
//!    * *blend within e* (G64 P at a block end; every vertex inside a spline): round the corner.
//!
//!    Between two straight elements the corner becomes the circular arc tangent to both whose
//!    distance from the corner is e_d = d·tan(θ/4) ≤ e, where θ is the turning angle and d the
//!    length cut from each: d = min(e / tan(θ/4), L_in/2, L_out/2); radius r = d / tan(θ/2). Half
//!    of each element at most goes to each of its two corners, so blends never overlap. Collinear
//!    elements pass unblended.
//!
//!    **SOFT** (either side SOFT) replaces the circle by a symmetric pair of clothoids, whose
//!    curvature runs 0 → 2φ/ℓ → 0 ([`crate::clothoid`]; same plane, same half-length rule, and
//!    every point within e of the elements — measured from them rather than the corner). A line
//!    meets such a blend with equal (zero) curvature, so the axis accelerations stay continuous and
//!    the servo trace's finite-difference jerk stays within the axis limits.
//!
//!    Where an **arc** takes part, the corner becomes a smooth blend of the two curves
//!    ([`Blend`]: quintic smooth step from one curve into the other, within e, curvature
//!    continuous). Tangent junctions pass, except in SOFT where the curvature steps (a line into a
//!    circle, two circles): there the smooth blend joins them within e (G64) or 1 µm
//!    ([`INTERNAL_TOLERANCE`], exact path), so that no axis acceleration steps. A SOFT path thus
//!    has no curvature step at any join (lines and clothoid ends have κ = 0, smooth blends match
//!    both sides; a corner that cannot be blended is a stop; dwells and the tool-centre-point
//!    segments, which end in exact stops, join at rest), and no join needs a speed cap of its own.
//! 3. **Tolerances.** Under G64 with tolerance P (or the default when P is absent) a block-end
//!    corner gets e = P − the chord tolerance of its sides (0 for lines and arcs, 0.5 µm for spline
//!    chords). So every point of a blend is within e of an element and every element within its
//!    chord tolerance of the programmed curve: the path stays within P. Away from junctions the
//!    path is the programmed one (lines, arcs) or within 1 µm of it (splines).
//! 4. **Limits per piece** (see [`crate::piece`]): lines by projecting the axis limits on the
//!    direction, arcs, blends and clothoids by per-axis bounds of their derivatives with a
//!    centripetal (and in SOFT a turning-jerk) share; a blend runs at most at the lower of the two
//!    programmed feeds.
//!
//! ## Invariants
//! * Consecutive pieces share their end point and, unless the second starts from rest, their
//!   tangent (to rounding): axis velocities are continuous.
//! * Memory: one pending element plus the chords of the current segment (a spline's).
//! * Zero-length elements are dropped; segments with non-finite coordinates are dropped whole.

use crate::clothoid::{unit_shape, Clothoid};
use crate::curve::{Blend, BlendSide, HelixCurve};
use crate::limits::MotionConfig;
use crate::piece::{cap_acceleration, shape_limits, Overrides, Piece, ProgrammedSpeed, Shape};
use crate::segment::{
    PathSegment, PlannerInput, Point9, SegmentGeometry, SpeedClass, Spindles,
    SPLINE_CHORD_TOLERANCE,
};
use stanok_canon::PathMode;
use std::sync::Arc;

/// Tolerance of the smooth blend at a SOFT curvature step under exact path, and of the joins
/// inside a G96 split under exact stop, mm.
pub const INTERNAL_TOLERANCE: f64 = 1e-3;
/// Turning angles at or below this (rad) pass without blend or stop.
pub const TANGENT_ANGLE: f64 = 1e-9;
/// Curvatures (1/mm) closer than this are equal: a tangent junction between them passes in SOFT.
const SAME_CURVATURE: f64 = 1e-9;
/// Turning angles closer than this to π (rad) are reversals: stop.
const REVERSAL_MARGIN: f64 = 1e-6;

/// What happens where an element ends.
#[derive(Debug, Clone, Copy, PartialEq)]
enum EndRule {
    Stop,
    TangentOnly,
    Blend { tolerance: f64 },
}

/// The shape of an element.
#[derive(Debug, Clone, Copy)]
enum Geom {
    /// Straight, with unit direction.
    Line { dir: Point9 },
    /// An exact arc; `theta0` its angle at the element's start.
    Helix { curve: HelixCurve, theta0: f64 },
}

/// A line, an arc or a spline chord whose end is not yet known to be trimmed.
#[derive(Debug, Clone, Copy)]
struct Element {
    start: Point9,
    /// Exact end point (the programmed one).
    end: Point9,
    geom: Geom,
    length: f64,
    /// Already cut from the start by the previous blend.
    start_trim: f64,
    speed: ProgrammedSpeed,
    /// Highest path speed the segment's kinematics allow, unit/s; ∞ = none.
    velocity_cap: f64,
    /// Highest path acceleration the segment allows (its kinematics), unit/s²; ∞ = none.
    accel_cap: f64,
    soft: bool,
    line: u32,
    seq: u64,
    spindles: Spindles,
    chord_tolerance: f64,
    end_rule: EndRule,
    entry_stop: bool,
    /// It starts, or ends, at a stop its path mode makes (G60/G61 exact stop, an exact-path
    /// corner): what a report names as the limit of its ramps.
    exact_stop: bool,
    /// Path tolerance in force (for the report).
    tolerance: f64,
}

impl Element {
    fn is_line(&self) -> bool {
        matches!(self.geom, Geom::Line { .. })
    }

    /// Angle at the (untrimmed) end of an arc element.
    fn theta_end(curve: &HelixCurve, theta0: f64, length: f64) -> f64 {
        theta0 + length / curve.rho
    }

    /// Unit tangent and second derivative along s at the end (`at_end`) or the start.
    fn tangent_and_curvature(&self, at_end: bool) -> (Point9, Point9) {
        match self.geom {
            Geom::Line { dir } => (dir, [0.0; 9]),
            Geom::Helix { curve, theta0 } => {
                let th = if at_end {
                    Self::theta_end(&curve, theta0, self.length)
                } else {
                    theta0
                };
                let q = curve.at(th);
                let n = norm9(&q.d1);
                (q.d1.map(|x| x / n), q.d2)
            }
        }
    }

    /// The curve through the end, for a blend into the next element.
    fn side_at_end(&self) -> BlendSide {
        match self.geom {
            Geom::Line { dir } => BlendSide::Line { at: self.end, dir },
            Geom::Helix { curve, theta0 } => BlendSide::Helix {
                curve,
                theta: Self::theta_end(&curve, theta0, self.length),
            },
        }
    }

    /// The curve through the start, for a blend from the previous element.
    fn side_at_start(&self) -> BlendSide {
        match self.geom {
            Geom::Line { dir } => BlendSide::Line {
                at: self.start,
                dir,
            },
            Geom::Helix { curve, theta0 } => BlendSide::Helix {
                curve,
                theta: theta0,
            },
        }
    }

    fn dir(&self) -> Point9 {
        self.tangent_and_curvature(true).0
    }
}

/// Turns planner input into pieces (module doc).
#[derive(Debug, Clone)]
pub struct PathBuilder {
    config: MotionConfig,
    /// The overrides pieces are first limited with (the run's initial ones; the planner limits
    /// them again when the factors in force differ).
    overrides: Overrides,
    pending: Option<Element>,
    stop_next: bool,
    /// End of the last element received (exact programmed point).
    position: Point9,
    /// The spindle speed of the last segment received (dwells keep it).
    spindles: Spindles,
    /// The running number of the last segment received (see [`PathBuilder::next_seq`]).
    seq: u64,
    scratch: Vec<Point9>,
}

fn sub9(a: &Point9, b: &Point9) -> Point9 {
    std::array::from_fn(|i| a[i] - b[i])
}
fn dot9(a: &Point9, b: &Point9) -> f64 {
    (0..9).map(|i| a[i] * b[i]).sum()
}
fn norm9(a: &Point9) -> f64 {
    dot9(a, a).sqrt()
}
fn finite9(a: &Point9) -> bool {
    a.iter().all(|x| x.is_finite())
}

impl PathBuilder {
    /// An empty builder; the first piece starts from rest.
    pub fn new(config: &MotionConfig) -> Self {
        PathBuilder {
            overrides: config.overrides(),
            config: config.clone().sanitised(),
            pending: None,
            stop_next: true,
            position: [0.0; 9],
            spindles: Spindles::default(),
            seq: 0,
            scratch: Vec::new(),
        }
    }

    /// The running number the next segment pushed will get (its pieces' `seq`), so that a caller
    /// can keep the programmed geometry under the same number (the contour measurement).
    pub fn next_seq(&self) -> u64 {
        self.seq + 1
    }

    fn effective_tolerance(&self, mode: PathMode) -> Option<f64> {
        match mode {
            PathMode::Continuous { tolerance } if tolerance.is_finite() && tolerance > 0.0 => {
                Some(tolerance)
            }
            PathMode::Continuous { .. } => Some(self.config.default_tolerance),
            _ => None,
        }
    }

    /// Feeds one planner input; finished pieces go to `out` in path order.
    pub fn push(&mut self, input: PlannerInput, out: &mut impl FnMut(Piece)) {
        match input {
            PlannerInput::Stop { dwell_s, line } => {
                self.flush(out);
                if dwell_s > 0.0 {
                    out(dwell_piece(
                        self.position,
                        dwell_s,
                        line,
                        self.seq,
                        self.spindles,
                    ));
                }
                self.stop_next = true;
            }
            PlannerInput::Segment(seg) => self.push_segment(&seg, out),
        }
    }

    /// Sets where the machine stands (the start of the program, or after a probe). Any pending
    /// element is flushed first.
    pub fn set_position(&mut self, at: Point9, out: &mut impl FnMut(Piece)) {
        self.flush(out);
        self.position = at;
    }

    /// Emits the pending element: the path ends or stops there.
    pub fn flush(&mut self, out: &mut impl FnMut(Piece)) {
        if let Some(c) = self.pending.take() {
            self.emit(&c, 0.0, out);
        }
        self.stop_next = true;
    }

    fn push_segment(&mut self, seg: &PathSegment, out: &mut impl FnMut(Piece)) {
        self.seq += 1;
        if !finite9(&seg.start) || !finite9(&seg.end) {
            return;
        }
        // The adapter always gives a positive finite speed; anything else runs at the maximum feed.
        let mut seg_speed = seg.path_speed;
        if !(seg_speed.is_finite() && seg_speed > 0.0) {
            seg_speed = self.config.max_feed;
        }
        let class = if seg.rapid {
            SpeedClass::Rapid
        } else {
            seg.speed_class
        };
        let speed = ProgrammedSpeed {
            speed: seg_speed,
            class,
        };
        let tol = self.effective_tolerance(seg.path_mode);
        let end_rule = match seg.path_mode {
            PathMode::ExactStop => EndRule::Stop,
            PathMode::ExactPath => EndRule::TangentOnly,
            PathMode::Continuous { .. } => EndRule::Blend {
                tolerance: tol.unwrap_or(self.config.default_tolerance),
            },
        };
        let report_tol = tol.unwrap_or(0.0);
        let template = Element {
            start: self.position,
            end: self.position,
            geom: Geom::Line { dir: [0.0; 9] },
            length: 0.0,
            start_trim: 0.0,
            speed,
            velocity_cap: if seg.velocity_cap > 0.0 {
                seg.velocity_cap
            } else {
                f64::INFINITY
            },
            accel_cap: seg.acceleration_cap,
            soft: seg.profile == stanok_canon::AccelerationProfile::Soft,
            line: seg.line,
            seq: self.seq,
            spindles: seg.spindles,
            chord_tolerance: 0.0,
            end_rule,
            entry_stop: false,
            exact_stop: false,
            tolerance: report_tol,
        };
        match &seg.geometry {
            SegmentGeometry::Arc(h) => {
                // The path is continuous whatever the caller says: if the machine is not where
                // the arc starts (a segment before it was dropped), a line takes it there.
                let here = self.position;
                if norm9(&sub9(&seg.start, &here)) > 1e-9 {
                    let mut join = template;
                    join.end_rule = EndRule::Stop;
                    self.push_line(here, seg.start, join, out);
                }
                match HelixCurve::of_segment(h, &seg.start, &seg.end) {
                    Some((curve, sweep)) => {
                        let mut e = template;
                        e.start = seg.start;
                        e.end = seg.end;
                        e.geom = Geom::Helix { curve, theta0: 0.0 };
                        e.length = curve.rho * sweep;
                        self.push_element(e, out);
                    }
                    None => self.push_line(seg.start, seg.end, template, out),
                }
            }
            SegmentGeometry::Line => self.push_line(self.position, seg.end, template, out),
            SegmentGeometry::Polyline(p) => {
                let mut points = std::mem::take(&mut self.scratch);
                points.clear();
                points.extend_from_slice(p);
                if let Some(first) = points.first_mut() {
                    *first = self.position;
                }
                let mut chord = template;
                chord.chord_tolerance = SPLINE_CHORD_TOLERANCE;
                let count = points.len();
                for k in 1..count {
                    // Inside the spline: chord and blend 0.5 µm each (module doc, step 1).
                    chord.end_rule = if k + 1 == count {
                        end_rule
                    } else {
                        EndRule::Blend {
                            tolerance: 2.0 * SPLINE_CHORD_TOLERANCE,
                        }
                    };
                    self.push_line(points[k - 1], points[k], chord, out);
                }
                self.scratch = points;
            }
        }
    }

    /// A straight element from `a` to `b` with the properties of `template`.
    fn push_line(&mut self, a: Point9, b: Point9, template: Element, out: &mut impl FnMut(Piece)) {
        let delta = sub9(&b, &a);
        let length = norm9(&delta);
        let mut e = template;
        e.start = a;
        e.end = b;
        e.length = length;
        e.geom = Geom::Line {
            dir: delta.map(|d| d / length),
        };
        self.push_element(e, out);
    }

    fn push_element(&mut self, mut next: Element, out: &mut impl FnMut(Piece)) {
        let length = next.length;
        if length.is_nan() || length <= 0.0 || !length.is_finite() {
            // Nothing to move; the rule of this end still applies to what follows.
            if let Some(p) = &mut self.pending {
                if next.end_rule == EndRule::Stop {
                    p.end_rule = EndRule::Stop;
                }
            }
            return;
        }
        self.position = next.end;
        self.spindles = next.spindles;
        match self.pending.take() {
            None => next.entry_stop = true,
            Some(prev) => self.join(prev, &mut next, out),
        }
        if self.stop_next {
            next.entry_stop = true;
            self.stop_next = false;
        }
        self.pending = Some(next);
    }

    /// The junction between `prev` and `next` (module doc, step 2).
    fn join(&mut self, mut prev: Element, next: &mut Element, out: &mut impl FnMut(Piece)) {
        let (t1, k1) = prev.tangent_and_curvature(true);
        let (t2, k2) = next.tangent_and_curvature(false);
        let cos = dot9(&t1, &t2).clamp(-1.0, 1.0);
        let perp: Point9 = std::array::from_fn(|i| t2[i] - cos * t1[i]);
        let sin = norm9(&perp);
        let theta = sin.atan2(cos);
        let rule = if self.stop_next {
            EndRule::Stop
        } else {
            prev.end_rule
        };
        let soft = prev.soft || next.soft;
        let both_lines = prev.is_line() && next.is_line();
        let curvature_step = soft && !both_lines && norm9(&sub9(&k2, &k1)) > SAME_CURVATURE;
        let blend_tol = match rule {
            EndRule::Stop => None,
            _ if theta <= TANGENT_ANGLE && !curvature_step => {
                self.emit(&prev, 0.0, out);
                return;
            }
            EndRule::TangentOnly if theta <= TANGENT_ANGLE => Some(INTERNAL_TOLERANCE),
            EndRule::TangentOnly => None,
            EndRule::Blend { tolerance } => {
                Some(tolerance - prev.chord_tolerance.max(next.chord_tolerance))
            }
        };
        let Some(e) =
            blend_tol.filter(|e| *e > 0.0 && theta < std::f64::consts::PI - REVERSAL_MARGIN)
        else {
            if !self.stop_next && matches!(rule, EndRule::Stop | EndRule::TangentOnly) {
                prev.exact_stop = true;
                next.exact_stop = true;
            }
            self.emit(&prev, 0.0, out);
            next.entry_stop = true;
            return;
        };
        let d = if !both_lines {
            self.emit_smooth(&prev, next, e, out)
        } else if soft {
            self.emit_clothoid(&prev, next, e, theta, cos, sin, out)
        } else {
            self.emit_arc(&prev, next, e, theta, sin, &perp, out)
        };
        let Some(d) = d else {
            self.emit(&prev, 0.0, out);
            next.entry_stop = true;
            return;
        };
        next.start_trim = d;
    }

    /// A junction with an arc: the smooth blend of the two curves within `e` (see
    /// [`crate::curve`]). Emits `prev` less the cut and the blend; returns the length cut from
    /// each, or None (nothing emitted) if no blend of useful size exists.
    fn emit_smooth(
        &self,
        prev: &Element,
        next: &Element,
        e: f64,
        out: &mut impl FnMut(Piece),
    ) -> Option<f64> {
        let d_max = (0.5 * prev.length).min(0.5 * next.length);
        let blend = Blend::new(prev.side_at_end(), next.side_at_start(), e, d_max)?;
        let d = blend.d;
        self.emit(prev, d, out);
        let end = next.side_at_start().at(d).p;
        let deviation = blend.deviation + prev.chord_tolerance.max(next.chord_tolerance);
        let length = blend.length();
        out(self.limited(Piece {
            end,
            shape: Shape::Blend(Arc::new(blend)),
            length,
            speeds: [prev.speed, next.speed],
            velocity_cap: prev.velocity_cap.min(next.velocity_cap),
            accel_cap: prev.accel_cap.min(next.accel_cap),
            v_max: 0.0,
            a_max: 0.0,
            j_max: 0.0,
            soft: prev.soft || next.soft,
            entry_stop: false,
            exact_stop: false,
            line: next.line,
            seq: next.seq,
            junction: prev.seq != next.seq,
            spindles: prev.spindles,
            deviation,
            tolerance: prev.tolerance.max(next.tolerance),
        }));
        Some(d)
    }

    /// BRISK: the circular blend of the corner between two straight elements within `e` (module
    /// doc, step 2). Emits `prev` less the cut and the arc; returns the length cut from each, or
    /// None (nothing emitted) if the blend would be degenerate.
    #[allow(clippy::too_many_arguments)]
    fn emit_arc(
        &self,
        prev: &Element,
        next: &Element,
        e: f64,
        theta: f64,
        sin: f64,
        perp: &Point9,
        out: &mut impl FnMut(Piece),
    ) -> Option<f64> {
        let d = (e / (0.25 * theta).tan())
            .min(0.5 * prev.length)
            .min(0.5 * next.length);
        let radius = d / (0.5 * theta).tan();
        if !(d > 1e-12 && radius.is_finite() && radius > 1e-12) {
            return None;
        }
        self.emit(prev, d, out);
        let (pdir, ndir) = (prev.dir(), next.dir());
        let n1: Point9 = perp.map(|x| x / sin);
        let corner = prev.end;
        let p1: Point9 = std::array::from_fn(|i| corner[i] - d * pdir[i]);
        let centre: Point9 = std::array::from_fn(|i| p1[i] + radius * n1[i]);
        let e1 = n1.map(|x| -x);
        let e2 = pdir;
        let exit: Point9 = std::array::from_fn(|i| corner[i] + d * ndir[i]);
        out(self.limited(Piece {
            end: exit,
            shape: Shape::Arc {
                centre,
                e1,
                e2,
                radius,
            },
            length: radius * theta,
            speeds: [prev.speed, next.speed],
            velocity_cap: prev.velocity_cap.min(next.velocity_cap),
            accel_cap: prev.accel_cap.min(next.accel_cap),
            v_max: 0.0,
            a_max: 0.0,
            j_max: 0.0,
            soft: false,
            entry_stop: false,
            exact_stop: false,
            line: next.line,
            seq: next.seq,
            junction: prev.seq != next.seq,
            spindles: prev.spindles,
            deviation: d * (0.25 * theta).tan() + prev.chord_tolerance.max(next.chord_tolerance),
            tolerance: prev.tolerance.max(next.tolerance),
        }));
        Some(d)
    }

    /// SOFT: the clothoid blend of the corner between two straight elements (see
    /// [`crate::clothoid`]). The unit shape for the half-turning angle φ = θ/2 gives the cut
    /// d = ℓ·D(φ) and the largest distance from the two elements ℓ·Fs(φ); the half length is
    /// ℓ = min(e/Fs, L_in/(2D), L_out/(2D)), so the blend is within `e` of them and takes at most
    /// half of each. Emits `prev` less the cut and the blend; returns d, or None (nothing
    /// emitted) if the blend would be degenerate.
    #[allow(clippy::too_many_arguments)]
    fn emit_clothoid(
        &self,
        prev: &Element,
        next: &Element,
        e: f64,
        theta: f64,
        cos: f64,
        sin: f64,
        out: &mut impl FnMut(Piece),
    ) -> Option<f64> {
        let phi = 0.5 * theta;
        let unit = unit_shape(phi);
        let half = (e / unit.from_chords)
            .min(0.5 * prev.length / unit.cut)
            .min(0.5 * next.length / unit.cut);
        let d = half * unit.cut;
        if !(d > 1e-12 && half > 1e-12 && half.is_finite()) {
            return None;
        }
        self.emit(prev, d, out);
        let clothoid = Clothoid {
            corner: prev.end,
            t1: prev.dir(),
            t2: next.dir(),
            cut: d,
            half,
            phi,
            cos_turn: cos,
            sin_turn: sin,
        };
        out(self.limited(Piece {
            end: clothoid.end(),
            shape: Shape::Clothoid(clothoid),
            length: clothoid.length(),
            speeds: [prev.speed, next.speed],
            velocity_cap: prev.velocity_cap.min(next.velocity_cap),
            accel_cap: prev.accel_cap.min(next.accel_cap),
            v_max: 0.0,
            a_max: 0.0,
            j_max: 0.0,
            soft: true,
            entry_stop: false,
            exact_stop: false,
            line: next.line,
            seq: next.seq,
            junction: prev.seq != next.seq,
            spindles: prev.spindles,
            deviation: half * unit.from_chords + prev.chord_tolerance.max(next.chord_tolerance),
            tolerance: prev.tolerance.max(next.tolerance),
        }));
        Some(d)
    }

    /// Emits an element less its start trim and `end_trim`.
    fn emit(&self, c: &Element, end_trim: f64, out: &mut impl FnMut(Piece)) {
        let length = c.length - c.start_trim - end_trim;
        if length.is_nan() || length <= 0.0 {
            return;
        }
        let (shape, end) = match c.geom {
            Geom::Line { dir } => {
                let start: Point9 = std::array::from_fn(|i| c.start[i] + c.start_trim * dir[i]);
                let end: Point9 = if end_trim == 0.0 {
                    c.end
                } else {
                    std::array::from_fn(|i| c.end[i] - end_trim * dir[i])
                };
                (Shape::Line { start, dir }, end)
            }
            Geom::Helix { curve, theta0 } => {
                // The same expressions as the blends' sides (`BlendSide::at`), so that pieces
                // meet bit for bit.
                let theta = theta0 + c.start_trim / curve.rho;
                let end = if end_trim == 0.0 {
                    c.end
                } else {
                    let theta_end = Element::theta_end(&curve, theta0, c.length);
                    curve.at(theta_end + (-end_trim) / curve.rho).p
                };
                (Shape::Helix { curve, theta }, end)
            }
        };
        out(self.limited(Piece {
            end,
            shape,
            length,
            speeds: [c.speed, c.speed],
            velocity_cap: c.velocity_cap,
            accel_cap: c.accel_cap,
            v_max: 0.0,
            a_max: 0.0,
            j_max: 0.0,
            soft: c.soft,
            entry_stop: c.entry_stop && c.start_trim == 0.0,
            exact_stop: c.exact_stop,
            line: c.line,
            seq: c.seq,
            junction: false,
            spindles: c.spindles,
            deviation: c.chord_tolerance,
            tolerance: c.tolerance,
        }));
    }

    /// The piece with its speed, acceleration and jerk limits at the initial overrides.
    #[inline]
    fn limited(&self, mut piece: Piece) -> Piece {
        let cap = piece.programmed_speed(&self.overrides);
        let (v, a, j) = shape_limits(
            &piece.shape,
            piece.length,
            piece.soft,
            cap,
            &self.config.axes,
        );
        let (a, j) = cap_acceleration(a, j, piece.accel_cap);
        piece.v_max = v;
        piece.a_max = a;
        piece.j_max = j;
        piece
    }
}

fn dwell_piece(at: Point9, seconds: f64, line: u32, seq: u64, spindles: Spindles) -> Piece {
    let fixed = ProgrammedSpeed {
        speed: 0.0,
        class: SpeedClass::Fixed,
    };
    Piece {
        end: at,
        shape: Shape::Dwell { at, seconds },
        length: 0.0,
        speeds: [fixed, fixed],
        velocity_cap: f64::INFINITY,
        accel_cap: f64::INFINITY,
        v_max: 0.0,
        a_max: 0.0,
        j_max: 0.0,
        soft: false,
        entry_stop: true,
        exact_stop: false,
        line,
        seq,
        junction: false,
        spindles,
        deviation: 0.0,
        tolerance: 0.0,
    }
}
