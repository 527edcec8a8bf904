//! The round-trip machinery shared by the table test and the property test: interpret, compare
//! two motion streams (see `round_trip.rs` for what is compared and the tolerances).
#![allow(dead_code)]

use stanok_canon::{Canon, Pose, Spanned};
use stanok_convert::Target;
use stanok_geom::{distance_to_segment, Helix, Nurbs, Vec3};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// Positions: 4 × the printing rounding (6 decimals).
pub const TOL_MM: f64 = 2e-6;
/// The converter's default chord tolerance.
pub const CHORD_TOL_MM: f64 = 0.001;

pub fn path_of(row: &str) -> PathBuf {
    if let Some(rest) = row.strip_prefix("programs/") {
        return PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/programs")).join(rest);
    }
    match row.strip_prefix("examples/") {
        Some(rest) => {
            PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples")).join(rest)
        }
        None => PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/corpus"
        ))
        .join(row),
    }
}

pub fn target_dialect(t: Target) -> Dialect {
    match t {
        Target::Rs274ngc => Dialect::Rs274ngc,
        Target::Axioma => Dialect::Axioma,
    }
}

/// Interprets `text` up to its first error (corpus fragments often lack a program end or a feed:
/// the commands before the error are what a control would have run); `dir` is where subroutine
/// files are looked up.
pub fn interpret_prefix(text: &str, dialect: Dialect, dir: &Path) -> Vec<Spanned<Canon>> {
    let mut opts = InterpOptions::new(dialect);
    opts.subroutine_path = vec![dir.to_path_buf()];
    Interpreter::new(Cursor::new(text.as_bytes().to_vec()), opts)
        .map_while(Result::ok)
        .collect()
}

/// Interprets a lab-dialect program (held in memory whole, as the lab front ends need) up to its
/// first error.
pub fn interpret_lab_prefix(text: &str, dialect: Dialect, dir: &Path) -> Vec<Spanned<Canon>> {
    let mut opts = InterpOptions::new(dialect);
    opts.subroutine_path = vec![dir.to_path_buf()];
    Interpreter::from_text(text, opts)
        .map_while(Result::ok)
        .collect()
}

/// Interprets `text` (a converted program), which must run without an error.
pub fn interpret(text: &str, dialect: Dialect, dir: &Path) -> Result<Vec<Spanned<Canon>>, String> {
    let mut opts = InterpOptions::new(dialect);
    opts.subroutine_path = vec![dir.to_path_buf()];
    let interp = Interpreter::new(Cursor::new(text.as_bytes().to_vec()), opts);
    let mut out = Vec::new();
    for item in interp {
        match item {
            Ok(c) => out.push(c),
            Err(d) => return Err(format!("line {}: {} {}", d.span.line, d.code, d.message)),
        }
    }
    Ok(out)
}

/// A curve of the source as a dense polyline (for chord checks).
pub fn dense(c: &Canon) -> Option<Vec<Vec3>> {
    match c {
        Canon::ArcFeed(a) => {
            let h = Helix {
                start: a.start.xyz(),
                end: a.end.xyz(),
                centre: a.centre,
                axis: a.axis,
                turns: a.turns,
            };
            let mut pts = vec![a.start.xyz()];
            h.tessellate(1e-7, &mut pts);
            Some(pts)
        }
        Canon::SplineFeed(s) => {
            let mut pts = Vec::new();
            Nurbs::new(s.degree, &s.control_points, &s.weights, &s.knots)
                .tessellate(1e-7, &mut pts);
            Some(pts)
        }
        _ => None,
    }
}

