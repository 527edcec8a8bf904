//! The rotary chain shared by every 5-axis machine type (spec axioma-4 §4.5, §5.7; the Balt-System
//! and Mazatrol machines are instances of the same model).
//!
//! # Model
//!
//! Each rotary orientation axis k is carried either by the **head** (it moves the tool) or by the
//! **table** (it moves the workpiece); within each carrier the axes are listed outer → inner (head:
//! outer is carried by the slides, inner is nearest the spindle; table: outer is on the bed, inner
//! carries the workpiece). Axis k turns by θ_k about the unit vector a_k = sign_k·direction_k through
//! the point q_k (both at all rotary axes 0; head points relative to the head reference point H,
//! table points in machine coordinates). `sign_k` = +1 is the right-hand rule of GOST 23597-79;
//! −1 reverses the axis, as cvu-five-axis.md recommends a per-axis sign setting.
//!
//! `F_k(x) = q_k + Rot(a_k, θ_k)·(x − q_k)` (a rigid rotation), and with c0 the tool offset vector
//! (tool tip → tool mount point at zero rotary positions; L·b for a plain tool length L):
//!
//! ```text
//!  R_H = Rot(a_h1, θ_h1)·Rot(a_h2, θ_h2)      R_W = Rot(a_w1, θ_w1)·Rot(a_w2, θ_w2)
//!  D(θ_h) = F_h1(F_h2(−c0))                   vector from H to the tool tip
//!  G(x)   = F_w1(F_w2(x))                     a table-fixed point → machine coordinates
//!  forward: T = G⁻¹(H + D(θ_h)),  t = R_Wᵀ·R_H·b
//!  inverse: H = G(T) − D(θ_h)
//! ```
//!
//! T is the tool tip in the table-fixed frame (= machine frame when the table axes are at 0), the
//! frame a 5-axis program is written in; H (the joints X Y Z) is what the linear slides position.
//! Rotary values pass through unchanged: a pose carries the rotary axes, and [`FiveAxis::orient`]
//! turns a tool vector into them.
//!
//! # Orientation → rotary axes (Paden–Kahan subproblem 2)
//!
//! Every head/head, table/table or head/table pair reduces to `Rot(u, α)·Rot(v, β)·b = t`:
//! head/head u = a_h1, α = θ_h1, v = a_h2, β = θ_h2; table/table u = a_w2, α = −θ_w2, v = a_w1,
//! β = −θ_w1; head/table u = a_w, α = −θ_w, v = a_h, β = θ_h. With k = u·v:
//!
//! ```text
//!  x = (k(v·b) − u·t)/(k² − 1)     y = (k(u·t) − v·b)/(k² − 1)
//!  z² = (1 − x² − y² − 2xyk)/|u × v|²           z² < 0: the vector is unreachable
//!  c = x·u + y·v ± z·(u × v)                    two branches (one when z = 0)
//!  β = sang(v; b → c)    α = sang(u; c → t)
//! ```
//!
//! Singular poses: when c (or t) lies on the axis u, α is undetermined (the tool is parallel to
//! the outer rotary axis, e.g. vertical on a C/B head) and the axis **keeps its current value**;
//! likewise for β. So reaching such a pose never makes the free axis jump.
//!
//! # Choosing among solutions
//!
//! Candidates: the two branches, each axis unwrapped to the value nearest its current one and that
//! value ±360° (all within the travel limits). The choice (spec axioma-4 §5.7 [P]) is:
//! 1. drop candidates outside the limits;
//! 2. the least time: the minimum of max_k(|Δθ_k| / v_max,k);
//! 3. tie: the least Σ|Δθ_k|;
//! 4. tie: the tilting axis (the solver's v axis) at a value ≥ 0;
//! 5. nothing left: [`KinError::OrientationUnreachable`].
//!
//! Invariants (property-tested in `tests/props.rs`): `forward(inverse(p)) = p` within 1e-9 for every
//! reachable pose, and `tool_vector(orient(t)) = t` within 1e-9 for every reachable t.

