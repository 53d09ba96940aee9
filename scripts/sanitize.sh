#!/usr/bin/env bash
# Builds the whole test suite with AddressSanitizer + UndefinedBehaviorSanitizer (g++, the main
# compiler) in build-asan/ and runs it. Any sanitizer report fails the run (halt_on_error, and UBSan
# does not recover). Usage: scripts/sanitize.sh [ctest args], e.g. scripts/sanitize.sh -LE dem-calibration
# The Python package (a sanitized module cannot load into an unsanitized interpreter) and the
# designer's WebAssembly page (em++, not native code) are left out; their tests report "not run".
# Result of the last recorded run: tests/SANITIZERS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bdir=${CHUTELAB_ASAN_BUILD:-build-asan}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1"
cmake -S . -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" -DCHUTELAB_FUZZ=OFF \
  -DCHUTELAB_PYTHON=OFF -DCHUTELAB_WASM=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
# SANITIZE_TARGETS="chutelab test_cli ...": build only these (then pick their tests with ctest -R).
targets=()
[[ -n ${SANITIZE_TARGETS:-} ]] && targets=(--target $SANITIZE_TARGETS)
cmake --build "$bdir" -j"${JOBS:-2}" "${targets[@]}" >/dev/null
[[ ${SANITIZE_BUILD_ONLY:-0} == 1 ]] && exit 0
# OpenMP's runtime keeps thread pools alive at exit, and Open MPI's libraries keep their own state
# past MPI_Finalize: leaks from those are not ours.
supp=$(mktemp)
trap 'rm -f "$supp"' EXIT
printf 'leak:libgomp\nleak:libmpi\nleak:libopen-pal\nleak:libopen-rte\nleak:libhwloc\nleak:libevent\nleak:libpmix\nleak:mca_\n' >"$supp"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$supp"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
ctest --test-dir "$bdir" -j"${JOBS:-2}" --output-on-failure --timeout 3000 "$@"
