//! RS274/NGC dialect: words, expressions, parameters, comments, O-words, errors.

mod common;

use common::*;
use stanok_syntax::{
    BinOp, Block, CommentKind, Dialect, ExprId, ExprNode, OKind, OLabel, ParamRef, UnaryFn, Value,
};

const NGC: Dialect = Dialect::Rs274ngc;

/// An expression as an S-expression string, e.g. `(+ 1 (* 2 3))`, to compare trees exactly.
fn tree(b: &Block, id: ExprId) -> String {
    match *b.expr(id) {
        ExprNode::Number(v) => format!("{v}"),
        ExprNode::Param(p) => param(b, p),
        ExprNode::Unary(f, a) => format!("({f:?} {})", tree(b, a)),
        ExprNode::Binary(op, l, r) => format!("({op:?} {} {})", tree(b, l), tree(b, r)),
        ExprNode::Atan(y, x) => format!("(Atan {} {})", tree(b, y), tree(b, x)),
        ExprNode::Exists(p) => format!("(Exists {})", param(b, p)),
    }
}

fn param(b: &Block, p: ParamRef) -> String {
    match p {
        ParamRef::Numbered(id) => format!("#{}", tree(b, id)),
        ParamRef::Named { name, global } => {
            format!("#<{}>{}", b.slice(name), if global { "g" } else { "" })
        }
    }
}

/// The tree of the value of word `i`.
fn word_tree(b: &Block, i: usize) -> String {
    match b.words[i].value {
        Value::Expr(id) => tree(b, id),
        v => panic!("word {i} is not an expression: {v:?}"),
    }
}

#[test]
fn numbers_and_blanks() {
    let b = clean("G 0 X 1 . 5 Y-.5 Z+1 A1. B.5 c-0", NGC);
    assert_eq!(
        words(&b),
        vec![
            (l('G'), n(0.0), "G 0"),
            (l('X'), n(1.5), "X 1 . 5"),
            (l('Y'), n(-0.5), "Y-.5"),
            (l('Z'), n(1.0), "Z+1"),
            (l('A'), n(1.0), "A1."),
            (l('B'), n(0.5), "B.5"),
            (l('C'), n(-0.0), "c-0"),
        ]
    );
    let b = clean("g1x1y2", NGC);
    assert_eq!(words(&b).len(), 3);
    let b = clean("M3 $1 S1000", NGC);
    assert_eq!(words(&b)[1], (l('$'), n(1.0), "$1"));
}

#[test]
fn line_numbers_and_block_delete() {
    let b = clean("/N10 G1", NGC);
    assert!(b.block_delete);
    assert_eq!(
        (b.number, b.slice(b.number_span.unwrap())),
        (Some(10), "N10")
    );
    let b = clean("  n 2 0 G1", NGC);
    assert_eq!(b.number, Some(20));
    let b = clean("N10.5 G1", NGC);
    assert_eq!((b.number, words(&b).len()), (Some(10), 1));
    let b = single_error("G1 N10 X1", NGC, "syntax::unexpected-character", 4, "N");
    assert_eq!(words(&b).len(), 1);
    single_error("N G1", NGC, "syntax::bad-number", 1, "N");
}

#[test]
fn percent_lines() {
    assert!(clean("%", NGC).percent);
    assert!(clean("  %  ", NGC).percent);
    let b = clean("% (start)", NGC);
    assert!(b.percent && b.comments.len() == 1);
    let b = single_error("% G1", NGC, "syntax::unexpected-character", 3, "G");
    assert!(!b.percent);
    single_error("G1 %", NGC, "syntax::unexpected-character", 4, "%");
}

