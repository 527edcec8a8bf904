//! RS274/NGC canned cycles G73, G74, G76 excluded (see `sync.rs`), G81–G89, with G98/G99, sticky
//! words and L repeats — LinuxCNC's sequences, call for call (spec rs274ngc §4.33–§4.45; where the
//! document is thin, LinuxCNC 2.9's `rs274` is the oracle and the probes are in tests/rs274).
//!
//! ## The frame of a cycle
//!
//! A cycle works in the active plane: `aa`, `bb` are the plane's two axes (X, Y in G17; Z, X in
//! G18; Y, Z in G19) and `cc` the plane normal, the drilling axis. All values are program
//! coordinates in mm.
//!
//! ## Set-up, once per block (LinuxCNC's `convert_cycle_xy` and its two siblings)
//!
//! 1. The normal-axis word (Z in G17) is required unless the block continues the same cycle, which
//!    then reuses the previous one (`cycle_cc`); R likewise (`cycle_r`). L defaults to 1 and is
//!    never sticky; L0 is an error.
//! 2. The *initial level* `il` is the normal-axis position when the series began (the first cycle
//!    block after a non-cycle motion mode); every block of the series measures from it.
//! 3. G90: `r = R`, `bottom = Z`, the hole at the given plane words (else the current position).
//!    G91: `r = il + R`, `bottom = r + Z`, the plane words are increments added once per repeat.
//!    `r < bottom` is an error.
//! 4. If `il < r` the tool first rapids along the normal axis to `r` where it stands (even down, if
//!    it stands higher — LinuxCNC's reading, corpus derived-canned-series-lowered-r), and `il` is
//!    taken as `r` for this block.
//! 5. The clear level is `r` under G99 and `il` under G98. Under G91 the repeats travel at the
//!    clear level from the first hole on (LinuxCNC 2.9's trace; G90 travels the first hole at `il`).
//! 6. Motion control is switched to exact path for the cycle (`SET_MOTION_CONTROL_MODE`) and back
//!    afterwards, unless exact path was already in force.
//!
//! ## One hole (repeated L times)
//!
//! rapid in the plane at the travel level → rapid to `r` if the travel level differs → the cycle's
//! own moves (the table in `hole`) → the travel level becomes the clear level.
//!
//! After the block the position is the last hole at the clear level (also after G88, whose retract
//! is the operator's: LinuxCNC emits no move for it and neither does Stanok — the next move starts
//! from the clear level).
//!
//! Invariant: the number of holes and pecks is bounded ([`MAX_REPEATS`], [`MAX_PECKS`]); beyond it
//! the block is refused with a diagnostic instead of hanging.

use super::Rs274State;
use crate::codes::*;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::state::{DistanceMode, PathMode};
use stanok_canon::{Canon, Diagnostic, FeedMode, LengthUnits, Plane, Pose, SpindleDirection};
use stanok_syntax::ColSpan;

/// Most holes one block may drill (L).
pub const MAX_REPEATS: u32 = 100_000;
/// Most pecks one G73/G83 hole may take.
pub const MAX_PECKS: f64 = 100_000.0;

/// The geometry of one block's cycle, in program mm.
#[derive(Debug, Clone, Copy)]
struct CycleFrame {
    /// Plane axes and the drilling axis (indices into Pose order).
    a: usize,
    b: usize,
    n: usize,
    r: f64,
    bottom: f64,
    clear: f64,
    /// R and the bottom in program units as LinuxCNC computes them (G73/G83 step their pecks
    /// from these: see `hole`).
    r_units: f64,
    bottom_units: f64,
}

/// LinuxCNC's plane name in its cycle messages.
fn plane_name(plane: Plane) -> &'static str {
    match plane {
        Plane::XY => "xy",
        Plane::ZX => "xz",
        Plane::YZ => "yz",
    }
}

