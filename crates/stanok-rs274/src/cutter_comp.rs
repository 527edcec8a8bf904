//! RS274/NGC cutter radius compensation G40, G41, G42, G41.1, G42.1 — LinuxCNC 2.9's rules
//! (spec rs274ngc §4.20–§4.21; corner and entry behaviour taken from `rs274` traces, see
//! tests/rs274/comp-*.ngc).
//!
//! ## Model
//!
//! Compensation works in the active plane (G17 or G18) on the *programmed* path: the state keeps
//! the programmed point (where the program thinks the tool is) apart from the tool centre
//! (`ModalState::position`). Every programmed element — a line or an arc — is offset by the tool
//! radius r to the left (G41) or right (G42) of its direction of travel:
//!
//! * a line moves sideways by r (its normal n, left = direction rotated +90°);
//! * an arc of radius R about C keeps C and gets radius R' = R − r when the tool is on its inside
//!   (G41 with G3, G42 with G2) and R + r otherwise; R' ≤ 0 is an error.
//!
//! ## Entry (the first move after G41/G42)
//!
//! A line ends at its programmed end + r·n (the tool travels straight there from where it
//! stands; the move must be longer than r). An arc ends at C + R'·u(E − C) on a circle whose
//! centre lies on the line C–E and that passes through the current point.
//!
//! ## Corners (every later move), with `a` = the previous element's end tangent and `b` = the new
//! element's start tangent at the programmed corner S
//!
//! * **convex** (the tool is on the outside: G41 turning right, G42 turning left, by more than
//!   [`CONCAVE_TOLERANCE`]; or a near reversal, |turn| within it of π, either way): an arc of
//!   radius r about S is inserted from the previous offset end to the new offset start
//!   (clockwise for G41, counter-clockwise for G42; for a G0 a straight traverse to its end);
//! * **concave** (turning towards the tool by more than the tolerance, short of a near
//!   reversal; and a near reversal where an arc has the tool outside it — the new arc, or the
//!   last arc before a line, LinuxCNC's "h" and "m" shapes): the previous offset element is
//!   shortened to where it meets the new offset element — two lines' crossing, or with an arc
//!   the root LinuxCNC's own formulas pick (`join.rs`); none is a gouge error in its words;
//! * **straight on** (turn within ±[`CONCAVE_TOLERANCE`]): nothing is moved; the new element
//!   starts where the tool is (LinuxCNC's "convex, one arc" and "colinear" cases).
//!
//! An arc's offset uses its programmed points as LinuxCNC 2.9 does when the end is off the circle
//! through the start (|E − C| ≠ |S − C|, by the program's rounding): the offset start is S moved
//! r along the radius C→S, the offset end E moved r along C→E, and the circle it meets its
//! neighbours on (and the radius check) is the end's, |E − C| ± r.
//!
//! Shortening the previous element means changing a command already queued: while compensation is
//! on, the driver holds back the last motion command and everything after it (the interpreter's
//! `held` rule), and the corner code edits it in place (`Emitter::last_motion_mut`). Moves without
//! motion in the plane (a Z plunge) do not form corners; they follow the corner point when it moves.
//!
//! G40 releases the held commands; the next move goes from the tool position straight to the
//! programmed point.

use super::Rs274State;
use crate::arc::PlanarArc;
use crate::codes::*;
use crate::ctx::Ctx;
use crate::params::Parameters;
use stanok_canon::{Canon, Diagnostic, LengthUnits, Plane, Pose};
use stanok_syntax::ColSpan;

mod geometry;
mod join;
mod stale;

use geometry::*;

/// A corner turning the "convex" way by less than this many radians is joined like a concave one.
pub const CONCAVE_TOLERANCE: f64 = 0.05;

/// A programmed element in plane coordinates (mm, program frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Element {
    /// A straight move.
    Line {
        /// Programmed start.
        from: [f64; 2],
        /// Programmed end.
        to: [f64; 2],
    },
    /// An arc.
    Arc {
        /// Centre.
        centre: [f64; 2],
        /// Counter-clockwise.
        ccw: bool,
        /// Programmed end.
        to: [f64; 2],
        /// Radius of the tool's arc (R').
        tool_radius: f64,
        /// Where the tool's arc starts (plane, program frame).
        tool_from: [f64; 2],
        /// The sweep LinuxCNC queues it with (`original_turns`, signed), which moving its end
        /// must not exceed: the programmed one, start to end about the centre; for the entry
        /// arc the tool's own. Set when the arc is emitted.
        queued_turn: f64,
    },
}

