//! Properties of the 3D compensation offsets (spec axioma-4 §7.8, §7.9, §7.11) on random
//! tangents, normals, tool vectors and cutters, 1e-9 mm:
//!
//! * peripheral (CUT3DC): Q + ISD·t − P is perpendicular to t, of length R, on the side
//!   side·(t × p);
//! * limiting surface (CUT3DCC): the tool side passes through P (axis at R) and the lowest point
//!   of the cutter in the direction −n lies on the surface plane through P;
//! * face (CUT3DF/FS/FF, no side tilt): the cutter surface touches P with its normal there equal
//!   to the programmed normal (the torus tube centre is P + r·n on the tube circle), and the
//!   cutter's lowest point towards −n is on the surface plane (touching, not cutting).

use proptest::prelude::*;
use stanok_geom::offset3d::{face_offset, limiting_offset, peripheral_offset, Cutter};
use stanok_geom::{add, cross, dot, norm, normalize, scale, sub, Vec3};

fn dir() -> impl Strategy<Value = Vec3> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0).prop_filter_map("non-zero", |(x, y, z)| {
        normalize([x, y, z]).filter(|_| (x * x + y * y + z * z) > 0.01)
    })
}

/// Lowest value of n·X over the cutter with tip `q`, axis `t`, radius R and corner r.
fn lowest(q: Vec3, t: Vec3, c: Cutter, n: Vec3) -> f64 {
    let centre = add(q, scale(t, c.corner));
    let n_perp = sub(n, scale(t, dot(n, t)));
    dot(n, centre) - (c.radius - c.corner) * norm(n_perp) - c.corner
}

fn cutter() -> impl Strategy<Value = Cutter> {
    (0.5f64..10.0, 0u8..3, 0.05f64..0.95).prop_map(|(radius, kind, k)| Cutter {
        radius,
        corner: match kind {
            0 => 0.0,
            1 => radius,
            _ => k * radius,
        },
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn peripheral_axis_at_r_on_its_side(p in dir(), t in dir(), radius in 0.1f64..20.0, isd in -10.0f64..10.0, left in any::<bool>()) {
        prop_assume!(norm(cross(t, p)) > 0.05);
        let side = if left { 1.0 } else { -1.0 };
        let v = peripheral_offset(p, t, radius, side, isd).unwrap();
        let w = add(v, scale(t, isd));
        prop_assert!(dot(w, t).abs() < 1e-9);
        prop_assert!((norm(w) - radius).abs() < 1e-9);
        prop_assert!(dot(w, scale(cross(t, p), side)) > 0.0);
    }

    #[test]
    fn limiting_surface_touched_by_the_end(p in dir(), t in dir(), n in dir(), c in cutter(), left in any::<bool>()) {
        prop_assume!(norm(cross(t, p)) > 0.05 && dot(t, n) > 0.1);
        let side = if left { 1.0 } else { -1.0 };
        let v = limiting_offset(p, t, n, c, side).unwrap();
        // The side passes through P: P is R from the axis.
        let axis_off = sub(v, scale(t, dot(v, t)));
        prop_assert!((norm(axis_off) - c.radius).abs() < 1e-9);
        // The end touches the plane through P with normal n.
        prop_assert!(lowest(v, t, c, n).abs() < 1e-9, "lowest {}", lowest(v, t, c, n));
    }

    #[test]
    fn face_touches_the_point_with_the_normal(p in dir(), m in dir(), beta in -1.3f64..1.3, c in cutter()) {
        // n ⟂ p; t in the (p, n) plane, at most 74° from n.
        let Some(n) = normalize(sub(m, scale(p, dot(m, p)))) else { return Ok(()) };
        prop_assume!(norm(sub(m, scale(p, dot(m, p)))) > 0.05);
        let t = add(scale(n, beta.cos()), scale(p, beta.sin()));
        let q = face_offset(p, t, n, c);
        // The tube centre of the contact is P + r·n, on the circle of radius R − r about the axis
        // r above the tip.
        let k = scale(n, c.corner);
        let centre = add(q, scale(t, c.corner));
        let d = sub(k, centre);
        prop_assert!(dot(d, t).abs() < 1e-9, "off the tube plane by {}", dot(d, t));
        let radial = norm(sub(d, scale(t, dot(d, t))));
        // A flat end touching with its rim, or any cutter standing on the normal (radial 0).
        prop_assert!((radial - (c.radius - c.corner)).abs() < 1e-9 || (radial < 1e-9 && beta.abs() < 1e-12), "radial {radial}");
        // Touching, not cutting: the cutter's lowest point towards −n is on the surface.
        prop_assert!(lowest(q, t, c, n).abs() < 1e-9, "lowest {}", lowest(q, t, c, n));
    }
}
