//! The front end's part of the RS274/NGC lathe cycles G70–G72 outside a block (`lathe_cycles.rs`
//! has the cycle itself): calling the profile subroutine and keeping its commands back.
//!
//! ```text
//!  G7x block commits ─▶ start: Flow::call(oQ), capture = { before: queue.len(), depth }
//!  profile blocks    ─▶ executed as usual; their commands stay in the queue behind `before`
//!                       (`held` covers them, so nothing of them leaves the interpreter)
//!  return from oQ    ─▶ finish: drain them, read the profile, put the tool back at S, undo
//!                       what the profile's F, S and M codes set, and let
//!                       lathe_cycles::finish emit the cycle in their place
//! ```
//!
//! LinuxCNC reads a profile's motions, parameters and control flow only; its feed, speed,
//! coolant, spindle and override words never take effect. Stanok executes the blocks (the
//! profile's own positions and parameters need it) and restores that state afterwards.
//!
//! Invariant: while a capture runs, `before` counts the queue entries that precede it (the
//! iterator decrements it as it releases them), so the profile's commands are exactly
//! `queue[before..]`. A failing `finish` leaves none of them and none of the cycle's.

use crate::lathe_cycles::{self, LatheCall};
use crate::{params, Rs274};
use stanok_canon::{Canon, Diagnostic, Span};
use stanok_interp_core::Core;
use stanok_syntax::{ColSpan, SourcePos};
use std::io::{BufRead, Seek};

/// A profile subroutine being executed for a G7x block.
#[derive(Debug, Clone)]
pub(crate) struct LatheCapture {
    call: LatheCall,
    /// Queue entries ahead of the profile's commands (and of `kept`).
    pub(crate) before: usize,
    /// Commands cutter compensation holds back at the G7x block (G70 under G41/G42): they stay
    /// in the queue, between `before` and the profile's commands, for the cycle to edit.
    kept: usize,
    /// Compensation's state at the G7x block: off while the profile runs (its moves are the
    /// programmed profile), back for the cycle.
    comp: crate::cutter_comp::CutterComp,
    /// The tool position at the G7x block (under compensation not S itself).
    position: stanok_canon::Pose,
    /// Call depth at the G7x block; the profile is over when the depth is back to it.
    depth: usize,
    /// The G7x block: the cycle's commands carry its span (and the endsub line's N label).
    span: Span,
    /// Feed and spindle speeds before the profile (F and S in a profile are ignored).
    feed: f64,
    spindle_speed: [f64; 4],
    /// The G96 cutting speed and the law last sent: the profile's commands are dropped, so a
    /// law it "sent" never reached the machine and the state must say so.
    css_mm_per_min: f64,
    css_law: Option<stanok_canon::SurfaceSpeedLaw>,
    /// The M-code state before the profile: LinuxCNC reads a profile's motions and control flow
    /// only, so its M3–M5, M7–M9 and M48–M53 never happened.
    switches: Switches,
}

/// The state the M codes of a profile would change (`LatheCapture::switches`).
#[derive(Debug, Clone, Copy)]
struct Switches {
    mist: bool,
    flood: bool,
    spindle_on: [bool; 4],
    spindle_direction: Option<stanok_canon::SpindleDirection>,
    feed_override_disabled: bool,
    speed_override_disabled: bool,
}

