#!/usr/bin/env bash
# Runs LinuxCNC's rs274 and `stanok canon --machine linuxcnc` on every LinuxCNC sample program
# through the differential runner (stanok-parity --program, the golden tests' comparison) and
# prints one line per program that differs, then `parity: M/N`. Needs LinuxCNC:
#   apt-get update && apt-get install -y --no-install-recommends linuxcnc-uspace
#   scripts/linuxcnc-parity.sh [--update-goldens]
# With --update-goldens the traces of the programs listed in tests/linuxcnc-samples/list.txt
# are written to tests/linuxcnc-samples/expected/ (cargo test compares them without LinuxCNC).
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
tbl="$here/crates/stanok/tests/linuxcnc-samples/sim.tbl"
command -v rs274 >/dev/null || { echo "rs274 not found: install linuxcnc-uspace" >&2; exit 1; }
(cd "$here" && cargo build -q -p stanok -p stanok-ngcgen) || exit 1
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
# rs274 maps its tool table from $HOME/.tool.mmap: a home of its own keeps other runs out.
export HOME="$tmp"
mapfile -t progs < <(find /usr/share/linuxcnc/ncfiles /usr/share/doc/linuxcnc/examples -name '*.ngc' | sort)
"$here/target/debug/stanok-parity" --tools "$tbl" --no-shrink --program "${progs[@]}" \
  | grep -E '^(== |parity:)'

if [ "${1:-}" = "--update-goldens" ]; then
  out="$here/crates/stanok/tests/linuxcnc-samples/expected"
  rm -rf "$out"; mkdir -p "$out"
  grep -v '^#' "$here/crates/stanok/tests/linuxcnc-samples/list.txt" | while read -r rel; do
    name="$(echo "$rel" | tr '/' '_')"
    (cd "$tmp" && timeout 20 rs274 -t "$tbl" -g "/$rel" lx.txt 2>lx.err </dev/null >/dev/null)
    cat "$tmp/lx.txt" "$tmp/lx.err" > "$out/${name%.ngc}.canon.txt"
  done
  echo "goldens: $(ls "$out" | wc -l) written to $out"
fi
