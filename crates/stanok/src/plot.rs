//! `stanok plot`: the tool path as a picture, in memory bounded by the picture.
//!
//! The program is interpreted twice (`stanok_plot`'s two passes): first for the extent of the path,
//! then to draw it; nothing of the stream is kept between commands. A program that uses cutter
//! radius compensation gets its programmed contour drawn under the path: a second interpreter runs
//! the same program with every tool radius 0, in step with the first, and its moves are drawn if
//! they differ from the compensated ones. On a 5-axis machine, moves under tool-centre-point
//! control get tool-axis ticks (`tool_axis.rs`).
//!
//! The picture's format comes from the output's extension: `.svg`, `.png` (rendered by resvg), or
//! `-` for SVG on standard output; without `-o`, the program's name with `.svg`. Lathes (a
//! transverse axis and no Y) and the lathe dialects get the lathe's ZX view. `--color speed|limit`
//! runs the program on the machine once more and colours each line by its mean speed or by the
//! limit that set its speed (`plot_colour.rs`).

use crate::cli::{PlotColor, ViewArg};
use crate::cli_args::{MachineArgs, ProgramArgs};
use crate::source::Program;
use crate::tool_axis::Ticks;
use crate::{diagnostics, program, write_stdout_bytes};
use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::Interpreter;
use stanok_machine::MachineData;
use stanok_plot::{Extent, PlotOptions, Sheet, ViewChoice};
use stanok_syntax::Dialect;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// What to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Svg,
    Png,
}

/// Where the picture goes and in which format; the error is for the user.
fn destination(
    output: Option<&Path>,
    program: &Program,
) -> Result<(Option<PathBuf>, Format), String> {
    let path = match output {
        Some(p) if p.as_os_str() == "-" => return Ok((None, Format::Svg)),
        Some(p) => p.to_path_buf(),
        None => {
            let stem = program
                .path
                .as_ref()
                .and_then(|p| p.file_stem())
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "plot".into());
            PathBuf::from(format!("{stem}.svg"))
        }
    };
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("svg") => Ok((Some(path), Format::Svg)),
        Some("png") => Ok((Some(path), Format::Png)),
        _ => Err(format!(
            "{}: the picture format comes from the extension: .svg or .png (or -o - for SVG on standard output)",
            path.display()
        )),
    }
}

/// The same machine with every tool radius 0: its run is the programmed contour.
fn without_radii(machine: &MachineData) -> Option<MachineData> {
    let mut zero = machine.clone();
    let mut any = false;
    for tool in zero.control.tools.tools.values_mut() {
        for edge in &mut tool.edges {
            any |= edge.radius != 0.0 || edge.radius_wear != 0.0;
            edge.radius = 0.0;
            edge.radius_wear = 0.0;
        }
    }
    any.then_some(zero)
}

/// The next motion command of a stream (None at its end or error); `each` sees every command.
fn next_motion<R: std::io::BufRead + std::io::Seek>(
    interp: &mut Interpreter<R>,
    mut each: impl FnMut(&Canon),
) -> Option<Canon> {
    for item in interp.by_ref() {
        let cmd = item.ok()?;
        each(&cmd.value);
        if cmd.value.motion().is_some() {
            return Some(cmd.value);
        }
    }
    None
}

