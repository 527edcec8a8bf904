//! RS274/NGC spindle-synchronised motion: G33 (threading move), G33.1 (rigid tapping) and the G76
//! multi-pass threading cycle (spec rs274ngc §4.22, §4.23, §4.36; LinuxCNC 2.9 as the oracle).
//!
//! Synchronisation is a pair of Canon commands around the moves: `StartSpindleSync { pitch }`
//! (LinuxCNC's START_SPEED_FEED_SYNC) and `StopSpindleSync`; the moves in between advance `pitch`
//! per spindle revolution, which the planner turns into time from the spindle speed. Their Canon
//! feed is the nominal pitch × commanded rpm (mm/min), so that reports without a planner agree.
//!
//! ## G76 pass schedule (spec §4.36, LinuxCNC's arithmetic)
//!
//! With the drive line at the start position (x0, z0), thread end `Z`, crest offset I (I < 0
//! external: depths go towards −X; I > 0 internal), first depth J, full depth K, degression R
//! (default 1), compound angle Q, spring passes H, taper length E and taper ends L:
//!
//! ```text
//!   depth_n = |I| + J·n^(1/R)  for n = 1, 2, … while depth_n < |I| + K; then |I| + K, H+1 times
//!   zoff    = (depth − |I|)·tan Q        s = +1 when Z < z0 (cutting towards −Z), else −1
//!   start Z = z0 − s·zoff                end Z = Z + s·K·tan Q − s·zoff
//!   cut X   = x0 ∓ depth                 clear X = cut X ± (|I| + K)   (∓: external −, internal +)
//!   taper pitch = P·√(E² + K²)/E
//! ```
//!
//! Each pass: rapid to (clear X, start Z); without entry taper rapid in to the cut X, with it a
//! synchronised feed in to K outside the cut and a taper to the cut X, E along; feed override off,
//! synchronised feed to the end Z (with exit taper: to E before it, then a taper out by K); rapid
//! out to the clear X; override on. Finally a rapid to (x0, Z). Under G7 I, J, K are diameters.
//!
//! Invariant: the number of passes is bounded ([`MAX_PASSES`]); a schedule that would need more
//! is refused before anything moves.

use crate::codes::*;
use crate::ctx::Ctx;
use stanok_canon::{Canon, Diagnostic, Pose};
use stanok_syntax::ColSpan;

/// Most passes a G76 may take.
pub const MAX_PASSES: usize = 10_000;

fn spindle_turning(cx: &Ctx<'_>) -> bool {
    cx.st.spindle_on[0] && cx.fe.modes.spindle_direction.is_some()
}

/// The pitch word K of G33/G33.1, mm per revolution.
fn pitch_word(cx: &mut Ctx<'_>, span: ColSpan) -> Result<f64, Diagnostic> {
    match cx.words.take(b'K') {
        Some(k) => Ok(cx.mm(k.v)),
        None => Err(cx.err(
            "rs274::g33-k-missing",
            "K word missing with g33/g33.1",
            span,
        )),
    }
}

fn start_sync(cx: &mut Ctx<'_>, pitch: f64) {
    cx.out.push(Canon::StartSpindleSync {
        pitch,
        velocity_mode: false,
    });
}

/// Nominal feed of a synchronised move: pitch × commanded spindle speed, mm/min.
fn sync_feed(cx: &Ctx<'_>, pitch: f64) -> f64 {
    pitch.abs() * cx.st.spindle_speed[0]
}

/// G33: one synchronised straight move.
pub(super) fn g33(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if !spindle_turning(cx) {
        return Err(cx.err("rs274::g33-spindle", "Spindle not turning in G33", span));
    }
    let pitch = pitch_word(cx, span)?;
    let (end, _) = cx.end_point()?;
    start_sync(cx, pitch);
    let feed = sync_feed(cx, pitch);
    cx.straight(false, end, feed);
    cx.out.push(Canon::StopSpindleSync);
    cx.fe.modes.motion_code = Some(G33);
    Ok(())
}

