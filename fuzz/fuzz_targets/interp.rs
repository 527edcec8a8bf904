//! The interpreter of every dialect, in `run`/`canon` mode (stop at the first error) and in
//! `check` mode (go on after errors), with the Canon stream printed as `stanok canon` prints it.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((dialect, check, _, program)) = stanok_fuzz::split(data) else {
        return;
    };
    let (commands, _) = stanok_fuzz::interpret(dialect, check, program);
    let mut printer = stanok_canon::linuxcnc::LinuxCncPrinter::new();
    for c in &commands {
        let _ = printer.print(c);
        let _ = serde_json::to_string(c);
    }
    let _ = printer.finish();
});
