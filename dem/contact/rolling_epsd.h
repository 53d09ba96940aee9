#pragma once
// Elastic-plastic spring-dashpot rolling resistance (Ai, Chen, Rotter & Ooi 2011, model C).
//   spring:  M_k += -k_r dtheta_r,  k_r = 2.25 k_n mu_r^2 R*^2,  |M_k| <= mu_r R* F_n (plastic limit)
//   damper:  M_d = -eta_r 2 sqrt(I_r k_r) w_r while the spring is below its limit, 0 at the limit,
//            I_r = 1 / (1/(I_i + m_i R_i^2) + 1/(I_j + m_j R_j^2)) (inertia about the contact point).
// dtheta_r is the relative rolling rotation (the part of w_i - w_j normal to n, twist excluded). The
// torque history is kept in the tangent plane like the tangential spring. Torque on j is -M.
#include <cmath>

#include "dem/contact/kinematics.h"
#include "dem/contact/pair_coeffs.h"

namespace chutelab::dem {

struct RollingEpsd {
  static constexpr bool has_history = true;
  CHUTELAB_INLINE static void torque(const SharedCoeffs& c, const NormalResult& nr, const ContactKinematics& k,
                     LaneVec* history, double dt, LaneVec& ti, LaneVec& tj) {
    LaneVec& m = *history;
    const double fn = std::max(nr.force, 0.0);
    if (c.rolling_friction <= 0.0 || fn <= 0.0) {
      m = LaneVec::zero();
      return;
    }
    const LaneVec wr = k.w_rel - k.w_rel.dot(k.n) * k.n;
    const double m2 = m.squared_norm();
    if (m2 > 0.0) {
      m -= m.dot(k.n) * k.n;
      const double p2 = m.squared_norm();
      if (p2 > 0.0) m *= std::sqrt(m2 / p2);
    }
    const double kr = 2.25 * nr.kn * c.rolling_friction * c.rolling_friction * k.r_eff * k.r_eff;
    m -= kr * dt * wr;
    const double limit = c.rolling_friction * k.r_eff * fn;
    const double s2 = m.squared_norm();
    LaneVec total = m;
    if (s2 > limit * limit) {
      m *= limit / std::sqrt(s2);
      total = m;
    } else {
      // Inertia about the contact point; a wall (m_j == 0) is infinitely heavy.
      const double inv_i = 1.0 / (1.0 / k.inv_inertia_i + k.m_i * k.r_i * k.r_i);
      const double inv_j = k.m_j > 0.0 ? 1.0 / (1.0 / k.inv_inertia_j + k.m_j * k.r_j * k.r_j) : 0.0;
      const double ir = 1.0 / (inv_i + inv_j);
      total -= c.rolling_damping_ratio * 2.0 * std::sqrt(ir * kr) * wr;
    }
    ti += total;
    tj -= total;
  }
};

}  // namespace chutelab::dem
