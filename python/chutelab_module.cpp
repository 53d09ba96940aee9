// _chutelab: the compiled half of the Python package. It binds the library's functions (api/:
// estimate, validate, diagnose, synthesize), the ones the command line calls, keeps their result
// structs, and hands their doubles to Python as NumPy arrays (no text in between), with the
// columns of the files the command line writes; chutelab/__init__.py makes DataFrames and typed
// values of them. No physics here, and nothing of the command line's (app/ is not included).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cctype>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <fmt/format.h>

#include "api/calibrate.h"
#include "api/dem_options.h"
#include "api/diagnose.h"
#include "api/effects.h"
#include "api/estimate.h"
#include "api/files.h"
#include "api/import_logs.h"
#include "api/sensitivity.h"
#include "api/sweep.h"
#include "api/synthesize.h"
#include "api/synthesize_logs.h"
#include "api/validate.h"
#include "core/input_error.h"
#include "core/interrupt.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/output_folder.h"
#include "core/progress.h"
#include "core/units.h"
#include "core/csv_field.h"
#include "validation/csv_table.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/harness.h"
#include "validation/model.h"
#include "validation/self_check.h"
#include "validation/synthesize.h"
#include "validation/tolerances.h"

namespace py = pybind11;
using namespace chutelab;

namespace {

// Whether `key` is a [dem] setting validate and diagnose take here as a keyword: only the quality.
bool dem_keyword(std::string_view key) { return key == api::key(api::DemSetting::quality); }

// The library names an input by a neutral key ("dem.threads", core/input_error.h); here it is the
// keyword of the package's function (dem_threads). Keys that are no keyword here (a column, a TOML
// key, an option the package does not have) are shown as they are.
std::string python_keyword(std::string_view key) {
  static const std::pair<std::string_view, std::string_view> renamed[] = {
      {"effect", "effects"}, {"input", "inputs"}, {"dem.threads", "dem_threads"},
      {"dem.cache", "dem_cache"}, {"dem.no_cache", "no_dem_cache"}, {"shape", "shapes"}, {"sizes", "sizes_mm"},
      {"sphere_diameter", "sphere_diameter_mm"}, {"clump_diameter", "clump_diameter_mm"},
      {"target_pile_height", "target_pile_height_mm"}};
  for (const auto& [k, word] : renamed)
    if (k == key) return std::string(word);
  // The [dem] settings validate and diagnose take (api/dem_options.h): "dem.quality" is dem_quality.
  if (dem_keyword(key)) return "dem_" + std::string(key.substr(4));
  return std::string(key);
}

// Inside a message another input is named as it is typed here: "use dataset=".
std::string python_mention(std::string_view key) {
  static const std::string_view keywords[] = {"dataset", "setup", "condition", "effect", "models", "tolerances",
                                              "seed", "noise_scale", "out", "alpha", "dem.threads",
                                              "dem.cache", "dem.no_cache", "self_check", "belt_speed", "mass_flow",
                                              "plate_distance", "plate_top", "stream_thickness", "pulley_diameter",
                                              "belt_width", "bulk_density", "diagnose", "input",
                                              "accept_with_effects", "sweep", "rolling", "density", "shape",
                                              "quality", "only", "sizes", "limit", "threads", "jobs", "sphere_diameter",
                                              "clump_diameter", "target_bulk_density", "target_pile_height"};
  for (const auto k : keywords)
    if (k == key) return python_keyword(key) + "=";
  if (dem_keyword(key)) return python_keyword(key) + "=";
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

// A seed from Python, checked as the command line's --seed; a huge int exactly, not wrapped.
std::uint64_t seed_value(const py::object& seed_arg) {
  const double checked = whole_number(seed_arg, options::rules::seed);
  return py::isinstance<py::float_>(seed_arg)
             ? static_cast<std::uint64_t>(checked)
             : py::reinterpret_steal<py::int_>(PyNumber_Index(seed_arg.ptr())).cast<std::uint64_t>();
}

// Ctrl-C during a long call. The library asks this at its interruption points (core/interrupt.h),
// on the calling thread; Python's handler runs there (KeyboardInterrupt, or the user's own), and
// the exception it raises is kept until the call has unwound.
std::optional<py::error_already_set>& pending_signal() {
  static std::optional<py::error_already_set> e;
  return e;
}

bool python_signalled() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() == 0) return false;
  pending_signal().emplace();  // takes (and clears) the handler's exception
  return true;
}

