//! Calls and returns (`docs/dialects/mazatrol-eia.md` §11.1, §14, §15.7): the targets of M98,
//! M99 P, G65, G66 and G70–G73 found before their block runs, and the calls made after it.

use crate::flow::{self, CallKind, Flow, Frame, Program};
use crate::front::{err, Mazatrol, MazatrolPart, Target};
use crate::macro_b::MVal;
use stanok_canon::{Diagnostic, Span};
use stanok_interp_core::{Core, OpenFile, Read};
use stanok_syntax::{Address, Block, SourcePos, Value};
use std::io::{BufRead, Seek};

/// The raw value of the first word with `letter` (`Ok(None)`: absent or vacant).
fn word<R: BufRead + Seek>(
    part: &MazatrolPart,
    core: &Core<R>,
    letter: u8,
) -> Result<Option<f64>, Diagnostic> {
    for w in &core.block.words {
        if w.address == Address::Letter(letter) {
            return match w.value {
                Value::Number(v) => Ok(Some(v)),
                Value::Expr(e) => part.env(&core.state).value(&core.block, e),
                _ => Ok(None),
            };
        }
    }
    Ok(None)
}

/// True if the block has the G code `code` (× 10) or M code written as a plain number.
pub(crate) fn has_code(b: &Block, letter: u8, code: u32) -> bool {
    b.words.iter().any(|w| {
        w.address == Address::Letter(letter)
            && matches!(w.value, Value::Number(v) if ((if letter == b'G' { v * 10.0 } else { v }).round() as i64) == i64::from(code))
    })
}

/// True if the block may call or return (a cheap look at its words).
pub(crate) fn may_jump(b: &Block) -> bool {
    b.words.iter().any(|w| match (w.address, w.value) {
        (Address::Letter(b'M'), Value::Number(v)) => v == 98.0 || v == 99.0,
        (Address::Letter(b'G'), Value::Number(v)) => {
            (65.0..=66.1).contains(&v) || (70.0..=73.0).contains(&v)
        }
        (Address::Letter(b'M' | b'G'), _) => true,
        _ => false,
    })
}

