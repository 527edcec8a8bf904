//! LinuxCNC 2.9's G7x cycle over a chain of model segments (`model.rs`), in program units:
//! the frame it works in, corner finishing, the offset by the allowance, and the passes of
//! G70 (finishing), G71/G72 (roughing with pockets), G7x.1 (no pockets) and G7x.2 (pockets only).
//!
//! # The chain and its frame
//!
//! Element 0 is the entry, from the cycle start S to the profile's start P0; the others are the
//! profile. The cycle turns the chain (G72: a quarter turn, so that it faces like G71) and flips
//! it (in X, in Z) so that the profile runs towards −Z with X falling from its start to its end;
//! `flips` records what was done (bit 0: Z mirrored, bit 1: X mirrored, bit 2: turned) and maps
//! every printed move back (`to_program`).
//!
//! # Offset (`add_distance`)
//!
//! The profile (not the entry) is offset by D on the side away from the material, in steps no
//! larger than half the shortest element, so that no element turns over in one step. After each
//! step: an element shorter than 10⁻³ is dropped; a gap between neighbours that opened on a
//! convex corner (more than 10⁻² along Z) gets an arc about the corner; an element that stopped
//! being monotonic is dropped (the shorter of it and its predecessor); neighbours are joined at
//! their crossing. At the end every joint is moved to the midpoint of the two ends, and the entry
//! is made to end at the offset profile's start.
//!
//! # Roughing (`pocket`)
//!
//! From the entry's start, level by level (X steps of I), the tool dives along the chain to the
//! current level, then feeds along +Z… in the model frame −Z… to the next crossing of the level
//! with the chain, retracts by R diagonally, rapids back and steps down. Where the chain climbs
//! (a pocket's far wall) it follows it up and starts the pocket from there. LinuxCNC's loop is
//! recursive; here it is a loop, and all the cycle's work is bounded (`MAX_WORK`): a chain on which
//! LinuxCNC's loop would never end is an error instead of a hang.

use super::cplx::Cx;
use super::model::{intersect, Kind, Out, Seg, Thrown, TOL};

/// Most work of one cycle — element visits of its offset steps, clean-up passes, levels and
/// crossing searches, all passes together; more is an error (a long profile offset in tiny steps
/// would otherwise take hours, and some of LinuxCNC's loops never end).
pub(super) const MAX_WORK: usize = 200_000_000;

/// Most moves one cycle may print (a million: LinuxCNC's own sample cycles print hundreds; a
/// level step of 10⁻⁷ over a tall profile would otherwise fill the memory).
pub(super) const MAX_MOVES: usize = 1_000_000;

/// Counts a cycle's work against `MAX_WORK`.
#[derive(Debug, Default)]
pub(super) struct Work(usize);

impl Work {
    fn add(&mut self, n: usize) -> Result<(), Thrown> {
        self.0 += n.max(1);
        if self.0 > MAX_WORK {
            return Err(format!(
                "the cycle needs more than {MAX_WORK} steps: stopping (endless loop?)"
            ));
        }
        Ok(())
    }
}

/// The chain of a cycle and its frame.
#[derive(Debug, Clone)]
pub(super) struct Chain {
    pub segs: Vec<Seg>,
    /// Bit 0: Z mirrored; bit 1: X mirrored; bit 2: turned a quarter (`rotate`).
    pub flips: u8,
}

impl Chain {
    pub fn new(segs: Vec<Seg>) -> Chain {
        Chain { segs, flips: 0 }
    }

    fn rotate(&mut self) {
        for s in &mut self.segs {
            s.rotate();
        }
        self.flips ^= 4;
    }

    /// Flips so that X and Z fall from the entry's end to the last element's end.
    fn swap(&mut self) {
        let (Some(first), Some(last)) = (self.segs.first(), self.segs.last()) else {
            return;
        };
        let v = first.e - last.e;
        if v.im > 0.0 {
            for s in &mut self.segs {
                s.flip_imag();
            }
            self.flips ^= 2;
        }
        if v.re < 0.0 {
            for s in &mut self.segs {
                s.flip_real();
            }
            self.flips ^= 1;
        }
    }

    /// The entry starts no further along −Z than P0; every element must be monotonic.
    fn monotonic(&mut self) -> Result<(), Thrown> {
        let Some(first) = self.segs.first_mut() else {
            return Ok(());
        };
        if (first.e - first.s).re > 0.0 {
            first.s.re = first.e.re;
        }
        if self.segs.iter().any(|s| !s.monotonic()) {
            return Err("Not monotonic".into());
        }
        Ok(())
    }

