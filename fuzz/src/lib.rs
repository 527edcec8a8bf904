//! What the fuzz targets share: the input's layout, the bounds a fuzzed run gets, and the
//! properties every run must keep.
//!
//! Input layout of the program targets: byte 0 chooses the dialect (`byte % 8`, in
//! [`DIALECTS`] order) and the mode (bit 3: `check`'s continue-after-error), byte 1 the target
//! of `convert`; the rest is the program text, any bytes. The bounds are the project's own
//! options, set low so that one input takes milliseconds: a runaway program must end with a
//! diagnostic at the bound, never by the fuzzer's timeout.

use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

/// The eight dialects, in the order byte 0 selects them.
pub const DIALECTS: [Dialect; 8] = [
    Dialect::Axioma,
    Dialect::Rs274ngc,
    Dialect::Nc31,
    Dialect::P2p32,
    Dialect::Mc2101,
    Dialect::Gost20999,
    Dialect::Mazatrol,
    Dialect::Balt,
];

/// Byte 0 → (dialect, check mode), and the rest.
pub fn split(data: &[u8]) -> Option<(Dialect, bool, u8, &[u8])> {
    let (&head, rest) = data.split_first()?;
    let (&target, program) = rest.split_first().unwrap_or((&0, &[]));
    Some((
        DIALECTS[usize::from(head % 8)],
        head & 8 != 0,
        target,
        program,
    ))
}

/// Interpreter options with the fuzzing bounds.
pub fn options(dialect: Dialect, check: bool) -> InterpOptions {
    let mut o = InterpOptions::new(dialect);
    o.continue_after_error = check;
    o.max_blocks = 20_000;
    o.max_loop_iterations = 2_000;
    o.max_errors = 50;
    o
}

/// Runs the interpreter to its end: the commands and the diagnostics (errors, then warnings).
pub fn interpret(dialect: Dialect, check: bool, program: &[u8]) -> (Vec<Spanned<Canon>>, Vec<Diagnostic>) {
    let mut interp = Interpreter::new(std::io::Cursor::new(program), options(dialect, check));
    let mut commands = Vec::new();
    let mut diags = Vec::new();
    for item in interp.by_ref() {
        match item {
            Ok(c) => commands.push(c),
            Err(d) => {
                diags.push(d);
                if !check {
                    break;
                }
            }
        }
    }
    diags.extend(interp.take_warnings());
    for d in &diags {
        assert_located(d, program);
    }
    (commands, diags)
}

/// Every diagnostic about the program names a line of it (line 0 is only for the file as a
/// whole, which a program text never earns here) and a column on that line.
pub fn assert_located(d: &Diagnostic, program: &[u8]) {
    let lines = program.iter().filter(|&&b| b == b'\n').count() as u64 + 1;
    assert!(
        d.span.line >= 1 && u64::from(d.span.line) <= lines,
        "diagnostic without a line of the program: {d:?}"
    );
    assert!(d.span.column >= 1, "diagnostic without a column: {d:?}");
}
