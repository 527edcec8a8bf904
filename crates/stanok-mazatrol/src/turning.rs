//! T-series turning cycles as geometry (`docs/dialects/mazatrol-eia.md` §11): G71/G72 stock
//! removal, G73 pattern repeating, G74/G75 grooving and peck drilling, G76 multiple threading,
//! G77/G78/G79 single cycles. Pure functions from the cycle's words and its profile to a list of
//! [`Step`]s in the turning plane; the front end turns the steps into Canon.
//!
//! Plane coordinates are `(z, x)` with **x the radius** (the front end halves diameters first),
//! as `stanok_geom::offset2d::Seg2` `(a, b)`: counter-clockwise turns from +Z towards +X, so G03 is
//! a positive sweep and G02 a negative one (G18 seen from +Y, `docs` §5.3).
//!
//! G71 (type I), the algorithm, with A the start point, P the profile from A' (A moved in X only)
//! to B, Δd the depth per pass, e the retract, (Δu/2, Δw) the allowance:
//! ```text
//!   P' = P translated by (Δw, Δu/2)                      the rough contour
//!   s  = sign(x_A' − x_A)                                 levels go from A towards the profile
//!   x_k = x_A + s·k·Δd, k = 1, 2, … while s·(x_ext − x_k) > 0     x_ext: P' farthest in s
//!   each level: rapid X to x_k; feed Z to the first crossing of x = x_k with P' (in P' order);
//!               feed 45° back by e (Z towards A, X away from P'); rapid Z to z_A
//!   then: rapid to P'(start); feed along P'; rapid to A
//! ```
//! *Invariant:* no roughing step enters P' (every feed ends on P' or on its level); the last pass
//! is P' itself, so the part is left with exactly the allowance (`tests` check the example's
//! numbers). G72 is G71 with the roles of Z and X exchanged.

use stanok_geom::chain2d::level_crossings;
use stanok_geom::offset2d::{Seg2, P2};

/// A point of the turning plane: `[z, x]`, x the radius, mm.
pub type Zx = P2;

/// One move of a cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step {
    /// Rapid traverse to the point.
    Rapid(Zx),
    /// Feed to the point at the cycle's feed.
    Feed(Zx),
    /// Feed along an arc to `to` about `centre` (`ccw` in the (z, x) frame).
    Arc {
        /// End point.
        to: Zx,
        /// Centre.
        centre: Zx,
        /// Counter-clockwise from +Z towards +X (G03).
        ccw: bool,
    },
    /// Spindle-synchronised move to the point, `lead` mm per revolution.
    Thread {
        /// End point.
        to: Zx,
        /// Lead, mm/rev.
        lead: f64,
    },
    /// Dwell, seconds.
    Dwell(f64),
}

/// Why a cycle cannot be run.
#[derive(Debug, Clone, PartialEq)]
pub struct CycleError(pub String);

type R<T> = Result<T, CycleError>;

fn err<T>(m: impl Into<String>) -> R<T> {
    Err(CycleError(m.into()))
}

/// The profile elements as segments from `start`.
fn segments(start: Zx, profile: &[Step]) -> R<Vec<Seg2>> {
    let mut at = start;
    let mut out = Vec::with_capacity(profile.len());
    for s in profile {
        let seg = match *s {
            Step::Rapid(p) | Step::Feed(p) | Step::Thread { to: p, .. } => {
                Seg2::Line { a: at, b: p }
            }
            Step::Arc { to, centre, ccw } => Seg2::arc_through(centre, at, to, ccw, false),
            Step::Dwell(_) => continue,
        };
        at = match *s {
            Step::Rapid(p) | Step::Feed(p) | Step::Thread { to: p, .. } => p,
            Step::Arc { to, .. } => to,
            Step::Dwell(_) => at,
        };
        out.push(seg);
    }
    Ok(out)
}

fn shifted(steps: &[Step], d: Zx) -> Vec<Step> {
    let m = |p: Zx| [p[0] + d[0], p[1] + d[1]];
    steps
        .iter()
        .map(|s| match *s {
            Step::Rapid(p) => Step::Rapid(m(p)),
            Step::Feed(p) => Step::Feed(m(p)),
            Step::Arc { to, centre, ccw } => Step::Arc {
                to: m(to),
                centre: m(centre),
                ccw,
            },
            Step::Thread { to, lead } => Step::Thread { to: m(to), lead },
            Step::Dwell(t) => Step::Dwell(t),
        })
        .collect()
}

