//! A printer of the Canon stream in the format of LinuxCNC's standalone interpreter (`rs274 -g`).
//!
//! `rs274` prints each canonical call as `NNNNN N..... CALL(args)`: a running line counter right-aligned
//! in five columns, then the block's N label (`N` plus the number left-aligned in five columns, or
//! `N.....` when the block has none), then the call. Positions are printed in the **active work
//! coordinate system and program units** with four decimals, so the printer keeps the offsets and units
//! that the stream announces and re-expresses every machine position through LinuxCNC's chain:
//!
//! ```text
//! work = Rot(−R)·(machine − g5x − tlo) − g92        (rotation about Z acts on X, Y only)
//! ```
//!
//! then divides linear axes by 25.4 in inch mode. `rs274`'s own start-up calls (units, offsets,
//! feed reference, `ON_RESET`) come from [`Canon::Init`]; [`LinuxCncPrinter::finish`] adds the two
//! `ON_RESET()` lines `rs274` prints when it exits.

use crate::canon::{
    AccelerationProfile, ArcMove, Canon, FeedMode, LengthUnits, LogAction,
    OrientationInterpolation, PathMode, Plane, Pose, SpindleDirection,
};
use crate::span::Spanned;
use std::fmt::Write as _;

/// mm per machine length unit of `rs274`'s simulated machine, which works in inches (its tool
/// table and parameters `#5161…` are in inches whatever the program's units).
pub const RS274_MACHINE_MM: f64 = 25.4;

/// Turns `Canon` commands into `rs274 -g` lines.
#[derive(Debug)]
pub struct LinuxCncPrinter {
    counter: u32,
    units: LengthUnits,
    g5x: Pose,
    g92: Pose,
    tlo: Pose,
    rotation_deg: f64,
    /// G96 in force: spindle speeds are surface speeds (m/min in Canon; ft/min printed in G20).
    css: bool,
    out: String,
}

impl Default for LinuxCncPrinter {
    fn default() -> Self {
        Self::new()
    }
}

impl LinuxCncPrinter {
    /// A printer in the power-on state (mm, no offsets).
    pub fn new() -> Self {
        LinuxCncPrinter {
            counter: 0,
            units: LengthUnits::Millimetres,
            g5x: Pose::ZERO,
            g92: Pose::ZERO,
            tlo: Pose::ZERO,
            rotation_deg: 0.0,
            css: false,
            out: String::new(),
        }
    }

