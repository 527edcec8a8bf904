//! GOST-20999 cutter radius compensation G41/G42/G40 (spec lab-collection §4.9), as a filter on
//! the Canon of the blocks: the executor emits the *programmed* contour; this filter holds the last
//! in-plane move until the next one is known, then moves its end to the corner point the manual
//! prescribes and inserts the corner moves.
//!
//! Geometry in the plane's (a, b) coordinates, s = +1 (G41) or −1 (G42), R ≥ 0, rot(x, y) = (−y, x):
//!
//! ```text
//!   t1 = tangent at the end of the held move, t2 = tangent at the start of the next one
//!   v1 = R·s·rot(t1), v2 = R·s·rot(t2);  S1 = P + v1,  S3 = P + v2   (P = programmed corner)
//!   S2 = intersection of S1 + λ·t1 and S3 + μ·t2;  S4 = S1 + R·t1,  S5 = S3 − R·t2
//!   θ = signed turn t1 → t2 in (−180°, 180°];  α = 180° + s·θ  (angle on the part side)
//!
//!   |v1 − v2| ≤ 0.005 mm      smooth:   the move ends at S3
//!   α > 180° (internal)       start-up: A → S3;  contour: ends at S2;  exit: ends at S1, S1 → B
//!   α < 180° (external)       ends at S1, then S1 → S2 → S3; when α < 90° and |S1S2| > R + 1 mm
//!                             S1 → S4 → S5 → S3 instead (start-up, contour and exit alike)
//!   G41 ↔ G42 on the contour  S1 → S3
//! ```
//!
//! A *break* (blocks without motion in the plane, e.g. Z only) between two in-plane moves runs with
//! the tool where the held move ends (S2 at an internal corner, S1 otherwise); the inserted corner
//! moves follow the break. Stanok looks ahead over the break itself, so the manual's I/J/K hint in the
//! block before a break is accepted but not needed ([decide] §4.9: a missing hint is no error).
//! Corner moves take the next block's span and feed. Arcs: t1/t2 are the tangents at the junction
//! points; an arc keeps its centre and gets its start and end moved to the corner points, so at an
//! internal corner it ends at S2, off its offset circle (the manual's intended inaccuracy δ; the
//! Canon arc is then a slight spiral). Error 19: a concave arc whose offset radius would be ≤ 0
//! (rule i), a move between two internal corners no longer than R (rule iii).
//! Invariant: every released motion starts where the previous one ended.

use super::Emit;
use stanok_canon::{Canon, Diagnostic, LineMove, Plane, Pose, Span, Spanned};

/// The held move: where its programmed part starts and ends, and its tangent.
#[derive(Debug, Clone)]
struct Held {
    p_end: [f64; 2],
    t: [f64; 2],
    length: f64,
    startup: bool,
    start_internal: bool,
}

/// The compensation filter's state (cloned with the block state: a failing block changes nothing).
#[derive(Debug, Clone, Default)]
pub(crate) struct Comp {
    /// The held move first, then the commands that came after it.
    held: Vec<Spanned<Canon>>,
    move_: Option<Held>,
    side: f64,
    /// The tool radius of the last block, mm.
    radius: f64,
}

/// The block's compensation situation.
pub(crate) struct BlockComp {
    /// Side after the block: +1 G41, −1 G42, 0 off.
    pub after: i8,
    /// Tool radius, mm.
    pub radius: f64,
    pub plane: Plane,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
fn add(a: [f64; 2], b: [f64; 2], k: f64) -> [f64; 2] {
    [a[0] + k * b[0], a[1] + k * b[1]]
}
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn plane_of(p: &Pose, plane: Plane) -> [f64; 2] {
    let (a, b, _) = plane.axes();
    let v = p.to_array();
    [v[a], v[b]]
}

fn set_plane(p: &mut Pose, plane: Plane, q: [f64; 2]) {
    let (a, b, _) = plane.axes();
    let mut v = p.to_array();
    v[a] = q[0];
    v[b] = q[1];
    *p = Pose::from_array(v);
}

impl Comp {
    /// True when nothing is held and compensation is off: the block passes unchanged.
    pub fn idle(&self) -> bool {
        self.move_.is_none() && self.held.is_empty()
    }

    /// Filters one block's commands into `out`.
    pub fn block(&mut self, emit: &mut Emit, bc: &BlockComp, at: Span) -> Result<(), Diagnostic> {
        self.radius = bc.radius;
        let cmds = std::mem::take(&mut emit.cmds);
        for c in cmds {
            self.command(c, bc, at, &mut emit.cmds)?;
        }
        Ok(())
    }