impl Rs274 {
    /// After a committed block: a G7x block left a call, so run its profile subroutine.
    #[cold]
    pub(crate) fn start_lathe_capture<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
    ) -> Result<(), Diagnostic> {
        let Some(call) = self.part.lathe_call.take() else {
            return Ok(());
        };
        if self.lathe.is_some() {
            return Err(Diagnostic::error(
                "rs274::g7x-nested",
                "G7X error: a lathe cycle cannot be used in another cycle's profile",
                core.block.span(),
            ));
        }
        let kept = if self.part.modes.comp.on() {
            self.held_when_compensating(&core.queue, false)
        } else {
            0
        };
        let next: SourcePos = core.source.position();
        let action = {
            let eval = params::Evaluator {
                block: &core.block,
                params: &self.params,
                state: &core.state,
                modes: &self.part.modes,
            };
            self.flow.call(
                &core.block,
                &eval,
                call.q.to_string(),
                Vec::new(),
                next,
                &core.opts,
            )?
        };
        let st = &core.state;
        self.lathe = Some(LatheCapture {
            call,
            before: core.queue.len() - kept,
            kept,
            comp: self.part.modes.comp,
            position: st.position,
            depth: self.flow.depth().saturating_sub(usize::from(matches!(
                action,
                crate::FlowAction::Seek(_) | crate::FlowAction::CallFile { .. }
            ))),
            span: core.block.span(),
            feed: st.feed,
            spindle_speed: st.spindle_speed,
            css_mm_per_min: self.part.modes.css_mm_per_min,
            css_law: self.part.modes.css_law,
            switches: Switches {
                mist: st.mist,
                flood: st.flood,
                spindle_on: st.spindle_on,
                spindle_direction: self.part.modes.spindle_direction,
                feed_override_disabled: self.part.modes.feed_override_disabled,
                speed_override_disabled: self.part.modes.speed_override_disabled,
            },
        });
        self.part.modes.in_profile = true;
        self.part.profile_blocks.clear();
        self.part.modes.comp = Default::default();
        match action {
            crate::FlowAction::Seek(pos) => core.seek(pos)?,
            crate::FlowAction::CallFile { path, label } => {
                self.open_subroutine_file(core, &path, &label)?
            }
            _ => {}
        }
        self.apply_flow_params(core);
        Ok(())
    }

    /// After a return from a subroutine: if it was the profile, emit the cycle.
    pub(crate) fn finish_lathe_capture<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
    ) -> Result<(), Diagnostic> {
        match &self.lathe {
            Some(c) if self.flow.depth() <= c.depth => {}
            _ => return Ok(()),
        }
        let Some(cap) = self.lathe.take() else {
            return Ok(());
        };
        let queue = &mut core.queue;
        let before = cap.before.min(queue.len());
        let from = (before + cap.kept).min(queue.len());
        let commands: Vec<_> = queue.drain(from..).map(|c| c.value).collect();
        let kept: Vec<_> = queue.range(before..).cloned().collect();
        let blocks = std::mem::take(&mut self.part.profile_blocks);
        self.part.modes.in_profile = false;
        self.part.modes.comp = cap.comp;
        let sw = cap.switches;
        core.state.mist = sw.mist;
        core.state.flood = sw.flood;
        core.state.spindle_on = sw.spindle_on;
        self.part.modes.spindle_direction = sw.spindle_direction;
        self.part.modes.feed_override_disabled = sw.feed_override_disabled;
        self.part.modes.speed_override_disabled = sw.speed_override_disabled;
        let backup = (core.state, *self.part.modes);
        core.state.feed = cap.feed;
        core.state.spindle_speed = cap.spindle_speed;
        self.part.modes.css_mm_per_min = cap.css_mm_per_min;
        self.part.modes.css_law = cap.css_law;
        core.state.position = cap.position;
        let whole = ColSpan::new(0, core.block.text.len());
        // rs274 prints the label of the line it executes when it issues the cycle: the
        // profile's endsub line, not the G7x line.
        let number = core.block.number;
        let mut cx = core.parts(cap.span, number).with(&mut self.part);
        let other_motion = commands.iter().any(|c| {
            c.motion().is_some()
                && !matches!(
                    c,
                    Canon::StraightTraverse(_) | Canon::StraightFeed(_) | Canon::ArcFeed(_)
                )
        });
        let result = if other_motion {
            Err(cx.err(
                "rs274::g7x-profile",
                "G7X error: only G0, G1, G2 and G3 may move in a profile",
                whole,
            ))
        } else {
            lathe_cycles::finish(&mut cx, &cap.call, &blocks, &commands, whole)
        };
        if let Err(d) = result {
            core.queue.truncate(before);
            core.queue.extend(kept);
            core.state = backup.0;
            *self.part.modes = backup.1;
            return Err(d);
        }
        Ok(())
    }
}
