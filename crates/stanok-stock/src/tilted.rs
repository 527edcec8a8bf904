//! Culling for a tilted tool: which vertical lines a swept primitive can touch, and how high its
//! lowest point must be on each of them.
//!
//! A 5-axis finishing sweep is short (the chain closes when the flute end has moved half a cell
//! sideways, `sim.rs`) but its tool is long and leans: a Ø6 ball with 25 mm of flutes at 15° covers
//! a footprint box of ~70 mm², 7 000 lines at 0.1 mm, and the generic chord (`sweep.rs`, a quadric
//! in (s, t) against four lines) costs ~40 ns per line and primitive. Yet only the ball touches
//! the stock; the flutes above it stand over air. Two bounds make each primitive visit only the
//! lines it can cut, and the sphere has a closed form whatever the axis:
//!
//! 1. **The band** ([`TiltedPrim::x_range`]). At a fixed pose a frustum from height h0 to h1
//!    projects onto the XY plane inside the capsule of radius R (its larger radius) around the
//!    segment `A0 A1` (its axis points at h0 and h1, projected). Swept by `d`, that segment sweeps
//!    the parallelogram `P = A0 A1 ⊕ [0, d_xy]`, so the swept primitive projects inside
//!    `P ⊕ disk(R)`. A row y meets that convex set in one interval, whose ends lie within R of an
//!    edge of P: the interval is the hull of the four edges' capsule chords
//!    (`lathe::capsule_chord`). A sphere is the degenerate case `A0 = A1` (its centre).
//! 2. **The height bound** ([`HeightBound`]). Write the axis as `a = (sinθ·â, cosθ)` (â horizontal
//!    and unit, cosθ = a_z of either sign) and a point of the frustum as
//!    `tip + h·a + α·e1 + β·e2` with `e1 = (cosθ·â, −sinθ)` and `e2` horizontal, both ⊥ a, and
//!    `α² + β² ≤ R²`. Its height is `z = tip_z + h·cosθ − α·sinθ` and its offset along â from the
//!    tip is `s = h·sinθ + α·cosθ`. Eliminating h: `z = tip_z + s·cotθ − α/sinθ`. So on the
//!    vertical line at c, with `s = (c − tip_xy)·â`, every point of the primitive lies above both
//!    `tip_z + min(h0·cosθ, h1·cosθ) − R·sinθ` and `tip_z + s·cotθ − R/sinθ`. Over the sweep the
//!    tip moves affinely; `min_t max(f, g) ≥ max(min_t f, min_t g)`, and each is affine in t, so its
//!    minimum is at t = 0 or 1. The result is `max(k1, k2 + cotθ·(c·â))`: one dot product per line.
//!    A line whose material top is below it is skipped for that primitive: its chord lies above
//!    the material, and since the cutter (a convex stack) meets a line in one interval, the other
//!    primitives' chords still reach up to the top, so the cut is the same. With the highest
//!    material under the footprint known (the tiles' upper bounds, `mill.rs`), the same bound
//!    clips the band of each row to a half-line before any line is visited, and drops a
//!    primitive whose `k1` is above it for the whole sweep: the flutes of a leaning finishing
//!    tool then visit no line at all.
//! 3. **The sphere** is the same solid whatever the axis: a ball of radius r centred at
//!    `tip + hc·a` is swept by the vertical fast path (`sweep::chord_vertical`) as a sphere at
//!    height 0 over a vertical axis through that centre.
//! 4. **The sphere's floor** (the same role as item 2, per line, before the chord). With the
//!    centre at `m(t) = m0 + t·d`, the swept ball's lowest point on the line at c is
//!    `min_t (m_z(t) − √(r² − ρ(t)²))`, ρ(t) the horizontal distance of c from m(t). Each term is
//!    bounded alone: `m_z(t) ≥ min(m_z(0), m_z(1))` (that is `k1 + r`) and `ρ(t) ≥ ρ_min`, the
//!    distance of c from the centre's XY segment (one clamped projection). So every point of the
//!    ball is above `k1 + r − √(r² − ρ_min²)`, and nothing at all when `ρ_min > r`: a dot product,
//!    a clamp and one square root, against the two quadratics and up to six roots of the chord.
//!    On a finishing path most lines under the ball were cut to its surface by the pass before
//!    and the sweep before; their tops are above that floor only where this sweep cuts.
//!
//! `tests::tilted_sweeps_cut_what_the_brute_force_cuts` holds the culled sweep against every
//! line of the grid cut by the generic chord of every primitive.

