// validation/response_pooling.h: an expensive model's noisy own responses read together.
#include <boost/test/unit_test.hpp>
#include <atomic>
#include <cmath>

#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/response_pooling.h"
#include "validation/synthesize.h"
#include "../cli/cli_runner.h"

using namespace chutelab;
using namespace chutelab::validation;

BOOST_AUTO_TEST_SUITE(response_pooling)

// Exact responses (no stated noise) are what they are: nothing to weigh.
BOOST_AUTO_TEST_CASE(responses_without_noise_are_kept) {
  const std::vector<double> own = {1.0, 5.0, -2.0, 0.5}, sd(4, 0.0);
  const std::vector<std::optional<double>> shape = {1.0, 1.0, 1.0, 1.0};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(!r.pooled);
  BOOST_TEST(r.response == own, boost::test_tools::per_element());
}

// Two responses say nothing about their spread about a fitted scale.
BOOST_AUTO_TEST_CASE(too_few_responses_are_kept) {
  const std::vector<double> own = {1.0, 9.0}, sd = {0.1, 5.0};
  const std::vector<std::optional<double>> shape = {1.0, 1.0};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(!r.pooled);
  BOOST_TEST(r.response == own, boost::test_tools::per_element());
}

// Six precise responses twice the shape (a code responding twice as strongly as the analytical
// chain) and one probe that caught a fluctuation: 12 times the shape, with a standard error 40
// times the others'. The precise ones fix the scale at 2 and leave no spread beyond their noise, so
// the noisy one is read as twice its shape; the precise ones move by less than their own sd.
BOOST_AUTO_TEST_CASE(a_noisy_probe_is_read_with_the_shape_the_precise_ones_give) {
  const std::vector<std::optional<double>> shape = {-0.3, -0.5, -0.8, -1.2, -1.5, -1.7, -0.4};
  std::vector<double> own, sd;
  for (std::size_t i = 0; i + 1 < shape.size(); ++i) own.push_back(2.0 * *shape[i] + (i % 2 ? 0.02 : -0.02)), sd.push_back(0.05);
  own.push_back(12.0 * *shape.back());
  sd.push_back(2.0);
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.pooled);
  // The scale from the precise six (their +-0.02 alternate); the noisy one weighs 1/1600 as much.
  BOOST_TEST(r.scale == 2.0, boost::test_tools::tolerance(0.02));
  // Its excess over the shape (4) is 2 of its sd: no spread beyond the noise is needed (the weighted
  // sum of squares ~5 is below its 6 degrees of freedom), so it is read as the shape.
  BOOST_TEST(std::abs(r.response.back() - 2.0 * *shape.back()) < 0.1 * std::abs(own.back() - 2.0 * *shape.back()));
  for (std::size_t i = 0; i + 1 < own.size(); ++i) BOOST_TEST(std::abs(r.response[i] - own[i]) < sd[i]);
}

// A precise response that disagrees with the shape is the code's own physics there: kept.
BOOST_AUTO_TEST_CASE(a_precise_response_that_departs_from_the_shape_is_kept) {
  const std::vector<std::optional<double>> shape = {1.0, 2.0, 3.0, 4.0, 5.0};
  const std::vector<double> own = {1.0, 2.0, 3.0, 4.0, -5.0}, sd = {0.3, 0.3, 0.3, 0.3, 0.001};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.pooled);
  BOOST_TEST(r.response[4] == -5.0, boost::test_tools::tolerance(1e-3));
}

// Where the cheap models do not respond at all, the shape is a common response: responses that are
// noise about one value move toward it, not toward zero.
BOOST_AUTO_TEST_CASE(without_a_shape_the_responses_share_a_common_value) {
  const std::vector<double> own = {-1.1, -0.9, -1.05, -0.95, -1.0, 3.0}, sd = {0.2, 0.2, 0.2, 0.2, 0.2, 4.0};
  const std::vector<std::optional<double>> shape(6, std::nullopt);
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.pooled);
  BOOST_TEST(r.scale == -1.0, boost::test_tools::tolerance(0.05));
  BOOST_TEST(r.response.back() < -0.5);
  BOOST_TEST(r.response.back() > -1.5);
}

