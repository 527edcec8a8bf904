//! LinuxCNC's lathe cycles: G70 finishing, G71/G71.1/G71.2 and G72/G72.1/G72.2 roughing, with the
//! profile taken from the subroutine named by Q — LinuxCNC 2.9's model of them reproduced step by
//! step (spec rs274ngc §4.31–4.32 is thin; `scripts/regen-linuxcnc-goldens.sh` regenerates the
//! traces).
//!
//! # How a cycle runs (three stages, each in its own block)
//!
//! 1. **The G7x block** (`begin`): checks its words (Q, G18, no cutter compensation for G71/G72),
//!    rapids to the cycle start S = X/Z (default: where the tool is) and leaves a `LatheCall` in
//!    the state, with the block's words as written (program units). The driver then *calls* `oQ`
//!    as an O-word call would.
//! 2. **The profile**: the subroutine's blocks run as ordinary blocks (control flow, parameters
//!    and `#<_x>`/`#<_z>` see the profile's own positions), but the driver keeps their commands
//!    back. Each motion block's words are recorded as written (`profile_block`): LinuxCNC builds the
//!    profile from the words, not from positions, and so does `read_profile`.
//! 3. **The return from oQ** (`finish`): the driver drops the kept commands, puts the tool back at
//!    S and this module runs the cycle and emits its moves. Errors found now ("Not monotonic",
//!    I ≤ 0, an arc the cycle cuts off its radius) belong to the `endsub` block, as in LinuxCNC.
//!
//! # Why a step-by-step model
//!
//! LinuxCNC computes the cycle in program units on `std::complex<double>` and makes exact
//! comparisons of computed points (an offset level element whose end rounds one ulp below its
//! start is skipped by G7x.1; a gap of 10⁻² decides a bridging arc). Stanok's own geometry (in
//! mm, with its own formulas) matched on nearly every program but not on those; the model
//! (`model.rs`: the elements, `path.rs`: the cycle, `cplx.rs`: the arithmetic) follows LinuxCNC's
//! floating-point steps so that it prints what LinuxCNC prints. Its moves are then converted to
//! mm and emitted like any move (an arc checked for its radius as LinuxCNC's `convert_arc` checks
//! it; an arc ending within 10⁻⁴ of where the tool is, is not printed).
//!
//! Invariants: the model's work is bounded (`path::MAX_WORK`; LinuxCNC's own loops can
//! run forever on some profiles, Stanok's stop with an error); a failing cycle emits nothing.

use crate::arc::PlanarArc;
use crate::codes::*;
use crate::ctx::Ctx;
use cplx::Cx;
use model::{Out, Seg};
use stanok_canon::{Canon, Diagnostic, Plane, Pose};
use stanok_syntax::ColSpan;

mod cplx;
mod model;
mod path;

/// Most motion blocks one profile may record (more is an error, never unbounded memory).
pub const MAX_PROFILE_BLOCKS: usize = 100_000;

/// A G7x block waiting for its profile (set by `begin`, taken by the driver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LatheCall {
    /// G70, G71, G71_1, G71_2, G72, G72_1, G72_2 (`codes.rs`).
    pub code: u32,
    /// The subroutine number (Q).
    pub q: i64,
    /// Where the G7x block's rapid went, program coordinates, mm (the other axes stay there).
    pub start: Pose,
    /// The cycle's words as LinuxCNC reads them, program units: S = (x, z) (under G91 the tool's
    /// position plus X/Z, where the rapid went to X/Z), D, E, I, P, R, U, W.
    words: path::Words,
    /// The profile reads its X/Z (and arc centres) incrementally (G91, G91.1 at the G7x block).
    incremental: bool,
    ijk_incremental: bool,
    /// Lathe diameter mode at the G7x block (U words are halved).
    diameter: bool,
}

/// One motion block of a profile, its words as written (program units; X already halved in
/// diameter mode).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileBlock {
    /// G0, G1, G2 or G3.
    code: u32,
    x: Option<f64>,
    z: Option<f64>,
    u: Option<f64>,
    w: Option<f64>,
    i: Option<f64>,
    k: Option<f64>,
    r: Option<f64>,
    /// Corner words: A fillet radius, C chamfer size.
    a: Option<f64>,
    c: Option<f64>,
}

