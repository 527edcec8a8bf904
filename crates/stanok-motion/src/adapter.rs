//! From the Canon stream to planner input: modal state that matters to motion.
//!
//! ## What it tracks and why
//! Canon carries motion and modal changes as separate commands; the planner wants every segment to
//! be self-contained. `CanonAdapter` keeps the modal state and stamps it on each segment:
//! * path mode (`SetPathMode`: G60/G61 exact stop, G61.1 exact path, G64 P tolerance),
//! * acceleration profile (`SetAccelerationProfile`: BRISK/SOFT; `MotionConfig::forced_profile`
//!   overrides it),
//! * whether the feed override applies (`SetFeedOverrideEnabled`; never in spindle sync),
//! * the speeds of spindles 0–3 (`SetSpindleSpeed`, and G96's `SetSurfaceSpeedLaw`) and how they
//!   turn (`StartSpindle` M3 +1 / M4 −1, `StopSpindle` M5, M19 and program end 0): stamped on every
//!   segment so that each setpoint reports the signed speed at its position; under G96 a feed per
//!   revolution (of the main spindle) is cut into pieces that follow its law ([`crate::css`]).
//!
//! It keeps no copy of the interpreter's feed modes: every motion states its own feed law
//! (`stanok_canon::FeedLaw`), and `SetFeedMode`/`SetFeedRate` are for printers.
//!
//! ## Speeds
//! From the move alone: its `feed` (mm/min along the feed length — the interpreter already turned
//! G93 inverse time and G95 per-revolution feeds at the commanded spindle speed into mm/min), or
//! under `FeedLaw::SpindleSync` pitch × spindle rpm, or under `FeedLaw::SurfaceSpeed` (G95 with
//! G96) pieces that follow the law, each at mm/rev × its lowest spindle speed ([`crate::css`]).
//! Then: mm/min → mm/s, clamp to the machine's maximum feed, times (9-D length / feed length) —
//! see [`crate::segment`]. A feed that is zero, negative or not a number (the interpreter never
//! emits one; a spindle-synchronised move with the spindle at rest could) runs at the maximum
//! feed, so that nothing waits for ever. Rapids use the rapid rate. No override is applied here:
//! every segment says which override scales it ([`SpeedClass`]: feed, rapid, spindle for
//! synchronised moves, none where the program disabled it), and the planner and the
//! interpolator apply the factors in force at each servo instant ([`crate::overrides`]).
//!
//! ## Stops (spec axioma-2 §3.4, rs274 §4.30)
//! Exact stops are forced by M0/M1, tool changes, the tool-change start, program end, pallet
//! shuttle, dwell (stop, then stand), waiting for an input, spindle orientation, the start and the
//! end of spindle synchronisation, around probe moves and rigid taps, and between two motions whose
//! feed laws are of different modes (per minute, inverse time, per revolution: a feed-mode change
//! G93/G94/G95 in between; rapids carry the law in force, so the stop falls where the mode
//! changed among the motions).
//!
//! ## Tool-centre-point control
//! `SetToolCentrePoint` stops the path; while it is on, every segment is handed to
//! [`crate::tcp`] for its ORIVECT geometry, joint-rate speed and acceleration caps and an exact
//! stop at its end.
//!
//! Invariant: no input panics; non-finite coordinates make a segment that the path builder drops.

use crate::limits::MotionConfig;
use crate::segment::{
    PathSegment, PlannerInput, Point9, SegmentGeometry, SpeedClass, SpindleSpeed, Spindles,
    SPLINE_CHORD_TOLERANCE,
};
use stanok_canon::{
    AccelerationProfile, ArcMove, Canon, FeedLaw, FeedMode, LineMove, OrientationInterpolation,
    PathMode, Pose, SplineMove, SurfaceSpeedLaw,
};
use stanok_geom::{Helix, Nurbs};
use stanok_kin::FiveAxis;

/// Modal motion state between Canon commands (see the module doc).
#[derive(Debug, Clone)]
pub struct CanonAdapter {
    config: MotionConfig,
    path_mode: PathMode,
    profile: AccelerationProfile,
    /// The mode of the last motion's feed law: motions of another mode do not blend into it.
    last_mode: FeedMode,
    /// Last `SetSpindleSpeed` of spindles 0–3, rev/min.
    spindle_rpm: [f64; 4],
    /// How spindles 0–3 turn: +1 M3, −1 M4, 0 stopped.
    spindle_dir: [f64; 4],
    override_enabled: bool,
    /// The machine's kinematics with the active tool, while tool-centre-point control is on.
    tcp: Option<FiveAxis>,
    /// ORIAXES or ORIVECT.
    orientation: OrientationInterpolation,
    /// G96's law of spindles 0–3, where in force.
    surface_speed: [Option<SurfaceSpeedLaw>; 4],
    /// Serial number of the command being adapted (stamped on its segments).
    command: u64,
}