fn swap(p: Zx) -> Zx {
    [p[1], p[0]]
}

/// Exchanges Z and X in every step (G72 from G71). Arcs change their sense.
fn swapped(steps: &[Step]) -> Vec<Step> {
    steps
        .iter()
        .map(|s| match *s {
            Step::Rapid(p) => Step::Rapid(swap(p)),
            Step::Feed(p) => Step::Feed(swap(p)),
            Step::Arc { to, centre, ccw } => Step::Arc {
                to: swap(to),
                centre: swap(centre),
                ccw: !ccw,
            },
            Step::Thread { to, lead } => Step::Thread { to: swap(to), lead },
            Step::Dwell(t) => Step::Dwell(t),
        })
        .collect()
}

/// Words of G71/G72.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockRemoval {
    /// Depth of cut per pass (radius), > 0.
    pub depth: f64,
    /// Retract e, ≥ 0.
    pub retract: f64,
    /// Finishing allowance in X (radius, signed: Δu/2).
    pub allowance_x: f64,
    /// Finishing allowance in Z (signed Δw).
    pub allowance_z: f64,
}

/// Most passes of one cycle (a bound on work, `mazatrol::cycle` beyond).
pub const MAX_PASSES: usize = 10_000;

/// G71 type I: `a` the start point, `profile` the moves of blocks ns…nf from A (the first one
/// moves X only).
pub fn g71(a: Zx, profile: &[Step], w: StockRemoval) -> R<Vec<Step>> {
    stock_removal(a, profile, w, "G71")
}

/// G72: G71 along the other axis (levels in Z, cuts along X).
pub fn g72(a: Zx, profile: &[Step], w: StockRemoval) -> R<Vec<Step>> {
    let swapped_w = StockRemoval {
        allowance_x: w.allowance_z,
        allowance_z: w.allowance_x,
        ..w
    };
    let out = stock_removal(swap(a), &swapped(profile), swapped_w, "G72")?;
    Ok(swapped(&out))
}

fn stock_removal(a: Zx, profile: &[Step], w: StockRemoval, name: &str) -> R<Vec<Step>> {
    // NaN fails both tests.
    if w.depth.is_nan() || w.depth <= 0.0 || w.retract.is_nan() || w.retract < 0.0 {
        return err(format!(
            "{name}: the depth of cut must be positive and the retract not negative"
        ));
    }
    let Some(first) = profile.first() else {
        return err(format!("{name}: the profile is empty"));
    };
    let a1 = match *first {
        Step::Rapid(p) | Step::Feed(p) => p,
        _ => {
            return err(format!(
                "{name}: the profile's first block must be G00 or G01"
            ))
        }
    };
    if (a1[0] - a[0]).abs() > 1e-9 {
        return err(format!(
            "{name}: the profile's first block moves Z as well (type II); only type I is simulated"
        ));
    }
    let s = (a1[1] - a[1]).signum();
    if s == 0.0 {
        return err(format!(
            "{name}: the profile starts at the start point's level"
        ));
    }
    let shift = [w.allowance_z, w.allowance_x];
    let rough_profile = shifted(profile, shift);
    let p_start = [a1[0] + shift[0], a1[1] + shift[1]];
    let segs = segments(p_start, &rough_profile[1..])?;
    // Type I: after A' the profile runs monotonically back towards the start level.
    let mut prev = p_start[1];
    for sg in &segs {
        let x = sg.end()[1];
        if s * (x - prev) > 1e-9 {
            return err(format!(
                "{name}: the profile turns back in X (a pocket, type II); only type I is simulated"
            ));
        }
        prev = x;
    }
    let extreme = if s < 0.0 {
        segs.iter()
            .map(|g| g.start()[1].min(g.end()[1]))
            .fold(p_start[1], f64::min)
    } else {
        segs.iter()
            .map(|g| g.start()[1].max(g.end()[1]))
            .fold(p_start[1], f64::max)
    };
    let dz = (segs.last().map_or(a[0], |g| g.end()[0]) - a[0]).signum();
    let mut out = Vec::new();
    let mut k = 1;
    loop {
        let level = a[1] + s * k as f64 * w.depth;
        if s * (extreme - level) <= 1e-9 {
            break;
        }
        if k > MAX_PASSES {
            return err(format!("{name}: more than {MAX_PASSES} passes"));
        }
        let crossings = level_crossings(&segs, level);
        let Some(&(z_end, _)) = crossings
            .iter()
            .min_by(|p, q| p.1.cmp(&q.1).then((dz * p.0).total_cmp(&(dz * q.0))))
        else {
            return err(format!(
                "{name}: the level X{level} does not meet the profile"
            ));
        };
        out.push(Step::Rapid([a[0], level]));
        out.push(Step::Feed([z_end, level]));
        let back = [z_end - dz * w.retract, level - s * w.retract];
        out.push(Step::Feed(back));
        out.push(Step::Rapid([a[0], back[1]]));
        k += 1;
    }
    out.push(Step::Rapid(p_start));
    out.extend_from_slice(&rough_profile[1..]);
    out.push(Step::Rapid(a));
    Ok(out)
}

