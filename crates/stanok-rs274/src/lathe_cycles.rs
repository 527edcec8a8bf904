//! LinuxCNC's lathe cycles: G70 finishing, G71/G71.1/G71.2 and G72/G72.1/G72.2 roughing, with the
//! profile taken from the subroutine named by Q — behaviour read off LinuxCNC 2.9's `rs274`
//! (spec rs274ngc §4.31–4.32 is thin; `scripts/regen-linuxcnc-goldens.sh` regenerates the traces).
//!
//! # How a cycle runs (three stages, each in its own block)
//!
//! 1. **The G7x block** (`begin`): checks its words (Q, G18, no cutter compensation for G71/G72,
//!    I > 0 at the end), rapids to the cycle start S = X/Z (default: where the tool is) and leaves
//!    a `LatheCall` in the state. The driver then *calls* `oQ` as an O-word call would.
//! 2. **The profile**: the subroutine's blocks run as ordinary blocks (control flow, parameters and
//!    `#<_x>`/`#<_z>` see the profile's own positions), but the driver keeps their commands back.
//!    Its first motion is the approach to the profile start P0; the motions after it are the
//!    profile (G0 counts as G1; F, S and the like in it are ignored).
//! 3. **The return from oQ** (`finish`): the driver drops the kept commands, puts the tool back at
//!    S and this module emits the cycle. Errors found now ("Not monotonic", I ≤ 0) belong to the
//!    `endsub` block, as in LinuxCNC.
//!
//! # Geometry (plane coordinates (z, x) of G18; canonical frame (c, l))
//!
//! G71 (and G70) cut along Z in layers of constant X: cut axis c = z, level axis l = x. G72 cuts
//! along X in layers of constant Z: c = x, l = z. The canonical frame flips both so that the
//! profile runs towards +c overall and S lies on the +l side of P0:
//!
//! ```text
//!   l ▲   S ●━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━● (Pend'.c, S.l)   ← level l₀ = S.l
//!     │     ╲  closing line I → P0'     cut ──▶ | retract ↗ r       ┃
//!     │      ╲━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━●                  ┃    ← level l₀ − I …
//!     │  P0'  ●━━━━━━━━━━━━━━╮ profile' (= profile offset by D towards +l)
//!     │                      ╰━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━● Pend'
//!     └──────────────────────────────────────────────────────────────▶ c
//! ```
//!
//! * I (the entry point): S if S is not past P0 along c (S.c ≤ P0.c), else (P0.c, S.l) — P0 of the
//!   programmed profile, not of the offset one.
//! * Roughing (G71/G72): rapid to I; for every level l = S.l − k·I while l > P0'.l: rapid to the
//!   closing line I → P0' at l (c_s), feed along +c to the first crossing of the level with
//!   profile' beyond c_s (none: to Pend'.c), retract r = min(R, cut/2) diagonally (−c, +l), rapid
//!   back to (c_s + r, l + r) and to (c_s, l). Then the final pass: rapid to P0', feed along
//!   profile' — cutting its pockets on the way (`pockets.rs`; G7x.1 climbs it element by element
//!   instead, `climb.rs`) — and feed to (Pend'.c, S.l).
//! * profile' is the profile offset by D (on the side `side.rs` picks) as LinuxCNC offsets it,
//!   arcs that end off their radius included (`arcs.rs`); an arc is printed with its own end
//!   point, the next feed's start.
//! * Finishing (G70): passes k = P … 1 at offset (k − 1)(D − E)/P + E: rapid to I, rapid to the
//!   pass's start, feed along it. The tool stays at the profile's end. The frame is G71's when the
//!   profile is monotonic in Z, else G72's.
//!
//! Corners: `A` on a profile move rounds its end corner with a tangent arc of that radius, `C`
//! cuts it with the chord between the same tangent points, next to lines and arcs alike
//! (`corners.rs`).
//!
//! LinuxCNC orients its frame by the profile (P0 below Pend), not by S. A profile that ends below
//! P0 here (it runs away from S overall) has S below it there: it gets no levels — rapid to I,
//! then the final pass from I, the entry I → P0' its first element, in the frame mirrored in l;
//! the tool stays at its end (`away_from_start`). Where the frame's cut direction is undecided
//! (Pend level with P0 along c) it runs towards −Z (G71) or −X (G72), as LinuxCNC's does.
//!
//! The allowance's side is LinuxCNC's rule (`side.rs`): towards S for the usual profile, by the
//! turn from the entry to the last element where S is level with P0 or behind the profile.
//! A motion of the profile that moves neither X nor Z is no element (the first motion that does
//! is the approach to P0).
//!
//! Invariants: no roughing feed crosses profile' (cuts stop at its first crossing); the final pass
//! follows profile' exactly (G7x.1: but for arc pieces under 0.001 mm, fed along their chord); the
//! number of levels is bounded by `MAX_LEVELS`; every offset chain is connected
//! (stanok_geom::chain2d; within an off-radius arc's |R_e − R| at its end, `arcs.rs`); an element
//! the allowance swallows is left out and its neighbours joined, and an offset that would then
//! come nearer the profile than the allowance is refused rather than cut.

