"""chutelab from Python: the same C++ models, dataset reader, harness and diagnosis as the
`chutelab` command line, with results as dicts, NumPy arrays and pandas DataFrames.

    import chutelab
    chutelab.estimate(belt_speed=4, mass_flow=35, plate_distance=450)   # dict, as estimate --format json
    ds = chutelab.read_dataset("datasets/grima2010")
    v = chutelab.validate(ds)                       # v.errors: errors.csv as a DataFrame
    d = chutelab.diagnose(ds)                       # d.ranking: diagnosis.csv as a DataFrame
    after = chutelab.validate(ds, effects={"air_drag": "fit"})

Units are the command line's and the files': m/s, t/h, mm, N, degrees. Tables carry the column
names and numbers of the CSV files the commands write (each number as written there: the shortest
decimal that reads back as the computed double).
Bad input raises chutelab.InputError (a ValueError) with .file, .line (0 = none) and .field.
NumPy and pandas are optional: without pandas a table is a dict of NumPy arrays, without NumPy a
dict of lists.
"""

import json as _json
import math as _math
import os as _os
import tempfile as _tempfile

from . import _chutelab
from ._tables import parse_csv as _parse_csv, table as _table

InputError = _chutelab.InputError

__all__ = ["estimate", "read_dataset", "validate", "diagnose", "synthesize", "models", "effects",
           "Dataset", "Validation", "Diagnosis", "InputError", "DEFAULT_DATASET"]

DEFAULT_DATASET = _chutelab.default_dataset
"""The bundled rig (datasets/grima2010) that estimate() and synthesize() use by default."""


def _path(p):
    return "" if p is None else _os.fspath(p)


def _refuse(field, problem):
    """An InputError as the library raises them (file "", line 0, the keyword as field)."""
    e = InputError(f"{field}: {problem}")
    e.file, e.line, e.field, e.problem = "", 0, field, problem
    return e


def _flag(field, value):
    """A yes/no keyword takes True or False, not "no" (which bool() would read as True)."""
    if not isinstance(value, bool) and type(value).__name__ != "bool_":
        raise _refuse(field, f"must be True or False, got {value!r}")
    return bool(value)


def _real(field, value, optional=False):
    """A number keyword takes a real number (int, float, NumPy scalar), not a text or a bool; the
    library then checks that it is finite and in range, as the command line's flag."""
    if value is None and optional:
        return None
    if isinstance(value, (bool, str, bytes)) or not hasattr(value, "__float__"):
        raise _refuse(field, f"must be a number, got {value!r}")
    return float(value)


def _whole(field, value, optional=False):
    """A count keyword takes a whole number: 2 or 2.0, not 1.5, "2" or True."""
    if value is None and optional:
        return None
    f = None if isinstance(value, (bool, str, bytes)) or not hasattr(value, "__float__") else float(value)
    if f is None or not _math.isfinite(f) or f != int(f):
        raise _refuse(field, f"must be a whole number, got {value!r}")
    return int(f)


def _text(field, value):
    """A text keyword (a quality, a condition) takes a str; None is the default."""
    if value is None:
        return ""
    if not isinstance(value, str):
        raise _refuse(field, f"must be a text, got {value!r}")
    return value


def _effect_args(effects):
    """{"air_drag": 0.7, "belt_slip": "fit"}, ["air_drag=0.7"], "air_drag=fit" or None ->
    the command line's NAME=VALUE strings."""
    if effects is None:
        return []
    if isinstance(effects, str):
        return [effects]
    if isinstance(effects, dict):
        out = []
        for name, value in effects.items():
            if isinstance(value, str):
                out.append(f"{name}={value}")
            else:
                out.append(f"{name}={float(value)!r}")
        return out
    return [str(e) for e in effects]


def _model_list(models):
    """"korzen,booth-cema" or a list; an empty item is passed on for the library to refuse."""
    if isinstance(models, str):
        return models.split(",") if models else []
    return list(models)


