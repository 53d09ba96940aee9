#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang + ASan + UBSan) in build/fuzz/ (where the main build puts them too) and runs them.
#   scripts/fuzz.sh build                 # build only
#   scripts/fuzz.sh run TARGET SECONDS    # one target, corpus copied from tests/fuzz/corpus/TARGET
#   scripts/fuzz.sh all SECONDS           # every target in turn
# Targets: dataset setup tolerances mapping stl dem_table studies dem_cache. Crashes are written to build/fuzz/crashes/TARGET/.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
bdir=${CHUTELAB_FUZZ_BUILD:-$root/build/fuzz}
targets=(dataset setup tolerances mapping stl dem_table studies dem_cache)

build() {
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S tests/fuzz -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    "${launcher[@]}" >/dev/null
  cmake --build "$bdir" -j"${JOBS:-2}" --target $(printf 'fuzz_%s ' "${targets[@]}") >/dev/null
}

run() {
  local t=$1 secs=$2
  local work="$bdir/corpus/$t" crashes="$bdir/crashes/$t"
  mkdir -p "$work" "$crashes"
  cp -n tests/fuzz/corpus/"$t"/* "$work"/ 2>/dev/null || true
  # rss and input limits keep a run on a shared machine small; leaks are reported by ASan.
  "$bdir/fuzz_$t" -max_total_time="$secs" -rss_limit_mb=2048 -max_len=8192 -timeout=10 \
    -artifact_prefix="$crashes/" -print_final_stats=1 "$work" 2>&1 | tail -n 25
}

case ${1:-} in
  build) build ;;
  run) [[ -x "$bdir/fuzz_$2" ]] || build; run "$2" "$3" ;;
  all) build; for t in "${targets[@]}"; do run "$t" "$2"; done ;;
  *) echo "usage: $0 build | run TARGET SECONDS | all SECONDS" >&2; exit 2 ;;
esac
