//! Drilling, tapping and boring cycles as sequences along the drilling axis
//! (`docs/dialects/mazatrol-eia.md` §10, §11.8): the M-series G73, G74, G76, G81–G89 and the
//! T-series face/side forms G83–G85, G87–G89.
//!
//! One hole is a list of [`HoleStep`]s on one coordinate, the drilling axis (program coordinates
//! of that axis); the front end positions the plane axes first (a rapid at the current level) and
//! maps each step to a pose. `dir` = the sign of (Z − R): −1 for the usual downward hole.
//!
//! Sequences (d = the peck clearance, ret = the initial level under G98, R under G99):
//! ```text
//!   G81  R↓ Z~ ret↑            G82  R↓ Z~ P ret↑           G85  R↓ Z~ R~ (initial↑ under G98)
//!   G73  R↓ {Z_i~ (Z_i − d)↑} Z~ ret↑                       (pecks of Q, back by d)
//!   G83  R↓ {Z_i~ R↑ (Z_i − d)↓} Z~ ret↑                    (pecks of Q, out to R each time)
//!   G84  R↓ Z~ P rev R~ fwd (initial↑)      G74: the same with the spindle reversed
//!   G76  R↓ Z~ P orient shift ret↑ unshift fwd
//!   G86  R↓ Z~ stop ret↑ fwd                G88  R↓ Z~ P stop program-stop ret↑ fwd
//!   G87  orient shift R↓ unshift fwd Z~ orient shift initial↑ unshift fwd   (R below the part)
//!   G89  R↓ Z~ P R~ (initial↑)
//! ```
//! (↓↑ rapid, ~ feed.) *Invariant:* every sequence ends at the return level with the spindle
//! turning as it did before the hole.

use crate::turning::{CycleError, MAX_PASSES};

/// One step of a hole.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HoleStep {
    /// Rapid along the drilling axis to this level.
    Rapid(f64),
    /// Feed along the drilling axis to this level.
    Feed(f64),
    /// Dwell, seconds.
    Dwell(f64),
    /// Spindle reversed (tapping at the bottom).
    Reverse,
    /// Spindle back to its direction before the hole.
    Restore,
    /// Spindle stopped.
    Stop,
    /// Spindle oriented (M19).
    Orient,
    /// Rapid shift in the plane by this signed amount along the shift direction (G76, G87).
    Shift(f64),
    /// The operator's stop (G88's manual retract).
    ProgramStop,
    /// Rigid tapping (M29): down to the level and back to the start at the pitch.
    RigidTap(f64),
}

/// The words of one hole.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hole {
    /// The initial level (where the cycle mode was entered).
    pub initial: f64,
    /// The R level.
    pub r: f64,
    /// The bottom.
    pub z: f64,
    /// Q: peck depth (G73, G83) or shift (G76, G87); 0 when absent.
    pub q: f64,
    /// Dwell at the bottom, seconds (P).
    pub dwell: f64,
    /// The peck clearance d (machine data).
    pub clearance: f64,
    /// G98 (true) or G99.
    pub to_initial: bool,
    /// M29 rigid tapping is in force.
    pub rigid: bool,
}

/// The kinds of hole sequences.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// G81: drill.
    Drill,
    /// G82: drill, dwell.
    DrillDwell,
    /// G73: high-speed peck (back by d).
    PeckHighSpeed,
    /// G83: deep peck (out to R).
    PeckDeep,
    /// G84: tap (right hand).
    Tap,
    /// G74 (M): tap, left hand — the same sequence.
    TapLeft,
    /// G76 (M): fine boring.
    FineBore,
    /// G85: bore, feed out.
    Bore,
    /// G86: bore, spindle stop, rapid out.
    BoreStop,
    /// G87 (M): back boring.
    BackBore,
    /// G88: bore, dwell, manual retract.
    BoreManual,
    /// G89: bore, dwell, feed out.
    BoreDwell,
}

impl Kind {
    /// The M-series cycle of a G code × 10.
    pub fn m_series(code: u32) -> Option<Kind> {
        Some(match code {
            730 => Kind::PeckHighSpeed,
            740 => Kind::TapLeft,
            760 => Kind::FineBore,
            810 => Kind::Drill,
            820 => Kind::DrillDwell,
            830 => Kind::PeckDeep,
            840 => Kind::Tap,
            850 => Kind::Bore,
            860 => Kind::BoreStop,
            870 => Kind::BackBore,
            880 => Kind::BoreManual,
            890 => Kind::BoreDwell,
            _ => return None,
        })
    }

    /// The T-series face (G83–G85) or side (G87–G89) cycle: (kind, along X).
    pub fn t_series(code: u32, q: f64) -> Option<(Kind, bool)> {
        let drill = if q > 0.0 {
            Kind::PeckDeep
        } else {
            Kind::DrillDwell
        };
        Some(match code {
            830 => (drill, false),
            840 => (Kind::Tap, false),
            850 => (Kind::BoreDwell, false),
            870 => (drill, true),
            880 => (Kind::Tap, true),
            890 => (Kind::BoreDwell, true),
            _ => return None,
        })
    }
}

