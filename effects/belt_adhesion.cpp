// belt_adhesion: adhesive stress between the layer and the belt delays the release.
//
// Physics: an adhesive (tensile) stress sigma_a between belt and material holds the layer on the
// pulley with an extra acceleration towards its axis a_h = sigma_a / m'', where m'' = rho_bl A / W
// is the layer's mass per unit belt area. Booth's release condition becomes
//   V^2 / r = g cos(theta) + a_h,
// so a sticky layer rides further round the pulley and the stream leaves lower and steeper (the
// adhesion term of the trajectory models reviewed by Hastie & Wypych 2007). sigma_a in Pa, 0 = dry
// cohesionless material (the reference study's case); physical range 0-2000 Pa for damp or sticky bulk solids.
// Hook: discharge conditions. DEM: honoured — the stress becomes simplified-JKR cohesion between the
// particles and the belt and the pulley, k_c = (24 sqrt(3) E*^2 sigma_a)^{1/3} / pi, the value at
// which a hexagonal bottom layer of spheres holds sigma_a (derivation in dem/station/belt_cohesion.h).
// Only the spheres touching the belt are held; the rigid layer of the analytical model has no DEM
// counterpart (the material itself is cohesionless). With the linear spring-dashpot contact sJKR
// has no finite pull-off, so the DEM run notes that the adhesion is not represented.
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class BeltAdhesion final : public analytical::Effect {
 public:
  explicit BeltAdhesion(double sigma) : sigma_(sigma) {}
  std::string name() const override { return "belt_adhesion"; }
  void adjust_discharge(analytical::DischargeInput& d, const Station&) const override {
    if (d.layer_mass_per_area > 0.0) d.holding_accel += sigma_ / d.layer_mass_per_area;
  }

 private:
  double sigma_;
};

const Registration registration({
    "belt_adhesion", "adhesive_stress", "Pa", "discharge",
    "Booth's release condition with adhesion: V^2 / r = g cos(theta) + sigma_a / m'', with m'' = "
    "rho_bl A / W the layer's mass per belt area; the layer rides further round the pulley.",
    "Hastie & Wypych (2007), The prediction of conveyor trajectories - a review (adhesion terms)",
    0.0, 0.0, 2000.0, 330.0, [](double v) { return std::make_shared<BeltAdhesion>(v); }});

}  // namespace
}  // namespace chutelab::effects
