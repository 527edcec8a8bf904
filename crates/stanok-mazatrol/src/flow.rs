//! Where the program goes next (`docs/dialects/mazatrol-eia.md` §2.2, §14, §15.5): the programs
//! of a file and their `O` lines, sequence numbers, WHILE/DO/END loops, and the stack of
//! subprogram and macro calls.
//!
//! The program is streamed: nothing is held in memory but positions. A search for `O p`, `N n` or
//! `END m` reads lines forward from a known position (the core's `Source`, the reader seeks back),
//! and what it finds is cached (bounded: [`MAX_CACHED`]), so a loop that jumps to the same label
//! does not read the program again. *Invariants:* every seek goes to a position a reader gave for
//! the file that is current at that call depth; a call frame records the file depth it returns to;
//! loops belong to a call level and are popped with it; every jump and loop pass counts against the
//! core's `max_blocks`, and loop passes against `max_loop_iterations`, so nothing hangs.

use stanok_canon::Diagnostic;
use stanok_interp_core::{Core, Read};
use stanok_syntax::{Address, Block, MacroKind, SourcePos, Value};
use std::collections::HashMap;
use std::io::{BufRead, Seek};
use std::path::PathBuf;

/// Deepest subprogram nesting (M98) [M].
pub const MAX_SUBPROGRAM_DEPTH: usize = 8;
/// Deepest WHILE … DO nesting per call level [M].
pub const MAX_LOOP_DEPTH: usize = 27;
/// Largest loop identification number [M].
pub const MAX_LOOP_NUMBER: u32 = 127;
/// Most cached label positions.
pub const MAX_CACHED: usize = 100_000;

/// Which file a position belongs to: the program (None) or a subprogram file.
pub type FileKey = Option<PathBuf>;

/// A program found by number.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// The file it is in.
    pub file: FileKey,
    /// Its `O` line.
    pub header: SourcePos,
}

/// What kind of call a frame is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CallKind {
    /// M98.
    Subprogram,
    /// G65 / G66 / G66.1: a new level of local variables.
    Macro,
    /// G70: the blocks ns … nf of the same program, then back to the G70 block's end point.
    Profile {
        /// The line of N nf (the last block run).
        last: u32,
        /// Where the tool returns (program coordinates of the G70 block's start).
        back_to: [f64; 9],
        /// The G70 block (the return belongs to it).
        span: stanok_canon::Span,
        /// Its N label.
        number: Option<u32>,
    },
}

/// One call in progress.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// What it is.
    pub kind: CallKind,
    /// Where the caller continues (the line after the calling block), in the caller's file.
    pub return_to: SourcePos,
    /// The caller's file depth (files opened above the program).
    pub caller_depth: usize,
    /// The caller's program header (for `M99 P n` and GOTO in the caller).
    pub caller_program: Option<SourcePos>,
    /// The caller's file.
    pub caller_file: FileKey,
    /// The called program's first line after its `O` line (for the repeats).
    pub entry: SourcePos,
    /// The called program's header.
    pub program: Option<SourcePos>,
    /// The called program's file.
    pub file: FileKey,
    /// Runs still to do after this one (L − 1 …).
    pub repeats_left: u32,
    /// The loops of the caller, kept while the call runs.
    pub caller_loops: Vec<Loop>,
}

/// One WHILE … DO m / DO m loop in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loop {
    /// m.
    pub label: u32,
    /// The WHILE / DO line.
    pub start: SourcePos,
    /// The line after END m.
    pub after: SourcePos,
    /// Passes so far.
    pub passes: u64,
}

/// The control flow state of a run. Its `Debug` leaves out the two lookup caches (found
/// positions, not state: a failed block may keep what it found).
#[derive(Default)]
pub struct Flow {
    /// The call stack, innermost last.
    pub frames: Vec<Frame>,
    /// The loops of the current call level, innermost last.
    pub loops: Vec<Loop>,
    /// The program being run: its header (None: the file's start), and its file.
    pub program: Option<SourcePos>,
    /// The current program's file.
    pub file: FileKey,
    /// The first `%` was read (the tape has started) or the file has none.
    pub started: bool,
    /// The main program's `O` line was read.
    pub main_header_seen: bool,
    /// Cached positions: (file, program, label kind, key) → position.
    pub(crate) cache: HashMap<(FileKey, Option<u64>, u8, u64), SourcePos>,
    /// The programs of the main file: number → header.
    pub index: Option<HashMap<u32, SourcePos>>,
}

impl std::fmt::Debug for Flow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Flow")
            .field("frames", &self.frames)
            .field("loops", &self.loops)
            .field("program", &self.program)
            .field("file", &self.file)
            .field("started", &self.started)
            .field("main_header_seen", &self.main_header_seen)
            .finish_non_exhaustive()
    }
}

/// Label kinds of the cache.
const N_LABEL: u8 = 0;
const END_LABEL: u8 = 1;

impl Flow {
    /// Macro (G65/G66) levels in progress.
    pub fn macro_depth(&self) -> usize {
        self.frames
            .iter()
            .filter(|f| f.kind == CallKind::Macro)
            .count()
    }

    /// M98 levels in progress.
    pub fn subprogram_depth(&self) -> usize {
        self.frames
            .iter()
            .filter(|f| f.kind == CallKind::Subprogram)
            .count()
    }

