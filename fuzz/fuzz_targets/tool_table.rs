//! The LinuxCNC tool-table (.tbl) and parameter-file (.var) readers, in mm and in inches.
#![no_main]
use libfuzzer_sys::fuzz_target;
use stanok_canon::LengthUnits;
use stanok_machine::linuxcnc::{parse_tool_table, parse_var_file, write_tool_table};

fuzz_target!(|data: &[u8]| {
    let Some((&head, rest)) = data.split_first() else {
        return;
    };
    let text = String::from_utf8_lossy(rest);
    let units = if head & 1 == 0 {
        LengthUnits::Millimetres
    } else {
        LengthUnits::Inches
    };
    if let Ok(t) = parse_tool_table(&text, "fuzz.tbl", units) {
        let _ = write_tool_table(&t, units);
    }
    let _ = parse_var_file(&text, "fuzz.var", units);
});
