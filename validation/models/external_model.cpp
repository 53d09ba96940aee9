#include "validation/models/external_model.h"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::validation {
namespace fs = std::filesystem;

ExternalModel::ExternalModel(const std::string& spec) {
  const auto eq = spec.find('=');
  const std::string usage = "give external:NAME=DIR (DIR with predictions.csv, optional trajectory.csv, README.md)";
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
    throw InputError("", 0, "models", fmt::format("'external:{}': {}", spec, usage));
  name_ = spec.substr(0, eq);
  dir_ = spec.substr(eq + 1);
  // The name becomes a CSV cell, a TOML table name and a heading: plain characters only.
  const bool plain = std::all_of(name_.begin(), name_.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '-' || c == '_' || c == '.';
  });
  if (!plain)
    throw InputError("", 0, "models",
                     fmt::format("external model name '{}' may hold only letters, digits, '-', '_' and '.'", name_));
  for (const auto& builtin : model_names())
    if (builtin == name_)
      throw InputError("", 0, "models",
                       fmt::format("external model name '{}' is a built-in model's; choose another", name_));
  if (!fs::is_directory(dir_)) throw InputError(dir_.string(), 0, "models", "external results folder not found");
  const fs::path readme = dir_ / "README.md";
  if (!fs::is_regular_file(readme))
    throw InputError(readme.string(), 0, "README.md",
                     "missing: say which code made these predictions, its version and settings (provenance)");
  const fs::path pred = dir_ / "predictions.csv";
  if (!fs::is_regular_file(pred)) throw InputError(pred.string(), 0, "", "file not found");
  values_ = read_measurements(pred, nullptr);
  if (fs::exists(dir_ / "trajectory.csv")) trajectory_ = read_trajectory(dir_ / "trajectory.csv", nullptr);
  // The first non-empty line of the README (a heading, usually) says what the results are.
  std::ifstream in(readme);
  std::string line, title;
  while (title.empty() && std::getline(in, line)) {
    const auto a = line.find_first_not_of("# \t");
    if (a != std::string::npos) title = line.substr(a);
  }
  description_ = fmt::format("external results from {}{}", dir_.string(), title.empty() ? "" : ": " + title);
}

void ExternalModel::check_conditions(const Dataset& d) const {
  auto check = [&](const std::string& c, const SourceLine& where) {
    if (!d.station(c)) {
      std::vector<std::string> known;
      for (const auto& s : d.stations) known.push_back(s.condition);
      throw InputError(where.file, where.line, "condition",
                       fmt::format("condition '{}' is not in {} (known: {})", c,
                                   (d.dir / "conditions.csv").string(), fmt::join(known, ", ")));
    }
  };
  for (const auto& m : values_) check(m.condition, m.where);
  for (const auto& p : trajectory_) check(p.condition, p.where);
}

ModelPrediction ExternalModel::predict(const Station& station, const analytical::EffectList& effects,
                                       const PredictRequest& request) const {
  ModelPrediction p;
  for (const auto& m : values_) {
    if (m.condition != station.condition) continue;
    p.values[m.quantity] = m.value;
    if (m.uncertainty) p.uncertainty[m.quantity] = *m.uncertainty;
  }
  // The stream limits between the exported points, linearly; nothing beyond the first and last.
  auto points = [&](Boundary b) {
    std::vector<const TrajectoryPoint*> out;
    for (const auto& t : trajectory_)
      if (t.condition == station.condition && t.boundary == b) out.push_back(&t);
    std::sort(out.begin(), out.end(), [](const auto* a, const auto* c) { return a->x < c->x; });
    return out;
  };
  p.trajectory.reserve(request.trajectory.size());
  for (const auto& q : request.trajectory) {
    const auto pts = points(q.boundary);
    std::optional<double> y;
    for (std::size_t k = 0; k < pts.size() && !y; ++k) {
      if (std::abs(pts[k]->x - q.x) < 1e-9) y = pts[k]->y;
      else if (k + 1 < pts.size() && pts[k]->x < q.x && q.x < pts[k + 1]->x) {
        const double f = (q.x - pts[k]->x) / (pts[k + 1]->x - pts[k]->x);
        y = pts[k]->y + f * (pts[k + 1]->y - pts[k]->y);
      }
    }
    p.trajectory.push_back(y);
  }
  if (request.curves)
    for (Boundary b : kAllBoundaries) {
      Curve c{std::string(chutelab::name(b)), {}};
      for (const auto* t : points(b)) c.points.emplace_back(t->x, t->y);
      if (!c.points.empty()) p.curves.push_back(std::move(c));
    }
  p.notes.push_back(fmt::format("{}: results of another code read from {} (provenance: {})", name_,
                                (dir_ / "predictions.csv").string(), (dir_ / "README.md").string()));
  if (!effects.empty())
    p.notes.push_back(fmt::format("{} cannot be re-run: its values are its results without the effects (the "
                                  "instrument's effects are applied by the harness)", name_));
  return p;
}

void check_external_models(const std::vector<ModelPtr>& models, const Dataset& d) {
  for (const auto& m : models)
    if (const auto* e = dynamic_cast<const ExternalModel*>(m.get())) e->check_conditions(d);
}

}  // namespace chutelab::validation
