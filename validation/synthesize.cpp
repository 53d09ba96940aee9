#include "validation/synthesize.h"
#include "core/csv_field.h"

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

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

}  // namespace

std::vector<OutputFile> synthesize(const Dataset& src, const std::vector<ModelPtr>& models,
                                   const SynthesizeOptions& opt) {
  NormalStream noise(opt.seed);
  std::map<std::pair<std::string, Quantity>, double> given_u;
  for (const auto& m : src.measurements)
    if (m.uncertainty) given_u[{m.condition, m.quantity}] = *m.uncertainty;

  std::string meas = "condition,quantity,value,uncertainty\n";
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
    std::vector<ConditionResult> same;
    try {
      for (const auto& m : models)
        same.push_back({st.condition, m->name(), m->predict(st, opt.effects, {queries, false})});
    } catch (const InputError& e) {
      throw e.located(src.station_lines[i].file, src.station_lines[i].line);
    }
    apply_measurement_effects(opt.effects, same);

    for (Quantity q : kAllQuantities) {
      std::optional<double> truth;
      for (const auto& s : same)
        if (!truth && s.prediction.values[q]) truth = s.prediction.values[q];
      if (!truth) continue;
      // The noise follows the true value (a load cell's error scales with the load it carries),
      // but the stated uncertainty is computed from the reading, as a lab computes it: one
      // computed from the noise-free value would carry that value, effect included, past the
      // noise (u / 0.02 of a force would be its noise-free value).
      auto it = given_u.find({st.condition, q});
      const bool given = it != given_u.end();
      if (info(q).optional && !given) continue;  // a rig not instrumented for it
      const double sigma = (given ? it->second : default_uncertainty(q, *truth)) * opt.noise_scale;
      const double s = info(q).to_boundary;
      const std::string value = fmt::format("{:.4f}", reading(q, *truth, sigma, noise) * s);
      double written = 0.0;  // what the reader will see: the uncertainty is a function of it alone
      std::from_chars(value.data(), value.data() + value.size(), written);
      written /= s;
      const std::string u = two_significant(
          (given ? it->second : default_uncertainty(q, written)) * opt.noise_scale * s);
      meas += fmt::format("{},{},{},{}\n", csv_field(st.condition), name(q), value, u);
    }
    for (std::size_t k = 0; k < queries.size(); ++k) {
      std::optional<double> truth;
      for (const auto& s : same)
        if (!truth && k < s.prediction.trajectory.size() && s.prediction.trajectory[k])
          truth = s.prediction.trajectory[k];
      if (!truth) continue;
      const double u = traj_u[k] * opt.noise_scale;
      traj += fmt::format("{},{},{:.1f},{:.3f},{:.3f}\n", csv_field(st.condition), name(queries[k].boundary),
                          queries[k].x * 1e3, (*truth + u * noise.next()) * 1e3, u * 1e3);
    }
  }
  const std::string readme = fmt::format(
      "# Synthetic dataset\n\n"
      "Made by `chutelab synthesize` from the rig and conditions of `{}` (copied unchanged, in UTF-8,\n"
      "as `setup.toml` and `conditions.csv`), random seed {}. `measurements.csv` and `trajectory.csv` hold\n"
      "values computed by chutelab's analytical models with Gaussian noise of one stated uncertainty\n"
      "added to each; magnitudes (R, V_p, V_a) never read below zero, their noise is the normal\n"
      "truncated there. Each uncertainty is computed from the written value (two significant\n"
      "figures). What else went into the generating model is deliberately not recorded here, so\n"
      "the dataset can serve as a blind test of `chutelab diagnose`.\n",
      src.setup.name.empty() ? src.dir.filename().string() : src.setup.name, opt.seed);
  // Copied as read, but in UTF-8 like the files written beside them: a Latin-1 conditions.csv
  // would otherwise make one dataset of two encodings.
  return {{"setup.toml", to_utf8(slurp(src.dir / "setup.toml"))},
          {"conditions.csv", to_utf8(slurp(src.dir / "conditions.csv"))},
          {"measurements.csv", meas},
          {"trajectory.csv", traj},
          {"README.md", readme}};
}

}  // namespace chutelab::validation
