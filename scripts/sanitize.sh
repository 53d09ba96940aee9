#!/usr/bin/env bash
# Builds chutelab's test suite with AddressSanitizer + UndefinedBehaviorSanitizer and runs it. Any
# sanitizer report fails the run (halt_on_error; UBSan does not recover).
#
# With clang (the default when clang++ is found): the suite is built inside the fuzz targets' project
# (tests/fuzz, CHUTELAB_SANITIZE_TESTS=ON) in build/fuzz, with the very flags of the fuzz targets'
# libraries (-fsanitize=address,undefined -O1, plus libFuzzer's coverage instrumentation), so the
# libraries the fuzzers were built with are reused, not rebuilt. Without clang: g++ in build-asan/.
#
# Usage: scripts/sanitize.sh [ctest args]     e.g. scripts/sanitize.sh -R "test_cli|test_validation"
#   SANITIZE_TARGETS="chutelab test_cli ..."   build only these (then pick their tests with ctest -R)
#   SANITIZE_BUILD_ONLY=1                      build, do not run
#   JOBS=N                                     parallel build and test jobs (default 2)
# Left out always: the Python package (a sanitized module cannot load into an unsanitized
# interpreter) and the designer's WebAssembly page (em++, not native code).
# Result of the last recorded run: tests/SANITIZERS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if command -v clang++ >/dev/null && [[ ${SANITIZE_COMPILER:-clang} == clang ]]; then
  bdir=${CHUTELAB_SANITIZE_BUILD:-build/fuzz}
  cmake -S tests/fuzz -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$(command -v clang++)" \
    "${launcher[@]}" -DCHUTELAB_SANITIZE_TESTS=ON -DCHUTELAB_WASM=OFF >/dev/null
else
  bdir=${CHUTELAB_ASAN_BUILD:-build-asan}
  flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1"
  cmake -S . -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" -DCHUTELAB_FUZZ=OFF \
    -DCHUTELAB_PYTHON=OFF -DCHUTELAB_WASM=OFF \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
fi
if [[ -n ${SANITIZE_TARGETS:-} ]]; then
  read -r -a targets <<<"$SANITIZE_TARGETS"
else
  # Every test executable ctest knows of, and the command line they drive.
  mapfile -t known < <(cmake --build "$bdir" --target help | sed -n 's/^\.\.\. \([A-Za-z0-9_]*\).*/\1/p')
  targets=(chutelab)
  while read -r t; do
    printf '%s\n' "${known[@]}" | grep -qx "$t" && targets+=("$t")
  done < <(ctest --test-dir "$bdir" -N | sed -n 's/^ *Test *#[0-9]*: //p')
fi
cmake --build "$bdir" -j"${JOBS:-2}" --target "${targets[@]}" >/dev/null
[[ ${SANITIZE_BUILD_ONLY:-0} == 1 ]] && exit 0
# OpenMP's runtime keeps thread pools alive at exit, and Open MPI's libraries keep their own state
# past MPI_Finalize: leaks from those are not ours.
supp=$(mktemp)
trap 'rm -f "$supp"' EXIT
printf 'leak:libgomp\nleak:libomp\nleak:libmpi\nleak:libopen-pal\nleak:libopen-rte\nleak:libhwloc\nleak:libevent\nleak:libpmix\nleak:mca_\n' >"$supp"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$supp"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
exclude=(-E "test_python|test_design_page")
[[ " $* " == *" -E "* ]] && exclude=()  # a caller's -E replaces it (then name those two as well)
ctest --test-dir "$bdir" -j"${JOBS:-2}" --output-on-failure --timeout 3000 "${exclude[@]}" "$@"
