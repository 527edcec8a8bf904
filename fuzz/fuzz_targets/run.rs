//! `stanok run` and `stanok plot`: the Canon stream on the simulated mill (with a low bound on
//! simulated time) and drawn.
#![no_main]
use libfuzzer_sys::fuzz_target;
use stanok_machine::{MachineData, SimMachine, SimOptions};

fuzz_target!(|data: &[u8]| {
    let Some((dialect, _, _, program)) = stanok_fuzz::split(data) else {
        return;
    };
    let (commands, _) = stanok_fuzz::interpret(dialect, false, program);
    let options = SimOptions {
        max_machine_time_s: 600.0,
        ..SimOptions::default()
    };
    let mut sim = SimMachine::with_options(MachineData::default_mill(), options);
    for c in &commands {
        if sim.apply(c).is_err() {
            break;
        }
    }
    let _ = sim.finish();
    let _ = stanok_plot::render_svg(&commands, &stanok_plot::PlotOptions::default());
});
