// plate_friction: the stream's friction on the plate differs from the bench-test value mu_pw.
//
// Physics: Korzen's model uses one wall friction coefficient for the stationary-flow test (Eq 3),
// the exit velocity (Eq 4) and the shear force (Eqs 6-7). The dynamic friction of a fast stream on
// a plate (wet, worn, or coated with fines) can differ from the static bench value; this effect
// replaces mu_pw by mu_pw + d_mu. d_mu is dimensionless, 0 = the setup's value; physical range
// -0.2 to +0.5 (the sum is kept at least 0.01). The reference study measured 0.22-0.27 on mild steel
// (kinematic and static, Table 2), a spread of 0.05 from the method alone.
// Hook: plate interaction. DEM: honoured — the particle-plate sliding friction becomes mu_pw + d_mu
// (the same floor of 0.01).
#include <algorithm>

#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class PlateFriction final : public analytical::Effect {
 public:
  explicit PlateFriction(double d) : d_(d) {}
  std::string name() const override { return "plate_friction"; }
  void adjust_plate(analytical::PlateInteraction& p) const override {
    p.friction = std::max(0.01, p.friction + d_);
  }

 private:
  double d_;
};

const Registration registration({
    "plate_friction", "friction_change", "", "plate",
    "mu_pw -> mu_pw + d_mu in Korzen's Eqs 3, 4, 6 and 7: a different stream-plate friction changes "
    "the shear force, the exit velocity and where stationary flow forms.",
    "Korzen (1988); Grima & Wypych (2010) Table 2 (static vs kinematic wall friction)",
    0.0, -0.2, 0.5, 0.12, [](double v) { return std::make_shared<PlateFriction>(v); }});

}  // namespace
}  // namespace chutelab::effects