#[test]
fn expressions_follow_linuxcnc_precedence() {
    let cases = [
        ("X[1+2*3]", "(Add 1 (Mul 2 3))"),
        ("X[1*2+3]", "(Add (Mul 1 2) 3)"),
        ("X[2**3**2]", "(Pow (Pow 2 3) 2)"),
        ("X[2*3**2]", "(Mul 2 (Pow 3 2))"),
        ("X[1-2-3]", "(Sub (Sub 1 2) 3)"),
        ("X[8/4/2]", "(Div (Div 8 4) 2)"),
        ("X[7 MOD 3 * 2]", "(Mul (Mod 7 3) 2)"),
        ("X[1 + 2 GT 2 AND 3 LT 4]", "(And (Gt (Add 1 2) 2) (Lt 3 4))"),
        ("X[1 eq 2 or 3 ne 4 xor 5 ge 6]", "(Xor (Or (Eq 1 2) (Ne 3 4)) (Ge 5 6))"),
        ("X[1 le 2]", "(Le 1 2)"),
        ("X[[1+2]*3]", "(Mul (Add 1 2) 3)"),
        ("X[-2**2]", "(Pow -2 2)"),
        ("X[-[2]]", "(Neg 2)"),
        ("X[1 - -2]", "(Sub 1 -2)"),
        ("X[5]", "5"),
        ("X-[1]", "(Neg 1)"),
        ("X+#1", "(Plus #1)"),
        ("X--1", "(Neg -1)"),
        ("X[1mod2]", "(Mod 1 2)"),
        ("X sin[30]", "(Sin 30)"),
        ("X[ABS[-1] + ACOS[0] + ASIN[0] + COS[0] + EXP[0] + FIX[1] + FUP[1] + LN[1] + ROUND[1] + SQRT[4] + TAN[0]]",
         "(Add (Add (Add (Add (Add (Add (Add (Add (Add (Add (Abs -1) (Acos 0)) (Asin 0)) (Cos 0)) (Exp 0)) (Fix 1)) (Fup 1)) (Ln 1)) (Round 1)) (Sqrt 4)) (Tan 0))"),
        ("X atan[1]/[1]", "(Atan 1 1)"),
        ("X[atan[1]/[2] / 3]", "(Div (Atan 1 2) 3)"),
        ("X[sin[1]/[2]]", "(Div (Sin 1) 2)"),
        ("X[EXISTS[#<_x>]]", "(Exists #<_x>g)"),
        ("X s i n [0]", "(Sin 0)"),
        ("X[1 * * 2]", "(Pow 1 2)"),
    ];
    for (text, expected) in cases {
        let b = clean(text, NGC);
        assert_eq!(word_tree(&b, 0), expected, "{text}");
    }
}

#[test]
fn expression_spans() {
    let b = clean("G1 X[1+2*3] Y2", NGC);
    assert_eq!(b.slice(b.words[1].span), "X[1+2*3]");
    let Value::Expr(root) = b.words[1].value else {
        panic!()
    };
    assert_eq!(b.slice(b.expr_span(root)), "[1+2*3]");
    let ExprNode::Binary(BinOp::Add, one, mul) = *b.expr(root) else {
        panic!()
    };
    assert_eq!(b.slice(b.expr_span(one)), "1");
    assert_eq!(b.slice(b.expr_span(mul)), "2*3");
    // Children come before their parents in the arena.
    for (i, (node, _)) in b.exprs.iter().enumerate() {
        let kids = match *node {
            ExprNode::Unary(_, a) => vec![a],
            ExprNode::Binary(_, l, r) | ExprNode::Atan(l, r) => vec![l, r],
            ExprNode::Param(ParamRef::Numbered(a)) => vec![a],
            _ => vec![],
        };
        assert!(kids.iter().all(|k| (k.0 as usize) < i));
    }
    let b = clean("X atan[1]/[1]", NGC);
    let Value::Expr(root) = b.words[0].value else {
        panic!()
    };
    assert_eq!(b.slice(b.expr_span(root)), "atan[1]/[1]");
}

#[test]
fn parameters() {
    let b = clean(
        "G1 X#5 Y#<zwork offset> Z#<_global> A##2 B#[5203 + #5220 * 20]",
        NGC,
    );
    assert_eq!(word_tree(&b, 1), "#5");
    assert_eq!(word_tree(&b, 2), "#<zwork offset>");
    assert_eq!(word_tree(&b, 3), "#<_global>g");
    assert_eq!(word_tree(&b, 4), "##2");
    assert_eq!(word_tree(&b, 5), "#(Add 5203 (Mul #5220 20))");
    assert_eq!(b.slice(b.words[5].span), "B#[5203 + #5220 * 20]");
    let b = clean("X#< _g>", NGC);
    assert_eq!(word_tree(&b, 0), "#< _g>g");
}

#[test]
fn assignments() {
    let b = clean(
        "#1 = 2 G1 X#1 #<name> = [#1 + 1] #[#1+1] = 3 #<_g>=-#1",
        NGC,
    );
    assert_eq!(b.assignments.len(), 4);
    assert_eq!(words(&b).len(), 2);
    let a = &b.assignments;
    assert_eq!(param(&b, a[0].target), "#1");
    assert_eq!(tree(&b, a[0].value), "2");
    assert_eq!(b.slice(a[0].span), "#1 = 2");
    assert_eq!(param(&b, a[1].target), "#<name>");
    assert_eq!(tree(&b, a[1].value), "(Add #1 1)");
    assert_eq!(b.slice(a[1].span), "#<name> = [#1 + 1]");
    assert_eq!(param(&b, a[2].target), "#(Add #1 1)");
    assert_eq!(tree(&b, a[2].value), "3");
    assert_eq!(param(&b, a[3].target), "#<_g>g");
    assert_eq!(tree(&b, a[3].value), "(Neg #1)");
    let b = clean(
        "#<zworkoffset> = [#[5203 + #5220 * 20] + #5213 * #5210]",
        NGC,
    );
    assert_eq!(
        tree(&b, b.assignments[0].value),
        "(Add #(Add 5203 (Mul #5220 20)) (Mul #5213 #5210))"
    );
    single_error("#1 G1", NGC, "syntax::bad-assignment", 1, "#1");
    single_error("#1 =", NGC, "syntax::missing-value", 1, "#1 =");
    single_error("#<a = 1", NGC, "syntax::bad-parameter", 2, "<a = 1");
    single_error("#<  > = 1", NGC, "syntax::bad-parameter", 2, "<  >");
}

