//! AxiOMA canned cycles (spec axioma-3 §6–§9, manual 11): activation, parameters, call, cancel.
//!
//! ```text
//!  G81…G389 [Q<i>=v …]      activation: all Q reset to "not written", then the block's Q assigned
//!  Q<i>=v (cycle active)    changes a parameter (before the call in the same block)
//!  any axis word            call: the axis words give the call point; the cycle expands to Canon
//!  G80                      cancel; the interpolation active before the cycle is active again
//!  G00/G01/G02/G03          cancel; that interpolation becomes active
//! ```
//! Validation happens at the call (error 603 for any invalid or missing parameter), never at the
//! activation (Example 11.2 activates with an incomplete set). Q values are absolute mm, degrees,
//! seconds whatever G70/G71/G90/G91 (§6.1); Q3/Q4 are mm/min ([D] A21).
//!
//! Moves are generated in program coordinates and go through the work frame like any point
//! ([D]): for mirror and rotation this is exactly the manual's parameter tables (Q9, Q11 follow the
//! frame). Under G173 the lengths the manual never transforms (Q1, Q2, Q6, Q12, Q13 and all drilling
//! and turning parameters) are divided by the axis scale first, so that they come out unscaled;
//! unequal in-plane factors are refused for the milling cycles.
//!
//! Bounds: every cycle counts its passes first and refuses more than [`MAX_PASSES`] (603), so no
//! parameter combination loops long.

mod drilling;
mod pockets;
mod turning;

use crate::codes;
use crate::ctx::Ctx;
use crate::words::Val;
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_syntax::ColSpan;

/// Most passes (layers, pecks, rings, plunges) one cycle call may generate.
pub const MAX_PASSES: f64 = 10_000.0;

/// The canned cycles of this part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleKind {
    /// G81 drilling.
    Drill,
    /// G83 peck drilling.
    PeckDrill,
    /// G276 threading.
    Thread,
    /// G281 longitudinal recess.
    RecessLongitudinal,
    /// G282 face recess.
    RecessFace,
    /// G288 longitudinal groove.
    GrooveLongitudinal,
    /// G289 face groove.
    GrooveFace,
    /// G387 rectangular pocket.
    RectPocket,
    /// G388 slot.
    Slot,
    /// G389 circular pocket.
    CircPocket,
}

impl CycleKind {
    /// From a G code (`codes.rs`).
    pub fn from_code(code: u32) -> Option<CycleKind> {
        Some(match code {
            codes::G81 => CycleKind::Drill,
            codes::G83 => CycleKind::PeckDrill,
            codes::G276 => CycleKind::Thread,
            codes::G281 => CycleKind::RecessLongitudinal,
            codes::G282 => CycleKind::RecessFace,
            codes::G288 => CycleKind::GrooveLongitudinal,
            codes::G289 => CycleKind::GrooveFace,
            codes::G387 => CycleKind::RectPocket,
            codes::G388 => CycleKind::Slot,
            codes::G389 => CycleKind::CircPocket,
            _ => return None,
        })
    }

    fn name(self) -> &'static str {
        match self {
            CycleKind::Drill => "G81",
            CycleKind::PeckDrill => "G83",
            CycleKind::Thread => "G276",
            CycleKind::RecessLongitudinal => "G281",
            CycleKind::RecessFace => "G282",
            CycleKind::GrooveLongitudinal => "G288",
            CycleKind::GrooveFace => "G289",
            CycleKind::RectPocket => "G387",
            CycleKind::Slot => "G388",
            CycleKind::CircPocket => "G389",
        }
    }
}

/// The active cycle and its parameters as written (None = default).
#[derive(Debug, Clone, Copy, Default)]
pub struct CycleState {
    /// The active cycle (None = G80).
    pub active: Option<CycleKind>,
    /// Q1…Q32 (index 0 = Q1).
    pub q: [Option<f64>; 32],
}

