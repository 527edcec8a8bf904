//! Corner finishes of a G7x profile: `A` on a profile move rounds the corner at its end with a
//! tangent arc of that radius (a fillet), `C` cuts it with the chord between the same two tangent
//! points (a chamfer) — between lines and arcs in any combination, as LinuxCNC 2.9 does.
//!
//! # The rule (LinuxCNC's corner finish, in our own geometry)
//!
//! The fillet of radius ρ at the corner P between element e₁ (ending at P) and e₂ (starting there)
//! is the circle of radius ρ tangent to both on the inside of the turn:
//!
//! 1. θ = the signed turn from e₁'s end tangent to e₂'s start tangent; a tangent corner
//!    (|θ| < 1e-9) has nothing to round.
//! 2. Both elements are offset by ρ towards the inside of the turn (to the left when θ > 0): a line
//!    shifts, an arc's radius grows or shrinks about its centre. The offsets cross near P; the
//!    crossing nearest P is the fillet's centre C. (LinuxCNC tries one side, and takes the other if
//!    the offsets then leave a gap — the inside of the turn is the side where they cross.)
//! 3. The tangent points are C projected back onto the elements' curves: the foot of the
//!    perpendicular on a line, the point of the circle on the ray from its centre through C.
//! 4. e₁ is cut back to its tangent point T₁, e₂ starts at T₂, and between them runs the arc about C
//!    turning the way the corner turns (fillet), or the line T₁T₂ (chamfer).
//!
//! Invariants: the elements keep their curves (a line stays on its line, an arc on its circle, with
//! its centre); the new chain is connected (T₁ and T₂ are the new joints); a finish that would cut
//! an element back past its other end — or has no tangent circle at all — is an error, never a
//! profile that doubles back. For two lines this is the tangent distance t = ρ·tan(|θ|/2) on each.

use super::Corner;
use stanok_geom::offset2d::{curve_intersections, dist2, turn_angle, Seg2, LEN_EPS};

/// The error of a finish that does not fit its elements.
const TOO_LARGE: &str = "G7X error: fillet or chamfer larger than its elements";