/// Executes a canned-cycle block (G73, G74, G81…G89).
pub(super) fn canned_cycle(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    let (a, b, n) = plane.axes();
    let same_series = cx.fe.modes.motion_code == Some(code);
    let g = format!("g{}", code / 10);
    // Feed checks come first in LinuxCNC (before any other word is looked at).
    if cx.st.feed_mode == FeedMode::InverseTime {
        return Err(cx.err(
            "rs274::cycle-inverse-time",
            "Cannot use inverse time feed with canned cycles",
            span,
        ));
    }
    if cx.st.feed_mode == FeedMode::UnitsPerMinute && cx.st.feed <= 0.0 {
        return Err(cx.err("rs274::zero-feed", "Cannot feed with zero feed rate", span));
    }
    for (k, &letter) in AXIS_WORDS.iter().enumerate().skip(3) {
        if let Some(w) = cx.words.take(letter) {
            return Err(cx.err(
                "rs274::cycle-axis",
                format!(
                    "Cannot put a{} {} in canned cycle",
                    if k == 3 || k == 6 { "n" } else { "" },
                    (letter as char).to_ascii_lowercase()
                ),
                w.span,
            ));
        }
    }
    let r_word = cx.words.take(b'R');
    let r_value = match r_word {
        Some(r) => cx.mm(r.v),
        None if same_series => cx.fe.modes.cycle_r,
        None => {
            return Err(cx.err(
                "rs274::cycle-r-missing",
                "R clearance plane unspecified in cycle",
                span,
            ))
        }
    };
    let repeats = match cx.words.take(b'L') {
        Some(l) => {
            if l.v.fract() != 0.0 {
                return Err(cx.err(
                    "rs274::non-integer",
                    "Non integer value for integer",
                    l.span,
                ));
            }
            if l.v <= 0.0 {
                return Err(cx.err(
                    "rs274::cycle-zero-repeats",
                    "Cannot do zero repeats of cycle",
                    l.span,
                ));
            }
            if l.v > MAX_REPEATS as f64 {
                return Err(cx
                    .err("rs274::cycle-repeats", "Too many repeats of cycle", l.span)
                    .with_note(format!("at most {MAX_REPEATS} holes per block")));
            }
            l.v as u32
        }
        None => 1,
    };
    let n_word = cx.words.take(AXIS_WORDS[n]);
    let cc_value = match n_word {
        Some(w) => cx.mm(w.v),
        None if same_series => cx.fe.modes.cycle_cc,
        None => {
            return Err(cx.err(
                "rs274::cycle-normal-missing",
                format!(
                    "{} value unspecified in {} plane canned cycle",
                    AXIS_WORDS[n] as char,
                    plane_name(plane)
                ),
                span,
            ))
        }
    };
    let aw = cx.words.take(AXIS_WORDS[a]).map(|w| cx.mm(w.v));
    let bw = cx.words.take(AXIS_WORDS[b]).map(|w| cx.mm(w.v));
    // LinuxCNC's polar words in the XY plane: G90 places the hole at radius @, angle ^ about the
    // origin (the current point's own where one is missing); G91 adds them once per repeat.
    let radius = cx.words.take(b'@').map(|w| cx.mm(w.v));
    let angle = cx.words.take(b'^').map(|w| w.v.to_radians());
    let polar = (radius.is_some() || angle.is_some()).then_some((radius, angle));
    if polar.is_some() && plane != Plane::XY {
        return Err(cx.err(
            "rs274::polar-plane",
            "Polar coordinates only in the XY plane",
            span,
        ));
    }
    // After G40 LinuxCNC's current point is the programmed one, not the compensated tool's.
    let pos = cx.programmed_position().to_array();
    let il = if cx.fe.modes.cycle_il_set {
        cx.fe.modes.cycle_il
    } else {
        pos[n]
    };
    let incremental = cx.st.distance == DistanceMode::Incremental;
    let (r, bottom, mut aa, mut bb, da, db) = if incremental {
        let r = r_value + il;
        (
            r,
            r + cc_value,
            pos[a],
            pos[b],
            aw.unwrap_or(0.0),
            bw.unwrap_or(0.0),
        )
    } else {
        (
            r_value,
            cc_value,
            aw.unwrap_or(pos[a]),
            bw.unwrap_or(pos[b]),
            0.0,
            0.0,
        )
    };
    let mut polar_step = (0.0, 0.0);
    if let Some((radius, angle)) = polar {
        let (r0, t0) = (aa.hypot(bb), bb.atan2(aa));
        if incremental {
            polar_step = (radius.unwrap_or(0.0), angle.unwrap_or(0.0));
        } else {
            let (rr, tt) = (radius.unwrap_or(r0), angle.unwrap_or(t0));
            aa = rr * tt.cos();
            bb = rr * tt.sin();
        }
    }
    if r < bottom {
        return Err(cx.err(
            "rs274::cycle-r-below-bottom",
            format!(
                "R less than {} in cycle in {} plane",
                (AXIS_WORDS[n] as char).to_ascii_lowercase(),
                plane_name(plane)
            ),
            span,
        ));
    }
    // Per-cycle words, checked before anything moves.
    let words = CycleWords::read(cx, code, &g, same_series, incremental, bottom, span)?;
    let direction = cx.fe.modes.spindle_direction;
    match code {
        // LinuxCNC 2.9's messages: a stopped spindle first, then the wrong direction.
        G74 | G84 if direction.is_none() || !cx.st.spindle_on[0] => {
            return Err(cx.err(
                "rs274::tap-spindle",
                format!(
                    "Spindle not turning in {}",
                    if code == G74 { "G74" } else { "G84" }
                ),
                span,
            ))
        }
        G84 if direction != Some(SpindleDirection::Clockwise) => {
            return Err(cx.err(
                "rs274::g84-spindle",
                "Spindle turning counterclockwise in G84",
                span,
            ))
        }
        G74 if direction != Some(SpindleDirection::CounterClockwise) => {
            return Err(cx.err(
                "rs274::g74-spindle",
                "Spindle turning clockwise in G74",
                span,
            ))
        }
        G86 | G87 | G88 if direction.is_none() || !cx.st.spindle_on[0] => {
            return Err(cx.err(
                "rs274::cycle-spindle",
                format!("Spindle not turning in {g} canned cycle"),
                span,
            ))
        }
        _ => {}
    }
    if let Some(pecks) = words.q.map(|q| (r - bottom) / q) {
        if pecks > MAX_PECKS {
            return Err(cx
                .err("rs274::cycle-pecks", "Too many pecks in cycle", span)
                .with_note(format!("at most {MAX_PECKS} pecks per hole")));
        }
    }

    // Set-up step 4: below R, rise (or sink) to it where the tool stands. The level is read back
    // through the work frame, so a tool left at R by the previous hole may read a few ulp below
    // it (LinuxCNC keeps the program value): 10⁻⁹ mm is not below.
    let mut old_level = il;
    let mut current = pos[n];
    if old_level < r - 1e-9 {
        let mut p = cx.programmed_position().to_array();
        p[n] = r;
        cx.straight(true, Pose::from_array(p), 0.0);
        old_level = r;
        current = r;
    }
    let clear = if cx.st.retract_to_initial {
        old_level
    } else {
        r
    };
    // Step 5: the first hole is approached at the current level, never below R.
    let mut travel = current.max(r);
    let saved_mode = cx.st.path_mode;
    let saved_naive = cx.fe.modes.naive_cam_tolerance;
    let switch_mode = saved_mode != PathMode::ExactPath;
    if switch_mode {
        cx.out.push(Canon::SetPathMode {
            mode: stanok_canon::PathMode::ExactPath,
            naive_cam_tolerance: None,
        });
    }
    // LinuxCNC's R and bottom in program units: the words as written, or under G91 the level the
    // series began at plus R, plus the drilling-axis word — float sums whose last bit decides
    // whether one more peck comes where R − nQ is the bottom in decimal. (mm values are read back
    // to program units on a 10⁻⁹ grid, which recovers the words as written.)
    let k = cx.st.units.mm_per_unit();
    let written = |mm: f64| (mm / k * 1e9).round() / 1e9;
    let (r_units, bottom_units) = if incremental {
        let r_units = written(il) + written(r_value);
        (r_units, r_units + written(cc_value))
    } else {
        (written(r_value), written(cc_value))
    };
    let f = CycleFrame {
        a,
        b,
        n,
        r,
        bottom,
        clear,
        r_units,
        bottom_units,
    };
    for _ in 0..repeats {
        aa += da;
        bb += db;
        if polar_step != (0.0, 0.0) {
            let (r0, t0) = (aa.hypot(bb), bb.atan2(aa));
            let (rr, tt) = (r0 + polar_step.0, t0 + polar_step.1);
            aa = rr * tt.cos();
            bb = rr * tt.sin();
        }
        traverse(cx, &f, aa, bb, travel);
        // (Read back through the work frame, a level at R may be off by a few ulp: step 4.)
        if (travel - r).abs() > 1e-9 {
            traverse(cx, &f, aa, bb, r);
        }
        hole(cx, code, &f, aa, bb, &words, direction);
        travel = clear;
    }
    // The position is the last hole at the clear level, whatever the cycle's last move.
    place(cx, &f, aa, bb, clear);
    if switch_mode {
        // LinuxCNC's convert_cycle restores the mode and then the naive-CAM tolerance, whatever
        // the mode (issue 21, reproduction 3: SET_NAIVECAM_TOLERANCE after a cycle under G61.1).
        let mut restore = super::path_mode_canon(saved_mode, saved_naive);
        if let Canon::SetPathMode {
            naive_cam_tolerance,
            ..
        } = &mut restore
        {
            *naive_cam_tolerance = Some(saved_naive);
        }
        cx.out.push(restore);
    }
    let st: &mut Rs274State = &mut cx.fe.modes;
    st.cycle_il = il;
    st.cycle_il_set = true;
    st.cycle_r = r_value;
    st.cycle_cc = cc_value;
    st.motion_code = Some(code);
    if let Some(p) = words.p {
        st.cycle_p = p;
    }
    if let Some(q) = words.q {
        st.cycle_q = q;
    }
    Ok(())
}