// `f` without the GIL, hearing Ctrl-C: an interrupted call raises the signal handler's exception.
template <class F>
auto interruptible(F&& f) -> decltype(f()) {
  const interrupt::Scope scope(python_signalled);
  try {
    py::gil_scoped_release free;
    return f();
  } catch (const interrupt::Interrupted&) {
    if (auto& e = pending_signal()) {
      py::error_already_set raised = std::move(*e);
      e.reset();
      throw raised;
    }
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
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

// A table for the Python layer: {column: values} in column order, numbers as NumPy arrays of the
// C++ doubles themselves (no text in between), flags as bool arrays, names as lists of str.
class Table {
 public:
  void text(const char* name, std::vector<std::string> v) { d_[name] = py::cast(std::move(v)); }
  void real(const std::string& name, const std::vector<double>& v) { d_[py::str(name)] = py::array_t<double>(v.size(), v.data()); }
  void real(const char* name, const std::vector<double>& v) { d_[name] = py::array_t<double>(v.size(), v.data()); }
  void whole(const char* name, const std::vector<long long>& v) {
    d_[name] = py::array_t<long long>(v.size(), v.data());
  }
  void flag(const char* name, const std::vector<bool>& v) {
    py::array_t<bool> a(v.size());
    auto m = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < v.size(); ++i) m(static_cast<py::ssize_t>(i)) = v[i];
    d_[name] = a;
  }
  py::dict dict() const { return d_; }

 private:
  py::dict d_;
};

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
double or_nan(const std::optional<double>& v, double scale = 1.0) { return v ? *v * scale : kNan; }

// A file's value went to SI and back; 15 significant digits drop the conversion's last-bit noise,
// so a table shows the number the file holds (41.9, not 41.900000000000006).
double as_written(double v) { return std::isfinite(v) ? std::stod(fmt::format("{:.15g}", v)) : v; }
double written_or_nan(const std::optional<double>& v, double scale) { return v ? as_written(*v * scale) : kNan; }

py::dict conditions_table(const validation::Dataset& d) {
  std::vector<std::string> condition;
  std::vector<double> speed, flow, distance, top, thickness, angle, incline;
  for (const auto& s : d.stations) {
    condition.push_back(s.condition);
    speed.push_back(as_written(s.belt_speed)), flow.push_back(as_written(s.mass_flow / units::tph));
    distance.push_back(as_written(s.plate_distance / units::mm)), top.push_back(as_written(s.plate_top / units::mm));
    thickness.push_back(written_or_nan(s.stream_thickness, 1.0 / units::mm));
    angle.push_back(as_written(s.plate.angle * units::deg_per_rad)), incline.push_back(as_written(s.belt.incline * units::deg_per_rad));
  }
  Table t;
  t.text("condition", condition), t.real("belt_speed_mps", speed), t.real("mass_flow_tph", flow);
  t.real("plate_distance_mm", distance), t.real("plate_top_mm", top), t.real("stream_thickness_mm", thickness);
  t.real("plate_angle_deg", angle), t.real("belt_incline_deg", incline);
  return t.dict();
}

py::dict measurements_table(const validation::Dataset& d) {
  std::vector<std::string> condition, quantity;
  std::vector<double> value, uncertainty;
  for (const auto& m : d.measurements) {
    const double s = info(m.quantity).to_boundary;
    condition.push_back(m.condition), quantity.emplace_back(name(m.quantity));
    value.push_back(as_written(m.value * s)), uncertainty.push_back(written_or_nan(m.uncertainty, s));
  }
  Table t;
  t.text("condition", condition), t.text("quantity", quantity), t.real("value", value);
  t.real("uncertainty", uncertainty);
  return t.dict();
}

py::dict trajectory_table(const validation::Dataset& d) {
  std::vector<std::string> condition, boundary;
  std::vector<double> x, y, u;
  for (const auto& p : d.trajectory) {
    condition.push_back(p.condition), boundary.emplace_back(name(p.boundary));
    x.push_back(as_written(p.x / units::mm)), y.push_back(as_written(p.y / units::mm));
    u.push_back(written_or_nan(p.uncertainty, 1.0 / units::mm));
  }
  Table t;
  t.text("condition", condition), t.text("boundary", boundary), t.real("x_mm", x), t.real("y_mm", y);
  t.real("uncertainty_mm", u);
  return t.dict();
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

// predictions.csv's rows, as numbers.
py::dict predictions_table(const validation::ValidationResult& r) {
  std::vector<std::string> condition, model, quantity;
  std::vector<double> value, uncertainty, x_mm;
  for (const auto& p : r.predictions)
    for (Quantity q : kAllQuantities) {
      const auto& v = p.prediction.values[q];
      if (!v) continue;
      const double s = info(q).to_boundary;
      condition.push_back(p.condition), model.push_back(p.model), quantity.emplace_back(name(q));
      value.push_back(*v * s), uncertainty.push_back(or_nan(p.prediction.uncertainty[q], s));
      x_mm.push_back(kNan);
    }
  for (const auto& c : r.comparisons)
    if (c.boundary && c.predicted) {
      condition.push_back(c.condition), model.push_back(c.model), quantity.push_back(c.quantity);
      value.push_back(*c.predicted * c.scale), uncertainty.push_back(or_nan(c.u_num_stat(), c.scale));
      x_mm.push_back(c.x * 1e3);
    }
  Table t;
  t.text("condition", condition), t.text("model", model), t.text("quantity", quantity);
  t.real("value", value), t.real("uncertainty", uncertainty), t.real("x_mm", x_mm);
  return t.dict();
}

// errors.csv's rows, as numbers; the tolerance verdict as flags and the limits as numbers.
py::dict errors_table(const validation::ValidationResult& r, const validation::Tolerances* tol) {
  std::vector<std::string> condition, model, quantity, limit;
  std::vector<double> measured, uncertainty, predicted, error, relative, normalised, x_mm, u_val, ratio, stat, disc,
      input, y_mm, z_mm, t_rel, t_abs, t_norm;
  std::vector<bool> checked, within;
  for (const auto& c : r.comparisons) {
    const double s = c.scale;
    condition.push_back(c.condition), model.push_back(c.model), quantity.push_back(c.quantity);
    measured.push_back(c.measured * s), uncertainty.push_back(or_nan(c.uncertainty, s));
    predicted.push_back(or_nan(c.predicted, s));
    error.push_back(c.predicted ? c.error() * s : kNan);
    relative.push_back(or_nan(c.relative_error())), normalised.push_back(or_nan(c.normalised_error()));
    x_mm.push_back(c.boundary ? c.x * 1e3 : kNan);
    u_val.push_back(or_nan(c.validation_uncertainty(), s)), ratio.push_back(or_nan(c.vv20_ratio()));
    // The parts of u_val only beside a prediction: without one nothing was propagated.
    stat.push_back(c.predicted ? or_nan(c.u_num_stat(), s) : kNan);
    disc.push_back(c.predicted ? or_nan(c.u_num_disc, s) : kNan);
    input.push_back(c.predicted ? or_nan(c.u_input, s) : kNan);
    y_mm.push_back(or_nan(c.plate_y, 1e3)), z_mm.push_back(or_nan(c.plate_z, 1e3));
    checked.push_back(c.verdict.checked), within.push_back(c.verdict.passed);
    limit.push_back(c.verdict.passed ? std::string() : c.verdict.limit);
    const validation::Tolerance* t = c.verdict.checked && tol ? tol->find(c.model, c.quantity) : nullptr;
    t_rel.push_back(t ? or_nan(t->relative) : kNan), t_abs.push_back(t ? or_nan(t->absolute) : kNan);
    t_norm.push_back(t ? or_nan(t->normalised) : kNan);
  }
  Table t;
  t.text("condition", condition), t.text("model", model), t.text("quantity", quantity);
  t.real("measured", measured), t.real("uncertainty", uncertainty), t.real("predicted", predicted);
  t.real("error", error), t.real("relative_error", relative), t.real("normalised_error", normalised);
  t.real("x_mm", x_mm), t.real("validation_uncertainty", u_val), t.real("vv20_ratio", ratio);
  t.flag("tolerance_checked", checked), t.flag("within_tolerance", within), t.text("tolerance_failed", limit);
  t.real("tolerance_relative", t_rel), t.real("tolerance_absolute", t_abs), t.real("tolerance_normalised", t_norm);
  t.real("u_num_stat", stat), t.real("u_num_disc", disc), t.real("u_input", input);
  t.real("y_mm", y_mm), t.real("z_mm", z_mm);
  return t.dict();
}

py::dict summary_table(const validation::ValidationResult& r) {
  std::vector<std::string> model, quantity;
  std::vector<long long> n;
  std::vector<double> rms, rms_norm, max_rel;
  std::vector<bool> checked, within;
  for (const auto& s : r.summary) {
    model.push_back(s.model), quantity.push_back(s.quantity), n.push_back(s.n);
    rms.push_back(s.rms_error), rms_norm.push_back(or_nan(s.rms_normalised_error));
    max_rel.push_back(or_nan(s.max_abs_relative_error));
    checked.push_back(s.within_tolerance.has_value()), within.push_back(s.within_tolerance.value_or(true));
  }
  Table t;
  t.text("model", model), t.text("quantity", quantity), t.whole("n", n);
  t.real("rms_error", rms), t.real("rms_normalised_error", rms_norm), t.real("max_abs_relative_error", max_rel);
  t.flag("tolerance_checked", checked), t.flag("within_tolerance", within);
  return t.dict();
}

// A strength as the Python layer's Strength wants it.
py::dict strength(const std::string& effect, const std::string& parameter, double value,
                  std::optional<double> sd, bool fitted) {
  py::dict d;
  d["effect"] = effect, d["parameter"] = parameter, d["value"] = value;
  d["sd"] = sd ? py::object(py::float_(*sd)) : py::object(py::none());
  std::string unit;
  for (const auto& e : api::effect_library())
    if (e.name == effect) unit = e.unit;
  d["unit"] = unit;
  d["fitted"] = fitted;
  return d;
}

// The ranking of diagnosis.csv as numbers: the single effects, and the pairs with one column per
// member (diagnosis.csv joins a pair's two values with "+").
py::dict ranking_table(const std::vector<validation::EffectFit>& fits, bool pairs) {
  const std::size_t k = pairs ? 2 : 1;
  std::vector<std::vector<std::string>> effect(k), parameter(k);
  std::vector<std::vector<double>> estimate(k), uncertainty(k);
  std::vector<long long> rank;
  std::vector<double> chi2_before, chi2_after, bic, explained, p, p_adj, ub_est, ub_unc;
  std::vector<bool> significant, wants_outside;
  std::vector<std::string> signature, beaten;
  for (const auto& f : fits) {
    for (std::size_t i = 0; i < k; ++i) {
      effect[i].push_back(i < f.effects.size() ? f.effects[i] : "");
      parameter[i].push_back(i < f.parameters.size() ? f.parameters[i] : "");
      estimate[i].push_back(i < f.estimate.size() ? f.estimate[i] : kNan);
      uncertainty[i].push_back(i < f.uncertainty.size() ? f.uncertainty[i] : kNan);
    }
    rank.push_back(f.rank);
    chi2_before.push_back(f.chi2_before), chi2_after.push_back(f.chi2_after), bic.push_back(f.delta_bic);
    explained.push_back(f.explained_fraction), p.push_back(f.p_value), p_adj.push_back(f.p_adjusted);
    significant.push_back(f.significant), signature.push_back(f.signature);
    ub_est.push_back(f.unbounded ? f.unbounded->estimate : kNan);
    ub_unc.push_back(f.unbounded ? f.unbounded->uncertainty : kNan);
    wants_outside.push_back(f.unbounded && f.unbounded->wants_outside);
    beaten.push_back(f.beaten_outside_range_by);
  }
  Table t;
  if (pairs) {
    t.text("effect_1", effect[0]), t.text("effect_2", effect[1]);
    t.text("parameter_1", parameter[0]), t.text("parameter_2", parameter[1]);
    t.real("estimate_1", estimate[0]), t.real("uncertainty_1", uncertainty[0]);
    t.real("estimate_2", estimate[1]), t.real("uncertainty_2", uncertainty[1]);
  } else {
    t.whole("rank", rank), t.text("effect", effect[0]), t.text("parameter", parameter[0]);
    t.real("estimate", estimate[0]), t.real("uncertainty", uncertainty[0]);
  }
  t.real("chi2_before", chi2_before), t.real("chi2_after", chi2_after), t.real("delta_bic", bic);
  t.real("explained_fraction", explained), t.flag("significant", significant), t.real("p_value", p);
  t.real("p_adjusted", p_adj), t.text("signature", signature);
  if (!pairs) {
    t.real("outside_range_estimate", ub_est), t.real("outside_range_uncertainty", ub_unc);
    t.flag("wants_outside_range", wants_outside);
  }
  t.text("beaten_outside_range_by", beaten);
  return t.dict();
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
py::dict diagnosis_numbers(const validation::DiagnosisResult& x) {
  py::dict r;
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
  py::list fit;
  if (const auto* b = x.best())
    for (std::size_t i = 0; i < b->effects.size(); ++i)
      fit.append(strength(b->effects[i], b->parameters[i], b->estimate[i], b->uncertainty[i], true));
  r["best_fit"] = fit;
  r["ranking"] = ranking_table(x.singles, false);
  r["pairs"] = ranking_table(x.pairs, true);
  r["verdict"] = x.verdict;
  r["evidence"] = x.evidence;
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
  Table p;
  std::vector<std::string> pm, pq, pd;
  std::vector<long long> pn;
  std::vector<double> mean, rms, corr;
  std::vector<bool> notable;
  for (const auto& q : x.patterns) {
    pm.push_back(q.model), pq.push_back(q.quantity), pd.push_back(q.driver), pn.push_back(q.n);
    mean.push_back(q.mean_normalised), rms.push_back(q.rms_normalised), corr.push_back(q.correlation);
    notable.push_back(q.notable);
  }
  p.text("model", pm), p.text("quantity", pq), p.text("driver", pd), p.whole("n", pn);
  p.real("mean_normalised", mean), p.real("rms_normalised", rms), p.real("correlation", corr);
  p.flag("notable", notable);
  r["patterns"] = p.dict();
  r["markdown"] = validation::diagnosis_markdown(x);
  return r;
}

// What validate() keeps: the library's result (for the tables, and the report when asked) and the
// inputs it read (which write_report never overwrites).
struct Validated {
  api::ValidateResult result;
  std::vector<std::filesystem::path> inputs;
};

py::dict validation_numbers(const Validated& v) {
  const api::ValidateResult& res = v.result;
  const validation::ValidationResult& result = res.final_result();
  // The acceptance judges the models as delivered unless accept_with_effects (api/validate.h).
  const validation::ValidationResult& judged = res.accepted();
  const validation::ValidationResult* beside = res.beside_acceptance();
  const validation::Tolerances* tol = res.tolerances ? &*res.tolerances : nullptr;
  py::dict r;
  r["predictions"] = predictions_table(result);
  r["errors"] = errors_table(result, tol);
  r["summary"] = summary_table(result);
  r["models"] = result.models;
  py::list fx;
  for (const auto& e : res.effects) fx.append(strength(e.name, e.parameter, e.value, e.uncertainty, e.fitted));
  r["effects"] = fx;
  r["notes"] = res.notes;
  r["brief"] = result.brief(&result == &judged);
  r["acceptance_checked"] = judged.acceptance_checked;
  r["acceptance_failed"] = judged.acceptance_failed;
  r["acceptance_problems"] = judged.acceptance_problems;
  r["accepted_with_effects"] = res.accepted_with_effects && res.with_effects;
  r["outside_tolerance_beside"] =
      beside && beside->acceptance_checked ? py::object(py::int_(beside->failed_count())) : py::object(py::none());
  r["combined_rms_normalised_error"] = or_nan(result.combined_rms_normalised());
  py::dict overall;
  for (const auto& m : result.models) overall[py::str(m)] = or_nan(result.overall_rms_normalised(m));
  r["rms_normalised_error"] = overall;
  r["diagnosis"] = res.diagnosis ? py::object(diagnosis_numbers(*res.diagnosis)) : py::object(py::none());
  return r;
}

std::unique_ptr<Validated> validate(const validation::Dataset& d, const std::vector<std::string>& model_names,
                                    const std::vector<std::string>& effect_args, const std::string& tolerances,
                                    bool diagnose, bool accept_with_effects, const std::string& dem_quality, std::optional<int> dem_threads,
                                    const std::string& dem_cache, bool no_dem_cache) {
  api::ValidateOptions o;
  o.models = model_names;
  o.effects = effect_args;
  o.tolerances = tolerances;
  o.diagnose = diagnose;
  o.accept_with_effects = accept_with_effects;
  o.dem = dem_options(dem_quality, dem_threads, dem_cache, no_dem_cache);
  std::vector<std::filesystem::path> inputs;
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    inputs = plan.inputs;
    return {};
  };
  return interruptible([&] { return std::make_unique<Validated>(Validated{api::validate(d, o), std::move(inputs)}); });
}

struct Diagnosed {
  api::DiagnoseResult result;
  std::vector<std::filesystem::path> inputs;
};

py::dict diagnosed_numbers(const Diagnosed& diagnosed) {
  py::dict r = diagnosis_numbers(diagnosed.result.diagnosis);
  const auto& sc = diagnosed.result.self_check;
  if (sc) {
    py::dict c;
    c["null_replicas"] = sc->null_replicas, c["false_alarms"] = sc->false_alarms;
    c["false_alarm_rate"] = sc->false_alarm_rate(), c["false_alarm_upper"] = sc->false_alarm_upper;
    c["truth"] = sc->truth, c["truth_strength"] = sc->truth_strength;
    c["effect_replicas"] = sc->effect_replicas, c["named"] = sc->named, c["named_other"] = sc->named_other;
    c["covered"] = sc->covered, c["power"] = sc->power(), c["coverage"] = sc->coverage();
    c["markdown"] = validation::self_check_markdown(*sc, diagnosed.result.alpha);
    r["self_check"] = c;
  } else {
    r["self_check"] = py::none();
  }
  return r;
}

std::unique_ptr<Diagnosed> diagnose(const validation::Dataset& d, const std::vector<std::string>& model_names,
                                    double alpha, bool pairs, const std::string& dem_quality,
                                    std::optional<int> dem_threads, const std::string& dem_cache, bool no_dem_cache,
                                    const py::object& self_check_arg, const py::object& seed_arg,
                                    const std::vector<std::string>& corrected) {
  api::DiagnoseOptions o;
  o.inputs = corrected;
  o.self_check = static_cast<int>(whole_number(self_check_arg, options::rules::self_check));
  const double seed_checked = whole_number(seed_arg, options::rules::seed);
  o.seed = py::isinstance<py::float_>(seed_arg)
               ? static_cast<std::uint64_t>(seed_checked)
               : py::reinterpret_steal<py::int_>(PyNumber_Index(seed_arg.ptr())).cast<std::uint64_t>();
  o.models = model_names;
  o.alpha = alpha;
  o.pairs = pairs;
  o.dem = dem_options(dem_quality, dem_threads, dem_cache, no_dem_cache);
  std::vector<std::filesystem::path> inputs;
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    inputs = plan.inputs;
    return {};
  };
  return interruptible([&] { return std::make_unique<Diagnosed>(Diagnosed{api::diagnose(d, o), std::move(inputs)}); });
}

// Writes a result's files into `out` as the command line's --out does: all or nothing, never onto
// a file the run read.
void write_files(const std::vector<api::OutputFile>& files, const std::vector<std::filesystem::path>& inputs,
                 const std::filesystem::path& out, const char* command) {
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  py::gil_scoped_release free;
  api::write_files(out, files, inputs, command);
}

// estimate(): the library's result, kept for its views.
// estimate()'s keywords as the api takes them; sweep() takes the same (SweepOptions is an
// EstimateOptions with the swept input).
api::EstimateOptions estimate_options(std::optional<double> belt_speed, std::optional<double> mass_flow,
                                      std::optional<double> plate_distance, std::optional<double> plate_top,
                                      std::optional<double> stream_thickness, std::optional<double> pulley_diameter,
                                      std::optional<double> belt_width, std::optional<double> bulk_density,
                                      const std::string& dataset, const std::string& setup, const std::string& condition,
                                      const std::vector<std::string>& effect_args, const std::string& default_dataset,
                                      const validation::Dataset* dataset_read) {
  api::EstimateOptions in;
  in.dataset = dataset;
  in.dataset_read = dataset_read;
  in.setup = setup;
  in.condition = condition;
  in.default_dataset = default_dataset;
  in.belt_speed = belt_speed;
  in.mass_flow = mass_flow;
  in.plate_distance = plate_distance;
  in.plate_top = plate_top;
  in.stream_thickness = stream_thickness;
  in.pulley_diameter = pulley_diameter;
  in.belt_width = belt_width;
  in.bulk_density = bulk_density;
  in.effects = effect_args;
  return in;
}

struct Estimated {
  api::EstimateResult result;
};

py::dict estimate_values(const Estimated& e) {
  py::dict r;
  for (const auto& [n, v] : api::estimate_scalars(e.result.analysis)) r[py::str(n)] = v;
  return r;
}

py::dict estimate_models(const Estimated& e) {
  std::vector<std::string> model, quantity;
  std::vector<double> value;
  for (const auto& [m, vals] : e.result.models)
    for (Quantity q : kAllQuantities)
      if (vals[q]) {
        model.push_back(m), quantity.emplace_back(name(q));
        value.push_back(*vals[q] * info(q).to_boundary);
      }
  Table t;
  t.text("model", model), t.text("quantity", quantity), t.real("value", value);
  return t.dict();
}

// The streamlines as drawn (the same points as estimate's JSON, CSV and DXF), mm.
py::dict estimate_paths(const Estimated& e) {
  py::dict r;
  for (analytical::Streamline s : analytical::kAllStreamlines) {
    const auto pts = e.result.path(s);
    py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t{2}});
    auto m = a.mutable_unchecked<2>();
    for (std::size_t k = 0; k < pts.size(); ++k) {
      m(static_cast<py::ssize_t>(k), 0) = pts[k].x() * 1e3;
      m(static_cast<py::ssize_t>(k), 1) = pts[k].y() * 1e3;
    }
    r[py::str(std::string(name(s)))] = a;
  }
  return r;
}

