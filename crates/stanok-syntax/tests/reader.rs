//! BlockReader: line endings, offsets, invalid UTF-8, long lines, position/seek.

mod common;

use stanok_syntax::{parse, Block, BlockReader, CommentKind, Dialect, SourcePos, MAX_LINE_BYTES};
use std::io::Cursor;

/// All blocks and diagnostics of `bytes`, read through a BlockReader.
fn read_all(bytes: &[u8], dialect: Dialect) -> (Vec<Block>, Vec<stanok_canon::Diagnostic>) {
    let mut reader = BlockReader::new(Cursor::new(bytes), dialect);
    let mut blocks = Vec::new();
    let mut diags = Vec::new();
    let mut block = Block::default();
    while reader.next_block(&mut block, &mut diags).unwrap() {
        blocks.push(block.clone());
    }
    (blocks, diags)
}

#[test]
fn lf_and_crlf_lines() {
    let text = b"G1 X1\r\nG2 X2\n\r\nG3 X3";
    let (blocks, diags) = read_all(text, Dialect::Axioma);
    assert!(diags.is_empty());
    let summary: Vec<(&str, u32, u64)> = blocks
        .iter()
        .map(|b| (b.text.as_str(), b.line, b.offset))
        .collect();
    assert_eq!(
        summary,
        [
            ("G1 X1", 1, 0),
            ("G2 X2", 2, 7),
            ("", 3, 13),
            ("G3 X3", 4, 15)
        ]
    );
    assert_eq!(blocks[3].words.len(), 2);
    // Offsets point into the file.
    let b = &blocks[1];
    let s = b.span_of(b.words[1].span);
    assert_eq!(&text[s.start as usize..s.end as usize], b"X2");
    assert_eq!((s.line, s.column), (2, 4));
}

#[test]
fn only_one_carriage_return_is_dropped_as_in_parse() {
    // Found by proptest: `parse` and the reader must agree on a line ending `\r\r\n`.
    let text = "G1\r\r\nG2\r\n";
    let (blocks, _) = read_all(text.as_bytes(), Dialect::Rs274ngc);
    let (program, _) = parse(text, Dialect::Rs274ngc);
    assert_eq!(blocks, program.blocks);
    assert_eq!(blocks[0].text, "G1\r");
    assert_eq!(blocks[1].text, "G2");
}

#[test]
fn empty_input_and_final_newline() {
    assert!(read_all(b"", Dialect::Axioma).0.is_empty());
    assert_eq!(read_all(b"\n", Dialect::Axioma).0.len(), 1);
    assert_eq!(read_all(b"G1\n", Dialect::Axioma).0.len(), 1);
    assert_eq!(read_all(b"G1\nG2", Dialect::Axioma).0.len(), 2);
}

#[test]
fn same_blocks_as_parse() {
    let text = "%\n(MSG, a)\r\nG1 X[1+2] #1=3\n\no100 sub\nG0 X1 (open\n";
    let (blocks, diags) = read_all(text.as_bytes(), Dialect::Rs274ngc);
    let (program, pdiags) = parse(text, Dialect::Rs274ngc);
    assert_eq!(blocks, program.blocks);
    assert_eq!(diags, pdiags);
    let text = "G1 /* a\n b */ X1\r\n/ G2\n";
    let (blocks, diags) = read_all(text.as_bytes(), Dialect::Axioma);
    let (program, pdiags) = parse(text, Dialect::Axioma);
    assert_eq!(blocks, program.blocks);
    assert_eq!(diags, pdiags);
}

#[test]
fn invalid_utf8_is_reported_not_fatal() {
    let text = b"G1 X1\nG1 (\xD0\x96\xFF) X2\nG3\n";
    let (blocks, diags) = read_all(text, Dialect::Axioma);
    assert_eq!(blocks.len(), 3);
    assert_eq!(blocks[1].words.len(), 2);
    assert_eq!(blocks[1].slice(blocks[1].comments[0].text), "Ж\u{FFFD}");
    assert_eq!(diags.len(), 1);
    let d = &diags[0];
    assert_eq!(d.code.to_string(), "syntax::invalid-utf8");
    assert_eq!((d.span.line, d.span.column, d.span.start), (2, 6, 6 + 6));
    // Invalid bytes outside a comment: the UTF-8 diagnostic comes first, then the parser's.
    let (_, diags) = read_all(b"G1 \xFF X1", Dialect::Axioma);
    let codes: Vec<String> = diags.iter().map(|d| d.code.to_string()).collect();
    assert_eq!(
        codes,
        ["syntax::invalid-utf8", "syntax::unexpected-character"]
    );
}