use crate::orientation::{rot, signed_angle};
use crate::{Joints, KinError, Kinematics};
use nalgebra::{Rotation3, Vector3};
use serde::{Deserialize, Serialize};
use stanok_canon::Pose;

/// Which body a rotary axis moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Carrier {
    /// The axis tilts or turns the tool (a swivel head).
    Head,
    /// The axis tilts or turns the workpiece (a rotary table, a C spindle).
    Table,
}

/// One rotary orientation axis, as machine data gives it.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RotaryAxis {
    /// The program letter: 'A', 'B' or 'C' (the pose slot it drives).
    pub name: char,
    /// Head or table.
    pub carrier: Carrier,
    /// Axis direction with every rotary axis at 0 (machine frame; need not be unit).
    pub direction: [f64; 3],
    /// A point on the axis, mm: relative to the head reference point for head axes, in machine
    /// coordinates for table axes.
    #[serde(default)]
    pub point: [f64; 3],
    /// +1: positive rotation by the right-hand rule about `direction` (GOST 23597-79); −1 reversed.
    #[serde(default = "plus_one")]
    pub sign: f64,
    /// Travel limits, degrees (−inf/inf = endless).
    #[serde(default = "minus_infinity")]
    pub min: f64,
    /// Upper travel limit, degrees.
    #[serde(default = "infinity")]
    pub max: f64,
    /// deg/min, used to pick the fastest orientation solution.
    #[serde(default = "default_rotary_rate")]
    pub max_velocity: f64,
}

fn plus_one() -> f64 {
    1.0
}
fn minus_infinity() -> f64 {
    f64::NEG_INFINITY
}
fn infinity() -> f64 {
    f64::INFINITY
}
fn default_rotary_rate() -> f64 {
    3600.0
}

impl RotaryAxis {
    /// An axis through `point` along `direction`, right-handed, endless, 3600 deg/min.
    pub fn new(name: char, carrier: Carrier, direction: [f64; 3], point: [f64; 3]) -> Self {
        RotaryAxis {
            name,
            carrier,
            direction,
            point,
            sign: 1.0,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
            max_velocity: default_rotary_rate(),
        }
    }

    /// The same axis with travel limits, degrees.
    pub fn with_limits(mut self, min: f64, max: f64) -> Self {
        self.min = min;
        self.max = max;
        self
    }

    /// The pose slot (3 = A, 4 = B, 5 = C).
    pub fn slot(&self) -> usize {
        match self.name.to_ascii_uppercase() {
            'A' => 3,
            'B' => 4,
            _ => 5,
        }
    }

    /// The unit axis with the sign applied.
    fn unit(&self) -> Vector3<f64> {
        Vector3::from(self.direction).normalize() * self.sign.signum()
    }

    fn rotation(&self, deg: f64) -> Rotation3<f64> {
        rot(&self.unit(), deg)
    }

    /// `F_k(x) = q + Rot(a, θ)(x − q)`.
    fn apply(&self, deg: f64, x: &Vector3<f64>) -> Vector3<f64> {
        let q = Vector3::from(self.point);
        q + self.rotation(deg) * (x - q)
    }

    /// `F_k⁻¹(x) = q + Rot(a, θ)ᵀ(x − q)`.
    fn unapply(&self, deg: f64, x: &Vector3<f64>) -> Vector3<f64> {
        let q = Vector3::from(self.point);
        q + self.rotation(deg).transpose() * (x - q)
    }

    fn within_limits(&self, deg: f64) -> bool {
        deg >= self.min - 1e-9 && deg <= self.max + 1e-9
    }
}

/// A machine with up to two rotary orientation axes on head and/or table (see the module doc).
/// The per-type constructors live in `head_head.rs`, `table_table.rs`, `head_table.rs` and
/// `millturn.rs`.
#[derive(Debug, Clone, PartialEq)]
pub struct FiveAxis {
    /// Head axes, outer → inner.
    head: Vec<RotaryAxis>,
    /// Table axes, outer → inner.
    table: Vec<RotaryAxis>,
    /// Spindle base vector b (tool direction at zero rotary positions), unit.
    base: Vector3<f64>,
    /// c0: tool tip → tool mount point at zero rotary positions, mm.
    tool_offset: Vector3<f64>,
    /// Subtracted from H to give the joints X Y Z (where the linear axes count from), mm.
    linear_offset: Vector3<f64>,
    /// Joint X is a diameter value (a mill-turn's X on the C spindle).
    x_is_diameter: bool,
}