/// G73 pattern repeating: `relief` = (Δk, Δi) total relief (z, x radius), `passes` = d.
pub fn g73(a: Zx, profile: &[Step], relief: Zx, passes: u32, allowance: Zx) -> R<Vec<Step>> {
    if passes == 0 || passes as usize > MAX_PASSES {
        return err(format!("G73: the number of passes must be 1…{MAX_PASSES}"));
    }
    if profile.is_empty() {
        return err("G73: the profile is empty");
    }
    let mut out = Vec::new();
    for j in 1..=passes {
        let f = if passes == 1 {
            0.0
        } else {
            f64::from(passes - j) / f64::from(passes - 1)
        };
        let d = [relief[0] * f + allowance[0], relief[1] * f + allowance[1]];
        let moved = shifted(profile, d);
        // The first profile block, shifted, is the approach: a rapid.
        if let Some(Step::Rapid(p) | Step::Feed(p)) = moved.first().copied() {
            out.push(Step::Rapid(p));
        }
        out.extend_from_slice(&moved[1..]);
        out.push(Step::Rapid(a));
    }
    Ok(out)
}

/// Words of G74 / G75 (lengths in mm, radii; `step` and `peck` already converted from µm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grooving {
    /// End point (z, x).
    pub end: Zx,
    /// Shift between grooves Δi (G74: in X; G75: in Z), > 0; 0 = one groove.
    pub step: f64,
    /// Peck depth Δk (G74: in Z; G75: in X), > 0; 0 = no pecking.
    pub peck: f64,
    /// Retract after each peck, e ≥ 0.
    pub retract: f64,
    /// Relief at the bottom Δd (signed, in the step's axis).
    pub relief: f64,
}

/// G74: pecks along Z, grooves stepped in X.
pub fn g74(a: Zx, w: Grooving) -> R<Vec<Step>> {
    grooving(a, w, 0, "G74")
}

/// G75: pecks along X, grooves stepped in Z.
pub fn g75(a: Zx, w: Grooving) -> R<Vec<Step>> {
    grooving(a, w, 1, "G75")
}

