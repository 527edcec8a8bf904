//! Issue 17: inputs that crashed or hung the interpreter, each a regression test, and the bounds
//! that keep every run finite (docs/robustness.md).

use stanok_canon::{Canon, Diagnostic, Spanned};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

/// A finished run: its commands, its errors, and the interpreter (for its stats and warnings).
type Run<'a> = (
    Vec<Spanned<Canon>>,
    Vec<Diagnostic>,
    Interpreter<std::io::Cursor<&'a [u8]>>,
);

/// Every command and diagnostic of a run (check mode: goes on after errors when `check`).
fn run(text: &str, opts: InterpOptions) -> Run<'_> {
    let check = opts.continue_after_error;
    let mut interp = Interpreter::from_text(text, opts);
    let mut cmds = Vec::new();
    let mut errors = Vec::new();
    for item in interp.by_ref() {
        match item {
            Ok(c) => cmds.push(c),
            Err(d) => {
                errors.push(d);
                if !check {
                    break;
                }
            }
        }
    }
    (cmds, errors, interp)
}

fn first_error(text: &str, dialect: Dialect) -> Option<Diagnostic> {
    run(text, InterpOptions::new(dialect)).1.into_iter().next()
}

/// Runs `f` on a thread with `stack` bytes of stack (the panel's workers have 2 MiB).
fn on_stack<T: Send + 'static>(stack: usize, f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(stack)
        .spawn(f)
        .expect("thread")
        .join()
        .expect("no panic, no overflow")
}

fn chain(op: &str, n: usize) -> String {
    vec!["1"; n].join(op)
}

// ---------------------------------------------------------------- item 1: long chains

/// `double aa = 1+1+…` of 5,000 and 20,000 terms (the panel's `/api/check` died on 5,000), the ISO
/// word form `G0 X=1+1+…`, RS274/NGC `[1+1+…]`, `AND`/`OR` chains: a diagnostic, on a thread with
/// the panel's 2 MiB stack.
#[test]
fn long_left_associative_chains_are_refused_on_a_small_stack() {
    let cases: Vec<(Dialect, String, &str)> = vec![
        (
            Dialect::Axioma,
            format!("double aa = {};\nM30\n", chain("+", 5_000)),
            "hll::too-long",
        ),
        (
            Dialect::Axioma,
            format!("double aa = {};\nM30\n", chain("+", 20_000)),
            "hll::too-long",
        ),
        (
            Dialect::Axioma,
            format!("G0 X={}\nM30\n", chain("+", 20_000)),
            "hll::too-long",
        ),
        (
            Dialect::Axioma,
            format!("bool b = {};\nM30\n", chain(" && ", 5_000)),
            "hll::too-long",
        ),
        (
            Dialect::Rs274ngc,
            format!("G0 X[{}]\nM2\n", chain("+", 20_000)),
            "syntax::expression-too-long",
        ),
        (
            Dialect::Rs274ngc,
            format!("#1=[{}]\nM2\n", chain(" AND ", 5_000)),
            "syntax::expression-too-long",
        ),
        (
            Dialect::Rs274ngc,
            format!("#1=[{}]\nM2\n", chain(" OR ", 5_000)),
            "syntax::expression-too-long",
        ),
    ];
    for (dialect, text, code) in cases {
        let d = on_stack(2 << 20, move || first_error(&text, dialect));
        let d = d.expect("an error");
        assert_eq!(d.code.to_string(), code, "{dialect:?}: {d:?}");
        assert_eq!(d.span.line, 1);
    }
    // Mazatrol EIA/ISO (Fanuc macro B) evaluates an expression in one forward pass without
    // recursion (five bracket levels at most), so a long chain is no danger to the stack: it
    // evaluates, on the same 2 MiB.
    let text = format!("G0 X[{}]\nM30\n", chain("+", 5_000));
    let d = on_stack(2 << 20, move || first_error(&text, Dialect::Mazatrol));
    assert!(d.is_none(), "{d:?}");
}