/// One axis of the (u, v) reduction: which axis it is and the sign between the solver angle and
/// the axis value.
#[derive(Clone, Copy)]
struct SolverAxis<'a> {
    axis: &'a RotaryAxis,
    /// α (or β) = sign·θ.
    sign: f64,
}

impl FiveAxis {
    /// Builds a machine from its rotary axes (listed outer → inner within each carrier; at most
    /// two in all) and its spindle base vector.
    pub fn new(axes: Vec<RotaryAxis>, base: [f64; 3]) -> Result<Self, KinError> {
        if axes.len() > 2 {
            return Err(KinError::Degenerate(
                "at most two rotary orientation axes".into(),
            ));
        }
        let base = crate::orientation::normalised(base)
            .ok_or_else(|| KinError::Degenerate("zero spindle base vector".into()))?;
        let mut slots = Vec::new();
        for a in &axes {
            if !matches!(a.name.to_ascii_uppercase(), 'A' | 'B' | 'C') {
                return Err(KinError::Degenerate(format!(
                    "rotary axis {} is not A, B or C",
                    a.name
                )));
            }
            if crate::orientation::normalised(a.direction).is_none() {
                return Err(KinError::Degenerate(format!(
                    "axis {} has a zero direction",
                    a.name
                )));
            }
            if slots.contains(&a.slot()) {
                return Err(KinError::Degenerate(format!("axis {} given twice", a.name)));
            }
            slots.push(a.slot());
        }
        let (head, table) = axes.into_iter().partition(|a| a.carrier == Carrier::Head);
        Ok(FiveAxis {
            head,
            table,
            base,
            tool_offset: Vector3::zeros(),
            linear_offset: Vector3::zeros(),
            x_is_diameter: false,
        })
    }

    /// The same machine with the tool offset c0 (tool tip → mount point at zero rotary positions,
    /// mm). A plain tool length L along the base vector is `base·L`.
    pub fn with_tool_offset(mut self, c0: [f64; 3]) -> Self {
        self.tool_offset = Vector3::from(c0);
        self
    }

    /// The same machine with a tool of length `length` mm along its base vector.
    pub fn with_tool_length(self, length: f64) -> Self {
        let c0 = self.base * length;
        self.with_tool_offset(c0.into())
    }

    /// The same machine with joints X Y Z = H − `offset` (where the linear scales count from).
    pub fn with_linear_offset(mut self, offset: [f64; 3]) -> Self {
        self.linear_offset = Vector3::from(offset);
        self
    }

    /// Joint X is a diameter value (doubles the radial position).
    pub fn with_x_diameter(mut self, on: bool) -> Self {
        self.x_is_diameter = on;
        self
    }

    /// True if joint X is a diameter value (a mill-turn on its C spindle).
    pub fn x_is_diameter(&self) -> bool {
        self.x_is_diameter
    }

    /// The spindle base vector b.
    pub fn base(&self) -> [f64; 3] {
        self.base.into()
    }

    /// The rotary axes: head outer → inner, then table outer → inner.
    pub fn rotary_axes(&self) -> impl Iterator<Item = &RotaryAxis> {
        self.head.iter().chain(self.table.iter())
    }

    fn angle(pose_or_joints: &[f64; 9], axis: &RotaryAxis) -> f64 {
        pose_or_joints[axis.slot()]
    }

    /// D(θ_h): the vector from the head reference point to the tool tip.
    fn head_to_tip(&self, v: &[f64; 9]) -> Vector3<f64> {
        self.head
            .iter()
            .rev()
            .fold(-self.tool_offset, |x, a| a.apply(Self::angle(v, a), &x))
    }

    /// G(x): a table-fixed point to machine coordinates.
    fn table_to_machine(&self, v: &[f64; 9], x: Vector3<f64>) -> Vector3<f64> {
        self.table
            .iter()
            .rev()
            .fold(x, |x, a| a.apply(Self::angle(v, a), &x))
    }