/// Distance from `q` to the arc/helix/spiral `a`: from the point at the same swept angle (mod one
/// turn, each turn tried), a ternary search over ±0.05 rad finds the nearest point (steep helices
/// have it at another angle). Canon's model: radius and axial height linear in the swept angle,
/// counter-clockwise about `axis`.
pub fn distance_to_arc(q: Vec3, a: &stanok_canon::ArcMove) -> f64 {
    use stanok_geom::{cross, dot, norm, normalize, scale, sub};
    let axis = normalize(a.axis).unwrap_or([0.0, 0.0, 1.0]);
    let off = |p: Vec3| {
        let d = sub(p, a.centre);
        let h = dot(d, axis);
        (sub(d, scale(axis, h)), h)
    };
    let (ws, h_s) = off(a.start.xyz());
    let (we, h_e) = off(a.end.xyz());
    let (r_s, r_e) = (norm(ws), norm(we));
    let u = normalize(ws).unwrap_or([1.0, 0.0, 0.0]);
    let v = cross(axis, u);
    let tau = std::f64::consts::TAU;
    let mut planar = dot(we, v).atan2(dot(we, u)).rem_euclid(tau);
    if planar < 1e-12 {
        planar = tau;
    }
    let sweep = planar + tau * f64::from(a.turns.max(1) - 1);
    let (wq, _) = off(q);
    let theta0 = dot(wq, v).atan2(dot(wq, u)).rem_euclid(tau);
    let point = |theta: f64| {
        let t = theta / sweep;
        let r = r_s + (r_e - r_s) * t;
        let h = h_s + (h_e - h_s) * t;
        let radial = stanok_geom::add(scale(u, r * theta.cos()), scale(v, r * theta.sin()));
        stanok_geom::add(stanok_geom::add(a.centre, scale(axis, h)), radial)
    };
    let mut best = f64::INFINITY;
    for k in 0..=a.turns.max(1) {
        let theta = theta0 + tau * f64::from(k);
        for th in [theta, theta - tau] {
            if (-0.05..=sweep + 0.05).contains(&th) {
                let f = |x: f64| norm(sub(q, point(x)));
                let (mut lo, mut hi) = ((th - 0.05).max(0.0), (th + 0.05).min(sweep));
                for _ in 0..100 {
                    let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
                    if f(m1) < f(m2) {
                        hi = m2;
                    } else {
                        lo = m1;
                    }
                }
                best = best.min(f(0.5 * (lo + hi)));
            }
        }
    }
    best
}