    /// Prints one command and returns the text it produced (zero or more lines, each ending in `\n`).
    pub fn print(&mut self, cmd: &Spanned<Canon>) -> &str {
        self.out.clear();
        let n = cmd.block_number.map(|n| (n, cmd.label_digits as usize));
        match &cmd.value {
            Canon::Init {
                units,
                g5x_index,
                g5x_offset,
                g92_offset,
                xy_rotation,
                ..
            } => {
                // rs274 starts in mm whatever the configuration, then applies the start-up state.
                self.units = LengthUnits::Millimetres;
                self.line(n, "USE_LENGTH_UNITS(CANON_UNITS_MM)".into());
                self.units = *units;
                self.g5x = *g5x_offset;
                self.g92 = *g92_offset;
                self.rotation_deg = *xy_rotation;
                let g5x = self.offset6(g5x_offset);
                self.line(n, format!("SET_G5X_OFFSET({}, {g5x})", g5x_index.max(&1)));
                let g92 = self.offset6(g92_offset);
                self.line(n, format!("SET_G92_OFFSET({g92})"));
                self.line(n, format!("SET_XY_ROTATION({:.4})", xy_rotation));
                self.line(n, "SET_FEED_REFERENCE(CANON_XYZ)".into());
                self.line(n, "ON_RESET()".into());
                if *units == LengthUnits::Inches {
                    self.line(n, "USE_LENGTH_UNITS(CANON_UNITS_INCHES)".into());
                }
            }
            Canon::StraightTraverse(m) => {
                let p = self.pose6(&m.end);
                self.line(n, format!("STRAIGHT_TRAVERSE({p})"));
            }
            Canon::StraightFeed(m) => {
                let p = self.pose6(&m.end);
                self.line(n, format!("STRAIGHT_FEED({p})"));
            }
            Canon::ArcFeed(a) => {
                let s = self.arc(a);
                self.line(n, s);
            }
            Canon::Dwell { seconds } => self.line(n, format!("DWELL({seconds:.4})")),
            Canon::SetFeedRate { feed } => {
                let f = feed / self.units.mm_per_unit();
                self.line(n, format!("SET_FEED_RATE({f:.4})"));
            }
            Canon::SetFeedMode { mode } => {
                // LinuxCNC's canon knows per-minute (0) and per-revolution (1); inverse time is
                // turned into a per-move feed by the interpreter.
                let m = match mode {
                    FeedMode::UnitsPerMinute | FeedMode::InverseTime => 0,
                    FeedMode::UnitsPerRevolution => 1,
                };
                self.line(n, format!("SET_FEED_MODE(0, {m})"));
            }
            Canon::SelectPlane { plane: p } => {
                let name = match p {
                    Plane::XY => "CANON_PLANE_XY",
                    Plane::ZX => "CANON_PLANE_XZ",
                    Plane::YZ => "CANON_PLANE_YZ",
                };
                self.line(n, format!("SELECT_PLANE({name})"));
            }
            Canon::UseLengthUnits { units: u } => {
                self.units = *u;
                let name = match u {
                    LengthUnits::Millimetres => "CANON_UNITS_MM",
                    LengthUnits::Inches => "CANON_UNITS_INCHES",
                };
                self.line(n, format!("USE_LENGTH_UNITS({name})"));
            }
            Canon::SetG5xOffset { index, offset } => {
                self.g5x = *offset;
                let o = self.offset6(offset);
                self.line(n, format!("SET_G5X_OFFSET({}, {o})", index.max(&1)));
            }
            Canon::SetG92Offset { offset } => {
                self.g92 = *offset;
                let o = self.offset6(offset);
                self.line(n, format!("SET_G92_OFFSET({o})"));
            }
            Canon::SetXyRotation { degrees } => {
                self.rotation_deg = *degrees;
                self.line(n, format!("SET_XY_ROTATION({degrees:.4})"));
            }
            Canon::SetSpindleSpeed { spindle, rpm } => {
                let s = if self.css && self.units == LengthUnits::Inches {
                    rpm / 0.3048
                } else {
                    *rpm
                };
                self.line(n, format!("SET_SPINDLE_SPEED({spindle}, {s:.4})"))
            }
            Canon::StartSpindle { spindle, direction } => {
                let name = match direction {
                    SpindleDirection::Clockwise => "START_SPINDLE_CLOCKWISE",
                    SpindleDirection::CounterClockwise => "START_SPINDLE_COUNTERCLOCKWISE",
                };
                self.line(n, format!("{name}({spindle})"));
            }
            Canon::StopSpindle { spindle } => {
                self.line(n, format!("STOP_SPINDLE_TURNING({spindle})"))
            }
            Canon::SetSpindleMode {
                spindle,
                constant_surface_speed,
                max_rpm,
            } => {
                self.css = *constant_surface_speed;
                let mode = if *constant_surface_speed {
                    *max_rpm
                } else {
                    0.0
                };
                self.line(n, format!("SET_SPINDLE_MODE({spindle} {mode:.4})"))
            }
            Canon::SplineFeed(s) => {
                // rs274 prints only the number of control points of a NURBS.
                self.line(n, format!("NURBS_FEED({}, ...)", s.control_points.len()))
            }
            Canon::StraightProbe { motion, .. } => {
                self.line(n, "TURN_PROBE_ON()".into());
                let p = self.pose6(&motion.end);
                self.line(n, format!("STRAIGHT_PROBE({p})"));
                self.line(n, "TURN_PROBE_OFF()".into());
            }
            Canon::RigidTap { end, .. } => {
                let w = self.to_work(end);
                self.line(n, format!("RIGID_TAP({})", fmt_list(&w[..3])));
            }
            Canon::StartSpindleSync {
                pitch,
                velocity_mode,
            } => {
                let k = pitch / self.units.mm_per_unit();
                self.line(
                    n,
                    format!("START_SPEED_FEED_SYNC({k:.6},{})", *velocity_mode as u8),
                );
            }
            Canon::StopSpindleSync => self.line(n, "STOP_SPEED_FEED_SYNCH()".into()),
            Canon::SetPathMode {
                mode,
                naive_cam_tolerance,
            } => {
                let k = self.units.mm_per_unit();
                // rs274 prints the tolerance, and then the naive-CAM one, for G64 (and the naive-CAM one
                // whenever the command carries it).
                match mode {
                    PathMode::ExactStop | PathMode::ExactPath => {
                        let name = if *mode == PathMode::ExactStop {
                            "CANON_EXACT_STOP"
                        } else {
                            "CANON_EXACT_PATH"
                        };
                        self.line(n, format!("SET_MOTION_CONTROL_MODE({name})"));
                        // After a canned cycle rs274 restores the naive-CAM tolerance too.
                        if let Some(q) = naive_cam_tolerance {
                            self.line(n, format!("SET_NAIVECAM_TOLERANCE({:.4})", q / k));
                        }
                    }
                    PathMode::Continuous { tolerance } => {
                        self.line(
                            n,
                            format!(
                                "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, {:.6})",
                                tolerance / k
                            ),
                        );
                        let q = naive_cam_tolerance.unwrap_or(*tolerance);
                        self.line(n, format!("SET_NAIVECAM_TOLERANCE({:.4})", q / k));
                    }
                }
            }
            Canon::SetAccelerationProfile { profile } => {
                let name = match profile {
                    AccelerationProfile::Brisk => "BRISK",
                    AccelerationProfile::Soft => "SOFT",
                };
                self.line(n, format!("SET_ACCELERATION_PROFILE({name})"));
            }
            Canon::SetFeedOverrideEnabled { enabled } => self.line(
                n,
                if *enabled {
                    "ENABLE_FEED_OVERRIDE()"
                } else {
                    "DISABLE_FEED_OVERRIDE()"
                }
                .into(),
            ),
            Canon::OrientSpindle {
                spindle,
                degrees,
                direction,
                timeout,
            } => {
                self.line(
                    n,
                    format!("ORIENT_SPINDLE({spindle}, {degrees:.4}, {direction})"),
                );
                if let Some(t) = timeout {
                    self.line(n, format!("SPINDLE.{spindle}.WAIT_ORIENT_COMPLETE({t:.4})"));
                }
            }
            Canon::WaitSpindleOrient { spindle, timeout } => self.line(
                n,
                format!("SPINDLE.{spindle}.WAIT_ORIENT_COMPLETE({timeout:.4})"),
            ),
            Canon::SetSpindleOverrideEnabled { spindle, enabled } => self.line(
                n,
                format!(
                    "{}_SPEED_OVERRIDE({spindle})",
                    if *enabled { "ENABLE" } else { "DISABLE" }
                ),
            ),
            Canon::SetAdaptiveFeed { enabled } => self.line(
                n,
                format!(
                    "{}_ADAPTIVE_FEED()",
                    if *enabled { "ENABLE" } else { "DISABLE" }
                ),
            ),
            Canon::SetFeedHoldEnabled { enabled } => self.line(
                n,
                format!(
                    "{}_FEED_HOLD()",
                    if *enabled { "ENABLE" } else { "DISABLE" }
                ),
            ),
            Canon::SetCurrentTool { slot, .. } => {
                self.line(n, format!("CHANGE_TOOL_NUMBER({slot})"))
            }
            Canon::DigitalOutput {
                index,
                on,
                synchronised,
            } => {
                let name = match (synchronised, on) {
                    (true, true) => "SET_MOTION_OUTPUT_BIT",
                    (true, false) => "CLEAR_MOTION_OUTPUT_BIT",
                    (false, true) => "SET_AUX_OUTPUT_BIT",
                    (false, false) => "CLEAR_AUX_OUTPUT_BIT",
                };
                self.line(n, format!("{name}({index})"));
            }
            // rs274 prints nothing for M66 (its simulated inputs answer at once).
            Canon::WaitInput { .. } => {}
            // rs274 has no such call: LinuxCNC's motion evaluates CSS from SET_SPINDLE_MODE/SPEED.
            Canon::SetSurfaceSpeedLaw { .. } => {}
            Canon::Mist { on } => self.line(n, if *on { "MIST_ON()" } else { "MIST_OFF()" }.into()),
            Canon::Flood { on } => {
                self.line(n, if *on { "FLOOD_ON()" } else { "FLOOD_OFF()" }.into())
            }
            Canon::SelectTool { tool } => self.line(n, format!("SELECT_TOOL({tool})")),
            Canon::SetToolTableEntry {
                slot,
                tool,
                offset,
                front_angle,
                back_angle,
                orientation,
                ..
            } => {
                // rs274 prints the table's own values, which LinuxCNC keeps in the machine's units:
                // inches in the standalone interpreter, whatever the program's G20/G21. It does
                // not print the diameter.
                let mut v = offset.to_array();
                for i in [0, 1, 2, 6, 7, 8] {
                    v[i] /= RS274_MACHINE_MM;
                }
                self.line(
                    n,
                    format!(
                        "SET_TOOL_TABLE_ENTRY({slot}, {tool}, {:.4} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4}, {front_angle:.4}, {back_angle:.4}, {orientation})",
                        v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]
                    ),
                );
            }
            Canon::ReloadToolTable => self.line(n, "RELOAD_TOOLDATA()".into()),
            // LinuxCNC has one spindle tool; this never comes from an RS274/NGC program.
            Canon::ChangeSpindleTool { spindle, tool } => {
                self.line(n, format!("CHANGE_SPINDLE_TOOL({spindle}, {tool})"))
            }
            // Stanok's own calls (LinuxCNC switches kinematics outside the interpreter).
            Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } => {
                let v = self.scale_linear([
                    tool_offset[0],
                    tool_offset[1],
                    tool_offset[2],
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                ]);
                let state = if *active { "ON" } else { "OFF" };
                self.line(
                    n,
                    format!(
                        "SET_TOOL_CENTRE_POINT({state}, {:.4} {:.4} {:.4})",
                        v[0], v[1], v[2]
                    ),
                )
            }
            Canon::SetOrientationInterpolation { mode } => {
                let name = match mode {
                    OrientationInterpolation::Axes => "AXES",
                    OrientationInterpolation::Vector => "VECTOR",
                };
                self.line(n, format!("SET_ORIENTATION_INTERPOLATION({name})"))
            }
            Canon::StartToolChange => self.line(n, "START_CHANGE()".into()),
            Canon::ChangeTool { slot, .. } => self.line(n, format!("CHANGE_TOOL({slot})")),
            Canon::UseToolLengthOffset { offset } => {
                self.tlo = *offset;
                let v = self.scale_linear(offset.to_array());
                self.line(
                    n,
                    format!(
                        "USE_TOOL_LENGTH_OFFSET({:.4} {:.4} {:.4}, {:.4} {:.4} {:.4}, {:.4} {:.4} {:.4})",
                        v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]
                    ),
                );
            }
            Canon::AuxiliaryFunction { number, .. } => {
                self.line(n, format!("AUXILIARY_FUNCTION({number})"))
            }
            Canon::Message { text } => self.line(n, format!("MESSAGE(\"{text}\")")),
            Canon::Comment { text } => self.line(n, format!("COMMENT(\"{text}\")")),
            Canon::Log { action, text } => {
                let call = match action {
                    LogAction::Open => format!("LOGOPEN(\"{text}\")"),
                    LogAction::Append => format!("LOGAPPEND(\"{text}\")"),
                    LogAction::Close => "LOGCLOSE()".to_string(),
                    LogAction::Write => format!("LOG(\"{text}\")"),
                };
                self.line(n, call);
            }
            Canon::ProgramStop { optional } => self.line(
                n,
                if *optional {
                    "OPTIONAL_PROGRAM_STOP()"
                } else {
                    "PROGRAM_STOP()"
                }
                .into(),
            ),
            Canon::PalletShuttle => self.line(n, "PALLET_SHUTTLE()".into()),
            Canon::ProgramEnd => self.line(n, "PROGRAM_END()".into()),
            Canon::Finish => self.line(n, "FINISH()".into()),
        }
        &self.out
    }

    /// The lines `rs274` prints when it exits (after a program end or an error).
    pub fn finish(&mut self) -> &str {
        self.out.clear();
        self.line(None, "ON_RESET()".into());
        self.line(None, "ON_RESET()".into());
        &self.out
    }

    fn line(&mut self, n: Option<(u32, usize)>, call: String) {
        self.counter += 1;
        let _ = match n {
            Some((n, digits)) => {
                let label = format!("{n:0digits$}");
                writeln!(self.out, "{:5} N{label:<5} {call}", self.counter)
            }
            None => writeln!(self.out, "{:5} N..... {call}", self.counter),
        };
    }

    /// Machine pose → work pose in program units (all nine axes).
    fn to_work(&self, p: &Pose) -> [f64; 9] {
        let m = p.to_array();
        let g5x = self.g5x.to_array();
        let g92 = self.g92.to_array();
        let tlo = self.tlo.to_array();
        let mut w = [0.0; 9];
        for i in 0..9 {
            w[i] = m[i] - g5x[i] - tlo[i];
        }
        let (s, c) = (-self.rotation_deg).to_radians().sin_cos();
        let (x, y) = (w[0], w[1]);
        w[0] = x * c - y * s;
        w[1] = x * s + y * c;
        for i in 0..9 {
            w[i] -= g92[i];
        }
        self.scale_linear(w)
    }

    fn scale_linear(&self, mut v: [f64; 9]) -> [f64; 9] {
        let k = self.units.mm_per_unit();
        for i in [0, 1, 2, 6, 7, 8] {
            v[i] /= k;
        }
        v
    }

    fn pose6(&self, p: &Pose) -> String {
        let w = self.to_work(p);
        fmt_list(&w[..6])
    }

    fn offset6(&self, p: &Pose) -> String {
        let w = self.scale_linear(p.to_array());
        fmt_list(&w[..6])
    }

    fn arc(&self, a: &ArcMove) -> String {
        let end = self.to_work(&a.end);
        let centre = self.to_work(&a.start.with_xyz(a.centre));
        let (i1, i2, ia) = a.plane.axes();
        let normal = match a.plane {
            Plane::XY => a.axis[2],
            Plane::ZX => a.axis[1],
            Plane::YZ => a.axis[0],
        };
        let rotation = if normal < 0.0 {
            -(a.turns as i64)
        } else {
            a.turns as i64
        };
        format!(
            "ARC_FEED({:.4}, {:.4}, {:.4}, {:.4}, {}, {:.4}, {:.4}, {:.4}, {:.4})",
            end[i1], end[i2], centre[i1], centre[i2], rotation, end[ia], end[3], end[4], end[5]
        )
    }
}

fn fmt_list(v: &[f64]) -> String {
    let mut s = String::new();
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            s.push_str(", ");
        }
        // Avoid printing "-0.0000" where rs274 prints "0.0000".
        let _ = write!(s, "{x:.4}");
    }
    s
}
