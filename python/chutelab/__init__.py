"""chutelab from Python: the same C++ library (models, dataset reader, V&V 20 harness, diagnosis)
as the `chutelab` command line, with results as pandas DataFrames and typed values.

    import chutelab
    e = chutelab.estimate(belt_speed=4, mass_flow=35, plate_distance=450)
    e.predictions                        # DataFrame: model, quantity, value (full double precision)
    e.trajectory()                       # DataFrame: the streamlines' flight, t_s, x_mm, y_mm, ...
    ds = chutelab.read_dataset(chutelab.DATASETS + "/hidden-effect")
    v = chutelab.validate(ds)            # v.errors: E = S - D, u_val, tolerance flags, per value
    d = chutelab.diagnose(ds)            # d.ranking; d.best_fit["air_drag"]: Strength(value, sd, unit)
    after = chutelab.validate(ds, effects={"air_drag": "fit"})
    after.write_report("out/report")     # report.html, report.md and the CSV files, as validate --out

Units are the command line's and the files': m/s, t/h, mm, N, degrees. A column's unit is in its
name (x_mm, t_s) or, in the long tables (value, measured, predicted, error, ...), in the row's
quantity (normal_force_N), as in the CSV files; quantities() gives each quantity's symbol, label
and unit. Numbers are the C++ doubles themselves, not rounded text.

Tables are pandas DataFrames; without pandas (python3-pandas) they are NumPy record arrays with
the same column names. NumPy is required.
Bad input raises chutelab.InputError (a ValueError) with .file, .line (0 = none) and .field (the
keyword of the argument, or the file's column).
"""

import json as _json
import os as _os
import tempfile as _tempfile
from collections.abc import Mapping as _Mapping
from typing import Any, Dict, Iterator, List, Optional, Sequence, Union

from types import MappingProxyType as _MappingProxy

from ._tables import table as _table, np as _np
from ._types import Quantity, Strength
from ._args import (EffectsArg, _effect_args, _flag, _model_list, _new, _options, _path, _real, _reals, _refuse,
                    _seed_like, _text, _texts, _whole)
from . import _chutelab
from . import _edits

InputError = _chutelab.InputError
InputError.__doc__ = ("Bad input: a ValueError with .file and .line (\"\", 0 when an argument, not a file, "
                      "is wrong), .field (the keyword or the file's column) and .problem.")

__all__ = ["estimate", "sweep", "read_dataset", "validate", "diagnose", "synthesize", "import_logs", "synthesize_logs",
           "calibrate", "sensitivity", "write_report", "models", "effects", "quantities", "Estimate", "Sweep", "Dataset",
           "Validation", "Diagnosis", "Calibration", "Sensitivity", "Strength", "Quantity", "InputError", "DATASETS",
           "DEFAULT_DATASET"]

PathLike = Union[str, _os.PathLike]
# A table: a pandas DataFrame, or a NumPy record array (same columns) without pandas.
TABLE = "pandas.DataFrame | numpy.recarray"

_here = _os.path.dirname(_os.path.abspath(__file__))
DATASETS: str = (_os.path.join(_here, "datasets") if _os.path.isdir(_os.path.join(_here, "datasets"))
                 else _chutelab.source_datasets)
"""The bundled datasets (grima2010, hidden-effect, liggghts-rig, ...): installed with the package,
or the checkout's datasets/ when the package is used from the build folder."""

DEFAULT_DATASET: str = _os.path.join(DATASETS, "grima2010")
"""The bundled rig (datasets/grima2010) that estimate() and synthesize() use by default."""


# ---- estimate ------------------------------------------------------------------------------------

