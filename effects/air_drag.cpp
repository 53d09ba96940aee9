// air_drag: aerodynamic drag on the particles in flight.
//
// Physics: each particle of diameter d and solid density rho_s feels quadratic drag
//   a = -(3 rho_air C_d / (4 rho_s d)) |v| v
// (drag force C_d rho_air |v| v A / 2 on a sphere of cross-section A = pi d^2 / 4, divided by its
// mass rho_s pi d^3 / 6). C_d is the effective drag coefficient of a particle in the stream:
// about 0.44-0.47 for an isolated sphere at Re ~ 10^3 (Clift, Grace & Weber 1978); shielding inside
// a dense stream lowers it, so the physical range is 0 (no drag, the reference study's assumption) to 1.5.
// Hook: forces in flight. DEM: honoured — the same acceleration, with the dataset's real particle
// diameter and density, as a body force on every particle past the pulley's tangent point
// (dem/station/flight_force.h), so a scaled-up DEM particle is slowed like a real one.
#include <cmath>

#include "core/units.h"
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class AirDrag final : public analytical::Effect {
 public:
  explicit AirDrag(double cd) : cd_(cd) {}
  std::string name() const override { return "air_drag"; }
  bool has_flight_force() const override { return cd_ != 0.0; }
  Eigen::Vector2d flight_acceleration(const Eigen::Vector2d& v,
                                      const analytical::FlightContext& c) const override {
    const double k = 3.0 * units::air_density * cd_ / (4.0 * c.solid_density * c.particle_diameter);
    return -k * v.norm() * v;
  }

 private:
  double cd_;
};

EffectInfo info() {
  EffectInfo e{
    "air_drag", "drag_coefficient", "", "flight",
    "a = -(3 rho_air C_d / (4 rho_s d)) |v| v on every particle in flight (quadratic drag on a "
    "sphere of diameter d, solid density rho_s; rho_air = 1.204 kg/m^3).",
    "Clift, Grace & Weber (1978), Bubbles, Drops and Particles: C_d ~ 0.44 for a sphere at Re ~ 1e3",
    0.0, 0.0, 1.5, 0.6, [](double v) { return std::make_shared<AirDrag>(v); },
    "the stream's speed along its flight (e.g. high-speed video at two points), or a run at another particle size"};
  e.growth = EffectInfo::Growth{"the drag", "belt speed", 2.0};
  return e;
}

const Registration registration(info());

}  // namespace
}  // namespace chutelab::effects
