//! What the panel shows and what the tests compare: the machine state read off the executed Canon
//! stream, the interpreter's modal vectors, and the snapshot sent to the page.
//!
//! ## Machine state (the block-search contract)
//! [`MachineState`] is everything a block leaves behind that the next blocks depend on, taken from
//! the commands the simulated machine accepted (never from the interpreter's guesses ahead of it):
//! * axis positions — the end of the last accepted motion, machine coordinates (mm, deg);
//! * tool in the spindle and the prepared tool;
//! * every spindle's commanded speed and sense (0 = stopped), mist and flood;
//! * the offsets in force: G5x index and offset, G92/G52 offset, tool-length offset, XY rotation;
//! * the modal motion state: feed (mm/min), feed mode, plane, program units, path mode, BRISK/SOFT.
//!
//! Two runs are "in the same machine state" when these are equal (positions within 1e-9). A
//! block search to line N must reach line N in the state a full run has there, and end in the
//! state a full run ends in (`tests/block_search.rs`).
//!
//! The modal vectors the operator reads (G groups, M groups, tool edge) come from the interpreter's
//! state ([`g_vector_of`], [`m_vector`]), read when the interpreter hands over a command; they
//! travel with that command to the machine (`executing.rs`), so the page shows them when the
//! command's motion executes, not when the interpreter prepares it.

use serde::Serialize;
use stanok_canon::{Canon, FeedMode, LengthUnits, PathMode, Plane, SpindleDirection};
use stanok_interp::Interpreter;
use stanok_interp::{DistanceMode, LengthComp, ModalState, MotionMode};
use stanok_syntax::Dialect;

/// One spindle: commanded speed and sense.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct SpindleState {
    /// Commanded speed, rev/min (kept while stopped, as a control keeps S).
    pub rpm: f64,
    /// 3 = clockwise (M3), 4 = counter-clockwise (M4), 5 = stopped (M5).
    pub m: u8,
}

/// The machine state of the module doc.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MachineState {
    /// X Y Z A B C U V W, machine coordinates, mm / deg.
    pub position: [f64; 9],
    /// Tool in the main spindle (0 = none).
    pub tool: u32,
    /// Prepared tool (T word), 0 = none.
    pub selected_tool: u32,
    /// Spindles 0…3.
    pub spindles: [SpindleState; 4],
    /// M7.
    pub mist: bool,
    /// M8.
    pub flood: bool,
    /// 1 = G54 … 9 = G59.3, 0 = none.
    pub g5x_index: u8,
    /// mm / deg.
    pub g5x_offset: [f64; 9],
    /// G92 / G52, mm / deg.
    pub g92_offset: [f64; 9],
    /// Tool length offset in force, mm / deg.
    pub tool_offset: [f64; 9],
    /// Degrees.
    pub xy_rotation_deg: f64,
    /// Last programmed feed, mm/min.
    pub feed: f64,
    /// `UnitsPerMinute`, `InverseTime`, `UnitsPerRevolution`.
    pub feed_mode: String,
    /// `XY`, `ZX`, `YZ`.
    pub plane: String,
    /// `Millimetres`, `Inches`.
    pub units: String,
    /// `ExactStop`, `ExactPath`, `Continuous(P)`.
    pub path_mode: String,
    /// SOFT (jerk-limited) acceleration.
    pub soft: bool,
}

impl Default for MachineState {
    fn default() -> Self {
        let stopped = SpindleState { rpm: 0.0, m: 5 };
        MachineState {
            position: [0.0; 9],
            tool: 0,
            selected_tool: 0,
            spindles: [stopped; 4],
            mist: false,
            flood: false,
            g5x_index: 0,
            g5x_offset: [0.0; 9],
            g92_offset: [0.0; 9],
            tool_offset: [0.0; 9],
            xy_rotation_deg: 0.0,
            feed: 0.0,
            feed_mode: format!("{:?}", FeedMode::UnitsPerMinute),
            plane: format!("{:?}", Plane::XY),
            units: format!("{:?}", LengthUnits::Millimetres),
            path_mode: "ExactStop".into(),
            soft: false,
        }
    }
}

