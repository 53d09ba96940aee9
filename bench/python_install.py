"""How long `pip install` of the Python package takes (bench/PYTHON_INSTALL.md).

    python3 bench/python_install.py            # the three ways below, in this checkout
    python3 bench/python_install.py --fresh    # also: a clean clone, ccache off (a new machine)

Each way makes a new virtual environment (--system-site-packages: meson-python, pybind11 and NumPy
from Debian) and installs with --no-build-isolation --no-index, timing the venv and the install:
  reuse-build   --config-settings=setup-args=-Dcmake_build_dir=build (what test_python_venv does)
  build-pip     the default: CMake build in build-pip/ (as it is: a reinstall)
  build-pip-new the default with build-pip/ removed first (ccache, if configured, may hold the objects)
Needs build/ configured and built with the package (scripts/setup.sh; cmake --build build).
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def python_of_build():
    with open(os.path.join(ROOT, "build", "CMakeCache.txt"), encoding="utf-8") as f:
        for line in f:
            if line.startswith("Python_EXECUTABLE:FILEPATH="):
                return line.split("=", 1)[1].strip()
    sys.exit("build/CMakeCache.txt names no Python_EXECUTABLE: configure build/ first")


def install(name, source, extra, env, tmp):
    venv = os.path.join(tmp, name)
    t0 = time.monotonic()
    subprocess.run([python_of_build(), "-m", "venv", "--system-site-packages", venv], check=True)
    t1 = time.monotonic()
    log = os.path.join(tmp, name + ".log")
    with open(log, "w") as out:
        r = subprocess.run([os.path.join(venv, "bin", "python"), "-m", "pip", "install", "-v", "--no-index",
                            "--no-build-isolation", *extra, source], stdout=out, stderr=subprocess.STDOUT, env=env,
                           cwd=tmp)
    t2 = time.monotonic()
    if r.returncode:
        sys.exit(f"{name}: pip install failed, see {log}")
    compiled = sum(1 for line in open(log) if "Building CXX object" in line)
    check = subprocess.run([os.path.join(venv, "bin", "python"), "-c",
                            "import chutelab; print(chutelab.estimate(belt_speed=4, mass_flow=35, "
                            "plate_distance=450).values['normal_force_N'])"],
                           capture_output=True, text=True, env=env, cwd=tmp, check=True)
    print(f"{name:14s} venv {t1 - t0:5.1f} s   pip install {t2 - t1:6.1f} s   {compiled:4d} objects compiled"
          f"   R_n = {check.stdout.strip()} N", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fresh", action="store_true", help="also a clean clone with ccache off")
    a = p.parse_args()
    env = dict(os.environ, PYTHONNOUSERSITE="1")
    env.pop("PYTHONPATH", None)
    with tempfile.TemporaryDirectory(prefix="chutelab-install-") as tmp:
        install("reuse-build", ROOT, ["--config-settings=setup-args=-Dcmake_build_dir=" + os.path.join(ROOT, "build")],
                env, tmp)
        install("build-pip", ROOT, [], env, tmp)
        shutil.rmtree(os.path.join(ROOT, "build-pip"), ignore_errors=True)
        install("build-pip-new", ROOT, [], env, tmp)
        if a.fresh:
            clone = os.path.join(tmp, "clone")
            subprocess.run(["git", "clone", "-q", ROOT, clone], check=True)
            install("fresh-clone", clone, [], dict(env, CCACHE_DISABLE="1"), tmp)


if __name__ == "__main__":
    main()
