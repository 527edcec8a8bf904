#!/usr/bin/env bash
# Regenerates crates/stanok-rs274/tests/rs274/expected/*.canon.txt with LinuxCNC's standalone
# interpreter, the oracle for RS274/NGC semantics. CI does not run this (it needs LinuxCNC); the
# outputs are committed.
#
#   apt-get update && apt-get install -y --no-install-recommends linuxcnc-uspace
#   scripts/regen-linuxcnc-goldens.sh
#
# Each golden is what `rs274 -t tool.tbl -g prog.ngc` writes, followed by its stderr ("executing",
# and on an error the message and the offending block), the same layout as
# ../shared/corpus/rs274ngc/expected.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
dir="$here/crates/stanok-rs274/tests/rs274"
tbl="$here/../shared/corpus/rs274ngc/tool.tbl"
command -v rs274 >/dev/null || { echo "rs274 not found: install linuxcnc-uspace" >&2; exit 1; }
tmp="$(mktemp -d)"
# rs274 maps its tool table from $HOME/.tool.mmap: a home of its own keeps other runs out.
export HOME="$tmp"
trap 'rm -rf "$tmp"' EXIT
for prog in "$dir"/*.ngc; do
  name="$(basename "$prog" .ngc)"
  out="$dir/expected/$name.canon.txt"
  (cd "$tmp" && rs274 -t "$tbl" -g "$prog" canon.txt 2> err.txt < /dev/null) || true
  cat "$tmp/canon.txt" "$tmp/err.txt" > "$out"
  echo "$name: $(wc -l < "$out") lines"
done

# Subroutine files on the search path: rs274 reads SUBROUTINE_PATH from an ini file (-i).
sub="$here/crates/stanok-rs274/tests/rs274-subfiles"
printf "[RS274NGC]\nSUBROUTINE_PATH = %s\n" "$sub" > "$tmp/sub.ini"
(cd "$tmp" && rs274 -i "$tmp/sub.ini" -t "$tbl" -g "$sub/main.ngc" canon.txt 2> err.txt < /dev/null) || true
cat "$tmp/canon.txt" "$tmp/err.txt" > "$sub/expected.canon.txt"
echo "rs274-subfiles: $(wc -l < "$sub/expected.canon.txt") lines"
