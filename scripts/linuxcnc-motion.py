#!/usr/bin/env python3
"""Stanok's cycle time against LinuxCNC 2.9's real planner on LinuxCNC's own sample programs.

For every sample program LinuxCNC ships (/usr/share/linuxcnc/ncfiles and
/usr/share/doc/linuxcnc/examples, recursively) this script
  1. keeps the ones that only move (`stanok canon`): X Y Z motion only; no probing, tool change,
     program stop (M0/M1 wait for the operator), spindle synchronisation, rigid tap, input wait;
     no error on Stanok's side (`stanok run` on the comparison machine);
  2. runs each through LinuxCNC's planner headless (../shared/tools/lcnc-sim/run.sh, limits
     --vmax 100 --amax 1000: X Y Z at 100 mm/s and 1000 mm/s^2, path speed at most 100 mm/s) and
     through Stanok (`stanok run --trace` with scripts/linuxcnc-motion/machine.toml: the same
     limits, BRISK, the same zero-length tool table), both on a copy of the program that starts
     with `G64 P<tolerance> Q0` (default 0.05 mm, Stanok's default path tolerance), so that both
     round corners within the same tolerance. Q0 turns LinuxCNC's naive-CAM detector off: with
     Q (which defaults to P) it replaces runs of short feed moves that lie within Q of a line by
     that line — on systems.ngc's 0.3 mm letters it drops 8 % of the path — a simplification of
     the path, not planning, which Stanok does not do. The copy sits in a directory that links
     the program's siblings, so subroutine calls resolve as before. A program that programs G64
     itself (comp.ngc, arcspiral.ngc: G64 without P) runs that from there on, in both;
  3. runs LinuxCNC once more on the program as written: LinuxCNC's G64 without P has no
     tolerance (it rounds a corner as far as the segment lengths allow — 0.37 mm at the rapid
     corners of 3dtest.ngc), the column "LinuxCNC, G64 without P" shows what that buys;
  4. measures all traces the same way: lcnc-sim's motion_time_s, "from the last sample before
     the first position change to the first sample after the last change", which on Stanok's
     trace is the same rule applied to its setpoints;
  5. prints a Markdown table (program, segments, LinuxCNC s and Stanok s under the same
     tolerance, ratio, LinuxCNC s under G64 without P, ratio, Stanok's limit violations and
     measured contour error at junctions and elsewhere) and writes it to --out.

A LinuxCNC run that fails (exit status != 0: a capture gap on a busy machine, a start-up race)
is retried once, then listed as failed.

Usage: scripts/linuxcnc-motion.py [--stanok target/debug/stanok] [--out FILE] [--list]
       [--max-seconds 300] [--tolerance 0.05] [--keep DIR] [--lcnc-cache FILE] [PROGRAM ...]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
LCNC = os.path.normpath(os.path.join(ROOT, "..", "shared", "tools", "lcnc-sim"))
MACHINE = os.path.join(HERE, "linuxcnc-motion", "machine.toml")
TOOLS = os.path.join(LCNC, "config", "mill3.tbl")
SAMPLE_DIRS = ["/usr/share/linuxcnc/ncfiles", "/usr/share/doc/linuxcnc/examples"]

# Canon commands that mean "not only motion" (waiting for an operator, a probe, a spindle).
REFUSED = {
    "straight_probe": "probe",
    "change_tool": "tool change",
    "change_spindle_tool": "tool change",
    "start_tool_change": "tool change",
    "program_stop": "M0/M1",
    "start_spindle_sync": "spindle sync",
    "rigid_tap": "rigid tap",
    "wait_input": "input wait",
    "pallet_shuttle": "pallet",
    "set_tool_centre_point": "TCP",
}


def samples():
    out = []
    for d in SAMPLE_DIRS:
        for root, _, files in os.walk(d):
            for f in files:
                if f.endswith(".ngc"):
                    out.append(os.path.join(root, f))
    return sorted(out)


def classify(stanok, prog):
    """None if the program only moves on X Y Z (and Stanok runs it), else the reason."""
    canon = subprocess.run(
        [stanok, "canon", prog, "--format", "jsonl", "--tools", TOOLS, "--machine", MACHINE],
        capture_output=True, text=True, timeout=120, cwd=os.path.dirname(prog))
    if canon.returncode != 0:
        return "interpreter error"
    moves = 0
    for line in canon.stdout.splitlines():
        try:
            c = json.loads(line)
        except ValueError:
            continue
        kind = c.get("kind", "")
        if kind in REFUSED:
            return REFUSED[kind]
        if kind in ("straight_traverse", "straight_feed", "arc_feed", "spline_feed"):
            moves += 1
            for end in ("start", "end"):
                p = c.get(end) or {}
                if any(abs(p.get(a, 0.0)) > 1e-9 for a in ("a", "b", "c", "u", "v", "w")):
                    return "rotary/UVW axes"
    if moves == 0:
        return "no motion"
    return None


def motion_time(rows, dt):
    """lcnc-sim's rule: last sample before the first change to the first sample after the last."""
    if not rows:
        return 0.0
    first = rows[0]
    k0 = next((k for k, r in enumerate(rows) if r != first), None)
    if k0 is None:
        return 0.0
    k1 = max(k for k in range(1, len(rows)) if rows[k] != rows[k - 1])
    return (k1 - (k0 - 1)) * dt


