// load_cell_gain: every force channel of the plate reads (1 + g) times the true force.
//
// Physics: a load cell's sensitivity (mV/V per N) comes from its calibration; a wrong calibration
// factor, a wrong excitation voltage or an amplifier gain error scales everything the cell records.
// The reference study's plate hangs on load cells for the normal and the shear force (Fig. 3); when they share
// one calibration, R_n, R_s and R all read (1 + g) times the true force. The point of application
// comes from moments over forces, y_R = M / R_n, so a shared gain cancels in it and y_R is unchanged
// (DESIGN.md §6). g is a fraction, 0 = a true calibration; physical range -0.3 to +0.3.
// Hook: the measurement itself, so it applies to every model's prediction (DEM included) exactly,
// with no DEM run. With the stream thickness given, mass_flow_bias scales every force the same way
// and changes nothing else: only an independent check (a static calibration of the cells with known
// weights, or an independent mass-flow reading) tells the two apart.
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class LoadCellGain final : public analytical::Effect {
 public:
  explicit LoadCellGain(double g) : g_(g) {}
  std::string name() const override { return "load_cell_gain"; }
  void adjust_measurement(QuantityValues& v) const override {
    for (Quantity q : {Quantity::normal_force, Quantity::shear_force, Quantity::resultant_force})
      if (auto& f = v[q]) *f *= 1.0 + g_;
  }

 private:
  double g_;
};

EffectInfo info() {
  EffectInfo e{"load_cell_gain", "gain_error", "", "measurement",
               "R_n, R_s and R recorded = (1 + g) x true: a calibration (sensitivity) error shared by the plate's "
               "load cells; y_R = M / R_n is unchanged.",
               "Grima & Wypych (2010) Fig. 3 (plate on load cells); DESIGN.md §6",
               0.0, -0.3, 0.3, 0.1, [](double v) { return std::make_shared<LoadCellGain>(v); },
               "a static calibration of the plate's load cells with known weights"};
  // The cells' calibration is a record like the flow's: plausibly 2 % off when nothing is stated (a
  // calibration carried from the bench to the rig, with its mounting and temperature). Without a
  // plausible size of its own it would win every tie with the mass-flow record it mimics.
  e.kind = EffectInfo::Kind::record;
  e.prior_width = 0.02;
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