    /// Rounds and chamfers the corners marked by fillet and chamfer elements, then drops every
    /// element shorter than 10⁻³.
    fn do_finish(&mut self) -> Result<(), Thrown> {
        let n = self.segs.len();
        for h in 1..n.saturating_sub(1) {
            if !matches!(self.segs[h].kind, Kind::Fillet | Kind::Chamfer) {
                continue;
            }
            let (prev, next) = (self.segs[h - 1], self.segs[h + 1]);
            let (centre, pe, ns) = corner_finish(&mut self.segs[h], &prev, &next)?;
            self.segs[h - 1].e = pe;
            self.segs[h + 1].s = ns;
            let seg = &mut self.segs[h];
            seg.s = pe;
            seg.e = ns;
            if seg.kind == Kind::Fillet {
                seg.c = centre;
                seg.ccw = (seg.s - seg.c).im > 0.0 || (seg.e - seg.c).im > 0.0;
                seg.finish = 0.0;
            }
        }
        self.segs.retain(|s| s.radius() >= 1e-3);
        Ok(())
    }

    /// Offsets the profile (every element but the entry) by `distance` (module comment).
    fn add_distance(&mut self, distance: f64, work: &mut Work) -> Result<(), Thrown> {
        if self.segs.len() < 2 {
            return Err("the profile cannot be offset".into());
        }
        let (front, back) = (self.segs[0], self.segs[self.segs.len() - 1]);
        let angle = (front.e - front.s) / (back.s - front.s);
        let distance = if angle.im < 0.0 { -distance } else { distance };
        let mut entry = self.segs.remove(0);
        let segs = &mut self.segs;
        let mut current = 0.0;
        while current != distance {
            work.add(segs.len())?;
            if segs.is_empty() {
                return Err("the profile cannot be offset by this distance".into());
            }
            let mut step = segs.iter().fold(1e9f64, |m, s| m.min(s.radius() / 2.0));
            step = step.min((distance - current).abs());
            if distance < 0.0 {
                step = -step;
            }
            let mut k = 0;
            while k < segs.len() {
                segs[k].offset(step);
                if segs[k].radius() < 1e-3 {
                    segs.remove(k);
                } else {
                    k += 1;
                }
            }
            // Convex corners: an arc about the corner bridges the gap.
            let mut p = 0;
            while p + 1 < segs.len() {
                if (segs[p].e - segs[p + 1].s).re > 1e-2 {
                    let (mut s, mut e) = (segs[p], segs[p + 1]);
                    s.offset(-step);
                    e.offset(-step);
                    let centre = (s.e + e.s).div_real(2.0);
                    let arc = Seg::round(distance > 0.0, segs[p].e, centre, segs[p + 1].s);
                    segs.insert(p + 1, arc);
                    p += 1;
                }
                p += 1;
            }
            join_neighbours(segs, work)?;
            current += step;
        }
        for p in 0..segs.len().saturating_sub(1) {
            let mid = (segs[p].e + segs[p + 1].s).div_real(2.0);
            segs[p].e = mid;
            segs[p + 1].s = mid;
        }
        let Some(first) = segs.first() else {
            return Err("the profile cannot be offset by this distance".into());
        };
        entry.e = first.s;
        segs.insert(0, entry);
        Ok(())
    }
}

/// One offset step's clean-up pass: drop elements that stopped being monotonic (the shorter of
/// it and its predecessor) or became too short, and join each element to the next. After a drop
/// LinuxCNC starts over from the first element's successor (its loop resets to the first and
/// then steps on), which is kept here.
fn join_neighbours(segs: &mut Vec<Seg>, work: &mut Work) -> Result<(), Thrown> {
    let mut p = 0;
    while p + 1 < segs.len() {
        work.add(1)?;
        if !segs[p].monotonic() {
            if p == 0 {
                segs.remove(0);
            } else if segs[p].radius() < segs[p - 1].radius() {
                segs.remove(p);
            } else {
                segs.remove(p - 1);
            }
            p = 0;
            if p + 1 >= segs.len() {
                break;
            }
        }
        if segs[p].radius() < 1e-3 {
            segs.remove(p);
            p = 0;
        } else {
            let (a, b) = segs.split_at_mut(p + 1);
            intersect(&mut a[p], &mut b[0])?;
        }
        p += 1;
    }
    Ok(())
}

