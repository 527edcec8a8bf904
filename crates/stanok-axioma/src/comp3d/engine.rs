//! The 3D compensation look-ahead: programmed motions in, compensated tip motions out
//! (spec axioma-4 §7.3, §7.8–§7.12).
//!
//! ```text
//!  window:  [first] [reorientation blocks …]  ← a new geometric element arrives
//!  first = Entry:   the entry line ends at the compensated start of the new element (§13.2.1)
//!  first = Contour: the corner between `first` and the new element, with t at the end of `first`:
//!     smooth  → `first` runs to its end
//!     outer   → `first` to its end, the reorientations about the vertex, then the bypass
//!               (peripheral: the arc of radius R ⟂ t about P_c − ISD·t; face: Q(λ) = P_c +
//!               v(slerp n, slerp p))
//!     inner   → the crossing (s*, σ*) of both tip curves projected on the plane ⟂ t (face: on
//!               span(n1, p1)); `first` runs [from, s*] with the off-plane jump D spread linearly
//!               over it, the new element starts at σ*
//!  Exit:    `first` to its end, the reorientations, then a straight line to the programmed point
//! ```
//!
//! Along an element the rotary (and other) axes run linearly from its start pose to its end pose
//! over the part that is executed (λ ∈ [0, 1]); the contour point, tangent, normal and ISD follow
//! the geometric parameter s. Each executed piece becomes Canon through `fit`: a line or an arc
//! when the tip path is one exactly, else a polyline within `CHORD_TOL`. Every output keeps its
//! block's span and N label and goes out at its block's slot (extension.rs).

use super::fit::emit_path;
use stanok_canon::{Canon, Diagnostic, Pose, Span, Spanned};
use stanok_geom::offset3d::{
    face_corner, face_offset, intersect_projected, limiting_offset, peripheral_corner,
    peripheral_offset, plane_basis, slerp, Corner, Curve3, Cutter,
};
use stanok_geom::{add, cross, dot, normalize, scale, sub, Vec3};
use stanok_kin::FiveAxis;
use std::collections::VecDeque;

/// The six 3D modes (CUT2DF is 2D compensation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode3 {
    /// CUT3DC.
    C,
    /// CUT3DCC.
    Cc,
    /// CUT3DCCD.
    Ccd,
    /// CUT3DF.
    F,
    /// CUT3DFS.
    Fs,
    /// CUT3DFF (= CUT3DFE).
    Ff,
}

impl Mode3 {
    /// Face modes (CUT3DF/FS/FF).
    pub fn face(self) -> bool {
        matches!(self, Mode3::F | Mode3::Fs | Mode3::Ff)
    }

    /// The keyword.
    pub fn name(self) -> &'static str {
        match self {
            Mode3::C => "CUT3DC",
            Mode3::Cc => "CUT3DCC",
            Mode3::Ccd => "CUT3DCCD",
            Mode3::F => "CUT3DF",
            Mode3::Fs => "CUT3DFS",
            Mode3::Ff => "CUT3DFF",
        }
    }
}

/// Most reorientation blocks in one corner (spec §7.10: the manual guarantees 10).
pub const MAX_REORIENT: usize = 10;

/// What a window element is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The entry block (straight, G00/G01).
    Entry,
    /// A compensated contour block.
    Contour,
    /// A block that only turns the tool (and moves non-XYZ axes): the tip keeps its contact.
    Reorient,
    /// The exit block (straight).
    Exit,
}

/// One programmed motion in the window, in machine coordinates.
#[derive(Debug, Clone)]
pub struct Elem {
    /// What it is.
    pub kind: Kind,
    /// Its tip path as programmed.
    pub curve: Curve3,
    /// Programmed start and end poses (tip + rotary and other axes).
    pub start: Pose,
    /// End pose.
    pub end: Pose,
    /// Surface normals at the start and end (§13.4).
    pub n0: Vec3,
    /// End normal.
    pub n1: Vec3,
    /// ISD at the start and end (linear along the block).
    pub isd0: f64,
    /// End ISD.
    pub isd1: f64,
    /// Executed part starts at this parameter (an inner corner shortened it).
    pub from: f64,
    /// The command it came from (span, N label): every output is a copy with a new value.
    pub tmpl: Spanned<Canon>,
    /// Its slot in the held stream.
    pub slot: u64,
    /// G00.
    pub rapid: bool,
    /// Feed, mm/min.
    pub feed: f64,
}