impl MachineState {
    /// Takes in one command the machine accepted.
    pub fn apply(&mut self, cmd: &Canon) {
        match cmd {
            Canon::Init {
                position,
                g5x_index,
                g5x_offset,
                g92_offset,
                xy_rotation,
                ..
            } => {
                self.position = position.to_array();
                self.g5x_index = *g5x_index;
                self.g5x_offset = g5x_offset.to_array();
                self.g92_offset = g92_offset.to_array();
                self.xy_rotation_deg = *xy_rotation;
            }
            Canon::StraightProbe {
                motion, contact, ..
            } => {
                self.position = motion
                    .stopped_at(contact.as_deref().copied())
                    .end
                    .to_array()
            }
            Canon::SetFeedRate { feed } => self.feed = *feed,
            Canon::SetFeedMode { mode } => self.feed_mode = format!("{mode:?}"),
            Canon::SelectPlane { plane } => self.plane = format!("{plane:?}"),
            Canon::UseLengthUnits { units } => self.units = format!("{units:?}"),
            Canon::SetG5xOffset { index, offset } => {
                self.g5x_index = *index;
                self.g5x_offset = offset.to_array();
            }
            Canon::SetG92Offset { offset } => self.g92_offset = offset.to_array(),
            Canon::SetXyRotation { degrees } => self.xy_rotation_deg = *degrees,
            Canon::UseToolLengthOffset { offset } => self.tool_offset = offset.to_array(),
            Canon::SetSpindleSpeed { spindle, rpm } => {
                if let Some(s) = self.spindles.get_mut(*spindle as usize) {
                    s.rpm = *rpm;
                }
            }
            Canon::StartSpindle { spindle, direction } => {
                if let Some(s) = self.spindles.get_mut(*spindle as usize) {
                    s.m = match direction {
                        SpindleDirection::Clockwise => 3,
                        SpindleDirection::CounterClockwise => 4,
                    };
                }
            }
            Canon::StopSpindle { spindle } => {
                if let Some(s) = self.spindles.get_mut(*spindle as usize) {
                    s.m = 5;
                }
            }
            Canon::Mist { on } => self.mist = *on,
            Canon::Flood { on } => self.flood = *on,
            Canon::SelectTool { tool } => self.selected_tool = *tool,
            Canon::ChangeTool { tool, .. } => self.tool = *tool,
            Canon::SetPathMode { mode, .. } => {
                self.path_mode = match mode {
                    PathMode::ExactStop => "ExactStop".into(),
                    PathMode::ExactPath => "ExactPath".into(),
                    PathMode::Continuous { tolerance } => format!("Continuous({tolerance})"),
                }
            }
            Canon::SetAccelerationProfile { profile } => {
                self.soft = matches!(profile, stanok_canon::AccelerationProfile::Soft)
            }
            other => {
                if let Some(m) = other.motion() {
                    self.position = m.end().to_array();
                }
            }
        }
    }

    /// Work coordinates of a machine position under the offsets in force:
    /// `R(−rotation)·(machine − tool offset − G5x) − G92` (LinuxCNC's chain; AxiOMA frames with
    /// mirror or scale are shown by their offsets only).
    pub fn work_of(&self, machine: &[f64; 9]) -> [f64; 9] {
        let mut w = [0.0; 9];
        for (i, v) in w.iter_mut().enumerate() {
            *v = machine[i] - self.tool_offset[i] - self.g5x_offset[i];
        }
        if self.xy_rotation_deg != 0.0 {
            let (s, c) = (-self.xy_rotation_deg).to_radians().sin_cos();
            let (x, y) = (w[0], w[1]);
            w[0] = c * x - s * y;
            w[1] = s * x + c * y;
        }
        for (i, v) in w.iter_mut().enumerate() {
            *v -= self.g92_offset[i];
        }
        w
    }

