//! AxiOMA technology words (spec axioma-2 §3): FTABLE/STABLE, S and S<i>= per spindle, G96/G97
//! constant surface speed with LMAXS/LMINS/REFAX, G60/G64 and BRISK/SOFT as Canon modes, and the
//! kinematic length that F refers to (§3.2).
//!
//! Constant surface speed (§3.6, PROPOSAL formula):
//!
//! ```text
//!   n = clamp( V / (2π·r), LMINS, LMAXS )      V = S·1000 mm/min (G71: m/min) or S·304.8 (G70: ft/min)
//!   r = |program coordinate of the REFAX axis|  (1-based channel axis, default 1 = X; work
//!                                                coordinates: "G96 takes the offset into account")
//!   r → 0: n = LMAXS (no LMAXS: the speed stays)
//! ```
//!
//! The interpreter resolves CSS itself, block by block: the spindle speed is recomputed when G96,
//! S or a limit is programmed and after every block's motion at the tool's new position, and goes
//! out as `Canon::SetSpindleSpeed` in rev/min (so G95 feeds and every consumer keep reading rpm).
//! Those steps are what the control's screen shows at block ends. The speed the spindle really
//! turns at is the law itself: whenever it changes (G96/G97, S, LMAXS/LMINS/REFAX, or the work zero
//! of the REFAX axis moving with the offsets) it goes out as `Canon::SetSurfaceSpeedLaw`, with the
//! REFAX axis' work zero as the centre line in machine coordinates, and the planner and the
//! simulated machine evaluate it at every point of the path (`stanok_motion::css`).

use crate::ctx::Ctx;
use crate::words::Val;
use stanok_canon::{Canon, Diagnostic, LengthUnits, Pose, SurfaceSpeedLaw};
use stanok_syntax::{ColSpan, Keyword};

/// G96 state of one spindle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceSpeed {
    /// Cutting speed as programmed (m/min under G71, ft/min under G70); None = not programmed.
    pub speed: Option<f64>,
    /// Speed in mm/min.
    pub mm_per_min: f64,
    /// LMAXS, rev/min.
    pub max_rpm: Option<f64>,
    /// LMINS, rev/min.
    pub min_rpm: Option<f64>,
    /// REFAX: 1-based channel axis whose coordinate is the radius (0 = default X).
    pub reference_axis: u8,
}

/// The AxiOMA technology state that `ModalState` does not hold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Technology {
    /// The start-up modes of the machine parameters were applied (first block).
    pub powered_on: bool,
    /// G96 active.
    pub css: bool,
    /// Per spindle.
    pub spindles: [SurfaceSpeed; 4],
    /// The law last sent per spindle as `Canon::SetSurfaceSpeedLaw` (see `publish_laws`).
    pub laws: [Option<SurfaceSpeedLaw>; 4],
}

/// The default tables of §3.1/§3.7: the manual prints entries 0…3 and 127 only; the others are
/// interpolated linearly between entry 3 and 127 (Stanok's choice, A21: configure the real table).
pub fn default_table(first: [f64; 4], last: f64) -> Vec<f64> {
    (0..128)
        .map(|i| {
            if i < 4 {
                first[i]
            } else {
                first[3] + (last - first[3]) * (i as f64 - 3.0) / 124.0
            }
        })
        .collect()
}

/// `FTABLE(i)` / `STABLE(i)`: entry i of a channel table (index 0…127, A: outside → error).
fn table_value(
    cx: &Ctx<'_>,
    table: &[f64],
    name: &str,
    index: Val,
    at: ColSpan,
) -> Result<f64, Diagnostic> {
    let i = index.v;
    if i.fract() != 0.0 || !(0.0..128.0).contains(&i) || i as usize >= table.len() {
        return Err(cx.err(
            "axioma::table-index",
            format!("{name}({i}): the table index is 0 … 127"),
            at,
        ));
    }
    Ok(table[i as usize])
}

/// Technology keyword words of one block, resolved.
#[derive(Debug, Default)]
pub(super) struct TechWords {
    /// `F=FTABLE(i)`.
    pub feed: Option<Val>,
    /// `S=STABLE(i)` (index 0) and `S<i>=STABLE(j)`.
    pub speed: [Option<Val>; 4],
    /// LMAXS / LMINS / REFAX per spindle.
    pub max_rpm: [Option<Val>; 4],
    pub min_rpm: [Option<Val>; 4],
    pub reference_axis: [Option<Val>; 4],
}

impl TechWords {
    /// True if the keyword belongs here.
    pub fn handles(kw: Keyword) -> bool {
        matches!(
            kw,
            Keyword::Ftable | Keyword::Stable | Keyword::Lmaxs | Keyword::Lmins | Keyword::Refax
        )
    }

