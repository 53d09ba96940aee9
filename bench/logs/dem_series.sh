#!/bin/sh
# Logs whose stream fluctuation is the DEM's own (bench/LOGS.md): one quick DEM run a condition of
# the hidden-effect rig, the virtual rig's logs from the true means with that fluctuation on them,
# SEEDS seeds, each read back by import-logs; prints coverage and RMS z per quantity.
#   bench/logs/dem_series.sh build/app/chutelab WORK [SEEDS]
set -eu
B=$1; W=$2; N=${3:-25}
mkdir -p "$W"
"$B" synthesize --dataset datasets/grima2010 --effect air_drag=0.7 --noise-scale 0 --out "$W/truth" >/dev/null
for c in V2-26 V2-41 V3-28 V3-41 V4-28 V4-41 V5-28 V5-44; do
  [ -f "$W/dem/$c/timeseries.csv" ] ||
    "$B" simulate --dataset datasets/hidden-effect --condition "$c" --quality quick --threads 1 --quiet \
        --out "$W/dem/$c" >/dev/null
done
for s in $(seq 1 "$N"); do
  "$B" synthesize-logs --dataset datasets/hidden-effect --truth "$W/truth/measurements.csv" --dem-series "$W/dem" \
      --seed "$s" --out "$W/l$s" >/dev/null
  "$B" import-logs --dataset "$W/l$s" --out "$W/m$s" >/dev/null 2>&1
done
python3 - "$W" "$N" <<'PY'
import csv, math, sys
W, N = sys.argv[1], int(sys.argv[2])
truth = {(r['condition'], r['quantity']): float(r['value']) for r in csv.DictReader(open(f"{W}/truth/measurements.csv"))}
stats = {}
for s in range(1, N + 1):
    for r in csv.DictReader(open(f"{W}/m{s}/measurements.csv")):
        if not r['source_file']:
            continue
        z = (float(r['value']) - truth[(r['condition'], r['quantity'])]) / float(r['uncertainty'])
        st = stats.setdefault(r['quantity'], [0, 0, 0.0])
        st[0] += 1
        st[1] += abs(z) <= 2
        st[2] += z * z
print("| quantity | logs | ±2 u covers the truth | RMS z |\n|---|---:|---:|---:|")
for q, (n, c, z2) in stats.items():
    print(f"| {q} | {n} | {100 * c / n:.0f} % | {math.sqrt(z2 / n):.2f} |")
PY
