#!/usr/bin/env bash
# Installs the Debian packages chutelab needs (only the missing ones) and configures a Release build
# in build/. Idempotent and quiet when everything is present. Usage: scripts/setup.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake g++ make libeigen3-dev libgsl-dev libboost-test-dev libfmt-dev libfccp-dev
          libtomlplusplus-dev libcli11-dev chromium emscripten
          python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pandas python3-matplotlib
          python3-pytest python3-venv python3-mesonpy meson ninja-build  # pip install . (pyproject.toml)
          libxml2-utils openmpi-bin libopenmpi-dev liggghts
          python3-ezdxf python3-vtk9  # read back the designer's DXF and simulate's ParaView series in tests
          clang libclang-rt-dev libomp-dev)  # clang: libFuzzer targets and sanitizer runtimes (tests/fuzz)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

# chutelab is built where it runs, so the build is for this CPU (-march=native): the DEM's contact
# law then runs 4-8 contacts per vector instruction instead of 2 (1.35-1.4x on the bench bed,
# bench/log/RESULTS.md). With -ffp-contract=off the numbers are those of the portable build.
# CHUTELAB_PORTABLE=1 builds for any x86-64 instead (a binary to copy to other machines).
native=ON
[[ -n ${CHUTELAB_PORTABLE:-} ]] && native=OFF
if [[ ! -f build/CMakeCache.txt ]]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCHUTELAB_NATIVE=$native "$@" >/dev/null
fi

# `import chutelab` (README, "Python"): a chutelab.pth in the user site-packages of python3 (and of
# the interpreter the package is built for) names this checkout's build/python, as an editable
# install would. CHUTELAB_NO_PTH=1 leaves site-packages alone; PYTHONPATH=build/python then works.
if [[ -z ${CHUTELAB_NO_PTH:-} ]]; then
  pythons=(python3 "$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' build/CMakeCache.txt)")
  for py in "${pythons[@]}"; do
    [[ -n $py ]] && command -v "$py" >/dev/null || continue
    site=$("$py" -c 'import site, sys; print(site.getusersitepackages()) if site.ENABLE_USER_SITE else sys.exit(1)' \
           2>/dev/null) || continue
    [[ -n $site ]] || continue
    pth="$site/chutelab.pth"
    if [[ $(cat "$pth" 2>/dev/null) != "$PWD/build/python" ]]; then
      if mkdir -p "$site" && echo "$PWD/build/python" >"$pth"; then
        echo "setup: $py imports chutelab from $PWD/build/python ($pth)"
      fi
    fi
  done
fi
