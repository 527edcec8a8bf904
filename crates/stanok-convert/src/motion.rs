//! The moves: lines, arcs and helices, splines, probe moves, rigid taps.
//!
//! Lines are written absolute with every configured X Y Z (`ConvertOptions::axes`) and with A–W only when they move. Arcs keep their
//! exact form whenever their axis is the normal of one of the three planes (in the output's frame):
//! G17/G18/G19, G2 (clockwise: axis = −normal) or G3, the centre as I/J/K offsets from the start
//! (LinuxCNC's G91.1 default, AxiOMA's G191), the helix end along the normal, and the extra turns
//! (LinuxCNC P = turns, AxiOMA P = turns − 1). An arc about any other axis (a rotated frame)
//! becomes chords. Splines: RS274/NGC G5.2/G5.3 when the Canon NURBS is one (flat in XY, clamped
//! uniform knots up to scale — LinuxCNC's only knot vector, which every G5/G5.1/G5.2 source
//! gives), otherwise chords; AxiOMA always gets chords (its BSPLINE knot rules are not shown to give
//! the same curve), each chord within `chord_tolerance_mm` of the curve.

use crate::format::num;
use crate::writer::Converter;
use stanok_canon::{ArcMove, Canon, LineMove, Plane, Pose, ProbeKind, SplineMove};
use stanok_geom::{Helix, Nurbs};

/// |cos| above which an arc axis counts as a plane normal.
const PARALLEL: f64 = 1.0 - 1e-12;

impl Converter {
    /// Writes one motion command.
    pub(crate) fn motion(&mut self, src: u32, c: &Canon) {
        let with_feed;
        let c = match self.feed_for_no_feed(src, c) {
            Some(replaced) => {
                with_feed = replaced;
                &with_feed
            }
            None => c,
        };
        match c {
            Canon::StraightTraverse(m) => {
                let g = if self.rs274() { "G0" } else { "G00" };
                let axes = self.axes(&m.end);
                self.line(src, &format!("{g}{axes}"));
            }
            Canon::StraightFeed(m) => self.feed_line(src, m),
            Canon::ArcFeed(a) => self.arc(src, a),
            Canon::SplineFeed(s) => self.spline(src, s),
            Canon::StraightProbe {
                motion,
                probe,
                contact,
            } => self.probe(src, motion, *probe, contact.as_deref().copied()),
            Canon::RigidTap {
                start, end, scale, ..
            } => self.rigid_tap(src, start, end, *scale),
            _ => {}
        }
    }

    /// A feed move without a feed (F 0: the lab controls' "no F", which runs the machine's
    /// maximum feed; Canon and the motion stage read feed 0 the same way). Neither target accepts
    /// F0 in a feed move, so the move is written at `ConvertOptions::max_feed_mm_per_min` — the
    /// same motion on the same machine — with a warning; `None` when the move has a feed.
    fn feed_for_no_feed(&mut self, src: u32, c: &Canon) -> Option<Canon> {
        let max = self.opts.max_feed_mm_per_min;
        let fix = |f: &mut f64| {
            let missing = !(f.is_finite() && *f > 0.0);
            if missing {
                *f = max;
            }
            missing
        };
        let mut c = c.clone();
        let missing = match &mut c {
            Canon::StraightFeed(m) => fix(&mut m.feed),
            Canon::ArcFeed(a) => fix(&mut a.feed),
            Canon::SplineFeed(s) => fix(&mut s.feed),
            Canon::StraightProbe { motion, .. } => fix(&mut motion.feed),
            _ => false,
        };
        if !missing {
            return None;
        }
        self.cannot(
            src,
            &format!(
                "feed move without a feed: written at the machine's maximum feed F{}",
                num(max)
            ),
        );
        Some(c)
    }