/// `axis`: the index of the peck axis (0 = z, 1 = x).
fn grooving(a: Zx, w: Grooving, axis: usize, name: &str) -> R<Vec<Step>> {
    let other = 1 - axis;
    if w.step < 0.0 || w.peck < 0.0 || w.retract < 0.0 {
        return err(format!("{name}: P, Q and R must not be negative"));
    }
    let depth_dir = (w.end[axis] - a[axis]).signum();
    let step_dir = (w.end[other] - a[other]).signum();
    let span = (w.end[other] - a[other]).abs();
    let grooves = if w.step > 0.0 {
        (span / w.step - 1e-9).ceil().max(0.0) as usize + 1
    } else {
        1
    };
    let depth = (w.end[axis] - a[axis]).abs();
    let pecks = if w.peck > 0.0 {
        (depth / w.peck - 1e-9).ceil().max(1.0) as usize
    } else {
        1
    };
    if grooves.saturating_mul(pecks) > MAX_PASSES {
        return err(format!("{name}: more than {MAX_PASSES} pecks"));
    }
    let at = |d: f64, o: f64| {
        let mut p = [0.0; 2];
        p[axis] = d;
        p[other] = o;
        p
    };
    let mut out = Vec::new();
    for gi in 0..grooves {
        let o = if gi + 1 == grooves {
            w.end[other]
        } else {
            a[other] + step_dir * w.step * gi as f64
        };
        if gi > 0 {
            out.push(Step::Rapid(at(a[axis], o)));
        }
        let mut reached = 0.0;
        for pi in 0..pecks {
            let next = if pi + 1 == pecks {
                depth
            } else {
                w.peck * (pi + 1) as f64
            };
            if pi > 0 {
                // Back by e after the previous peck, then on.
                out.push(Step::Rapid(at(
                    a[axis] + depth_dir * (reached - w.retract),
                    o,
                )));
            }
            out.push(Step::Feed(at(a[axis] + depth_dir * next, o)));
            reached = next;
        }
        if w.relief != 0.0 {
            out.push(Step::Feed(at(w.end[axis], o - step_dir * w.relief)));
            out.push(Step::Rapid(at(a[axis], o - step_dir * w.relief)));
        } else {
            out.push(Step::Rapid(at(a[axis], o)));
        }
    }
    out.push(Step::Rapid(a));
    Ok(out)
}

/// Words of G76.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Threading {
    /// The root end point (z, x radius of the thread's root at its end).
    pub end: Zx,
    /// Taper i: the radius difference start − end.
    pub taper: f64,
    /// Thread height k (radius), > 0.
    pub height: f64,
    /// First depth of cut Δd (radius), > 0.
    pub first_depth: f64,
    /// Least infeed Δdmin.
    pub min_depth: f64,
    /// Finishing allowance d.
    pub allowance: f64,
    /// Finishing passes m ≥ 1.
    pub finishing_passes: u32,
    /// Chamfer r in tenths of the lead.
    pub chamfer_tenths: u32,
    /// Tool angle a, degrees.
    pub angle: f64,
    /// Lead L, mm/rev.
    pub lead: f64,
    /// Pull-out angle (machine data), degrees.
    pub chamfer_angle: f64,
}

/// The infeed depths of G76: `Δd·√n` with increments of at least Δdmin, up to k − d, then m
/// passes at k.
pub fn g76_depths(w: &Threading) -> R<Vec<f64>> {
    let positive = |v: f64| v > 0.0;
    if !positive(w.height) || !positive(w.first_depth) || !positive(w.lead) {
        return err("G76: the thread height, the first depth and the lead must be positive");
    }
    let rough_to = (w.height - w.allowance).max(0.0);
    let mut depths = Vec::new();
    let mut last = 0.0;
    let mut n = 1.0_f64;
    while last < rough_to - 1e-12 {
        let mut d = w.first_depth * n.sqrt();
        if d - last < w.min_depth {
            d = last + w.min_depth;
        }
        let d = d.min(rough_to);
        depths.push(d);
        last = d;
        n += 1.0;
        if depths.len() > MAX_PASSES {
            return err(format!("G76: more than {MAX_PASSES} passes"));
        }
    }
    for _ in 0..w.finishing_passes.max(1) {
        depths.push(w.height);
    }
    Ok(depths)
}

/// G76 multiple threading from A.
pub fn g76(a: Zx, w: &Threading) -> R<Vec<Step>> {
    let depths = g76_depths(w)?;
    let dir = (w.end[0] - a[0]).signum();
    // The X side of the thread: outside (OD) when A is above the root.
    let side = (a[1] - w.end[1]).signum();
    let half = (w.angle / 2.0).to_radians().tan();
    let pull = f64::from(w.chamfer_tenths) / 10.0 * w.lead;
    let mut out = Vec::new();
    for &d in &depths {
        // Depth D below the crest: the root is at depth k.
        let x_end = w.end[1] + side * (w.height - d);
        let x_start = x_end + w.taper;
        let z_start = a[0] - dir * d * half;
        out.push(Step::Rapid([z_start, a[1]]));
        out.push(Step::Rapid([z_start, x_start]));
        if pull > 0.0 {
            let dzp = pull;
            let dxp = pull * w.chamfer_angle.to_radians().tan();
            let z_pull = w.end[0] - dir * dzp;
            let x_pull = x_end + w.taper * (w.end[0] - z_pull) / (w.end[0] - z_start);
            out.push(Step::Thread {
                to: [z_pull, x_pull],
                lead: w.lead,
            });
            out.push(Step::Thread {
                to: [w.end[0], x_pull + side * dxp],
                lead: w.lead,
            });
        } else {
            out.push(Step::Thread {
                to: [w.end[0], x_end],
                lead: w.lead,
            });
        }
        out.push(Step::Rapid([w.end[0], a[1]]));
    }
    out.push(Step::Rapid(a));
    Ok(out)
}

