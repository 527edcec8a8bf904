//! Round trip: a program is interpreted, its Canon stream converted to each target dialect, the
//! converted text interpreted again by Stanok's own interpreter, and the two motion streams
//! compared. One row per (source dialect, file); the lab dialects' fixtures are added as rows.
//!
//! Compared, motion by motion: the kind (rapid, feed line, arc, spline, probe, rigid tap), the end
//! point of all nine axes, the feed (mm/min), and for arcs the centre, the axis and the number of
//! turns; for splines the control points, weights and the knot vector up to scale. Tolerance:
//! `TOL_MM` = 2e-6 mm on positions (the converter prints 6 decimals: each printed coordinate is
//! within 5e-7 mm, a re-derived centre within 1e-6 mm) and 1e-6 relative on feeds. Where the
//! converter writes chords for a curve the target cannot express (it warns), the chords replace
//! the curve: every chord end must lie on the source curve (within `TOL_MM`), every chord's
//! midpoint within the chord tolerance of it, and the last chord must end at the curve's end.

use stanok_canon::{Canon, Pose, Spanned};
use stanok_convert::{convert, ConvertOptions, Target};
use stanok_geom::{distance_to_segment, Helix, Nurbs, Vec3};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;
use std::io::Cursor;
use std::path::{Path, PathBuf};

const TOL_MM: f64 = 2e-6;
const CHORD_TOL_MM: f64 = 0.001;

/// The programs: lines, arcs in G17/G18/G19, helices with turns, full circles, splines (Bézier,
/// NURBS, Akima, cubic), canned cycles, cutter compensation, frames, polar moves, probing, dwell,
/// spindle, coolant, tool changes. Paths are relative to `../shared/corpus`, or to the repository's
/// `examples/` and this crate's `tests/programs/` (programs written for this test: what the corpus
/// fragments do not reach — G18/G19 arcs, helices with P in two planes, G5/G5.1/G5.2 in one
/// program, cycles, dynamic compensation, G92/G10 L2 rotation/G55 frames, G93/G95 feed modes, inch
/// moves, G33, probing) with those prefixes.
const ROWS: &[(Dialect, &str)] = &[
    (Dialect::Rs274ngc, "rs274ngc/g01-linear-example-1.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g02-arc-center-example-1.ngc"),
    (
        Dialect::Rs274ngc,
        "rs274ngc/g02-g03-arc-center-example-2.ngc",
    ),
    (Dialect::Rs274ngc, "rs274ngc/g02-helix-example-3.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g02-p-word-example-4.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/derived-g02-full-circle.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g05-cubic-spline-example-1.ngc"),
    (
        Dialect::Rs274ngc,
        "rs274ngc/g05.1-quadratic-spline-example-1.ngc",
    ),
    (Dialect::Rs274ngc, "rs274ngc/g05.2-nurbs-example-1.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g81-twelve-holes-example.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/g40-example-1.ngc"),
    (Dialect::Rs274ngc, "rs274ngc/derived-g10-l2-rotation.ngc"),
    (Dialect::Rs274ngc, "examples/demo-bolt-circle.ngc"),
    (Dialect::Rs274ngc, "programs/planes-helices-splines.ngc"),
    (Dialect::Rs274ngc, "programs/technology-frames-cycles.ngc"),
    (Dialect::Axioma, "examples/demo-plate.nc"),
    (
        Dialect::Axioma,
        "axioma/s5_3_1-arc-centre-ijk-absolute-milling-example-5_5.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_3_1-arc-centre-ijk-relative-turning-example-5_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_3_4-full-circle-ijk-only-example-5_12.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_3_6-helix-extra-turns-p-example-5_14.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_9_3-polar-arc-yz-example-4_25.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_3_3-rotation-loop-slots-example-4_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_4_1-aspline-akima-example-5_15.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_4_3-cspline-cubic-example-5_17.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s5_4_2-bspline-nurbs-circle-example-5_16.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s11_6_2-g83-peck-drilling-example-11_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s11_8_3-g389-circular-pocket-example-11_14.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s9_2_1-g41-square-contour-example-9_6.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s9_2_1-g42-turning-contour-example-9_7.nc",
    ),
    (Dialect::Axioma, "axioma/s5_5-probe-g75-example-5_19.nc"),
    (
        Dialect::Axioma,
        "axioma/s5_5-probe-batch-m910-m911-example-5_20.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s11_8_1-g387-rectangular-pocket-example-11_12.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_3_4-combined-transforms-pole-example-4_8.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s4_9_4-polar-absolute-keyhole-example-4_29.nc",
    ),
    (
        Dialect::Axioma,
        "axioma/s9_2_1-g143-g41-incremental-bore-example-9_12.nc",
    ),
    (Dialect::Axioma, "axioma/s5_4_4-splbreak-example-5_18.nc"),
    (
        Dialect::Axioma,
        "axioma/s4_8_1-absolute-centre-turning-example-4_18.nc",
    ),
];

