#include "validation/synthesize.h"
#include "core/csv_field.h"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <span>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "core/input_error.h"
#include "core/utf8.h"
#include "validation/harness.h"

namespace chutelab::validation {

NormalStream::NormalStream(std::uint64_t seed) : state_(seed ^ 0x9E3779B97F4A7C15ull) {}

double NormalStream::uniform() {
  // splitmix64: a full-period 64-bit generator with a fixed definition.
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;  // in (0, 1)
}

double NormalStream::next() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Box-Muller: two uniforms give two independent standard normals.
  const double r = std::sqrt(-2.0 * std::log(uniform()));
  const double t = 2.0 * 3.14159265358979323846 * uniform();
  spare_ = r * std::sin(t);
  has_spare_ = true;
  return r * std::cos(t);
}

namespace {

// The instrument's one-sigma uncertainty for a reading (or, to draw the noise, for the true value):
// 2 % of a force with a floor of 0.2 N, constants for speeds and the impact point.
double default_uncertainty(Quantity q, double value) {
  switch (q) {
    case Quantity::normal_force:
    case Quantity::shear_force:
    case Quantity::resultant_force: return std::max(0.02 * std::abs(value), 0.2);
    case Quantity::impact_velocity:
    case Quantity::exit_velocity: return 0.04;
    case Quantity::impact_point_y: return 2.5e-3;
    case Quantity::belt_layer_velocity: return 0.04;
    case Quantity::stream_mass_flow: return 0.02 * std::abs(value);
  }
  return 0.0;
}

// Uncertainties are quoted to two significant figures ("0.30", "0.040", "2.5"), as a lab quotes
// them; more digits would only carry the digits of whatever the uncertainty was computed from.
std::string two_significant(double u) {
  if (!(u > 0.0) || !std::isfinite(u)) return "0";
  const double step = std::pow(10.0, std::floor(std::log10(u)) - 1.0);
  const double rounded = std::round(u / step) * step;
  // Decimals from the rounded value, so 0.0996 is written 0.10, not 0.100.
  const int decimals = std::max(0, 1 - static_cast<int>(std::floor(std::log10(rounded))));
  return fmt::format("{:.{}f}", rounded, decimals);
}

// One reading of a value with noise of standard deviation sigma. A magnitude (a speed, R) is read
// by an instrument that never reports it below zero, and the dataset reader refuses it negative,
// so its noise is the normal truncated at -truth: resample until the reading is >= 0. This leaves
// well-measured values alone (a value 4 sigma above zero is resampled with probability 3e-5) and
// keeps every row; a value within about 2 sigma of zero comes out biased upwards, by at most
// 0.8 sigma (the half-normal mean, truth = 0), as a real speed reading near zero is. Omitting such
// rows was rejected: the choice would be made on the noise-free value, so a missing row would
// itself tell the diagnosis that the hidden truth is near zero. Resampling draws from the same
// stream, so the dataset stays a function of the seed.
double reading(Quantity q, double truth, double sigma, NormalStream& noise) {
  if (!info(q).magnitude || sigma <= 0.0) return truth + sigma * noise.next();
  if (truth < 0.0)
    throw std::logic_error(fmt::format("model predicts a negative {} ({})", name(q), truth));
  for (;;)
    if (const double v = truth + sigma * noise.next(); v >= 0.0) return v;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Every model's prediction of one condition with the hidden effects, measurement effects applied:
// each value comes from the first model (in the order given) that predicts it.
std::vector<ConditionResult> truth_of(const Dataset& src, std::size_t i, const Station& st,
                                      const std::vector<ModelPtr>& models, const analytical::EffectList& all,
                                      std::span<const TrajectoryQuery> queries) {
  const analytical::EffectList effects = analytical::acting_at(all, st);
  std::vector<ConditionResult> same;
  try {
    for (const auto& m : models) same.push_back({st.condition, m->name(), m->predict(st, effects, {queries, false})});
  } catch (const InputError& e) {
    if (i < src.station_lines.size()) throw e.located(src.station_lines[i].file, src.station_lines[i].line);
    throw;
  }
  apply_measurement_effects(effects, same);
  return same;
}

std::optional<double> first_value(const std::vector<ConditionResult>& same, Quantity q) {
  for (const auto& s : same)
    if (s.prediction.values[q]) return s.prediction.values[q];
  return std::nullopt;
}

std::optional<double> first_point(const std::vector<ConditionResult>& same, std::size_t k) {
  for (const auto& s : same)
    if (k < s.prediction.trajectory.size() && s.prediction.trajectory[k]) return s.prediction.trajectory[k];
  return std::nullopt;
}

// One measured value as drawn: its reading and the standard deviation its gross error is scaled by.
struct Drawn {
  Quantity q;
  double value = 0.0;  // SI
  double sigma = 0.0;  // SI, the stated size of its noise
};

// Gross reading errors on `count` of the drawn values, from a stream of their own (so the other
// readings stay those of the seed): 8 to 15 stated uncertainties off, either way, never below zero
// for a magnitude. Each value is hit at most once.
void add_outliers(std::vector<Drawn*>& values, int count, std::uint64_t seed) {
  NormalStream pick(seed ^ 0xA5A5A5A5DEADBEEFull);
  for (int k = 0; k < count && !values.empty(); ++k) {
    const auto at = std::min(values.size() - 1, static_cast<std::size_t>(pick.uniform() * values.size()));
    Drawn& d = *values[at];
    const double size = (8.0 + 7.0 * pick.uniform()) * d.sigma;
    const double sign = pick.uniform() < 0.5 ? -1.0 : 1.0;
    d.value += (info(d.q).magnitude && d.value - size < 0.0) ? size : sign * size;
    values.erase(values.begin() + static_cast<std::ptrdiff_t>(at));
  }
}

}  // namespace

std::vector<OutputFile> synthesize(const Dataset& src, const std::vector<ModelPtr>& models,
                                   const SynthesizeOptions& opt) {
  NormalStream noise(opt.seed);
  std::map<std::pair<std::string, Quantity>, double> given_u;
  for (const auto& m : src.measurements)
    if (m.uncertainty) given_u[{m.condition, m.quantity}] = *m.uncertainty;

  // Measurements are drawn for every condition first and written after the outliers are placed.
  struct Row {
    std::size_t station;
    Drawn d;
  };
  std::vector<Row> rows;
  std::string traj = "condition,boundary,x_mm,y_mm,uncertainty_mm\n";
  for (std::size_t i = 0; i < src.stations.size(); ++i) {
    const Station& st = src.stations[i];
    std::vector<TrajectoryQuery> queries = trajectory_queries(src, st.condition);
    std::vector<double> traj_u;
    for (const auto& p : src.trajectory)
      if (p.condition == st.condition) traj_u.push_back(p.uncertainty.value_or(2e-3));
    if (queries.empty())
      for (double x = 0.1; x <= st.plate_distance - 0.05 + 1e-9; x += 0.05)
        for (Boundary b : {Boundary::upper, Boundary::centre, Boundary::lower}) {
          queries.push_back({b, x});
          traj_u.push_back(2e-3);
        }
    const auto same = truth_of(src, i, st, models, opt.effects, queries);
    // What the rig's record predicts, without the hidden effects: the instrument's uncertainty at
    // this condition comes from it. Not from the reading: a reading the noise pushed up would get a
    // larger uncertainty than one pushed down, and every weighted fit on the data would lean low (a
    // strength 0.3-0.5 % off, which at 10 000 conditions is several of its sd). Not from the true
    // value either: that would carry the hidden effect past the noise (u / 0.02 of a force would be
    // its true value). The record's prediction is what the diagnosis computes anyway. Where the
    // record alone has no answer (the hidden effects make the rig possible), the truth stands in.
    std::optional<std::vector<ConditionResult>> recorded;
    try {
      recorded = truth_of(src, i, st, models, {}, queries);
    } catch (const InputError&) {
    }
    for (Quantity q : kAllQuantities) {
      const auto truth = first_value(same, q);
      if (!truth) continue;
      auto it = given_u.find({st.condition, q});
      const bool given = it != given_u.end();
      if (info(q).optional && !given) continue;  // a rig not instrumented for it
      const auto expected = recorded ? first_value(*recorded, q) : std::nullopt;
      // The noise is drawn with the uncertainty the dataset states (noise_factor aside).
      const double sigma = (given ? it->second : default_uncertainty(q, expected.value_or(*truth))) * opt.noise_scale;
      rows.push_back({i, {q, reading(q, *truth, sigma * opt.noise_factor, noise), sigma}});
    }
    for (std::size_t k = 0; k < queries.size(); ++k) {
      const auto truth = first_point(same, k);
      if (!truth) continue;
      const double u = traj_u[k] * opt.noise_scale;
      traj += fmt::format("{},{},{:.1f},{:.3f},{:.3f}\n", csv_field(st.condition), name(queries[k].boundary),
                          queries[k].x * 1e3, (*truth + u * opt.noise_factor * noise.next()) * 1e3, u * 1e3);
    }
  }
  std::vector<Drawn*> candidates;
  for (auto& r : rows) candidates.push_back(&r.d);
  add_outliers(candidates, opt.outliers, opt.seed);

  std::string meas = "condition,quantity,value,uncertainty\n";
  for (const auto& r : rows) {
    const Station& st = src.stations[r.station];
    const Quantity q = r.d.q;
    const double s = info(q).to_boundary;
    const std::string value = fmt::format("{:.4f}", r.d.value * s);
    const std::string u = two_significant(r.d.sigma * s);
    meas += fmt::format("{},{},{},{}\n", csv_field(st.condition), name(q), value, u);
  }
  std::string readme = fmt::format(
      "# Synthetic dataset\n\n"
      "Made by `chutelab synthesize` from the rig and conditions of `{}` (copied unchanged, in UTF-8,\n"
      "as `setup.toml` and `conditions.csv`), random seed {}. `measurements.csv` and `trajectory.csv` hold\n"
      "values computed by chutelab's analytical models with Gaussian noise of one stated uncertainty\n"
      "added to each; magnitudes (R, V_p, V_a) never read below zero, their noise is the normal\n"
      "truncated there. Each uncertainty is the instrument's for the value the rig's record\n"
      "predicts (two significant figures), whatever else went into the generating model. What\n"
      "that was is deliberately not recorded here, so the dataset can serve as a blind test of `chutelab diagnose`.\n",
      src.setup.name.empty() ? src.dir.filename().string() : src.setup.name, opt.seed);
  // What makes the data break the diagnosis's assumptions on purpose is said (not which effect).
  if (opt.noise_factor != 1.0)
    readme += fmt::format("\nThe real scatter is {:g} times the stated uncertainties: the uncertainties are stated "
                          "{}.\n", opt.noise_factor, opt.noise_factor > 1.0 ? "too small" : "too large");
  if (opt.outliers > 0)
    readme += fmt::format("\n{} reading{} carr{} a gross error of 8 to 15 stated uncertainties (which is not said).\n",
                          opt.outliers, opt.outliers == 1 ? "" : "s", opt.outliers == 1 ? "ies" : "y");
  if (opt.out_of_range)
    readme += "\nFOR TESTING ONLY: the hidden physics may include strengths outside their physical range "
              "(no real rig behaves so).\n";
  // Copied as read, but in UTF-8 like the files written beside them: a Latin-1 conditions.csv
  // would otherwise make one dataset of two encodings.
  // The source's files as they were read with it (its folder may have changed since, or it has none).
  auto copy = [&](const char* name) {
    const DatasetFile* f = src.source(name);
    return to_utf8(f ? f->text : slurp(src.dir / name));
  };
  return {{"setup.toml", copy("setup.toml")},
          {"conditions.csv", copy("conditions.csv")},
          {"measurements.csv", meas},
          {"trajectory.csv", traj},
          {"README.md", readme}};
}

Dataset replica(const Dataset& design, const std::vector<ModelPtr>& models, const SynthesizeOptions& opt,
                const std::vector<Station>* truth) {
  NormalStream noise(opt.seed);
  Dataset out = design;
  out.station_index = std::make_shared<Dataset::StationIndex>();
  out.measurements.clear();
  out.trajectory.clear();
  std::vector<Drawn*> candidates;
  std::vector<Drawn> drawn;
  drawn.reserve(design.measurements.size());
  std::vector<const Measurement*> source;
  // Each condition's rows, found once: a replica stays linear in the size of the design.
  std::unordered_map<std::string, std::vector<const Measurement*>> measured;
  std::unordered_map<std::string, std::vector<const TrajectoryPoint*>> points;
  for (const auto& m : design.measurements) measured[m.condition].push_back(&m);
  for (const auto& p : design.trajectory) points[p.condition].push_back(&p);
  for (std::size_t i = 0; i < design.stations.size(); ++i) {
    const Station& st = design.stations[i];
    std::vector<TrajectoryQuery> queries;
    for (const auto* p : points[st.condition]) queries.push_back({p->boundary, p->x});
    const auto same = truth_of(design, i, truth ? (*truth)[i] : st, models, opt.effects, queries);
    for (const auto* mp : measured[st.condition]) {
      const Measurement& m = *mp;
      if (!m.uncertainty) continue;
      const auto t = first_value(same, m.quantity);
      if (!t) continue;
      const double sigma = *m.uncertainty * opt.noise_scale;
      drawn.push_back({m.quantity, reading(m.quantity, *t, sigma * opt.noise_factor, noise), sigma});
      source.push_back(&m);
    }
    for (std::size_t k = 0; k < points[st.condition].size(); ++k) {
      const TrajectoryPoint& p = *points[st.condition][k];
      const auto t = first_point(same, k);
      if (!t || !p.uncertainty) continue;
      TrajectoryPoint r = p;
      r.uncertainty = *p.uncertainty * opt.noise_scale;
      r.y = *t + *r.uncertainty * opt.noise_factor * noise.next();
      out.trajectory.push_back(r);
    }
  }
  for (auto& d : drawn) candidates.push_back(&d);
  add_outliers(candidates, opt.outliers, opt.seed);
  for (std::size_t j = 0; j < drawn.size(); ++j) {
    Measurement m = *source[j];
    m.value = drawn[j].value;
    m.uncertainty = drawn[j].sigma;
    out.measurements.push_back(m);
  }
  return out;
}

}  // namespace chutelab::validation
