// A fit on many conditions scans its grid on an even sample of them and polishes the minimum on
// all (validation/strength_fit.h, kGridConditions): it must land where the grid over every
// condition lands, within a small part of the fit's own sd. Seeds 6600-6609 are this file's own.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"
#include "effects/registry.h"
#include "validation/misfit.h"
#include "validation/strength_fit.h"
#include "validation/synthesize.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

std::vector<ModelPtr> cheap() {
  std::vector<ModelPtr> v;
  for (const auto& n : model_names())
    if (auto m = make_model(n); !m->expensive()) v.push_back(m);
  return v;
}

// The bundled rig's eight conditions repeated at belt speeds spread by +-15 %, each with the
// readings its original has: more conditions than twice the grid's sample.
Dataset many_conditions(std::size_t n) {
  const Dataset rig = read_dataset(CHUTELAB_SOURCE_DIR "/datasets/hidden-effect");
  Dataset d = rig;
  d.stations.clear();
  d.station_lines.clear();
  d.input_uncertainty.clear();
  d.measurements.clear();
  d.trajectory.clear();
  d.plate_map.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = i % rig.stations.size();
    Station s = rig.stations[k];
    const std::string original = s.condition;
    s.condition = fmt::format("L{:04d}", i);
    s.belt_speed *= 0.85 + 0.3 * static_cast<double>(i) / static_cast<double>(n);
    d.stations.push_back(s);
    d.station_lines.push_back(rig.station_lines[k]);
    if (k < rig.input_uncertainty.size()) d.input_uncertainty.push_back(rig.input_uncertainty[k]);
    for (auto m : rig.measurements)
      if (m.condition == original) {
        m.condition = s.condition;
        d.measurements.push_back(m);
      }
    for (auto p : rig.trajectory)
      if (p.condition == original) {
        p.condition = s.condition;
        d.trajectory.push_back(p);
      }
  }
  return d;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(large_fits)

// 600 conditions with air drag hidden: a physical effect, a plate effect and a recorded input, each
// fitted both ways. The sampled fit's estimate is within a tenth of an sd of the whole grid's, and
// its chi^2 no higher than that within the same tenth (chi^2 rises by 0.01 at 0.1 sd).
BOOST_AUTO_TEST_CASE(a_sampled_grid_lands_where_the_whole_grid_does) {
  const std::vector<ModelPtr> models = cheap();
  SynthesizeOptions so;
  so.seed = 6600;
  so.effects = {effects::find("air_drag")->make(0.7)};
  const Dataset data = replica(many_conditions(600), models, so);
  const Misfit m(data, models);
  const Cost cost(m);
  BOOST_REQUIRE(cost.conditions().size() > 2 * kGridConditions);
  for (const char* name : {"air_drag", "plate_friction", "belt_speed"}) {
    const std::vector<const effects::EffectInfo*> fx = {effects::find(name)};
    const StrengthFit sampled = fit_strengths(cost, fx);
    FitOptions every;
    every.grid_conditions = 0;
    const StrengthFit whole = fit_strengths(cost, fx, every);
    BOOST_TEST_MESSAGE(fmt::format("{}: sampled {} +- {} (chi2 {}), whole grid {} +- {} (chi2 {})", name,
                                   sampled.estimate[0], sampled.uncertainty[0], sampled.chi2, whole.estimate[0],
                                   whole.uncertainty[0], whole.chi2));
    BOOST_TEST((sampled.status == FitStatus::converged), name);
    BOOST_TEST(std::isfinite(whole.uncertainty[0]), name);
    BOOST_TEST(std::abs(sampled.estimate[0] - whole.estimate[0]) < 0.1 * whole.uncertainty[0], name);
    BOOST_TEST(sampled.chi2 <= whole.chi2 + 0.01, name);
    BOOST_TEST(std::abs(sampled.uncertainty[0] / whole.uncertainty[0] - 1.0) < 0.05, name);
  }
}

// The residuals are taken per condition on the thread that predicted it (PredictionSource::visit):
// they must be those read from the whole predictions kept, bit for bit, on two threads (200
// conditions: 64 a thread and more), for every point and for a part's rows, and all infeasible
// when a strength makes a condition impossible.
BOOST_AUTO_TEST_CASE(residuals_per_condition_are_those_of_the_kept_predictions) {
  const std::vector<ModelPtr> models = cheap();
  SynthesizeOptions so;
  so.seed = 6601;
  const Dataset data = replica(many_conditions(200), models, so);
  const Misfit m(data, models, {}, 2);
  const std::vector<const effects::EffectInfo*> fx = {effects::find("air_drag"), effects::find("plate_friction")};
  const std::vector<double> at = {0.6, 0.05};
  const std::vector<double> kept = m.residuals_of(m.source().predict(fx, at));
  const std::vector<double> visited = m.residuals(fx, at);
  BOOST_REQUIRE_EQUAL(kept.size(), visited.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < kept.size(); ++i) differ += kept[i] != visited[i];
  BOOST_TEST(differ == 0u);

  const MisfitPart part = m.part({150, 3, 77, 3});
  const std::vector<double> rows = m.residuals(fx, at, part);
  BOOST_REQUIRE_EQUAL(rows.size(), part.rows.size());
  BOOST_TEST(part.conditions == (std::vector<std::size_t>{3, 77, 150}), boost::test_tools::per_element());
  for (std::size_t j = 0; j < rows.size(); ++j) BOOST_TEST(rows[j] == kept[part.rows[j]], j);

  // A plate a metre nearer than recorded stands behind the pulley: no condition can be predicted,
  // and every residual is the infeasible one, beyond its residual without candidates.
  const std::vector<const effects::EffectInfo*> plate = {effects::find("plate_distance")};
  const std::vector<double> behind = {-1000.0};
  BOOST_CHECK_THROW((void)m.source().predict(plate, behind), InputError);
  const std::vector<double> base = m.residuals({}, {}), impossible = m.residuals(plate, behind);
  std::size_t feasible = 0;
  for (std::size_t i = 0; i < base.size(); ++i) feasible += impossible[i] != Misfit::kInfeasible + std::abs(base[i]);
  BOOST_TEST(feasible == 0u);
}

BOOST_AUTO_TEST_SUITE_END()
