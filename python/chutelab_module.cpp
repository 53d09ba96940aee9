// _chutelab: the compiled half of the Python package. It binds the library's functions (api/:
// estimate, validate, diagnose, synthesize), the ones the command line calls, and hands back their
// results (the estimate's JSON, the CSV tables, the numbers) so that Python sees the same names and
// the same numbers; chutelab/__init__.py turns them into dicts, NumPy arrays and DataFrames. No
// physics here, and nothing of the command line's.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cctype>
#include <cmath>
#include <fmt/format.h>

#include "api/diagnose.h"
#include "api/effects.h"
#include "api/estimate.h"
#include "api/synthesize.h"
#include "api/validate.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/output_folder.h"
#include "core/units.h"
#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/dataset_output.h"
#include "validation/diagnosis.h"
#include "validation/harness.h"
#include "validation/model.h"
#include "validation/output_files.h"
#include "validation/self_check.h"
#include "validation/synthesize.h"
#include "validation/tolerances.h"

namespace py = pybind11;
using namespace chutelab;

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

// The library names an input by a neutral key ("dem.threads", core/input_error.h); here it is the
// keyword of the package's function (dem_threads). Keys that are no keyword here (a column, a TOML
// key, an option the package does not have) are shown as they are.
std::string python_keyword(std::string_view key) {
  static const std::pair<std::string_view, std::string_view> renamed[] = {
      {"effect", "effects"}, {"dem.quality", "dem_quality"}, {"dem.threads", "dem_threads"},
      {"dem.cache", "dem_cache"}, {"dem.no_cache", "no_dem_cache"}};
  for (const auto& [k, word] : renamed)
    if (k == key) return std::string(word);
  return std::string(key);
}

// Inside a message another input is named as it is typed here: "use dataset=".
std::string python_mention(std::string_view key) {
  static const std::string_view keywords[] = {"dataset", "setup", "condition", "effect", "models", "tolerances",
                                              "seed", "noise_scale", "out", "alpha", "dem.quality", "dem.threads",
                                              "dem.cache", "dem.no_cache", "self_check", "belt_speed", "mass_flow",
                                              "plate_distance", "plate_top", "stream_thickness"};
  for (const auto k : keywords)
    if (k == key) return python_keyword(key) + "=";
  return std::string(key);
}

// A whole number from Python: an int (not a bool), or a float that is whole; checked by `rule`, the
// command line's (core/option_check.h). seed=1.5 is refused, not truncated to 1.
double whole_number(const py::object& v, const options::NumberRule& rule) {
  if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) ||
                                         py::hasattr(v, "__index__")))
    throw InputError("", 0, std::string(rule.key),
                     fmt::format("must be {}, got {}", rule.describe(), std::string(py::str(py::repr(v)))));
  if (py::isinstance<py::float_>(v)) return rule.check(v.cast<double>());
  // An int of any size, checked exactly by its digits (as the command line checks what is typed), so a
  // huge one is refused, not wrapped.
  const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  if (!i) throw py::error_already_set();
  return rule.check(std::string(py::repr(i)));
}

api::DemOptions dem_options(const std::string& quality, std::optional<int> threads, const std::string& cache,
                            bool no_cache) {
  api::DemOptions d;
  d.quality = quality;
  d.threads = threads;
  d.cache = cache;
  d.no_cache = no_cache;
  return d;
}

// Columns of a table in boundary units, named as in the dataset's CSV files.
using Columns = std::vector<std::pair<std::string, py::list>>;
Columns columns(std::initializer_list<const char*> names) {
  Columns c;
  for (const char* n : names) c.emplace_back(n, py::list());
  return c;
}
py::dict as_dict(const Columns& cols) {
  py::dict d;
  for (const auto& [name, values] : cols) d[py::str(name)] = values;
  return d;
}
// A file's value went to SI and back; 15 significant digits drop the conversion's last-bit noise,
// so a table shows the number the file holds (41.9, not 41.900000000000006).
double as_written(double v) { return std::isfinite(v) ? std::stod(fmt::format("{:.15g}", v)) : v; }
py::object number_or_nan(const std::optional<double>& v) {
  return py::float_(v ? as_written(*v) : std::nan(""));
}

py::dict conditions_table(const validation::Dataset& d) {
  Columns c = columns({"condition", "belt_speed_mps", "mass_flow_tph", "plate_distance_mm", "plate_top_mm",
                       "stream_thickness_mm", "plate_angle_deg", "belt_incline_deg"});
  for (const auto& s : d.stations) {
    c[0].second.append(s.condition);
    c[1].second.append(as_written(s.belt_speed));
    c[2].second.append(as_written(s.mass_flow / units::tph));
    c[3].second.append(as_written(s.plate_distance / units::mm));
    c[4].second.append(as_written(s.plate_top / units::mm));
    c[5].second.append(number_or_nan(s.stream_thickness ? std::optional(*s.stream_thickness / units::mm)
                                                        : std::nullopt));
    c[6].second.append(as_written(s.plate.angle * kDeg));
    c[7].second.append(as_written(s.belt.incline * kDeg));
  }
  return as_dict(c);
}