    /// G⁻¹(x).
    fn machine_to_table(&self, v: &[f64; 9], x: Vector3<f64>) -> Vector3<f64> {
        self.table
            .iter()
            .fold(x, |x, a| a.unapply(Self::angle(v, a), &x))
    }

    /// t = R_Wᵀ·R_H·b for the rotary values of `pose`, in the table-fixed frame.
    pub fn tool_vector_at(&self, pose: &Pose) -> [f64; 3] {
        (self.orientation_rotation(pose) * self.base).into()
    }

    /// G(r)⁻¹: the home coordinates (machine position with every table axis at 0) of the
    /// table-fixed point at machine position `x` when the rotary axes are at `pose`. The identity
    /// on a machine without table axes.
    pub fn table_home(&self, pose: &Pose, x: [f64; 3]) -> [f64; 3] {
        self.machine_to_table(&pose.to_array(), Vector3::from(x))
            .into()
    }

    /// G(r): the machine position at `pose` of the table-fixed point with home coordinates `l`.
    pub fn table_at(&self, pose: &Pose, l: [f64; 3]) -> [f64; 3] {
        self.table_to_machine(&pose.to_array(), Vector3::from(l))
            .into()
    }

    /// R = R_Wᵀ·R_H: the rotation the rotary axes at `pose` give the tool relative to the
    /// workpiece (R_H = head rotations outer → inner, R_W = table rotations outer → inner), so
    /// that the tool vector is R·b. Row-major. Used for the Balt-System CVU=3 local frame, whose
    /// rotation is built "with the same formula as u" (cvu-five-axis.md §5.10).
    pub fn orientation_frame(&self, pose: &Pose) -> [[f64; 3]; 3] {
        let m = self.orientation_rotation(pose).into_inner();
        std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
    }

    fn orientation_rotation(&self, pose: &Pose) -> Rotation3<f64> {
        let v = pose.to_array();
        let r_h = self.head.iter().fold(Rotation3::identity(), |r, a| {
            r * a.rotation(Self::angle(&v, a))
        });
        let r_w = self.table.iter().fold(Rotation3::identity(), |r, a| {
            r * a.rotation(Self::angle(&v, a))
        });
        r_w.transpose() * r_h
    }

    /// The (u, v) reduction of the two rotary axes, or None with fewer than two.
    fn solver_axes(&self) -> Option<(SolverAxis<'_>, SolverAxis<'_>)> {
        match (self.head.as_slice(), self.table.as_slice()) {
            ([h1, h2], []) => Some((
                SolverAxis {
                    axis: h1,
                    sign: 1.0,
                },
                SolverAxis {
                    axis: h2,
                    sign: 1.0,
                },
            )),
            ([], [w1, w2]) => Some((
                SolverAxis {
                    axis: w2,
                    sign: -1.0,
                },
                SolverAxis {
                    axis: w1,
                    sign: -1.0,
                },
            )),
            ([h], [w]) => Some((
                SolverAxis {
                    axis: w,
                    sign: -1.0,
                },
                SolverAxis { axis: h, sign: 1.0 },
            )),
            _ => None,
        }
    }