def estimate(belt_speed=None, mass_flow=None, plate_distance=None, plate_top=None,
             stream_thickness=None, *, dataset=None, setup=None, condition=None, effects=None):
    """The analytical answer (Booth/CEMA + Korzen) for one condition, in the units of the
    command-line flags: belt_speed in m/s, mass_flow in t/h, plate_distance, plate_top and
    stream_thickness in mm. dataset (a folder) or setup (a setup.toml) picks the rig (default:
    the bundled grima2010); condition starts from a row of the dataset's conditions.csv; effects
    as {"air_drag": 0.5}. Returns the object `chutelab estimate --format json` prints."""
    text = _chutelab.estimate_json(_real("belt_speed", belt_speed, True), _real("mass_flow", mass_flow, True),
                                   _real("plate_distance", plate_distance, True),
                                   _real("plate_top", plate_top, True),
                                   _real("stream_thickness", stream_thickness, True), _path(dataset),
                                   _path(setup), _text("condition", condition), _effect_args(effects))
    return _json.loads(text)


class Dataset:
    """A dataset folder read by the strict reader (DESIGN.md §2).

    name, dir, setup (dict "section.key" -> value in the file's units), and the tables
    conditions (resolved per condition, plate_angle_deg and belt_incline_deg included),
    measurements and trajectory, with the files' column names and units."""

    def __init__(self, core):
        self._core = core
        self.name = core.name
        self.dir = core.dir
        self.setup = core.setup
        self.conditions = _table(core.conditions(), text_columns=("condition",))
        self.measurements = _table(core.measurements(), text_columns=("condition", "quantity"))
        self.trajectory = _table(core.trajectory(), text_columns=("condition", "boundary"))

    def __repr__(self):
        return f"chutelab.Dataset({self.name!r}, dir={self.dir!r})"


def read_dataset(path, measurements_required=False):
    """Reads a dataset folder; raises InputError naming file, line and field on bad input.
    measurements.csv may be absent (a rig and its conditions, e.g. datasets/grima2010) unless
    measurements_required; validate() and diagnose() need it."""
    return Dataset(_chutelab.read_dataset(_os.fspath(path), _flag("measurements_required", measurements_required)))


def _dataset(d, measurements_required=True):
    if isinstance(d, Dataset):
        if measurements_required and not _os.path.exists(_os.path.join(d.dir, "measurements.csv")):
            read_dataset(d.dir, True)  # raises the reader's InputError
        return d
    return read_dataset(d, measurements_required)


class Validation:
    """What `chutelab validate` writes, as tables: predictions, errors (E = S - D, E/u, u_val,
    tolerance verdicts) and summary, with the CSV files' columns. effects lists the effects as
    applied ("air_drag=0.61 (fitted)"); brief is the command's one-line summary."""

    def __init__(self, raw):
        text = ("condition", "model", "quantity", "tolerance", "within_tolerance")
        self.predictions = _table(_parse_csv(raw["predictions"]), text_columns=text)
        self.errors = _table(_parse_csv(raw["errors"]), text_columns=text)
        self.summary = _table(_parse_csv(raw["summary"]), text_columns=text)
        self.models = list(raw["models"])
        self.effects = list(raw["effects"])
        self.notes = list(raw["notes"])
        self.brief = raw["brief"]
        self.acceptance_checked = raw["acceptance_checked"]
        self.acceptance_failed = raw["acceptance_failed"]
        self.rms_normalised_error = dict(raw["rms_normalised_error"])
        self.combined_rms_normalised_error = raw["combined_rms_normalised_error"]

    def __repr__(self):
        return f"chutelab.Validation({self.brief!r})"


def validate(dataset, models=("korzen", "booth-cema"), effects=None, *, tolerances=None,
             dem_quality="", dem_threads=None, dem_cache=None, no_dem_cache=False):
    """Every condition of `dataset` (a Dataset or a folder) through `models`, compared with its
    measurements, as `chutelab validate`. effects: {"air_drag": 0.7} fixed or {"air_drag": "fit"}
    calibrated on the dataset; the result is then the models with the effects (call once without
    effects for "before"). tolerances: a tolerances.toml; acceptance_failed says whether any
    limit was exceeded."""
    d = _dataset(dataset)
    raw = _chutelab.validate(d._core, _model_list(models), _effect_args(effects), _path(tolerances),
                             _text("dem_quality", dem_quality), _whole("dem_threads", dem_threads, True),
                             _path(dem_cache),
                             _flag("no_dem_cache", no_dem_cache))
    return Validation(raw)