/// Stage 1: the G7x block. Rapids to the cycle start and leaves the call for the driver.
pub(super) fn begin(cx: &mut Ctx<'_>, code: u32, span: ColSpan) -> Result<(), Diagnostic> {
    let Some(q) = cx.words.take(b'Q') else {
        return Err(cx.err("rs274::g7x-q-missing", "G7x.x  requires a Q word", span));
    };
    if cx.st.plane != Plane::ZX {
        return Err(cx.err(
            "rs274::g7x-plane",
            format!(
                "G{}.{} can only be used in XZ plane (G18)",
                code / 10,
                code % 10
            ),
            span,
        ));
    }
    if code != G70 && cx.fe.modes.comp.on() {
        return Err(cx.err(
            "rs274::g7x-comp",
            format!(
                "G{}.{} cannot be used with cutter compensation enabled",
                code / 10,
                code % 10
            ),
            span,
        ));
    }
    let unit = cx.mm(1.0);
    let incremental = cx.st.distance == crate::state::DistanceMode::Incremental;
    let here = cx.programmed_position();
    let peek = |cx: &Ctx<'_>, l: u8| cx.words.peek(l).map(|w| w.v);
    // S as LinuxCNC's model reads it: X/Z, under G91 added to where the tool is.
    let along = |word: Option<f64>, at_mm: f64| {
        let at = to_units(at_mm, unit);
        match word {
            Some(v) if incremental => at + v,
            Some(v) => v,
            None => at,
        }
    };
    let mut words = path::Words {
        x: along(peek(cx, b'X'), here.x),
        z: along(peek(cx, b'Z'), here.z),
        d: peek(cx, b'D').unwrap_or(0.0),
        e: 0.0,
        i: 1.0,
        p: 1.0,
        r: 0.5,
        u: peek(cx, b'U').unwrap_or(0.0),
        w: peek(cx, b'W').unwrap_or(0.0),
    };
    // The rapid's X and Z are absolute even under G91 (LinuxCNC 2.9); the profile itself
    // follows G90/G91.
    let distance = cx.st.distance;
    cx.st.distance = crate::state::DistanceMode::Absolute;
    let start = cx.end_point();
    cx.st.distance = distance;
    let (start, _) = start?;
    cx.words.take(b'D');
    if code == G70 {
        words.e = cx.words.take(b'E').map_or(0.0, |w| w.v);
        words.p = cx.words.take(b'P').map_or(1.0, |w| w.v);
    } else {
        words.i = cx.words.take(b'I').map_or(1.0, |w| w.v);
        words.r = cx.words.take(b'R').map_or(0.5, |w| w.v);
    }
    // Under compensation (G70 only) the rapid is compensated like any move (LinuxCNC 2.9).
    if cx.fe.modes.comp.on() {
        super::cutter_comp::straight(cx, true, start, 0.0, span)?;
    } else {
        cx.straight(true, start, 0.0);
    }
    cx.fe.lathe_call = Some(LatheCall {
        code,
        q: q.v.round() as i64,
        start,
        words,
        incremental,
        ijk_incremental: cx.st.arc_distance == crate::state::DistanceMode::Incremental,
        diameter: cx.st.diameter_mode,
    });
    Ok(())
}

/// A position (mm) in program units as LinuxCNC holds it. Stanok keeps positions in mm, so an
/// inch value comes back from the conversion with a rounding error of an ulp or two: the
/// neighbour that is a short decimal (a number as written, at most 12 significant digits) is
/// taken for it, else the quotient.
fn to_units(v_mm: f64, unit: f64) -> f64 {
    let digits = |v: f64| {
        let s = format!("{v:e}");
        s.split('e')
            .next()
            .map_or(99, |m| m.chars().filter(char::is_ascii_digit).count())
    };
    let q = v_mm / unit;
    let (mut best, mut best_digits) = (q, digits(q));
    let (mut down, mut up) = (q, q);
    for _ in 0..2 {
        down = down.next_down();
        up = up.next_up();
        for c in [down, up] {
            let d = digits(c);
            if d < best_digits {
                (best, best_digits) = (c, d);
            }
        }
    }
    if best_digits <= 12 {
        best
    } else {
        q
    }
}