    /// ` X… Y… Z…` plus every other axis that moves, in program coordinates; remembers the end.
    fn axes(&mut self, end_machine: &Pose) -> String {
        let end = self.fold.pose(end_machine);
        let before = self.last.unwrap_or(end).to_array();
        let e = end.to_array();
        let mut s = String::new();
        for (i, letter) in stanok_canon::AXIS_LETTERS.iter().enumerate() {
            if (i < 3 && self.opts.axes[i]) || (e[i] - before[i]).abs() > 1e-9 {
                s += &format!(" {letter}{}", num(e[i]));
            }
        }
        self.last = Some(end);
        s
    }

    fn feed_line(&mut self, src: u32, m: &LineMove) {
        self.last_feed = m.feed;
        match (self.sync_pitch, self.rs274()) {
            (Some(pitch), true) => {
                let axes = self.axes(&m.end);
                self.line(src, &format!("G33{axes} K{}", num(pitch)));
            }
            (Some(pitch), false) => {
                self.cannot(
                    src,
                    &format!("spindle-synchronised move (pitch {} mm/rev) written as G01 at the path feed", num(pitch)),
                );
                let axes = self.axes(&m.end);
                self.line(src, &format!("G01{axes} F{}", num(m.feed)));
            }
            (None, rs) => {
                let g = if rs { "G1" } else { "G01" };
                let axes = self.axes(&m.end);
                self.line(src, &format!("{g}{axes} F{}", num(m.feed)));
            }
        }
    }

    fn arc(&mut self, src: u32, a: &ArcMove) {
        self.last_feed = a.feed;
        let axis = self.fold.direction(a.axis);
        let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        let mut planes = vec![a.plane, Plane::XY, Plane::ZX, Plane::YZ];
        planes.dedup();
        let found = planes.into_iter().find_map(|plane| {
            let n = plane.axes().2;
            let cos = axis[n] / len;
            (cos.abs() > PARALLEL).then_some((plane, cos > 0.0))
        });
        // AxiOMA moves an arc's centre onto the perpendicular bisector of start and end (as read,
        // i.e. as printed): a spiral (LinuxCNC accepts start and end radii that differ within its
        // tolerance), or a short chord whose printed ends tilt the bisector, would then be another
        // curve. The converter predicts that correction from the printed numbers and writes chords
        // when it would move the centre by more than 1e-6 mm. RS274/NGC keeps the spiral exactly.
        let centre_shift_mm = match found {
            Some((plane, _)) if !self.rs274() => self.axioma_centre_shift(a, plane),
            _ => 0.0,
        };
        let exact = found.filter(|_| len > 0.0 && centre_shift_mm <= 1e-6);
        let Some((plane, ccw)) = exact else {
            let why = if found.is_some() && len > 0.0 {
                format!(
                    "AxiOMA would move this arc's centre by {} mm onto the chord's bisector (a spiral, or a short chord)",
                    num(centre_shift_mm)
                )
            } else {
                "arc about an axis that is no plane normal (a rotated frame)".to_string()
            };
            self.cannot(
                src,
                &format!(
                    "{why}: written as chords within {} mm",
                    num(self.opts.chord_tolerance_mm)
                ),
            );
            let helix = Helix {
                start: a.start.xyz(),
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
                turns: a.turns,
            };
            // Helix::tessellate leaves the start out; `chords` wants it first.
            let mut pts = vec![a.start.xyz()];
            helix.tessellate(self.opts.chord_tolerance_mm, &mut pts);
            self.chords(src, &a.start, &a.end, &pts, a.feed);
            return;
        };
        let start = self.fold.point(a.start.xyz());
        let centre = self.fold.point(a.centre);
        let (i1, i2, _) = plane.axes();
        let letter = |i: usize| ['I', 'J', 'K'][i];
        let plane_code = match plane {
            Plane::XY => "G17",
            Plane::ZX => "G18",
            Plane::YZ => "G19",
        };
        let rs = self.rs274();
        let g = match (rs, ccw) {
            (true, true) => "G3",
            (true, false) => "G2",
            (false, true) => "G03",
            (false, false) => "G02",
        };
        let mut s = String::new();
        if self.plane_code != Some(plane_code) {
            s += plane_code;
            s.push(' ');
            self.plane_code = Some(plane_code);
        }
        s += g;
        s += &self.axes(&a.end);
        // Centre words in the plane's (first, second) order: I J (G17), K I (G18), J K (G19).
        for i in [i1, i2] {
            s += &format!(" {}{}", letter(i), num(centre[i] - start[i]));
        }
        let turns = a.turns.max(1);
        if rs && turns > 1 {
            s += &format!(" P{turns}");
        } else if !rs && turns > 1 {
            s += &format!(" P{}", turns - 1);
        }
        s += &format!(" F{}", num(a.feed));
        self.line(src, &s);
    }