/// The words of one cycle beyond X Y Z R L.
struct CycleWords {
    /// Dwell, s (G82, G86, G88, G89; optional for G74/G84).
    p: Option<f64>,
    /// Peck depth, mm (G73, G83).
    q: Option<f64>,
    /// G87: the offset point in the plane (relative to the hole) and the back-boring level.
    offset: [f64; 2],
    middle: f64,
}

impl CycleWords {
    fn read(
        cx: &mut Ctx<'_>,
        code: u32,
        g: &str,
        same_series: bool,
        incremental: bool,
        bottom: f64,
        span: ColSpan,
    ) -> Result<Self, Diagnostic> {
        let mut w = CycleWords {
            p: None,
            q: None,
            offset: [0.0; 2],
            middle: 0.0,
        };
        let needs_p = matches!(code, G82 | G86 | G88 | G89);
        let takes_p = needs_p || matches!(code, G74 | G84);
        if takes_p {
            w.p = match cx.words.take(b'P') {
                Some(p) => Some(p.v),
                None if same_series && needs_p => Some(cx.fe.modes.cycle_p),
                None if needs_p => {
                    return Err(cx.err(
                        "rs274::cycle-p-missing",
                        format!("Dwell time p word missing with {g}"),
                        span,
                    ))
                }
                // G74/G84 without P dwell the sticky P of any earlier cycle (LinuxCNC's
                // settings->cycle_p, 0 before any).
                None => Some(cx.fe.modes.cycle_p),
            };
        }
        if matches!(code, G73 | G83) {
            let q = match cx.words.take(b'Q') {
                Some(q) => cx.mm(q.v),
                None if same_series => cx.fe.modes.cycle_q,
                None => {
                    return Err(cx.err(
                        "rs274::cycle-q-missing",
                        format!("Q word missing with {g}"),
                        span,
                    ))
                }
            };
            if q <= 0.0 {
                return Err(cx.err(
                    "rs274::cycle-q-not-positive",
                    "Negative or zero q value used",
                    span,
                ));
            }
            w.q = Some(q);
        }
        if code == G87 {
            let (a, b, _) = cx.st.plane.axes();
            let letters = [b'I', b'J', b'K'];
            let (la, lb) = (letters[a], letters[b]);
            let ln = letters[cx.st.plane.axes().2];
            // LinuxCNC keeps I, J and K of G87 like R and Q: a block repeating the series may
            // leave them out (its settings->cycle_i/j/k).
            let get = |cx: &mut Ctx<'_>, l: u8| -> Result<f64, Diagnostic> {
                let at = usize::from(l - b'I');
                match cx.words.take(l) {
                    Some(v) => {
                        let v = cx.mm(v.v);
                        cx.fe.modes.cycle_ijk[at] = v;
                        Ok(v)
                    }
                    None if same_series => Ok(cx.fe.modes.cycle_ijk[at]),
                    None => Err(cx.err(
                        "rs274::g87-word-missing",
                        format!("{} word missing with g87", l as char),
                        span,
                    )),
                }
            };
            w.offset = [get(cx, la)?, get(cx, lb)?];
            let k = get(cx, ln)?;
            w.middle = if incremental { bottom + k } else { k };
        }
        Ok(w)
    }
}

