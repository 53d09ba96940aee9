// belt_slip: the layer moves slower than the belt when it reaches the pulley.
//
// Physics: the material discharges at V_d = (1 - s) V_b instead of the reference study's V_d = V_b, where s is
// the slip fraction (0 = no slip, the reference study's assumption; physical range 0-0.3). Slip of this kind
// appears when the belt accelerates a freshly fed layer over too short a distance, or when rolling
// particles do not reach belt speed (the reference study, section 5: "if slip/rolling occurs at the discharge
// point ... the impact zone on the impact plate will be lower than anticipated").
// Hook: discharge conditions (speed of every streamline). DEM: honoured — the belt and the pulley
// carry the layer at (1 - s) V_b (validation/models/dem_model.cpp), so the material reaches the
// pulley and leaves it at that speed; the station's sensors measure the layer's speed before the
// pulley (belt_layer_velocity_mps), which tells slip apart from drag.
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class BeltSlip final : public analytical::Effect {
 public:
  explicit BeltSlip(double s) : s_(s) {}
  std::string name() const override { return "belt_slip"; }
  void adjust_discharge(analytical::DischargeInput& d, const Station&) const override {
    d.speed *= 1.0 - s_;
  }

 private:
  double s_;
};

const Registration registration({
    "belt_slip", "slip_fraction", "", "discharge",
    "V_d = (1 - s) V_b: the stream leaves the pulley slower than the belt by the slip fraction s.",
    "Grima & Wypych (2010) section 5 (slip at the discharge lowers the impact zone)",
    0.0, 0.0, 0.3, 0.06, [](double v) { return std::make_shared<BeltSlip>(v); },
    "the layer's speed on the belt just before the pulley (belt_layer_velocity_mps, e.g. from high-speed video)"});

}  // namespace
}  // namespace chutelab::effects
