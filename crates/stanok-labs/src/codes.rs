//! The lab controls' G codes, one table per language (`code_table!`: the value × 10, the name,
//! the modal group, what executes it):
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
}

/// The G codes of the word-address lab controls: GOST-20999, 2P32, MC2101 (spec §3.4, §4.4).
pub mod iso {
    use stanok_canon::Plane;
    use stanok_interp_core::code_table;

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
        SetMotion(u8),
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
        G0 = 0, "G0", Motion, SetMotion(0);
        /// Straight feed.
        G1 = 10, "G1", Motion, SetMotion(1);
        /// Clockwise arc.
        G2 = 20, "G2", Motion, SetMotion(2);
        /// Counter-clockwise arc.
        G3 = 30, "G3", Motion, SetMotion(3);
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
}