use crate::arc::PlanarArc;
use crate::codes::*;
use crate::ctx::Ctx;
use stanok_canon::{Canon, Diagnostic, Plane, Pose};
use stanok_geom::chain2d::level_crossings;
use stanok_geom::offset2d::{Seg2, LEN_EPS, P2};
use stanok_syntax::ColSpan;

mod arcs;
mod climb;
mod corners;
mod pockets;
mod side;

/// A profile motion moving X and Z less than this is no element (LinuxCNC compares the ends
/// exactly; this only absorbs the unit conversions' rounding), mm.
const IN_PLACE: f64 = 1e-9;

/// Most roughing levels or finishing passes of one cycle (more is an error, never a hang).
pub const MAX_LEVELS: usize = 10_000;

/// A G7x block waiting for its profile (set by `begin`, taken by the driver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LatheCall {
    /// G70, G71, G71_1, G71_2, G72, G72_1, G72_2 (`codes.rs`).
    pub code: u32,
    /// The subroutine number (Q).
    pub q: i64,
    /// Cycle start S, program coordinates, mm.
    pub start: Pose,
    /// D: allowance left for finishing (G71/G72) or first finishing pass distance (G70), mm.
    pub d: f64,
    /// E: last finishing pass distance (G70), mm.
    pub e: f64,
    /// I: depth of cut per level, mm (> 0, checked at the end as LinuxCNC does).
    pub i: f64,
    /// R: retract, mm.
    pub r: f64,
    /// P: number of finishing passes (G70).
    pub passes: i64,
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
    // X and Z are absolute even under G91 (LinuxCNC 2.9); the profile itself follows G90/G91.
    let distance = cx.st.distance;
    cx.st.distance = crate::state::DistanceMode::Absolute;
    let start = cx.end_point();
    cx.st.distance = distance;
    let (start, _) = start?;
    // Defaults are in program units, as LinuxCNC reads them (I 1, R 0.5: inches under G20).
    let word = |cx: &mut Ctx<'_>, letter: u8, default: f64| {
        let v = cx.words.take(letter).map_or(default, |w| w.v);
        cx.mm(v)
    };
    let d = word(cx, b'D', 0.0);
    let (mut e, mut i, mut r, mut passes) = (0.0, 1.0, 0.5, 1);
    if code == G70 {
        e = word(cx, b'E', 0.0);
        passes = cx.words.take(b'P').map_or(1, |w| w.v.round() as i64);
    } else {
        i = word(cx, b'I', 1.0);
        r = word(cx, b'R', 0.5);
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
        d,
        e,
        i,
        r,
        passes,
    });
    Ok(())
}

/// Text of the internal marker a profile move with `A`/`C` leaves behind it in the captured
/// commands: `MARK` + `A|C` + the size in mm. It never leaves the interpreter (the capture drains
/// every command of the profile, `lathe.rs`).
const CORNER_MARK: &str = "\u{0}g7x-corner ";

