//! Steady-state parsing allocates nothing: a counting global allocator (per thread) checks that
//! re-parsing lines into a warmed-up `Block` makes no allocation, in both dialects.

use stanok_syntax::{Block, BlockParser, Dialect};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> usize {
    ALLOCATIONS.with(|c| c.get())
}

fn steady_state(dialect: Dialect, lines: &[&str]) {
    let mut parser = BlockParser::new(dialect);
    let mut block = Block::default();
    let mut diags = Vec::new();
    // Warm up: the block's vectors grow to the largest line once.
    for (i, line) in lines.iter().enumerate() {
        parser.parse_line(line, i as u32 + 1, 0, &mut block, &mut diags);
    }
    assert!(diags.is_empty(), "{diags:#?}");
    let before = allocations();
    for round in 0..100u32 {
        for (i, line) in lines.iter().enumerate() {
            parser.parse_line(line, round * 100 + i as u32, 0, &mut block, &mut diags);
        }
    }
    assert_eq!(
        allocations() - before,
        0,
        "{dialect:?} allocated in steady state"
    );
}

#[test]
fn parse_line_does_not_allocate_in_steady_state() {
    steady_state(
        Dialect::Axioma,
        &[
            "N10 G1 X12.345 Y-6.789 Z0.5 F1200",
            "G2 X1 Y2 I3 J4",
            "G17 G90 G15 G191 G71 G72 G172 G272 G94 G97 G49 G40 G00 G80 G98",
            "G53 G153 G193 G64 BRISK CUT2DF ORIAxes // Строка безопасности",
            "N20 G3 X17.203 Y38.029 CR=-34.913 S2=1000 LMAXS2=4500 F=FTABLE(3) (c) ; d",
            "N30 MSG(\"Tool T3 is active\") /* a */ X1",
            "X1 /* open",
            "still comment",
            "*/ G1 X2",
            "% header",
            "* star comment",
        ],
    );
    steady_state(
        Dialect::Rs274ngc,
        &[
            "N10 G1 X12.345 Y-6.789 Z0.5 F1200",
            "G2 X1 Y2 I3 J4",
            "#<zworkoffset> = [#[5203 + #5220 * 20] + #5213 * #5210]",
            "G1 X[1+2*3] Y-#1 Z atan[1]/[1] (MSG, hello) ; tail",
            "o100 if [#1 GT 2 AND #2 LT 3]",
            "o100 endsub [#1]",
            "%",
            "/N5 G 0 X 1 . 5 (DEBUG, x=#5420)",
        ],
    );
}

#[test]
fn block_reader_does_not_allocate_in_steady_state() {
    use stanok_syntax::BlockReader;
    use std::io::Cursor;
    // An odd number of distinct lines, repeated: the reader's two swapped buffers both meet
    // every line length during the warm-up.
    let pattern = "N10 G1 X12.345 Y-6.789 Z0.5 F1200\r\nG2 X1 Y2 I3 J4\n(a comment) M3 S1000\n";
    let text = pattern.repeat(1000);
    let mut reader = BlockReader::new(Cursor::new(text.as_bytes()), Dialect::Axioma);
    let mut block = Block::default();
    let mut diags = Vec::new();
    for _ in 0..12 {
        assert!(reader.next_block(&mut block, &mut diags).unwrap());
    }
    let before = allocations();
    let mut n = 0;
    while reader.next_block(&mut block, &mut diags).unwrap() {
        n += 1;
    }
    assert_eq!(n, 3000 - 12);
    assert!(diags.is_empty());
    assert_eq!(
        allocations() - before,
        0,
        "BlockReader allocated in steady state"
    );
}
