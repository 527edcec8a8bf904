//! Balt-System's G and M codes (spec cvu-five-axis §3, the words table and §3.3.1): one table
//! each — the value (G: × 10; M: the number, M codes have no decimals), the name, the group and
//! what executes it. `execute` (lib.rs) looks every G word of a block up in [`g_code`] and runs
//! its handler in written order, and every M word up in [`m_code`] and runs its handler in its
//! phase (before the block's motion or after it); a code a table lacks is not supported.
//! Everywhere else a code is named by its constant (`G06`, `M6`), never by its number.
//!
//! The codes the manual prohibits under CVU=1 (§3.3.1) are rows too (`Handler::ProhibitedInCvu`):
//! the front end recognises them — under CVU they are `balt::prohibited-in-cvu`, outside it they
//! are not supported, like any code it does not build.

use stanok_canon::SpindleDirection;
use stanok_interp_core::code_table;
use stanok_interp_core::state::{DistanceMode, MotionMode};

/// The modal groups of the codes Balt-System names (the words table of spec §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// G00–G03, G06: the motion type (G06 until G00–G03).
    Motion,
    /// G90/G91.
    Distance,
    /// G27 and the codes prohibited under CVU: no modal group the front end keeps.
    NonModal,
    /// G40–G42: profile (cutter radius) compensation.
    CutterComp,
    /// G60–G62: spatial tool radius compensation.
    SpatialComp,
    /// G20/G21: GTL geometric profile definition.
    Profile,
    /// G72–G74, G81–G86, G89: measuring and machining cycles.
    Cycle,
}

/// What executes a code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handler {
    /// G00–G03: the motion mode (and G06 ends).
    SetMotion(MotionMode),
    /// G06: spline nodes (spline.rs) until G00–G03.
    SplineNodes,
    /// G90/G91.
    SetDistance(DistanceMode),
    /// G27: used by the manual's programs, not defined there; no motion effect here.
    NoEffect,
    /// §3.3.1: `balt::prohibited-in-cvu` under CVU, else not supported.
    ProhibitedInCvu,
}

use Group::*;
use Handler::*;

code_table! {
    /// Every G code the Balt-System front end recognises.
    pub G_CODES, pub fn g_code -> Code<Group, Handler>;
    /// Rapid.
    G00 = 0, "G00", Motion, SetMotion(MotionMode::Rapid);
    /// Straight feed.
    G01 = 10, "G01", Motion, SetMotion(MotionMode::Linear);
    /// Clockwise arc with R in the `(DPI …)` plane (arc.rs).
    G02 = 20, "G02", Motion, SetMotion(MotionMode::ArcCw);
    /// Counter-clockwise arc.
    G03 = 30, "G03", Motion, SetMotion(MotionMode::ArcCcw);
    /// Spline nodes inside `(BSP …)`/`(ESP)`.
    G06 = 60, "G06", Motion, SplineNodes;
    /// Absolute X Y Z.
    G90 = 900, "G90", Distance, SetDistance(DistanceMode::Absolute);
    /// Incremental X Y Z (under CVU the angles stay absolute, §6.3).
    G91 = 910, "G91", Distance, SetDistance(DistanceMode::Incremental);
    /// Used by the manual's programs, not defined there.
    G27 = 270, "G27", NonModal, NoEffect;
    /// GTL profile definition.
    G20 = 200, "G20", Profile, ProhibitedInCvu;
    /// GTL profile definition.
    G21 = 210, "G21", Profile, ProhibitedInCvu;
    /// Profile compensation off.
    G40 = 400, "G40", CutterComp, ProhibitedInCvu;
    /// Profile compensation left.
    G41 = 410, "G41", CutterComp, ProhibitedInCvu;
    /// Profile compensation right.
    G42 = 420, "G42", CutterComp, ProhibitedInCvu;
    /// Spatial tool radius compensation.
    G60 = 600, "G60", SpatialComp, ProhibitedInCvu;
    /// Spatial tool radius compensation.
    G61 = 610, "G61", SpatialComp, ProhibitedInCvu;
    /// Spatial tool radius compensation.
    G62 = 620, "G62", SpatialComp, ProhibitedInCvu;
    /// Measuring cycle.
    G72 = 720, "G72", Cycle, ProhibitedInCvu;
    /// Measuring cycle.
    G73 = 730, "G73", Cycle, ProhibitedInCvu;
    /// Measuring cycle.
    G74 = 740, "G74", Cycle, ProhibitedInCvu;
    /// Drilling.
    G81 = 810, "G81", Cycle, ProhibitedInCvu;
    /// Boring.
    G82 = 820, "G82", Cycle, ProhibitedInCvu;
    /// Deep drilling.
    G83 = 830, "G83", Cycle, ProhibitedInCvu;
    /// Tapping.
    G84 = 840, "G84", Cycle, ProhibitedInCvu;
    /// Counter-drilling.
    G85 = 850, "G85", Cycle, ProhibitedInCvu;
    /// Reaming.
    G86 = 860, "G86", Cycle, ProhibitedInCvu;
    /// Reaming with dwell.
    G89 = 890, "G89", Cycle, ProhibitedInCvu;
}