    /// Equal within 1e-9 in every number (module doc).
    pub fn same_as(&self, other: &MachineState) -> bool {
        let close =
            |a: &[f64; 9], b: &[f64; 9]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-9);
        let mut a = self.clone();
        let mut b = other.clone();
        let numbers_equal = close(&a.position, &b.position)
            && close(&a.g5x_offset, &b.g5x_offset)
            && close(&a.g92_offset, &b.g92_offset)
            && close(&a.tool_offset, &b.tool_offset);
        for s in [&mut a, &mut b] {
            s.position = [0.0; 9];
            s.g5x_offset = [0.0; 9];
            s.g92_offset = [0.0; 9];
            s.tool_offset = [0.0; 9];
        }
        numbers_equal && a == b
    }
}

/// One active G code with its group, e.g. `("motion", "G1")`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ActiveCode {
    /// Modal group.
    pub group: String,
    /// The code.
    pub code: String,
}

fn code(group: &str, code: impl Into<String>) -> ActiveCode {
    ActiveCode {
        group: group.into(),
        code: code.into(),
    }
}

/// The G code of a motion mode.
fn motion_code(m: MotionMode) -> &'static str {
    match m {
        MotionMode::Rapid => "G0",
        MotionMode::Linear => "G1",
        MotionMode::ArcCw => "G2",
        MotionMode::ArcCcw => "G3",
        MotionMode::None => "G80",
    }
}

/// The active G codes by modal group (module doc); `length_comp`: AxiOMA's tool length group
/// (the others show G49).
pub fn g_vector(s: &ModalState, length_comp: LengthComp, dialect: Dialect) -> Vec<ActiveCode> {
    let axioma = dialect == Dialect::Axioma;
    let mut v = vec![
        code("motion", motion_code(s.motion)),
        code(
            "plane",
            match s.plane {
                Plane::XY => "G17",
                Plane::ZX => "G18",
                Plane::YZ => "G19",
            },
        ),
        code(
            "distance",
            match s.distance {
                DistanceMode::Absolute => "G90",
                DistanceMode::Incremental => "G91",
            },
        ),
        code(
            "units",
            match (s.units, axioma) {
                (LengthUnits::Millimetres, false) => "G21",
                (LengthUnits::Inches, false) => "G20",
                (LengthUnits::Millimetres, true) => "G71",
                (LengthUnits::Inches, true) => "G70",
            },
        ),
        code(
            "feed",
            match s.feed_mode {
                FeedMode::InverseTime => "G93",
                FeedMode::UnitsPerMinute => "G94",
                FeedMode::UnitsPerRevolution => "G95",
            },
        ),
    ];
    v.push(code(
        "path",
        match (s.path_mode, axioma) {
            (stanok_interp::PathMode::ExactStop, true) => "G60".to_string(),
            (stanok_interp::PathMode::ExactStop, false) => "G61".to_string(),
            (stanok_interp::PathMode::ExactPath, _) => "G61.1".to_string(),
            (stanok_interp::PathMode::Continuous { blend_tolerance }, _)
                if blend_tolerance > 0.0 =>
            {
                format!("G64 P{blend_tolerance}")
            }
            (stanok_interp::PathMode::Continuous { .. }, _) => "G64".to_string(),
        },
    ));
    if axioma {
        v.push(code(
            "acceleration",
            if s.soft_acceleration { "SOFT" } else { "BRISK" },
        ));
    }
    const G5X: [&str; 10] = [
        "G53", "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
    ];
    v.push(code(
        "work offset",
        G5X.get(s.g5x_index as usize).copied().unwrap_or("G54"),
    ));
    v.push(code(
        "tool length",
        match length_comp {
            LengthComp::Off => "G49",
            LengthComp::Plus => "G43",
            LengthComp::Minus => "G44",
            LengthComp::Fixed { .. } => "G43.1",
        },
    ));
    if !axioma {
        v.push(code(
            "retract",
            if s.retract_to_initial { "G98" } else { "G99" },
        ));
    }
    v
}

