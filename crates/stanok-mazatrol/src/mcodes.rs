//! The M codes the Mazatrol EIA/ISO front end executes, as one table (`docs/dialects/mazatrol-eia.md`
//! §3.4 and §5): the number, the name as the manual writes it, the group and the handler. The
//! block runs them in the steps of `block.rs`: M6 with the tool (step 5), the spindle start,
//! coolant on, orientation and rigid tapping before the motion (step 6), and the spindle stop,
//! coolant off, stops, subprogram calls and the program end after it (step 10). Any other M
//! number is a machine function: passed on with a warning, in step 10.

use stanok_interp_core::code_table;

/// The groups of the M codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MGroup {
    /// M0, M1, M2, M30: stops and the program end.
    Stop,
    /// M3/M4/M5 (the turning or main spindle), M203/M204/M205 (the T-series milling spindle),
    /// M19 (orientation).
    Spindle,
    /// M7/M8/M9.
    Coolant,
    /// M6.
    ToolChange,
    /// M29: rigid tapping for the next tapping cycle.
    Tapping,
    /// M98/M99: subprogram call and return.
    Subprogram,
}

/// When an M code acts within its block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// With the tool selection (step 5).
    Tool,
    /// Before the block's motion (step 6).
    BeforeMotion,
    /// After it (step 10).
    AfterMotion,
}

/// What executes an M code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MHandler {
    /// M0 / M1 (optional, only with the optional stop switched on).
    Stop {
        /// M1.
        optional: bool,
    },
    /// M2 / M30: the spindles and coolant stop, the modes return to power-on.
    End,
    /// M3/M4/M203/M204.
    StartSpindle,
    /// M5/M205.
    StopSpindle,
    /// M19.
    Orient,
    /// M7/M8.
    CoolantOn,
    /// M9.
    CoolantOff,
    /// M6.
    ToolChange,
    /// M29.
    RigidTapping,
    /// M98.
    Call,
    /// M99.
    Return,
}

impl MHandler {
    /// The step of the block in which the code acts.
    pub const fn phase(self) -> Phase {
        match self {
            MHandler::ToolChange => Phase::Tool,
            MHandler::StartSpindle
            | MHandler::Orient
            | MHandler::CoolantOn
            | MHandler::RigidTapping => Phase::BeforeMotion,
            MHandler::StopSpindle
            | MHandler::CoolantOff
            | MHandler::Stop { .. }
            | MHandler::End
            | MHandler::Call
            | MHandler::Return => Phase::AfterMotion,
        }
    }
}

code_table! {
    /// Every M code the front end executes (the value is the M number; no decimals).
    pub M_CODES, pub fn m_code -> Code<MGroup, MHandler>;
    /// Program stop.
    M0 = 0, "M00", MGroup::Stop, MHandler::Stop { optional: false };
    /// Optional stop.
    M1 = 1, "M01", MGroup::Stop, MHandler::Stop { optional: true };
    /// Program end.
    M2 = 2, "M02", MGroup::Stop, MHandler::End;
    /// Spindle clockwise.
    M3 = 3, "M03", MGroup::Spindle, MHandler::StartSpindle;
    /// Spindle counter-clockwise.
    M4 = 4, "M04", MGroup::Spindle, MHandler::StartSpindle;
    /// Spindle stop.
    M5 = 5, "M05", MGroup::Spindle, MHandler::StopSpindle;
    /// Tool change.
    M6 = 6, "M06", MGroup::ToolChange, MHandler::ToolChange;
    /// Mist coolant on.
    M7 = 7, "M07", MGroup::Coolant, MHandler::CoolantOn;
    /// Flood coolant on.
    M8 = 8, "M08", MGroup::Coolant, MHandler::CoolantOn;
    /// Coolant off.
    M9 = 9, "M09", MGroup::Coolant, MHandler::CoolantOff;
    /// Spindle orientation at S degrees.
    M19 = 19, "M19", MGroup::Spindle, MHandler::Orient;
    /// Rigid tapping.
    M29 = 29, "M29", MGroup::Tapping, MHandler::RigidTapping;
    /// Program end and rewind.
    M30 = 30, "M30", MGroup::Stop, MHandler::End;
    /// Subprogram call.
    M98 = 98, "M98", MGroup::Subprogram, MHandler::Call;
    /// Subprogram return.
    M99 = 99, "M99", MGroup::Subprogram, MHandler::Return;
    /// Milling spindle clockwise (T-series).
    M203 = 203, "M203", MGroup::Spindle, MHandler::StartSpindle;
    /// Milling spindle counter-clockwise (T-series).
    M204 = 204, "M204", MGroup::Spindle, MHandler::StartSpindle;
    /// Milling spindle stop (T-series).
    M205 = 205, "M205", MGroup::Spindle, MHandler::StopSpindle;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_m_code_once_named_as_written_and_found() {
        let mut seen = std::collections::HashSet::new();
        for c in M_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(c.name, format!("M{:02}", c.code));
            assert_eq!(m_code(c.code), Some(*c));
        }
        for m in 0..1000 {
            assert_eq!(m_code(m).is_some(), seen.contains(&m), "M{m}");
        }
    }
}