#[test]
fn overlong_lines_are_cut() {
    let mut text = b"G1 X1 (".to_vec();
    text.extend(vec![b'a'; MAX_LINE_BYTES + 10]);
    text.extend(b")\nG2 X2\n");
    let (blocks, diags) = read_all(&text, Dialect::Axioma);
    assert_eq!(blocks.len(), 2);
    assert_eq!(blocks[0].text.len(), MAX_LINE_BYTES);
    assert_eq!(blocks[1].line, 2);
    assert_eq!(blocks[1].offset, (text.len() - 6) as u64);
    let codes: Vec<String> = diags.iter().map(|d| d.code.to_string()).collect();
    // The bound first: it is why the comment is left open.
    assert_eq!(codes, ["syntax::line-too-long", "syntax::unclosed-comment"]);
    // A multi-byte character split by the cut is dropped, not reported as invalid UTF-8.
    let mut text = b"(".to_vec();
    text.extend(vec![b'a'; MAX_LINE_BYTES - 2]);
    text.extend("ЖЖ)".as_bytes());
    let (blocks, diags) = read_all(&text, Dialect::Axioma);
    assert_eq!(blocks[0].text.len(), MAX_LINE_BYTES - 1);
    let codes: Vec<String> = diags.iter().map(|d| d.code.to_string()).collect();
    assert_eq!(codes, ["syntax::line-too-long", "syntax::unclosed-comment"]);
}

#[test]
fn seek_back_reparses_a_line_identically() {
    let text = "N10 G1 X1\r\nN20 G2 X2 I1\nN30 G3 X3 (c)\n";
    let mut reader = BlockReader::new(Cursor::new(text.as_bytes()), Dialect::Axioma);
    assert_eq!(reader.position(), SourcePos::start());
    let mut block = Block::default();
    let mut diags = Vec::new();
    assert!(reader.next_block(&mut block, &mut diags).unwrap());
    let second = reader.position();
    assert_eq!((second.offset, second.line), (11, 2));
    assert!(reader.next_block(&mut block, &mut diags).unwrap());
    let first_read = block.clone();
    assert!(reader.next_block(&mut block, &mut diags).unwrap());
    assert!(!reader.next_block(&mut block, &mut diags).unwrap());
    reader.seek(second).unwrap();
    assert_eq!(reader.position(), second);
    assert!(reader.next_block(&mut block, &mut diags).unwrap());
    assert_eq!(block, first_read);
    assert!(reader.next_block(&mut block, &mut diags).unwrap());
    assert_eq!(block.number, Some(30));
    assert_eq!(block.line, 3);
    assert!(diags.is_empty());
}

#[test]
fn seek_restores_the_multiline_comment_state() {
    let text = "G1 X1 /* open\nG0 X99\nstill */ G2 X2\nG3 X3\n";
    let mut reader = BlockReader::new(Cursor::new(text.as_bytes()), Dialect::Axioma);
    assert_eq!(reader.dialect(), Dialect::Axioma);
    let mut block = Block::default();
    let mut diags = Vec::new();
    reader.next_block(&mut block, &mut diags).unwrap();
    let inside = reader.position();
    reader.next_block(&mut block, &mut diags).unwrap();
    let commented = block.clone();
    assert!(commented.words.is_empty());
    assert_eq!(commented.comments[0].kind, CommentKind::Block);
    reader.next_block(&mut block, &mut diags).unwrap();
    let closing = block.clone();
    assert_eq!(closing.words.len(), 2);
    reader.next_block(&mut block, &mut diags).unwrap();
    // The state at the end is "no comment"; seeking back must restore "inside a comment".
    reader.seek(inside).unwrap();
    reader.next_block(&mut block, &mut diags).unwrap();
    assert_eq!(block, commented);
    reader.next_block(&mut block, &mut diags).unwrap();
    assert_eq!(block, closing);
    assert!(diags.is_empty());
    // Two positions differing only in the comment state are different positions.
    assert_ne!(inside, {
        let mut r = BlockReader::new(Cursor::new("X1\nG0 X99\n".as_bytes()), Dialect::Axioma);
        r.next_block(&mut block, &mut diags).unwrap();
        r.position()
    });
}

#[test]
fn reads_a_real_file() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/corpus/axioma/s2_3-msg-example-2_1.nc"
    );
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = BlockReader::new(file, Dialect::Axioma);
    let mut block = Block::default();
    let mut diags = Vec::new();
    let mut messages = Vec::new();
    while reader.next_block(&mut block, &mut diags).unwrap() {
        if let Some(m) = block.message {
            messages.push(block.slice(m).to_string());
        }
    }
    assert_eq!(messages, ["Tool T3 is active", ""]);
    assert!(diags.is_empty());
}
