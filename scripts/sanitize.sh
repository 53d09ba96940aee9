#!/usr/bin/env bash
# Builds chutelab's whole test suite with AddressSanitizer + UndefinedBehaviorSanitizer (+ LeakSanitizer)
# and runs it. Any sanitizer report fails the run (halt_on_error; UBSan does not recover).
#
# With clang (the default when clang++ is found): the project itself, configured in build-san/ with
# -fsanitize=address,undefined at -O2 (-gline-tables-only for file:line in reports), without the fuzz
# targets' coverage instrumentation. The ASan runtime is linked as a shared library
# (-shared-libasan, found through an rpath), so that the Python package can run in the system
# interpreter with that same runtime preloaded (test_python), and the chutelab binary that pytest
# starts shares it instead of refusing a second copy. The designer's page is built by em++ as in the
# normal build; its native side (chutelab design, the test driving Chromium) is sanitized. The fuzz
# smoke tests build and run tests/fuzz's own ASan + UBSan targets. Without clang: g++ in build-asan/
# (no Python package there).
#
# Usage: scripts/sanitize.sh [ctest args]     e.g. scripts/sanitize.sh -R "test_cli|test_validation"
#   SANITIZE_TARGETS="chutelab test_cli ..."   build only these (then pick their tests with ctest -R)
#   SANITIZE_BUILD_ONLY=1                      build, do not run
#   JOBS=N                                     parallel build and test jobs (default 2)
#   SANITIZE_TIMEOUT_FACTOR=N                  multiplies the tests' own time limits (default 5)
# Result of the last recorded run: tests/SANITIZERS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
factor=${SANITIZE_TIMEOUT_FACTOR:-5}
sanitize="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
asan_options="halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1"
python_env=()
if command -v clang++ >/dev/null && [[ ${SANITIZE_COMPILER:-clang} == clang ]]; then
  bdir=${CHUTELAB_SANITIZE_BUILD:-build-san}
  asan_rt=$(clang++ -print-file-name=libclang_rt.asan-x86_64.so)
  link="$sanitize -shared-libasan -Wl,-rpath,$(dirname "$asan_rt")"
  # The MPI ranks of mpi_campaign (and no other process: Open MPI applies mca_base_env_list to the
  # ranks it starts, not to mpirun; the LIGGGHTS runs of other tests never see it). MPI_Finalize
  # dlcloses Open MPI's MCA components, so LeakSanitizer's report at exit finds their allocations
  # under code no longer mapped (`<unknown module>`), which no suppression by library name matches.
  # In the ranks: dlclose does nothing (a preloaded two-line library, after the ASan runtime, which
  # must come first and whose dlclose interceptor calls it), so the components stay mapped and
  # named; and malloc stacks are unwound in full (fast_unwind_on_malloc=0), since Open MPI is built
  # without frame pointers and the fast unwinder stops inside it (a leak under libc's vasprintf,
  # called by libopen-pal, had no other frame). Leaks under chutelab's own frames are still reported.
  mkdir -p "$bdir"
  keep_dso=$(realpath "$bdir")/keep-dlopened.so
  printf 'int dlclose(void* handle) { (void)handle; return 0; }\n' |
    clang++ -x c -shared -fPIC -O2 -o "$keep_dso" -
  mpi_env="OMPI_MCA_mca_base_env_list_delimiter=|;OMPI_MCA_mca_base_env_list=LD_PRELOAD=$asan_rt:$keep_dso|ASAN_OPTIONS=$asan_options:fast_unwind_on_malloc=0"
  cmake -S . -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$(command -v clang++)" \
    "${launcher[@]}" -DCMAKE_CXX_FLAGS="$sanitize -shared-libasan" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DCMAKE_EXE_LINKER_FLAGS="$link" -DCMAKE_SHARED_LINKER_FLAGS="$link" -DCMAKE_MODULE_LINKER_FLAGS="$link" \
    -DCHUTELAB_TEST_TIMEOUT_FACTOR="$factor" -DCHUTELAB_TEST_PYTHON_ENV="LD_PRELOAD=$asan_rt" \
    -DCHUTELAB_TEST_MPI_ENV="$mpi_env" >/dev/null
else
  bdir=${CHUTELAB_ASAN_BUILD:-build-asan}
  cmake -S . -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" -DCHUTELAB_FUZZ=OFF \
    -DCHUTELAB_PYTHON=OFF -DCHUTELAB_WASM=OFF -DCMAKE_CXX_FLAGS="$sanitize -g -O2" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCHUTELAB_TEST_TIMEOUT_FACTOR="$factor" >/dev/null
fi
# A lookup table, not `printf | grep -q`: grep quitting early would fail printf with SIGPIPE, and
# pipefail would then count a target that exists as missing.
declare -A known=()
while read -r t; do known[$t]=1; done < <(cmake --build "$bdir" --target help | sed -n 's/^\.\.\. \([A-Za-z0-9_]*\).*/\1/p')
has_target() { [[ -n ${known[$1]:-} ]]; }
if [[ -n ${SANITIZE_TARGETS:-} ]]; then
  read -r -a targets <<<"$SANITIZE_TARGETS"
else
  # Every test executable ctest knows of, the command line they drive, the Python package and the
  # fuzz targets (an external project) when this build has them.
  targets=(chutelab)
  for t in chutelab_python chutelab_fuzz; do has_target "$t" && targets+=("$t"); done
  while read -r t; do
    has_target "$t" && targets+=("$t")
  done < <(ctest --test-dir "$bdir" -N | sed -n 's/^ *Test *#[0-9]*: //p')
fi
cmake --build "$bdir" -j"${JOBS:-2}" --target "${targets[@]}" >/dev/null
[[ ${SANITIZE_BUILD_ONLY:-0} == 1 ]] && exit 0
# Leaks that are not ours, suppressed by the module that holds them: OpenMP's runtime keeps its
# thread pools alive at exit; Open MPI's libraries keep their own state past MPI_Finalize. CPython
# frees neither its interpreter state nor objects in its own arenas at exit, nor do the extension
# modules of Debian's python3 packages (NumPy's, whose unwound stacks stop in its own .so): leaks
# allocated under python3 frames or in those modules are dropped. That hides a leak in our own
# module too (Python calls it, so its stacks end in python3): its code is the command line's
# libraries, which the native tests leak-check. The chutelab processes pytest starts are checked.
supp=$(mktemp)
trap 'rm -f "$supp"' EXIT
printf '%s\n' leak:libgomp leak:libomp leak:libmpi leak:libopen-pal leak:libopen-rte leak:libhwloc \
  leak:libevent leak:libpmix leak:mca_ leak:/usr/bin/python3 leak:/usr/lib/python3/dist-packages/ >"$supp"
export ASAN_OPTIONS="$asan_options"
export LSAN_OPTIONS="suppressions=$supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
ctest --test-dir "$bdir" -j"${JOBS:-2}" --output-on-failure --timeout $((600 * factor)) "$@"
