//! The lab controls' G and M codes, tables per language (`code_table!`: the value — G × 10, M
//! as written —, the name, the group, what executes it; an M number without a row is a machine
//! function, `Canon::AuxiliaryFunction`):
//!
//! * [`nc31`] — the Elektronika NC-31 (spec lab-collection §2): a G frame either sets a mode on
//!   its own or starts a `*` group; `nc31.rs` dispatches both through the table.
//! * [`iso`] — the word-address controls, GOST-20999 (§4), 2P32 (§3) and the MC2101 notation
//!   (§3.10), which share one set of codes; `iso.rs` sorts a block's G words by the table's
//!   handler into the block's modes.
//!
//! The lab numbers are integers (`lab::not-an-integer` otherwise), so every value is a whole code
//! × 10, as in the other dialects' tables; [`lookup`] takes the number as written.

/// The row of `table`'s lookup for the integer code `g` as written (negative or huge: none).
#[inline]
pub fn lookup<C>(g: i64, find: impl Fn(u32) -> Option<C>) -> Option<C> {
    u32::try_from(g)
        .ok()
        .and_then(|g| g.checked_mul(10))
        .and_then(find)
}

/// The Elektronika NC-31's G codes (spec §2.6, §2.7, §2.9, §2.10).
pub mod nc31 {
    use stanok_canon::FeedMode;
    use stanok_interp_core::code_table;

    /// The document's groups of NC-31 G functions.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum Group {
        /// G94/G95: the unit of F (modal, a frame of its own).
        FeedUnit,
        /// G2/G3/G12/G13: the motion of an arc or rounding group.
        Arc,
        /// G25: repeat a range of frames.
        Repeat,
        /// G31–G33, G77, G78: canned cycles.
        Cycle,
    }

    /// What executes a code.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum Handler {
        /// A stand-alone frame sets the feed unit.
        SetFeedUnit(FeedMode),
        /// Starts an arc group of less than 90° (§2.6.1); alone: `nc31::group-expected`.
        ArcGroup,
        /// Starts a quarter-circle rounding group (§2.6.2); alone: `nc31::group-expected`.
        RoundingGroup,
        /// Starts a `G25* P aaabbb* [R k]` repeat group; alone: not supported.
        RepeatGroup,
        /// Recognised, refused as not supported (the document gives no rule).
        Unsupported,
    }

    use Group::*;
    use Handler::*;

    code_table! {
        /// Every G code of the NC-31 the lab document names.
        pub G_CODES, pub fn g_code -> Code<Group, Handler>;
        /// Arc, counter-clockwise in the Z-right/X-up view.
        G2 = 20, "G2", Arc, ArcGroup;
        /// Arc, clockwise in that view.
        G3 = 30, "G3", Arc, ArcGroup;
        /// Quarter-circle rounding (as G2).
        G12 = 120, "G12", Arc, RoundingGroup;
        /// Quarter-circle rounding (as G3).
        G13 = 130, "G13", Arc, RoundingGroup;
        /// Repeat frames aaa…bbb.
        G25 = 250, "G25", Repeat, RepeatGroup;
        /// Canned cycle.
        G31 = 310, "G31", Cycle, Unsupported;
        /// Canned cycle.
        G32 = 320, "G32", Cycle, Unsupported;
        /// Canned cycle.
        G33 = 330, "G33", Cycle, Unsupported;
        /// Canned cycle.
        G77 = 770, "G77", Cycle, Unsupported;
        /// Canned cycle.
        G78 = 780, "G78", Cycle, Unsupported;
        /// F in mm/min.
        G94 = 940, "G94", FeedUnit, SetFeedUnit(FeedMode::UnitsPerMinute);
        /// F in mm/rev.
        G95 = 950, "G95", FeedUnit, SetFeedUnit(FeedMode::UnitsPerRevolution);
    }

    /// What an NC-31 M function does. Executed where its frame stands (a frame holds one word);
    /// an M number without a row is a machine function (`Canon::AuxiliaryFunction`).
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum MHandler {
        /// M3/M4.
        StartSpindle(stanok_canon::SpindleDirection),
        /// M5.
        StopSpindle,
        /// M0: program stop.
        Stop,
        /// M17: back from a subprogram.
        Return,
        /// M2/M30: program end.
        End,
        /// M38–M41: the gearbox range (the next S is its code); also a machine function.
        GearRange,
    }

    /// The NC-31's M groups.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum MGroup {
        /// M0, M2, M17, M30.
        Program,
        /// M3–M5.
        Spindle,
        /// M38–M41.
        Gearbox,
    }

    code_table! {
        /// The NC-31's M functions with a meaning of their own (the value is the M number).
        pub M_CODES, pub fn m_code -> Code<MGroup, MHandler>;
        /// Program stop.
        M0 = 0, "M0", MGroup::Program, MHandler::Stop;
        /// Program end.
        M2 = 2, "M2", MGroup::Program, MHandler::End;
        /// Spindle clockwise.
        M3 = 3, "M3", MGroup::Spindle, MHandler::StartSpindle(stanok_canon::SpindleDirection::Clockwise);
        /// Spindle counter-clockwise.
        M4 = 4, "M4", MGroup::Spindle, MHandler::StartSpindle(stanok_canon::SpindleDirection::CounterClockwise);
        /// Spindle stop.
        M5 = 5, "M5", MGroup::Spindle, MHandler::StopSpindle;
        /// End of subprogram.
        M17 = 17, "M17", MGroup::Program, MHandler::Return;
        /// Program end.
        M30 = 30, "M30", MGroup::Program, MHandler::End;
        /// Gearbox range 1.
        M38 = 38, "M38", MGroup::Gearbox, MHandler::GearRange;
        /// Gearbox range 2.
        M39 = 39, "M39", MGroup::Gearbox, MHandler::GearRange;
        /// Gearbox range 3.
        M40 = 40, "M40", MGroup::Gearbox, MHandler::GearRange;
        /// Gearbox range 4.
        M41 = 41, "M41", MGroup::Gearbox, MHandler::GearRange;
    }
}

