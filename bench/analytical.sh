#!/usr/bin/env bash
# Analytical performance: per-condition estimate compute, a full validate and a full diagnose.
# Usage: bench/analytical.sh   (results are recorded in bench/ANALYTICAL.md)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build build -j"$(nproc)" --target bench_analytical chutelab >/dev/null
build/bench/analytical/bench_analytical "$PWD"
for cmd in "estimate --condition V3-41" \
           "validate --dataset datasets/hidden-effect --out /tmp/chutelab-bench-validate" \
           "diagnose --dataset datasets/hidden-effect --out /tmp/chutelab-bench-diagnose"; do
  start=$(date +%s.%N)
  build/app/chutelab $cmd >/dev/null
  end=$(date +%s.%N)
  # awk, not bc: setup.sh does not install bc, and awk's doubles resolve these stamps to ~1 us.
  awk -v c="chutelab $cmd" -v a="$start" -v b="$end" 'BEGIN { printf "wall %-90s %.3f s\n", c, b - a }'
done