    /// How far AxiOMA's centre correction (interp `arc::axioma_centre_format`) would move the
    /// centre of `a` as the converter prints it, mm.
    fn axioma_centre_shift(&self, a: &ArcMove, plane: Plane) -> f64 {
        let printed = |v: f64| (v * 1e6).round() / 1e6;
        let (i1, i2, _) = plane.axes();
        let start = self.fold.point(a.start.xyz());
        let end = self.fold.point(a.end.xyz());
        let centre = self.fold.point(a.centre);
        let s = [printed(start[i1]), printed(start[i2])];
        let e = [printed(end[i1]), printed(end[i2])];
        let c = [
            s[0] + printed(centre[i1] - start[i1]),
            s[1] + printed(centre[i2] - start[i2]),
        ];
        let chord = [e[0] - s[0], e[1] - s[1]];
        let d = chord[0].hypot(chord[1]);
        let corrected = if d > 1e-9 {
            let u = [chord[0] / d, chord[1] / d];
            let along = (c[0] - 0.5 * (s[0] + e[0])) * u[0] + (c[1] - 0.5 * (s[1] + e[1])) * u[1];
            [c[0] - along * u[0], c[1] - along * u[1]]
        } else {
            c
        };
        (corrected[0] - centre[i1]).hypot(corrected[1] - centre[i2])
    }

    fn spline(&mut self, src: u32, sp: &SplineMove) {
        self.last_feed = sp.feed;
        if self.rs274() {
            if let Some(points) = self.g5_2_points(sp) {
                // G5.2 needs G17 in force.
                if self.plane_code != Some("G17") {
                    self.plane_code = Some("G17");
                    self.line(src, &format!("G17 F{}", num(sp.feed)));
                } else {
                    self.line(src, &format!("F{}", num(sp.feed)));
                }
                let k = sp.degree as usize + 1;
                self.line(src, &format!("G5.2 P{} L{k}", num(sp.weights[0])));
                for (p, w) in points.iter().zip(&sp.weights).skip(1) {
                    self.line(src, &format!("X{} Y{} P{}", num(p[0]), num(p[1]), num(*w)));
                }
                self.line(src, "G5.3");
                self.last = Some(self.fold.pose(&sp.end));
                return;
            }
            self.cannot(
                src,
                &format!(
                    "spline that is not a G5.2 curve (not flat in XY, other axes moving, or knots other than LinuxCNC's clamped uniform ones): written as chords within {} mm",
                    num(self.opts.chord_tolerance_mm)
                ),
            );
        } else {
            if let Some(lines) = self.bspline_lines(sp) {
                for l in lines {
                    self.line(src, &l);
                }
                self.last = Some(self.fold.pose(&sp.end));
                return;
            }
            self.cannot(
                src,
                &format!(
                    "spline that is no AxiOMA BSPLINE (degree other than 2 or 3, weights beyond 0-3 times the first, other axes moving, or knots not clamped): written as chords within {} mm",
                    num(self.opts.chord_tolerance_mm)
                ),
            );
        }
        let mut pts = Vec::new();
        Nurbs::new(sp.degree, &sp.control_points, &sp.weights, &sp.knots)
            .tessellate(self.opts.chord_tolerance_mm, &mut pts);
        self.chords(src, &sp.start, &sp.end, &pts, sp.feed);
    }

