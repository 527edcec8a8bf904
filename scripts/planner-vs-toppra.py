#!/usr/bin/env python3
"""Stanok's BRISK planner against the acceleration-limited time-optimal bound (toppra).

For each reference path this script
  1. writes the path as points (x,y,z in mm) and runs Stanok's planner on it
     (`planner_time` example of stanok-motion: the built-in mill, 1 ms servo period);
  2. computes the time-optimal time of the same path under the same limits with toppra
     (the `toppra` Python package, `python3 -m pip install toppra`):
     per-axis velocity 10 000 mm/min and acceleration 1000 mm/s^2, and the path feed F as a
     velocity limit on a fourth pseudo-joint equal to the arc length (so ds/dt <= F).

What "the same path" means (the honest fine print):
  * square: four 100 mm sides, each side from rest to rest (a sharp corner forces a stop in any
    planner): Stanok runs G61/G60 exact stop; toppra each side as a straight path.
  * circle (200 chords, r = 50 mm), spiral (10 000 chords, r 5 -> 50 mm over 10 turns) and the
    3-D finishing path (a raster of 40 rows x 100 points over a wavy surface, rows joined by short
    links): Stanok runs the *polyline* under G64 with P = 0.01 mm (its corners blended within
    0.01 mm); toppra runs the smooth cubic spline through the same vertices. The spline is the
    path the polyline approximates; the two differ by less than the chord error.
Ratio = Stanok / toppra; the target is <= 1.03.

Usage: scripts/planner-vs-toppra.py [--stanok PATH_TO_planner_time] [--feed 5000]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

V_AXIS = 10000.0 / 60.0  # mm/s
A_AXIS = 1000.0  # mm/s^2


def square():
    return [(0, 0, 0), (100, 0, 0), (100, 100, 0), (0, 100, 0), (0, 0, 0)]


def circle(n=200, r=50.0):
    return [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n), 0.0) for k in range(n + 1)]


def spiral(n=10000, r0=5.0, r1=50.0, turns=10):
    pts = []
    for k in range(n + 1):
        f = k / n
        a = 2 * math.pi * turns * f
        r = r0 + (r1 - r0) * f
        pts.append((r * math.cos(a), r * math.sin(a), 0.0))
    return pts


def finishing(rows=40, cols=100):
    pts = []
    for i in range(rows):
        y = i * 1.0
        xs = [j * 1.0 for j in range(cols)]
        if i % 2:
            xs.reverse()
        for x in xs:
            pts.append((x, y, 5.0 * math.sin(x / 10.0) * math.cos(y / 15.0)))
    return pts


def toppra_time(points, feed, smooth):
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    ta.setup_logging("WARNING")
    p = np.array(points, dtype=float)
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    # Fourth pseudo-joint: the arc length itself; its velocity limit is the feed.
    way = np.column_stack([p, s])
    if smooth:
        path = ta.SplineInterpolator(s, way)
        grid = min(max(len(points) * 2, 1000), 20000)
    else:
        path = ta.SplineInterpolator(s, way, bc_type="natural") if len(points) > 2 else None
        if path is None:
            path = ta.SplineInterpolator([0.0, s[-1]], way[[0, -1]], bc_type="clamped")
        grid = 1000
    vlim = np.array([[-V_AXIS, V_AXIS]] * 3 + [[-feed, feed]])
    alim = np.array([[-A_AXIS, A_AXIS]] * 3 + [[-1e9, 1e9]])
    pc_vel = constraint.JointVelocityConstraint(vlim)
    pc_acc = constraint.JointAccelerationConstraint(alim, discretization_scheme=constraint.DiscretizationType.Interpolation)
    gridpoints = np.linspace(0.0, path.duration, grid + 1)
    inst = algo.TOPPRA([pc_vel, pc_acc], path, gridpoints=gridpoints, parametrizer="ParametrizeConstAccel")
    traj = inst.compute_trajectory(0, 0)
    if traj is None:
        return float("nan")
    return float(traj.duration)


def stanok_time(exe, points, feed, mode, tol):
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        for q in points:
            f.write("%.9f,%.9f,%.9f\n" % q)
        name = f.name
    try:
        out = subprocess.run([exe, name, str(feed * 60.0), mode, str(tol)], capture_output=True, text=True, check=True).stdout
    finally:
        os.unlink(name)
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--stanok", default=os.path.join(here, "..", "target", "release", "examples", "planner_time"))
    ap.add_argument("--feed", type=float, default=5000.0, help="path feed, mm/min")
    args = ap.parse_args()
    feed = args.feed / 60.0
    rows = []
    # Square: each side rest to rest.
    sq = square()
    t_top = sum(toppra_time([sq[k], sq[k + 1]], feed, smooth=False) for k in range(4))
    r = stanok_time(args.stanok, sq, feed, "exact", 0.0)
    rows.append(("square 4 x 100 mm, exact stop", 4, r, t_top))
    for name, pts in [
        ("circle r 50 mm, 200 chords, G64 P0.01", circle()),
        ("spiral 10 000 chords, G64 P0.01", spiral()),
        ("3-D finishing raster, 4 000 points, G64 P0.01", finishing()),
    ]:
        r = stanok_time(args.stanok, pts, feed, "g64", 0.01)
        rows.append((name, len(pts) - 1, r, toppra_time(pts, feed, smooth=True)))
    print("| path | segments | Stanok BRISK (s) | toppra optimum (s) | ratio | limit violations |")
    print("|---|---|---|---|---|---|")
    for name, n, r, t in rows:
        print("| %s | %d | %.3f | %.3f | %.3f | %d |" % (name, n, r["time_s"], t, r["time_s"] / t, r["violations"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
