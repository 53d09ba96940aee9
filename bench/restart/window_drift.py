#!/usr/bin/env python3
"""How steady is the steady window? For every cached standard run at the standard time step in a DEM
cache folder (default: the peer cache), the plate's R_n, R_s and impact point y_R in 0.1 s blocks
over the run's steady window, a straight line through them, and its change over the window with
the line's slope in standard errors. Summarised per condition (bench/RESTART.md).

    python3 bench/restart/window_drift.py [tests/peer/dem-cache]
"""
import glob
import math
import statistics
import sys


def line(x, dt=0.1):
    t = [i * dt for i in range(len(x))]
    tm, xm = sum(t) / len(t), sum(x) / len(x)
    sxx = sum((ti - tm) ** 2 for ti in t)
    s = sum((ti - tm) * (xi - xm) for ti, xi in zip(t, x)) / sxx
    rss = sum((xi - xm - s * (ti - tm)) ** 2 for ti, xi in zip(t, x))
    return s, math.sqrt(rss / (len(x) - 2) / sxx)


def read(path):
    cond, win, kv, forces = None, None, {}, []
    for l in open(path).read().split("\n"):
        if " = " in l:
            k, v = l.split(" = ", 1)
            kv.setdefault(k, v)
        elif l.startswith("condition "):
            cond = l.split(" ", 1)[1]
        elif l.startswith("window "):
            w = l.split()
            win = (float(w[2]), float(w[3]))
        elif l.startswith("force "):
            p = l.split()
            forces.append(tuple(float(v) for v in p[1:5]))
    return cond, win, kv, forces


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "tests/peer/dem-cache"
    per = {}
    for f in sorted(glob.glob(folder + "/*.txt")):
        cond, win, kv, forces = read(f)
        if kv.get("quality") != "standard" or kv.get("dt_fraction") != "0.10000000000000001" or not win:
            continue
        a, b = win
        n = int(round((b - a) / 0.1))
        if n < 3:
            continue
        rn, rs, y = [], [], []
        for i in range(n):
            sel = [r for r in forces if a + i * 0.1 < r[0] <= a + (i + 1) * 0.1 + 1e-12]
            N = sum(r[1] for r in sel) / len(sel)
            S = sum(r[2] for r in sel) / len(sel)
            M = sum(r[3] for r in sel) / len(sel)
            rn.append(N)
            rs.append(S)
            y.append(-M / N * 1e3)
        span = n * 0.1
        out = []
        for x, rel in ((rn, True), (rs, True), (y, False)):
            s, se = line(x)
            change = s * span / (sum(x) / len(x)) * 100 if rel else s * span
            out.append((change, s / se))
        per.setdefault(cond, []).append(out)
    print("| condition | runs | R_n change over the window | R_s change | y_R change | runs with R_s's slope > 2 se |")
    print("|---|---:|---:|---:|---:|---:|")
    for cond in sorted(per):
        runs = per[cond]
        med = [statistics.median(r[k][0] for r in runs) for k in range(3)]
        sig = sum(1 for r in runs if r[1][1] > 2.0)
        print(f"| {cond} | {len(runs)} | {med[0]:+.1f} % | {med[1]:+.1f} % | {med[2]:+.1f} mm | {sig} of {len(runs)} |")


if __name__ == "__main__":
    main()
