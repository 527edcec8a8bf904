//! The driver's part of the RS274/NGC lathe cycles G70–G72 (`rs274/lathe_cycles.rs` has the
//! cycle itself): calling the profile subroutine and keeping its commands back.
//!
//! ```text
//!  G7x block commits ─▶ start: Flow::call(oQ), capture = { before: queue.len(), depth }
//!  profile blocks    ─▶ executed as usual; their commands stay in the queue behind `before`
//!                       (`held` covers them, so nothing of them leaves the interpreter)
//!  return from oQ    ─▶ finish: drain them, read the profile, put the tool back at S and let
//!                       lathe_cycles::finish emit the cycle in their place
//! ```
//!
//! Invariant: while a capture runs, `before` counts the queue entries that precede it (the
//! iterator decrements it as it releases them), so the profile's commands are exactly
//! `queue[before..]`. A failing `finish` leaves none of them and none of the cycle's.

use crate::rs274::lathe_cycles::{self, LatheCall, Profile};
use crate::{ctx, params, Ctx, Interpreter};
use stanok_canon::{Diagnostic, Span};
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
    comp: crate::rs274::cutter_comp::CutterComp,
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
}

impl<R: BufRead + Seek> Interpreter<R> {
    /// After a committed block: a G7x block left a call, so run its profile subroutine.
    pub(crate) fn start_lathe_capture(&mut self) -> Result<(), Diagnostic> {
        let Some(call) = self.lathe_call.take() else {
            return Ok(());
        };
        if self.lathe.is_some() {
            return Err(Diagnostic::error(
                "rs274::g7x-nested",
                "G7X error: a lathe cycle cannot be used in another cycle's profile",
                self.block.span(),
            ));
        }
        let kept = if self.state.rs274.comp.on() {
            self.held_when_compensating()
        } else {
            0
        };
        let next: SourcePos = self.read_position();
        let action = {
            let eval = params::Evaluator {
                block: &self.block,
                params: &self.params,
                state: &self.state,
            };
            self.flow.call(
                &self.block,
                &eval,
                call.q.to_string(),
                Vec::new(),
                next,
                &self.opts,
            )?
        };
        self.lathe = Some(LatheCapture {
            call,
            before: self.queue.len() - kept,
            kept,
            comp: self.state.rs274.comp,
            position: self.state.position,
            depth: self.flow.depth().saturating_sub(usize::from(matches!(
                action,
                crate::FlowAction::Seek(_) | crate::FlowAction::CallFile { .. }
            ))),
            span: self.block.span(),
            feed: self.state.feed,
            spindle_speed: self.state.spindle_speed,
            css_mm_per_min: self.state.rs274.css_mm_per_min,
            css_law: self.state.rs274.css_law,
        });
        self.state.rs274.in_profile = true;
        self.state.rs274.comp = Default::default();
        match action {
            crate::FlowAction::Seek(pos) => self.seek_to(pos)?,
            crate::FlowAction::CallFile { path, label } => {
                self.open_subroutine_file(&path, &label)?
            }
            _ => {}
        }
        self.apply_flow_params();
        Ok(())
    }

    /// After a return from a subroutine: if it was the profile, emit the cycle.
    pub(crate) fn finish_lathe_capture(&mut self) -> Result<(), Diagnostic> {
        match &self.lathe {
            Some(c) if self.flow.depth() <= c.depth => {}
            _ => return Ok(()),
        }
        let Some(cap) = self.lathe.take() else {
            return Ok(());
        };
        let before = cap.before.min(self.queue.len());
        let from = (before + cap.kept).min(self.queue.len());
        let commands: Vec<_> = self.queue.drain(from..).map(|c| c.value).collect();
        let kept: Vec<_> = self.queue.range(before..).cloned().collect();
        let frame = *self.state.frame;
        let profile = Profile::from_commands(&commands, |p| frame.to_program(p));
        self.state.rs274.in_profile = false;
        self.state.rs274.comp = cap.comp;
        let backup = self.state;
        self.state.feed = cap.feed;
        self.state.spindle_speed = cap.spindle_speed;
        self.state.rs274.css_mm_per_min = cap.css_mm_per_min;
        self.state.rs274.css_law = cap.css_law;
        self.state.position = cap.position;
        let out = ctx::Emitter {
            queue: &mut self.queue,
            span: cap.span,
            // rs274 prints the label of the line it executes when it issues the cycle: the
            // profile's endsub line, not the G7x line.
            number: self.block.number,
            label_digits: 0,
        };
        let mut cx = Ctx {
            block: &self.block,
            words: &mut self.words,
            st: &mut self.state,
            out,
            opts: &self.opts,
            warnings: &mut self.warnings,
            axioma: &mut self.axioma,
            lathe_call: &mut self.lathe_call,
        };
        let whole = ColSpan::new(0, self.block.text.len());
        let result = match profile {
            Ok(p) => lathe_cycles::finish(&mut cx, &cap.call, &p, whole),
            Err(msg) => Err(cx.err("rs274::g7x-profile", msg, whole)),
        };
        if let Err(d) = result {
            self.queue.truncate(before);
            self.queue.extend(kept);
            self.state = backup;
            return Err(d);
        }
        Ok(())
    }
}
