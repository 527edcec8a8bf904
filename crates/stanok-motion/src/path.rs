//! The path builder: programmed segments → tangent-continuous pieces (lines and blends: circular
//! arcs in BRISK, clothoid pairs in SOFT).
//!
//! ## Algorithm
//! 1. **Chords.** A line is one chord. An arc (helix, spiral) is cut into n equal-angle chords with
//!    n = ⌈sweep / √(8·t_c / r_max)⌉ (the sagitta rule: every chord within t_c of the arc); a spline
//!    arrives already as chords within 1 µm ([`SPLINE_CHORD_TOLERANCE`]).
//! 2. **Junctions.** Where two chords meet, the rule of the first one's end applies:
//!    * *stop* (G60/G61 exact stop at a block end, a forced stop, a reversal): the piece after it
//!      starts from rest;
//!    * *tangent only* (G61.1 exact path at a block end): pass at speed if the chords are tangent
//!      (turning angle ≤ 1e-9 rad), otherwise stop;
//!    * *blend within e* (G64 P at a block end; every vertex inside an arc or a spline): replace the
//!      corner by the circular arc tangent to both chords whose distance from the corner is
//!      e_d = d·tan(θ/4) ≤ e, where θ is the turning angle and d the length cut from each chord:
//!      d = min(e / tan(θ/4), L_in/2, L_out/2); radius r = d / tan(θ/2). Half of each chord at most
//!      goes to each of its two corners, so blends never overlap. Collinear chords pass unblended.
//!      **SOFT** (either chord SOFT) replaces the circle by a symmetric pair of clothoids, whose
//!      curvature runs 0 → 2φ/ℓ → 0 ([`crate::clothoid`]; same plane, same half-chord rule, and
//!      every point within e of the chords — measured from the chords rather than the corner). A
//!      line meets such a blend with equal (zero) curvature, so the axis accelerations stay
//!      continuous and the servo trace's finite-difference jerk stays within the axis limits. A
//!      SOFT path has no curvature step at any join (lines and clothoid ends have κ = 0; the two
//!      halves meet at equal κ; a corner that cannot be blended is a stop; dwells and the
//!      tool-centre-point segments, which end in exact stops, join at rest), so no join needs a
//!      speed cap of its own.
//! 3. **Tolerances.** Under G64 with tolerance P (or the default when P is absent): arcs get
//!    t_c = P/2 and their inner corners e = P/2; a block-end corner gets e = P − max(t_c of both
//!    chords). So every point of a blend is within e of a chord and every chord within t_c of the
//!    programmed curve: the path stays within P. Under G60/G61/G61.1, arcs and splines use 1 µm chords
//!    and 1 µm inner blends ([`INTERNAL_TOLERANCE`]); block ends are met exactly.
//! 4. **Limits per piece** (see [`crate::piece`]): lines by projecting the axis limits on the
//!    direction, arcs and clothoids by the conservative bound over their plane plus the
//!    centripetal (and in SOFT the turning-jerk) share; a blend runs at most at the lower of the
//!    two programmed feeds.
//!
//! ## Invariants
//! * Consecutive pieces share their end point and, unless the second starts from rest, their
//!   tangent (to rounding): axis velocities are continuous.
//! * Memory: one pending chord plus the chords of the current segment (≤ 100 000 for one arc).
//! * Zero-length chords are dropped; segments with non-finite coordinates are dropped whole.

use crate::clothoid::{unit_shape, Clothoid};
use crate::limits::MotionConfig;
use crate::piece::{cap_acceleration, shape_limits, Overrides, Piece, ProgrammedSpeed, Shape};
use crate::segment::{
    PathSegment, PlannerInput, Point9, SegmentGeometry, Spindles, SPLINE_CHORD_TOLERANCE,
};
use stanok_canon::PathMode;

/// Chord and blend tolerance inside arcs and splines under exact-stop and exact-path modes, mm.
pub const INTERNAL_TOLERANCE: f64 = 1e-3;
/// Turning angles at or below this (rad) pass without blend or stop.
pub const TANGENT_ANGLE: f64 = 1e-9;
/// Turning angles closer than this to π (rad) are reversals: stop.
const REVERSAL_MARGIN: f64 = 1e-6;
/// Most chords of one arc.
const MAX_ARC_CHORDS: usize = 100_000;