/// Activation: defaults first, then the block's parameters (§6.2).
pub(super) fn activate(cx: &mut Ctx<'_>, kind: CycleKind) {
    *cx.fe.cycle = CycleState {
        active: Some(kind),
        q: [None; 32],
    };
}

/// Assigns the block's `Q<i>=` words to the active cycle.
pub(super) fn set_params(cx: &mut Ctx<'_>, qs: &[(u8, Val)]) -> Result<(), Diagnostic> {
    for &(i, v) in qs {
        if !(1..=32).contains(&i) {
            return Err(cx.err(
                "axioma::cycle-parameter-index",
                format!("Q{i}=: cycle parameters are Q1 … Q32"),
                v.span,
            ));
        }
        cx.fe.cycle.q[i as usize - 1] = Some(v.v);
    }
    Ok(())
}

/// One cycle call: parameters, call point and the move helpers every cycle uses.
pub(crate) struct Call<'c, 'a> {
    pub cx: &'c mut Ctx<'a>,
    pub kind: CycleKind,
    q: [Option<f64>; 32],
    /// Position at the moment of the call (program coordinates).
    pub h0: Pose,
    /// Call point (program coordinates).
    pub p: Pose,
    /// Working feed Q3, mm/min.
    pub q3: f64,
    /// Idle feed Q4, mm/min (None = rapid).
    pub q4: Option<f64>,
    pub span: ColSpan,
}

impl<'c, 'a> Call<'c, 'a> {
    /// Error 603 for parameter `i`.
    pub fn invalid(&self, i: usize, why: &str) -> Diagnostic {
        let value = match self.q[i - 1] {
            Some(v) => format!("Q{i}={v}"),
            None => format!("Q{i} (not written)"),
        };
        self.cx
            .manual(
                603,
                format!(
                    "invalid cycle parameter at the call of {}: {value}",
                    self.kind.name()
                ),
                self.span,
            )
            .with_note(why.to_string())
    }

    /// Parameter `i` as written, or `default`, checked with `valid`.
    pub fn q(
        &self,
        i: usize,
        default: f64,
        valid: impl Fn(f64) -> bool,
        why: &str,
    ) -> Result<f64, Diagnostic> {
        let v = self.q[i - 1].unwrap_or(default);
        if !v.is_finite() || !valid(v) {
            return Err(self.invalid(i, why));
        }
        Ok(v)
    }

    /// Parameter `i` if written (checked with `valid`).
    pub fn q_opt(
        &self,
        i: usize,
        valid: impl Fn(f64) -> bool,
        why: &str,
    ) -> Result<Option<f64>, Diagnostic> {
        match self.q[i - 1] {
            None => Ok(None),
            Some(v) if v.is_finite() && valid(v) => Ok(Some(v)),
            Some(_) => Err(self.invalid(i, why)),
        }
    }

    /// A pass count checked against [`MAX_PASSES`].
    pub fn passes(&self, total: f64, step: f64, i: usize) -> Result<usize, Diagnostic> {
        let n = (total / step - 1e-9).ceil().max(0.0);
        if !n.is_finite() || n > MAX_PASSES {
            return Err(self.invalid(
                i,
                &format!("more than {MAX_PASSES} passes: the step is too small for the length"),
            ));
        }
        Ok(n as usize)
    }

    /// 1 / scale factor of program axis `axis` (lengths the manual never transforms).
    pub fn unscale(&self, axis: usize) -> f64 {
        if axis > 2 {
            return 1.0;
        }
        let m = self.cx.st.frame.linear();
        let k = (0..3).map(|r| m[r][axis] * m[r][axis]).sum::<f64>().sqrt();
        if k > 1e-12 {
            1.0 / k
        } else {
            1.0
        }
    }

    fn current(&self) -> Pose {
        self.cx.st.program_position()
    }

    /// A move to `target` (program coordinates): rapid when `feed` is None. Zero-length moves are
    /// not emitted.
    pub fn move_to(&mut self, target: Pose, feed: Option<f64>) {
        let here = self.current().to_array();
        let t = target.to_array();
        if (0..9).all(|k| (here[k] - t[k]).abs() < 1e-12) {
            return;
        }
        match feed {
            None => self.cx.straight(true, target, 0.0),
            Some(f) => self.cx.straight(false, target, f),
        }
    }