/// Cutter compensation state (part of `Rs274State`, so it is saved and restored with the block).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CutterComp {
    /// 0 off (G40), 1 left (G41), 2 right (G42).
    pub side: u8,
    /// Tool radius r, mm.
    pub radius: f64,
    /// The programmed point in the plane, once the first move after G41/G42 set it.
    pub program: Option<[f64; 2]>,
    /// The last programmed element (its offset is the held motion).
    pub last: Option<Element>,
    /// Moves without plane motion emitted after the last element's motion (held with it).
    pub moves_since: u32,
    /// Where the tool's controlled point lies from its nose centre (plane coordinates): a lathe
    /// tool of orientation 1–8 in G18 (`nose_shift`); every compensated move is emitted shifted.
    pub nose: [f64; 2],
    /// LinuxCNC's tool position when it is not the real one (nose centre, plane): reading a G70
    /// profile under compensation leaves it at the profile's end (`stale.rs`).
    pub stale: Option<[f64; 2]>,
    /// After G40 of a compensation that moved with a radius > 0, the next move must be straight
    /// (LinuxCNC's `arc_not_allowed`: an arc is refused until a G0/G1; dwells, cycles and tool
    /// changes leave it set).
    pub arc_refused: bool,
    /// The entry move starts here rather than at the tool: the programmed point a G40 left
    /// (LinuxCNC resets its current point to it), if no move has been made since.
    pub entry_from: Option<[f64; 2]>,
    /// The last element is the entry line: LinuxCNC queues it with the offset normal as its
    /// direction, not its travel (`convert_straight_comp1`), and its gouge check tests that.
    pub entry_held: bool,
    /// A stop flushed the held moves (LinuxCNC's `convert_stop`: M0, M1, M60): the last
    /// element's motion is issued as it was, no corner moves it or checks it; only the moves
    /// without plane motion made since are held (`moves_since`).
    pub released: bool,
    /// LinuxCNC's endpoint is invalid (`endpoint_valid` 0: a stop dequeued the moves and the
    /// corner after it found nothing queued to move): the held move's next gouge check is
    /// skipped.
    pub unchecked: bool,
}

impl CutterComp {
    /// Compensation is on.
    pub fn on(&self) -> bool {
        self.side != 0
    }

    /// +1 for the left side, −1 for the right.
    fn sign(&self) -> f64 {
        if self.side == 1 {
            1.0
        } else {
            -1.0
        }
    }
}

impl Element {
    fn end_tangent(&self) -> [f64; 2] {
        match *self {
            Element::Line { from, to } => unit(sub(to, from)),
            Element::Arc {
                centre, ccw, to, ..
            } => arc_tangent(centre, to, ccw),
        }
    }
}

/// The plane coordinates of a pose.
fn plane_of(p: &Pose, plane: Plane) -> [f64; 2] {
    let (a, b, _) = plane.axes();
    let v = p.to_array();
    [v[a], v[b]]
}

fn with_plane(p: Pose, plane: Plane, q: [f64; 2]) -> Pose {
    let (a, b, _) = plane.axes();
    let mut v = p.to_array();
    v[a] = q[0];
    v[b] = q[1];
    Pose::from_array(v)
}

/// The block a convex corner belongs to: its programmed end, whether it is a rapid, its feed.
#[derive(Clone, Copy)]
pub(super) struct CornerOf {
    pub end: Pose,
    pub rapid: bool,
    pub feed: f64,
}

/// LinuxCNC's move round a convex corner about the programmed corner `s` to `to` (offset
/// point): an arc, or for a rapid a straight traverse to the arc's end (there is no arc
/// traverse; `convert_straight_comp2`). Either carries the block's end on every axis outside
/// the plane but its normal, which stays where the tool is (`cz`, `AA_end`… in LinuxCNC), so a
/// rotary or UVW move of the block happens on the corner move.
fn corner_move(cx: &mut Ctx<'_>, of: CornerOf, s: [f64; 2], to: [f64; 2]) {
    let plane = cx.st.plane;
    let comp = cx.fe.modes.comp;
    let (_, _, normal) = plane.axes();
    let mut v = of.end.to_array();
    v[normal] = cx.st.program_position().to_array()[normal];
    let end = emit_at(cx, Pose::from_array(v), to);
    if of.rapid {
        cx.straight(true, end, of.feed);
    } else {
        cx.arc(
            plane,
            comp.side == 2,
            end,
            PlanarArc {
                centre: add(s, comp.nose),
                turns: 1,
            },
            of.feed,
        );
    }
}

