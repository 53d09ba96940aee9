// The time-step ladder at three conditions carried to the others (validation/models/dem_model.cpp,
// DemModelConfig::ladder_conditions; bench/LADDER.md): which runs a condition asks for, and that a
// carried u_num,disc is what the three conditions' own ladders give, scaled as the note says.
#define BOOST_TEST_MODULE dem_ladder_subset
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "tiny_station.h"
#include "validation/models/dem_model.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

// Four tiny stations from the slowest to the fastest stream; their own particle size is the quick
// preset's 13.6 mm, so there is no particle-size ladder, only the time step's.
std::vector<Station> four_stations() {
  std::vector<Station> out;
  for (double v : {2.5, 3.0, 3.5, 4.0}) {
    Station s = test::tiny_station();
    s.condition = fmt::format("V{:.1f}", v);
    s.material.particle_diameter = 13.6e-3;
    s.belt_speed = v;
    s.mass_flow = 2.5 * v / 3.0;  // the same layer
    out.push_back(s);
  }
  return out;
}

DemModelConfig config(const std::string& cache, std::vector<Station> conditions, bool all) {
  DemModelConfig c;
  c.overrides.set_quality(dem::station::Quality::quick);
  c.overrides.threads = 1;
  c.overrides.set("max_time", 0.75);
  c.cache_dir = cache;
  c.ladder_conditions = std::move(conditions);
  c.ladder_all = all;
  return c;
}

// Stream limits 100 and 200 mm from the pulley (the plate is 350 mm away).
const std::vector<TrajectoryQuery> kPoints = {
    {Boundary::upper, 0.10}, {Boundary::lower, 0.10}, {Boundary::upper, 0.20}, {Boundary::lower, 0.20}};

bool has_note(const ModelPrediction& p, const std::string& text) {
  return std::any_of(p.notes.begin(), p.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

struct Cache {
  std::string dir = (std::filesystem::temp_directory_path() / fmt::format("chutelab-ladder-subset-{}", ::getpid())).string();
  ~Cache() { std::filesystem::remove_all(dir); }
};

}  // namespace

BOOST_AUTO_TEST_CASE(three_conditions_ladder_and_the_rest_carry_it) {
  const Cache cache;
  const std::vector<Station> st = four_stations();
  const ModelPtr subset = make_dem_model(config(cache.dir, st, false));
  const ModelPtr all = make_dem_model(config(cache.dir, st, true));
  PredictRequest request;
  request.curves = false;
  request.trajectory = kPoints;

  // V3.0 lies between the slowest (V2.5), the middle by order (V3.5) and the fastest (V4.0): its own
  // 2 dt run is not asked for, theirs are.
  std::vector<std::string> rungs;
  for (const ModelJob& j : subset->campaign_jobs(st[1], {}, request))
    if (!j.ladder_rung.empty()) rungs.push_back(j.job.key);
  std::sort(rungs.begin(), rungs.end());
  BOOST_TEST(rungs == (std::vector<std::string>{"dem V2.5 (2 dt, for u_num)", "dem V3.5 (2 dt, for u_num)",
                                                 "dem V4.0 (2 dt, for u_num)"}),
             boost::test_tools::per_element());

  const ModelPrediction carried = subset->predict(st[1], {}, request);
  BOOST_TEST(has_note(carried, "carried from the ladders at V2.5, V3.5, V4.0"));
  const ModelPrediction own = all->predict(st[1], {}, request);
  BOOST_TEST(!has_note(own, "carried"));
  std::vector<ModelPrediction> from;
  for (std::size_t k : {0u, 2u, 3u}) from.push_back(all->predict(st[k], {}, request));

  // Each value: the three ladders' largest u_disc / u_stat (or u_disc / |f|, where the note says the
  // value) times this condition's own standard error (or value). The ladder_all predictions carry
  // their own ladders' u_disc, so the largest ratio is recomputed from them independently; where
  // the kinds are mixed the carried value is the larger of the two scalings, so it is at least the
  // one recomputed here.
  int checked = 0;
  for (Quantity q : {Quantity::normal_force, Quantity::shear_force, Quantity::impact_point_y, Quantity::impact_velocity}) {
    const auto& u = carried.discretisation[q];
    BOOST_REQUIRE(u.has_value());
    BOOST_REQUIRE(carried.uncertainty[q].has_value());
    double k_stat = 0.0, k_rel = 0.0;
    for (const auto& p : from) {
      BOOST_REQUIRE(p.discretisation[q] && p.uncertainty[q] && p.values[q]);
      k_stat = std::max(k_stat, *p.discretisation[q] / *p.uncertainty[q]);
      k_rel = std::max(k_rel, *p.discretisation[q] / std::abs(*p.values[q]));
    }
    const double by_noise = k_stat * *carried.uncertainty[q], by_value = k_rel * std::abs(*carried.values[q]);
    BOOST_TEST_MESSAGE(info(q).symbol << ": carried " << *u << ", by the noise " << by_noise << ", by the value "
                                      << by_value << ", own ladder " << *own.discretisation[q]);
    BOOST_TEST(*u <= std::max(by_noise, by_value) * (1 + 1e-12));
    BOOST_TEST(*u >= std::min(by_noise, by_value) * (1 - 1e-12));
    ++checked;
  }
  BOOST_TEST(checked == 4);
  // The stream limits carry too: every point the run predicts has its part.
  BOOST_REQUIRE(carried.trajectory.size() == kPoints.size());
  int points = 0;
  for (std::size_t j = 0; j < kPoints.size(); ++j)
    if (carried.trajectory[j] && carried.trajectory_uncertainty[j]) {
      BOOST_TEST(carried.trajectory_discretisation[j].has_value());
      ++points;
    }
  BOOST_TEST(points >= 2);
}

// Three conditions or fewer: each its own ladder, as before.
BOOST_AUTO_TEST_CASE(three_conditions_or_fewer_ladder_themselves) {
  const Cache cache;
  std::vector<Station> st = four_stations();
  st.pop_back();
  const ModelPtr m = make_dem_model(config(cache.dir, st, false));
  PredictRequest request;
  request.curves = false;
  std::vector<std::string> rungs;
  for (const ModelJob& j : m->campaign_jobs(st[1], {}, request))
    if (!j.ladder_rung.empty()) rungs.push_back(j.job.key);
  BOOST_TEST(rungs == std::vector<std::string>{"dem V3.0 (2 dt, for u_num)"}, boost::test_tools::per_element());
}
