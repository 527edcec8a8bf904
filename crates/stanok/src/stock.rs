//! `--stock`: the stock-removal simulation on the command line (`run`, `plot`).
//!
//! The options build a [`StockSim`] from the machine data (tools, kinematics, `[stock]`) and
//! hand it to the simulated machine; after the run, `--stock-out` writes the final stock as STL
//! and `plot --stock` draws it (`stanok_stock::render`). The report's stock section is [`text`].

use clap::Args;
use stanok_machine::{MachineData, SimMachine};
use stanok_stock::report::StockReport;
use stanok_stock::sim::{StockConfig, StockSim};
use stanok_stock::spec::{StockFrame, StockShape};
use stanok_syntax::Dialect;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The stock options of `run` and `plot`.
#[derive(Debug, Clone, Args, Default)]
pub struct StockArgs {
    /// Simulate the material the program removes, from this stock:
    /// `box:X0,Y0,Z-30:X100,Y80,Z0` (two corners), `cylinder:Z-80:D50,Z0` (axis along Z through
    /// X0 Y0, or `cylinder:X10,Y20,Z-80:D50,Z0,B20`; a lathe's bar), or a closed `part.stl`.
    /// In work coordinates unless --stock-frame machine. Without it, the machine data's [stock].
    #[arg(long, value_name = "STOCK")]
    pub stock: Option<String>,
    /// Coordinates of the stock: `work` (the work frame in force at the program's first motion;
    /// default) or `machine`.
    #[arg(long, value_name = "FRAME", value_parser = ["work", "machine"])]
    pub stock_frame: Option<String>,
    /// Cell size of the stock model, mm (default 0.1, coarser for stocks over 200 × 200 mm).
    #[arg(long, value_name = "MM")]
    pub stock_resolution: Option<f64>,
    /// Write the stock after the run as a binary STL file (stock frame, mm).
    #[arg(long, value_name = "FILE")]
    pub stock_out: Option<PathBuf>,
}

/// Whether the program runs on a lathe: a machine with a transverse axis, or a lab lathe dialect.
pub fn is_lathe(machine: &MachineData, dialect: Dialect) -> bool {
    machine.axes.iter().any(|a| a.transverse) || matches!(dialect, Dialect::Nc31 | Dialect::P2p32)
}

/// The simulation the options ask for (None: no stock given anywhere).
pub fn build(
    args: &StockArgs,
    machine: &MachineData,
    dialect: Dialect,
) -> Result<Option<StockSim>, String> {
    let section = machine.stock.as_ref();
    let shape = match &args.stock {
        Some(text) => StockShape::parse(text).map_err(|e| format!("--stock: {e}"))?,
        None => match section.and_then(|s| s.shape.clone()) {
            Some(s) => s,
            None if args.stock_out.is_some() => {
                return Err(
                    "--stock-out needs a stock: --stock or the machine's [stock] shape".into(),
                )
            }
            None => return Ok(None),
        },
    };
    let frame = match &args.stock_frame {
        Some(f) => StockFrame::parse(f)?,
        None => section.map_or(StockFrame::Work, |s| s.frame),
    };
    let config = StockConfig {
        shape,
        frame,
        resolution: args
            .stock_resolution
            .or_else(|| section.and_then(|s| s.resolution)),
        tools: machine.control.tools.clone(),
        kinematics: machine.five_axis(),
        lathe: is_lathe(machine, dialect),
        fixture_z: section.and_then(|s| s.fixture_z),
    };
    StockSim::new(config).map(Some)
}

/// After the run: `--stock-out`.
pub fn write_outputs(args: &StockArgs, sim: &SimMachine) -> Result<(), String> {
    let (Some(path), Some(stock)) = (&args.stock_out, sim.stock()) else {
        return Ok(());
    };
    let mesh = stock
        .mesh(1)
        .ok_or("--stock-out: the program has no motion, no stock was made")?;
    mesh.write_stl(path)?;
    eprintln!(
        "wrote {} ({} triangles)",
        path.display(),
        mesh.triangles.len()
    );
    Ok(())
}

/// `plot --stock`: the stock after the run as a PNG of four views, collisions in red.
pub fn write_png(sim: &SimMachine, path: &Path) -> Result<(), String> {
    let stock = sim.stock().ok_or("no stock")?;
    let mesh = stock
        .mesh(1)
        .ok_or("the program has no motion: no stock to draw")?;
    let marks: Vec<[f64; 3]> = stock
        .collisions()
        .iter()
        .map(|c| stock.to_stock(c.position))
        .collect();
    let png = stanok_stock::render::render_png(&mesh, &marks)?;
    std::fs::write(path, png).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// The report's stock section.
pub fn text(r: &StockReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Stock       {} model at {} mm: {:.1} mm³ → {:.1} mm³, removed {:.1} mm³ ({} sweeps, model {:.1} MB)",
        r.model,
        r.resolution_mm,
        r.initial_volume_mm3,
        r.final_volume_mm3,
        r.removed_volume_mm3.total,
        r.sweeps,
        r.model_bytes as f64 / 1e6
    );
    for t in &r.removed_volume_mm3.per_tool {
        let _ = writeln!(
            s,
            "  T{:<4} removed {:.1} mm³ in {:.3} s in material",
            t.tool, t.volume_mm3, t.time_in_material_s
        );
    }
    if r.peak_mrr_mm3_per_min > 0.0 {
        let _ = writeln!(
            s,
            "  peak removal rate {:.0} mm³/min ({} blocks cut)",
            r.peak_mrr_mm3_per_min,
            r.blocks.len()
        );
    }
    if r.collision_count == 0 {
        let _ = writeln!(s, "Collisions  none");
    } else {
        let _ = writeln!(s, "Collisions  {}", r.collision_count);
        for c in r.collisions.iter().take(20) {
            let _ = writeln!(
                s,
                "  line {:>5}  {:<17} t = {:.3} s  T{}  at X{:.3} Y{:.3} Z{:.3}  depth {:.3} mm",
                c.line,
                c.kind.name(),
                c.time_s,
                c.tool,
                c.position[0],
                c.position[1],
                c.position[2],
                c.depth_mm
            );
        }
        if r.collisions.len() > 20 {
            let _ = writeln!(
                s,
                "  … {} more (run --json lists them)",
                r.collisions.len() - 20
            );
        }
    }
    for n in &r.notes {
        let _ = writeln!(s, "  note: {n}");
    }
    s
}
