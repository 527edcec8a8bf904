//! The built-in machines written in code (`mill`, `lathe`); the 5-axis ones are TOML files
//! (`BUILTIN_FIVE_AXIS`). Tests keep each equal to its file in `machines/`.

use super::{AxisData, AxisKind, ChannelData, MachineData, PATH_TOLERANCE};
use stanok_canon::setup::ControlData;
use stanok_canon::LengthUnits;
use std::collections::BTreeMap;

impl MachineData {
    /// The default 3-axis mill: X, Y ±500 mm, Z ±300 mm, 10 000 mm/min per axis and rapid, 5 000
    /// mm/min feed, 1 000 mm/s², 20 000 mm/s³; no stored data. Equal to `machines/mill.toml`.
    pub fn default_mill() -> MachineData {
        let axis = |name: char, limit: f64| AxisData {
            name,
            kind: AxisKind::Linear,
            min: -limit,
            max: limit,
            max_velocity: 10_000.0,
            max_acceleration: 1_000.0,
            max_jerk: 20_000.0,
            transverse: false,
        };
        MachineData {
            name: "mill".into(),
            description: "Built-in 3-axis vertical mill, travel ±500 mm in X and Y, ±300 mm in Z around the origin"
                .into(),
            rapid_rate: 10_000.0,
            max_feed: 5_000.0,
            arc_tolerance: 0.01,
            path_tolerance: PATH_TOLERANCE,
            axes: vec![axis('X', 500.0), axis('Y', 500.0), axis('Z', 300.0)],
            linuxcnc_units: LengthUnits::Millimetres,
            rs274_linuxcnc_arc_tolerance: false,
            control: ControlData::default(),
            m_functions: "generic".into(),
            kinematics: None,
            feed_table: BTreeMap::new(),
            speed_table: BTreeMap::new(),
            channel: ChannelData::default(),
            mazatrol: None,
            stock: None,
        }
    }

    /// The built-in 2-axis lathe: X (transverse, radius values in machine data; may be programmed
    /// as a diameter) −300…300 mm and Z −1000…500 mm, 8 000 mm/min per axis and rapid, 3 000 mm/min
    /// feed, 800 mm/s², 16 000 mm/s³; no stored data. Equal to `machines/lathe.toml`.
    pub fn default_lathe() -> MachineData {
        let axis = |name: char, min: f64, max: f64, transverse: bool| AxisData {
            name,
            kind: AxisKind::Linear,
            min,
            max,
            max_velocity: 8_000.0,
            max_acceleration: 800.0,
            max_jerk: 16_000.0,
            transverse,
        };
        MachineData {
            name: "lathe".into(),
            description: "Built-in 2-axis lathe (X transverse, Z along the spindle)".into(),
            rapid_rate: 8_000.0,
            max_feed: 3_000.0,
            arc_tolerance: 0.01,
            path_tolerance: PATH_TOLERANCE,
            axes: vec![
                axis('X', -300.0, 300.0, true),
                axis('Z', -1000.0, 500.0, false),
            ],
            linuxcnc_units: LengthUnits::Millimetres,
            rs274_linuxcnc_arc_tolerance: false,
            control: ControlData::default(),
            m_functions: "generic".into(),
            kinematics: None,
            feed_table: BTreeMap::new(),
            speed_table: BTreeMap::new(),
            channel: ChannelData::default(),
            mazatrol: None,
            stock: None,
        }
    }
}