py::dict measurements_table(const validation::Dataset& d) {
  Columns c = columns({"condition", "quantity", "value", "uncertainty"});
  for (const auto& m : d.measurements) {
    const double s = info(m.quantity).to_boundary;
    c[0].second.append(m.condition);
    c[1].second.append(std::string(name(m.quantity)));
    c[2].second.append(as_written(m.value * s));
    c[3].second.append(number_or_nan(m.uncertainty ? std::optional(*m.uncertainty * s) : std::nullopt));
  }
  return as_dict(c);
}

py::dict trajectory_table(const validation::Dataset& d) {
  Columns c = columns({"condition", "boundary", "x_mm", "y_mm", "uncertainty_mm"});
  for (const auto& p : d.trajectory) {
    c[0].second.append(p.condition);
    c[1].second.append(std::string(name(p.boundary)));
    c[2].second.append(as_written(p.x / units::mm));
    c[3].second.append(as_written(p.y / units::mm));
    c[4].second.append(number_or_nan(p.uncertainty ? std::optional(*p.uncertainty / units::mm) : std::nullopt));
  }
  return as_dict(c);
}

// setup.toml as "section.key" -> value in the file's units (the rig-field table says which).
py::dict setup_dict(const Setup& setup) {
  py::dict d;
  d["name"] = setup.name;
  d["source"] = setup.source;
  Setup copy = setup;
  for (const auto& f : rig_fields()) {
    const std::string key = f.section.empty() ? std::string(f.key) : fmt::format("{}.{}", f.section, f.key);
    d[py::str(key)] = as_written(f.ref(copy) / f.to_si);
  }
  return d;
}

py::dict validate(const validation::Dataset& d, const std::vector<std::string>& model_names,
                  const std::vector<std::string>& effect_args, const std::string& tolerances,
                  const std::string& dem_quality, std::optional<int> dem_threads,
                  const std::string& dem_cache, bool no_dem_cache) {
  api::ValidateOptions o;
  o.models = model_names;
  o.effects = effect_args;
  o.tolerances = tolerances;
  o.diagnose_with_effects = false;
  o.dem = dem_options(dem_quality, dem_threads, dem_cache, no_dem_cache);
  std::optional<api::ValidateResult> v;
  {
    py::gil_scoped_release free;
    v = api::validate(d, o);
  }
  const validation::ValidationResult* result = &v->final_result();
  py::dict r;
  r["predictions"] = validation::predictions_csv(*result);
  r["errors"] = validation::errors_csv(*result);
  r["summary"] = validation::summary_csv(*result);
  r["models"] = result->models;
  r["effects"] = result->effects;
  r["notes"] = v->notes;
  r["brief"] = result->brief();
  r["acceptance_checked"] = result->acceptance_checked;
  r["acceptance_failed"] = result->acceptance_failed;
  r["combined_rms_normalised_error"] = number_or_nan(result->combined_rms_normalised());
  py::dict overall;
  for (const auto& m : result->models) overall[py::str(m)] = number_or_nan(result->overall_rms_normalised(m));
  r["rms_normalised_error"] = overall;
  return r;
}

const char* verdict_name(validation::Verdict v) {
  switch (v) {
    case validation::Verdict::no_data: return "no_data";
    case validation::Verdict::consistent: return "consistent";
    case validation::Verdict::missing_effect: return "missing_effect";
    case validation::Verdict::partial_explanation: return "partial_explanation";
    case validation::Verdict::out_of_range: return "out_of_range";
    case validation::Verdict::outside_library: return "outside_library";
  }
  return "";
}