/// The groups of the M functions the front end executes. The manual uses M3, M6 and M30 in its
/// programs without defining them (spec §3: "used but not defined"); the others are the usual
/// meanings of the control family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MGroup {
    /// M0, M1, M2, M30: program stop and end.
    Stop,
    /// M3–M5: the spindle.
    Spindle,
    /// M6: tool change.
    ToolChange,
}

/// When an M function acts within its block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Before the block's motion (spindle, tool).
    BeforeMotion,
    /// After it (stop, end).
    AfterMotion,
}

/// What executes an M function.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MHandler {
    /// M3/M4: start the spindle.
    StartSpindle(SpindleDirection),
    /// M5: stop the spindle.
    StopSpindle,
    /// M6: change to tool t with corrector c of the block's `T t.c` (required).
    ToolChange,
    /// M0 (false) / M1 (true, optional): program stop.
    Stop {
        /// M1.
        optional: bool,
    },
    /// M2/M30: program end.
    End,
}

impl MHandler {
    /// Before or after the block's motion.
    pub const fn phase(self) -> Phase {
        match self {
            MHandler::StartSpindle(_) | MHandler::StopSpindle | MHandler::ToolChange => {
                Phase::BeforeMotion
            }
            MHandler::Stop { .. } | MHandler::End => Phase::AfterMotion,
        }
    }
}

code_table! {
    /// Every M function the Balt-System front end executes (the value is the M number).
    pub M_CODES, pub fn m_code -> Code<MGroup, MHandler>;
    /// Program stop.
    M0 = 0, "M0", MGroup::Stop, MHandler::Stop { optional: false };
    /// Optional stop.
    M1 = 1, "M1", MGroup::Stop, MHandler::Stop { optional: true };
    /// Program end.
    M2 = 2, "M2", MGroup::Stop, MHandler::End;
    /// Spindle clockwise.
    M3 = 3, "M3", MGroup::Spindle, MHandler::StartSpindle(SpindleDirection::Clockwise);
    /// Spindle counter-clockwise.
    M4 = 4, "M4", MGroup::Spindle, MHandler::StartSpindle(SpindleDirection::CounterClockwise);
    /// Spindle stop.
    M5 = 5, "M5", MGroup::Spindle, MHandler::StopSpindle;
    /// Tool change (`T t.c M6`, in either order).
    M6 = 6, "M6", MGroup::ToolChange, MHandler::ToolChange;
    /// Program end.
    M30 = 30, "M30", MGroup::Stop, MHandler::End;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_once_named_as_written_and_found_by_its_value() {
        let mut seen = std::collections::HashSet::new();
        for c in G_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(
                c.code % 10,
                0,
                "{}: Balt-System has no decimal G codes",
                c.name
            );
            assert_eq!(c.name, format!("G{:02}", c.code / 10));
            assert_eq!(g_code(c.code), Some(*c));
        }
        assert_eq!(g_code(G06).map(|c| c.handler), Some(SplineNodes));
        for absent in [40, 50, 70, 170, 800, 870, 880, 921] {
            assert_eq!(g_code(absent), None, "{absent}");
        }
    }

    #[test]
    fn every_m_code_once_named_as_written_with_its_phase() {
        let mut seen = std::collections::HashSet::new();
        for c in M_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(c.name, format!("M{}", c.code));
            assert_eq!(m_code(c.code), Some(*c));
            let before = matches!(c.group, MGroup::Spindle | MGroup::ToolChange);
            assert_eq!(
                c.handler.phase() == Phase::BeforeMotion,
                before,
                "{}",
                c.name
            );
        }
        assert_eq!(m_code(M6).map(|c| c.handler), Some(MHandler::ToolChange));
        for absent in [7, 8, 9, 19, 99, 300] {
            assert_eq!(m_code(absent), None, "M{absent}");
        }
    }
}
