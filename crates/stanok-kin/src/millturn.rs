//! The mill-turn of the Mazatrol spec (family MT, e.g. a 5-axis turning centre): a B-axis milling
//! head about +Y (B = 0 puts the tool along +Z) and the C workpiece spindle about +Z, with machine
//! X programmed and shown as a **diameter** (joint X = 2 × the radial position of the head
//! reference point).
//!
//! The B axis is at `pivot_mm` above the head reference point (the Mazatrol Lp = A8 + B234); the
//! C axis is the Z axis of the machine (X = 0, Y = 0).

use crate::{Carrier, FiveAxis, KinError, RotaryAxis};

/// The B-head + C-spindle mill-turn with the B pivot `pivot_mm` above the gauge point.
pub fn millturn_bc(pivot_mm: f64) -> Result<FiveAxis, KinError> {
    Ok(FiveAxis::new(
        vec![
            RotaryAxis::new('B', Carrier::Head, [0.0, 1.0, 0.0], [0.0, 0.0, pivot_mm]),
            RotaryAxis::new('C', Carrier::Table, [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]),
        ],
        [0.0, 0.0, 1.0],
    )?
    .with_x_diameter(true))
}
