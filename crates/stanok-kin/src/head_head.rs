//! Head-head (TT) machines: both rotary axes swivel the tool, the outer one carried by the slides,
//! the inner one by the outer.
//!
//! Pairs (outer / inner): BC = C about +Z carrying B about +Y (the fork head of the AxiOMA worked
//! examples); AC = C about +Z carrying A about +X; AB = B about +Y carrying A about +X. The inner
//! axis passes through the pivot point (0, 0, `pivot_mm`) above the head reference point, on the
//! outer axis; with `pivot_mm` = 0 the machine XYZ is the tool mount point and H = T + L·t.

use crate::{Carrier, FiveAxis, KinError, RotaryAxis, RotaryPair};

/// A head-head machine of the given pair with base vector +Z and the pivot `pivot_mm` above the
/// head reference point.
pub fn head_head(pair: RotaryPair, pivot_mm: f64) -> Result<FiveAxis, KinError> {
    let pivot = [0.0, 0.0, pivot_mm];
    let (outer, inner) = match pair {
        RotaryPair::BC => (('C', [0.0, 0.0, 1.0]), ('B', [0.0, 1.0, 0.0])),
        RotaryPair::AC => (('C', [0.0, 0.0, 1.0]), ('A', [1.0, 0.0, 0.0])),
        RotaryPair::AB => (('B', [0.0, 1.0, 0.0]), ('A', [1.0, 0.0, 0.0])),
    };
    FiveAxis::new(
        vec![
            RotaryAxis::new(outer.0, Carrier::Head, outer.1, pivot),
            RotaryAxis::new(inner.0, Carrier::Head, inner.1, pivot),
        ],
        [0.0, 0.0, 1.0],
    )
}
