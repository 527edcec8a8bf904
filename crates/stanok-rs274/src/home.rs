//! RS274/NGC predefined positions (spec rs274ngc §4.16): G28/G30 go to the position stored in
//! #5161…#5169 / #5181…#5189 (machine coordinates, machine units), G28.1/G30.1 store the current
//! one there.

use crate::ctx::Ctx;
use crate::params::Parameters;
use stanok_canon::{Diagnostic, Pose};

fn base(g28: bool) -> usize {
    if g28 {
        5161
    } else {
        5181
    }
}

/// G28 / G30: a rapid to the intermediate point given by the axis words (program coordinates,
/// G90/G91 as for any move; with no axis words the current point, which LinuxCNC still "moves"
/// to), then a rapid to the stored position — for the named axes only, or all axes when none is
/// named. As in LinuxCNC, "named axes" are axes of the program frame: the stored machine point is
/// expressed in program coordinates and its named components replace the intermediate point's.
pub(super) fn go_home(cx: &mut Ctx<'_>, params: &Parameters, g28: bool) -> Result<(), Diagnostic> {
    let (via, named) = cx.end_point()?;
    cx.straight(true, via, 0.0);
    let stored = params.pose_mm(base(g28));
    let home = cx.st.frame.to_program(&stored).to_array();
    let all = !named.iter().any(|&n| n);
    let mut end = via.to_array();
    for k in 0..9 {
        if all || named[k] {
            end[k] = home[k];
        }
    }
    cx.straight(true, Pose::from_array(end), 0.0);
    Ok(())
}

/// G28.1 / G30.1: store the current machine position.
pub(super) fn store_home(cx: &mut Ctx<'_>, params: &mut Parameters, g28: bool) {
    params.set_pose_mm(base(g28), &cx.st.position);
}