impl Mazatrol {
    /// Finds the targets of the block's calls and returns before it runs (`docs` §14, §15.7).
    pub(crate) fn prepare<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        pos: SourcePos,
        next_line: SourcePos,
    ) -> Result<(), Diagnostic> {
        let b = &core.block;
        let span = b.span();
        let m98 = has_code(b, b'M', 98);
        let m99 = has_code(b, b'M', 99);
        let g65 = has_code(b, b'G', 650);
        let g66 = has_code(b, b'G', 660) || has_code(b, b'G', 661);
        let g70 = has_code(b, b'G', 700) && self.part.m.t();
        let g7x = self.part.m.t()
            && (has_code(b, b'G', 710) || has_code(b, b'G', 720) || has_code(b, b'G', 730))
            && b.words.iter().any(|w| w.address == Address::Letter(b'P'));
        let level = self.part.vars.level();
        let modal = self
            .part
            .m
            .modal_call
            .filter(|c| !m98 && !g65 && !g66 && c.level == level)
            .map(|c| c.program);
        let mut searched = false;
        if m99 {
            if self.flow.frames.is_empty() {
                return Err(err(
                    "mazatrol::m99-without-caller",
                    "M99 without a caller: this is the main program",
                    span,
                ));
            }
            if let Some(p) = word(&self.part, core, b'P')? {
                let n = p as u32;
                let found = self.find_in_caller(core, n)?;
                searched = true;
                let Some(found) = found else {
                    reread_at(core, pos)?;
                    return Err(err(
                        "mazatrol::sequence-not-found",
                        format!("M99 P{n}: no block N{n} in the calling program"),
                        core.block.span(),
                    ));
                };
                self.part.prepared.ret = Some(found);
            }
        }
        let program = if m98 || g65 || g66 {
            match word(&self.part, core, b'P')? {
                Some(p) if p >= 0.0 && p.fract() == 0.0 => Some(p as u32),
                Some(p) => {
                    return Err(err(
                        "mazatrol::value-range",
                        format!("P{p}: a program number is a whole number"),
                        span,
                    ))
                }
                None => {
                    return Err(err(
                        "mazatrol::missing-word",
                        if m98 {
                            "M98 needs the program number P"
                        } else {
                            "G65/G66 need the program number P"
                        },
                        span,
                    ))
                }
            }
        } else {
            modal
        };
        if let Some(p) = program {
            let h = if m98 {
                word(&self.part, core, b'H')?
            } else {
                None
            };
            let t = self.find_program(core, p, h.map(|h| h as u32), span)?;
            searched = true;
            self.part.prepared.call = Some(t);
        }
        if g70 || g7x {
            let p = word(&self.part, core, b'P')?;
            let q = word(&self.part, core, b'Q')?;
            let (Some(p), Some(q)) = (p, q) else {
                return Err(err(
                    "mazatrol::missing-word",
                    "the cycle needs P (the first) and Q (the last sequence number of the profile)",
                    span,
                ));
            };
            let (ns, nf) = (p as u32, q as u32);
            let Some(first) = flow::find_sequence(core, &mut self.flow, ns, next_line)? else {
                reread_at(core, pos)?;
                return Err(err(
                    "mazatrol::sequence-not-found",
                    format!("P{ns}: no block N{ns} in this program"),
                    core.block.span(),
                ));
            };
            searched = true;
            if g70 {
                self.part.prepared.profile_first = Some(first);
            } else {
                let blocks = self.read_range(core, first, nf)?;
                self.part.prepared.profile_after = Some(core.source.position());
                let profile = self.profile(core, &blocks)?;
                self.part.prepared.profile = Some(profile);
            }
        }
        if searched {
            reread_at(core, pos)?;
        }
        let _ = next_line;
        Ok(())
    }

    /// The blocks N ns … N nf from `first` (at most 10 000).
    pub(crate) fn read_range<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        first: SourcePos,
        last: u32,
    ) -> Result<Vec<Block>, Diagnostic> {
        let lines = core.stats.lines_read;
        core.seek(first)?;
        let mut out = Vec::new();
        while let Read::Line(_) = core.read_line()? {
            if let Some(e) = core.take_syntax(true) {
                core.stats.lines_read = lines;
                return Err(e);
            }
            if core.block.percent || flow::program_number(&core.block).is_some() {
                break;
            }
            let done = core.block.number == Some(last);
            out.push(core.block.clone());
            if done || out.len() > crate::turning::MAX_PASSES {
                core.stats.lines_read = lines;
                if !done {
                    break;
                }
                return Ok(out);
            }
        }
        core.stats.lines_read = lines;
        Err(err(
            "mazatrol::sequence-not-found",
            format!("Q{last}: no block N{last} after the profile's first block"),
            core.block.span(),
        ))
    }

    /// The profile of G71/G72/G73 from its blocks, from the tool's current position.
    pub(crate) fn profile<R: BufRead + Seek>(
        &self,
        core: &Core<R>,
        blocks: &[Block],
    ) -> Result<Vec<crate::turning::Step>, Diagnostic> {
        let st = &core.state;
        let p = st.program_position();
        let a = [p.z, p.x];
        let modes = crate::profile::ProfileModes {
            incremental: st.distance == stanok_interp_core::DistanceMode::Incremental,
            x_diameter: !self.part.m.x_radius,
            motion: match st.motion {
                stanok_interp_core::MotionMode::Linear => 10,
                stanok_interp_core::MotionMode::ArcCw => 20,
                stanok_interp_core::MotionMode::ArcCcw => 30,
                _ => 0,
            },
            arc_tolerance: core.opts.arc_tolerance_mm,
        };
        let env = self.part.env(st);
        let mut value = |b: &Block, w: &stanok_syntax::Word| match w.value {
            Value::Number(v) => Ok(Some(v)),
            Value::Expr(e) => env.value(b, e).map_err(|d| crate::profile::ProfileError {
                message: d.message.clone(),
                span: b.span(),
            }),
            _ => Ok(None),
        };
        crate::profile::read_profile(blocks, a, modes, &mut value)
            .map_err(|e| err("mazatrol::cycle", e.message, e.span))
    }

    /// A program by number: the file's own programs, then the subroutine path (`docs` §14).
    pub(crate) fn find_program<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        p: u32,
        h: Option<u32>,
        at: Span,
    ) -> Result<Target, Diagnostic> {
        // The current file's programs.
        let header = if self.flow.file.is_none() {
            if self.flow.index.is_none() {
                self.flow.index = Some(flow::index_programs(core)?);
            }
            self.flow.index.as_ref().and_then(|i| i.get(&p).copied())
        } else {
            flow::scan(
                core,
                SourcePos::start(),
                |b| flow::program_number(b) == Some(p),
                true,
            )?
        };
        if let Some(header) = header {
            let program = Program {
                file: self.flow.file.clone(),
                header,
            };
            let entry = self.entry(core, &program, p, h, at)?;
            return Ok(Target { program, entry });
        }
        // A file on the subroutine path.
        for dir in core.opts.subroutine_path.clone() {
            for path in crate::rules::subprogram_files(&dir, p) {
                if !path.is_file() {
                    continue;
                }
                let mut reader = core.source.open(&path, at)?;
                let mut block = Block::default();
                let mut diags = Vec::new();
                let mut found = None;
                let mut first = None;
                let mut lines = 0;
                loop {
                    let pos = reader.position();
                    match reader.next_block(&mut block, &mut diags) {
                        Ok(true) => {}
                        _ => break,
                    }
                    lines += 1;
                    if first.is_none() && !block.is_empty() && !block.percent {
                        first = Some(pos);
                    }
                    if flow::program_number(&block) == Some(p) {
                        found = Some(pos);
                        break;
                    }
                    if lines > 1_000_000 {
                        break;
                    }
                }
                // A file holding the program without its O line: it starts at its first block.
                let Some(header) = found.or(first) else {
                    continue;
                };
                let program = Program {
                    file: Some(path.clone()),
                    header,
                };
                let entry = file_entry(&mut reader, header, found.is_some(), h, at)?;
                return Ok(Target { program, entry });
            }
        }
        Err(err(
            "mazatrol::program-not-found",
            format!("program O{p:04} is in neither this file nor --subroutine-path"),
            at,
        ))
    }

    /// Where a call of `program` enters it in the current file: after its O line, or at N h.
    pub(crate) fn entry<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        program: &Program,
        number: u32,
        h: Option<u32>,
        at: Span,
    ) -> Result<SourcePos, Diagnostic> {
        let after = flow::line_after(core, program.header)?;
        let Some(h) = h else {
            return Ok(after);
        };
        match flow::scan(core, after, |b| b.number == Some(h), false)? {
            Some(p) => Ok(p),
            None => Err(err(
                "mazatrol::sequence-not-found",
                format!("H{h}: no block N{h} in program O{number:04}"),
                at,
            )),
        }
    }

    /// N n in the calling program (the caller may be in a file below the current one).
    pub(crate) fn find_in_caller<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        n: u32,
    ) -> Result<Option<SourcePos>, Diagnostic> {
        let Some(frame) = self.flow.frames.last().cloned() else {
            return Ok(None);
        };
        // Lift the files above the caller's, search, put them back.
        let mut lifted: Vec<OpenFile> = Vec::new();
        while core.source.depth() > frame.caller_depth {
            if let Some(f) = core.source.pop() {
                lifted.push(f);
            }
        }
        let mut caller = Flow {
            program: frame.caller_program,
            file: frame.caller_file.clone(),
            ..Flow::default()
        };
        let found = flow::find_sequence(core, &mut caller, n, frame.return_to);
        while let Some(f) = lifted.pop() {
            core.source.push(f);
        }
        found
    }

    /// The end of a called program's text without M99: a return with a warning.
    pub(crate) fn end_without_m99<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
    ) -> Result<(), Diagnostic> {
        if self.flow.frames.is_empty() {
            return Ok(());
        }
        core.warnings.push(Diagnostic::warning(
            "mazatrol::missing-program-end",
            "a called program ends without M99: it returns as M99 would",
            core.block.span(),
        ));
        self.return_from_call(core, None)
    }

    /// Enters a program (commit of M98 / G65 / G66).
    pub(crate) fn call<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        target: Target,
        repeats: u32,
        kind: CallKind,
        args: Option<Box<[MVal; 33]>>,
    ) -> Result<(), Diagnostic> {
        if repeats == 0 {
            return Ok(());
        }
        let return_to = core.source.position();
        let caller_depth = core.source.depth();
        if target.program.file != self.flow.file {
            match &target.program.file {
                Some(path) => {
                    let reader = core.source.open(path, core.block.span())?;
                    core.source.push(OpenFile {
                        reader,
                        path: path.clone(),
                    });
                }
                None => {
                    return Err(err(
                        "mazatrol::program-not-found",
                        "a program in a subprogram file cannot call a program of the main program's file",
                        core.block.span(),
                    ))
                }
            }
        }
        if let (CallKind::Macro, Some(a)) = (kind, args) {
            if !self.part.vars.push(*a) {
                return Err(err(
                    "mazatrol::call-nesting",
                    format!(
                        "macro calls nested deeper than {}",
                        crate::vars::MAX_MACRO_LEVELS
                    ),
                    core.block.span(),
                ));
            }
            self.part.vars.commit();
        }
        if kind == CallKind::Subprogram {
            self.part.sub_depth += 1;
        }
        let frame = Frame {
            kind,
            return_to,
            caller_depth,
            caller_program: self.flow.program,
            caller_file: self.flow.file.clone(),
            entry: target.entry,
            program: Some(target.program.header),
            file: target.program.file.clone(),
            repeats_left: repeats - 1,
            caller_loops: std::mem::take(&mut self.flow.loops),
        };
        self.flow.frames.push(frame);
        self.flow.program = Some(target.program.header);
        self.flow.file = target.program.file;
        core.seek(target.entry)
    }

    /// M99 (commit), or the end of a called program.
    pub(crate) fn return_from_call<R: BufRead + Seek>(
        &mut self,
        core: &mut Core<R>,
        to: Option<SourcePos>,
    ) -> Result<(), Diagnostic> {
        let Some(frame) = self.flow.frames.last_mut() else {
            return Ok(());
        };
        if frame.repeats_left > 0 && to.is_none() {
            frame.repeats_left -= 1;
            self.flow.loops.clear();
            let entry = frame.entry;
            return core.seek(entry);
        }
        let Some(frame) = self.flow.frames.pop() else {
            return Ok(());
        };
        if frame.kind == CallKind::Macro {
            self.part.vars.pop();
            self.part.vars.commit();
        }
        if frame.kind == CallKind::Subprogram {
            self.part.sub_depth = self.part.sub_depth.saturating_sub(1);
        }
        self.flow.loops = frame.caller_loops;
        while core.source.depth() > frame.caller_depth {
            core.source.pop();
        }
        self.flow.program = frame.caller_program;
        self.flow.file = frame.caller_file;
        core.seek(to.unwrap_or(frame.return_to))
    }
}

