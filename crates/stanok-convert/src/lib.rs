//! Conversion: a `Canon` stream written back as a part program of a target dialect
//! (`stanok convert FILE --to rs274ngc|axioma`).
//!
//! The converter sits after the interpreter, like every other consumer of the boundary: any
//! program Stanok can interpret (AxiOMA, RS274/NGC, later the lab dialects) converts to any
//! target, because the target program is written from what the source program *does* (its
//! canonical commands), not from its text. Cycles, subprograms, loops, parameters, frames and
//! cutter compensation therefore arrive already expanded, and the converted program is a flat
//! list of moves and technology commands.
//!
//! How positions are expressed (the invariant the round-trip tests hold):
//! * Canon positions are machine Cartesian. The converted program writes them **absolute (G90)
//!   in the work frame that was active when the source program started** (`Canon::Init`: its G5x
//!   offset, G92 offset and XY rotation folded out), with no tool length offset (G49) and no
//!   cutter compensation (G40): run from the same start state on the same machine, it moves the
//!   machine along the same path. For AxiOMA the header selects G53 G153 G193 (no offsets at all),
//!   so positions are machine coordinates there. The program header says which.
//! * Feeds are always G94 mm/min (Canon's unit): G95 and G93 sources are folded into the path feed
//!   the source would have had.
//! * Every output line that comes from a source line carries its line number in a comment.
//!
//! What cannot be expressed in the target (an AxiOMA BRISK/SOFT in RS274/NGC, a LinuxCNC digital
//! output in AxiOMA, a spline that is no G5.2 or BSPLINE curve, …) is written as a comment and reported as
//! a [`Warning`]; a curve the target would read as another curve (a spline that is no G5.2 or
//! BSPLINE, an arc about a tilted axis, an arc whose centre AxiOMA would correct) becomes chords
//! within the chord tolerance — never silently dropped.
#![deny(missing_docs)]

mod format;
mod motion;
mod writer;

pub use writer::Converter;

/// The dialect written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// LinuxCNC RS274/NGC.
    Rs274ngc,
    /// AxiOMA Control.
    Axioma,
}

impl Target {
    /// The dialect id (`rs274ngc`, `axioma`).
    pub fn id(self) -> &'static str {
        match self {
            Target::Rs274ngc => "rs274ngc",
            Target::Axioma => "axioma",
        }
    }

    /// The usual file extension of the target (`ngc`, `nc`).
    pub fn extension(self) -> &'static str {
        match self {
            Target::Rs274ngc => "ngc",
            Target::Axioma => "nc",
        }
    }
}

/// What the converter needs to know besides the commands.
#[derive(Debug, Clone)]
pub struct ConvertOptions {
    /// The dialect to write.
    pub target: Target,
    /// The source file's name (for the header).
    pub source_name: String,
    /// The source dialect's id (for the header).
    pub source_dialect: String,
    /// Largest deviation of the chords written for curves the target cannot express, mm.
    pub chord_tolerance_mm: f64,
    /// The machine's maximum feed, mm/min: written for a feed move the source gives no feed
    /// (feed 0, which the machine runs at this feed). Default 5000, the built-in mill's.
    pub max_feed_mm_per_min: f64,
    /// The target machine's configured axes (X Y Z A B C U V W): X, Y and Z are written in every
    /// move only where configured (a lathe's X Z; an unconfigured axis word is an error there),
    /// the others when they move. Default X Y Z.
    pub axes: [bool; 9],
}

impl ConvertOptions {
    /// Options with the default chord tolerance of 1 µm.
    pub fn new(target: Target, source_name: &str, source_dialect: &str) -> Self {
        ConvertOptions {
            target,
            source_name: source_name.into(),
            source_dialect: source_dialect.into(),
            chord_tolerance_mm: 0.001,
            max_feed_mm_per_min: 5000.0,
            axes: [true, true, true, false, false, false, false, false, false],
        }
    }
}

/// Something the target cannot express exactly: written as a comment, reported here.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// Source line of the command (0 = none).
    pub line: u32,
    /// What was done instead.
    pub message: String,
}

/// Converts a whole stream: the program text and the warnings.
pub fn convert(
    commands: &[stanok_canon::Spanned<stanok_canon::Canon>],
    options: ConvertOptions,
) -> (String, Vec<Warning>) {
    let mut c = Converter::new(options);
    for cmd in commands {
        c.push(cmd);
    }
    c.finish();
    let text = c.take_text();
    (text, c.warnings().to_vec())
}