pub fn distance_to_polyline(q: Vec3, poly: &[Vec3]) -> f64 {
    poly.windows(2)
        .map(|w| distance_to_segment(q, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

pub fn pose_diff(a: &Pose, b: &Pose) -> f64 {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

pub fn vec_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

pub fn feed_close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * a.abs().max(1.0)
}

/// Knots scaled to [0, 1].
pub fn unit_knots(k: &[f64]) -> Vec<f64> {
    let (a, b) = (k[0], k[k.len() - 1]);
    k.iter().map(|t| (t - a) / (b - a)).collect()
}

/// Compares one source motion with the converted one exactly (same kind, same geometry).
pub fn same_motion(src: &Canon, dst: &Canon) -> Result<(), String> {
    let end_err = |a: &Pose, b: &Pose| {
        let d = pose_diff(a, b);
        if d > TOL_MM {
            Err(format!("end differs by {d:e} mm"))
        } else {
            Ok(())
        }
    };
    match (src, dst) {
        (Canon::StraightTraverse(a), Canon::StraightTraverse(b)) => end_err(&a.end, &b.end),
        (Canon::StraightFeed(a), Canon::StraightFeed(b)) => {
            end_err(&a.end, &b.end)?;
            if !feed_close(a.feed, b.feed) {
                return Err(format!("feed {} vs {}", a.feed, b.feed));
            }
            Ok(())
        }
        (Canon::ArcFeed(a), Canon::ArcFeed(b)) => {
            end_err(&a.end, &b.end)?;
            let dc = vec_diff(a.centre, b.centre);
            let da = vec_diff(a.axis, b.axis);
            if dc > TOL_MM || da > 1e-9 || a.turns != b.turns || !feed_close(a.feed, b.feed) {
                return Err(format!(
                    "arc: centre Δ {dc:e}, axis Δ {da:e}, turns {} vs {}, feed {} vs {}",
                    a.turns, b.turns, a.feed, b.feed
                ));
            }
            Ok(())
        }
        (Canon::SplineFeed(a), Canon::SplineFeed(b)) => {
            end_err(&a.end, &b.end)?;
            let cps_ok = a.control_points.len() == b.control_points.len()
                && a.control_points
                    .iter()
                    .zip(&b.control_points)
                    .all(|(p, q)| vec_diff(*p, *q) <= TOL_MM);
            let w_ok = a
                .weights
                .iter()
                .zip(&b.weights)
                .all(|(x, y)| (x - y).abs() < 1e-9);
            let k_ok = unit_knots(&a.knots)
                .iter()
                .zip(unit_knots(&b.knots))
                .all(|(x, y)| (x - y).abs() < 1e-12);
            if !(cps_ok && w_ok && k_ok && a.degree == b.degree && feed_close(a.feed, b.feed)) {
                return Err("spline control points, weights, knots, degree or feed differ".into());
            }
            Ok(())
        }
        (
            Canon::StraightProbe {
                motion: a,
                contact: ca,
                ..
            },
            Canon::StraightProbe {
                motion: b,
                contact: cb,
                ..
            },
        ) => {
            end_err(&a.end, &b.end)?;
            // Without configured probe surfaces the RS274/NGC probe stands 0.01 in (0.254 mm)
            // short of its target, as LinuxCNC's standalone rs274 puts it (docs/decisions.md),
            // where the other dialects' probe stands at the target: the same untripped probe.
            let untripped_rs274 = |m: &stanok_canon::LineMove, c: &stanok_canon::Pose| {
                let (s, e, c) = (m.start.to_array(), m.end.to_array(), c.to_array());
                let len = (0..3).map(|k| (s[k] - e[k]).powi(2)).sum::<f64>().sqrt();
                len > 0.0
                    && (0..3).all(|k| (e[k] + 0.254 * (s[k] - e[k]) / len - c[k]).abs() < 1e-6)
            };
            match (ca, cb) {
                (None, None) => Ok(()),
                (Some(x), Some(y)) => end_err(x, y),
                (Some(x), None) if untripped_rs274(a, x) => Ok(()),
                (None, Some(y)) if untripped_rs274(b, y) => Ok(()),
                _ => Err("probe contact differs".into()),
            }
        }
        (
            Canon::RigidTap {
                start: sa, end: ea, ..
            },
            Canon::RigidTap {
                start: sb, end: eb, ..
            },
        ) => {
            end_err(sa, sb)?;
            end_err(ea, eb)
        }
        _ => Err(format!("kind differs: {:?} vs {:?}", kind(src), kind(dst))),
    }
}

pub fn kind(c: &Canon) -> &'static str {
    match c {
        Canon::StraightTraverse(_) => "rapid",
        Canon::StraightFeed(_) => "line",
        Canon::ArcFeed(_) => "arc",
        Canon::SplineFeed(_) => "spline",
        Canon::StraightProbe { .. } => "probe",
        Canon::RigidTap { .. } => "rigid tap",
        _ => "other",
    }
}

/// The motions of a stream, with the initial position first (as a rapid "to" it).
pub fn motions(stream: &[Spanned<Canon>]) -> (Pose, Vec<(u32, Canon)>) {
    let start = stream
        .iter()
        .find_map(|c| match &c.value {
            Canon::Init { position, .. } => Some(*position),
            _ => None,
        })
        .unwrap_or(Pose::ZERO);
    let moves = stream
        .iter()
        .filter(|c| c.value.motion().is_some())
        .map(|c| (c.span.line, c.value.clone()))
        .collect();
    (start, moves)
}

/// What the table compared, so that a row that silently lost its curves shows.
#[derive(Debug, Default)]
pub struct Tally {
    pub motions: usize,
    /// Arcs compared exactly, per plane normal X, Y, Z.
    pub arcs_by_normal: [usize; 3],
    /// Arcs with more than one turn.
    pub multi_turn: usize,
    /// Splines compared exactly (control points, weights, knots).
    pub splines: usize,
    /// Curves replaced by chords.
    pub chorded: usize,
    /// Splines that came back as several pieces (AxiOMA BSPLINE emits one rational Bézier per
    /// knot interval), each on the source curve.
    pub spline_pieces: usize,
    pub probes: usize,
}

/// The converted splines from `dst[*j]` on that together stand for the source spline `s`: 17
/// samples of each piece within `TOL_MM` of the source curve, the last piece ending at its end.
pub fn spline_pieces(s: &Canon, dst: &[(u32, Canon)], j: &mut usize) -> Result<(), String> {
    let poly = dense(s).unwrap();
    let end = s.motion().unwrap().end();
    loop {
        let Some((_, Canon::SplineFeed(piece))) = dst.get(*j) else {
            return Err("spline pieces end before the curve does".into());
        };
        *j += 1;
        let curve = Nurbs::new(
            piece.degree,
            &piece.control_points,
            &piece.weights,
            &piece.knots,
        );
        let (u0, u1) = curve.domain();
        for k in 0..=16 {
            let q = curve.point_at(u0 + (u1 - u0) * k as f64 / 16.0);
            let d = distance_to_polyline(q, &poly);
            if d > TOL_MM {
                return Err(format!("spline piece off the source curve by {d:e} mm"));
            }
        }
        if pose_diff(&piece.end, &end) <= TOL_MM {
            return Ok(());
        }
    }
}

/// Compares the motion streams; chords may stand for one source curve.
pub fn compare(
    src: &[Spanned<Canon>],
    dst: &[Spanned<Canon>],
    tally: &mut Tally,
) -> Result<(), String> {
    let (s0, src) = motions(src);
    let (d0, dst) = motions(dst);
    if pose_diff(&s0, &d0) > TOL_MM {
        return Err("initial positions differ".into());
    }
    let mut j = 0;
    for (line, s) in &src {
        let here = |why: String| format!("source line {line} ({}): {why}", kind(s));
        let d = &dst
            .get(j)
            .ok_or_else(|| here("missing in the converted program".into()))?
            .1;
        // A rigid tap where the target has none: down and back as two feed lines.
        if let (Canon::RigidTap { start, end, .. }, Canon::StraightFeed(_)) = (s, d) {
            for want in [end, start] {
                match dst.get(j) {
                    Some((_, Canon::StraightFeed(m))) if pose_diff(&m.end, want) <= TOL_MM => {
                        j += 1
                    }
                    _ => return Err(here("rigid tap not written as down-and-back lines".into())),
                }
            }
            tally.motions += 1;
            continue;
        }
        let curve_as_chords = matches!(s, Canon::ArcFeed(_) | Canon::SplineFeed(_))
            && matches!(d, Canon::StraightFeed(_));
        tally.motions += 1;
        if let (Canon::SplineFeed(_), Canon::SplineFeed(_)) = (s, d) {
            if same_motion(s, d).is_err() {
                spline_pieces(s, &dst, &mut j).map_err(here)?;
                tally.spline_pieces += 1;
                continue;
            }
        }
        if !curve_as_chords {
            same_motion(s, d).map_err(here)?;
            match s {
                Canon::ArcFeed(a) => {
                    let n = (0..3).max_by(|&i, &k| a.axis[i].abs().total_cmp(&a.axis[k].abs()));
                    tally.arcs_by_normal[n.unwrap_or(2)] += 1;
                    tally.multi_turn += usize::from(a.turns > 1);
                }
                Canon::SplineFeed(_) => tally.splines += 1,
                Canon::StraightProbe { .. } => tally.probes += 1,
                _ => {}
            }
            j += 1;
            continue;
        }
        tally.chorded += 1;
        // Chords: consume lines until the curve's end. Arcs are checked analytically (a dense
        // polyline of a multi-turn helix is slow), splines against a 1e-7 mm tessellation.
        let poly = match s {
            Canon::ArcFeed(_) => Vec::new(),
            _ => dense(s).unwrap(),
        };
        let distance = |q: Vec3| match s {
            Canon::ArcFeed(a) => distance_to_arc(q, a),
            _ => distance_to_polyline(q, &poly),
        };
        let end = s.motion().unwrap().end();
        loop {
            let Some((_, Canon::StraightFeed(m))) = dst.get(j) else {
                return Err(here("chords end before the curve does".into()));
            };
            j += 1;
            let mid = [
                0.5 * (m.start.x + m.end.x),
                0.5 * (m.start.y + m.end.y),
                0.5 * (m.start.z + m.end.z),
            ];
            let de = distance(m.end.xyz());
            let dm = distance(mid);
            if de > TOL_MM || dm > CHORD_TOL_MM + TOL_MM {
                return Err(here(format!(
                    "chord off the curve: end {de:e} mm, middle {dm:e} mm"
                )));
            }
            if pose_diff(&m.end, &end) <= TOL_MM {
                break;
            }
        }
    }
    if j != dst.len() {
        return Err(format!(
            "{} extra motions in the converted program",
            dst.len() - j
        ));
    }
    Ok(())
}
