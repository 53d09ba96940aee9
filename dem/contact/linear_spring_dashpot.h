#pragma once
// Linear spring-dashpot (reference study Eq 8): F_n = k_n delta + D_n d(delta)/dt with D_n = 2 zeta sqrt(k_n m*),
// zeta = -ln e / sqrt(ln^2 e + pi^2), which is the exact restitution of the damped linear oscillator
// when the contact ends at delta = 0 (tensile tail kept). Tangential spring k_t = ratio * k_n with the
// same damping ratio.
#include <cmath>

#include "dem/contact/kinematics.h"

namespace chutelab::dem {

struct LinearSpringDashpot {
  CHUTELAB_INLINE static NormalResult normal(const PairCoeffs& c, double delta, double delta_dot, double /*r_eff*/,
                             double m_eff) {
    const double damping = c.linear_damping * std::sqrt(c.linear_kn * m_eff) * delta_dot;
    return {c.linear_kn * delta + damping, c.linear_kn, c.linear_kt,
            c.linear_damping * std::sqrt(c.linear_kt * m_eff)};
  }
  static double elastic_energy(const PairCoeffs& c, double delta, double /*r_eff*/) {
    return 0.5 * c.linear_kn * delta * delta;
  }
};

}  // namespace chutelab::dem
