//! AxiOMA's G codes (spec axioma-2 table 2.1): one table — the value × 10, the name as the manual
//! writes it (`G01`), the modal group and the action. `execute` (lib.rs) looks each written code
//! up here, keeps the last of a group, and runs the actions in the manual's order; everywhere else
//! a code is named by its constant (`G193`), never by its number.

use crate::cycles::CycleKind;
use crate::state::{DistanceMode, MotionMode};
use stanok_canon::{FeedMode, LengthUnits, Plane};
use stanok_interp_core::code_table;

/// Modal groups of table 2.1 ("last one wins" within a group). G28/G29 and G75 share the motion
/// group with G00–G03.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Group {
    /// G00–G03, G75, G28/G29.
    Motion,
    /// G04.
    Dwell,
    /// G17–G19.
    Plane,
    /// G20/G21, G70/G71.
    Units,
    /// G90/G91.
    Distance,
    /// G190/G191.
    ArcCentre,
    /// G93–G95.
    FeedMode,
    /// G60/G64.
    PathMode,
    /// G98/G99.
    Retract,
    /// G72/G73.
    Mirror,
    /// G172/G173.
    Scale,
    /// G272/G273.
    Rotate,
    /// G193–G195.
    Shift,
    /// G53–G59.
    ZeroOffset,
    /// G153–G159.
    Workpiece,
    /// G10.
    Diameter,
    /// G15/G16.
    Polar,
    /// G43–G45, G49.
    LengthComp,
    /// G40–G42, G143/G144.
    Radius,
    /// G110/G111.
    Output,
    /// G80, G81 … G389.
    Cycle,
    /// G96/G97.
    Css,
}

/// What a G code does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum GAction {
    Motion(MotionMode),
    Dwell,
    Plane(Plane),
    Units(LengthUnits),
    Distance(DistanceMode),
    ArcCentre(DistanceMode),
    FeedMode(FeedMode),
    PathMode(bool),
    Retract(bool),
    /// G72 (false) / G73 (true).
    Mirror(bool),
    /// G172 / G173.
    Scale(bool),
    /// G272 / G273.
    Rotate(bool),
    /// G193 / G194 / G195 (the code).
    Shift(u32),
    /// G53 (None) / G54…G59 (1…6).
    ZeroOffset(Option<u8>),
    /// G153 (None) / G154…G159 (1…6).
    Workpiece(Option<u8>),
    /// G10: radius/diameter programming per axis.
    Diameter,
    /// G15 (false) / G16 (true).
    Polar(bool),
    /// G43 / G44 / G45 / G49 (the code).
    LengthComp(u32),
    /// G28 (true) / G29 (false).
    Home(bool),
    /// G40 / G41 / G42 / G143 / G144 (the code).
    Radius(u32),
    /// G110 (true, set) / G111 (false, reset).
    Output(bool),
    /// G75 probe move (the motion group).
    Probe,
    /// G96 (true) / G97 (false): constant surface speed.
    Css(bool),
    /// G80.
    CycleCancel,
    /// G81 … G389.
    Cycle(CycleKind),
}