// Each streamline's flight from its release to the plate line (1 s when it never gets there) at
// `points` equal time steps: the model's own trajectory (closed form, or RK4 with a flight force).
py::dict estimate_flight(const Estimated& e, int points) {
  std::vector<std::string> line;
  std::vector<double> t, x, y, vx, vy;
  for (analytical::Streamline s : analytical::kAllStreamlines) {
    const auto& l = e.result.analysis.line(s);
    const double t_end = l.hit ? l.hit->point.t : 1.0;
    for (const auto& f : l.trajectory.sample(t_end, points - 1)) {
      line.emplace_back(name(s));
      t.push_back(f.t), x.push_back(f.position.x() * 1e3), y.push_back(f.position.y() * 1e3);
      vx.push_back(f.velocity.x()), vy.push_back(f.velocity.y());
    }
  }
  Table tb;
  tb.text("streamline", line), tb.real("t_s", t), tb.real("x_mm", x), tb.real("y_mm", y);
  tb.real("vx_mps", vx), tb.real("vy_mps", vy);
  return tb.dict();
}

// The synthetic dataset: written to `out` and read back from there, or without `out` made in memory
// from its files (it has no folder).
validation::Dataset synthesize(const validation::Dataset& source, const std::vector<std::string>& effect_args,
                               const py::object& seed_arg, double noise_scale, const std::filesystem::path& out) {
  api::SynthesizeOptions o;
  const double seed_checked = whole_number(seed_arg, options::rules::seed);
  o.seed = py::isinstance<py::float_>(seed_arg)
               ? static_cast<std::uint64_t>(seed_checked)
               : py::reinterpret_steal<py::int_>(PyNumber_Index(seed_arg.ptr())).cast<std::uint64_t>();
  o.noise_scale = noise_scale;
  o.effects = effect_args;
  api::check(o);
  // The same refusal as the command line's before any work: out may not be the source.
  if (!out.empty())
    o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
      OutputFolder check(out, plan.inputs, "synthesize");
      return {};
    };
  const api::SynthesizeResult r = interruptible([&] { return api::synthesize(source, o); });
  py::gil_scoped_release free;
  if (!out.empty()) {
    api::write_dataset(out, r.files, source.dir, "synthesize");
    return validation::read_dataset(out);
  }
  validation::DatasetTexts files;
  for (const auto& [name, text] : r.files)
    if (name.ends_with(".csv") || name.ends_with(".toml")) files[name] = {name, text};
  return api::read_dataset(files, {}, true);
}

