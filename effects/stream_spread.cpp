// stream_spread: the stream fans out in flight instead of keeping its thickness.
//
// Physics: Booth's limits assume every layer leaves the pulley parallel to the belt. Collisions in
// the layer and the spread of particle velocities make the stream diverge: the upper limit leaves
// turned up by delta and the lower limit turned down by delta from the Booth direction, so the
// stream thickens with distance (divergence coefficients in the trajectory models reviewed by
// Hastie & Wypych 2007). delta in degrees, 0 = Booth; physical range 0-15 deg. The centroid and
// with it the impact point and the plate forces are unchanged.
// Hook: discharge conditions of the outer streamlines. DEM: ignored, with a note in the prediction —
// a DEM stream spreads by itself, through the collisions and velocity spread this effect stands for.
#include <cmath>

#include "core/units.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class StreamSpread final : public analytical::Effect {
 public:
  explicit StreamSpread(double deg) : delta_(deg * units::deg) {}
  std::string name() const override { return "stream_spread"; }
  void adjust_release(Boundary b, Eigen::Vector2d& v) const override {
    const double turn = b == Boundary::upper ? delta_ : b == Boundary::lower ? -delta_ : 0.0;
    const double c = std::cos(turn), s = std::sin(turn);
    v = Eigen::Vector2d(c * v.x() - s * v.y(), s * v.x() + c * v.y());
  }

 private:
  double delta_;
};

const Registration registration({
    "stream_spread", "divergence_angle", "deg", "discharge",
    "The upper limit leaves turned up by delta and the lower limit turned down by delta from the "
    "Booth direction; the centroid is unchanged.",
    "Hastie & Wypych (2007), The prediction of conveyor trajectories - a review (divergence)",
    0.0, 0.0, 15.0, 3.0, [](double v) { return std::make_shared<StreamSpread>(v); }});

}  // namespace
}  // namespace chutelab::effects