class Estimate(_Mapping):
    """The analytical answer (Booth/CEMA + Korzen) for one condition, from estimate().

    As a mapping it is the object `chutelab estimate --format json` prints (e["models"]["korzen"]
    ["normal_force_N"]). Its attributes hold the C++ doubles themselves:

    values       {name: float}: the condition as resolved and the analysis (belt_speed_mps,
                 stream_thickness_mm, release_angle_deg, impact_velocity_mps, normal_force_N, ...,
                 impact_zone_*_mm, mean_pressure_Pa)
    predictions  table model, quantity, value: every analytical model's quantities (units in the
                 quantity's name; quantities() for labels)
    effects      {effect: strength} as applied
    streamlines  {"lower"|"upper"|"cema_centroid"|"korzen_centroid": array (n, 2) of x_mm, y_mm}:
                 the paths as drawn and exported (DESIGN.md frame: origin at the pulley centre,
                 x towards the plate, y up), round the pulley then in flight to the plate
    trajectory() a dense table of the same lines' flight, with time and velocity
    """

    _core: Any
    _dict: Optional[dict]

    @classmethod
    def _make(cls, core) -> "Estimate":
        self = _new(cls)
        self._core = core
        self._dict = None
        self.values: Dict[str, float] = dict(core.values())
        self.predictions = _table(core.models())
        self.effects: Dict[str, float] = dict(core.effects())
        self.streamlines: Dict[str, Any] = dict(core.paths())
        return self

    def trajectory(self, points: int = 200) -> TABLE:
        """Each streamline's flight from its release to the plate line (to 1 s of flight when it
        misses the plate), at `points` (>= 2) equal time steps: a table with columns streamline
        (lower, upper, cema_centroid, korzen_centroid), t_s (from the release), x_mm, y_mm,
        vx_mps, vy_mps. The model's own trajectory (closed form, or its RK4 path when an effect
        adds a force in flight), so any density gives points on the same curve."""
        n = _whole("points", points)
        if n < 2 or n > 1_000_000:
            raise _refuse("points", f"must be from 2 to 1000000, got {points!r}")
        return _table(self._core.flight(n))

    def as_dict(self) -> dict:
        """The object `chutelab estimate --format json` prints (a new dict each call)."""
        return _json.loads(self._core.json())

    def _mapping(self) -> dict:
        if self._dict is None:
            self._dict = self.as_dict()
        return self._dict

    def __getitem__(self, key: str) -> Any:
        return self._mapping()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._mapping())

    def __len__(self) -> int:
        return len(self._mapping())

    def __repr__(self) -> str:
        v = self.values
        return (f"chutelab.Estimate(belt_speed_mps={v['belt_speed_mps']!r}, mass_flow_tph={v['mass_flow_tph']!r}, "
                f"plate_distance_mm={v['plate_distance_mm']!r}, normal_force_N={v['normal_force_N']!r})")


def _estimate_options(options, belt_speed, mass_flow, plate_distance, plate_top, stream_thickness, pulley_diameter,
                      belt_width, bulk_density, dataset, setup, condition, effects, head=dict):
    """estimate()'s keywords checked and set on the module's `options` (EstimateOptions, or
    SweepOptions with head(): sweep()'s own keyword, checked once the dataset is read)."""
    read = _dataset(dataset, measurements_required=False) if isinstance(dataset, Dataset) else None
    return _options(options, **head(), belt_speed=_real("belt_speed", belt_speed, True),
                    mass_flow=_real("mass_flow", mass_flow, True),
                    plate_distance=_real("plate_distance", plate_distance, True),
                    plate_top=_real("plate_top", plate_top, True),
                    stream_thickness=_real("stream_thickness", stream_thickness, True),
                    pulley_diameter=_real("pulley_diameter", pulley_diameter, True),
                    belt_width=_real("belt_width", belt_width, True), bulk_density=_real("bulk_density", bulk_density, True),
                    dataset="" if read is not None else _path("dataset", dataset), setup=_path("setup", setup),
                    condition=_text("condition", condition), effects=_effect_args(effects),
                    default_dataset=DEFAULT_DATASET, dataset_read=read)


def estimate(belt_speed: Optional[float] = None, mass_flow: Optional[float] = None,
             plate_distance: Optional[float] = None, plate_top: Optional[float] = None,
             stream_thickness: Optional[float] = None, *, dataset: Union["Dataset", PathLike, None] = None,
             setup: Optional[PathLike] = None, condition: Optional[str] = None,
             effects: EffectsArg = None, pulley_diameter: Optional[float] = None,
             belt_width: Optional[float] = None, bulk_density: Optional[float] = None) -> Estimate:
    """The analytical answer (Booth/CEMA + Korzen) for one condition, in milliseconds.

    belt_speed in m/s, mass_flow in t/h, plate_distance, plate_top and stream_thickness in mm.
    dataset (a Dataset, as edited, or a folder) or setup (a setup.toml) picks the rig (default:
    the bundled grima2010);
    pulley_diameter and belt_width (mm) and bulk_density (kg/m^3) replace the rig's values;
    condition starts from a row of the dataset's conditions.csv, the numbers given replace its
    values; effects as {"air_drag": 0.5}. Returns an Estimate (see help(chutelab.Estimate)).
    Raises InputError naming the keyword for a missing, impossible or mistyped value."""
    core = _chutelab.estimate(_estimate_options(_chutelab.EstimateOptions(), belt_speed, mass_flow, plate_distance,
                                                plate_top, stream_thickness, pulley_diameter, belt_width,
                                                bulk_density, dataset, setup, condition, effects))
    return Estimate._make(core)


