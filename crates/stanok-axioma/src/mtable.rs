//! The AxiOMA M-function table as machine data (spec axioma-2 §1.3, §4, §5; manual tables 2.2/2.3).
//!
//! The manual: "the actual set of M functions is defined by the channel machine-parameter
//! configuration". So the table is data, not code: each entry names its number, its modal group,
//! its prefix/postfix timing and what it does (`MKind`); each group has an execution order number,
//! a default (the M vector at start-up) and whether program end resets it. Two built-in profiles:
//!
//! * `MTable::generic()` — table 2.2: program control, spindles 1–4 (M<x>03/04/05/13/14/19/70),
//!   M902/M903/M905, coolant M07/M08/M09, tool change M06/M66, chuck M21/M22, chip conveyor
//!   M50/M51, guard M54/M55, batch probe M910/M911.
//! * `MTable::beavermill()` — the generic table with the BeaverMill BVR B-110 groups of table 8.1:
//!   M_Cool_AirCool (M7/M8/M9/M10/M708/M710, replacing the generic coolant group),
//!   M_ProbeSwitch (M73/M74/M75) and MSwivelRotaryTable (M115/M116/M120–M123).
//!
//! Execution order inside a block (§4.1): prefix functions, then postfix ones; inside each class by
//! the group's order number, then by the group's position in the table (so the main spindle's group
//! runs before spindle 2's), then as written. Known order numbers (from the manual's example):
//! spindle 1, coolant 2, tool 3; the rest are this table's choice (A32). Program control (M00, M01,
//! M02, M30, M99) always runs last.

use stanok_canon::{AuxTiming, SpindleDirection};

/// What an M function does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MKind {
    /// M00 (false) / M01 (true): stop at the end of the block.
    ProgramStop {
        /// M01: only with the optional-stop switch on.
        optional: bool,
    },
    /// M02 / M30.
    ProgramEnd,
    /// M99: end of program and move to the waiting position (`MTable::waiting_position`).
    ProgramEndToWaitingPosition,
    /// M<x>03 / M<x>04 / M<x>13 / M<x>14.
    SpindleOn {
        /// 0 = main spindle … 3 = spindle 4.
        spindle: u8,
        /// Rotation sense.
        direction: SpindleDirection,
        /// M<x>13 / M<x>14 also switch the coolant on.
        coolant: bool,
    },
    /// M<x>05.
    SpindleStop {
        /// 0 … 3.
        spindle: u8,
    },
    /// M<x>19 with S (S<i>=) the angle in degrees.
    SpindleOrient {
        /// 0 … 3.
        spindle: u8,
    },
    /// M<x>70: the spindle becomes an interpolated axis.
    SpindleAxisMode {
        /// 0 … 3.
        spindle: u8,
    },
    /// M902 H1=<spindle>: the given spindle to axis mode.
    AxisModeOf,
    /// M903 N1=<spindle>: the given spindle back to spindle mode.
    SpindleModeOf,
    /// M905 [N1=<n>]: cutter-compensation look-ahead depth.
    CompensationDepth,
    /// Generic M07 (mist, coolant mode 1).
    CoolantMist,
    /// Generic M08 (flood, coolant mode 2).
    CoolantFlood,
    /// Generic M09: coolant off.
    CoolantOff,
    /// M06 (automatic) / M66 (manual) tool change with its T/D words.
    ToolChange,
    /// M910 (true) / M911 (false): batch probe (skip) mode.
    BatchProbe {
        /// Armed.
        on: bool,
    },
    /// BeaverMill rotary-table clamps: Some(true) clamps, Some(false) unclamps, None leaves the axis.
    TableClamp {
        /// Axis A.
        a: Option<bool>,
        /// Axis C.
        c: Option<bool>,
    },
    /// A machine builder's function: passed to the PLC as `Canon::AuxiliaryFunction`; the CNC's
    /// only state is the M vector. `all_off` marks the function that program end implies (M9).
    Machine,
}

/// One modal group of M functions.
#[derive(Debug, Clone, PartialEq)]
pub struct MGroup {
    /// The manual's group name (`M_SpnCtrl`).
    pub name: String,
    /// Execution order within prefix/postfix (lower first).
    pub order: u32,
    /// The function shown in the M vector at start-up.
    pub default: Option<u32>,
    /// Program end (M02/M30/M99) returns the group to its default (spindles, coolant).
    pub reset_at_end: bool,
}