/// G77 turning (G90 of system A): `end` (z, x), taper r (radius difference start − end).
pub fn g77(a: Zx, end: Zx, taper: f64) -> Vec<Step> {
    vec![
        Step::Rapid([a[0], end[1] + taper]),
        Step::Feed(end),
        Step::Feed([end[0], a[1]]),
        Step::Rapid(a),
    ]
}

/// G78 threading (G92 of system A), pull-out as G76's.
pub fn g78(a: Zx, end: Zx, taper: f64, lead: f64, pull: f64, pull_angle: f64) -> Vec<Step> {
    let dir = (end[0] - a[0]).signum();
    let side = (a[1] - end[1]).signum();
    let mut out = vec![Step::Rapid([a[0], end[1] + taper])];
    if pull > 0.0 {
        let z_pull = end[0] - dir * pull;
        let x_pull = end[1] + taper * (end[0] - z_pull) / (end[0] - a[0]);
        out.push(Step::Thread {
            to: [z_pull, x_pull],
            lead,
        });
        out.push(Step::Thread {
            to: [end[0], x_pull + side * pull * pull_angle.to_radians().tan()],
            lead,
        });
    } else {
        out.push(Step::Thread { to: end, lead });
    }
    out.push(Step::Rapid([end[0], a[1]]));
    out.push(Step::Rapid(a));
    out
}

/// G79 facing (G94 of system A): taper r along Z (start − end).
pub fn g79(a: Zx, end: Zx, taper: f64) -> Vec<Step> {
    vec![
        Step::Rapid([end[0] + taper, a[1]]),
        Step::Feed(end),
        Step::Feed([a[0], end[1]]),
        Step::Rapid(a),
    ]
}

