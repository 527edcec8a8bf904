//! Profile arcs whose programmed end is off the circle through their start, as LinuxCNC's G7x
//! treats them (read off `rs274` traces, with LinuxCNC's `interp_g7x.cc` for the formulas).
//!
//! LinuxCNC keeps an arc's start S, centre C and end E as programmed (|E − C| may differ from
//! |S − C| by the program's rounding, 10⁻⁴ mm and more). Offsetting the profile by d it scales S
//! and E about C by (|S − C| ± d)/|S − C|, and where an arc meets a line it puts the joint on the
//! circle through the arc's (scaled) *end*, moving the arc's start there too when a line precedes
//! it. Its level crossings (G71/G72 levels, pocket walls) use the circle through the arc's start
//! as it then is, and the arc is printed with its own end point (which is where the next element
//! starts). So, with r_s = |S − C| and r_e = |E − C|:
//!
//! ```text
//!   joints with lines (both ends)       circle r_e ± d      (Stanok: the profile's arcs lie on
//!                                                            the end circle, `end_circle_arc`)
//!   level crossings, d ≠ 0:
//!     arc after a line                  circle r_e ± d      (its start was moved there)
//!     first element, after an arc       circle r_s ± d      (its start was only scaled)
//!       (programmed, or inserted at a corner), or after a line
//!       that ends exactly (10⁻⁶ mm) at the scaled start
//!   level crossings, d = 0              circle r_s          (nothing is moved)
//!   printed end point                   the next element's start (`lathe_cycles::emit`)
//! ```
//!
//! Precisely, r_e ± d is r_e·(r_s ± d₁)/r_s ± (d − d₁): LinuxCNC offsets in steps, the first d₁
//! of at most half the shortest element (an arc counting with the lesser of its chord and
//! radius), and only that first step scales the end radius by the start's factor — from then on
//! the arc's start lies on the end circle. The 10⁻⁵ mm this adds decides whether a line that
//! nearly touches the arc crosses its circle (lathe_g70_71_demo's first arc).
//! Not modelled: later steps' erasures and inserted arcs, the arc-after-arc joint (both circles
//! keep their offset radius here; LinuxCNC meets them on their start circles).
//!
//! Invariants: arcs keep their centre, sweep and sense (only the radius changes, by at most
//! |r_e − r_s|); lines are untouched; the chain stays connected within |r_e − r_s|.

use stanok_geom::chain2d::offset_chain_sourced;
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
/// each arc on the circle its level crossings use (module comment). None: see `offset_chain`.
pub(super) fn offset_profile(chain: &[Seg2], p0: P2, d: f64) -> Option<Vec<Seg2>> {
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
    Some(
        offset_chain_sourced(chain, Some(&start_radii), d)?
            .into_iter()
            .map(|(s, _)| s)
            .collect(),
    )
}

/// Largest gap between an arc's end on its crossing circle and the next element's start that is
/// the arc's own end point (|r_e − r_s| of a programmed arc; joints are otherwise exact).
const END_GAP: f64 = 1e-3;

/// Whether feed `next` starts at the end point of arc `arc` (module comment: an arc is printed
/// with its end point, which may be up to |r_e − r_s| off the circle its `Seg2` lies on).
pub(super) fn joins(arc: &Seg2, next: &Seg2) -> bool {
    dist2(arc.end(), next.start()) < END_GAP
}
