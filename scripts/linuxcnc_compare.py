#!/usr/bin/env python3
"""Compares a LinuxCNC `rs274 -g` trace with `stanok canon` output by the rules of
crates/stanok-rs274/tests/rs274_traces.rs: line by line, numbers within 1e-4; when LinuxCNC
stopped with an error, Stanok must stop on the same block with nothing moved after the last
common line (Stanok commits a block all or nothing, LinuxCNC prints the failing block's calls
up to the error).

  linuxcnc_compare.py LINUXCNC_TRACE STANOK_TRACE PROGRAM
Prints one line: `same`, or `differs: <reason>`; exit status 0/1.
"""
import re
import sys

NUM = re.compile(r"-?\d+\.\d+(?:e[-+]?\d+)?")
# Numbers are printed with 4 decimals: two values a rounding apart differ by 1e-4 exactly.
TOL = 1.0001e-4


def read(path):
    lines, tail = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for raw in f:
            raw = raw.rstrip("\n")
            m = re.match(r"^\s*\d+ (N[.\d ]{5}) (.*)$", raw)
            if m:
                call = m.group(2)
                if call.startswith("ON_RESET()"):
                    rest = call[len("ON_RESET()"):].strip()
                    if rest:
                        tail.append(rest)
                    continue
                lines.append(m.group(1) + " " + call)
            elif raw.strip() and raw.strip() != "executing":
                tail.append(raw)
    return lines, tail


def same(a, b):
    na, nb = NUM.findall(a), NUM.findall(b)
    if NUM.sub("#", a) != NUM.sub("#", b) or len(na) != len(nb):
        return False
    return all(abs(float(x) - float(y)) <= TOL for x, y in zip(na, nb))


def main():
    lx, lx_tail = read(sys.argv[1])
    st, st_tail = read(sys.argv[2])
    lx_error = lx_tail[0] if lx_tail else None
    st_error = next((t for t in st_tail if "×" in t), None)
    for i, (a, b) in enumerate(zip(st, lx)):
        if not same(a, b):
            print(f"differs: line {i + 1}: stanok {a!r} linuxcnc {b!r}")
            return 1
    if lx_error is None and st_error is None:
        if len(st) != len(lx):
            print(f"differs: {len(st)} lines vs LinuxCNC {len(lx)}")
            return 1
        print("same")
        return 0
    if lx_error is None:
        print(f"differs: stanok stopped: {st_error.strip()}")
        return 1
    if st_error is None:
        print(f"differs: linuxcnc stopped ({lx_error}), stanok ran it")
        return 1
    head = lx_error.split(":")[0]
    if not st_error.strip().lstrip("×").strip().startswith(head):
        print(f"differs: error {st_error.strip()!r}, LinuxCNC {lx_error!r}")
        return 1
    extra = [l for l in lx[len(st):] if "STRAIGHT_" in l or "ARC_FEED" in l or "NURBS" in l]
    if extra:
        print(f"differs: LinuxCNC moved before its error: {extra[0]}")
        return 1
    print("same (both stop: " + lx_error + ")")
    return 0


sys.exit(main())
