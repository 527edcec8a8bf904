//! The AxiOMA state that is not `Copy` (so it does not live in `ModalState`): the cutter
//! compensation look-ahead and the canned-cycle parameters, plus the release of held commands.
//!
//! ```text
//!  block runs ──▶ its commands go to `held` (behind a mark)       compensation keeps the block's
//!                 its motions, if compensated, go to `comp`  ───▶ motions as elements with a *slot*
//!  block commits ─▶ release(): held[..first unresolved slot] ──▶ queue, with every resolved motion
//!                  inserted at its slot                            (the iterator only reads `queue`)
//! ```
//!
//! A slot is the absolute index in the stream of held commands at which a motion was produced:
//! `held_base` counts the commands already released, so `slot − held_base` is an index into
//! `held`. Invariants: resolved motions are in program order and their slots never decrease;
//! nothing is released before the block that produced it has committed (a failing block restores
//! this whole struct from its backup and truncates `held`), so "a failing block emits nothing"
//! holds with the look-ahead.

use super::cutter_comp::Comp;
use super::cycles::CycleState;
use crate::InterpOptions;
use stanok_canon::{Canon, Diagnostic, Spanned};
use std::collections::VecDeque;

/// Machine parameters of the AxiOMA functions of spec axioma-3 that the machine data does not hold
/// yet (defaults stated per field).
#[derive(Debug, Clone, PartialEq)]
pub struct AxiomaMachineParams {
    /// A spindle position encoder is configured (G276 needs it, else error 2301). Default true.
    pub spindle_encoder: bool,
    /// Number of PLC outputs that G110/G111 may address (addresses 0 … n − 1). Default 64.
    pub plc_outputs: u32,
    /// Channel maximum feed, mm/min (G276 refuses a faster thread feed). Default None = no limit.
    pub max_feed: Option<f64>,
    /// Look-ahead depth of radius compensation (M905 without N1= restores it). Default 3.
    pub comp_depth: usize,
    /// Lathe cutting-edge positions: for code i, the vector v (in units of the nose radius, in the
    /// plane's (a1, a2) = (Z, X) components for G18) from the nose centre S to the tool tip P
    /// (spec axioma-3 §4.5.10, A9). Code 0 and 9: v = 0 (the programmed point is the nose centre).
    pub edge_positions: [[f64; 2]; 10],
}

impl Default for AxiomaMachineParams {
    fn default() -> Self {
        AxiomaMachineParams {
            spindle_encoder: true,
            plc_outputs: 64,
            max_feed: None,
            comp_depth: 3,
            // [D] A9: imaginary tip directions (Z, X): 1…4 the diagonal quadrants counter-clockwise
            // from (+Z, +X), 5…8 the axis directions +X, −Z, −X, +Z; configurable.
            edge_positions: [
                [0.0, 0.0],
                [1.0, 1.0],
                [-1.0, 1.0],
                [-1.0, -1.0],
                [1.0, -1.0],
                [0.0, 1.0],
                [-1.0, 0.0],
                [0.0, -1.0],
                [1.0, 0.0],
                [0.0, 0.0],
            ],
        }
    }
}

/// Compensation, cycle and release state of one AxiOMA run.
#[derive(Debug, Clone, Default)]
pub struct Extension {
    /// Cutter radius compensation (G40/G41/G42/G143/G144).
    pub comp: Comp,
    /// The active canned cycle and its parameters.
    pub cycle: CycleState,
    /// Commands released from `held` so far (slot base).
    pub held_base: u64,
    /// Where the last released motion ended (machine coordinates).
    pub released_end: Option<stanok_canon::Pose>,
}

/// Every released straight move starts where the previous motion ended. The compensation
/// engine's own tool bookkeeping can lag behind moves that bypass it (a Z plunge after a G143
/// contour was switched off), and the machine moves from where it is: the stream must say so.
/// Arcs are left as computed (their centre fixes their start).
fn chain(prev: &mut Option<stanok_canon::Pose>, c: &mut Spanned<Canon>) {
    if let Canon::StraightFeed(m) | Canon::StraightTraverse(m) = &mut c.value {
        if let Some(p) = *prev {
            m.start = p;
        }
    }
    if let Some(m) = c.value.motion() {
        *prev = Some(m.end());
    }
}

impl Extension {
    /// Moves every held command that no unresolved motion precedes into `queue`, with the
    /// resolved compensated motions inserted at their slots.
    pub fn release(
        &mut self,
        held: &mut VecDeque<Spanned<Canon>>,
        queue: &mut VecDeque<Spanned<Canon>>,
    ) {
        let limit = match self.comp.first_unresolved_slot() {
            Some(slot) => (slot.saturating_sub(self.held_base) as usize).min(held.len()),
            None => held.len(),
        };
        let mut ready = self.comp.take_ready().into_iter().peekable();
        let mut index = self.held_base;
        let mut prev = self.released_end;
        for mut item in held.drain(..limit) {
            while let Some((_, mut c)) = ready.next_if(|(slot, _)| *slot <= index) {
                chain(&mut prev, &mut c);
                queue.push_back(c);
            }
            chain(&mut prev, &mut item);
            queue.push_back(item);
            index += 1;
        }
        // Motions at the end of the released part (their slot is the next held index).
        for (_, mut c) in ready {
            chain(&mut prev, &mut c);
            queue.push_back(c);
        }
        self.released_end = prev;
        self.held_base = index;
    }

    /// End of the program text: compensation ends its path (the last element at its perpendicular
    /// point) and everything held is released.
    pub fn finish(
        &mut self,
        opts: &InterpOptions,
        held: &mut VecDeque<Spanned<Canon>>,
        queue: &mut VecDeque<Spanned<Canon>>,
        warnings: &mut Vec<Diagnostic>,
    ) -> Result<(), Diagnostic> {
        self.comp.flush_at_end(opts, warnings)?;
        self.release(held, queue);
        Ok(())
    }
}