/// The longest chain allowed (`MAX_EXPR_HEIGHT` operands) still evaluates, on 2 MiB, to the sum.
#[test]
fn the_longest_allowed_chain_evaluates_on_a_small_stack() {
    let n = stanok_syntax::MAX_EXPR_HEIGHT as usize;
    let hll = format!("double aa = {};\nG1 X=aa F100\nM30\n", chain("+", n));
    let cmds = on_stack(2 << 20, move || {
        run(&hll, InterpOptions::new(Dialect::Axioma)).0
    });
    let x = cmds.iter().find_map(|c| match &c.value {
        Canon::StraightFeed(m) => Some(m.end.x),
        _ => None,
    });
    assert_eq!(x, Some(n as f64));
    let ngc = format!("G1 X[{}] F100\nM2\n", chain("+", n));
    let (cmds, errors) = on_stack(2 << 20, move || {
        let (c, e, _) = run(&ngc, InterpOptions::new(Dialect::Rs274ngc));
        (c, e)
    });
    assert!(errors.is_empty(), "{errors:?}");
    let x = cmds.iter().find_map(|c| match &c.value {
        Canon::StraightFeed(m) => Some(m.end.x),
        _ => None,
    });
    assert_eq!(x, Some(n as f64));
}

/// Unary chains stay under the nesting bound: `-------…1` and `!!!!…1`.
#[test]
fn long_unary_chains_are_refused() {
    let d = first_error(
        &format!("G0 X{}1\nM2\n", "-".repeat(20_000)),
        Dialect::Rs274ngc,
    )
    .unwrap();
    assert_eq!(d.code.to_string(), "syntax::expression-too-deep");
    let d = first_error(
        &format!("bool b = {}true;\nM30\n", "!".repeat(20_000)),
        Dialect::Axioma,
    )
    .unwrap();
    assert_eq!(d.code.to_string(), "hll::too-deep");
}

// ---------------------------------------------------------------- item 4: runaway loops

/// The 103 bytes: three nested `repeat [1000]` with a parameter update, 10⁹ passes, none
/// over the per-loop bound. The run-wide bound stops it (here lowered so the test is quick).
#[test]
fn nested_repeats_stop_at_the_total_loop_bound() {
    let text = "#1=0\no1 repeat [1000]\no2 repeat [1000]\no3 repeat [1000]\n#1=[#1+1]\no3 endrepeat\no2 endrepeat\no1 endrepeat\nM2\n";
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_total_loop_iterations = 20_000;
    let (_, errors, interp) = run(text, opts);
    let d = &errors[0];
    assert_eq!(d.code.to_string(), "flow::too-many-iterations");
    assert!(d.message.contains("20000"), "{}", d.message);
    assert!(d.span.line >= 5, "{d:?}");
    // It stopped at the bound: 20,001 passes of o3's body at most.
    assert!(interp.parameters().expect("RS274/NGC parameters").get(1) <= 20_001.0);
}

/// AxiOMA's nested `for` loops share the same run-wide bound.
#[test]
fn nested_hll_loops_stop_at_the_total_loop_bound() {
    let text = "int i; int j; int k; double s = 0;\nfor (i = 0; i < 1000; i++) {\nfor (j = 0; j < 1000; j++) {\nfor (k = 0; k < 1000; k++) {\ns = s + 1;\n}\n}\n}\nM30\n";
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.max_total_loop_iterations = 20_000;
    let (_, errors, _) = run(text, opts);
    assert_eq!(errors[0].code.to_string(), "hll::loop-limit");
    assert!(errors[0].message.contains("20000"));
}

/// A loop whose body is skipped text still counts its lines against `max_blocks` (lines read).
#[test]
fn skipped_lines_count_against_the_line_bound() {
    let mut text = String::from("o1 while [1]\no2 if [0]\n");
    text.push_str(&"G1 X1\n".repeat(100));
    text.push_str("o2 endif\no1 endwhile\nM2\n");
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_blocks = 50_000;
    let (_, errors, interp) = run(&text, opts);
    assert_eq!(errors[0].code.to_string(), "interp::too-many-blocks");
    assert!(errors[0].span.line >= 1);
    assert_eq!(interp.stats().lines_read, 50_001);
}

