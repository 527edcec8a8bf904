//! Open chains of planar lines and arcs: the equidistant of a whole chain, with its corners
//! resolved, and where a line parallel to the first axis meets a chain.
//!
//! ```text
//!   offset of a chain s₀ … sₙ by d to the left (d < 0: right), element by element (offset2d):
//!     oᵢ = sᵢ.offset_left(d)
//!   then at every joint i | i+1, with the turn θ from tangent(sᵢ, end) to tangent(sᵢ₊₁, start):
//!     |θ| ≤ ANGLE_EPS (tangential)        → the pieces meet already: keep them;
//!     |θ| < NEAR_TANGENT, an arc, crossing → cut both at the first crossing near the corner;
//!       (no crossing, gap < 0.001 mm)      → join them at the foot of the perpendicular from
//!                                             the arc's centre to the line;
//!     θ turns away from the offset side   → a gap opens: insert an arc of radius |d| about the
//!       (right turn for d > 0, …)             programmed corner from end(oᵢ) to start(oᵢ₊₁)
//!       (two lines, a short gap: LinuxCNC's → extend both to their crossing (`ArcStarts`);
//!     θ turns towards the offset side     → the pieces overlap: cut both at their intersection
//!                                             nearest the programmed corner.
//! ```
//!
//! The chain's two free ends are offset perpendicular to their element and never extended, so the
//! offset chain starts at `start(s₀) + d·n(s₀)` — which is where LinuxCNC's lathe cycles start their
//! finishing passes. Invariants: the result is a connected chain (each element starts within
//! [`LEN_EPS`] of the previous end); nothing panics.
//!
//! An element the offset swallows whole — a concave arc whose offset radius vanishes, or a piece
//! that would have to run backwards to meet its neighbour (a concave fillet or chamfer, a step in
//! a notch, smaller than the offset) — is left out, and its neighbours' offsets are joined where
//! they cross (the previous one dropped in turn if it is swallowed too), as LinuxCNC's G7x does.
//! `None` when an overlapping corner has no crossing, the first or last element is swallowed, or an arc
//! kept on its end circle (`offset_chain_sourced`) would have to move.

mod joins;

use crate::offset2d::{
    curve_intersections, dist2, turn_angle, Seg2, ANGLE_EPS, LEN_EPS, P2, PARAM_EPS,
};
use joins::{
    foot_on_line, join_after_swallowed, join_after_swallowed_or_keep, join_overlapping,
    keeps_distance, same_sense, trim_end, trim_start, Joined,
};

/// Turns below this (radians) are nearly tangential: see `offset_chain`.
const NEAR_TANGENT: f64 = 1e-2;

/// A line's offset end this close to the next arc's offset start is a tangent joint: the arc
/// keeps its start circle (`offset_chain_sourced`), mm.
const TANGENT_JOINT: f64 = 1e-6;

/// The equidistant of the connected chain `chain` at signed distance `d` to the left of its
/// direction of travel (d < 0: right), with corners resolved (see the module comment).
pub fn offset_chain(chain: &[Seg2], d: f64) -> Option<Vec<Seg2>> {
    offset_chain_sourced(chain, None, d).map(|v| v.into_iter().map(|(s, _)| s).collect())
}

/// The arcs of a chain that may end off the circle through their start (see
/// [`offset_chain_sourced`]).
#[derive(Debug, Clone, Copy)]
pub struct ArcStarts<'a> {
    /// For each element of the chain, the radius of the circle about its centre through its
    /// start (lines: ignored).
    pub radius: &'a [f64],
    /// The first of the steps the offset is made in, signed like the offset, |d₁| ≤ |d|.
    pub first_step: f64,
    /// At a corner that turns away from the offset side, LinuxCNC's G7x inserts its arc only if
    /// the gap the first step opens runs forward along the first axis by more than this (0.01
    /// program units); two lines with a shorter gap run on to their crossing instead (a sharp
    /// corner). 0: always an arc.
    pub corner_arc_gap: f64,
    /// The program's length unit in mm (1: mm, 25.4: inches). LinuxCNC compares the gap in
    /// program units, so where it ties with `corner_arc_gap` the comparison is redone in them
    /// (see [`sharp_corner`]).
    pub unit: f64,
}

/// Gaps this close to `ArcStarts::corner_arc_gap` (mm) tie in mm arithmetic: the program-unit
/// rounding decides them.
const GAP_TIE: f64 = 1e-9;

