//! The AxiOMA coordinate chain as state: program frames (mirror G72/G73, scale G172/G173,
//! rotation G272/G273, each about its own pole), the programmed zero shift (G193/G194/G195), the
//! table zero offset (G53/G54…G59 with page) and the table workpiece system (G153/G154…G159 with
//! page). `apply_to` turns it into the pieces of a [`WorkFrame`] (spec axioma-1 §8.1):
//!
//! ```text
//!   F      = Rot ∘ S ∘ M            (fixed order, whatever order the program switched them on)
//!   shift  = v_prog + v_zo          (stage C; zero offsets are not mirrored, scaled or rotated)
//!   R, O   = G154…G159 page         (stage D: p_MCS = O + R(φ,θ,ψ)·p, R = Rz(φ)·Ry(θ)·Rz(ψ))
//! ```
//!
//! Poles are program (PCS) points resolved when the G73/G173/G273 block is read, with the program
//! position *before* the change; they are not themselves transformed (spec A4).

use crate::frame::{mul, rotation, Affine, Mat3, WorkFrame, IDENTITY};
use stanok_canon::setup::ControlData;
use stanok_canon::{Plane, Pose};

/// The chain's modal state. `Copy`: it lives in the interpreter's per-block state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxiomaChain {
    /// G73 factors per axis X, Y, Z: +1 or −1.
    pub mirror: [f64; 3],
    /// Pole component of each mirrored axis.
    pub mirror_pole: [f64; 3],
    /// G173 factors per axis (> 0).
    pub scale: [f64; 3],
    /// Pole component of each scaled axis.
    pub scale_pole: [f64; 3],
    /// G273 angle, degrees, counter-clockwise about the normal of `rotation_plane`.
    pub rotation_deg: f64,
    /// G273 pole.
    pub rotation_pole: [f64; 3],
    /// The plane the rotation was programmed in (it keeps it when the plane changes: spec A9).
    pub rotation_plane: Plane,
    /// G194/G195 vector, mm.
    pub prog_shift: [f64; 3],
    /// Active G54…G59 (1…6) and page (1…32); None = G53.
    pub zero: Option<(u8, u8)>,
    /// Active G154…G159 (1…6) and page; None = G153.
    pub wcs: Option<(u8, u8)>,
}

impl Default for AxiomaChain {
    fn default() -> Self {
        AxiomaChain {
            mirror: [1.0; 3],
            mirror_pole: [0.0; 3],
            scale: [1.0; 3],
            scale_pole: [0.0; 3],
            rotation_deg: 0.0,
            rotation_pole: [0.0; 3],
            rotation_plane: Plane::XY,
            prog_shift: [0.0; 3],
            zero: None,
            wcs: None,
        }
    }
}