#[test]
fn comments() {
    let b = clean("G1 (plain  text ) X1 ; rest", NGC);
    assert_eq!(words(&b).len(), 2);
    assert_eq!(
        (b.comments[0].kind, b.slice(b.comments[0].text)),
        (CommentKind::Paren, "plain  text ")
    );
    assert_eq!(
        (b.comments[1].kind, b.slice(b.comments[1].text)),
        (CommentKind::Line, " rest")
    );
    for (text, kind, msg) in [
        ("(MSG, hello)", CommentKind::Msg, " hello"),
        ("(msg,hello)", CommentKind::Msg, "hello"),
        ("( Msg , hello )", CommentKind::Msg, " hello "),
        ("(DEBUG, x=#5420)", CommentKind::Debug, " x=#5420"),
        (
            "(debug, after G92 X7: x=#5420)",
            CommentKind::Debug,
            " after G92 X7: x=#5420",
        ),
        ("(PRINT, p)", CommentKind::Print, " p"),
        ("(message, no)", CommentKind::Paren, "message, no"),
        ("(msg no comma)", CommentKind::Paren, "msg no comma"),
        (
            "(швидке переміщення)",
            CommentKind::Paren,
            "швидке переміщення",
        ),
    ] {
        let b = clean(text, NGC);
        assert_eq!(
            (b.comments[0].kind, b.slice(b.comments[0].text)),
            (kind, msg),
            "{text}"
        );
    }
    let b = single_error("G1 X1 (open", NGC, "syntax::unclosed-comment", 7, "(open");
    assert_eq!(words(&b).len(), 2);
    single_error("G1 (a (b) c)", NGC, "syntax::nested-comment", 7, "(");
}

#[test]
fn owords() {
    let cases: Vec<(&str, OKind, &str)> = vec![
        ("o100 sub", OKind::Sub, "o100 sub"),
        ("O100 ENDSUB", OKind::EndSub(None), "O100 ENDSUB"),
        ("o100 else", OKind::Else, "o100 else"),
        ("o100 endif", OKind::EndIf, "o100 endif"),
        ("o100 endwhile", OKind::EndWhile, "o100 endwhile"),
        ("o100 do", OKind::Do, "o100 do"),
        ("o100 endrepeat", OKind::EndRepeat, "o100 endrepeat"),
        ("o100 break", OKind::Break, "o100 break"),
        ("o100 continue", OKind::Continue, "o100 continue"),
        ("o100 return", OKind::Return(None), "o100 return"),
        ("o100 call", OKind::Call(vec![]), "o100 call"),
        ("o100 end sub", OKind::EndSub(None), "o100 end sub"),
    ];
    for (text, kind, span) in cases {
        let b = clean(text, NGC);
        let o = b.oword.as_ref().unwrap();
        assert_eq!(
            (o.label, &o.kind, b.slice(o.span)),
            (OLabel::Number(100), &kind, span),
            "{text}"
        );
    }
    let b = clean("N5 o<my sub> call [1] [#2+1] [3] (call it)", NGC);
    assert_eq!(b.number, Some(5));
    let o = b.oword.as_ref().unwrap();
    let OLabel::Name(name) = o.label else {
        panic!()
    };
    assert_eq!(b.slice(name), "my sub");
    let OKind::Call(args) = &o.kind else { panic!() };
    let args: Vec<String> = args.iter().map(|&a| tree(&b, a)).collect();
    assert_eq!(args, ["1", "(Add #2 1)", "3"]);
    assert_eq!(b.slice(o.span), "o<my sub> call [1] [#2+1] [3]");
    assert_eq!(b.slice(b.comments[0].text), "call it");

    for (text, expected) in [
        ("o1 if [#1 GT 2]", "(Gt #1 2)"),
        ("o1 elseif [#1 LT 2]", "(Lt #1 2)"),
        ("o1 while [#1 LE 5] ; loop", "(Le #1 5)"),
        ("o1 repeat [3]", "3"),
        ("o1 endsub [#1*2]", "(Mul #1 2)"),
        ("o1 return [0]", "0"),
    ] {
        let b = clean(text, NGC);
        let o = b.oword.as_ref().unwrap();
        let id = match o.kind {
            OKind::If(e) | OKind::ElseIf(e) | OKind::While(e) | OKind::Repeat(e) => e,
            OKind::EndSub(Some(e)) | OKind::Return(Some(e)) => e,
            ref k => panic!("{k:?}"),
        };
        assert_eq!(tree(&b, id), expected, "{text}");
    }
}