class Sweep:
    """One input stepped over a range, the rest of the design held, from sweep(): every point
    through the same estimate as a single design (`chutelab estimate --sweep`).

    column       the swept value's name with its unit ("belt_speed_mps")
    rows         table, one row a value: the swept value, the estimate's values, each model's
                 quantities as MODEL_QUANTITY ("korzen_normal_force_N"; NaN where a point has no
                 answer) and a note (why there is no answer, or what is partial; "" when none)
    csv(), json(), text()  the command line's --format csv, json and table, as text
    svg()        the chart of impact points and plate forces (--svg), as text
    """

    column: str
    rows: Any

    @classmethod
    def _make(cls, core) -> "Sweep":
        self = _new(cls)
        self._core = core
        self.column = core.column()
        self.rows = _table(core.rows())
        return self

    def csv(self) -> str:
        return self._core.csv()

    def json(self) -> str:
        return self._core.json()

    def text(self) -> str:
        return self._core.table()

    def svg(self) -> str:
        return self._core.svg()

    def __repr__(self) -> str:
        return f"chutelab.Sweep({self.column!r}, {len(self.rows)} points)"


def sweep(sweep: str, belt_speed: Optional[float] = None, mass_flow: Optional[float] = None,
          plate_distance: Optional[float] = None, plate_top: Optional[float] = None,
          stream_thickness: Optional[float] = None, *, dataset: Union["Dataset", PathLike, None] = None,
          setup: Optional[PathLike] = None, condition: Optional[str] = None,
          effects: EffectsArg = None, pulley_diameter: Optional[float] = None,
          belt_width: Optional[float] = None, bulk_density: Optional[float] = None) -> Sweep:
    """estimate() at every value of one input, as `chutelab estimate --sweep`.

    sweep: "NAME=FROM:TO:STEP", NAME a condition input (belt_speed in m/s, mass_flow in t/h,
    plate_distance, plate_top, stream_thickness in mm; leave that keyword out), a conditions.csv
    override column (plate_angle_deg, pulley_diameter_mm, friction_plate, ...) or an effect's name
    (its strength). The other keywords are estimate()'s. A point with no answer (the stream misses
    the plate, the belt is overfilled) is a row with its note; InputError when no point has one.
    Returns a Sweep (see help(chutelab.Sweep))."""
    core = _chutelab.sweep(_estimate_options(_chutelab.SweepOptions(), belt_speed, mass_flow, plate_distance,
                                             plate_top, stream_thickness, pulley_diameter, belt_width, bulk_density,
                                             dataset, setup, condition, effects,
                                             head=lambda: {"sweep": _text("sweep", sweep)}))
    return Sweep._make(core)


# ---- datasets ------------------------------------------------------------------------------------

_TABLES = ("conditions", "measurements", "trajectory")


class Dataset:
    """A dataset in memory, from read_dataset() or synthesize() (docs/datasets.md has the files).

    name, dir (the folder it was read from; None for one synthesize() made without out=), setup
    ({"section.key": value} in the file's units; read-only), and the tables conditions (resolved
    per condition: plate_angle_deg and belt_incline_deg included), measurements and trajectory,
    with the files' column names and units (a number as the file holds it).

    It owns what it read: read_dataset() copies the folder's files, so the folder may change or go
    afterwards. The tables may be edited (a value, a row added or dropped, a table replaced):
    validate(), diagnose(), synthesize() and estimate() take the tables as they are then, read
    again by the files' own reader with every check it makes, and a bad edit raises InputError
    naming the table, its row (1 = the first) and column. In conditions, an edited cell replaces
    that condition's value in conditions.csv (a new column there: a per-condition override, or an
    input uncertainty); what is not edited keeps the file's own text. name, dir and setup cannot be
    changed (edit setup.toml and read the dataset again)."""

    @classmethod
    def _make(cls, core) -> "Dataset":
        self = _new(cls)
        self._core = core
        self._sources = dict(core.sources())
        self._name = core.name
        self._dir = core.dir or None
        self._setup = _MappingProxy(dict(core.setup))
        self.conditions = _table(core.conditions())
        self.measurements = _table(core.measurements())
        self.trajectory = _table(core.trajectory())
        self._seen = {t: _edits.copy(getattr(self, t)) for t in _TABLES}
        # A dataset of rig logs has measurements that are in no measurements.csv (logs/): after an
        # edit of any table they are written from the measurements table, not lost.
        meas = self._sources.get("measurements.csv")
        in_file = len(_chutelab.csv_cells(meas[1], meas[0])[1]) if meas else 0
        self._measured_elsewhere = len(self.measurements) != in_file
        return self

    name = property(lambda self: self._name, doc="The setup's name.")
    dir = property(lambda self: self._dir, doc="The folder it was read from (None: made in memory).")
    setup = property(lambda self: self._setup, doc="setup.toml as {\"section.key\": value}, read-only.")

    def _current(self, measurements_required: bool = False):
        """The C++ dataset of the tables as they are now (read again when one was edited)."""
        edited = [t for t in _TABLES if not _edits.same(getattr(self, t), self._seen[t])]
        if edited:
            if self._measured_elsewhere and "measurements" not in edited:
                edited.append("measurements")
            files = dict(self._sources)
            for t in edited:
                table = getattr(self, t)
                try:
                    if t == "conditions":
                        shown, text, _ = files["conditions.csv"]
                        text = _edits.conditions_csv(table, self._seen[t], text, shown)
                    else:
                        text = _edits.table_csv(table)
                except KeyError as e:
                    raise _refuse(t, f"the table has no column {e.args[0]!r}") from None
                except AttributeError:
                    raise _refuse(t, f"must be a table, got {type(table).__name__}") from None
                files[f"{t}.csv"] = (f"the {t} table", text.encode("utf-8"), False)
            try:
                core = _chutelab.dataset_from_sources(files, self._dir or "", False)
            except InputError as e:
                raise self._edit_error(e, edited) from None
            self._core, self._sources, self._measured_elsewhere = core, files, False
            self._seen = {t: _edits.copy(getattr(self, t)) for t in _TABLES}
        if measurements_required and "measurements.csv" not in self._sources and not len(self.measurements):
            _chutelab.dataset_from_sources(self._sources, self._dir or "", True)  # raises the reader's error
        return self._core

    def _edit_error(self, e, edited):
        """The reader's error in an edited table, said by table, row and column."""
        for t in edited:
            if e.file == f"the {t} table":
                k = e.line - 2  # the header is line 1
                table = getattr(self, t)
                where = f"{t} table" + (f", row {k + 1} (index {_edits.index_of(table, k)!r})" if 0 <= k < len(table)
                                        else "")
                err = InputError(f"{where}: {e.field + ': ' if e.field else ''}{e.problem}")
                err.file, err.line, err.field, err.problem = f"{t} table", max(k + 1, 0), e.field, e.problem
                return err
        return e

    def __repr__(self) -> str:
        return f"chutelab.Dataset({self.name!r}, dir={self.dir!r})"