/// The corner element `seg` between `prev` and `next`: offsets both by its size (towards the
/// side where they meet), joins them, and takes the centre between the joined ends; returns
/// (centre, prev's new end, next's new start). LinuxCNC's `corner_finish`.
fn corner_finish(seg: &mut Seg, prev: &Seg, next: &Seg) -> Result<(Cx, Cx, Cx), Thrown> {
    let offset_pair = |d: f64| {
        let (mut p, mut n) = (*prev, *next);
        p.offset(d);
        n.offset(d);
        (p, n)
    };
    let (mut p, mut n) = offset_pair(seg.finish);
    if (p.e - n.s).re > 1e-2 {
        seg.finish = -seg.finish;
        (p, n) = offset_pair(seg.finish);
    }
    if (p.e - n.s).re > 1e-2 {
        return Err(format!(
            "Corner finish failed at ({},{})",
            crate::cfmt::g(prev.e.re, 6),
            crate::cfmt::g(prev.e.im, 6)
        ));
    }
    intersect(&mut p, &mut n)?;
    let centre = (p.e + n.s).div_real(2.0);
    p.offset(-seg.finish);
    n.offset(-seg.finish);
    Ok((centre, p.e, n.s))
}

/// The inputs of a cycle besides its chain, program units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Words {
    /// Cycle start.
    pub x: f64,
    pub z: f64,
    pub d: f64,
    pub e: f64,
    pub i: f64,
    pub p: f64,
    pub r: f64,
    pub u: f64,
    pub w: f64,
}

/// G70: passes from D to E (module comment of `lathe_cycles`); the moves in program frame.
pub(super) fn g70(mut chain: Chain, w: &Words) -> Result<Vec<Out>, Thrown> {
    let mut work = Work::default();
    chain.segs[0].s = Cx::new(w.z, w.x);
    let mut probe = chain.clone();
    probe.segs.remove(0);
    probe.swap();
    if probe.segs.iter().any(|s| !s.monotonic()) {
        probe.rotate();
        probe.swap();
    }
    probe.monotonic()?;
    if probe.flips & 4 != 0 {
        chain.rotate();
    }
    chain.swap();
    chain.do_finish()?;
    chain.monotonic()?;
    let mut out = Vec::new();
    let passes = if w.p >= 1.0 {
        (w.p as i64).min(MAX_WORK as i64)
    } else {
        0
    };
    for pass in (1..=passes).rev() {
        let distance = (pass - 1) as f64 * (w.d - w.e) / w.p + w.e;
        work.add(chain.segs.len())?;
        let mut path = chain.clone();
        path.add_distance(distance, &mut work)?;
        let Some((first, rest)) = path.segs.split_first() else {
            continue;
        };
        if out.len() > MAX_MOVES {
            return Err(format!(
                "the cycle makes more than {MAX_MOVES} moves: stopping (endless loop?)"
            ));
        }
        out.push(Out::Rapid(first.s));
        out.push(Out::Rapid(first.e));
        for s in rest {
            s.draw(&mut out);
        }
    }
    Ok(to_program(chain.flips, out))
}

/// G71/G72 (`facing`) of type `cycle` (0: G7x, 1: G7x.1, 2: G7x.2); the moves in program
/// frame.
pub(super) fn g71(
    mut chain: Chain,
    w: &Words,
    cycle: u8,
    facing: bool,
) -> Result<Vec<Out>, Thrown> {
    chain.segs[0].s = Cx::new(w.z, w.x);
    if facing {
        chain.rotate();
    }
    chain.swap();
    chain.do_finish()?;
    chain.monotonic()?;
    let mut work = Work::default();
    chain.add_distance(w.d, &mut work)?;
    let shift = Cx::new(w.w, w.u);
    for s in &mut chain.segs {
        s.shift(shift);
    }
    let mut pocket = Pocket {
        segs: chain.segs,
        delta: w.i.max(2.0 * TOL),
        escape: Cx::new(w.r, w.r),
        starts: Vec::new(),
        out: Vec::new(),
        work,
    };
    let start = pocket.segs[0].s;
    pocket.out.push(Out::Rapid(start));
    let last_end = pocket.segs[pocket.segs.len() - 1].e;
    if last_end.im < start.im {
        let up = Cx::new(last_end.re, start.im);
        pocket.segs.push(Seg::straight(last_end, up));
    }
    pocket.starts.push(start);
    pocket.run(cycle, start)?;
    Ok(to_program(chain.flips, pocket.out))
}

/// The roughing state (LinuxCNC's `g7x::pocket` and the members it uses).
struct Pocket {
    segs: Vec<Seg>,
    /// Depth of cut.
    delta: f64,
    /// Retract (R, R).
    escape: Cx,
    /// The levels the pockets started from (G7x.2 bookkeeping).
    starts: Vec<Cx>,
    out: Vec<Out>,
    work: Work,
}

impl Pocket {
    fn step(&mut self) -> Result<(), Thrown> {
        if self.out.len() > MAX_MOVES {
            return Err(format!(
                "the cycle makes more than {MAX_MOVES} moves: stopping (endless loop?)"
            ));
        }
        self.work.add(1)
    }

