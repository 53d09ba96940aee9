// Recorded inputs as candidates (effects/registry.h, Kind::record): a wrong number in the rig's
// record is named as such and its error recovered within the printed ±, one input at a time, on
// replicas whose truth is made by changing the rig itself (not through the candidate), so that the
// candidate's own arithmetic is checked too. Seeds 6400-6499 are this file's own.
#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "analytical/transfer_station.h"
#include "effects/registry.h"
#include "validation/diagnosis.h"
#include "validation/synthesize.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

const std::string kRig = CHUTELAB_SOURCE_DIR "/datasets/hidden-effect";
constexpr double kDeg = std::numbers::pi / 180.0;

std::vector<ModelPtr> cheap() {
  std::vector<ModelPtr> v;
  for (const auto& n : model_names())
    if (auto m = make_model(n); !m->expensive()) v.push_back(m);
  return v;
}

const Dataset& design() {
  static const Dataset d = read_dataset(kRig);
  return d;
}

struct WrongRecord {
  std::string input;
  double error;  // truth minus record, in the candidate's unit
  std::function<void(Station&)> truth;
};

DiagnosisResult diagnose_wrong(const WrongRecord& w, std::uint64_t seed) {
  std::vector<Station> truth = design().stations;
  for (auto& s : truth) w.truth(s);
  SynthesizeOptions so;
  so.seed = seed;
  const Dataset d = replica(design(), cheap(), so, &truth);
  return diagnose(d, cheap());
}

}  // namespace

BOOST_AUTO_TEST_SUITE(record_inputs)

// The candidate changes the station exactly as the rig would be changed: the chain's numbers agree
// to the last bit (an offset in mm, degrees or % turned into SI the same way as the record is read).
BOOST_AUTO_TEST_CASE(a_record_candidate_is_the_rig_as_really_built) {
  const Station& st = design().stations.front();
  struct Case {
    const char* name;
    double v;
    std::function<void(Station&)> same;
  };
  for (const Case& c : {Case{"plate_distance", 25.0, [](Station& s) { s.plate_distance += 0.025; }},
                        Case{"plate_angle", 4.0, [](Station& s) { s.plate.angle += 4.0 * kDeg; }},
                        Case{"belt_speed", 5.0, [](Station& s) { s.belt_speed *= 1.05; }},
                        Case{"pulley_diameter", 20.0, [](Station& s) { s.belt.pulley_diameter += 0.020; }},
                        Case{"bulk_density", -10.0, [](Station& s) { s.material.bulk_density *= 0.9; }}}) {
    Station really = st;
    c.same(really);
    const auto a = analytical::analyse_transfer(st, {effects::find(c.name)->make(c.v)});
    const auto b = analytical::analyse_transfer(really, {});
    BOOST_TEST(a.korzen.normal_force == b.korzen.normal_force, c.name);
    BOOST_TEST(a.korzen.shear_force == b.korzen.shear_force, c.name);
    BOOST_TEST(a.load.height == b.load.height, c.name);
  }
  // A memo filled without the candidate is not reused with it (the load shape depends on the record).
  analytical::TransferMemo memo;
  (void)analytical::analyse_transfer(st, {}, &memo);
  const auto with = analytical::analyse_transfer(st, {effects::find("bulk_density")->make(20.0)}, &memo);
  Station denser = st;
  denser.material.bulk_density *= 1.2;
  BOOST_TEST(with.load.height == analytical::analyse_transfer(denser, {}).load.height);
}

