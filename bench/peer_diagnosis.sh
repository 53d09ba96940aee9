#!/usr/bin/env bash
# The DEM-baseline diagnosis of the two peer datasets (datasets/liggghts-rig, effect-free, and
# datasets/liggghts-flowbias, one hidden effect) at standard quality, with the DEM's own signatures
# at quick quality, timed; it records every DEM run in tests/peer/dem-cache, from which the ctest
# acceptance case (tests/peer/test_peer_diagnosis.cpp) diagnoses again with --dem-cache-only.
# Usage: bench/peer_diagnosis.sh [OUT]   (after scripts/setup.sh && cmake --build build)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/peer-diagnosis}
bin=${CHUTELAB:-build/app/chutelab}
cache=tests/peer/dem-cache
mkdir -p "$out" "$cache"
lscpu | grep -m1 'Model name' || true
uptime
for ds in liggghts-rig liggghts-flowbias; do
  start=$(date +%s)
  "$bin" diagnose --dataset "datasets/$ds" --models dem --dem-quality standard \
    --signature-quality quick --dem-cache "$cache" --out "$out/$ds" 2> "$out/$ds.log"
  echo "$ds: $(( $(date +%s) - start )) s wall"
done
uptime
du -sh "$cache"
