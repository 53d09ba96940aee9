#!/usr/bin/env bash
# The designer's page: time per input change of its WebAssembly estimate (node, same module as the
# browser), beside the native command doing the same (one design, JSON + SVG) as a whole process.
# Usage: bench/design_page.sh   (results are recorded in bench/DESIGN_PAGE.md)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build build -j"$(nproc)" --target chutelab >/dev/null
uptime
NODE_PATH=/usr/share/nodejs node bench/design/page_speed.js build
start=$(date +%s.%N)
for i in $(seq 50); do
  build/app/chutelab estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --format json --svg /tmp/chutelab-bench.svg >/dev/null
done
end=$(date +%s.%N)
awk -v a="$start" -v b="$end" 'BEGIN { printf "native one design (json + svg), whole process  %.2f ms\n", (b - a) / 50 * 1e3 }'
uptime
