//! # stanok-axioma: the AxiOMA Control front end
//!
//! Block semantics (spec axioma-1 §2, §5, §6, §13, §15, §16 and axioma-2 §2, §3.3, §4), the
//! high-level language (`hll/`), the chain of frames (`chain.rs`), compensation, cycles,
//! splines, M tables, technology and 5-axis orientation. `front.rs` is the front end the driver
//! calls (`stanok_interp_core::FrontEnd`).
//!
//! Order of execution inside one block (the manual's prefix/postfix model, spec axioma-2 §4.1):
//!
//! ```text
//!  1. MSG("…")                         5. prefix M functions, by group order:
//!  2. modal G codes (plane, units,        spindle (1) with its S, coolant (2), tool (3) with its T,
//!     G90/G91, G190/G191, feed type,      then the other prefix groups in table order
//!     G60/G64, BRISK/SOFT …)           6. G04 dwell or the block's motion
//!  3. F                                7. postfix M functions by group order; program control
//!  4. S and T without an M function       (M00/M01/M02/M30/M99) always last
//! ```
//!
//! Conflicting words: the manual says only the last word of a group takes effect; Stanok does that
//! and warns. Functions of later capabilities (5-axis kinematics, 3D compensation, orientation
//! words) are recognised and rejected with `interp::unsupported` naming the issue that adds them.

mod arc_rules;
mod chain;
mod codes;
pub mod comp3d;
pub mod cutter_comp;
pub mod cycles;
mod extension;
mod frames;
mod front;
mod hll;
mod home;
mod message;
mod mfunc;
mod modes;
mod motion;
pub mod mtable;
mod orientation;
mod outputs;
mod polar;
pub mod probe;
pub mod splines;
mod steps;
mod technology;
mod tools;

/// The core's pieces under the names the front end's files use.
mod ctx {
    pub use stanok_interp_core::ctx::*;
    /// A block's context with the AxiOMA part.
    pub type Ctx<'a> = stanok_interp_core::Ctx<'a, crate::front::AxiomaPart>;
}
use stanok_interp_core::{arc, frame, state, words};

use codes::*;

pub use chain::AxiomaChain;
pub use extension::{AxiomaMachineParams, Extension};
pub use front::{Axioma, AxiomaPart};
pub use hll::value::HVal;
pub use modes::{AxiomaModes, HomeReturn, LengthComp, Polar};
pub use mtable::{MEntry, MGroup, MTable};
pub use probe::ProbeLatch;
pub use technology::css_rpm;

use crate::ctx::Ctx;
use crate::state::{MotionMode, PathMode};
use crate::words::Val;
use stanok_canon::{AuxTiming, Canon, Diagnostic, FeedMode};
use stanok_interp_core::Outcome;
use stanok_syntax::{ColSpan, Keyword};

/// The code's name as the manual writes it (`G01`, `G193`).
fn g_name(code: u32) -> String {
    match g_code(code) {
        Some(c) => c.name.to_string(),
        None => format!("G{:02}", code / 10),
    }
}

/// The modal group of a code the table has.
#[inline(always)]
fn group_of(code: u32) -> Option<Group> {
    g_code(code).map(|c| c.group)
}

use cutter_comp::{forbidden_under_comp, Comp};

use mfunc::{m_function, run_m, set_speed, MFunction, MWords};
use motion::{dwell_block, motion};
use mtable::MKind;
use splines::{SplineKind, SplineWords};
use technology::TechWords;

/// `_area`: the part of the language it belongs to (for readers of the code; users are told only
/// that it is not implemented).
fn unsupported(cx: &Ctx<'_>, what: &str, _area: &str, at: ColSpan) -> Diagnostic {
    cx.err(
        "interp::unsupported",
        format!("{what} is not supported yet"),
        at,
    )
    .with_note("not implemented in this version of Stanok")
}

/// A block's G codes after "last of a group wins": the action, the code, where it is written.
pub(crate) type Actions = Vec<(GAction, u32, ColSpan)>;

/// The words of a block beyond letters: keywords (`CR=`, `SOFT`, spline and technology words)
/// and indexed addresses (`S2=`, `T2=`, `Q1=`, orientation words), read before anything runs.
#[derive(Default)]
pub(crate) struct ExtraWords {
    pub(crate) cr: Option<Val>,
    pub(crate) tech: TechWords,
    pub(crate) sw: SplineWords,
    pub(crate) indexed_speeds: Vec<(u8, f64)>,
    pub(crate) spindle_tools: Vec<(u8, Val)>,
    pub(crate) spindle_edges: Vec<(u8, Val)>,
    /// `Q<i>=`: G110/G111 outputs or cycle parameters.
    pub(crate) q_words: Vec<(u8, Val)>,
    /// `N1=`/`H1=`: the M905 depth (A15).
    pub(crate) m905_depth: Option<Val>,
    pub(crate) ori_words: orientation::OriWords,
    /// 3D compensation's words: normals A4=…C5=, ISD=.
    pub(crate) words3: comp3d::Words3,
}

/// What the modal step found: the interpolation code (or G75) and the dwell.
pub(crate) struct Modal {
    pub(crate) motion_code: Option<(MotionMode, ColSpan)>,
    pub(crate) dwell: Option<ColSpan>,
}

/// The block's auxiliary functions, sorted, and their words (steps 4/5 and 7).
pub(crate) struct Aux {
    pub(crate) ms: Vec<(MFunction, ColSpan)>,
    pub(crate) mw: MWords,
}

/// Executes one AxiOMA block: the manual's steps in order (module doc). Each step is a function
/// below; a step that fails ends the block (the driver undoes what earlier steps did).
pub fn execute(cx: &mut Ctx<'_>) -> Result<Outcome, Diagnostic> {
    use steps::*;
    technology::power_on(cx);
    // Where this block's commands start: 3D compensation takes the block's motions from here.
    let block_start = cx.out.queue.len();
    let mut x = ExtraWords::default();
    read_keywords(cx, &mut x)?;
    read_indexed(cx, &mut x)?;
    let actions = sort_g_codes(cx)?;
    let comp_active = cx.fe.ext.comp.is_active();
    // 1. Message.
    message(cx);
    // 2. Modal G codes, spline breaks, cycle and output words, frames and offsets.
    let modal = modal_codes(cx, &actions, comp_active)?;
    spline_modes(cx, &actions, &x.sw, modal.dwell)?;
    let output = cycle_and_outputs(cx, &actions, &modal, &x.q_words)?;
    let parameter_block = frames_and_offsets(cx, &actions)?;
    // 3. F.
    feed(cx, &x.tech)?;
    // 4./5. S, T and prefix M functions.
    let mut aux = prefix_aux(cx, &actions, &x, comp_active)?;
    // 6. Dwell or motion.
    if let Some((on, span)) = output {
        outputs::switch(cx, on, &x.q_words, span)?;
    }
    dwell_or_motion(cx, &actions, &x, &modal, parameter_block, comp_active)?;
    cx.check_all_used()?;
    technology::refresh(cx);
    comp3d::after_block(cx, block_start)?;
    // 7. Postfix M functions; program control last.
    postfix_aux(cx, &mut aux)
}
