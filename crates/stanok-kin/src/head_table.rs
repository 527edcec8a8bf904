//! Head-table (TD/DT) machines: one rotary axis turns the workpiece (a rotary table), the other
//! swivels the tool.
//!
//! Pairs (table / head): BC = C table about +Z + B head about +Y; AC = C table about +Z + A head
//! about +X; AB = A table about +X + B head about +Y. The table axis passes through `table_point`
//! (machine coordinates), the head axis through (0, 0, `pivot_mm`) relative to the head reference
//! point.

use crate::{Carrier, FiveAxis, KinError, RotaryAxis, RotaryPair};

/// A head-table machine of the given pair with base vector +Z.
pub fn head_table(
    pair: RotaryPair,
    table_point: [f64; 3],
    pivot_mm: f64,
) -> Result<FiveAxis, KinError> {
    let (table, head) = match pair {
        RotaryPair::BC => (('C', [0.0, 0.0, 1.0]), ('B', [0.0, 1.0, 0.0])),
        RotaryPair::AC => (('C', [0.0, 0.0, 1.0]), ('A', [1.0, 0.0, 0.0])),
        RotaryPair::AB => (('A', [1.0, 0.0, 0.0]), ('B', [0.0, 1.0, 0.0])),
    };
    FiveAxis::new(
        vec![
            RotaryAxis::new(head.0, Carrier::Head, head.1, [0.0, 0.0, pivot_mm]),
            RotaryAxis::new(table.0, Carrier::Table, table.1, table_point),
        ],
        [0.0, 0.0, 1.0],
    )
}
