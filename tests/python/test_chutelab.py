"""The Python package against the command line: same names, same numbers, same errors.

Run by ctest twice: test_python with the system python3 and PYTHONPATH=build/python, and
test_python_venv in a virtual environment the package was `pip install`ed into
(tests/python/venv_test.sh). Both set CHUTELAB_BINARY (the chutelab binary of the same build),
CHUTELAB_SOURCE_DIR and CHUTELAB_EXPECT_PACKAGE_UNDER (where `import chutelab` must come from).
Only the analytical models run here, and one quick DEM condition.
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
    """Every column of the file is in ours with the same values: numbers bit for bit (the files
    hold the shortest decimal that reads back as the double)."""
    assert [c for c in ours.columns if c in theirs.columns] == list(theirs.columns)
    assert len(ours) == len(theirs)
    for c in theirs.columns:
        if c in text:
            assert list(ours[c]) == list(theirs[c]), c
        else:
            a, b = ours[c].to_numpy(dtype=float), theirs[c].to_numpy(dtype=float)
            assert np.array_equal(a, b, equal_nan=True), c


def test_the_package_is_the_one_this_run_installed():
    where = os.environ.get("CHUTELAB_EXPECT_PACKAGE_UNDER")
    if not where:
        pytest.skip("CHUTELAB_EXPECT_PACKAGE_UNDER not set (ctest sets it)")
    assert os.path.realpath(chutelab.__file__).startswith(os.path.realpath(where) + os.sep)


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


def test_estimate_takes_the_rigs_common_geometry_and_material_as_keywords():
    args = dict(belt_speed=4, mass_flow=35, plate_distance=450)
    ours = chutelab.estimate(**args, pulley_diameter=500, belt_width=600, bulk_density=800)
    r = cli("estimate", "--belt-speed", "4", "--mass-flow", "35", "--plate-distance", "450", "--pulley-diameter",
            "500", "--belt-width", "600", "--bulk-density", "800", "--format", "json")
    assert r.returncode == 0, r.stderr
    assert ours == json.loads(r.stdout)
    assert ours != chutelab.estimate(**args)
    with pytest.raises(chutelab.InputError) as e:
        chutelab.estimate(**args, pulley_diameter=-5)
    assert e.value.field == "pulley_diameter"


def test_estimate_numbers_are_the_command_lines_doubles_bit_for_bit():
    # Odd inputs and a flight force (RK4 path), so the numbers have all their digits.
    args = dict(belt_speed=4.37, mass_flow=35.3, plate_distance=451.7)
    e = chutelab.estimate(**args, effects={"air_drag": 0.61})
    r = cli("estimate", "--belt-speed", "4.37", "--mass-flow", "35.3", "--plate-distance", "451.7",
            "--effect", "air_drag=0.61", "--format", "json")
    assert r.returncode == 0, r.stderr
    # The JSON holds the shortest decimal that reads back as the double; json.loads reads it back.
    j = json.loads(r.stdout)
    assert len(e.predictions) == sum(len(q) for q in j["models"].values()) > 0
    for row in e.predictions.itertuples():
        assert row.value == j["models"][row.model][row.quantity], (row.model, row.quantity)
    for name, points in e.streamlines.items():
        assert np.array_equal(points, np.array(j["streamlines"][name]["points_mm"])), name
    for name in ("belt_speed_mps", "mass_flow_tph", "plate_distance_mm", "stream_thickness_mm"):
        assert e.values[name] == j["condition"][name], name
    for name, value in j["impact_zone"].items():
        if not isinstance(value, (bool, str)):  # flags and the note on a stream that misses the plate
            assert e.values[name] == value, name
    assert e.values["impact_angle_deg"] == j["impact_angle_deg"]
    assert e.effects == {"air_drag": 0.61}
    # Not rounded on the way: a force carries (nearly) all of a double's 17 digits.
    rn = e.predictions[(e.predictions.model == "korzen") & (e.predictions.quantity == "normal_force_N")].value.iloc[0]
    assert len(repr(float(rn)).replace(".", "").lstrip("0")) >= 15
    assert e.predictions.value.dtype == np.float64


def test_the_dense_trajectory_is_the_models_parabola():
    e = chutelab.estimate(belt_speed=4, mass_flow=35, plate_distance=450)
    t = e.trajectory(points=500)
    assert list(t.columns) == ["streamline", "t_s", "x_mm", "y_mm", "vx_mps", "vy_mps"]
    assert list(t.streamline.unique()) == ["lower", "upper", "cema_centroid", "korzen_centroid"]
    for name, g in t.groupby("streamline", sort=False):
        assert len(g) == 500
        # Without a flight force the path is the closed-form parabola from the release point:
        # x = x0 + vx t, y = y0 + vy0 t - g t^2 / 2 (g = 9.80665, the rig's), mm.
        t_s, x0, y0 = g.t_s.to_numpy(), g.x_mm.iloc[0], g.y_mm.iloc[0]
        vx, vy0 = g.vx_mps.iloc[0], g.vy_mps.iloc[0]
        assert t_s[0] == 0.0 and np.all(np.diff(t_s) > 0)
        assert np.allclose(g.x_mm, x0 + 1e3 * vx * t_s, rtol=0, atol=1e-9)
        assert np.allclose(g.y_mm, y0 + 1e3 * (vy0 * t_s - 0.5 * 9.80665 * t_s ** 2), rtol=0, atol=1e-9)
        # It starts where the drawn path leaves the pulley and ends where it meets the plate.
        drawn = e.streamlines[name]
        release = e["streamlines"][name]
        assert (x0, y0) == pytest.approx((release["release_x_mm"], release["release_y_mm"]), abs=1e-9)
        assert (g.x_mm.iloc[-1], g.y_mm.iloc[-1]) == pytest.approx(tuple(drawn[-1]), abs=1e-9)
        if "impact_y_mm" in release:
            assert g.y_mm.iloc[-1] == pytest.approx(release["impact_y_mm"], abs=1e-9)
            assert g.x_mm.iloc[-1] == pytest.approx(450, abs=1e-6)  # a vertical plate at 450 mm
    with pytest.raises(chutelab.InputError) as err:
        e.trajectory(points=1)
    assert err.value.field == "points"


def test_quantities_name_every_quantity_of_the_tables():
    q = chutelab.quantities()
    assert q["normal_force_N"] == chutelab.Quantity("normal_force_N", "R_n", "plate normal force", "N")
    assert q["normal_force_N"].axis_label == "plate normal force R_n [N]"
    assert q["impact_point_y_mm"].unit == "mm" and q["stream_mass_flow_tph"].unit == "t/h"
    v = chutelab.validate(RIG)
    assert set(v.errors.quantity) <= set(q) and set(v.predictions.quantity) <= set(q)
    assert [x.unit for x in q.values()] == ["N", "N", "N", "m/s", "m/s", "mm", "m/s", "t/h", "mm", "mm", "mm"]
    assert all(x.symbol and x.label for x in q.values())


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


def test_a_wrong_type_is_an_input_error_naming_the_keyword_not_a_binding_signature():
    for call, field in ((lambda: chutelab.estimate(belt_speed="4"), "belt_speed"),
                        (lambda: chutelab.estimate(belt_speed=4, mass_flow=35, plate_distance=[450]), "plate_distance"),
                        (lambda: chutelab.estimate(dataset=5), "dataset"),
                        (lambda: chutelab.estimate(condition=3, dataset=RIG), "condition"),
                        (lambda: chutelab.estimate(belt_speed=4, effects={"air_drag": None}), "effects"),
                        (lambda: chutelab.estimate(belt_speed=4, effects=7), "effects"),
                        (lambda: chutelab.validate(RIG, models=[1, 2]), "models"),
                        (lambda: chutelab.validate(RIG, tolerances=3.5), "tolerances"),
                        (lambda: chutelab.validate(42), "dataset"),
                        (lambda: chutelab.read_dataset(None), "path"),
                        (lambda: chutelab.diagnose(RIG, seed="1"), "seed"),
                        (lambda: chutelab.synthesize(RIG, out=1), "out")):
        with pytest.raises(chutelab.InputError) as e:
            call()
        msg = str(e.value)
        assert e.value.field == field and msg.startswith(field + ": "), msg
        assert "incompatible function arguments" not in msg and "_chutelab" not in msg and "--" not in msg, msg
    with pytest.raises(chutelab.InputError) as e:
        chutelab.estimate(belt_speed="4")
    assert str(e.value) == "belt_speed: must be a number, got '4'"


def test_help_shows_signatures_types_and_docstrings():
    import inspect
    import typing
    for f in (chutelab.estimate, chutelab.validate, chutelab.diagnose, chutelab.synthesize, chutelab.read_dataset,
              chutelab.write_report, chutelab.quantities, chutelab.models, chutelab.effects):
        sig = inspect.signature(f)
        assert f.__doc__ and len(f.__doc__) > 40, f.__name__
        assert sig.return_annotation is not inspect.Signature.empty, f.__name__
        assert all(p.annotation is not inspect.Parameter.empty for p in sig.parameters.values()), f.__name__
    assert "belt_speed: Optional[float] = None" in str(inspect.signature(chutelab.estimate))
    for cls in (chutelab.Estimate, chutelab.Dataset, chutelab.Validation, chutelab.Diagnosis):
        text = pydoc_text(cls)
        assert "(self, raw" not in text and "(self, core" not in text and "_make" not in text, cls
        assert len(cls.__doc__) > 100, cls
    assert "write_report(self, out:" in pydoc_text(chutelab.Validation)
    assert "Strength" in typing.get_type_hints(chutelab.Validation)["effects"].__args__[0].__name__


def pydoc_text(obj):
    import pydoc
    return pydoc.render_doc(obj, renderer=pydoc.plaintext)


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
        file = read_csv(out / f"{name}.csv").drop(columns=["tolerance", "within_tolerance"], errors="ignore")
        assert_same_table(getattr(v, name), file)
    assert v.brief == r.stdout.splitlines()[0]
    assert not v.acceptance_checked and not v.errors.tolerance_checked.any() and v.errors.within_tolerance.all()
    assert v.errors.measured.dtype == np.float64 and v.summary.n.dtype == np.int64
    assert v.effects == [] and v.diagnosis is None
    # The report: the very files `validate --out` wrote.
    v.write_report(tmp_path / "py")
    assert _files(tmp_path / "py") == _files(out)
    # report.md links each chart, written beside it as an SVG file.
    charts = [f for f in _files(out) if f.startswith("figures" + os.sep)]
    assert len(charts) >= 3 and all(f.endswith(".svg") for f in charts)
    md = (out / "report.md").read_text()
    assert all(f"]({f.replace(os.sep, '/')})" in md for f in charts)
    with pytest.raises(chutelab.InputError) as e:
        chutelab.write_report(v, RIG)  # onto the dataset it read
    assert e.value.field == "out" and "is the input folder" in str(e.value)
    # E = S - D row by row, in the columns' own units.
    e = v.errors.dropna(subset=["predicted"])
    assert np.allclose(e.error, e.predicted - e.measured, atol=1e-3, rtol=1e-5)


def test_tolerances_and_acceptance(tmp_path):
    tol = tmp_path / "tol.toml"
    tol.write_text("[korzen]\nshear_force_N = { relative = 0.15 }\n")
    v = chutelab.validate(RIG, tolerances=tol)
    assert v.acceptance_checked and v.acceptance_failed
    checked = v.errors[v.errors.tolerance_checked]
    assert set(checked.quantity) == {"shear_force_N"} and len(checked) == 8
    assert (checked.tolerance_relative == 0.15).all() and checked.tolerance_absolute.isna().all()
    # The flag is the limit applied to the numbers beside it.
    assert list(checked.within_tolerance) == list(checked.relative_error.abs() <= 0.15)
    failed = checked[~checked.within_tolerance]
    assert len(failed) > 0
    assert all(t.startswith("relative error ") and t.endswith(" % > 15 %") for t in failed.tolerance_failed)
    assert (v.errors[~v.errors.tolerance_checked].tolerance_failed == "").all()
    s = v.summary.set_index(["model", "quantity"])
    assert s.loc[("korzen", "shear_force_N"), "tolerance_checked"]
    assert not s.loc[("korzen", "shear_force_N"), "within_tolerance"]
    assert s.tolerance_checked.sum() == 1
    # As the command line writes it.
    r = cli("validate", "--dataset", RIG, "--tolerances", str(tol), "--out", str(tmp_path / "out"))
    assert r.returncode == 1
    file = read_csv(tmp_path / "out" / "errors.csv")
    assert list(file.tolerance != "") == list(v.errors.tolerance_checked)
    assert list(file.tolerance.str.startswith("fail")) == list(~v.errors.within_tolerance)


def test_acceptance_judges_the_models_as_delivered(tmp_path):
    # As the command line's exit code (docs/guide-ci.md): a fitted effect is reported beside the
    # acceptance, never judged; a fixed one only with accept_with_effects=True.
    tol = tmp_path / "tol.toml"
    tol.write_text("[korzen]\nnormal_force_N = { relative = 0.04 }\n")
    fitted = chutelab.validate(HIDDEN, effects={"air_drag": "fit"}, tolerances=tol)
    assert fitted.acceptance_failed and not fitted.accepted_with_effects
    assert fitted.outside_tolerance_beside == 0
    fixed = chutelab.validate(HIDDEN, effects={"air_drag": 0.75}, tolerances=tol, accept_with_effects=True)
    assert not fixed.acceptance_failed and fixed.accepted_with_effects and fixed.outside_tolerance_beside > 0
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(HIDDEN, effects={"air_drag": "fit"}, tolerances=tol, accept_with_effects=True)
    assert e.value.field == "accept_with_effects" and "air_drag=fit" in str(e.value)


def test_python_says_keywords_not_the_command_lines_flags():
    # Every text the package gives back (verdicts, notes, caveats, the brief, a refusal) names another
    # input as it is typed here (effects=, dataset=), never as the command line's flag (--effect).
    flag = re.compile(r"(?<![\w-])--[a-z]")
    v = chutelab.validate(HIDDEN, effects={"air_drag": "fit"}, diagnose=True)
    d = chutelab.diagnose(RIG, pairs=False)
    texts = [repr(v), v.brief, *v.notes, *v.acceptance_problems]
    for g in (v.diagnosis, d):
        texts += [repr(g), g.verdict, *g.caveats, *g.failure_summary, *g.discriminators,
                  *g.indistinguishable]
    assert len(texts) > 10
    for t in texts:
        assert not flag.search(t), t
    for call, said in ((lambda: chutelab.validate(HIDDEN, accept_with_effects=True), "effects="),
                       (lambda: chutelab.estimate(condition="V3-41", setup=os.path.join(RIG, "setup.toml")),
                        "dataset=")):
        with pytest.raises(chutelab.InputError) as e:
            call()
        assert said in str(e.value) and not flag.search(str(e.value)), str(e.value)


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
    text = ("rank", "effect", "parameter", "estimate", "uncertainty", "significant", "signature",
            "wants_outside_range", "beaten_outside_range_by", "outside_range_uncertainty")
    file = read_csv(tmp_path / "d" / "diagnosis.csv", text=text)
    singles, pairs = file[file["rank"] != "pair"], file[file["rank"] == "pair"]
    # Singles: the file's numbers bit for bit, its yes/no as flags.
    assert list(d.ranking["rank"]) == [int(x) for x in singles["rank"]]
    assert list(d.ranking.effect) == list(singles.effect)
    for c in ("estimate", "uncertainty"):
        assert np.array_equal(d.ranking[c].to_numpy(), singles[c].astype(float).to_numpy()), c
    assert_same_table(d.ranking, singles.drop(columns=["rank", "estimate", "uncertainty", "significant",
                                                      "wants_outside_range", "outside_range_uncertainty"]),
                      text=text)
    assert list(d.ranking.significant) == list(singles.significant == "yes")
    assert list(d.ranking.wants_outside_range) == list(singles.wants_outside_range == "yes")
    # Pairs: "a+b" in the file, one column per member here.
    assert len(d.pairs) == len(pairs)
    for (_, ours), (_, theirs) in zip(d.pairs.iterrows(), pairs.iterrows()):
        assert f"{ours.effect_1}+{ours.effect_2}" == theirs.effect
        assert [float(x) for x in theirs.estimate.split("+")] == [ours.estimate_1, ours.estimate_2]
    # datasets/hidden-effect/HOW-MADE.md: air drag C_d = 0.7 was hidden in it.
    assert d.best == "air_drag" and d.ranking.effect[0] == "air_drag"
    assert d.any_significant
    assert {"model", "quantity", "driver", "correlation"} <= set(d.patterns.columns)
    # The verdict as numbers: its code and the fitted strength with its uncertainty.
    assert d.verdict_code == "missing_effect"
    fit = d.best_fit["air_drag"]
    assert isinstance(fit, chutelab.Strength) and fit.fitted and fit.parameter == "drag_coefficient"
    assert abs(fit.value - 0.7) < 3 * fit.sd
    assert (fit.value, fit.sd) == (d.ranking.estimate[0], d.ranking.uncertainty[0])
    assert d.outliers == [] and d.model_form == []
    # The report: the files `diagnose --out` wrote.
    d.write_report(tmp_path / "py")
    assert _files(tmp_path / "py") == _files(tmp_path / "d")


def test_diagnose_takes_corrected_records_as_the_command_line_does(tmp_path):
    # A plate corrected by 1 mm is within its plausible error: the drag is still what is missing, and
    # the verdict is the command line's with --input.
    d = chutelab.diagnose(HIDDEN, inputs={"plate_distance": 1.0})
    r = cli("diagnose", "--dataset", HIDDEN, "--input", "plate_distance=1", "--out", str(tmp_path / "d"))
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == "corrected record: plate_distance=1"
    assert d.verdict == lines[1]
    assert d.best == "air_drag"
    with pytest.raises(chutelab.InputError) as e:
        chutelab.diagnose(HIDDEN, inputs={"air_drag": 0.5})
    assert "input" in str(e.value) and "physical effect" in str(e.value)
    # ... said in this package's words: the keyword inputs=, not the command line's --input.
    assert e.value.field == "inputs" and "inputs= takes a recorded input" in str(e.value), str(e.value)


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
    [fit] = after.effects
    assert (fit.effect, fit.parameter, fit.unit, fit.fitted) == ("air_drag", "drag_coefficient", "", True)
    assert 0 < fit.sd < 0.2 and abs(fit.value - 0.7) < 3 * fit.sd
    # The command line's words say the same number to its shown digits.
    assert f"drag coefficient {fit.value:.2f}" in after_line or f"drag coefficient {fit.value:.3g}" in after_line
    assert re.fullmatch(r"air_drag: drag_coefficient = 0\.\d+ ± 0\.\d+ \(fitted\)", str(fit))
    assert after.combined_rms_normalised_error < 0.5 * before.combined_rms_normalised_error
    assert_same_table(after.errors, read_csv(tmp_path / "v" / "errors.csv").drop(columns=["tolerance"]))
    # With effects the command line diagnoses too, and so does the package; the reports are the same.
    assert after.diagnosis is not None and after.diagnosis.best == "air_drag"
    after.write_report(tmp_path / "py")
    assert _files(tmp_path / "py") == _files(tmp_path / "v")


def test_synthesize_writes_what_the_command_line_writes(tmp_path):
    ours = chutelab.synthesize(effects={"air_drag": 0.7}, seed=3, out=tmp_path / "py")
    r = cli("synthesize", "--effect", "air_drag=0.7", "--seed", "3", "--out", str(tmp_path / "cli"))
    assert r.returncode == 0, r.stderr
    assert _files(tmp_path / "py") == _files(tmp_path / "cli")
    assert len(ours.measurements) > 0
    # Without out= the files go to a temporary folder; the dataset is the same.
    again = chutelab.synthesize(effects={"air_drag": 0.7}, seed=3)
    assert_same_table(again.measurements, ours.measurements)
    assert again.dir is None


def test_registry_views():
    assert set(chutelab.models()) >= {"booth-cema", "korzen", "dem"}
    fx = chutelab.effects()
    assert "air_drag" in list(fx.effect)
    row = fx[fx.effect == "air_drag"].iloc[0]
    assert (row.lower, row.upper) == (0.0, 1.5)


# ---- without pandas, without NumPy ----------------------------------------------------------------

def test_tables_without_pandas_are_numpy_record_arrays():
    code = ("import sys; sys.modules['pandas'] = None\n"
            "import chutelab\n"
            f"m = chutelab.read_dataset({RIG!r}).measurements\n"
            "print(type(m).__name__, m.value.dtype, m.condition[0], repr(float(m.value[0])))\n"
            "e = chutelab.estimate(belt_speed=4, mass_flow=35, plate_distance=450)\n"
            "p = e.predictions\n"
            "print(type(p).__name__, p.dtype.names, p.value.dtype)\n"
            f"v = chutelab.validate({RIG!r})\n"
            "print(v.errors.within_tolerance.dtype, v.summary.n.dtype)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ)
    assert r.returncode == 0, r.stderr
    first = read_csv(os.path.join(RIG, "measurements.csv")).iloc[0]
    lines = r.stdout.splitlines()
    assert lines[0].split() == ["recarray", "float64", first.condition, repr(float(first.value))]
    assert lines[1] == "recarray ('model', 'quantity', 'value') float64"
    assert lines[2] == "bool int64"


def test_without_numpy_the_import_says_what_to_install():
    code = "import sys; sys.modules['numpy'] = None\nimport chutelab\n"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ)
    assert r.returncode != 0 and "python3-numpy" in r.stderr


# ---- the researcher guide's example----------------------------------------------------------------------

def test_the_guide_example_runs(tmp_path):
    readme = open(os.path.join(SOURCE, "docs", "guide-researcher.md"), encoding="utf-8").read()
    m = re.search(r"<!-- python example -->\s*```python\n(.*?)```", readme, re.S)
    assert m, "docs/guide-researcher.md has no python example block"
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
    assert (tmp_path / "stream.png").stat().st_size > 10000
    assert (tmp_path / "report-after" / "report.html").stat().st_size > 10000
    assert re.search(r"^air_drag: drag_coefficient = 0\.\d+ ± 0\.\d+ \(fitted\)$", out.getvalue(), re.M)


# ---- every guarantee of the command line holds here too ----------------------------------------------

def _files(folder):
    """Every file's bytes; the folder's record of what chutelab wrote as its lines without the times
    (two runs write the same bytes at different times)."""
    files = {}
    for root, _, names in sorted(os.walk(folder)):
        for f in sorted(names):
            path = os.path.join(root, f)
            files[os.path.relpath(path, folder)] = open(path, "rb").read()
    if ".chutelab-manifest" in files:
        lines = files[".chutelab-manifest"].decode().splitlines()
        files[".chutelab-manifest"] = [l.split("\t")[:3] + l.split("\t")[4:] if l.startswith("file\t") else l
                                       for l in lines]
    return files


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


# ---- a Dataset owns its tables; long calls hear Ctrl-C -------------------------------------------

def _same_frame(a, b):
    """The same table: columns, text and numbers bit for bit (NaN where NaN)."""
    pd.testing.assert_frame_equal(a.reset_index(drop=True), b.reset_index(drop=True), check_exact=True)


def _rig_copy(tmp_path, name="rig"):
    ds = tmp_path / name
    shutil.copytree(RIG, ds)
    return ds


def test_a_dataset_outlives_its_folder(tmp_path):
    folder = _rig_copy(tmp_path)
    (folder / "tolerances.toml").write_text("[korzen]\nshear_force_N = { relative = 0.15 }\n")
    ds = chutelab.read_dataset(folder)
    before = chutelab.validate(ds)
    assert before.acceptance_checked
    shutil.rmtree(folder)
    after = chutelab.validate(ds)  # the files it read are in memory, tolerances.toml too
    for name in ("predictions", "errors", "summary"):
        _same_frame(getattr(after, name), getattr(before, name))
    assert after.acceptance_checked and after.acceptance_failed == before.acceptance_failed
    _same_frame(chutelab.diagnose(ds, pairs=False).ranking, chutelab.diagnose(RIG, pairs=False).ranking)
    _same_frame(chutelab.synthesize(ds, seed=2).measurements, chutelab.synthesize(RIG, seed=2).measurements)
    # A folder that changes after reading changes nothing either.
    folder = _rig_copy(tmp_path, "rig2")
    ds = chutelab.read_dataset(folder)
    (folder / "measurements.csv").write_text("condition,quantity,value\nV2-26,normal_force_N,1\n")
    _same_frame(chutelab.validate(ds).errors, chutelab.validate(RIG).errors)


def test_a_synthesized_dataset_lives_in_memory(tmp_path):
    mem = chutelab.synthesize(effects={"air_drag": 0.7}, seed=3)
    assert mem.dir is None and len(mem.measurements) > 0
    on_disk = chutelab.synthesize(effects={"air_drag": 0.7}, seed=3, out=tmp_path / "synth")
    v_mem, v_disk = chutelab.validate(mem), chutelab.validate(on_disk)
    for name in ("predictions", "errors", "summary"):
        _same_frame(getattr(v_mem, name), getattr(v_disk, name))
    d = chutelab.diagnose(mem)
    assert d.best == "air_drag" and d.best == chutelab.diagnose(on_disk).best
    # Its report goes anywhere (it has no folder to protect); a synthesis from it works too.
    v_mem.write_report(tmp_path / "report")
    assert (tmp_path / "report" / "report.html").stat().st_size > 10000
    again = chutelab.synthesize(mem, seed=4)
    assert again.dir is None and len(again.measurements) == len(mem.measurements)


def test_edits_to_a_datasets_tables_are_honoured(tmp_path):
    ds = chutelab.read_dataset(RIG)
    # R_n of V3-41 read 10 % higher; V4-28 run at 4.2 m/s; the trajectory of V2-26 dropped.
    m = ds.measurements
    rn = m.index[(m.condition == "V3-41") & (m.quantity == "normal_force_N")][0]
    m.loc[rn, "value"] = m.loc[rn, "value"] * 1.1
    ds.conditions.loc[ds.conditions.condition == "V4-28", "belt_speed_mps"] = 4.2
    ds.trajectory = ds.trajectory[ds.trajectory.condition != "V2-26"].reset_index(drop=True)
    ours = chutelab.validate(ds)
    # The same edits in the files, through the command line.
    folder = _rig_copy(tmp_path)
    meas = read_csv(folder / "measurements.csv")
    meas.loc[rn, "value"] = m.loc[rn, "value"]
    meas.to_csv(folder / "measurements.csv", index=False, float_format="%.17g")
    cond = (folder / "conditions.csv").read_text().replace("\nV4-28,4.0,", "\nV4-28,4.2,")
    assert cond != (folder / "conditions.csv").read_text()
    (folder / "conditions.csv").write_text(cond)
    traj = (folder / "trajectory.csv").read_text().splitlines(keepends=True)
    (folder / "trajectory.csv").write_text("".join(l for l in traj if not l.startswith("V2-26,")))
    r = cli("validate", "--dataset", str(folder), "--out", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    for name in ("predictions", "errors", "summary"):
        file = read_csv(tmp_path / "out" / f"{name}.csv").drop(columns=["tolerance", "within_tolerance"], errors="ignore")
        assert_same_table(getattr(ours, name), file)
    assert ours.brief.split(": ", 1)[1] == r.stdout.splitlines()[0].split(": ", 1)[1]
    # estimate takes the edited row too.
    e = chutelab.estimate(dataset=ds, condition="V4-28")
    assert e.values["belt_speed_mps"] == 4.2
    r = cli("estimate", "--dataset", str(folder), "--condition", "V4-28", "--format", "json")
    assert r.returncode == 0, r.stderr
    assert e == json.loads(r.stdout)
    # A conditions row added: a new condition of the rig (the other rows keep their own cells).
    c = ds.conditions
    ds.conditions = pd.concat([c, c[c.condition == "V3-41"].assign(condition="V3-41b", mass_flow_tph=30.0)],
                              ignore_index=True)
    v = chutelab.validate(ds)
    assert "V3-41b" not in set(v.errors.condition)  # no measurements of it
    assert chutelab.estimate(dataset=ds, condition="V3-41b").values["mass_flow_tph"] == 30.0


def test_an_edited_dataset_of_logs_keeps_the_logs_means():
    # Its plate forces come from logs/, not measurements.csv: an edit of another table keeps them.
    ds = chutelab.read_dataset(os.path.join(SOURCE, "datasets", "hidden-effect-logs"), True)
    before = chutelab.validate(ds)
    ds.trajectory = ds.trajectory.iloc[1:]
    after = chutelab.validate(ds)
    # The measurements table shows the logs' means to 15 significant digits (a table shows the
    # number a file would hold), so the means read back agree to about 1e-15 of themselves; errors
    # near zero carry that as an absolute difference. Means lost or re-read would differ by percent.
    a, b = (r.errors[r.errors.x_mm.isna()].reset_index(drop=True) for r in (after, before))
    pd.testing.assert_frame_equal(a, b, check_exact=False, rtol=1e-12, atol=1e-12)
    assert len(after.errors) < len(before.errors)  # one trajectory point fewer


def test_a_bad_edit_is_refused_naming_table_row_and_column(tmp_path):
    ds = chutelab.read_dataset(RIG)
    assert ds.measurements.quantity[2] == "resultant_force_N"
    ds.measurements.loc[2, "value"] = -5.0  # a resultant force below zero
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(ds)
    assert (e.value.file, e.value.line, e.value.field) == ("measurements table", 3, "value")
    assert str(e.value).startswith("measurements table, row 3 (index 2): value: "), str(e.value)
    ds.measurements.loc[2, "value"] = 15.0
    ds.measurements.loc[5, "condition"] = "nowhere"
    with pytest.raises(chutelab.InputError) as e:
        chutelab.diagnose(ds)
    assert e.value.line == 6 and "not in conditions.csv" in str(e.value)
    ds.measurements = ds.measurements.drop(columns=["value"])
    with pytest.raises(chutelab.InputError) as e:
        chutelab.validate(ds)
    assert e.value.file == "measurements table" and e.value.field == "value" and "missing" in str(e.value)
    ds = chutelab.read_dataset(RIG)
    ds.conditions.loc[1, "belt_speed_mps"] = math.nan
    with pytest.raises(chutelab.InputError) as e:
        chutelab.estimate(dataset=ds, condition="V2-26")
    assert (e.value.file, e.value.line, e.value.field) == ("conditions table", 2, "belt_speed_mps")
    # What is not a table cannot be changed, rather than be ignored.
    with pytest.raises(TypeError):
        ds.setup["plate.angle_deg"] = 10.0
    with pytest.raises(AttributeError):
        ds.name = "other"


def test_ctrl_c_stops_a_long_call_promptly_and_writes_nothing(tmp_path):
    # A DEM validation (minutes) and a large self-check, each stopped by SIGINT a second after it
    # started: KeyboardInterrupt within seconds, no cache temporaries, every cache entry whole.
    cache = tmp_path / "cache"
    code = f"""