def with_tolerance(prog, tolerance, keep):
    """A copy of `prog` that starts with G64 P<tolerance> Q0 (after a leading `%` line), in a
    directory of its own that links the program's siblings (subroutine files)."""
    d = os.path.join(keep, "g64p", os.path.basename(prog) + ".d")
    os.makedirs(d, exist_ok=True)
    src = os.path.dirname(prog)
    for f in os.listdir(src):
        link = os.path.join(d, f)
        if f != os.path.basename(prog) and not os.path.lexists(link):
            os.symlink(os.path.join(src, f), link)
    with open(prog, errors="replace") as f:
        lines = f.read().splitlines(keepends=True)
    at = 1 if lines and lines[0].strip() == "%" else 0
    lines.insert(at, f"G64 P{tolerance} Q0\n")
    copy = os.path.join(d, os.path.basename(prog))
    with open(copy, "w") as f:
        f.writelines(lines)
    return copy


def stanok_run(stanok, prog, keep):
    trace = os.path.join(keep, os.path.basename(prog) + ".stanok.csv")
    r = subprocess.run(
        [stanok, "run", prog, "--json", "--machine", MACHINE, "--tools", TOOLS,
         "--trace", trace],
        capture_output=True, text=True, timeout=3600, cwd=os.path.dirname(prog))
    rep = json.loads(r.stdout)
    rows = []
    with open(trace) as f:
        rd = csv.reader(f)
        next(rd)
        for row in rd:
            rows.append(tuple(round(float(x), 6) for x in row[1:4]))
    return rep, motion_time(rows, rep["servo_period_s"])


def lcnc_run(prog, keep, timeout, tag):
    out = os.path.join(keep, os.path.basename(prog) + f".{tag}.lcnc.csv")
    rc = None
    for _ in range(2):
        r = subprocess.run(
            [os.path.join(LCNC, "run.sh"), prog, out, "--vmax", "100", "--amax", "1000",
             "--timeout", str(timeout)],
            capture_output=True, text=True)
        rc = r.returncode
        if rc != 0:
            continue
        for line in r.stdout.splitlines():
            if line.startswith("SUMMARY"):
                fields = dict(f.split("=", 1) for f in line.split()[1:] if "=" in f)
                return float(fields["motion_time_s"]), fields.get("limits", "?"), rc
    return None, None, rc


