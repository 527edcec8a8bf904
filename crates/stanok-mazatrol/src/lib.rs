//! # stanok-mazatrol: the Mazatrol EIA/ISO front end
//!
//! Mazak's Fanuc-compatible EIA/ISO language with tool tip point control inside it, as
//! `docs/dialects/mazatrol-eia.md` specifies it: the G codes of tables 12.1 (T-series) and 12.2
//! (M-series), spindle, coolant and tools, subprograms and the Fanuc custom macro B.
//!
//! | file | what |
//! |---|---|
//! | `front.rs` | the front end: lines, control flow, calls, the block transaction |
//! | `flow.rs` | programs, sequence numbers, loops, the call stack |
//! | `block.rs` | one block: words, checks, the order of execution |
//! | `codes.rs` | the G codes of both series and tables 12.1 / 12.2 |
//! | `ttpc_table.rs` | the tables applied: columns [1] and [2], R-08, R-09 |
//! | `ttpc.rs`, `ttpc_arc.rs`, `tlo.rs` | tool tip point control, G43/G44/G49, `T… M6` |
//! | `endpoint.rs` | end points: G90/G91, U/V/W, G122 polar input |
//! | `motion.rs` | lines, arcs, spirals, threads, G04, G27–G31, G53, G60, G22 |
//! | `coords.rs` | work offsets, G52, G92/G50, G10, scaling, mirror, rotations |
//! | `tools.rs` | the T-series turret `T tt oo`, G45–G48 |
//! | `spindle.rs` | S, G96/G97, M03–M05, M19, M203–M205, machine M codes, G109–G112 |
//! | `cycles.rs`, `drilling.rs`, `turning.rs`, `profile.rs` | canned cycles |
//! | `compensate.rs`, `comp.rs` | G40–G42, G46 |
//! | `polar_run.rs`, `polar.rs` | G12.1/G13.1, G07.1 |
//! | `macros.rs`, `macro_b.rs`, `vars.rs`, `eval.rs`, `rules.rs`, `tables.rs` | custom macro, variables, tables |
#![deny(missing_docs)]

mod block;
mod calls;
pub mod codes;
pub mod comp;
mod compensate;
mod coords;
mod cycles;
pub mod drilling;
pub(crate) mod endpoint;
mod eval;
pub mod flow;
mod front;
pub mod macro_b;
mod macros;
pub mod mcodes;
pub mod modes;
mod motion;
pub mod polar;
mod polar_run;
pub mod profile;
pub mod rules;
mod spindle;
mod statements;
pub mod tables;
mod tlo;
mod tools;
mod ttpc;
mod ttpc_arc;
mod ttpc_table;
pub mod turning;
pub mod vars;

/// The core's pieces under the names the front end's files use.
mod ctx {
    /// A block's context with the Mazatrol part.
    pub type Ctx<'a> = stanok_interp_core::Ctx<'a, crate::front::MazatrolPart>;
}

pub use compensate::CompState;
pub use front::{Mazatrol, MazatrolParams, MazatrolPart};
pub use tlo::LengthOffset;
pub use ttpc::{MazatrolState, TtpcMode};
