//! The work frame: the map from program coordinates to machine coordinates, composed from the
//! pieces each control defines, and its inverse.
//!
//! Both dialects fit one shape (X, Y, Z; the other axes only translate):
//!
//! ```text
//!   machine = origin + R · ( F(p) + shift ) + tlo
//!
//!   RS274/NGC (spec rs274ngc §3.1):  F = identity, shift = G92/G52, R = Rz(G5x rotation),
//!                                    origin = G54…G59.3, tlo = G43 offset
//!   AxiOMA (spec axioma-1 §8.1):     F = Rot∘S∘M (G273, G173, G73 about their poles),
//!                                    shift = G194/G195 + G54…G59 page, R and origin = G154…G159
//!                                    page, tlo = σ·V of G43/G44/G45 (axioma-3 §3.3)
//! ```
//!
//! The composition is kept as one affine map `A·p + b` with its inverse, recomputed only when a
//! piece changes (`WorkFrame::set_*`), so the per-block conversions are two small matrix products
//! (and nothing at all for the identity frame, the common case).
//!
//! Invariant: `to_program(to_machine(p)) == p` up to rounding for every frame whose linear part is
//! invertible (mirror ±1, scale factors > 0, rotations): property-tested below. The current
//! position is kept in machine coordinates; the program position is always derived through the
//! *current* frame, which is the spec's rule for a frame change (axioma-1 §8.2: recompute the
//! program position through the inverse of the new chain).

use stanok_canon::Pose;

/// 3 × 3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

/// The identity matrix.
pub const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `m · v`.
pub fn mul_vec(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}

/// `a · b`.
pub fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    r
}

/// Determinant.
pub fn det(m: &Mat3) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Inverse by the adjugate; None for a (near-)singular matrix.
pub fn inverse(m: &Mat3) -> Option<Mat3> {
    let d = det(m);
    if !d.is_finite() || d.abs() < 1e-12 {
        return None;
    }
    let c =
        |r0: usize, c0: usize, r1: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    Some([
        [c(1, 1, 2, 2) / d, -c(0, 1, 2, 2) / d, c(0, 1, 1, 2) / d],
        [-c(1, 0, 2, 2) / d, c(0, 0, 2, 2) / d, -c(0, 0, 1, 2) / d],
        [c(1, 0, 2, 1) / d, -c(0, 0, 2, 1) / d, c(0, 0, 1, 1) / d],
    ])
}

/// Rotation by `deg` about the axis with index `n` (0 = X, 1 = Y, 2 = Z), right-handed.
pub fn rotation(n: usize, deg: f64) -> Mat3 {
    let (s, c) = deg.to_radians().sin_cos();
    // Rotation from axis a towards axis b, the third axis n fixed: (a, b) = (Y, Z), (Z, X), (X, Y).
    let (a, b) = match n {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let mut m = IDENTITY;
    m[a][a] = c;
    m[a][b] = -s;
    m[b][a] = s;
    m[b][b] = c;
    m
}

/// An affine map of X, Y, Z: `m · p + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Linear part.
    pub m: Mat3,
    /// Translation.
    pub t: [f64; 3],
}

impl Affine {
    /// The identity map.
    pub const IDENTITY: Affine = Affine {
        m: IDENTITY,
        t: [0.0; 3],
    };

    /// `self(p)`.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let v = mul_vec(&self.m, p);
        [v[0] + self.t[0], v[1] + self.t[1], v[2] + self.t[2]]
    }

    /// `self ∘ inner`: first `inner`, then `self`.
    pub fn after(&self, inner: &Affine) -> Affine {
        Affine {
            m: mul(&self.m, &inner.m),
            t: self.apply(inner.t),
        }
    }

    /// A map that scales/mirrors/rotates about a pole: `pole + m·(p − pole)`.
    pub fn about(pole: [f64; 3], m: Mat3) -> Affine {
        let mp = mul_vec(&m, pole);
        Affine {
            m,
            t: [pole[0] - mp[0], pole[1] - mp[1], pole[2] - mp[2]],
        }
    }
}

/// The pieces of the chain (see the module doc) and their cached composition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkFrame {
    frames: Affine,
    shift: Pose,
    rotation: Mat3,
    origin: Pose,
    tlo: Pose,
    // Cache: machine_xyz = a.m · p + a.t; program_xyz = inv · (q − a.t).
    a: Affine,
    inv: Mat3,
    identity: bool,
    translation_only: bool,
}

