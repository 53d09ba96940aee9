#include <utility>

#include "validation/models/models.h"

namespace chutelab::validation {

const std::vector<ModelFactory>& analytical_model_registry() {
  static const std::vector<ModelFactory> models = {
      {"booth-cema", make_booth_cema_model},
      {"korzen", make_korzen_model},
  };
  return models;
}

std::vector<ModelPtr> analytical_models() {
  std::vector<ModelPtr> out;
  for (const auto& [n, f] : analytical_model_registry()) out.push_back(f());
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