def lcnc_cached(cache_file, key, run):
    """`run()` once per key: LinuxCNC runs in real time, a re-run of the script reads the cache."""
    cache = {}
    if cache_file and os.path.exists(cache_file):
        with open(cache_file) as f:
            cache = json.load(f)
    if key in cache:
        return cache[key]
    lt, limits, rc = run()
    if cache_file and lt is not None:
        cache[key] = [lt, limits, rc]
        with open(cache_file, "w") as f:
            json.dump(cache, f, indent=1, sort_keys=True)
    return lt, limits, rc


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--stanok", default=os.path.join(ROOT, "target", "debug", "stanok"))
    ap.add_argument("--out", help="write the Markdown table here too")
    ap.add_argument("--list", action="store_true", help="only classify the samples")
    ap.add_argument("--tolerance", type=float, default=0.05,
                    help="G64 P tolerance (mm) both run under")
    ap.add_argument("--max-seconds", type=float, default=300.0,
                    help="skip programs whose Stanok cycle time is longer (LinuxCNC runs in "
                         "real time)")
    ap.add_argument("--keep", help="directory for the traces (default: a temporary one)")
    ap.add_argument("--lcnc-cache", help="JSON file of LinuxCNC results by program, read and "
                    "written, so that a re-run only runs Stanok (LinuxCNC runs in real time)")
    ap.add_argument("programs", nargs="*")
    a = ap.parse_args()
    keep = a.keep or tempfile.mkdtemp(prefix="stanok-lcnc-")
    os.makedirs(keep, exist_ok=True)
    progs = a.programs or samples()
    rows = []
    for prog in progs:
        why = classify(a.stanok, prog)
        if why:
            print(f"skip {prog}: {why}", file=sys.stderr)
            continue
        same = with_tolerance(prog, a.tolerance, keep)
        rep, st = stanok_run(a.stanok, same, keep)
        if rep.get("status") != "ok":
            print(f"skip {prog}: stanok {rep.get('error', {}).get('message')}", file=sys.stderr)
            continue
        if rep["cycle_time_s"] > a.max_seconds:
            print(f"skip {prog}: {rep['cycle_time_s']:.0f} s (over --max-seconds)",
                  file=sys.stderr)
            continue
        if a.list:
            print(f"{prog}\t{rep['motion_segments']}\t{st:.3f}")
            continue
        timeout = int(max(300, 3 * st + 120))
        lt, limits, rc = lcnc_cached(a.lcnc_cache, f"{prog} G64 P{a.tolerance} Q0",
                                     lambda: lcnc_run(same, keep, timeout, "p"))
        ld, _, rcd = lcnc_cached(a.lcnc_cache, prog, lambda: lcnc_run(prog, keep, timeout, "g64"))
        row = {
            "program": os.path.relpath(prog, "/usr/share"),
            "segments": rep["motion_segments"],
            "lcnc": lt,
            "lcnc_limits": limits,
            "lcnc_rc": rc,
            "lcnc_g64": ld,
            "lcnc_g64_rc": rcd,
            "stanok": st,
            "violations": rep["violation_count"],
            "junction_mm": rep["contour_error"]["junctions"]["max_mm"],
            "elsewhere_mm": rep["contour_error"]["elsewhere"]["max_mm"],
        }
        rows.append(row)
        print(json.dumps(row), file=sys.stderr)
    if a.list:
        return
    tol = f"G64 P{a.tolerance:g} Q0"
    lines = [
        f"| program | motion segments | LinuxCNC 2.9, {tol} (s) | Stanok, {tol} (s) | "
        "Stanok / LinuxCNC | LinuxCNC 2.9, G64 without P (s) | Stanok / that | "
        "Stanok limit violations | Stanok contour error at junctions / elsewhere (mm) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]

    def secs(t, rc):
        return f"{t:.3f}" if t is not None else f"failed (exit {rc})"

    def ratio(t):
        return f"{r['stanok'] / t:.3f}" if t else "–"

    for r in rows:
        lines.append(f"| {r['program']} | {r['segments']} | {secs(r['lcnc'], r['lcnc_rc'])} | "
                     f"{r['stanok']:.3f} | {ratio(r['lcnc'])} | "
                     f"{secs(r['lcnc_g64'], r['lcnc_g64_rc'])} | {ratio(r['lcnc_g64'])} | "
                     f"{r['violations']} | {r['junction_mm']:.4f} / {r['elsewhere_mm']:.1e} |")
    table = "\n".join(lines)
    print(table)
    if a.out:
        with open(a.out, "w") as f:
            f.write(table + "\n")


if __name__ == "__main__":
    main()
