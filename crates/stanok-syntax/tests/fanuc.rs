//! The Mazatrol EIA/ISO (Fanuc-style) line parser: program numbers, EOB, words with variables and
//! expressions, Fanuc precedence, macro statements, the refusals, and properties (no panic, spans
//! inside the line, every expression a contiguous post-order range of the arena, no recursion).

mod common;

use common::*;
use proptest::prelude::*;
use stanok_canon::{Diagnostic, Severity};
use stanok_syntax::{
    Address, BinOp, Block, BlockParser, ColSpan, CommentKind, Dialect, ExprId, ExprNode, MacroKind,
    ParamRef, UnaryFn, Value,
};

const D: Dialect = Dialect::Mazatrol;

/// An expression tree rebuilt from the arena, as text (`(+ a b)`), for comparing structure.
fn tree(b: &Block, id: ExprId) -> String {
    match *b.expr(id) {
        ExprNode::Number(v) => format!("{v}"),
        ExprNode::Param(ParamRef::Numbered(i)) => format!("#{}", tree(b, i)),
        ExprNode::Param(ParamRef::Named { .. }) | ExprNode::Exists(_) => "?".into(),
        ExprNode::Unary(f, a) => format!("({} {})", unary_name(f), tree(b, a)),
        ExprNode::Binary(op, l, r) => format!("({} {} {})", op_name(op), tree(b, l), tree(b, r)),
        ExprNode::Atan(y, x) => format!("(atan {} {})", tree(b, y), tree(b, x)),
    }
}

fn unary_name(f: UnaryFn) -> &'static str {
    match f {
        UnaryFn::Neg => "neg",
        UnaryFn::Plus => "plus",
        UnaryFn::Sin => "sin",
        UnaryFn::Cos => "cos",
        UnaryFn::Tan => "tan",
        UnaryFn::Asin => "asin",
        UnaryFn::Acos => "acos",
        UnaryFn::Sqrt => "sqrt",
        UnaryFn::Abs => "abs",
        UnaryFn::Round => "round",
        UnaryFn::Fix => "fix",
        UnaryFn::Fup => "fup",
        UnaryFn::Ln => "ln",
        UnaryFn::Exp => "exp",
    }
}

fn op_name(op: BinOp) -> &'static str {
    match op {
        BinOp::Pow => "**",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::Mod => "mod",
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Eq => "eq",
        BinOp::Ne => "ne",
        BinOp::Gt => "gt",
        BinOp::Ge => "ge",
        BinOp::Lt => "lt",
        BinOp::Le => "le",
        BinOp::And => "and",
        BinOp::Or => "or",
        BinOp::Xor => "xor",
    }
}

/// The right side of the line's only assignment, as a tree.
fn rhs(text: &str) -> String {
    let b = clean(text, D);
    assert_eq!(b.assignments.len(), 1, "{text}");
    tree(&b, b.assignments[0].value)
}

/// The single diagnostic of a line (an error), its code and column.
fn error(text: &str) -> (String, u32, String) {
    let (_, diags) = one(text, D);
    assert_eq!(diags.len(), 1, "{text}: {diags:#?}");
    assert_eq!(diags[0].severity, Severity::Error, "{text}");
    (
        diags[0].code.to_string(),
        diags[0].span.column,
        diags[0].message.clone(),
    )
}

#[test]
fn program_numbers_are_o_words_alone_on_their_line() {
    let b = clean("O1234 (FLANGE OP10)", D);
    assert_eq!(words(&b), vec![(l('O'), n(1234.0), "O1234")]);
    assert_eq!(b.comments.len(), 1);
    assert_eq!(b.slice(b.comments[0].text), "FLANGE OP10");
    let b = clean(":0010;", D);
    assert_eq!(words(&b), vec![(l('O'), n(10.0), ":0010")]);
    assert_eq!(error("O12 G00 X0").0, "syntax::unexpected-character");
    assert_eq!(error("G00 O12").0, "syntax::unexpected-character");
    assert_eq!(error("O123456789").0, "syntax::bad-number");
    assert_eq!(error("OX").0, "syntax::bad-number");
}

#[test]
fn eob_ends_the_block_and_the_rest_is_a_comment() {
    let b = clean("N10 G01 X10. Y-5 F100; after the end of block", D);
    assert_eq!(b.number, Some(10));
    assert_eq!(
        words(&b),
        vec![
            (l('G'), n(1.0), "G01"),
            (l('X'), n(10.0), "X10."),
            (l('Y'), n(-5.0), "Y-5"),
            (l('F'), n(100.0), "F100"),
        ]
    );
    let c = b.comments.last().unwrap();
    assert_eq!(c.kind, CommentKind::Line);
    assert_eq!(b.slice(c.text), " after the end of block");
    // A fixture annotation line is a comment only.
    let b = clean("; source: 004_…txt", D);
    assert!(b.words.is_empty() && b.comments.len() == 1);
}

