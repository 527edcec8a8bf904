//! G143 / G144 "approach until touching" and the offsets G40 removes axis by axis (spec axioma-3
//! §4.7, Examples 9.8 and 9.10, A11).
//!
//! ```text
//!  o = tool centre − programmed point (plane). A linear block P0 → P1, d = (P1 − P0)/|P1 − P0|:
//!    G143: o_k = −r·d_k   G144: o_k = +r·d_k   for each plane axis k written with Δ_k ≠ 0
//!    G40 (after G143/G144): o_k = 0 for each plane axis k written in the block
//!  tool target = P1 + o; no look-ahead is needed, the move is emitted at once.
//! ```

use super::emit::line_canon;
use super::{CompMode, Tag};
use crate::ctx::{Ctx, AXIS_WORDS};
use stanok_canon::Pose;

/// A G00/G01 block under G143/G144, or with offsets G40 has not removed yet.
pub(super) fn line(cx: &mut Ctx<'_>, r: f64, rapid: bool, end: Pose, feed: f64, tag: Tag) {
    let (a, b, _) = cx.st.plane.axes();
    let p0 = cx.st.program_position().to_array();
    let p1 = end.to_array();
    let written = [
        cx.words.is_used(AXIS_WORDS[a]),
        cx.words.is_used(AXIS_WORDS[b]),
    ];
    let delta = [p1[a] - p0[a], p1[b] - p0[b]];
    let len = delta[0].hypot(delta[1]);
    let from = cx.fe.ext.comp.tool.unwrap_or(cx.st.program_position());
    let c = &mut cx.fe.ext.comp;
    for k in 0..2 {
        if !written[k] {
            continue;
        }
        match c.mode {
            CompMode::Outside | CompMode::Inside if len > 1e-12 && delta[k].abs() > 1e-12 => {
                let sign = if c.mode == CompMode::Outside {
                    -1.0
                } else {
                    1.0
                };
                c.offset[k] = sign * r * delta[k] / len;
            }
            CompMode::Off => c.offset[k] = 0.0,
            _ => {}
        }
    }
    let mut target = p1;
    target[a] += c.offset[0];
    target[b] += c.offset[1];
    let target = Pose::from_array(target);
    c.tool = (c.offset != [0.0, 0.0]).then_some(target);
    cx.out
        .push(line_canon(&tag, from, target, rapid, feed).value);
}