/// G33.1: rigid tapping to the end point and back (the machine reverses the spindle).
pub(super) fn g33_1(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if !spindle_turning(cx) {
        return Err(cx.err("rs274::g33-spindle", "Spindle not turning in G33.1", span));
    }
    let pitch = pitch_word(cx, span)?;
    // LinuxCNC reads and ignores I (a retract scale in later versions).
    let _ = cx.words.take(b'I');
    let (end, _) = cx.end_point()?;
    cx.apply_pending_tlo();
    start_sync(cx, pitch);
    let start = cx.st.position;
    let end_m = cx.st.frame.to_machine(&end);
    cx.out.push(Canon::RigidTap {
        start,
        end: end_m,
        scale: 1.0,
        law: stanok_canon::FeedLaw::PerMinute,
    });
    cx.out.push(Canon::StopSpindleSync);
    cx.fe.modes.motion_code = Some(G33_1);
    Ok(())
}

/// The words of a G76 block, in program mm (radius values).
struct ThreadWords {
    pitch: f64,
    z_end: f64,
    i: f64,
    k: f64,
    degression: f64,
    angle_deg: f64,
    spring_passes: u32,
    taper: f64,
    taper_ends: u32,
    /// I, J, K as LinuxCNC holds them (program units, halved under G7), and mm per unit: the
    /// passes are stepped in program units as LinuxCNC steps them (see `pass_depths`).
    ijk_units: [f64; 3],
    mm_per_unit: f64,
}

fn thread_words(cx: &mut Ctx<'_>, span: ColSpan, z_end: f64) -> Result<ThreadWords, Diagnostic> {
    let diameter = if cx.st.diameter_mode { 0.5 } else { 1.0 };
    let need = |cx: &mut Ctx<'_>, l: u8| -> Result<f64, Diagnostic> {
        match cx.words.take(l) {
            Some(v) => Ok(v.v),
            None => Err(cx.err(
                "rs274::g76-word-missing",
                format!("G76 requires {} word", l as char),
                span,
            )),
        }
    };
    let pitch = need(cx, b'P')?;
    let i = need(cx, b'I')?;
    let j = need(cx, b'J')?;
    let k = need(cx, b'K')?;
    let opt = |cx: &mut Ctx<'_>, l: u8, d: f64| cx.words.take(l).map_or(d, |v| v.v);
    let degression = opt(cx, b'R', 1.0);
    let angle_deg = opt(cx, b'Q', 0.0);
    let spring = opt(cx, b'H', 0.0);
    let taper = opt(cx, b'E', 0.0);
    let ends = opt(cx, b'L', 0.0);
    // LinuxCNC 2.9's checks and words, in its order.
    if i == 0.0 {
        return Err(cx.err("rs274::g76-i", "In G76, I must not be 0", span));
    }
    if j <= 0.0 {
        return Err(cx.err("rs274::g76-depth", "In G76, J must be greater than 0", span));
    }
    if k <= j {
        return Err(cx.err("rs274::g76-depth", "In G76, K must be greater than J", span));
    }
    if degression < 1.0 {
        return Err(cx.err("rs274::g76-degression", "R must be >= 1.0 with G76", span));
    }
    if !(0.0..=3.0).contains(&ends) || ends.fract() != 0.0 {
        return Err(cx.err("rs274::g76-l", "Invalid L value with G76", span));
    }
    if spring < 0.0 || spring.fract() != 0.0 || spring > MAX_PASSES as f64 {
        return Err(cx.err("rs274::g76-h", "Invalid H value with G76", span));
    }
    Ok(ThreadWords {
        pitch: cx.mm(pitch),
        z_end,
        i: cx.mm(i) * diameter,
        k: cx.mm(k) * diameter,
        degression,
        angle_deg,
        spring_passes: spring as u32,
        taper: cx.mm(taper),
        taper_ends: ends as u32,
        ijk_units: [i * diameter, j * diameter, k * diameter],
        mm_per_unit: cx.st.units.mm_per_unit(),
    })
}

/// The depths of the passes, from the drive line (see the module doc).
///
/// Stepped in program units, as LinuxCNC steps them (`depth < end_depth` decides the last pass
/// where the depths meet K in decimal: its rounding, not the mm rounding, counts), each depth then
/// converted to mm.
fn pass_depths(w: &ThreadWords) -> Option<Vec<f64>> {
    let [i, j, k] = w.ijk_units;
    let full = k.abs() + i.abs();
    let mut depths = Vec::new();
    let mut n = 1.0f64;
    loop {
        let d = i.abs() + j.abs() * n.powf(1.0 / w.degression);
        // (NaN stops too.)
        if d >= full || d.is_nan() {
            break;
        }
        depths.push(d * w.mm_per_unit);
        if depths.len() > MAX_PASSES {
            return None;
        }
        n += 1.0;
    }
    for _ in 0..=w.spring_passes {
        depths.push(full * w.mm_per_unit);
    }
    (depths.len() <= MAX_PASSES).then_some(depths)
}

