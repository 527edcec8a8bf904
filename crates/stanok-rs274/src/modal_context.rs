//! RS274/NGC M70–M73: saving and restoring the modal state (spec rs274ngc §5; what is restored,
//! in which order and what is printed taken from LinuxCNC 2.9's `rs274`, tests/rs274/m70-*.ngc).
//!
//! * M70 saves the modal state in the current call level (the main program is level 0);
//! * M72 restores it (error if that level has none: "Cannot restore context from invalid stack
//!   frame - missing M70/M73?");
//! * M71 forgets it;
//! * M73 saves it and marks it to be restored automatically when the subroutine returns.
//!
//! Restoring changes, and announces, only what differs, in LinuxCNC's order: units; feed mode
//! (which resets F, as a feed-mode change always does) — or else F; S; the spindle's sense; the
//! plane; the G54…G59.3 system; path control; distance mode; and whether the G92/G52
//! offset is applied (#5210): if that differs, M72 does what G92.3 (re-apply #5211…#5219) or
//! G92.2 (off, values kept) would — rs274 prints SET_G92_OFFSET for it, even when the values are
//! the same; a changed offset that stays applied is not restored. Coolant is restored by M7, M8
//! and M9 as LinuxCNC's `gen_m_codes` issues them (see `restore_state`). Tool length offsets, the
//! retract mode and the lathe diameter mode are not part of the context (LinuxCNC's choice).
//!
//! The contexts live in `Parameters` next to the local scopes of the calls, so they come and go
//! with the levels and a failing block's changes to them are rolled back with its other writes.

use super::offsets::select_coordinate_system;
use super::path_mode_canon;
use crate::ctx::Ctx;
use crate::params::Parameters;
use crate::state::{DistanceMode, PathMode};
use stanok_canon::{Canon, Diagnostic, FeedMode, LengthUnits, Plane, SpindleDirection};
use stanok_syntax::ColSpan;

/// What M70/M73 keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SavedContext {
    units: LengthUnits,
    feed_mode: FeedMode,
    feed: f64,
    feed_units: Option<LengthUnits>,
    speed: f64,
    spindle: Option<SpindleDirection>,
    plane: Plane,
    g5x_index: u8,
    path_mode: PathMode,
    naive_cam: f64,
    distance: DistanceMode,
    mist: bool,
    flood: bool,
    /// #5210: the G92/G52 offset is applied.
    g92_applied: bool,
    /// M73: restore when the subroutine returns.
    pub auto_restore: bool,
}

fn capture(cx: &Ctx<'_>, params: &Parameters, auto_restore: bool) -> SavedContext {
    let st = &cx.st;
    SavedContext {
        units: st.units,
        feed_mode: st.feed_mode,
        feed: st.feed,
        feed_units: cx.fe.modes.feed_units,
        speed: st.spindle_speed[0],
        spindle: if st.spindle_on[0] {
            cx.fe.modes.spindle_direction
        } else {
            None
        },
        plane: st.plane,
        g5x_index: st.g5x_index,
        path_mode: st.path_mode,
        naive_cam: cx.fe.modes.naive_cam_tolerance,
        distance: st.distance,
        mist: st.mist,
        flood: st.flood,
        g92_applied: params.get(5210) != 0.0,
        auto_restore,
    }
}

/// M70 (save), M71 (forget), M72 (restore), M73 (save, restore on return).
pub(super) fn m70_73(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    code: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    match code {
        70 | 73 => {
            let saved = capture(cx, params, code == 73);
            params.set_context(Some(saved));
        }
        71 => params.set_context(None),
        _ => match params.context() {
            Some(saved) => restore(cx, params, &saved),
            None => {
                return Err(cx.err(
                    "rs274::m72-no-context",
                    "Cannot restore context from invalid stack frame - missing M70/M73?",
                    span,
                ))
            }
        },
    }
    Ok(())
}

/// Puts the saved state back, announcing what changes (module doc for the order).
pub fn restore(cx: &mut Ctx<'_>, params: &mut Parameters, saved: &SavedContext) {
    // rs274 prints the restoring calls without the block's N label (observed for M72).
    let number = cx.out.number.take();
    restore_state(cx, params, saved);
    cx.out.number = number;
}