// ---------------------------------------------------------------- item 8: nesting

/// `if(1){` nested 100,000 deep took over 10 s: the nesting bound stops it at once.
#[test]
fn deep_hll_nesting_is_refused() {
    let text = format!(
        "{}{}M30\n",
        "if(1){\n".repeat(100_000),
        "}\n".repeat(100_000)
    );
    let t = std::time::Instant::now();
    let d = first_error(&text, Dialect::Axioma).unwrap();
    assert_eq!(d.code.to_string(), "hll::nesting-too-deep");
    assert_eq!(d.span.line as usize, stanok_interp::DEFAULT_MAX_NESTING + 1);
    assert!(t.elapsed().as_secs() < 10);
}

/// O-word ifs nested past the bound.
#[test]
fn deep_oword_nesting_is_refused() {
    let mut text = String::new();
    for i in 0..2_000 {
        text.push_str(&format!("o{i} if [1]\n"));
    }
    for i in (0..2_000).rev() {
        text.push_str(&format!("o{i} endif\n"));
    }
    text.push_str("M2\n");
    let d = first_error(&text, Dialect::Rs274ngc).unwrap();
    assert_eq!(d.code.to_string(), "flow::too-deep");
    assert_eq!(d.span.line as usize, stanok_interp::DEFAULT_MAX_NESTING + 1);
}

// ---------------------------------------------------------------- item 5: diagnostics per line

/// One AxiOMA line of 499 repeated `G1 X1` words (1,000 words, the most a block holds): at most
/// `max_diagnostics_per_line` warnings, the last counting the rest.
#[test]
fn warnings_per_line_are_bounded() {
    let text = format!("G1 F100 {}\nM30\n", "G1 X1 ".repeat(499));
    let mut opts = InterpOptions::new(Dialect::Axioma);
    opts.continue_after_error = true;
    let (_, _, mut interp) = run(&text, opts);
    let w = interp.take_warnings();
    let on_line_1 = w.iter().filter(|d| d.span.line == 1).count();
    assert!(!w.is_empty());
    assert!(
        on_line_1 <= stanok_interp::DEFAULT_MAX_DIAGNOSTICS_PER_LINE,
        "{on_line_1}"
    );
    if on_line_1 == stanok_interp::DEFAULT_MAX_DIAGNOSTICS_PER_LINE {
        let last = w.iter().rev().find(|d| d.span.line == 1).unwrap();
        assert!(last.notes.iter().any(|n| n.starts_with("and ")), "{last:?}");
    }
}

/// A warning inside a loop is given once, not once per pass.
#[test]
fn a_warning_in_a_loop_is_given_once() {
    let text = "#1=0\no1 while [#1 LT 1000]\n#1=[#1+1]\n(msg, pass)\nG1 X1 F100 G17 G17\no1 endwhile\nM2\n";
    let (_, errors, mut interp) = run(text, InterpOptions::new(Dialect::Rs274ngc));
    let w = interp.take_warnings();
    assert!(w.len() <= 10, "{errors:?} {w:?}");
}

// ---------------------------------------------------------------- item 6: program size

/// A program without end (`/dev/zero`): the reader stops at the size bound.
#[test]
fn an_endless_program_stops_at_the_size_bound() {
    for dialect in [
        Dialect::Rs274ngc,
        Dialect::Axioma,
        Dialect::Gost20999,
        Dialect::Nc31,
        Dialect::Balt,
    ] {
        let mut opts = InterpOptions::new(dialect);
        opts.max_program_bytes = 3 << 20;
        opts.continue_after_error = true;
        let endless = std::io::BufReader::new(Zeros(0));
        let mut interp = Interpreter::new(endless, opts);
        let mut errors = Vec::new();
        for item in interp.by_ref() {
            if let Err(d) = item {
                errors.push(d);
            }
            assert!(errors.len() < 200);
        }
        let codes: Vec<String> = errors.iter().map(|d| d.code.to_string()).collect();
        assert!(
            codes
                .iter()
                .any(|c| c == "syntax::program-too-large" || c == "lab::too-large"),
            "{dialect:?}: {codes:?}"
        );
        for d in &errors {
            assert!(d.span.line >= 1, "{d:?}");
        }
    }
}

