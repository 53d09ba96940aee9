#!/bin/sh
# Timings of the DEM transfer station (bench/log/STATION.md). From the repository root, after building
# (scripts/setup.sh && cmake --build build). Uses a fresh DEM cache so every run is really run.
#   bench/station.sh            quick: one condition, validate x8, validate x8 again (from the cache)
#   bench/station.sh standard   also the standard (9 mm) validate of the LIGGGHTS rig (~30-60 min)
set -eu
B=build/app/chutelab
OUT=${OUT:-/tmp/chutelab-bench-station}
rm -rf "$OUT"
mkdir -p "$OUT"
CHUTELAB_DEM_CACHE="$OUT/cache"
export CHUTELAB_DEM_CACHE
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at start"
/usr/bin/time -f "quick simulate V3-41: %e s wall, %U s user" \
  $B simulate --dataset datasets/liggghts-rig --condition V3-41 --no-cache --out "$OUT/quick-V3-41" >"$OUT/quick-V3-41.txt"
/usr/bin/time -f "quick simulate V2-41 (most particles): %e s wall, %U s user" \
  $B simulate --dataset datasets/liggghts-rig --condition V2-41 --no-cache --out "$OUT/quick-V2-41" >"$OUT/quick-V2-41.txt"
/usr/bin/time -f "quick validate x8 (korzen,booth-cema,dem): %e s wall, %U s user" \
  $B validate --dataset datasets/liggghts-rig --models korzen,booth-cema,dem --out "$OUT/quick" 2>"$OUT/quick.err" || true
/usr/bin/time -f "quick validate x8 again, from the DEM cache: %e s wall" \
  $B validate --dataset datasets/liggghts-rig --models korzen,booth-cema,dem --out "$OUT/quick-again" 2>/dev/null || true
echo "dem vs LIGGGHTS, quick (condition, quantity, LIGGGHTS, dem, relative error):"
awk -F, '$2=="dem" && ($3=="normal_force_N" || $3=="impact_point_y_mm") {printf "  %s %-18s %8.2f %8.2f %+6.1f%%\n", $1, $3, $4, $6, 100*$8}' "$OUT/quick/errors.csv"
if [ "${1:-}" = standard ]; then
  /usr/bin/time -f "standard validate x8 (dem, 9 mm): %e s wall, %U s user" \
    $B validate --dataset datasets/liggghts-rig --models korzen,booth-cema,dem --dem-quality standard \
    --tolerances bench/station-tolerances.toml --out "$OUT/standard" 2>"$OUT/standard.err" || true
  echo "dem vs LIGGGHTS, standard:"
  awk -F, '$2=="dem" && $3 !~ /trajectory/ {printf "  %s %-20s %8.3f %8.3f %+6.1f%%\n", $1, $3, $4, $6, 100*$8}' "$OUT/standard/errors.csv"
fi
