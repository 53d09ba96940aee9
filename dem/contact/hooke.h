#pragma once
// Hooke with mass-proportional damping, the law of LAMMPS' pair_style gran/hooke/history (and of its
// chute benchmark, in.chute; Silbert, Ertas, Grest, Halsey, Levine & Plimpton, Phys. Rev. E 64,
// 051302, 2001; LIGGGHTS: model hooke/stiffness):
//   normal:     F_n = k_n delta + m* gamma_n d(delta)/dt
//   tangential: spring k_t (the tangential part's history), damping m* gamma_t
// k_n, k_t in N/m and gamma_n, gamma_t in 1/s are given per material pair (LAMMPS' defaults: k_t =
// 2/7 k_n, gamma_t = gamma_n / 2). Unlike the linear spring-dashpot (reference study Eq 8), whose damping is set
// per pair from a restitution, here the damping rate is fixed, so the restitution depends on the
// effective mass: with w0^2 = k_n / m* and zeta = gamma_n / (2 w0) < 1, a binary collision (tensile
// tail kept, as LAMMPS does without limit_damping) lasts pi / (w0 sqrt(1 - zeta^2)) and rebounds with
//   e = exp(-pi zeta / sqrt(1 - zeta^2)),
// lighter contacts less damped than heavier ones (a sphere on a wall loses more than on its twin).
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

#include "dem/contact/damping_restitution.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/timestep.h"

namespace chutelab::dem {

struct Hooke {
  static constexpr std::string_view key = "hooke";
  static constexpr std::string_view title = "Hooke with mass-proportional damping (LAMMPS gran/hooke/history)";
  static constexpr std::string_view liggghts = "hooke/stiffness";
  static constexpr bool hertz_elastic = false;
  static constexpr std::array<LawParameter, 4> parameters{{
      {"normal_stiffness", "N/m", "normal spring k_n", LawParameter::kRequired},
      {"normal_damping", "1/s", "normal damping rate gamma_n (force m* gamma_n d(delta)/dt)", LawParameter::kRequired},
      {"tangential_stiffness", "N/m", "tangential spring k_t; 2/7 k_n if not given", LawParameter::kOwnRule},
      {"tangential_damping", "1/s", "tangential damping rate gamma_t; gamma_n / 2 if not given", LawParameter::kOwnRule},
  }};

  struct Coeffs {
    double kn = 0.0;       // N/m
    double kt = 0.0;       // N/m
    double gamma_n = 0.0;  // 1/s
    double gamma_t = 0.0;  // 1/s
  };
  static Coeffs mix(const Material&, const Material&, const Interaction& in) {
    Coeffs c;
    c.kn = in.law.value(parameters[0]);
    c.gamma_n = in.law.value(parameters[1]);
    c.kt = in.law.get(parameters[2].key).value_or(2.0 / 7.0 * c.kn);
    c.gamma_t = in.law.get(parameters[3].key).value_or(0.5 * c.gamma_n);
    return c;
  }
  static std::string check(const Coeffs& c) {
    if (!(c.kn > 0.0)) return "the hooke contact law needs normal_stiffness > 0 N/m";
    if (!(c.gamma_n >= 0.0)) return "the hooke contact law needs normal_damping >= 0 1/s";
    if (!(c.kt >= 0.0)) return "the hooke contact law needs tangential_stiffness >= 0 N/m";
    if (!(c.gamma_t >= 0.0)) return "the hooke contact law needs tangential_damping >= 0 1/s";
    return {};
  }

  CHUTELAB_INLINE static NormalResult normal(const Coeffs& c, double delta, double delta_dot, double /*r_eff*/,
                                             double m_eff) {
    return {c.kn * delta + m_eff * c.gamma_n * delta_dot, c.kn, c.kt, m_eff * c.gamma_t};
  }
  // pi / w_d; an overdamped contact (zeta >= 1) does not rebound, and the undamped half period pi / w0
  // is then its time scale.
  static double collision_time(const Coeffs& c, double m_eff, double /*r_eff*/, double /*v*/) {
    if (!(c.kn > 0.0)) return std::numeric_limits<double>::infinity();
    const double zeta = damping_ratio(c, m_eff);
    return linear_collision_time(m_eff, c.kn, zeta < 1.0 ? zeta : 0.0);
  }
  static double elastic_energy(const Coeffs& c, double delta, double /*r_eff*/) { return 0.5 * c.kn * delta * delta; }
  // k_n and gamma_n that give a collision of effective mass m_eff restitution e and duration `duration`
  // (other masses then rebound differently: see above).
  static LawParameters matched_parameters(double restitution, double m_eff, double duration) {
    const double zeta = damping_ratio_from_restitution(restitution);
    const double w0 = std::numbers::pi / duration / std::sqrt(1.0 - zeta * zeta);
    return {{"normal_stiffness", m_eff * w0 * w0}, {"normal_damping", 2.0 * zeta * w0}};
  }
  // LIGGGHTS' hooke/stiffness reads the four numbers per type pair (its damping, without
  // absolute_damping, is m* gamma as here).
  static LawParameters liggghts_pair_properties(const Coeffs& c) {
    return {{"kn", c.kn}, {"kt", c.kt}, {"gamman", c.gamma_n}, {"gammat", c.gamma_t}};
  }

  // zeta = gamma_n / (2 sqrt(k_n / m*)).
  static double damping_ratio(const Coeffs& c, double m_eff) { return 0.5 * c.gamma_n / std::sqrt(c.kn / m_eff); }
};

}  // namespace chutelab::dem