    fn command(
        &mut self,
        c: Spanned<Canon>,
        bc: &BlockComp,
        at: Span,
        out: &mut Vec<Spanned<Canon>>,
    ) -> Result<(), Diagnostic> {
        let plane = bc.plane;
        if matches!(c.value, Canon::ProgramEnd) {
            self.finish(plane, out);
            out.push(c);
            return Ok(());
        }
        let Some(m) = c.value.motion() else {
            if self.move_.is_some() {
                self.held.push(c);
            } else {
                out.push(c);
            }
            return Ok(());
        };
        let (s, e) = (plane_of(&m.start(), plane), plane_of(&m.end(), plane));
        let d = sub(e, s);
        let chord = d[0].hypot(d[1]);
        let rapid = matches!(c.value, Canon::StraightTraverse(_));
        let active = self.move_.is_some() || bc.after != 0;
        // Tangents at the start and the end of the move, in the plane; None = no motion in the
        // plane (a break).
        let tangents = match &c.value {
            Canon::StraightFeed(_) | Canon::StraightTraverse(_) => {
                (chord > 1e-9).then(|| ([d[0] / chord, d[1] / chord], [d[0] / chord, d[1] / chord]))
            }
            Canon::ArcFeed(a) => {
                let (ia, ib, n) = plane.axes();
                let cc = [a.centre[ia], a.centre[ib]];
                let ccw = a.axis[n] > 0.0;
                let rho = (s[0] - cc[0]).hypot(s[1] - cc[1]);
                let tan = |q: [f64; 2]| {
                    let u = sub(q, cc);
                    let l = u[0].hypot(u[1]).max(1e-300);
                    if ccw {
                        [-u[1] / l, u[0] / l]
                    } else {
                        [u[1] / l, -u[0] / l]
                    }
                };
                if rho <= 1e-9 {
                    None
                } else {
                    if active {
                        // Error 19 (i): the offset of a concave arc must keep a radius.
                        let side = if bc.after != 0 {
                            bc.after as f64
                        } else {
                            self.side
                        };
                        let offset = if ccw {
                            rho - side * bc.radius
                        } else {
                            rho + side * bc.radius
                        };
                        if offset <= 0.0 && bc.radius > 0.0 {
                            return Err(Diagnostic::manual(
                                19,
                                "the tool radius is not smaller than the radius of a concave arc",
                                at,
                            )
                            .with_note(format!("arc radius {rho:.3} mm, R = {} mm", bc.radius)));
                        }
                        if self.move_.is_none() {
                            return Err(Diagnostic::manual(
                                35,
                                "compensation starts with an arc",
                                at,
                            )
                            .with_note("start cutter compensation with a G0 or G1 block"));
                        }
                    }
                    Some((tan(s), tan(e)))
                }
            }
            _ if active => {
                return Err(Diagnostic::error(
                    "lab::unsupported",
                    "this motion cannot run under cutter radius compensation",
                    at,
                ))
            }
            _ => None,
        };
        let Some((t_start, t_end)) = tangents else {
            // No motion in the plane: a break.
            if self.move_.is_some() {
                self.held.push(c);
            } else {
                out.push(c);
            }
            return Ok(());
        };
        let length = chord;
        let t = t_end;
        let feed = match &c.value {
            Canon::StraightFeed(l) => l.feed,
            Canon::ArcFeed(a) => a.feed,
            _ => 0.0,
        };
        let Some(h) = self.move_.take() else {
            if bc.after == 0 {
                out.push(c);
                return Ok(());
            }
            // Start-up move.
            self.side = bc.after as f64;
            self.move_ = Some(Held {
                p_end: e,
                t,
                length,
                startup: true,
                start_internal: false,
            });
            self.held = vec![c];
            return Ok(());
        };
        let exit = bc.after == 0;
        let side2 = if exit { self.side } else { bc.after as f64 };
        let r = bc.radius;
        let (end1, inserted, internal) = corner(&h, t_start, self.side, side2, r, exit);
        if internal && h.start_internal && !h.startup && h.length <= r {
            return Err(Diagnostic::manual(
                19,
                "the tool radius is too large: a block between two internal corners is not longer than R",
                at,
            )
            .with_note(format!("block length {:.3} mm, R = {r} mm", h.length)));
        }
        // Release the held move (its end at the corner point) and the break after it.
        let mut held = std::mem::take(&mut self.held);
        for (i, hc) in held.iter_mut().enumerate() {
            patch(&mut hc.value, plane, end1, i == 0);
        }
        out.extend(held);
        let mut from = last_end(out).unwrap_or_default();
        for q in inserted {
            let mut to = from;
            set_plane(&mut to, plane, q);
            if plane_of(&to, plane) != plane_of(&from, plane) {
                let lm = LineMove {
                    start: from,
                    end: to,
                    feed,
                };
                out.push(Spanned {
                    value: if rapid {
                        Canon::StraightTraverse(lm)
                    } else {
                        Canon::StraightFeed(lm)
                    },
                    ..c.clone()
                });
            }
            from = to;
        }
        let mut c = c;
        set_start(&mut c.value, from);
        if exit {
            self.side = 0.0;
            out.push(c);
            return Ok(());
        }
        self.side = side2;
        self.move_ = Some(Held {
            p_end: e,
            t,
            length,
            startup: false,
            start_internal: internal,
        });
        self.held = vec![c];
        Ok(())
    }

