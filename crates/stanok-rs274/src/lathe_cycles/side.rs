//! Which side of the profile a G7x cycle leaves its allowance on — LinuxCNC 2.9's rule (its
//! `add_distance` in `interp_g7x.cc`), restated in the program's (z, x) plane.
//!
//! # The rule
//!
//! With I the entry point (S, or S moved along the cut axis to P0 when S lies past P0), v₁ = P0 − I
//! (the entry move) and v₂ = B − I, where B is the start of the profile's last element:
//!
//! ```text
//!   v₂ lies left of v₁  (the way from the entry to the profile's last element turns left)
//!        → the allowance is on the left of the profile as it runs
//!   v₂ lies right of v₁ → on its right
//!   v₂ parallel to v₁   → on the right *in LinuxCNC's working frame*: the (z, x) plane turned
//!                         for G72 and flipped so that the profile runs towards −real, +imag
//!                         (each flip mirrors, so "right" there is "left" in (z, x) after an
//!                         odd number of them)
//! ```
//!
//! (The `rs274` of LinuxCNC 2.9.0~pre1 this is read off; later 2.9 releases first append a line
//! from Pend to S's level to some G71/G72 profiles, which changes B and the frame.)
//!
//! For the usual profile (S outside the stock, the profile between S's level and P0) this puts
//! the allowance towards S. It matters where S is level with P0 (v₁ runs along the cut axis) or
//! the profile runs away from S.
//!
//! Invariant: the result depends only on the programmed geometry (P0, the chain, S, I), never
//! on Stanok's canonical frame; `sign_in_frame` converts it for an offset "to the left" there.

use stanok_geom::offset2d::{Seg2, P2};

/// +1 when the allowance lies on the left of the profile (as it runs) in the (z, x) plane,
/// −1 on its right. `entry` is I in (z, x); `facing`: the cycle works in G72's turned frame.
pub(super) fn left_in_plane(facing: bool, entry: P2, p0: P2, chain: &[Seg2]) -> f64 {
    let Some(last) = chain.last() else {
        return 1.0;
    };
    let (b, end) = (last.start(), last.end());
    let v1 = [p0[0] - entry[0], p0[1] - entry[1]];
    let v2 = [b[0] - entry[0], b[1] - entry[1]];
    // Parallel within rounding: B is P0 itself for a one-element profile, exactly so in
    // LinuxCNC, here recomputed from an arc's angle.
    let cross = v1[0] * v2[1] - v1[1] * v2[0];
    let cross = if cross.abs() <= 1e-9 * v1[0].hypot(v1[1]) * v2[0].hypot(v2[1]) {
        0.0
    } else {
        cross
    };
    // LinuxCNC's frame: G72 turns (z, x) by −90° (real = x, imag = −z), an orientation kept;
    // then flips imag where P0 lies above the end and real where P0 lies before it.
    let real = |p: P2| if facing { p[1] } else { p[0] };
    let imag = |p: P2| if facing { -p[0] } else { p[1] };
    let flips = usize::from(imag(p0) - imag(end) > 0.0) + usize::from(real(p0) - real(end) < 0.0);
    let orient = if flips % 2 == 0 { 1.0 } else { -1.0 };
    // In that frame: left when v₂ turns left of v₁, else (parallel included) right.
    let left_there = cross * orient > 0.0;
    if left_there == (orient > 0.0) {
        1.0
    } else {
        -1.0
    }
}
