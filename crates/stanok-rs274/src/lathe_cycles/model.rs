//! The elements of LinuxCNC 2.9's G7x model: straight and round segments in the plane (z, x) as
//! complex numbers z + i·x, in program units, with the operations the cycle applies to them —
//! offset, intersection with a neighbour, crossings with a level, and the three ways the cutter
//! moves along one (dive, climb, climb only). `path.rs` runs the cycle over a chain of them.
//!
//! Every formula keeps LinuxCNC's order of floating-point steps (`cplx.rs`): the cycle makes
//! exact comparisons of computed points, so a different but equivalent formula would change
//! which moves it prints on some programs. The frame: the cycle flips and turns the profile so
//! that it runs towards −Z with X falling (`path.rs`); "level" is constant X, "up" is +X.
//!
//! Tolerances are LinuxCNC's: 10⁻⁶ on levels and points, 10⁻³ for monotonicity and for arcs too
//! short to print, in program units.

use super::cplx::{Cx, I};

/// LinuxCNC's `tolerance`.
pub(super) const TOL: f64 = 1e-6;

/// What a segment is. A fillet is a round segment and a chamfer a straight one whose ends are
/// found from their neighbours (`finish_corner`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Kind {
    Straight,
    Round,
    Fillet,
    Chamfer,
}

#[derive(Debug, Clone, Copy)]
pub(super) struct Seg {
    pub kind: Kind,
    pub s: Cx,
    pub e: Cx,
    /// Round: the centre.
    pub c: Cx,
    /// Round: counter-clockwise (G3) in the model's frame.
    pub ccw: bool,
    /// Fillet radius or chamfer size still to apply (0 once applied, for fillets).
    pub finish: f64,
}

/// A move the cycle prints, model frame (`path.rs` maps it back).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Out {
    Rapid(Cx),
    Line(Cx),
    Arc { ccw: bool, c: Cx, e: Cx },
}

/// An error LinuxCNC throws from its model: its text follows "G7X error: ".
pub(super) type Thrown = String;

impl Seg {
    pub fn straight(s: Cx, e: Cx) -> Seg {
        Seg {
            kind: Kind::Straight,
            s,
            e,
            c: Cx::new(0.0, 0.0),
            ccw: false,
            finish: 0.0,
        }
    }

    pub fn round(ccw: bool, s: Cx, c: Cx, e: Cx) -> Seg {
        Seg {
            kind: Kind::Round,
            s,
            e,
            c,
            ccw,
            finish: 0.0,
        }
    }

    /// A corner to round (`fillet`) or cut (`!fillet`) at point `at`, of size `d`.
    pub fn corner(fillet: bool, d: f64, at: Cx) -> Seg {
        Seg {
            kind: if fillet { Kind::Fillet } else { Kind::Chamfer },
            s: at,
            e: at,
            c: at,
            ccw: false,
            finish: d,
        }
    }

    pub fn is_round(&self) -> bool {
        matches!(self.kind, Kind::Round | Kind::Fillet)
    }

    /// Its length for a straight one; for a round one the smaller of chord and radius.
    pub fn radius(&self) -> f64 {
        if self.is_round() {
            (self.s - self.e).abs().min((self.s - self.c).abs())
        } else {
            (self.s - self.e).abs()
        }
    }

    /// Whether it never runs towards +Z (and a round one stays on its side of the centre).
    pub fn monotonic(&self) -> bool {
        if !self.is_round() {
            return (self.e - self.s).re <= 1e-3;
        }
        if self.finish != 0.0 {
            return true;
        }
        let entry = (self.s - self.c).im;
        let exit = (self.e - self.c).im;
        let dz = (self.e - self.s).re;
        if self.ccw {
            entry >= -1e-3 && exit >= -1e-3 && dz <= -1e-3
        } else {
            entry <= 1e-3 && exit <= 1e-3 && dz <= -1e-3
        }
    }

    pub fn flip_imag(&mut self) {
        self.s = self.s.conj();
        self.e = self.e.conj();
        if self.is_round() {
            self.ccw = !self.ccw;
            self.c = self.c.conj();
        }
    }

    pub fn flip_real(&mut self) {
        self.s = -self.s.conj();
        self.e = -self.e.conj();
        if self.is_round() {
            self.ccw = !self.ccw;
            self.c = -self.c.conj();
        }
    }

    /// A quarter turn clockwise: z + i·x → −(z + i·x)·i.
    pub fn rotate(&mut self) {
        self.s = -self.s * I;
        self.e = -self.e * I;
        if self.is_round() {
            self.c = -self.c * I;
        }
    }

    pub fn shift(&mut self, d: Cx) {
        self.s += d;
        self.e += d;
        if self.is_round() {
            self.c += d;
        }
    }

