//! AxiOMA dialect: one test per construct, with exact addresses, values and spans.

mod common;

use common::*;
use stanok_canon::Severity;
use stanok_syntax::{Address, BlockParser, CommentKind, Dialect, Keyword, Value};

const AX: Dialect = Dialect::Axioma;

fn kw(keyword: Keyword) -> Address {
    Address::Keyword {
        keyword,
        index: None,
    }
}

fn kwi(keyword: Keyword, index: u8) -> Address {
    Address::Keyword {
        keyword,
        index: Some(index),
    }
}

fn idx(letter: char, index: u8) -> Address {
    Address::Indexed {
        letter: letter as u8,
        index,
    }
}

#[test]
fn word_forms() {
    let b = clean("X105.5 X.5 X-.5 X+05.50 X10 G0 G01", AX);
    assert_eq!(
        words(&b),
        vec![
            (l('X'), n(105.5), "X105.5"),
            (l('X'), n(0.5), "X.5"),
            (l('X'), n(-0.5), "X-.5"),
            (l('X'), n(5.5), "X+05.50"),
            (l('X'), n(10.0), "X10"),
            (l('G'), n(0.0), "G0"),
            (l('G'), n(1.0), "G01"),
        ]
    );
}

#[test]
fn words_without_spaces_and_lower_case() {
    let b = clean("G01X10Y20", AX);
    assert_eq!(
        words(&b),
        vec![
            (l('G'), n(1.0), "G01"),
            (l('X'), n(10.0), "X10"),
            (l('Y'), n(20.0), "Y20")
        ]
    );
    let b = clean("g1x-1.5f1800", AX);
    assert_eq!(
        words(&b),
        vec![
            (l('G'), n(1.0), "g1"),
            (l('X'), n(-1.5), "x-1.5"),
            (l('F'), n(1800.0), "f1800")
        ]
    );
    // A number ending in a point runs into the next keyword (corpus: `Z95.PL=1`).
    let b = clean("Z95.PL=1", AX);
    assert_eq!(
        words(&b),
        vec![(l('Z'), n(95.0), "Z95."), (kw(Keyword::Pl), n(1.0), "PL=1")]
    );
}

#[test]
fn missing_and_bad_numbers() {
    let b = single_error("G1 X Y2", AX, "syntax::missing-value", 4, "X");
    assert_eq!(
        words(&b),
        vec![(l('G'), n(1.0), "G1"), (l('Y'), n(2.0), "Y2")]
    );
    let b = single_error("G1 X- Y2", AX, "syntax::bad-number", 4, "X-");
    assert_eq!(words(&b).len(), 2);
    single_error("X.", AX, "syntax::bad-number", 1, "X.");
    single_error("G1 X", AX, "syntax::missing-value", 4, "X");
}

#[test]
fn block_numbers() {
    let b = clean("N10 G1", AX);
    assert_eq!(b.number, Some(10));
    assert_eq!(b.slice(b.number_span.unwrap()), "N10");
    assert_eq!(words(&b), vec![(l('G'), n(1.0), "G1")]);
    let b = clean("  n05 G1", AX);
    assert_eq!(
        (b.number, b.slice(b.number_span.unwrap())),
        (Some(5), "n05")
    );
    let b = clean(":10 G1", AX);
    assert_eq!(
        (b.number, b.slice(b.number_span.unwrap())),
        (Some(10), ":10")
    );
    let b = clean("N10G1", AX);
    assert_eq!(
        (b.number, words(&b)),
        (Some(10), vec![(l('G'), n(1.0), "G1")])
    );
    // The same label twice is fine: labels, not unique keys.
    let (p, d) = stanok_syntax::parse("N20 G1\nN20 G0\n", AX);
    assert!(d.is_empty());
    assert_eq!(p.blocks[0].number, p.blocks[1].number);
    single_error("N1.5 G1", AX, "syntax::bad-number", 1, "N1.5");
    single_error(
        "N99999999999 G1",
        AX,
        "syntax::bad-number",
        1,
        "N99999999999",
    );
}