// Five inputs, one at a time, each a tolerance-sized error or larger: named as the wrong record (not
// as a physical effect), with the error inside the printed ± 2 sd, and said as a record in words.
BOOST_AUTO_TEST_CASE(each_wrong_record_is_named_and_its_error_recovered) {
  const std::vector<WrongRecord> cases = {
      {"plate_distance", 25.0, [](Station& s) { s.plate_distance += 0.025; }},
      {"plate_angle", 4.0, [](Station& s) { s.plate.angle += 4.0 * kDeg; }},
      {"pulley_diameter", 25.0, [](Station& s) { s.belt.pulley_diameter += 0.025; }},
      {"belt_speed", 5.0, [](Station& s) { s.belt_speed *= 1.05; }},
      {"bulk_density", 10.0, [](Station& s) { s.material.bulk_density *= 1.10; }},
      {"mass_flow_bias", 0.1, [](Station& s) { s.mass_flow *= 1.10; }},
  };
  std::uint64_t seed = 6400;
  for (const auto& w : cases) {
    const auto r = diagnose_wrong(w, seed++);
    const EffectFit* b = r.best();
    BOOST_REQUIRE_MESSAGE(b, w.input << ": nothing named: " << r.verdict);
    BOOST_TEST(b->label() == w.input, w.input << ": " << r.verdict);
    if (b->label() != w.input) continue;
    BOOST_TEST(b->is_record());
    BOOST_TEST(std::abs(b->estimate[0] - w.error) <= 2.0 * b->uncertainty[0],
               w.input << ": " << b->estimate[0] << " ± " << b->uncertainty[0] << " against " << w.error);
    BOOST_TEST(r.verdict.find("The record looks wrong, not the physics") != std::string::npos, r.verdict);
    BOOST_TEST(r.verdict.find("than recorded") != std::string::npos, r.verdict);
    BOOST_TEST(r.verdict.find("Check it:") != std::string::npos, r.verdict);
  }
}

// With the record right, a physical effect is still the one named (the record candidates do not
// take its place), and effect-free data name nothing.
BOOST_AUTO_TEST_CASE(physics_is_still_found_when_the_record_is_right) {
  SynthesizeOptions so;
  so.effects = {effects::find("air_drag")->make(0.6)};
  so.seed = 6450;
  const auto r = diagnose(replica(design(), cheap(), so), cheap());
  BOOST_REQUIRE(r.best());
  BOOST_TEST(r.best()->label() == "air_drag", r.verdict);
  BOOST_TEST(!r.best()->is_record());
  SynthesizeOptions null;
  null.seed = 6451;
  const auto n = diagnose(replica(design(), cheap(), null), cheap());
  BOOST_TEST(!n.best(), n.verdict);
}

// The plausible error comes from the dataset's stated uncertainty of that input when it has one.
BOOST_AUTO_TEST_CASE(the_plausible_error_is_the_stated_uncertainty_when_given) {
  std::vector<Station> truth = design().stations;
  for (auto& s : truth) s.plate_distance += 0.025;
  SynthesizeOptions so;
  so.seed = 6460;
  Dataset d = replica(design(), cheap(), so, &truth);
  for (auto& iu : d.input_uncertainty) iu.plate_distance = 0.002;  // 2 mm stated
  const auto r = diagnose(d, cheap());
  BOOST_REQUIRE(r.best());
  BOOST_REQUIRE(r.best()->label() == "plate_distance");
  BOOST_TEST(r.best()->prior_stated[0]);
  BOOST_TEST(r.best()->prior_width[0] == 2.0, r.best()->prior_width[0]);
  // 25 mm against 2 mm stated: twelve widths off, a wrong entry rather than a tolerance.
  BOOST_TEST(r.verdict.find("a wrong entry or a changed rig") != std::string::npos, r.verdict);
  BOOST_TEST(r.best()->prior_penalty == 2.0 * std::log1p(std::pow(r.best()->estimate[0] / 2.0, 2)));
}

// Scope: a plate error of the whole rig is said to be the same at every condition.
BOOST_AUTO_TEST_CASE(a_rig_wide_record_error_is_said_to_be_the_rigs) {
  const auto rig_wide = diagnose_wrong({"plate_distance", 25.0, [](Station& s) { s.plate_distance += 0.025; }}, 6470);
  BOOST_REQUIRE(rig_wide.record_scope);
  BOOST_TEST(!rig_wide.record_scope->differs, rig_wide.record_scope->p);
  BOOST_TEST(!rig_wide.record_scope->one_condition);

  // A plate moved for one test only is not tested here: on this design 40 mm at one of eight
  // conditions raises chi^2 by ~8 (below detection), and 80-120 mm there is taken for excess scatter
  // by the noise model (docs/diagnosis.md, "What it cannot tell yet"); bench/DIAGNOSIS.md counts the
  // one-condition class.
}

BOOST_AUTO_TEST_SUITE_END()