fn point(cx: &Ctx<'_>, f: &CycleFrame, aa: f64, bb: f64, cc: f64) -> Pose {
    let mut p = cx.st.program_position().to_array();
    p[f.a] = aa;
    p[f.b] = bb;
    p[f.n] = cc;
    Pose::from_array(p)
}

fn traverse(cx: &mut Ctx<'_>, f: &CycleFrame, aa: f64, bb: f64, cc: f64) {
    let p = point(cx, f, aa, bb, cc);
    cx.straight(true, p, 0.0);
}

fn feed(cx: &mut Ctx<'_>, f: &CycleFrame, aa: f64, bb: f64, cc: f64) {
    let p = point(cx, f, aa, bb, cc);
    let feed = cx.path_feed(0.0);
    cx.straight(false, p, feed);
}

/// A feed of G74/G84. LinuxCNC 2.9 issues the tapping feeds with the coordinates of an XY-plane
/// cycle: in G18 and G19 the move goes to the hole's point with its program X Y Z rotated —
/// G18 (X, Y, Z) ← (Y, Z, X), G19 ← (Z, X, Y) — and the offsets then added as to any point —
/// while its interpreter goes on from the true point (rs274 and milltask alike: it is the
/// interpreter's doing). Stanok moves as LinuxCNC does; the next move starts from the true point,
/// the second exception to continuous motion beside G88's manual retract.
fn tap_feed(cx: &mut Ctx<'_>, f: &CycleFrame, aa: f64, bb: f64, cc: f64) {
    let p = point(cx, f, aa, bb, cc);
    let rotate: Option<fn([f64; 3]) -> [f64; 3]> = match f.n {
        1 => Some(|v| [v[1], v[2], v[0]]),
        0 => Some(|v| [v[2], v[0], v[1]]),
        _ => None,
    };
    let Some(rotate) = rotate else {
        return feed(cx, f, aa, bb, cc);
    };
    let mut v = p.to_array();
    let r = rotate([v[0], v[1], v[2]]);
    v[..3].copy_from_slice(&r);
    let p = Pose::from_array(v);
    let feed = cx.path_feed(0.0);
    cx.straight(false, p, feed);
}