def read_dataset(path: PathLike, measurements_required: bool = False) -> Dataset:
    """Reads a dataset folder into memory; raises InputError naming file, line and field on bad
    input. The Dataset keeps what it read (help(chutelab.Dataset)).

    measurements.csv may be absent (a rig and its conditions, e.g. DEFAULT_DATASET) unless
    measurements_required; validate() and diagnose() need it."""
    return Dataset._make(_chutelab.read_dataset(_path("path", path, optional=False),
                                                _flag("measurements_required", measurements_required)))


def _dataset(d, measurements_required=True, field="dataset"):
    """The C++ dataset of a Dataset (its tables as they are now) or of a folder."""
    if isinstance(d, Dataset):
        return d._current(measurements_required)
    return read_dataset(_path(field, d, optional=False), measurements_required)._core


def _strengths(rows) -> List[Strength]:
    return [Strength(effect=r["effect"], parameter=r["parameter"], value=r["value"], sd=r["sd"], unit=r["unit"],
                     fitted=r["fitted"]) for r in rows]


# ---- diagnose ------------------------------------------------------------------------------------

class Diagnosis:
    """Which candidate effect the models miss, from diagnose() (or validate()'s .diagnosis).

    ranking      table of the single effects, best first (diagnosis.csv's columns: rank, effect,
                 parameter, estimate, uncertainty (one sd, in the effect's unit; effects() has
                 it), chi2_before, chi2_after, delta_bic, explained_fraction, significant (bool),
                 p_value, p_adjusted, signature, outside_range_*, wants_outside_range (bool), ...)
    pairs        the pairs of effects fitted together, one column per member (effect_1,
                 estimate_1, uncertainty_1, effect_2, ...)
    best_fit     {effect: Strength} of the recommended fit (empty when nothing is named)
    best         the recommended effect ("air_drag", "a+b" for a pair) or None
    verdict      the verdict in words; verdict_code: "consistent", "missing_effect",
                 "partial_explanation", "out_of_range", "outside_library" or "no_data"
    any_significant, convincing, thin_data (bools); n_data, chi2_baseline, baseline_p_value
    patterns     table of the residuals' trends per model, quantity and driver
    outliers, model_form (lists of dicts), uncertainty_scale (dict), caveats, findings,
    failure_summary, discriminators (lists of text), markdown (diagnosis.md),
    self_check (dict of the replicas' rates, or None)
    """

    ranking: Any
    pairs: Any
    patterns: Any
    best_fit: Dict[str, Strength]
    best: Optional[str]
    verdict: str
    verdict_code: str

    _FIELDS = ("markdown", "verdict", "models", "n_data", "n_without_uncertainty", "chi2_baseline",
               "baseline_p_value", "any_significant", "convincing", "best", "failure_summary", "indistinguishable",
               "discriminators", "caveats", "verdict_code", "goodness_of_fit", "thin_data", "findings",
               "wants_outside", "outliers", "model_form", "uncertainty_scale")

    @classmethod
    def _make(cls, raw, core=None) -> "Diagnosis":
        self = _new(cls)
        self._core = core
        self.ranking = _table(raw["ranking"])
        self.pairs = _table(raw["pairs"])
        self.patterns = _table(raw["patterns"])
        self.best_fit = {s.effect: s for s in _strengths(raw["best_fit"])}
        for key in cls._FIELDS:
            setattr(self, key, raw[key])
        self.self_check = raw.get("self_check")
        return self

    def write_report(self, out: PathLike) -> None:
        """Writes diagnosis.csv and diagnosis.md (and the self-check's files) into the folder
        `out`, as `chutelab diagnose --out` does: all files or none, never onto the dataset."""
        if self._core is None:
            raise _refuse("out", "this diagnosis is part of a validation: use that Validation's write_report()")
        self._core.write(_path("out", out, optional=False))

    def __repr__(self) -> str:
        return f"chutelab.Diagnosis({self.verdict!r})"