/// A profile move's corner words: `A` fillet radius, `C` chamfer size (program units), at its end.
pub(super) fn take_corner(cx: &mut Ctx<'_>) -> Result<Option<Canon>, Diagnostic> {
    let a = cx.words.take(b'A');
    let c = cx.words.take(b'C');
    let (kind, w) = match (a, c) {
        (Some(_), Some(c)) => {
            return Err(cx.err(
                "rs274::g7x-a-and-c",
                "G7X error: Both A and C parameters on a corner",
                c.span,
            ))
        }
        (Some(a), None) => ('A', a),
        (None, Some(c)) => ('C', c),
        (None, None) => return Ok(None),
    };
    Ok(Some(Canon::Comment {
        text: format!("{CORNER_MARK}{kind}{}", cx.mm(w.v)),
    }))
}

/// A rounded (`A`) or chamfered (`C`) corner at the end of profile element `after`.
#[derive(Debug, Clone, Copy)]
struct Corner {
    after: usize,
    chamfer: bool,
    size: f64,
}

/// The profile as read from the subroutine: its start P0 and its elements, (z, x) program mm.
#[derive(Debug, Clone, Default)]
pub struct Profile {
    /// P0: the end of the subroutine's first motion.
    pub start: P2,
    /// The elements after it.
    pub chain: Vec<Seg2>,
}

impl Profile {
    /// The profile of the motions a profile subroutine produced (machine coordinates, converted
    /// with the work frame `to_program`). Err: a reason for the diagnostic.
    pub fn from_commands(
        commands: &[Canon],
        to_program: impl Fn(&Pose) -> Pose,
    ) -> Result<Profile, String> {
        let zx = |p: &Pose| {
            let q = to_program(p);
            [q.z, q.x]
        };
        // LinuxCNC reads only the motions that change X or Z (a move back to where the tool is,
        // a Y-only move and a full circle are no element): the first of them is the approach.
        let moves_in_plane = |c: &&Canon| match c {
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => {
                stanok_geom::offset2d::dist2(zx(&m.start), zx(&m.end)) > IN_PLACE
            }
            Canon::ArcFeed(a) => stanok_geom::offset2d::dist2(zx(&a.start), zx(&a.end)) > IN_PLACE,
            c => c.motion().is_some(),
        };
        let mut motions = commands
            .iter()
            .filter(|c| c.motion().is_some())
            .filter(moves_in_plane);
        let Some(first) = motions.next() else {
            // No cycle (LinuxCNC 2.9 returns without one).
            return Ok(Profile::default());
        };
        let end_of = |c: &Canon| match c {
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Some(m.end),
            Canon::ArcFeed(a) => Some(a.end),
            _ => None,
        };
        let Some(p0) = end_of(first) else {
            return Err("G7X error: only G0, G1, G2 and G3 may move in a profile".into());
        };
        let mut profile = Profile {
            start: zx(&p0),
            chain: Vec::new(),
        };
        let mut corners: Vec<Corner> = Vec::new();
        for c in commands
            .iter()
            .skip_while(|c| !std::ptr::eq(*c, first))
            .skip(1)
        {
            if let Canon::Comment { text } = c {
                if let Some(rest) = text.strip_prefix(CORNER_MARK) {
                    let size = rest[1..].parse::<f64>().unwrap_or(0.0);
                    if let Some(after) = profile.chain.len().checked_sub(1) {
                        corners.push(Corner {
                            after,
                            chamfer: rest.starts_with('C'),
                            size,
                        });
                    }
                }
                continue;
            }
            if c.motion().is_none() || !moves_in_plane(&c) {
                continue;
            }
            let seg = match c {
                Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Seg2::Line {
                    a: zx(&m.start),
                    b: zx(&m.end),
                },
                Canon::ArcFeed(a) if a.plane == Plane::ZX && a.turns == 1 => {
                    let centre = to_program(&Pose {
                        x: a.centre[0],
                        y: a.centre[1],
                        z: a.centre[2],
                        ..a.start
                    });
                    let (s, e) = (zx(&a.start), zx(&a.end));
                    let full = stanok_geom::offset2d::dist2(s, e) < LEN_EPS;
                    arcs::end_circle_arc([centre.z, centre.x], s, e, a.axis[1] > 0.0, full)
                }
                _ => return Err("G7X error: only G0, G1, G2 and G3 may move in a profile".into()),
            };
            if seg.length() > LEN_EPS {
                profile.chain.push(seg);
            }
        }
        for corner in corners.iter().rev() {
            corners::round_corner(&mut profile.chain, *corner)?;
        }
        Ok(profile)
    }
}