// The numbers behind the verdict, as plain Python values.
void diagnosis_numbers(const validation::DiagnosisResult& x, py::dict& r) {
  r["verdict_code"] = verdict_name(x.verdict_code);
  r["goodness_of_fit"] = x.goodness_of_fit;
  r["thin_data"] = x.thin_data;
  r["findings"] = x.findings;
  r["wants_outside"] = x.wants_outside;
  py::list outliers;
  for (const auto& o : x.outliers) {
    py::dict d;
    d["condition"] = o.condition, d["quantity"] = o.quantity, d["file"] = o.where.file, d["line"] = o.where.line;
    d["measured"] = o.measured, d["predicted"] = o.predicted, d["deviation"] = o.deviation;
    d["relative"] = o.relative;
    outliers.append(d);
  }
  r["outliers"] = outliers;
  py::list model_form;
  for (const auto& m : x.model_form) {
    py::dict d;
    d["quantity"] = m.quantity, d["model"] = m.model, d["n"] = m.n, d["discrepancy"] = m.tau;
    d["mean_error"] = m.mean_error, d["mean_relative_error"] = m.mean_relative;
    model_form.append(d);
  }
  r["model_form"] = model_form;
  py::dict scale;
  scale["factor"] = x.scale.factor, scale["dof"] = x.scale.dof, scale["applied"] = x.scale.applied;
  scale["too_large"] = x.scale.too_large, scale["p_high"] = x.scale.p_high, scale["p_low"] = x.scale.p_low;
  r["uncertainty_scale"] = scale;
  if (const auto* b = x.best()) {
    py::dict fit;
    for (std::size_t i = 0; i < b->effects.size(); ++i) {
      py::dict e;
      e["value"] = b->estimate[i];
      e["uncertainty"] = b->uncertainty[i];
      fit[py::str(b->effects[i])] = e;
    }
    r["best_fit"] = fit;
  } else {
    r["best_fit"] = py::none();
  }
}

py::dict diagnose(const validation::Dataset& d, const std::vector<std::string>& model_names, double alpha,
                  bool pairs, const std::string& dem_quality, std::optional<int> dem_threads,
                  const std::string& dem_cache, bool no_dem_cache, const py::object& self_check_arg,
                  const py::object& seed_arg) {
  api::DiagnoseOptions o;
  o.self_check = static_cast<int>(whole_number(self_check_arg, options::rules::self_check));
  const double seed_checked = whole_number(seed_arg, options::rules::seed);
  o.seed = py::isinstance<py::float_>(seed_arg) ? static_cast<std::uint64_t>(seed_checked)
                                                 : seed_arg.cast<std::uint64_t>();
  o.models = model_names;
  o.alpha = alpha;
  o.pairs = pairs;
  o.dem = dem_options(dem_quality, dem_threads, dem_cache, no_dem_cache);
  std::optional<api::DiagnoseResult> diagnosed;
  {
    py::gil_scoped_release free;
    diagnosed = api::diagnose(d, o);
  }
  const auto& res = diagnosed->diagnosis;
  const auto& sc = diagnosed->self_check;
  const auto& x = res;
  py::dict r;
  diagnosis_numbers(x, r);
  if (sc) {
    py::dict c;
    c["null_replicas"] = sc->null_replicas, c["false_alarms"] = sc->false_alarms;
    c["false_alarm_rate"] = sc->false_alarm_rate(), c["false_alarm_upper"] = sc->false_alarm_upper;
    c["truth"] = sc->truth, c["truth_strength"] = sc->truth_strength;
    c["effect_replicas"] = sc->effect_replicas, c["named"] = sc->named, c["named_other"] = sc->named_other;
    c["covered"] = sc->covered, c["power"] = sc->power(), c["coverage"] = sc->coverage();
    c["markdown"] = validation::self_check_markdown(*sc, alpha);
    r["self_check"] = c;
  } else {
    r["self_check"] = py::none();
  }
  r["ranking"] = validation::diagnosis_csv(x);
  r["markdown"] = validation::diagnosis_markdown(x);
  r["verdict"] = x.verdict;
  r["models"] = x.models;
  r["n_data"] = x.n_data;
  r["n_without_uncertainty"] = x.n_without_uncertainty;
  r["chi2_baseline"] = x.chi2_baseline;
  r["baseline_p_value"] = x.baseline_p_value;
  r["any_significant"] = x.any_significant;
  r["convincing"] = x.convincing;
  const auto* best = x.best();
  r["best"] = best ? py::object(py::str(best->label())) : py::object(py::none());
  r["failure_summary"] = x.failure_summary;
  r["indistinguishable"] = x.indistinguishable;
  r["discriminators"] = x.discriminators;
  r["caveats"] = x.caveats;
  Columns p = columns({"model", "quantity", "driver", "n", "mean_normalised", "rms_normalised", "correlation",
                       "notable"});
  for (const auto& q : x.patterns) {
    p[0].second.append(q.model);
    p[1].second.append(q.quantity);
    p[2].second.append(q.driver);
    p[3].second.append(q.n);
    p[4].second.append(q.mean_normalised);
    p[5].second.append(q.rms_normalised);
    p[6].second.append(q.correlation);
    p[7].second.append(q.notable);
  }
  r["patterns"] = as_dict(p);
  return r;
}

