//! Parameter- and subroutine-heavy interpretation: examples/hilbert-recursive.ngc (a Hilbert
//! curve drawn by O-word recursion, order 7: 16,384 moves, ~137,000 executed blocks counting the
//! O-word lines and assignments). Figures, and LinuxCNC's rs274 on the same file, go to the
//! docs/performance.md.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use stanok_interp::{InterpOptions, Interpreter};
use stanok_syntax::Dialect;

fn hilbert(c: &mut Criterion) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/hilbert-recursive.ngc"
    );
    let text = std::fs::read_to_string(path)
        .expect("examples/hilbert-recursive.ngc")
        .replace("#<_order> = 8", "#<_order> = 7");
    let mut g = c.benchmark_group("subroutines");
    g.sample_size(10);
    // Moves of an order-7 curve: 4^7 − 1 segments + 2 plunges/retracts + the rapid.
    g.throughput(Throughput::Elements(16_383));
    g.bench_function("hilbert_order7_moves", |b| {
        b.iter(|| {
            let mut moves = 0usize;
            for cmd in Interpreter::from_text(&text, InterpOptions::new(Dialect::Rs274ngc)) {
                let cmd = cmd.expect("the example is valid");
                moves += cmd.value.motion().is_some() as usize;
            }
            assert_eq!(moves, 16_383 + 3);
            moves
        })
    });
    g.finish();
}

criterion_group!(benches, hilbert);
criterion_main!(benches);
