#!/bin/sh
# LIGGGHTS as the station engine beside chutelab's DEM (bench/LIGGGHTS_ENGINE.md): the acceptance
# run on two conditions of datasets/liggghts-rig (default V4-28 and V5-28, the fewest
# particles). From the repository root, after building. Fresh cache, so every run is really run.
#   bench/liggghts_engine.sh [CONDITION ...]
# Each engine runs each condition in its own process (up to four at once on two cores); a final
# validate of the subset then takes every run from the cache and writes the side-by-side tables.
set -eu
B=${B:-build/app/chutelab}
OUT=${OUT:-/tmp/chutelab-bench-liggghts}
CONDITIONS=${*:-V4-28 V5-28}
FLAGS="--dem-quality standard --dem-threads 1 --liggghts-time 1.1"
rm -rf "$OUT"
mkdir -p "$OUT"
CHUTELAB_DEM_CACHE="$OUT/cache"
export CHUTELAB_DEM_CACHE
subset() {  # subset DIR CONDITION...: the rows of these conditions, the rig's setup and README
  d=$1; shift
  mkdir -p "$d"
  cp datasets/liggghts-rig/setup.toml datasets/liggghts-rig/README.md "$d/"
  pattern=$(echo "$@" | sed 's/ /,|^/g')
  for f in conditions.csv measurements.csv trajectory.csv; do
    { head -1 "datasets/liggghts-rig/$f"; grep -E "^$pattern," "datasets/liggghts-rig/$f"; } >"$d/$f"
  done
}
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg) at start"
for c in $CONDITIONS; do
  subset "$OUT/data-$c" "$c"
  for m in liggghts dem; do
    ( /usr/bin/time -f "$m $c: %e s wall, %U s user (chutelab itself; LIGGGHTS runs in a child)" \
        nice $B validate --dataset "$OUT/data-$c" --models $m $FLAGS --out "$OUT/$m-$c" >"$OUT/$m-$c.log" 2>&1 || true ) &
  done
done
wait
cat "$OUT"/*.log | grep -E "wall|done"
subset "$OUT/data" $CONDITIONS
/usr/bin/time -f "validate --models liggghts,dem on the subset, from the cache: %e s wall" \
  $B validate --dataset "$OUT/data" --models liggghts,dem $FLAGS --out "$OUT/both" 2>"$OUT/both.err" || true
echo "condition, quantity, model, measured, predicted, relative error:"
awk -F, 'NR>1 && $3 !~ /trajectory/ {printf "  %s %-20s %-9s %8.3f %8.3f %+6.1f%%\n", $1, $3, $2, $4, $6, 100*$8}' "$OUT/both/errors.csv"