/// LinuxCNC's lathe tool origin: a tool of orientation 1–8 (G18 only) is controlled at the
/// point of its nose that the orientation names, r from the nose centre along Z and/or X
/// (orientation 2: −X −Z; 1: −X +Z; 3: +X −Z; 4: +X +Z; 5/6/7/8: +Z/−X/−Z/+X only). The
/// compensated path is that of the nose centre; every compensated move is emitted shifted by
/// this (plane coordinates (z, x)), the moves after G40 are not.
pub fn nose_shift(plane: Plane, orientation: u8, r: f64) -> [f64; 2] {
    if plane != Plane::ZX {
        return [0.0; 2];
    }
    let dx = match orientation {
        1 | 2 | 6 => -r,
        3 | 4 | 8 => r,
        _ => 0.0,
    };
    let dz = match orientation {
        2 | 3 | 7 => -r,
        1 | 4 | 5 => r,
        _ => 0.0,
    };
    [dz, dx]
}

/// The nose centre (plane, program frame): the tool position less the nose shift once a
/// compensated move has put the tool there (before the entry move LinuxCNC takes the position
/// as it is).
fn tool_at(cx: &Ctx<'_>) -> [f64; 2] {
    let comp = &cx.fe.modes.comp;
    let here = plane_of(&cx.st.program_position(), cx.st.plane);
    if comp.program.is_some() {
        sub(here, comp.nose)
    } else {
        here
    }
}

/// `end` with its plane coordinates set to the nose-centre point `q` shifted to the tool origin.
fn emit_at(cx: &Ctx<'_>, end: Pose, q: [f64; 2]) -> Pose {
    with_plane(end, cx.st.plane, add(q, cx.fe.modes.comp.nose))
}

fn err(cx: &Ctx<'_>, code: &'static str, msg: &str, span: ColSpan) -> Diagnostic {
    cx.err(code, msg, span)
}

/// G41/G42 (radius from the tool table, D = tool number) and G41.1/G42.1 (
/// D = diameter).
pub(super) fn comp_on(
    cx: &mut Ctx<'_>,
    params: &Parameters,
    code: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    if cx.fe.modes.comp.on() {
        return Err(err(
            cx,
            "rs274::comp-already-on",
            "Cannot turn cutter radius comp on when on",
            span,
        ));
    }
    if cx.st.plane == Plane::YZ {
        return Err(err(
            cx,
            "rs274::comp-plane",
            "Cutter radius compensation allowed only in XY, XZ planes",
            span,
        ));
    }
    let dynamic = matches!(code, G41_1 | G42_1);
    let d = cx.words.take(b'D');
    let orientation = if dynamic { cx.words.take(b'L') } else { None };
    let mut tool_orientation = 0;
    let radius = if dynamic {
        match d {
            Some(d) => cx.mm(d.v) / 2.0,
            None => {
                return Err(err(
                    cx,
                    "rs274::comp-d-missing",
                    "D word missing with G41.1 or G42.1",
                    span,
                ))
            }
        }
    } else {
        let tool = match d {
            Some(d) => {
                if d.v < 0.0 || d.v.fract() != 0.0 {
                    return Err(err(
                        cx,
                        "rs274::comp-d",
                        "Negative or non-integer D word with G41 or G42",
                        d.span,
                    ));
                }
                let t = d.v as u32;
                if t != 0 && params.tools().get(t).is_none() {
                    return Err(cx.err(
                        "rs274::tool-not-found",
                        format!("Requested tool {t} not found in the tool table"),
                        d.span,
                    ));
                }
                t
            }
            None => cx.st.current_tool,
        };
        let edge = params.tools().get(tool).and_then(|t| t.edges.first());
        tool_orientation = edge.map_or(0, |e| e.orientation);
        edge.map_or(0.0, |e| e.radius)
    };
    let orientation = orientation.map_or(tool_orientation, |l| l.v.round().clamp(0.0, 9.0) as u8);
    // A negative diameter swaps the side, as in LinuxCNC.
    let mut side = if matches!(code, G41 | G41_1) { 1 } else { 2 };
    if radius < 0.0 {
        side = 3 - side;
    }
    cx.fe.modes.comp = CutterComp {
        side,
        radius: radius.abs(),
        program: None,
        last: None,
        moves_since: 0,
        nose: nose_shift(cx.st.plane, orientation, radius.abs()),
        stale: None,
        arc_refused: cx.fe.modes.comp.arc_refused,
        entry_from: cx.fe.modes.comp.program,
        entry_held: false,
        released: false,
        unchecked: false,
    };
    cx.out.push(Canon::Comment {
        text: format!(
            "interpreter: cutter radius compensation on {}",
            if side == 1 { "left" } else { "right" }
        ),
    });
    Ok(())
}