/// The canonical frame of a cycle (module comment): flips (and for G72 a swap) of (z, x).
#[derive(Debug, Clone, Copy)]
struct Frame {
    /// G72: c = x, l = z (else c = z, l = x).
    facing: bool,
    sc: f64,
    sl: f64,
}

impl Frame {
    fn new(facing: bool, p0: P2, pend: P2, s: P2) -> Frame {
        let (ci, li) = if facing { (1, 0) } else { (0, 1) };
        let sign = |v: f64| if v < 0.0 { -1.0 } else { 1.0 };
        Frame {
            facing,
            // A profile ending where it starts along the cut axis runs towards −Z (G71) or −X
            // (G72), as LinuxCNC's frame has it (it flips only where Pend is past P0).
            sc: if pend[ci] - p0[ci] > 0.0 { 1.0 } else { -1.0 },
            sl: sign(s[li] - p0[li]),
        }
    }

    fn to_canon(self, p: P2) -> P2 {
        let (c, l) = if self.facing {
            (p[1], p[0])
        } else {
            (p[0], p[1])
        };
        [self.sc * c, self.sl * l]
    }

    /// The inverse (every flip and the swap are involutions).
    fn to_real(self, q: P2) -> P2 {
        let (c, l) = (self.sc * q[0], self.sl * q[1]);
        if self.facing {
            [l, c]
        } else {
            [c, l]
        }
    }

    /// The same frame mirrored in l (for moves computed in the mirrored canonical frame).
    fn mirrored_l(self) -> Frame {
        Frame {
            sl: -self.sl,
            ..self
        }
    }

    /// Whether the map reverses orientation (arcs change their sense).
    fn mirrors(self) -> bool {
        let det = self.sc * self.sl * if self.facing { -1.0 } else { 1.0 };
        det < 0.0
    }

    fn seg(self, s: &Seg2, to: impl Fn(P2) -> P2) -> Seg2 {
        match *s {
            Seg2::Line { a, b } => Seg2::Line { a: to(a), b: to(b) },
            Seg2::Arc { c, sweep, .. } => {
                let ccw = (sweep > 0.0) != self.mirrors();
                Seg2::arc_through(to(c), to(s.start()), to(s.end()), ccw, false)
            }
        }
    }
}

/// Whether `a` and `b` are both lines and parallel (within rounding: LinuxCNC's test is exact on
/// its own numbers, Stanok's are converted from program units).
fn parallel_lines(a: &Seg2, b: &Seg2) -> bool {
    let (Seg2::Line { a: a0, b: a1 }, Seg2::Line { a: b0, b: b1 }) = (*a, *b) else {
        return false;
    };
    let (u, v) = (
        [a1[0] - a0[0], a1[1] - a0[1]],
        [b1[0] - b0[0], b1[1] - b0[1]],
    );
    let cross = u[0] * v[1] - u[1] * v[0];
    cross.abs() <= 1e-12 * u[0].hypot(u[1]) * v[0].hypot(v[1])
}

/// Whether coordinate `k` never turns back along the chain (arcs included).
fn monotonic(chain: &[Seg2], k: usize) -> bool {
    let mut dir = 0.0;
    for s in chain {
        let (v0, v1) = (s.start()[k], s.end()[k]);
        if let Seg2::Arc { start, sweep, .. } = *s {
            // The coordinate turns where the arc's tangent is perpendicular to axis k.
            let phase = if k == 0 {
                0.0
            } else {
                std::f64::consts::FRAC_PI_2
            };
            let (lo, hi) = if sweep > 0.0 {
                (start, start + sweep)
            } else {
                (start + sweep, start)
            };
            let first = ((lo - phase) / std::f64::consts::PI).floor() + 1.0;
            let turn = phase + first * std::f64::consts::PI;
            if turn < hi - 1e-9 && turn > lo + 1e-9 {
                return false;
            }
        }
        let step = v1 - v0;
        if step.abs() <= LEN_EPS {
            continue;
        }
        if dir == 0.0 {
            dir = step.signum();
        } else if step.signum() != dir {
            return false;
        }
    }
    true
}

