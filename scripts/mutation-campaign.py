#!/usr/bin/env python3
"""Mutation campaign against the release binary (issue 17): N runs over all eight dialects and
all program verbs (check, run, canon, plot, convert), one at a time, each with a time limit
(10 s of CPU, and 60 s of wall clock: the machine is shared, so CPU time is what measures the
work), an address-space limit (4 GiB) and an output-file limit (256 MiB), counting what must
never happen: panics (exit 101), aborts and other signals (stack overflow, allocation failure),
hangs (either time limit), runs over the memory limit, output blow-ups, and errors printed
without a location.

Programs: the examples, ../shared/corpus and LinuxCNC's sample programs (read in place), mutated
(byte flips, line duplication and deletion, huge and tiny numbers, long lines, deep and long
expressions, runaway loops, feeds and dwells), plus a few generated from nothing. Seeded, so a
run is reproducible: `scripts/mutation-campaign.py --runs 10000 --seed 1`. Failures are kept in
--out (program, command, stderr tail) and listed at the end.

Usage: scripts/mutation-campaign.py [--runs N] [--seed S] [--binary PATH] [--out DIR]
                                    [--timeout S] [--memory-gib G] [--jobs 1]
"""
import argparse, glob, os, random, resource, signal, subprocess, sys, time, json, re

DIALECTS = ["axioma", "rs274ngc", "nc31", "2p32", "mc2101", "gost20999", "mazatrol", "balt"]
VERBS = ["check", "run", "canon", "plot", "convert"]


def dialect_of(path):
    name = os.path.basename(path).lower()
    for d in DIALECTS[2:6]:
        if name.startswith(d + "-") or name.startswith(d + "_"):
            return d
    if "/cvu/" in path:
        return "balt"
    if "/mazatrol/" in path:
        return "mazatrol"
    if name.endswith(".ngc"):
        return "rs274ngc"
    return "axioma"


def seeds(repo, shared):
    files = []
    for pattern in [repo + "/examples/*", shared + "/corpus/**/*.nc", shared + "/corpus/**/*.ngc",
                    "/usr/share/linuxcnc/ncfiles/*.ngc"]:
        files += [p for p in glob.glob(pattern, recursive=True) if os.path.isfile(p)]
    out = []
    for p in sorted(files):
        data = open(p, "rb").read()
        if len(data) <= 256 * 1024:
            out.append((p, dialect_of(p), data))
    return out


NUMBER = re.compile(rb"[-+]?\d+\.?\d*")


def chain(rng, n, op):
    return op.join(["1"] * n)