/// G40.
pub(super) fn comp_off(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    flush(cx, span)?;
    // The programmed point stays until the exit move: its missing words come from it.
    let was = cx.fe.modes.comp;
    cx.fe.modes.comp = CutterComp {
        program: was.program.or(was.entry_from),
        arc_refused: was.arc_refused || (was.on() && was.radius > 0.0 && was.program.is_some()),
        ..CutterComp::default()
    };
    cx.out.push(Canon::Comment {
        text: "interpreter: cutter radius compensation off".into(),
    });
    Ok(())
}

/// LinuxCNC's flush of the held moves at G40 and at a stop (M0, M1, M2, M30, M60:
/// `convert_stop`): `move_endpoint_and_flush` to where the tool is, whose gouge check fails a
/// held straight move that the last corner turned against its programmed way.
/// Nothing is held after it: the next corner joins from where the tool is.
pub(super) fn flush(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let comp = cx.fe.modes.comp;
    if comp.on() && comp.radius > 0.0 && comp.last.is_some() {
        reachable(cx, tool_at(cx), span)?;
        let c = &mut cx.fe.modes.comp;
        c.released = true;
        c.unchecked = true;
        c.moves_since = 0;
    }
    Ok(())
}

/// How many motion commands from the back compensation holds: the last element's (unless a
/// stop released it) and the moves without plane motion after it.
pub fn held_count(comp: &CutterComp) -> usize {
    comp.moves_since as usize + usize::from(!comp.released)
}

/// The programmed point of the plane, if compensation has set it (else the tool position).
pub fn programmed_point(st: &Rs274State) -> Option<[f64; 2]> {
    st.comp.program
}

/// A straight move under compensation to the programmed `end` (program coordinates).
pub(super) fn straight(
    cx: &mut Ctx<'_>,
    rapid: bool,
    end: Pose,
    feed: f64,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    let comp = cx.fe.modes.comp;
    let r = comp.radius;
    let e = plane_of(&end, plane);
    let Some(s) = comp.program else {
        // Entry move.
        let t = comp.entry_from.unwrap_or_else(|| tool_at(cx));
        let d = len(sub(e, t));
        // LinuxCNC accepts an entry exactly as long as the radius.
        if d < r {
            return Err(err(
                cx,
                "rs274::comp-entry-short",
                "Length of cutter compensation entry move is not greater than the tool radius",
                span,
            ));
        }
        let n = scale(left(unit(sub(e, t))), r * comp.sign());
        cx.straight(rapid, emit_at(cx, end, add(e, n)), feed);
        let c = &mut cx.fe.modes.comp;
        c.program = Some(e);
        c.last = Some(Element::Line { from: t, to: e });
        c.entry_held = true;
        c.released = false;
        c.unchecked = false;
        c.moves_since = 0;
        c.entry_from = None;
        c.arc_refused = false;
        return Ok(());
    };
    // (Within 1e-9 mm: a G70 pass's first rapid to S comes back through the cycle's frame.)
    if len(sub(e, s)) <= 1e-9 {
        // No motion in the plane: the tool keeps its plane position (LinuxCNC's, if stale).
        // Every move held behind the last element is copied into each block's undo (the next
        // element may move them all to its corner): bounded, so that a loop of Z moves under
        // compensation cannot cost the square of its length (mutation campaign, session 3).
        if comp.moves_since as usize >= MAX_MOVES_OUT_OF_PLANE {
            return Err(err(
                cx,
                "rs274::comp-no-plane-motion",
                &format!(
                    "more than {MAX_MOVES_OUT_OF_PLANE} moves in a row without motion in the \
                     plane of cutter compensation"
                ),
                span,
            )
            .with_note("move in the plane, or turn compensation off with G40 before them"));
        }
        let t = comp.stale.unwrap_or_else(|| tool_at(cx));
        cx.straight(rapid, emit_at(cx, end, t), feed);
        cx.fe.modes.comp.moves_since += 1;
        cx.fe.modes.comp.arc_refused = false;
        return Ok(());
    }
    let dir = unit(sub(e, s));
    let n = scale(left(dir), r * comp.sign());
    let new = Element::Line { from: s, to: e };
    if let Some(c) = comp.stale {
        stale::corner(cx, s, c, e, CornerOf { end, rapid, feed }, span)?;
    } else {
        let of = CornerOf { end, rapid, feed };
        corner(cx, s, dir, add(s, n), new, of, span)?;
    }
    cx.straight(rapid, emit_at(cx, end, add(e, n)), feed);
    let c = &mut cx.fe.modes.comp;
    c.stale = None;
    c.program = Some(e);
    c.last = Some(new);
    c.entry_held = false;
    c.released = false;
    c.moves_since = 0;
    c.arc_refused = false;
    Ok(())
}