/// One move of the cycle, plane coordinates (z, x).
enum Move {
    Rapid(P2),
    Feed(Seg2),
}

/// Stage 3: emits the cycle for `call` over `profile`, from S (the tool is there). `at` is the
/// block the errors belong to (the profile's `endsub`).
pub fn finish(
    cx: &mut Ctx<'_>,
    call: &LatheCall,
    profile: &Profile,
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let s = [call.start.z, call.start.x];
    let chain = &profile.chain;
    let Some(last) = chain.last() else {
        // An approach alone, or no motion: LinuxCNC 2.9 cuts nothing (the driver leaves the tool
        // where the profile ended, `lathe.rs`).
        return Ok(());
    };
    if call.code != G70 && call.i <= 0.0 {
        return Err(cx.err(
            "rs274::g7x-i",
            "G7X error: I must be greater than zero.",
            at,
        ));
    }
    let (p0, pend) = (profile.start, last.end());
    let facing = match call.code {
        G70 => !monotonic(chain, 0) && monotonic(chain, 1),
        c => c >= G72,
    };
    if !monotonic(chain, if facing { 1 } else { 0 }) {
        return Err(cx.err("rs274::g7x-monotonic", "G7X error: Not monotonic", at));
    }
    // LinuxCNC joins neighbouring offset lines at their crossing and has none for parallel ones
    // (two moves along one line): an error as soon as it offsets at all (the first pass's
    // distance is not zero), before any move.
    let first_distance = if call.code == G70 {
        (call.passes - 1) as f64 * (call.d - call.e) / call.passes.max(1) as f64 + call.e
    } else {
        call.d
    };
    if first_distance != 0.0 && chain.windows(2).any(|w| parallel_lines(&w[0], &w[1])) {
        return Err(cx.err(
            "rs274::g7x-parallel",
            "G7X error: Cannot intersect parallel lines",
            at,
        ));
    }
    let f = Frame::new(facing, p0, pend, s);
    let canon: Vec<Seg2> = chain.iter().map(|g| f.seg(g, |p| f.to_canon(p))).collect();
    let (s_c, p0_c) = (f.to_canon(s), f.to_canon(p0));
    let entry = if s_c[0] <= p0_c[0] {
        s_c
    } else {
        [p0_c[0], s_c[1]]
    };
    let unit = cx.mm(1.0);
    // The allowance's side (`side.rs`), as a sign for an offset to the left in the frame.
    let side = side::left_in_plane(facing, f.to_real(entry), p0, chain)
        * if f.mirrors() { -1.0 } else { 1.0 };
    let offset = |d: f64| {
        arcs::offset_profile(&canon, p0_c, side * d, unit).ok_or_else(|| {
            cx.err(
                "rs274::g7x-offset",
                "G7X error: the profile cannot be offset by this distance",
                at,
            )
        })
    };
    let mut moves: Vec<Move> = Vec::new();
    if call.code == G70 {
        for k in (1..=call.passes.min(MAX_LEVELS as i64)).rev() {
            let dist = (k - 1) as f64 * (call.d - call.e) / call.passes as f64 + call.e;
            let pass = offset(dist)?;
            moves.push(Move::Rapid(entry));
            moves.push(Move::Rapid(pass[0].start()));
            moves.extend(pass.into_iter().map(Move::Feed));
        }
    } else {
        if s_below_in_linuxcnc_frame(facing, f, s, p0, pend) {
            let prof = offset(call.d)?;
            away_from_start(&mut moves, call, entry, &prof).ok_or_else(|| {
                cx.err(
                    "rs274::g7x-levels",
                    format!("G7X error: more than {MAX_LEVELS} levels"),
                    at,
                )
            })?;
            return emit(cx, call, &f.mirrored_l(), &moves, at);
        }
        let prof = offset(call.d)?;
        rough(&mut moves, call, entry, s_c, &prof).ok_or_else(|| {
            cx.err(
                "rs274::g7x-levels",
                format!("G7X error: more than {MAX_LEVELS} levels"),
                at,
            )
        })?;
    }
    if cx.fe.modes.comp.on() {
        // LinuxCNC read the profile by walking its idea of the tool along it (`stale.rs`).
        cx.fe.modes.comp.stale = Some(pend);
    }
    emit(cx, call, &f, &moves, at)
}