class Diagnosis:
    """What `chutelab diagnose` finds: ranking (diagnosis.csv; its first row is the best single
    effect), patterns (residual trends per
    model, quantity and driver), verdict, best (the recommended effect or None), markdown
    (diagnosis.md) and the numbers behind them."""

    def __init__(self, raw):
        # A pair's row joins its two values with "+" (as diagnosis.csv does), which leaves rank,
        # estimate and uncertainty as text when the ranking holds a pair.
        self.ranking = _table(_parse_csv(raw["ranking"]),
                              text_columns=("effect", "parameter", "significant", "signature",
                                            "wants_outside_range", "beaten_outside_range_by"))
        self.patterns = _table(raw["patterns"], text_columns=("model", "quantity", "driver"))
        # verdict_code: "consistent", "missing_effect", "partial_explanation", "out_of_range",
        # "outside_library" or "no_data"; best_fit: {effect: {"value", "uncertainty"}} or None;
        # outliers, model_form: lists of dicts; uncertainty_scale: what the scatter says of the
        # stated uncertainties; self_check: the replicas' rates (diagnose(..., self_check=N)).
        for key in ("markdown", "verdict", "models", "n_data", "n_without_uncertainty",
                    "chi2_baseline", "baseline_p_value", "any_significant", "convincing", "best",
                    "failure_summary", "indistinguishable", "discriminators", "caveats",
                    "verdict_code", "goodness_of_fit", "thin_data", "findings", "wants_outside",
                    "outliers", "model_form", "uncertainty_scale", "best_fit", "self_check"):
            setattr(self, key, raw[key])

    def __repr__(self):
        return f"chutelab.Diagnosis({self.verdict!r})"


def diagnose(dataset, models=("booth-cema", "korzen"), *, alpha=0.01, pairs=True, dem_quality="",
             dem_threads=None, dem_cache=None, no_dem_cache=False, self_check=0, seed=1):
    """Ranks the candidate physical effects by how much of the models' misfit each explains, as
    `chutelab diagnose`; self_check=N also diagnoses N replicas of the dataset's design (as
    `--self-check N`, replicas from `seed` on)."""
    d = _dataset(dataset)
    raw = _chutelab.diagnose(d._core, _model_list(models), _real("alpha", alpha), _flag("pairs", pairs),
                             _text("dem_quality", dem_quality), _whole("dem_threads", dem_threads, True),
                             _path(dem_cache),
                             _flag("no_dem_cache", no_dem_cache), self_check, seed)
    return Diagnosis(raw)


def synthesize(dataset=None, effects=None, *, seed=1, noise_scale=1.0, out=None):
    """A synthetic dataset, as `chutelab synthesize`: the analytical models plus hidden effects
    plus Gaussian noise on the rig and conditions of `dataset` (default: the bundled grima2010).
    Written to `out` when given (and read back from there); otherwise to a temporary folder that
    is removed once the dataset is read, so the returned Dataset's dir no longer exists."""
    source = _dataset(DEFAULT_DATASET if dataset is None else dataset, measurements_required=False)
    args = _effect_args(effects)
    if out is not None:
        _chutelab.synthesize(source._core, args, seed, _real("noise_scale", noise_scale), _os.fspath(out))
        return read_dataset(out)
    with _tempfile.TemporaryDirectory(prefix="chutelab-synthetic-") as tmp:
        _chutelab.synthesize(source._core, args, seed, _real("noise_scale", noise_scale), tmp)
        return read_dataset(tmp)


def models():
    """The model names --models accepts, in report order."""
    return list(_chutelab.model_names())


def effects():
    """The registered candidate effects: name, parameter, unit, stage, neutral value, physical
    range, typical strength, physics and source."""
    rows = _chutelab.effect_library()
    cols = {k: [r[k] for r in rows] for k in (rows[0].keys() if rows else [])}
    return _table(cols, text_columns=("effect", "parameter", "unit", "stage", "physics", "source"))