// A dataset's files as Python keeps them: {name: (shown, text, unread)}.
py::dict dataset_sources(const validation::Dataset& d) {
  py::dict out;
  if (d.sources)
    for (const auto& [name, f] : *d.sources) out[py::str(name)] = py::make_tuple(f.shown, py::bytes(f.text), f.unread);
  return out;
}

validation::Dataset dataset_from_sources(const py::dict& files, const std::string& dir, bool measurements_required) {
  validation::DatasetTexts texts;
  for (const auto& [name, entry] : files) {
    const auto t = entry.cast<py::tuple>();
    texts[name.cast<std::string>()] = {t[0].cast<std::string>(), t[1].cast<std::string>(), t[2].cast<bool>()};
  }
  py::gil_scoped_release free;
  return api::read_dataset(texts, dir, measurements_required);
}

// A CSV text's header and rows of cells, as chutelab's reader splits them (quotes, the writer's
// apostrophe before a formula character, trimmed edges).
py::tuple csv_cells(const std::string& text, const std::string& file) {
  const validation::CsvTable t = validation::CsvTable::parse(text, file);
  py::list rows;
  for (const auto& r : t.rows()) rows.append(py::cast(r.cells));
  return py::make_tuple(py::cast(t.header()), rows);
}

// A CSV text from a header and rows of cells: a str as a text cell, a number as the shortest
// decimal that reads back as the same double (NaN or None: an empty cell), as chutelab writes CSV.
std::string csv_text(const std::vector<std::string>& header, const py::list& rows) {
  auto line = [](const auto& cells, auto cell) {
    std::string o;
    bool first = true;
    for (const auto& c : cells) {
      if (!first) o += ',';
      first = false;
      o += cell(c);
    }
    return o + "\n";
  };
  std::string out = line(header, [](const std::string& h) { return csv_field(h); });
  for (const auto& row : rows)
    out += line(row.cast<py::list>(), [](const py::handle& c) -> std::string {
      if (c.is_none()) return {};
      if (py::isinstance<py::str>(c)) return csv_field(c.cast<std::string>());
      if (py::isinstance<py::bool_>(c)) return c.cast<bool>() ? "1" : "0";
      return csv_number(c.cast<double>());
    });
  return out;
}

