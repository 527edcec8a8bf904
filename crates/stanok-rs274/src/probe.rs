//! RS274/NGC G38.2–G38.5 straight probe (spec rs274ngc §4.19).
//!
//! The probe's world is data the caller supplies (`ControlData::probe_surfaces`, e.g. `z <= -3.2`),
//! the same data the simulated machine is given, so the interpreter knows where the probe trips
//! without asking back up the pipeline. The move goes straight from the current point towards the
//! programmed one at the feed; it stops where the contact state first becomes the requested one
//! (contact for G38.2/G38.3, loss of contact for G38.4/G38.5):
//!
//! * tripped: #5061–#5069 = the trip point (work coordinates, program units), #5070 = 1, and the
//!   tool stands there;
//! * not tripped: #5061–#5069 = the programmed point, #5070 = 0, the tool stands at the programmed
//!   point; G38.2 and G38.4 stop the program with an error, G38.3/G38.5 go on.
//!
//! With no surface configured the probe never trips and no error is raised, which is what LinuxCNC's
//! standalone `rs274` does (its simulated probe reports failure silently).
//!
//! Checks before anything moves (LinuxCNC's): feed not zero, cutter compensation off, the target at
//! least 0.01 in (0.254 mm) away for G38.2/G38.4, the probe not already in the requested state.
//!
//! With no surface configured (LinuxCNC's standalone `rs274`), the probe stands 0.254 mm short of
//! the programmed point along the move afterwards, as rs274's simulated probe puts it; the result
//! parameters hold the programmed point and #5070 = 0.

use crate::codes::*;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::params::Parameters;
use stanok_canon::{Canon, Diagnostic, FeedMode, LineMove, Pose, ProbeKind};
use stanok_syntax::ColSpan;

/// LinuxCNC's minimum probe distance: 0.01 in.
const MIN_PROBE_DISTANCE_MM: f64 = 0.254;

/// Executes G38.2 … G38.5.
pub(super) fn straight_probe(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    code: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let name = format!("G38.{}", code % 10);
    if !cx.has_axis_words() {
        return Err(cx.err(
            "rs274::probe-no-axis",
            format!("No axis words with {name}"),
            span,
        ));
    }
    if cx.st.feed_mode != FeedMode::InverseTime && cx.st.feed <= 0.0 {
        return Err(cx.err(
            "rs274::probe-zero-feed",
            "Cannot probe with zero feed rate",
            span,
        ));
    }
    for (k, &letter) in AXIS_WORDS.iter().enumerate().take(6).skip(3) {
        if let Some(v) = cx.words.take(letter) {
            if cx.opts.axes[k] {
                return Err(cx.err(
                    "rs274::probe-rotary",
                    "Cannot move rotary axes during probing".to_string(),
                    v.span,
                ));
            }
        }
    }
    let (end, _) = cx.end_point()?;
    cx.apply_pending_tlo();
    // The probe moves from where the machine stands (after a G74/G84 in G18/G19 not where the
    // interpreter believes: `TapApart`).
    super::reread_position(cx);
    let start_m = cx.st.position;
    let end_m = cx.st.frame.to_machine(&end);
    let d = {
        let (a, b) = (start_m.xyz(), end_m.xyz());
        (0..3).map(|i| (b[i] - a[i]).powi(2)).sum::<f64>().sqrt()
    };
    // LinuxCNC checks the distance for the probes that must change state (G38.2, G38.4) only.
    if d < MIN_PROBE_DISTANCE_MM && matches!(code, 382 | 384) {
        return Err(cx.err(
            "rs274::probe-too-close",
            "Start point too close to probe point",
            span,
        ));
    }
    let kind = match code {
        G38_2 => ProbeKind::TowardErrorIfNone,
        G38_3 => ProbeKind::Toward,
        G38_4 => ProbeKind::AwayErrorIfNone,
        _ => ProbeKind::Away,
    };
    let want_contact = matches!(kind, ProbeKind::TowardErrorIfNone | ProbeKind::Toward);
    let surfaces = &cx.opts.control.probe_surfaces;
    let no_surfaces = surfaces.is_empty();
    let in_contact = |p: &Pose| surfaces.iter().any(|s| s.contact(p));
    if !surfaces.is_empty() && in_contact(&start_m) == want_contact {
        return Err(cx.err(
            "rs274::probe-already",
            if want_contact {
                "Probe is already tripped when starting G38.2 or G38.3"
            } else {
                "Probe is not tripped when starting G38.4 or G38.5"
            },
            span,
        ));
    }
    // First change of the contact state along the move; the tripping surface's own coordinate is
    // taken exactly (no rounding of the interpolation), so the probe stands on the surface.
    let trip = surfaces
        .iter()
        .filter_map(|s| s.crossing(&start_m, &end_m).map(|t| (t, s)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(t, surface)| {
            let (a, b) = (start_m.to_array(), end_m.to_array());
            let mut p = [0.0; 9];
            for i in 0..9 {
                p[i] = a[i] + t * (b[i] - a[i]);
            }
            p[surface.axis.min(8)] = surface.value;
            Pose::from_array(p)
        });
    if trip.is_none()
        && !surfaces.is_empty()
        && matches!(
            kind,
            ProbeKind::TowardErrorIfNone | ProbeKind::AwayErrorIfNone
        )
    {
        return Err(cx
            .err(
                "rs274::probe-no-contact",
                format!("{name} move finished without the probe changing state"),
                span,
            )
            .with_note("the configured probe surfaces are not crossed by this move"));
    }
    let feed = cx.path_feed(d);
    if cx.st.feed_mode == FeedMode::InverseTime {
        cx.out.push(Canon::SetFeedRate { feed });
    }
    // Where the probe's result points are: the trip point, or the programmed point.
    cx.st.position = trip.unwrap_or(end_m);
    let work = cx.st.program_position().to_array();
    // With no surface configured (LinuxCNC's standalone rs274), the probe "stops" 0.254 mm
    // (0.01 in) short of the programmed point along the move, as rs274's simulated canon backs it
    // off (its STRAIGHT_PROBE); the result parameters still hold the programmed point.
    let contact = match trip {
        None if no_surfaces => {
            let (a, b) = (start_m.to_array(), end_m.to_array());
            let d = (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
            (d > 0.0).then(|| {
                let mut p = b;
                for k in 0..3 {
                    p[k] += MIN_PROBE_DISTANCE_MM * (a[k] - b[k]) / d;
                }
                Pose::from_array(p)
            })
        }
        t => t,
    };
    cx.out.push(Canon::StraightProbe {
        motion: LineMove {
            start: start_m,
            end: end_m,
            feed,
            law: stanok_canon::FeedLaw::PerMinute,
        },
        probe: kind,
        contact: contact.map(Box::new),
    });
    let k = cx.st.units.mm_per_unit();
    for (i, v) in work.iter().enumerate() {
        let v = if crate::ctx::is_linear(i) { v / k } else { *v };
        params.set(5061 + i, v);
    }
    params.set(5070, if trip.is_some() { 1.0 } else { 0.0 });
    cx.st.position = contact.unwrap_or(end_m);
    cx.fe.modes.motion_code = Some(code);
    Ok(())
}