#[test]
fn n_inside_a_block_is_a_word() {
    let b = clean("G28 G90 X1000.0 Y500.0 N1", AX);
    assert_eq!(b.number, None);
    assert_eq!(words(&b)[4], (l('N'), n(1.0), "N1"));
    let b = clean("M903 N1=1", AX);
    assert_eq!(words(&b)[1], (idx('N', 1), n(1.0), "N1=1"));
    // `N1=` first on the line is an indexed word too, not a label.
    let b = clean("N1=3 M905", AX);
    assert_eq!(b.number, None);
    assert_eq!(words(&b)[0], (idx('N', 1), n(3.0), "N1=3"));
    let b = clean("N130 G110 N256000 Q1=6", AX);
    assert_eq!(b.number, Some(130));
    assert_eq!(words(&b)[1], (l('N'), n(256000.0), "N256000"));
}

#[test]
fn extended_addresses() {
    let b = clean("S2=1000 T2=3 D2=1 A3=0.5 H1=1 Q5=1 Q11=-45", AX);
    assert_eq!(
        words(&b),
        vec![
            (idx('S', 2), n(1000.0), "S2=1000"),
            (idx('T', 2), n(3.0), "T2=3"),
            (idx('D', 2), n(1.0), "D2=1"),
            (idx('A', 3), n(0.5), "A3=0.5"),
            (idx('H', 1), n(1.0), "H1=1"),
            (idx('Q', 5), n(1.0), "Q5=1"),
            (idx('Q', 11), n(-45.0), "Q11=-45"),
        ]
    );
    let b = clean("G96 S2 = 100 S3 =1000 S2000", AX);
    assert_eq!(
        words(&b)[1..],
        [
            (idx('S', 2), n(100.0), "S2 = 100"),
            (idx('S', 3), n(1000.0), "S3 =1000"),
            (l('S'), n(2000.0), "S2000"),
        ]
    );
    // `F=` without an index is the plain letter.
    let b = clean("F=1000", AX);
    assert_eq!(words(&b), vec![(l('F'), n(1000.0), "F=1000")]);
    let b = single_error("S300=1 X1", AX, "syntax::bad-number", 1, "S300");
    assert_eq!(words(&b), vec![(l('X'), n(1.0), "X1")]);
    single_error("S2= M3", AX, "syntax::missing-value", 1, "S2=");
}

#[test]
fn modal_keywords_and_aliases() {
    let cases = [
        ("BRISK", Keyword::Brisk),
        ("SOFT", Keyword::Soft),
        ("TRAORI", Keyword::Traori),
        ("TRAFOFF", Keyword::TrafOff),
        ("TRAF0FF", Keyword::TrafOff),
        ("TRAFOOF", Keyword::TrafOff),
        ("TRAFFOFF", Keyword::TrafOff),
        ("ORIEULER", Keyword::OriEuler),
        ("ORIRPY", Keyword::OriRpy),
        ("ORIAXES", Keyword::OriAxes),
        ("ORIAxes", Keyword::OriAxes),
        ("ORIXES", Keyword::OriAxes),
        ("ORIVECT", Keyword::OriVect),
        ("ORIWKS", Keyword::OriWks),
        ("ORIMKS", Keyword::OriMks),
        ("ORIIMKS", Keyword::OriMks),
        ("CUT2DF", Keyword::Cut2df),
        ("CUT3DC", Keyword::Cut3dc),
        ("CUT3DCC", Keyword::Cut3dcc),
        ("CUT3DCCD", Keyword::Cut3dccd),
        ("CUT3DF", Keyword::Cut3df),
        ("CUT3DFS", Keyword::Cut3dfs),
        ("CUT3DFF", Keyword::Cut3dff),
        ("CUT3DFE", Keyword::Cut3dff),
        ("cut3dff", Keyword::Cut3dff),
        ("ASPLINE", Keyword::Aspline),
        ("BSPLINE", Keyword::Bspline),
        ("CSPLINE", Keyword::Cspline),
        ("SPLBREAK", Keyword::Splbreak),
        ("brisk", Keyword::Brisk),
    ];
    for (text, k) in cases {
        let line = format!("N1 {text} G1");
        let b = clean(&line, AX);
        assert_eq!(
            words(&b),
            vec![(kw(k), Value::None, text), (l('G'), n(1.0), "G1")],
            "{text}"
        );
    }
    let b = clean(
        "G53 G153 G193 G64 BRISK CUT2DF ORIAxes // Строка безопасности",
        AX,
    );
    assert_eq!(b.words.len(), 7);
    assert_eq!(b.comments[0].kind, CommentKind::Line);
    assert_eq!(b.slice(b.comments[0].text), " Строка безопасности");
}

