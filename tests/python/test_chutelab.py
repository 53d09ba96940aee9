"""The Python package against the command line: same names, same numbers, same errors.

Run by ctest (test_python) with PYTHONPATH=build/python, CHUTELAB_BINARY (the chutelab binary of
the same build) and CHUTELAB_SOURCE_DIR. Only the analytical models run here (milliseconds).
"""

import io
import json
import math
import os
import re
import shutil
import subprocess
import sys

import pytest

import chutelab

SOURCE = os.environ.get("CHUTELAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("CHUTELAB_BINARY", os.path.join(SOURCE, "build", "app", "chutelab"))
RIG = os.path.join(SOURCE, "datasets", "liggghts-rig")
HIDDEN = os.path.join(SOURCE, "datasets", "hidden-effect")

np = pytest.importorskip("numpy")
pd = pytest.importorskip("pandas")


def cli(*args, cwd=None):
    r = subprocess.run([BINARY, *args], capture_output=True, text=True, cwd=cwd)
    return r


def read_csv(path, text=("condition", "model", "quantity", "boundary", "tolerance", "within_tolerance")):
    df = pd.read_csv(path, dtype={c: str for c in text}, keep_default_na=False, na_values={},
                     float_precision="round_trip")
    for c in df.columns:
        if c not in text and df[c].dtype == object:
            # float() reads the shortest round-trip decimals the files hold exactly (pandas'
            # to_numeric may not: it has a faster, less exact parser).
            df[c] = df[c].map(lambda s: float(s) if s != "" else np.nan)
    return df


def assert_same_table(ours, theirs, text=("condition", "model", "quantity", "boundary", "tolerance",
                                          "within_tolerance")):
    assert list(ours.columns) == list(theirs.columns)
    assert len(ours) == len(theirs)
    for c in ours.columns:
        if c in text:
            assert list(ours[c]) == list(theirs[c]), c
        else:
            a, b = ours[c].to_numpy(dtype=float), theirs[c].to_numpy(dtype=float)
            assert np.array_equal(a, b, equal_nan=True), c


# ---- estimate -------------------------------------------------------------------------------------

def test_the_issue_line_gives_the_json_of_the_command_line():
    ours = chutelab.estimate(belt_speed=4, mass_flow=35, plate_distance=450)
    r = cli("estimate", "--belt-speed", "4", "--mass-flow", "35", "--plate-distance", "450", "--format", "json")
    assert r.returncode == 0, r.stderr
    assert ours == json.loads(r.stdout)
    # Korzen's R_n = m_s V_pn: 35 t/h = 9.722 kg/s at V_pn = V_b = 4 m/s on a vertical plate.
    assert ours["models"]["korzen"]["normal_force_N"] == pytest.approx(35 / 3.6 * 4, rel=1e-9)
    assert set(ours) >= {"condition", "stationary_flow", "impact_angle_deg", "models"}


def test_estimate_with_a_dataset_row_and_an_effect_equals_the_command_line():
    ours = chutelab.estimate(dataset=RIG, condition="V5-44", effects={"air_drag": 0.5})
    r = cli("estimate", "--dataset", RIG, "--condition", "V5-44", "--effect", "air_drag=0.5", "--format", "json")
    assert ours == json.loads(r.stdout)
    assert ours["effects"] == {"air_drag": 0.5}
    plain = chutelab.estimate(dataset=RIG, condition="V5-44")
    assert ours["models"]["korzen"]["impact_velocity_mps"] < plain["models"]["korzen"]["impact_velocity_mps"]


# ---- errors ---------------------------------------------------------------------------------------

def test_bad_arguments_raise_input_error_naming_the_keyword():
    with pytest.raises(chutelab.InputError) as e:
        chutelab.estimate(belt_speed=-4, mass_flow=35, plate_distance=450)
    assert isinstance(e.value, ValueError)
    assert (e.value.file, e.value.line, e.value.field) == ("", 0, "belt_speed")
    with pytest.raises(chutelab.InputError) as e:
        chutelab.estimate(belt_speed=4, mass_flow=35)
    assert e.value.field == "plate_distance"
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(RIG, effects={"air_dragg": 0.1})
    assert e.value.field == "effects" and "air_dragg" in str(e.value)
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(RIG, models=["korzen", "kozen"])
    assert e.value.field == "models"


def test_bad_files_raise_input_error_with_file_line_and_field(tmp_path):
    ds = tmp_path / "rig"
    shutil.copytree(RIG, ds)
    lines = (ds / "measurements.csv").read_text().splitlines()
    lines[2] = lines[2].split(",")[0] + ",shear_force_N,lots,0.02"
    (ds / "measurements.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(chutelab.InputError) as e:
        chutelab.read_dataset(ds)
    assert e.value.file == str(ds / "measurements.csv")
    assert e.value.line == 3
    assert e.value.field == "value"
    # The command line says the same.
    r = cli("validate", "--dataset", str(ds), "--out", str(tmp_path / "out"))
    assert r.returncode == 2 and f"{ds / 'measurements.csv'}:3: value" in r.stderr
    # A rig without measurements reads, but does not validate.
    rig = chutelab.read_dataset(os.path.join(SOURCE, "datasets", "grima2010"))
    assert len(rig.conditions) == 8 and len(rig.measurements) == 0
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(rig)
    assert e.value.file.endswith("measurements.csv") and "needs measurements" in str(e.value)
    with pytest.raises(chutelab.InputError) as e:
        chutelab.read_dataset(tmp_path / "nowhere")
    assert e.value.field == "" and "not found" in str(e.value)


# ---- tables ---------------------------------------------------------------------------------------

def test_dataset_tables_have_the_files_names_and_numbers():
    ds = chutelab.read_dataset(RIG)
    assert ds.name and ds.dir == RIG
    assert_same_table(ds.measurements, read_csv(os.path.join(RIG, "measurements.csv")))
    assert_same_table(ds.trajectory, read_csv(os.path.join(RIG, "trajectory.csv")))
    conditions = read_csv(os.path.join(RIG, "conditions.csv"))
    assert_same_table(ds.conditions[list(conditions.columns)], conditions)
    assert ds.setup["plate.angle_deg"] == 0.0
    assert ds.setup["material.friction_plate"] == pytest.approx(0.27)


def test_validate_gives_the_tables_validate_writes(tmp_path):
    out = tmp_path / "out"
    r = cli("validate", "--dataset", RIG, "--out", str(out))
    assert r.returncode == 0, r.stderr
    v = chutelab.validate(chutelab.read_dataset(RIG))
    for name in ("predictions", "errors", "summary"):
        assert_same_table(getattr(v, name), read_csv(out / f"{name}.csv"))
    assert v.brief == r.stdout.splitlines()[0]
    assert not v.acceptance_checked
    # E = S - D row by row, in the columns' own units.
    e = v.errors.dropna(subset=["predicted"])
    assert np.allclose(e.error, e.predicted - e.measured, atol=1e-3, rtol=1e-5)


def test_tolerances_and_acceptance(tmp_path):
    tol = tmp_path / "tol.toml"
    tol.write_text("[korzen]\nshear_force_N = { relative = 0.15 }\n")
    v = chutelab.validate(RIG, tolerances=tol)
    assert v.acceptance_checked and v.acceptance_failed
    checked = v.errors[v.errors.tolerance != ""]
    assert set(checked.quantity) == {"shear_force_N"} and len(checked) == 8
    assert all(t.startswith("fail: relative error ") and t.endswith(" % > 15 %") for t in checked.tolerance)


def test_the_dem_through_python_gives_the_command_lines_numbers(tmp_path):
    # One condition at quick quality (~4 s of CPU), in a cache of its own; the command line then
    # finds the run in that cache and must report the same predictions.
    ds = tmp_path / "one"
    ds.mkdir()
    shutil.copy(os.path.join(RIG, "setup.toml"), ds)
    for name in ("conditions.csv", "measurements.csv"):
        rows = open(os.path.join(RIG, name)).read().splitlines()
        (ds / name).write_text("\n".join([rows[0]] + [r for r in rows[1:] if r.startswith("V3-41,")]) + "\n")
    cache = tmp_path / "cache"
    v = chutelab.validate(ds, models=["dem"], dem_quality="quick", dem_cache=cache)
    dem = v.predictions[v.predictions.model == "dem"].set_index("quantity")
    assert dem.loc["normal_force_N", "uncertainty"] > 0  # u_num of the steady mean
    # The rig measured R_n = 35.0 N here; the quick DEM gives about 35.8 N. The 10 % band
    # is a sanity bound on a coarse run, not an accuracy claim: the numbers must be the CLI's.
    assert dem.loc["normal_force_N", "value"] == pytest.approx(35.0, rel=0.1)
    r = cli("validate", "--dataset", str(ds), "--models", "dem", "--dem-quality", "quick", "--dem-cache", str(cache),
            "--out", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    assert_same_table(v.predictions, read_csv(tmp_path / "out" / "predictions.csv"))


# ---- diagnose, effects, synthesize ---------------------------------------------------------------

def test_diagnose_finds_the_hidden_effect_as_the_command_line_does(tmp_path):
    d = chutelab.diagnose(HIDDEN)
    r = cli("diagnose", "--dataset", HIDDEN, "--out", str(tmp_path / "d"))
    assert r.returncode == 0, r.stderr
    assert d.verdict == r.stdout.splitlines()[0]
    assert d.markdown == (tmp_path / "d" / "diagnosis.md").read_text()
    text = ("effect", "parameter", "significant", "signature", "wants_outside_range", "beaten_outside_range_by")
    if (d.ranking["rank"] == "pair").any():
        text += ("rank", "estimate", "uncertainty")
    assert_same_table(d.ranking, read_csv(tmp_path / "d" / "diagnosis.csv", text=text), text=text)
    # datasets/hidden-effect/HOW-MADE.md: air drag C_d = 0.7 was hidden in it.
    assert d.best == "air_drag" and d.ranking.effect[0] == "air_drag"
    assert d.any_significant
    assert {"model", "quantity", "driver", "correlation"} <= set(d.patterns.columns)
    # The verdict as numbers: its code and the fitted strength with its uncertainty.
    assert d.verdict_code == "missing_effect"
    fit = d.best_fit["air_drag"]
    assert abs(fit["value"] - 0.7) < 3 * fit["uncertainty"]
    assert d.outliers == [] and d.model_form == []


def test_diagnose_self_check_gives_rates_for_the_design():
    d = chutelab.diagnose(HIDDEN, self_check=4, seed=6400)
    sc = d.self_check
    assert sc["null_replicas"] == 4 and sc["effect_replicas"] == 4
    assert sc["truth"] == ["air_drag"]
    assert 0 <= sc["false_alarms"] <= 4 and 0 <= sc["covered"] <= 4
    assert "False alarms" in sc["markdown"]


def test_an_effect_fitted_in_python_lowers_the_error_as_validate_effect_fit_does(tmp_path):
    before = chutelab.validate(HIDDEN)
    after = chutelab.validate(HIDDEN, effects={"air_drag": "fit"})
    r = cli("validate", "--dataset", HIDDEN, "--effect", "air_drag=fit", "--out", str(tmp_path / "v"))
    lines = r.stdout.splitlines()
    assert lines[0] == "before: " + before.brief
    after_line = next(line for line in lines if line.startswith("after:"))
    # The after: line names the effect and its value in words, then the same summary as Python's.
    assert after_line.startswith("after:  + air drag (drag coefficient 0.") and after_line.endswith(after.brief)
    assert re.fullmatch(r"air_drag=0\.\d+ \(fitted\)", after.effects[0])
    assert after.combined_rms_normalised_error < 0.5 * before.combined_rms_normalised_error
    assert_same_table(after.errors, read_csv(tmp_path / "v" / "errors.csv"))


def test_synthesize_writes_what_the_command_line_writes(tmp_path):
    ours = chutelab.synthesize(effects={"air_drag": 0.7}, seed=3, out=tmp_path / "py")
    r = cli("synthesize", "--effect", "air_drag=0.7", "--seed", "3", "--out", str(tmp_path / "cli"))
    assert r.returncode == 0, r.stderr
    for f in sorted(os.listdir(tmp_path / "cli")):
        assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes(), f
    assert len(ours.measurements) > 0
    # Without out= the files go to a temporary folder; the dataset is the same.
    again = chutelab.synthesize(effects={"air_drag": 0.7}, seed=3)
    assert_same_table(again.measurements, ours.measurements)
    assert not os.path.exists(again.dir)


def test_registry_views():
    assert set(chutelab.models()) >= {"booth-cema", "korzen", "dem"}
    fx = chutelab.effects()
    assert "air_drag" in list(fx.effect)
    row = fx[fx.effect == "air_drag"].iloc[0]
    assert (row.lower, row.upper) == (0.0, 1.5)


# ---- without pandas, without NumPy ----------------------------------------------------------------

@pytest.mark.parametrize("blocked,kind", [("pandas", "ndarray"), ("numpy", "list")])
def test_tables_without_pandas_or_numpy(blocked, kind):
    code = (f"import sys; sys.modules['{blocked}'] = None; sys.modules['pandas'] = None\n"
            "import chutelab\n"
            f"ds = chutelab.read_dataset({RIG!r})\n"
            "m = ds.measurements\n"
            "print(type(m).__name__, type(m['value']).__name__, m['condition'][0], float(m['value'][0]))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ)
    assert r.returncode == 0, r.stderr
    first = read_csv(os.path.join(RIG, "measurements.csv")).iloc[0]
    assert r.stdout.split() == ["dict", kind, first.condition, repr(float(first.value))]


# ---- the researcher guide's example----------------------------------------------------------------------

def test_the_guide_example_runs(tmp_path):
    readme = open(os.path.join(SOURCE, "docs", "guide-researcher.md"), encoding="utf-8").read()
    m = re.search(r"<!-- python example -->\s*```python\n(.*?)```", readme, re.S)
    assert m, "docs/guide-researcher.md has no python example block"
    os.symlink(os.path.join(SOURCE, "datasets"), tmp_path / "datasets")
    cwd = os.getcwd()
    out = io.StringIO()
    try:
        os.chdir(tmp_path)
        import contextlib
        with contextlib.redirect_stdout(out):
            exec(compile(m.group(1), "docs/guide-researcher.md", "exec"), {})
    finally:
        os.chdir(cwd)
    assert (tmp_path / "residuals.png").stat().st_size > 10000
    assert "air_drag" in out.getvalue()


# ---- every guarantee of the command line holds here too ----------------------------------------------

def _files(folder):
    return {f: open(os.path.join(folder, f), "rb").read() for f in sorted(os.listdir(folder))}


def test_synthesize_refuses_to_overwrite_its_source_dataset(tmp_path):
    ds = tmp_path / "rig"
    shutil.copytree(RIG, ds)
    before = _files(ds)
    for out in (ds, ds / ".", str(ds) + "/"):
        with pytest.raises(chutelab.InputError) as e:
            chutelab.synthesize(ds, out=out)
        assert e.value.field == "out" and "is the input folder" in str(e.value)
    os.symlink(ds, tmp_path / "alias")
    with pytest.raises(chutelab.InputError) as e:
        chutelab.synthesize(chutelab.read_dataset(ds), out=tmp_path / "alias")
    assert "is the input folder" in str(e.value)
    assert _files(ds) == before
    assert not [f for f in os.listdir(tmp_path) if ".partial" in f]


def test_arguments_are_checked_by_the_command_lines_rules(tmp_path):
    out = tmp_path / "out"
    for kwargs, field, says in (({"seed": 1.5}, "seed", "whole number"), ({"seed": True}, "seed", "whole number"),
                                ({"seed": -1}, "seed", "whole number"), ({"seed": "1"}, "seed", "whole number"),
                                ({"noise_scale": math.nan}, "noise_scale", "finite number"),
                                ({"noise_scale": math.inf}, "noise_scale", "finite number")):
        with pytest.raises(chutelab.InputError) as e:
            chutelab.synthesize(RIG, out=out, **kwargs)
        assert e.value.field == field and says in str(e.value), kwargs
        assert not out.exists()
    assert len(chutelab.synthesize(RIG, seed=2.0).measurements) > 0  # a whole number as a float is that number
    with pytest.raises(chutelab.InputError) as e:
        chutelab.diagnose(RIG, alpha=math.nan)
    assert e.value.field == "alpha"
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(RIG, models=["korzen"], dem_threads=-2)
    assert e.value.field == "dem_threads"
    # The right type, not whatever bool() or float() makes of it.
    for call, field in ((lambda: chutelab.diagnose(RIG, pairs="no"), "pairs"),
                        (lambda: chutelab.diagnose(RIG, alpha="0.01"), "alpha"),
                        (lambda: chutelab.validate(RIG, dem_threads=1.5), "dem_threads"),
                        (lambda: chutelab.validate(RIG, dem_quality=5), "dem_quality"),
                        (lambda: chutelab.estimate(belt_speed="4", mass_flow=35, plate_distance=450), "belt_speed"),
                        (lambda: chutelab.validate(RIG, models="korzen,,booth-cema"), "models")):
        with pytest.raises(chutelab.InputError) as e:
            call()
        assert e.value.field == field, field
    # A message names the keyword as typed here, not the command line's flag.
    with pytest.raises(chutelab.InputError) as e:
        chutelab.estimate(condition="V3-41", setup=os.path.join(RIG, "setup.toml"))
    assert "use dataset=" in str(e.value) and "--dataset" not in str(e.value)


def _tree(root):
    """Every file under root, relative path -> bytes (folders as None)."""
    out = {}
    for d, dirs, files in os.walk(root):
        for n in dirs:
            out[os.path.relpath(os.path.join(d, n), root)] = None
        for n in files:
            out[os.path.relpath(os.path.join(d, n), root)] = open(os.path.join(d, n), "rb").read()
    return out


def test_a_deep_or_huge_toml_file_is_refused_not_a_crash(tmp_path):
    # Every TOML reader the package reaches (setup.toml, whose [dem] table validate reads again, and a
    # tolerances file): refused as InputError naming file and line; nothing changed or written.
    ds = tmp_path / "rig"
    shutil.copytree(RIG, ds)
    setup = (ds / "setup.toml").read_text()
    deep_cases = ("a" + ".a" * 49999 + " = 1\n", "x = " + "[" * 100000 + "]" * 100000 + "\n",
                  "[" + "a." * 40000 + "b]\n", "x = " + "{a=" * 20000 + "1" + "}" * 20000 + "\n")
    for deep in deep_cases:
        (ds / "setup.toml").write_text(deep + setup)
        before = _tree(tmp_path)
        for call in (lambda: chutelab.read_dataset(ds), lambda: chutelab.validate(ds, models=["korzen"]),
                     lambda: chutelab.synthesize(ds, out=tmp_path / "out")):
            with pytest.raises(chutelab.InputError) as e:
                call()
            assert e.value.file == str(ds / "setup.toml") and e.value.line == 1 and "levels deep" in str(e.value)
            assert _tree(tmp_path) == before
    (ds / "setup.toml").write_text(setup + "# padding padding padding padding padding padding\n" * 25000)
    before = _tree(tmp_path)
    with pytest.raises(chutelab.InputError) as e:
        chutelab.read_dataset(ds)
    assert e.value.file == str(ds / "setup.toml") and "is larger than 1 MiB" in str(e.value)
    assert _tree(tmp_path) == before
    (ds / "setup.toml").write_text(setup)
    tol = tmp_path / "tol.toml"
    for deep in deep_cases:
        tol.write_text(deep)
        before = _tree(tmp_path)
        with pytest.raises(chutelab.InputError) as e:
            chutelab.validate(ds, models=["korzen"], tolerances=tol)
        assert e.value.file == str(tol) and e.value.line == 1 and "levels deep" in str(e.value)
        assert _tree(tmp_path) == before
