//! `stanok cutting turn`: the command-line arguments to a `stanok_cutting::TurningInput`, the
//! calculation, and its output as text or JSON.

use crate::cli_cutting::{MaterialArg, OperationArg, PassArg, TurnArgs};
use stanok_cutting::{
    calculate, DepthInput, Operation, PassKind, Tables, TurningInput, WorkMaterial,
};
use std::process::ExitCode;

/// The material with the strength value it needs (σ_B for steels, HB for irons).
fn material(args: &TurnArgs) -> Result<WorkMaterial, String> {
    let sigma = || {
        args.sigma_b
            .ok_or_else(|| "a steel needs --sigma-b (ultimate strength, MPa)".to_string())
    };
    let hb = || {
        args.hb
            .ok_or_else(|| "a cast iron needs --hb (Brinell hardness)".to_string())
    };
    Ok(match args.material {
        MaterialArg::CarbonSteel => WorkMaterial::CarbonSteel {
            sigma_b_mpa: sigma()?,
        },
        MaterialArg::HighCarbonSteel => WorkMaterial::HighCarbonSteel {
            sigma_b_mpa: sigma()?,
        },
        MaterialArg::FreeMachiningSteel => WorkMaterial::FreeMachiningSteel {
            sigma_b_mpa: sigma()?,
        },
        MaterialArg::CrNiSteel => WorkMaterial::CrNiSteel {
            sigma_b_mpa: sigma()?,
        },
        MaterialArg::GreyIron => WorkMaterial::GreyIron { hb: hb()? },
        MaterialArg::MalleableIron => WorkMaterial::MalleableIron { hb: hb()? },
    })
}

fn input(args: &TurnArgs) -> Result<TurningInput, String> {
    let depth = match (args.depth, args.allowance) {
        (Some(t), _) => DepthInput::Pass {
            t_mm: t,
            pass: match args.pass {
                PassArg::Rough => PassKind::Rough,
                PassArg::Finish => PassKind::Finish,
            },
        },
        (None, Some(a)) => DepthInput::Allowance {
            allowance_mm: a,
            split: args.split.clone(),
        },
        (None, None) => return Err("give --depth or --allowance".into()),
    };
    Ok(TurningInput {
        material: material(args)?,
        surface: args.surface.clone(),
        surface_factor: args.surface_factor,
        tool: args.tool_material.clone(),
        operation: match args.operation {
            OperationArg::Longitudinal => Operation::Longitudinal,
            OperationArg::Facing => Operation::Facing,
            OperationArg::Boring => Operation::Boring,
            OperationArg::PartingOff => Operation::PartingOff,
            OperationArg::Grooving => Operation::Grooving,
            OperationArg::FormTurning => Operation::FormTurning,
            OperationArg::Threading => Operation::Threading,
        },
        diameter_mm: args.diameter,
        depth,
        feed_mm_rev: args.feed,
        finish_feed_mm_rev: args.finish_feed,
        roughness: args.roughness.clone(),
        nose_radius_mm: args.nose_radius,
        tool_life_min: args.life,
        centre_height_mm: args.centre_height,
        machine_feeds: args.machine_feeds.clone(),
        machine_speeds: args.machine_speeds.clone(),
    })
}

/// Runs the calculation; exit 0 with the report, 1 when the document's data cannot give an answer
/// (the reason on stderr), 2 for unusable arguments.
pub fn turn(args: &TurnArgs) -> Result<ExitCode, String> {
    let input = match input(args) {
        Ok(i) => i,
        Err(why) => {
            eprintln!("error: {why}");
            return Ok(ExitCode::from(2));
        }
    };
    match calculate(&Tables::lab(), &input) {
        Ok(c) => {
            let out = if args.json {
                serde_json::to_string_pretty(&c).map_err(|e| e.to_string())? + "\n"
            } else {
                stanok_cutting::text(&c)
            };
            crate::write_stdout(&out)?;
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => {
            eprintln!("error: {e}");
            Ok(ExitCode::from(1))
        }
    }
}