#[test]
fn a_keyword_must_end_at_a_non_letter() {
    let b = single_error("BRISKX10 G1", AX, "syntax::unknown-word", 1, "BRISKX10");
    assert_eq!(words(&b), vec![(l('G'), n(1.0), "G1")]);
    // A digit ends the keyword; the digit is then a number without an address.
    let b = single_error("SOFT1", AX, "syntax::unexpected-character", 5, "1");
    assert_eq!(words(&b), vec![(kw(Keyword::Soft), Value::None, "SOFT")]);
}

#[test]
fn value_keywords() {
    let b = clean(
        "CR=-30 PW=2 PL=.10 SD=3 LMAXS 5000 LMAXS2=4500 LMINS 150 LMINS3=200 REFAX 3 LEAD=10 TILT 5 ISD=20 CR = 4",
        AX,
    );
    assert_eq!(
        words(&b),
        vec![
            (kw(Keyword::Cr), n(-30.0), "CR=-30"),
            (kw(Keyword::Pw), n(2.0), "PW=2"),
            (kw(Keyword::Pl), n(0.1), "PL=.10"),
            (kw(Keyword::Sd), n(3.0), "SD=3"),
            (kw(Keyword::Lmaxs), n(5000.0), "LMAXS 5000"),
            (kwi(Keyword::Lmaxs, 2), n(4500.0), "LMAXS2=4500"),
            (kw(Keyword::Lmins), n(150.0), "LMINS 150"),
            (kwi(Keyword::Lmins, 3), n(200.0), "LMINS3=200"),
            (kw(Keyword::Refax), n(3.0), "REFAX 3"),
            (kw(Keyword::Lead), n(10.0), "LEAD=10"),
            (kw(Keyword::Tilt), n(5.0), "TILT 5"),
            (kw(Keyword::Isd), n(20.0), "ISD=20"),
            (kw(Keyword::Cr), n(4.0), "CR = 4"),
        ]
    );
    let b = clean("N20 G3 X17.203 Y38.029 CR=34.913 S1200 F500", AX);
    assert_eq!(words(&b)[3], (kw(Keyword::Cr), n(34.913), "CR=34.913"));
    let b = single_error("G2 CR= X1", AX, "syntax::missing-value", 4, "CR=");
    assert_eq!(words(&b).len(), 2);
    single_error("LMAXS300=1", AX, "syntax::bad-number", 1, "LMAXS300");
    single_error("LEAD X1", AX, "syntax::missing-value", 1, "LEAD");
}

#[test]
fn feed_and_speed_tables() {
    let b = clean("N10 G90 G01 X50 F=FTABLE(20) // подача", AX);
    assert_eq!(words(&b)[3], (kw(Keyword::Ftable), n(20.0), "F=FTABLE(20)"));
    let b = clean("N10 S=STABLE(2) M3", AX);
    assert_eq!(words(&b)[0], (kw(Keyword::Stable), n(2.0), "S=STABLE(2)"));
    let b = clean("N10 S2=STABLE(20) M203", AX);
    assert_eq!(
        words(&b)[0],
        (kwi(Keyword::Stable, 2), n(20.0), "S2=STABLE(20)")
    );
    let b = clean("F = ftable [ 3 ] X1", AX);
    assert_eq!(
        words(&b),
        vec![
            (kw(Keyword::Ftable), n(3.0), "F = ftable [ 3 ]"),
            (l('X'), n(1.0), "X1")
        ]
    );
    single_error("F=FTABLE(#1)", AX, "syntax::bad-number", 1, "F=FTABLE(#1)");
    single_error("F=FTABLE", AX, "syntax::bad-number", 1, "F=FTABLE");
    single_error("G1 FTABLE(3)", AX, "syntax::misplaced-word", 4, "FTABLE(3)");
    // Any other form is a high-level-language expression, evaluated by the interpreter.
    let b = clean("F=STABLE(2)", AX);
    assert!(matches!(b.words[0].value, Value::Hll(_)));
}

#[test]
fn unknown_words_are_skipped() {
    let b = single_error("G1 FOO X1", AX, "syntax::unknown-word", 4, "FOO");
    assert_eq!(
        words(&b),
        vec![(l('G'), n(1.0), "G1"), (l('X'), n(1.0), "X1")]
    );
    let b = single_error("G1 XYZ=5 M3", AX, "syntax::unknown-word", 4, "XYZ=5");
    assert_eq!(words(&b).len(), 2);
    // The same first on a line reads as a high-level-language assignment, which must end
    // with `;` as in C.
    single_error("N10 XYZ=5 M3", AX, "hll::syntax", 11, "M3");
}

