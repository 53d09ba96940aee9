// Corrected records are held to physics (effects/registry.h, RecordLimits): a value given for a
// record that leaves the rig impossible (a belt -5 mm thick, particles -1.8 mm across) is refused
// naming the option it came from, never a row of conditions.csv; a record no condition states (a
// stream thickness where none is given) cannot be corrected; and a fit never lands where the rig
// has no answer. Seeds 9200-9299 are this file's own.
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <functional>

#include "analytical/transfer_station.h"
#include "api/estimate.h"
#include "api/synthesize.h"
#include "api/validate.h"
#include "core/input_error.h"
#include "effects/registry.h"
#include "validation/synthesize.h"

using namespace chutelab;
namespace fs = std::filesystem;

namespace {

const fs::path kDatasets = fs::path(CHUTELAB_SOURCE_DIR) / "datasets";
const fs::path kPeer = kDatasets / "liggghts-rig";     // 5 mm belt, 9 mm particles, stream thickness stated
const fs::path kHidden = kDatasets / "hidden-effect";  // no stream thickness stated

// The InputError `call` throws; it must name `key` and mention no file.
InputError refused(const std::function<void()>& call, const std::string& key) {
  try {
    call();
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == key, e.what());
    BOOST_TEST(e.file().empty(), e.what());
    BOOST_TEST(std::string(e.what()).find("conditions.csv") == std::string::npos, e.what());
    return e;
  }
  BOOST_FAIL("no InputError for " + key);
  return InputError("", 0, "", "");
}

bool says(const InputError& e, const std::string& text) { return std::string(e.what()).find(text) != std::string::npos; }

}  // namespace

BOOST_AUTO_TEST_SUITE(record_limits)

// Every record that changes the station declares its limits, with words and a unit.
BOOST_AUTO_TEST_CASE(every_station_record_declares_its_limits) {
  for (const auto& e : effects::library()) {
    if (e.kind != effects::EffectInfo::Kind::record || e.stage == "measurement") continue;
    if (e.name == "mass_flow_bias") continue;  // an operating-point record: (1 + b) stays positive in its range
    BOOST_TEST(static_cast<bool>(e.limits.value), e.name);
    BOOST_TEST(!e.limits.what.empty(), e.name);
    BOOST_TEST(!e.limits.unit.empty(), e.name);
    BOOST_TEST(e.limits.lower < e.limits.upper, e.name);
  }
}

BOOST_AUTO_TEST_CASE(a_record_value_outside_physics_is_refused_naming_its_option) {
  {
    api::ValidateOptions o;
    o.dataset = kPeer;
    o.inputs = {"belt_thickness=-10"};  // inside the offset's range, but the 5 mm belt would be -5 mm
    const auto e = refused([&] { api::validate(o); }, "input");
    BOOST_TEST(says(e, "belt thickness"), e.what());
    BOOST_TEST(says(e, "-5 mm"), e.what());
  }
  {
    api::ValidateOptions o;
    o.dataset = kPeer;
    o.effects = {"belt_thickness=-10"};
    refused([&] { api::validate(o); }, "effect");
  }
  {
    api::SynthesizeOptions o;
    o.dataset = kPeer;
    o.inputs = {"particle_size=-120"};  // the extended range allows it; 9 mm particles would be -1.8 mm
    o.allow_out_of_range = true;
    const auto e = refused([&] { api::synthesize(o); }, "input");
    BOOST_TEST(says(e, "particle diameter"), e.what());
    BOOST_TEST(says(e, "-1.8 mm"), e.what());
  }
  {
    api::EstimateOptions o;
    o.dataset = kPeer;
    o.condition = "V3-28";
    o.effects = {"plate_distance=-150"};
    o.plate_distance = 100.0;
    const auto e = refused([&] { api::estimate(o); }, "effect");
    BOOST_TEST(says(e, "plate distance"), e.what());
  }
}

BOOST_AUTO_TEST_CASE(a_record_no_condition_states_cannot_be_corrected) {
  for (const char* arg : {"stream_thickness=5", "stream_thickness=fit"}) {
    api::ValidateOptions o;
    o.dataset = kHidden;
    o.inputs = {arg};
    const auto e = refused([&] { api::validate(o); }, "input");
    BOOST_TEST(says(e, "no condition states a stream thickness"), e.what());
  }
  api::SynthesizeOptions s;
  s.dataset = kHidden;
  s.inputs = {"stream_thickness=5"};
  refused([&] { api::synthesize(s); }, "input");
}

// The chain itself refuses the impossible rig, so that every model, fit and synthesis sees it.
BOOST_AUTO_TEST_CASE(the_chain_refuses_an_impossible_record) {
  const auto d = validation::read_dataset(kPeer);
  BOOST_CHECK_THROW(analytical::analyse_transfer(d.stations.front(), {effects::find("belt_thickness")->make(-10.0)}),
                    InputError);
  BOOST_CHECK_NO_THROW(analytical::analyse_transfer(d.stations.front(), {effects::find("belt_thickness")->make(-4.0)}));
}

// Data that want a belt thinner than nothing (its signature comes from a pulley 30 mm smaller):
// the fit of the belt's thickness stops where the belt is still a belt.
BOOST_AUTO_TEST_CASE(a_fit_stays_where_the_record_is_possible) {
  std::vector<validation::ModelPtr> models;
  for (const auto& n : validation::model_names())
    if (auto m = validation::make_model(n); !m->expensive()) models.push_back(m);
  const auto design = validation::read_dataset(kPeer);
  validation::SynthesizeOptions so;
  so.seed = 9200;
  so.effects = {effects::find("pulley_diameter")->make(-30.0)};
  api::ValidateOptions o;
  o.inputs = {"belt_thickness=fit"};
  o.diagnose_with_effects = false;
  const api::ValidateResult r = api::validate(validation::replica(design, models, so), o);
  BOOST_REQUIRE(r.effects.size() == 1);
  BOOST_TEST(r.effects[0].value >= -5.0 - 1e-9, "the 5 mm belt fitted " << r.effects[0].value << " mm thinner");
  BOOST_TEST(r.effects[0].value < -4.0);  // it goes as far as the belt allows
}

BOOST_AUTO_TEST_SUITE_END()