    /// Takes one keyword word (`handles` was true).
    pub fn take(
        &mut self,
        cx: &Ctx<'_>,
        kw: Keyword,
        index: Option<u8>,
        val: Option<Val>,
        at: ColSpan,
    ) -> Result<(), Diagnostic> {
        let Some(val) = val else {
            return Err(cx.err("interp::missing-value", "the word has no value", at));
        };
        let spindle = match index {
            None | Some(1) => 0usize,
            Some(i @ 2..=4) => i as usize - 1,
            Some(i) => {
                return Err(cx.err(
                    "axioma::spindle-index",
                    format!("spindle index {i}: a channel has spindles 1 … 4"),
                    at,
                ))
            }
        };
        let p = &cx.fe.params;
        match kw {
            Keyword::Ftable => {
                let v = table_value(cx, &p.feed_table, "FTABLE", val, at)?;
                self.feed = Some(Val { v, span: at });
            }
            Keyword::Stable => {
                let v = table_value(cx, &p.speed_table, "STABLE", val, at)?;
                self.speed[spindle] = Some(Val { v, span: at });
            }
            Keyword::Lmaxs => self.max_rpm[spindle] = Some(val),
            Keyword::Lmins => self.min_rpm[spindle] = Some(val),
            _ => self.reference_axis[spindle] = Some(val),
        }
        Ok(())
    }
}

/// Stores the G96 limits of a block (they may stand in any block, §3.6).
pub(super) fn limits(cx: &mut Ctx<'_>, w: &TechWords) -> Result<(), Diagnostic> {
    for s in 0..4 {
        for (v, what) in [(w.max_rpm[s], "LMAXS"), (w.min_rpm[s], "LMINS")] {
            if let Some(v) = v {
                if v.v < 0.0 {
                    return Err(cx.err(
                        "axioma::css-limit",
                        format!("{what} {}: a speed limit cannot be negative", v.v),
                        v.span,
                    ));
                }
            }
        }
        let sp = &mut cx.fe.tech.spindles[s];
        if let Some(v) = w.max_rpm[s] {
            sp.max_rpm = Some(v.v);
        }
        if let Some(v) = w.min_rpm[s] {
            sp.min_rpm = Some(v.v);
        }
        if let (Some(lo), Some(hi)) = (sp.min_rpm, sp.max_rpm) {
            if lo > hi {
                let at = w.min_rpm[s].or(w.max_rpm[s]).map(|v| v.span);
                return Err(cx.err(
                    "axioma::css-limit",
                    format!("LMINS {lo} is above LMAXS {hi}"),
                    at.unwrap_or_else(|| cx.whole()),
                ));
            }
        }
        if let Some(v) = w.reference_axis[s] {
            if v.v.fract() != 0.0 || !(1.0..=9.0).contains(&v.v) {
                return Err(cx.err(
                    "axioma::css-reference-axis",
                    format!(
                        "REFAX {}: the reference axis is a channel axis number 1 … 9",
                        v.v
                    ),
                    v.span,
                ));
            }
            cx.fe.tech.spindles[s].reference_axis = v.v as u8;
        }
    }
    Ok(())
}

/// G96 (true) / G97 (false).
pub(super) fn css_mode(cx: &mut Ctx<'_>, on: bool) {
    cx.fe.tech.css = on;
}

/// An S word of spindle `spindle`: rev/min, or the cutting speed under G96.
pub(super) fn speed_word(cx: &mut Ctx<'_>, spindle: u8, v: Val) -> Result<(), Diagnostic> {
    if v.v < 0.0 {
        return Err(cx.err("axioma::negative-speed", "negative spindle speed S", v.span));
    }
    let s = spindle as usize;
    if cx.fe.tech.css {
        let factor = match cx.st.units {
            LengthUnits::Millimetres => 1000.0,
            LengthUnits::Inches => 304.8,
        };
        let sp = &mut cx.fe.tech.spindles[s];
        sp.speed = Some(v.v);
        sp.mm_per_min = v.v * factor;
        refresh_spindle(cx, spindle);
        return Ok(());
    }
    cx.st.spindle_speed[s] = v.v;
    cx.out.push(Canon::SetSpindleSpeed { spindle, rpm: v.v });
    Ok(())
}

/// The CSS law of the block comment: rev/min for a cutting speed (mm/min) at radius r (mm).
pub fn css_rpm(
    mm_per_min: f64,
    radius: f64,
    min_rpm: Option<f64>,
    max_rpm: Option<f64>,
) -> Option<f64> {
    let raw = if radius.abs() < 1e-9 {
        max_rpm?
    } else {
        mm_per_min / (2.0 * std::f64::consts::PI * radius.abs())
    };
    let hi = max_rpm.unwrap_or(f64::INFINITY);
    let lo = min_rpm.unwrap_or(0.0).min(hi);
    Some(raw.clamp(lo, hi))
}

