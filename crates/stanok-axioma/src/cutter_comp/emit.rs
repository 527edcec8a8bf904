//! Compensated motions as Canon: every point is a program-coordinate pose converted with the frame
//! of the block that programmed it (`Tag`), so a finalised move keeps its block's span, N label and
//! frame whenever it is emitted.

use super::contour::Tag;
use stanok_canon::{ArcMove, Canon, LineMove, Pose, Spanned};
use stanok_geom::offset2d::P2;

/// `from` with the non-plane axes of `end`.
pub(super) fn with_non_plane(from: Pose, end: Pose, plane: stanok_canon::Plane) -> Pose {
    let (a, b, _) = plane.axes();
    let mut to = end.to_array();
    let f = from.to_array();
    to[a] = f[a];
    to[b] = f[b];
    Pose::from_array(to)
}

fn spanned(tag: &Tag, value: Canon) -> Spanned<Canon> {
    // Built through `new` (not a literal): later fields of `Spanned` keep their defaults.
    let mut s = Spanned::new(tag.span, value);
    s.block_number = tag.number;
    s
}

pub(super) fn line_canon(
    tag: &Tag,
    from: Pose,
    to: Pose,
    rapid: bool,
    feed: f64,
) -> Spanned<Canon> {
    let m = LineMove {
        start: tag.frame.to_machine(&from),
        end: tag.frame.to_machine(&to),
        feed: if rapid { 0.0 } else { feed },
    };
    spanned(
        tag,
        if rapid {
            Canon::StraightTraverse(m)
        } else {
            Canon::StraightFeed(m)
        },
    )
}

pub(super) fn arc_canon(
    tag: &Tag,
    from: Pose,
    to: Pose,
    centre: P2,
    ccw: bool,
    feed: f64,
) -> Spanned<Canon> {
    let (a, b, n) = tag.plane.axes();
    let mut c = from.to_array();
    c[a] = centre[0];
    c[b] = centre[1];
    let mut normal = [0.0; 3];
    normal[n] = if ccw { 1.0 } else { -1.0 };
    spanned(
        tag,
        Canon::ArcFeed(ArcMove {
            start: tag.frame.to_machine(&from),
            end: tag.frame.to_machine(&to),
            centre: tag.frame.to_machine(&Pose::from_array(c)).xyz(),
            axis: tag.frame.arc_axis_to_machine(normal),
            turns: 1,
            plane: tag.plane,
            feed,
        }),
    )
}