use crate::lathe::capsule_chord;
use crate::sweep::{chord, chord_vertical, Prim, Sweep};
use crate::vec3::{add, scale, V3};

/// The lowest height a swept primitive can have on the vertical line through `c` (module doc,
/// item 2): `max(k1, k2 + dir·c)`, and for a sphere the floor of item 4.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HeightBound {
    k1: f64,
    k2: f64,
    dir: [f64; 2],
    /// A sphere's centre path in XY (start, displacement, 1/|e|², 0 when it stands), its radius²
    /// and its centre's lowest height less a nanometre (module doc, item 4); `r2 < 0` for a
    /// frustum.
    centre: [f64; 2],
    e: [f64; 2],
    inv_ee: f64,
    r2: f64,
    centre_z: f64,
}

impl HeightBound {
    /// The bound at the line through `c`, mm (∞: the primitive does not reach the line).
    #[cfg(test)]
    pub(crate) fn at(&self, c: [f64; 2]) -> f64 {
        if self.r2 >= 0.0 {
            let rest = self.r2 - self.rho_min2(c);
            return if rest < 0.0 {
                f64::INFINITY
            } else {
                self.centre_z - rest.sqrt()
            };
        }
        self.frustum_at(c)
    }

    #[inline]
    fn frustum_at(&self, c: [f64; 2]) -> f64 {
        self.k1
            .max(self.k2 + self.dir[0] * c[0] + self.dir[1] * c[1])
    }

    /// Item 4: the square of the centre path's nearest approach ρ_min to the line at `c`.
    #[inline]
    fn rho_min2(&self, c: [f64; 2]) -> f64 {
        let w = [c[0] - self.centre[0], c[1] - self.centre[1]];
        let t = ((w[0] * self.e[0] + w[1] * self.e[1]) * self.inv_ee).clamp(0.0, 1.0);
        let (x, y) = (w[0] - t * self.e[0], w[1] - t * self.e[1]);
        x * x + y * y
    }

    /// Whether every point of the swept primitive on the line at `c` is above `top` (the bound
    /// is above it). For a sphere without a root: `centre_z − √rest > top` ⟺ `rest < g²` with
    /// `g = centre_z − top > 0`.
    #[inline]
    pub(crate) fn above(&self, c: [f64; 2], top: f64) -> bool {
        if self.r2 >= 0.0 {
            let rest = self.r2 - self.rho_min2(c);
            let g = self.centre_z - top;
            return rest < 0.0 || (g > 0.0 && rest < g * g);
        }
        self.frustum_at(c) > top
    }
}

/// One primitive of a tilted tool, prepared for one sweep (module doc).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TiltedPrim {
    prim: Prim,
    sweep: Sweep,
    /// A sphere recentred on a vertical axis: the fast path applies.
    vertical: bool,
    /// The parallelogram's edges in (y, x), and the radius around them.
    edges: [[[f64; 2]; 2]; 4],
    radius: f64,
    /// Module doc, item 2.
    pub(crate) bound: HeightBound,
    /// The highest material under the footprint (∞: unknown); module doc, item 2.
    z_top: f64,
}

