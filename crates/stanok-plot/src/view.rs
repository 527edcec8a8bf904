//! The four views of the sheet: projections, cells, fitting and the screen mapping.
//!
//! ```text
//!  +----------------------+----------------------+
//!  | XY (top)             | isometric            |      third-angle arrangement: the top view
//!  |   Y                  |    Z                 |      stands above the front view (same X
//!  |   ^                  |    ^                 |      columns), the side view right of it
//!  |   +--> X             |  Y/ \X               |      (same Z rows). All three orthographic
//!  +----------------------+----------------------+      views share one scale and are centred on
//!  | XZ (front)           | YZ (side)            |      the middle of the path's bounding box,
//!  |   Z                  |   Z                  |      so a point lines up across views.
//!  |   ^                  |   ^                  |
//!  |   +--> X             |   +--> Y             |      Screen y grows downwards: every mapping
//!  +----------------------+----------------------+      flips the vertical world axis.
//! ```
//!
//! The isometric view looks from (+1, −1, +1) (front, right, above) towards the origin: X runs
//! right-down at 30°, Y right-up at 30°, Z straight up. It has its own scale, fitted to the projected
//! bounding box; its scale bar is true for lengths parallel to the picture plane.

use stanok_geom::Vec3;

/// A rectangle in px.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rect {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) w: f64,
    pub(crate) h: f64,
}

impl Rect {
    fn centre(&self) -> [f64; 2] {
        [self.x + self.w / 2.0, self.y + self.h / 2.0]
    }
}

/// How world points become 2D view coordinates (still mm, y up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Projection {
    /// World axis `h` to the right, world axis `v` up.
    Ortho {
        /// Index (0 = X, 1 = Y, 2 = Z) of the horizontal axis.
        h: usize,
        /// Index of the vertical axis.
        v: usize,
    },
    /// Isometric from (+1, −1, +1).
    Iso,
}

const SQRT_2: f64 = std::f64::consts::SQRT_2;
/// √6.
const SQRT_6: f64 = 2.449_489_742_783_178;

impl Projection {
    /// View coordinates (mm, y up) of a world point.
    pub(crate) fn project(self, p: Vec3) -> [f64; 2] {
        match self {
            Projection::Ortho { h, v } => [p[h], p[v]],
            Projection::Iso => [(p[0] + p[1]) / SQRT_2, (-p[0] + p[1] + 2.0 * p[2]) / SQRT_6],
        }
    }

    /// The direction towards the viewer for an orthographic view (h × v), `None` for the isometric.
    pub(crate) fn normal(self) -> Option<Vec3> {
        match self {
            Projection::Ortho { h, v } => {
                let mut e_h = [0.0; 3];
                let mut e_v = [0.0; 3];
                e_h[h] = 1.0;
                e_v[v] = 1.0;
                Some(stanok_geom::cross(e_h, e_v))
            }
            Projection::Iso => None,
        }
    }

    /// The world axes shown by the direction arrows, with their view-plane directions (y up).
    pub(crate) fn arrows(self) -> Vec<(char, [f64; 2])> {
        const LETTERS: [char; 3] = ['X', 'Y', 'Z'];
        match self {
            Projection::Ortho { h, v } => vec![(LETTERS[h], [1.0, 0.0]), (LETTERS[v], [0.0, 1.0])],
            Projection::Iso => (0..3)
                .map(|i| {
                    let mut e = [0.0; 3];
                    e[i] = 1.0;
                    let d = self.project(e);
                    let n = d[0].hypot(d[1]);
                    (LETTERS[i], [d[0] / n, d[1] / n])
                })
                .collect(),
        }
    }
}

/// One view of the sheet.
#[derive(Debug, Clone, Copy)]
pub(crate) struct View {
    /// Short id used in element ids and `data-view` (`xy`, `xz`, `yz`, `iso`, `zx`).
    pub(crate) id: &'static str,
    /// Shown above the view.
    pub(crate) title: &'static str,
    pub(crate) projection: Projection,
    /// The whole cell.
    pub(crate) cell: Rect,
    /// The part of the cell the path is fitted into.
    pub(crate) plot: Rect,
}

