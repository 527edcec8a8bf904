//! Writes a generated program of N blocks to stdout (for the memory measurements in docs/performance.md):
//! `cargo run --release -p stanok-interp --example gen_program -- 10000000 > big.ngc`

#[path = "../benches/program_gen.rs"]
mod program_gen;

use std::io::Write;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    // Generate in chunks so that the generator itself stays small in memory.
    let out = std::io::stdout();
    let mut out = std::io::BufWriter::new(out.lock());
    let chunk = 100_000;
    let text = program_gen::stadium_program(chunk);
    let body: Vec<&str> = text.lines().collect();
    let (header, rest) = body.split_at(3);
    let motions = &rest[..rest.len() - 1];
    for l in header {
        let _ = writeln!(out, "{l}");
    }
    let mut written = 0;
    while written < n {
        for l in motions.iter().take(n - written) {
            let _ = writeln!(out, "{l}");
        }
        written += motions.len().min(n - written);
    }
    let _ = writeln!(out, "M2");
}