/// Whether S is not above P0 in LinuxCNC's frame, which orients "up" by the profile, not by S:
/// up is +X (G71) or −Z (G72), reversed where P0 lies above Pend that way (a tie keeps it).
/// S level with P0 counts too: no level lies between them, the tool feeds from S.
fn s_below_in_linuxcnc_frame(facing: bool, f: Frame, s: P2, p0: P2, pend: P2) -> bool {
    let li = if facing { 0 } else { 1 };
    let base = if facing { -1.0 } else { 1.0 };
    let up = if base * (p0[li] - pend[li]) > 0.0 {
        -base
    } else {
        base
    };
    // The canonical frame has S at or above P0 along l = f.sl · (z or x).
    let rise = s[li] - p0[li];
    rise.abs() <= 1e-9 || up * f.sl < 0.0
}

/// G71/G72 levels and the final pass, canonical frame (module comment). None: too many levels.
fn rough(moves: &mut Vec<Move>, call: &LatheCall, entry: P2, s: P2, prof: &[Seg2]) -> Option<()> {
    let p0 = prof.first()?.start();
    let pend = prof.last()?.end();
    moves.push(Move::Rapid(entry));
    let closing_c = |l: f64| {
        if (p0[1] - entry[1]).abs() < LEN_EPS {
            entry[0]
        } else {
            entry[0] + (l - entry[1]) / (p0[1] - entry[1]) * (p0[0] - entry[0])
        }
    };
    // G7x.2 cuts only the pockets: a type-1 profile has none.
    let levels = if matches!(call.code, G71_2 | G72_2) {
        0
    } else {
        MAX_LEVELS
    };
    for k in 0..=levels {
        let l = s[1] - k as f64 * call.i;
        if l <= p0[1] + 1e-9 {
            break;
        }
        if k == levels {
            if levels == 0 {
                break;
            }
            return None;
        }
        let cs = closing_c(l);
        let ce = level_crossings(prof, l)
            .into_iter()
            .map(|(c, _)| c)
            .find(|&c| c > cs + LEN_EPS)
            .unwrap_or(pend[0]);
        if ce <= cs + LEN_EPS {
            // A level with nothing to cut (the profile meets the closing line there): LinuxCNC
            // still rapids down the closing line to it.
            moves.push(Move::Rapid([cs, l]));
            continue;
        }
        // At most half the cut; a negative R retracts by half the cut (LinuxCNC 2.9).
        let half = (ce - cs) / 2.0;
        let r = if call.r < 0.0 { half } else { call.r.min(half) };
        moves.push(Move::Rapid([cs, l]));
        moves.push(Move::Feed(Seg2::Line {
            a: [cs, l],
            b: [ce, l],
        }));
        moves.push(Move::Rapid([ce - r, l + r]));
        moves.push(Move::Rapid([cs + r, l + r]));
        moves.push(Move::Rapid([cs, l]));
    }
    moves.push(Move::Rapid(p0));
    // The closing move up to S's level, only from below it: a profile ending above S's level
    // leaves the tool at its end (LinuxCNC 2.9).
    let close = Seg2::Line {
        a: pend,
        b: [pend[0], s[1].max(pend[1])],
    };
    if matches!(call.code, G71_1 | G72_1) {
        climb::climb_pass(moves, prof, p0, close);
        return Some(());
    }
    pockets::final_pass(moves, call, s, &pockets::split_at_turns(prof), close)
}