void import_logs(const std::filesystem::path& dataset, const std::filesystem::path& out) {
  api::ImportLogsOptions o;
  o.dataset = dataset;
  api::check(o);
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    OutputFolder check(out, plan.inputs, "import-logs");
    return {};
  };
  py::gil_scoped_release free;
  const api::ImportLogsResult r = api::import_logs(o);
  api::write_dataset(out, r.files(), r.dataset.dir, "import-logs");
}

void synthesize_logs(const std::filesystem::path& dataset, const std::filesystem::path& truth,
                     const std::filesystem::path& sensor, const std::filesystem::path& dem_series,
                     const py::object& seed_arg, const std::filesystem::path& out) {
  api::SynthesizeLogsOptions o;
  const double seed_checked = whole_number(seed_arg, options::rules::seed);
  o.seed = py::isinstance<py::float_>(seed_arg)
               ? static_cast<std::uint64_t>(seed_checked)
               : py::reinterpret_steal<py::int_>(PyNumber_Index(seed_arg.ptr())).cast<std::uint64_t>();
  o.dataset = dataset;
  o.truth = truth;
  o.sensor = sensor;
  o.dem_series = dem_series;
  api::check(o);
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    OutputFolder check(out, plan.inputs, "synthesize-logs");
    return {};
  };
  py::gil_scoped_release free;
  const api::SynthesizeLogsResult r = api::synthesize_logs(o);
  api::write_dataset(out, r.files, r.source.dir, "synthesize-logs");
}