/// In a profile: a motion block's words as the cycle will read them (`ProfileBlock`), taking its
/// corner words, which are not axes here. The caller keeps it once the motion has run, and the
/// front end's rollback takes it back if the block fails (ARCHITECTURE.md invariant 4).
pub(super) fn profile_block(cx: &mut Ctx<'_>, code: u32) -> Result<ProfileBlock, Diagnostic> {
    let a = cx.words.take(b'A');
    let c = cx.words.take(b'C');
    if let (Some(_), Some(c)) = (a, c) {
        return Err(cx.err(
            "rs274::g7x-a-and-c",
            "G7X error: Both A and C parameters on a corner",
            c.span,
        ));
    }
    if cx.fe.profile_blocks.len() >= MAX_PROFILE_BLOCKS {
        return Err(cx.err(
            "rs274::g7x-profile-too-long",
            format!("G7X error: a profile of more than {MAX_PROFILE_BLOCKS} moves"),
            cx.whole(),
        ));
    }
    let v = |l: u8| cx.words.peek(l).map(|w| w.v);
    Ok(ProfileBlock {
        code,
        x: v(b'X'),
        z: v(b'Z'),
        u: v(b'U'),
        w: v(b'W'),
        i: v(b'I'),
        k: v(b'K'),
        r: v(b'R'),
        a: a.map(|w| w.v),
        c: c.map(|w| w.v),
    })
}

/// The chain LinuxCNC's reader builds from a profile's blocks: the entry from S to the first
/// move's end, then one element per move that changes X or Z (compared exactly), each followed
/// by its corner element if it has A or C.
fn read_profile(call: &LatheCall, blocks: &[ProfileBlock]) -> Vec<Seg> {
    let mut start = Cx::new(call.words.z, call.words.x);
    let mut segs = Vec::new();
    for b in blocks {
        let mut end = if call.incremental {
            Cx::new(0.0, 0.0)
        } else {
            start
        };
        if let Some(u) = b.u {
            end.im += if call.diameter { u / 2.0 } else { u };
        } else if let Some(x) = b.x {
            end.im = x;
        }
        if let Some(w) = b.w {
            end.re += w;
        } else if let Some(z) = b.z {
            end.re = z;
        }
        let mut centre = Cx::new(b.k.unwrap_or(0.0), b.i.unwrap_or(0.0));
        if call.incremental {
            end += start;
        }
        if start == end {
            continue;
        }
        if matches!(b.code, G2 | G3) {
            let ccw = b.code == G3;
            if let Some(r) = b.r {
                let chord = end - start;
                let n = chord.norm();
                let k = ((r * r - n / 4.0) / n).sqrt();
                let d = cplx::I.scale(k) * chord;
                centre = (start + end).div_real(2.0);
                centre = if ccw { centre + d } else { centre - d };
            } else if call.ijk_incremental {
                centre += start;
            }
            segs.push(Seg::round(ccw, start, centre, end));
        } else {
            segs.push(Seg::straight(start, end));
        }
        if let Some(a) = b.a {
            segs.push(Seg::corner(true, a, end));
        } else if let Some(c) = b.c {
            segs.push(Seg::corner(false, c, end));
        }
        start = end;
    }
    segs
}