#[test]
fn decimal_codes_turret_t_and_block_skip() {
    let b = clean("/N5 G43.4 G12.1 T0101", D);
    assert!(b.block_delete);
    assert_eq!(b.number, Some(5));
    assert_eq!(
        words(&b),
        vec![
            (l('G'), n(43.4), "G43.4"),
            (l('G'), n(12.1), "G12.1"),
            (l('T'), n(101.0), "T0101"),
        ]
    );
    assert!(clean("/2 G00 X1.", D).block_delete);
    assert_eq!(error("N1.5 G00").0, "syntax::bad-number");
    assert_eq!(error("G00 N10").0, "syntax::unexpected-character");
}

#[test]
fn percent_is_a_tape_delimiter() {
    assert!(clean("%", D).percent);
    assert!(clean("% (END)", D).percent);
    assert_eq!(error("% G00").0, "syntax::unexpected-character");
}

#[test]
fn word_values_are_numbers_variables_or_bracketed_expressions() {
    let b = clean("G00 X#1 Y-#2 Z[#3+1.5] A#[#4] F#9", D);
    let trees: Vec<String> = b
        .words
        .iter()
        .map(|w| match w.value {
            Value::Number(v) => format!("{v}"),
            Value::Expr(e) => tree(&b, e),
            _ => "?".into(),
        })
        .collect();
    assert_eq!(trees, ["0", "#1", "(neg #2)", "(+ #3 1.5)", "##4", "#9"]);
    assert_eq!(b.slice(b.words[3].span), "Z[#3+1.5]");
    // A signed literal written with a blank stays a plain number.
    assert_eq!(
        words(&clean("X - 5.", D)),
        vec![(l('X'), n(-5.0), "X - 5.")]
    );
    // Fanuc needs brackets around an expression and a function.
    let (code, col, msg) = error("G01 X SIN[30]");
    assert_eq!((code.as_str(), col), ("syntax::missing-value", 5));
    assert!(msg.contains("X[SIN[…]]"), "{msg}");
    assert_eq!(error("G01 X#1+2").0, "syntax::unexpected-character");
    assert_eq!(error("G01 X").0, "syntax::missing-value");
}

#[test]
fn assignments_read_fanuc_precedence() {
    assert_eq!(rhs("#1 = #2 + 3 * SIN[30]"), "(+ #2 (* 3 (sin 30)))");
    // AND sits with * and OR with +, unlike LinuxCNC, where both are below the comparisons.
    assert_eq!(rhs("#1 = 1 + 2 AND 3"), "(+ 1 (and 2 3))");
    assert_eq!(rhs("#1 = 1 OR 2 * 3"), "(or 1 (* 2 3))");
    assert_eq!(rhs("#1 = 1 - 2 - 3"), "(- (- 1 2) 3)");
    assert_eq!(rhs("#1 = 8 / 4 / 2"), "(/ (/ 8 4) 2)");
    assert_eq!(rhs("#1 = 7 MOD 4 XOR 1"), "(xor (mod 7 4) 1)");
    assert_eq!(rhs("#1 = -#2 * 2"), "(* (neg #2) 2)");
    assert_eq!(rhs("#1 = -[1 + 2] * 3"), "(* (neg (+ 1 2)) 3)");
    assert_eq!(rhs("#1 = 2 * - 3"), "(* 2 -3)");
    assert_eq!(rhs("#1 = #2 GT 3"), "(gt #2 3)");
    assert_eq!(rhs("#1 = #0"), "#0");
    assert_eq!(
        rhs("#1=ROUND[FIX[1.5]+FUP[ABS[-2]]]+SQRT[LN[EXP[1]]]"),
        "(+ (round (+ (fix 1.5) (fup (abs -2)))) (sqrt (ln (exp 1))))"
    );
    assert_eq!(
        rhs("#1 = ASIN[1]+ACOS[0]+TAN[COS[0]]"),
        "(+ (+ (asin 1) (acos 0)) (tan (cos 0)))"
    );
    // Indirect target; several assignments in one block.
    let b = clean("#[#1+100] = 5 #2 = #[#1+100]", D);
    assert_eq!(b.assignments.len(), 2);
    let ParamRef::Numbered(t) = b.assignments[0].target else {
        panic!()
    };
    assert_eq!(tree(&b, t), "(+ #1 100)");
    assert_eq!(tree(&b, b.assignments[1].value), "#(+ #1 100)");
    assert_eq!(b.slice(b.assignments[0].span), "#[#1+100] = 5");
}

