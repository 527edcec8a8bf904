#!/usr/bin/env bash
# Converts the programs listed below to RS274/NGC with `stanok convert` and writes LinuxCNC's own
# trace of each converted program (`rs274 -g`) to crates/stanok-convert/tests/linuxcnc/NAME.canon.txt.
# crates/stanok-convert/tests/linuxcnc_goldens.rs checks, without LinuxCNC, that Stanok reads the
# converted programs exactly as LinuxCNC does. Needs LinuxCNC's rs274 (linuxcnc-uspace):
#   cargo build && scripts/convert-linuxcnc-goldens.sh
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
stanok="$here/target/debug/stanok"
out="$here/crates/stanok-convert/tests/linuxcnc"
command -v rs274 >/dev/null || { echo "rs274 not found: install linuxcnc-uspace" >&2; exit 1; }
[ -x "$stanok" ] || { echo "build first: cargo build" >&2; exit 1; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
# name = source (relative to the repository; ../shared/corpus for corpus programs)
while read -r name src; do
  [ -z "$name" ] && continue
  "$stanok" convert "$here/$src" --to rs274ngc -o "$tmp/$name.ngc" 2>/dev/null
  (cd "$tmp" && rs274 -g "$name.ngc" lx.txt </dev/null >/dev/null 2>lx.err)
  cat "$tmp/lx.txt" "$tmp/lx.err" > "$out/$name.canon.txt"
done <<'LIST'
demo-plate examples/demo-plate.nc
demo-bolt-circle examples/demo-bolt-circle.ngc
planes-helices-splines crates/stanok-convert/tests/programs/planes-helices-splines.ngc
technology-frames-cycles crates/stanok-convert/tests/programs/technology-frames-cycles.ngc
axioma-aspline ../shared/corpus/axioma/s5_4_1-aspline-akima-example-5_15.nc
axioma-g42-turning ../shared/corpus/axioma/s9_2_1-g42-turning-contour-example-9_7.nc
axioma-g387-pocket ../shared/corpus/axioma/s11_8_1-g387-rectangular-pocket-example-11_12.nc
LIST
echo "wrote $(ls "$out" | wc -l) traces to $out"