/// The feed mode of a law (None: spindle-synchronised, which stops before and after anyway).
fn mode_of(law: &FeedLaw) -> Option<FeedMode> {
    match law {
        FeedLaw::PerMinute => Some(FeedMode::UnitsPerMinute),
        FeedLaw::InverseTime => Some(FeedMode::InverseTime),
        FeedLaw::PerRevolution { .. } | FeedLaw::SurfaceSpeed { .. } => {
            Some(FeedMode::UnitsPerRevolution)
        }
        FeedLaw::SpindleSync { .. } => None,
    }
}

/// Length the feed applies to (spec axioma-2 §3.2) and the 9-D length, of a straight move.
fn feed_and_path_length(start: &Point9, end: &Point9) -> (f64, f64) {
    let len =
        |r: std::ops::Range<usize>| r.map(|i| (end[i] - start[i]).powi(2)).sum::<f64>().sqrt();
    let (xyz, abc, uvw) = (len(0..3), len(3..6), len(6..9));
    let path = (xyz * xyz + abc * abc + uvw * uvw).sqrt();
    let feed = if xyz > 0.0 {
        xyz
    } else if uvw > 0.0 {
        uvw
    } else {
        abc
    };
    (feed, path)
}

impl CanonAdapter {
    /// Power-on state: G64 with the default tolerance, BRISK, G94, override enabled.
    pub fn new(config: &MotionConfig) -> Self {
        CanonAdapter {
            config: config.clone().sanitised(),
            path_mode: PathMode::Continuous { tolerance: 0.0 },
            profile: AccelerationProfile::Brisk,
            last_mode: FeedMode::UnitsPerMinute,
            spindle_rpm: [0.0; 4],
            spindle_dir: [0.0; 4],
            override_enabled: true,
            tcp: None,
            orientation: OrientationInterpolation::Axes,
            surface_speed: [None; 4],
            command: 0,
        }
    }

    /// The serial number stamped on the segments adapted from now on (see
    /// [`PathSegment::command`]).
    pub fn set_command(&mut self, serial: u64) {
        self.command = serial;
    }

    /// The kinematics of tool-centre-point control, while it is on.
    pub fn tcp(&self) -> Option<&FiveAxis> {
        self.tcp.as_ref()
    }

