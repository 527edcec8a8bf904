//! Travel (soft) limits of a Canon stream: what the simulated machine refuses before a command
//! runs, and what `stanok check` and the panel's preview report before a program starts.
//!
//! Every position in a Canon command is already a machine position — work offsets, G92, tool
//! length offsets and rotations are in it — so the check compares positions with the machine's
//! axis limits directly:
//! 1. **Axes.** A move may only change axes the machine has (`machine::missing-axis`).
//! 2. **Travel** (`machine::travel-limit`). A straight move is checked at its end point (its start
//!    is the previous end, already checked; the `Init` position is checked on its own). An arc is
//!    checked over its tight bounding box (`stanok-geom`), so an arc whose end points are inside
//!    but whose bulge is not is refused; its non-XYZ axes move linearly and are checked at the end.
//!    A spline over its tessellation (1 µm). A limit may be touched: positions within 1e-9 mm
//!    (deg) of it pass, so that rounding in the interpreter does not refuse a move programmed
//!    exactly to the limit.
//! 3. **Joints.** Under tool-centre-point control (`SetToolCentrePoint`) positions are tool poses:
//!    the joints of 64 poses along each move (the machine's inverse kinematics with the active
//!    tool) are checked instead; the servo trace itself is checked setpoint by setpoint by the
//!    motion monitor.

use crate::data::{AxisData, AxisKind, MachineData};
use stanok_canon::{Canon, Diagnostic, LineMove, Pose, Span, Spanned, AXIS_LETTERS};
use stanok_geom::{Helix, Nurbs};
use stanok_kin::{FiveAxis, Kinematics};

/// Positions within this distance beyond a limit (mm or deg) still pass.
const LIMIT_SLACK: f64 = 1e-9;

fn unit(axis: &AxisData) -> &'static str {
    match axis.kind {
        AxisKind::Linear => "mm",
        AxisKind::Rotary => "deg",
    }
}

/// The check of the module doc, following the stream's tool-centre-point switches.
#[derive(Debug, Clone)]
pub struct TravelCheck {
    name: String,
    /// The machine's axis for each index of `Pose::to_array`, if it has one.
    axes: [Option<AxisData>; 9],
    /// The machine's kinematics (without a tool), if any.
    kinematics: Option<FiveAxis>,
    /// The kinematics with the active tool while tool-centre-point control is on.
    tcp: Option<FiveAxis>,
}

impl TravelCheck {
    /// The check for `machine`'s axes and kinematics.
    pub fn new(machine: &MachineData) -> Self {
        let mut axes: [Option<AxisData>; 9] = Default::default();
        for a in &machine.axes {
            axes[a.pose_index()] = Some(a.clone());
        }
        TravelCheck {
            name: machine.name.clone(),
            axes,
            kinematics: machine.five_axis(),
            tcp: None,
        }
    }

    /// True while tool-centre-point control is on (positions are tool poses).
    pub fn tcp(&self) -> Option<&FiveAxis> {
        self.tcp.as_ref()
    }