/// The G codes of the word-address lab controls: GOST-20999, 2P32, MC2101 (spec §3.4, §4.4).
pub mod iso {
    use stanok_canon::Plane;
    use stanok_interp_core::code_table;
    use stanok_interp_core::state::MotionMode;

    /// The modal groups (§4.4); two codes of one group in a block are `lab::g-group`.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum Group {
        /// G0–G3.
        Motion,
        /// G17–G19.
        Plane,
        /// G90/G91.
        Distance,
        /// G54/G55.
        WorkSystem,
        /// G40–G42.
        RadiusComp,
        /// G43/G44/G49: per-axis length correction (they may repeat: each binds an axis).
        LengthComp,
        /// G4, G28, G92: at most one of them in a block ([decide] §4.4).
        OneShot,
        /// G9, G53: this block only; they combine with motion and with each other.
        ThisBlock,
        /// G20: the XA system of compensation on a cylinder.
        Cylinder,
    }

    impl Group {
        /// How a message names the group ("two {name} codes in one block").
        pub fn name(self) -> &'static str {
            match self {
                Group::Motion => "motion",
                Group::Plane => "plane",
                Group::Distance => "distance",
                Group::WorkSystem => "work system",
                Group::RadiusComp => "radius compensation",
                Group::LengthComp => "length correction",
                Group::OneShot => "one-shot",
                Group::ThisBlock => "this-block",
                Group::Cylinder => "cylinder system",
            }
        }
    }

    /// What executes a code.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum Handler {
        /// The motion mode 0…3.
        SetMotion(MotionMode),
        /// The plane.
        SetPlane(Plane),
        /// Incremental (true) or absolute.
        SetIncremental(bool),
        /// Work system 1 (G54) or 2 (G55).
        SetWork(u8),
        /// Radius compensation: 0 off, 1 left, −1 right.
        SetRadiusComp(i8),
        /// The per-axis binding (iso_words.rs `Pending`): the mode the next axis word binds, +1
        /// (G43) or −1 (G44); `None` (G49) clears every binding.
        LengthBinding(Option<i8>),
        /// G9: exact stop at the end of this block.
        ExactStop,
        /// G53: this block's motion in machine coordinates.
        MachineCoordinates,
        /// G4: dwell, the time in the X word.
        Dwell,
        /// G28: home.
        Home,
        /// G92: set the position.
        SetPosition,
        /// G20: error 17 when corrector 175 is 0, else not supported.
        CylinderSystem,
    }

    use Group::*;
    use Handler::*;

    code_table! {
        /// Every G code of the word-address lab controls.
        pub G_CODES, pub fn g_code -> Code<Group, Handler>;
        /// Rapid (2P32: also a bare `G`).
        G0 = 0, "G0", Motion, SetMotion(MotionMode::Rapid);
        /// Straight feed.
        G1 = 10, "G1", Motion, SetMotion(MotionMode::Linear);
        /// Clockwise arc.
        G2 = 20, "G2", Motion, SetMotion(MotionMode::ArcCw);
        /// Counter-clockwise arc.
        G3 = 30, "G3", Motion, SetMotion(MotionMode::ArcCcw);
        /// Dwell.
        G4 = 40, "G4", OneShot, Dwell;
        /// Exact stop, this block.
        G9 = 90, "G9", ThisBlock, ExactStop;
        /// XY plane.
        G17 = 170, "G17", Group::Plane, SetPlane(stanok_canon::Plane::XY);
        /// ZX plane.
        G18 = 180, "G18", Group::Plane, SetPlane(stanok_canon::Plane::ZX);
        /// YZ plane.
        G19 = 190, "G19", Group::Plane, SetPlane(stanok_canon::Plane::YZ);
        /// The XA system on a cylinder.
        G20 = 200, "G20", Cylinder, CylinderSystem;
        /// Home.
        G28 = 280, "G28", OneShot, Home;
        /// Radius compensation off.
        G40 = 400, "G40", RadiusComp, SetRadiusComp(0);
        /// Radius compensation left.
        G41 = 410, "G41", RadiusComp, SetRadiusComp(1);
        /// Radius compensation right.
        G42 = 420, "G42", RadiusComp, SetRadiusComp(-1);
        /// Length correction +.
        G43 = 430, "G43", LengthComp, LengthBinding(Some(1));
        /// Length correction −.
        G44 = 440, "G44", LengthComp, LengthBinding(Some(-1));
        /// Length correction off.
        G49 = 490, "G49", LengthComp, LengthBinding(None);
        /// Machine coordinates, this block.
        G53 = 530, "G53", ThisBlock, MachineCoordinates;
        /// Work system 1.
        G54 = 540, "G54", WorkSystem, SetWork(1);
        /// Work system 2.
        G55 = 550, "G55", WorkSystem, SetWork(2);
        /// Absolute.
        G90 = 900, "G90", Distance, SetIncremental(false);
        /// Incremental.
        G91 = 910, "G91", Distance, SetIncremental(true);
        /// Set the position.
        G92 = 920, "G92", OneShot, SetPosition;
    }

    /// What a word-address control's M function does, and when: [`MHandler::phase`]. An M number
    /// without a row is a machine function (`Canon::AuxiliaryFunction`, before the motion).
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum MHandler {
        /// M3/M4.
        StartSpindle(stanok_canon::SpindleDirection),
        /// M5.
        StopSpindle,
        /// M7.
        Mist,
        /// M8.
        Flood,
        /// M9: mist and flood off.
        CoolantOff,
        /// M0 (false) / M1 (true): program stop.
        Stop(bool),
        /// M2/M30: program end.
        End,
        /// M17: end of a subprogram (§4.10).
        SubprogramEnd,
        /// M89 (true) / M90 (false): on the 2P32 the servo spindle (Y is the C axis while on,
        /// §3); on every control also the machine function.
        ServoSpindle(bool),
    }

    impl MHandler {
        /// After the block's motion (stops, ends, spindle stop, coolant off), else before it.
        pub const fn after_motion(self) -> bool {
            matches!(
                self,
                MHandler::StopSpindle
                    | MHandler::CoolantOff
                    | MHandler::Stop(_)
                    | MHandler::End
                    | MHandler::SubprogramEnd
            )
        }
    }

    /// The word-address controls' M groups.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum MGroup {
        /// M0–M2, M17, M30.
        Program,
        /// M3–M5, M89/M90.
        Spindle,
        /// M7–M9.
        Coolant,
    }

    code_table! {
        /// The M functions with a meaning of their own (the value is the M number).
        pub M_CODES, pub fn m_code -> Code<MGroup, MHandler>;
        /// Program stop.
        M0 = 0, "M0", MGroup::Program, MHandler::Stop(false);
        /// Optional stop.
        M1 = 1, "M1", MGroup::Program, MHandler::Stop(true);
        /// Program end.
        M2 = 2, "M2", MGroup::Program, MHandler::End;
        /// Spindle clockwise.
        M3 = 3, "M3", MGroup::Spindle, MHandler::StartSpindle(stanok_canon::SpindleDirection::Clockwise);
        /// Spindle counter-clockwise.
        M4 = 4, "M4", MGroup::Spindle, MHandler::StartSpindle(stanok_canon::SpindleDirection::CounterClockwise);
        /// Spindle stop.
        M5 = 5, "M5", MGroup::Spindle, MHandler::StopSpindle;
        /// Mist on.
        M7 = 7, "M7", MGroup::Coolant, MHandler::Mist;
        /// Flood on.
        M8 = 8, "M8", MGroup::Coolant, MHandler::Flood;
        /// Coolant off.
        M9 = 9, "M9", MGroup::Coolant, MHandler::CoolantOff;
        /// End of subprogram.
        M17 = 17, "M17", MGroup::Program, MHandler::SubprogramEnd;
        /// Program end.
        M30 = 30, "M30", MGroup::Program, MHandler::End;
        /// 2P32: servo spindle on.
        M89 = 89, "M89", MGroup::Spindle, MHandler::ServoSpindle(true);
        /// 2P32: servo spindle off.
        M90 = 90, "M90", MGroup::Spindle, MHandler::ServoSpindle(false);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn named_as_written<G: PartialEq + std::fmt::Debug, H: PartialEq + std::fmt::Debug>(
        table: &[stanok_interp_core::codes::Code<G, H>],
    ) {
        let mut seen = std::collections::HashSet::new();
        for c in table {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(c.code % 10, 0, "{}: the lab codes are integers", c.name);
            assert_eq!(c.name, format!("G{}", c.code / 10));
        }
    }

    #[test]
    fn every_code_once_named_as_written_and_found() {
        named_as_written(nc31::G_CODES);
        named_as_written(iso::G_CODES);
        for c in nc31::G_CODES {
            assert_eq!(lookup(i64::from(c.code / 10), nc31::g_code), Some(*c));
        }
        for c in iso::G_CODES {
            assert_eq!(lookup(i64::from(c.code / 10), iso::g_code), Some(*c));
        }
        assert_eq!(lookup(-2, iso::g_code), None);
        assert_eq!(lookup(i64::MAX, nc31::g_code), None);
        assert_eq!(lookup(429_496_730, iso::g_code), None);
    }

    #[test]
    fn every_m_code_once_named_as_written_and_found() {
        let mut seen = std::collections::HashSet::new();
        for c in nc31::M_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(c.name, format!("M{}", c.code));
            assert_eq!(nc31::m_code(c.code), Some(*c));
        }
        seen.clear();
        for c in iso::M_CODES {
            assert!(seen.insert(c.code), "{} twice", c.name);
            assert_eq!(c.name, format!("M{}", c.code));
            assert_eq!(iso::m_code(c.code), Some(*c));
        }
        assert_eq!(nc31::m_code(1), None, "NC-31 M1 is a machine function");
        assert_eq!(iso::m_code(6), None);
    }
}