impl TiltedPrim {
    /// `prim` swept along `sw` (any axis).
    pub(crate) fn new(prim: &Prim, sw: &Sweep) -> TiltedPrim {
        let a = sw.axis;
        let (z0, z1) = (sw.p0[2], sw.p0[2] + sw.d[2]);
        let tip_z_min = z0.min(z1);
        let yx = |p: V3| [p[1], p[0]];
        let (prim_here, sweep, vertical, h0, h1, radius, k1) = match *prim {
            Prim::Sphere { hc, r } => {
                let centre = add(sw.p0, scale(a, hc));
                let sweep = Sweep {
                    p0: centre,
                    d: sw.d,
                    axis: [0.0, 0.0, 1.0],
                };
                let k1 = tip_z_min + hc * a[2] - r;
                (Prim::Sphere { hc: 0.0, r }, sweep, true, hc, hc, r, k1)
            }
            Prim::Frustum { h0, h1, r0, r1 } => {
                let big = r0.max(r1);
                let sin = (a[0] * a[0] + a[1] * a[1]).sqrt();
                let k1 = tip_z_min + (h0 * a[2]).min(h1 * a[2]) - big * sin;
                (*prim, *sw, false, h0, h1, big, k1)
            }
        };
        let a0 = add(sw.p0, scale(a, h0));
        let a1 = add(sw.p0, scale(a, h1));
        let edges = [
            [yx(a0), yx(a1)],
            [yx(add(a0, sw.d)), yx(add(a1, sw.d))],
            [yx(a0), yx(add(a0, sw.d))],
            [yx(a1), yx(add(a1, sw.d))],
        ];
        // The slope term exists for a frustum on a leaning axis only; the floor for a sphere.
        let mut bound = HeightBound {
            k1,
            k2: f64::NEG_INFINITY,
            dir: [0.0; 2],
            centre: [sweep.p0[0], sweep.p0[1]],
            e: [sw.d[0], sw.d[1]],
            inv_ee: match sw.d[0] * sw.d[0] + sw.d[1] * sw.d[1] {
                ee if ee > 1e-18 => 1.0 / ee,
                _ => 0.0,
            },
            r2: if vertical { radius * radius } else { -1.0 },
            // A nanometre below, so that rounding cannot lift the bound above the chord's end.
            centre_z: k1 + radius - 1e-9,
        };
        let sin = (a[0] * a[0] + a[1] * a[1]).sqrt();
        if !vertical && sin > 1e-6 {
            let hat = [a[0] / sin, a[1] / sin];
            let cot = a[2] / sin;
            let along = |v: V3| v[0] * hat[0] + v[1] * hat[1];
            bound.k2 = sw.p0[2] - along(sw.p0) * cot + (sw.d[2] - along(sw.d) * cot).min(0.0)
                - radius / sin;
            bound.dir = [hat[0] * cot, hat[1] * cot];
        }
        TiltedPrim {
            prim: prim_here,
            sweep,
            vertical,
            edges,
            radius,
            bound,
            z_top: f64::INFINITY,
        }
    }

    /// The same, knowing that no material under the footprint is higher than `z_top`: its band
    /// is clipped to the lines where its height bound is below that (module doc, item 2).
    pub(crate) fn below(mut self, z_top: f64) -> TiltedPrim {
        self.z_top = z_top;
        self
    }

