//! Nominal move times: no acceleration, no look-ahead.
//!
//! ```text
//!   speed ^
//!         |   +--------------+        nominal: the move runs at full rate from its first to its
//!         |   |              |        last instant; time = length / rate.
//!         |   |              |        A real profile ramps (acceleration, jerk) and so takes longer:
//!         +---+--------------+--> t   the nominal time is a lower bound.
//! ```
//!
//! Rules (units legend as in Klipper: `_mm` length, `_per_min` rate, `_s` seconds):
//! 1. **Feed move:** t = L / F, with F in mm/min (deg/min for a rotary-only move) → seconds.
//! 2. **Rapid:** the channel's rapid rate applies to the path, reduced so that no axis exceeds its own
//!    maximum velocity: t = max(L / rapid_rate, max_i |Δ_i| / v_max,i). This is the uniform
//!    slow-down of AxiOMA's "the CNC assigns the feed taking limitations into account" (spec
//!    axioma-2 §3.2) and what LinuxCNC does for a traverse.
//! 3. **Dwell:** the given seconds.
//!
//! Invariant: every function returns a finite, non-negative number for finite input, and never NaN
//! or ∞ for any input: a rate of zero (or a negative or NaN one) imposes no time rather than an
//! infinite one — the interpreter rejects F0 moves, and machine data validation rejects zero limits,
//! so a zero here is a caller's bug that must not poison a report.

/// One axis' velocity limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisLimits {
    /// Maximum velocity, mm/min (deg/min for a rotary axis). Zero, negative or NaN: no limit.
    pub max_velocity_per_min: f64,
}

/// Seconds for `length` at `rate` per minute; 0 for a non-positive or non-finite quotient.
fn minutes_to_seconds(length: f64, rate_per_min: f64) -> f64 {
    let t = length.abs() / rate_per_min * 60.0;
    if t.is_finite() && t > 0.0 {
        t
    } else {
        0.0
    }
}

/// Rule 1: seconds for a feed move of `path_length_mm` at `feed_per_min` (mm/min).
pub fn feed_time(path_length_mm: f64, feed_per_min: f64) -> f64 {
    minutes_to_seconds(path_length_mm, feed_per_min)
}

/// Rule 2: seconds for a rapid of `path_length_mm` at `rapid_rate_per_min` (mm/min), slowed down so
/// that axis i moving `deltas[i]` (mm or deg) stays within `limits[i]`. `deltas` and `limits` are
/// paired by index; extra entries of the longer one are ignored.
pub fn rapid_time(
    path_length_mm: f64,
    deltas: &[f64],
    rapid_rate_per_min: f64,
    limits: &[AxisLimits],
) -> f64 {
    deltas
        .iter()
        .zip(limits)
        .map(|(d, l)| minutes_to_seconds(*d, l.max_velocity_per_min))
        .fold(
            minutes_to_seconds(path_length_mm, rapid_rate_per_min),
            f64::max,
        )
}

/// Rule 3: seconds of a dwell (negative or NaN counts as 0).
pub fn dwell_time(seconds: f64) -> f64 {
    if seconds.is_finite() && seconds > 0.0 {
        seconds
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(v: &[f64]) -> Vec<AxisLimits> {
        v.iter()
            .map(|&max_velocity_per_min| AxisLimits {
                max_velocity_per_min,
            })
            .collect()
    }

    #[test]
    fn feed_is_length_over_rate() {
        assert_eq!(feed_time(50.0, 1000.0), 3.0);
        // A quarter circle of r = 10 (5π mm) at 600 mm/min: π/2 s.
        let t = feed_time(5.0 * std::f64::consts::PI, 600.0);
        assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-15, "{t}");
        // Rotary-only: 90° at 1800 deg/min.
        assert_eq!(feed_time(90.0, 1800.0), 3.0);
    }

    #[test]
    fn zero_or_bad_rates_give_no_time_not_infinity() {
        assert_eq!(feed_time(50.0, 0.0), 0.0);
        assert_eq!(feed_time(50.0, -10.0), 0.0);
        assert_eq!(feed_time(f64::NAN, 100.0), 0.0);
        assert_eq!(feed_time(0.0, 0.0), 0.0);
        assert_eq!(dwell_time(-1.0), 0.0);
        assert_eq!(dwell_time(f64::INFINITY), 0.0);
        assert_eq!(dwell_time(2.5), 2.5);
        assert_eq!(rapid_time(10.0, &[10.0], 0.0, &limits(&[0.0])), 0.0);
    }

    #[test]
    fn rapid_is_slowed_by_the_slowest_axis() {
        // 100 mm along X at 10 000 mm/min: 0.6 s; X allows 12 000 mm/min → the rapid rate rules.
        let l = limits(&[12_000.0, 12_000.0, 6_000.0]);
        assert_eq!(rapid_time(100.0, &[100.0, 0.0, 0.0], 10_000.0, &l), 0.6);
        // 100 mm straight down Z, which allows only 6 000 mm/min: 1 s.
        assert_eq!(rapid_time(100.0, &[0.0, 0.0, -100.0], 10_000.0, &l), 1.0);
        // Diagonal (60, 0, 80): length 100 → 0.6 s by rate; Z needs 80/6000 min = 0.8 s.
        let t = rapid_time(100.0, &[60.0, 0.0, 80.0], 10_000.0, &l);
        assert!((t - 0.8).abs() < 1e-12, "{t}");
        // A rotary-only rapid: no path length, 180° at 3600 deg/min → 3 s.
        let t = rapid_time(
            0.0,
            &[0.0, 0.0, 0.0, 180.0],
            10_000.0,
            &limits(&[1e4, 1e4, 1e4, 3600.0]),
        );
        assert_eq!(t, 3.0);
    }
}