// calibrate(): the library's result and what it read (the folder written to may not be among them).
struct Calibrated {
  api::CalibrateResult result;
  std::vector<std::filesystem::path> inputs;
};

// Table 3 a row (calibration.csv's columns, the doubles themselves) and the incline's onsets.
py::dict calibrated_numbers(const Calibrated& c) {
  const dem::rigs::CalibrationStudy& s = c.result.study;
  std::vector<std::string> shape, grain;
  std::vector<double> rolling, density, bulk, pile, repose, distance, seconds;
  std::vector<long long> particles;
  std::vector<bool> settled, closest;
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const auto& r = s.rows[k];
    shape.emplace_back(dem::rigs::name(r.shape)), grain.push_back(studies::grain_label(s, r.shape));
    rolling.push_back(r.rolling_friction), density.push_back(r.solid_density);
    bulk.push_back(r.slump.bulk_density), pile.push_back(r.slump.pile_height * 1e3);
    repose.push_back(r.slump.repose_angle_deg), distance.push_back(r.distance), seconds.push_back(r.slump.wall_seconds);
    particles.push_back(static_cast<long long>(r.slump.particles)), settled.push_back(r.slump.settled);
    closest.push_back(static_cast<int>(k) == s.closest);
  }
  Table rows;
  rows.text("shape", shape), rows.text("grain", grain), rows.real("rolling_friction", rolling);
  rows.real("solid_density_kgm3", density), rows.real("bulk_density_kgm3", bulk), rows.real("pile_height_mm", pile);
  rows.real("repose_angle_deg", repose), rows.whole("particles", particles), rows.flag("settled", settled);
  rows.real("run_seconds", seconds), rows.real("target_distance", distance), rows.flag("closest", closest);
  std::vector<double> i_rolling, wall, onset, eq10;
  std::vector<std::string> motion, eq10_motion;
  for (const auto& r : s.incline) {
    i_rolling.push_back(r.rolling_friction), wall.push_back(r.wall_friction);
    onset.push_back(r.result.onset_deg), eq10.push_back(r.result.predicted.onset_deg);
    motion.emplace_back(dem::rigs::name(r.result.motion)), eq10_motion.emplace_back(dem::rigs::name(r.result.predicted.motion));
  }
  Table incline;
  incline.real("rolling_friction", i_rolling), incline.real("wall_friction", wall), incline.real("onset_deg", onset);
  incline.text("motion", motion), incline.real("eq10_onset_deg", eq10), incline.text("eq10_motion", eq10_motion);
  py::dict r;
  r["rows"] = rows.dict();
  r["incline"] = incline.dict();
  r["closest"] = s.closest >= 0 ? py::cast(s.closest) : py::none();
  r["findings"] = studies::calibration_findings(s);
  r["table3"] = c.result.table3();
  for (const auto& [name, text] : c.result.files())
    if (name == "material.toml") r["material_toml"] = text;
  return r;
}

// sensitivity(): the library's result and what it read.
struct Sensitized {
  api::SensitivityResult result;
  std::vector<std::filesystem::path> inputs;
};

// Table 6 a row (sensitivity.csv's numbers, SI at the boundary: N, %, s, mm) and the verdict.
py::dict sensitivity_numbers(const Sensitized& s) {
  const studies::SensitivityStudy& st = s.result.study;
  std::vector<std::string> key, label, group;
  std::vector<double> d, rn, rn_se, rs, rs_se, r, r_se, sd_r, change, change_se, dt, seconds;
  std::vector<long long> particles;
  std::vector<bool> steady;
  for (const auto& row : st.rows) {
    const auto& o = row.outcome;
    key.push_back(row.variant.key), label.push_back(row.variant.label), group.emplace_back(studies::name(row.variant.group));
    d.push_back(o.diameter * 1e3), rn.push_back(o.normal.value), rn_se.push_back(o.normal.se);
    rs.push_back(o.shear.value), rs_se.push_back(o.shear.se), r.push_back(o.resultant.value), r_se.push_back(o.resultant.se);
    sd_r.push_back(o.fluct_resultant), change.push_back(row.change.value), change_se.push_back(row.change.se);
    dt.push_back(o.dt), seconds.push_back(o.wall_seconds), particles.push_back(static_cast<long long>(o.particles));
    steady.push_back(o.steady);
  }
  Table t;
  t.text("variant", key), t.text("label", label), t.text("group", group), t.real(studies::variant_columns().diameter, d);
  t.real("normal_force_N", rn), t.real("normal_force_se_N", rn_se), t.real("shear_force_N", rs);
  t.real("shear_force_se_N", rs_se), t.real("resultant_force_N", r), t.real("resultant_force_se_N", r_se);
  t.real("resultant_force_sd_N", sd_r), t.real("change_percent", change), t.real("change_se_percent", change_se);
  t.real("dt_s", dt), t.whole("particles", particles), t.flag("steady", steady), t.real("run_seconds", seconds);
  py::dict out;
  out["rows"] = t.dict();
  out["verdict"] = st.verdict.text;
  out["reproduced"] = st.verdict.reproduced();
  out["complete"] = st.verdict.complete();
  out["notes"] = studies::run_notes(st);
  return out;
}

// estimate's sweep: one row a value, the columns of its CSV as numbers (NaN where a point has no
// answer), the note as text.
struct Swept {
  api::SweepResult result;
};