    /// The x interval of row `y` the swept primitive can cover (module doc, item 1) and still
    /// meet material below [`TiltedPrim::below`]'s height.
    #[inline]
    pub(crate) fn x_range(&self, y: f64) -> Option<(f64, f64)> {
        let b = &self.bound;
        if b.k1 > self.z_top {
            return None;
        }
        let mut out: Option<(f64, f64)> = None;
        for [p, q] in self.edges {
            if let Some((a, b)) = capsule_chord(p, q, self.radius, y) {
                out = Some(out.map_or((a, b), |(x, z)| (x.min(a), z.max(b))));
            }
        }
        let (mut lo, mut hi) = out?;
        // k2 + dir·(x, y) ≤ z_top: a half-line in x (all or nothing when dir[0] = 0).
        let rest = self.z_top - b.k2 - b.dir[1] * y;
        if b.dir[0] > 1e-12 {
            hi = hi.min(rest / b.dir[0]);
        } else if b.dir[0] < -1e-12 {
            lo = lo.max(rest / b.dir[0]);
        } else if rest < 0.0 {
            return None;
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// The z chord of the vertical line through `c` with the swept primitive.
    #[inline]
    pub(crate) fn chord(&self, c: [f64; 2]) -> Option<(f64, f64)> {
        if self.vertical {
            chord_vertical(&self.prim, &self.sweep, c[0], c[1])
        } else {
            chord(&self.prim, &self.sweep, [c[0], c[1], 0.0], [0.0, 0.0, 1.0])
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::mill::tests::tool;
    use crate::mill::{MillModel, SweepHits};
    use crate::sweep::{chord, Sweep};
    use crate::tool::MillTool;
    use proptest::prelude::*;
    use stanok_canon::setup::CutterShape;

    /// Every line of the grid, every primitive, the generic chord: no band, no bound, no
    /// fast path. Returns the removed volume and the longest overlap of the bodies above the
    /// flutes with the material left.
    fn brute_force(m: &mut MillModel, t: &MillTool, sw: &Sweep) -> (f64, f64) {
        let g = &mut m.grid;
        let area = g.cell_area();
        let mut removed = 0.0;
        for j in 0..g.n[1] {
            for i in 0..g.n[0] {
                let c = g.centre(i, j);
                let mut range: Option<(f64, f64)> = None;
                for p in &t.cutter {
                    if let Some((a, b)) = chord(p, sw, [c[0], c[1], 0.0], [0.0, 0.0, 1.0]) {
                        range = Some(range.map_or((a, b), |(x, y)| (x.min(a), y.max(b))));
                    }
                }
                if let Some((a, b)) = range {
                    removed += g.lines[j * g.n[0] + i].cut(a, b).0 * area;
                }
            }
        }
        let mut body = 0.0f64;
        for p in t.flute_ext.iter().chain(&t.shank).chain(&t.holder) {
            for j in 0..g.n[1] {
                for i in 0..g.n[0] {
                    let c = g.centre(i, j);
                    if let Some((a, b)) = chord(p, sw, [c[0], c[1], 0.0], [0.0, 0.0, 1.0]) {
                        body = body.max(g.lines[j * g.n[0] + i].overlap(a, b));
                    }
                }
            }
        }
        (removed, body)
    }

    fn shape() -> impl Strategy<Value = (CutterShape, f64)> {
        (
            prop_oneof![
                Just(CutterShape::Flat),
                Just(CutterShape::Ball),
                Just(CutterShape::Bull),
                Just(CutterShape::Drill),
            ],
            0.5..4.0f64,
        )
    }

    /// A unit axis leaning up to `max_deg` from +Z (beyond 90°: pointing down).
    fn axis(max_deg: f64) -> impl Strategy<Value = [f64; 3]> {
        (0.0..max_deg, 0.0..360.0f64).prop_map(|(tilt, az)| {
            let (t, a) = (tilt.to_radians(), az.to_radians());
            [t.sin() * a.cos(), t.sin() * a.sin(), t.cos()]
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]
        /// A few consecutive tilted sweeps through a small stock (so later sweeps meet the
        /// surface the earlier ones left, with overhangs where the tool leans far): the culled
        /// sweep removes on every line what the brute force removes, and finds the same body
        /// collisions.
        #[test]
        fn tilted_sweeps_cut_what_the_brute_force_cuts(
            (kind, r) in shape(),
            axes in proptest::collection::vec(axis(120.0), 3),
            starts in proptest::collection::vec(proptest::array::uniform3(-1.0..1.0f64), 3),
            moves in proptest::collection::vec(proptest::array::uniform3(-4.0..4.0f64), 3),
        ) {
            let t = tool(kind, r);
            let mut fast = MillModel::new_box([0.0, 0.0, -8.0], [16.0, 12.0, 0.0], 0.25);
            let mut slow = fast.clone();
            for k in 0..3 {
                let sw = Sweep {
                    p0: [8.0 + 5.0 * starts[k][0], 6.0 + 4.0 * starts[k][1], -3.0 + 3.0 * starts[k][2]],
                    d: moves[k],
                    axis: axes[k],
                };
                let hits: SweepHits = fast.apply(&t, &sw);
                let (removed, body) = brute_force(&mut slow, &t, &sw);
                prop_assert!((hits.removed - removed).abs() <= 1e-4 * removed.max(1.0),
                    "sweep {k}: {} vs {removed}", hits.removed);
                let found = hits.flute.max(hits.shank).max(hits.holder);
                prop_assert!((found - body).abs() < 1e-4, "sweep {k}: bodies {found} vs {body}");
                for (a, b) in fast.grid.lines.iter().zip(&slow.grid.lines) {
                    prop_assert!((a.length() - b.length()).abs() < 1e-4, "{a:?} vs {b:?}");
                    prop_assert!((a.top().unwrap_or(0.0) - b.top().unwrap_or(0.0)).abs() < 1e-4,
                        "{a:?} vs {b:?}");
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        /// The sphere's floor (module doc, item 4) is below the swept ball's lowest point on every
        /// line it meets, and `above` says the same as the floor.
        #[test]
        fn the_sphere_floor_is_below_the_swept_ball(
            hc in 0.5..5.0f64, r in 0.5..5.0f64,
            axis in axis(120.0),
            p0 in proptest::array::uniform3(-2.0..2.0f64),
            d in proptest::array::uniform3(-3.0..3.0f64),
            c in proptest::array::uniform2(-8.0..8.0f64),
            top in -8.0..8.0f64,
        ) {
            let sw = Sweep { p0, d, axis };
            let tp = super::TiltedPrim::new(&crate::sweep::Prim::Sphere { hc, r }, &sw);
            let floor = tp.bound.at(c);
            if let Some((lo, _)) = tp.chord(c) {
                prop_assert!(floor <= lo + 1e-12, "{floor} > {lo}");
            }
            prop_assert_eq!(tp.bound.above(c, top), floor > top);
        }
    }

    #[test]
    fn a_standing_ball_has_its_floor_at_its_surface() {
        // d = 0: the floor is the ball's lower surface (less a nanometre), ∞ beyond its radius.
        let sw = Sweep {
            p0: [1.0, 2.0, -3.0],
            d: [0.0; 3],
            axis: [0.0, 0.6, 0.8],
        };
        let tp = super::TiltedPrim::new(&crate::sweep::Prim::Sphere { hc: 2.0, r: 2.0 }, &sw);
        // Centre (1, 3.2, −1.4); at 1.2 mm from it the surface is √(4 − 1.44) below.
        let floor = tp.bound.at([2.2, 3.2]);
        assert!((floor - (-1.4 - 2.56f64.sqrt())).abs() < 1e-8, "{floor}");
        assert_eq!(tp.bound.at([3.3, 3.2]), f64::INFINITY);
        let (lo, _) = tp.chord([2.2, 3.2]).unwrap();
        assert!((floor - lo).abs() < 1e-8);
    }

    #[test]
    fn a_leaning_ball_touches_only_its_lines() {
        // Ø6 ball, 40 mm of flutes leaning 15° along +X, 2 mm into the top, moved 0.1 mm: the
        // flutes' band reaches 10 mm beyond the ball, their height bound keeps them off the
        // lines beyond it, and the ball's recentred fast path cuts what the generic chord cuts.
        let t = tool(CutterShape::Ball, 3.0);
        let (s, c) = 15f64.to_radians().sin_cos();
        let sw = Sweep {
            p0: [10.0, 10.0, -2.0],
            d: [0.1, 0.0, 0.0],
            axis: [s, 0.0, c],
        };
        let flutes = super::TiltedPrim::new(&t.cutter[1], &sw);
        // From the ball's centre (h 3) less the radius to the flute end (h 40) plus the move
        // and the radius.
        let (xa, xb) = flutes.x_range(10.0).unwrap();
        assert!((xa - (10.0 + 3.0 * s - 3.0)).abs() < 1e-9, "{xa}");
        assert!((xb - (10.1 + 40.0 * s + 3.0)).abs() < 1e-9, "{xb}");
        // On the line 4 mm along the lean, the flutes start above the stock top.
        assert!(flutes.bound.at([14.0, 10.0]) > 0.0);
        let mut fast = MillModel::new_box([0.0, 0.0, -8.0], [30.0, 20.0, 0.0], 0.1);
        let mut slow = fast.clone();
        let hits = fast.apply(&t, &sw);
        let (removed, _) = brute_force(&mut slow, &t, &sw);
        assert!(
            (hits.removed - removed).abs() < 1e-6 * removed,
            "{} {removed}",
            hits.removed
        );
        assert!(hits.removed > 0.0);
    }
}
