//! Every motion leaves the interpreter with its feed law (`stanok_canon::FeedLaw`), so that the
//! motion stage times it from the command alone.
//!
//! The front ends state their feed modes as commands, in the order a control would act on them:
//! `SetFeedMode` (G93/G94/G95), `SetFeedRate` (F: mm/min, or mm/rev under G95), `SetSpindleSpeed`
//! of the main spindle, `SetSurfaceSpeedLaw` of the main spindle (G96), and
//! `StartSpindleSync`/`StopSpindleSync` around synchronised moves. [`FeedLaws`] reads them as the
//! driver releases the stream and completes each motion (and rapid, and probe, and rigid tap) with
//! the law they put in force *at its place in the stream*:
//!
//! ```text
//!  in sync (pitch p)            → SpindleSync { p, rpm }
//!  G94                          → PerMinute
//!  G93                          → InverseTime            (feed already holds length × F)
//!  G95, no G96 law              → PerRevolution { F, rpm }
//!  G95 with the main spindle's G96 law L → SurfaceSpeed { F, L }
//! ```
//!
//! Stamping at release, not at emission, is what makes it right for a front end that inserts
//! motions among commands of later blocks (AxiOMA's compensation look-ahead): a motion gets the
//! law of its place, whatever the front end's state was when it computed the motion. The motion
//! stage once kept this same state itself; it now reads only the moves.

use stanok_canon::{Canon, FeedLaw, FeedMode, SurfaceSpeedLaw};

/// The feed modes the released stream has stated so far (module doc).
#[derive(Debug, Clone)]
pub struct FeedLaws {
    mode: FeedMode,
    /// The last F: mm/min, or mm/rev under G95.
    feed: f64,
    /// The main spindle's last commanded speed, rev/min.
    rpm: f64,
    /// The main spindle's G96 law, while in force.
    surface: Option<SurfaceSpeedLaw>,
    /// The pitch while spindle-synchronised, mm/rev.
    pitch: Option<f64>,
}

impl Default for FeedLaws {
    fn default() -> Self {
        FeedLaws {
            mode: FeedMode::UnitsPerMinute,
            feed: 0.0,
            rpm: 0.0,
            surface: None,
            pitch: None,
        }
    }
}

impl FeedLaws {
    /// The law in force now.
    #[inline(always)]
    pub fn law(&self) -> FeedLaw {
        if let Some(pitch) = self.pitch {
            return FeedLaw::SpindleSync {
                pitch,
                rpm: self.rpm,
            };
        }
        match self.mode {
            FeedMode::UnitsPerMinute => FeedLaw::PerMinute,
            FeedMode::InverseTime => FeedLaw::InverseTime,
            FeedMode::UnitsPerRevolution => match self.surface {
                Some(law) => FeedLaw::SurfaceSpeed {
                    mm_per_rev: self.feed,
                    law: Box::new(law),
                },
                None => FeedLaw::PerRevolution {
                    mm_per_rev: self.feed,
                    rpm: self.rpm,
                },
            },
        }
    }

    /// Completes `c` with the law in force, or takes the mode it states.
    #[inline(always)]
    pub fn stamp(&mut self, c: &mut Canon) {
        match c {
            Canon::StraightFeed(m) | Canon::StraightTraverse(m) => m.law = self.law(),
            Canon::ArcFeed(a) => a.law = self.law(),
            _ => self.stamp_other(c),
        }
    }

    #[inline(never)]
    fn stamp_other(&mut self, c: &mut Canon) {
        match c {
            Canon::SplineFeed(s) => s.law = self.law(),
            Canon::StraightProbe { motion, .. } => motion.law = self.law(),
            Canon::RigidTap { law, .. } => *law = self.law(),
            Canon::SetFeedMode { mode } => self.mode = *mode,
            Canon::SetFeedRate { feed } => self.feed = *feed,
            Canon::SetSpindleSpeed { spindle: 0, rpm } => self.rpm = rpm.abs(),
            Canon::SetSurfaceSpeedLaw { spindle: 0, law } => self.surface = *law,
            Canon::StartSpindleSync { pitch, .. } => self.pitch = Some(pitch.abs()),
            Canon::StopSpindleSync => self.pitch = None,
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::{LineMove, Pose};

    fn feed_move() -> Canon {
        Canon::StraightFeed(LineMove {
            start: Pose::ZERO,
            end: Pose::ZERO,
            feed: 0.0,
            law: FeedLaw::PerMinute,
        })
    }

    fn law_of(laws: &mut FeedLaws, cmds: &[Canon]) -> FeedLaw {
        for c in cmds {
            laws.stamp(&mut c.clone());
        }
        let mut m = feed_move();
        laws.stamp(&mut m);
        match m {
            Canon::StraightFeed(m) => m.law,
            _ => unreachable!(),
        }
    }

    #[test]
    fn each_mode_gives_its_law() {
        let mut l = FeedLaws::default();
        assert_eq!(law_of(&mut l, &[]), FeedLaw::PerMinute);
        let g95 = [
            Canon::SetFeedMode {
                mode: FeedMode::UnitsPerRevolution,
            },
            Canon::SetFeedRate { feed: 0.2 },
            Canon::SetSpindleSpeed {
                spindle: 0,
                rpm: -500.0,
            },
        ];
        assert_eq!(
            law_of(&mut l, &g95),
            FeedLaw::PerRevolution {
                mm_per_rev: 0.2,
                rpm: 500.0
            }
        );
        let law = SurfaceSpeedLaw {
            mm_per_min: 100_000.0,
            axis: 0,
            centre: 0.0,
            min_rpm: 0.0,
            max_rpm: 2000.0,
        };
        let g96 = [Canon::SetSurfaceSpeedLaw {
            spindle: 0,
            law: Some(law),
        }];
        assert_eq!(
            law_of(&mut l, &g96),
            FeedLaw::SurfaceSpeed {
                mm_per_rev: 0.2,
                law: Box::new(law)
            }
        );
        // A law of another spindle does not change the main spindle's.
        let other = [Canon::SetSurfaceSpeedLaw {
            spindle: 1,
            law: None,
        }];
        assert!(matches!(
            law_of(&mut l, &other),
            FeedLaw::SurfaceSpeed { .. }
        ));
        let sync = [Canon::StartSpindleSync {
            pitch: -1.5,
            velocity_mode: false,
        }];
        assert_eq!(
            law_of(&mut l, &sync),
            FeedLaw::SpindleSync {
                pitch: 1.5,
                rpm: 500.0
            }
        );
        let back = [
            Canon::StopSpindleSync,
            Canon::SetFeedMode {
                mode: FeedMode::InverseTime,
            },
        ];
        assert_eq!(law_of(&mut l, &back), FeedLaw::InverseTime);
    }
}
