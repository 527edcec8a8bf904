//! Writes the stock-simulation benchmark programs of docs/performance.md into a directory:
//!
//! * `finishing.ngc` — a 3-axis raster finish (RS274/NGC) of `z = −8 + 3·sin(x/9)·cos(y/13)` over a
//!   100 × 100 mm stock with a Ø6 ball, 0.1 mm steps and 0.1 mm stepover: 1 001 000 blocks;
//!   `finishing-tools.toml` its tool.
//! * `five-axis.nc` — a 5-axis finish (AxiOMA TRAORI, `5axis-bc-head`) of
//!   `z = −5 + 2·sin(x/8)·cos(y/11)` over 50 × 50 mm with the tool leaning `B = 15·sin(x/10)`°,
//!   0.5 mm steps, 0.05 mm stepover: 100 100 blocks; `five-axis-tools.toml` its tool (L 100).
//!
//! `cargo run --release -p stanok-stock --example stock_programs -- DIR [SCALE]`; SCALE (default 1)
//! divides the number of passes, for quick runs.

use std::fmt::Write as _;
use std::io::Write as _;

fn main() -> std::io::Result<()> {
    let mut args = std::env::args().skip(1);
    let dir = std::path::PathBuf::from(args.next().unwrap_or_else(|| ".".into()));
    let scale: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(1).max(1);
    std::fs::create_dir_all(&dir)?;

    // 3-axis: 1001 passes along X (alternating), 1000 steps each.
    let z = |x: f64, y: f64| -8.0 + 3.0 * (x / 9.0).sin() * (y / 13.0).cos();
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join("finishing.ngc"))?);
    writeln!(f, "(raster finish: Ø6 ball, 0.1 mm steps and stepover)")?;
    writeln!(
        f,
        "G21 G90 G17 G54 G64 P0.01\nT1 M6\nS12000 M3\nG0 X0 Y0 Z10"
    )?;
    writeln!(f, "G1 Z{:.4} F3000", z(0.0, 0.0))?;
    let passes = 1001 / scale;
    for j in 0..passes {
        let y = j as f64 * 0.1 * scale as f64;
        let mut line = String::new();
        for k in 0..=1000 {
            let i = if j % 2 == 0 { k } else { 1000 - k };
            let x = i as f64 * 0.1;
            if k == 0 && j == 0 {
                continue;
            }
            line.clear();
            let _ = write!(line, "X{x:.3} Y{y:.3} Z{:.4}", z(x, y));
            writeln!(f, "{line}")?;
        }
    }
    writeln!(f, "G0 Z10\nM5\nM30")?;
    std::fs::write(
        dir.join("finishing-tools.toml"),
        "[[tool]]\nnumber = 1\ncutter = \"ball\"\nflute_length = 25.0\nreach = 40.0\n\
         holder = [{ diameter = 20.0, length = 40.0 }]\n[[tool.edge]]\nradius = 3.0\n",
    )?;

    // 5-axis: 1001 passes along X, 100 blocks of 0.5 mm each.
    let z5 = |x: f64, y: f64| -5.0 + 2.0 * (x / 8.0).sin() * (y / 11.0).cos();
    let b5 = |x: f64| 15.0 * (x / 10.0).sin();
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join("five-axis.nc"))?);
    writeln!(
        f,
        "G17 G90 G15 G191 G71 G72 G172 G272 G94 G97 G49 G40 G00 G80 G98\n\
         G53 G153 G193 G64 BRISK CUT2DF ORIAXES\nT2 M6\nG43\nS12000 M3\nG00 Z150\nTRAORI\n\
         G00 X0 Y0 Z10 B0\nG01 Z{:.4} F2000",
        z5(0.0, 0.0)
    )?;
    let passes = 1001 / scale;
    for j in 0..passes {
        let y = j as f64 * 0.05 * scale as f64;
        for k in 0..=100 {
            let i = if j % 2 == 0 { k } else { 100 - k };
            let x = i as f64 * 0.5;
            if k == 0 && j == 0 {
                continue;
            }
            writeln!(f, "X{x:.3} Y{y:.3} Z{:.4} B{:.4}", z5(x, y), b5(x))?;
        }
    }
    writeln!(f, "G00 Z50\nTRAFOOF\nM30")?;
    std::fs::write(
        dir.join("five-axis-tools.toml"),
        "[[tool]]\nnumber = 2\ncutter = \"ball\"\nflute_length = 25.0\nreach = 40.0\n\
         holder = [{ diameter = 20.0, length = 40.0 }]\n[[tool.edge]]\nlength = [100.0]\nradius = 3.0\n",
    )?;
    Ok(())
}
