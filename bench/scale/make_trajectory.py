#!/usr/bin/env python3
"""The LIGGGHTS rig with a trajectory.csv of N rows (a large trajectory file): each condition's upper and
lower stream limit measured at N / (2 x conditions) evenly spaced x values from 100 mm to 60 mm
before the plate, on a plausible parabola. The benchmark measures time, memory and report size.
Usage: make_trajectory.py N OUT_DIR"""
import csv, os, shutil, sys

n, out = int(sys.argv[1]), sys.argv[2]
rig = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "datasets", "liggghts-rig")
shutil.copytree(rig, out, dirs_exist_ok=True)
conds = list(csv.DictReader(open(os.path.join(rig, "conditions.csv"))))
per = n // (2 * len(conds))
with open(os.path.join(out, "trajectory.csv"), "w") as t:
    t.write("condition,boundary,x_mm,y_mm,uncertainty_mm\n")
    for c in conds:
        xmax = float(c["plate_distance_mm"]) - 60
        for b, y0 in (("upper", 150.0), ("lower", 120.0)):
            for k in range(per):
                x = 100 + (xmax - 100) * k / per
                t.write(f"{c['condition']},{b},{x:.6f},{y0 - 0.0005 * x * x:.3f},1.0\n")