/// Stage 3: runs the cycle for `call` over the profile recorded in `blocks` and emits it, from
/// S (the tool is there). `commands` are the profile's own (dropped) commands. `at` is the block
/// the errors belong to (the profile's `endsub`).
pub fn finish(
    cx: &mut Ctx<'_>,
    call: &LatheCall,
    blocks: &[ProfileBlock],
    commands: &[Canon],
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let segs = read_profile(call, blocks);
    if segs.len() <= 1 {
        // An approach alone, or no motion: LinuxCNC 2.9 cuts nothing, and its idea of the
        // tool's position is where the profile left it.
        if let Some(end) = commands.iter().rev().find_map(|c| match c {
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Some(m.end),
            Canon::ArcFeed(a) => Some(a.end),
            _ => None,
        }) {
            cx.st.position = end;
        }
        return Ok(());
    }
    // LinuxCNC checks the feed when the cycle cuts, not in the profile (which keeps the G7x
    // block's feed).
    if cx.st.feed_mode == stanok_canon::FeedMode::UnitsPerMinute && cx.st.feed <= 0.0 {
        return Err(cx.err("rs274::zero-feed", "Cannot do g1 with zero feed rate", at));
    }
    if call.words.i <= 0.0 {
        return Err(cx.err(
            "rs274::g7x-i",
            "G7X error: I must be greater than zero.",
            at,
        ));
    }
    let profile_end = segs[segs.len() - 1].e;
    let chain = path::Chain::new(segs);
    let moves = match call.code {
        G70 => path::g70(chain, &call.words),
        c => path::g71(chain, &call.words, (c % 10) as u8, c >= G72),
    };
    let moves = moves.map_err(|msg| cx.err("rs274::g7x", format!("G7X error: {msg}"), at))?;
    if cx.fe.modes.comp.on() {
        // LinuxCNC read the profile by walking its idea of the tool along it (`stale.rs`).
        let unit = cx.mm(1.0);
        cx.fe.modes.comp.stale = Some([profile_end.re * unit, profile_end.im * unit]);
    }
    emit(cx, call, &moves, at)
}

/// Emits the model's moves (program units) as Canon; other axes stay where the G7x block's
/// rapid left them. Under cutter compensation (G70) every move is compensated as if programmed.
/// An arc ending within 10⁻⁴ (program units, each axis) of the tool is not printed, as
/// LinuxCNC's `circular_move` skips it; an arc ending off its radius is LinuxCNC's
/// `convert_arc` error.
fn emit(cx: &mut Ctx<'_>, call: &LatheCall, moves: &[Out], at: ColSpan) -> Result<(), Diagnostic> {
    let unit = cx.mm(1.0);
    let pose = |p: Cx| Pose {
        z: p.re * unit,
        x: p.im * unit,
        ..call.start
    };
    let comp = cx.fe.modes.comp.on();
    let tol = super::arc_tolerance(cx);
    let mut tool: Option<Cx> = None;
    for m in moves {
        match *m {
            Out::Rapid(p) if comp => super::cutter_comp::straight(cx, true, pose(p), 0.0, at)?,
            Out::Rapid(p) => cx.straight(true, pose(p), 0.0),
            Out::Line(p) => {
                let from = cx.programmed_position();
                let to = pose(p);
                let feed = cx.path_feed((to.z - from.z).hypot(to.x - from.x));
                if comp {
                    super::cutter_comp::straight(cx, false, to, feed, at)?;
                } else {
                    cx.straight(false, to, feed);
                }
            }
            Out::Arc { ccw, c, e } => {
                if let Some(t) = tool {
                    if (t.re - e.re).abs() < 1e-4 && (t.im - e.im).abs() < 1e-4 {
                        continue;
                    }
                }
                let from = cx.programmed_position();
                let (s, end) = ([from.z, from.x], [e.re * unit, e.im * unit]);
                let centre = [c.re * unit, c.im * unit];
                let arc =
                    crate::arc_rules::centre_format(s, end, centre, 1, tol).map_err(|err| {
                        crate::motion::radius_mismatch(cx, err, s, end, centre, tol, at)
                    })?;
                let feed = cx.path_feed(crate::arc::helix_length(
                    from,
                    pose(e),
                    Plane::ZX,
                    centre,
                    ccw,
                    1,
                ));
                let arc = PlanarArc { turns: 1, ..arc };
                if comp {
                    super::cutter_comp::arc(cx, ccw, pose(e), arc, feed, at)?;
                } else {
                    cx.arc(Plane::ZX, ccw, pose(e), arc, feed);
                }
            }
        }
        tool = Some(match *m {
            Out::Rapid(p) | Out::Line(p) => p,
            Out::Arc { e, .. } => e,
        });
    }
    Ok(())
}