/// The program-unit value `v` (mm) was converted from: of the doubles next to v/unit, one that
/// converts back to v exactly, the one with the shortest decimal form (a programmed number).
fn in_units(v: f64, unit: f64) -> f64 {
    if unit == 1.0 {
        return v;
    }
    let u0 = v / unit;
    [u0, u0.next_down(), u0.next_up()]
        .into_iter()
        .filter(|u| u * unit == v)
        .min_by_key(|u| format!("{u}").len())
        .unwrap_or(u0)
}

/// LinuxCNC's `add_distance` gap test in program units: the corner's first-axis coordinate
/// plus each piece's first-step offset along that axis, each sum rounded as a double in program
/// units (`start += d·I·dir/|dir|`), then subtracted and compared with the threshold. An
/// axis-aligned piece's offset direction is exactly ±1 or 0, so the result is bit-exact there.
fn gap_in_units(arcs: &ArcStarts, corner: P2, last: &Seg2, next: &Seg2) -> f64 {
    let unit = arcs.unit;
    let c = in_units(corner[0], unit);
    let step = in_units(arcs.first_step.abs(), unit);
    let along = |p: P2| {
        let len = dist2(p, corner);
        if len > 0.0 {
            (p[0] - corner[0]) / len
        } else {
            0.0
        }
    };
    (c + step * along(next.start())) - (c + step * along(last.end()))
}

/// Where the offsets `last` and `next` meet when the gap between them is too short for an arc
/// (`ArcStarts::corner_arc_gap`): the two pieces trimmed or extended to the point; None: an arc
/// closes it. LinuxCNC's `intersect_end`: two lines at their crossing; a line and an arc at the
/// crossing of the line with the arc's circle nearest `next`'s start (the foot of the
/// perpendicular from the centre if the line misses the circle); two arcs at the crossing of
/// their circles nearest `next`'s start (none: an arc after all).
fn sharp_corner(
    arcs: Option<&ArcStarts>,
    d: f64,
    corner: P2,
    last: &Seg2,
    next: &Seg2,
) -> Option<(Seg2, Seg2)> {
    let arcs = arcs?;
    // The gaps of every step have the same direction; their size scales with the step.
    let gap = (next.start()[0] - last.end()[0]) * (arcs.first_step / d).abs();
    if arcs.corner_arc_gap <= 0.0 {
        return None;
    }
    let arc = if (gap - arcs.corner_arc_gap).abs() <= GAP_TIE && arcs.unit > 0.0 {
        // A tie in mm (D exactly 0.01 inch at an axis-aligned corner): decided in program units.
        gap_in_units(arcs, corner, last, next) > in_units(arcs.corner_arc_gap, arcs.unit)
    } else {
        gap > arcs.corner_arc_gap
    };
    if arc {
        return None;
    }
    let nearest = |ps: Vec<P2>| {
        ps.into_iter()
            .min_by(|p, q| dist2(*p, next.start()).total_cmp(&dist2(*q, next.start())))
    };
    let x = match (*last, *next) {
        (Seg2::Line { .. }, Seg2::Line { .. }) => nearest(curve_intersections(last, next))?,
        (Seg2::Arc { c, .. }, Seg2::Line { a, b }) | (Seg2::Line { a, b }, Seg2::Arc { c, .. }) => {
            nearest(curve_intersections(last, next)).unwrap_or_else(|| foot_on_line(c, a, b))
        }
        (Seg2::Arc { .. }, Seg2::Arc { .. }) => nearest(curve_intersections(last, next))?,
    };
    if !(x[0].is_finite() && x[1].is_finite()) {
        return None;
    }
    let (a, b) = (trim_end(last, x), trim_start(next, x));
    (same_sense(last, &a) && same_sense(next, &b)).then_some((a, b))
}