    /// Checks one command; Ok or its first violation. A `SetToolCentrePoint` switches the check
    /// to joints (or back); a machine without kinematics refuses it.
    pub fn check(&mut self, cmd: &Spanned<Canon>) -> Result<(), Diagnostic> {
        let span = cmd.span;
        match &cmd.value {
            Canon::Init { position, .. } => {
                let p = position.to_array();
                self.check_limits(&p, &p, span)
            }
            Canon::StraightTraverse(m) | Canon::StraightFeed(m) => self.check_line(m, span),
            Canon::StraightProbe {
                motion, contact, ..
            } => self.check_line(&motion.stopped_at(contact.as_deref().copied()), span),
            Canon::RigidTap { start, end, .. } => {
                self.check_move(start, end, &end.to_array(), &end.to_array(), span)
            }
            Canon::ArcFeed(a) => {
                let helix = Helix {
                    start: a.start.xyz(),
                    end: a.end.xyz(),
                    centre: a.centre,
                    axis: a.axis,
                    turns: a.turns,
                };
                let (box_lo, box_hi) = helix.bounding_box();
                let (s, e) = (a.start.to_array(), a.end.to_array());
                let mut lo = [0.0; 9];
                let mut hi = [0.0; 9];
                for i in 0..9 {
                    (lo[i], hi[i]) = if i < 3 {
                        (box_lo[i], box_hi[i])
                    } else {
                        (s[i].min(e[i]), s[i].max(e[i]))
                    };
                }
                self.check_move(&a.start, &a.end, &lo, &hi, span)
            }
            Canon::SplineFeed(sp) => {
                let curve = Nurbs::new(sp.degree, &sp.control_points, &sp.weights, &sp.knots);
                let mut pts = Vec::new();
                curve.tessellate(1e-3, &mut pts);
                let (s, e) = (sp.start.to_array(), sp.end.to_array());
                let mut lo = [0.0; 9];
                let mut hi = [0.0; 9];
                for i in 0..9 {
                    (lo[i], hi[i]) = (s[i].min(e[i]), s[i].max(e[i]));
                }
                for p in &pts {
                    for i in 0..3 {
                        lo[i] = lo[i].min(p[i]);
                        hi[i] = hi[i].max(p[i]);
                    }
                }
                self.check_move(&sp.start, &sp.end, &lo, &hi, span)
            }
            Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } => self.switch_tcp(*active, *tool_offset, span),
            _ => Ok(()),
        }
    }

    fn check_line(&self, m: &LineMove, span: Span) -> Result<(), Diagnostic> {
        let e = m.end.to_array();
        self.check_move(&m.start, &m.end, &e, &e, span)
    }

    /// Rules 1–3 of the module doc for a move that spans `lo..=hi` per axis and goes start → end.
    fn check_move(
        &self,
        start: &Pose,
        end: &Pose,
        lo: &[f64; 9],
        hi: &[f64; 9],
        span: Span,
    ) -> Result<(), Diagnostic> {
        let (s, e) = (start.to_array(), end.to_array());
        for i in 0..9 {
            if self.axes[i].is_none() && (s[i] != e[i] || lo[i] != hi[i]) {
                let letter = AXIS_LETTERS[i];
                return Err(Diagnostic::error(
                    "machine::missing-axis",
                    format!(
                        "machine {} has no {letter} axis, but this block moves {letter} from {} to {}",
                        self.name, s[i], e[i]
                    ),
                    span,
                ));
            }
        }
        match &self.tcp {
            None => self.check_limits(lo, hi, span),
            Some(kin) => {
                // The joints of the poses along the move (the straight interpolation of the
                // pose; the servo trace is checked setpoint by setpoint by the motion monitor).
                const SAMPLES: usize = 64;
                let mut jlo = [f64::INFINITY; 9];
                let mut jhi = [f64::NEG_INFINITY; 9];
                for k in 0..=SAMPLES {
                    let f = k as f64 / SAMPLES as f64;
                    let p: [f64; 9] = std::array::from_fn(|i| s[i] + (e[i] - s[i]) * f);
                    let j = kin.inverse(&Pose::from_array(p)).unwrap_or(p);
                    for i in 0..9 {
                        jlo[i] = jlo[i].min(j[i]);
                        jhi[i] = jhi[i].max(j[i]);
                    }
                }
                self.check_limits(&jlo, &jhi, span)
            }
        }
    }

    /// Tool-centre-point control on or off (the interpreter has checked that the machine has
    /// the kinematics; a machine without them refuses here too).
    fn switch_tcp(
        &mut self,
        active: bool,
        tool_offset: [f64; 3],
        span: Span,
    ) -> Result<(), Diagnostic> {
        if !active {
            self.tcp = None;
            return Ok(());
        }
        match &self.kinematics {
            Some(k) => {
                self.tcp = Some(k.clone().with_tool_offset(tool_offset));
                Ok(())
            }
            None => Err(Diagnostic::error(
                "machine::no-kinematics",
                format!(
                    "machine {} has no 5-axis kinematics for tool-centre-point control",
                    self.name
                ),
                span,
            )),
        }
    }

    /// Travel limits for positions spanning `lo..=hi` per axis.
    fn check_limits(&self, lo: &[f64; 9], hi: &[f64; 9], span: Span) -> Result<(), Diagnostic> {
        for (i, axis) in self.axes.iter().enumerate() {
            let Some(axis) = axis else { continue };
            let u = unit(axis);
            let violation = if lo[i].is_nan() || hi[i].is_nan() {
                Some(format!("{} position is not a number", axis.name))
            } else if lo[i] < axis.min - LIMIT_SLACK {
                Some(format!(
                    "{} would reach {:.4} {u}, beyond its minimum {:.4} {u}",
                    axis.name, lo[i], axis.min
                ))
            } else if hi[i] > axis.max + LIMIT_SLACK {
                Some(format!(
                    "{} would reach {:.4} {u}, beyond its maximum {:.4} {u}",
                    axis.name, hi[i], axis.max
                ))
            } else {
                None
            };
            if let Some(message) = violation {
                return Err(Diagnostic::error("machine::travel-limit", message, span)
                    .with_note("travel limits are in machine coordinates: the block's position with the work offset and tool length offset in force"));
            }
        }
        Ok(())
    }
}