/// Moves the state to a point without a move (G88's manual retract).
fn place(cx: &mut Ctx<'_>, f: &CycleFrame, aa: f64, bb: f64, cc: f64) {
    let p = point(cx, f, aa, bb, cc);
    cx.st.position = cx.st.frame.to_machine(&p);
}

fn spindle(cx: &mut Ctx<'_>, direction: SpindleDirection) {
    cx.out.push(Canon::StartSpindle {
        spindle: 0,
        direction,
    });
}

fn stop_spindle(cx: &mut Ctx<'_>) {
    cx.out.push(Canon::StopSpindle { spindle: 0 });
}

/// Tapping switches both overrides off and then back on each one that was on before it:
/// LinuxCNC keeps a feed and a speed flag (M50 P0 / M51 P0 / M49 clear them) and re-enables the
/// feed override, then the speed override, only where its flag is set.
fn overrides(cx: &mut Ctx<'_>, enabled: bool) {
    if !enabled || !cx.fe.modes.feed_override_disabled {
        cx.out.push(Canon::SetFeedOverrideEnabled { enabled });
    }
    if !enabled || !cx.fe.modes.speed_override_disabled {
        cx.out.push(Canon::SetSpindleOverrideEnabled {
            spindle: 0,
            enabled,
        });
    }
}

