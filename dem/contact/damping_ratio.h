#pragma once
// Damping at a constant damping ratio zeta, given per material pair and independent of the
// restitution: c = 2 zeta sqrt(k m*) with k the stiffness at the overlap (normal, and the tangential
// spring's for the tangential dashpot) and m* the effective mass. On a linear spring the contact
// rebounds with e = exp(-pi zeta / sqrt(1 - zeta^2)) whatever the mass; on Hertz (k = S_n, the
// Tsuji-type delta^{1/4} dashpot) with one e at every impact speed, 1 - e = pi sqrt(6/5) zeta to first
// order (tests/dem/test_normal_impact.cpp).
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/material.h"

namespace chutelab::dem {

struct DampingRatio {
  static constexpr std::string_view key = "damping-ratio";
  static constexpr std::string_view title = "a constant damping ratio";
  static constexpr std::array<LawParameter, 1> parameters{{
      {"damping_ratio", "", "damping ratio zeta of both dashpots, c = 2 zeta sqrt(k m*), 0 <= zeta < 1",
       LawParameter::kRequired},
  }};

  struct Coeffs {
    double zeta = 0.0;
  };
  template <class Spring>
  static Coeffs set(const Interaction& in) {
    return {in.law.value(parameters[0])};
  }
  // At zeta >= 1 a contact does not rebound, and the collision time the time step follows has no
  // bound.
  static std::string check(const Coeffs& c) {
    if (!(c.zeta >= 0.0 && c.zeta < 1.0)) return "needs 0 <= damping_ratio < 1";
    return {};
  }

  template <class Spring>
  CHUTELAB_INLINE static Dashpot dashpot(const Coeffs& c, const SpringForce& s, double m_eff) {
    const double cn = 2.0 * c.zeta * std::sqrt(s.kn * m_eff);
    if constexpr (Spring::fixed_tangential_ratio) return {cn, cn * s.tangential_ratio};
    else return {cn, 2.0 * c.zeta * std::sqrt(s.kt * m_eff)};
  }
  static double ratio(const Coeffs& c, double /*stiffness*/, double /*m_eff*/) { return c.zeta; }
  static LawParameters matched_parameters(double zeta, double /*m_eff*/, double /*w0*/) {
    return {{"damping_ratio", zeta}};
  }
};

}  // namespace chutelab::dem
