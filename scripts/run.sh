#!/usr/bin/env bash
# The main job: set up, build, and show on bundled measurements the loop chutelab exists for. The
# measurements (datasets/hidden-effect) hide one physical effect the models do not have; validate
# finds where the models fail, the diagnosis names what is missing, the effect is added, fitted, and
# the error falls. Prints a few lines in plain words and where the report is.
# Usage: scripts/run.sh [DATASET]   (the same loop on another dataset; output in out/<its name>/)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# The compiler's output goes to a log and is shown only when the build fails.
log=build/build.log
start=$SECONDS
printf 'chutelab: building (the first time takes about 15 min on 2 cores) ... '
if ! cmake --build build -j"$(nproc)" --target chutelab chutelab_python >"$log" 2>&1; then
  echo "failed"
  tail -n 40 "$log"
  echo "chutelab: the build failed; the whole log is $log"
  exit 1
fi
elapsed=$((SECONDS - start))
printf 'done in %d min %02d s\n' $((elapsed / 60)) $((elapsed % 60))
dataset=${1:-datasets/hidden-effect}
out="out/$(basename "$dataset")"
echo "chutelab validate --dataset $dataset --add-missing --out $out"
# The recorded calibration and sensitivity studies of the reference study's rig (bench/) join the report.
exec build/app/chutelab validate --dataset "$dataset" --add-missing --studies bench/calibration,bench/sensitivity \
  --out "$out"