def mutate(rng, data, dialect):
    """One to four mutations of the kinds the issue names."""
    lines = data.split(b"\n")
    for _ in range(rng.randint(1, 4)):
        kind = rng.randrange(14)
        if kind == 0:  # byte flips
            b = bytearray(b"\n".join(lines))
            for _ in range(rng.randint(1, 8) if b else 0):
                i = rng.randrange(len(b))
                b[i] = rng.randrange(256)
            lines = bytes(b).split(b"\n")
        elif kind == 1 and lines:  # duplicate a line (or a run of lines)
            i = rng.randrange(len(lines))
            k = rng.randint(1, 4)
            lines[i:i] = lines[i:i + k] * rng.choice([1, 2, 10, 1000])
        elif kind == 2 and len(lines) > 1:  # delete lines
            i = rng.randrange(len(lines))
            del lines[i:i + rng.randint(1, 5)]
        elif kind == 3 and lines:  # huge and tiny numbers
            i = rng.randrange(len(lines))
            v = rng.choice([b"1e308", b"99999999999999999999999999", b"0.0000001", b"1e-300",
                            b"-0", b"4294967296", b"65536", b"nan", b"999999999"])
            lines[i] = NUMBER.sub(lambda m: v if rng.random() < 0.5 else m.group(0), lines[i], count=3)
        elif kind == 4 and lines:  # long lines
            i = rng.randrange(len(lines))
            pad = rng.choice([b" ", b"X1 ", b"G1 X1 ", b"(", b"a", b"1"]) * rng.choice([1000, 70000, 300000])
            lines[i] = lines[i] + pad + rng.choice([b"", b"G999", b")"])
        elif kind == 5:  # long expressions
            n = rng.choice([300, 5000, 20000])
            if dialect in ("rs274ngc", "mazatrol"):
                e = b"G1 X[" + chain(rng, n, rng.choice(["+", " AND ", "*", "-"])).encode() + b"] F100"
            else:
                e = rng.choice([b"double aa = ", b"G0 X="]) + chain(rng, n, rng.choice(["+", "&&", "*"])).encode() + b";"
            lines.insert(rng.randrange(len(lines) + 1), e)
        elif kind == 6:  # deep expressions
            n = rng.choice([70, 1000, 100000])
            if dialect in ("rs274ngc", "mazatrol"):
                e = b"G1 X" + b"[" * n + b"1" + b"]" * n
            else:
                e = b"double d = " + b"(" * n + b"1" + b")" * n + b";"
            lines.insert(rng.randrange(len(lines) + 1), e)
        elif kind == 7:  # runaway loops
            if dialect in ("rs274ngc", "mazatrol"):
                body = [b"#1=0", b"o1 repeat [1000]", b"o2 repeat [1000]", b"o3 repeat [1000]",
                        b"#1=[#1+1]", b"o3 endrepeat", b"o2 endrepeat", b"o1 endrepeat"]
                if rng.random() < 0.5:
                    body = [b"o9 while [1]", b"G1 X1 F100", b"o9 endwhile"]
            else:
                body = [b"int i; int j;", b"for (i = 0; i < 100000; i++) {",
                        b"for (j = 0; j < 100000; j++) {", b"G1 X1 F100", b"}", b"}"]
                if rng.random() < 0.3:
                    body = [b"if(1){"] * 100000 + [b"}"] * 100000
            at = rng.randrange(len(lines) + 1)
            lines[at:at] = body
        elif kind == 8:  # runaway feeds and dwells
            e = rng.choice([b"G1 X100 F0.0000001", b"G4 P1000000000", b"G4 X" + b"9" * 30,
                            b"G1 X50 F0.01", b"G4 P300000", b"G1 X100 F1", b"G2 X10 Y0 I5 J0 F0.001"])
            lines.insert(rng.randrange(len(lines) + 1), e)
        elif kind == 9 and lines:  # swap two lines
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif kind == 10 and lines:  # splice a piece of another line
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            a = lines[j]
            k = rng.randrange(len(a) + 1)
            lines[i] = lines[i][:rng.randrange(len(lines[i]) + 1)] + a[k:]
        elif kind == 11 and lines:  # truncate the program
            del lines[rng.randrange(len(lines)):]
        elif kind == 12:  # many diagnostics on one line
            lines.insert(rng.randrange(len(lines) + 1), b"G1 F100 " + b"G1 X1 " * rng.choice([1000, 4000]))
        elif kind == 13 and lines:  # insert random bytes
            i = rng.randrange(len(lines))
            lines[i] = lines[i] + bytes(rng.randrange(256) for _ in range(rng.randint(1, 40)))
    return b"\n".join(lines)


def generated(rng):
    """A program from nothing: random words and numbers."""
    letters = b"GMXYZABCIJKRFSTPQDHNO#[]=+-*/ ()%;"
    return b"\n".join(bytes(rng.choice(letters) for _ in range(rng.randint(1, 60)))
                      for _ in range(rng.randint(1, 50)))