impl Default for WorkFrame {
    fn default() -> Self {
        WorkFrame {
            frames: Affine::IDENTITY,
            shift: Pose::ZERO,
            rotation: IDENTITY,
            origin: Pose::ZERO,
            tlo: Pose::ZERO,
            a: Affine::IDENTITY,
            inv: IDENTITY,
            identity: true,
            translation_only: true,
        }
    }
}

impl WorkFrame {
    /// F: the program frames (mirror, scale, rotation about poles). Must be invertible.
    pub fn frames(&self) -> &Affine {
        &self.frames
    }
    /// The shift added before R.
    pub fn shift(&self) -> &Pose {
        &self.shift
    }
    /// R.
    pub fn rotation(&self) -> &Mat3 {
        &self.rotation
    }
    /// The origin added after R.
    pub fn origin(&self) -> &Pose {
        &self.origin
    }
    /// The tool length offset.
    pub fn tlo(&self) -> &Pose {
        &self.tlo
    }

    /// Sets F (returns false, leaving the frame unchanged, if it is not invertible).
    pub fn set_frames(&mut self, f: Affine) -> bool {
        if inverse(&f.m).is_none() {
            return false;
        }
        self.frames = f;
        self.update();
        true
    }
    /// Sets the shift.
    pub fn set_shift(&mut self, s: Pose) {
        self.shift = s;
        self.update();
    }
    /// Sets R (a rotation matrix).
    pub fn set_rotation(&mut self, r: Mat3) {
        self.rotation = r;
        self.update();
    }
    /// Sets the origin.
    pub fn set_origin(&mut self, o: Pose) {
        self.origin = o;
        self.update();
    }
    /// Sets the tool length offset.
    pub fn set_tlo(&mut self, t: Pose) {
        self.tlo = t;
        self.update();
    }

    fn update(&mut self) {
        let f = &self.frames;
        let s = self.shift.xyz();
        let inner = Affine {
            m: f.m,
            t: [f.t[0] + s[0], f.t[1] + s[1], f.t[2] + s[2]],
        };
        let outer = Affine {
            m: self.rotation,
            t: {
                let o = self.origin.xyz();
                let t = self.tlo.xyz();
                [o[0] + t[0], o[1] + t[1], o[2] + t[2]]
            },
        };
        self.a = outer.after(&inner);
        self.inv = inverse(&self.a.m).unwrap_or(IDENTITY);
        let zero_rest = |p: &Pose| {
            p.a == 0.0 && p.b == 0.0 && p.c == 0.0 && p.u == 0.0 && p.v == 0.0 && p.w == 0.0
        };
        self.translation_only = self.a.m == IDENTITY;
        self.identity = self.a == Affine::IDENTITY
            && zero_rest(&self.shift)
            && zero_rest(&self.origin)
            && zero_rest(&self.tlo);
    }

    /// The linear part of program → machine (for directions: arc axes, vectors).
    pub fn linear(&self) -> &Mat3 {
        &self.a.m
    }

    /// Program coordinates → machine coordinates.
    #[inline]
    pub fn to_machine(&self, p: &Pose) -> Pose {
        if self.identity {
            return *p;
        }
        let xyz = if self.translation_only {
            [p.x + self.a.t[0], p.y + self.a.t[1], p.z + self.a.t[2]]
        } else {
            self.a.apply(p.xyz())
        };
        let mut v = p.to_array();
        v[0] = xyz[0];
        v[1] = xyz[1];
        v[2] = xyz[2];
        let (s, o, t) = (
            self.shift.to_array(),
            self.origin.to_array(),
            self.tlo.to_array(),
        );
        for k in 3..9 {
            v[k] += s[k] + o[k] + t[k];
        }
        Pose::from_array(v)
    }

    /// Machine coordinates → program coordinates.
    #[inline]
    pub fn to_program(&self, q: &Pose) -> Pose {
        if self.identity {
            return *q;
        }
        let d = [q.x - self.a.t[0], q.y - self.a.t[1], q.z - self.a.t[2]];
        let xyz = if self.translation_only {
            d
        } else {
            mul_vec(&self.inv, d)
        };
        let mut v = q.to_array();
        v[0] = xyz[0];
        v[1] = xyz[1];
        v[2] = xyz[2];
        let (s, o, t) = (
            self.shift.to_array(),
            self.origin.to_array(),
            self.tlo.to_array(),
        );
        for k in 3..9 {
            v[k] -= s[k] + o[k] + t[k];
        }
        Pose::from_array(v)
    }