/// Path length of the feed moves (lines and arcs; threads included).
pub fn feed_length(start: Zx, steps: &[Step]) -> f64 {
    let mut at = start;
    let mut total = 0.0;
    for s in steps {
        match *s {
            Step::Rapid(p) => at = p,
            Step::Feed(p) | Step::Thread { to: p, .. } => {
                total += (p[0] - at[0]).hypot(p[1] - at[1]);
                at = p;
            }
            Step::Arc { to, centre, ccw } => {
                total += Seg2::arc_through(centre, at, to, ccw, false).length();
                at = to;
            }
            Step::Dwell(_) => {}
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profile N20–N26 of `examples/mazak-t-job.eia` (radii): A = (2, 31).
    fn example_profile() -> Vec<Step> {
        vec![
            Step::Rapid([2.0, 15.0]),
            Step::Feed([-20.0, 15.0]),
            Step::Feed([-25.0, 20.0]),
            Step::Feed([-40.0, 20.0]),
            Step::Arc {
                to: [-45.0, 25.0],
                centre: [-40.0, 25.0],
                ccw: false,
            },
            Step::Feed([-45.0, 29.0]),
            Step::Feed([-60.0, 29.0]),
        ]
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn g71_of_the_example_job() {
        let a = [2.0, 31.0];
        let w = StockRemoval {
            depth: 2.0,
            retract: 0.5,
            allowance_x: 0.2,
            allowance_z: 0.1,
        };
        let steps = g71(a, &example_profile(), w).unwrap();
        // Seven levels (R29 … R17), four steps each, then the rough contour and the return.
        let levels: Vec<(f64, f64)> = steps
            .chunks(4)
            .take(7)
            .map(|c| match (c[0], c[1]) {
                (Step::Rapid(p), Step::Feed(q)) => (p[1], q[0]),
                other => panic!("{other:?}"),
            })
            .collect();
        let expected = [
            (29.0, -44.9),
            (27.0, -44.9),
            (25.0, -44.895998),
            (23.0, -44.389989),
            (21.0, -42.612932),
            (19.0, -23.7),
            (17.0, -21.7),
        ];
        for (got, want) in levels.iter().zip(expected) {
            assert!(
                close(got.0, want.0) && close(got.1, want.1),
                "{got:?} {want:?}"
            );
        }
        assert_eq!(steps[28], Step::Rapid([2.1, 15.2]));
        assert_eq!(*steps.last().unwrap(), Step::Rapid(a));
        // Retract: 45° by 0.5 (back in Z, out in X, away from the material).
        assert_eq!(steps[2], Step::Feed([-44.9 + 0.5, 29.5]));
        let rough: f64 = levels.iter().map(|(_, z)| 2.0 - z).sum();
        assert!(close(rough, 281.098919), "{rough}");
        let finish = feed_length([2.1, 15.2], &steps[29..steps.len() - 1]);
        assert!(close(finish, 70.925049), "{finish}");
        let total = feed_length(a, &steps);
        // The three printed figures are rounded to 1e-6 each.
        assert!(
            (total - (281.098919 + 4.949747 + 70.925049)).abs() < 3e-6,
            "{total}"
        );
    }

    #[test]
    fn g72_is_g71_turned() {
        // Facing from A (Z2, R31): A' = Z-10 (Z only), a face at Z-10 out to R20, a cone to
        // (Z-5, R10), a boss R10 up to Z0, the face Z0 to the axis.
        let a = [2.0, 31.0];
        let profile = vec![
            Step::Rapid([-10.0, 31.0]),
            Step::Feed([-10.0, 20.0]),
            Step::Feed([-5.0, 10.0]),
            Step::Feed([0.0, 10.0]),
            Step::Feed([0.0, 0.0]),
        ];
        let w = StockRemoval {
            depth: 2.0,
            retract: 0.5,
            allowance_x: 0.0,
            allowance_z: 0.0,
        };
        let steps = g72(a, &profile, w).unwrap();
        // Levels Z0 … Z-8, each cut in -X to the profile: R10 (boss), R10, R10, R12, R16 (cone).
        let cuts: Vec<(Zx, Zx)> = steps
            .chunks(4)
            .take(5)
            .map(|c| match (c[0], c[1]) {
                (Step::Rapid(p), Step::Feed(q)) => (p, q),
                other => panic!("{other:?}"),
            })
            .collect();
        let want = [
            (0.0, 10.0),
            (-2.0, 10.0),
            (-4.0, 10.0),
            (-6.0, 12.0),
            (-8.0, 16.0),
        ];
        for ((from, to), (z, x)) in cuts.iter().zip(want) {
            assert_eq!(*from, [z, 31.0]);
            assert!(close(to[0], z) && close(to[1], x), "{to:?}");
        }
        // The 45° retract: up in Z and out in X by e.
        assert_eq!(steps[2], Step::Feed([0.5, 10.5]));
        assert_eq!(steps[3], Step::Rapid([0.5, 31.0]));
        assert_eq!(steps[20], Step::Rapid([-10.0, 31.0]));
        assert_eq!(*steps.last().unwrap(), Step::Rapid(a));
    }

    #[test]
    fn g73_shifts_from_relief_to_allowance() {
        let a = [5.0, 40.0];
        let profile = vec![Step::Rapid([0.0, 20.0]), Step::Feed([-10.0, 20.0])];
        let steps = g73(a, &profile, [2.0, 6.0], 3, [0.1, 0.2]).unwrap();
        // Pass 1: shift (2.1, 6.2); pass 2: (1.1, 3.2); pass 3: (0.1, 0.2).
        assert_eq!(steps[0], Step::Rapid([2.1, 26.2]));
        assert_eq!(steps[1], Step::Feed([-7.9, 26.2]));
        assert_eq!(steps[2], Step::Rapid(a));
        assert_eq!(steps[3], Step::Rapid([1.1, 23.2]));
        assert_eq!(steps[6], Step::Rapid([0.1, 20.2]));
    }

    #[test]
    fn g74_pecks_and_steps() {
        // Peck drilling on the axis: A (2, 0) to Z-10, pecks of 4, retract 1.
        let steps = g74(
            [2.0, 0.0],
            Grooving {
                end: [-10.0, 0.0],
                step: 0.0,
                peck: 4.0,
                retract: 1.0,
                relief: 0.0,
            },
        )
        .unwrap();
        assert_eq!(
            steps,
            vec![
                Step::Feed([-2.0, 0.0]),
                Step::Rapid([-1.0, 0.0]),
                Step::Feed([-6.0, 0.0]),
                Step::Rapid([-5.0, 0.0]),
                Step::Feed([-10.0, 0.0]),
                Step::Rapid([2.0, 0.0]),
                Step::Rapid([2.0, 0.0]),
            ]
        );
        // G75 grooves at Z-10, -13, -15 from X30 to X20 in one plunge each.
        let steps = g75(
            [-10.0, 30.0],
            Grooving {
                end: [-15.0, 20.0],
                step: 3.0,
                peck: 0.0,
                retract: 0.0,
                relief: 0.0,
            },
        )
        .unwrap();
        let plunges: Vec<Zx> = steps
            .iter()
            .filter_map(|s| match s {
                Step::Feed(p) => Some(*p),
                _ => None,
            })
            .collect();
        assert_eq!(plunges, vec![[-10.0, 20.0], [-13.0, 20.0], [-15.0, 20.0]]);
    }

    #[test]
    fn g76_depths_follow_the_square_root_law() {
        let w = Threading {
            end: [-30.0, 8.7],
            taper: 0.0,
            height: 1.3,
            first_depth: 0.4,
            min_depth: 0.1,
            allowance: 0.1,
            finishing_passes: 2,
            chamfer_tenths: 0,
            angle: 60.0,
            lead: 2.0,
            chamfer_angle: 45.0,
        };
        let d = g76_depths(&w).unwrap();
        // 0.4·√n while the increment is at least Δdmin = 0.1 (n = 1…4), then steps of 0.1 up
        // to k − d = 1.2, then m = 2 passes at k = 1.3.
        let want = [
            0.4,
            0.4 * 2f64.sqrt(),
            0.4 * 3f64.sqrt(),
            0.8,
            0.9,
            1.0,
            1.1,
            1.2,
            1.3,
            1.3,
        ];
        assert_eq!(d.len(), want.len(), "{d:?}");
        for (g, w) in d.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{d:?}");
        }
        // Single-flank infeed: the first pass starts tan 30° · 0.4 behind A in Z.
        let steps = g76([5.0, 12.0], &w).unwrap();
        assert_eq!(
            steps[0],
            Step::Rapid([5.0 + 0.4 * 30f64.to_radians().tan(), 12.0])
        );
        // First pass depth 0.4 below the crest (root 8.7 + 1.3 = 10): x 9.6.
        match steps[1] {
            Step::Rapid(p) => assert!((p[1] - 9.6).abs() < 1e-12),
            s => panic!("{s:?}"),
        }
        assert!(matches!(steps[2], Step::Thread { lead, .. } if lead == 2.0));
    }

    #[test]
    fn single_cycles() {
        let s = g77([5.0, 30.0], [-20.0, 25.0], 0.0);
        assert_eq!(feed_length([5.0, 30.0], &s), 25.0 + 5.0);
        let s = g79([5.0, 30.0], [0.0, 10.0], 0.0);
        assert_eq!(feed_length([5.0, 30.0], &s), 20.0 + 5.0);
        let s = g78([5.0, 12.0], [-20.0, 9.0], 0.0, 1.5, 0.0, 45.0);
        assert_eq!(
            s[1],
            Step::Thread {
                to: [-20.0, 9.0],
                lead: 1.5
            }
        );
    }

    #[test]
    fn refusals() {
        let w = StockRemoval {
            depth: 2.0,
            retract: 0.5,
            allowance_x: 0.0,
            allowance_z: 0.0,
        };
        // Type II: the first block moves Z too.
        let p = vec![Step::Rapid([0.0, 15.0]), Step::Feed([-10.0, 20.0])];
        assert!(g71([2.0, 31.0], &p, w).unwrap_err().0.contains("type II"));
        // A pocket: X goes down again.
        let p = vec![
            Step::Rapid([2.0, 15.0]),
            Step::Feed([-10.0, 20.0]),
            Step::Feed([-12.0, 18.0]),
        ];
        assert!(g71([2.0, 31.0], &p, w).unwrap_err().0.contains("type II"));
        assert!(g71([2.0, 31.0], &[], w).is_err());
    }
}
