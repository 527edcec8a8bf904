//! The AxiOMA state that is not `Copy` (so it is copied, not journalled, per block): the cutter
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
use super::mtable::{MState, MTable};
use super::splines::SplineState;
use super::technology::default_table;
use stanok_canon::{Canon, Diagnostic, Span, Spanned};
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
    /// The channel's M-function table (spec axioma-2 §4, §5). Default: the generic profile.
    pub m_table: MTable,
    /// Channel feed table of `FTABLE(i)`, 128 entries, mm/min. Default: the manual's printed
    /// entries (0…3: 2000, 2500, 3000, 3500; 127: 15000), linear in between.
    pub feed_table: Vec<f64>,
    /// Channel spindle table of `STABLE(i)`, 128 entries, rev/min. Default: the printed entries
    /// (0…3: 1000, 1100, 1200, 1500; 127: 50000), linear in between.
    pub speed_table: Vec<f64>,
    /// CSPLINE zone of influence: the points after a knot that determine its derivative. Default 8.
    pub cspline_window: usize,
    /// Channel parameter "feed control": G60 (true) or G64 (false, default) at start-up (§3.4).
    pub start_exact_stop: bool,
    /// Channel parameter "type of acceleration": SOFT (true) or BRISK (false, default) at start-up.
    pub start_soft: bool,
    /// 3D compensation: allow direct rotary axes and angles/vectors to alternate along one
    /// compensated contour, as the corner fragments of §13.5.2–§13.7.3 do although §13.2.3
    /// forbids it (spec A-14). Default false: `axioma::cut3d-ori-method-change`.
    pub cut3d_mixed_orientation: bool,
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
            m_table: MTable::generic(),
            feed_table: default_table([2000.0, 2500.0, 3000.0, 3500.0], 15000.0),
            speed_table: default_table([1000.0, 1100.0, 1200.0, 1500.0], 50000.0),
            cspline_window: 8,
            start_exact_stop: false,
            start_soft: false,
            cut3d_mixed_orientation: false,
        }
    }
}

impl AxiomaMachineParams {
    /// The channel parameters the machine data gives (issue 22 item 8): the channel's maximum
    /// feed (G276 refuses a faster thread), and each `[channel]` key that is present — spindle
    /// encoder, PLC outputs, compensation look-ahead depth, cutting-edge positions by code (codes
    /// past 9 are ignored: the machine data refuses them). Absent values keep the defaults.
    pub fn set_channel<'a>(
        &mut self,
        max_feed: Option<f64>,
        spindle_encoder: Option<bool>,
        plc_outputs: Option<u32>,
        comp_depth: Option<u32>,
        edge_positions: impl IntoIterator<Item = (&'a u32, &'a [f64; 2])>,
    ) {
        self.max_feed = max_feed.or(self.max_feed);
        self.spindle_encoder = spindle_encoder.unwrap_or(self.spindle_encoder);
        self.plc_outputs = plc_outputs.unwrap_or(self.plc_outputs);
        self.comp_depth = comp_depth.map_or(self.comp_depth, |d| d as usize);
        for (&code, &v) in edge_positions {
            if let Some(slot) = self.edge_positions.get_mut(code as usize) {
                *slot = v;
            }
        }
    }

    /// Replaces the table entries the machine data gives (`[feed_table]`, `[speed_table]`:
    /// index 0…127 → value); the others keep their defaults. Indices past the table are ignored
    /// (the machine data refuses them).
    pub fn set_table_entries<'a>(
        &mut self,
        feed: impl IntoIterator<Item = (&'a u32, &'a f64)>,
        speed: impl IntoIterator<Item = (&'a u32, &'a f64)>,
    ) {
        for (table, entries) in [
            (&mut self.feed_table, feed.into_iter().collect::<Vec<_>>()),
            (&mut self.speed_table, speed.into_iter().collect()),
        ] {
            for (&i, &v) in entries {
                if let Some(slot) = table.get_mut(i as usize) {
                    *slot = v;
                }
            }
        }
    }
}