    /// The axis of a counter-clockwise rotation in the program frame → the axis of the same motion in
    /// the machine frame: `sign(det L) · L·n / |L·n|` (a mirror reverses the sense of rotation).
    pub fn arc_axis_to_machine(&self, n: [f64; 3]) -> [f64; 3] {
        if self.identity || self.a.m == IDENTITY {
            return n;
        }
        let v = mul_vec(&self.a.m, n);
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let k = det(&self.a.m).signum() / len;
        [v[0] * k, v[1] * k, v[2] * k]
    }

    /// A direction in the program frame → machine frame (linear part only, not normalised).
    pub fn direction_to_machine(&self, d: [f64; 3]) -> [f64; 3] {
        if self.identity {
            return d;
        }
        mul_vec(&self.a.m, d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
    }

    #[test]
    fn rs274_chain_matches_linuxcnc_formula() {
        // machine = Rot_R(p + g92) + g5x + tlo with R = 90°: p (1, 0) + g92 (1, 0) → (0, 2) + g5x (5, 0).
        let mut f = WorkFrame::default();
        f.set_shift(Pose {
            x: 1.0,
            ..Pose::ZERO
        });
        f.set_rotation(rotation(2, 90.0));
        f.set_origin(Pose {
            x: 5.0,
            ..Pose::ZERO
        });
        f.set_tlo(Pose {
            z: 2.0,
            ..Pose::ZERO
        });
        let q = f.to_machine(&Pose {
            x: 1.0,
            ..Pose::ZERO
        });
        assert!(close(q.xyz(), [5.0, 2.0, 2.0], 1e-12), "{q:?}");
        assert!(close(f.to_program(&q).xyz(), [1.0, 0.0, 0.0], 1e-12));
    }

    #[test]
    fn axioma_example_4_8_mirror_scale_rotate_about_one_pole() {
        // spec axioma-1 §11.5: poles (−5, 0), mirror X and Y, scale 2, rotate 90°: (10, 0) → (−5, −30).
        let pole = [-5.0, 0.0, 0.0];
        let m = Affine::about(pole, [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]);
        let s = Affine::about(pole, [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]]);
        let r = Affine::about(pole, rotation(2, 90.0));
        let f = r.after(&s.after(&m));
        assert!(close(f.apply([10.0, 0.0, 0.0]), [-5.0, -30.0, 0.0], 1e-12));
    }

    proptest! {
        #[test]
        fn chain_then_inverse_returns_the_point(
            p in prop::array::uniform3(-500.0f64..500.0),
            pole in prop::array::uniform3(-100.0f64..100.0),
            mirror in prop::array::uniform3(any::<bool>()),
            scale in prop::array::uniform3(0.1f64..10.0),
            angle in -360.0f64..360.0,
            shift in prop::array::uniform3(-100.0f64..100.0),
            euler in prop::array::uniform3(-180.0f64..180.0),
            origin in prop::array::uniform3(-300.0f64..300.0),
        ) {
            let d = |b: bool| if b { -1.0 } else { 1.0 };
            let m = Affine::about(pole, [[d(mirror[0]), 0.0, 0.0], [0.0, d(mirror[1]), 0.0], [0.0, 0.0, d(mirror[2])]]);
            let s = Affine::about(pole, [[scale[0], 0.0, 0.0], [0.0, scale[1], 0.0], [0.0, 0.0, scale[2]]]);
            let r = Affine::about(pole, rotation(2, angle));
            let mut f = WorkFrame::default();
            prop_assert!(f.set_frames(r.after(&s.after(&m))));
            f.set_shift(Pose { x: shift[0], y: shift[1], z: shift[2], ..Pose::ZERO });
            f.set_rotation(mul(&rotation(2, euler[0]), &mul(&rotation(1, euler[1]), &rotation(2, euler[2]))));
            f.set_origin(Pose { x: origin[0], y: origin[1], z: origin[2], a: 5.0, ..Pose::ZERO });
            let pose = Pose { x: p[0], y: p[1], z: p[2], a: 30.0, ..Pose::ZERO };
            let back = f.to_program(&f.to_machine(&pose));
            prop_assert!(close(back.xyz(), p, 1e-7), "{back:?} vs {p:?}");
            prop_assert!((back.a - 30.0).abs() < 1e-12);
        }
    }
}