#[test]
fn high_level_language_lines_are_statements() {
    use stanok_syntax::hll::{HExpr, HItem, HType};
    for (text, kinds) in [
        ("int ii=0;", "D"),
        ("for(ii=1; ii<8; ii++)", "F"),
        ("{", "{"),
        ("    }  ", "}"),
        ("string str;          //создание переменной", "D"),
        ("long num = 50;      // создание", "D"),
        (
            "sprintf (str, \"value: %d\", num); //форматирование строки",
            "E",
        ),
        ("ii++;", "E"),
        ("kk += 1; kk <<= 2; kk |= 1;", "EEE"),
        ("i++;", "E"),
        ("$iPerm[1] = 5;", "E"),
        ("} else if (a >= 2 && !b) { x = a ? 1 : 2; }", "}LI{E}"),
        ("do { k += 2; } while (k < 7);", "O{E}W"),
        ("while (k > 0) k--;", "WE"),
        ("break; continue; ;", "BC;"),
        ("double p[3] = {1, 2.5, -3}, q;", "D"),
    ] {
        let b = clean(text, AX);
        assert!(b.hll().statement && b.words.is_empty(), "{text}");
        let got: String = b
            .hll()
            .items
            .iter()
            .map(|(i, _)| match i {
                HItem::Decl { .. } => 'D',
                HItem::Expr(_) => 'E',
                HItem::If(_) => 'I',
                HItem::Else => 'L',
                HItem::While { .. } => 'W',
                HItem::Do => 'O',
                HItem::For { .. } => 'F',
                HItem::Open => '{',
                HItem::Close => '}',
                HItem::Break => 'B',
                HItem::Continue => 'C',
                HItem::Empty => ';',
            })
            .collect();
        assert_eq!(got, kinds, "{text}");
        if text.contains("//") {
            assert_eq!(b.comments.len(), 1);
            assert_eq!(b.comments[0].kind, CommentKind::Line);
        }
    }
    // Precedence: `1 + 2 * 3 == 7` is `(1 + (2 * 3)) == 7`.
    let b = clean("xx = 1 + 2 * 3 == 7;", AX);
    let HItem::Expr(root) = &b.hll().items[0].0 else {
        panic!()
    };
    let HExpr::Assign(None, _, value) = b.hll().expr(*root) else {
        panic!()
    };
    assert_eq!(b.slice(b.hll().expr_span(*value)), "1 + 2 * 3 == 7");
    let HExpr::Binary(op, lhs, _) = b.hll().expr(*value) else {
        panic!()
    };
    assert_eq!(op.symbol(), "==");
    assert_eq!(b.slice(b.hll().expr_span(*lhs)), "1 + 2 * 3");
    let b = clean("const double d[2];", AX);
    assert!(
        matches!(&b.hll().items[0].0, HItem::Decl { ty: HType::Double, vars } if vars[0].len.is_some())
    );
    // Expression values of ISO words end where the expression ends.
    let b = clean("G1 X=ii * 10 Y=$iPerm[1] (c) F=FTABLE(n+1) Z2", AX);
    let spans: Vec<&str> = b.words.iter().map(|w| b.slice(w.span)).collect();
    assert_eq!(
        spans,
        ["G1", "X=ii * 10", "Y=$iPerm[1]", "F=FTABLE(n+1)", "Z2"]
    );
    assert_eq!(b.comments.len(), 1);
    // `X=ii (comment)`: a blank before `(` in a word value is no call.
    let b = clean("X=ii (comment) ; more", AX);
    assert_eq!(b.comments.len(), 2);
    let b = clean("N10 MSG(str)        // выдача", AX);
    assert!(b.hll().message.is_some() && b.message.is_none());
    let b = clean("MSG(\"a\" + s)", AX);
    assert!(b.hll().message.is_some());
    // Errors: one diagnostic with its span, the rest of the line skipped.
    single_error("int x = ;", AX, "hll::syntax", 9, ";");
    single_error("xx = 1", AX, "hll::syntax", 7, "");
    single_error("s = \"open;", AX, "syntax::unclosed-string", 5, "\"open;");
    single_error("for (i = 0; i < 3) {", AX, "hll::syntax", 18, ")");
    single_error("switch (a) {", AX, "hll::unsupported", 1, "switch");
    single_error("ii++ = 3;", AX, "hll::not-assignable", 1, "ii++");
    single_error("G1 X=(a", AX, "hll::syntax", 8, "");
    let b = clean("G1 X=(a+b)*2 Y1", AX);
    assert_eq!(b.slice(b.words[1].span), "X=(a+b)*2");
    // A `/*` in an HLL line still opens a multi-line comment, also after an error.
    for first in ["int a; /* open", "int = 1; /* open"] {
        let mut parser = BlockParser::new(AX);
        let mut block = stanok_syntax::Block::default();
        let mut diags = Vec::new();
        parser.parse_line(first, 1, 0, &mut block, &mut diags);
        parser.parse_line("G1 X1", 2, 15, &mut block, &mut diags);
        assert!(block.words.is_empty(), "{first}");
    }
}

