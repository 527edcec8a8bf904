//! Constant surface speed (G96) along the path: the spindle speed as a function of position, and
//! feed per revolution that follows it.
//!
//! ## Model
//! Under G96 the main spindle turns at n(p) = clamp(v / (2π·|p[axis] − centre|), n_min, n_max)
//! (`stanok_canon::SurfaceSpeedLaw`). Every segment carries the law
//! ([`SpindleSpeed::Surface`]); the interpolator evaluates it at each setpoint, so the speed the
//! simulated machine sees changes continuously as the tool crosses the part — not in steps at
//! block ends.
//!
//! A feed per revolution (G95) then means a path speed f·n(p) that changes along the segment too.
//! The planner's pieces have one speed limit each, so a G95 feed segment under G96 is cut into
//! sub-segments on which n varies by at most [`RPM_STEP`] (2 %), each limited to f · (the lowest n
//! on it): the tool never cuts more than f per revolution, and at most 2 % less.
//!
//! ## Algorithm (`split`)
//! The segment is parameterised by u ∈ [0, 1] (length fraction of a line, sweep fraction of an arc,
//! vertex index of a tessellated spline). Lines start as one interval, arcs as intervals of at most
//! 45° of sweep (n is not monotone along an arc, so every interval must be short enough for three
//! samples to show its variation). Each interval is accepted when n at its ends and its middle
//! differs by at most the step, otherwise halved, down to [`MAX_DEPTH`] halvings; the intervals come
//! out in path order. On a line |p[axis] − centre| is convex in u, so n is lowest at an end and the
//! limit taken from the samples is exact; on an arc it holds to the sampling. A spline's polyline is
//! cut at vertices, greedily, where the speed range of the current run would exceed the step.
//!
//! ## Invariants
//! * The sub-segments join end to start exactly (the same evaluated point) and cover the segment.
//! * Inner joints pass at speed: sub-segments keep G64 with its tolerance; under G60/G61/G61.1 the
//!   inner joints get the internal 1 µm blend that the chords of one arc get anyway, and only the
//!   last sub-segment carries the programmed block-end rule.
//! * At most [`MAX_PIECES`] sub-segments per segment (a facing cut from r = 100 mm to the centre at
//!   a 20:1 speed range needs about 150).

use crate::path::INTERNAL_TOLERANCE;
use crate::segment::{PathSegment, Point9, SegmentGeometry, SpindleSpeed};
use stanok_canon::{PathMode, SurfaceSpeedLaw};
use stanok_geom::Helix;

/// Largest relative change of the spindle speed within one sub-segment.
pub const RPM_STEP: f64 = 0.02;
/// Most halvings of one interval.
pub const MAX_DEPTH: u32 = 12;
/// Most sub-segments of one segment.
pub const MAX_PIECES: usize = 4096;
/// Largest sweep of one arc interval before halving, rad.
const ARC_INTERVAL: f64 = std::f64::consts::FRAC_PI_4;

/// One cut of a segment: the sub-segment and the lowest spindle speed on it, rev/min.
#[derive(Debug, Clone, PartialEq)]
pub struct CssPiece {
    /// The sub-segment (its `path_speed` still the whole segment's; the caller sets it).
    pub segment: PathSegment,
    /// Lowest spindle speed found on it, rev/min.
    pub min_rpm: f64,
}

fn lerp9(a: &Point9, b: &Point9, u: f64) -> Point9 {
    std::array::from_fn(|i| a[i] + (b[i] - a[i]) * u)
}

/// The point at parameter u of a line or arc segment (module doc).
fn point_at(seg: &PathSegment, u: f64) -> Point9 {
    if u <= 0.0 {
        return seg.start;
    }
    if u >= 1.0 {
        return seg.end;
    }
    let mut p = lerp9(&seg.start, &seg.end, u);
    if let SegmentGeometry::Arc(h) = &seg.geometry {
        p[..3].copy_from_slice(&h.point_at(u));
    }
    p
}

fn rpm_range(law: &SurfaceSpeedLaw, points: &[&Point9]) -> (f64, f64) {
    points.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
        let n = law.rpm_at(p);
        (lo.min(n), hi.max(n))
    })
}

fn within_step(lo: f64, hi: f64) -> bool {
    hi <= lo * (1.0 + RPM_STEP) || hi - lo < 1e-9
}

/// The path mode of an inner joint (module doc, invariants).
fn inner_mode(mode: PathMode) -> PathMode {
    match mode {
        PathMode::Continuous { .. } => mode,
        PathMode::ExactStop | PathMode::ExactPath => PathMode::Continuous {
            tolerance: 2.0 * INTERNAL_TOLERANCE,
        },
    }
}

