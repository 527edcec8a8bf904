//! Profile arcs whose programmed end is off the circle through their start, as LinuxCNC's G7x
//! treats them (read off `rs274` traces, with LinuxCNC's `interp_g7x.cc` for the formulas).
//!
//! LinuxCNC keeps an arc's start S, centre C and end E as programmed (|E − C| may differ from
//! |S − C| by the program's rounding, 10⁻⁴ mm and more). It offsets the profile by d in steps (the
//! first, d₁, at most half its shortest element, an arc counting with the lesser of its chord and
//! start radius); each step scales S and E about C by (|S − C| ± step)/|S − C| and then joins the
//! neighbours, a line meeting an arc on the circle through the arc's *end* and moving the arc's
//! start there too. Its level crossings (G71/G72 levels, pocket walls) use the circle through
//! the arc's start as it then is, and the arc is printed with its own end point. With r_s = |S − C|,
//! r_e = |E − C| and ± the side the offset goes (the arc grows or shrinks), the result is:
//!
//! ```text
//!   arc after a line (not ending exactly     end circle  r_e·(r_s ± d₁)/r_s ± (d − d₁), which is
//!     at its scaled start)                     also the circle its levels cross
//!   first element, after an arc (programmed  levels cross r_s ± d (the start was only scaled);
//!     or inserted at a corner), after a        end circle r_e·(r_s ± d)/r_s
//!     line ending at its scaled start
//!   followed by a nearly tangent line its    end circle = that line's distance from C (rs274
//!     end circle would not reach               resets the end to the foot of the perpendicular)
//!   d = 0                                    nothing moves: levels cross r_s
//!   joints with lines                        on the end circle; printed end = next element's
//!                                              start (`lathe_cycles::emit`, `climb.rs`)
//! ```
//!
//! Evidence: `rs274` traces of `lathe_g70_71_demo.ngc` and of test programs (a line, an arc whose
//! end is 1.5·10⁻³ mm outside its start's circle, a line; with and without a short element that
//! makes the offset take several steps): the level crossings on the arc agree to 10⁻⁵ mm with
//! the formulas above and not with r_e ± d or r_s ± d. Golden: `tests/rs274/stanok-g7x-offradius`.
//! Not modelled: later steps' erasures and inserted arcs, and the joint of two arcs is made on
//! their resulting circles once (rs274 re-makes it every step).
//!
//! Invariants: arcs keep their centre, sweep and sense (only the radius changes, by at most
//! |r_e − r_s|); lines are untouched; the chain stays connected within |r_e − r_s|.

use stanok_geom::chain2d::{offset_chain_sourced, ArcStarts};
use stanok_geom::offset2d::{dist2, Seg2, P2};

/// The arc about `c` from `s` to `e` on the circle through `e` (the start keeps its angle).
pub(super) fn end_circle_arc(c: P2, s: P2, e: P2, ccw: bool, full: bool) -> Seg2 {
    match Seg2::arc_through(c, s, e, ccw, full) {
        Seg2::Arc { start, sweep, .. } => Seg2::Arc {
            c,
            r: dist2(c, e),
            start,
            sweep,
        },
        line => line,
    }
}

/// The profile `chain` (arcs on their end circles, starting at `p0`) offset by `d` to the left,
/// each arc on the circle its level crossings use (module comment). `unit` is the program's
/// length unit in mm: a convex corner between two lines gets its arc only where the first step
/// opens a gap of more than 0.01 units along the cut axis, else the lines meet at their crossing
/// (LinuxCNC's `add_distance`; D0.0067 in inches leaves sharp corners, D0.03 rounds them).
/// None: see `offset_chain`.
pub(super) fn offset_profile(chain: &[Seg2], p0: P2, d: f64, unit: f64) -> Option<Vec<Seg2>> {
    // The programmed start of element i is where element i − 1 ends (arcs on their end circles
    // end exactly at their programmed end), or P0.
    let start_radius = |i: usize| {
        let s = i.checked_sub(1).map_or(p0, |j| chain[j].end());
        match chain[i] {
            Seg2::Arc { c, .. } => dist2(c, s),
            Seg2::Line { .. } => 0.0,
        }
    };
    let start_radii: Vec<f64> = (0..chain.len()).map(start_radius).collect();
    // LinuxCNC's first step: at most half the shortest element (an arc counting with the lesser
    // of its chord and its start radius).
    let first_step = chain
        .iter()
        .zip(&start_radii)
        .map(|(s, &r_s)| match *s {
            Seg2::Line { a, b } => dist2(a, b) / 2.0,
            Seg2::Arc { .. } => dist2(s.start(), s.end()).min(r_s) / 2.0,
        })
        .fold(d.abs(), f64::min)
        * d.signum();
    let arcs = ArcStarts {
        radius: &start_radii,
        first_step,
        corner_arc_gap: 0.01 * unit,
        unit,
    };
    Some(
        offset_chain_sourced(chain, Some(&arcs), d)?
            .into_iter()
            .map(|(s, _)| s)
            .collect(),
    )
}

/// How far an arc's end on its `Seg2` circle may be from the next element's start and still be
/// taken as the arc's own end point: twice what the arc check accepts for |r_e − r_s| (0.1 % of
/// the radius, or its absolute tolerance, `rs274/motion.rs`), as a fraction of the radius and in
/// mm. Consecutive feeds of a cycle are connected by construction, so any gap is this one.
const END_GAP_REL: f64 = 2e-3;
const END_GAP_ABS: f64 = 0.02;

/// Whether feed `next` starts at the end point of arc `arc` (module comment: an arc is printed
/// with its end point, which may be up to |R_e − R| off the circle its `Seg2` lies on).
/// A line (it ends where it ends) never does.
pub(super) fn joins(arc: &Seg2, next: &Seg2) -> bool {
    match *arc {
        Seg2::Arc { r, .. } => dist2(arc.end(), next.start()) <= END_GAP_REL * r + END_GAP_ABS,
        Seg2::Line { .. } => false,
    }
}
