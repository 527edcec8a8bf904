//! What a caller may ask the interpreter between commands: warnings, the modal state, parameters,
//! the control's tables, HLL variables, the AxiOMA M vector and probe latch, counters.

use crate::{HVal, Interpreter, ModalState, Parameters, ProbeLatch, Stats};
use stanok_canon::setup::ControlData;
use stanok_canon::Diagnostic;
use stanok_syntax::Dialect;
use std::io::{BufRead, Seek};

impl<R: BufRead + Seek> Interpreter<R> {
    /// Warnings so far (they never stop the run).
    pub fn warnings(&self) -> &[Diagnostic] {
        &self.warnings
    }

    /// Takes the warnings collected so far.
    pub fn take_warnings(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.warnings)
    }

    /// The modal state after the commands produced so far.
    pub fn state(&self) -> &ModalState {
        &self.state
    }

    /// Starts in `state` instead of the power-on state: an operator's MDI session, where each
    /// block is a new interpreter that continues in the modes the previous block left (with
    /// `state.position` set to where the machine stands now, after any jog). Call it before the
    /// first command; the lab dialects keep their own state and ignore it.
    pub fn resume_modal_state(&mut self, state: ModalState) {
        self.state = state;
    }

    /// Parameter storage (RS274/NGC), e.g. to preset work offsets before a run.
    pub fn parameters_mut(&mut self) -> &mut Parameters {
        &mut self.params
    }

    /// Parameters and tool table as the blocks run so far left them (RS274/NGC).
    pub fn parameters(&self) -> &Parameters {
        &self.params
    }

    /// The stored control data as the run left it (RS274/NGC): what LinuxCNC writes back to its
    /// `.var` file and tool table when it exits — the options' data with the offsets, G28/G30
    /// positions, G92, active system, tool table and preset parameters updated.
    pub fn control_data(&self) -> ControlData {
        match self.opts.dialect {
            // AxiOMA: `$iPerm`/`$dPerm` and the tables `settable_zs`/`settable_wcs` wrote.
            Dialect::Axioma => self.opts.control.clone(),
            // RS274/NGC (and the lab dialects, as main has them): the numbered parameters.
            _ => self.params.to_control(&self.opts.control),
        }
    }

    /// AxiOMA: the value of a high-level-language variable (a scalar) visible now.
    pub fn hll_variable(&self, name: &str) -> Option<HVal> {
        self.hll.as_deref()?.vars.get(name).cloned()
    }

    /// AxiOMA: the M vector ("active functions" screen) after the blocks run so far: each modal
    /// M group's name and the function it shows (spec axioma-2 §4.1, §5).
    pub fn axioma_m_vector(&self) -> Vec<(String, u32)> {
        self.axioma.m.display(&self.opts.axioma.m_table)
    }

    /// AxiOMA: the result of the last G75 (or batch-mode) probe move: the latched machine
    /// position and whether the probe tripped (spec axioma-2 §2.5).
    pub fn axioma_probe_latch(&self) -> Option<ProbeLatch> {
        self.axioma.probe.latch
    }

    /// Counters.
    pub fn stats(&self) -> Stats {
        self.stats
    }
}