#[test]
fn atan_has_three_forms() {
    assert_eq!(rhs("#1 = ATAN[1]/[2]"), "(atan 1 2)");
    assert_eq!(rhs("#1 = ATAN[1, 2]"), "(atan 1 2)");
    assert_eq!(rhs("#1 = ATAN[1]"), "(atan 1 1)");
    // The division after a one-argument ATAN is an ordinary division when no `[` follows.
    assert_eq!(rhs("#1 = ATAN[1]/2"), "(/ (atan 1 1) 2)");
}

#[test]
fn macro_statements() {
    let b = clean("N100 IF [#1 GT 10] GOTO 20", D);
    assert_eq!(b.number, Some(100));
    let s = b.statement.expect("a statement");
    assert_eq!(b.slice(s.span), "IF [#1 GT 10] GOTO 20");
    let MacroKind::IfGoto { condition, target } = s.kind else {
        panic!("{s:?}")
    };
    assert_eq!(tree(&b, condition), "(gt #1 10)");
    assert_eq!(b.slice(b.expr_span(condition)), "[#1 GT 10]");
    assert_eq!(tree(&b, target), "20");

    let b = clean("IF[#1EQ#0]THEN#2=1", D);
    let Some(s) = b.statement else { panic!() };
    assert!(matches!(s.kind, MacroKind::IfThen { .. }));
    assert_eq!(b.assignments.len(), 1);
    assert_eq!(tree(&b, b.assignments[0].value), "1");

    let b = clean("WHILE [#1 LE 10] DO 1 (loop)", D);
    let Some(s) = b.statement else { panic!() };
    let MacroKind::While { condition, label } = s.kind else {
        panic!()
    };
    assert_eq!((tree(&b, condition).as_str(), label), ("(le #1 10)", 1));
    assert_eq!(b.slice(s.label_span.unwrap()), "1");
    assert!(matches!(
        clean("END 1", D).statement.unwrap().kind,
        MacroKind::End { label: 1 }
    ));
    assert!(matches!(
        clean("DO2", D).statement.unwrap().kind,
        MacroKind::Do { label: 2 }
    ));
    let b = clean("GOTO [#5+10]", D);
    let MacroKind::Goto(t) = b.statement.unwrap().kind else {
        panic!()
    };
    assert_eq!(tree(&b, t), "(+ #5 10)");
    let b = clean("goto #5", D);
    assert!(matches!(b.statement.unwrap().kind, MacroKind::Goto(_)));
    // A bracketed AND of comparisons is fine.
    let b = clean("IF [[#1 GT 0] AND [#2 LT 5]] GOTO 1", D);
    let MacroKind::IfGoto { condition, .. } = b.statement.unwrap().kind else {
        panic!()
    };
    assert_eq!(tree(&b, condition), "(and (gt #1 0) (lt #2 5))");
}

#[test]
fn refusals_name_what_is_wrong() {
    let cases: &[(&str, &str, u32)] = &[
        ("G00 X10. #1=5", "syntax::mixed-block", 10),
        ("#1=5 G00", "syntax::mixed-block", 6),
        ("G00 X1. GOTO 10", "syntax::mixed-block", 9),
        ("#1=5 IF [1 EQ 1] GOTO 3", "syntax::mixed-block", 6),
        ("IF [1 LT 2 LT 3] GOTO 1", "syntax::chained-comparison", 12),
        ("#1 = ##2", "syntax::bad-parameter", 6),
        ("#<x> = 1", "syntax::bad-parameter", 1),
        ("#1 = BIN[3]", "syntax::unknown-word", 6),
        ("#1 = FOO[3]", "syntax::unknown-word", 6),
        ("#1 = SIN 30", "syntax::bad-function", 6),
        ("#1 = [1 + 2", "syntax::unbalanced-brackets", 6),
        ("#1 = 1 + 2]", "syntax::unbalanced-brackets", 11),
        ("#1 = [[[[[[1]]]]]]", "syntax::expression-too-deep", 11),
        ("#1 = 1 +", "syntax::missing-value", 9),
        ("#1 5", "syntax::bad-assignment", 1),
        ("#1 = 1, 2", "syntax::unexpected-character", 7),
        ("IF #1 GOTO 1", "syntax::unexpected-character", 4),
        ("IF [1 EQ 1] X1", "syntax::unexpected-character", 13),
        ("WHILE [1 EQ 1] 1", "syntax::unexpected-character", 16),
        ("END", "syntax::missing-value", 4),
        ("GOTO 10 X1.", "syntax::unexpected-character", 9),
        ("G01 X10. ,C2.", "syntax::unexpected-character", 10),
        ("(open", "syntax::unclosed-comment", 1),
        ("(a (b) c)", "syntax::nested-comment", 4),
    ];
    for &(text, code, column) in cases {
        let (c, col, msg) = error(text);
        assert_eq!((c.as_str(), col), (code, column), "{text}: {msg}");
    }
    // Five levels are the limit, not an error.
    assert_eq!(rhs("#1 = [[[[[1]]]]]"), "1");
}