import sys, time, chutelab
for what in ("dem", "self_check"):
    print("start", what, flush=True)
    t0 = time.monotonic()
    try:
        if what == "dem":
            chutelab.validate({RIG!r}, models=["dem"], dem_quality="quick", dem_threads=1, dem_cache={str(cache)!r})
        else:
            chutelab.diagnose({RIG!r}, self_check=2000)
        print("finished", what, flush=True)
    except KeyboardInterrupt:
        print("interrupted", what, round(time.monotonic() - t0, 2), flush=True)
"""
    import signal
    import time
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=os.environ)
    try:
        for what in ("dem", "self_check"):
            assert child.stdout.readline().split() == ["start", what]
            time.sleep(1.5)
            sent = time.monotonic()
            child.send_signal(signal.SIGINT)
            import select
            ready, _, _ = select.select([child.stdout], [], [], 30)
            assert ready, f"{what}: no answer 30 s after Ctrl-C"
            line = child.stdout.readline().split()
            assert line[:2] == ["interrupted", what], line
            assert time.monotonic() - sent < 15
        assert child.wait(timeout=30) == 0, child.stderr.read()
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    left = os.listdir(cache) if cache.exists() else []
    assert not [f for f in left if f.endswith(".tmp")]
    for f in left:
        if f.endswith(".txt"):
            assert (cache / f).read_bytes().splitlines()[-1].startswith(b"end "), f