/// The active G codes of whatever dialect the interpreter runs: the lab controls keep their own
/// modal state ([`Interpreter::lab_state`]).
pub fn g_vector_of<R: std::io::BufRead + std::io::Seek>(
    interp: &Interpreter<R>,
    dialect: Dialect,
) -> Vec<ActiveCode> {
    let Some(lab) = interp.lab_state() else {
        let length_comp = interp
            .axioma_modes()
            .map_or(LengthComp::Off, |m| m.length_comp);
        return g_vector(interp.state(), length_comp, dialect);
    };
    let mut v = vec![
        code("motion", motion_code(lab.motion)),
        code(
            "plane",
            match lab.plane {
                Plane::XY => "G17",
                Plane::ZX => "G18",
                Plane::YZ => "G19",
            },
        ),
        code("distance", if lab.incremental { "G91" } else { "G90" }),
        code(
            "feed",
            match lab.feed_mode {
                FeedMode::InverseTime => "G93",
                FeedMode::UnitsPerMinute => "G94",
                FeedMode::UnitsPerRevolution => "G95",
            },
        ),
    ];
    if dialect == Dialect::Gost20999 {
        v.push(code("work offset", format!("G{}", 53 + lab.work_system)));
    }
    v
}

/// The active M functions by group: AxiOMA's M vector from its M table; for RS274/NGC spindle,
/// coolant and tool from the state.
pub fn m_vector<R: std::io::BufRead + std::io::Seek>(
    interp: &Interpreter<R>,
    machine: &MachineState,
    dialect: Dialect,
) -> Vec<ActiveCode> {
    if dialect == Dialect::Axioma {
        let v = interp.axioma_m_vector();
        if !v.is_empty() {
            return v
                .into_iter()
                .map(|(group, m)| code(&group, format!("M{m}")))
                .collect();
        }
    }
    let coolant = match (machine.mist, machine.flood) {
        (false, false) => "M9",
        (true, false) => "M7",
        (false, true) => "M8",
        (true, true) => "M7 M8",
    };
    vec![
        code("spindle", format!("M{}", machine.spindles[0].m)),
        code("coolant", coolant),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use stanok_canon::Pose;

    fn pose(x: f64, y: f64, z: f64) -> Pose {
        Pose::from_array([x, y, z, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[test]
    fn work_coordinates_undo_tool_offset_g5x_rotation_and_g92_in_that_order() {
        let mut s = MachineState::default();
        s.apply(&Canon::SetG5xOffset {
            index: 2,
            offset: pose(100.0, 50.0, -20.0),
        });
        s.apply(&Canon::UseToolLengthOffset {
            offset: pose(0.0, 0.0, 30.0),
        });
        s.apply(&Canon::SetXyRotation { degrees: 90.0 });
        s.apply(&Canon::SetG92Offset {
            offset: pose(1.0, 2.0, 3.0),
        });
        // machine − tlo − G5x = (10, 20, 5); rotated by −90°: (20, −10, 5); − G92: (19, −12, 2).
        let w = s.work_of(&[110.0, 70.0, 15.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        for (got, want) in w.iter().zip([19.0, -12.0, 2.0]) {
            assert!((got - want).abs() < 1e-12, "{w:?}");
        }
        assert_eq!(s.g5x_index, 2);
    }

    #[test]
    fn the_state_follows_spindle_coolant_tool_and_motion_commands() {
        let mut s = MachineState::default();
        s.apply(&Canon::SetSpindleSpeed {
            spindle: 0,
            rpm: 1200.0,
        });
        s.apply(&Canon::StartSpindle {
            spindle: 0,
            direction: SpindleDirection::CounterClockwise,
        });
        s.apply(&Canon::Flood { on: true });
        s.apply(&Canon::SelectTool { tool: 7 });
        s.apply(&Canon::ChangeTool { tool: 7, slot: 7 });
        s.apply(&Canon::StraightFeed(stanok_canon::LineMove {
            start: pose(0.0, 0.0, 0.0),
            end: pose(5.0, 6.0, 7.0),
            feed: 100.0,
            law: stanok_canon::FeedLaw::PerMinute,
        }));
        assert_eq!(s.spindles[0], SpindleState { rpm: 1200.0, m: 4 });
        assert!(s.flood && !s.mist);
        assert_eq!((s.tool, s.selected_tool), (7, 7));
        assert_eq!(&s.position[..3], &[5.0, 6.0, 7.0]);
        let mut other = s.clone();
        assert!(s.same_as(&other));
        other.position[0] += 1e-6;
        assert!(!s.same_as(&other));
    }
}