#[test]
fn messages() {
    let b = clean("N30 MSG(\"Tool T3 is active\")", AX);
    assert_eq!(b.slice(b.message.unwrap()), "Tool T3 is active");
    assert_eq!(b.message.unwrap().start, 9);
    let b = clean("N70 MSG()", AX);
    let m = b.message.unwrap();
    assert_eq!((m.start, m.end), (8, 8));
    let b = clean("msg ( \"a (b) ; c\" ) G1", AX);
    assert_eq!(b.slice(b.message.unwrap()), "a (b) ; c");
    assert_eq!(words(&b), vec![(l('G'), n(1.0), "G1")]);
    single_error("MSG(\"open", AX, "syntax::unclosed-string", 5, "\"open");
    single_error("MSG \"x\"", AX, "syntax::bad-message", 1, "MSG");
    // After the string, anything but `)` continues an expression (`MSG("a" + s)`).
    single_error("MSG(\"x\" G1", AX, "hll::syntax", 9, "G1");
}

#[test]
fn comments() {
    let b = clean("N10 G1 (Параметры: X100) X1 ; конец", AX);
    assert_eq!(words(&b).len(), 2);
    assert_eq!(b.comments.len(), 2);
    assert_eq!(b.comments[0].kind, CommentKind::Paren);
    assert_eq!(b.slice(b.comments[0].text), "Параметры: X100");
    assert_eq!(b.comments[1].kind, CommentKind::Line);
    assert_eq!(b.slice(b.comments[1].text), " конец");

    let b = clean("  * Выходные инструкции G1 X1", AX);
    assert!(b.words.is_empty());
    assert_eq!(
        (b.comments[0].kind, b.slice(b.comments[0].text)),
        (CommentKind::Line, " Выходные инструкции G1 X1")
    );
    let b = clean("G1 X1 // c", AX);
    assert_eq!(b.slice(b.comments[0].text), " c");
    let b = clean("N15 G54 /*Параметры: X100 и Y100*/ X1", AX);
    assert_eq!(words(&b).len(), 2);
    assert_eq!(
        (b.comments[0].kind, b.slice(b.comments[0].text)),
        (CommentKind::Block, "Параметры: X100 и Y100")
    );
    let b = clean("% PROGRAM 1", AX);
    assert_eq!(
        (b.comments[0].kind, b.slice(b.comments[0].text)),
        (CommentKind::Header, " PROGRAM 1")
    );
    // Column in characters, after Cyrillic text.
    let b = single_error(
        "(Ж) G1 X1 (open",
        AX,
        "syntax::unclosed-comment",
        11,
        "(open",
    );
    assert_eq!(words(&b).len(), 2);
    let (_, d) = one("(Ж) G1 X1 (open", AX);
    assert_eq!(
        d[0].message,
        "unclosed comment: `(` has no `)` on this line"
    );
    assert_eq!(d[0].span.start, 11); // bytes: Ж is two
    single_error("G1 * X1", AX, "syntax::unexpected-character", 4, "*");
    single_error("G1 % X1", AX, "syntax::unexpected-character", 4, "%");
}

