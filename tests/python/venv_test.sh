#!/bin/sh
# test_python_venv: what a researcher does (README, "Python"): a virtual environment with the
# system's packages, `pip install` of this checkout into it (meson-python from Debian, no PyPI),
# then the package's tests run by that environment's python. The install drives the CMake build
# folder of this test run (meson option cmake_build_dir), so it compiles nothing already built.
# Usage: venv_test.sh SOURCE_DIR BUILD_DIR PYTHON CHUTELAB_BINARY
set -eu
src=$1 build=$2 py=$3 binary=$4
skip() { echo "$1: skipped"; exit 77; }
"$py" -c 'import venv, ensurepip' 2>/dev/null || skip "python3-venv not installed"
"$py" -c 'import mesonpy' 2>/dev/null || skip "meson-python not installed (python3-mesonpy)"
"$py" -c 'import pytest' 2>/dev/null || skip "pytest not installed (python3-pytest)"
command -v meson >/dev/null || skip "meson not installed"
command -v ninja >/dev/null || command -v ninja-build >/dev/null || skip "ninja not installed (ninja-build)"

venv=$build/python-venv
rm -rf "$venv"
# The user site-packages may hold a chutelab.pth naming some checkout's build/python
# (scripts/setup.sh); it must not stand in for the installed package.
export PYTHONNOUSERSITE=1
unset PYTHONPATH || true
t0=$(date +%s)
"$py" -m venv --system-site-packages "$venv"
# --no-index: nothing from PyPI; meson-python, pybind11 and NumPy come from the system.
"$venv/bin/python" -m pip install -q --no-index --no-build-isolation \
  --config-settings=setup-args=-Dcmake_build_dir="$build" "$src"
t1=$(date +%s)
echo "venv and pip install: $((t1 - t0)) s"
"$venv/bin/python" -m pip show -f chutelab | grep '_chutelab\..*\.so' >/dev/null || { echo "no module installed"; exit 1; }
cd "$venv"
CHUTELAB_BINARY=$binary CHUTELAB_SOURCE_DIR=$src CHUTELAB_EXPECT_PACKAGE_UNDER=$venv MPLBACKEND=Agg \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "$src/tests/python"
echo "pytest in the venv: $(($(date +%s) - t1)) s"