    /// The program ends with compensation on: the held move ends at its own S1 ([decide]).
    pub fn finish(&mut self, plane: Plane, out: &mut Vec<Spanned<Canon>>) {
        let Some(h) = self.move_.take() else {
            out.append(&mut self.held);
            return;
        };
        let s1 = add(h.p_end, [-h.t[1], h.t[0]], self.side * self.radius);
        let mut held = std::mem::take(&mut self.held);
        for (i, hc) in held.iter_mut().enumerate() {
            patch(&mut hc.value, plane, s1, i == 0);
        }
        out.extend(held);
    }
}

/// The corner between the held move and the next tangent: where the held move ends, the inserted
/// points, and whether the corner is internal.
fn corner(
    h: &Held,
    t2: [f64; 2],
    s1: f64,
    s2: f64,
    r: f64,
    exit: bool,
) -> ([f64; 2], Vec<[f64; 2]>, bool) {
    let p = h.p_end;
    let t1 = h.t;
    let v1 = [-t1[1] * r * s1, t1[0] * r * s1];
    let v2 = [-t2[1] * r * s2, t2[0] * r * s2];
    let p1 = add(p, v1, 1.0);
    let p3 = add(p, v2, 1.0);
    if s1 != s2 {
        return (p1, vec![p3], false);
    }
    if (v1[0] - v2[0]).hypot(v1[1] - v2[1]) <= 0.005 {
        return (if exit { p1 } else { p3 }, Vec::new(), false);
    }
    let theta = cross(t1, t2)
        .atan2(t1[0] * t2[0] + t1[1] * t2[1])
        .to_degrees();
    let alpha = 180.0 + s1 * theta;
    let denom = cross(t1, t2);
    let p2 = (denom.abs() > 1e-12).then(|| add(p1, t1, cross(sub(p3, p1), t2) / denom));
    if alpha > 180.0 {
        return match (h.startup, exit, p2) {
            (true, _, _) => (p3, Vec::new(), true),
            (_, true, _) => (p1, Vec::new(), true),
            (_, _, Some(q)) => (q, Vec::new(), true),
            (_, _, None) => (p3, Vec::new(), true),
        };
    }
    let short = |q: [f64; 2]| (q[0] - p1[0]).hypot(q[1] - p1[1]) <= r + 1.0;
    match p2 {
        Some(q) if alpha >= 90.0 || short(q) => (p1, vec![q, p3], false),
        _ => (p1, vec![add(p1, t1, r), add(p3, t2, -r), p3], false),
    }
}

/// Moves a held command's plane coordinates: the held move's end (`first`), or a break's start and
/// end (it runs where the held move ends).
fn patch(c: &mut Canon, plane: Plane, q: [f64; 2], first: bool) {
    if let Canon::StraightFeed(m) | Canon::StraightTraverse(m) = c {
        if !first {
            set_plane(&mut m.start, plane, q);
        }
        set_plane(&mut m.end, plane, q);
    } else if let Canon::ArcFeed(a) = c {
        if !first {
            set_plane(&mut a.start, plane, q);
        }
        set_plane(&mut a.end, plane, q);
    }
}

fn set_start(c: &mut Canon, p: Pose) {
    match c {
        Canon::StraightFeed(m) | Canon::StraightTraverse(m) => m.start = p,
        Canon::ArcFeed(a) => a.start = p,
        _ => {}
    }
}

fn last_end(out: &[Spanned<Canon>]) -> Option<Pose> {
    out.iter()
        .rev()
        .find_map(|c| c.value.motion().map(|m| m.end()))
}
