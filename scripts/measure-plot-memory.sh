#!/usr/bin/env bash
# Measures `stanok plot` on programs far larger than a picture can show (docs/performance.md,
# "Plotting"): time, peak resident memory (/usr/bin/time %M) and the size of the SVG and PNG.
#
#   scripts/measure-plot-memory.sh [BLOCKS]        (default 10000000)
#
# Two programs of BLOCKS blocks each:
#   stadium - the benchmark program of crates/stanok-interp/benches/program_gen.rs: lines and 180°
#             arcs around one 10 × 10 mm stadium, shifted by µm (the path stays in one place);
#   raster  - a zig-zag finishing raster over 200 × 100 mm, each line the full width, 0.01 mm
#             apart (every block a long new line: the worst case for the drawing).
# The pictures are left in target/plot-memory/ to look at.
set -euo pipefail
cd "$(dirname "$0")/.."
blocks="${1:-10000000}"
out="target/plot-memory"
mkdir -p "$out"
cargo build --release -q -p stanok
cargo build --release -q -p stanok-interp --example gen_program
./target/release/examples/gen_program "$blocks" > "$out/stadium.ngc"
awk -v n="$blocks" 'BEGIN {
  print "G21 G17 G90 F3000"; print "G0 X0 Y0 Z1"; print "G1 Z-1";
  for (i = 0; i < n; i++) {
    y = i * 100.0 / n;
    if (i % 2 == 0) printf "G1 X200 Y%.4f\n", y; else printf "G1 X0 Y%.4f\n", y;
  }
  print "M2"
}' > "$out/raster.ngc"
for name in stadium raster; do
  prog="$out/$name.ngc"
  echo "== $name: $blocks blocks, $(stat -c %s "$prog") bytes"
  /usr/bin/time -f "svg: %e s, peak resident %M KiB" ./target/release/stanok plot "$prog" -o "$out/$name.svg" 2>&1 | grep -v "^dialect\|^wrote"
  echo "svg: $(stat -c %s "$out/$name.svg") bytes"
  /usr/bin/time -f "png: %e s, peak resident %M KiB" ./target/release/stanok plot "$prog" -o "$out/$name.png" 2>&1 | grep -v "^dialect\|^wrote"
  echo "png: $(stat -c %s "$out/$name.png") bytes"
done