#[test]
fn block_comments_across_lines() {
    let mut parser = BlockParser::new(AX);
    let mut block = stanok_syntax::Block::default();
    let mut diags = Vec::new();
    parser.parse_line("G1 X1 /* начало", 1, 0, &mut block, &mut diags);
    assert_eq!(words(&block).len(), 2);
    assert_eq!(block.slice(block.comments[0].text), " начало");
    parser.parse_line("G0 X99 ; still comment", 2, 20, &mut block, &mut diags);
    assert!(block.words.is_empty());
    assert_eq!(block.comments[0].kind, CommentKind::Block);
    assert_eq!(
        block.slice(block.comments[0].text),
        "G0 X99 ; still comment"
    );
    parser.parse_line("  end */ N5 G2 X3", 3, 40, &mut block, &mut diags);
    assert_eq!(block.slice(block.comments[0].text), "  end ");
    assert_eq!(block.number, Some(5));
    assert_eq!(
        words(&block),
        vec![(l('G'), n(2.0), "G2"), (l('X'), n(3.0), "X3")]
    );
    parser.parse_line("G1 X4", 4, 60, &mut block, &mut diags);
    assert_eq!(words(&block).len(), 2);
    assert!(diags.is_empty(), "{diags:#?}");
}

#[test]
fn block_skip_is_ignored_with_a_warning() {
    let (b, d) = one("/N10 G1 X1", AX);
    assert!(b.block_delete);
    assert_eq!(b.number, Some(10));
    assert_eq!(words(&b).len(), 2);
    let d = single(&d, "syntax::block-skip-ignored", Severity::Warning, 1);
    assert_eq!(
        d.message,
        "`/` block skip is not supported by AxiOMA: ignored, block executed"
    );
    let (b, d) = one("   / G1", AX);
    assert!(b.block_delete);
    single(&d, "syntax::block-skip-ignored", Severity::Warning, 4);
    // `//` and `/*` are comments, not a skip.
    assert!(!clean("// G1", AX).block_delete);
    assert!(!clean("/* G1 */ G1", AX).block_delete);
    let b = single_error("G1 / X1", AX, "syntax::unexpected-character", 4, "/");
    assert_eq!(words(&b).len(), 2);
}

#[test]
fn colons_are_ignored() {
    let b = clean("G1 : X1:Y2", AX);
    assert_eq!(words(&b).len(), 3);
}

#[test]
fn unexpected_characters_are_one_error_per_run() {
    let b = single_error("G1 @@# X1", AX, "syntax::unexpected-character", 4, "@@#");
    assert_eq!(words(&b).len(), 2);
    let b = single_error("G1 10 X1", AX, "syntax::unexpected-character", 4, "10");
    assert_eq!(words(&b).len(), 2);
    let b = single_error("G1 Жж X1", AX, "syntax::unexpected-character", 4, "Жж");
    assert_eq!(words(&b).len(), 2);
}

#[test]
fn trailing_carriage_return_is_dropped() {
    let b = clean("G1 X1\r", AX);
    assert_eq!(b.text, "G1 X1");
    assert_eq!(words(&b).len(), 2);
}

#[test]
fn block_is_reset_between_lines() {
    let mut parser = BlockParser::new(AX);
    let mut block = stanok_syntax::Block::default();
    let mut diags = Vec::new();
    parser.parse_line("/N1 G1 X1 MSG(\"a\") (c)", 1, 0, &mut block, &mut diags);
    parser.parse_line("Y2", 2, 30, &mut block, &mut diags);
    assert_eq!(block.text, "Y2");
    assert_eq!((block.line, block.offset), (2, 30));
    assert_eq!(block.number, None);
    assert!(!block.block_delete && block.message.is_none() && block.comments.is_empty());
    assert_eq!(words(&block), vec![(l('Y'), n(2.0), "Y2")]);
    // Spans of diagnostics are absolute.
    diags.clear();
    parser.parse_line("G1 X", 7, 100, &mut block, &mut diags);
    assert_eq!(
        (
            diags[0].span.line,
            diags[0].span.start,
            diags[0].span.column
        ),
        (7, 103, 4)
    );
}

#[test]
fn hll_nesting_is_bounded_with_a_diagnostic() {
    // 60 levels are fine; past 64 (brackets, unary operators, in statements and in word values)
    // one `hll::too-deep` and no deeper recursion, however long the line.
    clean(
        &format!("int a = {}1{};", "(".repeat(60), ")".repeat(60)),
        AX,
    );
    for text in [
        format!("int a = {}1{};", "(".repeat(70), ")".repeat(70)),
        format!("int a = {}1;", "-".repeat(10_000)),
        format!("G1 X={}", "(".repeat(100_000)),
        format!("MSG({}\"x\")", "!".repeat(500)),
    ] {
        let (_, diags) = one(&text, AX);
        assert_eq!(diags.len(), 1, "{diags:?}");
        assert_eq!(diags[0].code.to_string(), "hll::too-deep");
        assert!(diags[0].message.contains("64"), "{}", diags[0].message);
    }
}