    /// The raw branches for tool vector `t` (table-fixed frame, normalised here): each is the
    /// (u-axis, v-axis) values in degrees in (−180, 180], with an undetermined (singular) angle
    /// set to that axis' value in `current`.
    pub fn branches(
        &self,
        t: [f64; 3],
        current: &Pose,
    ) -> Result<Vec<[(usize, f64); 2]>, KinError> {
        let t = crate::orientation::normalised(t).ok_or(KinError::ZeroVector)?;
        let (su, sv) = self
            .solver_axes()
            .ok_or_else(|| KinError::Degenerate("orientation needs two rotary axes".into()))?;
        let u = su.axis.unit();
        let v = sv.axis.unit();
        let b = self.base;
        let k = u.dot(&v);
        let denom = k * k - 1.0;
        if denom.abs() < 1e-12 {
            return Err(KinError::Degenerate("parallel rotary axes".into()));
        }
        let x = (k * v.dot(&b) - u.dot(&t)) / denom;
        let y = (k * u.dot(&t) - v.dot(&b)) / denom;
        let uxv = u.cross(&v);
        let z2 = (1.0 - x * x - y * y - 2.0 * x * y * k) / uxv.norm_squared();
        if z2 < -1e-9 {
            return Err(KinError::OrientationUnreachable);
        }
        let z = z2.max(0.0).sqrt();
        let cur = current.to_array();
        let mut out = Vec::with_capacity(2);
        for zs in [z, -z] {
            let c = u * x + v * y + uxv * zs;
            let beta = signed_angle(&v, &b, &c);
            let alpha = signed_angle(&u, &c, &t);
            let theta_u = alpha.map_or(cur[su.axis.slot()], |a| a * su.sign);
            let theta_v = beta.map_or(cur[sv.axis.slot()], |b| b * sv.sign);
            let branch = [(su.axis.slot(), theta_u), (sv.axis.slot(), theta_v)];
            if !out.contains(&branch) {
                out.push(branch);
            }
            if z == 0.0 {
                break;
            }
        }
        Ok(out)
    }

    /// The pose `current` with its rotary axes turned to give tool vector `t` (table-fixed frame),
    /// chosen by the rule of the module doc. X Y Z are untouched.
    pub fn orient(&self, t: [f64; 3], current: &Pose) -> Result<Pose, KinError> {
        let (su, sv) = self
            .solver_axes()
            .ok_or_else(|| KinError::Degenerate("orientation needs two rotary axes".into()))?;
        let cur = current.to_array();
        let mut best: Option<([f64; 9], (f64, f64, bool))> = None;
        for branch in self.branches(t, current)? {
            let cand_u = unwrapped_candidates(su.axis, branch[0].1, cur[su.axis.slot()]);
            let cand_v = unwrapped_candidates(sv.axis, branch[1].1, cur[sv.axis.slot()]);
            for &tu in &cand_u {
                for &tv in &cand_v {
                    let du = (tu - cur[su.axis.slot()]).abs();
                    let dv = (tv - cur[sv.axis.slot()]).abs();
                    let time = (du / su.axis.max_velocity).max(dv / sv.axis.max_velocity);
                    let key = (time, du + dv, tv < 0.0);
                    let better = match &best {
                        None => true,
                        Some((_, k)) => prefer(key, *k),
                    };
                    if better {
                        let mut p = cur;
                        p[su.axis.slot()] = tu;
                        p[sv.axis.slot()] = tv;
                        best = Some((p, key));
                    }
                }
            }
        }
        best.map(|(p, _)| Pose::from_array(p))
            .ok_or(KinError::OrientationUnreachable)
    }

    /// The Balt-System CVU choice between the solutions (cvu-five-axis §5.8): every branch and
    /// whole-turn variant within the travel limits is a candidate; the one with the least
    /// |Δθo| + |Δθi| wins, on a tie (1e-9°) the smaller |Δθo| (θo: the outer axis — the head's
    /// first, else the table's first), then the first solution S1. Unlike [`Self::orient`]
    /// (AxiOMA's least time), the axes' speeds play no part.
    pub fn orient_least_travel(&self, t: [f64; 3], current: &Pose) -> Result<Pose, KinError> {
        const TIE: f64 = 1e-9;
        let (su, sv) = self
            .solver_axes()
            .ok_or_else(|| KinError::Degenerate("orientation needs two rotary axes".into()))?;
        let u_is_outer = match (self.head.as_slice(), self.table.as_slice()) {
            ([h1, _], []) => std::ptr::eq(h1, su.axis),
            ([], [w1, _]) => std::ptr::eq(w1, su.axis),
            _ => std::ptr::eq(self.table.first().unwrap_or(su.axis), su.axis),
        };
        let cur = current.to_array();
        // (Σ|Δ|, |Δθo|): the first candidate met keeps a tie, and branches come S1 first.
        let mut best: Option<([f64; 9], (f64, f64))> = None;
        for branch in self.branches(t, current)? {
            let cand_u = unwrapped_candidates(su.axis, branch[0].1, cur[su.axis.slot()]);
            let cand_v = unwrapped_candidates(sv.axis, branch[1].1, cur[sv.axis.slot()]);
            for &tu in &cand_u {
                for &tv in &cand_v {
                    let du = (tu - cur[su.axis.slot()]).abs();
                    let dv = (tv - cur[sv.axis.slot()]).abs();
                    let key = (du + dv, if u_is_outer { du } else { dv });
                    let better = match &best {
                        None => true,
                        Some((_, k)) if (key.0 - k.0).abs() > TIE => key.0 < k.0,
                        Some((_, k)) => key.1 < k.1 - TIE,
                    };
                    if better {
                        let mut p = cur;
                        p[su.axis.slot()] = tu;
                        p[sv.axis.slot()] = tv;
                        best = Some((p, key));
                    }
                }
            }
        }
        best.map(|(p, _)| Pose::from_array(p))
            .ok_or(KinError::OrientationUnreachable)
    }