    /// A segment under tool-centre-point control: ORIVECT geometry, joint-rate caps, exact stop
    /// (see [`crate::tcp`]).
    fn under_tcp(&self, input: PlannerInput) -> PlannerInput {
        let (Some(kin), PlannerInput::Segment(mut seg)) = (&self.tcp, input.clone()) else {
            return input;
        };
        if self.orientation == OrientationInterpolation::Vector
            && !matches!(seg.geometry, SegmentGeometry::Polyline(_))
        {
            if let Some((g, omega)) = crate::tcp::vector_polyline(&seg, kin) {
                // Orientation-only: F is the vector's angular speed (duration Ω / F); the
                // polyline's 9-D length runs in the same time.
                let tip_moves = (0..3).any(|i| seg.start[i] != seg.end[i]);
                if let (false, SegmentGeometry::Polyline(p)) = (tip_moves, &g) {
                    let length: f64 = p
                        .windows(2)
                        .map(|w| {
                            (0..9)
                                .map(|i| (w[1][i] - w[0][i]).powi(2))
                                .sum::<f64>()
                                .sqrt()
                        })
                        .sum();
                    let straight = (0..9)
                        .map(|i| (seg.end[i] - seg.start[i]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    if straight > 0.0 && omega > 0.0 {
                        // path_speed = F·(straight/straight) now; want length / (Ω / F).
                        seg.path_speed *= length / omega;
                        seg.velocity_cap *= length / omega;
                    }
                }
                seg.geometry = g;
            }
        }
        crate::tcp::limit_segment(&mut seg, kin, &self.config.axes);
        PlannerInput::Segment(seg)
    }

    /// Path speed (unit/s along the 9-D path) of a feed move at `feed_per_min` under `law`,
    /// before any override, and the override that will scale it.
    fn feed_speed(&self, feed_per_min: f64, law: &FeedLaw, ratio: f64) -> (f64, SpeedClass) {
        let (mut f, synchronised) = match law {
            FeedLaw::SpindleSync { pitch, rpm } => (pitch * rpm / 60.0, true),
            _ => (feed_per_min / 60.0, false),
        };
        if !(f.is_finite() && f > 0.0) {
            f = self.config.max_feed;
        }
        f = f.min(self.config.max_feed);
        let class = if synchronised {
            SpeedClass::Spindle
        } else if self.override_enabled {
            SpeedClass::Feed
        } else {
            SpeedClass::Fixed
        };
        (f * ratio, class)
    }

    /// An exact stop before a motion whose feed law is of another mode than the last one's.
    fn stop_on_mode_change(
        &mut self,
        law: &FeedLaw,
        line: u32,
        out: &mut impl FnMut(PlannerInput),
    ) {
        if let Some(mode) = mode_of(law) {
            if mode != self.last_mode {
                out(PlannerInput::Stop { dwell_s: 0.0, line });
                self.last_mode = mode;
            }
        }
    }

    fn rapid_speed(&self, ratio: f64) -> (f64, SpeedClass) {
        (self.config.rapid_rate * ratio, SpeedClass::Rapid)
    }

    fn segment(
        &self,
        start: Pose,
        end: Pose,
        geometry: SegmentGeometry,
        (speed, speed_class): (f64, SpeedClass),
        rapid: bool,
        line: u32,
    ) -> PathSegment {
        PathSegment {
            acceleration_cap: f64::INFINITY,
            velocity_cap: f64::INFINITY,
            speed_class,
            start: start.to_array(),
            end: end.to_array(),
            geometry,
            path_speed: speed,
            rapid,
            path_mode: self.path_mode,
            profile: self.config.forced_profile.unwrap_or(self.profile),
            line,
            command: self.command,
            spindles: self.spindles(),
        }
    }

    /// The spindles' speeds as segments carry them.
    fn spindles(&self) -> Spindles {
        Spindles(
            std::array::from_fn(|i| match self.surface_speed[i] {
                Some(law) => SpindleSpeed::Surface(law),
                None => SpindleSpeed::Constant(self.spindle_rpm[i]),
            }),
            self.spindle_dir,
        )
    }

    /// Emits a feed segment; under G96 with a feed per revolution (`FeedLaw::SurfaceSpeed`), as
    /// the pieces of [`crate::css::split`], each at f × (its lowest spindle speed).
    fn emit_feed(
        &self,
        input: PlannerInput,
        feed_law: &FeedLaw,
        ratio: f64,
        out: &mut impl FnMut(PlannerInput),
    ) {
        let PlannerInput::Segment(seg) = &input else {
            return out(input);
        };
        let (mm_per_rev, law) = match feed_law {
            FeedLaw::SurfaceSpeed { mm_per_rev, law } if !seg.rapid => (*mm_per_rev, law),
            _ => return out(input),
        };
        for piece in crate::css::split(seg, law) {
            let mut s = piece.segment;
            (s.path_speed, s.speed_class) =
                self.feed_speed(mm_per_rev * piece.min_rpm, &FeedLaw::PerMinute, ratio);
            out(PlannerInput::Segment(s));
        }
    }

    fn line(&self, m: &LineMove, rapid: bool, line: u32) -> PlannerInput {
        self.line_with_ratio(m, rapid, line).0
    }

    fn line_with_ratio(&self, m: &LineMove, rapid: bool, line: u32) -> (PlannerInput, f64) {
        let (s, e) = (m.start.to_array(), m.end.to_array());
        let (feed_len, path_len) = feed_and_path_length(&s, &e);
        let ratio = if feed_len > 0.0 {
            path_len / feed_len
        } else {
            1.0
        };
        let speed = if rapid {
            self.rapid_speed(ratio)
        } else {
            self.feed_speed(m.feed, &m.law, ratio)
        };
        let seg = self.segment(m.start, m.end, SegmentGeometry::Line, speed, rapid, line);
        (PlannerInput::Segment(seg), ratio)
    }

    fn arc(&self, a: &ArcMove, line: u32) -> (PlannerInput, f64) {
        let helix = Helix {
            start: a.start.xyz(),
            end: a.end.xyz(),
            centre: a.centre,
            axis: a.axis,
            turns: a.turns,
        };
        let xyz = helix.length();
        let (s, e) = (a.start.to_array(), a.end.to_array());
        let other: f64 = (3..9).map(|i| (e[i] - s[i]).powi(2)).sum();
        let path = (xyz * xyz + other).sqrt();
        let ratio = if xyz > 0.0 && path.is_finite() {
            path / xyz
        } else {
            1.0
        };
        let speed = self.feed_speed(a.feed, &a.law, ratio);
        let seg = self.segment(
            a.start,
            a.end,
            SegmentGeometry::Arc(helix),
            speed,
            false,
            line,
        );
        (PlannerInput::Segment(seg), ratio)
    }

    fn spline(&self, sp: &SplineMove, line: u32) -> (PlannerInput, f64) {
        let curve = Nurbs::new(sp.degree, &sp.control_points, &sp.weights, &sp.knots);
        let mut xyz = vec![sp.start.xyz()];
        if curve.validate().is_ok() {
            curve.tessellate(SPLINE_CHORD_TOLERANCE, &mut xyz);
        }
        // The curve ends exactly at the programmed end.
        let end = sp.end.xyz();
        if xyz.len() > 1 {
            let last = xyz.len() - 1;
            xyz[last] = end;
        } else {
            xyz.push(end);
        }
        let lengths: Vec<f64> = xyz
            .windows(2)
            .map(|w| stanok_geom::norm(stanok_geom::sub(w[1], w[0])))
            .collect();
        let total: f64 = lengths.iter().sum();
        let (s, e) = (sp.start.to_array(), sp.end.to_array());
        let mut points = Vec::with_capacity(xyz.len());
        let mut run = 0.0;
        for (k, p) in xyz.iter().enumerate() {
            if k > 0 {
                run += lengths[k - 1];
            }
            let f = if total > 0.0 { run / total } else { 1.0 };
            let mut q = [0.0; 9];
            q[..3].copy_from_slice(p);
            for i in 3..9 {
                q[i] = s[i] + (e[i] - s[i]) * f;
            }
            points.push(q);
        }
        let other: f64 = (3..9).map(|i| (e[i] - s[i]).powi(2)).sum();
        let ratio = if total > 0.0 {
            (total * total + other).sqrt() / total
        } else {
            1.0
        };
        let speed = self.feed_speed(sp.feed, &sp.law, ratio);
        let seg = self.segment(
            sp.start,
            sp.end,
            SegmentGeometry::Polyline(points),
            speed,
            false,
            line,
        );
        (PlannerInput::Segment(seg), ratio)
    }

    /// Turns one Canon command into zero or more planner inputs, in order.
    pub fn adapt(&mut self, cmd: &Canon, line: u32, out: &mut impl FnMut(PlannerInput)) {
        let stop =
            |out: &mut dyn FnMut(PlannerInput)| out(PlannerInput::Stop { dwell_s: 0.0, line });
        match cmd {
            Canon::StraightTraverse(m) => {
                self.stop_on_mode_change(&m.law, line, out);
                out(self.under_tcp(self.line(m, true, line)))
            }
            // Under G96 + G95 a feed may come in pieces (emit_feed); each goes through the TCP
            // caps on its own.
            Canon::StraightFeed(m) => {
                self.stop_on_mode_change(&m.law, line, out);
                let (input, ratio) = self.line_with_ratio(m, false, line);
                self.emit_feed(input, &m.law, ratio, &mut |i| out(self.under_tcp(i)))
            }
            Canon::ArcFeed(a) => {
                self.stop_on_mode_change(&a.law, line, out);
                let (input, ratio) = self.arc(a, line);
                self.emit_feed(input, &a.law, ratio, &mut |i| out(self.under_tcp(i)))
            }
            Canon::SplineFeed(sp) => {
                self.stop_on_mode_change(&sp.law, line, out);
                let (input, ratio) = self.spline(sp, line);
                self.emit_feed(input, &sp.law, ratio, &mut |i| out(self.under_tcp(i)))
            }
            // The switch stops the path; the stage re-expresses the position (stage.rs).
            Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } => {
                stop(out);
                self.tcp = match (&self.config.kinematics, active) {
                    (Some(k), true) => Some(k.clone().with_tool_offset(*tool_offset)),
                    _ => None,
                };
            }
            Canon::SetOrientationInterpolation { mode } => self.orientation = *mode,
            // The probe stops where it makes (or loses) contact, at rest.
            Canon::StraightProbe {
                motion, contact, ..
            } => {
                self.stop_on_mode_change(&motion.law, line, out);
                stop(out);
                out(self.line(&motion.stopped_at(contact.as_deref().copied()), false, line));
                stop(out);
            }
            Canon::RigidTap {
                start,
                end,
                scale,
                law,
            } => {
                self.stop_on_mode_change(law, line, out);
                stop(out);
                let down = LineMove {
                    start: *start,
                    end: *end,
                    feed: 0.0,
                    law: law.clone(),
                };
                out(self.line(&down, false, line));
                stop(out);
                let mut up = self.line(
                    &LineMove {
                        start: *end,
                        end: *start,
                        feed: 0.0,
                        law: law.clone(),
                    },
                    false,
                    line,
                );
                if let PlannerInput::Segment(s) = &mut up {
                    if scale.is_finite() && *scale > 0.0 {
                        s.path_speed = (s.path_speed * scale).min(self.config.max_feed);
                    }
                }
                out(up);
                stop(out);
            }
            Canon::Dwell { seconds } => out(PlannerInput::Stop {
                dwell_s: if seconds.is_finite() && *seconds > 0.0 {
                    *seconds
                } else {
                    0.0
                },
                line,
            }),
            Canon::SetPathMode { mode, .. } => self.path_mode = *mode,
            Canon::SetAccelerationProfile { profile } => self.profile = *profile,
            Canon::SetSpindleSpeed { spindle, rpm } if *spindle < 4 => {
                self.spindle_rpm[*spindle as usize] = rpm.abs()
            }
            Canon::SetSurfaceSpeedLaw { spindle, law } if *spindle < 4 => {
                self.surface_speed[*spindle as usize] = *law
            }
            Canon::StartSpindleSync { .. } | Canon::StopSpindleSync => stop(out),
            Canon::SetFeedOverrideEnabled { enabled } => self.override_enabled = *enabled,
            Canon::StartSpindle { spindle, direction } if *spindle < 4 => {
                self.spindle_dir[*spindle as usize] = match direction {
                    stanok_canon::SpindleDirection::Clockwise => 1.0,
                    stanok_canon::SpindleDirection::CounterClockwise => -1.0,
                }
            }
            Canon::StopSpindle { spindle } if *spindle < 4 => {
                self.spindle_dir[*spindle as usize] = 0.0
            }
            Canon::ProgramEnd => {
                // M2/M30 stop the spindles (RS274/NGC §4.5, AxiOMA M30).
                self.spindle_dir = [0.0; 4];
                stop(out)
            }
            Canon::OrientSpindle { spindle, .. } => {
                // M19 turns the spindle to an angle: it no longer turns at speed.
                if let Some(d) = self.spindle_dir.get_mut(*spindle as usize) {
                    *d = 0.0;
                }
                stop(out)
            }
            Canon::ProgramStop { .. }
            | Canon::ChangeTool { .. }
            | Canon::ChangeSpindleTool { .. }
            | Canon::StartToolChange
            | Canon::PalletShuttle
            | Canon::WaitInput { .. }
            | Canon::WaitSpindleOrient { .. } => stop(out),
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::AxisLimit;

    fn adapter() -> CanonAdapter {
        CanonAdapter::new(&MotionConfig::new(
            [AxisLimit::UNLIMITED; 9],
            10_000.0,
            5_000.0,
        ))
    }

    fn collect(a: &mut CanonAdapter, cmds: &[Canon]) -> Vec<PlannerInput> {
        let mut out = Vec::new();
        for c in cmds {
            a.adapt(c, 1, &mut |i| out.push(i));
        }
        out
    }

    fn x(v: f64) -> Pose {
        Pose { x: v, ..Pose::ZERO }
    }

    fn speeds(inputs: &[PlannerInput]) -> Vec<Option<f64>> {
        inputs
            .iter()
            .map(|i| match i {
                PlannerInput::Segment(s) => Some(s.path_speed),
                PlannerInput::Stop { .. } => None,
            })
            .collect()
    }

    #[test]
    fn feeds_are_clamped_overridden_and_spindle_synchronised() {
        let mut a = adapter();
        let feed = |f| {
            Canon::StraightFeed(LineMove {
                start: x(0.0),
                end: x(10.0),
                feed: f,
                law: FeedLaw::PerMinute,
            })
        };
        // 1200 mm/min = 20 mm/s; 9000 is clamped to 5000 = 83.3 mm/s.
        let got = speeds(&collect(
            &mut a,
            &[feed(1200.0), feed(9000.0), feed(f64::NAN)],
        ));
        assert_eq!(got[0], Some(20.0));
        assert!((got[1].unwrap() - 5000.0 / 60.0).abs() < 1e-12);
        assert!((got[2].unwrap() - 5000.0 / 60.0).abs() < 1e-12);
        // The override is not applied here: the class says which one scales the speed.
        let classes = |inputs: &[PlannerInput]| -> Vec<SpeedClass> {
            inputs
                .iter()
                .filter_map(|i| match i {
                    PlannerInput::Segment(s) => Some(s.speed_class),
                    PlannerInput::Stop { .. } => None,
                })
                .collect()
        };
        assert_eq!(
            classes(&collect(&mut a, &[feed(1200.0)])),
            [SpeedClass::Feed]
        );
        let off = Canon::SetFeedOverrideEnabled { enabled: false };
        assert_eq!(
            classes(&collect(&mut a, &[off, feed(1200.0)])),
            [SpeedClass::Fixed]
        );
        a.adapt(
            &Canon::SetFeedOverrideEnabled { enabled: true },
            1,
            &mut |_| {},
        );
        // G33-style sync: pitch 1.5 mm × 600 rpm = 900 mm/min = 15 mm/s, scaled by the spindle
        // override, whatever the move's nominal feed; stops before and after. The move states
        // its law itself.
        let synchronised = Canon::StraightFeed(LineMove {
            start: x(0.0),
            end: x(10.0),
            feed: 100.0,
            law: FeedLaw::SpindleSync {
                pitch: 1.5,
                rpm: 600.0,
            },
        });
        let got = speeds(&collect(
            &mut a,
            &[
                Canon::StartSpindleSync {
                    pitch: 1.5,
                    velocity_mode: false,
                },
                synchronised,
                Canon::StopSpindleSync,
            ],
        ));
        assert_eq!(got, vec![None, Some(15.0), None]);
        // Feed mode and F commands are for printers: they change no speed.
        let got = speeds(&collect(
            &mut a,
            &[
                Canon::SetFeedMode {
                    mode: FeedMode::UnitsPerRevolution,
                },
                Canon::SetFeedRate { feed: 0.1 },
                feed(1200.0),
            ],
        ));
        assert_eq!(got, vec![Some(20.0)]);
    }

    #[test]
    fn modes_are_stamped_and_stops_forced() {
        let mut a = adapter();
        let got = collect(
            &mut a,
            &[
                Canon::SetPathMode {
                    mode: PathMode::ExactStop,
                    naive_cam_tolerance: None,
                },
                Canon::SetAccelerationProfile {
                    profile: AccelerationProfile::Soft,
                },
                Canon::StraightTraverse(LineMove {
                    start: x(0.0),
                    end: x(10.0),
                    feed: 0.0,
                    law: FeedLaw::PerMinute,
                }),
                // Two moves under inverse time (G93): the change of mode stops the path once.
                Canon::StraightTraverse(LineMove {
                    start: x(10.0),
                    end: x(20.0),
                    feed: 0.0,
                    law: FeedLaw::InverseTime,
                }),
                Canon::StraightTraverse(LineMove {
                    start: x(20.0),
                    end: x(30.0),
                    feed: 0.0,
                    law: FeedLaw::InverseTime,
                }),
                Canon::Dwell { seconds: 2.0 },
                Canon::ProgramStop { optional: true },
                Canon::ChangeTool { tool: 3, slot: 3 },
                Canon::ProgramEnd,
            ],
        );
        let PlannerInput::Segment(s) = &got[0] else {
            panic!("{got:?}")
        };
        assert_eq!(
            (s.path_mode, s.profile, s.rapid),
            (PathMode::ExactStop, AccelerationProfile::Soft, true)
        );
        assert!((s.path_speed - 10_000.0 / 60.0).abs() < 1e-12);
        // One stop for the feed-mode change (before the first G93 move, not again for the
        // second), then the dwell, M1, M6, M2.
        assert_eq!(got.len(), 8, "{got:?}");
        assert_eq!(
            got[1],
            PlannerInput::Stop {
                dwell_s: 0.0,
                line: 1
            }
        );
        assert!(matches!(
            got[2..4],
            [PlannerInput::Segment(_), PlannerInput::Segment(_)]
        ));
        assert_eq!(
            got[4],
            PlannerInput::Stop {
                dwell_s: 2.0,
                line: 1
            }
        );
    }
}
