//! The parsers of every dialect: `BlockReader` streaming (the interpreter's way) and
//! `stanok_syntax::parse` of the whole text, and the lab readers. No panic, bounded time.
#![no_main]
use libfuzzer_sys::fuzz_target;
use stanok_syntax::{Block, BlockReader};

fuzz_target!(|data: &[u8]| {
    let Some((dialect, _, _, program)) = stanok_fuzz::split(data) else {
        return;
    };
    let mut reader = BlockReader::new(std::io::Cursor::new(program), dialect);
    let mut block = Block::default();
    let mut diags = Vec::new();
    while let Ok(true) = reader.next_block(&mut block, &mut diags) {
        diags.clear();
    }
    let text = String::from_utf8_lossy(program);
    let _ = stanok_syntax::parse(&text, dialect);
    let _ = stanok_syntax::labs::strip_fixture_comments(&text);
});