/// Cuts a feed segment so that the spindle speed of `law` varies by at most [`RPM_STEP`] on each
/// piece (module doc). Every piece carries the law as its main spindle's speed.
pub fn split(seg: &PathSegment, law: &SurfaceSpeedLaw) -> Vec<CssPiece> {
    let mut pieces = Vec::new();
    match &seg.geometry {
        SegmentGeometry::Polyline(points) => split_polyline(seg, points, law, &mut pieces),
        SegmentGeometry::Line | SegmentGeometry::Arc(_) => {
            let initial = match &seg.geometry {
                SegmentGeometry::Arc(h) => {
                    let n = (h.sweep() / ARC_INTERVAL).ceil();
                    if n.is_finite() {
                        (n as usize).clamp(1, MAX_PIECES / 4)
                    } else {
                        1
                    }
                }
                _ => 1,
            };
            let mut bounds = Vec::new();
            for k in 0..initial {
                let (u0, u1) = (k as f64 / initial as f64, (k + 1) as f64 / initial as f64);
                bisect(seg, law, u0, u1, 0, &mut bounds);
            }
            let mut u0 = 0.0;
            for (u1, min_rpm) in bounds {
                pieces.push(CssPiece {
                    segment: sub_segment(seg, u0, u1),
                    min_rpm,
                });
                u0 = u1;
            }
        }
    }
    let last = pieces.len().saturating_sub(1);
    for (k, p) in pieces.iter_mut().enumerate() {
        p.segment.spindles.0[0] = SpindleSpeed::Surface(*law);
        if k != last {
            p.segment.path_mode = inner_mode(seg.path_mode);
        }
    }
    pieces
}

/// Halves [u0, u1] until n varies by at most the step on each half; pushes (end u, lowest n).
fn bisect(
    seg: &PathSegment,
    law: &SurfaceSpeedLaw,
    u0: f64,
    u1: f64,
    depth: u32,
    out: &mut Vec<(f64, f64)>,
) {
    let um = 0.5 * (u0 + u1);
    let (a, m, b) = (point_at(seg, u0), point_at(seg, um), point_at(seg, u1));
    let (lo, hi) = rpm_range(law, &[&a, &m, &b]);
    if within_step(lo, hi) || depth >= MAX_DEPTH || out.len() + 2 > MAX_PIECES {
        out.push((u1, lo));
        return;
    }
    bisect(seg, law, u0, um, depth + 1, out);
    bisect(seg, law, um, u1, depth + 1, out);
}

/// The part [u0, u1] of a line or arc segment.
fn sub_segment(seg: &PathSegment, u0: f64, u1: f64) -> PathSegment {
    let (start, end) = (point_at(seg, u0), point_at(seg, u1));
    let geometry = match &seg.geometry {
        SegmentGeometry::Arc(h) => SegmentGeometry::Arc(Helix {
            start: [start[0], start[1], start[2]],
            end: [end[0], end[1], end[2]],
            centre: h.centre,
            axis: h.axis,
            // Every interval sweeps at most 45°: never a full turn.
            turns: 1,
        }),
        other => other.clone(),
    };
    PathSegment {
        start,
        end,
        geometry,
        ..seg.clone()
    }
}