fn refresh_spindle(cx: &mut Ctx<'_>, spindle: u8) {
    let s = spindle as usize;
    let sp = cx.fe.tech.spindles[s];
    if sp.speed.is_none() {
        return;
    }
    let axis = (sp.reference_axis.max(1) - 1) as usize;
    let radius = cx.st.program_position().to_array()[axis.min(8)];
    if let Some(rpm) = css_rpm(sp.mm_per_min, radius, sp.min_rpm, sp.max_rpm) {
        if (rpm - cx.st.spindle_speed[s]).abs() > 1e-9 {
            cx.st.spindle_speed[s] = rpm;
            cx.out.push(Canon::SetSpindleSpeed { spindle, rpm });
        }
    }
}

/// Under G96: every spindle with a cutting speed follows the tool's position (after the block's
/// motion, and when G96 or a limit was programmed).
pub(super) fn refresh(cx: &mut Ctx<'_>) {
    if cx.fe.tech.css {
        for spindle in 0..4u8 {
            refresh_spindle(cx, spindle);
        }
    }
    if cx.fe.tech.css || cx.fe.tech.laws.iter().any(Option::is_some) {
        publish_laws(cx);
    }
}

/// Sends each spindle's G96 law (module doc) when it differs from the one last sent: `None` under
/// G97 or before a cutting speed was programmed for that spindle.
fn publish_laws(cx: &mut Ctx<'_>) {
    for spindle in 0..4usize {
        let sp = cx.fe.tech.spindles[spindle];
        let law = match (cx.fe.tech.css, sp.speed) {
            (true, Some(_)) => {
                let axis = (sp.reference_axis.max(1) - 1).min(8);
                let mut zero = cx.st.program_position().to_array();
                zero[axis as usize] = 0.0;
                let centre =
                    cx.st.frame.to_machine(&Pose::from_array(zero)).to_array()[axis as usize];
                Some(SurfaceSpeedLaw {
                    mm_per_min: sp.mm_per_min,
                    axis,
                    centre,
                    min_rpm: sp.min_rpm.unwrap_or(0.0),
                    max_rpm: sp.max_rpm.unwrap_or(0.0),
                })
            }
            _ => None,
        };
        if law != cx.fe.tech.laws[spindle] {
            cx.fe.tech.laws[spindle] = law;
            cx.out.push(Canon::SetSurfaceSpeedLaw {
                spindle: spindle as u8,
                law,
            });
        }
    }
}

/// G96 without a cutting speed for the main spindle and none before: error (PROPOSAL §3.6).
pub(super) fn check_css_speed(cx: &Ctx<'_>, at: ColSpan) -> Result<(), Diagnostic> {
    if cx.fe.tech.spindles.iter().all(|s| s.speed.is_none()) {
        return Err(cx
            .err(
                "axioma::css-without-speed",
                "G96 needs the cutting speed S (m/min) the first time it is programmed",
                at,
            )
            .with_note("example: G96 S300 LMAXS 5000 LMINS 150 REFAX 1"));
    }
    Ok(())
}

/// The length F refers to (§3.2): the spatial distance if X/Y/Z move; else the Euclidean norm of
/// the rotary axes (degrees); else the norm of all axes.
pub(super) fn feed_length(start: &[f64; 9], end: &[f64; 9]) -> f64 {
    let norm = |axes: &[usize]| {
        axes.iter()
            .map(|&k| (end[k] - start[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let spatial = norm(&[0, 1, 2]);
    if spatial > 1e-12 {
        return spatial;
    }
    let rotary = norm(&[3, 4, 5]);
    if rotary > 1e-12 {
        return rotary;
    }
    norm(&[0, 1, 2, 3, 4, 5, 6, 7, 8])
}

/// Before the first block: the start-up G60/G64 and BRISK/SOFT of the machine parameters, sent
/// to the planner only where they differ from the power-on G64/BRISK every consumer assumes.
pub(super) fn power_on(cx: &mut Ctx<'_>) {
    if cx.fe.tech.powered_on {
        return;
    }
    cx.fe.tech.powered_on = true;
    let p = &cx.fe.params;
    let (exact, soft) = (p.start_exact_stop, p.start_soft);
    if exact {
        cx.st.path_mode = crate::state::PathMode::ExactStop;
        cx.out.push(Canon::SetPathMode {
            mode: stanok_canon::PathMode::ExactStop,
            naive_cam_tolerance: None,
        });
    }
    if soft {
        cx.st.soft_acceleration = true;
        cx.out.push(Canon::SetAccelerationProfile {
            profile: stanok_canon::AccelerationProfile::Soft,
        });
    }
}