    /// Offset by `distance`: a straight one to its left (towards i·(s − e)), a round one away
    /// from its centre when counter-clockwise.
    pub fn offset(&mut self, distance: f64) {
        if self.is_round() {
            let r = (self.s - self.c).abs();
            let sign = if self.ccw { 1.0 } else { -1.0 };
            let factor = (r + sign * distance) / r;
            self.s = (self.s - self.c).scale(factor) + self.c;
            self.e = (self.e - self.c).scale(factor) + self.c;
        } else {
            let v = self.s - self.e;
            let d = (I.scale(distance) * v).div_real(v.abs());
            self.s += d;
            self.e += d;
        }
    }

    /// The Z of its crossings with the level X = `x` (a level straight one gives both ends).
    pub fn crossings(&self, x: f64) -> Vec<f64> {
        let mut is = Vec::new();
        if self.is_round() {
            let r = self.s - self.c;
            let rr = r.abs();
            let mut s = -(x - rr - self.c.im) * (x + rr - self.c.im);
            if s < -TOL {
                return is;
            }
            if s < 0.0 {
                s = 0.0;
            }
            s = s.sqrt();
            let p1 = Cx::new(self.c.re + s, x);
            if self.on_arc(p1) {
                is.push(p1.re);
            }
            let p2 = Cx::new(self.c.re - s, x);
            if self.on_arc(p2) {
                is.push(p2.re);
            }
            return is;
        }
        let (s, e) = (self.s, self.e);
        if s.im.min(e.im) > x + TOL || s.im.max(e.im) < x - TOL {
            return is;
        }
        if (s - e).im.abs() < TOL {
            is.push(s.re);
            is.push(e.re);
        } else {
            is.push((x - s.im) / (e.im - s.im) * (e.re - s.re) + s.re);
        }
        is
    }

    /// Whether point `p` (on the circle) lies within the arc's sweep.
    fn on_arc(&self, p: Cx) -> bool {
        let from_start = (self.s - self.c).conj() * (p - self.c);
        let from_end = (self.e - self.c).conj() * (p - self.c);
        if self.ccw {
            from_start.im >= -TOL && from_end.im <= TOL
        } else {
            from_start.im <= TOL && from_end.im >= -TOL
        }
    }

    /// Its own move to its end.
    pub fn draw(&self, out: &mut Vec<Out>) {
        out.push(if self.is_round() {
            Out::Arc {
                ccw: self.ccw,
                c: self.c,
                e: self.e,
            }
        } else {
            Out::Line(self.e)
        });
    }

    /// The top of a counter-clockwise arc that ends past it, else its end.
    fn climb_end(&self) -> Cx {
        if self.e.re < self.c.re {
            Cx::new(self.c.re, self.c.im + (self.s - self.c).abs())
        } else {
            self.e
        }
    }

    /// Moves up along the segment from `at` (its start). Ok(true): it does not climb (a
    /// pocket starts here, or a counter-clockwise arc went over its top).
    pub fn climb(&self, at: &mut Cx, out: &mut Vec<Out>) -> Result<bool, Thrown> {
        if !self.is_round() {
            if self.e.im + TOL < self.s.im {
                return Ok(true);
            }
            if (*at - self.s).abs() > TOL {
                return Err("How did we get here?".into());
            }
            out.push(Out::Line(self.e));
            *at = self.e;
            return Ok(false);
        }
        if !self.ccw {
            if at.re > self.c.re {
                return Ok(true);
            }
            if (*at - self.e).abs() > 1e-3 {
                out.push(Out::Arc {
                    ccw: false,
                    c: self.c,
                    e: self.e,
                });
            }
            *at = self.e;
            return Ok(false);
        }
        if at.re < self.c.re {
            return Ok(true);
        }
        let ep = self.climb_end();
        if (*at - ep).abs() > 1e-3 {
            out.push(Out::Arc {
                ccw: true,
                c: self.c,
                e: ep,
            });
        }
        *at = ep;
        Ok(true)
    }

    /// G7x.1: feeds along the level from `at` to where the segment rises through it, then up
    /// the segment; nothing where it does not.
    pub fn climb_only(&self, at: &mut Cx, out: &mut Vec<Out>) {
        if !self.is_round() {
            if self.e.im < self.s.im {
                return;
            }
            let is = self.crossings(at.im);
            let Some(&first) = is.first() else {
                return;
            };
            at.re = first;
            out.push(Out::Line(*at));
            out.push(Out::Line(self.e));
            *at = self.e;
            return;
        }
        let is = self.crossings(at.im);
        let (Some(&first), Some(&last)) = (is.first(), is.last()) else {
            return;
        };
        let ep = if !self.ccw {
            if last > self.c.re {
                return;
            }
            at.re = last;
            self.e
        } else {
            if first < self.c.re {
                return;
            }
            at.re = first;
            self.climb_end()
        };
        out.push(Out::Line(*at));
        if (*at - ep).abs() > 1e-3 {
            out.push(Out::Arc {
                ccw: self.ccw,
                c: self.c,
                e: ep,
            });
        }
        *at = ep;
    }