    /// The control points in program X Y when the spline is exactly a LinuxCNC G5.2 NURBS.
    fn g5_2_points(&self, sp: &SplineMove) -> Option<Vec<[f64; 3]>> {
        let n_points = sp.control_points.len();
        let k = sp.degree as usize + 1;
        if n_points < k || sp.weights.len() != n_points || sp.knots.len() != n_points + k {
            return None;
        }
        let start = self.fold.pose(&sp.start).to_array();
        let end = self.fold.pose(&sp.end).to_array();
        if (3..9).any(|i| (start[i] - end[i]).abs() > 1e-9) {
            return None;
        }
        let points: Vec<[f64; 3]> = sp
            .control_points
            .iter()
            .map(|p| self.fold.point(*p))
            .collect();
        if points.iter().any(|p| (p[2] - start[2]).abs() > 1e-9) || (end[2] - start[2]).abs() > 1e-9
        {
            return None;
        }
        // LinuxCNC's knots t_i = 0 (i < k), i − k + 1 (k ≤ i ≤ n), n − k + 2 (i > n), n = points − 1.
        let n = n_points - 1;
        let (k0, k1) = (sp.knots[0], sp.knots[sp.knots.len() - 1]);
        let span = (n + 2 - k) as f64;
        if k1 <= k0 {
            return None;
        }
        let uniform = sp.knots.iter().enumerate().all(|(i, &t)| {
            let want = if i < k {
                0.0
            } else if i <= n {
                (i - k + 1) as f64
            } else {
                span
            };
            ((t - k0) / (k1 - k0) * span - want).abs() < 1e-9
        });
        uniform.then_some(points)
    }

    /// The AxiOMA BSPLINE blocks of a Canon NURBS, when it is one (spec axioma-2 §2.4.4):
    /// degree SD = 2 or 3; the start point is P₀ with weight 1, so the weights are divided by the
    /// first (the same rational curve) and must stay within 0 < PW ≤ 3; clamped knots, whose
    /// interior increments become the PL= of the points that own them,
    /// `t_{i+2} = t_{i+1} + PL_i` for i = p−1 … n−1 (PL of the other points is ignored by the
    /// control and not written); only X Y Z move. A closing SPLBREAK ends this spline, so that the
    /// next one starts afresh.
    fn bspline_lines(&self, sp: &SplineMove) -> Option<Vec<String>> {
        let p = sp.degree as usize;
        let n_points = sp.control_points.len();
        if !(p == 2 || p == 3) || n_points < p + 1 || sp.weights.len() != n_points {
            return None;
        }
        if sp.knots.len() != n_points + p + 1 {
            return None;
        }
        let start = self.fold.pose(&sp.start).to_array();
        let end = self.fold.pose(&sp.end).to_array();
        if (3..9).any(|i| (start[i] - end[i]).abs() > 1e-9) {
            return None;
        }
        let k = &sp.knots;
        let last = k[k.len() - 1];
        let clamped =
            k[..=p].iter().all(|&t| t == k[0]) && k[k.len() - p - 1..].iter().all(|&t| t == last);
        if !clamped || last <= k[0] {
            return None;
        }
        let w0 = sp.weights[0];
        let weights: Vec<f64> = sp.weights.iter().map(|w| w / w0).collect();
        if weights.iter().any(|&w| !(w > 0.0 && w <= 3.0)) {
            return None;
        }
        // Knots scaled so that the increments read as the manual's (the curve ignores the scale).
        let scale = (n_points - p) as f64 / (last - k[0]);
        let n = n_points - 1;
        let mut lines = Vec::new();
        for i in 1..=n {
            let q = self.fold.point(sp.control_points[i]);
            let mut l = if i == 1 {
                format!("BSPLINE SD={p} ")
            } else {
                String::new()
            };
            l += &format!("X{} Y{} Z{}", num(q[0]), num(q[1]), num(q[2]));
            if (weights[i] - 1.0).abs() > 1e-12 {
                l += &format!(" PW={}", num(weights[i]));
            }
            if i + 1 >= p && i < n {
                l += &format!(" PL={}", num((k[i + 2] - k[i + 1]) * scale));
            }
            if i == 1 {
                l += &format!(" F{}", num(sp.feed));
            }
            lines.push(l);
        }
        lines.push("SPLBREAK".into());
        Some(lines)
    }

