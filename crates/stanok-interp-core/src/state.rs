//! The interpreter's persistent state common to every front end (grbl's `parser_state_t`): modal
//! groups, units, the work frame, the current position, technology values. A block runs on the
//! live state; the driver takes its undo first ([`ModalState::begin_block`]) and rolls it back if
//! the block fails (`driver.rs`), so an erroneous block leaves this untouched. Each front end keeps
//! its own modes beside it, journalled the same way ([`Journalled`]).

pub use crate::frame::WorkFrame;
use crate::options::CoreOptions;
use stanok_canon::{FeedMode, LengthUnits, Plane, Pose};

/// Group 1 / Interpolate: the motion mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionMode {
    /// G0.
    Rapid,
    /// G1.
    Linear,
    /// G2.
    ArcCw,
    /// G3.
    ArcCcw,
    /// No motion mode in force (RS274/NGC G80, its power-on mode): axis words alone are an error.
    None,
}

/// G90/G91 (and G90.1/G91.1, G190/G191 for arc centres).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DistanceMode {
    /// Positions.
    Absolute,
    /// Increments.
    Incremental,
}

/// Path control (AxiOMA G60/G64, RS274/NGC G61/G61.1/G64): kept for the planner (a later stage).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PathMode {
    /// G60 / G61.1: stop at every block end.
    ExactStop,
    /// RS274/NGC G61: exact path.
    ExactPath,
    /// G64 with optional blend tolerance P and naive-CAM tolerance Q (program units).
    Continuous {
        /// P, mm (0 = as fast as possible).
        blend_tolerance: f64,
    },
}

/// A part of the modal state that blocks rarely change, with its own undo journal.
///
/// ## Why
/// A block runs on the live state and a failing block must leave no trace, so the driver keeps
/// a copy of the state from before the block. Copying the whole state (1.6 kB: the work frame
/// with its cached inverse, every front end's own modes) on every block cost about 180
/// instructions per block, while an ordinary block changes a few scalars. The large parts are
/// therefore journalled where they are written: the first mutable access in a block saves the
/// value beside it, and only then hands out `&mut`.
///
/// ## Invariants
/// * `begin_block` clears the journal (the driver calls it before each block's execution);
///   after it, `saved` is meaningless until the first `DerefMut`.
/// * While `journalled` is set, `saved` holds the value at the start of the block, whatever
///   happened since: so `rollback` restores exactly the pre-block value.
/// * Reading (`Deref`) never journals; any `&mut` access does, even one that writes nothing
///   (correct, only a copy more).
#[derive(Clone, Copy)]
pub struct Journalled<T: Copy> {
    value: T,
    saved: T,
    journalled: bool,
}

impl<T: Copy> Journalled<T> {
    /// A cell holding `value` with an empty journal.
    pub fn new(value: T) -> Self {
        Journalled {
            value,
            saved: value,
            journalled: false,
        }
    }
    /// Starts a block: forget the journal.
    #[inline(always)]
    pub fn begin_block(&mut self) {
        self.journalled = false;
    }
    /// Undoes every change since `begin_block`.
    #[inline]
    pub fn rollback(&mut self) {
        if self.journalled {
            self.value = self.saved;
            self.journalled = false;
        }
    }
}

impl<T: Copy> std::ops::Deref for Journalled<T> {
    type Target = T;
    #[inline(always)]
    fn deref(&self) -> &T {
        &self.value
    }
}

impl<T: Copy> std::ops::DerefMut for Journalled<T> {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut T {
        if !self.journalled {
            self.saved = self.value;
            self.journalled = true;
        }
        &mut self.value
    }
}

impl<T: Copy + std::fmt::Debug> std::fmt::Debug for Journalled<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.value.fmt(f)
    }
}

impl<T: Copy + Default> Default for Journalled<T> {
    fn default() -> Self {
        Journalled::new(T::default())
    }
}

/// Everything that persists from block to block. `Copy` (no heap data). The large parts that
/// blocks rarely change are [`Journalled`]; the rest is copied per block by [`ModalState::snapshot`].
#[derive(Debug, Clone, Copy)]
pub struct ModalState {
    /// Interpolate group.
    pub motion: MotionMode,
    /// G17/G18/G19.
    pub plane: Plane,
    /// G90/G91.
    pub distance: DistanceMode,
    /// Arc centres absolute or incremental (RS274/NGC G90.1/G91.1, AxiOMA G190/G191).
    pub arc_distance: DistanceMode,
    /// G20/G21 (G70/G71).
    pub units: LengthUnits,
    /// G93/G94/G95.
    pub feed_mode: FeedMode,
    /// F as programmed, converted to mm/min (G94), mm/rev (G95) or 1/min (G93).
    pub feed: f64,
    /// Commanded spindle speeds, rev/min, per spindle (0 = main).
    pub spindle_speed: [f64; 4],
    /// Spindle on/off per spindle.
    pub spindle_on: [bool; 4],
    /// Tool prepared by the last T word.
    pub selected_tool: Option<u32>,
    /// Tool in the spindle.
    pub current_tool: u32,
    /// G60/G64 family.
    pub path_mode: PathMode,
    /// BRISK (false) / SOFT (true) acceleration.
    pub soft_acceleration: bool,
    /// Canned-cycle retract: G98 to the initial level (true) / G99 to R.
    pub retract_to_initial: bool,
    /// Lathe diameter mode (RS274/NGC G7 (true) / G8): X words are diameters.
    pub diameter_mode: bool,
    /// Mist (M7) and flood (M8).
    pub mist: bool,
    /// See `mist`.
    pub flood: bool,
    /// Active work offset number (1 = G54 … 9 = G59.3), 0 = none (e.g. AxiOMA G53).
    pub g5x_index: u8,
    /// The work frame (program → machine), composed from the pieces below.
    pub frame: Journalled<WorkFrame>,
    /// Rotation of the active work offset system about Z, degrees (RS274/NGC G10 L2 R: what R
    /// of `frame` is), announced in `Canon::Init`.
    pub xy_rotation_deg: f64,
    /// Where the tool is, machine coordinates, mm.
    pub position: Pose,
}

