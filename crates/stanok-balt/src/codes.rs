//! Balt-System's G codes (spec cvu-five-axis §3, the words table and §3.3.1): one table — the
//! value × 10, the name, the modal group and what executes it. `execute` (lib.rs) looks every G
//! word of a block up in [`g_code`] and runs its handler in written order; a code the table lacks
//! is not supported. Everywhere else a code is named by its constant (`G06`), never by its number.
//!
//! The codes the manual prohibits under CVU=1 (§3.3.1) are rows too (`Handler::ProhibitedInCvu`):
//! the front end recognises them — under CVU they are `balt::prohibited-in-cvu`, outside it they
//! are not supported, like any code it does not build.

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
}
