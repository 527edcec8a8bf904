//! LinuxCNC 2.9's concave joins where an arc meets its neighbour under cutter compensation
//! (`convert_arc_comp2` for a line or an arc before an arc, `convert_straight_comp2` for an arc
//! before a line), computed as LinuxCNC computes them: each picks one root of the offsets'
//! intersection by the elements' senses, not the nearest one, and words its own error when
//! there is none. With s the programmed corner, t the tool (the held move's offset end), r the
//! tool radius, "inside" the tool on the side an arc turns to (G41 with G3, G42 with G2):
//!
//! ```text
//! line → arc (centre C, end radius R, sense σ = ±1 for G3/G2):
//!   θ = ∠(t − s) ∓ π/2 (G41/G42: the line's direction)   α = ∠(C − s) ∓ σπ/2 (the arc's)
//!   β = ±(θ − α) (G41/G42), into [−π/2, 3π/2);  h = R·sin(β − π/2)
//!   inside:  ρ = R − r, l = (h + r)/ρ, φ = θ + σ·asin l
//!   outside: ρ = R + r, l = (h − r)/ρ, φ = θ + π − σ·asin l
//!   join = C + ρ·u(φ)  (|l| > 1: "Arc move in concave corner cannot be reached …")
//! arc (centre P, offset radius ρ, sense σ) → line towards e:
//!   θ = ∠(e − s) + σπ/2,  ρ₀ = ρ ± r (inside/outside),  d = ρ₀·cos(θ − ∠(P − s))
//!   inside:  l = (d − r)/ρ, φ = θ + π − σ·acos l;  outside: l = (d + r)/ρ, φ = θ + π + σ·acos l
//!   join = P + ρ·u(φ)  (|l| > 1: "Arc to straight motion makes a corner …")
//! arc (P, ρ) → arc (C, ρ' = its offset radius, sense σ'):
//!   a = (ρ² + |C − P|² − ρ'²)/(2ρ|C − P|),  φ = ∠(C − P) ± σ'·acos a (+ if the tool is inside
//!   the first arc)  join = P + ρ·u(φ)  (|a| > 1: "Arc to arc motion makes a corner …";
//!   same centres: "Arc to arc motion is invalid because the arcs have the same center")
//! ```
//!
//! Two lines are joined at their offsets' crossing (`geometry::meet_lines`; LinuxCNC's retreat
//! along the first line reaches the same point).

use super::geometry::{len, meet_lines, sub};
use super::Element;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn angle(v: [f64; 2]) -> f64 {
    v[1].atan2(v[0])
}

fn at(c: [f64; 2], r: f64, phi: f64) -> [f64; 2] {
    [c[0] + r * phi.cos(), c[1] + r * phi.sin()]
}

/// Where the held element's offset end moves for a concave corner (module doc), or LinuxCNC's
/// message when the tool cannot fit. `left`: G41; `s`: the programmed corner; `tool`: the held
/// move's offset end; `new_start`: the new element's offset start (two parallel lines).
pub(super) fn concave_join(
    last: Element,
    new: Element,
    left: bool,
    r: f64,
    s: [f64; 2],
    tool: [f64; 2],
    new_start: [f64; 2],
) -> Result<[f64; 2], &'static str> {
    let inside = |ccw: bool| left == ccw;
    let sense = |ccw: bool| if ccw { 1.0 } else { -1.0 };
    match (last, new) {
        (Element::Line { from, to }, Element::Line { from: f2, to: t2 }) => {
            let off = if left { r } else { -r };
            Ok(meet_lines((from, to), (f2, t2), off, new_start))
        }
        (
            Element::Line { .. },
            Element::Arc {
                centre, ccw, to, ..
            },
        ) => {
            let arc_radius = len(sub(to, centre));
            let theta = angle(sub(tool, s)) + if left { -FRAC_PI_2 } else { FRAC_PI_2 };
            let delta = angle(sub(centre, s));
            let alpha = delta - sense(ccw) * FRAC_PI_2;
            let mut beta = if left { theta - alpha } else { alpha - theta };
            if beta > 1.5 * PI {
                beta -= TAU;
            } else if beta < -FRAC_PI_2 {
                beta += TAU;
            }
            let h = arc_radius * (beta - FRAC_PI_2).sin();
            let (rho, l) = if inside(ccw) {
                (arc_radius - r, (h + r) / (arc_radius - r))
            } else {
                (arc_radius + r, (h - r) / (arc_radius + r))
            };
            if !(-1.0..=1.0).contains(&l) {
                Err("Arc move in concave corner cannot be reached by the tool without gouging")
            } else if inside(ccw) {
                Ok(at(centre, rho, theta + sense(ccw) * l.asin()))
            } else {
                Ok(at(centre, rho, theta + PI - sense(ccw) * l.asin()))
            }
        }
        (
            Element::Arc {
                centre: p,
                ccw,
                tool_radius: rho,
                ..
            },
            Element::Line { to: e, .. },
        ) => {
            let theta = angle(sub(e, s)) + sense(ccw) * FRAC_PI_2;
            let uncomp = if inside(ccw) { rho + r } else { rho - r };
            let d = uncomp * (theta - angle(sub(p, s))).cos();
            let l = (if inside(ccw) { d - r } else { d + r }) / rho;
            if !(-1.0..=1.0).contains(&l) {
                Err("Arc to straight motion makes a corner the compensated tool can't fit in without gouging")
            } else if inside(ccw) {
                Ok(at(p, rho, theta + PI - sense(ccw) * l.acos()))
            } else {
                Ok(at(p, rho, theta + PI + sense(ccw) * l.acos()))
            }
        }
        (
            Element::Arc {
                centre: p,
                ccw: first_ccw,
                tool_radius: rho,
                ..
            },
            Element::Arc {
                centre: c,
                ccw,
                tool_radius: new_rho,
                ..
            },
        ) => {
            let cc = len(sub(c, p));
            if rho == 0.0 || cc == 0.0 {
                return Err("Arc to arc motion is invalid because the arcs have the same center");
            }
            let a = (rho * rho + cc * cc - new_rho * new_rho) / (2.0 * rho * cc);
            if !(-1.0..=1.0).contains(&a) {
                Err("Arc to arc motion makes a corner the compensated tool can't fit in without gouging")
            } else {
                let towards = if inside(first_ccw) { 1.0 } else { -1.0 };
                Ok(at(
                    p,
                    rho,
                    angle(sub(c, p)) + towards * sense(ccw) * a.acos(),
                ))
            }
        }
    }
}
