//! RS274/NGC work offsets (spec rs274ngc §3.1, §4.11, §4.13, §4.27, §4.29, §4.43): the G54…G59.3
//! table in parameters #5221…#5390, G10 L2/L20 writing it, selecting a system, the G92/G52 offset
//! vector #5210…#5219, and the resets of a program end (M2/M30), in LinuxCNC's order.
//!
//! The chain is the work frame's (`frame.rs`): `machine = origin + Rz(R)·(p + shift) + tlo` with
//! origin = the active system's offset, R its rotation and shift = the G92/G52 vector, which is why
//! G92 arithmetic below happens in program coordinates (before the rotation) and G10 L20 in the
//! unrotated frame. The machine position never changes here: the program position is re-derived
//! through the new frame, as LinuxCNC's DRO changes without motion.

use super::{axis_values, unsupported};
use crate::codes::*;
use crate::ctx::Ctx;
use crate::params::Parameters;
use crate::state::{DistanceMode, MotionMode};
use stanok_canon::{Canon, Diagnostic, FeedMode, Plane, Pose};
use stanok_syntax::ColSpan;

/// First parameter of system `index` (1 = G54 … 9 = G59.3): X at 5201 + 20·index, R at +9.
fn system_base(index: u8) -> usize {
    5201 + 20 * index as usize
}

/// Makes `offset` and `rotation` (degrees about Z) the G5x part of the work frame.
fn set_g5x(cx: &mut Ctx<'_>, offset: Pose, rotation: f64) {
    cx.st.frame.set_origin(offset);
    cx.st.frame.set_rotation(rotation_z(rotation));
    cx.st.xy_rotation_deg = rotation;
}

fn rotation_z(deg: f64) -> crate::frame::Mat3 {
    if deg == 0.0 {
        crate::frame::IDENTITY
    } else {
        crate::frame::rotation(2, deg)
    }
}

/// The stored origin (mm/deg) and XY rotation (degrees) of system `index`.
pub fn g5x_from_params(params: &Parameters, index: u8) -> (Pose, f64) {
    let base = system_base(index);
    (params.pose_mm(base), params.get(base + 9))
}

/// Makes a G54…G59.3 system active, loading it from the parameters *now* (so a program's writes to
/// #5221… take effect here). LinuxCNC re-announces the G92 offset on a G5x selection but not on
/// the reset of a program end.
pub(super) fn select_coordinate_system(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    index: u8,
    announce_g92: bool,
) {
    let (offset, rotation) = g5x_from_params(params, index);
    cx.st.g5x_index = index;
    params.set(5220, index as f64);
    set_g5x(cx, offset, rotation);
    cx.out.push(Canon::SetG5xOffset { index, offset });
    if announce_g92 {
        cx.out.push(Canon::SetG92Offset {
            offset: *cx.st.frame.shift(),
        });
    }
    cx.out.push(Canon::SetXyRotation { degrees: rotation });
}