impl View {
    /// True for the orthographic views, which get a grid and dimensioned extents.
    pub(crate) fn is_orthographic(&self) -> bool {
        self.projection != Projection::Iso
    }
}

/// Space inside a cell above the drawing (view title), below it (extent dimension, arrows, scale
/// bar) and at the sides (left: the other extent dimension and grid labels).
const TITLE_BAND: f64 = 28.0;
const FOOT_BAND: f64 = 64.0;
const LEFT_MARGIN: f64 = 66.0;
const RIGHT_MARGIN: f64 = 20.0;

/// The views a sheet can show.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewChoice {
    /// XY, isometric, XZ (or the lathe's ZX) and YZ in a 2 × 2 grid.
    All,
    /// XY (top) alone.
    Xy,
    /// XZ (front) alone.
    Xz,
    /// YZ (side) alone.
    Yz,
    /// The isometric view alone.
    Iso,
    /// The lathe's ZX view alone: Z to the right, X (the radius) up.
    Lathe,
}

fn single(choice: ViewChoice) -> (&'static str, &'static str, Projection) {
    match choice {
        ViewChoice::Xy | ViewChoice::All => ("xy", "XY (top)", Projection::Ortho { h: 0, v: 1 }),
        ViewChoice::Xz => ("xz", "XZ (front)", Projection::Ortho { h: 0, v: 2 }),
        ViewChoice::Yz => ("yz", "YZ (side)", Projection::Ortho { h: 1, v: 2 }),
        ViewChoice::Iso => ("iso", "isometric", Projection::Iso),
        ViewChoice::Lathe => ("zx", LATHE_TITLE, Projection::Ortho { h: 2, v: 0 }),
    }
}

const LATHE_TITLE: &str = "ZX (lathe: Z right, X radius up)";

/// The views for a sheet of `width` × `height` px with a header band of `header` px: the 2 × 2
/// grid for [`ViewChoice::All`] (for a lathe with the ZX view in place of XZ), else one view filling
/// the sheet.
pub(crate) fn layout(
    width: f64,
    height: f64,
    header: f64,
    choice: ViewChoice,
    lathe: bool,
) -> Vec<View> {
    let grid = choice == ViewChoice::All;
    let (cw, ch) = if grid {
        (width / 2.0, (height - header) / 2.0)
    } else {
        (width, height - header)
    };
    let view =
        |(id, title, projection): (&'static str, &'static str, Projection), col: f64, row: f64| {
            let cell = Rect {
                x: col * cw,
                y: header + row * ch,
                w: cw,
                h: ch,
            };
            let plot = Rect {
                x: cell.x + LEFT_MARGIN,
                y: cell.y + TITLE_BAND,
                w: (cw - LEFT_MARGIN - RIGHT_MARGIN).max(1.0),
                h: (ch - TITLE_BAND - FOOT_BAND).max(1.0),
            };
            View {
                id,
                title,
                projection,
                cell,
                plot,
            }
        };
    if !grid {
        return vec![view(single(choice), 0.0, 0.0)];
    }
    vec![
        view(single(ViewChoice::Xy), 0.0, 0.0),
        view(single(ViewChoice::Iso), 1.0, 0.0),
        view(
            single(if lathe {
                ViewChoice::Lathe
            } else {
                ViewChoice::Xz
            }),
            0.0,
            1.0,
        ),
        view(single(ViewChoice::Yz), 1.0, 1.0),
    ]
}

/// From view coordinates (mm, y up) to sheet px (y down).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mapping {
    /// px per mm.
    pub(crate) scale: f64,
    world_centre: [f64; 2],
    screen_centre: [f64; 2],
}

impl Mapping {
    pub(crate) fn to_screen(self, w: [f64; 2]) -> [f64; 2] {
        [
            self.screen_centre[0] + (w[0] - self.world_centre[0]) * self.scale,
            self.screen_centre[1] - (w[1] - self.world_centre[1]) * self.scale,
        ]
    }

    /// The inverse of [`Mapping::to_screen`].
    pub(crate) fn to_world(self, s: [f64; 2]) -> [f64; 2] {
        [
            self.world_centre[0] + (s[0] - self.screen_centre[0]) / self.scale,
            self.world_centre[1] - (s[1] - self.screen_centre[1]) / self.scale,
        ]
    }
}