    fn cached(&self, kind: u8, n: u64) -> Option<SourcePos> {
        self.cache
            .get(&(self.file.clone(), self.program.map(|p| p.offset), kind, n))
            .copied()
    }

    fn remember(&mut self, kind: u8, n: u64, pos: SourcePos) {
        if self.cache.len() < MAX_CACHED {
            self.cache.insert(
                (self.file.clone(), self.program.map(|p| p.offset), kind, n),
                pos,
            );
        }
    }
}

/// True when the block is a program's `O` line.
pub fn program_number(b: &Block) -> Option<u32> {
    match b.words.first() {
        Some(w) if w.address == Address::Letter(b'O') => match w.value {
            Value::Number(v) => Some(v as u32),
            _ => None,
        },
        _ => None,
    }
}

/// Reads lines from `from` (which is read first) until `pred` holds for one, the current program
/// ends (another `O` line, `%`, the end of the file) or `max` lines were read. Returns the
/// position of the matching line. The reader is left anywhere: the caller seeks. The core's line
/// counter is not advanced by the search.
pub fn scan<R: BufRead + Seek>(
    core: &mut Core<R>,
    from: SourcePos,
    mut pred: impl FnMut(&Block) -> bool,
    skip_first_o: bool,
) -> Result<Option<SourcePos>, Diagnostic> {
    let lines = core.stats.lines_read;
    core.seek(from)?;
    let mut first = true;
    let found = loop {
        let pos = match core.read_line()? {
            Read::Line(p) => p,
            Read::EndOfInput | Read::EndOfFile => break None,
        };
        core.syntax.clear();
        let b = &core.block;
        if b.percent || (program_number(b).is_some() && !(first && skip_first_o)) {
            break None;
        }
        first = false;
        if pred(b) {
            break Some(pos);
        }
    };
    core.stats.lines_read = lines;
    Ok(found)
}

/// The position of the line after `pos` (reads the line at `pos`).
pub fn line_after<R: BufRead + Seek>(
    core: &mut Core<R>,
    pos: SourcePos,
) -> Result<SourcePos, Diagnostic> {
    let lines = core.stats.lines_read;
    core.seek(pos)?;
    core.read_line()?;
    core.syntax.clear();
    core.stats.lines_read = lines;
    Ok(core.source.position())
}

/// Re-reads the line at `pos` into `core.block` (after a search overwrote it); the reader is left
/// after it.
pub fn reread<R: BufRead + Seek>(core: &mut Core<R>, pos: SourcePos) -> Result<(), Diagnostic> {
    let lines = core.stats.lines_read;
    core.seek(pos)?;
    core.read_line()?;
    core.syntax.clear();
    core.stats.lines_read = lines;
    Ok(())
}

/// The programs (`O` lines) of the program file: read once, from its start (the caller seeks
/// back).
pub fn index_programs<R: BufRead + Seek>(
    core: &mut Core<R>,
) -> Result<HashMap<u32, SourcePos>, Diagnostic> {
    let lines = core.stats.lines_read;
    core.seek(SourcePos::start())?;
    let mut index = HashMap::new();
    while let Read::Line(pos) = core.read_line()? {
        core.syntax.clear();
        if let Some(n) = program_number(&core.block) {
            index.entry(n).or_insert(pos);
        }
        if index.len() >= MAX_CACHED {
            break;
        }
    }
    core.stats.lines_read = lines;
    Ok(index)
}

/// The sequence number `n` in the current program: forward from `from` to the program's end,
/// then from the program's start [F]. None when it is not there.
pub fn find_sequence<R: BufRead + Seek>(
    core: &mut Core<R>,
    flow: &mut Flow,
    n: u32,
    from: SourcePos,
) -> Result<Option<SourcePos>, Diagnostic> {
    if let Some(p) = flow.cached(N_LABEL, u64::from(n)) {
        return Ok(Some(p));
    }
    let is_n = |b: &Block| b.number == Some(n);
    let mut found = scan(core, from, is_n, false)?;
    if found.is_none() {
        let start = flow.program.unwrap_or_else(SourcePos::start);
        found = scan(core, start, is_n, true)?;
    }
    if let Some(p) = found {
        flow.remember(N_LABEL, u64::from(n), p);
    }
    Ok(found)
}

/// The line after `END m` of the loop that starts at `start`.
pub fn find_end<R: BufRead + Seek>(
    core: &mut Core<R>,
    flow: &mut Flow,
    label: u32,
    start: SourcePos,
) -> Result<Option<SourcePos>, Diagnostic> {
    let key = (start.offset << 8) | u64::from(label);
    if let Some(p) = flow.cached(END_LABEL, key) {
        return Ok(Some(p));
    }
    let is_end = |b: &Block| matches!(b.statement, Some(s) if matches!(s.kind, MacroKind::End { label: l } if l == label));
    let lines = core.stats.lines_read;
    let found = scan(core, start, is_end, false)?;
    let after = match found {
        Some(p) => Some(line_after(core, p)?),
        None => None,
    };
    core.stats.lines_read = lines;
    if let Some(p) = after {
        flow.remember(END_LABEL, key, p);
    }
    Ok(after)
}
