#!/usr/bin/env bash
# Developer aid: runs one RS274/NGC program through LinuxCNC's rs274 and `stanok canon` (with the
# corpus tool table, inch machine units as rs274's simulated machine) and diffs the two traces.
#   scripts/linuxcnc-diff.sh prog.ngc [tool.tbl]
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
prog="$(realpath "$1")"
tbl="$(realpath "${2:-$here/../shared/corpus/rs274ngc/tool.tbl}")"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && rs274 -t "$tbl" -g "$prog" lx.txt 2>lx.err </dev/null >/dev/null)
cat "$tmp/lx.txt" "$tmp/lx.err" | sed "s/ON_RESET()executing/ON_RESET()/; /^executing$/d" > "$tmp/linuxcnc.txt"
"$here/target/debug/stanok" canon --dialect rs274ngc --tools "$tbl" --linuxcnc-units inch "$prog" > "$tmp/stanok.txt" 2>"$tmp/stanok.err"
cat "$tmp/stanok.err" >> "$tmp/stanok.txt"
diff "$tmp/linuxcnc.txt" "$tmp/stanok.txt" && echo "identical"
