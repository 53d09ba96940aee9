// load_cell_offset: the plate's normal load cells read a constant offset (a zero error).
//
// Physics: the plate rests on four load cells for the normal force (reference study Fig. 3); a tare drift or a
// preload from the tie rod adds a constant F_0 to the recorded R_n (and so to R). The recorded
// point of application comes from moments, y_R = M / R_n; an offset shared evenly by the cells
// about the reference point adds force but no moment, so the recorded y_R = M / (R_n + F_0). The
// reference study notes creep and vibration of the load cells at low momentum (section 6). F_0 in N, 0 = a
// true zero; physical range -20 to +20 N.
// Hook: the measurement itself — it applies to every model's prediction, DEM included: the harness
// adds it to the DEM's R_n and y_R as to any model's; no DEM input changes.
#include <cmath>

#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class LoadCellOffset final : public analytical::Effect {
 public:
  explicit LoadCellOffset(double f0) : f0_(f0) {}
  std::string name() const override { return "load_cell_offset"; }
  void adjust_measurement(QuantityValues& v) const override {
    auto& rn = v[Quantity::normal_force];
    if (!rn) return;
    const double recorded = *rn + f0_;
    if (auto& y = v[Quantity::impact_point_y]; y && recorded != 0.0) *y *= *rn / recorded;
    rn = recorded;
    if (auto& rs = v[Quantity::shear_force]; rs) v[Quantity::resultant_force] = std::hypot(recorded, *rs);
  }

 private:
  double f0_;
};

const Registration registration({
    "load_cell_offset", "normal_offset", "N", "measurement",
    "R_n,recorded = R_n + F_0 and y_R,recorded = M / (R_n + F_0): a zero error of the normal load "
    "cells adds force but no moment; R follows from R_n and R_s.",
    "Grima & Wypych (2010) Fig. 3 and section 6 (load-cell creep and vibration)",
    0.0, -20.0, 20.0, 2.5, [](double v) { return std::make_shared<LoadCellOffset>(v); },
    "a zero reading of the load cells with the belt running empty"});

}  // namespace
}  // namespace chutelab::effects
