// DESIGN.md §5: with an expensive baseline the diagnosis must not run it per candidate; it shifts
// one baseline run by the cheap models' response and confirms the winner with a real run.
#include <boost/test/unit_test.hpp>
#include <atomic>

#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/synthesize.h"
#include "effects/registry.h"
#include "../cli/cli_runner.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

// Korzen dressed up as an expensive model that counts its runs and adds a constant +0.5 N to R_n
// (a "different code" whose baseline differs from the analytical one).
class CountingModel final : public Model {
 public:
  explicit CountingModel(std::atomic<int>& calls) : inner_(make_model("korzen")), calls_(calls) {}
  std::string name() const override { return "slow"; }
  std::string description() const override { return "counting expensive stand-in"; }
  bool expensive() const override { return true; }
  ModelPrediction predict(const Station& st, const analytical::EffectList& fx,
                          const PredictRequest& req) const override {
    ++calls_;
    auto p = inner_->predict(st, fx, req);
    *p.values[Quantity::normal_force] += 0.5;
    p.values[Quantity::impact_point_y].reset();  // let booth-cema own the trajectory side
    p.values[Quantity::impact_velocity].reset();
    return p;
  }

 private:
  ModelPtr inner_;
  std::atomic<int>& calls_;
};

}  // namespace

BOOST_AUTO_TEST_CASE(expensive_model_runs_once_per_condition_plus_confirmation) {
  std::atomic<int> calls{0};
  auto slow = std::make_shared<CountingModel>(calls);
  const auto rig = read_dataset(CHUTELAB_SOURCE_DIR "/datasets/grima2010", MeasurementsRequired::no);
  // Data from the same expensive model with hidden air drag, via the synthesizer; the diagnosis is
  // asked about the expensive model alone, as `--models dem` would.
  SynthesizeOptions so;
  so.effects = {chutelab::effects::find("air_drag")->make(0.6)};
  so.seed = 6190;  // outside 7100-7199, which the blind acceptance test reserves
  const auto dir = test::fresh_dir("expensive");
  write_outputs(dir, synthesize(rig, {slow}, so));
  const auto d = read_dataset(dir);
  calls = 0;
  const auto r = diagnose(d, {slow});
  const int n = static_cast<int>(d.stations.size());
  BOOST_TEST(calls.load() == 2 * n);  // one baseline run + one confirming run per condition
  BOOST_TEST(r.used_surrogate);
  BOOST_REQUIRE(r.best());
  BOOST_TEST(r.best()->label() == "air_drag");
  BOOST_REQUIRE(r.confirmed_chi2.has_value());
  // The difference estimate and the real run agree closely here (the stand-in responds to drag
  // exactly as Korzen does), so the confirmed chi^2 is within 5 % of the surrogate's.
  BOOST_TEST(*r.confirmed_chi2 <= 1.05 * r.best()->chi2_after + 1.0);
}
