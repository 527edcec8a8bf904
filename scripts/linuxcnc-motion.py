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
     limits, BRISK, the same zero-length tool table);
  3. measures both traces the same way: lcnc-sim's motion_time_s, "from the last sample before
     the first position change to the first sample after the last change", which on Stanok's
     trace is the same rule applied to its setpoints;
  4. prints a Markdown table (program, segments, LinuxCNC s, Stanok s, ratio, Stanok's limit
     violations, Stanok's contour error at junctions) and writes it to --out.

Programs whose LinuxCNC run fails (exit status != 0) are listed as such.

Usage: scripts/linuxcnc-motion.py [--stanok target/debug/stanok] [--out FILE] [--list]
       [--max-seconds 400] [--keep DIR] [--lcnc-cache FILE] [PROGRAM ...]
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


def lcnc_run(prog, keep, timeout):
    out = os.path.join(keep, os.path.basename(prog) + ".lcnc.csv")
    r = subprocess.run(
        [os.path.join(LCNC, "run.sh"), prog, out, "--vmax", "100", "--amax", "1000",
         "--timeout", str(timeout)],
        capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if line.startswith("SUMMARY"):
            fields = dict(f.split("=", 1) for f in line.split()[1:] if "=" in f)
            return float(fields["motion_time_s"]), fields.get("limits", "?"), r.returncode
    return None, None, r.returncode


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--stanok", default=os.path.join(ROOT, "target", "debug", "stanok"))
    ap.add_argument("--out", help="write the Markdown table here too")
    ap.add_argument("--list", action="store_true", help="only classify the samples")
    ap.add_argument("--max-seconds", type=float, default=400.0,
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
        rep, st = stanok_run(a.stanok, prog, keep)
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
        cache = {}
        if a.lcnc_cache and os.path.exists(a.lcnc_cache):
            with open(a.lcnc_cache) as f:
                cache = json.load(f)
        if prog in cache:
            lt, limits, rc = cache[prog]
        else:
            lt, limits, rc = lcnc_run(prog, keep, int(max(300, 3 * st + 120)))
            if a.lcnc_cache and rc == 0:
                cache[prog] = [lt, limits, rc]
                with open(a.lcnc_cache, "w") as f:
                    json.dump(cache, f, indent=1, sort_keys=True)
        row = {
            "program": os.path.relpath(prog, "/usr/share"),
            "segments": rep["motion_segments"],
            "lcnc": lt,
            "lcnc_limits": limits,
            "lcnc_rc": rc,
            "stanok": st,
            "violations": rep["violation_count"],
            "junction_mm": rep["contour_error"]["junctions"]["max_mm"],
        }
        rows.append(row)
        print(json.dumps(row), file=sys.stderr)
    if a.list:
        return
    lines = [
        "| program | motion segments | LinuxCNC 2.9 (s) | Stanok (s) | Stanok / LinuxCNC | "
        "Stanok limit violations | Stanok contour error at junctions (mm) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["lcnc"] is None:
            lines.append(f"| {r['program']} | {r['segments']} | failed (exit {r['lcnc_rc']}) | "
                         f"{r['stanok']:.3f} | – | {r['violations']} | {r['junction_mm']:.4f} |")
            continue
        lines.append(f"| {r['program']} | {r['segments']} | {r['lcnc']:.3f} | {r['stanok']:.3f} | "
                     f"{r['stanok'] / r['lcnc']:.3f} | {r['violations']} | {r['junction_mm']:.4f} |")
    table = "\n".join(lines)
    print(table)
    if a.out:
        with open(a.out, "w") as f:
            f.write(table + "\n")


if __name__ == "__main__":
    main()
