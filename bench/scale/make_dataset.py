#!/usr/bin/env python3
"""A large synthetic-looking dataset for the scale benchmark (bench/log/SCALE.md): N conditions of the
LIGGGHTS rig's geometry at speeds 2-5 m/s and flows 20-45 t/h, each with the six measured quantities
and 8 stream points. Values are plausible, not physical truth: the benchmark measures time, not fit.
Usage: make_dataset.py N OUT_DIR"""
import os, random, shutil, sys

n, out = int(sys.argv[1]), sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
rig = os.path.join(here, "..", "..", "datasets", "liggghts-rig")
os.makedirs(out, exist_ok=True)
shutil.copy(os.path.join(rig, "setup.toml"), os.path.join(out, "setup.toml"))
rnd = random.Random(13)
with open(os.path.join(out, "conditions.csv"), "w") as c, \
     open(os.path.join(out, "measurements.csv"), "w") as m, \
     open(os.path.join(out, "trajectory.csv"), "w") as t:
    c.write("condition,belt_speed_mps,mass_flow_tph,plate_distance_mm,plate_top_mm\n")
    m.write("condition,quantity,value,uncertainty\n")
    t.write("condition,boundary,x_mm,y_mm,uncertainty_mm\n")
    for i in range(n):
        v, f = rnd.uniform(2, 5), rnd.uniform(20, 45)
        z = 300 + 100 * int(v - 2)
        name = f"C{i:05d}"
        c.write(f"{name},{v:.3f},{f:.2f},{z:.0f},250\n")
        rn = f * v / 3.6 * 0.9
        for q, val, u in (("normal_force_N", rn, 0.1), ("shear_force_N", 0.1 * rn, 0.05),
                          ("resultant_force_N", rn * 1.005, 0.1), ("impact_velocity_mps", 0.9 * v, 0.02),
                          ("exit_velocity_mps", 1.8, 0.02), ("impact_point_y_mm", 60 + 10 * v, 0.5)):
            m.write(f"{name},{q},{val:.4f},{u}\n")
        for b, dy in (("upper", 20.0), ("lower", 0.0)):
            for k in range(4):
                x = 100 + 50 * k
                y = 130 + dy - 9.81 / 2 * (x / 1000 / v) ** 2 * 1000
                t.write(f"{name},{b},{x:.1f},{y:.2f},1.0\n")