code_table! {
    /// Every G code of AxiOMA, by group.
    pub(crate) G_CODES, pub(crate) fn g_code -> Code<Group, GAction>;
    /// Rapid.
    G0 = 0, "G00", Group::Motion, GAction::Motion(MotionMode::Rapid);
    /// Linear feed.
    G1 = 10, "G01", Group::Motion, GAction::Motion(MotionMode::Linear);
    /// Clockwise arc.
    G2 = 20, "G02", Group::Motion, GAction::Motion(MotionMode::ArcCw);
    /// Counter-clockwise arc.
    G3 = 30, "G03", Group::Motion, GAction::Motion(MotionMode::ArcCcw);
    /// Probe move (a linear move watched by the probe).
    G75 = 750, "G75", Group::Motion, GAction::Probe;
    /// To the home position.
    G28 = 280, "G28", Group::Motion, GAction::Home(true);
    /// Back from the home position.
    G29 = 290, "G29", Group::Motion, GAction::Home(false);
    /// Dwell.
    G4 = 40, "G04", Group::Dwell, GAction::Dwell;
    /// XY plane.
    G17 = 170, "G17", Group::Plane, GAction::Plane(Plane::XY);
    /// ZX plane.
    G18 = 180, "G18", Group::Plane, GAction::Plane(Plane::ZX);
    /// YZ plane.
    G19 = 190, "G19", Group::Plane, GAction::Plane(Plane::YZ);
    /// Inches.
    G20 = 200, "G20", Group::Units, GAction::Units(LengthUnits::Inches);
    /// Inches (G70 = G20).
    G70 = 700, "G70", Group::Units, GAction::Units(LengthUnits::Inches);
    /// Millimetres.
    G21 = 210, "G21", Group::Units, GAction::Units(LengthUnits::Millimetres);
    /// Millimetres (G71 = G21).
    G71 = 710, "G71", Group::Units, GAction::Units(LengthUnits::Millimetres);
    /// Absolute dimensions.
    G90 = 900, "G90", Group::Distance, GAction::Distance(DistanceMode::Absolute);
    /// Incremental dimensions.
    G91 = 910, "G91", Group::Distance, GAction::Distance(DistanceMode::Incremental);
    /// Absolute arc centres.
    G190 = 1900, "G190", Group::ArcCentre, GAction::ArcCentre(DistanceMode::Absolute);
    /// Incremental arc centres.
    G191 = 1910, "G191", Group::ArcCentre, GAction::ArcCentre(DistanceMode::Incremental);
    /// Inverse time feed.
    G93 = 930, "G93", Group::FeedMode, GAction::FeedMode(FeedMode::InverseTime);
    /// Feed per minute.
    G94 = 940, "G94", Group::FeedMode, GAction::FeedMode(FeedMode::UnitsPerMinute);
    /// Feed per revolution.
    G95 = 950, "G95", Group::FeedMode, GAction::FeedMode(FeedMode::UnitsPerRevolution);
    /// Exact stop.
    G60 = 600, "G60", Group::PathMode, GAction::PathMode(true);
    /// Continuous path.
    G64 = 640, "G64", Group::PathMode, GAction::PathMode(false);
    /// Cycles retract to the initial level.
    G98 = 980, "G98", Group::Retract, GAction::Retract(true);
    /// Cycles retract to R.
    G99 = 990, "G99", Group::Retract, GAction::Retract(false);
    /// Mirror off.
    G72 = 720, "G72", Group::Mirror, GAction::Mirror(false);
    /// Mirror on.
    G73 = 730, "G73", Group::Mirror, GAction::Mirror(true);
    /// Scale off.
    G172 = 1720, "G172", Group::Scale, GAction::Scale(false);
    /// Scale on.
    G173 = 1730, "G173", Group::Scale, GAction::Scale(true);
    /// Rotation off.
    G272 = 2720, "G272", Group::Rotate, GAction::Rotate(false);
    /// Rotation on.
    G273 = 2730, "G273", Group::Rotate, GAction::Rotate(true);
    /// Shift off.
    G193 = 1930, "G193", Group::Shift, GAction::Shift(1930);
    /// Shift added to the one in force.
    G194 = 1940, "G194", Group::Shift, GAction::Shift(1940);
    /// Shift set (axes not written keep theirs).
    G195 = 1950, "G195", Group::Shift, GAction::Shift(1950);
    /// Zero offsets off.
    G53 = 530, "G53", Group::ZeroOffset, GAction::ZeroOffset(None);
    /// Zero offset 1.
    G54 = 540, "G54", Group::ZeroOffset, GAction::ZeroOffset(Some(1));
    /// Zero offset 2.
    G55 = 550, "G55", Group::ZeroOffset, GAction::ZeroOffset(Some(2));
    /// Zero offset 3.
    G56 = 560, "G56", Group::ZeroOffset, GAction::ZeroOffset(Some(3));
    /// Zero offset 4.
    G57 = 570, "G57", Group::ZeroOffset, GAction::ZeroOffset(Some(4));
    /// Zero offset 5.
    G58 = 580, "G58", Group::ZeroOffset, GAction::ZeroOffset(Some(5));
    /// Zero offset 6.
    G59 = 590, "G59", Group::ZeroOffset, GAction::ZeroOffset(Some(6));
    /// Workpiece offsets off.
    G153 = 1530, "G153", Group::Workpiece, GAction::Workpiece(None);
    /// Workpiece offset 1.
    G154 = 1540, "G154", Group::Workpiece, GAction::Workpiece(Some(1));
    /// Workpiece offset 2.
    G155 = 1550, "G155", Group::Workpiece, GAction::Workpiece(Some(2));
    /// Workpiece offset 3.
    G156 = 1560, "G156", Group::Workpiece, GAction::Workpiece(Some(3));
    /// Workpiece offset 4.
    G157 = 1570, "G157", Group::Workpiece, GAction::Workpiece(Some(4));
    /// Workpiece offset 5.
    G158 = 1580, "G158", Group::Workpiece, GAction::Workpiece(Some(5));
    /// Workpiece offset 6.
    G159 = 1590, "G159", Group::Workpiece, GAction::Workpiece(Some(6));
    /// Radius/diameter programming per axis.
    G10 = 100, "G10", Group::Diameter, GAction::Diameter;
    /// Polar coordinates off.
    G15 = 150, "G15", Group::Polar, GAction::Polar(false);
    /// Polar coordinates on.
    G16 = 160, "G16", Group::Polar, GAction::Polar(true);
    /// Tool length compensation, positive.
    G43 = 430, "G43", Group::LengthComp, GAction::LengthComp(430);
    /// Tool length compensation, negative.
    G44 = 440, "G44", Group::LengthComp, GAction::LengthComp(440);
    /// Tool length compensation along the tool axis.
    G45 = 450, "G45", Group::LengthComp, GAction::LengthComp(450);
    /// Tool length compensation off.
    G49 = 490, "G49", Group::LengthComp, GAction::LengthComp(490);
    /// Radius compensation off.
    G40 = 400, "G40", Group::Radius, GAction::Radius(400);
    /// Radius compensation left.
    G41 = 410, "G41", Group::Radius, GAction::Radius(410);
    /// Radius compensation right.
    G42 = 420, "G42", Group::Radius, GAction::Radius(420);
    /// 3D radius compensation left.
    G143 = 1430, "G143", Group::Radius, GAction::Radius(1430);
    /// 3D radius compensation right.
    G144 = 1440, "G144", Group::Radius, GAction::Radius(1440);
    /// Set outputs.
    G110 = 1100, "G110", Group::Output, GAction::Output(true);
    /// Reset outputs.
    G111 = 1110, "G111", Group::Output, GAction::Output(false);
    /// Cancel the canned cycle.
    G80 = 800, "G80", Group::Cycle, GAction::CycleCancel;
    /// Drilling.
    G81 = 810, "G81", Group::Cycle, GAction::Cycle(CycleKind::Drill);
    /// Peck drilling.
    G83 = 830, "G83", Group::Cycle, GAction::Cycle(CycleKind::PeckDrill);
    /// Threading.
    G276 = 2760, "G276", Group::Cycle, GAction::Cycle(CycleKind::Thread);
    /// Longitudinal recess.
    G281 = 2810, "G281", Group::Cycle, GAction::Cycle(CycleKind::RecessLongitudinal);
    /// Face recess.
    G282 = 2820, "G282", Group::Cycle, GAction::Cycle(CycleKind::RecessFace);
    /// Longitudinal groove.
    G288 = 2880, "G288", Group::Cycle, GAction::Cycle(CycleKind::GrooveLongitudinal);
    /// Face groove.
    G289 = 2890, "G289", Group::Cycle, GAction::Cycle(CycleKind::GrooveFace);
    /// Rectangular pocket.
    G387 = 3870, "G387", Group::Cycle, GAction::Cycle(CycleKind::RectPocket);
    /// Slot.
    G388 = 3880, "G388", Group::Cycle, GAction::Cycle(CycleKind::Slot);
    /// Circular pocket.
    G389 = 3890, "G389", Group::Cycle, GAction::Cycle(CycleKind::CircPocket);
    /// Constant surface speed.
    G96 = 960, "G96", Group::Css, GAction::Css(true);
    /// Constant spindle speed.
    G97 = 970, "G97", Group::Css, GAction::Css(false);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_once_named_as_the_manual_writes_it() {
        let mut seen = std::collections::HashSet::new();
        for c in G_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(c.name, format!("G{:02}", c.code / 10));
            assert_eq!(g_code(c.code), Some(*c));
            if let GAction::Cycle(kind) = c.handler {
                assert_eq!(CycleKind::from_code(c.code), Some(kind));
            }
        }
        assert_eq!(g_code(G389).map(|c| c.group), Some(Group::Cycle));
        assert_eq!(g_code(G75).map(|c| c.group), Some(Group::Motion));
        assert_eq!(g_code(2740), None);
    }
}
