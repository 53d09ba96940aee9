"""calibrate(), sensitivity() and sweep() against the command line: the same files, text and numbers.

The DEM runs here are the command-line tests' quick ones: one quick slump test, and the base and one
variant of the sensitivity study on a tiny station (a few seconds each)."""

import io
import os
import subprocess

import pytest

import chutelab

SOURCE = os.environ.get("CHUTELAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("CHUTELAB_BINARY", os.path.join(SOURCE, "build", "app", "chutelab"))

np = pytest.importorskip("numpy")
pd = pytest.importorskip("pandas")


def cli(*args):
    return subprocess.run([BINARY, *args], capture_output=True, text=True)


def same_files(ours, theirs, names):
    """Every file the command wrote, byte for byte, but for the wall-clock times."""
    for name in names:
        with open(os.path.join(ours, name), "rb") as a, open(os.path.join(theirs, name), "rb") as b:
            assert a.read() == b.read(), name


# The tiny station of the command-line tests (2.5 kg/s at 3 m/s, 13.6 mm quick spheres, 0.4 s
# simulated a run).
TINY_SETUP = """name = "tiny"
source = "test"
[belt]
pulley_diameter_mm = 250.0
belt_thickness_mm = 5.0
belt_width_mm = 200.0
loaded_width_mm = 120.0
incline_deg = 0.0
[plate]
width_mm = 600.0
height_mm = 400.0
angle_deg = 0.0
[material]
particle_diameter_mm = 9.0
solid_density_kgm3 = 1000.0
bulk_density_kgm3 = 558.0
youngs_modulus_Pa = 2.5e7
poisson_ratio = 0.38
friction_particle = 0.3
friction_plate = 0.27
friction_belt = 0.7
rolling_friction_particle = 0.1
restitution_particle = 0.7
restitution_plate = 0.66
[dem]
max_time_s = 0.4
min_window_s = 0.1
"""


def tiny_dataset(folder):
    os.makedirs(folder)
    with open(os.path.join(folder, "setup.toml"), "w") as f:
        f.write(TINY_SETUP)
    with open(os.path.join(folder, "conditions.csv"), "w") as f:
        f.write("condition,belt_speed_mps,mass_flow_tph,plate_distance_mm,plate_top_mm,stream_thickness_mm\n"
                "T3,3.0,9.0,350.0,250.0,\n")
    return folder


@pytest.mark.parametrize("args", [("belt_speed=2:6:1",), ("mass_flow=10:400:130",), ("air_drag=0:1:0.5",),
                                  ("plate_top=-200:400:150",)])
def test_a_sweep_is_the_command_lines_text_and_numbers(args):
    s = chutelab.sweep(*args, condition="V5-44", effects={"belt_slip": 0.01})
    base = ["estimate", "--condition", "V5-44", "--effect", "belt_slip=0.01", "--sweep", args[0]]
    for fmt, text in (("csv", s.csv()), ("json", s.json()), ("table", s.text())):
        r = cli(*base, "--format", fmt)
        assert r.returncode == 0, r.stderr
        assert text == r.stdout, fmt
    # The rows are the CSV's numbers bit for bit (the file holds the shortest decimal of the double).
    theirs = pd.read_csv(io.StringIO(s.csv()), float_precision="round_trip", keep_default_na=False, na_values={})
    assert s.column == theirs.columns[0]
    assert len(s.rows) == len(theirs)
    for c in s.rows.columns:
        if c == "note":
            assert list(s.rows[c]) == list(theirs[c])
        else:
            a = s.rows[c].to_numpy(dtype=float)
            b = theirs[c].map(lambda v: float(v) if v != "" else np.nan).to_numpy(dtype=float)
            assert np.array_equal(a, b, equal_nan=True), c


def test_a_bad_sweep_names_the_keyword():
    with pytest.raises(chutelab.InputError) as e:
        chutelab.sweep("belt_speed=2:6:1", belt_speed=3, condition="V5-44")
    assert e.value.field == "sweep"
    assert "leave out belt_speed=" in str(e.value)
    with pytest.raises(chutelab.InputError) as e:
        chutelab.sweep("nope=1:2:1", condition="V5-44")
    assert e.value.field == "sweep"
    with pytest.raises(chutelab.InputError) as e:
        chutelab.sweep("plate_distance=2000:3000:500", condition="V5-44")
    assert "no point of the sweep has an answer" in str(e.value)


def test_calibrate_writes_what_the_command_line_writes(tmp_path):
    # The same folder for both: calibration.md names it (an installed package has its own copy).
    rig = os.path.join(SOURCE, "datasets", "grima2010")
    c = chutelab.calibrate(rig, shapes="sphere", rolling=0.15, density=990, incline=False, jobs=1)
    assert len(c.rows) == 1 and c.closest == 0
    assert c.rows["grain"][0] == "sphere d=5.6mm"
    assert "rolling_friction_particle = 0.15" in c.material_toml
    c.write_report(tmp_path / "py")
    r = cli("calibrate", "--dataset", rig, "--shape", "sphere", "--rolling", "0.15", "--density", "990", "--no-incline",
            "--out", str(tmp_path / "cli"))
    assert r.returncode == 0, r.stderr
    same_files(tmp_path / "py", tmp_path / "cli", ["calibration.csv", "incline.csv", "calibration.md",
                                                   "calibration.html", "calibration.svg", "material.toml"])
    assert c.table3 in r.stdout
    csv = pd.read_csv(tmp_path / "cli" / "calibration.csv", float_precision="round_trip")
    assert c.rows["bulk_density_kgm3"][0] == csv["bulk_density_kgm3"][0]


def test_sensitivity_writes_what_the_command_line_writes(tmp_path):
    tiny = tiny_dataset(str(tmp_path / "tiny"))
    s = chutelab.sensitivity(tiny, "T3", only="G/10", jobs=1)
    assert list(s.rows["variant"]) == ["base", "G/10"]
    assert not s.complete and not s.reproduced
    assert "NOT FULLY TESTED" in s.verdict
    assert s.rows["change_percent"][0] == 0.0
    s.write_report(tmp_path / "py")
    r = cli("sensitivity", "--dataset", tiny, "--condition", "T3", "--only", "G/10", "--out", str(tmp_path / "cli"))
    assert r.returncode == 0, r.stderr
    assert s.verdict in r.stdout
    same_files(tmp_path / "py", tmp_path / "cli", ["sensitivity.csv", "sensitivity.md", "sensitivity.html",
                                                   "sensitivity.svg"])
    with pytest.raises(chutelab.InputError) as e:
        s.write_report(tiny)  # never onto the dataset it read
    assert e.value.field == "out"


@pytest.mark.parametrize("call, field", [
    (lambda: chutelab.calibrate(shapes="cube"), "shapes"),
    (lambda: chutelab.calibrate(rolling=[0.1, 2.0]), "rolling"),
    (lambda: chutelab.calibrate(rolling="abc"), "rolling"),
    (lambda: chutelab.calibrate(quality="paper"), "quality"),
    (lambda: chutelab.calibrate(target_pile_height_mm=-1), "target_pile_height_mm"),
    (lambda: chutelab.calibrate(threads=1.5), "threads"),
    (lambda: chutelab.sensitivity(sizes_mm=[9, -5]), "sizes_mm"),
    (lambda: chutelab.sensitivity(quality="fast"), "quality"),
    (lambda: chutelab.sensitivity(only=["LSD", ""]), "only"),
    (lambda: chutelab.sensitivity(condition="nope"), "condition"),
    (lambda: chutelab.sensitivity(only="cube"), "only"),
])
def test_bad_study_arguments_name_the_keyword_before_any_run(call, field):
    with pytest.raises(chutelab.InputError) as e:
        call()
    assert e.value.field == field, str(e.value)
