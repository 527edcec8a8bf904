#!/usr/bin/env bash
# Seeds the cargo-fuzz corpora (fuzz/corpus/<target>/, gitignored) from the programs the project
# already has, read in place: the examples, ../shared/corpus (all eight dialects), LinuxCNC's
# sample programs when installed, the machine data and the tool table. Nothing is copied into the
# repository. Input layout of the program targets: byte 0 = dialect (fuzz/src/lib.rs), byte 1 =
# convert target, then the program.
set -euo pipefail
cd "$(dirname "$0")/.."
shared="${STANOK_SHARED:-../shared}"
python3 - "$shared" <<'PY'
import hashlib, os, sys, glob
shared = sys.argv[1]
DIALECTS = ["axioma", "rs274ngc", "nc31", "2p32", "mc2101", "gost20999", "mazatrol", "balt"]

def dialect_of(path):
    name = os.path.basename(path).lower()
    for i, d in enumerate(DIALECTS[2:6], start=2):
        if name.startswith(d + "-") or name.startswith(d + "_"):
            return i
    if "/cvu/" in path:
        return 7
    if "/mazatrol/" in path:
        return 6
    if name.endswith(".ngc"):
        return 1
    return 0

def put(target, data):
    d = os.path.join("fuzz", "corpus", target)
    os.makedirs(d, exist_ok=True)
    h = hashlib.sha1(data).hexdigest()[:16]
    with open(os.path.join(d, h), "wb") as f:
        f.write(data)

programs = []
for pattern in ["examples/*", shared + "/corpus/**/*.nc", shared + "/corpus/**/*.ngc",
                "/usr/share/linuxcnc/ncfiles/*.ngc"]:
    programs += [p for p in glob.glob(pattern, recursive=True) if os.path.isfile(p)]
n = 0
for p in programs:
    data = open(p, "rb").read()
    if len(data) > 64 * 1024:
        continue  # libFuzzer's -max_len is far below; long inputs only slow it down
    d = dialect_of(p)
    for target in ["parse", "interp", "run", "convert"]:
        put(target, bytes([d, 0]) + data)
    put("interp", bytes([d | 8, 1]) + data)  # check mode
    n += 1
for p in glob.glob("machines/*.toml"):
    put("machine_data", open(p, "rb").read())
for p in glob.glob(shared + "/corpus/**/*.tbl", recursive=True) + glob.glob("/usr/share/linuxcnc/ncfiles/*.var"):
    put("tool_table", b"\0" + open(p, "rb").read())
print(f"seeded {n} programs into fuzz/corpus/")
PY
