#!/usr/bin/env bash
# The eight standard runs of the LIGGGHTS rig carried on to 1.3 s, past the early stop, so that their
# R_s and y_R can be averaged over the windows the rig itself used (bench/WINDOW.md).
#   bench/window/long_runs.sh BIN OUT     BIN: a chutelab binary; OUT: a new folder
# The runs use a copy of datasets/liggghts-rig whose [dem] asks for a 1.0 s steady window within
# 1.3 s, which no run finds, so every run goes on to 1.3 s. Same seed as the standard runs, so up to
# its early stop each long run is the standard run.
set -euo pipefail
bin=${1:?chutelab binary}
out=${2:?output folder}
here=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
cp -r "$here/datasets/liggghts-rig" "$out/rig"
sed -i 's/^rolling_lever = "effective"/rolling_lever = "effective"\nmax_time_s = 1.3\nmin_window_s = 1.0/' "$out/rig/setup.toml"
grep -q '^max_time_s = 1.3' "$out/rig/setup.toml"
# Each run's own report goes to OUT/<condition>.log; only the table is printed.
export bin out
printf '%s\n' V2-41 V5-44 V3-41 V4-41 V2-26 V3-28 V4-28 V5-28 |
  xargs -P "$(nproc)" -I{} sh -c '"$bin" simulate --dataset "$out/rig" --condition {} --quality standard --threads 1 \
    --no-cache --quiet --out "$out/{}" >"$out/{}.log" 2>&1'

python3 "$here/bench/window/compare_windows.py" "$out" "$here/datasets/liggghts-rig/measurements.csv"