/// Compensation, cycle and release state of one AxiOMA run.
#[derive(Debug, Clone, Default)]
pub struct Extension {
    /// Cutter radius compensation (G40/G41/G42/G143/G144).
    pub comp: Comp,
    /// 3D tool radius compensation (CUT3D*, G41/G42/G40 under a 3D mode).
    pub comp3d: super::comp3d::Comp3d,
    /// Commands released from `held` so far (slot base).
    pub held_base: u64,
    /// The M vector and the states behind the M functions.
    pub m: MState,
    /// ASPLINE/CSPLINE/BSPLINE mode and the spline points not yet emitted.
    pub spline: SplineState,
    /// Where the last released motion ended (machine coordinates).
    pub released_end: Option<stanok_canon::Pose>,
    /// TRAORI and the orientation modes (spec axioma-4).
    pub ori: super::orientation::OriState,
}

/// Every released straight move starts where the previous motion ended. The compensation
/// engine's own tool bookkeeping can lag behind moves that bypass it (a Z plunge after a G143
/// contour was switched off), and the machine moves from where it is: the stream must say so.
/// Arcs are left as computed (their centre fixes their start).
fn chain(prev: &mut Option<stanok_canon::Pose>, c: &mut Spanned<Canon>) {
    // Tool-centre-point control changes what a position means: the next move states its own start.
    if let Canon::SetToolCentrePoint { .. } = c.value {
        *prev = None;
        return;
    }
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
    /// End of the program (M02/M30 or the end of the text): the spline pieces still in the
    /// contour go to 3D compensation, whose look-ahead then ends its path.
    pub fn comp3d_finish(&mut self, warnings: &mut Vec<Diagnostic>) -> Result<(), Diagnostic> {
        // The end of the text has no block: the warning names the last compensated block.
        let span = self.comp3d.last_span;
        self.comp3d
            .flush_spline_and_end(&mut self.spline, warnings, span)
    }

    /// Moves every held command that no unresolved motion precedes into `queue`, with the
    /// resolved compensated motions inserted at their slots.
    pub fn release(
        &mut self,
        held: &mut VecDeque<Spanned<Canon>>,
        queue: &mut VecDeque<Spanned<Canon>>,
    ) {
        // The first slot a later block may still fill: compensation's or the spline's.
        let unresolved = [
            self.comp.first_unresolved_slot(),
            self.spline.first_unresolved_slot(),
            self.comp3d.first_unresolved_slot(),
        ]
        .into_iter()
        .flatten()
        .min();
        let limit = match unresolved {
            Some(slot) => (slot.saturating_sub(self.held_base) as usize).min(held.len()),
            None => held.len(),
        };
        let mut resolved = self.comp.take_ready();
        resolved.extend(self.spline.take_ready());
        resolved.extend(self.comp3d.take_ready());
        if resolved.is_empty() {
            // Nothing to insert (a block without compensation or splines): the released part
            // moves as it is, without the per-command merge below, whose `Peekable` writes a
            // ~290-byte `Option` per command (callgrind, docs/performance.md).
            let from = queue.len();
            queue.extend(held.drain(..limit));
            let mut prev = self.released_end;
            for c in queue.range_mut(from..) {
                chain(&mut prev, c);
            }
            self.released_end = prev;
            self.held_base += limit as u64;
            return;
        }
        // Stable: motions of one slot keep their order (compensation and splines never share
        // a slot: a spline is refused under compensation).
        resolved.sort_by_key(|(slot, _)| *slot);
        let mut ready = resolved.into_iter().peekable();
        let mut index = self.held_base;
        let mut prev = self.released_end;
        // Each command is chained where it lands (`back_mut`): moving it straight from the
        // drain into the queue saves a copy of the ~330-byte Spanned<Canon> per command
        // (callgrind).
        for item in held.drain(..limit) {
            while let Some((_, mut c)) = ready.next_if(|(slot, _)| *slot <= index) {
                chain(&mut prev, &mut c);
                queue.push_back(c);
            }
            queue.push_back(item);
            if let Some(last) = queue.back_mut() {
                chain(&mut prev, last);
            }
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
        params: &AxiomaMachineParams,
        held: &mut VecDeque<Spanned<Canon>>,
        queue: &mut VecDeque<Spanned<Canon>>,
        warnings: &mut Vec<Diagnostic>,
        reported_spline: &mut Option<Span>,
    ) -> Result<(), Diagnostic> {
        self.comp.flush_at_end(warnings)?;
        self.spline.finish(params.cspline_window, reported_spline)?;
        self.comp3d_finish(warnings)?;
        self.release(held, queue);
        Ok(())
    }
}