/// What happens where a chord ends.
#[derive(Debug, Clone, Copy, PartialEq)]
enum EndRule {
    Stop,
    TangentOnly,
    Blend { tolerance: f64 },
}

/// A chord whose end is not yet known to be trimmed.
#[derive(Debug, Clone, Copy)]
struct Chord {
    start: Point9,
    /// Exact end point (the programmed one).
    end: Point9,
    dir: Point9,
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
    command: u64,
    spindles: Spindles,
    chord_tolerance: f64,
    end_rule: EndRule,
    entry_stop: bool,
    /// Path tolerance in force (for the report).
    tolerance: f64,
}

/// Turns planner input into pieces (module doc).
#[derive(Debug, Clone)]
pub struct PathBuilder {
    config: MotionConfig,
    /// The overrides pieces are first limited with (the run's initial ones; the planner limits
    /// them again when the factors in force differ).
    overrides: Overrides,
    pending: Option<Chord>,
    stop_next: bool,
    /// End of the last chord received (exact programmed point).
    position: Point9,
    /// The spindle speed of the last segment received (dwells keep it).
    spindles: Spindles,
    /// The command serial of the last segment received (dwells keep it).
    command: u64,
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
            command: 0,
            scratch: Vec::new(),
        }
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
                        self.command,
                        self.spindles,
                    ));
                }
                self.stop_next = true;
            }
            PlannerInput::Segment(seg) => self.push_segment(&seg, out),
        }
    }

    /// Sets where the machine stands (the start of the program, or after a probe). Any pending
    /// chord is flushed first.
    pub fn set_position(&mut self, at: Point9, out: &mut impl FnMut(Piece)) {
        self.flush(out);
        self.position = at;
    }

    /// Emits the pending chord: the path ends or stops there.
    pub fn flush(&mut self, out: &mut impl FnMut(Piece)) {
        if let Some(c) = self.pending.take() {
            self.emit_line(&c, 0.0, out);
        }
        self.stop_next = true;
    }

    fn push_segment(&mut self, seg: &PathSegment, out: &mut impl FnMut(Piece)) {
        if !finite9(&seg.start) || !finite9(&seg.end) {
            return;
        }
        // The adapter always gives a positive finite speed; anything else runs at the maximum feed.
        let mut seg_speed = seg.path_speed;
        if !(seg_speed.is_finite() && seg_speed > 0.0) {
            seg_speed = self.config.max_feed;
        }
        let class = if seg.rapid {
            crate::segment::SpeedClass::Rapid
        } else {
            seg.speed_class
        };
        let seg_speed = ProgrammedSpeed {
            speed: seg_speed,
            class,
        };
        let tol = self.effective_tolerance(seg.path_mode);
        let chord_tol = match tol {
            Some(p) => 0.5 * p,
            None => INTERNAL_TOLERANCE,
        };
        let end_rule = match seg.path_mode {
            PathMode::ExactStop => EndRule::Stop,
            PathMode::ExactPath => EndRule::TangentOnly,
            PathMode::Continuous { .. } => EndRule::Blend {
                tolerance: tol.unwrap_or(self.config.default_tolerance),
            },
        };
        let report_tol = tol.unwrap_or(0.0);
        let mut points = std::mem::take(&mut self.scratch);
        points.clear();
        let this_chord_tol = match &seg.geometry {
            SegmentGeometry::Line => {
                points.push(seg.start);
                points.push(seg.end);
                0.0
            }
            SegmentGeometry::Arc(h) => {
                let sweep = h.sweep();
                let r = h.start_radius().max(h.end_radius());
                let step = (8.0 * chord_tol / r).sqrt();
                let n = ((sweep / step).ceil() as usize).clamp(1, MAX_ARC_CHORDS);
                points.push(seg.start);
                for k in 1..n {
                    let f = k as f64 / n as f64;
                    let xyz = h.point_at(f);
                    let mut q = [0.0; 9];
                    q[..3].copy_from_slice(&xyz);
                    for (i, qi) in q.iter_mut().enumerate().skip(3) {
                        *qi = seg.start[i] + (seg.end[i] - seg.start[i]) * f;
                    }
                    points.push(q);
                }
                points.push(seg.end);
                chord_tol
            }
            SegmentGeometry::Polyline(p) => {
                points.extend_from_slice(p);
                SPLINE_CHORD_TOLERANCE
            }
        };
        // A blend rule's tolerance is the whole distance allowed from the programmed path; the
        // blend itself gets what the chords leave of it (`join`).
        let inner_rule = EndRule::Blend {
            tolerance: tol.unwrap_or(2.0 * INTERNAL_TOLERANCE),
        };
        // The path is continuous whatever the caller says: the first chord starts where the
        // machine is (the programmed start, unless a segment was dropped before this one).
        if let Some(first) = points.first_mut() {
            *first = self.position;
        }
        let count = points.len();
        for k in 1..count {
            let rule = if k + 1 == count { end_rule } else { inner_rule };
            self.push_chord(
                &points[k - 1],
                &points[k],
                seg,
                seg_speed,
                this_chord_tol,
                rule,
                report_tol,
                out,
            );
        }
        self.scratch = points;
    }

    #[allow(clippy::too_many_arguments)]
    fn push_chord(
        &mut self,
        a: &Point9,
        b: &Point9,
        seg: &PathSegment,
        speed: ProgrammedSpeed,
        chord_tolerance: f64,
        end_rule: EndRule,
        tolerance: f64,
        out: &mut impl FnMut(Piece),
    ) {
        let delta = sub9(b, a);
        let length = norm9(&delta);
        if length.is_nan() || length <= 0.0 || !length.is_finite() {
            // Nothing to move; the rule of this end still applies to what follows.
            if let Some(p) = &mut self.pending {
                if end_rule == EndRule::Stop {
                    p.end_rule = EndRule::Stop;
                }
            }
            return;
        }
        let dir = delta.map(|d| d / length);
        self.position = *b;
        self.spindles = seg.spindles;
        self.command = seg.command;
        let mut next = Chord {
            start: *a,
            end: *b,
            dir,
            length,
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
            command: seg.command,
            spindles: seg.spindles,
            chord_tolerance,
            end_rule,
            entry_stop: false,
            tolerance,
        };
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

    /// The corner between `prev` and `next` (module doc, step 2).
    fn join(&mut self, prev: Chord, next: &mut Chord, out: &mut impl FnMut(Piece)) {
        let cos = dot9(&prev.dir, &next.dir).clamp(-1.0, 1.0);
        let perp: Point9 = std::array::from_fn(|i| next.dir[i] - cos * prev.dir[i]);
        let sin = norm9(&perp);
        let theta = sin.atan2(cos);
        let rule = if self.stop_next {
            EndRule::Stop
        } else {
            prev.end_rule
        };
        let blend_tol = match rule {
            EndRule::Stop => None,
            _ if theta <= TANGENT_ANGLE => {
                self.emit_line(&prev, 0.0, out);
                return;
            }
            EndRule::TangentOnly => None,
            EndRule::Blend { tolerance } => {
                Some(tolerance - prev.chord_tolerance.max(next.chord_tolerance))
            }
        };
        let Some(e) =
            blend_tol.filter(|e| *e > 0.0 && theta < std::f64::consts::PI - REVERSAL_MARGIN)
        else {
            self.emit_line(&prev, 0.0, out);
            next.entry_stop = true;
            return;
        };
        let soft = prev.soft || next.soft;
        let d = if soft {
            self.emit_clothoid(&prev, next, e, theta, cos, sin, &perp, out)
        } else {
            self.emit_arc(&prev, next, e, theta, sin, &perp, out)
        };
        let Some(d) = d else {
            self.emit_line(&prev, 0.0, out);
            next.entry_stop = true;
            return;
        };
        next.start_trim = d;
    }

    /// BRISK: the circular blend of the corner between `prev` and `next` within `e` (module doc,
    /// step 2). Emits `prev` less the cut and the arc; returns the length cut from each chord, or
    /// None (nothing emitted) if the blend would be degenerate.
    #[allow(clippy::too_many_arguments)]
    fn emit_arc(
        &self,
        prev: &Chord,
        next: &Chord,
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
        self.emit_line(prev, d, out);
        let n1: Point9 = perp.map(|x| x / sin);
        let corner = prev.end;
        let p1: Point9 = std::array::from_fn(|i| corner[i] - d * prev.dir[i]);
        let centre: Point9 = std::array::from_fn(|i| p1[i] + radius * n1[i]);
        let e1 = n1.map(|x| -x);
        let e2 = prev.dir;
        let exit: Point9 = std::array::from_fn(|i| corner[i] + d * next.dir[i]);
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
            line: next.line,
            command: next.command,
            spindles: prev.spindles,
            deviation: d * (0.25 * theta).tan() + prev.chord_tolerance.max(next.chord_tolerance),
            tolerance: prev.tolerance.max(next.tolerance),
        }));
        Some(d)
    }

    /// SOFT: the clothoid blend of the corner (see [`crate::clothoid`]). The unit shape for the
    /// half-turning angle φ = θ/2 gives the cut d = ℓ·D(φ) and the largest distance from the two
    /// chords ℓ·Fs(φ); the half length is ℓ = min(e/Fs, L_in/(2D), L_out/(2D)), so the blend is
    /// within `e` of the chords and takes at most half of each. Emits `prev` less the cut and the
    /// blend; returns d, or None (nothing emitted) if the blend would be degenerate.
    #[allow(clippy::too_many_arguments)]
    fn emit_clothoid(
        &self,
        prev: &Chord,
        next: &Chord,
        e: f64,
        theta: f64,
        cos: f64,
        sin: f64,
        perp: &Point9,
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
        self.emit_line(prev, d, out);
        let clothoid = Clothoid {
            corner: prev.end,
            t1: prev.dir,
            t2: next.dir,
            cut: d,
            half,
            phi,
            cos_turn: cos,
            sin_turn: sin,
        };
        let _ = perp;
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
            line: next.line,
            command: next.command,
            spindles: prev.spindles,
            deviation: half * unit.from_chords + prev.chord_tolerance.max(next.chord_tolerance),
            tolerance: prev.tolerance.max(next.tolerance),
        }));
        Some(d)
    }

    /// Emits a chord less its start trim and `end_trim`.
    fn emit_line(&self, c: &Chord, end_trim: f64, out: &mut impl FnMut(Piece)) {
        let length = c.length - c.start_trim - end_trim;
        if length.is_nan() || length <= 0.0 {
            return;
        }
        let start: Point9 = std::array::from_fn(|i| c.start[i] + c.start_trim * c.dir[i]);
        let end: Point9 = if end_trim == 0.0 {
            c.end
        } else {
            std::array::from_fn(|i| c.end[i] - end_trim * c.dir[i])
        };
        out(self.limited(Piece {
            end,
            shape: Shape::Line { start, dir: c.dir },
            length,
            speeds: [c.speed, c.speed],
            velocity_cap: c.velocity_cap,
            accel_cap: c.accel_cap,
            v_max: 0.0,
            a_max: 0.0,
            j_max: 0.0,
            soft: c.soft,
            entry_stop: c.entry_stop && c.start_trim == 0.0,
            line: c.line,
            command: c.command,
            spindles: c.spindles,
            deviation: c.chord_tolerance,
            tolerance: c.tolerance,
        }));
    }

    /// The piece with its speed, acceleration and jerk limits at the initial overrides.
    #[inline]
    fn limited(&self, mut piece: Piece) -> Piece {
        let cap = piece.programmed_speed(&self.overrides);
        let (v, a, j) = shape_limits(&piece.shape, cap, &self.config.axes);
        let (a, j) = cap_acceleration(a, j, piece.accel_cap);
        piece.v_max = v;
        piece.a_max = a;
        piece.j_max = j;
        piece
    }
}

fn dwell_piece(at: Point9, seconds: f64, line: u32, command: u64, spindles: Spindles) -> Piece {
    let fixed = ProgrammedSpeed {
        speed: 0.0,
        class: crate::segment::SpeedClass::Fixed,
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
        line,
        command,
        spindles,
        deviation: 0.0,
        tolerance: 0.0,
    }
}