/// Extent (min, max) of the projections of the eight corners of a box.
pub(crate) fn projected_extent(projection: Projection, lo: Vec3, hi: Vec3) -> ([f64; 2], [f64; 2]) {
    let mut min = [f64::INFINITY; 2];
    let mut max = [f64::NEG_INFINITY; 2];
    for corner in 0..8 {
        let p = [
            if corner & 1 == 0 { lo[0] } else { hi[0] },
            if corner & 2 == 0 { lo[1] } else { hi[1] },
            if corner & 4 == 0 { lo[2] } else { hi[2] },
        ];
        let q = projection.project(p);
        for i in 0..2 {
            min[i] = min[i].min(q[i]);
            max[i] = max[i].max(q[i]);
        }
    }
    (min, max)
}

/// The largest scale (px/mm) at which the box fits every given view; 10 px/mm for a box of no size.
fn fit_scale(views: &[View], lo: Vec3, hi: Vec3) -> f64 {
    let mut scale = f64::INFINITY;
    for v in views {
        let (min, max) = projected_extent(v.projection, lo, hi);
        for (extent, room) in [(max[0] - min[0], v.plot.w), (max[1] - min[1], v.plot.h)] {
            if extent > 1e-9 {
                scale = scale.min(room / extent);
            }
        }
    }
    if scale.is_finite() && scale > 0.0 {
        scale
    } else {
        10.0
    }
}

/// Mappings for the views of `layout`: one common scale for the orthographic ones, so that a
/// point lines up across them; the isometric view fits on its own.
pub(crate) fn fit(views: &[View], lo: Vec3, hi: Vec3) -> Vec<Mapping> {
    let ortho: Vec<View> = views
        .iter()
        .filter(|v| v.is_orthographic())
        .copied()
        .collect();
    let ortho_scale = fit_scale(&ortho, lo, hi);
    views
        .iter()
        .map(|v| {
            let scale = match v.projection {
                Projection::Iso => fit_scale(std::slice::from_ref(v), lo, hi),
                Projection::Ortho { .. } => ortho_scale,
            };
            let (min, max) = projected_extent(v.projection, lo, hi);
            Mapping {
                scale,
                world_centre: [(min[0] + max[0]) / 2.0, (min[1] + max[1]) / 2.0],
                screen_centre: v.plot.centre(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_axes_point_the_usual_way() {
        let [x, y, z] = [0, 1, 2].map(|i| {
            let mut e = [0.0; 3];
            e[i] = 1.0;
            Projection::Iso.project(e)
        });
        assert!(x[0] > 0.0 && x[1] < 0.0, "X right-down: {x:?}");
        assert!(y[0] > 0.0 && y[1] > 0.0, "Y right-up: {y:?}");
        assert!(z[0].abs() < 1e-15 && z[1] > 0.0, "Z up: {z:?}");
        // Orthonormal rows: a unit vector in the picture plane keeps its length.
        let d = Projection::Iso.project([1.0, 1.0, 0.0]);
        assert!((d[0].hypot(d[1]) - SQRT_2).abs() < 1e-12);
    }

    #[test]
    fn orthographic_views_share_scale_and_align() {
        let views = layout(1000.0, 840.0, 40.0, ViewChoice::All, false);
        let m = fit(&views, [0.0, 0.0, -10.0], [100.0, 50.0, 0.0]);
        assert_eq!(m[0].scale, m[2].scale);
        assert_eq!(m[0].scale, m[3].scale);
        // A point has the same screen x in the top and front views, the same y in front and side.
        let p = [30.0, 20.0, -4.0];
        let (top, front, side) = (
            m[0].to_screen(views[0].projection.project(p)),
            m[2].to_screen(views[2].projection.project(p)),
            m[3].to_screen(views[3].projection.project(p)),
        );
        assert!((top[0] - front[0]).abs() < 1e-9);
        assert!((front[1] - side[1]).abs() < 1e-9);
        assert_eq!(views[2].projection.normal(), Some([0.0, -1.0, 0.0]));
    }
}