/// Moves held in a row under compensation without motion in its plane (each waits for the next
/// element's corner): far beyond any real program's retract-and-plunge sequences.
pub const MAX_MOVES_OUT_OF_PLANE: usize = 2000;

/// An arc under compensation: programmed end `end`, programmed centre and turns in `planar`.
pub(super) fn arc(
    cx: &mut Ctx<'_>,
    ccw: bool,
    end: Pose,
    planar: PlanarArc,
    feed: f64,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let plane = cx.st.plane;
    let comp = cx.fe.modes.comp;
    let r = comp.radius;
    let s = comp
        .program
        .or(comp.entry_from)
        .unwrap_or_else(|| tool_at(cx));
    let e = plane_of(&end, plane);
    let c = planar.centre;
    let radius = len(sub(e, c));
    // Inside when the tool's side is the arc's turning side.
    let inside = (comp.side == 1) == ccw;
    let tool_radius = if inside { radius - r } else { radius + r };
    // Zero is allowed: a circle of the tool's own size is cut with the tool standing at its centre.
    // (LinuxCNC refuses arc radius ≤ tool radius after the entry, but compares in program units
    // after its own unit conversions: a tool-table radius under G20 comes out an ulp small, so
    // the tie passes there — LinuxCNC's sample `useful-subroutines` cuts such a circle — and a
    // G41.1 D radius ties exactly and fails; docs/linuxcnc.md, open differences.)
    if tool_radius < 0.0 {
        return Err(err(
            cx,
            "rs274::comp-arc-radius",
            "Tool radius not less than arc radius with comp",
            span,
        ));
    }
    let tool_end = add(c, scale(unit(sub(e, c)), tool_radius));
    let mut new = Element::Arc {
        centre: c,
        ccw,
        to: e,
        tool_radius,
        tool_from: [0.0; 2],
        queued_turn: 0.0,
    };
    if comp.program.is_none() {
        // Entry arc: through the current point, centre on the line C–E.
        let t = comp.entry_from.unwrap_or_else(|| tool_at(cx));
        let u = unit(sub(e, c));
        let chord = sub(tool_end, t);
        let k = dot(u, chord);
        if k.abs() < 1e-12 {
            return Err(err(
                cx,
                "rs274::comp-entry-arc",
                "Cannot make the cutter compensation entry arc from here",
                span,
            ));
        }
        let rho = dot(chord, chord) / (2.0 * k);
        let centre = sub(tool_end, scale(u, rho));
        if let Element::Arc {
            tool_from,
            queued_turn,
            ..
        } = &mut new
        {
            *tool_from = t;
            *queued_turn = find_turn(t, c, ccw, tool_end);
        }
        cx.arc(
            plane,
            ccw,
            emit_at(cx, end, tool_end),
            PlanarArc {
                centre: add(centre, cx.fe.modes.comp.nose),
                turns: planar.turns,
            },
            feed,
        );
    } else {
        // The offset start lies on the radius through the programmed start, r from it.
        let start_radius = len(sub(s, c));
        let start_tool = add(
            c,
            scale(
                unit(sub(s, c)),
                if inside {
                    start_radius - r
                } else {
                    start_radius + r
                },
            ),
        );
        let of = CornerOf {
            end,
            rapid: false,
            feed,
        };
        corner(cx, s, arc_tangent(c, s, ccw), start_tool, new, of, span)?;
        if let Element::Arc {
            tool_from,
            queued_turn,
            ..
        } = &mut new
        {
            *tool_from = tool_at(cx);
            *queued_turn = find_turn(s, c, ccw, e);
        }
        cx.arc(
            plane,
            ccw,
            emit_at(cx, end, tool_end),
            PlanarArc {
                centre: add(c, cx.fe.modes.comp.nose),
                turns: planar.turns,
            },
            feed,
        );
    }
    let cc = &mut cx.fe.modes.comp;
    cc.stale = None;
    cc.program = Some(e);
    cc.last = Some(new);
    cc.entry_held = false;
    cc.released = false;
    cc.moves_since = 0;
    Ok(())
}

