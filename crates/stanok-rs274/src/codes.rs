//! RS274/NGC's G codes (LinuxCNC 2.9): one table — the value × 10, the name, the modal group
//! (spec rs274ngc §2.1) and what executes it. `execute` (lib.rs) sorts a block's codes by
//! [`g_code`]'s group and runs the groups in LinuxCNC's order; the motion group's codes go to
//! their handler in `motion.rs`. Everywhere else a code is named by its constant (`G33`), never
//! by its number.

use crate::Group;
use stanok_interp_core::code_table;

/// What executes a code (beside its group's step in `execute`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Handler {
    /// The group's step sets the mode (planes, units, distance modes, G54…, G61/G64 …).
    Mode,
    /// Recognised, refused as not supported yet.
    Unsupported,
    /// G4.
    Dwell,
    /// G10 L…: tool table and coordinate systems.
    SetData,
    /// G28, G30: go home.
    Home,
    /// G28.1, G30.1: store the home position.
    StoreHome,
    /// G52, G92 family: offsets.
    Offset,
    /// G53: motion in machine coordinates (travels with G0/G1).
    MachineCoordinates,
    /// G5.3: ends a G5.2 NURBS block.
    NurbsEnd,
    /// G0, G1.
    Straight,
    /// G2, G3.
    Arc,
    /// G80.
    CancelMotion,
    /// G5 (cubic), G5.1 (quadratic) splines.
    Spline,
    /// G5.2: NURBS control points.
    Nurbs,
    /// G33: spindle-synchronised move.
    Thread,
    /// G33.1: rigid tapping.
    RigidTap,
    /// G76: threading cycle.
    ThreadCycle,
    /// G38.2–G38.5.
    Probe,
    /// G70–G72 and their .1/.2 forms: lathe cycles.
    LatheCycle,
    /// G73, G74, G81–G89: canned cycles.
    CannedCycle,
}

use Group::*;
use Handler::*;

