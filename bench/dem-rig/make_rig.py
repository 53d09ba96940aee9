#!/usr/bin/env python3
"""A virtual rig from chutelab's own DEM: the bundled LIGGGHTS rig's conditions, uncertainties and
layout, its measured values replaced by a DEM run of that rig with a hidden effect (another seed of
the particle feed, so the baseline the diagnosis runs is not the run that made the data).

Usage: make_rig.py TRUTH_OUT RIG_DIR OUT_DIR
  TRUTH_OUT: the --out folder of `chutelab validate --models korzen,dem` on the seeded copy
  RIG_DIR:   the rig the truth was made from (datasets/liggghts-rig)
  OUT_DIR:   the new dataset (created; must not exist)
"""
import csv
import shutil
import sys
from pathlib import Path


def main():
    truth, rig, out = (Path(a) for a in sys.argv[1:4])
    if out.exists():
        sys.exit(f"{out}: exists; give a new folder")
    pred = {}
    with open(truth / "predictions.csv", newline="") as f:
        for row in csv.DictReader(f):
            if row["model"] != "dem":
                continue
            x = row["x_mm"]
            pred[(row["condition"], row["quantity"], float(x) if x else None)] = float(row["value"])
    shutil.copytree(rig, out)
    for name, key in (("measurements.csv", lambda r: (r["condition"], r["quantity"], None)),
                      ("trajectory.csv", lambda r: (r["condition"], f"trajectory_{r['boundary']}_y_mm", float(r["x_mm"])))):
        with open(rig / name, newline="") as f:
            reader = csv.DictReader(f)
            rows, fields = list(reader), reader.fieldnames
        column = "value" if name == "measurements.csv" else "y_mm"
        for r in rows:
            k = key(r)
            if k not in pred:
                sys.exit(f"{truth / 'predictions.csv'}: no DEM prediction of {k} for {name}")
            r[column] = f"{pred[k]:.6g}"
        with open(out / name, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
