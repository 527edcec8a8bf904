//! Cutter and nose radius compensation G41/G42 (G46 on the T-series) as geometry
//! (`docs/dialects/mazatrol-eia.md` §8.5).
//!
//! The tool centre runs on the equidistant of the programmed contour at the signed distance
//! `d` (+r left of the direction of travel for G41, −r right for G42). The front end streams the
//! contour: a compensated element is known only when the next one is, so it keeps one element
//! pending and asks [`corner`] for the joint when the next arrives:
//!
//! ```text
//!   start-up  (G41/G42 line S → P1, first element E1):  tool S → start(offset E1)        type A
//!   corner    (pending Ep, next En):  offset_chain([Ep, En], d) from stanok-geom —
//!             a convex corner gets an arc of radius r about the programmed corner,
//!             a concave one the intersection of the two offsets nearest the corner
//!   cancel    (G40 line from the end of Ep to E):  tool end(offset Ep) → E               type A
//! ```
//! *Invariants:* consecutive tool pieces join within 1e-7 mm; the pending element's tool piece
//! keeps the start an earlier corner gave it ([`piece`]); a joint the geometry cannot make (the
//! offset swallows an element, no intersection) is an error, never a gouge.
//!
//! Nose radius (T-series): the programmed contour is the imaginary tip's path; the tool
//! controlled point is the nose centre plus `r·tip_vector(tip)` ([`tip_vector`]).

use stanok_geom::chain2d::offset_chain_sourced;
use stanok_geom::offset2d::{Seg2, P2};
use std::f64::consts::{PI, TAU};

/// Why compensation cannot continue.
#[derive(Debug, Clone, PartialEq)]
pub struct CompError(pub String);

/// The joint of two compensated elements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// Where the pending element's tool piece ends.
    pub prev_end: P2,
    /// The arc inserted at a convex corner (about the programmed corner).
    pub arc: Option<Seg2>,
    /// Where the next element's tool piece starts.
    pub next_start: P2,
}

/// The start of the offset of `first` (start-up, type A).
pub fn start_point(first: &Seg2, d: f64) -> Result<P2, CompError> {
    first
        .offset_left(d)
        .map(|o| o.start())
        .ok_or_else(swallowed)
}

/// The end of the offset of `last` (cancel, type A).
pub fn end_point(last: &Seg2, d: f64) -> Result<P2, CompError> {
    last.offset_left(d).map(|o| o.end()).ok_or_else(swallowed)
}

fn swallowed() -> CompError {
    CompError("a concave arc is smaller than the tool radius: the tool would gouge".into())
}

/// The joint of the pending element `prev` and the next one.
pub fn corner(prev: &Seg2, next: &Seg2, d: f64) -> Result<Corner, CompError> {
    let pieces = offset_chain_sourced(&[*prev, *next], None, d).ok_or_else(|| {
        CompError("the offset paths of the two elements do not meet: the tool would gouge".into())
    })?;
    let prev_piece = pieces.iter().find(|(_, s)| *s == Some(0));
    let next_piece = pieces.iter().find(|(_, s)| *s == Some(1));
    let (Some((p, _)), Some((n, _))) = (prev_piece, next_piece) else {
        return Err(CompError(
            "an element is shorter than the tool radius allows: the tool would gouge".into(),
        ));
    };
    let arc = pieces.iter().find(|(_, s)| s.is_none()).map(|(a, _)| *a);
    Ok(Corner {
        prev_end: p.end(),
        arc,
        next_start: n.start(),
    })
}

/// The tool piece of `programmed` (offset by `d`) from `start` to `end` (both on the offset).
pub fn piece(programmed: &Seg2, d: f64, start: P2, end: P2) -> Result<Seg2, CompError> {
    match programmed.offset_left(d).ok_or_else(swallowed)? {
        Seg2::Line { .. } => Ok(Seg2::Line { a: start, b: end }),
        Seg2::Arc {
            c,
            r,
            start: a0,
            sweep,
        } => {
            let s0 = (start[1] - c[1]).atan2(start[0] - c[0]);
            let s1 = (end[1] - c[1]).atan2(end[0] - c[0]);
            // The sweep nearest the offset's own, in its sense: the trims moved the ends a little.
            let a1 = a0 + sweep;
            let d0 = wrap(s0 - a0);
            let d1 = wrap(s1 - a1);
            let new = sweep - d0 + d1;
            if new * sweep <= 0.0 && sweep.abs() < TAU - 1e-9 {
                return Err(CompError(
                    "the compensated arc turns back on itself: the tool would gouge".into(),
                ));
            }
            Ok(Seg2::Arc {
                c,
                r,
                start: s0,
                sweep: new,
            })
        }
    }
}

fn wrap(x: f64) -> f64 {
    let mut y = x % TAU;
    if y > PI {
        y -= TAU;
    }
    if y <= -PI {
        y += TAU;
    }
    y
}

/// The imaginary tip relative to the nose centre, in (z, x) radius units, for tip number 0–9
/// (Fanuc's numbering as AxiOMA A9: 1–4 the diagonals counter-clockwise from (+Z, +X), 5–8 +X, −Z,
/// −X, +Z, 0 and 9 the centre).
pub fn tip_vector(tip: u8) -> P2 {
    match tip {
        1 => [1.0, 1.0],
        2 => [-1.0, 1.0],
        3 => [-1.0, -1.0],
        4 => [1.0, -1.0],
        5 => [0.0, 1.0],
        6 => [-1.0, 0.0],
        7 => [0.0, -1.0],
        8 => [1.0, 0.0],
        _ => [0.0, 0.0],
    }
}

