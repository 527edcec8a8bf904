//! Generator of large test programs for the throughput benchmarks and the memory measurement.
//!
//! The program is valid RS274/NGC (and valid AxiOMA apart from the `%`-free end): groups of four
//! blocks trace a 10 × 10 mm stadium — a feed line, a 180° counter-clockwise arc (centre format),
//! a line back and a 180° radius-format arc — with coordinates shifted by a few µm per group so
//! that numbers differ from block to block, written with 3–4 decimals like CAM output.

use std::fmt::Write;

/// Appends `blocks` motion blocks (a multiple of 4 is used) plus header and `M2`.
pub fn stadium_program(blocks: usize) -> String {
    let mut s = String::with_capacity(blocks * 28 + 64);
    s.push_str("G21 G17 G90 F1200\nG0 X0 Y0 Z1\nG1 Z-1\n");
    for g in 0..blocks.div_ceil(4) {
        let d = (g % 1000) as f64 * 0.001;
        let _ = writeln!(s, "G1 X{:.3} Y{:.4}", 10.0 + d, d);
        let _ = writeln!(s, "G3 X{:.3} Y{:.4} I0 J5", 10.0 + d, 10.0 + d);
        let _ = writeln!(s, "G1 X{:.3} Y{:.4}", d, 10.0 + d);
        let _ = writeln!(s, "G3 X{:.3} Y{:.4} R5.0", d, d + 0.001);
    }
    s.push_str("M2\n");
    s
}