/// One M function.
#[derive(Debug, Clone, PartialEq)]
pub struct MEntry {
    /// The M number (`203` for M203).
    pub number: u32,
    /// Index into `MTable::groups`.
    pub group: usize,
    /// Before or after the block's motion.
    pub timing: AuxTiming,
    /// What it does.
    pub kind: MKind,
}

/// The channel's M-function configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct MTable {
    /// Profile name (`generic`, `beavermill`).
    pub profile: String,
    /// Modal groups.
    pub groups: Vec<MGroup>,
    /// Functions.
    pub entries: Vec<MEntry>,
    /// M99's waiting position: a home position number 1…8 (None = M99 ends where it is, warning).
    pub waiting_position: Option<u8>,
}

impl Default for MTable {
    fn default() -> Self {
        MTable::generic()
    }
}

/// Order of program control: after every other postfix function.
pub const PROGRAM_CONTROL_ORDER: u32 = 1000;

impl MTable {
    /// A built-in profile by name: `generic` or `beavermill`.
    pub fn profile(name: &str) -> Option<MTable> {
        match name.to_ascii_lowercase().as_str() {
            "generic" | "axioma" => Some(MTable::generic()),
            "beavermill" => Some(MTable::beavermill()),
            _ => None,
        }
    }

    /// The function with this number.
    pub fn lookup(&self, number: u32) -> Option<&MEntry> {
        self.entries.iter().find(|e| e.number == number)
    }

    /// The group index of a group name.
    pub fn group_index(&self, name: &str) -> Option<usize> {
        self.groups.iter().position(|g| g.name == name)
    }

    fn group(&mut self, name: &str, order: u32, default: Option<u32>, reset_at_end: bool) -> usize {
        self.groups.push(MGroup {
            name: name.to_string(),
            order,
            default,
            reset_at_end,
        });
        self.groups.len() - 1
    }

    fn add(&mut self, number: u32, group: usize, timing: AuxTiming, kind: MKind) {
        self.entries.retain(|e| e.number != number);
        self.entries.push(MEntry {
            number,
            group,
            timing,
            kind,
        });
    }

    /// Table 2.2: the functions every AxiOMA channel has.
    pub fn generic() -> MTable {
        use AuxTiming::{Postfix, Prefix};
        use SpindleDirection::{Clockwise, CounterClockwise};
        let mut t = MTable {
            profile: "generic".into(),
            groups: Vec::new(),
            entries: Vec::new(),
            waiting_position: None,
        };
        let prg = t.group("M_PrgCtrl", PROGRAM_CONTROL_ORDER, None, false);
        t.add(0, prg, Postfix, MKind::ProgramStop { optional: false });
        t.add(1, prg, Postfix, MKind::ProgramStop { optional: true });
        t.add(2, prg, Postfix, MKind::ProgramEnd);
        t.add(30, prg, Postfix, MKind::ProgramEnd);
        t.add(99, prg, Postfix, MKind::ProgramEndToWaitingPosition);
        for spindle in 0..4u8 {
            let base = if spindle == 0 {
                0
            } else {
                100 * (spindle as u32 + 1)
            };
            let name = if spindle == 0 {
                "M_SpnCtrl".to_string()
            } else {
                format!("M_Spn{}Ctrl", spindle + 1)
            };
            let g = t.group(&name, 1, Some(base + 5), true);
            let on = |direction, coolant| MKind::SpindleOn {
                spindle,
                direction,
                coolant,
            };
            t.add(base + 3, g, Prefix, on(Clockwise, false));
            t.add(base + 4, g, Prefix, on(CounterClockwise, false));
            t.add(base + 5, g, Postfix, MKind::SpindleStop { spindle });
            t.add(base + 13, g, Prefix, on(Clockwise, true));
            t.add(base + 14, g, Prefix, on(CounterClockwise, true));
            t.add(base + 19, g, Prefix, MKind::SpindleOrient { spindle });
            t.add(base + 70, g, Prefix, MKind::SpindleAxisMode { spindle });
        }
        let coolant = t.group("M_Ctrl", 2, Some(9), true);
        t.add(7, coolant, Prefix, MKind::CoolantMist);
        t.add(8, coolant, Prefix, MKind::CoolantFlood);
        t.add(9, coolant, Postfix, MKind::CoolantOff);
        let tool = t.group("M_Tool", 3, None, false);
        t.add(6, tool, Prefix, MKind::ToolChange);
        t.add(66, tool, Prefix, MKind::ToolChange);
        let ext = t.group("M_ExtCmd", 4, Some(903), false);
        t.add(902, ext, Prefix, MKind::AxisModeOf);
        // Table 2.2 marks M903 prefix, §7.4 postfix: the section text wins (A30).
        t.add(903, ext, Postfix, MKind::SpindleModeOf);
        t.add(905, ext, Postfix, MKind::CompensationDepth);
        let clamp = t.group("M_ClampLock", 5, Some(22), false);
        t.add(21, clamp, Prefix, MKind::Machine);
        t.add(22, clamp, Postfix, MKind::Machine);
        let chips = t.group("M_ChipConveyorCtrl", 6, Some(51), false);
        t.add(50, chips, Prefix, MKind::Machine);
        t.add(51, chips, Postfix, MKind::Machine);
        let guard = t.group("M_SafeguardCtrl", 7, Some(55), false);
        t.add(54, guard, Prefix, MKind::Machine);
        t.add(55, guard, Postfix, MKind::Machine);
        let probe = t.group("M_BatchProbe", 8, Some(911), false);
        t.add(910, probe, Prefix, MKind::BatchProbe { on: true });
        t.add(911, probe, Postfix, MKind::BatchProbe { on: false });
        t
    }

