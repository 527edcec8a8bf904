//! Parse throughput, measured on demand (the criterion bench comes later):
//!
//! ```text
//! cargo test --release -p stanok-syntax --test throughput -- --ignored --nocapture
//! ```

use stanok_syntax::{Block, BlockParser, BlockReader, Dialect};
use std::io::Cursor;
use std::time::Instant;

/// About `bytes` of typical G-code lines (`G1 X12.345 Y-6.789 Z0.5 F1200`, `G2 X1 Y2 I3 J4`).
fn program(bytes: usize) -> String {
    let mut text = String::with_capacity(bytes + 64);
    let mut i = 0u64;
    while text.len() < bytes {
        let a = (i * 7919 % 100_000) as f64 / 1000.0;
        let b = (i * 104_729 % 100_000) as f64 / 1000.0;
        if i % 3 == 2 {
            text.push_str(&format!(
                "G2 X{} Y{} I{} J{}\n",
                i % 97,
                i % 89,
                i % 13,
                i % 11
            ));
        } else {
            text.push_str(&format!("G1 X{a:.3} Y-{b:.3} Z0.5 F1200\n"));
        }
        i += 1;
    }
    text
}

fn mb_per_s(bytes: usize, seconds: f64) -> f64 {
    bytes as f64 / seconds / 1e6
}

/// Reference workload: split every line at blanks and `str::parse` each word's number.
fn reference(lines: &[&str]) -> f64 {
    let mut acc = 0.0;
    for line in lines {
        for w in line.split(' ') {
            if let Some(Ok(v)) = w.get(1..).map(str::parse::<f64>) {
                acc += v;
            }
        }
    }
    acc
}

/// Best-of-5 MB/s of `parse_line` over `lines` (repeated `reps` times), interleaved with the
/// reference (the VM's speed drifts). Returns (ours, reference).
fn measure(dialect: Dialect, lines: &[&str], reps: usize) -> (f64, f64) {
    let bytes: usize = lines.iter().map(|l| l.len() + 1).sum::<usize>() * reps;
    let mut parser = BlockParser::new(dialect);
    let mut block = Block::default();
    let mut diags = Vec::new();
    let (mut best, mut best_ref) = (f64::MAX, f64::MAX);
    for _ in 0..5 {
        let t = Instant::now();
        for _ in 0..reps {
            std::hint::black_box(reference(lines));
        }
        best_ref = best_ref.min(t.elapsed().as_secs_f64());
        let mut words = 0usize;
        let t = Instant::now();
        for _ in 0..reps {
            let mut offset = 0u64;
            for (i, line) in lines.iter().enumerate() {
                parser.parse_line(line, i as u32 + 1, offset, &mut block, &mut diags);
                offset += line.len() as u64 + 1;
                words += block.words.len();
            }
        }
        best = best.min(t.elapsed().as_secs_f64());
        assert!(words > lines.len() * reps * 4);
    }
    assert!(diags.is_empty());
    (mb_per_s(bytes, best), mb_per_s(bytes, best_ref))
}

#[test]
#[ignore = "measurement; run in release with --ignored --nocapture"]
fn throughput() {
    let small = program(256 << 10);
    let small_lines: Vec<&str> = small.lines().collect();
    let big = program(32 << 20);
    let big_lines: Vec<&str> = big.lines().collect();
    for dialect in [Dialect::Axioma, Dialect::Rs274ngc] {
        let (ours, reference) = measure(dialect, &small_lines, 128);
        println!(
            "{dialect:?} parse_line, 256 KiB in cache: {ours:.0} MB/s (reference split+str::parse: {reference:.0} MB/s)"
        );
        let (ours, reference) = measure(dialect, &big_lines, 1);
        println!(
            "{dialect:?} parse_line, 32 MiB streamed: {ours:.0} MB/s (reference split+str::parse: {reference:.0} MB/s)"
        );
        let mut block = Block::default();
        let mut diags = Vec::new();
        let t = Instant::now();
        let mut reader = BlockReader::new(Cursor::new(big.as_bytes()), dialect);
        let mut n = 0usize;
        while reader.next_block(&mut block, &mut diags).unwrap() {
            n += 1;
        }
        assert_eq!(n, big_lines.len());
        println!(
            "{dialect:?} BlockReader, 32 MiB: {:.0} MB/s",
            mb_per_s(big.len(), t.elapsed().as_secs_f64())
        );
    }
}