fn err<T>(m: impl Into<String>) -> Result<T, CycleError> {
    Err(CycleError(m.into()))
}

/// The levels of the pecks: Q, 2Q, … up to the depth, from R in the direction of Z.
fn pecks(h: &Hole, name: &str) -> Result<Vec<f64>, CycleError> {
    if h.q.is_nan() || h.q <= 0.0 {
        return err(format!("{name} needs a positive peck depth Q"));
    }
    let depth = (h.z - h.r).abs();
    let n = (depth / h.q - 1e-9).ceil().max(1.0);
    if n > MAX_PASSES as f64 {
        return err(format!("{name}: more than {MAX_PASSES} pecks"));
    }
    let dir = (h.z - h.r).signum();
    Ok((1..=n as usize)
        .map(|i| {
            if i == n as usize {
                h.z
            } else {
                h.r + dir * h.q * i as f64
            }
        })
        .collect())
}

/// The steps of one hole. `name` is the code for messages ("G83").
pub fn hole(kind: Kind, h: &Hole, name: &str) -> Result<Vec<HoleStep>, CycleError> {
    use HoleStep::*;
    let ret = if h.to_initial { h.initial } else { h.r };
    let dir = (h.z - h.r).signum();
    let mut s = Vec::new();
    match kind {
        Kind::Drill | Kind::DrillDwell => {
            s.extend([Rapid(h.r), Feed(h.z)]);
            if kind == Kind::DrillDwell && h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.push(Rapid(ret));
        }
        Kind::PeckHighSpeed => {
            s.push(Rapid(h.r));
            let levels = pecks(h, name)?;
            for (i, &l) in levels.iter().enumerate() {
                s.push(Feed(l));
                if i + 1 < levels.len() {
                    s.push(Rapid(l - dir * h.clearance));
                }
            }
            if h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.push(Rapid(ret));
        }
        Kind::PeckDeep => {
            s.push(Rapid(h.r));
            let levels = pecks(h, name)?;
            let mut last = None;
            for &l in &levels {
                if let Some(prev) = last {
                    s.push(Rapid(h.r));
                    s.push(Rapid(prev - dir * h.clearance));
                }
                s.push(Feed(l));
                last = Some(l);
            }
            if h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.push(Rapid(ret));
        }
        Kind::Tap | Kind::TapLeft => {
            s.push(Rapid(h.r));
            if h.rigid {
                s.push(RigidTap(h.z));
            } else {
                s.push(Feed(h.z));
                if h.dwell > 0.0 {
                    s.push(Dwell(h.dwell));
                }
                s.extend([Reverse, Feed(h.r), Restore]);
            }
            if h.to_initial {
                s.push(Rapid(h.initial));
            }
        }
        Kind::FineBore => {
            s.extend([Rapid(h.r), Feed(h.z)]);
            if h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.extend([Orient, Shift(-h.q), Rapid(ret), Shift(h.q), Restore]);
        }
        Kind::Bore | Kind::BoreDwell => {
            s.extend([Rapid(h.r), Feed(h.z)]);
            if kind == Kind::BoreDwell && h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.push(Feed(h.r));
            if h.to_initial {
                s.push(Rapid(h.initial));
            }
        }
        Kind::BoreStop => {
            s.extend([Rapid(h.r), Feed(h.z), Stop, Rapid(ret), Restore]);
        }
        Kind::BackBore => {
            if !h.to_initial {
                return err(format!(
                    "{name} returns to the initial level only: G99 is not allowed"
                ));
            }
            s.extend([
                Orient,
                Shift(-h.q),
                Rapid(h.r),
                Shift(h.q),
                Restore,
                Feed(h.z),
            ]);
            if h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.extend([Orient, Shift(-h.q), Rapid(h.initial), Shift(h.q), Restore]);
        }
        Kind::BoreManual => {
            s.extend([Rapid(h.r), Feed(h.z)]);
            if h.dwell > 0.0 {
                s.push(Dwell(h.dwell));
            }
            s.extend([Stop, ProgramStop, Rapid(ret), Restore]);
        }
    }
    Ok(s)
}