impl ModalState {
    /// The state at power-on, before a front end sets its own defaults (motion G0, XY plane,
    /// absolute, incremental arc centres, mm, feed per minute, continuous path, no work offset,
    /// the tool at `initial_position`).
    pub fn power_on(opts: &CoreOptions) -> Self {
        ModalState {
            motion: MotionMode::Rapid,
            plane: Plane::XY,
            distance: DistanceMode::Absolute,
            arc_distance: DistanceMode::Incremental,
            units: LengthUnits::Millimetres,
            feed_mode: FeedMode::UnitsPerMinute,
            feed: 0.0,
            spindle_speed: [0.0; 4],
            spindle_on: [false; 4],
            selected_tool: None,
            current_tool: 0,
            path_mode: PathMode::Continuous {
                blend_tolerance: 0.0,
            },
            soft_acceleration: false,
            retract_to_initial: false,
            diameter_mode: false,
            mist: false,
            flood: false,
            g5x_index: 0,
            frame: Default::default(),
            xy_rotation_deg: 0.0,
            position: opts.initial_position,
        }
    }

    /// Current position in program coordinates (mm).
    #[inline]
    pub fn program_position(&self) -> Pose {
        self.frame.to_program(&self.position)
    }
}

/// Declares [`ModalSnapshot`] (the copied part of the state) and the per-block begin/rollback
/// pair from one list. Destructuring `ModalState` without `..` makes a field added to the state
/// but to neither list a compile error, so nothing can escape the undo.
macro_rules! modal_undo {
    (copied { $($c:ident : $ct:ty,)* } journalled { $($j:ident,)* }) => {
        /// The part of [`ModalState`] a block's undo copies: everything but the [`Journalled`]
        /// work frame.
        #[derive(Clone, Copy)]
        pub struct ModalSnapshot {
            $($c: $ct,)*
        }

        impl ModalState {
            /// Starts a block: clears the journals and returns the copy `rollback` restores.
            #[inline(always)]
            pub fn begin_block(&mut self) -> ModalSnapshot {
                let ModalState { $($c,)* $($j,)* } = self;
                $($j.begin_block();)*
                ModalSnapshot { $($c: *$c,)* }
            }

            /// Undoes the block begun with `begin_block` (which returned `snapshot`).
            #[cold]
            pub fn rollback(&mut self, snapshot: ModalSnapshot) {
                let ModalState { $($c,)* $($j,)* } = self;
                $($j.rollback();)*
                $(*$c = snapshot.$c;)*
            }
        }
    };
}

modal_undo! {
    copied {
        motion: MotionMode,
        plane: Plane,
        distance: DistanceMode,
        arc_distance: DistanceMode,
        units: LengthUnits,
        feed_mode: FeedMode,
        feed: f64,
        spindle_speed: [f64; 4],
        spindle_on: [bool; 4],
        selected_tool: Option<u32>,
        current_tool: u32,
        path_mode: PathMode,
        soft_acceleration: bool,
        retract_to_initial: bool,
        diameter_mode: bool,
        mist: bool,
        flood: bool,
        g5x_index: u8,
        xy_rotation_deg: f64,
        position: Pose,
    }
    journalled {
        frame,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_journalled_part_restores_the_value_from_before_the_block() {
        let mut cell = Journalled::new(1);
        cell.begin_block();
        *cell = 2;
        *cell = 3;
        cell.rollback();
        assert_eq!(*cell, 1);
        // A committed block (no rollback) keeps its value, and the next block's rollback goes
        // back to it, not to an older one.
        cell.begin_block();
        *cell = 4;
        cell.begin_block();
        *cell = 5;
        cell.rollback();
        assert_eq!(*cell, 4);
        // Untouched in a block: rollback changes nothing.
        cell.begin_block();
        cell.rollback();
        assert_eq!(*cell, 4);
    }

    #[test]
    fn rollback_restores_the_copied_and_the_journalled_parts() {
        let mut st = ModalState::power_on(&CoreOptions::new(stanok_syntax::Dialect::Rs274ngc));
        let before_x = st.position.x;
        let snapshot = st.begin_block();
        st.position.x += 5.0;
        st.feed = 123.0;
        st.frame.set_shift(Pose {
            x: 7.0,
            ..Pose::ZERO
        });
        st.rollback(snapshot);
        assert_eq!(st.position.x, before_x);
        assert_eq!(st.feed, 0.0);
        assert_eq!(*st.frame.shift(), Pose::ZERO);
    }
}
