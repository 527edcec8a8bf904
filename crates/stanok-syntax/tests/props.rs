//! Property tests: no input panics; spans stay inside the text; generated lines round-trip;
//! BlockReader and `parse` agree and `seek` reproduces blocks.

mod common;

use proptest::prelude::*;
use stanok_canon::Diagnostic;
use stanok_syntax::{
    parse, Address, Block, BlockParser, BlockReader, ColSpan, Dialect, ExprNode, OKind, OLabel,
    ParamRef, Value,
};
use std::io::Cursor;

const DIALECTS: [Dialect; 2] = [Dialect::Axioma, Dialect::Rs274ngc];

fn span_ok(b: &Block, c: ColSpan) -> bool {
    c.start <= c.end
        && (c.end as usize) <= b.text.len()
        && b.text.is_char_boundary(c.start as usize)
        && b.text.is_char_boundary(c.end as usize)
}

fn param_ok(b: &Block, p: ParamRef, limit: usize) -> bool {
    match p {
        ParamRef::Numbered(id) => (id.0 as usize) < limit,
        ParamRef::Named { name, .. } => span_ok(b, name),
    }
}

/// Every span in range and on character boundaries; every expression id valid, children first.
fn check(b: &Block, diags: &[Diagnostic]) -> Result<(), TestCaseError> {
    for w in &b.words {
        prop_assert!(span_ok(b, w.span), "{w:?}");
        if let Value::Expr(id) = w.value {
            prop_assert!((id.0 as usize) < b.exprs.len());
        }
    }
    for c in &b.comments {
        prop_assert!(span_ok(b, c.text), "{c:?}");
    }
    if let Some(m) = b.message {
        prop_assert!(span_ok(b, m));
    }
    if let Some(s) = b.number_span {
        prop_assert!(span_ok(b, s));
    }
    for a in &b.assignments {
        prop_assert!(span_ok(b, a.span));
        prop_assert!((a.value.0 as usize) < b.exprs.len());
        prop_assert!(param_ok(b, a.target, b.exprs.len()));
    }
    if let Some(o) = &b.oword {
        prop_assert!(span_ok(b, o.span));
        if let OLabel::Name(n) = o.label {
            prop_assert!(span_ok(b, n));
        }
        if let OKind::Call(args) = &o.kind {
            prop_assert!(args.iter().all(|a| (a.0 as usize) < b.exprs.len()));
        }
    }
    for (i, (node, span)) in b.exprs.iter().enumerate() {
        prop_assert!(span_ok(b, *span));
        let ok = match *node {
            ExprNode::Number(_) => true,
            ExprNode::Param(p) | ExprNode::Exists(p) => param_ok(b, p, i),
            ExprNode::Unary(_, a) => (a.0 as usize) < i,
            ExprNode::Binary(_, l, r) | ExprNode::Atan(l, r) => {
                (l.0 as usize) < i && (r.0 as usize) < i
            }
        };
        prop_assert!(ok, "node {i} {node:?}");
    }
    let end = b.offset + b.text.len() as u64;
    for d in diags {
        prop_assert!(d.span.start >= b.offset && d.span.end <= end, "{d:?}");
        prop_assert_eq!(d.span.line, b.line);
        prop_assert!(d.span.column >= 1);
    }
    Ok(())
}

/// Parses `lines` with one parser per dialect (cross-line state included) and checks every block.
fn parse_and_check(lines: &[String]) -> Result<(), TestCaseError> {
    for dialect in DIALECTS {
        let mut parser = BlockParser::new(dialect);
        let mut block = Block::default();
        let mut offset = 0;
        for (i, line) in lines.iter().enumerate() {
            let mut diags = Vec::new();
            parser.parse_line(line, i as u32 + 1, offset, &mut block, &mut diags);
            check(&block, &diags)?;
            offset += line.len() as u64 + 1;
        }
    }
    Ok(())
}