fn same_length(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

fn same_path_mode(a: PathMode, b: PathMode) -> bool {
    match (a, b) {
        (
            PathMode::Continuous { blend_tolerance: x },
            PathMode::Continuous { blend_tolerance: y },
        ) => same_length(x, y),
        _ => a == b,
    }
}

fn restore_state(cx: &mut Ctx<'_>, params: &mut Parameters, saved: &SavedContext) {
    if cx.st.units != saved.units {
        super::set_units(cx, saved.units);
        cx.out.push(Canon::UseLengthUnits { units: saved.units });
    }
    cx.fe.modes.feed_units = saved.feed_units;
    if cx.st.feed_mode != saved.feed_mode {
        super::set_feed_mode(cx, saved.feed_mode);
    } else if cx.st.feed != saved.feed {
        cx.st.feed = saved.feed;
        if saved.feed_mode != FeedMode::InverseTime {
            cx.out.push(Canon::SetFeedRate { feed: saved.feed });
        }
    }
    if cx.st.spindle_speed[0] != saved.speed {
        cx.st.spindle_speed[0] = saved.speed;
        cx.out.push(Canon::SetSpindleSpeed {
            spindle: 0,
            rpm: saved.speed,
        });
    }
    let now = if cx.st.spindle_on[0] {
        cx.fe.modes.spindle_direction
    } else {
        None
    };
    // Coolant as LinuxCNC restores it: its M-code slots (mist: M7 if on, else M9 unless flood is
    // on; flood: M8 if on) are compared, each that differs is issued — unless the saved slot is
    // empty — as the M code itself, so restoring mist off (M9) turns flood off too, and flood
    // off is never restored by its own slot. The first M code of the restore (the spindle's,
    // else the first coolant code) runs in the restoring block in its place after S; the others
    // as blocks of their own after it.
    let mist_slot = |mist: bool, flood: bool| match (mist, flood) {
        (true, _) => Some(7),
        (false, true) => None,
        (false, false) => Some(9),
    };
    let mut coolant: Vec<u32> = Vec::with_capacity(2);
    let saved_mist = mist_slot(saved.mist, saved.flood);
    if saved_mist != mist_slot(cx.st.mist, cx.st.flood) {
        coolant.extend(saved_mist);
    }
    if saved.flood && !cx.st.flood {
        coolant.push(8);
    }
    let spindle_restored = now != saved.spindle;
    if now != saved.spindle {
        match saved.spindle {
            Some(direction) => {
                cx.st.spindle_on[0] = true;
                cx.out.push(Canon::StartSpindle {
                    spindle: 0,
                    direction,
                });
            }
            None => {
                cx.st.spindle_on[0] = false;
                cx.out.push(Canon::StopSpindle { spindle: 0 });
            }
        }
        cx.fe.modes.spindle_direction = saved.spindle;
    }
    let mut coolant = coolant.into_iter();
    if !spindle_restored {
        if let Some(code) = coolant.next() {
            cx.coolant(code);
        }
    }
    if cx.st.plane != saved.plane {
        cx.st.plane = saved.plane;
        cx.out.push(Canon::SelectPlane { plane: saved.plane });
    }
    if cx.st.g5x_index != saved.g5x_index {
        select_coordinate_system(cx, params, saved.g5x_index, true);
    }
    // (Tolerances compared as numbers: a G20/G21 pair rescales them there and back, which may
    // leave an ulp.)
    if !same_path_mode(cx.st.path_mode, saved.path_mode)
        || !same_length(cx.fe.modes.naive_cam_tolerance, saved.naive_cam)
    {
        cx.st.path_mode = saved.path_mode;
        cx.fe.modes.naive_cam_tolerance = saved.naive_cam;
        cx.out
            .push(path_mode_canon(saved.path_mode, saved.naive_cam));
    }
    if cx.st.distance != saved.distance {
        let old = std::mem::replace(&mut cx.st.distance, saved.distance);
        super::announce_distance(cx, "distance", old, saved.distance);
    }
    if (params.get(5210) != 0.0) != saved.g92_applied {
        let code = if saved.g92_applied {
            super::codes::G92_3
        } else {
            super::codes::G92_2
        };
        // Neither can fail: G92.2 and G92.3 read no words.
        let _ = super::offsets::g92_family(cx, params, code, ColSpan::default());
    }
    for code in coolant {
        cx.coolant(code);
    }
}