    /// How fast each joint moves per mm of path over a sampled segment: the largest
    /// |Δjoint| / Δs between consecutive samples (`samples[i]` at path length `i·length/(n−1)`).
    /// The planner divides each joint's velocity limit by it to bound the path speed.
    pub fn joint_rates(&self, samples: &[Pose], length: f64) -> Result<[f64; 9], KinError> {
        let mut rates = [0.0; 9];
        if samples.len() < 2 || length <= 0.0 {
            return Ok(rates);
        }
        let ds = length / (samples.len() - 1) as f64;
        let mut prev = self.inverse(&samples[0])?;
        for s in &samples[1..] {
            let q = self.inverse(s)?;
            for k in 0..9 {
                rates[k] = f64::max(rates[k], (q[k] - prev[k]).abs() / ds);
            }
            prev = q;
        }
        Ok(rates)
    }
}

/// Lexicographic comparison of (time, Σ|Δ|, v-axis negative) with a 1e-9 tie tolerance.
fn prefer(a: (f64, f64, bool), b: (f64, f64, bool)) -> bool {
    const TIE: f64 = 1e-9;
    if (a.0 - b.0).abs() > TIE {
        return a.0 < b.0;
    }
    if (a.1 - b.1).abs() > TIE {
        return a.1 < b.1;
    }
    !a.2 && b.2
}

/// `value` moved by whole turns to the one nearest `current`, with that one ±360°, within the
/// axis limits.
fn unwrapped_candidates(axis: &RotaryAxis, value: f64, current: f64) -> Vec<f64> {
    let nearest = value + 360.0 * ((current - value) / 360.0).round();
    [nearest - 360.0, nearest, nearest + 360.0]
        .into_iter()
        .filter(|v| axis.within_limits(*v))
        .collect()
}

impl Kinematics for FiveAxis {
    fn inverse(&self, pose: &Pose) -> Result<Joints, KinError> {
        let p = pose.to_array();
        let tip_machine = self.table_to_machine(&p, Vector3::from(pose.xyz()));
        let h = tip_machine - self.head_to_tip(&p) - self.linear_offset;
        let mut joints = p;
        joints[0] = if self.x_is_diameter { 2.0 * h.x } else { h.x };
        joints[1] = h.y;
        joints[2] = h.z;
        Ok(joints)
    }

    fn forward(&self, joints: &Joints) -> Result<Pose, KinError> {
        let hx = if self.x_is_diameter {
            joints[0] / 2.0
        } else {
            joints[0]
        };
        let h = Vector3::new(hx, joints[1], joints[2]) + self.linear_offset;
        let tip = self.machine_to_table(joints, h + self.head_to_tip(joints));
        let mut p = *joints;
        p[0] = tip.x;
        p[1] = tip.y;
        p[2] = tip.z;
        Ok(Pose::from_array(p))
    }

    fn tool_vector(&self, pose: &Pose) -> [f64; 3] {
        self.tool_vector_at(pose)
    }

    fn orient(&self, t: [f64; 3], current: &Pose) -> Result<Pose, KinError> {
        FiveAxis::orient(self, t, current)
    }
}