def diagnose(dataset: Union[Dataset, PathLike], models: Union[str, Sequence[str]] = ("booth-cema", "korzen"), *,
             alpha: float = 0.01, pairs: bool = True, dem_quality: Optional[str] = None,
             dem_threads: Optional[int] = None, dem_cache: Optional[PathLike] = None, no_dem_cache: bool = False,
             self_check: int = 0, seed: int = 1, inputs: EffectsArg = None) -> Diagnosis:
    """Ranks the candidate physical effects (and recorded inputs) by how much of the models'
    misfit each explains, as `chutelab diagnose`.

    inputs: recorded inputs corrected first, {"plate_distance": 25.0} (truth minus record, in the
    input's unit) or {"plate_distance": "fit"}, as `diagnose --input`: the candidates are then what
    the corrected rig still misses.

    dataset: a Dataset or a folder with measurements. alpha: the family-wise false-alarm rate;
    pairs: also fit pairs of effects. self_check=N also diagnoses N replicas of the dataset's
    design (replicas from `seed` on) and reports the false-alarm rate and power. Models include
    "dem" (dem_quality "quick"/"standard"/..., dem_threads, dem_cache; slow, cached)."""
    d = _dataset(dataset)
    core = _chutelab.diagnose(d, _model_list(models), _real("alpha", alpha), _flag("pairs", pairs),
                              _text("dem_quality", dem_quality), _whole("dem_threads", dem_threads, True),
                              _path("dem_cache", dem_cache), _flag("no_dem_cache", no_dem_cache),
                              _seed_like("self_check", self_check), _seed_like("seed", seed),
                              _effect_args(inputs, "inputs"))
    return Diagnosis._make(core.numbers(), core)


# ---- validate ------------------------------------------------------------------------------------

class Validation:
    """Every condition through the models, compared with the measurements (ASME V&V 20), from
    validate(). The tables have the columns of the files `chutelab validate` writes, with the
    verdicts as flags and the limits as numbers:

    predictions  condition, model, quantity, value, uncertainty, x_mm
    errors       condition, model, quantity, measured, uncertainty, predicted, error (E = S - D),
                 relative_error, normalised_error (E/u_val), x_mm, validation_uncertainty (u_val),
                 vv20_ratio, tolerance_checked (bool: a limit applied), within_tolerance (bool;
                 True where none applied), tolerance_failed (the first limit exceeded, in words),
                 tolerance_relative, tolerance_absolute, tolerance_normalised (the limits; NaN
                 where not set), u_num_stat, u_num_disc, u_input, y_mm, z_mm
    summary      model, quantity, n, rms_error, rms_normalised_error, max_abs_relative_error,
                 tolerance_checked, within_tolerance

    effects      [Strength]: the effects added, fitted ones with their ± (empty without effects)
    brief        the command's one-line summary; notes: e.g. the fit's chi^2
    rms_normalised_error {model: float}; combined_rms_normalised_error: float
    acceptance_checked, acceptance_failed (bools), acceptance_problems (texts): the acceptance of
                 the models as delivered, also when effects were added (as the command line's exit
                 code); of the models with the effects only with accept_with_effects=True
    accepted_with_effects (bool); outside_tolerance_beside: how many checked values of the other
                 result (with the effects, or as delivered) are outside tolerance, or None
    diagnosis    the Diagnosis validate ran (with effects, or diagnose=True), or None
    write_report(out) writes report.html, report.md and the CSV files, as validate --out
    """

    predictions: Any
    errors: Any
    summary: Any
    effects: List[Strength]
    brief: str
    acceptance_checked: bool
    acceptance_failed: bool
    combined_rms_normalised_error: float
    diagnosis: Optional[Diagnosis]

    @classmethod
    def _make(cls, core) -> "Validation":
        raw = core.numbers()
        self = _new(cls)
        self._core = core
        self.predictions = _table(raw["predictions"])
        self.errors = _table(raw["errors"])
        self.summary = _table(raw["summary"])
        self.models = list(raw["models"])
        self.effects = _strengths(raw["effects"])
        self.notes = list(raw["notes"])
        self.brief = raw["brief"]
        self.acceptance_checked = raw["acceptance_checked"]
        self.acceptance_failed = raw["acceptance_failed"]
        self.acceptance_problems = list(raw["acceptance_problems"])
        self.accepted_with_effects = raw["accepted_with_effects"]
        self.outside_tolerance_beside = raw["outside_tolerance_beside"]
        self.rms_normalised_error = dict(raw["rms_normalised_error"])
        self.combined_rms_normalised_error = raw["combined_rms_normalised_error"]
        self.diagnosis = Diagnosis._make(raw["diagnosis"]) if raw["diagnosis"] is not None else None
        return self

    def write_report(self, out: PathLike) -> None:
        """Writes predictions.csv, errors.csv, summary.csv, report.md, report.html and the report's
        charts as figures/NN-ID.svg (and, with a diagnosis, diagnosis.csv and diagnosis.md) into the
        folder `out`: the files
        `chutelab validate --out` writes for the same inputs, all or none, never onto an input.
        With the "dem" model the command line also keeps each condition's series under dem/;
        these are not written here (the DEM cache, dem_cache=, keeps the runs)."""
        self._core.write(_path("out", out, optional=False))

    def __repr__(self) -> str:
        return f"chutelab.Validation({self.brief!r})"


