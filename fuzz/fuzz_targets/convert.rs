//! `stanok convert`: the Canon stream of any dialect written as RS274/NGC or AxiOMA (byte 1).
#![no_main]
use libfuzzer_sys::fuzz_target;
use stanok_convert::{ConvertOptions, Converter, Target};

fuzz_target!(|data: &[u8]| {
    let Some((dialect, _, target, program)) = stanok_fuzz::split(data) else {
        return;
    };
    let (commands, _) = stanok_fuzz::interpret(dialect, false, program);
    let target = if target & 1 == 0 {
        Target::Rs274ngc
    } else {
        Target::Axioma
    };
    let mut converter = Converter::new(ConvertOptions::new(target, "fuzz", dialect.id()));
    for c in &commands {
        converter.push(c);
        let _ = converter.take_text();
    }
    converter.finish();
    let _ = converter.take_text();
});
