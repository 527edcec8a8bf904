//! What a caller may ask the interpreter between commands: warnings, the modal state, counters,
//! the control's tables, and what only one front end has (parameters, HLL variables, the AxiOMA
//! M vector and probe latch, the lab state).

use crate::{
    AxiomaChain, AxiomaModes, HVal, Interpreter, LabState, ModalState, Parameters, ProbeLatch, Run,
    Stats,
};
use stanok_canon::setup::ControlData;
use stanok_canon::Diagnostic;
use std::io::{BufRead, Seek};

impl<R: BufRead + Seek> Interpreter<R> {
    /// Warnings so far (they never stop the run).
    pub fn warnings(&self) -> &[Diagnostic] {
        &self.run.core().warnings
    }

    /// Takes the warnings collected so far.
    pub fn take_warnings(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.run.core_mut().warnings)
    }

    /// The common modal state after the commands produced so far.
    pub fn state(&self) -> &ModalState {
        &self.run.core().state
    }

    /// Counters.
    pub fn stats(&self) -> Stats {
        self.run.core().stats
    }

    /// RS274/NGC: parameter storage, e.g. to preset work offsets before a run. None for the
    /// other dialects.
    pub fn parameters_mut(&mut self) -> Option<&mut Parameters> {
        match &mut self.run {
            Run::Rs274(d) => Some(d.front_end_mut().parameters_mut()),
            _ => None,
        }
    }

    /// RS274/NGC: parameters and tool table as the blocks run so far left them.
    pub fn parameters(&self) -> Option<&Parameters> {
        match &self.run {
            Run::Rs274(d) => Some(d.front_end().parameters()),
            _ => None,
        }
    }

    /// The stored control data as the run left it. RS274/NGC: what LinuxCNC writes back to its
    /// `.var` file and tool table when it exits — the options' data with the offsets, G28/G30
    /// positions, G92, active system, tool table and preset parameters updated. AxiOMA:
    /// `$iPerm`/`$dPerm` and the tables `settable_zs`/`settable_wcs` wrote. The others write no
    /// control data: the options' data.
    pub fn control_data(&self) -> ControlData {
        let control = &self.run.core().opts.control;
        match &self.run {
            Run::Rs274(d) => d.front_end().parameters().to_control(control),
            _ => control.clone(),
        }
    }

    /// AxiOMA: the value of a high-level-language variable (a scalar) visible now.
    pub fn hll_variable(&self, name: &str) -> Option<HVal> {
        match &self.run {
            Run::Axioma(d) => d.front_end().hll_variable(name),
            _ => None,
        }
    }

    /// AxiOMA: the M vector ("active functions" screen) after the blocks run so far: each modal
    /// M group's name and the function it shows (spec axioma-2 §4.1, §5). Empty for the others.
    pub fn axioma_m_vector(&self) -> Vec<(String, u32)> {
        match &self.run {
            Run::Axioma(d) => d.front_end().m_vector(),
            _ => Vec::new(),
        }
    }

    /// AxiOMA: the result of the last G75 (or batch-mode) probe move: the latched machine
    /// position and whether the probe tripped (spec axioma-2 §2.5).
    pub fn axioma_probe_latch(&self) -> Option<ProbeLatch> {
        match &self.run {
            Run::Axioma(d) => d.front_end().probe_latch(),
            _ => None,
        }
    }

    /// AxiOMA: the chain of frames (shift, rotation, scale, mirror, zero offsets) as the blocks
    /// run so far left it.
    pub fn axioma_chain(&self) -> Option<&AxiomaChain> {
        match &self.run {
            Run::Axioma(d) => Some(d.front_end().chain()),
            _ => None,
        }
    }

    /// AxiOMA: its own modes (polar, tool length compensation, edges, G28/G29, diameter axes).
    pub fn axioma_modes(&self) -> Option<&AxiomaModes> {
        match &self.run {
            Run::Axioma(d) => Some(d.front_end().modes()),
            _ => None,
        }
    }

    /// Runs the next unit (block) and releases nothing: Ok(true) when the program is over. For
    /// tests that look at the state between blocks, with [`Interpreter::state_dump`].
    #[doc(hidden)]
    pub fn step_unit(&mut self) -> Result<bool, Diagnostic> {
        self.run.step_unit()
    }

    /// Everything a block may change, printed: the common modal state, the commands not yet
    /// released (queue and staging), the stored control data, and the front end's own state.
    /// Not the read position, the counters or the warnings. For the transaction test.
    #[doc(hidden)]
    pub fn state_dump(&self) -> String {
        let core = self.run.core();
        format!(
            "state {:#?}\nqueue {:#?}\nstaging {:#?}\ncontrol {:#?}\nfront end {}",
            core.state,
            core.queue,
            core.staging,
            core.opts.control,
            self.run.front_end_state()
        )
    }

    /// Lab dialects (NC-31, 2P32, MC2101, GOST-20999): their modal state after the commands
    /// produced so far. None for the others.
    pub fn lab_state(&self) -> Option<&LabState> {
        match &self.run {
            Run::Labs(d) => Some(d.front_end().state()),
            _ => None,
        }
    }
}
