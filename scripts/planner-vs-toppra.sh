#!/bin/sh
# Builds Stanok's planner example and compares its BRISK times with toppra's time-optimal ones
# (scripts/planner-vs-toppra.py explains the paths and the fine print). Needs python3 with
# numpy and toppra: `python3 -m pip install toppra`.
set -eu
cd "$(dirname "$0")/.."
cargo build --release -q -p stanok-motion --example planner_time
python3 -c "import toppra" 2>/dev/null || python3 -m pip install -q toppra
exec python3 scripts/planner-vs-toppra.py "$@"