/// [`offset_chain`] of a chain whose arcs may end off the circle through their start (a lathe
/// profile as LinuxCNC's G7x offsets it, `stanok-interp`'s `lathe_cycles/arcs.rs`): each arc of
/// `chain` lies on the circle through its *end* (radius r_e), `arcs.radius[i]` is r_s, the radius
/// through its start (`None`: every arc's own radius, which is [`offset_chain`]). Each element
/// comes with the index of the element of `chain` it is the offset of (None: an arc inserted at
/// a corner). With σ = +1 for a clockwise arc (−1 counter-clockwise), d₁ = `first_step`:
///
/// ```text
///   an arc after a line that does not end    resulting circle = end circle
///     at its offset start (10⁻⁶ mm)            R_e = r_e·(r_s + σd₁)/r_s + σ(d − d₁)
///   first, after an arc, or d = 0            resulting circle = start circle r_s + σd,
///                                              end circle R_e = r_e·(r_s + σd)/r_s
///   either, followed by a nearly tangent     R_e = the distance of that line's offset from the
///     line its end circle would not reach      centre (they meet at the foot, below)
///   joints with lines                        on the end circle R_e
///   joints of two arcs                       on their resulting circles
/// ```
///
/// An arc's resulting end point (on its resulting circle) may then be up to |R_e − R| from the
/// next element's start: the caller takes the latter as the arc's end.
pub fn offset_chain_sourced(
    chain: &[Seg2],
    arcs: Option<&ArcStarts>,
    d: f64,
) -> Option<Vec<(Seg2, Option<usize>)>> {
    // The arc of element i on its offset start circle (None: a line, or no start radii).
    let on_start_circle = |i: usize, o: &Seg2, d: f64| match (*o, arcs) {
        (
            Seg2::Arc {
                c, start, sweep, ..
            },
            Some(arcs),
        ) => {
            let r = *arcs.radius.get(i)? - d * sweep.signum();
            Some((r > LEN_EPS && r.is_finite()).then_some(Seg2::Arc { c, r, start, sweep }))
        }
        _ => None,
    };
    if d.abs() < LEN_EPS {
        return chain
            .iter()
            .enumerate()
            .map(|(i, s)| match on_start_circle(i, s, 0.0) {
                Some(arc) => arc.map(|a| (a, Some(i))),
                None => Some((*s, Some(i))),
            })
            .collect();
    }
    let mut out: Vec<Seg2> = Vec::with_capacity(chain.len() * 2);
    let mut source: Vec<Option<usize>> = Vec::with_capacity(chain.len() * 2);
    // The offset end circle of each arc of `out` that lies on another circle.
    let mut end_radius: Vec<Option<f64>> = Vec::with_capacity(chain.len() * 2);
    // An element the offset swallows whole (module comment) is left out: `skipped` says one was,
    // since the last element pushed.
    let mut skipped = false;
    let mut swallowed_any = false;
    for (i, s) in chain.iter().enumerate() {
        let Some(mut o) = s.offset_left(d) else {
            // An arc whose offset radius vanishes: a concave arc smaller than the offset.
            if i == 0 {
                return None;
            }
            skipped = true;
            swallowed_any = true;
            continue;
        };
        let mut o_end_radius = None;
        if let (
            Some(start_arc),
            Some(arcs),
            Seg2::Arc {
                c, r: r_e, sweep, ..
            },
        ) = (on_start_circle(i, &o, d), arcs, *s)
        {
            let Some(start_arc) = start_arc else {
                if i == 0 {
                    return None;
                }
                skipped = true;
                swallowed_any = true;
                continue;
            };
            // A corner turning away from the offset side gets an arc first (below): the arc
            // then follows that one, not the line.
            let turns_away = i.checked_sub(1).is_some_and(|j| {
                let theta = turn_angle(chain[j].tangent(1.0), s.tangent(0.0));
                theta.abs() >= NEAR_TANGENT && (theta < 0.0) == (d > 0.0)
            });
            let moved = !turns_away
                && matches!(out.last(), Some(l @ Seg2::Line { .. })
                    if dist2(l.end(), start_arc.start()) >= TANGENT_JOINT);
            let (r_s, sigma) = (arcs.radius[i], -sweep.signum());
            let d1 = if moved { arcs.first_step } else { d };
            let mut r_end = r_e * (r_s + sigma * d1) / r_s + sigma * (d - d1);
            // A nearly tangent line after it that the end circle would not reach.
            if let Some(next @ Seg2::Line { .. }) = chain.get(i + 1) {
                let theta = turn_angle(s.tangent(1.0), next.tangent(0.0));
                if let Some(Seg2::Line { a, b }) = next.offset_left(d) {
                    let h = dist2(c, foot_on_line(c, a, b));
                    if theta.abs() < NEAR_TANGENT && h > r_end {
                        r_end = h;
                    }
                }
            }
            if !(r_end > LEN_EPS && r_end.is_finite()) {
                return None;
            }
            if moved {
                if let Seg2::Arc { r, .. } = &mut o {
                    *r = r_end;
                }
            } else {
                o_end_radius = Some(r_end);
                o = start_arc;
            }
        }
        if let Some(prev_prog) = i.checked_sub(1).map(|j| chain[j]) {
            if skipped {
                // Elements were swallowed since the last one pushed: join it and this one where
                // their offsets cross (they overlap: the swallowed part was concave).
                let last = out.last()?;
                let reference = [
                    (last.end()[0] + o.start()[0]) / 2.0,
                    (last.end()[1] + o.start()[1]) / 2.0,
                ];
                let Some(joined) = join_after_swallowed_or_keep(
                    &mut out,
                    &mut source,
                    &mut end_radius,
                    o,
                    reference,
                )?
                else {
                    // Swallowed as well.
                    continue;
                };
                o = joined;
                skipped = false;
                out.push(o);
                source.push(Some(i));
                end_radius.push(o_end_radius);
                continue;
            }
            // The programmed corner (an arc's start may be off the circle it is given on).
            let corner = prev_prog.end();
            let theta = turn_angle(prev_prog.tangent(1.0), s.tangent(0.0));
            let last_index = out.len().checked_sub(1)?;
            let last = out.last_mut()?;
            // An arc meets the line after it on its end circle.
            let last_radius = match (&mut *last, end_radius.last().copied().flatten(), &o) {
                (Seg2::Arc { r, .. }, Some(end_r), Seg2::Line { .. }) => {
                    Some(std::mem::replace(r, end_r))
                }
                _ => None,
            };
            // Nearly tangential joints with an arc (a programmed arc whose end is a few µm off the
            // tangent) meet where the offset pieces cross, if they do, near the corner — of two
            // such crossings the first along the path (LinuxCNC does).
            let with_arc = matches!(last, Seg2::Arc { .. }) || matches!(o, Seg2::Arc { .. });
            let near = (theta.abs() < NEAR_TANGENT && with_arc)
                .then(|| {
                    curve_intersections(last, &o)
                        .into_iter()
                        .filter(|p| dist2(*p, corner) <= d.abs() * 2.0)
                        .map(|p| (trim_end(last, p), trim_start(&o, p)))
                        .filter(|(a, b)| same_sense(last, a) && same_sense(&o, b))
                        .min_by(|x, y| x.0.length().total_cmp(&y.0.length()))
                })
                .flatten();
            if theta.abs() <= ANGLE_EPS || dist2(last.end(), o.start()) < LEN_EPS {
                // Tangential: nothing to do.
            } else if let Some((a, b)) = near {
                *last = a;
                o = b;
            } else if with_arc && theta.abs() < NEAR_TANGENT && dist2(last.end(), o.start()) < 1e-3
            {
                // Tangential within the programmed arc's tolerance, the offset line passing just
                // outside the arc's circle: both end at the foot of the perpendicular from the
                // arc's centre to the line, the point of the line nearest the circle (LinuxCNC
                // does). The line keeps its direction; the arc ends at the foot's angle, its
                // point on the circle within 0.001 mm of the foot.
                match (*last, o) {
                    (arc @ Seg2::Arc { c, .. }, Seg2::Line { a, b }) => {
                        let foot = foot_on_line(c, a, b);
                        *last = trim_end(&arc, foot);
                        o = Seg2::Line { a: foot, b };
                    }
                    (Seg2::Line { a, b }, arc @ Seg2::Arc { c, .. }) => {
                        let foot = foot_on_line(c, a, b);
                        *last = Seg2::Line { a, b: foot };
                        o = trim_start(&arc, foot);
                    }
                    _ => {}
                }
            } else if let Some((a, b)) = ((theta < 0.0) == (d > 0.0))
                .then(|| sharp_corner(arcs, d, corner, last, &o))
                .flatten()
            {
                // Turn away from the offset side with a gap too short for LinuxCNC to close it
                // with an arc (`ArcStarts::corner_arc_gap`): both run on to their crossing.
                *last = a;
                o = b;
            } else if (theta < 0.0) == (d > 0.0) {
                // Turn away from the offset side: an arc about the corner closes the gap.
                let ccw = d < 0.0;
                let arc = Seg2::arc_through(corner, last.end(), o.start(), ccw, false);
                out.push(arc);
                source.push(None);
                end_radius.push(None);
            } else {
                // Turn towards it: the pieces overlap; meet at the crossing nearest the corner.
                match join_overlapping(last, &o, corner, false)? {
                    Joined::Both(a, b) => {
                        *last = a;
                        o = b;
                    }
                    // This element's trimmed piece would run backwards: it is swallowed.
                    Joined::NextSwallowed => {
                        if last_radius.is_some() {
                            return None;
                        }
                        skipped = true;
                        swallowed_any = true;
                        continue;
                    }
                    // The previous one is swallowed: drop it and join its predecessor to this
                    // one — which may be swallowed in turn (at most every element pushed).
                    Joined::LastSwallowed => {
                        if last_radius.is_some() {
                            return None;
                        }
                        swallowed_any = true;
                        let Some(joined) = join_after_swallowed(
                            &mut out,
                            &mut source,
                            &mut end_radius,
                            o,
                            corner,
                        )?
                        else {
                            skipped = true;
                            continue;
                        };
                        o = joined;
                        out.push(o);
                        source.push(Some(i));
                        end_radius.push(o_end_radius);
                        continue;
                    }
                }
            }
            // Back on the circle the arc ends up on, ending at the joint's angle.
            if let (Some(r0), Some(Seg2::Arc { r, .. })) = (last_radius, out.get_mut(last_index)) {
                *r = r0;
            }
        }
        out.push(o);
        source.push(Some(i));
        end_radius.push(o_end_radius);
    }
    // A swallowed last element would leave the chain's free end short of it (the end is offset
    // perpendicular to its element, never trimmed against anything): refused like a first one.
    if skipped {
        return None;
    }
    // Leaving elements out joins pieces that were not neighbours; where the offset is larger than
    // the whole neighbourhood (a chain of tiny elements), a free end or a joint can still come
    // nearer the profile than d. Checked, and refused, rather than cut into the profile.
    if swallowed_any && !keeps_distance(&out, chain, d.abs()) {
        return None;
    }
    Some(out.into_iter().zip(source).collect())
}