/// An endless reader of NUL bytes that can seek (as `/dev/zero` can).
struct Zeros(u64);
impl std::io::Read for Zeros {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        buf.fill(0);
        self.0 += buf.len() as u64;
        Ok(buf.len())
    }
}
impl std::io::Seek for Zeros {
    fn seek(&mut self, pos: std::io::SeekFrom) -> std::io::Result<u64> {
        if let std::io::SeekFrom::Start(p) = pos {
            self.0 = p;
        }
        Ok(self.0)
    }
}

/// The line-length bound is an option.
#[test]
fn the_line_length_bound_is_an_option() {
    let text = format!("G1 X1 F100 ({})\nM2\n", "x".repeat(1000));
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_line_bytes = 100;
    let (_, errors, _) = run(&text, opts);
    assert_eq!(errors[0].code.to_string(), "syntax::line-too-long");
    assert!(errors[0].message.contains("100 bytes"));
}

// ---------------------------------------------------------------- item 10: blocks counted

/// The block that fails is not counted as executed, in every dialect (it was counted in
/// RS274/NGC and AxiOMA, not in GOST-20999).
#[test]
fn the_failing_block_is_not_counted_in_any_dialect() {
    let cases = [
        (Dialect::Rs274ngc, "G0 X1\nG1 X2 F100\nG999\nM2\n"),
        (Dialect::Axioma, "G0 X1\nG1 X2 F100\nG999\nM30\n"),
        (Dialect::Mazatrol, "G0 X1\nG1 X2 F100\nG999\nM30\n"),
        (
            Dialect::Gost20999,
            "N1 G0 X1000\nN2 G1 X2000 F100\nN3 G999\nN4 M2\n",
        ),
    ];
    for (dialect, text) in cases {
        let (_, errors, interp) = run(text, InterpOptions::new(dialect));
        assert_eq!(errors.len(), 1, "{dialect:?}: {errors:?}");
        assert_eq!(errors[0].span.line, 3, "{dialect:?}");
        assert_eq!(interp.stats().blocks_executed, 2, "{dialect:?}");
    }
}

/// The line bound in a lab dialect names a line of the program (it had none).
#[test]
fn the_line_bound_in_a_lab_dialect_is_located() {
    let text = "N1 G1 X1000 F100\nN2 X2000\nN3 X3000\nN4 X4000\nN5 X5000\nN6 M2\n";
    let mut opts = InterpOptions::new(Dialect::Gost20999);
    opts.max_blocks = 3;
    let (_, errors, _) = run(text, opts);
    assert_eq!(errors[0].code.to_string(), "interp::too-many-blocks");
    assert!(
        errors[0].span.line >= 1 && errors[0].span.line <= 4,
        "{:?}",
        errors[0]
    );
}

/// Lines read again (loop passes) have their own, lower bound; a long program read once does not
/// touch it.
#[test]
fn lines_read_again_have_their_own_bound() {
    let mut text = String::from("o1 while [1]\n");
    text.push_str(&"G1 X1 F100\nG1 X0\n".repeat(50));
    text.push_str("o1 endwhile\nM2\n");
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_repeated_lines = 10_000;
    let (_, errors, interp) = run(&text, opts);
    assert_eq!(errors[0].code.to_string(), "interp::too-many-blocks");
    assert!(errors[0]
        .notes
        .iter()
        .any(|n| n.contains("--max-repeated-lines")));
    assert!(interp.stats().lines_read < 10_200);

    let straight = format!("G1 F100\n{}M2\n", "G1 X1\nG1 X0\n".repeat(20_000));
    let mut opts = InterpOptions::new(Dialect::Rs274ngc);
    opts.max_repeated_lines = 10;
    let (_, errors, _) = run(&straight, opts);
    assert!(errors.is_empty(), "{errors:?}");
}

// ------------------------------------------- mutation campaign, session 3: a megabyte of words

