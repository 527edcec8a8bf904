//! A small harness: run a Mazatrol program through the core driver on a described machine.
#![allow(dead_code)]

use stanok_canon::setup::{ControlData, Tool, ToolEdge, ToolKind, ZeroOffset};
use stanok_canon::{Canon, Diagnostic, Pose, Spanned};
use stanok_interp_core::{CoreOptions, Driver, ModalState};
use stanok_kin::{Carrier, FiveAxis, RotaryAxis};
use stanok_mazatrol::codes::Series;
use stanok_mazatrol::{Mazatrol, MazatrolParams};
use stanok_syntax::Dialect;

/// What a run gave.
pub struct Run {
    /// The commands.
    pub canon: Vec<Spanned<Canon>>,
    /// The first error.
    pub error: Option<Diagnostic>,
    /// Warnings.
    pub warnings: Vec<Diagnostic>,
}

impl Run {
    /// The motion commands' end poses (machine coordinates).
    pub fn ends(&self) -> Vec<Pose> {
        self.canon
            .iter()
            .filter_map(|c| match &c.value {
                Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Some(m.end),
                Canon::ArcFeed(a) => Some(a.end),
                Canon::StraightProbe {
                    motion, contact, ..
                } => Some(contact.as_deref().copied().unwrap_or(motion.end)),
                Canon::RigidTap { start, .. } => Some(*start),
                _ => None,
            })
            .collect()
    }

    /// The last pose of the block on `line` (1-based).
    pub fn at_line(&self, line: u32) -> Option<Pose> {
        self.canon
            .iter()
            .filter(|c| c.span.line == line)
            .filter_map(|c| match &c.value {
                Canon::StraightTraverse(m) | Canon::StraightFeed(m) => Some(m.end),
                Canon::ArcFeed(a) => Some(a.end),
                _ => None,
            })
            .next_back()
    }

    /// The last machine joint pose of the block on `line`: motion ends under tool-centre-point
    /// control turned into joints with the kinematics `kin` (the tip pose otherwise is the joint
    /// pose already).
    pub fn joints_at_line(&self, line: u32, kin: &FiveAxis) -> Option<Pose> {
        use stanok_kin::Kinematics;
        let mut tcp: Option<[f64; 3]> = None;
        let mut last = None;
        for c in &self.canon {
            if let Canon::SetToolCentrePoint {
                active,
                tool_offset,
            } = &c.value
            {
                tcp = active.then_some(*tool_offset);
            }
            if c.span.line != line {
                continue;
            }
            let end = match &c.value {
                Canon::StraightTraverse(m) | Canon::StraightFeed(m) => m.end,
                Canon::ArcFeed(a) => a.end,
                _ => continue,
            };
            last = Some(match tcp {
                Some(off) => Pose::from_array(
                    kin.clone()
                        .with_tool_offset(off)
                        .inverse(&end)
                        .expect("reachable"),
                ),
                None => end,
            });
        }
        last
    }

    /// The commands, panicking on an error.
    pub fn ok(&self) -> &Self {
        if let Some(e) = &self.error {
            panic!("unexpected error: {e:?}");
        }
        self
    }

    /// Total feed length (straight feeds and arcs, XYZ), mm.
    pub fn feed_length(&self) -> f64 {
        let mut t = 0.0;
        for c in &self.canon {
            match &c.value {
                Canon::StraightFeed(m) => {
                    let (a, b) = (m.start, m.end);
                    t += ((b.x - a.x).powi(2) + (b.y - a.y).powi(2) + (b.z - a.z).powi(2)).sqrt();
                }
                Canon::ArcFeed(a) => {
                    t += stanok_geom::Helix {
                        start: a.start.xyz(),
                        end: a.end.xyz(),
                        centre: a.centre,
                        axis: a.axis,
                        turns: a.turns,
                    }
                    .length();
                }
                _ => {}
            }
        }
        t
    }
}

/// A machine for the tests.
pub struct Machine {
    pub opts: CoreOptions,
    pub params: MazatrolParams,
}

fn tool(n: u32, kind: ToolKind, length: [f64; 3], radius: f64, tip: u8) -> Tool {
    Tool {
        number: n,
        pocket: n,
        kind,
        edges: vec![ToolEdge {
            length,
            radius,
            orientation: tip,
            ..Default::default()
        }],
        comment: String::new(),
        body: Default::default(),
    }
}