void synthesize(const validation::Dataset& source, const std::vector<std::string>& effect_args,
                const py::object& seed_arg, double noise_scale, const std::filesystem::path& out) {
  api::SynthesizeOptions o;
  const double seed_checked = whole_number(seed_arg, options::rules::seed);
  o.seed = py::isinstance<py::float_>(seed_arg)
               ? static_cast<std::uint64_t>(seed_checked)
               : py::reinterpret_steal<py::int_>(PyNumber_Index(seed_arg.ptr())).cast<std::uint64_t>();
  o.noise_scale = noise_scale;
  o.effects = effect_args;
  api::check(o);
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  // The same refusal as the command line's before any work: out may not be the source.
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    OutputFolder check(out, plan.inputs);
    return {};
  };
  py::gil_scoped_release free;
  const api::SynthesizeResult r = api::synthesize(source, o);
  validation::write_dataset(out, r.files, source.dir);
}

}  // namespace

PYBIND11_MODULE(_chutelab, m) {
  m.doc() = "chutelab's C++ core (use the chutelab package, not this module)";

  // InputError(ValueError) carrying file, line (0 = none) and field, as the command line's
  // one-line message names them.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object err = py::reinterpret_borrow<py::object>(input_error)(py::str(e.said(python_keyword, python_mention)));
      err.attr("file") = e.file();
      err.attr("line") = e.line();
      err.attr("field") = one_line(python_keyword(e.field()));
      err.attr("problem") = one_line(e.problem_said(python_mention));
      PyErr_SetObject(input_error.ptr(), err.ptr());
    }
  });

  m.attr("default_dataset") = std::string(CHUTELAB_DATASETS_DIR) + "/grima2010";

  m.def(
      "estimate_json",
      [](std::optional<double> belt_speed, std::optional<double> mass_flow,
         std::optional<double> plate_distance, std::optional<double> plate_top,
         std::optional<double> stream_thickness, const std::string& dataset, const std::string& setup,
         const std::string& condition, const std::vector<std::string>& effect_args) {
        api::EstimateOptions in;
        in.dataset = dataset;
        in.setup = setup;
        in.condition = condition;
        in.default_dataset = std::filesystem::path(CHUTELAB_DATASETS_DIR) / "grima2010";
        in.belt_speed = belt_speed;
        in.mass_flow = mass_flow;
        in.plate_distance = plate_distance;
        in.plate_top = plate_top;
        in.stream_thickness = stream_thickness;
        in.effects = effect_args;
        return api::estimate(in).json();
      },
      py::arg("belt_speed"), py::arg("mass_flow"), py::arg("plate_distance"), py::arg("plate_top"),
      py::arg("stream_thickness"), py::arg("dataset"), py::arg("setup"), py::arg("condition"),
      py::arg("effects"));

  py::class_<validation::Dataset>(m, "Dataset")
      .def_property_readonly("dir", [](const validation::Dataset& d) { return d.dir.string(); })
      .def_property_readonly("name", [](const validation::Dataset& d) { return d.setup.name; })
      .def_property_readonly("setup", [](const validation::Dataset& d) { return setup_dict(d.setup); })
      .def("conditions", &conditions_table)
      .def("measurements", &measurements_table)
      .def("trajectory", &trajectory_table);

  m.def(
      "read_dataset",
      [](const std::filesystem::path& dir, bool measurements_required) {
        return validation::read_dataset(dir, measurements_required ? validation::MeasurementsRequired::yes
                                                                   : validation::MeasurementsRequired::no);
      },
      py::arg("dir"), py::arg("measurements_required"));

  m.def("validate", &validate, py::arg("dataset"), py::arg("models"), py::arg("effects"),
        py::arg("tolerances"), py::arg("dem_quality"), py::arg("dem_threads"), py::arg("dem_cache"),
        py::arg("no_dem_cache"));
  m.def("diagnose", &diagnose, py::arg("dataset"), py::arg("models"), py::arg("alpha"), py::arg("pairs"),
        py::arg("dem_quality"), py::arg("dem_threads"), py::arg("dem_cache"), py::arg("no_dem_cache"),
        py::arg("self_check"), py::arg("seed"));
  m.def("synthesize", &synthesize, py::arg("source"), py::arg("effects"), py::arg("seed"),
        py::arg("noise_scale"), py::arg("out"));

  m.def("model_names", &validation::model_names);
  m.def("effect_library", [] {
    py::list out;
    for (const auto& e : effects::library()) {
      py::dict d;
      d["effect"] = e.name;
      d["parameter"] = e.parameter;
      d["unit"] = e.unit;
      d["stage"] = e.stage;
      d["kind"] = e.kind == effects::EffectInfo::Kind::record ? "record" : "physics";
      d["neutral"] = e.neutral;
      d["lower"] = e.lower;
      d["upper"] = e.upper;
      d["typical"] = e.typical;
      d["physics"] = e.physics;
      d["source"] = e.source;
      out.append(d);
    }
    return out;
  });
}