/// G76: the multi-pass threading cycle, in LinuxCNC 2.9's order of checks: P, then I J K present
/// (its `check_items`); the spindle turning; no rotary or UVW axis moved. It threads in XZ
/// whatever the plane (LinuxCNC does not check the plane), and its last rapid goes to the block's
/// end point — X and Y words are allowed and taken there, Z is the thread's end (the current Z
/// without one).
pub(super) fn g76(cx: &mut Ctx<'_>, span: ColSpan) -> Result<(), Diagnostic> {
    if !cx.words.has(b'P') {
        return Err(cx.err("rs274::g76-p", "P word missing with G76", span));
    }
    if !(cx.words.has(b'I') && cx.words.has(b'J') && cx.words.has(b'K')) {
        return Err(cx.err("rs274::g76-ijk", "I J or K words missing with G76", span));
    }
    if !spindle_turning(cx) {
        return Err(cx.err(
            "rs274::g76-spindle",
            "Chosen spindle (0) not turning in G76",
            span,
        ));
    }
    let here = cx.st.program_position().to_array();
    let (end, _) = cx.end_point()?;
    let e = end.to_array();
    if (3..9).any(|k| e[k] != here[k]) {
        return Err(cx.err(
            "rs274::g76-rotary",
            "Cannot move rotary axes with G76",
            span,
        ));
    }
    let w = thread_words(cx, span, end.z)?;
    let Some(depths) = pass_depths(&w) else {
        return Err(cx
            .err("rs274::g76-passes", "Too many passes in G76", span)
            .with_note(format!("at most {MAX_PASSES} passes")));
    };
    let p0 = cx.st.program_position();
    let (x0, z0) = (p0.x, p0.z);
    let s = if w.z_end < z0 { 1.0 } else { -1.0 };
    // External threads (I < 0) cut towards −X.
    let toward = if w.i < 0.0 { -1.0 } else { 1.0 };
    let tan_q = w.angle_deg.to_radians().tan();
    let taper_pitch = if w.taper > 0.0 {
        w.pitch * (w.taper.powi(2) + w.k.powi(2)).sqrt() / w.taper
    } else {
        w.pitch
    };
    let entry_taper = w.taper > 0.0 && (w.taper_ends & 1) != 0;
    let exit_taper = w.taper > 0.0 && (w.taper_ends & 2) != 0;
    let feed = sync_feed(cx, w.pitch);
    let at = |x: f64, z: f64| Pose { x, z, ..p0 };
    for d in depths {
        let zoff = (d - w.i.abs()) * tan_q;
        let start_z = z0 - s * zoff;
        let end_z = w.z_end + s * w.k * tan_q - s * zoff;
        let cut_x = x0 + toward * d;
        let clear_x = cut_x - toward * (w.i.abs() + w.k);
        cx.straight(true, at(clear_x, start_z), 0.0);
        if entry_taper {
            cx.out
                .push(Canon::SetFeedOverrideEnabled { enabled: false });
            start_sync(cx, taper_pitch);
            cx.straight(false, at(cut_x - toward * w.k, start_z), feed);
            cx.straight(false, at(cut_x, start_z - s * w.taper), feed);
            start_sync(cx, w.pitch);
        } else {
            cx.straight(true, at(cut_x, start_z), 0.0);
            cx.out
                .push(Canon::SetFeedOverrideEnabled { enabled: false });
            start_sync(cx, w.pitch);
        }
        if exit_taper {
            cx.straight(false, at(cut_x, end_z + s * w.taper), feed);
            start_sync(cx, taper_pitch);
            cx.straight(false, at(cut_x - toward * w.k, end_z), feed);
        } else {
            cx.straight(false, at(cut_x, end_z), feed);
        }
        cx.out.push(Canon::StopSpindleSync);
        cx.straight(true, at(clear_x, end_z), 0.0);
        cx.out.push(Canon::SetFeedOverrideEnabled { enabled: true });
    }
    cx.straight(
        true,
        Pose {
            x: end.x,
            y: end.y,
            ..at(x0, w.z_end)
        },
        0.0,
    );
    cx.fe.modes.motion_code = Some(G76);
    Ok(())
}
