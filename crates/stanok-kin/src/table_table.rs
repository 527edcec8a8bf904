//! Table-table (DD) machines: both rotary axes move the workpiece; the outer one (a trunnion) is
//! on the bed and carries the inner one (the rotary table), which carries the workpiece.
//!
//! Pairs (outer / inner): AC = A about +X carrying C about +Z; BC = B about +Y carrying C about +Z;
//! AB = A about +X carrying B about +Y. The outer axis passes through `outer_point`, the inner one
//! through `inner_point` (machine coordinates at zero rotary positions).

use crate::{Carrier, FiveAxis, KinError, RotaryAxis, RotaryPair};

/// A table-table machine of the given pair with base vector +Z.
pub fn table_table(
    pair: RotaryPair,
    outer_point: [f64; 3],
    inner_point: [f64; 3],
) -> Result<FiveAxis, KinError> {
    let (outer, inner) = match pair {
        RotaryPair::AC => (('A', [1.0, 0.0, 0.0]), ('C', [0.0, 0.0, 1.0])),
        RotaryPair::BC => (('B', [0.0, 1.0, 0.0]), ('C', [0.0, 0.0, 1.0])),
        RotaryPair::AB => (('A', [1.0, 0.0, 0.0]), ('B', [0.0, 1.0, 0.0])),
    };
    FiveAxis::new(
        vec![
            RotaryAxis::new(outer.0, Carrier::Table, outer.1, outer_point),
            RotaryAxis::new(inner.0, Carrier::Table, inner.1, inner_point),
        ],
        [0.0, 0.0, 1.0],
    )
}