/// G83's (and G73's) retract before re-entering a peck: 0.010 in, or 0.254 mm in G21 programs.
fn peck_clearance(cx: &Ctx<'_>) -> f64 {
    match cx.st.units {
        LengthUnits::Inches => 0.010 * 25.4,
        LengthUnits::Millimetres => 0.254,
    }
}

/// One hole, after the tool reached R above it:
///
/// | code | moves |
/// |---|---|
/// | G81 | feed to bottom; rapid to clear |
/// | G82 | feed to bottom; dwell P; rapid to clear |
/// | G73 | for each peck Q: feed to depth, rapid up 0.010 in; feed to bottom; rapid to clear |
/// | G83 | for each peck Q: feed to depth, rapid to R, rapid to 0.010 in above the depth; feed to bottom; rapid to clear |
/// | G84/G74 | overrides off; feed to bottom; spindle stop, reverse; dwell P; feed to clear; spindle stop, forward; overrides on |
/// | G85 | feed to bottom; feed to R; rapid to clear if it differs |
/// | G86 | feed to bottom; dwell P; spindle stop; rapid to clear; spindle on |
/// | G87 | rapid to the offset point; spindle stop + orient; rapid down to bottom; rapid to the hole; spindle on; feed up to K and back to bottom; spindle stop + orient; rapid to the offset point, up to clear, back over the hole; spindle on |
/// | G88 | feed to bottom; dwell P; spindle stop; program stop; spindle on (the operator retracts) |
/// | G89 | feed to bottom; dwell P; feed to clear |
fn hole(
    cx: &mut Ctx<'_>,
    code: u32,
    f: &CycleFrame,
    aa: f64,
    bb: f64,
    w: &CycleWords,
    direction: Option<SpindleDirection>,
) {
    let dwell = w.p.unwrap_or(0.0);
    let dir = direction.unwrap_or(SpindleDirection::Clockwise);
    match code {
        G81 => {
            feed(cx, f, aa, bb, f.bottom);
            traverse(cx, f, aa, bb, f.clear);
        }
        G82 => {
            feed(cx, f, aa, bb, f.bottom);
            cx.out.push(Canon::Dwell { seconds: dwell });
            traverse(cx, f, aa, bb, f.clear);
        }
        G73 | G83 => {
            let q = w.q.unwrap_or(f.r - f.bottom);
            let up = peck_clearance(cx);
            // LinuxCNC steps the depth in program units, R − Q, R − 2Q, … while above the bottom:
            // where R − nQ is the bottom in decimal its rounding decides whether one more peck
            // comes, so the levels are stepped here as it does (`CycleFrame::r_units`).
            let k = cx.st.units.mm_per_unit();
            let q_u = (q / k * 1e9).round() / 1e9;
            let (r_u, bottom_u) = (f.r_units, f.bottom_units);
            let mut depth_u = r_u - q_u;
            while depth_u > bottom_u {
                let depth = depth_u * k;
                feed(cx, f, aa, bb, depth);
                if code == G83 {
                    traverse(cx, f, aa, bb, f.r);
                }
                traverse(cx, f, aa, bb, depth + up);
                depth_u -= q_u;
            }
            feed(cx, f, aa, bb, f.bottom);
            traverse(cx, f, aa, bb, f.clear);
        }
        G74 | G84 => {
            let reverse = match dir {
                SpindleDirection::Clockwise => SpindleDirection::CounterClockwise,
                SpindleDirection::CounterClockwise => SpindleDirection::Clockwise,
            };
            overrides(cx, false);
            tap_feed(cx, f, aa, bb, f.bottom);
            stop_spindle(cx);
            spindle(cx, reverse);
            cx.out.push(Canon::Dwell { seconds: dwell });
            tap_feed(cx, f, aa, bb, f.clear);
            stop_spindle(cx);
            spindle(cx, dir);
            overrides(cx, true);
            // The interpreter's position is the hole's clear point (see `tap_feed`).
            let machine = cx.st.position;
            place(cx, f, aa, bb, f.clear);
            let believed = cx.st.position;
            cx.fe.modes.tap_apart = (machine != believed).then_some(super::TapApart {
                machine: [machine.x, machine.y, machine.z],
                believed: [believed.x, believed.y, believed.z],
                reread: false,
            });
        }
        G85 => {
            feed(cx, f, aa, bb, f.bottom);
            feed(cx, f, aa, bb, f.r);
            // LinuxCNC's convert_cycle_g85 traverses to the clear level even when it is R.
            traverse(cx, f, aa, bb, f.clear);
        }
        G86 => {
            feed(cx, f, aa, bb, f.bottom);
            cx.out.push(Canon::Dwell { seconds: dwell });
            stop_spindle(cx);
            traverse(cx, f, aa, bb, f.clear);
            spindle(cx, dir);
        }
        G87 => {
            let (oa, ob) = (aa + w.offset[0], bb + w.offset[1]);
            // LinuxCNC orients in the spindle's sense: 2 under M3, 3 under M4 (rs274's trace).
            let orient = Canon::OrientSpindle {
                spindle: 0,
                degrees: 0.0,
                direction: if dir == SpindleDirection::CounterClockwise {
                    3
                } else {
                    2
                },
                timeout: None,
            };
            traverse(cx, f, oa, ob, f.r);
            stop_spindle(cx);
            cx.out.push(orient.clone());
            traverse(cx, f, oa, ob, f.bottom);
            traverse(cx, f, aa, bb, f.bottom);
            spindle(cx, dir);
            feed(cx, f, aa, bb, w.middle);
            feed(cx, f, aa, bb, f.bottom);
            stop_spindle(cx);
            cx.out.push(orient);
            traverse(cx, f, oa, ob, f.bottom);
            traverse(cx, f, oa, ob, f.clear);
            traverse(cx, f, aa, bb, f.clear);
            spindle(cx, dir);
        }
        G88 => {
            feed(cx, f, aa, bb, f.bottom);
            cx.out.push(Canon::Dwell { seconds: dwell });
            stop_spindle(cx);
            cx.out.push(Canon::ProgramStop { optional: false });
            spindle(cx, dir);
        }
        G89 => {
            feed(cx, f, aa, bb, f.bottom);
            cx.out.push(Canon::Dwell { seconds: dwell });
            feed(cx, f, aa, bb, f.clear);
        }
        _ => {}
    }
}
