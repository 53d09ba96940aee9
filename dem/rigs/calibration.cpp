#include "dem/rigs/calibration.h"

#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem::rigs {

std::string_view name(GrainKind k) { return k == GrainKind::sphere ? "sphere" : "clump"; }

double target_distance(const SlumpResult& r, const CalibrationTargets& t) {
  if (!t.any()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  int n = 0;
  if (t.bulk_density) {
    const double e = (r.bulk_density - *t.bulk_density) / *t.bulk_density;
    sum += e * e;
    ++n;
  }
  if (t.pile_height) {
    const double e = (r.pile_height - *t.pile_height) / *t.pile_height;
    sum += e * e;
    ++n;
  }
  return std::sqrt(sum / n);
}

CalibrationStudy run_calibration(const chutelab::Material& m, const CalibrationPlan& plan,
                                 const std::function<void(const CalibrationProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (plan.rolling.empty()) throw InputError("", 0, "--rolling", "give at least one rolling friction coefficient");
  if (plan.density.empty()) throw InputError("", 0, "--density", "give at least one solid density");
  if (plan.shapes.empty()) throw InputError("", 0, "--shape", "give at least one shape (sphere, clump)");
  for (double r : plan.rolling)
    if (!(r >= 0.0) || !std::isfinite(r) || r > 10.0)
      throw InputError("", 0, "--rolling", fmt::format("rolling friction must be in [0, 10], got {}", r));
  for (double d : plan.density)
    if (!(d > 0.0) || !std::isfinite(d) || d > 3e4)
      throw InputError("", 0, "--density", fmt::format("solid density must be in (0, 30000] kg/m^3, got {}", d));
  if (plan.targets.bulk_density && !(*plan.targets.bulk_density > 0.0))
    throw InputError("", 0, "--target-bulk-density", "must be > 0 kg/m^3");
  if (plan.targets.pile_height && !(*plan.targets.pile_height > 0.0))
    throw InputError("", 0, "--target-pile-height", "must be > 0 mm");

  CalibrationStudy st;
  st.plan = plan;
  const int count = static_cast<int>(plan.shapes.size() * plan.rolling.size() * plan.density.size());
  int index = 0;
  for (GrainKind shape : plan.shapes)
    for (double mu_r : plan.rolling)
      for (double rho : plan.density) {
        ++index;
        CalibrationRow row;
        row.shape = shape;
        row.rolling_friction = mu_r;
        row.solid_density = rho;
        const Grain& g = shape == GrainKind::sphere ? plan.sphere : plan.clump;
        auto each = [&](const SlumpProgress& sp) {
          if (progress) progress({index, count, nullptr, sp});
        };
        row.slump = run_slump_test(m, rho, mu_r, g, plan.settings, each);
        row.distance = target_distance(row.slump, plan.targets);
        st.rows.push_back(row);
        if (progress) progress({index, count, &st.rows.back(), {}});
      }
  if (plan.targets.any()) {
    for (std::size_t k = 0; k < st.rows.size(); ++k)
      if (std::isfinite(st.rows[k].distance) &&
          (st.closest < 0 || st.rows[k].distance < st.rows[static_cast<std::size_t>(st.closest)].distance))
        st.closest = static_cast<int>(k);
  }
  if (plan.incline) {
    const double mu_w = m.friction_plate;
    for (double mu_r : plan.rolling) {
      InclineRow r;
      r.rolling_friction = mu_r;
      r.wall_friction = mu_w;
      r.result = find_incline_onset(m, mu_w, mu_r, plan.sphere);
      st.incline.push_back(r);
    }
  }
  st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

}  // namespace chutelab::dem::rigs