/// Feed length of a hole (rigid taps count down and up).
pub fn feed_length(start: f64, steps: &[HoleStep]) -> f64 {
    let mut at = start;
    let mut total = 0.0;
    for s in steps {
        match *s {
            HoleStep::Rapid(l) => at = l,
            HoleStep::Feed(l) => {
                total += (l - at).abs();
                at = l;
            }
            HoleStep::RigidTap(l) => total += 2.0 * (l - at).abs(),
            _ => {}
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::HoleStep::*;
    use super::*;

    fn words() -> Hole {
        Hole {
            initial: 20.0,
            r: 3.0,
            z: -10.0,
            q: 4.0,
            dwell: 0.5,
            clearance: 1.0,
            to_initial: false,
            rigid: false,
        }
    }

    #[test]
    fn g81_of_the_example_job() {
        let s = hole(Kind::Drill, &words(), "G81").unwrap();
        assert_eq!(s, vec![Rapid(3.0), Feed(-10.0), Rapid(3.0)]);
        assert_eq!(feed_length(20.0, &s), 13.0);
        let g98 = Hole {
            to_initial: true,
            ..words()
        };
        assert_eq!(hole(Kind::Drill, &g98, "G81").unwrap()[2], Rapid(20.0));
    }

    #[test]
    fn pecks() {
        // G73: 3 → -1 → back to 0 → -5 → back to -4 → -9 → back to -8 → -10.
        let s = hole(
            Kind::PeckHighSpeed,
            &Hole {
                dwell: 0.0,
                ..words()
            },
            "G73",
        )
        .unwrap();
        assert_eq!(
            s,
            vec![
                Rapid(3.0),
                Feed(-1.0),
                Rapid(0.0),
                Feed(-5.0),
                Rapid(-4.0),
                Feed(-9.0),
                Rapid(-8.0),
                Feed(-10.0),
                Rapid(3.0)
            ]
        );
        // G73's feed: 4 + 5 + 5 + 2 = 16 (each re-feed starts d above the last depth).
        assert_eq!(feed_length(20.0, &s), 16.0);
        // G83: out to R after each peck, back to d above the last depth.
        let s = hole(
            Kind::PeckDeep,
            &Hole {
                dwell: 0.0,
                ..words()
            },
            "G83",
        )
        .unwrap();
        assert_eq!(
            s,
            vec![
                Rapid(3.0),
                Feed(-1.0),
                Rapid(3.0),
                Rapid(0.0),
                Feed(-5.0),
                Rapid(3.0),
                Rapid(-4.0),
                Feed(-9.0),
                Rapid(3.0),
                Rapid(-8.0),
                Feed(-10.0),
                Rapid(3.0)
            ]
        );
        assert_eq!(feed_length(20.0, &s), 16.0);
        assert!(hole(Kind::PeckDeep, &Hole { q: 0.0, ..words() }, "G83").is_err());
    }

    #[test]
    fn tapping_and_boring() {
        let s = hole(Kind::Tap, &words(), "G84").unwrap();
        assert_eq!(
            s,
            vec![
                Rapid(3.0),
                Feed(-10.0),
                Dwell(0.5),
                Reverse,
                Feed(3.0),
                Restore
            ]
        );
        let rigid = hole(
            Kind::Tap,
            &Hole {
                rigid: true,
                ..words()
            },
            "G84",
        )
        .unwrap();
        assert_eq!(rigid, vec![Rapid(3.0), RigidTap(-10.0)]);
        let s = hole(Kind::FineBore, &Hole { q: 0.2, ..words() }, "G76").unwrap();
        assert_eq!(
            s,
            vec![
                Rapid(3.0),
                Feed(-10.0),
                Dwell(0.5),
                Orient,
                Shift(-0.2),
                Rapid(3.0),
                Shift(0.2),
                Restore
            ]
        );
        let s = hole(Kind::BoreStop, &words(), "G86").unwrap();
        assert_eq!(s, vec![Rapid(3.0), Feed(-10.0), Stop, Rapid(3.0), Restore]);
        let s = hole(Kind::BoreManual, &words(), "G88").unwrap();
        assert!(s.contains(&ProgramStop));
        let s = hole(
            Kind::BoreDwell,
            &Hole {
                to_initial: true,
                ..words()
            },
            "G89",
        )
        .unwrap();
        assert_eq!(
            s,
            vec![Rapid(3.0), Feed(-10.0), Dwell(0.5), Feed(3.0), Rapid(20.0)]
        );
        // G87: R below the part, boring upwards to Z.
        let back = Hole {
            r: -30.0,
            z: -10.0,
            q: 0.5,
            to_initial: true,
            dwell: 0.0,
            ..words()
        };
        let s = hole(Kind::BackBore, &back, "G87").unwrap();
        assert_eq!(s[2], Rapid(-30.0));
        assert_eq!(s[5], Feed(-10.0));
        assert_eq!(*s.last().unwrap(), Restore);
        assert!(hole(
            Kind::BackBore,
            &Hole {
                to_initial: false,
                ..back
            },
            "G87"
        )
        .is_err());
    }

    #[test]
    fn codes_map_to_kinds() {
        assert_eq!(Kind::m_series(810), Some(Kind::Drill));
        assert_eq!(Kind::m_series(800), None);
        assert_eq!(Kind::t_series(830, 2.0), Some((Kind::PeckDeep, false)));
        assert_eq!(Kind::t_series(830, 0.0), Some((Kind::DrillDwell, false)));
        assert_eq!(Kind::t_series(870, 0.0), Some((Kind::DrillDwell, true)));
    }
}