/// How the tool vector is obtained (fixed for one contour).
#[derive(Debug, Clone, PartialEq)]
pub enum ToolAxis {
    /// From the rotary axes (CUT3DC/CC/CCD/F under TRAORI); `vector`: ORIVECT (great circle).
    Kinematic {
        /// The machine's kinematics.
        kin: Box<FiveAxis>,
        /// ORIVECT.
        vector: bool,
    },
    /// A fixed vector (3-axis machines, CUT3DFS, CUT3DFF).
    Fixed(Vec3),
}

/// Why a compensated point does not exist.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fail {
    /// The tool axis is parallel to the path (peripheral modes).
    Undefined,
    /// The tool is below the surface: t·n < 0.
    Obtuse,
    /// Face modes: the normal is not perpendicular to the tangent (> 5°).
    NotPerpendicular,
    /// No tangent (a degenerate curve).
    NoTangent,
}

/// The compensation geometry of one contour: mode, side, cutter, tool axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// The mode.
    pub mode: Mode3,
    /// +1 G41, −1 G42.
    pub side: f64,
    /// R and r (absolute or, CUT3DCCD, the differences).
    pub cutter: Cutter,
    /// Where t comes from.
    pub axis: ToolAxis,
}

/// sin 5°: the normal/tangent perpendicularity tolerance of the face modes (spec §7.11 [P]).
const SIN_5: f64 = 0.087_155_742_747_658_17;

impl Geometry {
    /// The tool vector at pose `pose` of an element running from `a` to `b` at fraction `lambda`.
    pub fn tool(&self, a: &Pose, b: &Pose, lambda: f64) -> Vec3 {
        match &self.axis {
            ToolAxis::Fixed(t) => *t,
            ToolAxis::Kinematic { kin, vector } => {
                if *vector {
                    let (t0, t1) = (kin.tool_vector_at(a), kin.tool_vector_at(b));
                    slerp(t0, t1, lambda).unwrap_or(t1)
                } else {
                    kin.tool_vector_at(&lerp(a, b, lambda))
                }
            }
        }
    }

    /// `Q − P` for tangent `p`, tool `t`, normal `n`, depth `isd`.
    pub fn offset(&self, p: Vec3, t: Vec3, n: Vec3, isd: f64) -> Result<Vec3, Fail> {
        match self.mode {
            Mode3::C => {
                peripheral_offset(p, t, self.cutter.radius, self.side, isd).ok_or(Fail::Undefined)
            }
            Mode3::Cc | Mode3::Ccd => {
                if dot(t, n) < -1e-6 {
                    return Err(Fail::Obtuse);
                }
                if self.cutter.radius == 0.0 && self.cutter.corner == 0.0 {
                    return Ok([0.0; 3]);
                }
                limiting_offset(p, t, n, self.cutter, self.side).ok_or(
                    if stanok_geom::norm(cross(t, p)) < 1e-6 {
                        Fail::Undefined
                    } else {
                        Fail::Obtuse
                    },
                )
            }
            Mode3::F | Mode3::Fs | Mode3::Ff => {
                if dot(t, n) < -1e-6 {
                    return Err(Fail::Obtuse);
                }
                if dot(n, p).abs() > SIN_5 {
                    return Err(Fail::NotPerpendicular);
                }
                Ok(face_offset(p, t, n, self.cutter))
            }
        }
    }

    /// The compensated tip of element `e` at geometric parameter `s` with the axes at fraction
    /// `lambda` of the executed part.
    pub fn tip(&self, e: &Elem, s: f64, lambda: f64) -> Result<Vec3, Fail> {
        self.tip_with(e, s, self.tool(&e.start, &e.end, lambda))
    }

    /// The compensated tip of `e` at `s` for the tool vector `t`.
    pub fn tip_with(&self, e: &Elem, s: f64, t: Vec3) -> Result<Vec3, Fail> {
        let p = e.curve.tangent(s).ok_or(Fail::NoTangent)?;
        let n = normal_at(e, s);
        let isd = e.isd0 + (e.isd1 - e.isd0) * s;
        Ok(add(e.curve.point(s), self.offset(p, t, n, isd)?))
    }
}

/// The surface normal of `e` at `s` (uniform rotation in the plane of its ends).
pub fn normal_at(e: &Elem, s: f64) -> Vec3 {
    slerp(e.n0, e.n1, s).unwrap_or(if s < 0.5 { e.n0 } else { e.n1 })
}