fn diag(d: [f64; 3]) -> Mat3 {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// Euler ZY'Z'' rotation matrix, degrees.
pub fn euler_zyz(e: [f64; 3]) -> Mat3 {
    mul(
        &rotation(2, e[0]),
        &mul(&rotation(1, e[1]), &rotation(2, e[2])),
    )
}

impl AxiomaChain {
    /// F = Rot ∘ S ∘ M.
    pub fn frames(&self) -> Affine {
        let m = Affine::about(self.mirror_pole, diag(self.mirror));
        let s = Affine::about(self.scale_pole, diag(self.scale));
        let (_, _, n) = self.rotation_plane.axes();
        let r = Affine::about(self.rotation_pole, rotation(n, self.rotation_deg));
        r.after(&s.after(&m))
    }

    /// Writes F, the shift and the workpiece system into `frame` (tool length is set elsewhere).
    pub fn apply_to(&self, frame: &mut WorkFrame, control: &ControlData) {
        frame.set_frames(self.frames());
        let mut shift = Pose {
            x: self.prog_shift[0],
            y: self.prog_shift[1],
            z: self.prog_shift[2],
            ..Pose::ZERO
        };
        if let Some((system, page)) = self.zero {
            if let Some(z) = control.offsets.zero_offset(system, page) {
                let mut v = shift.to_array();
                for (a, b) in v.iter_mut().zip(z.offset.to_array()) {
                    *a += b;
                }
                shift = Pose::from_array(v);
            }
        }
        frame.set_shift(shift);
        let (r, o) = match self
            .wcs
            .and_then(|(s, p)| control.offsets.workpiece_frame(s, p))
        {
            Some(w) => (
                euler_zyz(w.euler),
                Pose {
                    x: w.origin[0],
                    y: w.origin[1],
                    z: w.origin[2],
                    ..Pose::ZERO
                },
            ),
            None => (IDENTITY, Pose::ZERO),
        };
        frame.set_rotation(r);
        frame.set_origin(o);
    }

    /// True when an odd number of the plane's two axes is mirrored: G02/G03 (and G41/G42) swap
    /// (spec axioma-1 §11.2, A2). `ctx.arc` gets this for free from the determinant of the frame;
    /// this is for reports and compensation.
    pub fn swaps_direction(&self, plane: Plane) -> bool {
        let (a, b, _) = plane.axes();
        self.mirror[a] * self.mirror[b] < 0.0
    }

    /// The in-plane scale factors differ (arcs then follow spec axioma-1 §11.3's k_max rule).
    pub fn non_uniform_in(&self, plane: Plane) -> Option<f64> {
        let (a, b, _) = plane.axes();
        let (ka, kb) = (self.scale[a], self.scale[b]);
        ((ka - kb).abs() > 1e-12).then_some(ka.max(kb))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::setup::WorkpieceFrame;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    }

    #[test]
    fn example_4_2_workpiece_system_rotated_90() {
        // Spec axioma-1 §20: G154/1 with O = (100,0,0), φ = 90°: (20,20) → MCS (80,20).
        let mut control = ControlData::default();
        control.offsets.workpiece[0][0] = WorkpieceFrame {
            origin: [100.0, 0.0, 0.0],
            euler: [90.0, 0.0, 0.0],
        };
        let chain = AxiomaChain {
            wcs: Some((1, 1)),
            ..Default::default()
        };
        let mut f = WorkFrame::default();
        chain.apply_to(&mut f, &control);
        let q = f.to_machine(&Pose {
            x: 20.0,
            y: 20.0,
            ..Pose::ZERO
        });
        assert!(close(q.xyz(), [80.0, 20.0, 0.0]), "{q:?}");
    }

    #[test]
    fn zero_offsets_are_not_mirrored() {
        // Mirror X about 0 with G54 = (100,0,0): programmed X10 → −10 + 100 = 90 (spec §8, "zero
        // offsets are not mirrored").
        let mut control = ControlData::default();
        control.offsets.zero[0][0].offset.x = 100.0;
        let chain = AxiomaChain {
            mirror: [-1.0, 1.0, 1.0],
            zero: Some((1, 1)),
            ..Default::default()
        };
        let mut f = WorkFrame::default();
        chain.apply_to(&mut f, &control);
        let q = f.to_machine(&Pose {
            x: 10.0,
            ..Pose::ZERO
        });
        assert!(close(q.xyz(), [90.0, 0.0, 0.0]), "{q:?}");
        assert!(chain.swaps_direction(Plane::XY));
        assert!(!chain.swaps_direction(Plane::YZ));
    }

    #[test]
    fn order_is_fixed_mirror_scale_rotation() {
        // Example 4.7: all poles (0,0): (x,y) → (√2(x+y), √2(x−y)); (20,20) → (56.5685, 0).
        let chain = AxiomaChain {
            mirror: [1.0, -1.0, 1.0],
            scale: [2.0; 3],
            rotation_deg: 45.0,
            ..Default::default()
        };
        let p = chain.frames().apply([50.0, 20.0, 0.0]);
        assert!(
            close(p, [98.99494936611666, 42.42640687119285, 0.0]),
            "{p:?}"
        );
    }
}