def validate(dataset: Union[Dataset, PathLike], models: Union[str, Sequence[str]] = ("korzen", "booth-cema"),
             effects: EffectsArg = None, *, tolerances: Optional[PathLike] = None, diagnose: bool = False,
             accept_with_effects: bool = False, dem_quality: Optional[str] = None, dem_threads: Optional[int] = None,
             dem_cache: Optional[PathLike] = None, no_dem_cache: bool = False) -> Validation:
    """Every condition of `dataset` (a Dataset or a folder) through `models`, compared with its
    measurements, as `chutelab validate`.

    effects: {"air_drag": 0.7} fixed or {"air_drag": "fit"} calibrated on the dataset; the tables
    are then those of the models with the effects (call once without effects for "before"), and
    the diagnosis runs too, as on the command line. diagnose=True ranks the candidate effects
    without adding any. tolerances: a tolerances.toml (default: the dataset's own when present);
    acceptance_failed judges the models as delivered, and the models with the effects only with
    accept_with_effects=True, which takes fixed strengths alone (a strength fitted to the
    measurements it is judged on passes for the wrong reason).
    Models include "dem" (dem_quality, dem_threads, dem_cache, no_dem_cache; slow, cached as on
    the command line)."""
    d = _dataset(dataset)
    core = _chutelab.validate(d, _model_list(models), _effect_args(effects), _path("tolerances", tolerances),
                              _flag("diagnose", diagnose), _flag("accept_with_effects", accept_with_effects),
                              _text("dem_quality", dem_quality),
                              _whole("dem_threads", dem_threads, True), _path("dem_cache", dem_cache),
                              _flag("no_dem_cache", no_dem_cache))
    return Validation._make(core)


def write_report(result: Union[Validation, Diagnosis], out: PathLike) -> None:
    """Writes a validation's or a diagnosis's files into the folder `out`, the same files the
    command line's --out gets (result.write_report(out))."""
    if not isinstance(result, (Validation, Diagnosis)):
        raise _refuse("result", f"must be what validate() or diagnose() returned, got {type(result).__name__}")
    result.write_report(out)


# ---- synthesize ----------------------------------------------------------------------------------

def synthesize(dataset: Union[Dataset, PathLike, None] = None, effects: EffectsArg = None, *, seed: int = 1,
               noise_scale: float = 1.0, out: Optional[PathLike] = None) -> Dataset:
    """A synthetic dataset, as `chutelab synthesize`: the analytical models plus hidden effects
    plus Gaussian noise on the rig and conditions of `dataset` (a Dataset, as edited, or a folder;
    default: the bundled grima2010).

    Written to the folder `out` when given (all files or none, never onto the source) and read
    back from there; without out= it lives in memory only (its dir is None) and is validated,
    diagnosed or synthesized from like any other."""
    source = _dataset(DEFAULT_DATASET if dataset is None else dataset, measurements_required=False)
    args = _effect_args(effects)
    seed = _seed_like("seed", seed)
    scale = _real("noise_scale", noise_scale)
    target = "" if out is None else _path("out", out, optional=False)
    if out is not None and not target:
        raise _refuse("out", "is empty; give a folder")
    return Dataset._make(_chutelab.synthesize(source, args, seed, scale, target))


# ---- rig logs ------------------------------------------------------------------------------------