/// G10 L2 (origin from values) and L20 (origin so that the current point reads the values).
pub(super) fn g10_origin(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    l: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let p = cx.words.take(b'P');
    let p_num = p
        .map(|p| p.v)
        .filter(|v| v.fract() == 0.0 && (0.0..=9.0).contains(v));
    let Some(p_num) = p_num else {
        return Err(cx
            .err(
                "rs274::g10-p-range",
                format!("P value out of range (0-9) with G10 L{l}"),
                p.map_or(span, |p| p.span),
            )
            .with_note("P0 is the active system, P1 … P9 are G54 … G59.3"));
    };
    if let Some(w) = cx.words.take(b'I').or_else(|| cx.words.take(b'J')) {
        return Err(cx.err("rs274::g10-ij", "I J words not allowed with G10 L2", w.span));
    }
    let index = if p_num == 0.0 {
        cx.st.g5x_index.max(1)
    } else {
        p_num as u8
    };
    let (old, mut rotation) = g5x_from_params(params, index);
    let mut o = old.to_array();
    let r_word = cx.words.take(b'R');
    if let Some(r) = r_word {
        if l == 20 {
            return Err(cx.err("rs274::g10-l20-r", "R not allowed in G10 L20", r.span));
        }
        rotation = r.v;
    }
    let given = axis_values(cx)?;
    if l == 2 {
        for (k, v) in given.iter().enumerate() {
            if let Some(v) = v {
                o[k] = *v;
            }
        }
    } else {
        // L20: the origin that makes the current machine point read `given` in system P (with
        // the active G92 shift and tool length offset). Solved in the unrotated frame:
        // origin = machine − Rz(R)·(want + shift) − tlo. X and Y are solved together: with a
        // rotation, naming X alone moves the origin along the rotated X axis, so both origin
        // components change (LinuxCNC keeps the Y reading, as here).
        let mut frame = cx.st.frame;
        frame.set_origin(old);
        frame.set_rotation(rotation_z(rotation));
        let mut want = frame.to_program(&cx.st.position).to_array();
        for (k, v) in given.iter().enumerate() {
            if let Some(v) = v {
                want[k] = *v;
            }
        }
        frame.set_origin(Pose::ZERO);
        let zero_origin = frame.to_machine(&Pose::from_array(want)).to_array();
        let m = cx.st.position.to_array();
        let xy = given[0].is_some() || given[1].is_some();
        for k in 0..9 {
            let solve = given[k].is_some() || (k < 2 && xy && rotation != 0.0);
            if solve {
                o[k] = m[k] - zero_origin[k];
            }
        }
    }
    let offset = Pose::from_array(o);
    let base = system_base(index);
    params.set_pose_mm(base, &offset);
    params.set(base + 9, rotation);
    if index == cx.st.g5x_index {
        let (old_origin, old_rotation) = (*cx.st.frame.origin(), cx.st.xy_rotation_deg);
        let (shift, p) = (*cx.st.frame.shift(), cx.st.program_position());
        set_g5x(cx, offset, rotation);
        if rotation != old_rotation && (shift.x != 0.0 || shift.y != 0.0) {
            believe_as_linuxcnc(cx, p, (old_origin, old_rotation), (offset, rotation));
        }
        cx.out.push(Canon::SetG5xOffset { index, offset });
        cx.out.push(Canon::SetXyRotation { degrees: rotation });
    } else {
        cx.out.push(Canon::Comment {
            text: "interpreter: setting coordinate system origin".into(),
        });
    }
    Ok(())
}

/// LinuxCNC's position after G10 L2/L20 changes the rotation of the active system while a G92/G52
/// shift is applied. Its `convert_setup` re-derives the current point as
/// `p' = Rz(−R_new)·(Rz(R_old)·p + origin_old − origin_new)`, turning the shifted point as if the
/// shift were not there: off the machine's true point by `shift − Rz(R_old − R_new)·shift` in X Y.
/// The interpreter goes on from that point — the next move's unnamed axes, an inverse-time length,
/// an arc's start — in rs274 and milltask alike, so Stanok takes it as the position (the machine
/// then moves from where it stands to the next programmed point, as LinuxCNC's does).
fn believe_as_linuxcnc(cx: &mut Ctx<'_>, p: Pose, old: (Pose, f64), new: (Pose, f64)) {
    let turn = |x: f64, y: f64, deg: f64| {
        let (s, c) = deg.to_radians().sin_cos();
        (x * c - y * s, x * s + y * c)
    };
    let (x, y) = turn(p.x, p.y, old.1);
    let (x, y) = turn(x + old.0.x - new.0.x, y + old.0.y - new.0.y, -new.1);
    let mut believed = cx.st.program_position();
    believed.x = x;
    believed.y = y;
    cx.st.position = cx.st.frame.to_machine(&believed);
}

/// Makes `shift` the applied G92/G52 vector: the frame, #5210 = 1 and #5211…#5219.
fn apply_g92(cx: &mut Ctx<'_>, params: &mut Parameters, shift: Pose) {
    cx.st.frame.set_shift(shift);
    params.set(5210, 1.0);
    params.set_pose_mm(5211, &shift);
    cx.out.push(Canon::SetG92Offset { offset: shift });
}

