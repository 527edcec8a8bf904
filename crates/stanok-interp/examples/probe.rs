//! Parses or interprets a program file and prints counts; used with `valgrind --tool=callgrind` to
//! count instructions per block (a figure that, unlike wall time, does not depend on machine load):
//!
//! `valgrind --tool=callgrind target/release/examples/probe parse|interpret FILE`
//!
//! The dialect follows the file name: `.ngc` is RS274/NGC, anything else AxiOMA.

use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::{Block, BlockParser, Dialect};

fn main() {
    let mut args = std::env::args().skip(1);
    let mode = args.next().unwrap_or_default();
    let path = args.next().expect("usage: probe parse|interpret FILE");
    let text = std::fs::read_to_string(&path).expect("read the program");
    let dialect = Dialect::from_path(std::path::Path::new(&path));
    match mode.as_str() {
        "parse" => {
            let mut parser = BlockParser::new(dialect);
            let mut block = Block::default();
            let mut diags = Vec::new();
            let (mut words, mut offset) = (0usize, 0u64);
            for (i, line) in text.lines().enumerate() {
                parser.parse_line(line, i as u32 + 1, offset, &mut block, &mut diags);
                words += block.words.len();
                offset += line.len() as u64 + 1;
            }
            println!(
                "{} bytes, {words} words, {} diagnostics",
                text.len(),
                diags.len()
            );
        }
        _ => {
            let n = Interpreter::from_text(&text, InterpOptions::new(dialect))
                .filter(|c| c.is_ok())
                .count();
            println!("{n} commands");
        }
    }
}