    /// Moves down along the segment from `at` to level `x` (or its end above it). Ok(true): it
    /// does not go down. `fast`: the first segment, the entry, is a rapid.
    pub fn dive(
        &self,
        at: &mut Cx,
        x: f64,
        out: &mut Vec<Out>,
        fast: bool,
    ) -> Result<bool, Thrown> {
        if !self.is_round() {
            if self.s.im <= self.e.im + TOL {
                return Ok(true);
            }
            let to = if x < self.e.im {
                self.e
            } else {
                let is = self.crossings(x);
                let Some(&first) = is.first() else {
                    return Err("x too large in straight dive".into());
                };
                Cx::new(first, x)
            };
            out.push(if fast { Out::Rapid(to) } else { Out::Line(to) });
            *at = to;
            return Ok(false);
        }
        if (*at - self.e).abs() < TOL || (*at - self.e).re <= TOL {
            *at = self.e;
            return Ok(false);
        }
        let mut is = self.crossings(x);
        if is.is_empty() {
            is = self.crossings(x - TOL);
        }
        let arc = |e: Cx| Out::Arc {
            ccw: self.ccw,
            c: self.c,
            e,
        };
        if self.ccw {
            if at.re - TOL > self.c.re {
                return Ok(true);
            }
            let to = match is.last() {
                Some(&last) if last <= self.c.re => Cx::new(last, x),
                _ => self.e,
            };
            out.push(arc(to));
            *at = to;
            return Ok(false);
        }
        if at.re <= self.c.re {
            return Ok(true);
        }
        let to = match is.first() {
            None => self.e,
            // Hit on the far side only: the pocket steps the level down.
            Some(&first) if first < self.c.re => return Ok(false),
            Some(&first) => Cx::new(first, x),
        };
        out.push(arc(to));
        *at = to;
        Ok(false)
    }
}

/// Joins `prev`'s end and `next`'s start at their crossing (LinuxCNC's `intersect`: the
/// intersection formula depends on both kinds). Err: two parallel straight ones.
pub(super) fn intersect(prev: &mut Seg, next: &mut Seg) -> Result<(), Thrown> {
    match (prev.is_round(), next.is_round()) {
        (false, false) => {
            let rot = (next.s - next.e).conj().div_real((next.s - next.e).abs());
            let ps = (prev.s - next.e) * rot;
            let pe = (prev.e - next.e) * rot;
            if (ps - pe).im == 0.0 {
                return Err("Cannot intersect parallel lines".into());
            }
            let f = ps.im / (ps - pe).im;
            let is = (ps + (pe - ps).scale(f)) / rot + next.e;
            next.s = is;
            prev.e = is;
        }
        (true, false) | (false, true) => {
            // A straight one and an arc, either way round; already joined within TOL.
            if (next.s - prev.e).abs() < TOL {
                return Ok(());
            }
            let (line, arc) = if prev.is_round() {
                (&*next, &*prev)
            } else {
                (&*prev, &*next)
            };
            let is = line_circle(line, arc, next.s);
            next.s = is;
            prev.e = is;
        }
        (true, true) => {
            let a = (next.s - next.c).abs();
            let b = (prev.s - prev.c).abs();
            let c = (next.c - prev.c).abs();
            let cos_b = (c * c + a * a - b * b) / 2.0 / a / c;
            let cos_b2 = (cos_b * cos_b).min(1.0);
            let rot = Cx::new(cos_b, (1.0 - cos_b2).sqrt());
            let is = (rot * (prev.c - next.c)).div_real(c).scale(a) + next.c;
            prev.e = is;
            next.s = is;
        }
    }
    Ok(())
}

/// The crossing of the straight segment `line` with the circle of `arc` through its end, the one
/// nearer `near`: the line turned onto the real axis about its end (LinuxCNC's `intersect_end` of
/// a straight and a round segment, whichever comes first).
fn line_circle(line: &Seg, arc: &Seg, near: Cx) -> Cx {
    let rot = (line.s - line.e).conj().div_real((line.s - line.e).abs());
    let pe = (arc.e - line.e) * rot;
    let pc = (arc.c - line.e) * rot;
    let mut b = (pc - pe).norm() - pc.im * pc.im;
    b = if b < 0.0 { 0.0 } else { b.sqrt() };
    let s1 = Cx::real_over(pc.re + b, rot) + line.e;
    let s2 = Cx::real_over(pc.re - b, rot) + line.e;
    if (near - s1).abs() < (near - s2).abs() {
        s1
    } else {
        s2
    }
}