/// A tessellated spline: runs of consecutive chords over which n stays within the step.
fn split_polyline(
    seg: &PathSegment,
    points: &[Point9],
    law: &SurfaceSpeedLaw,
    out: &mut Vec<CssPiece>,
) {
    let mut run_start = 0;
    let n0 = points.first().map(|p| law.rpm_at(p)).unwrap_or(0.0);
    let (mut lo, mut hi) = (n0, n0);
    let flush = |from: usize, to: usize, lo: f64, out: &mut Vec<CssPiece>| {
        let part = points[from..=to].to_vec();
        out.push(CssPiece {
            segment: PathSegment {
                start: part[0],
                end: part[part.len() - 1],
                geometry: SegmentGeometry::Polyline(part),
                ..seg.clone()
            },
            min_rpm: lo,
        });
    };
    for k in 1..points.len() {
        let n = law.rpm_at(&points[k]);
        let (l2, h2) = (lo.min(n), hi.max(n));
        if !within_step(l2, h2) && k - run_start > 1 && out.len() + 2 < MAX_PIECES {
            flush(run_start, k - 1, lo, out);
            run_start = k - 1;
            let prev = law.rpm_at(&points[k - 1]);
            (lo, hi) = (prev.min(n), prev.max(n));
        } else {
            (lo, hi) = (l2, h2);
        }
    }
    if points.len() >= 2 {
        flush(run_start, points.len() - 1, lo, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::segment::Spindles;
    use stanok_canon::AccelerationProfile;

    fn law() -> SurfaceSpeedLaw {
        // 200 m/min about X = 0, 100…3000 rpm.
        SurfaceSpeedLaw {
            mm_per_min: 200_000.0,
            axis: 0,
            centre: 0.0,
            min_rpm: 100.0,
            max_rpm: 3000.0,
        }
    }

    fn seg(start: Point9, end: Point9, geometry: SegmentGeometry) -> PathSegment {
        PathSegment {
            acceleration_cap: f64::INFINITY,
            velocity_cap: f64::INFINITY,
            speed_class: Default::default(),
            start,
            end,
            geometry,
            path_speed: 1.0,
            rapid: false,
            path_mode: PathMode::ExactStop,
            profile: AccelerationProfile::Brisk,
            line: 7,
            command: 0,
            spindles: Spindles::default(),
        }
    }

    fn x(v: f64) -> Point9 {
        let mut p = [0.0; 9];
        p[0] = v;
        p
    }

    #[test]
    fn rpm_law_follows_the_radius_and_its_limits() {
        let l = law();
        // 200 000 / (2π · 50) = 636.62 rpm.
        assert!((l.rpm_at(&x(50.0)) - 636.619_772).abs() < 1e-5);
        assert_eq!(l.rpm_at(&x(-500.0)), 100.0);
        assert_eq!(l.rpm_at(&x(1.0)), 3000.0);
        assert_eq!(l.rpm_at(&x(0.0)), 3000.0);
    }

    #[test]
    fn a_facing_cut_is_cut_where_the_speed_changes_by_two_percent() {
        let s = seg(x(50.0), x(0.0), SegmentGeometry::Line);
        let pieces = split(&s, &law());
        // Contiguous, in order, covering the segment.
        assert_eq!(pieces[0].segment.start, s.start);
        assert_eq!(pieces.last().unwrap().segment.end, s.end);
        for w in pieces.windows(2) {
            assert_eq!(w[0].segment.end, w[1].segment.start);
        }
        for p in &pieces {
            let (a, b) = (law().rpm_at(&p.segment.start), law().rpm_at(&p.segment.end));
            let (lo, hi) = (a.min(b), a.max(b));
            // Each piece within the step (or at the smallest interval), limited by its lowest n.
            assert!(
                hi <= lo * (1.0 + RPM_STEP) + 1e-9 || p.segment.start[0] - p.segment.end[0] < 0.1
            );
            assert!((p.min_rpm - lo).abs() < 1e-9);
            assert_eq!(p.segment.spindles.0[0], SpindleSpeed::Surface(law()));
        }
        // n goes from 636.6 to 3000 (clamped below r = 10.6 mm): ln(4.71)/ln(1.02) ≈ 78 steps at
        // least; halving overshoots by at most 2×.
        assert!((78..=200).contains(&pieces.len()), "{}", pieces.len());
        // Inner joints pass at speed; the block end keeps G60.
        assert!(matches!(
            pieces[0].segment.path_mode,
            PathMode::Continuous { .. }
        ));
        assert_eq!(
            pieces.last().unwrap().segment.path_mode,
            PathMode::ExactStop
        );
    }

    #[test]
    fn a_cut_at_constant_radius_stays_whole() {
        let mut a = x(40.0);
        let mut b = x(40.0);
        a[2] = 0.0;
        b[2] = -80.0;
        let pieces = split(&seg(a, b, SegmentGeometry::Line), &law());
        assert_eq!(pieces.len(), 1);
        assert!((pieces[0].min_rpm - 200_000.0 / (std::f64::consts::TAU * 40.0)).abs() < 1e-9);
    }

    #[test]
    fn arc_pieces_lie_on_the_arc() {
        // Quarter circle in XZ about (20, 0, 0), r = 20: from X40 Z0 to X20 Z20 (about −Y: CCW in
        // the XZ plane seen from +Y).
        let h = Helix {
            start: [40.0, 0.0, 0.0],
            end: [20.0, 0.0, 20.0],
            centre: [20.0, 0.0, 0.0],
            axis: [0.0, -1.0, 0.0],
            turns: 1,
        };
        let s = seg(
            x(40.0),
            {
                let mut e = x(20.0);
                e[2] = 20.0;
                e
            },
            SegmentGeometry::Arc(h),
        );
        let pieces = split(&s, &law());
        assert!(pieces.len() >= 2);
        for p in &pieces {
            let SegmentGeometry::Arc(sub) = &p.segment.geometry else {
                panic!()
            };
            for k in 0..=8 {
                let q = sub.point_at(k as f64 / 8.0);
                let r = ((q[0] - 20.0).powi(2) + q[2].powi(2)).sqrt();
                assert!((r - 20.0).abs() < 1e-9, "{q:?}");
                assert!(q[1].abs() < 1e-12);
            }
        }
        assert_eq!(pieces.last().unwrap().segment.end, s.end);
    }
}