/// Re-reads the current line (after a search moved the reader) and leaves the reader after it.
fn reread_at<R: BufRead + Seek>(core: &mut Core<R>, pos: SourcePos) -> Result<(), Diagnostic> {
    flow::reread(core, pos)
}

/// Where a call enters a subprogram file: after its header (when it is an O line) or at N h.
fn file_entry(
    reader: &mut stanok_syntax::BlockReader<stanok_syntax::SeekBufReader<std::fs::File>>,
    header: SourcePos,
    is_o_line: bool,
    h: Option<u32>,
    at: Span,
) -> Result<SourcePos, Diagnostic> {
    let io = |e: std::io::Error| err("io::read", format!("cannot read the subprogram: {e}"), at);
    reader.seek(header).map_err(io)?;
    let mut block = Block::default();
    let mut diags = Vec::new();
    if is_o_line {
        reader.next_block(&mut block, &mut diags).map_err(io)?;
    }
    let after = reader.position();
    let Some(h) = h else {
        return Ok(after);
    };
    loop {
        let pos = reader.position();
        if !reader.next_block(&mut block, &mut diags).map_err(io)? {
            break;
        }
        if block.number == Some(h) {
            return Ok(pos);
        }
        if flow::program_number(&block).is_some() || block.percent {
            break;
        }
    }
    Err(err(
        "mazatrol::sequence-not-found",
        format!("H{h}: no block N{h} in the subprogram"),
        at,
    ))
}