def import_logs(dataset: PathLike, out: PathLike) -> Dataset:
    """A dataset of means from a dataset of rig logs, as `chutelab import-logs`: each condition's
    logs/<condition>.csv read with logs/layout.toml (steady window, zero, drift and creep found from
    the log; the uncertainty counts the samples' correlation). Written to `out` (measurements.csv
    with each row's provenance, log_provenance.csv, log_checks.csv) and read back from there."""
    target = _path("out", out, optional=False)
    _chutelab.import_logs(_path("dataset", dataset, optional=False), target)
    return read_dataset(target, True)


def synthesize_logs(dataset: PathLike, truth: PathLike, *, sensor: Optional[PathLike] = None,
                    dem_series: Optional[PathLike] = None, seed: int = 1, out: PathLike) -> Dataset:
    """A dataset of rig logs written by the virtual rig, as `chutelab synthesize-logs`: the true
    means in `truth` (CSV condition,quantity,value) through a sensor model (`sensor`, TOML; default
    the built-in one), optionally with the fluctuation of DEM runs (`dem_series`). Written to `out`
    and read back from there (its logs read into means)."""
    target = _path("out", out, optional=False)
    _chutelab.synthesize_logs(_path("dataset", dataset, optional=False), _path("truth", truth, optional=False),
                              _path("sensor", sensor) or "", _path("dem_series", dem_series) or "",
                              _seed_like("seed", seed), target)
    return read_dataset(target, True)


# ---- the studies: calibration and sensitivity -----------------------------------------------------

class Calibration:
    """The slump-test calibration (the reference study's §5, Table 3), from calibrate().

    rows          one slump test a row: shape, grain, rolling_friction, solid_density_kgm3,
                  bulk_density_kgm3, pile_height_mm, repose_angle_deg, particles, settled (bool),
                  run_seconds, target_distance (NaN without a target), closest (bool)
    incline       the inclined-plane rig: rolling_friction, wall_friction, onset_deg, motion,
                  eq10_onset_deg, eq10_motion
    closest       the index in rows of the combination closest to the target, or None
    material_toml the dataset's [material] with the chosen solid density and rolling friction
    findings      the trends in words; table3: the reference study's layout (Markdown)
    write_report(out) writes calibration.csv, incline.csv, calibration.md, .html, .svg,
                  material.toml and calibration-timing.csv, as `chutelab calibrate --out`
    """

    rows: Any
    incline: Any
    closest: Optional[int]
    material_toml: str

    @classmethod
    def _make(cls, core) -> "Calibration":
        raw = core.numbers()
        self = _new(cls)
        self._core = core
        self.rows = _table(raw["rows"])
        self.incline = _table(raw["incline"])
        self.closest = raw["closest"]
        self.material_toml = raw["material_toml"]
        self.findings = list(raw["findings"])
        self.table3 = raw["table3"]
        return self

    def write_report(self, out: PathLike) -> None:
        """Writes the calibration's files into the folder `out`, all or none, never onto the dataset."""
        self._core.write(_path("out", out, optional=False))

    def __repr__(self) -> str:
        return f"chutelab.Calibration({len(self.rows)} slump tests, closest {self.closest!r})"


def calibrate(dataset: Optional[PathLike] = None, *, quality: str = "quick",
              rolling: Union[float, Sequence[float]] = (0.05, 0.1, 0.2),
              density: Union[float, Sequence[float]] = (925.0, 1000.0),
              shapes: Union[str, Sequence[str]] = ("sphere", "clump"), sphere_diameter_mm: float = 5.6,
              clump_diameter_mm: float = 4.4, target: bool = True, target_bulk_density: Optional[float] = None,
              target_pile_height_mm: Optional[float] = None, incline: bool = True, threads: int = 1,
              seed: int = 1, jobs: int = 0) -> Calibration:
    """Slump tests over rolling friction x solid density x shape on the swing-arm slump tester
    (the DEM), as `chutelab calibrate`: the combination closest to the measured bulk density (and
    pile height) is the calibrated material. Each quick test takes ~5-20 s of a core.

    dataset: a folder whose [material] to calibrate (default: the bundled grima2010). quality:
    "quick" or "standard". target_bulk_density (kg/m^3; default the dataset's bulk density),
    target_pile_height_mm; target=False marks no combination. incline=False skips the inclined-plane
    rig. threads: OpenMP threads per run; jobs: runs side by side (0: one per idle core); the numbers
    do not depend on either. Returns a Calibration (see help(chutelab.Calibration))."""
    core = _chutelab.calibrate(_options(
        _chutelab.CalibrateOptions(), dataset=_path("dataset", dataset) or DEFAULT_DATASET,
        quality=_text("quality", quality), rolling=_reals("rolling", rolling), density=_reals("density", density),
        shapes=_texts("shapes", shapes), sphere_diameter_mm=_real("sphere_diameter_mm", sphere_diameter_mm),
        clump_diameter_mm=_real("clump_diameter_mm", clump_diameter_mm), target=_flag("target", target),
        target_bulk_density=_real("target_bulk_density", target_bulk_density, True),
        target_pile_height_mm=_real("target_pile_height_mm", target_pile_height_mm, True),
        incline=_flag("incline", incline), threads=_whole("threads", threads), seed=_seed_like("seed", seed),
        jobs=_whole("jobs", jobs)))
    return Calibration._make(core)


