//! LinuxCNC's predefined read-only named parameters (`#<_x>`, `#<_metric>`, `#<_feed>` …): values
//! computed from the modal state when a program reads them (spec rs274ngc §3.5; the values and
//! their encodings checked against LinuxCNC 2.9's `rs274`, e.g. `#<_plane>` = 170 for G17 and
//! `#<_coord_system>` = 540 for G54: the code × 10, as `codes.rs` holds it).

use crate::codes::*;
use crate::params::Parameters;
use crate::state::{DistanceMode, ModalState, MotionMode};
use crate::Rs274State;
use stanok_canon::{FeedMode, LengthUnits, Plane, SpindleDirection};

/// LinuxCNC's version the parity is measured against: 2.9.
const VERSION: (f64, f64) = (2.9, 0.0);

fn flag(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// The value of predefined parameter `name` (without `#<`, `>`; lower case, leading `_`), or None
/// if `name` is not one of them.
pub fn predefined(
    name: &str,
    st: &ModalState,
    rs: &Rs274State,
    params: &Parameters,
    line: u32,
) -> Option<f64> {
    let units = st.units.mm_per_unit();
    let mut pos = st.program_position().to_array();
    // After G40, until a move, LinuxCNC's current point is the programmed one.
    if let (false, Some(q)) = (rs.comp.on(), rs.comp.program) {
        let (a, b, _) = st.plane.axes();
        pos[a] = q[0];
        pos[b] = q[1];
    }
    let axis = |i: usize| {
        if matches!(i, 3..=5) {
            pos[i]
        } else {
            pos[i] / units
        }
    };
    let abs = st.position.to_array();
    let abs_axis = |i: usize| {
        if matches!(i, 3..=5) {
            abs[i]
        } else {
            abs[i] / units
        }
    };
    Some(match name {
        "_vmajor" => VERSION.0,
        "_vminor" => VERSION.1,
        "_line" => line as f64,
        "_motion_mode" => match rs.motion_code {
            Some(c) => c as f64,
            None => match st.motion {
                MotionMode::Rapid => G0 as f64,
                MotionMode::Linear => G1 as f64,
                MotionMode::ArcCw => G2 as f64,
                MotionMode::ArcCcw => G3 as f64,
                MotionMode::None if rs.motion_unset => -1.0,
                MotionMode::None => G80 as f64,
            },
        },
        "_plane" => match st.plane {
            Plane::XY => G17 as f64,
            Plane::ZX => G18 as f64,
            Plane::YZ => G19 as f64,
        },
        "_ccomp" => match rs.comp.side {
            1 => G41 as f64,
            2 => G42 as f64,
            _ => G40 as f64,
        },
        "_metric" => flag(st.units == LengthUnits::Millimetres),
        "_imperial" => flag(st.units == LengthUnits::Inches),
        "_absolute" => flag(st.distance == DistanceMode::Absolute),
        "_incremental" => flag(st.distance == DistanceMode::Incremental),
        "_inverse_time" => flag(st.feed_mode == FeedMode::InverseTime),
        "_units_per_minute" => flag(st.feed_mode == FeedMode::UnitsPerMinute),
        "_units_per_rev" => flag(st.feed_mode == FeedMode::UnitsPerRevolution),
        "_coord_system" => match st.g5x_index {
            7 => G59_1 as f64,
            8 => G59_2 as f64,
            9 => G59_3 as f64,
            i => (G53 + 10 * i as u32) as f64,
        },
        "_tool_offset" => flag(*st.frame.tlo() != stanok_canon::Pose::ZERO),
        "_retract_r_plane" => flag(!st.retract_to_initial),
        "_retract_old_z" => flag(st.retract_to_initial),
        "_spindle_rpm_mode" => flag(!rs.css),
        "_spindle_css_mode" => flag(rs.css),
        "_ijk_absolute_mode" => flag(st.arc_distance == DistanceMode::Absolute),
        "_lathe_diameter_mode" => flag(st.diameter_mode),
        "_lathe_radius_mode" => flag(!st.diameter_mode),
        // LinuxCNC's spindle_turning: M19 and M6 leave it stopped without a stop command.
        "_spindle_on" => flag(st.spindle_on[0] && rs.spindle_direction.is_some()),
        "_spindle_cw" => flag(rs.spindle_direction == Some(SpindleDirection::Clockwise)),
        "_mist" => flag(st.mist),
        "_flood" => flag(st.flood),
        "_speed_override" => flag(!rs.speed_override_disabled),
        "_feed_override" => flag(!rs.feed_override_disabled),
        "_adaptive_feed" => 0.0,
        "_feed_hold" => 1.0,
        "_feed" => {
            if st.feed_mode == FeedMode::InverseTime {
                st.feed
            } else {
                st.feed / rs.feed_units.map_or(units, |u| u.mm_per_unit())
            }
        }
        "_rpm" => st.spindle_speed[0],
        "_x" => axis(0),
        "_y" => axis(1),
        "_z" => axis(2),
        "_a" => axis(3),
        "_b" => axis(4),
        "_c" => axis(5),
        "_u" => axis(6),
        "_v" => axis(7),
        "_w" => axis(8),
        "_abs_x" => abs_axis(0),
        "_abs_y" => abs_axis(1),
        "_abs_z" => abs_axis(2),
        "_abs_a" => abs_axis(3),
        "_abs_b" => abs_axis(4),
        "_abs_c" => abs_axis(5),
        "_abs_u" => abs_axis(6),
        "_abs_v" => abs_axis(7),
        "_abs_w" => abs_axis(8),
        "_current_tool" => st.current_tool as f64,
        // The tool's pocket as its table gives it (LinuxCNC's `P`; rs274 prints 10 for T10 P10);
        // −1 with the spindle empty, as milltask reads it (docs/linuxcnc.md, known differences:
        // the standalone rs274 starts with table slot 1 in the spindle).
        "_current_pocket" if st.current_tool == 0 => -1.0,
        "_current_pocket" => params
            .tools()
            .get(st.current_tool)
            .map_or(0.0, |t| t.pocket as f64),
        "_selected_tool" => st.selected_tool.map_or(-1.0, |t| t as f64),
        "_selected_pocket" => st.selected_tool.map_or(-1.0, |t| {
            params.tools().get(t).map_or(0.0, |t| t.pocket as f64)
        }),
        // Standalone interpretation (LinuxCNC's preview/rs274: 0; 1 = running on a machine).
        "_task" => 0.0,
        "_remap_level" => 0.0,
        _ => return None,
    })
}