#[test]
fn the_corpus_parses() {
    // The fixtures without the source's placeholders (`Xx1`, `X_`) parse without a diagnostic.
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus/mazatrol"
    );
    let mut clean_files = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let placeholders = text
            .lines()
            .filter(|l| !l.starts_with(';'))
            .any(|l| l.contains('_') || l.bytes().any(|c| c.is_ascii_lowercase()));
        let (_, diags) = stanok_syntax::parse(&text, D);
        if !placeholders {
            assert!(diags.is_empty(), "{}: {diags:#?}", path.display());
            clean_files += 1;
        }
    }
    assert!(clean_files >= 11, "{clean_files}");
}

#[test]
fn long_chains_do_not_recurse() {
    // 200,000 terms and 100,000 signs on a 256 KiB stack: the parser keeps its stacks on the heap.
    let handle = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(|| {
            let sum = format!("#1 = 1{}", "+1".repeat(200_000));
            let (b, diags) = one(&sum, D);
            assert!(diags.is_empty());
            assert_eq!(b.exprs.len(), 1 + 2 * 200_000 + 1);
            let signs = format!("#1 = {}1", "-".repeat(100_000));
            let (_, diags) = one(&signs, D);
            assert!(diags.is_empty(), "{diags:?}");
        })
        .unwrap();
    handle.join().unwrap();
}

// ---- properties ----

fn span_ok(b: &Block, c: ColSpan) -> bool {
    c.start <= c.end
        && (c.end as usize) <= b.text.len()
        && b.text.is_char_boundary(c.start as usize)
        && b.text.is_char_boundary(c.end as usize)
}

/// The lowest arena index of the subtree at `id` (following first children).
fn lowest(b: &Block, mut id: ExprId) -> usize {
    loop {
        id = match *b.expr(id) {
            ExprNode::Unary(_, a) => a,
            ExprNode::Binary(_, l, _) | ExprNode::Atan(l, _) => l,
            ExprNode::Param(ParamRef::Numbered(i)) => i,
            _ => return id.0 as usize,
        };
    }
}

/// Children before parents; every subtree a contiguous range ending at its root; spans inside.
fn check(b: &Block, diags: &[Diagnostic]) -> Result<(), TestCaseError> {
    for w in &b.words {
        prop_assert!(span_ok(b, w.span));
    }
    for c in &b.comments {
        prop_assert!(span_ok(b, c.text));
    }
    for a in &b.assignments {
        prop_assert!(span_ok(b, a.span));
    }
    if let Some(s) = b.statement {
        prop_assert!(span_ok(b, s.span));
    }
    for (i, (node, span)) in b.exprs.iter().enumerate() {
        prop_assert!(span_ok(b, *span), "node {i}");
        match *node {
            ExprNode::Unary(_, a) | ExprNode::Param(ParamRef::Numbered(a)) => {
                prop_assert_eq!(a.0 as usize, i - 1)
            }
            ExprNode::Binary(_, l, r) | ExprNode::Atan(l, r) => {
                // The right subtree ends just before the node; the left one just before it.
                prop_assert_eq!(r.0 as usize, i - 1);
                prop_assert_eq!(l.0 as usize + 1, lowest(b, r));
            }
            _ => {}
        }
    }
    let end = b.offset + b.text.len() as u64;
    for d in diags {
        prop_assert!(d.span.start >= b.offset && d.span.end <= end, "{d:?}");
    }
    Ok(())
}

const SOUP: &[&str] = &[
    "#", "#1", "#0", "#[", "[", "]", "=", "+", "-", "*", "/", ",", "1", "2.5", ".", "GT", "EQ",
    "AND", "OR", "MOD", "SIN", "ATAN", "IF", "GOTO", "THEN", "WHILE", "DO", "END", "G01", "X",
    "N10", "O12", ";", "(", ")", "%", "é",
];

