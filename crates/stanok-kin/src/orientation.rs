//! Orientation math shared by every 5-axis machine and every front end.
//!
//! Conventions (spec axioma-4 §0.2, the same for the Balt-System and Mazatrol specs): right-handed
//! frames, positive rotation by the right-hand rule, angles in degrees at the API and radians
//! inside. A frame is a rotation matrix whose columns are its axes in the base; the tool vector of a
//! tool frame R is its third column R·(0,0,1) and points from the tool tip towards the holder.
//!
//! * [`rot`]: rotation by an angle about a unit axis (Rodrigues, via nalgebra).
//! * [`euler_zyz`] (ORIEULER: A2=φ about Z, B2=θ about Y', C2=ψ about Z'') and
//!   [`rpy_zyx`] (ORIRPY: C2=γ yaw about Z, B2=β pitch about Y', A2=α roll about X'').
//! * [`normalised`]: a programmed vector (A3/B3/C3, I J K) made unit, zero refused.
//! * [`signed_angle`]: the angle that turns p into q about w (Paden–Kahan subproblem 1), or None
//!   when p or q is parallel to w (the singular pose: the angle is undetermined).
//! * [`slerp`]: the great-circle interpolation of ORIVECT.
//! * [`reduce_180`]: an angle word reduced into [−180, 180] (spec axioma-4 §5.4).

pub use nalgebra::{Matrix3, Vector3};
use nalgebra::{Rotation3, Unit};

/// A vector shorter than this is taken as zero (a programmed vector, or a projection that vanishes
/// at a singular pose).
pub const ZERO_VECTOR: f64 = 1e-12;

/// Rotation by `deg` degrees about the unit vector `axis` (right-hand rule).
pub fn rot(axis: &Vector3<f64>, deg: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Unit::new_normalize(*axis), deg.to_radians())
}

/// ZY'Z'' Euler angles (ORIEULER, and the G154–G159 workpiece frames): Rz(φ)·Ry(θ)·Rz(ψ).
/// Its tool vector is (cos φ sin θ, sin φ sin θ, cos θ).
pub fn euler_zyz(phi: f64, theta: f64, psi: f64) -> Matrix3<f64> {
    let z = Vector3::z();
    let y = Vector3::y();
    (rot(&z, phi) * rot(&y, theta) * rot(&z, psi)).into_inner()
}

/// Roll-pitch-yaw, order ZY'X'' (ORIRPY): Rz(γ)·Ry(β)·Rx(α), with α = A2 roll, β = B2 pitch,
/// γ = C2 yaw.
pub fn rpy_zyx(alpha: f64, beta: f64, gamma: f64) -> Matrix3<f64> {
    (rot(&Vector3::z(), gamma) * rot(&Vector3::y(), beta) * rot(&Vector3::x(), alpha)).into_inner()
}

/// The tool vector (third column) of a frame.
pub fn tool_vector_of(frame: &Matrix3<f64>) -> Vector3<f64> {
    frame.column(2).into_owned()
}

/// A programmed direction made unit length; None for the zero vector (spec axioma-4 §5.5 [P]: an
/// error, the manual does not say which).
pub fn normalised(v: [f64; 3]) -> Option<Vector3<f64>> {
    let v = Vector3::from(v);
    let n = v.norm();
    (n > ZERO_VECTOR && n.is_finite()).then(|| v / n)
}

/// The angle in degrees, in (−180, 180], that turns `p` into `q` about the unit axis `w`
/// (`sang(w; p → q)` of spec axioma-4 §5.7): both are projected on the plane normal to `w` and the
/// signed angle between the projections is taken. None when either projection vanishes: the
/// vector lies on the axis and any angle does (the singular pose).
pub fn signed_angle(w: &Vector3<f64>, p: &Vector3<f64>, q: &Vector3<f64>) -> Option<f64> {
    let p_proj = p - w * w.dot(p);
    let q_proj = q - w * w.dot(q);
    if p_proj.norm() < 1e-9 || q_proj.norm() < 1e-9 {
        return None;
    }
    Some(
        w.dot(&p_proj.cross(&q_proj))
            .atan2(p_proj.dot(&q_proj))
            .to_degrees(),
    )
}