code_table! {
    /// Every G code LinuxCNC 2.9 knows, by group.
    pub(crate) G_CODES, pub(crate) fn g_code -> Code<Group, Handler>;
    /// Dwell.
    G4 = 40, "G4", NonModal, Dwell;
    /// Set tool or coordinate data.
    G10 = 100, "G10", NonModal, SetData;
    /// Go to the G28 home.
    G28 = 280, "G28", NonModal, Home;
    /// Store the G28 home.
    G28_1 = 281, "G28.1", NonModal, StoreHome;
    /// Go to the G30 home.
    G30 = 300, "G30", NonModal, Home;
    /// Store the G30 home.
    G30_1 = 301, "G30.1", NonModal, StoreHome;
    /// Local offset.
    G52 = 520, "G52", NonModal, Offset;
    /// Machine coordinates for this block's G0/G1.
    G53 = 530, "G53", NonModal, MachineCoordinates;
    /// Coordinate offset.
    G92 = 920, "G92", NonModal, Offset;
    /// Cancel G92, reset its parameters.
    G92_1 = 921, "G92.1", NonModal, Offset;
    /// Cancel G92, keep its parameters.
    G92_2 = 922, "G92.2", NonModal, Offset;
    /// Apply G92 from its parameters.
    G92_3 = 923, "G92.3", NonModal, Offset;
    /// End of a G5.2 block.
    G5_3 = 53, "G5.3", NonModal, NurbsEnd;
    /// Rapid.
    G0 = 0, "G0", Motion, Straight;
    /// Linear feed.
    G1 = 10, "G1", Motion, Straight;
    /// Clockwise arc.
    G2 = 20, "G2", Motion, Arc;
    /// Counter-clockwise arc.
    G3 = 30, "G3", Motion, Arc;
    /// Cubic spline.
    G5 = 50, "G5", Motion, Spline;
    /// Quadratic spline.
    G5_1 = 51, "G5.1", Motion, Spline;
    /// NURBS block.
    G5_2 = 52, "G5.2", Motion, Nurbs;
    /// Spindle-synchronised motion.
    G33 = 330, "G33", Motion, Thread;
    /// Rigid tapping.
    G33_1 = 331, "G33.1", Motion, RigidTap;
    /// Probe towards, error if no contact.
    G38_2 = 382, "G38.2", Motion, Probe;
    /// Probe towards.
    G38_3 = 383, "G38.3", Motion, Probe;
    /// Probe away, error if no loss of contact.
    G38_4 = 384, "G38.4", Motion, Probe;
    /// Probe away.
    G38_5 = 385, "G38.5", Motion, Probe;
    /// Lathe finishing cycle.
    G70 = 700, "G70", Motion, LatheCycle;
    /// Lathe roughing along Z.
    G71 = 710, "G71", Motion, LatheCycle;
    /// G71 without pockets.
    G71_1 = 711, "G71.1", Motion, LatheCycle;
    /// G71 pockets only.
    G71_2 = 712, "G71.2", Motion, LatheCycle;
    /// Lathe roughing along X (facing).
    G72 = 720, "G72", Motion, LatheCycle;
    /// G72 without pockets.
    G72_1 = 721, "G72.1", Motion, LatheCycle;
    /// G72 pockets only.
    G72_2 = 722, "G72.2", Motion, LatheCycle;
    /// Peck drilling with chip break.
    G73 = 730, "G73", Motion, CannedCycle;
    /// Left-hand tapping.
    G74 = 740, "G74", Motion, CannedCycle;
    /// Threading cycle.
    G76 = 760, "G76", Motion, ThreadCycle;
    /// Cancel the modal motion.
    G80 = 800, "G80", Motion, CancelMotion;
    /// Drilling.
    G81 = 810, "G81", Motion, CannedCycle;
    /// Drilling with dwell.
    G82 = 820, "G82", Motion, CannedCycle;
    /// Peck drilling.
    G83 = 830, "G83", Motion, CannedCycle;
    /// Right-hand tapping.
    G84 = 840, "G84", Motion, CannedCycle;
    /// Boring, feed out.
    G85 = 850, "G85", Motion, CannedCycle;
    /// Boring, spindle stop, rapid out.
    G86 = 860, "G86", Motion, CannedCycle;
    /// Back boring.
    G87 = 870, "G87", Motion, CannedCycle;
    /// Boring, spindle stop, manual out.
    G88 = 880, "G88", Motion, CannedCycle;
    /// Boring, dwell, feed out.
    G89 = 890, "G89", Motion, CannedCycle;
    /// XY plane.
    G17 = 170, "G17", Plane, Mode;
    /// ZX plane.
    G18 = 180, "G18", Plane, Mode;
    /// YZ plane.
    G19 = 190, "G19", Plane, Mode;
    /// UV plane.
    G17_1 = 171, "G17.1", Plane, Unsupported;
    /// WU plane.
    G18_1 = 181, "G18.1", Plane, Unsupported;
    /// VW plane.
    G19_1 = 191, "G19.1", Plane, Unsupported;
    /// Absolute distance mode.
    G90 = 900, "G90", Distance, Mode;
    /// Incremental distance mode.
    G91 = 910, "G91", Distance, Mode;
    /// Absolute arc centres.
    G90_1 = 901, "G90.1", ArcDistance, Mode;
    /// Incremental arc centres.
    G91_1 = 911, "G91.1", ArcDistance, Mode;
    /// Inverse time feed.
    G93 = 930, "G93", FeedMode, Mode;
    /// Feed per minute.
    G94 = 940, "G94", FeedMode, Mode;
    /// Feed per revolution.
    G95 = 950, "G95", FeedMode, Mode;
    /// Inches.
    G20 = 200, "G20", Units, Mode;
    /// Millimetres.
    G21 = 210, "G21", Units, Mode;
    /// Cutter compensation off.
    G40 = 400, "G40", CutterComp, Mode;
    /// Compensation left.
    G41 = 410, "G41", CutterComp, Mode;
    /// Compensation right.
    G42 = 420, "G42", CutterComp, Mode;
    /// Dynamic compensation left.
    G41_1 = 411, "G41.1", CutterComp, Mode;
    /// Dynamic compensation right.
    G42_1 = 421, "G42.1", CutterComp, Mode;
    /// Tool length offset from the table.
    G43 = 430, "G43", ToolLength, Mode;
    /// Dynamic tool length offset.
    G43_1 = 431, "G43.1", ToolLength, Mode;
    /// Additional tool length offset.
    G43_2 = 432, "G43.2", ToolLength, Mode;
    /// Tool length offset off.
    G49 = 490, "G49", ToolLength, Mode;
    /// Retract to the initial level.
    G98 = 980, "G98", Retract, Mode;
    /// Retract to R.
    G99 = 990, "G99", Retract, Mode;
    /// Coordinate system 1.
    G54 = 540, "G54", CoordSystem, Mode;
    /// Coordinate system 2.
    G55 = 550, "G55", CoordSystem, Mode;
    /// Coordinate system 3.
    G56 = 560, "G56", CoordSystem, Mode;
    /// Coordinate system 4.
    G57 = 570, "G57", CoordSystem, Mode;
    /// Coordinate system 5.
    G58 = 580, "G58", CoordSystem, Mode;
    /// Coordinate system 6.
    G59 = 590, "G59", CoordSystem, Mode;
    /// Coordinate system 7.
    G59_1 = 591, "G59.1", CoordSystem, Mode;
    /// Coordinate system 8.
    G59_2 = 592, "G59.2", CoordSystem, Mode;
    /// Coordinate system 9.
    G59_3 = 593, "G59.3", CoordSystem, Mode;
    /// Exact path.
    G61 = 610, "G61", PathControl, Mode;
    /// Exact stop.
    G61_1 = 611, "G61.1", PathControl, Mode;
    /// Continuous path with tolerance.
    G64 = 640, "G64", PathControl, Mode;
    /// Constant surface speed.
    G96 = 960, "G96", SpindleMode, Mode;
    /// Constant spindle speed.
    G97 = 970, "G97", SpindleMode, Mode;
    /// Lathe diameter mode.
    G7 = 70, "G7", LatheDiameter, Mode;
    /// Lathe radius mode.
    G8 = 80, "G8", LatheDiameter, Mode;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_once_and_named_as_written() {
        let mut seen = std::collections::HashSet::new();
        for c in G_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            let written = if c.code % 10 == 0 {
                format!("G{}", c.code / 10)
            } else {
                format!("G{}.{}", c.code / 10, c.code % 10)
            };
            assert_eq!(c.name, written);
            assert_eq!(g_code(c.code), Some(*c));
        }
        assert_eq!(g_code(G33).map(|c| c.handler), Some(Handler::Thread));
        assert_eq!(g_code(345), None);
    }
}