/// Joins the previous offset element to the new one at the programmed corner `s` (module doc).
/// `dir` is the new element's start tangent, `start_tool` its offset start.
fn corner(
    cx: &mut Ctx<'_>,
    s: [f64; 2],
    dir: [f64; 2],
    start_tool: [f64; 2],
    new: Element,
    of: CornerOf,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let comp = cx.fe.modes.comp;
    let Some(last) = comp.last else {
        return Ok(());
    };
    let a = last.end_tangent();
    let turn = cross(a, dir).atan2(dot(a, dir));
    // LinuxCNC's zones (`convert_straight_comp2`, `convert_arc_comp2`: β = the turn away from
    // the tool's side, tolerance t = CONCAVE_TOLERANCE), in `towards` = the turn towards it:
    // concave for t < towards < π − t; a near reversal (|turn| within t of π, either sign, an
    // exact one's sign being a rounding accident) is convex — a half circle round the end —
    // unless an arc there has the tool outside it (the "h" and "m" shapes: the new arc, or the
    // last arc before a line), which LinuxCNC joins as concave; convex for towards < −t; and
    // within ±t of straight on nothing moves: the new element starts where the tool is, the
    // held move keeps its end (lines too: LinuxCNC does not seek the crossing there).
    let towards = comp.sign() * turn;
    let tool_outside = |e: Element| match e {
        Element::Arc { ccw, .. } => (comp.side == 1) != ccw,
        Element::Line { .. } => false,
    };
    let near_reversal = std::f64::consts::PI - turn.abs() <= CONCAVE_TOLERANCE;
    let concave = if near_reversal {
        match new {
            Element::Arc { .. } => tool_outside(new),
            Element::Line { .. } => tool_outside(last),
        }
    } else {
        towards > CONCAVE_TOLERANCE
    };
    if !concave && (near_reversal || towards < -CONCAVE_TOLERANCE) {
        // Convex: an arc about the corner (a traverse to its end for a rapid). Before a line
        // LinuxCNC flushes the held move first, with its gouge check; before an arc it only
        // issues it (`convert_arc_comp2`'s "convex, two arcs").
        if matches!(new, Element::Line { .. }) {
            reachable(cx, tool_at(cx), span)?;
        }
        corner_move(cx, of, s, start_tool);
        cx.fe.modes.comp.unchecked = false;
        return Ok(());
    }
    if !concave {
        cx.fe.modes.comp.unchecked = false;
        // Within the tolerance of straight on (LinuxCNC's "convex, one arc" with an arc): no
        // meeting point is sought, and the new offset start may be off the tool's position by
        // as much as an arc's end is off its radius or a line's normal turns.
        return Ok(());
    }
    // Concave: where the two offset paths meet — by LinuxCNC's own arithmetic where an arc is
    // one of them (`join.rs`), else the lines' crossing.
    let r = comp.radius;
    let prev_end = tool_at(cx);
    let p = join::concave_join(last, new, comp.side == 1, r, s, prev_end, start_tool)
        .map_err(|msg| cx.err("rs274::comp-gouge", msg, span))?;
    reachable(cx, p, span)?;
    move_held_end(cx, p);
    // Nothing queued to move (a stop flushed it all): LinuxCNC's endpoint stays invalid.
    cx.fe.modes.comp.unchecked = comp.released && held_count(&comp) == 0;
    Ok(())
}

