//! Parse-only and parse+interpret throughput on a generated 1,000,000-block program of lines and
//! arcs (see program_gen.rs). Figures go to docs/performance.md.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::{Block, BlockParser, Dialect};

#[path = "program_gen.rs"]
mod program_gen;

const BLOCKS: usize = 1_000_000;

fn parse_only(c: &mut Criterion) {
    let text = program_gen::stadium_program(BLOCKS);
    let mut g = c.benchmark_group("parse");
    g.sample_size(10);
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.bench_function("rs274ngc_1M_blocks", |b| {
        b.iter(|| {
            let mut parser = BlockParser::new(Dialect::Rs274ngc);
            let mut block = Block::default();
            let mut diags = Vec::new();
            let mut words = 0usize;
            let mut offset = 0u64;
            for (i, line) in text.lines().enumerate() {
                parser.parse_line(line, i as u32 + 1, offset, &mut block, &mut diags);
                words += block.words.len();
                offset += line.len() as u64 + 1;
            }
            assert!(diags.is_empty());
            words
        })
    });
    g.finish();
}

fn parse_and_interpret(c: &mut Criterion) {
    let text = program_gen::stadium_program(BLOCKS);
    let blocks = text.lines().count() as u64;
    let mut g = c.benchmark_group("interpret");
    g.sample_size(10);
    g.throughput(Throughput::Elements(blocks));
    g.bench_function("rs274ngc_1M_blocks_to_canon", |b| {
        b.iter(|| {
            let opts = InterpOptions::new(Dialect::Rs274ngc);
            let mut n = 0usize;
            for cmd in Interpreter::from_text(&text, opts) {
                let cmd = cmd.expect("the generated program is valid");
                n += cmd.value.motion().is_some() as usize;
            }
            assert_eq!(n, BLOCKS + 2);
            n
        })
    });
    g.finish();
}

criterion_group!(benches, parse_only, parse_and_interpret);
criterion_main!(benches);
