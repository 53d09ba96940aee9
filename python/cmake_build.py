"""Builds the extension module _chutelab with this repository's CMake build, for meson.build.

meson-python (pyproject.toml) calls it through meson.build's custom target; it configures a CMake
build of its own, build-pip/ beside build/ (unless --build-dir names an existing one of this
checkout), builds the one target _chutelab there, and copies the module to where meson installs it
from. The module is thus compiled by the same CMakeLists.txt, with the same flags, as `cmake --build
build` makes it. build-pip/ stays, so a second `pip install .` compiles only what changed; and as it
lies as deep as build/, ccache (base_dir set to a folder above the checkout) finds the objects
build/ already compiled.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys


def cache_value(cache, key):
    with open(cache, encoding="utf-8") as f:
        for line in f:
            m = re.match(rf"{re.escape(key)}:[A-Z]+=(.*)$", line.rstrip("\n"))
            if m:
                return m.group(1)
    return None


def fail(message):
    print(f"chutelab: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--source", required=True)
    p.add_argument("--cmake", required=True)
    p.add_argument("--python", required=True, help="the interpreter the module is built for")
    p.add_argument("--version", required=True, help="meson.build's project version")
    p.add_argument("--build-dir", default="")
    p.add_argument("--native", default="true")
    p.add_argument("--jobs", type=int, default=0)
    p.add_argument("--output", required=True)
    a = p.parse_args()

    source = os.path.realpath(a.source)
    with open(os.path.join(source, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(chutelab VERSION ([0-9.]+)", f.read())
    if not m or m.group(1) != a.version:
        fail(f"meson.build says version {a.version}, CMakeLists.txt {m.group(1) if m else 'none'}: "
             "make them the same")

    if a.build_dir:
        build = os.path.realpath(a.build_dir)
        cache = os.path.join(build, "CMakeCache.txt")
        if not os.path.isfile(cache):
            fail(f"cmake_build_dir {build} has no CMakeCache.txt: configure it first (README, Build)")
        home = cache_value(cache, "CMAKE_HOME_DIRECTORY")
        if home is None or os.path.realpath(home) != source:
            fail(f"cmake_build_dir {build} is the build of {home}, not of {source}")
    else:
        build = os.path.join(source, "build-pip")
        if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
            args = [a.cmake, "-S", source, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                    f"-DCHUTELAB_NATIVE={'ON' if a.native == 'true' else 'OFF'}",
                    "-DCHUTELAB_BUILD_TESTS=OFF", f"-DPython_EXECUTABLE={a.python}"]
            ccache = shutil.which("ccache")
            if ccache:
                args += [f"-DCMAKE_CXX_COMPILER_LAUNCHER={ccache}", f"-DCMAKE_C_COMPILER_LAUNCHER={ccache}"]
            subprocess.run(args, check=True)
    cache = os.path.join(build, "CMakeCache.txt")
    if cache_value(cache, "pybind11_DIR") in (None, "", "pybind11_DIR-NOTFOUND"):
        fail("CMake did not find pybind11: install python3-pybind11 and pybind11-dev (scripts/setup.sh)")

    jobs = a.jobs or os.cpu_count() or 1
    subprocess.run([a.cmake, "--build", build, "--target", "_chutelab", "-j", str(jobs)], check=True)

    name = os.path.basename(a.output)
    built = os.path.join(build, "python", "chutelab", name)
    if not os.path.isfile(built):
        made = cache_value(cache, "Python_EXECUTABLE")
        fail(f"{built} was not made: that build is for {made}, whose modules are named otherwise "
             f"than {name} for {a.python}")
    shutil.copy2(built, a.output)


if __name__ == "__main__":
    main()
