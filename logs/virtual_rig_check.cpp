#include "logs/virtual_rig_check.h"

#include <cmath>
#include <fstream>

#include "logs/log_file.h"
#include "logs/log_reading.h"

namespace chutelab::logs {

TrialCounts run_trials(const TrueCondition& truth, SensorModel model, std::uint64_t first, int count,
                       const std::vector<double>& rates_hz, const std::filesystem::path& scratch,
                       const Fluctuation* fluctuation) {
  TrialCounts c;
  std::filesystem::create_directories(scratch);
  const std::map<Quantity, double> expect = {{Quantity::normal_force, truth.normal},
                                             {Quantity::shear_force, truth.shear},
                                             {Quantity::resultant_force, std::hypot(truth.normal, truth.shear)},
                                             {Quantity::impact_point_y, truth.impact_y}};
  for (int s = 0; s < count; ++s) {
    model.rate_hz = rates_hz[static_cast<std::size_t>(s) % rates_hz.size()];
    const Layout layout = virtual_layout(model, truth.impact_y + 0.06, truth.impact_y - 0.09);
    const auto file = scratch / (truth.condition + ".csv");
    {
      std::ofstream f(file);
      f << virtual_log(truth, model, layout, first + static_cast<std::uint64_t>(s), fluctuation);
    }
    const Log log = read_log(file, layout);
    const ConditionReading r = read_condition(log, layout, truth.condition, truth.belt_speed, truth.mass_flow);
    ++c.logs;
    c.flagged += r.flagged();
    c.drift_flagged += r.drift_flagged();
    c.creep_flagged += r.creep_flagged();
    bool short_log = false;
    for (const auto& q : r.quantities) {
      short_log = short_log || q.budget.too_short;
      const auto it = expect.find(q.quantity);
      if (it == expect.end()) continue;
      ++c.read[q.quantity];
      const double z = (q.value - it->second) / q.budget.u;
      c.covered[q.quantity] += std::abs(z) <= 2.0;
      c.sum_z2[q.quantity] += z * z;
      c.sum_rel_u[q.quantity] += q.budget.u / std::abs(it->second);
    }
    c.warned_short += short_log;
    for (const auto& k : r.checks) c.speed_off += k.role == Role::belt_speed && k.off;
    std::filesystem::remove(file);
  }
  return c;
}

}  // namespace chutelab::logs