/// LinuxCNC's check whenever a corner sets the held move's end (moved to a concave corner, or
/// kept before a convex arc) at `to` (nose centre): a held straight move must still run its
/// programmed direction from where it starts, else the tool would gouge (its error texts).
///
/// A held arc (LinuxCNC's `move_endpoint_and_flush`): moving its end must not make it sweep more
/// than it was queued with (`queued_turn`: the programmed sweep, so a concave join that starts
/// it early can fail even at the flush of a stop) — its turn from the tool's start to the new
/// end may exceed that by at most 0.0254 (G21) or 0.001 (G20), LinuxCNC comparing radians with
/// a length tolerance as written.
fn reachable(cx: &mut Ctx<'_>, to: [f64; 2], span: ColSpan) -> Result<(), Diagnostic> {
    let comp = cx.fe.modes.comp;
    if comp.released || comp.unchecked {
        // LinuxCNC's queue holds no move of the element now, or its endpoint is invalid:
        // nothing is checked.
        return Ok(());
    }
    let (from, end) = match comp.last {
        Some(Element::Line { from, to: end }) => (from, end),
        Some(Element::Arc {
            centre,
            ccw,
            tool_from,
            queued_turn: original,
            ..
        }) => {
            let moved = find_turn(tool_from, centre, ccw, to);
            let tolerance = match cx.st.units {
                LengthUnits::Millimetres => 0.0254,
                LengthUnits::Inches => 0.001,
            };
            if original != 0.0 && moved.abs() > original.abs() + tolerance {
                return Err(err(
                    cx,
                    "rs274::comp-concave-gouge",
                    "Arc move in concave corner cannot be reached by the tool without gouging",
                    span,
                ));
            }
            return Ok(());
        }
        None => return Ok(()),
    };
    let (frame, plane) = (cx.st.frame, cx.st.plane);
    let mut start = None;
    cx.out
        .edit_last_motions(held_count(&comp), |cmd, first| match (first, &*cmd) {
            (true, Canon::StraightTraverse(m)) => start = Some((m.start, true)),
            (true, Canon::StraightFeed(m)) => start = Some((m.start, false)),
            _ => {}
        });
    let Some((s, rapid)) = start else {
        return Ok(());
    };
    let s = sub(plane_of(&frame.to_program(&s), plane), comp.nose);
    // The direction LinuxCNC queued the move with: its travel, or for the entry line the
    // offset normal (so a crossing far behind the entry's end can pass, and one beside it fail).
    let travel = sub(end, from);
    let queued = if comp.entry_held {
        scale(left(travel), comp.sign())
    } else {
        travel
    };
    if dot(queued, sub(to, s)) >= 0.0 {
        return Ok(());
    }
    let what = if rapid { "traverse" } else { "feed" };
    Err(err(
        cx,
        "rs274::comp-concave-gouge",
        &format!("Straight {what} in concave corner cannot be reached by the tool without gouging"),
        span,
    ))
}

/// Moves the end of the held motion (and the plane position of the moves without plane motion
/// after it) to `p` (plane coordinates, program frame).
fn move_held_end(cx: &mut Ctx<'_>, p: [f64; 2]) {
    let plane = cx.st.plane;
    let p = add(p, cx.fe.modes.comp.nose);
    let frame = cx.st.frame;
    let remap = |m: &Pose| -> Pose {
        let prog = frame.to_program(m);
        frame.to_machine(&with_plane(prog, plane, p))
    };
    let n = held_count(&cx.fe.modes.comp);
    if n == 0 {
        // Released by a stop with nothing since: the tool stays where the issued move ended.
        return;
    }
    cx.out.edit_last_motions(n, |cmd, first| match cmd {
        Canon::StraightFeed(l) | Canon::StraightTraverse(l) => {
            if !first {
                l.start = remap(&l.start);
            }
            l.end = remap(&l.end);
        }
        Canon::ArcFeed(a) => {
            if !first {
                a.start = remap(&a.start);
            }
            a.end = remap(&a.end);
        }
        _ => {}
    });
    let np = remap(&cx.st.position);
    cx.st.position = np;
}