/// Pose interpolated linearly (every axis).
pub fn lerp(a: &Pose, b: &Pose, l: f64) -> Pose {
    let (a, b) = (a.to_array(), b.to_array());
    Pose::from_array(std::array::from_fn(|i| a[i] + (b[i] - a[i]) * l))
}

fn with_xyz(p: Pose, q: Vec3) -> Pose {
    let mut a = p.to_array();
    a[..3].copy_from_slice(&q);
    Pose::from_array(a)
}

/// The look-ahead of one contour and what it has finished.
#[derive(Debug, Clone)]
pub struct Engine {
    /// Mode, side, cutter, tool axis.
    pub geo: Geometry,
    /// Elements not final yet: a geometric one, then reorientations.
    pub window: VecDeque<Elem>,
    /// Finished motions with their slots.
    pub ready: Vec<(u64, Spanned<Canon>)>,
    /// Where the emitted tool path ends (machine pose).
    pub tool_at: Option<Pose>,
}

/// An engine failure: a message and a diagnostic code.
pub type EResult<T> = Result<T, (&'static str, String)>;

fn fail_msg(f: Fail) -> (&'static str, String) {
    match f {
        Fail::Undefined => ("axioma::cut3d-offset-undefined", "3D compensation: the tool axis is parallel to the path, the offset direction t × p is undefined".into()),
        Fail::Obtuse => ("axioma::cut3d-normal-obtuse", "3D compensation: the tool vector makes an obtuse angle with the surface normal (the tool would be below the surface)".into()),
        Fail::NotPerpendicular => ("axioma::cut3d-normal-not-perpendicular", "3D face compensation: the surface normal deviates more than 5° from perpendicular to the path".into()),
        Fail::NoTangent => ("axioma::cut3d-no-tangent", "3D compensation: the block has no tangent".into()),
    }
}

impl Engine {
    /// A new engine for one contour.
    pub fn new(geo: Geometry) -> Self {
        Engine {
            geo,
            window: VecDeque::new(),
            ready: Vec::new(),
            tool_at: None,
        }
    }

    /// Slot of the first element not emitted yet.
    pub fn first_unresolved_slot(&self) -> Option<u64> {
        self.window.front().map(|e| e.slot)
    }

    /// Takes a new element of the contour.
    pub fn push(&mut self, e: Elem) -> EResult<()> {
        match e.kind {
            Kind::Entry => {
                self.tool_at = Some(e.start);
                self.window.push_back(e);
            }
            Kind::Reorient => {
                let n = self
                    .window
                    .iter()
                    .filter(|w| w.kind == Kind::Reorient)
                    .count();
                if n >= MAX_REORIENT {
                    return Err((
                        "axioma::cut3d-too-many-reorientations",
                        format!("3D compensation: more than {MAX_REORIENT} reorientation blocks in one corner"),
                    ));
                }
                // Spec A-21: the turning tool is checked against the side it touches now.
                if let Some(first) = self.window.front().filter(|f| f.kind == Kind::Contour) {
                    let p1 = first.curve.tangent(1.0).ok_or(fail_msg(Fail::NoTangent))?;
                    for k in 0..=8 {
                        let t = self.geo.tool(&e.start, &e.end, k as f64 / 8.0);
                        self.geo
                            .offset(p1, t, first.n1, first.isd1)
                            .map_err(fail_msg)?;
                    }
                }
                self.window.push_back(e);
            }
            Kind::Contour => {
                let from = self.join(&e)?;
                let mut e = e;
                e.from = from;
                self.window.clear();
                self.window.push_back(e);
            }
            Kind::Exit => {
                self.finish_window(Some(&e))?;
                self.window.clear();
            }
        }
        Ok(())
    }

    /// The end of the program without an exit: the last element runs to its end.
    pub fn flush(&mut self) -> EResult<()> {
        self.finish_window(None)?;
        self.window.clear();
        Ok(())
    }

    /// The window's geometric element, then its reorientations, then `exit` (if any).
    fn finish_window(&mut self, exit: Option<&Elem>) -> EResult<()> {
        let Some(first) = self.window.front().cloned() else {
            if let Some(x) = exit {
                // Nothing compensated: the exit is a plain move.
                self.emit_line(x, x.end.xyz());
            }
            return Ok(());
        };
        let reorients: Vec<Elem> = self.window.iter().skip(1).cloned().collect();
        match first.kind {
            Kind::Entry => {
                // No contour between entry and exit: both run as programmed.
                self.emit_line(&first, first.end.xyz());
                for r in &reorients {
                    self.emit_line(r, r.end.xyz());
                }
            }
            _ => {
                self.emit_elem(&first, 1.0, [0.0; 3])?;
                let p1 = first.curve.tangent(1.0).ok_or(fail_msg(Fail::NoTangent))?;
                let (pc, n1) = (first.curve.point(1.0), first.n1);
                for r in &reorients {
                    self.emit_reorient(r, pc, p1, n1, first.isd1)?;
                }
            }
        }
        if let Some(x) = exit {
            self.emit_line(x, x.end.xyz());
        }
        Ok(())
    }

    /// Joins the window to the new geometric element `e2`; returns where `e2` starts (σ* after
    /// an inner corner, else 0).
    fn join(&mut self, e2: &Elem) -> EResult<f64> {
        let Some(first) = self.window.front().cloned() else {
            return Ok(0.0);
        };
        let reorients: Vec<Elem> = self.window.iter().skip(1).cloned().collect();
        let geo = self.geo.clone();
        let q2 = geo.tip(e2, 0.0, 0.0).map_err(fail_msg)?;
        if first.kind == Kind::Entry {
            // §13.2.1: straight to the compensated start of the first contour block, no corner.
            let p2 = e2.curve.tangent(0.0).ok_or(fail_msg(Fail::NoTangent))?;
            if reorients.is_empty() {
                self.emit_line(&first, q2);
            } else {
                let t = geo.tool(&first.start, &first.end, 1.0);
                let off = geo.offset(p2, t, e2.n0, e2.isd0).map_err(fail_msg)?;
                self.emit_line(&first, add(first.curve.point(1.0), off));
                for r in &reorients {
                    self.emit_reorient(r, e2.curve.point(0.0), p2, e2.n0, e2.isd0)?;
                }
            }
            return Ok(0.0);
        }
        let p1 = first.curve.tangent(1.0).ok_or(fail_msg(Fail::NoTangent))?;
        let p2 = e2.curve.tangent(0.0).ok_or(fail_msg(Fail::NoTangent))?;
        let t_end = geo.tool(&first.start, &first.end, 1.0);
        let (n1, n2) = (first.n1, e2.n0);
        let pc = first.curve.point(1.0);
        let corner = if geo.mode.face() {
            let c = face_corner(p1, n1, p2, n2);
            if c == Corner::Undetermined {
                // Antiparallel normals at the joint: decide on chords and normals a little away
                // from it (spec §7.12, "in the neighbourhood").
                let eps = 0.01;
                let s1 = (1.0 - eps / first.curve.length().max(1e-9)).max(0.0);
                let s2 = (eps / e2.curve.length().max(1e-9)).min(1.0);
                let c1 = normalize(sub(pc, first.curve.point(s1))).unwrap_or(p1);
                let c2 = normalize(sub(e2.curve.point(s2), pc)).unwrap_or(p2);
                face_corner(c1, normal_at(&first, s1), c2, normal_at(e2, s2))
            } else {
                c
            }
        } else {
            peripheral_corner(p1, p2, t_end, geo.side)
        };
        match corner {
            Corner::Undetermined => Err((
                "axioma::cut3d-corner-undetermined",
                if geo.mode.face() {
                    "3D compensation: the corner type cannot be determined (antiparallel normals without a neighbourhood of less than 180°)".into()
                } else {
                    "3D compensation: the corner type cannot be determined: the tool vector lies in the plane of the corner".into()
                },
            )),
            Corner::Flip => Err((
                "axioma::cut3d-normal-flip",
                "3D compensation: the surface orientation flips across the corner (wrong normals)"
                    .into(),
            )),
            Corner::Smooth => {
                self.emit_elem(&first, 1.0, [0.0; 3])?;
                for r in &reorients {
                    self.emit_reorient(r, pc, p1, n1, first.isd1)?;
                }
                Ok(0.0)
            }
            Corner::Outer => {
                self.emit_elem(&first, 1.0, [0.0; 3])?;
                for r in &reorients {
                    self.emit_reorient(r, pc, p1, n1, first.isd1)?;
                }
                let last = reorients.last().unwrap_or(&first);
                let t_c = geo.tool(&last.start, &last.end, 1.0);
                self.emit_bypass(&first, pc, (p1, n1, first.isd1), (p2, n2, e2.isd0), t_c)?;
                Ok(0.0)
            }
            Corner::Inner => {
                // The first block ends at the crossing for the tool it ends with, the second
                // starts at the crossing for the tool it starts with (after the reorientations);
                // in between the tip follows the crossing for the turning tool.
                let (s_star, _, d) = self.crossing(&first, e2, t_end, p1, n1)?;
                self.emit_elem(&first, s_star, d)?;
                for r in &reorients {
                    let (a, b) = (r.start, r.end);
                    let this = &*self;
                    let mut points = Vec::with_capacity(17);
                    for k in 0..=16 {
                        let l = k as f64 / 16.0;
                        let t = this.geo.tool(&a, &b, l);
                        let (_, sg, _) = this.crossing(&first, e2, t, p1, n1)?;
                        let q = this.geo.tip_with(e2, sg, t).map_err(fail_msg)?;
                        points.push(with_xyz(lerp(&a, &b, l), q));
                    }
                    let start = self.tool_at.unwrap_or(points[0]);
                    let out = super::fit::emit_points(&r.tmpl, start, &points, r.feed);
                    self.push_out(r.slot, out);
                }
                let t_start = geo.tool(&e2.start, &e2.end, 0.0);
                let (_, sg_star, _) = self.crossing(&first, e2, t_start, p1, n1)?;
                // The new element starts at its crossing parameter.
                Ok(sg_star)
            }
        }
    }

    /// (s*, σ*, D) for the tool vector `t`: the inner-corner crossing of both tip paths
    /// (compensated with `t`) projected on the plane ⟂ t (face: the plane of n1 and p1), and the
    /// off-plane jump that the first block spreads over its length.
    fn crossing(
        &self,
        first: &Elem,
        e2: &Elem,
        t: Vec3,
        p1: Vec3,
        n1: Vec3,
    ) -> EResult<(f64, f64, Vec3)> {
        let geo = &self.geo;
        let normal = if geo.mode.face() {
            normalize(cross(p1, n1)).unwrap_or(t)
        } else {
            t
        };
        let (b1, b2) = plane_basis(normal);
        let from = first.from;
        let c1 = |s: f64| {
            geo.tip_with(first, s, t)
                .unwrap_or_else(|_| first.curve.point(s))
        };
        let c2 = |s: f64| geo.tip_with(e2, s, t).unwrap_or_else(|_| e2.curve.point(s));
        let zero = geo.cutter.radius == 0.0 && geo.cutter.corner == 0.0;
        if zero {
            return Ok((1.0, 0.0, [0.0; 3]));
        }
        let (s, sg) = intersect_projected(&c1, from, &c2, b1, b2).ok_or((
            "axioma::cut3d-inner-no-intersection",
            "3D compensation: the tip paths of the two blocks of an inner corner do not intersect (blocks too short for the tool)".to_string(),
        ))?;
        let d = sub(c2(sg), c1(s));
        let d = scale(normal, dot(d, normal));
        Ok((s, sg, d))
    }

    /// Emits `e` from its `from` to `to`, adding `spread`·λ (the inner corner's off-plane jump).
    fn emit_elem(&mut self, e: &Elem, to: f64, spread: Vec3) -> EResult<()> {
        let from = e.from;
        let geo = self.geo.clone();
        // Check the points the path is built from (ends and a few inside) before emitting.
        for k in 0..=8 {
            let s = from + (to - from) * k as f64 / 8.0;
            geo.tip(e, s, k as f64 / 8.0).map_err(fail_msg)?;
        }
        let f = |l: f64| {
            let s = from + (to - from) * l;
            let q = geo.tip(e, s, l).unwrap_or_else(|_| e.curve.point(s));
            with_xyz(lerp(&e.start, &e.end, l), add(q, scale(spread, l)))
        };
        let start = self.tool_at.unwrap_or_else(|| f(0.0));
        let out = emit_path(&e.tmpl, start, &f, e.rapid, e.feed);
        self.push_out(e.slot, out);
        Ok(())
    }

    /// A reorientation block at the vertex `pc` (tangent `p`, normal `n`): the tip follows the
    /// offset for the turning tool.
    fn emit_reorient(&mut self, r: &Elem, pc: Vec3, p: Vec3, n: Vec3, isd: f64) -> EResult<()> {
        let geo = self.geo.clone();
        for k in 0..=8 {
            let t = geo.tool(&r.start, &r.end, k as f64 / 8.0);
            geo.offset(p, t, n, isd).map_err(fail_msg)?;
        }
        let f = |l: f64| {
            let t = geo.tool(&r.start, &r.end, l);
            let off = geo.offset(p, t, n, isd).unwrap_or([0.0; 3]);
            with_xyz(lerp(&r.start, &r.end, l), add(pc, off))
        };
        let start = self.tool_at.unwrap_or_else(|| f(0.0));
        let out = emit_path(&r.tmpl, start, &f, false, r.feed);
        self.push_out(r.slot, out);
        Ok(())
    }

    /// The outer-corner bypass at `pc` with the tool `t_c` (spec §7.10, §7.12).
    fn emit_bypass(
        &mut self,
        first: &Elem,
        pc: Vec3,
        (p1, n1, isd1): (Vec3, Vec3, f64),
        (p2, n2, isd2): (Vec3, Vec3, f64),
        t_c: Vec3,
    ) -> EResult<()> {
        let geo = self.geo.clone();
        let pose = self.tool_at.unwrap_or(first.end);
        let f: Box<dyn Fn(f64) -> Pose> = if geo.mode.face() {
            geo.offset(p1, t_c, n1, 0.0).map_err(fail_msg)?;
            geo.offset(p2, t_c, n2, 0.0).map_err(fail_msg)?;
            let g = geo.clone();
            Box::new(move |l: f64| {
                let n = slerp(n1, n2, l).unwrap_or(if l < 0.5 { n1 } else { n2 });
                let p = slerp(p1, p2, l).unwrap_or(if l < 0.5 { p1 } else { p2 });
                let off = g
                    .offset(p, t_c, n, 0.0)
                    .or_else(|_| g.offset(p1, t_c, n, 0.0))
                    .unwrap_or([0.0; 3]);
                with_xyz(pose, add(pc, off))
            })
        } else {
            let u1 = sub(
                geo.offset(p1, t_c, n1, isd1).map_err(fail_msg)?,
                axial(&geo, t_c, p1, n1, isd1),
            );
            let u2 = sub(
                geo.offset(p2, t_c, n2, isd2).map_err(fail_msg)?,
                axial(&geo, t_c, p2, n2, isd2),
            );
            let phi = dot(t_c, cross(u1, u2)).atan2(dot(u1, u2));
            let g = geo.clone();
            Box::new(move |l: f64| {
                let n = slerp(n1, n2, l).unwrap_or(n2);
                let isd = isd1 + (isd2 - isd1) * l;
                let u = stanok_geom::offset3d::rotate(u1, t_c, phi * l);
                let p = normalize(cross(u, t_c))
                    .map(|v| scale(v, g.side))
                    .unwrap_or(p1);
                let ax = axial(&g, t_c, p, n, isd);
                with_xyz(pose, add(add(pc, u), ax))
            })
        };
        let start = self.tool_at.unwrap_or_else(|| f(0.0));
        let out = emit_path(&first.tmpl, start, &*f, false, first.feed.max(0.0));
        if first.rapid && first.feed <= 0.0 {
            return Err((
                "axioma::cut3d-rapid-corner",
                "a compensated rapid move turns an outer corner: program a feed F for its bypass"
                    .into(),
            ));
        }
        self.push_out(first.slot, out);
        Ok(())
    }

    /// A straight move of `e` to the tip `q` (entry, exit, plain moves).
    fn emit_line(&mut self, e: &Elem, q: Vec3) {
        let start = self.tool_at.unwrap_or(e.start);
        let end = with_xyz(e.end, q);
        let f = |l: f64| lerp(&start, &end, l);
        let out = emit_path(&e.tmpl, start, &f, e.rapid, e.feed);
        self.push_out(e.slot, out);
    }

    fn push_out(&mut self, slot: u64, out: Vec<Spanned<Canon>>) {
        for c in out {
            if let Some(m) = c.value.motion() {
                self.tool_at = Some(m.end());
            }
            self.ready.push((slot, c));
        }
    }
}

/// The part of a peripheral offset along the tool (−ISD·t for CUT3DC, δ·t for CUT3DCC/CCD).
fn axial(geo: &Geometry, t: Vec3, p: Vec3, n: Vec3, isd: f64) -> Vec3 {
    match geo.offset(p, t, n, isd) {
        Ok(off) => scale(t, dot(off, t)),
        Err(_) => [0.0; 3],
    }
}

/// Reports an engine failure as a diagnostic at `span`.
pub fn diagnostic((code, msg): (&'static str, String), span: Span) -> Diagnostic {
    Diagnostic::error(code, msg, span)
}