// A response with no shape where the others have one is not pooled with them.
BOOST_AUTO_TEST_CASE(a_response_without_a_shape_among_shaped_ones_is_kept) {
  const std::vector<double> own = {1.0, 2.0, 3.0, 7.0}, sd = {0.5, 0.5, 0.5, 3.0};
  const std::vector<std::optional<double>> shape = {1.0, 2.0, 3.0, std::nullopt};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.response[3] == 7.0);
}

BOOST_AUTO_TEST_SUITE_END()

namespace {

// An expensive stand-in that represents mass_flow_bias itself (its response doubles the analytical
// one, as in test_expensive_baseline.cpp) and states a standard error for its forces, as a DEM
// mean does. Its signature-quality probe of the flow at one condition catches a fluctuation: the
// forces there read 60 % high, with a standard error to match. Read alone, that one difference
// drags the fitted flow bias; read with the others, it does not.
class FluctuatingProbeModel final : public Model {
 public:
  FluctuatingProbeModel(std::string fluctuating, std::atomic<int>& calls)
      : inner_(make_model("korzen")), fluctuating_(std::move(fluctuating)), calls_(calls) {}
  std::string name() const override { return "own"; }
  std::string description() const override { return "expensive stand-in with one noisy probe"; }
  bool expensive() const override { return true; }
  bool represents(const Station&, const analytical::EffectList& fixed, const analytical::EffectList& with) const override {
    return with.size() > fixed.size() && with.back()->name() == "mass_flow_bias";
  }
  ModelPrediction predict(const Station& st, const analytical::EffectList& fx, const PredictRequest& req) const override {
    ++calls_;
    analytical::OperatingPoint op{st.belt_speed, st.mass_flow};
    for (const auto& e : fx) e->adjust_operating_point(op);
    Station s = st;
    s.mass_flow = st.mass_flow + 2.0 * (op.mass_flow - st.mass_flow);
    auto p = inner_->predict(s, {}, req);
    p.values[Quantity::impact_point_y].reset();
    p.values[Quantity::impact_velocity].reset();
    const bool noisy_probe = req.signature && !fx.empty() && st.condition == fluctuating_;
    for (Quantity q : {Quantity::normal_force, Quantity::shear_force, Quantity::resultant_force})
      if (p.values[q]) {
        if (noisy_probe) *p.values[q] *= 1.6;
        p.uncertainty[q] = (noisy_probe ? 0.4 : 0.01) * std::abs(*p.values[q]);
      }
    return p;
  }

 private:
  ModelPtr inner_;
  std::string fluctuating_;
  std::atomic<int>& calls_;
};

}  // namespace

BOOST_AUTO_TEST_CASE(one_noisy_probe_does_not_drag_the_signature_fit) {
  const auto rig = read_dataset(CHUTELAB_SOURCE_DIR "/datasets/liggghts-rig", MeasurementsRequired::no);
  std::atomic<int> calls{0};
  // The data: the stand-in without its fluctuation (a condition name that does not exist).
  auto clean = std::make_shared<FluctuatingProbeModel>("none", calls);
  SynthesizeOptions so;
  so.effects = {chutelab::effects::find("mass_flow_bias")->make(-0.06)};
  so.seed = 6193;
  so.noise_scale = 0.3;
  const auto dir = test::fresh_dir("noisy-probe");
  write_outputs(dir, synthesize(rig, {clean}, so), {}, "synthesize");
  const auto d = read_dataset(dir);
  auto noisy = std::make_shared<FluctuatingProbeModel>(d.stations.front().condition, calls);
  DiagnoseOptions opt;
  opt.pairs = false;
  opt.confirm = 0;  // the signatures' fit itself is under test
  opt.profile_runs = 0;
  const auto r = diagnose(d, {noisy}, opt);
  bool seen = false;
  for (const auto& s : r.singles)
    if (s.label() == "mass_flow_bias") {
      seen = true;
      // Without the pooling the fluctuating probe's forces (a 60 % jump read as the flow's doing at
      // that condition) pull the estimate to -0.0362 +- 0.0007 (33 sd from the truth); with it,
      // -0.0598 +- 0.0010.
      BOOST_TEST(std::abs(s.estimate[0] - -0.06) < 3.0 * s.uncertainty[0] + 0.002, s.estimate[0] << " +- " << s.uncertainty[0]);
    }
  BOOST_TEST(seen);
}
