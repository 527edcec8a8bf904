//! The interpreter's persistent state (grbl's `parser_state_t`): modal groups, units, the work frame,
//! the current position, technology values. A block reads it, computes everything it will do, and
//! only then commits (see `block.rs`), so an erroneous block leaves this untouched.

use crate::axioma_chain::AxiomaChain;
pub use crate::frame::WorkFrame;
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
    /// RS274/NGC G80 (its power-on motion mode): axis words alone are an error.
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

/// AxiOMA G60/G64 and RS274/NGC G61/G61.1/G64: kept for the planner (a later stage).
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

/// AxiOMA tool length compensation group (G43/G44/G45/G49, spec axioma-3 §3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LengthComp {
    /// G49.
    Off,
    /// G43: lengths on the axes of the active plane's row, positive.
    Plus,
    /// G44: the same, negative.
    Minus,
    /// G45 L±17/18/19: a fixed row, independent of G17–G19.
    Fixed {
        /// The row's plane.
        plane: Plane,
        /// +1 or −1.
        sign: f64,
    },
}

/// AxiOMA G28/G29: how the last G28 reached its home position (spec axioma-2 §3.8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HomeReturn {
    /// No G28 to return from.
    None,
    /// At a home position, reached via this intermediate point (machine coordinates) or directly.
    From {
        /// The intermediate point.
        via: Option<Pose>,
    },
}

/// AxiOMA polar programming (G15/G16, spec axioma-1 §17).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polar {
    /// G16 active.
    pub on: bool,
    /// Pole (abscissa, ordinate) of `plane`, program coordinates, mm.
    pub pole: [f64; 2],
    /// The plane the pole belongs to.
    pub plane: Plane,
    /// Modal polar radius ρ, mm.
    pub rho: f64,
    /// Modal polar angle θ, degrees.
    pub theta: f64,
}

impl Default for Polar {
    fn default() -> Self {
        Polar {
            on: false,
            pole: [0.0; 2],
            plane: Plane::XY,
            rho: 0.0,
            theta: 0.0,
        }
    }
}

/// AxiOMA's own modes (the RS274/NGC and other front ends never change them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxiomaModes {
    /// AxiOMA polar programming.
    pub polar: Polar,
    /// AxiOMA tool length compensation mode.
    pub length_comp: LengthComp,
    /// AxiOMA active cutting edge D0…D4.
    pub edge: u8,
    /// AxiOMA: a tool length offset that the next motion block applies (spec axioma-3 §3.4).
    pub pending_tlo: Option<Pose>,
    /// AxiOMA: the G28 that G29 returns from.
    pub home_return: HomeReturn,
    /// AxiOMA: tools in spindles 2…4 (index 1…3; index 0 unused: the main spindle is `current_tool`).
    pub spindle_tools: [u32; 4],
    /// AxiOMA: active edges of spindles 2…4.
    pub spindle_edges: [u8; 4],
    /// AxiOMA G10: axes programmed as diameters (their words are halved).
    pub axioma_diameter: [bool; 9],
}

impl Default for AxiomaModes {
    fn default() -> Self {
        AxiomaModes {
            polar: Polar::default(),
            length_comp: LengthComp::Off,
            edge: 0,
            pending_tlo: None,
            home_return: HomeReturn::None,
            spindle_tools: [0; 4],
            spindle_edges: [0; 4],
            axioma_diameter: [false; 9],
        }
    }
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
    pub(crate) fn begin_block(&mut self) {
        self.journalled = false;
    }
    /// Undoes every change since `begin_block`.
    #[inline]
    pub(crate) fn rollback(&mut self) {
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
    /// Arc centres: G90.1/G91.1 (RS274/NGC), G190/G191 (AxiOMA).
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
    /// AxiOMA BRISK (false) / SOFT (true).
    pub soft_acceleration: bool,
    /// RS274/NGC G98 (true) / G99; AxiOMA G98/G99.
    pub retract_to_initial: bool,
    /// RS274/NGC G7 (true) / G8.
    pub diameter_mode: bool,
    /// Mist (M7) and flood (M8).
    pub mist: bool,
    /// See `mist`.
    pub flood: bool,
    /// Active work offset number (1 = G54 … 9 = G59.3), 0 = none (AxiOMA G53).
    pub g5x_index: u8,
    /// The work frame (program → machine), composed from the pieces below.
    pub frame: Journalled<WorkFrame>,
    /// RS274/NGC: rotation of the active G54…G59.3 system about Z, degrees (what R of `frame` is).
    pub xy_rotation_deg: f64,
    /// AxiOMA: frames, programmed shift, zero-offset and workpiece-system selections.
    pub axioma: Journalled<AxiomaChain>,
    /// AxiOMA: polar programming, tool length compensation, edges, G28/G29, diameter axes.
    pub axioma_modes: Journalled<AxiomaModes>,
    /// Mazatrol tool tip point control.
    pub mazatrol: Journalled<crate::mazatrol::MazatrolState>,
    /// Balt-System CVU.
    pub balt: Journalled<crate::balt::BaltState>,
    /// RS274/NGC: cycles, spindle direction, the motion codes beyond G0–G3/G80, overrides.
    pub rs274: Journalled<crate::rs274::Rs274State>,
    /// Where the tool is, machine coordinates, mm.
    pub position: Pose,
}

impl ModalState {
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
        /// parts (about 400 bytes instead of 1.6 kB).
        #[derive(Clone, Copy)]
        pub(crate) struct ModalSnapshot {
            $($c: $ct,)*
        }

        impl ModalState {
            /// Starts a block: clears the journals and returns the copy `rollback` restores.
            #[inline(always)]
            pub(crate) fn begin_block(&mut self) -> ModalSnapshot {
                let ModalState { $($c,)* $($j,)* } = self;
                $($j.begin_block();)*
                ModalSnapshot { $($c: *$c,)* }
            }

            /// Undoes the block begun with `begin_block` (which returned `snapshot`).
            #[cold]
            pub(crate) fn rollback(&mut self, snapshot: ModalSnapshot) {
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
        axioma,
        axioma_modes,
        mazatrol,
        balt,
        rs274,
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
        let mut st = crate::Interpreter::from_text(
            "",
            crate::InterpOptions::new(stanok_syntax::Dialect::Rs274ngc),
        )
        .state()
        .to_owned();
        let before_x = st.position.x;
        let snapshot = st.begin_block();
        st.position.x += 5.0;
        st.feed = 123.0;
        st.frame.set_shift(Pose {
            x: 7.0,
            ..Pose::ZERO
        });
        st.rs274.css = true;
        st.axioma_modes.edge = 3;
        st.rollback(snapshot);
        assert_eq!(st.position.x, before_x);
        assert_eq!(st.feed, 0.0);
        assert_eq!(*st.frame.shift(), Pose::ZERO);
        assert!(!st.rs274.css);
        assert_eq!(st.axioma_modes.edge, 0);
    }
}
