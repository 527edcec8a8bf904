#!/usr/bin/env bash
# A long local fuzzing run (docs/robustness.md, Figures): every cargo-fuzz target in turn, SLICE
# seconds each, for ROUNDS rounds, at the lowest priority, one job at a time. Prints the executions
# and crashes per target and in all; crash inputs stay in fuzz/artifacts/<target>/.
# Usage: scripts/fuzz-long.sh [ROUNDS] [SLICE]   (default 6 rounds of 600 s per target)
set -uo pipefail
cd "$(dirname "$0")/../fuzz"
rounds="${1:-6}"
slice="${2:-600}"
export RUSTC_BOOTSTRAP=1
cargo fuzz build -s none --fuzz-dir . >/dev/null
[ -d corpus/interp ] || ../scripts/fuzz-seed.sh
total=0
crashes=0
for round in $(seq 1 "$rounds"); do
  for target in parse interp run convert machine_data tool_table; do
    log="$(mktemp)"
    nice -n 19 cargo fuzz run -s none --fuzz-dir . "$target" -- \
      -max_total_time="$slice" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 >"$log" 2>&1
    rc=$?
    n=$(grep -E "^stat::number_of_executed_units" "$log" | awk '{print $2}' | tail -1)
    n=${n:-0}
    total=$((total + n))
    if [ "$rc" -ne 0 ]; then
      crashes=$((crashes + 1))
      echo "round $round $target: FAILED (exit $rc)"
      grep -E "^(==|SUMMARY|thread|Test unit|artifact)" "$log" | head -20
    fi
    echo "round $round $target: $n executions (total $total)"
    rm -f "$log"
  done
done
echo "total executions: $total; failed target runs: $crashes"