/// Where the line `{(a, b) : b = level}` meets the chain, as first-axis coordinates `a` sorted
/// ascending, each with the index of the element it lies on. An element lying along the line
/// counts with both of its ends; tangent contacts count once.
pub fn level_crossings(chain: &[Seg2], level: f64) -> Vec<(f64, usize)> {
    let mut v: Vec<(f64, usize)> = Vec::new();
    for (i, s) in chain.iter().enumerate() {
        match *s {
            Seg2::Line { a, b } => {
                let (b0, b1) = (a[1] - level, b[1] - level);
                if b0.abs() < LEN_EPS && b1.abs() < LEN_EPS {
                    v.push((a[0], i));
                    v.push((b[0], i));
                } else if (b0 <= LEN_EPS && b1 >= -LEN_EPS) || (b0 >= -LEN_EPS && b1 <= LEN_EPS) {
                    let t = (b0 / (b0 - b1)).clamp(0.0, 1.0);
                    v.push((a[0] + t * (b[0] - a[0]), i));
                }
            }
            Seg2::Arc { .. } => {
                let probe = Seg2::Line {
                    a: [0.0, level],
                    b: [1.0, level],
                };
                for p in curve_intersections(&probe, s) {
                    if on_arc(s, p) {
                        v.push((p[0], i));
                    }
                }
            }
        }
    }
    v.retain(|(a, _)| a.is_finite());
    v.sort_by(|x, y| x.0.total_cmp(&y.0));
    v
}