/// G92, G52, G92.1, G92.2, G92.3 (LinuxCNC: one offset vector for G52 and G92).
pub(super) fn g92_family(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    code: u32,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    match code {
        G52 | G92 => {
            let given = axis_values(cx)?;
            if given.iter().all(Option::is_none) {
                return Err(cx.err(
                    "rs274::g92-axes-missing",
                    "All axes missing with g52 or g92",
                    span,
                ));
            }
            // Program coordinates are taken after the shift: p = q − shift, with q the point in
            // the rotated frame. G92: the current point reads `value`, so shift' = p + shift − value.
            // G52: shift' = value. Axes not named keep their component (spec ambiguity 4: LinuxCNC).
            let current = cx.st.program_position().to_array();
            let mut shift = cx.st.frame.shift().to_array();
            for (k, v) in given.iter().enumerate() {
                if let Some(v) = v {
                    shift[k] = if code == G92 {
                        current[k] + shift[k] - v
                    } else {
                        *v
                    };
                }
            }
            apply_g92(cx, params, Pose::from_array(shift));
        }
        G92_1 | G92_2 => {
            // G92.1 also forgets the values; G92.2 keeps them for a later G92.3.
            cx.st.frame.set_shift(Pose::ZERO);
            params.set(5210, 0.0);
            if code == G92_1 {
                params.set_pose_mm(5211, &Pose::ZERO);
            }
            cx.out.push(Canon::SetG92Offset { offset: Pose::ZERO });
        }
        G92_3 => {
            let shift = params.pose_mm(5211);
            apply_g92(cx, params, shift);
        }
        _ => return Err(unsupported(cx, "this G92 code", "coordinate systems", span)),
    }
    Ok(())
}

/// M2/M30: LinuxCNC's end-of-program resets, in its order. G92 offsets persist unless the
/// options disable it (LinuxCNC's DISABLE_G92_PERSISTENCE), tool length offset and diameter
/// mode persist.
pub(super) fn program_end(cx: &mut Ctx<'_>, params: &mut Parameters, pallet_shuttle: bool) {
    if !cx.fe.opts.g92_persistence && *cx.st.frame.shift() != Pose::ZERO {
        cx.st.frame.set_shift(Pose::ZERO);
        params.set(5210, 0.0);
        params.set_pose_mm(5211, &Pose::ZERO);
        cx.out.push(Canon::SetG92Offset { offset: Pose::ZERO });
    }
    select_coordinate_system(cx, params, 1, false);
    if cx.st.plane != Plane::XY {
        cx.st.plane = Plane::XY;
        cx.out.push(Canon::SelectPlane { plane: Plane::XY });
    }
    cx.st.distance = DistanceMode::Absolute;
    cx.st.feed_mode = FeedMode::UnitsPerMinute;
    cx.out.push(Canon::SetFeedMode {
        mode: FeedMode::UnitsPerMinute,
    });
    cx.st.feed = 0.0;
    cx.out.push(Canon::SetFeedRate { feed: 0.0 });
    if cx.fe.modes.feed_override_disabled {
        cx.fe.modes.feed_override_disabled = false;
        cx.out.push(Canon::SetFeedOverrideEnabled { enabled: true });
    }
    cx.st.spindle_on[0] = false;
    cx.fe.modes.spindle_direction = None;
    cx.fe.modes.css = false;
    cx.out.push(Canon::StopSpindle { spindle: 0 });
    cx.out.push(Canon::SetSpindleMode {
        spindle: 0,
        constant_surface_speed: false,
        max_rpm: 0.0,
    });
    if cx.st.mist {
        cx.st.mist = false;
        cx.out.push(Canon::Mist { on: false });
    }
    if cx.st.flood {
        cx.st.flood = false;
        cx.out.push(Canon::Flood { on: false });
    }
    cx.st.motion = MotionMode::Linear;
    if pallet_shuttle {
        cx.out.push(Canon::PalletShuttle);
    }
    cx.out.push(Canon::ProgramEnd);
}