/// A profile running away from S (l only falls along it, canonical frame): LinuxCNC 2.9 cuts no
/// level. Its own frame for such a profile has S *below* P0 and the profile rising, so this
/// works in the canonical frame mirrored in l (the moves it leaves are in that frame: emit them
/// with `Frame::mirrored_l`). There the cycle is the final pass alone, from the entry point I,
/// with the entry I → P0' as the profile's first element (fed, never rapid):
///
/// * G7x.1 climbs every element from the tool's level (`climb.rs`): a right-turning arc that
///   passes its top — an offset arc ending beyond it, where it meets the next line — is cut to
///   the top only, and the tool then feeds across to the next element at that level;
/// * G7x and G7x.2 walk the profile with its pockets (`pockets.rs`): the same arc is cut to its
///   top and then on down to its end (a G7x.2 first cuts the dip it starts there as a pocket:
///   feed across, retract, back); S's level lies below the profile, so no other pocket level is
///   on G7x's grid.
///
/// No closing move: the profile ends beyond S's level and the tool stays at its end.
/// None: too many levels.
fn away_from_start(
    moves: &mut Vec<Move>,
    call: &LatheCall,
    entry: P2,
    prof: &[Seg2],
) -> Option<()> {
    let entry = mirror_l_point(entry);
    let mut elements: Vec<Seg2> = Vec::with_capacity(prof.len() + 1);
    elements.extend(prof.iter().map(mirror_l));
    let p0 = elements[0].start();
    elements.insert(0, Seg2::Line { a: entry, b: p0 });
    let pend = elements[elements.len() - 1].end();
    let close = Seg2::Line { a: pend, b: pend };
    moves.push(Move::Rapid(entry));
    if matches!(call.code, G71_1 | G72_1) {
        climb::climb_pass(moves, &elements, entry, close);
        return Some(());
    }
    // No level of S's grid lies above the profile: only a G7x.2 pocket anchored at its own top
    // is cut.
    // The entry stays even where it has no length (S level with P0 and past it along c: rs274
    // still feeds it).
    let mut pieces = pockets::split_at_turns(&elements[1..]);
    pieces.insert(0, elements[0]);
    pockets::final_pass(moves, call, entry, &pieces, close)
}

/// (c, l) → (c, −l).
fn mirror_l_point(p: P2) -> P2 {
    [p[0], -p[1]]
}

/// A segment mirrored in l (an arc keeps its radius and turns the other way).
fn mirror_l(s: &Seg2) -> Seg2 {
    match *s {
        Seg2::Line { a, b } => Seg2::Line {
            a: mirror_l_point(a),
            b: mirror_l_point(b),
        },
        Seg2::Arc { c, r, start, sweep } => Seg2::Arc {
            c: mirror_l_point(c),
            r,
            start: -start,
            sweep: -sweep,
        },
    }
}

/// Emits the moves (canonical frame) as Canon, program coordinates; other axes stay at S.
/// Under cutter compensation (G70) every move is compensated as if programmed.
fn emit(
    cx: &mut Ctx<'_>,
    call: &LatheCall,
    f: &Frame,
    moves: &[Move],
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let pose = |p: P2| Pose {
        z: p[0],
        x: p[1],
        ..call.start
    };
    let comp = cx.fe.modes.comp.on();
    for (k, m) in moves.iter().enumerate() {
        match m {
            Move::Rapid(q) if comp => {
                super::cutter_comp::straight(cx, true, pose(f.to_real(*q)), 0.0, at)?
            }
            Move::Rapid(q) => cx.straight(true, pose(f.to_real(*q)), 0.0),
            Move::Feed(seg) => {
                let real = f.seg(seg, |p| f.to_real(p));
                let feed = cx.path_feed(real.length());
                match real {
                    Seg2::Line { b, .. } if comp => {
                        super::cutter_comp::straight(cx, false, pose(b), feed, at)?
                    }
                    Seg2::Line { b, .. } => cx.straight(false, pose(b), feed),
                    Seg2::Arc { c, sweep, .. } => {
                        let arc = PlanarArc {
                            centre: c,
                            turns: 1,
                        };
                        // An arc ends where the next feed starts: its end point may be off
                        // the circle it crosses levels on (`arcs.rs`).
                        let end = match moves.get(k + 1) {
                            Some(Move::Feed(next)) if arcs::joins(seg, next) => {
                                pose(f.to_real(next.start()))
                            }
                            _ => pose(real.end()),
                        };
                        if comp {
                            super::cutter_comp::arc(cx, sweep > 0.0, end, arc, feed, at)?;
                        } else {
                            cx.arc(Plane::ZX, sweep > 0.0, end, arc, feed);
                        }
                    }
                }
            }
        }
    }
    Ok(())
}
