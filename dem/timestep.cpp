#include "dem/timestep.h"

#include <cmath>
#include <numbers>

namespace chutelab::dem {

double rayleigh_time(double radius, double density, double shear_modulus, double poisson_ratio) {
  return std::numbers::pi * radius * std::sqrt(density / shear_modulus) / (0.1631 * poisson_ratio + 0.8766);
}

double hertz_collision_time(double m_eff, double r_eff, double e_star, double impact_speed) {
  return 2.87 * std::pow(m_eff * m_eff / (r_eff * e_star * e_star * impact_speed), 0.2);
}

double linear_collision_time(double m_eff, double kn, double zeta) {
  return std::numbers::pi / std::sqrt(kn / m_eff * (1.0 - zeta * zeta));
}

}  // namespace chutelab::dem