    /// Table 2.3 / §8.1: the BeaverMill BVR B-110.
    pub fn beavermill() -> MTable {
        use AuxTiming::{Postfix, Prefix};
        let mut t = MTable::generic();
        t.profile = "beavermill".into();
        // M_Cool_AirCool takes the place (and order) of the generic coolant group.
        let generic_coolant = t.group_index("M_Ctrl").unwrap_or(0);
        t.groups[generic_coolant] = MGroup {
            name: "M_Cool_AirCool".into(),
            order: 2,
            default: Some(9),
            reset_at_end: true,
        };
        let cool = generic_coolant;
        for m in [7, 8, 10, 708, 710] {
            t.add(m, cool, Prefix, MKind::Machine);
        }
        t.add(9, cool, Postfix, MKind::Machine);
        let probe = t.group("M_ProbeSwitch", 9, Some(75), false);
        t.add(73, probe, Prefix, MKind::Machine);
        t.add(74, probe, Prefix, MKind::Machine);
        t.add(75, probe, Postfix, MKind::Machine);
        let table = t.group("MSwivelRotaryTable", 10, Some(115), false);
        let clamp = |a, c| MKind::TableClamp { a, c };
        t.add(115, table, Prefix, clamp(Some(false), Some(false)));
        t.add(116, table, Prefix, clamp(Some(true), Some(true)));
        t.add(120, table, Prefix, clamp(Some(true), None));
        t.add(121, table, Prefix, clamp(Some(false), None));
        t.add(122, table, Prefix, clamp(None, Some(true)));
        t.add(123, table, Prefix, clamp(None, Some(false)));
        t
    }
}

/// The M functions' part of the channel state: the M vector and the states behind it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MState {
    /// Last executed function per group (index = `MTable::groups`); empty until first used.
    pub vector: Vec<Option<u32>>,
    /// Rotary-table clamps (A, C) of the BeaverMill state machine.
    pub clamped: [bool; 2],
    /// M910 batch probe mode armed.
    pub batch_probe: bool,
    /// Spindles in interpolated-axis mode (M70, M902).
    pub axis_mode: [bool; 4],
    /// Last M<x>19 position per spindle, degrees (M19 without S returns there; 0 at start).
    pub orientation: [f64; 4],
}

impl MState {
    /// The vector, initialised with the table's defaults on first use.
    pub fn vector_mut(&mut self, table: &MTable) -> &mut Vec<Option<u32>> {
        if self.vector.len() != table.groups.len() {
            self.vector = table.groups.iter().map(|g| g.default).collect();
        }
        &mut self.vector
    }

    /// Group name and shown function of every group that shows one.
    pub fn display(&self, table: &MTable) -> Vec<(String, u32)> {
        table
            .groups
            .iter()
            .enumerate()
            .filter_map(|(i, g)| {
                let shown = if self.vector.len() == table.groups.len() {
                    self.vector[i]
                } else {
                    g.default
                };
                Some((g.name.clone(), shown?))
            })
            .collect()
    }

    /// The function the rotary-table group shows for the clamp state (§5.3).
    pub fn clamp_display(&self) -> u32 {
        match self.clamped {
            [false, false] => 115,
            [true, false] => 120,
            [false, true] => 122,
            [true, true] => 116,
        }
    }
}
