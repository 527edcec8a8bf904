#!/usr/bin/env bash
# Measures the interpreter figures of docs/performance.md in one run on this machine:
# criterion throughput (parse only; parse + interpret), instruction counts (callgrind; independent
# of machine load), LinuxCNC's rs274 on the same 1M-block program (if installed), and the peak
# resident memory of `stanok run` on a 10M-block program.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cargo build --release -q -p stanok -p stanok-interp --examples
./target/release/examples/gen_program 1000000 > "$tmp/p1m.ngc"
./target/release/examples/gen_program 100000 > "$tmp/p100k.ngc"
./target/release/examples/gen_program 10000000 > "$tmp/p10m.ngc"
echo "== criterion (1M blocks, $(stat -c %s "$tmp/p1m.ngc") bytes)"
cargo bench -q -p stanok-interp --bench throughput 2>&1 | grep -E "^[a-z]+/|thrpt:" | grep -v "%\]"
if command -v valgrind >/dev/null; then
  echo "== instructions per block (callgrind, 100k blocks)"
  for mode in parse interpret; do
    refs=$(valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" ./target/release/examples/probe "$mode" "$tmp/p100k.ngc" 2>&1 | sed -n 's/.*I *refs: *//p' | tr -d ,)
    echo "$mode: $((refs / 100000)) instructions/block"
  done
fi
if command -v rs274 >/dev/null; then
  echo "== LinuxCNC rs274 -g on the same 1M-block program (includes printing its trace)"
  tbl="$(pwd)/../shared/corpus/rs274ngc/tool.tbl"
  ( cd "$tmp" && /usr/bin/time -f "rs274: %e s" rs274 -t "$tbl" -g "$tmp/p1m.ngc" /dev/null < /dev/null 2>&1 >/dev/null | grep rs274: )
  /usr/bin/time -f "stanok canon (LinuxCNC format, same work): %e s" ./target/release/stanok canon "$tmp/p1m.ngc" 2>&1 >/dev/null | tail -1
fi
echo "== stanok run on 10M blocks ($(stat -c %s "$tmp/p10m.ngc") bytes)"
/usr/bin/time -f "%e s, peak resident %M KiB" ./target/release/stanok run "$tmp/p10m.ngc" 2>&1 >/dev/null | tail -1
