#!/usr/bin/env bash
# The main job: set up, build, validate the models against the bundled reference dataset
# (datasets/liggghts-rig, a virtual experiment of the rig made with LIGGGHTS) and diagnose what they
# miss. Writes out/<dataset>/ and prints where the report is. Usage: scripts/run.sh [DATASET]
# The DEM runs at quick quality (about half a minute for eight conditions the first time, cached after).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build build -j"$(nproc)" --target chutelab chutelab_python >/dev/null
dataset=${1:-datasets/liggghts-rig}
# The recorded calibration and sensitivity studies (bench/, seed Tables 3 and 6) join the report.
exec build/app/chutelab validate --dataset "$dataset" --models korzen,booth-cema,dem --diagnose \
  --studies bench/calibration,bench/sensitivity --out "out/$(basename "$dataset")"