py::dict sweep_rows(const Swept& w) {
  const api::SweepResult& res = w.result;
  std::vector<std::string> scalar_cols;
  std::vector<std::pair<std::string, Quantity>> model_cols;
  for (const auto& r : res.rows) {
    if (!r.point) continue;
    for (const auto& [n, v] : api::estimate_scalars(r.point->analysis))
      if (n != res.spec.column && std::find(scalar_cols.begin(), scalar_cols.end(), n) == scalar_cols.end())
        scalar_cols.push_back(n);
    for (const auto& [m, vals] : r.point->models)
      for (Quantity q : kAllQuantities)
        if (vals[q] && std::find(model_cols.begin(), model_cols.end(), std::pair{m, q}) == model_cols.end())
          model_cols.emplace_back(m, q);
  }
  std::vector<double> value;
  std::vector<std::vector<double>> scalars(scalar_cols.size()), models(model_cols.size());
  std::vector<std::string> note;
  for (const auto& r : res.rows) {
    value.push_back(r.value);
    note.push_back(said_text(r.note, python_mention));
    const std::vector<std::pair<std::string, double>> sc =
        r.point ? api::estimate_scalars(r.point->analysis) : std::vector<std::pair<std::string, double>>{};
    for (std::size_t c = 0; c < scalar_cols.size(); ++c) {
      double v = kNan;
      for (const auto& [n, x] : sc)
        if (n == scalar_cols[c]) v = x;
      scalars[c].push_back(v);
    }
    for (std::size_t c = 0; c < model_cols.size(); ++c) {
      double v = kNan;
      if (r.point)
        for (const auto& [m, vals] : r.point->models)
          if (m == model_cols[c].first && vals[model_cols[c].second])
            v = *vals[model_cols[c].second] * info(model_cols[c].second).to_boundary;
      models[c].push_back(v);
    }
  }
  Table t;
  t.real(res.spec.column, value);
  for (std::size_t c = 0; c < scalar_cols.size(); ++c) t.real(scalar_cols[c], scalars[c]);
  for (std::size_t c = 0; c < model_cols.size(); ++c)
    t.real(fmt::format("{}_{}", model_cols[c].first, name(model_cols[c].second)), models[c]);
  t.text("note", note);
  return t.dict();
}

}  // namespace