/// Spherical linear interpolation between unit vectors along the shorter great circle, s ∈ [0, 1]
/// (ORIVECT, spec axioma-4 §6.2): t(s) = [sin((1−s)Ω)·t0 + sin(sΩ)·t1] / sin Ω, Ω = acos(t0·t1).
/// At Ω = 0 it is t0; at Ω = 180° the plane is undefined and the caller must pass `via`, a
/// direction in the plane of the turn (spec: the rotary direction of the ORIAXES solution).
pub fn slerp(
    t0: &Vector3<f64>,
    t1: &Vector3<f64>,
    s: f64,
    via: Option<&Vector3<f64>>,
) -> Vector3<f64> {
    let cos_omega = t0.dot(t1).clamp(-1.0, 1.0);
    let omega = cos_omega.acos();
    if omega < 1e-12 {
        return *t0;
    }
    let sin_omega = omega.sin();
    if sin_omega < 1e-9 {
        // Antiparallel: turn about the normal of the plane (t0, via).
        let axis = via
            .map(|v| t0.cross(v))
            .filter(|a| a.norm() > ZERO_VECTOR)
            .unwrap_or_else(|| t0.cross(&any_normal(t0)));
        return rot(&axis, (s * omega).to_degrees()) * t0;
    }
    (t0 * ((1.0 - s) * omega).sin() + t1 * (s * omega).sin()) / sin_omega
}

/// The angle between two unit vectors, degrees in [0, 180].
pub fn angle_between(t0: &Vector3<f64>, t1: &Vector3<f64>) -> f64 {
    t0.dot(t1).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Some unit vector normal to `v`.
fn any_normal(v: &Vector3<f64>) -> Vector3<f64> {
    let helper = if v.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    v.cross(&helper).normalize()
}

/// An angle word reduced into [−180, 180] (spec axioma-4 §5.4 [P]): kept when |x| ≤ 180, else
/// x − 360·floor((x + 180)/360), which lies in [−180, 180).
pub fn reduce_180(x: f64) -> f64 {
    if x.abs() <= 180.0 {
        x
    } else {
        x - 360.0 * ((x + 180.0) / 360.0).floor()
    }
}

#[cfg(test)]
// The fixture headers print 1/√2 to four places; the tests compare with those numbers.
#[allow(clippy::approx_constant)]
mod tests {
    use super::*;

    fn close(a: &Vector3<f64>, b: [f64; 3], tol: f64) -> bool {
        (a - Vector3::from(b)).norm() < tol
    }

    #[test]
    fn euler_a2_90_b2_45_points_the_tool_along_plus_y() {
        // spec axioma-4 §5.2 check, Example 12.6 N50.
        let t = tool_vector_of(&euler_zyz(90.0, 45.0, 0.0));
        assert!(close(&t, [0.0, 0.707_106_781, 0.707_106_781], 1e-9));
    }

    #[test]
    fn rpy_matrix_is_the_worked_example() {
        // Example 12.7 N50 (A2=45, B2=15, C2=90): rows given in the fixture header.
        let r = rpy_zyx(45.0, 15.0, 90.0);
        let rows = [
            [0.0, -0.7071, 0.7071],
            [0.9659, 0.1830, 0.1830],
            [-0.2588, 0.6830, 0.6830],
        ];
        for (i, row) in rows.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!((r[(i, j)] - v).abs() < 1e-4, "R[{i}][{j}] = {}", r[(i, j)]);
            }
        }
    }

    #[test]
    fn angle_words_reduce_as_the_manual_says() {
        assert_eq!(reduce_180(-270.0), 90.0);
        assert_eq!(reduce_180(190.0), -170.0);
        assert_eq!(reduce_180(180.0), 180.0);
        assert_eq!(reduce_180(-180.0), -180.0);
    }

    #[test]
    fn slerp_stays_on_the_great_circle_and_unit() {
        let t0 = Vector3::new(0.0, 0.0, 1.0);
        let t1 = Vector3::new(1.0, 0.0, 0.0);
        let mid = slerp(&t0, &t1, 0.5, None);
        assert!(close(&mid, [0.5f64.sqrt(), 0.0, 0.5f64.sqrt()], 1e-12));
        let opposite = slerp(&t0, &-t0, 0.5, Some(&t1));
        assert!((opposite.norm() - 1.0).abs() < 1e-12);
        assert!(opposite.z.abs() < 1e-12 && (opposite.x.abs() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn zero_vector_is_refused() {
        assert!(normalised([0.0, 0.0, 0.0]).is_none());
        assert!(close(
            &normalised([0.0, 0.0, 5.0]).unwrap(),
            [0.0, 0.0, 1.0],
            1e-15
        ));
    }
}