/// Reference points 2 … 5 (machine Z 10, 20, 30; floating Z 50).
fn homes(control: &mut ControlData) {
    for (i, z) in [(1, 10.0), (2, 20.0), (3, 30.0), (4, 50.0)] {
        control.offsets.home[i] = Some(Pose { z, ..Pose::ZERO });
    }
}

/// `mazak-m`: B head (pivot 150) + C table, G54 (100, 50, −200), T1 150, T2 120 R3, T3 110 R5.
pub fn mazak_m() -> Machine {
    let mut opts = CoreOptions::new(Dialect::Mazatrol);
    opts.axes = [true, true, true, false, true, true, false, false, false];
    let mut control = ControlData::default();
    control.offsets.zero[0][0] = ZeroOffset {
        offset: Pose {
            x: 100.0,
            y: 50.0,
            z: -200.0,
            ..Pose::ZERO
        },
        rotation_xy: 0.0,
    };
    for t in [
        tool(1, ToolKind::Drilling, [150.0, 0.0, 0.0], 4.0, 0),
        tool(2, ToolKind::Milling, [120.0, 0.0, 0.0], 3.0, 0),
        tool(3, ToolKind::Milling, [110.0, 0.0, 0.0], 5.0, 0),
    ] {
        control.tools.tools.insert(t.number, t);
    }
    homes(&mut control);
    opts.control = control;
    let mut b = RotaryAxis::new('B', Carrier::Head, [0.0, 1.0, 0.0], [0.0, 0.0, 150.0]);
    b.min = -110.0;
    b.max = 110.0;
    let c = RotaryAxis::new('C', Carrier::Table, [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]);
    opts.five_axis = Some(FiveAxis::new(vec![b, c], [0.0, 0.0, 1.0]).unwrap());
    Machine {
        opts,
        params: MazatrolParams::default(),
    }
}

/// `mazak-t`: B head (pivot 200) + C spindle, X radius, G54 Z200, offset 1 turning X20 Z80 R0.8 tip 3,
/// offset 2 milling 100 R5.
pub fn mazak_t() -> Machine {
    let mut opts = CoreOptions::new(Dialect::Mazatrol);
    opts.axes = [true, true, true, false, true, true, false, false, false];
    let mut control = ControlData::default();
    control.offsets.zero[0][0] = ZeroOffset {
        offset: Pose {
            z: 200.0,
            ..Pose::ZERO
        },
        rotation_xy: 0.0,
    };
    for t in [
        tool(1, ToolKind::Turning, [20.0, 80.0, 0.0], 0.8, 3),
        tool(2, ToolKind::Milling, [100.0, 0.0, 0.0], 5.0, 0),
    ] {
        control.tools.tools.insert(t.number, t);
    }
    homes(&mut control);
    opts.control = control;
    let mut b = RotaryAxis::new('B', Carrier::Head, [0.0, 1.0, 0.0], [0.0, 0.0, 200.0]);
    b.min = -30.0;
    b.max = 210.0;
    let c = RotaryAxis::new('C', Carrier::Table, [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]);
    opts.five_axis = Some(FiveAxis::new(vec![b, c], [0.0, 0.0, 1.0]).unwrap());
    Machine {
        opts,
        params: MazatrolParams {
            series: Series::T,
            ..MazatrolParams::default()
        },
    }
}

/// A plain 3-axis M-series mill, no offsets.
pub fn mill() -> Machine {
    let mut opts = CoreOptions::new(Dialect::Mazatrol);
    opts.axes = [true, true, true, false, false, false, false, false, false];
    Machine {
        opts,
        params: MazatrolParams::default(),
    }
}

/// Runs `text` on `m`.
pub fn run(text: &str, m: &Machine) -> Run {
    let mut state = ModalState::power_on(&m.opts);
    let fe = Mazatrol::new(&m.opts, m.params.clone(), &mut state);
    let mut driver = Driver::new(
        std::io::Cursor::new(text.as_bytes().to_vec()),
        m.opts.clone(),
        state,
        fe,
    );
    let mut canon = Vec::new();
    let mut error = None;
    for item in driver.by_ref() {
        match item {
            Ok(c) => canon.push(c),
            Err(e) => {
                error = Some(e);
                break;
            }
        }
    }
    let warnings = driver.core().warnings.clone();
    Run {
        canon,
        error,
        warnings,
    }
}

/// Asserts two poses agree within 1e-6 on X Y Z B C.
pub fn near(p: Pose, want: [f64; 5]) {
    let got = [p.x, p.y, p.z, p.b, p.c];
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-6, "got {got:?}, want {want:?}");
    }
}
