#include "validation/model.h"

#include <fmt/format.h>
#include <functional>
#include <utility>

#include "core/input_error.h"
#include "validation/models/dem_model.h"
#include "validation/models/models.h"

namespace chutelab::validation {
namespace {

// The registry: adding a model is one factory and one line here. The order matters where models
// overlap: fits and synthetic data take each quantity from the first model that predicts it.
const std::vector<std::pair<std::string, std::function<ModelPtr()>>>& registry() {
  static const std::vector<std::pair<std::string, std::function<ModelPtr()>>> models = {
      {"booth-cema", make_booth_cema_model},
      {"korzen", make_korzen_model},
      {"dem", [] { return make_dem_model(); }},
  };
  return models;
}

}  // namespace

std::vector<std::string> model_names() {
  std::vector<std::string> out;
  for (const auto& [n, f] : registry()) out.push_back(n);
  return out;
}

ModelPtr make_model(const std::string& name) {
  for (const auto& [n, f] : registry())
    if (n == name) return f();
  throw InputError("", 0, "--models",
                   fmt::format("unknown model '{}' (known: {})", name,
                               fmt::join(model_names(), ", ")));
}

std::vector<ModelPtr> make_models(const std::vector<std::string>& names) {
  std::vector<ModelPtr> out;
  for (const auto& n : names) out.push_back(make_model(n));
  return out;
}

Curve streamline_curve(const analytical::TransferAnalysis& a, analytical::Streamline s,
                       std::string name) {
  const auto& line = a.line(s);
  const double t_end = line.hit ? line.hit->point.t : 1.0;
  Curve c{std::move(name), {}};
  for (const auto& p : line.trajectory.sample(t_end, 48)) c.points.push_back(p.position);
  return c;
}

}  // namespace chutelab::validation
