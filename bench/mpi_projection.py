#!/usr/bin/env python3
"""Projection of a sensitivity study over N MPI ranks from one measured run.

Reads OUT/sensitivity.csv and OUT/sensitivity-timing.csv, deals the variants out as chutelab does
(core/campaign.cpp assign(): by the estimated cost of app/cmd_sensitivity.cpp, dearest first onto
the least loaded rank) and prints, per N, the runs of each rank, the measured seconds each rank
would spend (the runs' own wall times) and the longest single run, which no rank count beats.
Usage: bench/mpi_projection.py OUT [N ...]"""
import csv
import sys


def main():
    out = sys.argv[1]
    ns = [int(a) for a in sys.argv[2:]] or [1, 2, 4, 8]
    rows = list(csv.DictReader(open(f"{out}/sensitivity.csv")))
    secs = {r["variant"]: float(r["run_seconds"]) for r in csv.DictReader(open(f"{out}/sensitivity-timing.csv"))}
    base = rows[0]
    d0, f0 = float(base["diameter_mm"]), float(base["dt_fraction"])
    cost = []
    for r in rows:  # the formula of app/cmd_sensitivity.cpp
        c = (d0 / float(r["diameter_mm"])) ** 4 * (f0 / float(r["dt_fraction"])) * float(r["modulus_scale"]) ** 0.4
        cost.append(c * (2.7 if r["shape"] == "clump" else 1.0))
    total = sum(secs[r["variant"]] for r in rows)
    longest = max(rows, key=lambda r: secs[r["variant"]])
    print(f"{len(rows)} runs, {total:.0f} s of runs in one process; longest run {longest['variant']} "
          f"{secs[longest['variant']]:.0f} s")
    print("| ranks | runs per rank | projected wall = busiest rank's runs (s) | speed-up |")
    print("|---:|---|---:|---:|")
    for n in ns:
        order = sorted(range(len(rows)), key=lambda k: -cost[k])  # stable: ties in job order
        load, owner = [0.0] * n, [0] * len(rows)
        for k in order:
            r = min(range(n), key=lambda i: (load[i], i))
            owner[k] = r
            load[r] += cost[k]
        per = [[rows[k]["variant"] for k in range(len(rows)) if owner[k] == r] for r in range(n)]
        busy = [sum(secs[v] for v in p) for p in per]
        print(f"| {n} | {'; '.join(','.join(p) if p else '-' for p in per)} | {max(busy):.0f} | "
              f"{total / max(busy):.2f} |")


if __name__ == "__main__":
    main()