#[test]
fn oword_errors() {
    single_error("o100 if", NGC, "syntax::bad-oword", 6, "if");
    single_error("o100 frobnicate", NGC, "syntax::bad-oword", 6, "frobnicate");
    single_error("o100", NGC, "syntax::missing-value", 5, "");
    single_error("o100 sub G1", NGC, "syntax::unexpected-character", 10, "G");
    single_error(
        "o100 sub o200 sub",
        NGC,
        "syntax::unexpected-character",
        10,
        "o",
    );
    single_error("G1 o100 sub", NGC, "syntax::bad-oword", 4, "o");
    single_error("o sub", NGC, "syntax::bad-oword", 1, "o");
    single_error("o[1] call", NGC, "syntax::bad-oword", 1, "o[");
    single_error("o<x call", NGC, "syntax::bad-oword", 2, "<x call");
    single_error(
        "o99999999999 sub",
        NGC,
        "syntax::bad-oword",
        1,
        "o99999999999",
    );
}

#[test]
fn expression_errors() {
    single_error("G1 X[1+2", NGC, "syntax::unbalanced-brackets", 5, "[");
    // Blanks are deleted before reading, as LinuxCNC does: `1 2 3` is 123.
    assert_eq!(word_tree(&clean("G1 X[1 2 3]", NGC), 1), "123");
    single_error("G1 X[1 ? 2]", NGC, "syntax::unknown-operation", 8, "?");
    single_error("G1 X1]", NGC, "syntax::unbalanced-brackets", 6, "]");
    single_error("G1 X[foo[1]]", NGC, "syntax::unknown-word", 6, "foo");
    single_error("G1 X sin 30", NGC, "syntax::bad-function", 6, "sin");
    single_error("G1 X atan[1]", NGC, "syntax::bad-function", 6, "atan[1]");
    single_error("G1 X atan[1]/2", NGC, "syntax::bad-function", 6, "atan[1]/");
    single_error(
        "G1 X[exists[#1]]",
        NGC,
        "syntax::bad-function",
        6,
        "exists[#",
    );
    single_error("G1 X Y1", NGC, "syntax::missing-value", 4, "X");
    single_error("G1 X", NGC, "syntax::missing-value", 4, "X");
    single_error("G1 X-", NGC, "syntax::missing-value", 6, "");
    // `@` and `^` are LinuxCNC's polar words: they need a value like any other.
    single_error("G1 X1 @", NGC, "syntax::missing-value", 7, "@");
    single_error("G1 X1 ~", NGC, "syntax::unexpected-character", 7, "~");
    single_error("G1 X1-2", NGC, "syntax::unexpected-character", 6, "-");
    let b = single_error("G1 X1 Y[", NGC, "syntax::missing-value", 9, "");
    assert_eq!(words(&b).len(), 2, "words before the error are kept");
}

#[test]
fn deep_nesting_is_bounded() {
    for text in [
        format!("X{}1{}", "[".repeat(100_000), "]".repeat(100_000)),
        format!("X{}1", "-".repeat(100_000)),
        format!("X{}1", "#".repeat(100_000)),
        format!("X{}", "sin[".repeat(100_000)),
        "[".repeat(100_000),
    ] {
        let (_, d) = one(&text, NGC);
        assert_eq!(d.len(), 1);
        assert!(d[0].is_error());
    }
    let text = format!("X{}1{}", "[".repeat(60), "]".repeat(60));
    assert_eq!(word_tree(&clean(&text, NGC), 0), "1");
    let (_, d) = one(&format!("X{}1{}", "[".repeat(100), "]".repeat(100)), NGC);
    assert_eq!(d[0].code.to_string(), "syntax::expression-too-deep");
}

#[test]
fn unary_fn_variants_exist() {
    // Keep the test above honest: every UnaryFn the parser can produce is reachable.
    let b = clean("X[-#1 + +#2]", NGC);
    assert_eq!(word_tree(&b, 0), "(Add (Neg #1) (Plus #2))");
    let _ = (UnaryFn::Neg, UnaryFn::Plus);
}