/// G46: G41 (true) or G42 from the tip and the first move's direction (`dir` in (z, x)): the
/// side on which the nose centre lies seen from the contour, i.e. opposite the imaginary tip
/// across the direction of travel [D]. Tips 0 and 9 (no side) give G42.
pub fn g46_left(tip: u8, dir: P2) -> bool {
    let t = tip_vector(tip);
    // The centre is at −t from the tip; left of travel when cross(dir, −t) > 0.
    let cross = dir[0] * -t[1] - dir[1] * -t[0];
    cross > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(a: P2, b: P2) -> Seg2 {
        Seg2::Line { a, b }
    }

    fn near(p: P2, q: P2) -> bool {
        (p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9
    }

    #[test]
    fn a_square_outside_with_g41_clockwise() {
        // Clockwise square (0,0) → (0,10) → (10,10), G41 r = 2: the tool is outside (left of a
        // clockwise path): convex corners get arcs about the corner.
        let e1 = line([0.0, 0.0], [0.0, 10.0]);
        let e2 = line([0.0, 10.0], [10.0, 10.0]);
        let d = 2.0;
        assert!(near(start_point(&e1, d).unwrap(), [-2.0, 0.0]));
        let c = corner(&e1, &e2, d).unwrap();
        assert!(near(c.prev_end, [-2.0, 10.0]));
        assert!(near(c.next_start, [0.0, 12.0]));
        let arc = c.arc.expect("a convex corner");
        assert!(near(arc.start(), [-2.0, 10.0]) && near(arc.end(), [0.0, 12.0]));
        match arc {
            Seg2::Arc { c, r, sweep, .. } => {
                assert!(near(c, [0.0, 10.0]) && (r - 2.0).abs() < 1e-12);
                assert!(
                    (sweep + PI / 2.0).abs() < 1e-12,
                    "clockwise quarter: {sweep}"
                );
            }
            _ => panic!(),
        }
        assert!(near(end_point(&e2, d).unwrap(), [10.0, 12.0]));
    }

    #[test]
    fn a_concave_corner_meets_at_the_intersection() {
        // The same path with G42: the tool is inside, the offsets cross at (2, 8).
        let e1 = line([0.0, 0.0], [0.0, 10.0]);
        let e2 = line([0.0, 10.0], [10.0, 10.0]);
        let c = corner(&e1, &e2, -2.0).unwrap();
        assert!(c.arc.is_none());
        assert!(near(c.prev_end, [2.0, 8.0]) && near(c.next_start, [2.0, 8.0]));
        let p = piece(&e1, -2.0, [2.0, 0.0], c.prev_end).unwrap();
        assert_eq!(p, line([2.0, 0.0], [2.0, 8.0]));
    }

    #[test]
    fn arcs_keep_their_centre() {
        // A line into a counter-clockwise quarter arc about (10, 10), G41 r = 1 (inside the arc).
        let e1 = line([0.0, 0.0], [10.0, 0.0]);
        let e2 = Seg2::arc_through([10.0, 10.0], [10.0, 0.0], [20.0, 10.0], true, false);
        let c = corner(&e1, &e2, 1.0).unwrap();
        assert!(c.arc.is_none(), "tangent joint");
        assert!(near(c.next_start, [10.0, 1.0]));
        let p = piece(&e2, 1.0, c.next_start, [19.0, 10.0]).unwrap();
        match p {
            Seg2::Arc { c, r, sweep, .. } => {
                assert!(near(c, [10.0, 10.0]) && (r - 9.0).abs() < 1e-12);
                assert!((sweep - PI / 2.0).abs() < 1e-12);
            }
            _ => panic!(),
        }
    }

    #[test]
    fn gouges_are_refused() {
        // A concave arc of radius 1 with r = 2.
        let e = Seg2::arc_through([0.0, 1.0], [0.0, 0.0], [1.0, 1.0], true, false);
        assert!(start_point(&e, 2.0).is_err());
        // A step shorter than the tool radius into a concave corner: the offset of the first
        // element would have to run backwards to meet the second (x = -1 lies before x = 0).
        let a = line([0.0, 0.0], [1.0, 0.0]);
        let b = line([1.0, 0.0], [1.0, -1.0]);
        assert!(corner(&a, &b, -2.0).is_err());
        // Long enough, it meets: the offsets y = -2 and x = -1 … of a 5 mm step: (3, -2).
        let a = line([0.0, 0.0], [5.0, 0.0]);
        let b = line([5.0, 0.0], [5.0, -5.0]);
        let c = corner(&a, &b, -2.0).unwrap();
        assert!(near(c.prev_end, [3.0, -2.0]));
    }

    #[test]
    fn tips_and_g46() {
        assert_eq!(tip_vector(3), [-1.0, -1.0]);
        assert_eq!(tip_vector(9), [0.0, 0.0]);
        // An OD tool (tip 3) turning towards -Z: the centre is above (+X) the contour, which is
        // right of travel (-Z): G42.
        assert!(!g46_left(3, [-1.0, 0.0]));
        // Facing down (-X) with tip 3: the centre is at +Z of the face, right of travel -X? The
        // left of -X (z, x) = (0, -1) is (1, 0)·… cross((0,-1), (1,1)) = 0·1 - (-1)·1 = 1 > 0.
        assert!(g46_left(3, [0.0, -1.0]));
    }
}
