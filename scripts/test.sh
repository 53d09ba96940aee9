#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (ctest over the Boost.Test executables).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
