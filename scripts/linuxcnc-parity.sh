#!/usr/bin/env bash
# Runs LinuxCNC's rs274 and `stanok canon` on every LinuxCNC sample program and prints
# `parity: M/N` with one line per program that differs. Needs LinuxCNC:
#   apt-get update && apt-get install -y --no-install-recommends linuxcnc-uspace
#   cargo build --release && scripts/linuxcnc-parity.sh [--update-goldens]
# With --update-goldens the traces of the programs listed in tests/linuxcnc-samples/list.txt
# are written to tests/linuxcnc-samples/expected/ (CI compares them without LinuxCNC).
set -uo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
stanok="$here/target/release/stanok"
tbl="$here/crates/stanok/tests/linuxcnc-samples/sim.tbl"
machine="$here/crates/stanok/tests/linuxcnc-samples/sim.toml"
command -v rs274 >/dev/null || { echo "rs274 not found: install linuxcnc-uspace" >&2; exit 1; }
[ -x "$stanok" ] || { echo "build first: cargo build --release" >&2; exit 1; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
mapfile -t progs < <(find /usr/share/linuxcnc/ncfiles /usr/share/doc/linuxcnc/examples -name '*.ngc' | sort)
same=0; total=0
for prog in "${progs[@]}"; do
  total=$((total + 1))
  dir="$(dirname "$prog")"
  (cd "$tmp" && timeout 20 rs274 -t "$tbl" -g "$prog" lx.txt 2>lx.err </dev/null >/dev/null)
  cat "$tmp/lx.txt" "$tmp/lx.err" > "$tmp/linuxcnc.txt" 2>/dev/null
  timeout 20 "$stanok" canon --dialect rs274ngc --machine "$machine" --tools "$tbl" --linuxcnc-units inch \
"$prog" > "$tmp/stanok.txt" 2>&1
  verdict="$(python3 "$here/scripts/linuxcnc_compare.py" "$tmp/linuxcnc.txt" "$tmp/stanok.txt" "$prog")"
  case "$verdict" in
    same*) same=$((same + 1)) ;;
    *) echo "${prog#/usr/share/}: $verdict" ;;
  esac
done
echo "parity: $same/$total"

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
