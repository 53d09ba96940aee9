// height_datum: every measured height reads the same amount off (a datum error of the height scale).
//
// Physics: the stream's limits are read off photographs against a scale, and the point of application
// is given in the same rig coordinates; if the scale's zero is not level with the pulley axis as the
// record assumes, every height reads dy too high: y_recorded = y + dy, for the trajectory points and
// the impact point alike. dy in mm, 0 = a true datum; physical range -50 to +50 mm.
// A pulley diameter error moves every height too (the discharge radius), nearly equally: the data
// can hardly tell them apart, the tape round the pulley and a level from its axis can.
// Hook: the measurement itself (DEM included): no input of any model changes.
#include <cmath>

#include "effects/recorded_input.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class HeightDatum final : public analytical::Effect {
 public:
  explicit HeightDatum(double dy) : dy_(dy) {}
  std::string name() const override { return "height_datum"; }
  void adjust_measurement(QuantityValues& v) const override {
    if (auto& y = v[Quantity::impact_point_y]) *y += dy_;
  }
  void adjust_trajectory(std::vector<std::optional<double>>& ys) const override {
    for (auto& y : ys)
      if (y) *y += dy_;
  }

 private:
  double dy_;  // m
};

EffectInfo info() {
  EffectInfo e{"height_datum", "offset", "mm", "measurement",
               "y_recorded = y + dy for every measured height (trajectory points and the impact point): the "
               "height scale's zero is not where the record puts it.",
               "",
               0.0, -50.0, 50.0, 6.0, [](double v) { return std::make_shared<HeightDatum>(v * kMm); },
               "a level from the pulley axis to the zero of the height scale the photographs were read against"};
  // The scale's zero is a record of the instrument: plausibly 2 mm off when nothing is stated.
  e.kind = EffectInfo::Kind::record;
  e.prior_width = 2.0;
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