fn soup_line() -> impl Strategy<Value = String> {
    proptest::collection::vec((proptest::sample::select(SOUP), any::<bool>()), 0..24).prop_map(
        |tokens| {
            let mut s = String::new();
            for (t, space) in tokens {
                s.push_str(t);
                if space {
                    s.push(' ');
                }
            }
            s
        },
    )
}

/// A random expression tree written with every binary bracketed, and the same tree printed.
fn expr_text() -> impl Strategy<Value = (String, String)> {
    let leaf = prop_oneof![
        (0u32..100).prop_map(|v| (format!("{v}"), format!("{v}"))),
        (1u32..40).prop_map(|v| (format!("#{v}"), format!("#{v}"))),
    ];
    leaf.prop_recursive(5, 32, 2, |inner| {
        prop_oneof![
            (
                inner.clone(),
                proptest::sample::select(
                    &["+", "-", "*", "/", "AND", "OR", "XOR", "MOD", "EQ", "LT"][..]
                ),
                inner.clone()
            )
                .prop_map(|((lt, ls), op, (rt, rs))| {
                    let name = match op {
                        "AND" => "and",
                        "OR" => "or",
                        "XOR" => "xor",
                        "MOD" => "mod",
                        "EQ" => "eq",
                        "LT" => "lt",
                        o => o,
                    };
                    (format!("[{lt} {op} {rt}]"), format!("({name} {ls} {rs})"))
                }),
            inner
                .clone()
                .prop_map(|(t, s)| (format!("SQRT[{t}]"), format!("(sqrt {s})"))),
            inner
                .clone()
                .prop_map(|(t, s)| (format!("-{t}"), format!("(neg {s})"))),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: ProptestConfig::default().cases.max(512), ..ProptestConfig::default() })]

    #[test]
    fn soup_never_panics_and_keeps_the_arena_invariant(line in soup_line()) {
        let mut parser = BlockParser::new(D);
        let mut block = Block::default();
        let mut diags = Vec::new();
        parser.parse_line(&line, 1, 0, &mut block, &mut diags);
        check(&block, &diags)?;
    }

    #[test]
    fn arbitrary_text_never_panics(line in any::<String>()) {
        let mut parser = BlockParser::new(D);
        let mut block = Block::default();
        let mut diags = Vec::new();
        parser.parse_line(&line, 1, 0, &mut block, &mut diags);
        check(&block, &diags)?;
    }

    #[test]
    fn bracketed_expressions_parse_to_their_tree((text, expected) in expr_text()) {
        // `[-x]` style signs of bracketed leaves are fine: the tree gives `(neg …)` for them.
        let line = format!("#1 = {text}");
        let (b, diags) = one(&line, D);
        // Deep random trees may pass the five-bracket limit: that must be the only refusal.
        if let Some(d) = diags.first() {
            prop_assert_eq!(d.code.to_string(), "syntax::expression-too-deep");
            return Ok(());
        }
        let got = tree(&b, b.assignments[0].value);
        // A signed literal is one number (`-5`), the tree printer writes `(neg 5)`.
        let got = normalise_signs(&got);
        prop_assert_eq!(got, expected);
        check(&b, &diags)?;
    }
}

/// `-5` (a signed literal) written as the tree `(neg 5)` would be.
fn normalise_signs(s: &str) -> String {
    let mut out = String::new();
    let mut chars = s.chars().peekable();
    let mut prev = ' ';
    while let Some(c) = chars.next() {
        if c == '-'
            && (prev == ' ' || prev == '(')
            && chars.peek().is_some_and(|d| d.is_ascii_digit())
        {
            let mut digits = String::new();
            while let Some(&d) = chars.peek() {
                if d.is_ascii_digit() || d == '.' {
                    digits.push(d);
                    chars.next();
                } else {
                    break;
                }
            }
            out.push_str(&format!("(neg {digits})"));
            prev = ')';
            continue;
        }
        out.push(c);
        prev = c;
    }
    out
}

#[test]
fn normalise_signs_rewrites_signed_literals() {
    assert_eq!(normalise_signs("(+ -5 #1)"), "(+ (neg 5) #1)");
    assert_eq!(normalise_signs("(- 5 1)"), "(- 5 1)");
    let _ = Address::Letter(b'X');
}

#[test]
fn the_example_jobs_parse() {
    for name in ["mazak-m-job.eia", "mazak-t-job.eia"] {
        let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        let (program, diags) = stanok_syntax::parse(&text, D);
        assert!(diags.is_empty(), "{name}: {diags:#?}");
        let programs = program
            .blocks
            .iter()
            .filter(|b| {
                b.words
                    .first()
                    .is_some_and(|w| w.address == Address::Letter(b'O'))
            })
            .count();
        assert!(programs >= 1, "{name}");
    }
}
