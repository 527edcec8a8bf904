//! AxiOMA's own modal state (the other front ends have none of it): polar programming, tool
//! length compensation, edges, G28/G29, spindle tools, diameter axes. Journalled with the block
//! (`stanok_interp_core::state::Journalled`), like the chain of frames (`chain.rs`).

use stanok_canon::{Plane, Pose};

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