def limits(memory, fsize, cpu):
    def apply():
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 1))
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        os.setsid()
    return apply


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.dirname(here)
    ap.add_argument("--runs", type=int, default=10000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--binary", default=os.path.join(repo, "target/release/stanok"))
    ap.add_argument("--shared", default=os.environ.get("STANOK_SHARED", os.path.join(repo, "../shared")))
    ap.add_argument("--out", default="/tmp/stanok-campaign")
    ap.add_argument("--timeout", type=float, default=10.0, help="CPU seconds per run")
    ap.add_argument("--wall", type=float, default=60.0, help="wall-clock seconds per run")
    ap.add_argument("--memory-gib", type=float, default=4.0)
    ap.add_argument("--output-mib", type=int, default=256)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    pool = seeds(repo, args.shared)
    if not pool:
        sys.exit("no seed programs found")
    os.makedirs(args.out, exist_ok=True)
    work = os.path.join(args.out, "work")
    os.makedirs(work, exist_ok=True)
    memory = int(args.memory_gib * (1 << 30))
    fsize = args.output_mib << 20
    counts = {k: 0 for k in ["ok", "exit1", "other-exit", "panic", "abort", "signal", "hang",
                             "memory", "output", "unlocated"]}
    failures = []
    slowest = (0.0, None)
    slowest_wall = 0.0
    peak_rss = (0, None)
    t_start = time.time()
    for n in range(args.runs):
        if rng.random() < 0.05:
            name, dialect, data = "generated", rng.choice(DIALECTS), generated(rng)
        else:
            name, dialect, data = rng.choice(pool)
            data = mutate(rng, data, dialect)
            if rng.random() < 0.1:
                dialect = rng.choice(DIALECTS)
        verb = rng.choice(VERBS)
        ext = ".ngc" if dialect == "rs274ngc" else ".nc"
        prog = os.path.join(work, "prog" + ext)
        with open(prog, "wb") as f:
            f.write(data)
        cmd = [args.binary, verb, prog, "--dialect", dialect]
        if verb == "plot":
            cmd += ["-o", os.path.join(work, "out.svg")]
        elif verb == "convert":
            cmd += ["--to", rng.choice(["rs274ngc", "axioma"]), "-o", os.path.join(work, "out.txt")]
        out_path, err_path = os.path.join(work, "stdout"), os.path.join(work, "stderr")
        t0 = time.time()
        with open(out_path, "wb") as out, open(err_path, "wb") as err:
            p = subprocess.Popen(cmd, stdout=out, stderr=err, stdin=subprocess.DEVNULL,
                                 preexec_fn=limits(memory, fsize, int(args.timeout)))
            hung = False
            deadline = t0 + args.wall
            while True:
                pid, status, usage = os.wait4(p.pid, os.WNOHANG)
                if pid:
                    break
                if time.time() > deadline:
                    hung = True
                    os.killpg(p.pid, signal.SIGKILL)
                    pid, status, usage = os.wait4(p.pid, 0)
                    break
                time.sleep(0.002)
        wall = time.time() - t0
        dt = usage.ru_utime + usage.ru_stime
        rss = usage.ru_maxrss * 1024
        slowest_wall = max(slowest_wall, wall)
        if dt > slowest[0]:
            slowest = (dt, f"{verb} {dialect} run {n}")
        if rss > peak_rss[0]:
            peak_rss = (rss, f"{verb} {dialect} run {n}")
        stderr = open(err_path, "rb").read(1 << 20).decode("utf-8", "replace")
        kind = None
        sig = os.WTERMSIG(status) if os.WIFSIGNALED(status) else 0
        if hung:
            kind = "hang"
        elif os.WIFSIGNALED(status):
            sig = os.WTERMSIG(status)
            if sig == signal.SIGXFSZ:
                kind = "output"
            elif sig == signal.SIGXCPU:
                kind = "hang"
            elif "memory allocation" in stderr:
                kind = "memory"
            elif sig == signal.SIGABRT:
                kind = "abort"
            else:
                kind = "signal"
        else:
            code = os.WEXITSTATUS(status)
            if code == 101:
                kind = "panic"
            elif code == 134:
                kind = "abort"
            elif code == 0:
                counts["ok"] += 1
            elif code == 1:
                counts["exit1"] += 1
            else:
                counts["other-exit"] += 1
        if kind is None and rss > memory:
            kind = "memory"
        if kind is None:
            # Every error printed names a place: a miette box (`╭─[file:line:col]`), or
            # `file:line:col: error[…]`, or the file alone for a whole-file problem.
            for m in re.finditer(r"^(error\[[^\]]*\])", stderr, re.M):
                following = stderr[m.end():m.end() + 2000]
                if "╭─[" not in following.split("error[")[0]:
                    kind = "unlocated"
                    break
        if kind:
            counts[kind] += 1
            keep = os.path.join(args.out, f"{kind}-{n}{ext}")
            with open(keep, "wb") as f:
                f.write(data)
            failures.append({"run": n, "kind": kind, "verb": verb, "dialect": dialect, "seed": name,
                             "file": keep, "seconds": round(dt, 2), "wall_s": round(wall, 2), "signal": sig,
                             "rss_mib": rss >> 20,
                             "stderr_tail": stderr[-600:]})
        if (n + 1) % 500 == 0:
            print(f"{n + 1} runs, {time.time() - t_start:.0f} s: {counts}", flush=True)
    summary = {"runs": args.runs, "seed": args.seed, "counts": counts,
               "wall_s": round(time.time() - t_start, 1),
               "slowest_cpu_s": round(slowest[0], 2), "slowest": slowest[1],
               "slowest_wall_s": round(slowest_wall, 2),
               "peak_rss_mib": peak_rss[0] >> 20, "peak_rss": peak_rss[1],
               "failures": failures[:200]}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(json.dumps({k: v for k, v in summary.items() if k != "failures"}, indent=1))
    for fl in failures[:30]:
        print(f"{fl['kind']}: run {fl['run']} {fl['verb']} --dialect {fl['dialect']} {fl['file']} "
              f"({fl['seconds']} s CPU, signal {fl['signal']}, {fl['rss_mib']} MiB)\n  {fl['stderr_tail'][-300:]!r}")
    bad = sum(counts[k] for k in ["panic", "abort", "signal", "hang", "memory", "output", "unlocated"])
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