PYBIND11_MODULE(_chutelab, m) {
  m.doc() = "chutelab's C++ core (use the chutelab package, not this module)";
  // Progress lines name other inputs as they are typed here, as errors do (set once, before any thread).
  progress::set_mention_names(python_mention);

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

  m.attr("source_datasets") = std::string(CHUTELAB_DATASETS_DIR);

  py::class_<Estimated>(m, "Estimated")
      .def("json", [](const Estimated& e) { return e.result.json(); })
      .def("values", &estimate_values)
      .def("models", &estimate_models)
      .def("effects",
           [](const Estimated& e) {
             py::dict d;
             for (const auto& s : e.result.settings)
               if (s.value) d[py::str(s.info->name)] = *s.value;
             return d;
           })
      .def("paths", &estimate_paths)
      .def("flight", &estimate_flight, py::arg("points"));

  m.def(
      "estimate",
      [](std::optional<double> belt_speed, std::optional<double> mass_flow, std::optional<double> plate_distance,
         std::optional<double> plate_top, std::optional<double> stream_thickness, std::optional<double> pulley_diameter,
         std::optional<double> belt_width, std::optional<double> bulk_density, const std::string& dataset,
         const std::string& setup, const std::string& condition, const std::vector<std::string>& effect_args,
         const std::string& default_dataset, const validation::Dataset* dataset_read) {
        const api::EstimateOptions in =
            estimate_options(belt_speed, mass_flow, plate_distance, plate_top, stream_thickness, pulley_diameter,
                             belt_width, bulk_density, dataset, setup, condition, effect_args, default_dataset, dataset_read);
        return std::make_unique<Estimated>(Estimated{api::estimate(in)});
      },
      py::arg("belt_speed"), py::arg("mass_flow"), py::arg("plate_distance"), py::arg("plate_top"),
      py::arg("stream_thickness"), py::arg("pulley_diameter"), py::arg("belt_width"), py::arg("bulk_density"),
      py::arg("dataset"), py::arg("setup"), py::arg("condition"),
      py::arg("effects"), py::arg("default_dataset"), py::arg("dataset_read") = nullptr);

  py::class_<Swept>(m, "Swept")
      .def("rows", &sweep_rows)
      .def("column", [](const Swept& w) { return w.result.spec.column; })
      .def("table", [](const Swept& w) { return w.result.table(python_mention); })
      .def("csv", [](const Swept& w) { return w.result.csv(python_mention); })
      .def("json", [](const Swept& w) { return w.result.json(python_mention); })
      .def("svg", [](const Swept& w) { return w.result.svg(python_mention); });
  m.def(
      "sweep",
      [](const std::string& sweep, std::optional<double> belt_speed, std::optional<double> mass_flow,
         std::optional<double> plate_distance, std::optional<double> plate_top, std::optional<double> stream_thickness,
         std::optional<double> pulley_diameter, std::optional<double> belt_width, std::optional<double> bulk_density,
         const std::string& dataset, const std::string& setup, const std::string& condition,
         const std::vector<std::string>& effect_args, const std::string& default_dataset,
         const validation::Dataset* dataset_read) {
        api::SweepOptions in;
        static_cast<api::EstimateOptions&>(in) =
            estimate_options(belt_speed, mass_flow, plate_distance, plate_top, stream_thickness, pulley_diameter,
                             belt_width, bulk_density, dataset, setup, condition, effect_args, default_dataset, dataset_read);
        in.sweep = sweep;
        return std::make_unique<Swept>(Swept{api::sweep(in)});
      },
      py::arg("sweep"), py::arg("belt_speed"), py::arg("mass_flow"), py::arg("plate_distance"), py::arg("plate_top"),
      py::arg("stream_thickness"), py::arg("pulley_diameter"), py::arg("belt_width"), py::arg("bulk_density"),
      py::arg("dataset"), py::arg("setup"), py::arg("condition"), py::arg("effects"), py::arg("default_dataset"),
      py::arg("dataset_read") = nullptr);

  py::class_<validation::Dataset>(m, "Dataset")
      .def_property_readonly("dir", [](const validation::Dataset& d) { return d.dir.string(); })
      .def_property_readonly("name", [](const validation::Dataset& d) { return d.setup.name; })
      .def_property_readonly("setup", [](const validation::Dataset& d) { return setup_dict(d.setup); })
      .def("sources", &dataset_sources)
      .def("conditions", &conditions_table)
      .def("measurements", &measurements_table)
      .def("trajectory", &trajectory_table);

  m.def(
      "read_dataset",
      [](const std::filesystem::path& dir, bool measurements_required) {
        // A dataset of logs reads its logs into means (logs/dataset_logs.h).
        return api::read_dataset(dir, measurements_required);
      },
      py::arg("dir"), py::arg("measurements_required"));

  py::class_<Validated>(m, "Validated")
      .def("numbers", &validation_numbers)
      .def("write", [](const Validated& v, const std::filesystem::path& out) {
        write_files(v.result.files(), v.inputs, out, "validate");
      });
  py::class_<Diagnosed>(m, "Diagnosed")
      .def("numbers", &diagnosed_numbers)
      .def("write", [](const Diagnosed& d, const std::filesystem::path& out) {
        write_files(d.result.files(), d.inputs, out, "diagnose");
      });

  m.def("validate", &validate, py::arg("dataset"), py::arg("models"), py::arg("effects"), py::arg("tolerances"),
        py::arg("diagnose"), py::arg("accept_with_effects"), py::arg("dem_quality"), py::arg("dem_threads"), py::arg("dem_cache"),
        py::arg("no_dem_cache"));
  m.def("diagnose", &diagnose, py::arg("dataset"), py::arg("models"), py::arg("alpha"), py::arg("pairs"),
        py::arg("dem_quality"), py::arg("dem_threads"), py::arg("dem_cache"), py::arg("no_dem_cache"),
        py::arg("self_check"), py::arg("seed"), py::arg("inputs"));
  m.def("synthesize", &synthesize, py::arg("source"), py::arg("effects"), py::arg("seed"),
        py::arg("noise_scale"), py::arg("out"));
  m.def("import_logs", &import_logs, py::arg("dataset"), py::arg("out"));

  py::class_<Calibrated>(m, "Calibrated")
      .def("numbers", &calibrated_numbers)
      .def("write", [](const Calibrated& c, const std::filesystem::path& out) {
        write_files(c.result.files(), c.inputs, out, "calibrate");
      });
  m.def(
      "calibrate",
      [](const std::filesystem::path& dataset, const std::string& quality, const std::vector<double>& rolling,
         const std::vector<double>& density, const std::vector<std::string>& shapes, double sphere_diameter_mm,
         double clump_diameter_mm, bool target, std::optional<double> target_bulk_density,
         std::optional<double> target_pile_height_mm, bool incline, int threads, const py::object& seed, int jobs) {
        api::CalibrateOptions o;
        o.dataset = dataset;
        o.quality = quality;
        o.rolling = rolling;
        o.density = density;
        o.shapes = shapes;
        o.sphere_diameter_mm = sphere_diameter_mm;
        o.clump_diameter_mm = clump_diameter_mm;
        o.target = target;
        o.target_bulk_density = target_bulk_density;
        o.target_pile_height_mm = target_pile_height_mm;
        o.incline = incline;
        o.threads = threads;
        o.seed = seed_value(seed);
        o.jobs = jobs;
        std::vector<std::filesystem::path> inputs;
        o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
          inputs = plan.inputs;
          return {};
        };
        return interruptible([&] { return std::make_unique<Calibrated>(Calibrated{api::calibrate(o), std::move(inputs)}); });
      },
      py::arg("dataset"), py::arg("quality"), py::arg("rolling"), py::arg("density"), py::arg("shapes"),
      py::arg("sphere_diameter_mm"), py::arg("clump_diameter_mm"), py::arg("target"), py::arg("target_bulk_density"),
      py::arg("target_pile_height_mm"), py::arg("incline"), py::arg("threads"), py::arg("seed"), py::arg("jobs"));

  py::class_<Sensitized>(m, "Sensitized")
      .def("numbers", &sensitivity_numbers)
      .def("write", [](const Sensitized& s, const std::filesystem::path& out) {
        write_files(s.result.files(), s.inputs, out, "sensitivity");
      });
  m.def(
      "sensitivity",
      [](const std::filesystem::path& dataset, const std::string& condition, const std::string& quality,
         const std::vector<std::string>& only, const std::vector<double>& sizes_mm, std::optional<int> threads,
         const py::object& seed, double limit, int jobs) {
        api::SensitivityOptions o;
        o.dataset = dataset;
        o.condition = condition;
        o.quality = quality;
        o.only = only;
        o.sizes_mm = sizes_mm;
        o.threads = threads;
        if (!seed.is_none()) o.seed = seed_value(seed);
        o.limit = limit;
        o.jobs = jobs;
        std::vector<std::filesystem::path> inputs;
        o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
          inputs = plan.inputs;
          return {};
        };
        return interruptible([&] { return std::make_unique<Sensitized>(Sensitized{api::sensitivity(o), std::move(inputs)}); });
      },
      py::arg("dataset"), py::arg("condition"), py::arg("quality"), py::arg("only"), py::arg("sizes_mm"),
      py::arg("threads"), py::arg("seed"), py::arg("limit"), py::arg("jobs"));
  m.def("synthesize_logs", &synthesize_logs, py::arg("dataset"), py::arg("truth"), py::arg("sensor"),
        py::arg("dem_series"), py::arg("seed"), py::arg("out"));
  m.def("dataset_from_sources", &dataset_from_sources, py::arg("files"), py::arg("dir"),
        py::arg("measurements_required"));
  m.def("csv_cells", &csv_cells, py::arg("text"), py::arg("file"));
  m.def("csv_text", &csv_text, py::arg("header"), py::arg("rows"));

  // The quantity vocabulary (core/quantity.h) and the stream boundaries trajectory.csv compares, for
  // axis labels: name (as in the tables), symbol, label, unit.
  m.def("quantities", [] {
    py::list out;
    for (Quantity q : kAllQuantities) {
      const auto& i = info(q);
      out.append(py::make_tuple(std::string(i.name), std::string(i.symbol), std::string(i.label), std::string(i.unit)));
    }
    for (Boundary b : kAllBoundaries) {
      const std::string n(name(b));
      out.append(py::make_tuple(trajectory_quantity(b), "y_" + n, "height of the stream's " + n + " line at x", "mm"));
    }
    return out;
  });

  m.def("model_names", &validation::model_names);
  m.def("effect_library", [] {
    py::list out;
    for (const auto& e : api::effect_library()) {
      py::dict d;
      d["effect"] = e.name;
      d["parameter"] = e.parameter;
      d["unit"] = e.unit;
      d["stage"] = e.stage;
      d["kind"] = e.record ? "record" : "physics";
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