class Sensitivity:
    """The reference study's Table 6 (§6.1) at one condition, from sensitivity().

    rows        one station DEM run a variant, the base first: variant, label, group, diameter_mm,
                normal_force_N, shear_force_N, resultant_force_N with their *_se_N (standard
                errors), resultant_force_sd_N (the fluctuation), change_percent and
                change_se_percent (of the mean R against the base), dt_s, particles, steady (bool),
                run_seconds
    verdict     the verdict on the reference study's conclusion, in words; reproduced, complete (bools)
    notes       what ran that a label cannot say (a step set by the Rayleigh cap, sizes left out)
    write_report(out) writes sensitivity.csv, .md, .html, .svg and sensitivity-timing.csv, as
                `chutelab sensitivity --out`
    """

    rows: Any
    verdict: str
    reproduced: bool
    complete: bool

    @classmethod
    def _make(cls, core) -> "Sensitivity":
        raw = core.numbers()
        self = _new(cls)
        self._core = core
        self.rows = _table(raw["rows"])
        self.verdict = raw["verdict"]
        self.reproduced = raw["reproduced"]
        self.complete = raw["complete"]
        self.notes = list(raw["notes"])
        return self

    def write_report(self, out: PathLike) -> None:
        """Writes the study's files into the folder `out`, all or none, never onto the dataset."""
        self._core.write(_path("out", out, optional=False))

    def __repr__(self) -> str:
        return f"chutelab.Sensitivity({len(self.rows)} runs, reproduced={self.reproduced})"


def sensitivity(dataset: Optional[PathLike] = None, condition: str = "V3-41", *, quality: str = "quick",
                only: Union[None, str, Sequence[str]] = None, sizes_mm: Union[None, float, Sequence[float]] = None,
                threads: Optional[int] = None, seed: Optional[int] = None, limit: float = 10.0,
                jobs: int = 0) -> Sensitivity:
    """The station DEM once per variant of the reference study's Table 6 (contact law, clump,
    dt/20, G x10 and /10, particle sizes) at one condition, as `chutelab sensitivity`: minutes at
    quick quality.

    dataset: a folder (default: the bundled grima2010); condition: a row of its conditions.csv.
    quality: the base run's preset. only: the variants to run besides the base ("G/10", ...);
    sizes_mm: the size variants' sphere diameters (default 5.6, 9, 13.6; 9 and 13.6 at quick
    quality). limit: "changes little" means |change of mean R| <= limit %. threads: OpenMP threads
    per run (default 1); jobs: runs side by side (0: one per idle core); the numbers do not depend
    on either. Returns a Sensitivity (see help(chutelab.Sensitivity))."""
    core = _chutelab.sensitivity(_options(
        _chutelab.SensitivityOptions(), dataset=_path("dataset", dataset) or DEFAULT_DATASET,
        condition=_text("condition", condition), quality=_text("quality", quality),
        only=[] if only is None else _texts("only", only),
        sizes_mm=[] if sizes_mm is None else _reals("sizes_mm", sizes_mm), threads=_whole("threads", threads, True),
        seed=None if seed is None else _seed_like("seed", seed), limit=_real("limit", limit),
        jobs=_whole("jobs", jobs)))
    return Sensitivity._make(core)


# ---- the registry --------------------------------------------------------------------------------

def models() -> List[str]:
    """The model names validate() and diagnose() accept, in report order."""
    return list(_chutelab.model_names())


def effects() -> TABLE:
    """The registered candidate effects as a table: effect, parameter, unit, stage, kind
    ("physics", or "record" for a recorded input that may be wrong), neutral, lower, upper
    (physical range), typical (strength), physics and source."""
    rows = _chutelab.effect_library()
    keys = ("effect", "parameter", "unit", "stage", "kind", "neutral", "lower", "upper", "typical", "physics", "source")
    numeric = {"neutral", "lower", "upper", "typical"}
    return _table({k: (_np.array([r[k] for r in rows], dtype=float) if k in numeric else [r[k] for r in rows])
                   for k in keys})


def quantities() -> Dict[str, Quantity]:
    """{name: Quantity(name, symbol, label, unit)} for every quantity the tables' `quantity`
    column can hold (normal_force_N, ..., trajectory_upper_y_mm): axis labels for plots,
    e.g. quantities()["normal_force_N"].axis_label == "plate normal force R_n [N]"."""
    return {n: Quantity(n, s, label, unit) for n, s, label, unit in _chutelab.quantities()}