    /// Moves the given axes (program coordinates) at `feed` (None = rapid).
    pub fn axes_to(&mut self, axes: &[(usize, f64)], feed: Option<f64>) {
        let mut t = self.current().to_array();
        for &(k, v) in axes {
            t[k] = v;
        }
        self.move_to(Pose::from_array(t), feed);
    }

    /// Rapid of the given axes.
    pub fn rapid(&mut self, axes: &[(usize, f64)]) {
        self.axes_to(axes, None);
    }

    /// Working feed Q3.
    pub fn cut(&mut self, axes: &[(usize, f64)]) {
        let f = self.q3;
        self.axes_to(axes, Some(f));
    }

    /// Idle feed Q4 (rapid if Q4 was not written).
    pub fn idle(&mut self, axes: &[(usize, f64)]) {
        let f = self.q4;
        self.axes_to(axes, f);
    }

    /// Dwell of `s` seconds (nothing for 0).
    pub fn dwell(&mut self, s: f64) {
        if s > 0.0 {
            self.cx.out.push(Canon::Dwell { seconds: s });
        }
    }

    /// Q2 (safety distance 2, default Q1) and the return level on an axis for G98/G99.
    /// `k` = 1 / scale of the axis (Q2 is never transformed).
    pub fn return_level(
        &self,
        h0: f64,
        surface: f64,
        s: f64,
        q1: f64,
        k: f64,
    ) -> Result<f64, Diagnostic> {
        let q2 = self.q(2, q1, |v| v >= 0.0, "safety distance 2 must be ≥ 0")?;
        Ok(if self.cx.st.retract_to_initial {
            h0
        } else {
            surface - s * q2 * k
        })
    }
}

/// Calls the active cycle at the block's axis words.
pub(super) fn call(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    let Some(kind) = cx.fe.cycle.active else {
        return Ok(());
    };
    if cx.fe.ext.comp.is_active() {
        return Err(cx
            .err(
                "axioma::cycle-under-compensation",
                "a canned cycle cannot be called while radius compensation is active",
                span,
            )
            .with_note("program G40 before the cycle call (spec axioma-3 §4.9)"));
    }
    if cx.fe.modes.polar.on {
        return Err(cx.err(
            "axioma::cycle-polar",
            "a canned cycle call point cannot be programmed in polar coordinates (G16)",
            span,
        ));
    }
    let h0 = cx.st.program_position();
    let (p, _) = cx.end_point()?;
    let q = cx.fe.cycle.q;
    // Q3: the F of the moment of the call, always mm/min.
    let f_now = cx.path_feed(0.0);
    let mut call = Call {
        cx,
        kind,
        q,
        h0,
        p,
        q3: 0.0,
        q4: None,
        span,
    };
    // G276 cuts at the thread feed S·pitch: Q3 is not used there.
    if kind != CycleKind::Thread {
        call.q3 = call.q(
            3,
            f_now,
            |v| v > 0.0,
            "the working feed Q3 must be > 0 (no F programmed)",
        )?;
    }
    call.q4 = call.q_opt(4, |v| v > 0.0, "the idle feed Q4 must be > 0")?;
    match kind {
        CycleKind::Drill | CycleKind::PeckDrill => drilling::run(&mut call),
        CycleKind::Thread => turning::thread(&mut call),
        CycleKind::RecessLongitudinal => turning::recess(&mut call, 0, 2),
        CycleKind::RecessFace => turning::recess(&mut call, 2, 0),
        CycleKind::GrooveLongitudinal => turning::groove(&mut call, 0, 2),
        CycleKind::GrooveFace => turning::groove(&mut call, 2, 0),
        CycleKind::RectPocket => pockets::rectangular(&mut call),
        CycleKind::Slot => pockets::slot(&mut call),
        CycleKind::CircPocket => pockets::circular(&mut call),
    }
}