/// Replaces the corner between elements `c.after` and `c.after + 1` by its fillet or chamfer
/// (module comment). The last element's end has no corner: nothing to do.
pub(super) fn round_corner(chain: &mut Vec<Seg2>, c: Corner) -> Result<(), String> {
    let i = c.after;
    let (Some(&e1), Some(&e2)) = (chain.get(i), chain.get(i + 1)) else {
        return Ok(());
    };
    let (u, v) = (e1.tangent(1.0), e2.tangent(0.0));
    let theta = turn_angle(u, v);
    if theta.abs() < 1e-9 || c.size <= 0.0 {
        return Ok(());
    }
    let p = e1.end();
    let inside = c.size * theta.signum();
    let (Some(o1), Some(o2)) = (e1.offset_left(inside), e2.offset_left(inside)) else {
        return Err(TOO_LARGE.into());
    };
    let Some(centre) = curve_intersections(&o1, &o2)
        .into_iter()
        .min_by(|a, b| dist2(*a, p).total_cmp(&dist2(*b, p)))
    else {
        return Err(TOO_LARGE.into());
    };
    // Parameters of the tangent points: e₁ is cut back (t₁ ≤ 1), e₂ cut forward (t₂ ≥ 0).
    let t1 = e1.param_near(centre, 1.0);
    let t2 = e2.param_near(centre, 0.0);
    let tol1 = LEN_EPS / e1.length().max(1e-300);
    let tol2 = LEN_EPS / e2.length().max(1e-300);
    if t1 < -tol1 || t2 > 1.0 + tol2 || t1 > 1.0 + tol1 || t2 < -tol2 {
        return Err(TOO_LARGE.into());
    }
    let (t1, t2) = (t1.clamp(0.0, 1.0), t2.clamp(0.0, 1.0));
    let (p1, p2) = (e1.point(t1), e2.point(t2));
    let finish = if c.chamfer {
        Seg2::Line { a: p1, b: p2 }
    } else {
        Seg2::arc_through(centre, p1, p2, theta > 0.0, false)
    };
    chain[i] = e1.piece(0.0, t1);
    chain[i + 1] = e2.piece(t2, 1.0);
    chain.insert(i + 1, finish);
    chain.retain(|s| s.length() > LEN_EPS);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-9;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        dist2(a, b) < TOL
    }

    fn corner(after: usize, chamfer: bool, size: f64) -> Corner {
        Corner {
            after,
            chamfer,
            size,
        }
    }

    #[test]
    fn two_lines_at_a_right_angle_get_a_quarter_circle() {
        // (z, x): along −z, then up +x.
        let mut chain = vec![
            Seg2::Line {
                a: [0.0, 10.0],
                b: [-10.0, 10.0],
            },
            Seg2::Line {
                a: [-10.0, 10.0],
                b: [-10.0, 20.0],
            },
        ];
        round_corner(&mut chain, corner(0, false, 2.0)).unwrap();
        assert_eq!(chain.len(), 3);
        assert!(close(chain[0].end(), [-8.0, 10.0]));
        assert!(close(chain[2].start(), [-10.0, 12.0]));
        let Seg2::Arc { c, r, sweep, .. } = chain[1] else {
            panic!("a fillet is an arc")
        };
        assert!(close(c, [-8.0, 12.0]) && (r - 2.0).abs() < TOL);
        // The path turns right (clockwise) here, so does the fillet.
        assert!((sweep + std::f64::consts::FRAC_PI_2).abs() < TOL);
    }

    #[test]
    fn a_line_into_an_arc_gets_the_circle_tangent_to_both() {
        // LinuxCNC 2.9 (`rs274`): G1 Z-10 A1 from X10 Z0, then G3 X14 Z-14 I0 K-4 gives the
        // fillet ARC_FEED(-10.0808, 10.8000, -9.1010, 11.0000, -1) and the line ends at Z-9.1010.
        let line = Seg2::Line {
            a: [0.0, 10.0],
            b: [-10.0, 10.0],
        };
        let arc = Seg2::arc_through([-14.0, 10.0], [-10.0, 10.0], [-14.0, 14.0], true, false);
        let mut chain = vec![line, arc];
        round_corner(&mut chain, corner(0, false, 1.0)).unwrap();
        let z_t = -14.0 + (24.0f64).sqrt();
        assert!(close(chain[0].end(), [z_t, 10.0]), "{:?}", chain[0].end());
        let Seg2::Arc { c, r, sweep, .. } = chain[1] else {
            panic!("a fillet is an arc")
        };
        assert!(close(c, [z_t, 11.0]) && (r - 1.0).abs() < TOL);
        assert!(sweep < 0.0);
        // The arc keeps its centre and radius and starts at the tangent point, which lies on the
        // line from its centre through the fillet's: (−14, 10) + 4/5·(z_t + 14, 1).
        let Seg2::Arc { c: c2, r: r2, .. } = chain[2] else {
            panic!("the arc stays an arc")
        };
        assert!(close(c2, [-14.0, 10.0]) && (r2 - 4.0).abs() < TOL);
        let t2 = [-14.0 + 0.8 * (z_t + 14.0), 10.8];
        assert!(close(chain[2].start(), t2), "{:?}", chain[2].start());
        assert!(close(chain[1].end(), t2));
        assert!((t2[0] - -10.0808).abs() < 1e-4);
    }

    #[test]
    fn a_chamfer_joins_the_fillets_tangent_points() {
        let line = Seg2::Line {
            a: [0.0, 10.0],
            b: [-10.0, 10.0],
        };
        let arc = Seg2::arc_through([-14.0, 10.0], [-10.0, 10.0], [-14.0, 14.0], true, false);
        let mut fillet = vec![line, arc];
        let mut chamfer = fillet.clone();
        round_corner(&mut fillet, corner(0, false, 1.0)).unwrap();
        round_corner(&mut chamfer, corner(0, true, 1.0)).unwrap();
        assert!(matches!(chamfer[1], Seg2::Line { .. }));
        assert!(close(chamfer[1].start(), fillet[1].start()));
        assert!(close(chamfer[1].end(), fillet[1].end()));
    }

    #[test]
    fn an_arc_into_a_line_and_an_arc_into_an_arc_stay_connected_and_tangent() {
        // The quarter circle ends heading −x; the line and the second arc leave along −z.
        let a1 = Seg2::arc_through([-10.0, 10.0], [-10.0, 20.0], [-20.0, 10.0], true, false);
        let line = Seg2::Line {
            a: [-20.0, 10.0],
            b: [-30.0, 10.0],
        };
        let a2 = Seg2::arc_through([-20.0, 4.0], [-20.0, 10.0], [-26.0, 4.0], true, false);
        for next in [line, a2] {
            let mut chain = vec![a1, next];
            round_corner(&mut chain, corner(0, false, 1.5)).unwrap();
            assert_eq!(chain.len(), 3);
            for k in 0..2 {
                assert!(close(chain[k].end(), chain[k + 1].start()));
                let turn = turn_angle(chain[k].tangent(1.0), chain[k + 1].tangent(0.0));
                assert!(turn.abs() < 1e-7, "joint {k} turns by {turn}");
            }
            let Seg2::Arc { r, .. } = chain[1] else {
                panic!("a fillet is an arc")
            };
            assert!((r - 1.5).abs() < TOL);
        }
    }

    #[test]
    fn a_finish_larger_than_its_elements_is_an_error() {
        let mut chain = vec![
            Seg2::Line {
                a: [0.0, 10.0],
                b: [-1.0, 10.0],
            },
            Seg2::Line {
                a: [-1.0, 10.0],
                b: [-1.0, 20.0],
            },
        ];
        assert_eq!(
            round_corner(&mut chain, corner(0, false, 2.0)),
            Err(TOO_LARGE.to_string())
        );
    }

    /// A random element leaving `p` in direction `angle`: a line of length `len`, or an arc of
    /// that length turning left or right on radius `r`.
    fn element(p: [f64; 2], angle: f64, len: f64, kind: u8, r: f64) -> Seg2 {
        let (s, c) = angle.sin_cos();
        match kind {
            0 => Seg2::Line {
                a: p,
                b: [p[0] + len * c, p[1] + len * s],
            },
            k => {
                let side = if k == 1 { 1.0 } else { -1.0 };
                let centre = [p[0] - side * r * s, p[1] + side * r * c];
                let a0 = (p[1] - centre[1]).atan2(p[0] - centre[0]);
                let sweep = side * (len / r).min(3.0);
                Seg2::Arc {
                    c: centre,
                    r,
                    start: a0,
                    sweep,
                }
            }
        }
    }

    /// Distance of `q` from the whole curve (line or circle) of `e`.
    fn off_curve(e: &Seg2, q: [f64; 2]) -> f64 {
        match *e {
            Seg2::Line { a, b } => {
                let d = [b[0] - a[0], b[1] - a[1]];
                let l = d[0].hypot(d[1]);
                ((q[0] - a[0]) * d[1] - (q[1] - a[1]) * d[0]).abs() / l
            }
            Seg2::Arc { c, r, .. } => (dist2(c, q) - r).abs(),
        }
    }

    proptest::proptest! {
        /// Any pair of lines and arcs meeting at a corner, any finish size: either an error, or a
        /// connected chain whose joints are tangent (fillet), whose fillet has the given radius,
        /// and whose trimmed elements stay on their own curves.
        #[test]
        fn every_finish_is_tangent_and_keeps_the_curves(
            a1 in -3.1f64..3.1, turn in -2.8f64..2.8,
            l1 in 0.5f64..20.0, l2 in 0.5f64..20.0,
            k1 in 0u8..3, k2 in 0u8..3, r1 in 1.0f64..30.0, r2 in 1.0f64..30.0,
            size in 0.05f64..5.0, chamfer in proptest::bool::ANY,
        ) {
            // e1 is built backwards from the corner so that it ends there heading `a1`.
            let p = [3.0, 7.0];
            let back = element(p, a1 + std::f64::consts::PI, l1, k1, r1);
            let e1 = back.piece(1.0, 0.0);
            let e2 = element(p, a1 + turn, l2, k2, r2);
            let mut chain = vec![e1, e2];
            if round_corner(&mut chain, corner(0, chamfer, size)).is_err() {
                return Ok(());
            }
            for k in 0..chain.len() - 1 {
                proptest::prop_assert!(dist2(chain[k].end(), chain[k + 1].start()) < 1e-7);
            }
            let theta = turn_angle(e1.tangent(1.0), e2.tangent(0.0));
            if chain.len() == 3 {
                proptest::prop_assert!(off_curve(&e1, chain[0].end()) < 1e-7);
                proptest::prop_assert!(off_curve(&e2, chain[2].start()) < 1e-7);
                if !chamfer {
                    let Seg2::Arc { r, sweep, .. } = chain[1] else {
                        return Err(proptest::test_runner::TestCaseError::fail("fillet not an arc"));
                    };
                    proptest::prop_assert!((r - size).abs() < 1e-7);
                    proptest::prop_assert!(sweep * theta > 0.0);
                    for k in 0..2 {
                        let t = turn_angle(chain[k].tangent(1.0), chain[k + 1].tangent(0.0));
                        proptest::prop_assert!(t.abs() < 1e-5, "joint {} turns by {}", k, t);
                    }
                }
            }
        }
    }
}
