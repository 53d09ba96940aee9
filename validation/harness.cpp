#include "validation/harness.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <map>
#include <set>
#include <span>
#include <unordered_map>

#include "core/input_error.h"
#include "core/progress.h"
#include "core/message.h"
#include "core/number.h"
#include "validation/input_uncertainty.h"
#include "validation/campaign_runs.h"
#include "validation/models/external_model.h"

namespace chutelab::validation {
namespace {

// "datasets/hidden-effect/" -> "hidden-effect": the name the user typed, for titles.
std::string folder_name(const std::filesystem::path& dir) {
  if (dir.empty()) return {};  // a dataset in memory: titles say its setup's name
  std::filesystem::path p = dir.lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  if (p.empty() || p == ".") p = std::filesystem::absolute(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().string();
}

}  // namespace

namespace {
// A metric that cannot be computed (0/0, x/0, x/1e-320 = inf, a NaN from a model) is no number:
// it is left out of sums and maxima, and a limit on it fails (check_tolerance).
std::optional<double> finite(double v) { return std::isfinite(v) ? std::optional(v) : std::nullopt; }
}  // namespace

bool is_height(std::string_view quantity) {
  return parse_quantity(quantity) == Quantity::impact_point_y || quantity.starts_with("trajectory_");
}

std::optional<double> Comparison::relative_error() const {
  if (!predicted || measured == 0.0) return std::nullopt;
  return finite(error() / std::abs(measured));
}

std::optional<double> Comparison::normalised_error() const {
  const auto u = validation_uncertainty();
  if (!u || !(*u > 0.0)) return std::nullopt;
  return finite(error() / *u);
}

std::string Comparison::unit() const {
  if (q) return std::string(info(*q).unit);
  if (boundary) return "mm";
  return quantity.substr(quantity.rfind('_') + 1);  // plate map: "plate_pressure_Pa" -> "Pa"
}

std::optional<double> Comparison::validation_uncertainty() const {
  if (!predicted || (!uncertainty && !prediction_uncertainty && !u_num_disc && !u_input)) return std::nullopt;
  double sum = 0.0;
  for (const auto& u : {uncertainty, prediction_uncertainty, u_num_disc, u_input}) sum += std::pow(u.value_or(0.0), 2);
  return finite(std::sqrt(sum));
}

std::optional<double> Comparison::vv20_ratio() const {
  const auto z = normalised_error();
  if (!z) return std::nullopt;
  return std::abs(*z);
}

const ConditionResult* ValidationResult::prediction(const std::string& condition,
                                                    const std::string& model) const {
  for (const auto& p : predictions)
    if (p.condition == condition && p.model == model) return &p;
  return nullptr;
}

std::optional<double> ValidationResult::overall_rms_normalised(const std::string& model) const {
  double sum = 0.0;
  int n = 0;
  for (const auto& c : comparisons)
    if (c.model == model)
      if (auto z = c.normalised_error()) {
        sum += *z * *z;
        ++n;
      }
  if (n == 0) return std::nullopt;
  return std::sqrt(sum / n);
}

std::optional<double> ValidationResult::combined_rms_normalised() const {
  const auto order = model_names();
  auto rank = [&](const std::string& m) {
    return static_cast<std::size_t>(std::find(order.begin(), order.end(), m) - order.begin());
  };
  std::map<std::tuple<std::string, std::string, double>, const Comparison*> chosen;
  for (const auto& c : comparisons) {
    if (!c.normalised_error()) continue;
    auto& slot = chosen[{c.condition, c.quantity, c.x}];
    if (!slot || rank(c.model) < rank(slot->model)) slot = &c;
  }
  if (chosen.empty()) return std::nullopt;
  double sum = 0.0;
  for (const auto& [key, c] : chosen) sum += std::pow(*c->normalised_error(), 2);
  return std::sqrt(sum / static_cast<double>(chosen.size()));
}

std::string ValidationResult::brief(bool judged) const {
  std::string s = fmt::format("{}: {} conditions x {} model{}", one_line(dataset_folder.empty() ? dataset_name : dataset_folder, 120),
                              predictions.size() / std::max<std::size_t>(1, models.size()),
                              models.size(), models.size() == 1 ? "" : "s");
  std::vector<std::string> rms;
  for (const auto& m : models)
    if (auto z = overall_rms_normalised(m)) rms.push_back(fmt::format("{} {:.2f}", m, *z));
  if (models.size() > 1)
    if (auto z = combined_rms_normalised()) rms.push_back(fmt::format("combined {:.2f}", *z));
  if (!rms.empty()) s += fmt::format("; RMS E/u_val {}", fmt::join(rms, ", "));
  if (acceptance_checked && !judged)
    s += fmt::format("; {} of {} checked values outside tolerance (not judged)", failed_count(), checked_count());
  else if (acceptance_checked)
    s += acceptance_failed ? fmt::format("; ACCEPTANCE FAILED ({} of {} checked values outside tolerance)",
                                         failed_count(), checked_count())
                           : fmt::format("; acceptance passed ({} values checked)", checked_count());
  if (!acceptance_problems.empty() && judged)
    s += fmt::format(" ({}{})", acceptance_problems.front(),
                     acceptance_problems.size() > 1 ? fmt::format("; and {} more", acceptance_problems.size() - 1) : "");
  return s;
}

int ValidationResult::failed_count() const {
  return static_cast<int>(std::count_if(comparisons.begin(), comparisons.end(),
                                        [](const Comparison& c) { return c.verdict.checked && !c.verdict.passed; }));
}

int ValidationResult::checked_count() const {
  return static_cast<int>(
      std::count_if(comparisons.begin(), comparisons.end(), [](const Comparison& c) { return c.verdict.checked; }));
}

std::vector<PlateQuery> plate_queries(const Dataset& d, const std::string& condition) {
  std::vector<PlateQuery> q;
  for (const auto& p : d.plate_map)
    if (p.condition == condition) q.push_back({p.quantity, p.y, p.z});
  return q;
}

std::vector<TrajectoryQuery> trajectory_queries(const Dataset& d, const std::string& condition) {
  std::vector<TrajectoryQuery> q;
  for (const auto& p : d.trajectory)
    if (p.condition == condition) q.push_back({p.boundary, p.x});
  return q;
}

// An instrument effect changes what the rig would have recorded, whichever model predicted. The
// instrument is one: a recorded value may depend on quantities this model does not predict (the
// point of application from moments needs R_n), so each model's values are completed from the
// other models of the same condition, in model order, before the effect acts; only the model's own
// quantities are kept.
void apply_measurement_effects(const analytical::EffectList& effects, std::span<ConditionResult> same) {
  if (effects.empty()) return;
  std::vector<QuantityValues> recorded;
  for (const auto& own : same) {
    QuantityValues v = own.prediction.values;
    for (const auto& other : same)
      for (Quantity q : kAllQuantities)
        if (!v[q] && other.prediction.values[q]) v[q] = other.prediction.values[q];
    for (const auto& e : effects) e->adjust_measurement(v);
    recorded.push_back(v);
  }
  for (std::size_t k = 0; k < same.size(); ++k) {
    for (Quantity q : kAllQuantities)
      if (same[k].prediction.values[q]) same[k].prediction.values[q] = recorded[k][q];
    for (const auto& e : effects) e->adjust_trajectory(same[k].prediction.trajectory);
  }
}

namespace {

// A number as an engineer reads it: 4 significant digits, no exponent in the usual range.
std::string plain(double v) { return message_number(v); }

void check_tolerance(Comparison& c, const Tolerances& tol) {
  const Tolerance* t = tol.find(c.model, c.quantity);
  if (!t || !c.predicted) return;
  c.verdict.checked = true;
  auto fail = [&](std::string kind, double actual, double allowed, std::string why) {
    if (c.verdict.passed) {
      c.verdict.limit = std::move(why);
      c.verdict.kind = std::move(kind);
      c.verdict.actual = actual;
      c.verdict.allowed = allowed;
    }
    c.verdict.passed = false;
  };
  // A limit whose metric cannot be computed is not met: a measured 0 against a relative limit has no
  // relative error, and "within" would be a check that cannot fail.
  if (!std::isfinite(c.measured) || !std::isfinite(*c.predicted))
    fail("", 0.0, 0.0, "value not finite: nothing to compare");
  if (t->relative) {
    if (auto r = c.relative_error(); !r)
      fail("", 0.0, *t->relative,
           c.measured == 0.0 ? "relative error undefined: the measured value is 0 (use an absolute limit)"
                             : "relative error not finite (measured value too close to 0; use an absolute limit)");
    else if (std::abs(*r) > *t->relative)
      fail("relative", std::abs(*r), *t->relative,
           fmt::format("relative error {} % > {} %", plain(100.0 * std::abs(*r)), plain(100.0 * *t->relative)));
  }
  if (t->normalised) {
    // Without a stated uncertainty a normalised limit cannot be met: that is a failure to show,
    // not a pass to assume.
    if (auto z = c.normalised_error(); !z)
      fail("normalised", 0.0, *t->normalised, "no uncertainty, so |E|/u_val cannot be checked");
    else if (std::abs(*z) > *t->normalised)
      fail("normalised", std::abs(*z), *t->normalised,
           fmt::format("|E|/u_val {:.2f} > {}", std::abs(*z), plain(*t->normalised)));
  }
  if (t->absolute) {
    const double e = std::abs(c.error() * c.scale);
    if (!std::isfinite(e)) fail("", 0.0, *t->absolute, "error not finite");
    else if (e > *t->absolute)
      fail("absolute", e, *t->absolute,
           fmt::format("error {} {} > {} {}", plain(e), c.unit(), plain(*t->absolute), c.unit()));
  }
}

// Where each (condition, model)'s prediction is in ValidationResult::predictions.
using PredictionIndex = std::map<std::pair<std::string, std::string>, std::size_t>;

// The expensive models' runs first, as one campaign (spread over MPI ranks or --jobs threads);
// predict_conditions() then finds each one done.
void run_expensive_models(const Dataset& d, const std::vector<ModelPtr>& models, const ValidateOptions& options) {
  std::vector<ModelRun> runs;
  for (std::size_t i = 0; i < d.stations.size(); ++i)
    for (const auto& m : models)
      if (m->expensive())
        runs.push_back({m, d.stations[i], analytical::acting_at(options.effects, d.stations[i]), d.station_lines[i].file, d.station_lines[i].line});
  run_models(runs, {"validate", options.jobs, {}});
}

// Every model's prediction at every condition, into r.predictions, with its input uncertainty and
// the measurement-stage effects applied.
PredictionIndex predict_conditions(const Dataset& d, const std::vector<ModelPtr>& models, const ValidateOptions& options,
                                   ValidationResult& r) {
  // Every look-up below is by index or hash, once per row: validate stays linear in the dataset.
  std::unordered_map<std::string, std::vector<TrajectoryQuery>> queries_of;
  for (const auto& p : d.trajectory) queries_of[p.condition].push_back({p.boundary, p.x});
  std::unordered_map<std::string, std::vector<PlateQuery>> plate_of;
  for (const auto& p : d.plate_map) plate_of[p.condition].push_back({p.quantity, p.y, p.z});
  PredictionIndex prediction_at;
  const bool progress = !options.quiet && d.stations.size() >= 2000;
  for (std::size_t i = 0; i < d.stations.size(); ++i) {
    const Station& st = d.stations[i];
    if (progress && (i + 1) % 1000 == 0)
      progress::line(fmt::format("validate: {}/{} conditions", i + 1, d.stations.size()));
    static const std::vector<TrajectoryQuery> none;
    static const std::vector<PlateQuery> no_plate;
    const auto qit = queries_of.find(st.condition);
    const auto& queries = qit == queries_of.end() ? none : qit->second;
    const auto pit = plate_of.find(st.condition);
    const auto& plate = pit == plate_of.end() ? no_plate : pit->second;
    const std::size_t first = r.predictions.size();
    const analytical::EffectList effects = analytical::acting_at(options.effects, st);
    for (const auto& m : models) {
      ModelPrediction p;
      try {
        PredictRequest req{queries, true};
        req.plate = plate;
        p = m->predict(st, effects, req);
      } catch (const InputError& e) {
        throw e.located(d.station_lines[i].file, d.station_lines[i].line);
      }
      // u_input on the raw prediction: measurement-stage effects act on the record, not the inputs.
      if (i < d.input_uncertainty.size() && !d.input_uncertainty[i].empty()) {
        auto ui = input_uncertainty(*m, st, d.input_uncertainty[i], effects, queries, p);
        p.input_uncertainty = ui.u;
        p.trajectory_input_uncertainty = std::move(ui.trajectory);
        for (auto& n : ui.notes) p.notes.push_back(std::move(n));
      }
      prediction_at[{st.condition, m->name()}] = r.predictions.size();
      r.predictions.push_back({st.condition, m->name(), std::move(p)});
    }
    apply_measurement_effects(effects, std::span(r.predictions).subspan(first, models.size()));
  }
  return prediction_at;
}

// The measured quantities (measurements.csv) against each model.
void compare_measurements(const Dataset& d, const std::vector<ModelPtr>& models, const PredictionIndex& prediction_at,
                          ValidationResult& r) {
  for (const auto& meas : d.measurements)
    for (const auto& m : models) {
      const ConditionResult* cr = &r.predictions[prediction_at.at({meas.condition, m->name()})];
      Comparison c;
      c.condition = meas.condition;
      c.model = m->name();
      c.quantity = std::string(name(meas.quantity));
      c.q = meas.quantity;
      c.scale = info(meas.quantity).to_boundary;
      c.measured = meas.value;
      c.uncertainty = meas.uncertainty;
      c.predicted = cr->prediction.values[meas.quantity];
      c.prediction_uncertainty = cr->prediction.uncertainty[meas.quantity];
      c.u_num_disc = cr->prediction.discretisation[meas.quantity];
      c.u_input = cr->prediction.input_uncertainty[meas.quantity];
      r.comparisons.push_back(std::move(c));
    }
}

// The stream boundaries (trajectory.csv) against each model.
void compare_trajectory(const Dataset& d, const std::vector<ModelPtr>& models, const PredictionIndex& prediction_at,
                        ValidationResult& r) {
  for (const auto& m : models) {
    std::map<std::string, std::size_t> next;  // query index per condition, in dataset order
    for (const auto& pt : d.trajectory) {
      const ConditionResult* cr = &r.predictions[prediction_at.at({pt.condition, m->name()})];
      const std::size_t k = next[pt.condition]++;
      Comparison c;
      c.condition = pt.condition;
      c.model = m->name();
      c.quantity = trajectory_quantity(pt.boundary);
      c.boundary = pt.boundary;
      c.x = pt.x;
      c.scale = 1e3;
      c.measured = pt.y;
      c.uncertainty = pt.uncertainty;
      const ModelPrediction& mp = cr->prediction;
      if (k < mp.trajectory.size()) c.predicted = mp.trajectory[k];
      if (k < mp.trajectory_uncertainty.size()) c.prediction_uncertainty = mp.trajectory_uncertainty[k];
      if (k < mp.trajectory_discretisation.size()) c.u_num_disc = mp.trajectory_discretisation[k];
      if (k < mp.trajectory_input_uncertainty.size()) c.u_input = mp.trajectory_input_uncertainty[k];
      r.comparisons.push_back(std::move(c));
    }
  }
}

// Plate-map points (pressure film, wear surveys), compared like the other measurements.
void compare_plate_map(const Dataset& d, const std::vector<ModelPtr>& models, const PredictionIndex& prediction_at,
                       ValidationResult& r) {
  for (const auto& m : models) {
    std::map<std::string, std::size_t> next;
    for (const auto& pt : d.plate_map) {
      const ConditionResult* cr = &r.predictions[prediction_at.at({pt.condition, m->name()})];
      const std::size_t k = next[pt.condition]++;
      if ( k >= cr->prediction.plate.size() || !cr->prediction.plate[k]) continue;
      Comparison c;
      c.condition = pt.condition;
      c.model = m->name();
      c.quantity = pt.quantity;
      c.plate_y = pt.y;
      c.plate_z = pt.z;
      c.scale = pt.scale;
      c.measured = pt.value;
      c.uncertainty = pt.uncertainty;
      c.predicted = cr->prediction.plate[k];
      if (k < cr->prediction.plate_uncertainty.size()) c.prediction_uncertainty = cr->prediction.plate_uncertainty[k];
      r.comparisons.push_back(std::move(c));
    }
  }
}

// Each comparison against the acceptance limits; a limit that checked nothing is a problem too.
void check_acceptance(const Tolerances& tol, ValidationResult& r) {
  r.acceptance_checked = true;
  std::set<Tolerances::Key> used;
  for (auto& c : r.comparisons) {
    check_tolerance(c, tol);
    if (c.verdict.checked) used.insert(*tol.find_key(c.model, c.quantity));
    if (c.verdict.checked && !c.verdict.passed) r.acceptance_failed = true;
  }
  if (tol.empty())
    r.acceptance_problems.push_back(fmt::format("{}: no limit in the file, so acceptance checked nothing", tol.file()));
  for (const auto& [key, line] : tol.entries())
    if (!used.count(key))
      r.acceptance_problems.push_back(fmt::format(
          "{}:{}: {}.{}: this limit checked no value (no model run here predicts {} for a measured value; the models: {})",
          tol.file(), line, key.first, key.second, key.second, fmt::join(r.models, ", ")));
  if (!r.acceptance_problems.empty()) r.acceptance_failed = true;
}

// Summary per model and quantity, in model order and the vocabulary's order.
void summarise(ValidationResult& r) {
  std::vector<std::string> quantities;
  for (Quantity q : kAllQuantities) quantities.emplace_back(name(q));
  for (Boundary b : kAllBoundaries) quantities.push_back(trajectory_quantity(b));
  for (const auto& [q, scale] : plate_quantities()) quantities.push_back(q);
  std::map<std::pair<std::string, std::string>, std::vector<const Comparison*>> by_key;
  for (const auto& c : r.comparisons) by_key[{c.model, c.quantity}].push_back(&c);
  for (const auto& m : r.models)
    for (const auto& qn : quantities) {
      SummaryRow s;
      s.model = m;
      s.quantity = qn;
      double se = 0.0, sz = 0.0, worst = 0.0;
      int nz = 0, nr = 0, ne = 0;
      bool checked = false, ok = true;
      for (const Comparison* cp : by_key[{m, qn}]) {
        const Comparison& c = *cp;
        if (!c.predicted) continue;
        ++s.n;
        // Summaries over the finite values (a metric that is not one is left out, not propagated).
        if (const double e = c.error() * c.scale; std::isfinite(e * e)) {
          se += e * e;
          ++ne;
        }
        if (auto z = c.normalised_error()) { sz += *z * *z; ++nz; }
        if (auto rel = c.relative_error(); rel && !is_height(qn)) { worst = std::max(worst, std::abs(*rel)); ++nr; }
        if (c.verdict.checked) { checked = true; ok = ok && c.verdict.passed; }
      }
      if (s.n == 0) continue;
      s.rms_error = ne ? std::sqrt(se / ne) : std::nan("");
      if (nz) s.rms_normalised_error = std::sqrt(sz / nz);
      if (nr) s.max_abs_relative_error = worst;
      if (checked) s.within_tolerance = ok;
      r.summary.push_back(s);
    }
}

}  // namespace

ValidationResult validate(const Dataset& d, const std::vector<ModelPtr>& models,
                          const ValidateOptions& options) {
  ValidationResult r;
  r.dataset_folder = folder_name(d.dir);
  r.dataset_name = d.setup.name.empty() ? r.dataset_folder : d.setup.name;
  for (const auto& m : models) r.models.push_back(m->name());
  r.effects = options.effect_labels;

  check_external_models(models, d);  // before anything runs: a bad condition name is bad input
  run_expensive_models(d, models, options);
  const PredictionIndex prediction_at = predict_conditions(d, models, options, r);
  compare_measurements(d, models, prediction_at, r);
  compare_trajectory(d, models, prediction_at, r);
  compare_plate_map(d, models, prediction_at, r);
  if (options.tolerances) check_acceptance(*options.tolerances, r);
  summarise(r);
  return r;
}

}  // namespace chutelab::validation