const SOUP: &[&str] = &[
    "G1",
    "G01",
    "X-1.5",
    "Y.5",
    "Z",
    "x",
    "N10",
    "N",
    ":",
    "/",
    "//",
    "/*",
    "*/",
    "*",
    "%",
    ";",
    "(",
    ")",
    "(MSG,",
    "[",
    "]",
    "#",
    "#<",
    "<",
    ">",
    "#<_a>",
    "=",
    "==",
    "S2=",
    "S2",
    "CR=",
    "LMAXS",
    "LMAXS2",
    "REFAX",
    "BRISK",
    "TRAF0FF",
    "CUT3DCCD",
    "CUT",
    "MSG(",
    "MSG",
    "\"",
    "\"x\"",
    "FTABLE(",
    "STABLE[",
    "F=",
    "$",
    "$iPerm[1]",
    "{",
    "}",
    "int",
    "for(",
    "sprintf",
    "o100",
    "o<",
    "sub",
    "endsub",
    "call",
    "if",
    "elseif",
    "while",
    "do",
    "repeat",
    "return",
    "sin",
    "atan",
    "exists",
    "**",
    "+",
    "-",
    ".",
    "..",
    "1",
    "123456789012345678901234",
    "0.000001",
    "mod",
    "eq",
    "and",
    " ",
    "  ",
    "\t",
    "Ж",
    "é",
    "\u{FFFD}",
    "\r",
    "+-",
    "e5",
    "@",
    "&",
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

proptest! {
    #![proptest_config(ProptestConfig { cases: ProptestConfig::default().cases.max(512), ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_strings_never_panic(lines in proptest::collection::vec(any::<String>(), 1..6)) {
        parse_and_check(&lines)?;
    }

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let lines: Vec<String> = text.split('\n').map(str::to_string).collect();
        parse_and_check(&lines)?;
        for dialect in DIALECTS {
            let mut reader = BlockReader::new(Cursor::new(&bytes[..]), dialect);
            let mut block = Block::default();
            let mut diags = Vec::new();
            while reader.next_block(&mut block, &mut diags).unwrap() {
                prop_assert!(block.text.len() <= bytes.len() * 3);
            }
        }
    }

    #[test]
    fn gcode_word_soup_never_panics(lines in proptest::collection::vec(soup_line(), 1..8)) {
        parse_and_check(&lines)?;
    }

    #[test]
    fn reader_agrees_with_parse_and_seek_replays(
        lines in proptest::collection::vec(soup_line(), 1..8),
        crlf in proptest::collection::vec(any::<bool>(), 8),
        back in 0usize..8,
    ) {
        let mut text = String::new();
        for (i, l) in lines.iter().enumerate() {
            text.push_str(l);
            text.push_str(if crlf[i] { "\r\n" } else { "\n" });
        }
        for dialect in DIALECTS {
            let (program, pdiags) = parse(&text, dialect);
            let mut reader = BlockReader::new(Cursor::new(text.as_bytes()), dialect);
            let mut blocks = Vec::new();
            let mut positions = Vec::new();
            let mut diags = Vec::new();
            let mut block = Block::default();
            loop {
                let pos = reader.position();
                if !reader.next_block(&mut block, &mut diags).unwrap() {
                    break;
                }
                positions.push(pos);
                blocks.push(block.clone());
            }
            prop_assert_eq!(&blocks, &program.blocks);
            prop_assert_eq!(&diags, &pdiags);
            let k = back % blocks.len();
            reader.seek(positions[k]).unwrap();
            for expected in &blocks[k..] {
                prop_assert!(reader.next_block(&mut block, &mut Vec::new()).unwrap());
                prop_assert_eq!(&block, expected);
            }
        }
    }

    #[test]
    fn generated_words_round_trip(
        words in proptest::collection::vec(
            (proptest::sample::select(&b"ABCDEFGHIJKLMPQRSTUVWXYZ"[..]), -1.0e6f64..1.0e6, 0usize..5),
            1..10,
        ),
        spaces in any::<bool>(),
    ) {
        // `{:.*}` prints a decimal with the given digits: no exponent, parses back exactly.
        let mut text = String::new();
        let mut expected = Vec::new();
        for &(letter, value, digits) in &words {
            let written = format!("{:.*}", digits, value);
            let value: f64 = written.parse().unwrap();
            text.push(letter as char);
            text.push_str(&written);
            if spaces {
                text.push(' ');
            }
            expected.push((Address::Letter(letter), Value::Number(value)));
        }
        for dialect in DIALECTS {
            let (b, d) = common::one(&text, dialect);
            prop_assert!(d.is_empty(), "{}: {:?}", text, d);
            let got: Vec<_> = b.words.iter().map(|w| (w.address, w.value)).collect();
            prop_assert_eq!(&got, &expected);
        }
    }
}