    /// Cuts from `location` along the chain from element `p` (module comment). LinuxCNC
    /// recurses into each pocket as its last action; this loops instead.
    fn run(&mut self, mut cycle: u8, location: Cx) -> Result<(), Thrown> {
        let mut location = location;
        let mut p = 0usize;
        'pocket: loop {
            let mut x = self.starts.last().map_or(location.im, |s| s.im);
            if cycle == 2 {
                // Skips the first roughing pass.
                while p < self.segs.len() {
                    self.step()?;
                    if self.segs[p].dive(&mut location, -1e9, &mut self.out, p == 0)? {
                        break;
                    }
                    p += 1;
                }
                cycle = 3;
            }
            while p < self.segs.len() {
                self.step()?;
                while x - TOL > location.im {
                    self.step()?;
                    x -= self.delta;
                }
                if self.segs[p].dive(&mut location, x, &mut self.out, p == 0)? {
                    if cycle == 1 {
                        // After the roughing, along the final contour and done.
                        for s in &self.segs[p..] {
                            s.climb_only(&mut location, &mut self.out);
                        }
                        return Ok(());
                    }
                    // Along the final contour until a pocket starts, then cut it.
                    while p < self.segs.len() {
                        if self.segs[p].climb(&mut location, &mut self.out)? {
                            if cycle == 3 {
                                if self.starts.len() > 1
                                    && location.im > self.starts[self.starts.len() - 1].im
                                {
                                    self.starts.pop();
                                }
                                if self.starts.len() == 1 {
                                    self.starts.push(location);
                                }
                            }
                            continue 'pocket;
                        }
                        p += 1;
                    }
                    return Ok(());
                }
                if (location.im - x).abs() > TOL {
                    // The level lies beyond this element: on to the next.
                    p += 1;
                    continue;
                }
                self.work.add(self.segs.len() - p)?;
                self.cut_level(&mut p, &mut x, location);
            }
            return Ok(());
        }
    }

    /// At level `x` (the tool at `location` on element `p`): feeds to the chain's next crossing
    /// of the level, retracts, rapids back and steps the level down.
    fn cut_level(&mut self, p: &mut usize, x: &mut f64, location: Cx) {
        for ip in *p..self.segs.len() {
            let is = self.segs[ip].crossings(location.im);
            let (Some(&first), Some(&last)) = (is.first(), is.last()) else {
                continue;
            };
            // The diving element can be hit again if it is an arc.
            let dest_z = if ip != *p { first } else { last };
            let distance = (dest_z - location.re).abs();
            if dest_z - TOL > location.re {
                continue; // the diving element at the starting point only
            }
            if distance < TOL {
                if *p == ip {
                    continue;
                } else if (location - self.segs[ip].s).abs() < TOL {
                    // Another element, at the entry point: move on to it.
                    *p = ip;
                    return;
                } else {
                    // A zero-length cut: done with this level.
                    *x -= self.delta;
                    return;
                }
            }
            let mut dest = location;
            dest.re = dest_z;
            self.out.push(Out::Line(dest));
            // A cut too short for the whole retract retracts less.
            let scale = (distance / 2.0 / self.escape.re).min(1.0);
            dest += self.escape.scale(scale);
            self.out.push(Out::Rapid(dest));
            let back = location - self.escape.scale(scale).conj();
            self.out.push(Out::Rapid(back));
            self.out.push(if *p == 0 {
                Out::Rapid(location)
            } else {
                Out::Line(location)
            });
            *x -= self.delta;
            return;
        }
    }
}

/// Maps the model frame's moves back to program (z, x) (LinuxCNC's `swapped_motion`).
fn to_program(flips: u8, out: Vec<Out>) -> Vec<Out> {
    let map = |p: Cx| -> Cx {
        match flips & 7 {
            0 => p,
            1 => -p.conj(),
            2 => p.conj(),
            3 => -p,
            4 => Cx::new(-p.im, p.re),
            5 => Cx::new(-p.im, -p.re),
            6 => Cx::new(p.im, p.re),
            _ => Cx::new(p.im, -p.re),
        }
    };
    let mirrors = matches!(flips & 7, 1 | 2 | 5 | 6);
    out.into_iter()
        .map(|m| match m {
            Out::Rapid(p) => Out::Rapid(map(p)),
            Out::Line(p) => Out::Line(map(p)),
            Out::Arc { ccw, c, e } => Out::Arc {
                ccw: ccw != mirrors,
                c: map(c),
                e: map(e),
            },
        })
        .collect()
}