/// `stanok plot`.
#[allow(clippy::too_many_arguments)]
pub fn plot(
    file: &Path,
    given: Option<Dialect>,
    output: Option<&Path>,
    view: Option<ViewArg>,
    size: (u32, u32),
    color: Option<PlotColor>,
    machine_args: &MachineArgs,
    args: &ProgramArgs,
) -> Result<ExitCode, String> {
    let machine = match program::load_machine(machine_args, &args.probe_surface) {
        Ok((m, _)) => m,
        Err(code) => return Ok(code),
    };
    let (program, choice) = match program::open(file, given) {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let (path, format) = match destination(output, &program) {
        Ok(d) => d,
        Err(why) => return Ok(program::refuse(why)),
    };
    program::say_dialect(&choice);
    let dialect = choice.dialect;
    let lathe = machine.is_lathe() || matches!(dialect, Dialect::Nc31 | Dialect::P2p32);
    let view = view.map_or(
        if lathe {
            ViewChoice::Lathe
        } else {
            ViewChoice::All
        },
        Into::into,
    );
    let reference_machine = without_radii(&machine);
    let kinematics = machine.five_axis();
    let run =
        |m: &MachineData| program::interpreter(&program, program::options(dialect, m, false, args));

    // Pass 1: the extent, the error if any, and whether the programmed contour differs.
    let mut extent = Extent::new();
    let mut reference_extent = Extent::new();
    let mut failure: Option<Diagnostic> = None;
    let mut differs = false;
    {
        let Ok(mut interp) = run(&machine) else {
            return Ok(program::usage_error());
        };
        let mut reference = match &reference_machine {
            Some(m) => run(m).ok(),
            None => None,
        };
        let mut ticks = Ticks::new(kinematics.as_ref());
        for item in interp.by_ref() {
            let cmd: Spanned<Canon> = match item {
                Ok(c) => c,
                Err(d) => {
                    failure = Some(d);
                    break;
                }
            };
            extent.add(&cmd.value);
            ticks.of(&cmd.value, |a, b| extent.add_tick(a, b));
            if let (Some(r), Some(_)) = (reference.as_mut(), cmd.value.motion()) {
                let theirs = next_motion(r, |c| reference_extent.add_reference(c));
                differs |= theirs.as_ref() != Some(&cmd.value);
            }
        }
        if let Some(r) = reference.as_mut() {
            while next_motion(r, |c| reference_extent.add_reference(c)).is_some() {
                differs = true;
            }
        }
    }
    if differs {
        extent.union(&reference_extent);
    }

    // `--color`: the program run on the machine for its block times (a pass of its own).
    let colouring = match color {
        Some(by) => {
            let Ok(interp) = run(&machine) else {
                return Ok(program::usage_error());
            };
            Some(crate::plot_colour::colouring(interp, &machine, by))
        }
        None => None,
    };

    // Pass 2: the drawing.
    let title = program
        .file_name()
        .unwrap_or_else(|| "standard input".into());
    let options = PlotOptions {
        title,
        width: size.0,
        height: size.1,
        view,
        lathe,
        legend: colouring
            .as_ref()
            .map(|c| c.legend.clone())
            .unwrap_or_default(),
        ..Default::default()
    };
    let mut sheet = Sheet::new(&options, &extent);
    if differs {
        if let Some(m) = &reference_machine {
            let Ok(r) = run(m) else {
                return Ok(program::usage_error());
            };
            for cmd in r.map_while(Result::ok) {
                sheet.draw_reference(&cmd.value);
            }
        }
    }
    let Ok(interp) = run(&machine) else {
        return Ok(program::usage_error());
    };
    let mut ticks = Ticks::new(kinematics.as_ref());
    for cmd in interp.map_while(Result::ok) {
        let colour = colouring
            .as_ref()
            .and_then(|c| c.line_colour.get(&cmd.span.line).copied());
        sheet.draw_styled(&cmd.value, colour);
        ticks.of(&cmd.value, |a, b| sheet.draw_tick(a, b));
    }
    let svg = sheet.finish();
    let bytes = match format {
        Format::Svg => svg.into_bytes(),
        Format::Png => stanok_plot::png::render_png(&svg)?,
    };
    let written = match &path {
        None => {
            write_stdout_bytes(&bytes)?;
            "standard output".to_string()
        }
        Some(p) => {
            if let Err(e) = std::fs::write(p, &bytes) {
                return Ok(program::refuse(format_args!(
                    "cannot write {}: {}",
                    p.display(),
                    crate::source::plain(&e)
                )));
            }
            p.display().to_string()
        }
    };
    if let Some(d) = failure {
        let mut d = d;
        crate::hints::enrich(&mut d, &machine);
        diagnostics::render(&program, &d);
        eprintln!("plotted up to the error: {written}");
        return Ok(program::program_error());
    }
    eprintln!(
        "wrote {written} ({} × {} px)",
        options.width, options.height
    );
    Ok(ExitCode::SUCCESS)
}
