//! RS274/NGC work offsets: the G54…G59.3 table in parameters #5221…#5390, G10 L2/L20 writing it,
//! selecting a system, and the resets of a program end (M2/M30), in LinuxCNC's order.

use super::unsupported;
use crate::ctx::{Ctx, AXIS_WORDS};
use crate::params::Parameters;
use crate::state::{DistanceMode, MotionMode};
use stanok_canon::{Canon, Diagnostic, FeedMode, Plane, Pose};
use stanok_syntax::ColSpan;

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

pub fn g5x_from_params(params: &Parameters, index: u8) -> (Pose, f64) {
    let base = 5201 + 20 * index as usize;
    let mut v = [0.0; 9];
    for (k, x) in v.iter_mut().enumerate() {
        *x = params.get(base + k);
    }
    (Pose::from_array(v), params.get(base + 9))
}

/// Makes a G54…G59.3 system active. LinuxCNC re-announces the G92 offset on a G5x selection but
/// not on the reset of a program end.
pub(super) fn select_coordinate_system(
    cx: &mut Ctx<'_>,
    params: &Parameters,
    index: u8,
    announce_g92: bool,
) {
    let (offset, rotation) = g5x_from_params(params, index);
    cx.st.g5x_index = index;
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
pub(super) fn g10(
    cx: &mut Ctx<'_>,
    params: &mut Parameters,
    span: ColSpan,
) -> Result<(), Diagnostic> {
    let Some(l) = cx.words.take(b'L') else {
        return Err(cx.err(
            "rs274::g10-l-missing",
            "Line with G10 does not have L2, L10, L11, L20 or L1",
            span,
        ));
    };
    let l_num = l.v.round() as i64;
    if l_num != 2 && l_num != 20 {
        return Err(unsupported(
            cx,
            &format!("G10 L{}", l.v),
            "coordinate systems and offsets",
            l.span,
        ));
    }
    let Some(p) = cx.words.take(b'P') else {
        return Err(cx.err("rs274::g10-p-missing", "P word missing with G10", span));
    };
    let p_num = p.v.round();
    if (p.v - p_num).abs() > 1e-6 || !(0.0..=9.0).contains(&p_num) {
        return Err(cx.err(
            "rs274::g10-p-range",
            "P value out of range with G10 L2",
            p.span,
        ));
    }
    let index = if p_num == 0.0 {
        cx.st.g5x_index.max(1)
    } else {
        p_num as u8
    };
    let (mut offset, mut rotation) = g5x_from_params(params, index);
    let mut o = offset.to_array();
    let r_word = cx.words.take(b'R');
    if l_num == 2 {
        for (k, &letter) in AXIS_WORDS.iter().enumerate() {
            if let Some(v) = cx.words.take(letter) {
                o[k] = if crate::ctx::is_linear(k) {
                    cx.mm(v.v)
                } else {
                    v.v
                };
            }
        }
        if let Some(r) = r_word {
            rotation = r.v;
        }
    } else {
        // L20: choose the origin so that the current machine point has the given program values.
        if let Some(r) = r_word {
            rotation = r.v;
        }
        let mut frame = cx.st.frame;
        frame.set_origin(offset);
        frame.set_rotation(rotation_z(rotation));
        let mut want = frame.to_program(&cx.st.position).to_array();
        let mut given = [false; 9];
        for (k, &letter) in AXIS_WORDS.iter().enumerate() {
            if let Some(v) = cx.words.take(letter) {
                want[k] = if crate::ctx::is_linear(k) {
                    cx.mm(v.v)
                } else {
                    v.v
                };
                given[k] = true;
            }
        }
        frame.set_origin(Pose::ZERO);
        let zero_origin = frame.to_machine(&Pose::from_array(want)).to_array();
        let m = cx.st.position.to_array();
        for k in 0..9 {
            if given[k] {
                o[k] = m[k] - zero_origin[k];
            }
        }
    }
    offset = Pose::from_array(o);
    let base = 5201 + 20 * index as usize;
    for (k, v) in o.iter().enumerate() {
        params.set(base + k, *v);
    }
    params.set(base + 9, rotation);
    if index == cx.st.g5x_index {
        set_g5x(cx, offset, rotation);
        cx.out.push(Canon::SetG5xOffset { index, offset });
        cx.out.push(Canon::SetXyRotation { degrees: rotation });
    } else {
        cx.out.push(Canon::Comment {
            text: "interpreter: setting coordinate system origin".into(),
        });
    }
    Ok(())
}

/// M2/M30: LinuxCNC's end-of-program resets, in its order.
pub(super) fn program_end(cx: &mut Ctx<'_>, params: &Parameters, pallet_shuttle: bool) {
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
    cx.st.spindle_on[0] = false;
    cx.out.push(Canon::StopSpindle { spindle: 0 });
    cx.out.push(Canon::SetSpindleMode {
        spindle: 0,
        css_speed: 0.0,
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
