#!/usr/bin/env bash
# The main job: set up, build, and validate the models against the bundled reference dataset
# (datasets/liggghts-rig, a virtual experiment of the rig made with LIGGGHTS), then diagnose what
# the models miss. Writes out/liggghts-rig/ and prints where the report is.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build build -j"$(nproc)" --target chutelab >/dev/null
dataset=${1:-datasets/liggghts-rig}
out=out/$(basename "$dataset")
status=0
build/app/chutelab validate --dataset "$dataset" --out "$out" || status=$?
build/app/chutelab diagnose --dataset "$dataset" --out "$out"
exit "$status"
