// belt_slip: the layer moves slower than the belt when it reaches the pulley.
//
// Physics: the material discharges at V_d = (1 - s) V_b instead of the seed's V_d = V_b, where s is
// the slip fraction (0 = no slip, the seed's assumption; physical range 0-0.3). Slip of this kind
// appears when the belt accelerates a freshly fed layer over too short a distance, or when rolling
// particles do not reach belt speed (the seed, section 5: "if slip/rolling occurs at the discharge
// point ... the impact zone on the impact plate will be lower than anticipated").
// Hook: discharge conditions (speed of every streamline). DEM: ignored, with a note in the
// prediction — a DEM layer slips on the belt or not by its own friction (the station's sensors
// measure its speed before the pulley); there is no DEM input that imposes a slip.
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
    0.0, 0.0, 0.3, 0.06, [](double v) { return std::make_shared<BeltSlip>(v); }});

}  // namespace
}  // namespace chutelab::effects