    /// Straight feeds through `pts` (machine X Y Z, the first = the start); the other axes move
    /// in proportion to the chord length, as Canon moves them with the arc length.
    fn chords(&mut self, src: u32, start: &Pose, end: &Pose, pts: &[[f64; 3]], feed: f64) {
        let total: f64 = pts.windows(2).map(|w| dist(w[0], w[1])).sum();
        let (s, e) = (start.to_array(), end.to_array());
        let mut done = 0.0;
        let g = if self.rs274() { "G1" } else { "G01" };
        for (j, w) in pts.windows(2).enumerate() {
            done += dist(w[0], w[1]);
            let f = if total > 0.0 { done / total } else { 1.0 };
            let mut p = [0.0; 9];
            for i in 3..9 {
                p[i] = s[i] + (e[i] - s[i]) * f;
            }
            p[..3].copy_from_slice(&w[1]);
            let pose = if j + 2 == pts.len() {
                *end
            } else {
                Pose::from_array(p)
            };
            let axes = self.axes(&pose);
            self.line(src, &format!("{g}{axes} F{}", num(feed)));
        }
    }

    fn probe(&mut self, src: u32, m: &LineMove, kind: ProbeKind, contact: Option<Pose>) {
        self.last_feed = m.feed;
        if self.rs274() {
            let g = match kind {
                ProbeKind::TowardErrorIfNone => "G38.2",
                ProbeKind::Toward => "G38.3",
                ProbeKind::AwayErrorIfNone => "G38.4",
                ProbeKind::Away => "G38.5",
            };
            let axes = self.axes(&m.end);
            self.line(src, &format!("{g}{axes} F{}", num(m.feed)));
            // The probe stops at the contact; the next move starts there.
            self.last = Some(self.fold.pose(&contact.unwrap_or(m.end)));
        } else if kind == ProbeKind::Toward || kind == ProbeKind::TowardErrorIfNone {
            if kind == ProbeKind::TowardErrorIfNone {
                self.cannot(
                    src,
                    "G38.2's error without contact has no AxiOMA form: G75 written",
                );
            }
            let axes = self.axes(&m.end);
            self.line(src, &format!("G75{axes} F{}", num(m.feed)));
            self.last = Some(self.fold.pose(&contact.unwrap_or(m.end)));
        } else {
            self.cannot(src, "probe move away from contact (G38.4/G38.5) has no AxiOMA form: written as G01 to where it stopped");
            let axes = self.axes(&contact.unwrap_or(m.end));
            self.line(src, &format!("G01{axes} F{}", num(m.feed)));
        }
    }

    fn rigid_tap(&mut self, src: u32, start: &Pose, bottom: &Pose, scale: f64) {
        match (self.rs274(), self.sync_pitch) {
            (true, Some(pitch)) => {
                let axes = self.axes(bottom);
                let mut s = format!("G33.1{axes} K{}", num(pitch));
                if (scale - 1.0).abs() > 1e-12 {
                    s += &format!(" I{}", num(scale));
                }
                self.line(src, &s);
                self.last = Some(self.fold.pose(start));
            }
            (_, pitch) => {
                // The tap's own feed is pitch × speed; without them, the last feed; without that,
                // 1 mm/min (the target needs a feed; the warning says so).
                let feed = match pitch {
                    Some(p) if p * self.spindle_rpm > 0.0 => p * self.spindle_rpm,
                    _ if self.last_feed > 0.0 => self.last_feed,
                    _ => 1.0,
                };
                self.cannot(
                    src,
                    &format!("rigid tap written as two G01 moves (down and back) at F{}: no spindle synchronisation", num(feed)),
                );
                let g = if self.rs274() { "G1" } else { "G01" };
                let f = num(feed);
                let down = self.axes(bottom);
                self.line(src, &format!("{g}{down} F{f}"));
                let up = self.axes(start);
                self.line(src, &format!("{g}{up} F{f}"));
            }
        }
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
