#!/usr/bin/env python3
"""R_n, R_s and y_R of the long standard runs (bench/window/long_runs.sh) averaged over the window the
early-stop rule picks and over the window the LIGGGHTS rig used (datasets/liggghts-rig/README.md),
each against the rig's measurement: E/u = (mean - measured) / hypot(u_measured, se), se from 0.1 s
block means. Usage: compare_windows.py OUT MEASUREMENTS_CSV"""
import csv
import math
import sys

out, measurements = sys.argv[1], sys.argv[2]
# The rig's steady windows (README "Steady state and averaging").
RIG = {'V2-26': (0.60, 1.30), 'V2-41': (0.60, 1.30), 'V3-28': (0.55, 1.15), 'V3-41': (0.55, 1.15),
       'V4-28': (0.40, 1.10), 'V4-41': (0.40, 1.10), 'V5-28': (0.45, 1.05), 'V5-44': (0.45, 1.05)}
BLOCK = 0.1


# The windows the standard runs stopped with (tests/peer/dem-cache, `window` lines).
STANDARD = {'V2-26': (0.5518, 1.0518), 'V2-41': (0.5518, 1.0518), 'V3-28': (0.4526, 0.9526),
            'V3-41': (0.4526, 0.9526), 'V4-28': (0.4025, 0.9025), 'V4-41': (0.4025, 0.9025),
            'V5-28': (0.4019, 0.9019), 'V5-44': (0.4019, 0.9019)}


def blocks(rows, a, b, col):
    vals = [(float(r['t_s']), float(r[col])) for r in rows if r[col] != '']
    means = []
    for k in range(int(round((b - a) / BLOCK))):
        lo, hi = a + BLOCK * k, a + BLOCK * (k + 1)
        xs = [v for t, v in vals if lo + 1e-9 < t <= hi + 1e-9]
        if xs:
            means.append(sum(xs) / len(xs))
    return means


def mean_se(means):
    m = sum(means) / len(means)
    sd = math.sqrt(sum((x - m) ** 2 for x in means) / (len(means) - 1))
    return m, sd / math.sqrt(len(means))


meas = {(r['condition'], r['quantity']): (float(r['value']), float(r['uncertainty']))
        for r in csv.DictReader(open(measurements))}
print("| condition | quantity | rig | chutelab, its own window | E/u | chutelab, the rig's window | E/u | 0.1 s block means from 0.4 s |")
print("|---|---|---|---|---:|---|---:|---|")
for c in RIG:
    rows = list(csv.DictReader(open(f'{out}/{c}/timeseries.csv')))
    for q in ('normal_force_N', 'shear_force_N', 'impact_point_y_mm'):
        d, ud = meas[(c, q)]
        (a, b), (ra, rb) = STANDARD[c], RIG[c]
        m1, s1 = mean_se(blocks(rows, a, b, q))
        m2, s2 = mean_se(blocks(rows, ra, rb, q))
        trace = ' '.join(f'{x:.2f}' for x in blocks(rows, 0.4, 1.3, q))
        print(f"| {c} | {q} | {d:.3f} ± {ud:.3f} | {m1:.3f} ± {s1:.3f} ({a:.2f}-{b:.2f} s) | "
              f"{(m1 - d) / math.hypot(ud, s1):+.1f} | {m2:.3f} ± {s2:.3f} ({ra:.2f}-{rb:.2f} s) | "
              f"{(m2 - d) / math.hypot(ud, s2):+.1f} | {trace} |")