fn path_of(row: &str) -> PathBuf {
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

fn target_dialect(t: Target) -> Dialect {
    match t {
        Target::Rs274ngc => Dialect::Rs274ngc,
        Target::Axioma => Dialect::Axioma,
    }
}

/// Interprets `text` up to its first error (corpus fragments often lack a program end or a feed:
/// the commands before the error are what a control would have run); `dir` is where subroutine
/// files are looked up.
fn interpret_prefix(text: &str, dialect: Dialect, dir: &Path) -> Vec<Spanned<Canon>> {
    let mut opts = InterpOptions::new(dialect);
    opts.subroutine_path = vec![dir.to_path_buf()];
    Interpreter::new(Cursor::new(text.as_bytes().to_vec()), opts)
        .map_while(Result::ok)
        .collect()
}

/// Interprets `text` (a converted program), which must run without an error.
fn interpret(text: &str, dialect: Dialect, dir: &Path) -> Result<Vec<Spanned<Canon>>, String> {
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
fn dense(c: &Canon) -> Option<Vec<Vec3>> {
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

fn distance_to_polyline(q: Vec3, poly: &[Vec3]) -> f64 {
    poly.windows(2)
        .map(|w| distance_to_segment(q, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

fn pose_diff(a: &Pose, b: &Pose) -> f64 {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn vec_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

fn feed_close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * a.abs().max(1.0)
}

/// Knots scaled to [0, 1].
fn unit_knots(k: &[f64]) -> Vec<f64> {
    let (a, b) = (k[0], k[k.len() - 1]);
    k.iter().map(|t| (t - a) / (b - a)).collect()
}

/// Compares one source motion with the converted one exactly (same kind, same geometry).
fn same_motion(src: &Canon, dst: &Canon) -> Result<(), String> {
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
            match (ca, cb) {
                (None, None) => Ok(()),
                (Some(x), Some(y)) => end_err(x, y),
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

fn kind(c: &Canon) -> &'static str {
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
fn motions(stream: &[Spanned<Canon>]) -> (Pose, Vec<(u32, Canon)>) {
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
struct Tally {
    motions: usize,
    /// Arcs compared exactly, per plane normal X, Y, Z.
    arcs_by_normal: [usize; 3],
    /// Arcs with more than one turn.
    multi_turn: usize,
    /// Splines compared exactly (control points, weights, knots).
    splines: usize,
    /// Curves replaced by chords.
    chorded: usize,
    /// Splines that came back as several pieces (AxiOMA BSPLINE emits one rational Bézier per
    /// knot interval), each on the source curve.
    spline_pieces: usize,
    probes: usize,
}

/// The converted splines from `dst[*j]` on that together stand for the source spline `s`: 17
/// samples of each piece within `TOL_MM` of the source curve, the last piece ending at its end.
fn spline_pieces(s: &Canon, dst: &[(u32, Canon)], j: &mut usize) -> Result<(), String> {
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
fn compare(
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
        // Chords: consume lines until the curve's end.
        let poly = dense(s).unwrap();
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
            let de = distance_to_polyline(m.end.xyz(), &poly);
            let dm = distance_to_polyline(mid, &poly);
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

#[test]
fn every_row_round_trips_to_the_same_tool_path_in_both_targets() {
    let mut failures = Vec::new();
    let mut tally = Tally::default();
    let files = ROWS.iter().map(|&(dialect, row)| {
        let path = path_of(row);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{row}: {e}"));
        (dialect, row, text, path.parent().unwrap().to_path_buf())
    });
    for (dialect, row, text, dir) in files {
        let dir = dir.as_path();
        let source = interpret_prefix(&text, dialect, dir);
        let moves = source.iter().filter(|c| c.value.motion().is_some()).count();
        if moves == 0 {
            failures.push(format!(
                "{row}: the source does not move before its first error"
            ));
        }
        for target in [Target::Rs274ngc, Target::Axioma] {
            let opts = ConvertOptions::new(target, row, &format!("{dialect:?}"));
            let (converted, _warnings) = convert(&source, opts);
            let again = match interpret(&converted, target_dialect(target), dir) {
                Ok(s) => s,
                Err(e) => {
                    failures.push(format!(
                        "{row} → {}: the converted program does not run: {e}\n{converted}",
                        target.id()
                    ));
                    continue;
                }
            };
            if let Err(e) = compare(&source, &again, &mut tally) {
                failures.push(format!("{row} → {}: {e}\n{converted}", target.id()));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    eprintln!("{tally:?}");
    // The table covers what it claims: arcs in all three planes, multi-turn helices, splines kept
    // exact (RS274/NGC G5.2, AxiOMA BSPLINE, whole or in pieces), probe moves.
    let t = &tally;
    assert!(t.motions > 500, "{t:?}");
    assert!(t.arcs_by_normal.iter().all(|&n| n >= 4), "{t:?}");
    assert!(t.multi_turn >= 8, "{t:?}");
    assert!(t.splines + t.spline_pieces >= 60, "{t:?}");
    assert!(t.probes >= 4, "{t:?}");
}

/// Beyond the table: every RS274/NGC and AxiOMA corpus program that moves before its first error
/// round-trips in both targets (the same comparison).
#[test]
fn every_corpus_program_that_moves_round_trips() {
    let mut failures = Vec::new();
    let mut tally = Tally::default();
    let mut programs = 0;
    let base = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus"
    ));
    for (sub, dialect) in [("rs274ngc", Dialect::Rs274ngc), ("axioma", Dialect::Axioma)] {
        let mut files: Vec<PathBuf> = std::fs::read_dir(base.join(sub))
            .unwrap_or_else(|e| panic!("{sub}: {e}"))
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "nc" || e == "ngc"))
            .collect();
        files.sort();
        for path in files {
            let Ok(text) = std::fs::read_to_string(&path) else {
                continue;
            };
            let dir = path.parent().unwrap();
            let source = interpret_prefix(&text, dialect, dir);
            if !source.iter().any(|c| c.value.motion().is_some()) {
                continue;
            }
            programs += 1;
            let row = format!("{sub}/{}", path.file_name().unwrap().to_string_lossy());
            for target in [Target::Rs274ngc, Target::Axioma] {
                let (converted, _) = convert(&source, ConvertOptions::new(target, &row, sub));
                match interpret(&converted, target_dialect(target), dir) {
                    Err(e) => failures.push(format!("{row} → {}: does not run: {e}", target.id())),
                    Ok(again) => {
                        if let Err(e) = compare(&source, &again, &mut tally) {
                            failures.push(format!("{row} → {}: {e}", target.id()));
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        programs >= 100 && tally.motions > 2000,
        "{programs} programs, {tally:?}"
    );
}
