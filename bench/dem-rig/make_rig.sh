#!/usr/bin/env bash
# A virtual rig made by chutelab's own DEM with a hidden effect, for the DEM-baseline diagnosis
# (bench/log/PEER_DIAGNOSIS.md, "A drag the DEM made itself"): the bundled LIGGGHTS rig run at
# standard quality with another feed seed and the effect on, its predictions written over the rig's
# measured values (uncertainties kept). Then diagnose it as the peer rigs are diagnosed:
#   chutelab diagnose --dataset OUT/rig --models dem --dem-quality standard --signature-quality quick \
#     --dem-cache COPY --out OUT/diagnosis
# (COPY: a copy of tests/peer/dem-cache, which holds the baseline and the probes: only
# confirmations run).
# Usage: bench/dem-rig/make_rig.sh OUT EFFECT=VALUE [SEED]   e.g. make_rig.sh out/drag air_drag=1.2 77
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$1 effect=$2 seed=${3:-77}
bin=${CHUTELAB:-build/app/chutelab}
mkdir -p "$out"
rm -rf "$out/seeded"
cp -r datasets/liggghts-rig "$out/seeded"
# The feed's seed under [dem] (the rig's own file sets none: the default is 1).
sed -i "s/^\[dem\]$/[dem]\nseed = $seed/" "$out/seeded/setup.toml"
grep -q "^seed = $seed" "$out/seeded/setup.toml"
"$bin" validate --dataset "$out/seeded" --models korzen,dem --dem-quality standard --effect "$effect" \
  --dem-cache "$out/cache" --out "$out/truth" --quiet
python3 bench/dem-rig/make_rig.py "$out/truth" datasets/liggghts-rig "$out/rig"
