// Whether a named cause has the shape the data want (validation/diagnosis_stage.h, shape_of). Real
// effects rarely have exactly the library's form: a drag that grows with speed rather than with its
// square is fitted by the library's air drag at a compromise coefficient, and the explanation is
// then named although it is not the one the data hold. So each cause's strength is fitted condition
// by condition, the other causes held at theirs, and tested against the operating variables it could
// depend on: where the strength the data want changes with one of them beyond chance, the library's
// shape is not the data's, and the verdict says so in that variable's terms.
#include <algorithm>
#include <cmath>
#include <gsl/gsl_cdf.h>

#include "analytical/transfer_station.h"
#include "effects/at_condition.h"
#include "validation/diagnosis_stage.h"

namespace chutelab::validation::detail {
namespace {

// Conditions with a strength of their own needed before a dependence is asked for (a line through
// fewer says little), and distinct values of the driver among them.
constexpr std::size_t kShapeConditions = 4;

struct Driver {
  std::string name, unit;
  std::vector<double> value;  // per condition, boundary units
};

std::vector<Driver> drivers_per_condition(const Dataset& d) {
  std::vector<Driver> out = {{"belt speed", "m/s", {}}, {"mass flow", "t/h", {}}, {"drop height", "mm", {}}};
  for (const auto& st : d.stations) {
    out[0].value.push_back(st.belt_speed);
    out[1].value.push_back(st.mass_flow * 3.6);
    double drop = 0.0;
    try {
      drop = analytical::analyse_transfer(st).drop_height() * 1e3;
    } catch (const std::exception&) {
      drop = 0.0;
    }
    out[2].value.push_back(drop);
  }
  return out;
}

// The weighted straight line y = a + b t through points (t, y) with sd u: a, b, their covariance and
// the fall of chi^2 it gives against a constant.
struct Line {
  double a = 0.0, b = 0.0, var_a = 0.0, var_b = 0.0, cov = 0.0, drop = 0.0;
};
std::optional<Line> weighted_line(const std::vector<double>& t, const std::vector<double>& y,
                                  const std::vector<double>& u) {
  double sw = 0, st = 0, sy = 0, stt = 0, sty = 0, syy = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double w = 1.0 / (u[i] * u[i]);
    sw += w, st += w * t[i], sy += w * y[i], stt += w * t[i] * t[i], sty += w * t[i] * y[i], syy += w * y[i] * y[i];
  }
  const double det = sw * stt - st * st;
  if (!(det > 1e-12 * sw * stt)) return std::nullopt;
  Line l;
  l.b = (sw * sty - st * sy) / det;
  l.a = (sy - l.b * st) / sw;
  l.var_a = stt / det, l.var_b = sw / det, l.cov = -st / det;
  // chi^2 about the weighted mean minus chi^2 about the line: b^2 / var_b.
  l.drop = l.b * l.b / l.var_b;
  return l;
}

}  // namespace

std::vector<ShapeFinding> shape_of(const Stage& s, const EffectFit& best) {
  std::vector<ShapeFinding> out;
  const Fx fx = infos_of(best);
  const auto& stations = s.m.dataset().stations;
  const auto drivers = drivers_per_condition(s.m.dataset());
  std::vector<std::size_t> tested;
  // Physical effects: a record's error that differs between conditions is the record scope's finding.
  for (std::size_t j = 0; j < fx.size(); ++j)
    if (fx[j]->kind == effects::EffectInfo::Kind::physics) tested.push_back(j);
  const double tests = static_cast<double>(tested.size() * drivers.size());
  for (std::size_t j : tested) {
    Fx others;
    std::vector<double> held;
    for (std::size_t k = 0; k < fx.size(); ++k)
      if (k != j) others.push_back(fx[k]), held.push_back(best.estimate[k]);
    std::vector<std::size_t> at;
    std::vector<double> strength, sd;
    for (std::size_t c = 0; c < stations.size(); ++c) {
      const Cost part = s.cost.only({c});
      if (part.size() == 0) continue;
      const Held h = fit_held(part, others, held, fx[j]);
      if (!std::isfinite(h.uncertainty) || !(h.uncertainty > 0.0)) continue;
      // A strength at an edge of the range says only that the condition wants it there or beyond.
      const double span = fx[j]->upper - fx[j]->lower;
      if (h.estimate <= fx[j]->lower + 1e-3 * span || h.estimate >= fx[j]->upper - 1e-3 * span) continue;
      at.push_back(c), strength.push_back(h.estimate), sd.push_back(h.uncertainty);
    }
    if (at.size() < kShapeConditions) continue;
    // The conditions' strengths scatter about any line more than their sd say where the readings do
    // (a scale widened, or a condition off on its own): the test takes the larger.
    const double scale2 = std::max(1.0, s.nm.scale * s.nm.scale);
    for (const auto& dr : drivers) {
      std::vector<double> t;
      double mean_log = 0.0;
      bool positive = true;
      for (std::size_t c : at) positive = positive && dr.value[c] > 0.0;
      if (!positive) continue;
      for (std::size_t c : at) mean_log += std::log(dr.value[c]) / static_cast<double>(at.size());
      for (std::size_t c : at) t.push_back(std::log(dr.value[c]) - mean_log);
      const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
      if (*hi - *lo < 0.05) continue;  // the driver hardly varies (within 5 %)
      const auto line = weighted_line(t, strength, sd);
      if (!line) continue;
      double about_line = 0.0;
      for (std::size_t i = 0; i < t.size(); ++i)
        about_line += std::pow((strength[i] - line->a - line->b * t[i]) / sd[i], 2);
      const double excess = std::max(scale2, about_line / static_cast<double>(t.size() - 2));
      const double p = std::min(1.0, gsl_cdf_chisq_Q(line->drop / excess, 1.0) * tests);
      if (p >= s.opt.alpha) continue;
      // The strength relative to its value at the conditions' centre: s ~ a (x / x0)^beta with beta = b / a.
      const double neutral = fx[j]->neutral;
      const double a = line->a - neutral;
      if (!(std::abs(a) > 2.0 * std::sqrt(line->var_a * excess))) continue;  // no strength to scale
      ShapeFinding f;
      f.effect = fx[j]->name;
      f.parameter = fx[j]->parameter;
      f.unit = fx[j]->unit;
      f.driver = dr.name;
      f.driver_unit = dr.unit;
      f.exponent = line->b / a;
      // Delta method for b / a.
      const double var = (line->var_b / (a * a) + line->b * line->b * line->var_a / std::pow(a, 4) -
                          2.0 * line->b * line->cov / std::pow(a, 3)) *
                         excess;
      f.exponent_uncertainty = std::sqrt(std::max(0.0, var));
      f.low_driver = std::exp(*lo + mean_log), f.high_driver = std::exp(*hi + mean_log);
      f.low_strength = line->a + line->b * *lo, f.high_strength = line->a + line->b * *hi;
      f.p = p;
      if (fx[j]->growth && fx[j]->growth->driver == dr.name) f.grows = fx[j]->growth->what, f.power = fx[j]->growth->power;
      out.push_back(f);
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.p < y.p; });
  // One dependence per cause: the drivers of a rig move together, so the strongest speaks for them.
  std::vector<ShapeFinding> one;
  for (const auto& f : out)
    if (std::none_of(one.begin(), one.end(), [&](const auto& g) { return g.effect == f.effect; })) one.push_back(f);
  return one;
}

}  // namespace chutelab::validation::detail
