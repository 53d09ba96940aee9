#pragma once
// Mass-proportional damping, the damping of LAMMPS' pair_style gran/hooke/history (and LIGGGHTS'
// hooke/stiffness): F_d = m* gamma_n d(delta)/dt, the tangential dashpot m* gamma_t, with the rates
// gamma_n, gamma_t in 1/s given per material pair (LAMMPS' default gamma_t = gamma_n / 2). The rate is
// fixed, so the damping ratio at a linear spring k_n, zeta = gamma_n / (2 sqrt(k_n / m*)), and with
// it the restitution follow the effective mass (dem/contact/hooke.h).
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/material.h"

namespace chutelab::dem {

struct MassProportionalDamping {
  static constexpr std::string_view key = "mass-proportional";
  static constexpr std::string_view title = "mass-proportional damping";
  static constexpr std::array<LawParameter, 2> parameters{{
      {"normal_damping", "1/s", "normal damping rate gamma_n (force m* gamma_n d(delta)/dt)", LawParameter::kRequired},
      {"tangential_damping", "1/s", "tangential damping rate gamma_t; gamma_n / 2 if not given", LawParameter::kOwnRule},
  }};

  struct Coeffs {
    double gamma_n = 0.0;  // 1/s
    double gamma_t = 0.0;  // 1/s
  };
  template <class Spring>
  static Coeffs set(const Interaction& in) {
    Coeffs c;
    c.gamma_n = in.law.value(parameters[0]);
    c.gamma_t = in.law.get(parameters[1].key).value_or(0.5 * c.gamma_n);
    return c;
  }
  static std::string check(const Coeffs& c) {
    if (!(c.gamma_n >= 0.0)) return "needs normal_damping >= 0 1/s";
    if (!(c.gamma_t >= 0.0)) return "needs tangential_damping >= 0 1/s";
    return {};
  }

  template <class Spring>
  CHUTELAB_INLINE static Dashpot dashpot(const Coeffs& c, const SpringForce& /*s*/, double m_eff) {
    return {m_eff * c.gamma_n, m_eff * c.gamma_t};
  }
  // zeta = gamma_n / (2 sqrt(k / m*)).
  static double ratio(const Coeffs& c, double stiffness, double m_eff) {
    return 0.5 * c.gamma_n / std::sqrt(stiffness / m_eff);
  }
  // gamma_n = 2 zeta w0.
  static LawParameters matched_parameters(double zeta, double /*m_eff*/, double w0) {
    return {{"normal_damping", 2.0 * zeta * w0}};
  }
};

}  // namespace chutelab::dem
