//! AxiOMA G75 probe (skip) move and M910/M911 batch probe mode (spec axioma-2 §2.5).
//!
//! ```text
//!  G75 X… Y… [I J K] F…   a G01 move with the skip signal armed (modal, Interpolate group)
//!  M910 … M911            batch mode: every feed move (G01 and G75) is monitored; rapids are not (A19)
//! ```
//!
//! The probe's world is data (`ControlData::probe_surfaces`, the same the machine is given), so
//! the trip point is known here: the first point of the straight move where the contact state
//! changes. On a trip the axes' positions are latched in machine coordinates (no offsets), the
//! block ends there (Stanok stops at the latch point: the braking distance belongs to the machine)
//! and the next block starts from it; without a trip the move runs to its end with the flag off
//! (A18). The latch is what later blocks see: the position they start from, and
//! `Interpreter::axioma_probe_latch`. I/J/K are read and kept without effect (A17).
//! G93 is forbidden with G75 (error 617); F must be set (a G01 rule).

use crate::ctx::Ctx;
use stanok_canon::{Canon, Diagnostic, FeedMode, LineMove, Pose, ProbeKind};
use stanok_syntax::ColSpan;

/// The last probe move's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeLatch {
    /// The probe tripped during the move.
    pub triggered: bool,
    /// Machine coordinates of the trip (the move's end when it did not trip), mm/deg.
    pub position: Pose,
    /// I, J, K of the G75 block as written (meaning not defined by the manual).
    pub ijk: [Option<f64>; 3],
}

/// G75 mode and the last latch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProbeState {
    /// G75 is the active Interpolate function.
    pub g75: bool,
    /// The last probe move's result.
    pub latch: Option<ProbeLatch>,
}

/// A monitored feed move to the block's end point (G75, or G01 in batch mode).
pub(super) fn probe_move(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if cx.st.feed_mode == FeedMode::InverseTime && cx.fe.probe.g75 {
        return Err(cx.manual(617, "G93 (inverse time) is not allowed with G75", span));
    }
    let ijk = [b'I', b'J', b'K'].map(|l| cx.words.take(l).map(|v| v.v));
    if !cx.has_axis_words() {
        return Ok(());
    }
    if cx.fe.ext.comp.is_active() {
        return Err(cx.err(
            "axioma::probe-under-compensation",
            "a probe move cannot be radius-compensated: switch G41/G42 off first",
            span,
        ));
    }
    let (end, _) = cx.end_point()?;
    cx.apply_pending_tlo();
    let start_m = cx.st.position;
    let end_m = cx.st.frame.to_machine(&end);
    let length = super::technology::feed_length(&start_m.to_array(), &end_m.to_array());
    let feed = super::motion::feed_check(cx, span, length)?;
    let trip = cx
        .opts
        .control
        .probe_surfaces
        .iter()
        .filter_map(|s| s.crossing(&start_m, &end_m))
        .fold(None, |best: Option<f64>, t| {
            Some(best.map_or(t, |b| b.min(t)))
        })
        .map(|t| {
            let (a, b) = (start_m.to_array(), end_m.to_array());
            Pose::from_array(std::array::from_fn(|i| a[i] + t * (b[i] - a[i])))
        });
    cx.out.push(Canon::StraightProbe {
        motion: LineMove {
            start: start_m,
            end: end_m,
            feed,
            law: stanok_canon::FeedLaw::PerMinute,
        },
        probe: ProbeKind::Toward,
        contact: trip.map(Box::new),
    });
    let stop = trip.unwrap_or(end_m);
    cx.st.position = stop;
    cx.fe.probe.latch = Some(ProbeLatch {
        triggered: trip.is_some(),
        position: stop,
        ijk,
    });
    Ok(())
}