/// Found by the mutation campaign (seed 20261127, run 565): one 2P32 line of 300,000 `G1 X1` words
/// took 95 s of CPU in every verb — each word's column was counted from the start of the line —
/// and an AxiOMA block of 160,000 repeated words 17 s (each warning's column likewise). A block
/// holds at most `MAX_WORDS_PER_BLOCK` words in every dialect: the next one is an error at its
/// column, found in milliseconds; a block of exactly that many reads.
#[test]
fn a_block_of_a_megabyte_of_words_is_refused_at_its_1001st_word() {
    let max = stanok_syntax::MAX_WORDS_PER_BLOCK;
    let words = "G1 X1 ".repeat(80_000);
    for dialect in [
        Dialect::Axioma,
        Dialect::Rs274ngc,
        Dialect::Mazatrol,
        Dialect::Balt,
        Dialect::Gost20999,
        Dialect::P2p32,
        Dialect::Mc2101,
    ] {
        let text = format!("N1 {words}\nN2 M2\n");
        let t0 = std::time::Instant::now();
        let err = first_error(&text, dialect).expect("refused");
        assert_eq!(
            err.code.to_string(),
            "syntax::too-many-words",
            "{dialect:?}: {err}"
        );
        assert_eq!(err.span.line, 1, "{dialect:?}");
        // Word 1,001 starts after "N1 " and 1,000 words of 3 characters each.
        assert_eq!(err.span.column as usize, 4 + 3 * max, "{dialect:?}: {err}");
        // Not a timing assertion of speed: a guard against the quadratic cost coming back (it
        // took minutes; linear work takes milliseconds even in a debug build).
        assert!(
            t0.elapsed().as_secs() < 20,
            "{dialect:?}: {:?}",
            t0.elapsed()
        );
    }
    let exactly = "X1 ".repeat(max - 2);
    let (_, errors, _) = run(
        &format!("N1 G1 F100 {exactly}\nN2 M2\n"),
        InterpOptions::new(Dialect::Axioma),
    );
    assert!(errors.is_empty(), "{errors:?}");
}

/// The lab parsers' columns are characters, not bytes, after the one-pass column count: a word
/// after Cyrillic text has the column a person counts.
#[test]
fn lab_columns_count_characters_after_cyrillic() {
    // `ПС` (2 characters, 4 bytes), then `Q` with no number: the error is at `?`, character
    // column 8 (byte column 10).
    let err = first_error("ПС N1 Q? X1\n", Dialect::P2p32).expect("refused");
    assert_eq!(err.span.line, 1);
    assert_eq!(err.span.column, 8, "{err}");
}

/// Mutation campaign (session 3): `o9 while [1]` / `G1 X1` / `o9 endwhile` under G41 — moves
/// without motion in the compensation plane, each held for the next element's corner and copied
/// into every block's undo — took minutes (the square of the count). After
/// `MAX_MOVES_OUT_OF_PLANE` such moves in a row, an error at the next one.
#[test]
fn moves_out_of_the_compensation_plane_are_bounded() {
    let text = "G21 G90 G17\nG0 X50 Y50\nG41.1 D10\nG3 X70 Y50 I10 J0 F100\n\
                G1 X1\no9 while [1]\nZ1\no9 endwhile\nM2\n";
    let t0 = std::time::Instant::now();
    let err = first_error(text, Dialect::Rs274ngc).expect("refused");
    assert_eq!(err.code.to_string(), "rs274::comp-no-plane-motion", "{err}");
    assert_eq!(err.span.line, 7, "{err}");
    assert!(t0.elapsed().as_secs() < 60, "{:?}", t0.elapsed());
    // A real retract-and-plunge sequence stays far below the bound.
    let ok = "G21 G90 G17\nG0 X50 Y50\nG41.1 D10\nG3 X70 Y50 I10 J0 F100\n\
              G1 X1\nZ5\nZ10\nZ5\nZ0\nG1 Y0\nG40 G0 X-10\nM2\n";
    assert!(first_error(ok, Dialect::Rs274ngc).is_none());
}