/// Whether `p`, a point of the arc's circle, lies within its sweep.
fn on_arc(s: &Seg2, p: P2) -> bool {
    match *s {
        Seg2::Arc { c, r, start, sweep } => {
            let phi = (p[1] - c[1]).atan2(p[0] - c[0]);
            let u = ((phi - start) * sweep.signum()).rem_euclid(std::f64::consts::TAU);
            let tol = PARAM_EPS + LEN_EPS / r.max(1e-300);
            u <= sweep.abs() + tol || u >= std::f64::consts::TAU - tol
        }
        Seg2::Line { .. } => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(a: P2, b: P2) -> Seg2 {
        Seg2::Line { a, b }
    }

    fn close(a: P2, b: P2) -> bool {
        dist2(a, b) < 1e-9
    }

    #[test]
    fn a_step_gets_an_intersection_inside_and_an_arc_outside() {
        // (z, x): along −z at x = 10, up to x = 14, on along −z; offset to +x (the right of −z).
        let chain = [
            line([0.0, 10.0], [-10.0, 10.0]),
            line([-10.0, 10.0], [-10.0, 14.0]),
            line([-10.0, 14.0], [-20.0, 14.0]),
        ];
        let o = offset_chain(&chain, -0.5).unwrap();
        assert_eq!(o.len(), 4);
        assert!(close(o[0].start(), [0.0, 10.5]));
        assert!(close(o[0].end(), [-9.5, 10.5]) && close(o[1].start(), [-9.5, 10.5]));
        assert!(matches!(o[2], Seg2::Arc { r, .. } if (r - 0.5).abs() < 1e-12));
        assert!(close(o[2].end(), [-10.0, 14.5]) && close(o[3].end(), [-20.0, 14.5]));
        for w in o.windows(2) {
            assert!(close(w[0].end(), w[1].start()));
        }
    }

    #[test]
    fn an_element_swallowed_by_the_offset_is_left_out() {
        // A 0.5 step inside a right-angled notch: offset by 1 towards the notch, the step's
        // offset would run backwards. It is left out and the corner's arc meets the next line:
        // LinuxCNC 2.9's G70 on this profile (X5 side, D1) cuts x = 9 to z = −10, the arc about
        // (−10, 10) to (−10.8660, 9.5), and x = 9.5 on.
        let chain = [
            line([0.0, 10.0], [-10.0, 10.0]),
            line([-10.0, 10.0], [-10.0, 10.5]),
            line([-10.0, 10.5], [-20.0, 10.5]),
        ];
        assert_eq!(offset_chain(&chain, 0.2).map(|o| o.len()), Some(4));
        let o = offset_chain(&chain, 1.0).expect("the step is left out");
        assert_eq!(o.len(), 3);
        assert!(close(o[0].start(), [0.0, 9.0]) && close(o[0].end(), [-10.0, 9.0]));
        let z = -10.0 - 0.75f64.sqrt();
        assert!(
            matches!(o[1], Seg2::Arc { c, r, .. } if close(c, [-10.0, 10.0]) && (r - 1.0).abs() < 1e-12)
        );
        assert!(close(o[1].end(), [z, 9.5]) && close(o[2].start(), [z, 9.5]));
        assert!(close(o[2].end(), [-20.0, 9.5]));
    }

    #[test]
    fn two_concave_elements_in_a_row_are_both_left_out() {
        // Along −z at x = 10, a 0.2 chamfer-like rise, a 0.3 steeper one, then up to x = 16:
        // every corner concave towards +x. Offset by 1 to +x (the right of −z), both short
        // elements vanish and the first line's offset meets the wall's at (−8.1, 11).
        let chain = [
            line([0.0, 10.0], [-8.8, 10.0]),
            line([-8.8, 10.0], [-9.0, 10.2]),
            line([-9.0, 10.2], [-9.1, 10.5]),
            line([-9.1, 10.5], [-9.1, 16.0]),
        ];
        let o = offset_chain(&chain, -1.0).expect("both are left out");
        assert_eq!(o.len(), 2);
        assert!(close(o[0].end(), [-8.1, 11.0]) && close(o[1].start(), [-8.1, 11.0]));
        assert!(close(o[1].end(), [-8.1, 16.0]));
    }

    /// A rising line, a clockwise arc about (4, 6) from (2, 6) over the top to (6.0015, 6) — its
    /// end 0.0015 outside its start's circle (r_s = 2, r_e = 2.0015) — and a falling line.
    fn off_radius_chain() -> [Seg2; 3] {
        let (c, s, e) = ([4.0, 6.0], [2.0, 6.0], [6.0015, 6.0]);
        let arc = match Seg2::arc_through(c, s, e, false, false) {
            Seg2::Arc { start, sweep, .. } => Seg2::Arc {
                c,
                r: dist2(c, e),
                start,
                sweep,
            },
            l => l,
        };
        [line([0.0, 4.0], s), arc, line(e, [8.0, 4.0])]
    }

    #[test]
    fn an_arc_after_a_line_ends_on_its_end_circle_scaled_by_the_first_step_only() {
        // Offset 0.5 outwards in steps, the first 0.1: R_e = r_e·(r_s + 0.1)/r_s + 0.4.
        let chain = off_radius_chain();
        let radius = [0.0, 2.0, 0.0];
        let arcs = ArcStarts {
            radius: &radius,
            first_step: 0.1,
            corner_arc_gap: 0.0,
            unit: 1.0,
        };
        let o = offset_chain_sourced(&chain, Some(&arcs), 0.5).unwrap();
        let expected = 2.0015 * 2.1 / 2.0 + 0.4;
        let Seg2::Arc { r, .. } = o[1].0 else {
            panic!("{o:?}")
        };
        assert!((r - expected).abs() < 1e-12, "{r} {expected}");
        // The lines meet it on that circle.
        assert!((dist2(o[0].0.end(), [4.0, 6.0]) - expected).abs() < 1e-9);
        assert!((dist2(o[2].0.start(), [4.0, 6.0]) - expected).abs() < 1e-9);
        // One step: the whole offset scales the end circle.
        let arcs = ArcStarts {
            radius: &radius,
            first_step: 0.5,
            corner_arc_gap: 0.0,
            unit: 1.0,
        };
        let o = offset_chain_sourced(&chain, Some(&arcs), 0.5).unwrap();
        assert!(matches!(o[1].0, Seg2::Arc { r, .. } if (r - 2.0015 * 2.5 / 2.0).abs() < 1e-12));
    }

    #[test]
    fn a_first_arc_crosses_on_its_start_circle_and_meets_lines_on_its_end_circle() {
        let chain = off_radius_chain();
        let radius = [2.0, 0.0];
        let arcs = ArcStarts {
            radius: &radius,
            first_step: 0.1,
            corner_arc_gap: 0.0,
            unit: 1.0,
        };
        let o = offset_chain_sourced(&chain[1..], Some(&arcs), 0.5).unwrap();
        assert!(
            matches!(o[0].0, Seg2::Arc { r, .. } if (r - 2.5).abs() < 1e-12),
            "{o:?}"
        );
        // The line after it starts on the end circle scaled with the start: r_e·2.5/2.
        assert!((dist2(o[1].0.start(), [4.0, 6.0]) - 2.0015 * 1.25).abs() < 1e-9);
        // Without start radii it is an ordinary arc of radius r_e.
        let plain = offset_chain(&chain[1..], 0.5).unwrap();
        assert!(matches!(plain[0], Seg2::Arc { r, .. } if (r - 2.5015).abs() < 1e-12));
    }

    #[test]
    fn a_nearly_tangent_line_that_misses_the_arc_meets_it_at_the_foot() {
        // A counter-clockwise quarter about the origin from (0, −10) to (10.0003, 0) (r_s = 10,
        // r_e = 10.0003), then the tangent line up from its end. Offset by 1 to the left (towards
        // the centre) the end circle would be r_e·9/10 = 9.00027, inside the offset line x =
        // 9.0003: they meet at the foot of the perpendicular, (9.0003, 0).
        let e = [10.0003, 0.0];
        let arc = match Seg2::arc_through([0.0, 0.0], [0.0, -10.0], e, true, false) {
            Seg2::Arc {
                c, start, sweep, ..
            } => Seg2::Arc {
                c,
                r: dist2(c, e),
                start,
                sweep,
            },
            l => l,
        };
        let chain = [arc, line(e, [10.0003, 5.0])];
        let radius = [10.0, 0.0];
        let arcs = ArcStarts {
            radius: &radius,
            first_step: 1.0,
            corner_arc_gap: 0.0,
            unit: 1.0,
        };
        let o = offset_chain_sourced(&chain, Some(&arcs), 1.0).unwrap();
        // The first arc keeps its start circle for its crossings.
        assert!(
            matches!(o[0].0, Seg2::Arc { r, .. } if (r - 9.0).abs() < 1e-12),
            "{o:?}"
        );
        assert!(dist2(o[1].0.start(), [9.0003, 0.0]) < 1e-9, "{o:?}");
        let end = o[0].0.end();
        assert!(end[1].atan2(end[0]).abs() < 1e-9);
    }

    #[test]
    fn level_crossings_of_lines_and_arcs() {
        let chain = [
            line([0.0, 0.0], [10.0, 10.0]),
            Seg2::arc_through([15.0, 10.0], [10.0, 10.0], [20.0, 10.0], false, false),
        ];
        let c = level_crossings(&chain, 5.0);
        assert_eq!(c.len(), 1);
        assert!((c[0].0 - 5.0).abs() < 1e-12);
        // The arc (clockwise from (10,10) over the top to (20,10)) meets b = 14 twice.
        let c = level_crossings(&chain, 14.0);
        assert_eq!(c.len(), 2);
        assert!((c[0].0 - 12.0).abs() < 1e-9 && (c[1].0 - 18.0).abs() < 1e-9);
    }

    /// A chain falling in z all along (as a lathe profile does): lines and arcs whose directions
    /// stay within 80° of −z, short elements included.
    fn falling_chain(steps: &[(f64, f64, f64, bool)]) -> Vec<Seg2> {
        let mut p = [0.0, 10.0];
        let mut chain = Vec::new();
        for &(angle, len, bend, arc) in steps {
            // Direction: −z turned by `angle` (|angle| < 80°).
            let dir = [-angle.cos(), angle.sin()];
            let s = if arc && bend.abs() > 0.05 {
                // An arc leaving in `dir` and turning by `bend` (so its end direction stays in
                // the cone when |angle + bend| < 80° too).
                let r = len / bend.abs();
                let side = bend.signum();
                let n = crate::offset2d::left_normal(dir);
                let c = [p[0] + side * r * n[0], p[1] + side * r * n[1]];
                let a0 = (p[1] - c[1]).atan2(p[0] - c[0]);
                Seg2::Arc {
                    c,
                    r,
                    start: a0,
                    sweep: bend,
                }
            } else {
                line(p, [p[0] + len * dir[0], p[1] + len * dir[1]])
            };
            p = s.end();
            chain.push(s);
        }
        chain
    }

    proptest::proptest! {
        /// Offsetting a falling chain — elements the offset swallows included — gives either
        /// nothing or a connected chain no point of which comes closer to the programmed chain
        /// than the offset distance (nothing is cut into the profile). Joints are kept clear of
        /// LinuxCNC's nearly tangent rule, which deliberately meets where the pieces cross (a
        /// short line extended back to an arc's offset passes up to ~0.2 µm nearer the arc).
        #[test]
        fn offsets_are_connected_and_keep_their_distance(
            steps in proptest::collection::vec(
                (-1.0f64..1.0, 0.05f64..4.0, -0.35f64..0.35, proptest::bool::ANY), 2..7),
            d in -2.0f64..2.0,
        ) {
            let chain = falling_chain(&steps);
            proptest::prop_assume!(chain.iter().all(|s| {
                let (a, b) = (s.tangent(0.0), s.tangent(1.0));
                a[0] < -0.17 && b[0] < -0.17
            }));
            proptest::prop_assume!(d.abs() > 1e-3);
            if chain.windows(2).any(|w| {
                turn_angle(w[0].tangent(1.0), w[1].tangent(0.0)).abs() < 2.0 * NEAR_TANGENT
            }) {
                return Ok(());
            }
            let Some(o) = offset_chain(&chain, d) else {
                return Ok(());
            };
            for w in o.windows(2) {
                proptest::prop_assert!(dist2(w[0].end(), w[1].start()) < 1e-6);
            }
            for s in &o {
                // 97 points a piece: not the points `keeps_distance` samples.
                for k in 0..=96 {
                    let q = s.point(k as f64 / 96.0);
                    let near = chain
                        .iter()
                        .map(|e| e.distance_to(q))
                        .fold(f64::INFINITY, f64::min);
                    proptest::prop_assert!(
                        near >= d.abs() - 1e-6,
                        "offset point {:?} is {} from the profile (offset {})", q, near, d
                    );
                }
            }
        }
    }

    #[test]
    fn a_short_gap_at_a_convex_corner_is_closed_by_the_crossing_not_an_arc() {
        // Along +c, then down (−l): a convex corner for an offset to the left (+l side). The gap
        // along c is d; LinuxCNC closes it with an arc only if that exceeds 0.01 program units.
        let chain = [line([0.0, 0.0], [5.0, 0.0]), line([5.0, 0.0], [5.0, -3.0])];
        let radius = [0.0, 0.0];
        let gap = |corner_arc_gap: f64, d: f64| {
            let arcs = ArcStarts {
                radius: &radius,
                first_step: d,
                corner_arc_gap,
                unit: 1.0,
            };
            offset_chain_sourced(&chain, Some(&arcs), d).unwrap()
        };
        let sharp = gap(0.254, 0.17);
        assert_eq!(sharp.len(), 2, "{sharp:?}");
        assert!(close(sharp[0].0.end(), [5.17, 0.17]), "{sharp:?}");
        assert!(close(sharp[1].0.start(), [5.17, 0.17]), "{sharp:?}");
        let round = gap(0.254, 0.762);
        assert_eq!(round.len(), 3, "{round:?}");
        assert!(matches!(round[1], (Seg2::Arc { r, .. }, None) if (r - 0.762).abs() < 1e-9));
        // 0: always an arc (the plain offset).
        assert_eq!(gap(0.0, 0.17).len(), 3);
    }

    #[test]
    fn a_gap_of_exactly_the_threshold_is_decided_in_program_units() {
        // D 0.01 inch at a corner at c inches: LinuxCNC arcs iff fl(c + 0.01) − c > 0.01 in
        // inches. c = 0.0013: 0.010000000000000002 in inches (an arc), exactly 0.254 in mm;
        // c = 0.0098: 0.009999999999999998 in inches (sharp), 0.25400000000000006 in mm.
        let pieces = |c_in: f64| {
            let c = c_in * 25.4;
            let chain = [line([-5.0, 0.0], [c, 0.0]), line([c, 0.0], [c, -3.0])];
            let radius = [0.0, 0.0];
            let d = 0.01 * 25.4;
            let arcs = ArcStarts {
                radius: &radius,
                first_step: d,
                corner_arc_gap: 0.01 * 25.4,
                unit: 25.4,
            };
            offset_chain_sourced(&chain, Some(&arcs), d).unwrap().len()
        };
        assert_eq!(pieces(0.0013), 3, "an arc");
        assert_eq!(pieces(0.0098), 2, "sharp");
        assert_eq!(in_units(0.4203 * 25.4, 25.4), 0.4203);
        assert_eq!(in_units(0.7746 * 25.4, 25.4), 0.7746);
    }
}
