//! The machine-data reader (TOML): any text gives a machine or a located diagnostic; a machine it
//! accepts writes back to TOML that reads again.
#![no_main]
use libfuzzer_sys::fuzz_target;
use stanok_machine::MachineData;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(m) = MachineData::from_toml_str(text, "fuzz.toml") {
        let _ = m.to_toml();
        let _ = m.tcp_kinematics();
    }
});
